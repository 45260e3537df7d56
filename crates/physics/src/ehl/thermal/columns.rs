use super::*;

impl TemperatureField {
    pub(super) fn uniform(x: &[f64], t: f64, nz: usize, ns: usize) -> Self {
        let n = x.len();
        TemperatureField { x: x.to_vec(), film: vec![t; n * nz], body_1: vec![t; n * ns], body_2: vec![t; n * ns], film_points: nz, solid_points: ns }
    }

    /// The field moved onto columns `x` (m), linear in `x`, the end columns held beyond the ends.
    pub(super) fn resampled(&self, x: &[f64]) -> Self {
        let (nz, ns) = (self.film_points, self.solid_points);
        let mut out = TemperatureField::uniform(x, 0.0, nz, ns);
        let m = self.x.len();
        for (i, &xi) in x.iter().enumerate() {
            let j = self.x.partition_point(|&v| v <= xi).clamp(1, m - 1);
            let t = ((xi - self.x[j - 1]) / (self.x[j] - self.x[j - 1])).clamp(0.0, 1.0);
            let mix = |v: &[f64], k: usize, w: usize| v[(j - 1) * w + k] * (1.0 - t) + v[j * w + k] * t;
            for k in 0..nz {
                out.film[i * nz + k] = mix(&self.film, k, nz);
            }
            for k in 0..ns {
                out.body_1[i * ns + k] = mix(&self.body_1, k, ns);
                out.body_2[i * ns + k] = mix(&self.body_2, k, ns);
            }
        }
        out
    }

    /// All temperatures as one vector (body 1, film, body 2).
    pub(super) fn flat(&self) -> Vec<f64> {
        let mut v = Vec::with_capacity(self.body_1.len() + self.film.len() + self.body_2.len());
        v.extend_from_slice(&self.body_1);
        v.extend_from_slice(&self.film);
        v.extend_from_slice(&self.body_2);
        v
    }

    /// The inverse of [`Self::flat`].
    pub(super) fn set_flat(&mut self, v: &[f64]) {
        let (a, b) = (self.body_1.len(), self.film.len());
        self.body_1.copy_from_slice(&v[..a]);
        self.film.copy_from_slice(&v[a..a + b]);
        self.body_2.copy_from_slice(&v[a + b..]);
    }

    /// Largest film temperature, K.
    pub fn film_max(&self) -> f64 {
        self.film.iter().fold(f64::NEG_INFINITY, |a, &b| a.max(b))
    }

    /// Film temperature across the film at column `i`.
    pub fn film_column(&self, i: usize) -> &[f64] {
        &self.film[i * self.film_points..(i + 1) * self.film_points]
    }

    /// Largest surface temperature of body 1 and of body 2, K.
    pub fn surface_max(&self) -> (f64, f64) {
        let ns = self.solid_points;
        let n = self.x.len();
        let max = |v: &[f64]| (0..n).map(|i| v[i * ns]).fold(f64::NEG_INFINITY, f64::max);
        (max(&self.body_1), max(&self.body_2))
    }
}

