use super::*;

impl Transfer1D {
    pub(super) fn identity(n: usize) -> Self {
        let idx: Vec<usize> = (0..n).collect();
        Transfer1D {
            p_lo: idx.clone(),
            p_hi: idx.clone(),
            p_w: vec![0.0; n],
            s_lo: idx.clone(),
            s_hi: idx,
            s_w: vec![0.0; n],
            kind: IDENTITY,
        }
    }

    /// `nf` fine and `nc` coarse nodes on a periodic interval (node 0 shared).
    pub(super) fn periodic(nf: usize, nc: usize) -> Self {
        let map = |n_from: usize, n_to: usize| {
            let (mut lo, mut hi, mut w) = (Vec::new(), Vec::new(), Vec::new());
            for k in 0..n_from {
                // position in units of the target grid, exact rational arithmetic first
                let num = k * n_to;
                let m = num / n_from;
                let t = (num % n_from) as f64 / n_from as f64;
                lo.push(m % n_to);
                hi.push((m + 1) % n_to);
                w.push(t);
            }
            (lo, hi, w)
        };
        let (p_lo, p_hi, p_w) = map(nf, nc);
        let (s_lo, s_hi, s_w) = map(nc, nf);
        let kind = if nf == 2 * nc { HALF } else { GENERAL };
        Transfer1D { p_lo, p_hi, p_w, s_lo, s_hi, s_w, kind }
    }

    /// `nf` fine and `nc` coarse nodes on a closed interval (both ends are nodes).
    pub(super) fn open(nf: usize, nc: usize) -> Self {
        let map = |n_from: usize, n_to: usize| {
            let (mut lo, mut hi, mut w) = (Vec::new(), Vec::new(), Vec::new());
            for k in 0..n_from {
                let num = k * (n_to - 1);
                let den = n_from - 1;
                let m = (num / den).min(n_to - 2);
                let t = (num - m * den) as f64 / den as f64;
                lo.push(m);
                hi.push(m + 1);
                w.push(t);
            }
            (lo, hi, w)
        };
        let (p_lo, p_hi, p_w) = map(nf, nc);
        let (s_lo, s_hi, s_w) = map(nc, nf);
        Transfer1D { p_lo, p_hi, p_w, s_lo, s_hi, s_w, kind: GENERAL }
    }

    /// [`Transfer1D::open`] on `nf` and `nc` nodes plus a ghost node after each (the mirrored
    /// half's ghost row, fixed at 0): the ghosts map to each other only.
    pub(super) fn open_with_ghost(nf: usize, nc: usize) -> Self {
        let mut t = Self::open(nf, nc);
        t.p_lo.push(nc);
        t.p_hi.push(nc);
        t.p_w.push(0.0);
        t.s_lo.push(nf);
        t.s_hi.push(nf);
        t.s_w.push(0.0);
        t
    }

    /// `out[i] = (1 − w_i) c[lo_i] + w_i c[hi_i]`: interpolation of the coarse row `c` to the
    /// fine row `out`.
    #[inline]
    pub(super) fn prolong_row(&self, c: &[f64], out: &mut [f64]) {
        match self.kind {
            // (1 − 0)·c + 0·c = c exactly
            IDENTITY => out.copy_from_slice(c),
            HALF => {
                // pairs of fine nodes against pairs of neighbouring coarse nodes (no bounds
                // checks, no wrap test per node), the last pair wrapping to coarse node 0
                let nc = c.len();
                let (body, tail) = out[..2 * nc].split_at_mut(2 * (nc - 1));
                for (o, w) in body.chunks_exact_mut(2).zip(c.windows(2)) {
                    o[0] = w[0];
                    o[1] = 0.5 * w[0] + 0.5 * w[1];
                }
                tail[0] = c[nc - 1];
                tail[1] = 0.5 * c[nc - 1] + 0.5 * c[0];
            }
            _ => {
                for i in 0..out.len() {
                    let w = self.p_w[i];
                    out[i] = (1.0 - w) * c[self.p_lo[i]] + w * c[self.p_hi[i]];
                }
            }
        }
    }

