//! Greenwood–Tripp asperity load sharing for two rough surfaces with Gaussian summit heights.
//!
//! Nominal asperity pressure at a mean separation `h` (Greenwood & Tripp, Proc. IMechE 185, 1970):
//! `p_a = K E* F_{5/2}(h/σ)`, `K = (16√2/15) π (ηβσ)² √(σ/β)`, with σ the composite RMS
//! roughness, η the summit density, β the summit radius and
//! `F_n(λ) = (2π)^(-1/2) ∫_λ^∞ (s − λ)^n e^(−s²/2) ds`.
//!
//! Modulus: Greenwood and co-workers write `E'` for `1/E' = Σ(1 − ν²)/E`, which is Johnson's `E*`
//! ([`crate::contact::contact_modulus`]); several mixed-lubrication papers substitute
//! Hamrock's `E' = 2E*`, which doubles the asperity load. This module takes `E*`.
//!
//! `F_{5/2}` is evaluated accurately — not by the power-law fit `4.4086e-5 (4 − λ)^6.804`, which
//! is 11 % low at λ = 0, 35 % low at 2.5, 74 % low at 3 and zero beyond 4 — a table of `ln F_{5/2}` on λ ∈ [0, 8] (step 0.02) built
//! once by quadrature, interpolated by cubic Hermite polynomials using the exact slope
//! `d ln F_{5/2}/dλ = −(5/2) F_{3/2}/F_{5/2}`. Relative error below 1e-8 (tested against direct
//! quadrature); beyond λ = 8, `F_{5/2} < 1e-16` and is returned as 0.

use std::sync::OnceLock;

const LAMBDA_MAX: f64 = 8.0;
const STEP: f64 = 0.02;
const NODES: usize = 401;

/// `F_n(λ)` for `n ≥ 0` by direct quadrature, λ ≥ 0: with `s = λ + u²`,
/// `F_n = (2π)^(-1/2) ∫_0^∞ 2 u^(2n+1) exp(−(λ + u²)²/2) du`, composite Simpson on `[0, U]` where
/// the integrand has decayed below 1e-20 of its scale. Used to build the table and by tests.
pub fn f_n_quadrature(n: f64, lambda: f64, panels: usize) -> f64 {
    let lambda = lambda.max(0.0);
    // (λ + u²)²/2 > 46 ⇒ e^(−…) < 1e-20.
    let u_max = ((92f64).sqrt() - lambda).max(0.0).sqrt().max(1e-3);
    let f = |u: f64| {
        let s = lambda + u * u;
        2.0 * u.powf(2.0 * n + 1.0) * (-0.5 * s * s).exp()
    };
    let m = panels + panels % 2;
    let h = u_max / m as f64;
    let mut sum = f(0.0) + f(u_max);
    for i in 1..m {
        sum += if i % 2 == 1 { 4.0 } else { 2.0 } * f(i as f64 * h);
    }
    sum * h / 3.0 / (2.0 * std::f64::consts::PI).sqrt()
}

struct Table {
    ln_f: Vec<f64>,
    slope: Vec<f64>,
}

fn table() -> &'static Table {
    static TABLE: OnceLock<Table> = OnceLock::new();
    TABLE.get_or_init(|| {
        let mut ln_f = Vec::with_capacity(NODES);
        let mut slope = Vec::with_capacity(NODES);
        for i in 0..NODES {
            let l = i as f64 * STEP;
            // `f_n_quadrature(n, l, 2000)` for n = 3/2 and 5/2 in one pass.
            let u_max = ((92f64).sqrt() - l).max(0.0).sqrt().max(1e-3);
            let [_, _, f32, f52] = simpson_set(l, u_max, 0.0, 2000);
            ln_f.push(f52.ln());
            slope.push(-2.5 * f32 / f52);
        }
        Table { ln_f, slope }
    })
}

/// `F_{5/2}(λ)`, accurate to ~1e-8 relative for λ ∈ [0, 8]; `F_{5/2}(0) = 0.6168`; 0 beyond 8.
/// Negative λ (interference) is clamped to 0.
pub fn f52(lambda: f64) -> f64 {
    f52_with_slope(lambda).0
}

