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
//! * [`PinFriction::FiniteBearing`]: seed 000's finite-length bearing (eq. 10–13) from the
//!   journal solver's Reynolds solutions (Reynolds cavitation) tabulated over ε once per run,
//!   with an effective film temperature from the bearing's energy balance; see
//!   [`super::pin_finite`]. The torque on the roller is again the rotating member's (Couette
//!   shear plus the pressure-gradient term).

use super::pin_finite::FinitePin;

/// Roller–pin friction model.
#[derive(Debug, Clone, PartialEq)]
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
    /// Finite-length hydrodynamic bearing (journal solver table) with an effective film
    /// temperature.
    FiniteBearing(FinitePin),
}

/// Torque (N·m, opposing the roller's rotation: same sign as Ω) and dT/dΩ (N·m·s) at roller
/// speed `omega` (rad/s) and pin load `load` (N). `side` selects the one-sided limit at Ω = 0
/// (−1 left, +1 right, 0 the value 0).
pub fn pin_torque(pin: &PinFriction, omega: f64, load: f64, side: i8) -> (f64, f64) {
    pin_torque_warm(pin, omega, load, side, &std::cell::Cell::new(f64::NAN))
}

/// [`pin_torque`] with a warm start for the short bearing's eccentricity solve: `warm` holds the
/// last eccentricity ε (NaN: none) and is updated. Inside one torque-balance solve the load is
/// fixed and Ω barely changes, so Newton then needs one or two steps. For the finite bearing
/// `warm` holds the last effective film temperature (K) of its energy balance instead (the
/// eccentricity is a table look-up); the slope then includes the temperature's response to Ω.
pub fn pin_torque_warm(pin: &PinFriction, omega: f64, load: f64, side: i8, warm: &std::cell::Cell<f64>) -> (f64, f64) {
    match *pin {
        PinFriction::FiniteBearing(ref p) => {
            let s = p.state(omega, load, warm);
            (s.torque, s.torque_slope)
        }
        PinFriction::Coefficient { coefficient, pin_radius } => {
            let t = coefficient * pin_radius * load.abs();
            let sign = if omega > 0.0 { 1.0 } else if omega < 0.0 { -1.0 } else { side as f64 };
            (t * sign, 0.0)
        }
        PinFriction::ShortBearing { .. } => {
            if omega == 0.0 {
                return (0.0, 0.0);
            }
            let (t, dt) = short_bearing_torque(pin, omega.abs(), load.abs(), warm);
            // T is odd in Ω, so dT/dΩ is even.
            (t * omega.signum(), dt)
        }
    }
}

/// Effective film temperature of the pin bearing (K) at roller speed `omega` (rad/s) and pin
/// load `load` (N): the finite bearing's energy-balance temperature (its ambient temperature when
/// isothermal or at Ω = 0); `None` for the models without a film temperature.
pub fn pin_film_temperature(pin: &PinFriction, omega: f64, load: f64) -> Option<f64> {
    pin_film_temperature_warm(pin, omega, load, &std::cell::Cell::new(f64::NAN))
}

/// [`pin_film_temperature`] warm-started like [`pin_torque_warm`] (the same cell may be shared).
pub fn pin_film_temperature_warm(pin: &PinFriction, omega: f64, load: f64, warm: &std::cell::Cell<f64>) -> Option<f64> {
    match pin {
        PinFriction::FiniteBearing(p) => {
            if p.thermal.is_none() {
                return Some(p.ambient_temperature);
            }
            Some(p.state(omega, load, warm).film_temperature)
        }
        _ => None,
    }
}

/// Eccentricity ratio of the short bearing for Sommerfeld-like target `s = 4c²W/(ηUL³)`.
pub fn short_bearing_eccentricity(s: f64) -> f64 {
    eccentricity_q(s, f64::NAN).0
}

/// Ocvirk's dimensionless load `f(ε) = ε √(π²(1 − ε²) + 16ε²)/(1 − ε²)²` (the short bearing's
/// `W = (η U L³/(4c²)) f(ε)`) and `d ln f/dε = 1/ε + (16 − π²)ε/A² + 4ε/(1 − ε²)`,
/// `A² = π²(1 − ε²) + 16ε²`.
fn load_function(e: f64) -> (f64, f64) {
    let pi2 = std::f64::consts::PI * std::f64::consts::PI;
    let e2 = e * e;
    let a2 = pi2 + (16.0 - pi2) * e2;
    let one_m = 1.0 - e2;
    (e * a2.sqrt() / (one_m * one_m), 1.0 / e + (16.0 - pi2) * e / a2 + 4.0 * e / one_m)
}

