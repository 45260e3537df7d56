use super::*;

impl Level {
    /// Factor `A_II` (free nodes) densely: `A_II = L Lᵀ` (Cholesky; `A` is a symmetric
    /// M-matrix with at least one fixed node in each connected part, hence positive definite).
    /// Returns false (and keeps no factor) if a pivot is not positive.
    pub(super) fn factor_dense(&mut self) -> bool {
        let nt = self.nt;
        let idx: Vec<usize> = (0..self.fixed.len()).filter(|&k| self.fixed[k] == FREE).collect();
        let m = idx.len();
        let mut pos = vec![usize::MAX; self.fixed.len()];
        for (a, &k) in idx.iter().enumerate() {
            pos[k] = a;
        }
        let mut a = vec![0.0; m * m];
        for (r, &k) in idx.iter().enumerate() {
            a[r * m + r] = self.diag[k];
            let i = k % nt;
            let kw = if i == 0 { k + nt - 1 } else { k - 1 };
            let ke = if i + 1 == nt { k + 1 - nt } else { k + 1 };
            for (nb, c) in [(ke, self.ce[k]), (kw, self.ce[kw]), (k + nt, self.cn[k]), (k - nt, self.cn[k - nt])] {
                let q = pos[nb];
                if q != usize::MAX {
                    a[r * m + q] -= c;
                }
            }
        }
        // in-place Cholesky, lower triangle (Golub & Van Loan, alg. 4.2.1)
        for c in 0..m {
            let mut d = a[c * m + c];
            for t in 0..c {
                d -= a[c * m + t] * a[c * m + t];
            }
            if !(d > 0.0) {
                self.chol = None;
                return false;
            }
            let d = d.sqrt();
            a[c * m + c] = d;
            for r in c + 1..m {
                let mut v = a[r * m + c];
                for t in 0..c {
                    v -= a[r * m + t] * a[c * m + t];
                }
                a[r * m + c] = v / d;
            }
        }
        self.chol = Some((idx, a));
        true
    }

    /// `x = A_II⁻¹ b` on the free nodes with the dense factor (0 at fixed nodes).
    pub(super) fn solve_dense(&mut self) {
        let (idx, l) = self.chol.as_ref().unwrap();
        let m = idx.len();
        // `r` is free on the coarsest level (no residual is restricted from it): the work vector
        let y = &mut self.r[..m];
        for (a, &k) in idx.iter().enumerate() {
            y[a] = self.b[k];
        }
        for r in 0..m {
            let mut v = y[r];
            for t in 0..r {
                v -= l[r * m + t] * y[t];
            }
            y[r] = v / l[r * m + r];
        }
        for r in (0..m).rev() {
            let mut v = y[r];
            for t in r + 1..m {
                v -= l[t * m + r] * y[t];
            }
            y[r] = v / l[r * m + r];
        }
        self.x.fill(0.0);
        for (a, &k) in idx.iter().enumerate() {
            self.x[k] = y[a];
        }
    }

    /// `Σ c_nb v_nb` at node `k` (neighbour sum of the operator).
    #[cfg(test)]
    #[inline(always)]
    pub(super) fn nb_sum(&self, v: &[f64], k: usize, kw: usize, ke: usize) -> f64 {
        let nt = self.nt;
        self.ce[k] * v[ke] + self.ce[kw] * v[kw] + self.cn[k] * v[k + nt] + self.cn[k - nt] * v[k - nt]
    }

    /// `out = A v − f` at every non-boundary node (the LCP multiplier `λ` when `v` solves the
    /// inactive equations), 0 at boundary nodes.
    pub(super) fn lambda(&self, v: &[f64], out: &mut [f64]) {
        self.kernel::<{ Self::MINUS_SUB }>(v, out, &self.interior, &self.src);
    }