/// `(F_{5/2}(λ), dF_{5/2}/dλ)`: the derivative of the same Hermite interpolant (so Newton
/// solvers see a consistent slope); 0 beyond λ = 8; for λ < 0 the value at 0 and slope 0.
pub fn f52_with_slope(lambda: f64) -> (f64, f64) {
    let l = lambda.max(0.0);
    if l >= LAMBDA_MAX {
        return (0.0, 0.0);
    }
    let t = table();
    let x = l / STEP;
    let i = (x.floor() as usize).min(NODES - 2);
    let u = x - i as f64;
    let (ln, dln_du) = hermite(t.ln_f[i], t.ln_f[i + 1], t.slope[i] * STEP, t.slope[i + 1] * STEP, u);
    let f = ln.exp();
    (f, if lambda < 0.0 { 0.0 } else { f * dln_du / STEP })
}

/// Cubic Hermite interpolation on one cell: values `y0`, `y1` and slopes `m0`, `m1` (per cell
/// width) at the ends, at `u ∈ [0, 1]`; returns the value and its derivative in `u`.
fn hermite(y0: f64, y1: f64, m0: f64, m1: f64, u: f64) -> (f64, f64) {
    let (u2, u3) = (u * u, u * u * u);
    let v = (2.0 * u3 - 3.0 * u2 + 1.0) * y0 + (u3 - 2.0 * u2 + u) * m0 + (-2.0 * u3 + 3.0 * u2) * y1 + (u3 - u2) * m1;
    let d = (6.0 * u2 - 6.0 * u) * y0 + (3.0 * u2 - 4.0 * u + 1.0) * m0 + (-6.0 * u2 + 6.0 * u) * y1 + (3.0 * u2 - 2.0 * u) * m1;
    (v, d)
}

/// The widely used power-law fit `F_{5/2} ≈ 4.4086e-5 (4 − λ)^6.804` (λ < 4, else 0), kept only to
/// document how poor it is above λ ≈ 2.5 (see the tests); never used by the solvers.
pub fn f52_power_law_fit(lambda: f64) -> f64 {
    if lambda >= 4.0 { 0.0 } else { 4.4086e-5 * (4.0 - lambda).powf(6.804) }
}

/// Statistical description of the two rough surfaces.
#[derive(Debug, Clone, PartialEq)]
pub struct Roughness {
    /// Composite RMS roughness `σ = sqrt(σ1² + σ2²)`, m.
    pub sigma: f64,
    /// Roughness parameter `ηβσ` (summit density × summit radius × σ), dimensionless
    /// (typically 0.03–0.07).
    pub eta_beta_sigma: f64,
    /// Slope parameter `σ/β`, dimensionless (typically 1e-4–1e-2).
    pub sigma_over_beta: f64,
    /// Plastic limit of the asperity contact pressure `p_a,lim`, Pa (seed 001 eq. 10, Table 1:
    /// 6 GPa); `f64::INFINITY`: purely elastic asperities.
    pub plastic_limit: f64,
    /// A tabulated pressure–gap relation (seed 001 eq. 12) that replaces Greenwood–Tripp in the
    /// load-sharing models; `None`: Greenwood–Tripp with `eta_beta_sigma`, `sigma_over_beta`.
    pub curve: Option<std::sync::Arc<super::curve::PressureGapCurve>>,
}

impl Roughness {
    /// Greenwood–Tripp constant `K = (16√2/15) π (ηβσ)² √(σ/β)`.
    pub fn gt_constant(&self) -> f64 {
        16.0 * std::f64::consts::SQRT_2 / 15.0
            * std::f64::consts::PI
            * self.eta_beta_sigma.powi(2)
            * self.sigma_over_beta.sqrt()
    }

    /// Nominal asperity pressure at mean separation `h`, Pa, for the contact modulus `E*`.
    pub fn asperity_pressure(&self, h: f64, contact_modulus: f64) -> f64 {
        if !(self.sigma > 0.0) {
            return 0.0;
        }
        self.gt_constant() * contact_modulus * f52(h / self.sigma)
    }

