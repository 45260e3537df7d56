//! Friction of a lubricated concentrated contact: viscous traction of the film (Newtonian or
//! Eyring, optionally capped by a limiting shear stress) integrated over the contact, plus the
//! asperity friction of the load share carried by the roughness (Greenwood–Tripp).
//!
//! The film model (see [`crate::physics::film`]) reduces a contact to a handful of
//! [`TractionNode`]s — area, local pressure, low-shear viscosity, film thickness — once per contact
//! point; [`viscous_traction`] then evaluates the traction for any sliding velocity cheaply, which
//! is what the roller torque balance needs inside its root finder.
//!
//! Shear stress at a node for sliding velocity `u_s` (seed 001 eq. 24–25, Couette part; the
//! Poiseuille part averages out across the film and is not a traction):
//! * Newtonian: `τ = η u_s / h`;
//! * Eyring: `τ = τ0 asinh(η u_s / (h τ0))` (seed 001 eq. 25, τ0 the Eyring stress);
//! * limiting shear (optional): `|τ| ≤ Λ p`.

pub mod greenwood_tripp;

pub use greenwood_tripp::{f52, Roughness};

/// Shear law of the lubricant film.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Rheology {
    Newtonian,
    /// Eyring with characteristic stress `tau0`, Pa.
    Eyring { tau0: f64 },
}

/// Film traction law.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TractionLaw {
    pub rheology: Rheology,
    /// Limiting shear stress coefficient Λ (`|τ| ≤ Λ p`), if any.
    pub limiting_shear_coefficient: Option<f64>,
}

/// One quadrature node of a contact for the traction integral.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TractionNode {
    /// Area represented by the node, m².
    pub area: f64,
    /// Fluid pressure at the node, Pa.
    pub pressure: f64,
    /// Low-shear viscosity at the node's pressure and temperature, Pa·s.
    pub viscosity: f64,
    /// Film thickness at the node, m (> 0).
    pub film: f64,
}

/// Viscous traction force (N, same sign as `u_s`) and its derivative with respect to `u_s`
/// (N·s/m) over `nodes`.
pub fn viscous_traction(nodes: &[TractionNode], law: &TractionLaw, sliding_velocity: f64) -> (f64, f64) {
    let u = sliding_velocity;
    let mut force = 0.0;
    let mut slope = 0.0;
    for n in nodes {
        let g = n.viscosity / n.film; // shear modulus of the rate: τ_N = g u
        let (mut tau, mut dtau) = match law.rheology {
            Rheology::Newtonian => (g * u, g),
            Rheology::Eyring { tau0 } => {
                let x = g * u / tau0;
                let r = (x * x + 1.0).sqrt();
                // asinh(x) = sign(x) ln(|x| + r), stable for large |x|.
                (tau0 * x.signum() * (x.abs() + r).ln(), g / r)
            }
        };
        if let Some(lam) = law.limiting_shear_coefficient {
            let cap = lam * n.pressure.max(0.0);
            if tau.abs() > cap {
                tau = cap * u.signum();
                dtau = 0.0;
            }
        }
        force += n.area * tau;
        slope += n.area * dtau;
    }
    (force, slope)
}

/// Friction law of the asperity-borne load share.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum AsperityModel {
    /// Gross sliding: `Q_a = μ_b W_a sign(u_s)` (set-valued at `u_s = 0`: the asperities stick and
    /// transmit any traction up to `μ_b W_a`). Seed 001's "constant asperity friction" case.
    Coulomb,
    /// Partial slip (Carter's 2D rolling-creep law applied to the asperity share; Johnson,
    /// *Contact Mechanics* §8.2): `Q_a/(μ_b W_a) = 1 − (1 − |ξ|/ξ_c)²` for `|ξ| < ξ_c`, 1 beyond,
    /// with creep `ξ = u_s/u_e` (the slide-to-roll ratio) and gross-sliding creep `ξ_c = μ_b b/R`.
    /// A smooth analogue of seed 001's stick–slip asperity friction map.
    Carter,
}

/// Asperity friction parameters.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct AsperityFriction {
    /// Boundary (asperity) friction coefficient μ_b.
    pub coefficient: f64,
    pub model: AsperityModel,
}

/// The asperity part of a contact's traction at one instant.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct AsperityContact {
    /// Load carried by the asperities, N.
    pub load: f64,
    /// Gross-sliding creep ξ_c = μ_b b/R (Carter).
    pub gross_sliding_creep: f64,
}