    /// `lam = λ = A u − f` ([`Level::lambda`]) and the new active set from it in one pass: a
    /// node is cavitated where `λ − d·P > 0` (`d` the diagonal, a per-node scale; `P` set to 0
    /// there), free elsewhere; rows whose flags change are marked dirty. Row `j` is classified
    /// once `λ` of row `j + 1` is computed, so every `λ` reads the pressure before the
    /// classification zeroes it: the values of a `lambda` pass followed by a classification
    /// pass. Returns the number of nodes whose flag changed.
    pub(super) fn lambda_and_classify(&mut self, lam: &mut [f64]) -> usize {
        let (nt, nz) = (self.nt, self.nz);
        lam[..nt].fill(0.0);
        lam[(nz - 1) * nt..].fill(0.0);
        let mut n_changed = 0usize;
        for j in 0..nz {
            if j + 2 < nz {
                self.kernel_row::<{ Self::MINUS_SUB }>(j + 1, [(0, nt), (nt, nt)], &self.u, lam, &self.interior, &self.src);
            }
            let row = j * nt..(j + 1) * nt;
            let before = n_changed;
            let (f, u, lam, d) = (&mut self.fixed[row.clone()], &mut self.u[row.clone()], &lam[row.clone()], &self.diag[row]);
            for (((f, u), lam), d) in f.iter_mut().zip(u.iter_mut()).zip(lam).zip(d) {
                if *f == BOUNDARY {
                    continue;
                }
                let active = lam - d * *u > 0.0;
                let flag = if active { CAVITATED } else { FREE };
                if flag != *f {
                    n_changed += 1;
                    *f = flag;
                }
                if active {
                    *u = 0.0;
                }
            }
            self.dirty[j] |= n_changed > before;
        }
        n_changed
    }

    /// The CG direction and its image in one pass: with `beta`, first `v = z + β v` (each row
    /// one row ahead of its use); then `out = A v` restricted to the free nodes (0 at fixed
    /// nodes), and returns `v·out` (summed in index order, as [`dot`]).
    pub(super) fn apply_free_dot(&self, z: &[f64], beta: Option<f64>, v: &mut [f64], out: &mut [f64]) -> f64 {
        let nt = self.nt;
        let nz = self.nz;
        // on the free ranges only: outside them `z` is 0, and so `v` stays (it starts as `z`)
        let update = |v: &mut [f64], j: usize| {
            if let Some(beta) = beta {
                for (lo, hi) in self.free_span[j] {
                    for (p, z) in v[j * nt + lo..j * nt + hi].iter_mut().zip(&z[j * nt + lo..j * nt + hi]) {
                        *p = z + beta * *p;
                    }
                }
            }
        };
        update(v, 0);
        update(v, 1);
        out[..nt].fill(0.0);
        out[(nz - 1) * nt..].fill(0.0);
        let mut s = 0.0;
        for j in 1..nz - 1 {
            update(v, j + 1);
            self.kernel_row::<{ Self::PLAIN }>(j, self.free_span[j], v, out, &self.mask, &self.src);
            let row = j * nt;
            for (lo, hi) in self.free_span[j] {
                for (a, b) in v[row + lo..row + hi].iter().zip(&out[row + lo..row + hi]) {
                    s += a * b;
                }
            }
        }
        s
    }

    /// `out = f − A v` at the free nodes, 0 at fixed nodes.
    pub(super) fn residual_free(&self, v: &[f64], out: &mut [f64]) {
        self.kernel::<{ Self::SUB_MINUS }>(v, out, &self.mask, &self.src);
    }

    /// [`Level::residual_free`] and `out·out` in one pass (each row summed as soon as it is
    /// written, in index order as [`dot`]; the edge rows are 0 and every term is ≥ 0, so the
    /// sum is that of `dot(out, out)` bit for bit).
    pub(super) fn residual_free_dot(&self, v: &[f64], out: &mut [f64]) -> f64 {
        let nt = self.nt;
        out[..nt].fill(0.0);
        out[(self.nz - 1) * nt..].fill(0.0);
        let mut acc = 0.0;
        for j in 1..self.nz - 1 {
            self.kernel_row::<{ Self::SUB_MINUS }>(j, [(0, nt), (nt, nt)], v, out, &self.mask, &self.src);
            for r in &out[j * nt..(j + 1) * nt] {
                acc += r * r;
            }
        }
        acc
    }