/// Eyring film across one column (Yang & Wen's generalized Newtonian fluid; Eyring's law
/// `γ̇ = (τ_E/η) sinh(τ/τ_E)`, e.g. Johnson & Tevaarwerk 1977): the shear stress
/// `τ(z) = τ_1 + (∂p/∂x) z` (momentum across a thin film) whose shear rate integrates,
/// trapezoidally over the levels as `F0`/`F1` do, to the surface speed difference `du`. Writes
/// the effective viscosities `η* = τ/γ̇ = η (τ/τ_E)/sinh(τ/τ_E)` relative to `eta_ref` into
/// `eta`, so the Newtonian-form velocities and stresses built from them are the Eyring ones.
/// `eta_n`: the Newtonian viscosities relative to `eta_ref`. Where no stress is found (not
/// expected: the constraint is monotone in `τ_1`) the Newtonian values stay.
pub(super) fn eyring_column(eta_n: &[f64], eta_ref: f64, dz: f64, du: f64, px: f64, te: f64, eta: &mut [f64]) {
    let nz = eta_n.len();
    let weight = |k: usize| if k == 0 || k == nz - 1 { 0.5 * dz } else { dz };
    // Stresses in units of τ_E: s_k = t + c_k.
    let c: Vec<f64> = (0..nz).map(|k| px * dz * k as f64 / te).collect();
    let cmax = c.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    // g(t) = Σ w_k (τ_E/η_k) sinh(t + c_k) − du and its derivative; increasing in t.
    let g = |t: f64| -> (f64, f64) {
        let (mut v, mut d) = (-du, 0.0);
        for k in 0..nz {
            let a = weight(k) * te / (eta_n[k] * eta_ref);
            let s = t + c[k];
            v += a * s.sinh();
            d += a * s.cosh();
        }
        (v, d)
    };
    let limit = 700.0 - cmax;
    if limit <= 1.0 {
        return;
    }
    // Bracket the root by doubling outwards from ±1.
    let (mut lo, mut hi) = (-1.0f64, 1.0f64);
    while g(lo).0 > 0.0 && lo > -limit {
        lo = (2.0 * lo).max(-limit);
    }
    while g(hi).0 < 0.0 && hi < limit {
        hi = (2.0 * hi).min(limit);
    }
    let (glo, ghi) = (g(lo).0, g(hi).0);
    if !(glo <= 0.0 && ghi >= 0.0) {
        return;
    }
    // Safeguarded Newton: a Newton step inside the bracket, else bisection.
    let mut t = 0.5 * (lo + hi);
    for _ in 0..200 {
        let (v, d) = g(t);
        if !v.is_finite() || v > 0.0 {
            hi = t;
        } else {
            lo = t;
        }
        // Converged at this t: the speed difference met to 1e-13 of itself (of the Poiseuille
        // part's scale in pure rolling) or the bracket closed.
        if v.abs() <= 1e-13 * du.abs().max(1e-9) || hi - lo < 1e-13 * (1.0 + t.abs()) {
            break;
        }
        let step = t - v / d;
        t = if v.is_finite() && d.is_finite() && d > 0.0 && step > lo && step < hi { step } else { 0.5 * (lo + hi) };
    }
    for k in 0..nz {
        let s = (t + c[k]).abs();
        let factor = if s > 1e-8 { s / s.sinh() } else { 1.0 };
        eta[k] = (eta_n[k] * factor).max(1e-300);
    }
}

/// Depths of the solid nodes from the surface: `d (g^k − 1)/(g^(m) − 1)`, the ratio `g` chosen so
/// the first cell is a fifth of the thermal penetration depth `√(κ 2b/|u|)` (at least uniform).
pub(super) fn solid_depths(d: f64, ns: usize, penetration: f64) -> Vec<f64> {
    let m = (ns - 1) as i32;
    let first = (penetration / 5.0).min(d / m as f64);
    let cell = |g: f64| if (g - 1.0).abs() < 1e-12 { d / m as f64 } else { d * (g - 1.0) / (g.powi(m) - 1.0) };
    let (mut lo, mut hi) = (1.0, 3.0);
    if cell(hi) > first {
        lo = hi;
    } else {
        for _ in 0..60 {
            let mid = 0.5 * (lo + hi);
            if cell(mid) > first {
                lo = mid;
            } else {
                hi = mid;
            }
        }
    }
    let g = lo;
    (0..ns).map(|k| if (g - 1.0).abs() < 1e-12 { d * k as f64 / m as f64 } else { d * (g.powi(k as i32) - 1.0) / (g.powi(m) - 1.0) }).collect()
}

impl AndersonMixer {
    pub(super) fn new(depth: usize) -> Self {
        AndersonMixer { depth, g: Default::default(), f: Default::default() }
    }

    pub(super) fn clear(&mut self) {
        self.g.clear();
        self.f.clear();
    }

    pub(super) fn next(&mut self, x: &[f64], g: &[f64]) -> Vec<f64> {
        use faer::linalg::solvers::SolveLstsq;
        self.f.push_back(g.iter().zip(x).map(|(a, b)| a - b).collect());
        self.g.push_back(g.to_vec());
        if self.g.len() > self.depth + 1 {
            self.g.pop_front();
            self.f.pop_front();
        }
        let m = self.g.len() - 1;
        if m == 0 {
            return g.to_vec();
        }
        let n = g.len();
        let fk = &self.f[m];
        let df = faer::Mat::from_fn(n, m, |r, c| self.f[c + 1][r] - self.f[c][r]);
        let rhs = faer::Mat::from_fn(n, 1, |r, _| fk[r]);
        let gamma = df.col_piv_qr().solve_lstsq(&rhs);
        let mut out = g.to_vec();
        for c in 0..m {
            let w = gamma[(c, 0)];
            if !w.is_finite() {
                // A degenerate history: plain fixed-point step, history restarted.
                self.clear();
                return g.to_vec();
            }
            for (r, o) in out.iter_mut().enumerate() {
                *o -= w * (self.g[c + 1][r] - self.g[c][r]);
            }
        }
        out
    }
}
