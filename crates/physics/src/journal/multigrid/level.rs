use super::*;

impl Level {
    /// `grooves`: 0 (periodic film), 1 (ambient line at column 0) or 2 (also at column
    /// `round(nt/2)`, the opposite line when `nt` is even).
    pub(super) fn new(nt: usize, nz: usize, grooves: usize, mirror: bool) -> Self {
        let n = nt * nz;
        let groove = grooves > 0;
        let second = (grooves > 1).then(|| (nt + 1) / 2 % nt);
        let mut l = Level {
            nt,
            nz,
            dt: std::f64::consts::TAU / nt as f64,
            // the mirrored half: `nz − 2` intervals over `[0, ½]` (0.5/m and 1/(2m) are the
            // same double: both the correctly rounded 1/(2m))
            dz: if mirror { 0.5 / (nz - 2) as f64 } else { 1.0 / (nz - 1) as f64 },
            groove,
            second_groove: second,
            mirror,
            theta0: 0.0,
            cos_n: vec![0.0; nt],
            sin_n: vec![0.0; nt],
            ce: vec![0.0; n],
            cn: vec![0.0; n],
            diag: vec![0.0; n],
            src: vec![0.0; n],
            h: vec![0.0; n],
            u: vec![0.0; n],
            fixed: vec![FREE; n],
            mask: vec![0.0; n],
            inv_d: vec![0.0; n],
            inv_diag: vec![0.0; n],
            free_span: vec![[(0, nt), (nt, nt)]; nz],
            dirty: vec![true; nz],
            cos_f: vec![0.0; nt],
            sin_f: vec![0.0; nt],
            zq: 1,
            zrows: Vec::new(),
            interior: vec![0.0; n],
            x: vec![0.0; n],
            b: vec![0.0; n],
            r: vec![0.0; n],
            tmp: Vec::new(),
            tt: None,
            tz: None,
            inj_t: Vec::new(),
            inj_z: Vec::new(),
            chol: None,
            coeffs_of: None,
            src_norm2: None,
            free_src_norm: None,
        };
        for j in 0..nz {
            for i in 0..nt {
                if j == 0 || j + 1 == nz || (groove && i == 0) || second == Some(i) {
                    l.fixed[j * nt + i] = BOUNDARY;
                } else {
                    l.interior[j * nt + i] = 1.0;
                }
            }
        }
        l
    }

    /// Back to the state of [`Level::new`] without reallocating: no coefficients, zero
    /// pressure and work arrays, every non-boundary node free. What a solve on this level does
    /// then depends only on its inputs, not on what the level solved before.
    pub(super) fn reset_state(&mut self) {
        for f in &mut self.fixed {
            if *f != BOUNDARY {
                *f = FREE;
            }
        }
        for v in [&mut self.u, &mut self.x, &mut self.b, &mut self.r, &mut self.mask, &mut self.inv_d] {
            v.fill(0.0);
        }
        self.free_span.fill([(0, self.nt), (self.nt, self.nt)]);
        self.dirty.fill(true);
        self.theta0 = 0.0;
        self.chol = None;
        self.coeffs_of = None;
        self.src_norm2 = None;
        self.free_src_norm = None;
    }

    /// Absolute angle of node `i`.
    pub fn theta(&self, i: usize) -> f64 {
        self.theta0 + i as f64 * self.dt
    }

