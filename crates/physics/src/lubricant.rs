//! Lubricant rheology: pressure- and temperature-dependent viscosity (Barus, Roelands) and
//! density (Dowson–Higginson), all in SI units (Pa·s, Pa, K, kg/m³).

use serde::{Deserialize, Serialize};

/// Roelands' pressure constant `p_r = 1/A2 = 1.96e8 Pa` (seed 000 eq. 4: `A2 = 5.1e-9 1/Pa`).
pub const ROELANDS_PRESSURE: f64 = 1.96e8;
/// Roelands' constant `ln η∞ = −9.67` (η∞ = 6.31e-5 Pa·s), seed 000 eq. 4 (`A1 = ln η0 + 9.67`).
pub const ROELANDS_LN_ETA_INF: f64 = -9.67;
/// Dowson–Higginson density constants (seed 000 eq. 5): `C1 = 0.6e-9 1/Pa`, `C2 = 1.7e-9 1/Pa`.
pub const DH_C1: f64 = 0.6e-9;
pub const DH_C2: f64 = 1.7e-9;
/// Thermal expansion coefficient of seed 000 eq. 5, `C3 = 6.5e-4 1/K`.
pub const DH_C3: f64 = 6.5e-4;

/// Pressure–viscosity law.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum ViscosityModel {
    /// Barus: `η = η0 exp(α p − β (T − T0))`. Overestimates viscosity above ≈ 0.5 GPa.
    Barus,
    /// Roelands (seed 000 eq. 4), with the pressure–viscosity index `Z` chosen so that the
    /// low-pressure slope equals `α`: `Z = α p_r / (ln η0 + 9.67)`, and the temperature index
    /// `S0 = β (T0 − 138) / (ln η0 + 9.67)`.
    #[default]
    Roelands,
}

/// Density law.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum DensityModel {
    /// Constant density.
    Incompressible,
    /// Dowson–Higginson with the linear thermal term of seed 000 eq. 5:
    /// `ρ/ρ0 = 1 + C1 p / (1 + C2 p) − C3 (T − T0)`.
    #[default]
    DowsonHigginson,
}

/// A lubricant's viscosity law at one temperature ([`Lubricant::viscosity_law`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum ViscosityLaw {
    /// `η = η0 exp(α p − thermal)`, `thermal = β (T − T0)`.
    Barus { viscosity: f64, alpha: f64, thermal: f64 },
    /// `η = η0 exp(A1 (−1 + (1 + p/p_r)^Z · thermal))`, `thermal = ((T − 138)/(T0 − 138))^(−S0)`.
    Roelands { viscosity: f64, a1: f64, z: f64, thermal: f64 },
}

impl ViscosityLaw {
    /// Viscosity at gauge pressure `p` (Pa, clamped at 0), Pa·s.
    #[inline]
    pub fn at(&self, p: f64) -> f64 {
        let p = p.max(0.0);
        match *self {
            ViscosityLaw::Barus { viscosity, alpha, thermal } => viscosity * (alpha * p - thermal).exp(),
            ViscosityLaw::Roelands { viscosity, a1, z, thermal } => {
                // (1 + p/p_r)^Z as exp(Z ln(1 + p/p_r)): one logarithm instead of a `powf`.
                viscosity * (a1 * (-1.0 + (z * (p / ROELANDS_PRESSURE).ln_1p()).exp() * thermal)).exp()
            }
        }
    }
}

/// A lubricant's viscosity–temperature law at one pressure ([`Lubricant::pressure_law`]): the
/// pressure-dependent factors evaluated once, for callers that evaluate many temperatures at
/// one pressure (the energy equation's film columns).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum PressureLaw {
    /// `ln(η/η0) = α p − β (T − T0)`.
    Barus { pressure_term: f64, beta: f64, reference_temperature: f64 },
    /// `ln(η/η0) = A1 (−1 + (1 + p/p_r)^Z · ((T − 138)/(T0 − 138))^(−S0))`, `pressure_factor`
    /// = `(1 + p/p_r)^Z`.
    Roelands { a1: f64, s0: f64, pressure_factor: f64, reference_temperature: f64 },
}

