//! Friction torque of the roller–pin contact (the roller turning on a stationary pin).
//!
//! * [`PinFriction::Coefficient`]: a constant friction coefficient, `T = μ_rp R_pin W sign(Ω)`
//!   (seed 001 eq. 26); set-valued at Ω = 0 (the roller sticks to the pin until the driving torque
//!   exceeds `μ_rp R_pin W`).
//! * [`PinFriction::ShortBearing`]: a hydrodynamic journal bearing in Ocvirk's short-bearing
//!   approximation (Hamrock, *Fundamentals of Fluid Film Lubrication*, ch. 10), standing in for
//!   seed 000's finite-length solution (eq. 10–13): eccentricity ε from the load
//!   `W = (η U L³/(4c²)) ε √(π²(1 − ε²) + 16ε²)/(1 − ε²)²`, `U = R Ω`, and the torque on the
//!   rotating member `T = 2πηR³LΩ/(c√(1 − ε²)) + (c ε W/2) sin φ`,
//!   `tan φ = π√(1 − ε²)/(4ε)`. Valid for `L/D ≲ 1` (seed 000: 14/32 = 0.44) and moderate ε;
//!   near Ω → 0 the film collapses (ε → 1) and the torque tends to 0 — a real pin then runs in
//!   mixed friction, which this model does not include. Rotating bush and rotating journal have
//!   the same pressure field (the film shape is fixed by the load direction); the driven member
//!   carries the `+` sign of the load-moment term in both cases.

/// Roller–pin friction model.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum PinFriction {
    /// Constant coefficient μ_rp on the pin radius.
    Coefficient { coefficient: f64, pin_radius: f64 },
    /// Short hydrodynamic bearing.
    ShortBearing {
        /// Pin radius R, m.
        pin_radius: f64,
        /// Radial clearance c, m.
        clearance: f64,
        /// Bearing length L, m.
        length: f64,
        /// Oil viscosity in the bearing, Pa·s.
        viscosity: f64,
    },
}

/// Torque (N·m, opposing the roller's rotation: same sign as Ω) and dT/dΩ (N·m·s) at roller
/// speed `omega` (rad/s) and pin load `load` (N). `side` selects the one-sided limit at Ω = 0
/// (−1 left, +1 right, 0 the value 0).
pub fn pin_torque(pin: &PinFriction, omega: f64, load: f64, side: i8) -> (f64, f64) {
    match *pin {
        PinFriction::Coefficient { coefficient, pin_radius } => {
            let t = coefficient * pin_radius * load.abs();
            let sign = if omega > 0.0 { 1.0 } else if omega < 0.0 { -1.0 } else { side as f64 };
            (t * sign, 0.0)
        }
        PinFriction::ShortBearing { .. } => {
            let t = short_bearing_torque(pin, omega.abs(), load.abs()) * omega.signum();
            let h = 1e-6 * omega.abs().max(1e-3);
            let slope = (short_bearing_torque(pin, omega.abs() + h, load.abs())
                - short_bearing_torque(pin, (omega.abs() - h).max(0.0), load.abs()))
                / (omega.abs() + h - (omega.abs() - h).max(0.0));
            (if omega == 0.0 { 0.0 } else { t }, slope)
        }
    }
}

/// Eccentricity ratio of the short bearing for Sommerfeld-like target `s = 4c²W/(ηUL³)`.
pub fn short_bearing_eccentricity(s: f64) -> f64 {
    if !(s > 0.0) {
        return 0.0;
    }
    let pi2 = std::f64::consts::PI * std::f64::consts::PI;
    let f = |e: f64| {
        let e2 = e * e;
        let a = pi2 + (16.0 - pi2) * e2;
        e * a.sqrt() / ((1.0 - e2) * (1.0 - e2))
    };
    // Bisection on e ∈ (0, 1) in the variable q = −ln(1 − e) for resolution near 1.
    let (mut lo, mut hi) = (0.0_f64, 40.0_f64);
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        let e = -(-mid).exp_m1();
        if f(e) < s { lo = mid } else { hi = mid }
        if hi - lo < 1e-13 {
            break;
        }
    }
    -(-(0.5 * (lo + hi))).exp_m1()
}

fn short_bearing_torque(pin: &PinFriction, omega: f64, load: f64) -> f64 {
    let PinFriction::ShortBearing { pin_radius: r, clearance: c, length: l, viscosity: eta } = *pin else {
        return 0.0;
    };
    if omega <= 0.0 {
        return 0.0;
    }
    let u = r * omega;
    let e = short_bearing_eccentricity(4.0 * c * c * load / (eta * u * l * l * l));
    let root = (1.0 - e * e).sqrt();
    let pi = std::f64::consts::PI;
    let a = (pi * pi * (1.0 - e * e) + 16.0 * e * e).sqrt();
    let sin_phi = pi * root / a;
    2.0 * pi * eta * r * r * r * l * omega / (c * root) + 0.5 * c * e * load * sin_phi
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn unloaded_short_bearing_is_petroff() {
        let pin = PinFriction::ShortBearing { pin_radius: 0.016, clearance: 10e-6, length: 0.014, viscosity: 0.152 };
        let (t, s) = pin_torque(&pin, 100.0, 0.0, 0);
        let petroff = 2.0 * std::f64::consts::PI * 0.152 * 0.016f64.powi(3) * 0.014 * 100.0 / 10e-6;
        assert!((t / petroff - 1.0).abs() < 1e-9, "{t} vs {petroff}");
        assert!((s / (petroff / 100.0) - 1.0).abs() < 1e-5);
    }

    #[test]
    fn eccentricity_inverts_the_load_relation() {
        let pi2 = std::f64::consts::PI.powi(2);
        for e in [0.05, 0.3, 0.6, 0.9, 0.99] {
            let s = e * (pi2 * (1.0 - e * e) + 16.0 * e * e).sqrt() / (1.0 - e * e).powi(2);
            assert!((short_bearing_eccentricity(s) - e).abs() < 1e-10, "ε = {e}");
        }
        // Load raises eccentricity and torque.
        let pin = PinFriction::ShortBearing { pin_radius: 0.016, clearance: 10e-6, length: 0.014, viscosity: 0.152 };
        assert!(pin_torque(&pin, 100.0, 5000.0, 0).0 > pin_torque(&pin, 100.0, 100.0, 0).0);
        assert_eq!(pin_torque(&pin, 0.0, 5000.0, 1).0, 0.0);
    }

    #[test]
    fn coefficient_pin_is_coulomb() {
        let pin = PinFriction::Coefficient { coefficient: 0.01, pin_radius: 0.0091 };
        assert_eq!(pin_torque(&pin, 3.0, 1000.0, 0).0, 0.091);
        assert_eq!(pin_torque(&pin, 0.0, 1000.0, -1).0, -0.091);
        assert_eq!(pin_torque(&pin, 0.0, 1000.0, 0).0, 0.0);
    }
}
