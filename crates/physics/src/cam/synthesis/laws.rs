//! The normalised pieces a synthesised lift is built of: the main rise laws `S(u)` (the classical
//! polynomials, cycloidal, and the polydyne), the ramp-velocity correction `G(u)` and the ramp's
//! velocity blend `B(t)`.
//!
//! Polydyne (Dudley 1948; Stoddart, "Polydyne cam design", *Machine Design* 1953; Rothbart, *Cam
//! Design Handbook*, polydyne cams; Norton, *Cam Design and Manufacturing Handbook*, polynomial
//! functions): the valve motion of a symmetric rise–return written from the nose,
//! `y/h = 1 + C₂x² + C_p x^p + C_q x^q + C_r x^r + C_s x^s`, `x` = angle from the nose over the
//! half-event angle, with `y = y' = y'' = y''' = y'''' = 0` at `x = 1`. Its coefficients are
//! Stoddart's closed forms, e.g. `C₂ = −pqrs/((p−2)(q−2)(r−2)(s−2))`,
//! `C_p = 2qrs/((p−2)(q−p)(r−p)(s−p))` — in general `C_k = −2pqrs/(k Π_{j≠k}(k − j))` over the
//! five powers (the divided-difference form of the same solution). The classic 2-6-10-14-18
//! polydyne has `C = (−315/128, 105/32, −189/64, 45/32, −35/128)`
//! `= (−2.4609, 3.2813, −2.9531, 1.4063, −0.2734)`.

use crate::cam::lift::LiftLaw;
use serde::{Deserialize, Serialize};

/// The law of the main rise (and, mirrored, of the return).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum RiseLaw {
    /// 2-6-10-14-18 polydyne: symmetric about the nose (no top dwell), lift derivatives through
    /// the fourth zero where it meets the ramp, continuous jerk everywhere.
    Polydyne,
    /// 3-4-5 polynomial: acceleration zero at both ends, jerk 60 h/β³ there (a finite step).
    #[serde(rename = "polynomial_345")]
    Polynomial345,
    /// 4-5-6-7 polynomial: acceleration and jerk zero at both ends (continuous jerk).
    #[serde(rename = "polynomial_4567")]
    Polynomial4567,
    /// Cycloidal: acceleration zero at both ends, jerk 4π² h/β³ there (a finite step).
    Cycloidal,
}

/// Powers of the standard polydyne.
pub const POLYDYNE_POWERS: [i32; 5] = [2, 6, 10, 14, 18];

/// Stoddart's coefficients `C_k = −2pqrs/(k Π_{j≠k}(k − j))` for the powers `[2, p, q, r, s]`
/// (distinct, the first 2): the polydyne with `y = y' = … = y'''' = 0` at `x = 1`, `y(0) = 1`.
pub fn polydyne_coefficients(powers: [i32; 5]) -> [f64; 5] {
    let k: [f64; 5] = powers.map(f64::from);
    let pqrs: f64 = k[1..].iter().product();
    let mut c = [0.0; 5];
    for i in 0..5 {
        let prod: f64 = (0..5).filter(|&j| j != i).map(|j| k[i] - k[j]).product();
        c[i] = -2.0 * pqrs / (k[i] * prod);
    }
    c
}

/// `[y, dy/dx, d²y/dx², d³y/dx³]` of `y = 1 + Σ C_k x^k`.
fn polydyne_x(x: f64) -> [f64; 4] {
    let c = polydyne_coefficients(POLYDYNE_POWERS);
    let mut out = [1.0, 0.0, 0.0, 0.0];
    for (ck, &p) in c.iter().zip(POLYDYNE_POWERS.iter()) {
        let n = f64::from(p);
        out[0] += ck * x.powi(p);
        out[1] += ck * n * x.powi(p - 1);
        out[2] += ck * n * (n - 1.0) * x.powi(p - 2);
        // The x² term has no third derivative (avoid 0 · x⁻¹ at x = 0).
        if p > 2 {
            out[3] += ck * n * (n - 1.0) * (n - 2.0) * x.powi(p - 3);
        }
    }
    out
}

impl RiseLaw {
    /// `[S, S', S'', S''']` of the normalised rise at `u ∈ [0, 1]` (clamped), `S(0) = 0`,
    /// `S(1) = 1`, `S'(0) = S'(1) = 0`.
    pub fn eval(self, u: f64) -> [f64; 4] {
        let u = u.clamp(0.0, 1.0);
        match self {
            RiseLaw::Polynomial345 => LiftLaw::Polynomial345.eval(u),
            RiseLaw::Polynomial4567 => LiftLaw::Polynomial4567.eval(u),
            RiseLaw::Cycloidal => LiftLaw::Cycloidal.eval(u),
            // x = 1 − u: odd derivatives change sign.
            RiseLaw::Polydyne => {
                let [y, y1, y2, y3] = polydyne_x(1.0 - u);
                [y, -y1, y2, -y3]
            }
        }
    }

    /// Whether the law ends at rest (zero acceleration at `u = 1`), so that it may meet a top
    /// dwell without an acceleration step. The polydyne is a rise–return law: it ends at the nose
    /// with its (negative) nose acceleration.
    pub fn ends_at_rest(self) -> bool {
        !matches!(self, RiseLaw::Polydyne)
    }
}

