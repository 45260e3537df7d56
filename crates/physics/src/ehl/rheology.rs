//! The lubricant's pressure dependence as the Newton EHL solver evaluates it at every node and
//! iteration: `ln(η/η(0,T))` and `ρ/ρ0` with their pressure derivatives at a uniform temperature,
//! the temperature factors evaluated once per problem (the laws of `physics::lubricant`).

use crate::lubricant::{DensityModel, Lubricant, ViscosityModel, DH_C1, DH_C2, DH_C3, ROELANDS_PRESSURE};

/// Pressure dependence of `ln η̄ = ln(η/η(0,T))` and `ρ̄ = ρ/ρ0` at the (uniform) temperature,
/// with the temperature factors evaluated once per problem (same laws as [`Lubricant`]).
#[derive(Debug, Clone, Copy)]
pub(crate) struct PressureRheology {
    /// Barus: `ln η̄ = α p`. Roelands: `ln η̄ = A1 θ ((1 + p/p_r)^Z − 1)`.
    pub(super) roelands: bool,
    pub(super) alpha: f64,
    /// Roelands `A1 θ` and `Z`.
    pub(super) a1_theta: f64,
    pub(super) z: f64,
    /// Dowson–Higginson thermal term `1 − C3 (T − T0)` (1 when incompressible, and then no
    /// pressure dependence).
    pub(super) compressible: bool,
    pub(super) rho_thermal: f64,
}

impl PressureRheology {
    pub(crate) fn new(lub: &Lubricant, t: f64) -> Self {
        let roelands = lub.viscosity_model == ViscosityModel::Roelands;
        // ln η̄ = ln η(p,T)/η0 − ln η(0,T)/η0; for Roelands both share A1 θ with
        // θ = ((T − 138)/(T0 − 138))^(−S0): recover A1 θ from the ratio at one pressure.
        let (a1_theta, z) = if roelands {
            let z = lub.roelands_z();
            let pr = ROELANDS_PRESSURE;
            // ln η̄(p_r) = A1 θ (2^Z − 1).
            let l = lub.ln_viscosity_ratio(pr, t) - lub.ln_viscosity_ratio(0.0, t);
            (l / (2f64.powf(z) - 1.0), z)
        } else {
            (0.0, 0.0)
        };
        let compressible = lub.density_model == DensityModel::DowsonHigginson;
        let rho_thermal = if compressible { 1.0 - DH_C3 * (t - lub.reference_temperature) } else { 1.0 };
        PressureRheology { roelands, alpha: lub.pressure_viscosity, a1_theta, z, compressible, rho_thermal }
    }

    /// `(ln η̄, d ln η̄/dp, ρ̄, dρ̄/dp)` at gauge pressure `p` (Pa; clamped at 0, slopes 0 below).
    #[inline]
    pub(crate) fn at(&self, p: f64) -> (f64, f64, f64, f64) {
        let pc = p.max(0.0);
        let on = if p < 0.0 { 0.0 } else { 1.0 };
        let (ln_eta, dln) = if self.roelands {
            let s = 1.0 + pc / ROELANDS_PRESSURE;
            // `1^z = 1` exactly: no `powf` for a cavitated node.
            let q = if pc == 0.0 { 1.0 } else { s.powf(self.z) };
            (self.a1_theta * (q - 1.0), on * self.a1_theta * self.z * q / (s * ROELANDS_PRESSURE))
        } else {
            (self.alpha * pc, on * self.alpha)
        };
        let (rho, drho) = if self.compressible {
            let d = 1.0 + DH_C2 * pc;
            (self.rho_thermal + DH_C1 * pc / d, on * DH_C1 / (d * d))
        } else {
            (1.0, 0.0)
        };
        (ln_eta, dln, rho, drho)
    }
}