impl PressureLaw {
    /// `ln(η/η0)` at temperature `t` (K) and `∂ ln η/∂T` (1/K), one `powf` per temperature (the
    /// one formula behind [`Lubricant::ln_viscosity_ratio`] and
    /// [`Lubricant::ln_viscosity_temperature_slope`]).
    #[inline]
    pub fn ln_ratio_and_temperature_slope(&self, t: f64) -> (f64, f64) {
        match *self {
            PressureLaw::Barus { pressure_term, beta, reference_temperature } => (pressure_term - beta * (t - reference_temperature), -beta),
            PressureLaw::Roelands { a1, s0, pressure_factor, reference_temperature } => {
                let thermal = ((t - 138.0).max(1.0) / (reference_temperature - 138.0)).powf(-s0);
                let ln_ratio = a1 * (-1.0 + pressure_factor * thermal);
                (ln_ratio, -(ln_ratio + a1) * s0 / (t - 138.0).max(1.0))
            }
        }
    }
}

/// A lubricant's rheology. Plain data: build it from a spec and pass it to solvers.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Lubricant {
    /// Dynamic viscosity at ambient pressure and the reference temperature, Pa·s.
    pub viscosity: f64,
    /// Pressure–viscosity coefficient α, 1/Pa.
    pub pressure_viscosity: f64,
    /// Temperature–viscosity coefficient β, 1/K (≥ 0).
    pub temperature_viscosity: f64,
    /// Reference temperature T0, K.
    pub reference_temperature: f64,
    /// Density at ambient pressure and T0, kg/m³.
    pub density: f64,
    pub viscosity_model: ViscosityModel,
    pub density_model: DensityModel,
}

impl Lubricant {
    /// Seed 000 Table 1 oil: η0 = 0.152 Pa·s, α = 2.2e-8 1/Pa, β = 0.042 1/K, T0 = 313 K,
    /// ρ0 = 870 kg/m³, Roelands + Dowson–Higginson.
    pub const SEED000: Lubricant = Lubricant {
        viscosity: 0.152,
        pressure_viscosity: 2.2e-8,
        temperature_viscosity: 0.042,
        reference_temperature: 313.0,
        density: 870.0,
        viscosity_model: ViscosityModel::Roelands,
        density_model: DensityModel::DowsonHigginson,
    };

    /// `A1 = ln η0 + 9.67` (seed 000 eq. 4).
    fn roelands_a1(&self) -> f64 {
        self.viscosity.ln() - ROELANDS_LN_ETA_INF
    }

    /// Roelands pressure–viscosity index `Z` (dimensionless, typically 0.5–0.7).
    pub fn roelands_z(&self) -> f64 {
        self.pressure_viscosity * ROELANDS_PRESSURE / self.roelands_a1()
    }

    /// Viscosity at gauge pressure `p` (Pa, clamped at 0) and temperature `t` (K), Pa·s.
    ///
    /// Seed 000 eq. 4 prints the temperature factor as `(A3/A4)^(−S0)` with `A3 = 1/(T0 − 138)`,
    /// `A4 = 138/(T0 − 138)`, which would be a constant; the intended Roelands factor is
    /// `((T − 138)/(T0 − 138))^(−S0)`, used here.
    pub fn viscosity_at(&self, p: f64, t: f64) -> f64 {
        self.viscosity_law(t).at(p)
    }