    /// Red–black Gauss–Seidel on the free nodes for `A x = b`; `reverse` swaps the colour order
    /// (the post-smoother of a symmetric cycle). All `2·sweeps` half-sweeps are pipelined in one
    /// pass over memory: at step `j` half-sweep `s` updates row `j − s`, so every row sees its
    /// neighbours exactly as in sweep after sweep (the same arithmetic, bit for bit) while the
    /// rows in flight stay in cache. `from_zero`: `x` is taken as 0 on entry (its old values are
    /// never read: the first half-sweep sets `x = b/d` on its colour, and a Gauss–Seidel update
    /// does not read the node's own value). `residual`: also `r = b − A x` at the free nodes (0
    /// at fixed ones), each row as soon as its neighbours are final. `dot`: returns `b·x` summed
    /// over the rows as they become final (in index order, as [`dot`]; the edge rows are 0).
    /// `prolong`: first `x += P·(coarse correction)` with the coarse level's correction `x`:
    /// each coarse row is interpolated around the circumference into `tmp` when first needed
    /// (as `prolong_theta`, the test reference) and each fine row gets its axial interpolation
    /// just before the first half-sweep needs it. `restrict`: with `residual`, also `coarse.b = Pᵀ r` (zero
    /// at the coarse fixed nodes, as `restrict`), each residual row accumulated into `tmp` while it
    /// is in cache and each coarse row finished as soon as no later fine row contributes to it.
    #[allow(clippy::too_many_arguments)]
    pub(super) fn smooth_pass(&mut self, sweeps: usize, reverse: bool, from_zero: bool, residual: bool, want_dot: bool, prolong: Option<&Level>, mut restrict: Option<&mut Level>) -> f64 {
        let nz = self.nz;
        let first = if reverse { 1 } else { 0 };
        let stages = 2 * sweeps;
        let last = if residual { nz - 2 + stages } else { nz - 2 + stages - 1 };
        let mut acc = 0.0;
        if residual {
            let nt = self.nt;
            self.r[..nt].fill(0.0);
            self.r[(nz - 1) * nt..].fill(0.0);
        }
        // restriction: `tmp` rows zeroed so far, coarse rows finished so far;
        // prolongation: `tmp` rows interpolated so far
        let (mut zeroed, mut finished, mut made) = (0, 0, 0);
        if let Some(c) = prolong {
            self.prolong_row_z(1, c, &mut made);
        }
        for j in 1..=last {
            if let Some(c) = prolong
                && j + 1 <= nz - 2
            {
                self.prolong_row_z(j + 1, c, &mut made);
            }
            for s in 0..stages {
                if j > s && j - s <= nz - 2 {
                    let color = if s % 2 == 0 { first } else { 1 - first };
                    if s == 0 && from_zero {
                        self.smooth_row_zero(j, color);
                    } else {
                        self.smooth_row(j - s, color);
                    }
                }
            }
            if residual && j > stages && j - stages <= nz - 2 {
                let jr = j - stages;
                self.residual_row(jr);
                if let Some(c) = restrict.as_deref_mut() {
                    self.restrict_row_z(jr, &mut zeroed);
                    // later fine rows contribute to coarse rows `p_lo[jr + 1]` and above only
                    let done = self.tz.as_ref().unwrap().p_lo[jr + 1];
                    self.restrict_finish(done, c, &mut zeroed, &mut finished);
                }
            }
            if want_dot && j >= stages && j + 1 - stages <= nz - 2 {
                let row = (j + 1 - stages) * self.nt;
                for (b, x) in self.b[row..row + self.nt].iter().zip(&self.x[row..row + self.nt]) {
                    acc += b * x;
                }
            }
        }
        if let Some(c) = restrict {
            let nzc = c.nz;
            self.restrict_finish(nzc, c, &mut zeroed, &mut finished);
        }
        acc
    }

    /// The axial half of the restriction for fine row `j` (its residual final): `tmp` rows
    /// `p_lo[j]` and `p_hi[j]` += the row's weighted residual on its free ranges (outside them
    /// the residual is 0), in the order of `restrict` (the test reference); the `tmp` rows are
    /// zeroed when first touched (`zeroed`: the rows zeroed so far).
    #[inline(always)]
    pub(super) fn restrict_row_z(&mut self, j: usize, zeroed: &mut usize) {
        let tz = self.tz.as_ref().unwrap();
        let nt = self.nt;
        let (a, b, w) = (tz.p_lo[j], tz.p_hi[j], tz.p_w[j]);
        let top = if w != 0.0 { b } else { a };
        if *zeroed <= top {
            self.tmp[*zeroed * nt..(top + 1) * nt].fill(0.0);
            *zeroed = top + 1;
        }
        let src = &self.r[j * nt..(j + 1) * nt];
        let wa = 1.0 - w;
        for (lo, hi) in self.free_span[j] {
            for (t, s) in self.tmp[a * nt + lo..a * nt + hi].iter_mut().zip(&src[lo..hi]) {
                *t += wa * s;
            }
            if w != 0.0 {
                for (t, s) in self.tmp[b * nt + lo..b * nt + hi].iter_mut().zip(&src[lo..hi]) {
                    *t += w * s;
                }
            }
        }
    }

