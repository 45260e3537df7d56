//! The discretisation on one grid ([`Problem`]): its construction, the squeeze terms, the fields
//! and Reynolds residual at an iterate, the matrix-free Newton matrix and the complementarity rows.

use super::*;

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
            thermal: None,
        }
    }

    /// The problem with the thermal multipliers `factors` at its nodes (physical position
    /// `x = sign·X·a`, `y = Y·a`); `None`: unchanged (isothermal).
    pub(super) fn with_thermal(mut self, factors: Option<&Factors2d>, a: f64, sign: f64) -> Self {
        if let Some(f) = factors {
            let (nx, n) = (self.nx, self.nx * self.ny);
            let (mut fp, mut fw) = (vec![1.0; n], vec![1.0; n]);
            for k in 0..n {
                let (p, w) = f.at(sign * self.x[k % nx] * a, self.y[k / nx] * a);
                fp[k] = p;
                fw[k] = w;
            }
            self.thermal = Some((fp, fw));
        }
        self
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
            let mut eps = rho * h * h * h * (-ln_eta).exp();
            let mut deps = eps * (drho / rho - dln) * self.p_ref;
            let (mut rho_w, mut drho_w) = (rho, drho * self.p_ref);
            // Thermal: the generalized Reynolds multipliers, held fixed in the Newton solve
            // (seed 000 eq. 2; see `Factors2d`).
            if let Some((fp, fw)) = &self.thermal {
                eps *= fp[k];
                deps *= fp[k];
                rho_w *= fw[k];
                drho_w *= fw[k];
            }
            v.h[k] = h;
            v.rho[k] = rho_w;
            v.drho[k] = drho_w;
            v.eps[k] = eps;
            v.deps[k] = deps;
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

    /// The face coefficients and `3ε/H` of [`Buffers`] at the iterate `v` (before a linear solve's
    /// [`Problem::apply`]s): `face_of(θ, ε_k, ε_{k+1})` and `face_of(θ, ε_k, ε_{k+nx})`.
    pub(super) fn faces(&self, v: &Fields, buf: &mut Buffers) {
        let (n, nx) = (self.nx * self.ny, self.nx);
        let e = &v.eps;
        buf.fx.clear();
        buf.fy.clear();
        buf.e3h.clear();
        buf.fx.extend((0..n).map(|k| if k + 1 < n { face_of(self.theta, e[k], e[k + 1]) } else { (0.0, 0.0, 0.0) }));
        buf.fy.extend((0..n).map(|k| if k + nx < n { face_of(self.theta, e[k], e[k + nx]) } else { (0.0, 0.0, 0.0) }));
        buf.e3h.extend((0..n).map(|k| 3.0 * e[k] / v.h[k]));
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
            buf.de[k] = v.deps[k] * buf.dp[k] + buf.e3h[k] * dh;
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
            let de = &buf.de;
            let mut df = 0.0;
            // The faces of `Problem::faces`, each with this node first (`face_of` is symmetric
            // but for the order of its weights).
            let (xe, xw, yn, ys) = (buf.fx[k], buf.fx[k - 1], buf.fy[k], buf.fy[k - nx]);
            for (nb, d2, (ef, w1, w2)) in [(k + 1, dx2, xe), (k - 1, dx2, (xw.0, xw.2, xw.1)), (k + nx, dy2, yn), (k - nx, dy2, (ys.0, ys.2, ys.1))] {
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
