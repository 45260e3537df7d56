//! The film's dynamic coefficients in figures: dimensionless (per unit load) always, SI with
//! the bearing's [`Dimensions`], and the stability threshold of a rigid rotor on the film
//! (Lund 1987, [`super::dynamics::stability`]) as a mass and, for a rotor whose weight is the
//! load, as a speed.
//!
//! Scaling ([`super::dynamics`]): `K = stiffness · 6ηωRL(R/c)²/c`, `C = damping · 6ηωRL(R/c)²/(cω)`;
//! the threshold mass `m = M̄ W/(c ω²)` with `W = W̄ · 6ηωRL(R/c)²`; for `m = W/g` the threshold
//! speed `ω_th = √(M̄ g/c)` (at this Sommerfeld number).

use super::dynamics::{stability, Coefficients, TiltCoefficients};
use super::Dimensions;
use crate::Convergence;

/// Standard gravity, m/s².
const GRAVITY: f64 = 9.80665;

/// The 2×2 coefficients `[[xx, xy], [yx, yy]]` in figures (see the module docs).
#[derive(Debug, Clone, PartialEq)]
pub struct DynamicFigures {
    /// N/m (with dimensions).
    pub stiffness: Option<[[f64; 2]; 2]>,
    /// N·s/m (with dimensions).
    pub damping: Option<[[f64; 2]; 2]>,
    /// `K̄ = K c/W`; absent at zero load.
    pub stiffness_dimensionless: Option<[[f64; 2]; 2]>,
    /// `C̄ = C c ω/W`; absent at zero load.
    pub damping_dimensionless: Option<[[f64; 2]; 2]>,
    /// Whirl frequency / running speed at the threshold; absent at zero load.
    pub whirl_ratio: Option<f64>,
    /// `M̄ = m c ω²/W` at the threshold; absent when stable for any mass or at zero load.
    pub critical_mass_dimensionless: Option<f64>,
    /// The threshold mass per bearing, kg (with dimensions).
    pub critical_mass: Option<f64>,
    /// The threshold speed of a rotor whose weight is the load, rad/s (with dimensions).
    pub threshold_speed: Option<f64>,
    pub convergence: Convergence,
}

/// The 4×4 force and moment coefficients in figures: coordinates `(x, y, tilt_x, tilt_y)`.
#[derive(Debug, Clone, PartialEq)]
pub struct MomentFigures {
    /// SI (with dimensions): N/m, N/rad, N, N·m/rad by block.
    pub stiffness: Option<[[f64; 4]; 4]>,
    /// SI (with dimensions): the units of `stiffness` times s.
    pub damping: Option<[[f64; 4]; 4]>,
    /// `K̄ = K_ij c/(W l_i l_j)`, `l = (1, 1, L, L)`; absent at zero load.
    pub stiffness_dimensionless: Option<[[f64; 4]; 4]>,
    /// `C̄ = C_ij c ω/(W l_i l_j)`; absent at zero load.
    pub damping_dimensionless: Option<[[f64; 4]; 4]>,
    pub convergence: Convergence,
}

/// The figures of the 2×2 coefficients `c` of a film carrying `load` (W̄).
pub fn dynamic_figures(c: &Coefficients, load: f64, dimensions: Option<&Dimensions>) -> DynamicFigures {
    let d = dimensions;
    let scaled = |m: [[f64; 2]; 2], s: f64| [[m[0][0] * s, m[0][1] * s], [m[1][0] * s, m[1][1] * s]];
    let nondim = c.dimensionless(load);
    let stab = nondim.map(|(k, cc)| stability(k, cc));
    // K = (−∂F̄/∂X) · 6ηωRL(R/c)²/c, C = (−∂F̄/∂X') · 6ηωRL(R/c)²/(cω)
    let critical_mass = match (d, stab.and_then(|s| s.critical_mass)) {
        (Some(d), Some(m)) => Some(m * load * d.load_scale() / (d.clearance * d.omega * d.omega)),
        _ => None,
    };
    let threshold_speed = match (d, stab.and_then(|s| s.critical_mass)) {
        (Some(d), Some(m)) => Some((m * GRAVITY / d.clearance).sqrt()),
        _ => None,
    };
    DynamicFigures {
        stiffness: d.map(|d| scaled(c.stiffness, d.load_scale() / d.clearance)),
        damping: d.map(|d| scaled(c.damping, d.load_scale() / (d.clearance * d.omega))),
        stiffness_dimensionless: nondim.map(|(k, _)| scaled(k, 1.0)),
        damping_dimensionless: nondim.map(|(_, cc)| scaled(cc, 1.0)),
        whirl_ratio: stab.map(|s| s.whirl_ratio),
        critical_mass_dimensionless: stab.and_then(|s| s.critical_mass),
        critical_mass,
        threshold_speed,
        convergence: c.convergence.clone(),
    }
}