    /// Rebuild coefficients for `film` with node 0 at absolute angle `theta0`.
    pub(super) fn set_film(&mut self, film: &Film, alpha: f64, theta0: f64) {
        // the coefficients are a function of (film, alpha, theta0) only, and nothing else writes
        // them; the masks are kept consistent with `fixed` by every change of it
        if self.coeffs_of == Some((*film, alpha, theta0)) {
            return;
        }
        self.coeffs_of = Some((*film, alpha, theta0));
        self.src_norm2 = None;
        let (nt, nz, dt, dz) = (self.nt, self.nz, self.dt, self.dz);
        self.theta0 = theta0;
        let mut cos_f = std::mem::take(&mut self.cos_f);
        let mut sin_f = std::mem::take(&mut self.sin_f);
        for i in 0..nt {
            let t = theta0 + i as f64 * dt;
            let (s, c) = t.sin_cos();
            self.cos_n[i] = c;
            self.sin_n[i] = s;
            let (s, c) = (t + 0.5 * dt).sin_cos();
            cos_f[i] = c;
            sin_f[i] = s;
        }
        let ke = dz / dt;
        let kn = alpha * dt / dz;
        let mut prev: Option<(super::super::film::Row, super::super::film::Row)> = None;
        for j in 0..nz {
            let z = j as f64 * dz;
            let r = film.row(z);
            let rn = film.row((z + 0.5 * dz).min(1.0));
            let row = j * nt;
            let (z_lo, z_hi) = ((z - 0.5 * dz).max(0.0), (z + 0.5 * dz).min(1.0));
            let east_avg = self.sub_cell_profile(film) && profile_in(film, z_lo, z_hi);
            let north_avg = self.sub_cell_profile(film) && j + 1 < nz && profile_in(film, z, (z + dz).min(1.0));
            if !east_avg && !north_avg && j + 1 < nz && prev == Some((r, rn)) {
                // the same film data as the row below (an aligned film, or the unprofiled middle
                // of a profiled one): the same coefficients
                for v in [&mut self.ce, &mut self.h, &mut self.cn, &mut self.src] {
                    v.copy_within(row - nt..row, row);
                }
                continue;
            }
            prev = (j + 1 < nz && !east_avg && !north_avg).then_some((r, rn));
            let base = 1.0 + r.gamma;
            let base_n = 1.0 + rn.gamma;
            // on slices of one length (no bounds checks, no reloads of the angle tables per node)
            let ce = &mut self.ce[row..row + nt];
            let h = &mut self.h[row..row + nt];
            let (cos_n, sin_n) = (&self.cos_n[..nt], &self.sin_n[..nt]);
            let faces = cos_f[..nt].iter().zip(&sin_f[..nt]);
            let nodes = cos_n.iter().zip(sin_n);
            for (((ce, h), (cf, sf)), (cn, sn)) in ce.iter_mut().zip(h.iter_mut()).zip(faces).zip(nodes) {
                let he = base + r.x * cf + r.y * sf;
                *ce = he * he * he * ke;
                *h = base + r.x * cn + r.y * sn;
            }
            if east_avg {
                face_means(film, z_lo, z_hi, self.zq, false, ke, &cos_f, &sin_f, &mut self.zrows, &mut self.ce[row..row + nt]);
            }
            let cn = &mut self.cn[row..row + nt];
            if north_avg {
                face_means(film, z, (z + dz).min(1.0), self.zq, true, kn, &self.cos_n, &self.sin_n, &mut self.zrows, cn);
            } else if j + 1 < nz {
                for ((c, cs), sn) in cn.iter_mut().zip(&self.cos_n[..nt]).zip(&self.sin_n[..nt]) {
                    let hn = base_n + rn.x * cs + rn.y * sn;
                    *c = hn * hn * hn * kn;
                }
            } else {
                cn.fill(0.0);
            }
            // f = −∂H/∂θ ΔθΔZ in flux form (faces): the profile Γ(Z) drops out.
            let src = &mut self.src[row..row + nt];
            src[0] = -dz * (r.x * (cos_f[0] - cos_f[nt - 1]) + r.y * (sin_f[0] - sin_f[nt - 1]));
            for i in 1..nt {
                src[i] = -dz * (r.x * (cos_f[i] - cos_f[i - 1]) + r.y * (sin_f[i] - sin_f[i - 1]));
            }
        }
        if self.mirror {
            // Mirror condition on the mid-plane row `m = nz − 2` (the full grid's row with
            // `P_{m+1} = P_{m−1}` and `c_{n,m} = c_{n,m−1}`): the full grid's equation of row `m`
            // halved, `½ c_e` east/west, `c_{n,m−1}` to the south, `½ f`, and no face to the
            // ghost row. `A` stays symmetric: it is `EᵀA_full E` (E: the even extension) with the
            // rows `j < m` halved, and the complementarity is node-wise, so the half problem's
            // solution is the full one's restricted (a positive row scale does not change it).
            let m = nz - 2;
            let row = m * nt..(m + 1) * nt;
            for v in &mut self.ce[row.clone()] {
                *v *= 0.5;
            }
            for v in &mut self.src[row.clone()] {
                *v *= 0.5;
            }
            self.cn[row].fill(0.0);
        }
        // the diagonal on the interior rows (on slices, so that the loop vectorises), then the
        // boundary nodes (edge rows, supply lines) set to the identity row
        for j in 1..nz - 1 {
            let row = j * nt;
            let ce = &self.ce[row..row + nt];
            let cn = &self.cn[row..row + nt];
            let cs = &self.cn[row - nt..row];
            let d = &mut self.diag[row..row + nt];
            let inv = &mut self.inv_diag[row..row + nt];
            d[0] = ce[0] + ce[nt - 1] + cn[0] + cs[0];
            inv[0] = 1.0 / d[0];
            for i in 1..nt {
                d[i] = ce[i] + ce[i - 1] + cn[i] + cs[i];
                inv[i] = 1.0 / d[i];
            }
        }
        for k in 0..self.fixed.len() {
            if self.fixed[k] == BOUNDARY {
                self.diag[k] = 1.0;
                self.inv_diag[k] = 1.0;
                self.src[k] = 0.0;
            }
        }
        self.cos_f = cos_f;
        self.sin_f = sin_f;
        // `fixed` is not changed here, so the masks and free spans of the rows not marked dirty
        // still match it: only their `inv_d` follows the new diagonal (`1/diag` at free nodes, 0
        // at fixed ones, as `refresh_dirty` writes it); the marked rows are refreshed in full
        let nt = self.nt;
        for (j, dirty) in self.dirty.iter().enumerate() {
            if !dirty {
                let row = j * nt..(j + 1) * nt;
                for ((inv, m), id) in self.inv_d[row.clone()].iter_mut().zip(&self.mask[row.clone()]).zip(&self.inv_diag[row]) {
                    *inv = if *m != 0.0 { *id } else { 0.0 };
                }
            }
        }
        self.refresh_dirty();
        // new coefficients: the dense factor and the free source norm are stale
        self.chol = None;
        self.free_src_norm = None;
    }

