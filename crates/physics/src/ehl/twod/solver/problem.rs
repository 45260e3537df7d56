use super::*;

/// The Poiseuille coefficient at a cell face from its two nodes' `ε = ρ̄H³/η̄`, with its
/// derivatives: the geometric mean `sqrt(ε_a ε_b)`, i.e. `ln ε` interpolated linearly to the face
/// (for Barus viscosity and an incompressible film of equal thickness, `ε` at the face's mean
/// pressure). Second order like the arithmetic mean for smooth `ε`, but `ε` falls by orders of
/// magnitude within a cell where the pressure rises into the contact, and there the arithmetic
/// mean (dominated by the upstream node) overstates the back-flow and thins the film: measured on
/// the circular M ≈ 300, L ≈ 11 contact (`BENCHMARKS.md`, issue 16) the central film's error on
/// 65² is −28 % with the arithmetic mean and −5 % with the geometric one (harmonic +16 %,
/// logarithmic −14 %), all converging to the same fine-grid limit.
/// `theta < 1`: the blend `(1 − θ)·arithmetic + θ·geometric` of the continuation ([`solve_level`]).
#[inline]
pub(super) fn face_of(theta: f64, a: f64, b: f64) -> (f64, f64, f64) {
    let g = (a * b).sqrt();
    let t = 1.0 - theta;
    (t * 0.5 * (a + b) + theta * g, 0.5 * t + theta * 0.5 * g / a, 0.5 * t + theta * 0.5 * g / b)
}

impl Problem {
    pub(super) fn new(input: &Ehl2dInput, s: &Scales, d: Domain, nx: usize, ny: usize, near: usize) -> Self {
        let NodeGrid { dx, dy, x, y, geom } = node_grid(input, s, d, nx, ny);
        let mut unk = vec![usize::MAX; nx * ny];
        let mut nodes = Vec::with_capacity((nx - 2) * (ny - 2));
        for j in 1..ny - 1 {
            for i in 1..nx - 1 {
                unk[j * nx + i] = nodes.len();
                nodes.push(j * nx + i);
            }
        }
        Problem {
            nx,
            ny,
            dx,
            dy,
            x,
            y,
            geom,
            lambda: s.lambda,
            kappa: 0.0,
            q_old: vec![0.0; nx * ny],
            target: None,
            load: s.load,
            p_ref: s.p_ref,
            rheo: PressureRheology::new(&input.lubricant, input.temperature),
            defl: Deflection::new(nx, ny, dx, dy, s.c_def),
            near,
            floor: FILM_FLOOR * s.h_est,
            second: true,
            theta: 1.0,
            unk,
            nodes,
            pattern: std::cell::RefCell::new(None),
            kept: None,
            factorisations: 0,
            forcing: None,
        }
    }

    /// The squeeze term of the problem itself: none (`κ = 0`, steady) or the transient step's
    /// ([`Problem::target`]).
    pub(super) fn restore_target(&mut self) {
        match &self.target {
            None => self.kappa = 0.0,
            Some((kappa, q)) => {
                self.kappa = *kappa;
                self.q_old.copy_from_slice(q);
            }
        }
    }

    /// A pseudo-time step `ΔT` ([`march`]) from the iterate with fields `v`: `κ_ps = λ/ΔT`,
    /// `(ρ̄H)_ps` the iterate's, on top of the problem's own squeeze term `(κ_t, q_t)`, if any:
    /// `κ = κ_t + κ_ps`, `q_old = (κ_t q_t + κ_ps (ρ̄H)_ps)/κ` (the residual's
    /// `−κ_t (ρ̄H − q_t) − κ_ps (ρ̄H − (ρ̄H)_ps)` in one term).
    pub(super) fn pseudo_step(&mut self, dt: f64, v: &Fields) {
        for (q, (r, h)) in self.q_old.iter_mut().zip(v.rho.iter().zip(&v.h)) {
            *q = r * h;
        }
        self.kappa = self.lambda / dt;
        if let Some((kt, qt)) = &self.target {
            let kp = self.kappa;
            self.kappa = kt + kp;
            for (q, b) in self.q_old.iter_mut().zip(qt) {
                *q = (kt * b + kp * *q) / self.kappa;
            }
        }
    }