    /// Mean asperity pressure of the load-sharing models, Pa, and its slope `dp_a/dh`, Pa/m, at
    /// the *film* `h` — the mean gap between the rough surfaces, i.e. the lubricant volume per
    /// area that the Reynolds equation carries (seed 001 eq. 9, Johnson–Greenwood–Poon):
    /// * the separation `d` of the mean planes follows from volume conservation with Gaussian
    ///   heights of RMS σ, `h = σ F_1(−d/σ)` (the mean of `(d − z)⁺`): `d ≈ h` when the surfaces
    ///   are apart (`h ≳ 3σ`), and `d → −∞` (interference) as the film vanishes;
    /// * Greenwood–Tripp at that separation, `p_GT = K E* F_{5/2}(d/σ)`, which grows without
    ///   bound under interference, so the asperities can carry any load as the film vanishes
    ///   (the dry rough limit);
    /// * saturated smoothly at the plastic limit, `p_a = p_GT/sqrt(1 + (p_GT/p_lim)²)` — `p_GT`
    ///   while the asperities are elastic, the fully plastic mean pressure `p_lim` when the
    ///   surfaces are pressed flat (seed 001 eq. 10's cap on the local pressures, applied to the
    ///   mean: a documented simplification of the statistical model).
    pub fn load_sharing_pressure(&self, h: f64, contact_modulus: f64) -> (f64, f64) {
        if !(self.sigma > 0.0) {
            return (0.0, 0.0);
        }
        if let Some(c) = &self.curve {
            let (p, dp) = c.pressure(h);
            return self.plastic_cap(p, dp);
        }
        let k = self.gt_constant() * contact_modulus;
        let lh = (h / self.sigma).max(0.0);
        let tables = general_tables();
        if lh >= GENERAL_HI_SEPARATION {
            return (0.0, 0.0);
        }
        // s = −d/σ solves F_1(s) = h/σ (F_1 decreasing); t = d/σ = −s.
        let s = tables.f1.inverse(lh);
        let t = -s;
        let (f52v, df52) = tables.f52.value_slope(t);
        // dh/dd = F_0(−d/σ) (the fraction of the area not in contact): dt/dh = 1/(σ F_0(s)).
        let f0 = tables.f0.value_slope(s).0.max(1e-300);
        self.plastic_cap(k * f52v, k * df52 / (self.sigma * f0))
    }

    /// `p/sqrt(1 + (p/p_lim)²)` and its slope from `(p, dp/dh)`.
    fn plastic_cap(&self, p: f64, dp: f64) -> (f64, f64) {
        if !(self.plastic_limit.is_finite() && self.plastic_limit > 0.0) {
            return (p, dp);
        }
        let r = p / self.plastic_limit;
        let q = (1.0 + r * r).sqrt();
        (p / q, dp / (q * q * q))
    }
}

/// Range of the general tables: `F_n(λ)` for λ ∈ [−16, 16].
const GENERAL_LO: f64 = -16.0;
const GENERAL_STEP: f64 = 0.04;
const GENERAL_NODES: usize = 801;
/// Films beyond this many σ carry no asperity pressure (`F_{5/2}(10) < 1e-24`).
const GENERAL_HI_SEPARATION: f64 = 10.0;

/// `F_n(λ)` for n = 0, 1, 3/2, 5/2 and any real λ by quadrature (`s = λ + u²`, Simpson on
/// `[0, U]` with `U² = sqrt(max(λ,0)² + 92) − λ`, beyond which the integrand is below e^(−46) of
/// its peak), each times `e^(peak)` (`peak = λ²/2` for λ ≥ 0): `ln_f_n_set` removes it.
fn f_n_set(lambda: f64, panels: usize) -> [f64; 4] {
    let u_max = ((lambda.max(0.0).powi(2) + 92.0).sqrt() - lambda).sqrt();
    let peak = if lambda < 0.0 { 0.0 } else { 0.5 * lambda * lambda };
    simpson_set(lambda, u_max, peak, panels)
}