/// The figures of the 4×4 coefficients `c` of a film carrying `load` (W̄). Generalised
/// coordinates `(X, Y, Γx, Γy)` with `Γ = ψ L/c` and forces `(F̄, M̄/L)` in the solver
/// ([`TiltCoefficients`]), so `K_ij = stiffness_ij · (W_scale/c) · l_i l_j` with
/// `l = (1, 1, L, L)`, `C_ij` the same over ω.
pub fn moment_figures(c: &TiltCoefficients, load: f64, dimensions: Option<&Dimensions>) -> MomentFigures {
    let d = dimensions;
    let scaled = |m: &[[f64; 4]; 4], s: f64, length: f64| -> [[f64; 4]; 4] {
        let l = [1.0, 1.0, length, length];
        std::array::from_fn(|i| std::array::from_fn(|j| m[i][j] * s * l[i] * l[j]))
    };
    let nondim = c.dimensionless(load);
    MomentFigures {
        stiffness: d.map(|d| scaled(&c.stiffness, d.load_scale() / d.clearance, d.length)),
        damping: d.map(|d| scaled(&c.damping, d.load_scale() / (d.clearance * d.omega), d.length)),
        stiffness_dimensionless: nondim.map(|(k, _)| scaled(&k, 1.0, 1.0)),
        damping_dimensionless: nondim.map(|(_, cc)| scaled(&cc, 1.0, 1.0)),
        convergence: c.convergence.clone(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::Termination;

    fn coefficients() -> Coefficients {
        // a typical film (short-bearing-like numbers, W̄ units): cross-coupled, unstable for a heavy rotor
        Coefficients {
            stiffness: [[1.5, 1.2], [-2.0, 0.9]],
            damping: [[3.0, 0.4], [0.4, 2.5]],
            convergence: Convergence { iterations: 1, residual: 0.0, tolerance: 0.0, termination: Termination::Converged },
        }
    }

    /// The threshold speed is `√(M̄ g/c)` of the dimensionless threshold mass, the SI threshold
    /// mass `M̄ W/(c ω²)`; without dimensions only the dimensionless figures; at zero load none.
    #[test]
    fn the_threshold_follows_the_dimensionless_mass() {
        let c = coefficients();
        let d = Dimensions { radius: 0.05, length: 0.04, clearance: 6e-5, omega: 300.0, viscosity: 0.02 };
        let load = 0.3;
        let f = dynamic_figures(&c, load, Some(&d));
        let m = f.critical_mass_dimensionless.expect("unstable for some mass");
        assert_eq!(f.threshold_speed, Some((m * GRAVITY / d.clearance).sqrt()));
        let w = load * d.load_scale();
        assert!((f.critical_mass.unwrap() - m * w / (d.clearance * d.omega * d.omega)).abs() <= 1e-12 * f.critical_mass.unwrap());
        assert_eq!(f.stiffness_dimensionless.unwrap()[0][1], 1.2 / load);
        let none = dynamic_figures(&c, load, None);
        assert!(none.stiffness.is_none() && none.critical_mass.is_none() && none.threshold_speed.is_none());
        assert_eq!(none.critical_mass_dimensionless, f.critical_mass_dimensionless);
        let unloaded = dynamic_figures(&c, 0.0, Some(&d));
        assert!(unloaded.stiffness_dimensionless.is_none() && unloaded.whirl_ratio.is_none() && unloaded.stiffness.is_some());
    }
}