    /// `ρ̄H` at the nodes (the film the Reynolds terms see) at `(p, h0)`; `None` when not finite.
    pub(super) fn mass(&mut self, p: &[f64], h0: f64) -> Option<Vec<f64>> {
        let mut v = Fields::default();
        self.evaluate(p, h0, &mut v).then(|| v.rho.iter().zip(&v.h).map(|(r, h)| r * h).collect())
    }

    /// Upwind stencil of `∂Q/∂X` at column `i`: `(offset back, weight)`.
    pub(super) fn wedge(&self, i: usize) -> [(usize, f64); 3] {
        if i >= 2 && self.second {
            [(0, 1.5 / self.dx), (1, -2.0 / self.dx), (2, 0.5 / self.dx)]
        } else {
            [(0, 1.0 / self.dx), (1, -1.0 / self.dx), (0, 0.0)]
        }
    }

    /// Weights of `ρ̄H` at `(offset back, weight)` in the convective and squeeze terms of column
    /// `i`: `λ ∂(ρ̄H)/∂X + κ ρ̄H` (the residual subtracts `Σ w ρ̄H` and adds `κ (ρ̄H)_old`).
    pub(super) fn stencil(&self, i: usize) -> [(usize, f64); 3] {
        let mut w = self.wedge(i);
        for e in w.iter_mut() {
            e.1 *= self.lambda;
        }
        w[0].1 += self.kappa;
        w
    }

    /// Fields at `(p, h0)` (the film held at the floor where it falls below); `false` when a value
    /// is not finite.
    pub(super) fn evaluate(&mut self, p: &[f64], h0: f64, v: &mut Fields) -> bool {
        let n = self.nx * self.ny;
        for a in [&mut v.w, &mut v.h, &mut v.rho, &mut v.drho, &mut v.eps, &mut v.deps, &mut v.f, &mut v.on, &mut v.hraw] {
            a.resize(n, 0.0);
        }
        self.defl.apply(p, &mut v.w);
        for k in 0..n {
            let mut h = h0 + self.geom[k] + v.w[k];
            v.hraw[k] = h;
            v.on[k] = 1.0;
            if h < self.floor {
                h = self.floor;
                v.on[k] = 0.0;
            }
            if !(h > 0.0 && h.is_finite()) {
                return false;
            }
            let (ln_eta, dln, rho, drho) = self.rheo.at(p[k] * self.p_ref);
            let ln_eta = ln_eta.min(LN_ETA_CAP);
            let eps = rho * h * h * h * (-ln_eta).exp();
            v.h[k] = h;
            v.rho[k] = rho;
            v.drho[k] = drho * self.p_ref;
            v.eps[k] = eps;
            v.deps[k] = eps * (drho / rho - dln) * self.p_ref;
        }
        let (nx, dx2, dy2) = (self.nx, self.dx * self.dx, self.dy * self.dy);
        let mut sum = 0.0;
        for &k in &self.nodes {
            let i = k % nx;
            let e = &v.eps;
            let exp_ = face_of(self.theta, e[k], e[k + 1]).0;
            let exm = face_of(self.theta, e[k], e[k - 1]).0;
            let eyp = face_of(self.theta, e[k], e[k + nx]).0;
            let eym = face_of(self.theta, e[k], e[k - nx]).0;
            let pois = (exp_ * (p[k + 1] - p[k]) - exm * (p[k] - p[k - 1])) / dx2
                + (eyp * (p[k + nx] - p[k]) - eym * (p[k] - p[k - nx])) / dy2;
            let mut wedge = 0.0;
            for (s, wt) in self.stencil(i) {
                wedge += wt * v.rho[k - s] * v.h[k - s];
            }
            v.f[k] = pois - wedge + self.kappa * self.q_old[k];
            sum += p[k];
        }
        v.g = sum * self.dx * self.dy / self.load - 1.0;
        v.f.iter().all(|x| x.is_finite()) && v.g.is_finite()
    }