/// `(2π)^(-1/2) ∫_0^U 2 u^(2n+1) exp(peak − (λ + u²)²/2) du` for n = 0, 1, 3/2, 5/2 (powers
/// u¹, u³, u⁴, u⁶ by products), composite Simpson with `panels` (rounded up to even) panels: one
/// exponential per abscissa for the four integrals.
fn simpson_set(lambda: f64, u_max: f64, peak: f64, panels: usize) -> [f64; 4] {
    let f = |u: f64| {
        let u2 = u * u;
        let s = lambda + u2;
        let e = 2.0 * (peak - 0.5 * s * s).exp();
        let (u3, u4) = (u2 * u, u2 * u2);
        [u * e, u3 * e, u4 * e, u4 * u2 * e]
    };
    let m = panels + panels % 2;
    let h = u_max / m as f64;
    let mut sum = f(0.0);
    for (acc, v) in sum.iter_mut().zip(f(u_max)) {
        *acc += v;
    }
    for i in 1..m {
        let w = if i % 2 == 1 { 4.0 } else { 2.0 };
        for (acc, v) in sum.iter_mut().zip(f(i as f64 * h)) {
            *acc += w * v;
        }
    }
    sum.map(|v| v * h / 3.0 / (2.0 * std::f64::consts::PI).sqrt())
}

/// `ln F_n(λ)` for n = 0, 1, 3/2, 5/2 and any λ (no underflow for large positive λ).
fn ln_f_n_set(lambda: f64) -> [f64; 4] {
    let peak = if lambda < 0.0 { 0.0 } else { 0.5 * lambda * lambda };
    f_n_set(lambda, 2000).map(|v| v.ln() - peak)
}

/// `ln F_n` on the general grid, Hermite-interpolated with exact slopes.
struct LnTable {
    ln_f: Vec<f64>,
    slope: Vec<f64>,
}

impl LnTable {
    /// `ln F_n` and `d ln F_n/dλ = −n F_{n−1}/F_n` (for n = 0: `−φ/F_0`) from `ln F_{n−1}`.
    fn build(ln_f: Vec<f64>, ln_lower: impl Fn(usize, f64) -> f64, n: f64) -> Self {
        let slope = (0..GENERAL_NODES)
            .map(|i| {
                let l = GENERAL_LO + i as f64 * GENERAL_STEP;
                -n.max(1.0) * (ln_lower(i, l) - ln_f[i]).exp()
            })
            .collect();
        LnTable { ln_f, slope }
    }

    fn locate(lambda: f64) -> (usize, f64) {
        let x = ((lambda - GENERAL_LO) / GENERAL_STEP).clamp(0.0, (GENERAL_NODES - 1) as f64);
        // x ≥ 0 (clamped; NaN maps to 0 either way): truncation is the floor, without a libm call.
        let i = (x as usize).min(GENERAL_NODES - 2);
        (i, x - i as f64)
    }

    /// `(ln F, d ln F/dλ)` at λ (clamped to the table).
    fn ln_value_slope(&self, lambda: f64) -> (f64, f64) {
        let (i, u) = Self::locate(lambda);
        let (ln, d) = hermite(self.ln_f[i], self.ln_f[i + 1], self.slope[i] * GENERAL_STEP, self.slope[i + 1] * GENERAL_STEP, u);
        (ln, d / GENERAL_STEP)
    }

    /// `(F, dF/dλ)` at λ.
    fn value_slope(&self, lambda: f64) -> (f64, f64) {
        let (ln, d) = self.ln_value_slope(lambda);
        let f = ln.exp();
        (f, f * d)
    }

    /// λ with `F(λ) = target` for a decreasing `F` (Newton on `ln F`, safeguarded by bisection).
    fn inverse(&self, target: f64) -> f64 {
        let goal = target.max(1e-300).ln();
        let (mut lo, mut hi) = (GENERAL_LO, GENERAL_LO + (GENERAL_NODES - 1) as f64 * GENERAL_STEP);
        // The interpolant at the table's ends is the end values (u = 1 and u = 0 exactly).
        if self.ln_f[GENERAL_NODES - 1] >= goal {
            return hi;
        }
        if self.ln_f[0] <= goal {
            return lo;
        }
        let mut x = 0.5 * (lo + hi);
        for _ in 0..100 {
            let (v, d) = self.ln_value_slope(x);
            let r = v - goal;
            if r > 0.0 { lo = x } else { hi = x }
            if r.abs() < 1e-13 || hi - lo < 1e-13 {
                break;
            }
            let next = x - r / d;
            x = if next > lo && next < hi && d < 0.0 { next } else { 0.5 * (lo + hi) };
        }
        x
    }
}