    /// Whether this level's face conductances take the film's edge profile as a cell mean
    /// ([`face_means`]): on a coarse level whose axial cell is wider than the profiled zone
    /// (`ψ < ΔZ`), where a point value at the face misses most of the profile. A profile that
    /// spans a cell or more keeps the point values: measured on the L9's nine cases (BENCHMARKS.md,
    /// speed seventh round), cell means there put the coarse equilibria farther from the
    /// finest grid's (one more finest Newton step in three of the six cases with ψ ≥ 0.2).
    pub(super) fn sub_cell_profile(&self, film: &Film) -> bool {
        self.zq > 1 && film.profile.is_some_and(|p| p.length_fraction < self.dz)
    }

    /// [`Hierarchy::lcp_residual`] with `lam = A u − f` already computed (at the non-boundary
    /// nodes). The denominator `‖f/d‖²` depends on the coefficients only: it is kept with them.
    pub(super) fn lcp_residual_of(&mut self, lam: &[f64]) -> f64 {
        let mut num = 0.0;
        for (((f, u), lam), d) in self.fixed.iter().zip(&self.u).zip(lam).zip(&self.diag) {
            if *f == BOUNDARY {
                continue;
            }
            let m = u.min(lam / d);
            num += m * m;
        }
        let den = match self.src_norm2 {
            Some(d) => d,
            None => {
                let mut den = 0.0;
                for idx in 0..lam.len() {
                    if self.fixed[idx] == BOUNDARY {
                        continue;
                    }
                    let s = self.src[idx] / self.diag[idx];
                    den += s * s;
                }
                self.src_norm2 = Some(den);
                den
            }
        };
        if den > 0.0 { (num / den).sqrt() } else { num.sqrt() }
    }

    /// Recompute `mask`, `inv_d` and the free spans of every row from `fixed` and `diag`.
    #[cfg(test)]
    pub(super) fn refresh_masks(&mut self) {
        self.dirty.fill(true);
        self.refresh_dirty();
    }