    /// `out = A x`: the scaled Newton matrix applied to `x` (`dP` at the unknowns, then `dH0`).
    pub(super) fn apply(&mut self, p: &[f64], v: &Fields, active: &[u8], c: &[f64], x: &[f64], out: &mut [f64], buf: &mut Buffers) {
        let n = self.nx * self.ny;
        let m = self.nodes.len();
        buf.dp.resize(n, 0.0);
        buf.dw.resize(n, 0.0);
        buf.dq.resize(n, 0.0);
        buf.de.resize(n, 0.0);
        buf.dp.iter_mut().for_each(|d| *d = 0.0);
        for (u, &k) in self.nodes.iter().enumerate() {
            buf.dp[k] = x[u];
        }
        let dh0 = x[m];
        self.defl.apply(&buf.dp, &mut buf.dw);
        for k in 0..n {
            let dh = (dh0 + buf.dw[k]) * v.on[k];
            buf.dq[k] = v.drho[k] * buf.dp[k] * v.h[k] + v.rho[k] * dh;
            buf.de[k] = v.deps[k] * buf.dp[k] + 3.0 * v.eps[k] / v.h[k] * dh;
        }
        let (nx, dx2, dy2) = (self.nx, self.dx * self.dx, self.dy * self.dy);
        let mut sum = 0.0;
        for (u, &k) in self.nodes.iter().enumerate() {
            let dp = &buf.dp;
            sum += dp[k];
            if active[u] == CAVITATED {
                out[u] = dp[k];
                continue;
            }
            if active[u] == CONTACT {
                out[u] = self.contact_scale() * (dh0 + buf.dw[k]);
                continue;
            }
            let i = k % nx;
            let (e, de) = (&v.eps, &buf.de);
            let mut df = 0.0;
            for (nb, d2) in [(k + 1, dx2), (k - 1, dx2), (k + nx, dy2), (k - nx, dy2)] {
                let (ef, w1, w2) = face_of(self.theta, e[k], e[nb]);
                let def = w1 * de[k] + w2 * de[nb];
                df += (def * (p[nb] - p[k]) + ef * (dp[nb] - dp[k])) / d2;
            }
            let mut wedge = 0.0;
            for (s, wt) in self.stencil(i) {
                wedge += wt * buf.dq[k - s];
            }
            out[u] = c[u] * (df - wedge);
        }
        out[m] = sum * self.dx * self.dy / self.load;
    }