/// `F_0`, `F_1` and `F_{5/2}` on λ ∈ [−16, 16] for the load-sharing law.
struct GeneralTables {
    f0: LnTable,
    f1: LnTable,
    f52: LnTable,
}

/// Build the process-wide tables of `F_n` (226 M instructions, callgrind: ≈ 0.04 s of one core,
/// once per process; one exponential per abscissa for all four orders) now rather
/// than inside the first job that needs them: a server calls it at start.
pub fn warm_up() {
    table();
    general_tables();
}

fn general_tables() -> &'static GeneralTables {
    static TABLES: OnceLock<GeneralTables> = OnceLock::new();
    TABLES.get_or_init(|| {
        let (mut ln0, mut ln1, mut ln32, mut ln52) = (Vec::new(), Vec::new(), Vec::new(), Vec::new());
        for i in 0..GENERAL_NODES {
            let [a, b, c, d] = ln_f_n_set(GENERAL_LO + i as f64 * GENERAL_STEP);
            ln0.push(a);
            ln1.push(b);
            ln32.push(c);
            ln52.push(d);
        }
        let ln_phi = |_: usize, l: f64| -0.5 * l * l - 0.5 * (2.0 * std::f64::consts::PI).ln();
        GeneralTables {
            f0: LnTable::build(ln0.clone(), ln_phi, 1.0),
            f1: LnTable::build(ln1, |i, _| ln0[i], 1.0),
            f52: LnTable::build(ln52, |i, _| ln32[i], 2.5),
        }
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Γ(7/4) (A&S table 6.1 gives Γ(1.75) = 0.919062527).
    const GAMMA_7_4: f64 = 0.919_062_526_848_883;

    #[test]
    fn f52_at_zero_is_the_closed_form() {
        // F_{5/2}(0) = (2π)^(-1/2) ∫0^∞ s^(5/2) e^(−s²/2) ds = 2^(3/4) Γ(7/4)/√(2π).
        let exact = 2f64.powf(0.75) * GAMMA_7_4 / (2.0 * std::f64::consts::PI).sqrt();
        assert!((f52(0.0) / exact - 1.0).abs() < 1e-9, "{} vs {exact}", f52(0.0));
        assert!((exact - 0.61664).abs() < 1e-5);
    }

    #[test]
    fn interpolated_table_matches_fine_quadrature() {
        for k in 0..=390 {
            let l = 0.0203 * k as f64 + 0.0011;
            let reference = f_n_quadrature(2.5, l, 20_000);
            let v = f52(l);
            assert!((v / reference - 1.0).abs() < 1e-8, "λ = {l}: {v} vs {reference}");
        }
        assert_eq!(f52(8.5), 0.0);
        assert!(f52(7.99) < 1e-15);
    }

    #[test]
    fn power_law_fit_is_poor_above_two_and_a_half() {
        // Documented: the fit is within ~10 % for λ ≤ 2 but off by > 30 % at 3 and zero at 4.
        for (l, max_err) in [(1.0, 0.10), (2.0, 0.10)] {
            let e = (f52_power_law_fit(l) / f52(l) - 1.0).abs();
            assert!(e < max_err, "λ = {l}: {e}");
        }
        let e3 = (f52_power_law_fit(3.0) / f52(3.0) - 1.0).abs();
        assert!(e3 > 0.3, "λ = 3: {e3}");
        assert_eq!(f52_power_law_fit(4.0), 0.0);
        assert!(f52(4.0) > 1e-6);
    }

    #[test]
    fn slope_matches_finite_differences_and_the_cap_saturates() {
        for k in 0..390 {
            let l = 0.0203 * k as f64 + 0.0011;
            let (_, d) = f52_with_slope(l);
            let fd = (f52(l + 1e-6) - f52(l - 1e-6)) / 2e-6;
            assert!((d - fd).abs() <= 1e-5 * fd.abs() + 1e-14, "λ = {l}: {d} vs {fd}");
            assert!(d < 0.0 || f52(l) < 1e-15);
        }
        let r = Roughness { sigma: 0.2e-6, eta_beta_sigma: 0.04, sigma_over_beta: 0.001, plastic_limit: 6e9, curve: None };
        let es = 1.1e11;
        let mut last = f64::INFINITY;
        for k in 1..200 {
            let h = 1e-9 * k as f64;
            let (p, dp) = r.load_sharing_pressure(h, es);
            assert!(p <= last && p < 6e9 && dp <= 0.0, "h = {h}: {p} {dp}");
            let fd = (r.load_sharing_pressure(h + 1e-12, es).0 - r.load_sharing_pressure((h - 1e-12).max(0.0), es).0) / (h + 1e-12 - (h - 1e-12).max(0.0));
            assert!((dp - fd).abs() <= 1e-4 * fd.abs() + 1.0, "h = {h}: {dp} vs {fd}");
            last = p;
        }
        // Apart (h = 4σ) the mean gap is the separation: Greenwood–Tripp at d = h.
        let elastic = Roughness { plastic_limit: f64::INFINITY, ..r.clone() };
        let h = 0.8e-6;
        assert!((r.load_sharing_pressure(h, es).0 / elastic.asperity_pressure(h, es) - 1.0).abs() < 1e-4);
        // As the film vanishes the asperity pressure grows without bound (Gaussian tails: slowly,
        // 0.37 GPa at h = 5e-6 σ with these parameters) until the plastic limit caps it.
        let (p_sigma, p_thin) = (r.load_sharing_pressure(0.2e-6, es).0, r.load_sharing_pressure(1e-12, es).0);
        assert!(p_thin > 30.0 * p_sigma && p_thin > 2e8, "{p_sigma} {p_thin}");
        assert!(r.load_sharing_pressure(1e-70, es).0 > 0.5 * 6e9);
    }

    #[test]
    fn general_tables_match_quadrature_and_closed_forms() {
        // F_0(λ) = Q(λ): Q(0) = 1/2, Q(−1) = 0.841344746, Q(2) = 0.022750132 (A&S 26.2).
        let t = general_tables();
        for (l, q) in [(0.0, 0.5), (-1.0, 0.841_344_746_068_543), (2.0, 0.022_750_131_948_179)] {
            assert!((t.f0.value_slope(l).0 / q - 1.0).abs() < 1e-7, "{l}");
        }
        // F_1(λ) = φ(λ) − λ Q(λ); F_1(−λ) = λ + F_1(λ).
        let f1 = |l: f64| t.f1.value_slope(l).0;
        assert!((f1(-3.0) - 3.0 - f1(3.0)).abs() < 1e-7);
        assert!((f1(0.0) - 1.0 / (2.0 * std::f64::consts::PI).sqrt()).abs() < 1e-8);
        // The inverse.
        for h in [1e-6, 0.01, 0.3, 1.0, 4.0, 9.0] {
            let s = t.f1.inverse(h);
            assert!((f1(s) / h - 1.0).abs() < 1e-9, "{h}: {}", f1(s));
        }
        // F_{5/2} agrees with the λ ≥ 0 table.
        for l in [0.0, 0.5, 2.0, 5.0] {
            assert!((t.f52.value_slope(l).0 / f52(l) - 1.0).abs() < 1e-6, "{l}");
        }
    }

    #[test]
    fn asperity_pressure_scales_with_modulus_and_vanishes_for_smooth_surfaces() {
        let r = Roughness { sigma: 0.2e-6, eta_beta_sigma: 0.04, sigma_over_beta: 0.001, plastic_limit: f64::INFINITY, curve: None };
        let p = r.asperity_pressure(0.2e-6, 1.15e11);
        assert!((p / (r.gt_constant() * 1.15e11 * f52(1.0)) - 1.0).abs() < 1e-15);
        let smooth = Roughness { sigma: 0.0, ..r.clone() };
        assert_eq!(smooth.asperity_pressure(1e-9, 1.15e11), 0.0);
    }
}