    /// `mask`, `inv_d` and the free span of the rows marked in `dirty` from `fixed` and `diag`
    /// (the others' already match `fixed`: every change of `fixed` marks its row), clearing the
    /// marks.
    /// The dense factor and the free source norm are dropped when any row changed.
    pub(super) fn refresh_dirty(&mut self) {
        let nt = self.nt;
        let mut any = false;
        for (j, d) in self.dirty.iter_mut().enumerate() {
            if !std::mem::take(d) {
                continue;
            }
            any = true;
            let row = j * nt..(j + 1) * nt;
            let (m, inv, f, id) = (&mut self.mask[row.clone()], &mut self.inv_d[row.clone()], &self.fixed[row.clone()], &self.inv_diag[row]);
            // the mask, and the free nodes' extent and longest inner run of fixed nodes
            let (mut first, mut last) = (usize::MAX, 0);
            let (mut gap, mut gap_start) = (0, 0);
            for i in 0..nt {
                let free = f[i] == FREE;
                m[i] = if free { 1.0 } else { 0.0 };
                inv[i] = if free { id[i] } else { 0.0 };
                if free {
                    if first != usize::MAX && i - last - 1 > gap {
                        (gap, gap_start) = (i - last - 1, last + 1);
                    }
                    first = first.min(i);
                    last = i;
                }
            }
            self.free_span[j] = free_ranges(nt, first, last, gap, gap_start);
        }
        if any {
            self.chol = None;
            self.free_src_norm = None;
        }
    }

}

/// Face conductances of one row of a coarse level under a profiled film whose edge profile
/// varies inside one coarse cell (a point value at the face does not see a profile narrower
/// than the cell): the film across the axial interval `[z0, z1]` sampled at `m` midpoints (the
/// finest grid's resolution), at the angles `(cs, sn)`. East faces (`north = false`, flow
/// around the bearing: the sub-cells conduct in parallel) take the arithmetic mean of `H³`
/// over the cell's axial extent; north faces (`north = true`, flow along the axis: the
/// sub-cells conduct in series) the harmonic mean over `[Z_j, Z_{j+1}]` (finite-volume
/// conductances of a varying coefficient, Patankar 1980, §4.2-3). `k` is the grid factor
/// `ΔZ/Δθ` or `αΔθ/ΔZ`; `zrows` is scratch.
#[allow(clippy::too_many_arguments)]
pub(super) fn face_means(film: &Film, z0: f64, z1: f64, m: usize, north: bool, k: f64, cs: &[f64], sn: &[f64], zrows: &mut Vec<super::super::film::Row>, out: &mut [f64]) {
    zrows.clear();
    zrows.extend((0..m).map(|q| film.row(z0 + (q as f64 + 0.5) / m as f64 * (z1 - z0))));
    let inv_m = 1.0 / m as f64;
    for ((o, c), s) in out.iter_mut().zip(cs).zip(sn) {
        let mut acc = 0.0;
        for r in zrows.iter() {
            let h = 1.0 + r.gamma + r.x * c + r.y * s;
            let h3 = h * h * h;
            acc += if north { 1.0 / h3 } else { h3 };
        }
        let mean = acc * inv_m;
        *o = if north { k / mean } else { mean * k };
    }
}

/// The columns of a row of `nt` nodes without its longest cyclic run of fixed nodes, as two
/// ascending ranges (both empty when no node is free), from the first and last free column
/// (`first = usize::MAX` when there is none) and the longest run of fixed nodes between them
/// (`gap` nodes from `gap_start`).
pub(super) fn free_ranges(nt: usize, first: usize, last: usize, gap: usize, gap_start: usize) -> Span {
    if first == usize::MAX {
        return [(0, 0), (0, 0)];
    }
    // the run around column 0 against the longest inside the row
    if first + (nt - 1 - last) >= gap {
        [(first, last + 1), (nt, nt)]
    } else {
        [(0, gap_start), (gap_start + gap, nt)]
    }
}

/// Zero of `row` outside the ranges of `span`.
#[inline(always)]
pub(super) fn fill_gaps(row: &mut [f64], span: Span) {
    let [(a1, b1), (a2, b2)] = span;
    row[..a1].fill(0.0);
    row[b1..a2].fill(0.0);
    row[b2..].fill(0.0);
}

/// Whether the film's edge profile is non-zero anywhere in `[z0, z1]` (it is zero exactly on
/// `[ψ, 1 − ψ]` and non-zero elsewhere when its height is).
pub(super) fn profile_in(film: &Film, z0: f64, z1: f64) -> bool {
    film.profile.is_some_and(|p| p.opening(z0) != 0.0 || p.opening(z1) != 0.0)
}