    /// The circumferential half of the restriction for the coarse rows `finished..upto` (no
    /// later fine row contributes to them): `coarse.b` row `a` = `Pᵀ` of `tmp` row `a`, 0 at the
    /// coarse fixed nodes.
    pub(super) fn restrict_finish(&mut self, upto: usize, coarse: &mut Level, zeroed: &mut usize, finished: &mut usize) {
        let nt = self.nt;
        let ntc = coarse.nt;
        if *zeroed < upto {
            self.tmp[*zeroed * nt..upto * nt].fill(0.0);
            *zeroed = upto;
        }
        let tt = self.tt.as_ref().unwrap();
        for a in *finished..upto {
            let t = &self.tmp[a * nt..(a + 1) * nt];
            let out = &mut coarse.b[a * ntc..(a + 1) * ntc];
            out.fill(0.0);
            tt.restrict_row(t, out);
            for (v, f) in out.iter_mut().zip(&coarse.fixed[a * ntc..(a + 1) * ntc]) {
                if *f != FREE {
                    *v = 0.0;
                }
            }
        }
        *finished = (*finished).max(upto);
    }

    /// `x += mask·(z-interpolation of the rows of tmp)` on row `j`, the `tmp` rows it reads
    /// first interpolated around the circumference from `coarse.x` (`made`: the rows done).
    #[inline(always)]
    pub(super) fn prolong_row_z(&mut self, j: usize, coarse: &Level, made: &mut usize) {
        let tz = self.tz.as_ref().unwrap();
        let nt = self.nt;
        let (a, b, w) = (tz.p_lo[j], tz.p_hi[j], tz.p_w[j]);
        if *made <= b {
            let tt = self.tt.as_ref().unwrap();
            let ntc = coarse.nt;
            for c in *made..=b {
                tt.prolong_row(&coarse.x[c * ntc..(c + 1) * ntc], &mut self.tmp[c * nt..(c + 1) * nt]);
            }
            *made = b + 1;
        }
        let row = j * nt;
        let (ta, tb) = (&self.tmp[a * nt..(a + 1) * nt], &self.tmp[b * nt..(b + 1) * nt]);
        let m = &self.mask[row..row + nt];
        let x = &mut self.x[row..row + nt];
        // outside the free ranges the mask is 0 (the correction adds nothing)
        for (lo, hi) in self.free_span[j] {
            for i in lo..hi {
                x[i] += m[i] * ((1.0 - w) * ta[i] + w * tb[i]);
            }
        }
    }

    /// The first half-sweep from `x = 0`: `x = b/d` on the nodes of colour `color` in row `j`
    /// within its free span, and `x = 0` on both colours outside it (the later half-sweeps
    /// skip those nodes: every one is fixed).
    #[inline(always)]
    pub(super) fn smooth_row_zero(&mut self, j: usize, color: usize) {
        let nt = self.nt;
        let row = j * nt;
        let inv = &self.inv_d[row..row + nt];
        let b = &self.b[row..row + nt];
        let cur = &mut self.x[row..row + nt];
        let span = self.free_span[j];
        fill_gaps(cur, span);
        for (lo, hi) in span {
            let mut i = lo + (color + j + lo) % 2;
            while i < hi {
                cur[i] = b[i] * inv[i];
                i += 2;
            }
        }
    }

    /// `r = b − A x` on row `j` (free nodes; 0 at fixed ones).
    #[inline(always)]
    pub(super) fn residual_row(&mut self, j: usize) {
        let mut r = std::mem::take(&mut self.r);
        self.kernel_row::<{ Self::SUB_MINUS }>(j, self.free_span[j], &self.x, &mut r, &self.mask, &self.b);
        self.r = r;
    }

    /// Gauss–Seidel update of the nodes of colour `color` (`(i + j) % 2`) in row `j` within its
    /// free span (outside it every node is fixed and `x` stays 0).
    #[inline(always)]
    pub(super) fn smooth_row(&mut self, j: usize, color: usize) {
        for (lo, hi) in self.free_span[j] {
            self.smooth_range(j, color, lo, hi);
        }
    }