/// The ramp-velocity correction `G(u) = u(1−u)⁴(1 + 4u + 10u²) = u − 20u⁴ + 45u⁵ − 36u⁶ + 10u⁷`:
/// `G'(0) = 1` and `G = G' = G'' = G''' = 0` at `u = 1`, `G = G'' = G''' = 0` at `u = 0` — added
/// as `V β G(u)` to a rise that starts on a ramp of velocity `V` (m/rad) it makes the rise leave
/// the ramp with the ramp's velocity and no step in acceleration or jerk, and leaves the rise's
/// end untouched. (The septic with these eight boundary conditions; derived here.)
pub fn ramp_correction(u: f64) -> [f64; 4] {
    let u = u.clamp(0.0, 1.0);
    let (u2, u3) = (u * u, u * u * u);
    [
        u - u2 * u2 * (20.0 - 45.0 * u + 36.0 * u2 - 10.0 * u3),
        1.0 - u3 * (80.0 - 225.0 * u + 216.0 * u2 - 70.0 * u3),
        -u2 * (240.0 - 900.0 * u + 1080.0 * u2 - 420.0 * u3),
        -u * (480.0 - 2700.0 * u + 4320.0 * u2 - 2100.0 * u3),
    ]
}

/// The ramp's velocity blend: the velocity rises as the 3-4-5 step `B(t) = 10t³ − 15t⁴ + 6t⁵`
/// (`B' = B'' = 0` at both ends: acceleration and jerk start and end at zero). Returns
/// `[∫₀ᵗ B, B, B', B'']`; `∫₀¹ B = 1/2`.
pub fn ramp_blend(t: f64) -> [f64; 4] {
    let t = t.clamp(0.0, 1.0);
    let (t2, t3) = (t * t, t * t * t);
    [
        t2 * t2 * (2.5 - 3.0 * t + t2),
        t3 * (10.0 - 15.0 * t + 6.0 * t2),
        30.0 * t2 * (1.0 - t) * (1.0 - t),
        t * (60.0 - 180.0 * t + 120.0 * t2),
    ]
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn polydyne_2_6_10_14_18_coefficients_are_stoddarts() {
        let c = polydyne_coefficients(POLYDYNE_POWERS);
        let expect = [-315.0 / 128.0, 105.0 / 32.0, -189.0 / 64.0, 45.0 / 32.0, -35.0 / 128.0];
        for (a, b) in c.iter().zip(expect) {
            assert!((a - b).abs() < 1e-12, "{c:?}");
        }
        // The printed four-decimal values.
        let printed = [-2.4609, 3.2813, -2.9531, 1.4063, -0.2734];
        for (a, b) in c.iter().zip(printed) {
            assert!((a - b).abs() < 6e-5, "{a} vs {b}");
        }
        // Stoddart's separate closed forms for C₂ and C_p.
        let (p, q, r, s) = (6.0, 10.0, 14.0, 18.0);
        assert!((c[0] + p * q * r * s / ((p - 2.0) * (q - 2.0) * (r - 2.0) * (s - 2.0))).abs() < 1e-12);
        assert!((c[1] - 2.0 * q * r * s / ((p - 2.0) * (q - p) * (r - p) * (s - p))).abs() < 1e-12);
    }

    #[test]
    fn polydyne_meets_its_boundary_conditions() {
        // y(1) = 0 and y' … y'''' = 0 at x = 1 (the fourth derivative written out here).
        for powers in [POLYDYNE_POWERS, [2, 4, 6, 8, 10], [2, 5, 7, 9, 11]] {
            let c = polydyne_coefficients(powers);
            let k = powers.map(f64::from);
            let d = |m: usize| -> f64 {
                let mut sum = if m == 0 { 1.0 } else { 0.0 };
                for i in 0..5 {
                    sum += c[i] * (0..m).map(|j| k[i] - j as f64).product::<f64>();
                }
                sum
            };
            for m in 0..5 {
                assert!(d(m).abs() < 1e-9, "{powers:?} derivative {m}: {}", d(m));
            }
        }
        let s = RiseLaw::Polydyne.eval(0.0);
        assert!(s.iter().all(|x| x.abs() < 1e-12), "{s:?}");
        let n = RiseLaw::Polydyne.eval(1.0);
        assert!((n[0] - 1.0).abs() < 1e-15 && n[1].abs() < 1e-15 && n[3].abs() < 1e-15);
        assert!((n[2] - 2.0 * (-315.0 / 128.0)).abs() < 1e-12, "nose acceleration 2 C₂: {}", n[2]);
    }

    #[test]
    fn pieces_are_consistent_and_meet_their_boundary_conditions() {
        let g0 = ramp_correction(0.0);
        let g1 = ramp_correction(1.0);
        assert_eq!(g0, [0.0, 1.0, 0.0, 0.0]);
        assert!(g1.iter().all(|x| x.abs() < 1e-12), "{g1:?}");
        let b1 = ramp_blend(1.0);
        assert!((b1[0] - 0.5).abs() < 1e-15 && (b1[1] - 1.0).abs() < 1e-15 && b1[2].abs() < 1e-15 && b1[3].abs() < 1e-12);
        let h = 1e-5;
        for u in [0.1, 0.37, 0.5, 0.81] {
            for k in 0..3 {
                let fd = |f: &dyn Fn(f64) -> [f64; 4]| (f(u + h)[k] - f(u - h)[k]) / (2.0 * h);
                for (name, f) in [
                    ("G", &ramp_correction as &dyn Fn(f64) -> [f64; 4]),
                    ("B", &ramp_blend),
                    ("polydyne", &|u| RiseLaw::Polydyne.eval(u)),
                ] {
                    let exact = f(u)[k + 1];
                    assert!((fd(f) - exact).abs() < 1e-5 * exact.abs().max(1.0), "{name} k={k} u={u}");
                }
            }
        }
        // The polydyne rises monotonically.
        assert!((0..=1000).all(|i| RiseLaw::Polydyne.eval(i as f64 / 1000.0)[1] >= 0.0));
    }
}