    /// The pressure–viscosity law at temperature `t` with its pressure-independent factors
    /// evaluated once (`A1`, `Z`, the Roelands temperature factor; Barus' `β (T − T0)`):
    /// [`ViscosityLaw::at`] equals [`Self::viscosity_at`] bit for bit at one logarithm and two
    /// exponentials per pressure (callers evaluating many pressures at one temperature use it).
    pub fn viscosity_law(&self, t: f64) -> ViscosityLaw {
        let dt = t - self.reference_temperature;
        match self.viscosity_model {
            ViscosityModel::Barus => ViscosityLaw::Barus {
                viscosity: self.viscosity,
                alpha: self.pressure_viscosity,
                thermal: self.temperature_viscosity * dt,
            },
            ViscosityModel::Roelands => {
                let a1 = self.roelands_a1();
                // = roelands_z() without a second logarithm.
                let z = self.pressure_viscosity * ROELANDS_PRESSURE / a1;
                let t0 = self.reference_temperature;
                let s0 = self.temperature_viscosity * (t0 - 138.0) / a1;
                let thermal = ((t - 138.0).max(1.0) / (t0 - 138.0)).powf(-s0);
                ViscosityLaw::Roelands { viscosity: self.viscosity, a1, z, thermal }
            }
        }
    }

    /// The viscosity–temperature law at gauge pressure `p` (Pa, clamped at 0): see [`PressureLaw`].
    pub fn pressure_law(&self, p: f64) -> PressureLaw {
        let p = p.max(0.0);
        let t0 = self.reference_temperature;
        match self.viscosity_model {
            ViscosityModel::Barus => PressureLaw::Barus { pressure_term: self.pressure_viscosity * p, beta: self.temperature_viscosity, reference_temperature: t0 },
            ViscosityModel::Roelands => {
                let a1 = self.roelands_a1();
                let z = self.roelands_z();
                let s0 = self.temperature_viscosity * (t0 - 138.0) / a1;
                PressureLaw::Roelands { a1, s0, pressure_factor: (1.0 + p / ROELANDS_PRESSURE).powf(z), reference_temperature: t0 }
            }
        }
    }

    /// `ln(η(p, t)/η0)`, the logarithm of the viscosity ratio (never overflows: EHL solvers work
    /// with it where `η` itself would exceed `f64` at absurd trial pressures).
    pub fn ln_viscosity_ratio(&self, p: f64, t: f64) -> f64 {
        self.pressure_law(p).ln_ratio_and_temperature_slope(t).0
    }

    /// `∂ ln η / ∂p` at `(p, t)`, 1/Pa (0 below ambient pressure, where `p` is clamped).
    pub fn ln_viscosity_pressure_slope(&self, p: f64, t: f64) -> f64 {
        if p < 0.0 {
            return 0.0;
        }
        match self.viscosity_model {
            ViscosityModel::Barus => self.pressure_viscosity,
            ViscosityModel::Roelands => {
                let a1 = self.roelands_a1();
                let z = self.roelands_z();
                let t0 = self.reference_temperature;
                let s0 = self.temperature_viscosity * (t0 - 138.0) / a1;
                let thermal = ((t - 138.0).max(1.0) / (t0 - 138.0)).powf(-s0);
                a1 * z * (1.0 + p / ROELANDS_PRESSURE).powf(z - 1.0) / ROELANDS_PRESSURE * thermal
            }
        }
    }

    /// `∂ ln η / ∂T` at `(p, t)`, 1/K (≤ 0): Barus `−β`; Roelands
    /// `−(ln(η/η0) + A1) S0/(T − 138)` (seed 000 eq. 4 differentiated).
    pub fn ln_viscosity_temperature_slope(&self, p: f64, t: f64) -> f64 {
        self.pressure_law(p).ln_ratio_and_temperature_slope(t).1
    }

    /// `∂(ρ/ρ0)/∂p` at `(p, t)`, 1/Pa (0 below ambient pressure, where `p` is clamped).
    pub fn density_ratio_pressure_slope(&self, p: f64, _t: f64) -> f64 {
        match self.density_model {
            DensityModel::Incompressible => 0.0,
            DensityModel::DowsonHigginson => {
                if p < 0.0 {
                    0.0
                } else {
                    DH_C1 / (1.0 + DH_C2 * p).powi(2)
                }
            }
        }
    }

    /// Viscosity at pressure `p` and the reference temperature.
    pub fn viscosity_at_pressure(&self, p: f64) -> f64 {
        self.viscosity_at(p, self.reference_temperature)
    }