impl AsperityFriction {
    /// Traction (N, sign of `u_s`) and slope (N·s/m) for sliding `u_s` and entrainment `u_e`.
    /// For [`AsperityModel::Coulomb`] at `u_s = 0` the value is 0: the caller treats the jump of
    /// height `±μ_b W_a` there ([`Self::stick_limit`]).
    pub fn traction(&self, contact: &AsperityContact, sliding: f64, entrainment: f64) -> (f64, f64) {
        let q = self.coefficient * contact.load;
        if q == 0.0 || sliding == 0.0 {
            let slope = match self.model {
                AsperityModel::Carter if entrainment.abs() > 0.0 && contact.gross_sliding_creep > 0.0 => {
                    2.0 * q / (contact.gross_sliding_creep * entrainment.abs())
                }
                _ => 0.0,
            };
            return (0.0, slope);
        }
        match self.model {
            AsperityModel::Coulomb => (q * sliding.signum(), 0.0),
            AsperityModel::Carter => {
                let ue = entrainment.abs();
                let xc = contact.gross_sliding_creep;
                if !(ue > 0.0 && xc > 0.0) {
                    return (q * sliding.signum(), 0.0);
                }
                let r = (sliding.abs() / ue) / xc;
                if r >= 1.0 {
                    (q * sliding.signum(), 0.0)
                } else {
                    (q * sliding.signum() * (1.0 - (1.0 - r).powi(2)), 2.0 * q * (1.0 - r) / (xc * ue))
                }
            }
        }
    }

    /// Half-height of the traction jump at `u_s = 0` (N): `μ_b W_a` for Coulomb, 0 for Carter.
    pub fn stick_limit(&self, contact: &AsperityContact) -> f64 {
        match self.model {
            AsperityModel::Coulomb => self.coefficient * contact.load,
            AsperityModel::Carter => 0.0,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn node() -> TractionNode {
        TractionNode { area: 1e-6, pressure: 1e9, viscosity: 100.0, film: 0.5e-6 }
    }

    #[test]
    fn newtonian_and_eyring_agree_at_low_shear_and_eyring_saturates() {
        let n = [node()];
        let newton = TractionLaw { rheology: Rheology::Newtonian, limiting_shear_coefficient: None };
        let eyring = TractionLaw { rheology: Rheology::Eyring { tau0: 5e6 }, limiting_shear_coefficient: None };
        let u = 1e-6; // τ_N = 100·1e-6/0.5e-6 = 200 Pa ≪ τ0
        let (fn_, sn) = viscous_traction(&n, &newton, u);
        let (fe, se) = viscous_traction(&n, &eyring, u);
        assert!((fn_ - 200.0 * 1e-6).abs() < 1e-15 && (fe / fn_ - 1.0).abs() < 1e-9);
        assert!((se / sn - 1.0).abs() < 1e-9);
        // High shear: τ = τ0 asinh(x) with x = 2e8·1/5e6 = 40 → τ0 ln(40 + √1601).
        let (fe, _) = viscous_traction(&n, &eyring, 1.0);
        assert!((fe / (1e-6 * 5e6 * (40.0f64 + 1601f64.sqrt()).ln()) - 1.0).abs() < 1e-12);
        // Odd in u_s.
        assert_eq!(viscous_traction(&n, &eyring, -1.0).0, -fe);
        // Limiting shear caps at Λp.
        let capped = TractionLaw { limiting_shear_coefficient: Some(0.01), ..eyring };
        assert!((viscous_traction(&n, &capped, 1.0).0 - 1e-6 * 1e7).abs() < 1e-9);
    }

    #[test]
    fn eyring_slope_matches_finite_differences() {
        let n = [node(), TractionNode { pressure: 2e8, viscosity: 0.5, ..node() }];
        let law = TractionLaw { rheology: Rheology::Eyring { tau0: 5e6 }, limiting_shear_coefficient: None };
        for u in [1e-4, 0.01, 0.3] {
            let h = 1e-6 * u;
            let fd = (viscous_traction(&n, &law, u + h).0 - viscous_traction(&n, &law, u - h).0) / (2.0 * h);
            let s = viscous_traction(&n, &law, u).1;
            assert!((fd / s - 1.0).abs() < 1e-6, "u={u}: {fd} vs {s}");
        }
    }

    #[test]
    fn carter_creep_curve() {
        let a = AsperityFriction { coefficient: 0.12, model: AsperityModel::Carter };
        let c = AsperityContact { load: 1000.0, gross_sliding_creep: 0.003 };
        let ue = 4.0;
        // Half the gross-sliding creep: 1 − (1/2)² = 3/4 of μ_b W_a.
        let (q, _) = a.traction(&c, 0.5 * 0.003 * ue, ue);
        assert!((q - 0.75 * 120.0).abs() < 1e-9);
        assert_eq!(a.traction(&c, 0.01 * ue, ue).0, 120.0);
        assert_eq!(a.traction(&c, -0.01 * ue, ue).0, -120.0);
        // Initial slope 2 μ_b W_a/(ξ_c u_e).
        assert!((a.traction(&c, 0.0, ue).1 - 2.0 * 120.0 / (0.003 * ue)).abs() < 1e-9);
        let coulomb = AsperityFriction { model: AsperityModel::Coulomb, ..a };
        assert_eq!(coulomb.stick_limit(&c), 120.0);
        assert_eq!(a.stick_limit(&c), 0.0);
    }
}