    /// The near-field preconditioner (scaled like the Newton matrix) and the row scales `c`;
    /// `factor` false: the row scales and the active set only (`None`).
    /// `observer`: a large factorisation runs beside the caller, which polls it
    /// ([`NearLu::new_watched`]); an interrupt there is `Err`.
    pub(super) fn precondition(&self, p: &[f64], v: &Fields, active: &mut [u8], c: &mut [f64], factor: bool, observer: &dyn Observer) -> Result<Option<Precond>, SolveError> {
        let (nx, ny, dx2, dy2) = (self.nx, self.ny, self.dx * self.dx, self.dy * self.dy);
        let m = self.nodes.len();
        let r = self.near as isize;
        if !factor {
            // The diagonal alone, summed in the order the rows below push its entries (the same
            // row scales to the last bit): the Poiseuille terms, then per wedge point its own
            // `ρ̄'H` term and the deflection self-coefficient reaching this node.
            for (u, &k) in self.nodes.iter().enumerate() {
                let i = k % nx;
                let e = &v.eps;
                let mut diag = 0.0;
                for (nb, d2) in [(k + 1, dx2), (k - 1, dx2), (k + nx, dy2), (k - nx, dy2)] {
                    let (ef, w1, _) = face_of(self.theta, e[k], e[nb]);
                    diag += -ef / d2 + w1 * v.deps[k] * (p[nb] - p[k]) / d2;
                }
                for (s, wt) in self.stencil(i) {
                    if wt == 0.0 {
                        continue;
                    }
                    let kk = k - s;
                    if s == 0 {
                        diag += -wt * v.drho[kk] * v.h[kk];
                    }
                    if s <= self.near {
                        diag += -wt * v.on[kk] * v.rho[kk] * self.defl.coefficient(s, 0);
                    }
                }
                let cu = 1.0 / diag.abs().max(1e-300);
                c[u] = cu;
                active[u] = self.row_kind(p, v, cu, k);
            }
            return Ok(None);
        }
        // Every row's entries (column, value), cavitated rows too: the pattern is then that of the
        // grid alone, its symbolic LU computed once ([`NearPattern`]).
        let mut ent: Vec<(usize, f64)> = Vec::with_capacity(m * (10 + (2 * self.near + 3) * (2 * self.near + 1)));
        let mut row_ptr: Vec<usize> = Vec::with_capacity(m + 1);
        row_ptr.push(0);
        let mut row: Vec<(usize, f64)> = Vec::with_capacity(64);
        for (u, &k) in self.nodes.iter().enumerate() {
            let (i, j) = (k % nx, k / nx);
            row.clear();
            let e = &v.eps;
            for (nb, d2) in [(k + 1, dx2), (k - 1, dx2), (k + nx, dy2), (k - nx, dy2)] {
                let (ef, w1, w2) = face_of(self.theta, e[k], e[nb]);
                let dpf = p[nb] - p[k];
                row.push((u, -ef / d2 + w1 * v.deps[k] * dpf / d2));
                if self.unk[nb] != usize::MAX {
                    row.push((self.unk[nb], ef / d2 + w2 * v.deps[nb] * dpf / d2));
                }
            }
            for (s, wt) in self.stencil(i) {
                if wt == 0.0 {
                    continue;
                }
                let kk = k - s;
                let (ki, kj) = (i - s, j);
                let lw = -wt;
                if self.unk[kk] != usize::MAX {
                    row.push((self.unk[kk], lw * v.drho[kk] * v.h[kk]));
                }
                let lw = lw * v.on[kk];
                row.push((m, lw * v.rho[kk]));
                for dj in -r..=r {
                    let lj = kj as isize + dj;
                    if lj < 1 || lj >= ny as isize - 1 {
                        continue;
                    }
                    for di in -r..=r {
                        let li = ki as isize + di;
                        if li < 1 || li >= nx as isize - 1 {
                            continue;
                        }
                        let l = lj as usize * nx + li as usize;
                        row.push((self.unk[l], lw * v.rho[kk] * self.defl.coefficient(di.unsigned_abs(), dj.unsigned_abs())));
                    }
                }
            }
            let diag: f64 = row.iter().filter(|(col, _)| *col == u).map(|(_, val)| val).sum();
            if poiseuille_film() {
                // The Poiseuille terms' film dependence `∂ε_f/∂H = w·3ε/H` at the row's node and
                // its four neighbours, through the near-field deflection, within the columns the
                // wedge terms already occupy (the pattern's box `i − 2 − r … i + r`,
                // `j − r … j + r`): with the geometric face mean (`θ → 1`) a face between an
                // inlet node (large ε) and a contact node (small ε) weighs the contact node's film
                // by `1.5 sqrt(ε_b/ε_a)`, which the wedge-only near field left out. The row scale
                // `c` (above) is unchanged, so is the residual.
                let lo = (if i >= 2 && self.second { 2 } else { 1 }) + r;
                let mut pts = [(k, 0.0); 5];
                for (q, (nb, d2)) in [(k + 1, dx2), (k - 1, dx2), (k + nx, dy2), (k - nx, dy2)].into_iter().enumerate() {
                    let (_, w1, w2) = face_of(self.theta, e[k], e[nb]);
                    let dpf = (p[nb] - p[k]) / d2;
                    pts[0].1 += w1 * 3.0 * e[k] / v.h[k] * v.on[k] * dpf;
                    pts[q + 1] = (nb, w2 * 3.0 * e[nb] / v.h[nb] * v.on[nb] * dpf);
                }
                for &(q, a) in &pts {
                    if a == 0.0 || !a.is_finite() {
                        continue;
                    }
                    let (qi, qj) = ((q % nx) as isize, (q / nx) as isize);
                    row.push((m, a));
                    for dj in -r..=r {
                        let lj = j as isize + dj;
                        if lj < 1 || lj >= ny as isize - 1 || (lj - qj).abs() > r {
                            continue;
                        }
                        for di in -lo..=r {
                            let li = i as isize + di;
                            if li < 1 || li >= nx as isize - 1 || (li - qi).abs() > r {
                                continue;
                            }
                            let l = lj as usize * nx + li as usize;
                            row.push((self.unk[l], a * self.defl.coefficient((li - qi).unsigned_abs(), (lj - qj).unsigned_abs())));
                        }
                    }
                }
            }
            let cu = 1.0 / diag.abs().max(1e-300);
            c[u] = cu;
            active[u] = self.row_kind(p, v, cu, k);
            ent.extend(row.iter().map(|&(col, val)| (col, cu * val)));
            row_ptr.push(ent.len());
        }
        // The bordered system `[B u; wᵀ 0]` (the `H0` column `u`, the load row `w`) by its Schur
        // complement: factorising it with the dense border made the sparse LU fill in (35 s at
        // 97², measured), the block `B` alone factorises in a fraction of a second.
        let pattern = {
            let mut cache = self.pattern.borrow_mut();
            match cache.as_ref().filter(|pat| pat.covers(m, &row_ptr, &ent)) {
                Some(pat) => pat.clone(),
                None => {
                    let order = nested_dissection(nx - 2, ny - 2, 2 + 2 * self.near, 2 * self.near.max(1));
                    let Some(pat) = NearPattern::new(m, &row_ptr, &ent, order) else { return Ok(None) };
                    let pat = std::sync::Arc::new(pat);
                    *cache = Some(pat.clone());
                    pat
                }
            }
        };
        let mut ucol = vec![0.0; m];
        let mut values = vec![0.0; pattern.row_idx.len()];
        let mut slot = vec![usize::MAX; m];
        for u in 0..m {
            let (a, b) = (pattern.row_ptr[u], pattern.row_ptr[u + 1]);
            for (&col, &pos) in pattern.row_col[a..b].iter().zip(&pattern.row_pos[a..b]) {
                slot[col] = pos;
            }
            if active[u] == CAVITATED {
                values[slot[u]] = 1.0;
                continue;
            }
            if active[u] == CONTACT {
                // `s (H0 + W_k)`: the deflection's near field about the node (inside the box the
                // row's wedge terms occupy) and the `H0` border.
                let sc = self.contact_scale();
                let k = self.nodes[u];
                let (i, j) = ((k % nx) as isize, (k / nx) as isize);
                ucol[u] += sc;
                for lj in (j - r).max(1)..=(j + r).min(ny as isize - 2) {
                    for li in (i - r).max(1)..=(i + r).min(nx as isize - 2) {
                        let l = lj as usize * nx + li as usize;
                        values[slot[self.unk[l]]] += sc * self.defl.coefficient((li - i).unsigned_abs(), (lj - j).unsigned_abs());
                    }
                }
                continue;
            }
            for &(col, val) in &ent[row_ptr[u]..row_ptr[u + 1]] {
                if col == m {
                    ucol[u] += val;
                } else {
                    values[slot[col]] += val;
                }
            }
        }
        let Some(lu) = NearLu::new_watched(pattern, values, observer)? else { return Ok(None) };
        lu.solve_in_place(&mut ucol);
        let sum_bu = ucol.iter().sum::<f64>();
        Ok((sum_bu.is_finite() && ucol.iter().all(|x| x.is_finite())).then_some(Precond { lu, bu: ucol, sum_bu, c: c.to_vec(), active: active.to_vec() }))
    }