    /// [`Level::smooth_row`] on the columns `lo..hi`.
    #[inline(always)]
    pub(super) fn smooth_range(&mut self, j: usize, color: usize, lo: usize, hi: usize) {
        let nt = self.nt;
        let row = j * nt;
        let ce = &self.ce[row..row + nt];
        let cn_s = &self.cn[row - nt..row];
        let cn_n = &self.cn[row..row + nt];
        let inv = &self.inv_d[row..row + nt];
        let b = &self.b[row..row + nt];
        let (below, rest) = self.x.split_at_mut(row);
        let below = &below[row - nt..];
        let (cur, above) = rest.split_at_mut(nt);
        let above = &above[..nt];
        #[inline(always)]
        #[allow(clippy::too_many_arguments)]
        fn upd(cur: &mut [f64], b: &[f64], ce: &[f64], cn_n: &[f64], cn_s: &[f64], above: &[f64], below: &[f64], inv: &[f64], i: usize, iw: usize, ie: usize) {
            let s = b[i] + ce[i] * cur[ie] + ce[iw] * cur[iw] + cn_n[i] * above[i] + cn_s[i] * below[i];
            cur[i] = s * inv[i];
        }
        let mut i = lo + (color + j + lo) % 2;
        if i >= hi {
            return;
        }
        if i == 0 {
            upd(cur, b, ce, cn_n, cn_s, above, below, inv, 0, nt - 1, 1);
            i = 2;
        }
        // interior nodes of this colour: 1 ≤ i ≤ nt − 2 and i < hi, step 2
        let end = hi.min(nt - 1);
        let mut k = i;
        while k < end {
            // SAFETY: 1 ≤ k − 1 < k + 1 < nt and every slice has length nt.
            unsafe {
                let s = *b.get_unchecked(k)
                    + *ce.get_unchecked(k) * *cur.get_unchecked(k + 1)
                    + *ce.get_unchecked(k - 1) * *cur.get_unchecked(k - 1)
                    + *cn_n.get_unchecked(k) * *above.get_unchecked(k)
                    + *cn_s.get_unchecked(k) * *below.get_unchecked(k);
                *cur.get_unchecked_mut(k) = s * *inv.get_unchecked(k);
            }
            k += 2;
        }
        if k + 1 == nt && k < hi {
            upd(cur, b, ce, cn_n, cn_s, above, below, inv, k, k - 1, 0);
        }
    }

    /// Projected Gauss–Seidel update of the nodes of colour `color` in row `j` for the LCP
    /// ([`Hierarchy::projected_sweeps`]): `P = max(0, (f + Σ c_nb P_nb)/d)`, 0 at boundary nodes.
    #[inline(always)]
    pub(super) fn projected_row(&mut self, j: usize, color: usize) {
        let nt = self.nt;
        let row = j * nt;
        let ce = &self.ce[row..row + nt];
        let cn_s = &self.cn[row - nt..row];
        let cn_n = &self.cn[row..row + nt];
        let inv = &self.inv_diag[row..row + nt];
        let f = &self.src[row..row + nt];
        let int = &self.interior[row..row + nt];
        let (below, rest) = self.u.split_at_mut(row);
        let below = &below[row - nt..];
        let (cur, above) = rest.split_at_mut(nt);
        let above = &above[..nt];
        let upd = |cur: &mut [f64], i: usize, iw: usize, ie: usize| {
            let s = f[i] + ce[i] * cur[ie] + ce[iw] * cur[iw] + cn_n[i] * above[i] + cn_s[i] * below[i];
            cur[i] = (s * inv[i]).max(0.0) * int[i];
        };
        let mut i = (color + j) % 2;
        if i == 0 {
            upd(cur, 0, nt - 1, 1);
            i = 2;
        }
        while i + 1 < nt {
            // SAFETY: 1 ≤ i − 1 < i + 1 < nt and every slice has length nt.
            unsafe {
                let s = *f.get_unchecked(i)
                    + *ce.get_unchecked(i) * *cur.get_unchecked(i + 1)
                    + *ce.get_unchecked(i - 1) * *cur.get_unchecked(i - 1)
                    + *cn_n.get_unchecked(i) * *above.get_unchecked(i)
                    + *cn_s.get_unchecked(i) * *below.get_unchecked(i);
                *cur.get_unchecked_mut(i) = (s * *inv.get_unchecked(i)).max(0.0) * *int.get_unchecked(i);
            }
            i += 2;
        }
        if i + 1 == nt {
            upd(cur, i, i - 1, 0);
        }
    }