    /// `out += Pᵀ t` for the fine row `t` (`out` the coarse row, zero on entry), in the order
    /// of the general loop over the fine nodes.
    #[inline]
    pub(super) fn restrict_row(&self, t: &[f64], out: &mut [f64]) {
        match self.kind {
            IDENTITY => {
                for (o, v) in out.iter_mut().zip(t) {
                    *o += v;
                }
            }
            HALF => {
                let nc = out.len();
                let nf = t.len();
                // coarse node 0 takes fine nodes 0 and 1 first and fine node nf − 1 last
                out[0] += t[0];
                out[0] += 0.5 * t[1];
                for m in 1..nc {
                    let mut v = out[m];
                    v += 0.5 * t[2 * m - 1];
                    v += t[2 * m];
                    v += 0.5 * t[2 * m + 1];
                    out[m] = v;
                }
                out[0] += 0.5 * t[nf - 1];
            }
            _ => {
                for i in 0..t.len() {
                    let w = self.p_w[i];
                    out[self.p_lo[i]] += (1.0 - w) * t[i];
                    if w != 0.0 {
                        out[self.p_hi[i]] += w * t[i];
                    }
                }
            }
        }
    }
}

/// `coarse.b = Pᵀ fine.r` (full weighting for nested grids), zero at coarse fixed nodes, as a
/// pass of its own: the V-cycle does it inside the pre-smoothing pass ([`Level::smooth_pass`]);
/// kept as the reference of the test.
#[cfg(test)]
pub(super) fn restrict(fine: &mut Level, coarse: &mut Level) {
    let tt = fine.tt.as_ref().unwrap();
    let tz = fine.tz.as_ref().unwrap();
    let (ntf, nzf) = (fine.nt, fine.nz);
    let ntc = coarse.nt;
    let tmp = &mut fine.tmp;
    tmp.fill(0.0);
    for j in 0..nzf {
        let (a, b, w) = (tz.p_lo[j], tz.p_hi[j], tz.p_w[j]);
        let src = &fine.r[j * ntf..(j + 1) * ntf];
        let wa = 1.0 - w;
        // the residual is 0 outside the row's free ranges
        for (lo, hi) in fine.free_span[j] {
            for i in lo..hi {
                tmp[a * ntf + i] += wa * src[i];
            }
            if w != 0.0 {
                for i in lo..hi {
                    tmp[b * ntf + i] += w * src[i];
                }
            }
        }
    }
    coarse.b.fill(0.0);
    for a in 0..coarse.nz {
        let t = &tmp[a * ntf..(a + 1) * ntf];
        let out = &mut coarse.b[a * ntc..(a + 1) * ntc];
        tt.restrict_row(t, out);
    }
    for (v, f) in coarse.b.iter_mut().zip(&coarse.fixed) {
        if *f != FREE {
            *v = 0.0;
        }
    }
}

/// The circumferential half of `fine.x += P coarse.x`: `fine.tmp` row `a` = the coarse
/// correction's row `a` interpolated around the circumference (the axial half and the addition
/// are [`Level::prolong_row_z`]), as a pass of its own: the V-cycle interpolates each row when
/// the post-smoothing pass first needs it; kept as the reference of the test.
#[cfg(test)]
pub(super) fn prolong_theta(coarse: &Level, fine: &mut Level) {
    let tt = fine.tt.as_ref().unwrap();
    let ntf = fine.nt;
    let ntc = coarse.nt;
    let tmp = &mut fine.tmp;
    for a in 0..coarse.nz {
        let c = &coarse.x[a * ntc..(a + 1) * ntc];
        let out = &mut tmp[a * ntf..(a + 1) * ntf];
        tt.prolong_row(c, out);
    }
}