    /// The load row's weight `ΔX ΔY / W` (the `wᵀ` of [`Precond`]).
    pub(super) fn load_weight(&self) -> f64 {
        self.dx * self.dy / self.load
    }

    pub(super) fn phi(&self, p: &[f64], v: &Fields, c: &[f64], out: &mut Vec<f64>) {
        out.clear();
        let contact = floor_contact();
        let sc = self.contact_scale();
        for (u, &k) in self.nodes.iter().enumerate() {
            let r = p[k].min(-c[u] * v.f[k]);
            out.push(if contact { r.min(sc * (v.hraw[k] - self.floor)) } else { r });
        }
    }

    /// Scale of the contact row `s (H − floor)`: `1/C₀₀` (the deflection's self-coefficient), so
    /// that its derivative in the node's own pressure is 1, as a cavitated row's.
    pub(super) fn contact_scale(&self) -> f64 {
        1.0 / self.defl.coefficient(0, 0)
    }

    /// The row of node `k` in the semismooth Newton matrix: the complementarity
    /// `min(P, −c F, s (H − floor)) = 0` of the three regimes — cavitated (`P = 0`, `F ≤ 0`),
    /// lubricated (`F = 0`, `P ≥ 0`, `H ≥ floor`) and in contact at the film floor (`H = floor`,
    /// the pressure free and set by it, `F ≤ 0`: the film carries less than the node's pressure,
    /// the rest is the floor's, as in the unified mixed-lubrication treatments, Hu & Zhu, ASME
    /// J. Tribol. 122 (2000)). The Reynolds terms keep `max(H, floor)`; without the contact row a
    /// node at the floor had no film feedback in the Jacobian and Newton asked for pressure
    /// changes of 100× P there (issue 16, `ehl2d-12`'s roller trace). Ties: cavitated, then
    /// lubricated.
    pub(super) fn row_kind(&self, p: &[f64], v: &Fields, cu: f64, k: usize) -> u8 {
        let (a, b) = (p[k], -cu * v.f[k]);
        if !floor_contact() {
            return if a <= b { CAVITATED } else { FLUID };
        }
        let h = self.contact_scale() * (v.hraw[k] - self.floor);
        if a <= b && a <= h {
            CAVITATED
        } else if h < b {
            CONTACT
        } else {
            FLUID
        }
    }
}

impl Problem {
    /// Poiseuille and wedge terms of the steady Reynolds operator at the interior nodes for given
    /// node fields (the truncation probe).
    pub(super) fn pieces(&self, p: &[f64], h: &[f64], rho: &[f64], e: &[f64]) -> (Vec<f64>, Vec<f64>) {
        let (nx, dx2, dy2) = (self.nx, self.dx * self.dx, self.dy * self.dy);
        let mut pois = vec![0.0; p.len()];
        let mut wedge = vec![0.0; p.len()];
        for &k in &self.nodes {
            let i = k % nx;
            let f = |a: usize, b: usize| face_of(self.theta, e[a], e[b]).0;
            pois[k] = (f(k, k + 1) * (p[k + 1] - p[k]) - f(k, k - 1) * (p[k] - p[k - 1])) / dx2 + (f(k, k + nx) * (p[k + nx] - p[k]) - f(k, k - nx) * (p[k] - p[k - nx])) / dy2;
            for (s, wt) in self.wedge(i) {
                wedge[k] += self.lambda * wt * rho[k - s] * h[k - s];
            }
        }
        (pois, wedge)
    }
}
