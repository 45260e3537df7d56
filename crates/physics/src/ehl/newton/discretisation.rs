use super::*;

impl AsperityScale<'_> {
    pub(super) fn at(&self, h: f64) -> (f64, f64) {
        let (p, dp) = self.law.pressure(h * self.film_scale);
        (p / self.ph, dp * self.film_scale / self.ph)
    }
}

impl NodeFactors {
    pub(super) fn on(grid_x: &[f64], b: f64, f: &ThermalFactors) -> Self {
        let at = |v: &[f64], x: f64| interpolate(&f.x, v, x * b);
        NodeFactors {
            poiseuille: grid_x.iter().map(|&x| at(&f.poiseuille, x)).collect(),
            wedge: grid_x.iter().map(|&x| at(&f.wedge, x)).collect(),
            mass: grid_x.iter().map(|&x| at(&f.mass, x)).collect(),
        }
    }
}

impl Fields {
    pub(super) fn new(n: usize) -> Self {
        let z = vec![0.0; n];
        Fields {
            h: z.clone(),
            rho: z.clone(),
            drho: z.clone(),
            e: z.clone(),
            ep: z.clone(),
            eh: z.clone(),
            f: z.clone(),
            fp: z.clone(),
            pa: z.clone(),
            dpa: z,
            load: 0.0,
        }
    }
}

impl Discretisation<'_> {
    pub(super) fn n(&self) -> usize {
        self.grid.n
    }

    /// Wedge stencil at the interior node `i` (kept in `self.wedge`, see [`wedge_stencils`]).
    #[inline]
    pub(super) fn wedge(&self, i: usize) -> [(isize, f64); 3] {
        self.wedge[i]
    }
}

/// Wedge stencils of the interior nodes of `x` (the ends zero): `(offset, weight)` of
/// `d(ρ̄H)/dX`, upwind for the sign of `λ` (three-point one-sided derivative on the graded grid for
/// the second-order scheme). They depend on `λ` through its sign only (a continuation that scales
/// `λ` by positive factors keeps them).
pub(super) fn wedge_stencils(x: &[f64], lambda: f64, upwind: Upwind) -> Vec<[(isize, f64); 3]> {
    let n = x.len();
    let mut out = vec![[(0, 0.0); 3]; n];
    for (i, w) in out.iter_mut().enumerate().take(n.saturating_sub(1)).skip(1) {
        *w = wedge_at(x, lambda, upwind, i);
    }
    out
}

fn wedge_at(x: &[f64], lambda: f64, upwind: Upwind, i: usize) -> [(isize, f64); 3] {
    let second = upwind == Upwind::Second;
    if lambda >= 0.0 {
        let a = x[i] - x[i - 1];
        if second && i >= 2 {
            let b = x[i - 1] - x[i - 2];
            [(0, (2.0 * a + b) / (a * (a + b))), (-1, -(a + b) / (a * b)), (-2, a / (b * (a + b)))]
        } else {
            [(0, 1.0 / a), (-1, -1.0 / a), (0, 0.0)]
        }
    } else {
        let a = x[i + 1] - x[i];
        if second && i + 2 < x.len() {
            let b = x[i + 2] - x[i + 1];
            [(0, -(2.0 * a + b) / (a * (a + b))), (1, (a + b) / (a * b)), (2, -a / (b * (a + b)))]
        } else {
            [(0, -1.0 / a), (1, 1.0 / a), (0, 0.0)]
        }
    }
}