/// `(ε, q = −ln(1 − ε))` for target `s`, Newton from `q_start` when finite.
fn eccentricity_q(s: f64, q_start: f64) -> (f64, f64) {
    if !(s > 0.0) {
        return (0.0, 0.0);
    }
    // Newton on q = −ln(1 − ε) (resolves ε → 1) for f(ε(q)) = s, safeguarded by bisection on
    // [0, 40]; d ln f/dq = (1 − ε) d ln f/dε.
    let (mut lo, mut hi) = (0.0_f64, 40.0_f64);
    // Start from the asymptotes: f ≈ πε (light load), f ≈ 4/(1 − ε²)² (heavy load).
    let mut q = if q_start.is_finite() && q_start > 0.0 {
        q_start
    } else if s < 1.0 { -(-(s / std::f64::consts::PI).min(0.5)).ln_1p() } else { -(1.0 - (1.0 - 2.0 / s.sqrt()).max(0.0).sqrt()).max(1e-17).ln() };
    q = q.clamp(1e-12, 39.0);
    for _ in 0..100 {
        let e = -(-q).exp_m1();
        // Newton on f − s (no logarithm per step): d(f − s)/dq = f · d ln f/dq.
        let (f, dln_f) = load_function(e);
        let g = f - s;
        if g.abs() < 1e-13 * s {
            break;
        }
        if g < 0.0 { lo = q } else { hi = q }
        let dg = f * (1.0 - e) * dln_f;
        // Far from the root the logarithmic step is the robust one.
        let next = if (g / s).abs() > 0.5 { q - (f / s).ln() / (dg / f) } else { q - g / dg };
        let next = if next > lo && next < hi && dg > 0.0 { next } else { 0.5 * (lo + hi) };
        // Newton converges quadratically here (f is smooth in q, |q f''/f'| = O(1)): from a
        // relative residual below 1e-7 the step lands within ~1e-14 of the root, so it is taken
        // without evaluating f again (the warm-started calls of the torque balance mostly end
        // here after one evaluation).
        let done = (next - q).abs() < 1e-11 * q.max(1e-9) || hi - lo < 1e-14 || (g / s).abs() < 1e-7;
        q = next;
        if done {
            break;
        }
    }
    (-(-q).exp_m1(), q)
}

/// Newton in ε from a nearby eccentricity `e0` (the last one of a warm start), without
/// transcendental functions: at most four steps, each staying in `(0, 1 − 1e-6)` (closer to 1 the
/// logarithmic variable of [`eccentricity_q`] is needed); done when the relative residual is
/// below 1e-13, or with the step taken from a residual below 1e-7 (it then lands within ~1e-14
/// of the root, as in [`eccentricity_q`]). From one angle of a cycle to the next the load and
/// speed move by parts per thousand and two or three steps suffice. `None`: not applicable.
fn eccentricity_near(s: f64, e0: f64) -> Option<f64> {
    if !(s > 0.0 && e0 > 0.0 && e0 < 1.0 - 1e-6) {
        return None;
    }
    let mut e = e0;
    for _ in 0..4 {
        let (f, dln_f) = load_function(e);
        let g = f - s;
        if g.abs() < 1e-13 * s {
            return Some(e);
        }
        let next = e - g / (f * dln_f);
        if !(next > 0.0 && next < 1.0 - 1e-6) {
            return None;
        }
        if g.abs() < 1e-7 * s {
            return Some(next);
        }
        e = next;
    }
    None
}

