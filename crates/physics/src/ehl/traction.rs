//! Traction of a converged EHL film (seed 001 eq. 24–25).
//!
//! Body 1 moves at `u1` (surface `z = 0`), body 2 at `u2` (`z = h`); `u_s = u1 − u2`. The Newtonian
//! shear stress on the surfaces is the Couette part `η u_s / h` and the Poiseuille part
//! `(h/2) dp/dx` (seed 001 eq. 24):
//! * force per length on body 1 along +x: `F1 = ∫ (−η u_s/h − (h/2) dp/dx) dx`,
//! * on body 2: `F2 = ∫ (+η u_s/h − (h/2) dp/dx) dx`.
//!
//! With the Eyring model each surface stress `τ` becomes `τ0 asinh(τ/τ0)` (seed 001 eq. 25, where
//! `τ0` is the Eyring stress); a limiting shear stress `τ_L = τ_L0 + Λ p` optionally caps `|τ|`.
//! The friction coefficient is the sliding part `(F2 − F1)/(2w')` (signed like `u_s`); the rolling
//! (Poiseuille) part is reported separately. The shear is isothermal: no shear heating.

use crate::lubricant::Lubricant;
use serde::{Deserialize, Serialize};

/// Shear rheology of the film for the traction.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
pub struct Rheology {
    /// Eyring stress `τ0`, Pa; `None` is Newtonian.
    pub eyring_stress: Option<f64>,
    /// Limiting shear stress pressure coefficient `Λ` (`τ_L = τ_L0 + Λ p`); `None`: no limit.
    pub limiting_shear_coefficient: Option<f64>,
    /// Limiting shear stress at ambient pressure `τ_L0`, Pa (used with the coefficient; default 0).
    pub limiting_shear_stress: f64,
}

/// Forces per unit length from the film shear.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
pub struct TractionResult {
    /// Shear force on body 1 along +x, N/m.
    pub force_body_1: f64,
    /// Shear force on body 2 along +x, N/m.
    pub force_body_2: f64,
    /// Sliding friction coefficient `(F2 − F1)/(2 w')`, signed like `u_s`.
    pub friction_coefficient: f64,
    /// Rolling (Poiseuille) resistance `−∫ (h/2) dp/dx dx`, N/m, on each body.
    pub rolling_force: f64,
}

/// Surface stress law: Newtonian, Eyring, then the limiting cap.
fn stress(tau_newtonian: f64, p: f64, rheology: &Rheology) -> f64 {
    let mut tau = match rheology.eyring_stress {
        Some(t0) if t0 > 0.0 => t0 * (tau_newtonian / t0).asinh(),
        _ => tau_newtonian,
    };
    if let Some(lambda) = rheology.limiting_shear_coefficient {
        let cap = rheology.limiting_shear_stress + lambda * p.max(0.0);
        tau = tau.clamp(-cap, cap);
    }
    tau
}

/// Traction of the film `(x, p, h)` (m, Pa, m; increasing nodes) at temperature `t`.
pub fn traction(
    x: &[f64],
    p: &[f64],
    h: &[f64],
    lubricant: &Lubricant,
    t: f64,
    sliding_velocity: f64,
    load_per_length: f64,
    rheology: &Rheology,
) -> TractionResult {
    let n = x.len();
    if n < 3 {
        return TractionResult::default();
    }
    let ln_eta0 = lubricant.viscosity_at(0.0, t).ln();
    let (mut f1, mut f2, mut roll) = (0.0, 0.0, 0.0);
    for i in 0..n {
        let (a, b) = (i.saturating_sub(1), (i + 1).min(n - 1));
        let dpdx = (p[b] - p[a]) / (x[b] - x[a]);
        let eta = (ln_eta0 + lubricant.ln_viscosity_ratio(p[i], t)).min(600.0).exp();
        let couette = eta * sliding_velocity / h[i];
        let poiseuille = 0.5 * h[i] * dpdx;
        // Trapezoidal weights.
        let w = 0.5 * (x[b] - x[a]);
        f1 += w * stress(-couette - poiseuille, p[i], rheology);
        f2 += w * stress(couette - poiseuille, p[i], rheology);
        roll -= w * poiseuille;
    }
    TractionResult {
        force_body_1: f1,
        force_body_2: f2,
        friction_coefficient: (f2 - f1) / (2.0 * load_per_length),
        rolling_force: roll,
    }
}