impl Discretisation<'_> {
    /// Evaluate the film, rheology and residuals at `(p, h0)`. `false` when the film is not
    /// positive everywhere or a value is not finite.
    pub(super) fn evaluate(&self, p: &[f64], h0: f64, v: &mut Fields) -> bool {
        let n = self.n();
        let x = &self.grid.x;
        self.grid.kernel.deflection(p, &mut v.h);
        for i in 0..n {
            let h = h0 + 0.5 * x[i] * x[i] - v.h[i];
            if !(h > 0.0 && h.is_finite()) {
                return false;
            }
            v.h[i] = h;
            let (pa, dpa) = match &self.asperity {
                Some(a) => a.at(h),
                None => (0.0, 0.0),
            };
            if !(pa.is_finite() && dpa.is_finite()) {
                return false;
            }
            v.pa[i] = pa;
            v.dpa[i] = dpa;
            v.fp[i] = p[i] - pa;
            let (ln_eta, dln, rho, drho) = self.rheology.at(v.fp[i] * self.ph);
            let ln_eta = ln_eta.min(LN_ETA_CAP);
            let ce = self.thermal.as_ref().map_or(1.0, |t| t.poiseuille[i]);
            v.rho[i] = rho;
            v.drho[i] = drho * self.ph;
            // `e^0 = 1` exactly: no `exp` at zero pressure.
            let visc = if ln_eta == 0.0 { 1.0 } else { (-ln_eta).exp() };
            v.e[i] = ce * rho * h * h * h * visc;
            v.ep[i] = v.e[i] * (v.drho[i] / rho - dln * self.ph);
            v.eh[i] = 3.0 * v.e[i] / h;
        }
        v.f[0] = 0.0;
        v.f[n - 1] = 0.0;
        let p = &v.fp;
        for i in 1..n - 1 {
            let er = 0.5 * (v.e[i] + v.e[i + 1]);
            let el = 0.5 * (v.e[i - 1] + v.e[i]);
            let (hl, hr) = (x[i] - x[i - 1], x[i + 1] - x[i]);
            let mut f = (er * (p[i + 1] - p[i]) / hr - el * (p[i] - p[i - 1]) / hl) / (0.5 * (hl + hr));
            if self.lambda != 0.0 {
                let mut d = 0.0;
                for (off, w) in self.wedge(i) {
                    let m = (i as isize + off) as usize;
                    d += w * v.rho[m] * self.wedge_factor(m) * v.h[m];
                }
                f -= self.lambda * d;
            }
            if self.kappa != 0.0 {
                f -= self.kappa * (self.mass_density(v, i) * v.h[i] - self.q_old[i]);
            }
            v.f[i] = f;
        }
        let sum: f64 = (0..n).map(|i| (v.fp[i] + v.pa[i]) * self.grid.cell[i]).sum();
        v.load = sum / (0.5 * PI) - 1.0;
        v.f.iter().all(|f| f.is_finite()) && v.load.is_finite()
    }

    /// Local derivatives of `F_i` with respect to the unknown (total) pressure `P` (offsets
    /// −2..=2) and through the film `H` (offsets −2..=2); with asperities `P_f = P − P_a(H)`, so
    /// `∂F/∂H` includes `−(∂F/∂P_f) dP_a/dH`.
    pub(super) fn local_derivatives(&self, v: &Fields, i: usize) -> ([f64; 5], [f64; 5]) {
        let (a, mut g) = self.fluid_derivatives(&v.fp, v, i);
        if self.asperity.is_some() {
            for o in 0..5 {
                let m = i as isize + o as isize - 2;
                if a[o] != 0.0 && m >= 0 && (m as usize) < self.n() {
                    g[o] -= a[o] * v.dpa[m as usize];
                }
            }
        }
        (a, g)
    }

    /// Local derivatives of `F_i`: direct in the fluid pressure (offsets −2..=2) and through the
    /// film `H` at fixed fluid pressure (offsets −2..=2).
    pub(super) fn fluid_derivatives(&self, p: &[f64], v: &Fields, i: usize) -> ([f64; 5], [f64; 5]) {
        let x = &self.grid.x;
        let mut a = [0.0; 5];
        let mut g = [0.0; 5];
        let er = 0.5 * (v.e[i] + v.e[i + 1]);
        let el = 0.5 * (v.e[i - 1] + v.e[i]);
        let (hl, hr) = (x[i] - x[i - 1], x[i + 1] - x[i]);
        let hc = 0.5 * (hl + hr);
        // Slopes (P_{i+1} − P_i)/h_R and (P_i − P_{i−1})/h_L.
        let sr = (p[i + 1] - p[i]) / hr;
        let sl = (p[i] - p[i - 1]) / hl;
        a[3] += (er / hr + 0.5 * v.ep[i + 1] * sr) / hc;
        a[2] += (0.5 * v.ep[i] * (sr - sl) - er / hr - el / hl) / hc;
        a[1] += (el / hl - 0.5 * v.ep[i - 1] * sl) / hc;
        g[3] += 0.5 * v.eh[i + 1] * sr / hc;
        g[2] += 0.5 * v.eh[i] * (sr - sl) / hc;
        g[1] += -0.5 * v.eh[i - 1] * sl / hc;
        if self.lambda != 0.0 {
            for (off, w) in self.wedge(i) {
                let m = (i as isize + off) as usize;
                let k = (off + 2) as usize;
                let cw = self.wedge_factor(m);
                a[k] -= self.lambda * w * v.drho[m] * cw * v.h[m];
                g[k] -= self.lambda * w * v.rho[m] * cw;
            }
        }
        if self.kappa != 0.0 {
            let cm = self.mass_factor(i);
            a[2] -= self.kappa * v.drho[i] * cm * v.h[i];
            g[2] -= self.kappa * v.rho[i] * cm;
        }
        (a, g)
    }

    /// Multiplier of `ρ̄` in the wedge term: 1, or the thermal `(u1 ρ*_1 + u2 ρ*_2)/(2 u_m ρ)`
    /// (seed 000 eq. 2).
    pub(super) fn wedge_factor(&self, i: usize) -> f64 {
        self.thermal.as_ref().map_or(1.0, |t| t.wedge[i])
    }

    /// Multiplier of `ρ̄` in the squeeze term: 1, or the thermal `ρ_e/ρ` (seed 000 eq. 2).
    pub(super) fn mass_factor(&self, i: usize) -> f64 {
        self.thermal.as_ref().map_or(1.0, |t| t.mass[i])
    }

    /// The density of the squeeze term `∂(ρ̄H)/∂t` at node `i`.
    pub(super) fn mass_density(&self, v: &Fields, i: usize) -> f64 {
        v.rho[i] * self.mass_factor(i)
    }
}