    /// Density ratio `ρ/ρ0` at pressure `p` (Pa, clamped at 0) and temperature `t` (K).
    pub fn density_ratio(&self, p: f64, t: f64) -> f64 {
        match self.density_model {
            DensityModel::Incompressible => 1.0,
            DensityModel::DowsonHigginson => {
                let p = p.max(0.0);
                1.0 + DH_C1 * p / (1.0 + DH_C2 * p) - DH_C3 * (t - self.reference_temperature)
            }
        }
    }

    /// Density at pressure `p` and temperature `t`, kg/m³.
    pub fn density_at(&self, p: f64, t: f64) -> f64 {
        self.density * self.density_ratio(p, t)
    }

    /// The effective pressure–viscosity coefficient of this law, 1/Pa: `α` itself for Barus, and
    /// for Roelands the reciprocal asymptotic isoviscous pressure `α* = 1 / ∫0^∞ η0/η(p) dp`
    /// (Blok's definition), by composite Simpson on the interval mapped to [0, 1).
    /// Film formulas written with Barus' α take this value.
    pub fn alpha_star(&self) -> f64 {
        match self.viscosity_model {
            ViscosityModel::Barus => self.pressure_viscosity,
            ViscosityModel::Roelands => {
                // ∫0^∞ η0/η(p) dp with p = s/(1−s) · p_α, s ∈ [0,1), p_α = 1/α.
                let scale = 1.0 / self.pressure_viscosity;
                let t0 = self.reference_temperature;
                let f = |s: f64| {
                    if s >= 1.0 {
                        return 0.0;
                    }
                    let p = scale * s / (1.0 - s);
                    let jac = scale / ((1.0 - s) * (1.0 - s));
                    self.viscosity / self.viscosity_at(p, t0) * jac
                };
                let n = 2000; // Simpson panels; the integrand is smooth and decays like exp(−αp)
                let h = 1.0 / n as f64;
                let mut sum = f(0.0) + f(1.0);
                for i in 1..n {
                    let w = if i % 2 == 1 { 4.0 } else { 2.0 };
                    sum += w * f(i as f64 * h);
                }
                1.0 / (sum * h / 3.0)
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn pressure_law_is_roelands_and_barus_with_their_temperature_slopes() {
        let roelands = Lubricant::SEED000;
        let barus = Lubricant { viscosity_model: ViscosityModel::Barus, ..roelands };
        let (t0, eta0, alpha, beta) = (roelands.reference_temperature, roelands.viscosity, roelands.pressure_viscosity, roelands.temperature_viscosity);
        // Roelands (seed 000 eq. 4, p_r = 1/A2 = 1.96e8 Pa, the temperature factor
        // ((T − 138)/(T0 − 138))^(−S0)).
        let a1 = eta0.ln() + 9.67;
        let (z, s0) = (alpha * 1.96e8 / a1, beta * (t0 - 138.0) / a1);
        for p in [-1e6, 0.0, 1e5, 3.7e8, 1.7e9, 4e9] {
            let pc = f64::max(p, 0.0);
            for t in [290.0, 313.0, 351.7, 800.0] {
                let want = [a1 * (-1.0 + (1.0 + pc / 1.96e8).powf(z) * ((t - 138.0) / (t0 - 138.0)).powf(-s0)), alpha * pc - beta * (t - t0)];
                for (oil, want) in [roelands, barus].into_iter().zip(want) {
                    let (ln, slope) = oil.pressure_law(p).ln_ratio_and_temperature_slope(t);
                    assert!((ln - want).abs() <= 1e-12 * want.abs().max(1.0), "{p} {t}: {ln} {want}");
                    assert_eq!(ln.to_bits(), oil.ln_viscosity_ratio(p, t).to_bits());
                    let fd = (oil.ln_viscosity_ratio(p, t + 1e-3) - oil.ln_viscosity_ratio(p, t - 1e-3)) / 2e-3;
                    assert!((slope - fd).abs() <= 1e-6 * fd.abs().max(1e-3), "{p} {t}: slope {slope} fd {fd}");
                }
            }
        }
    }

    #[test]
    fn roelands_matches_barus_slope_at_low_pressure() {
        let oil = Lubricant::SEED000;
        let dp = 1e5;
        let slope = (oil.viscosity_at_pressure(dp).ln() - oil.viscosity.ln()) / dp;
        assert!((slope / oil.pressure_viscosity - 1.0).abs() < 1e-3, "{slope}");
        // Roelands grows slower than Barus at high pressure.
        let barus = Lubricant { viscosity_model: ViscosityModel::Barus, ..oil };
        assert!(oil.viscosity_at_pressure(1e9) < barus.viscosity_at_pressure(1e9));
    }

    #[test]
    fn roelands_by_hand_at_half_gigapascal() {
        // η0 = 0.152: A1 = ln 0.152 + 9.67 = 7.786; Z = 2.2e-8·1.96e8/7.786 = 0.5538;
        // η(0.5 GPa) = 0.152 exp(7.7861 (−1 + 3.5510^0.55381)) = 0.152 exp(7.7861·1.01738)
        //            = 418.89 Pa·s
        let oil = Lubricant::SEED000;
        let eta = oil.viscosity_at_pressure(0.5e9);
        assert!((eta / 418.89 - 1.0).abs() < 1e-4, "{eta}");
    }

    #[test]
    fn viscosity_falls_with_temperature() {
        for model in [ViscosityModel::Barus, ViscosityModel::Roelands] {
            let oil = Lubricant { viscosity_model: model, ..Lubricant::SEED000 };
            let hot = oil.viscosity_at(0.0, oil.reference_temperature + 20.0);
            assert!(hot < oil.viscosity);
        }
    }

    #[test]
    fn dowson_higginson_limits() {
        let oil = Lubricant::SEED000;
        assert_eq!(oil.density_ratio(0.0, oil.reference_temperature), 1.0);
        // p → ∞: 1 + C1/C2 = 1.3529.
        let r = oil.density_ratio(1e13, oil.reference_temperature);
        assert!((r - (1.0 + DH_C1 / DH_C2)).abs() < 1e-3);
    }

    #[test]
    fn log_viscosity_and_slopes_match_finite_differences() {
        for model in [ViscosityModel::Barus, ViscosityModel::Roelands] {
            let oil = Lubricant { viscosity_model: model, ..Lubricant::SEED000 };
            let t = oil.reference_temperature + 7.0;
            for p in [1e6, 3e8, 1.2e9, 3e9] {
                let ln = oil.ln_viscosity_ratio(p, t);
                assert!((ln - (oil.viscosity_at(p, t) / oil.viscosity).ln()).abs() < 1e-9 * ln.abs().max(1.0));
                let dp = 1e3;
                let fd = (oil.ln_viscosity_ratio(p + dp, t) - oil.ln_viscosity_ratio(p - dp, t)) / (2.0 * dp);
                let slope = oil.ln_viscosity_pressure_slope(p, t);
                assert!((fd / slope - 1.0).abs() < 1e-6, "{model:?} {p}: {fd} vs {slope}");
                let fd = (oil.density_ratio(p + dp, t) - oil.density_ratio(p - dp, t)) / (2.0 * dp);
                let slope = oil.density_ratio_pressure_slope(p, t);
                assert!((fd / slope - 1.0).abs() < 1e-6, "density {p}: {fd} vs {slope}");
            }
        }
    }

    #[test]
    fn alpha_star_is_alpha_for_barus_and_below_alpha_for_roelands() {
        let barus = Lubricant { viscosity_model: ViscosityModel::Barus, ..Lubricant::SEED000 };
        assert!((barus.alpha_star() - 2.2e-8).abs() < 1e-20);
        let a = Lubricant::SEED000.alpha_star();
        assert!(a < 2.2e-8 && a > 1.5e-8, "{a}");
    }
}