    pub(super) const PLAIN: u8 = 0;
    pub(super) const MINUS_SUB: u8 = 1;
    pub(super) const SUB_MINUS: u8 = 2;

    /// One pass of the five-point operator: `out = m·(A v)` (`PLAIN`), `m·(A v − s)`
    /// (`MINUS_SUB`) or `m·(s − A v)` (`SUB_MINUS`); 0 on the edge rows. The interior of each
    /// row is written on equal-length slices so that the loop vectorises.
    pub(super) fn kernel<const MODE: u8>(&self, v: &[f64], out: &mut [f64], mask: &[f64], sub: &[f64]) {
        let nt = self.nt;
        out[..nt].fill(0.0);
        out[(self.nz - 1) * nt..].fill(0.0);
        for j in 1..self.nz - 1 {
            self.kernel_row::<MODE>(j, [(0, nt), (nt, nt)], v, out, mask, sub);
        }
    }

    /// Row `j` (not an edge row) of [`Level::kernel`] on the column ranges `span`; 0 on the
    /// other columns (where `mask` is 0).
    #[inline(always)]
    #[allow(clippy::too_many_arguments)]
    pub(super) fn kernel_row<const MODE: u8>(&self, j: usize, span: Span, v: &[f64], out: &mut [f64], mask: &[f64], sub: &[f64]) {
        let row = j * self.nt;
        fill_gaps(&mut out[row..row + self.nt], span);
        for (lo, hi) in span {
            self.kernel_range::<MODE>(j, lo, hi, v, out, mask, sub);
        }
    }

    /// [`Level::kernel_row`] on the columns `lo..hi` (the others untouched).
    #[inline(always)]
    #[allow(clippy::too_many_arguments)]
    pub(super) fn kernel_range<const MODE: u8>(&self, j: usize, lo: usize, hi: usize, v: &[f64], out: &mut [f64], mask: &[f64], sub: &[f64]) {
        #[inline(always)]
        fn finish<const MODE: u8>(m: f64, a: f64, s: f64) -> f64 {
            match MODE {
                0 => m * a,
                1 => m * (a - s),
                _ => m * (s - a),
            }
        }
        let nt = self.nt;
        let row = j * nt;
        let ce = &self.ce[row..row + nt];
        let cs = &self.cn[row - nt..row];
        let cnn = &self.cn[row..row + nt];
        let d = &self.diag[row..row + nt];
        let m = &mask[row..row + nt];
        let sb = &sub[row..row + nt];
        let vb = &v[row - nt..row];
        let vc = &v[row..row + nt];
        let va = &v[row + nt..row + 2 * nt];
        let o = &mut out[row..row + nt];
        if lo == 0 && hi > 0 {
            let a0 = d[0] * vc[0] - ce[0] * vc[1] - ce[nt - 1] * vc[nt - 1] - cnn[0] * va[0] - cs[0] * vb[0];
            o[0] = finish::<MODE>(m[0], a0, sb[0]);
        }
        if hi == nt && lo < nt {
            let an = d[nt - 1] * vc[nt - 1] - ce[nt - 1] * vc[0] - ce[nt - 2] * vc[nt - 2] - cnn[nt - 1] * va[nt - 1] - cs[nt - 1] * vb[nt - 1];
            o[nt - 1] = finish::<MODE>(m[nt - 1], an, sb[nt - 1]);
        }
        // the interior columns of the range, 1 ≤ i ≤ nt − 2
        let (a, b) = (lo.max(1), hi.min(nt - 1));
        if a >= b {
            return;
        }
        let (d1, ce0, ce1, cn1, cs1) = (&d[a..b], &ce[a - 1..b - 1], &ce[a..b], &cnn[a..b], &cs[a..b]);
        let (vw, vcc, ve, va1, vb1) = (&vc[a - 1..b - 1], &vc[a..b], &vc[a + 1..b + 1], &va[a..b], &vb[a..b]);
        let (m1, s1) = (&m[a..b], &sb[a..b]);
        let o1 = &mut o[a..b];
        let n = b - a;
        for i in 0..n {
            let a = d1[i] * vcc[i] - ce1[i] * ve[i] - ce0[i] * vw[i] - cn1[i] * va1[i] - cs1[i] * vb1[i];
            o1[i] = finish::<MODE>(m1[i], a, s1[i]);
        }
    }
}