/// `(T, dT/dΩ)` of the short bearing at `omega > 0`. With `ε(Ω)` from `f(ε) = s ∝ 1/Ω`,
/// `dε/dΩ = −1/(Ω d ln f/dε)`, `d ln f/dε = 1/ε + (16 − π²)ε/A² + 4ε/(1 − ε²)`,
/// `A² = π²(1 − ε²) + 16ε²`; the Petroff-like term `T_p ∝ Ω/√(1 − ε²)` has
/// `∂T_p/∂ε = T_p ε/(1 − ε²)` and the load-moment term `T_w ∝ ε√(1 − ε²)/A` has
/// `∂T_w/∂ε = T_w (1/ε − ε/(1 − ε²) − (16 − π²)ε/A²)`. The exact slope keeps the Newton iteration
/// of the torque balance quadratic.
fn short_bearing_torque(pin: &PinFriction, omega: f64, load: f64, warm: &std::cell::Cell<f64>) -> (f64, f64) {
    let PinFriction::ShortBearing { pin_radius: r, clearance: c, length: l, viscosity: eta } = *pin else {
        return (0.0, 0.0);
    };
    if omega <= 0.0 {
        return (0.0, 0.0);
    }
    let u = r * omega;
    let s = 4.0 * c * c * load / (eta * u * l * l * l);
    let e = match eccentricity_near(s, warm.get()) {
        Some(e) => e,
        None => {
            let w = warm.get();
            let q_start = if w > 0.0 && w < 1.0 { -(-w).ln_1p() } else { f64::NAN };
            eccentricity_q(s, q_start).0
        }
    };
    warm.set(e);
    let one_m = 1.0 - e * e;
    let root = one_m.sqrt();
    let pi = std::f64::consts::PI;
    let a2 = pi * pi * one_m + 16.0 * e * e;
    let a = a2.sqrt();
    let sin_phi = pi * root / a;
    let petroff = 2.0 * pi * eta * r * r * r * l * omega / (c * root);
    let moment = 0.5 * c * e * load * sin_phi;
    let mut slope = petroff / omega;
    if e > 0.0 {
        let k = (16.0 - pi * pi) * e / a2;
        let de_domega = -1.0 / (omega * load_function(e).1);
        slope += (petroff * e / one_m + moment * (1.0 / e - e / one_m - k)) * de_domega;
    }
    (petroff + moment, slope)
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
        assert!((s / (petroff / 100.0) - 1.0).abs() < 1e-9);
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
    fn warm_eccentricity_matches_the_cold_solve() {
        let f = |e: f64| load_function(e).0;
        for (e, e0) in [(0.3, 0.2999), (0.3, 0.31), (0.6, 0.59), (0.9, 0.899), (0.05, 0.06)] {
            let s = f(e);
            let cold = short_bearing_eccentricity(s);
            match eccentricity_near(s, e0) {
                Some(warm) => assert!((warm - cold).abs() < 1e-13, "ε = {e} from {e0}: {warm} vs {cold}"),
                None => panic!("ε = {e} from {e0}: no warm solve"),
            }
        }
        // Too far or too close to 1: left to the logarithmic solve.
        assert!(eccentricity_near(f(0.999), 0.5).is_none());
        assert!(eccentricity_near(f(0.5), 1.0 - 1e-7).is_none());
    }

    #[test]
    fn short_bearing_slope_is_the_derivative() {
        let pin = PinFriction::ShortBearing { pin_radius: 0.016, clearance: 10e-6, length: 0.014, viscosity: 0.152 };
        for (omega, load) in [(100.0, 600.0), (5.0, 2000.0), (300.0, 50.0), (0.5, 5000.0)] {
            let h = 1e-6 * omega;
            let fd = (pin_torque(&pin, omega + h, load, 0).0 - pin_torque(&pin, omega - h, load, 0).0) / (2.0 * h);
            let s = pin_torque(&pin, omega, load, 0).1;
            assert!((fd / s - 1.0).abs() < 1e-6, "Ω = {omega}, W = {load}: {fd} vs {s}");
            assert_eq!(pin_torque(&pin, -omega, load, 0).1, s);
        }
    }

    #[test]
    fn coefficient_pin_is_coulomb() {
        let pin = PinFriction::Coefficient { coefficient: 0.01, pin_radius: 0.0091 };
        assert_eq!(pin_torque(&pin, 3.0, 1000.0, 0).0, 0.091);
        assert_eq!(pin_torque(&pin, 0.0, 1000.0, -1).0, -0.091);
        assert_eq!(pin_torque(&pin, 0.0, 1000.0, 0).0, 0.0);
    }
}