impl Level {
    /// Right-hand sides of the linearised Reynolds equation at the converged pressure `p0` of
    /// this level, for a journal perturbation `δH = s(Z)·(cos θ, sin θ)[dir]` (`dir` 0: along
    /// the load, `X`; 1: across it, `Y`), on the cavitation set of `p0` (the free nodes):
    /// - `disp`: displacement, `∂f/∂X − (∂A/∂X) p0` — the derivative of `A(H) P = f(H)` with
    ///   the face conductances `c = H³ k` differentiated, `∂c/∂X = 3H² (∂H/∂X) k`;
    /// - `vel`: velocity `dX/d(ωt)`, the squeeze term of the time-dependent Reynolds equation,
    ///   `−2 ∂H/∂(ωt)` integrated over the cell (seed 002 eq. (4) with `∂h/∂t`; Lund 1987).
    ///
    /// Both are 0 at fixed (boundary or cavitated) nodes. `s` is the axial shape of the
    /// perturbation (1 for a translation).
    pub(crate) fn linearised_sources(&self, film: &Film, alpha: f64, dir: usize, s: &dyn Fn(f64) -> f64, p0: &[f64], disp: &mut [f64], vel: &mut [f64]) {
        let (nt, nz, dt, dz) = (self.nt, self.nz, self.dt, self.dz);
        let trig = |t: f64| if dir == 0 { t.cos() } else { t.sin() };
        // ∫ trig over a cell: d/dθ of the antiderivative at the faces
        let anti = |t: f64| if dir == 0 { t.sin() } else { -t.cos() };
        let ke = dz / dt;
        let kn = alpha * dt / dz;
        let g_f: Vec<f64> = (0..nt).map(|i| trig(self.theta0 + (i as f64 + 0.5) * dt)).collect();
        let a_f: Vec<f64> = (0..nt).map(|i| anti(self.theta0 + (i as f64 + 0.5) * dt)).collect();
        let g_n: Vec<f64> = (0..nt).map(|i| trig(self.theta0 + i as f64 * dt)).collect();
        let (s_face, s_node): (Vec<f64>, Vec<f64>) =
            (0..nz).map(|j| (s(((j as f64 + 0.5) * dz).min(1.0)), s(j as f64 * dz))).unzip();
        disp.fill(0.0);
        vel.fill(0.0);
        // derivatives of the face conductances
        let mut dce = vec![0.0; nt * nz];
        let mut dcn = vec![0.0; nt * nz];
        // the face angles' cosines and sines, once per column (not per node)
        let (cos_f, sin_f): (Vec<f64>, Vec<f64>) = (0..nt)
            .map(|i| {
                let tf = self.theta0 + (i as f64 + 0.5) * dt;
                (tf.cos(), tf.sin())
            })
            .unzip();
        for j in 0..nz {
            let z = j as f64 * dz;
            let r = film.row(z);
            let rn = film.row((z + 0.5 * dz).min(1.0));
            for i in 0..nt {
                let k = j * nt + i;
                let he = 1.0 + r.gamma + r.x * cos_f[i] + r.y * sin_f[i];
                dce[k] = 3.0 * he * he * s_node[j] * g_f[i] * ke;
                if j + 1 < nz {
                    let hn = 1.0 + rn.gamma + rn.x * self.cos_n[i] + rn.y * self.sin_n[i];
                    dcn[k] = 3.0 * hn * hn * s_face[j] * g_n[i] * kn;
                }
            }
        }
        for j in 1..nz - 1 {
            for i in 0..nt {
                let k = j * nt + i;
                if self.fixed[k] != FREE {
                    continue;
                }
                let iw = if i == 0 { nt - 1 } else { i - 1 };
                let ie = if i + 1 == nt { 0 } else { i + 1 };
                let (kw, kee) = (j * nt + iw, j * nt + ie);
                let dap = dce[k] * (p0[k] - p0[kee]) + dce[kw] * (p0[k] - p0[kw]) + dcn[k] * (p0[k] - p0[k + nt]) + dcn[k - nt] * (p0[k] - p0[k - nt]);
                // f = −∂H/∂θ ΔθΔZ in flux form
                let df = -dz * s_node[j] * (g_f[i] - g_f[iw]);
                disp[k] = df - dap;
                vel[k] = -2.0 * dz * s_node[j] * (a_f[i] - a_f[iw]);
            }
        }
    }
}
