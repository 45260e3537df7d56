//! Lift laws and rise–dwell–return–dwell programs.
//!
//! A lift law is a normalised rise `S(u)` on `u ∈ [0, 1]` with `S(0) = 0`, `S(1) = 1`; a program
//! scales it to a lift `h` over a rise angle `β`: `s(θ) = h S((θ − θ0)/β)`, so that
//! `ds/dθ = h S'(u)/β`, `d²s/dθ² = h S''(u)/β²`, `d³s/dθ³ = h S'''(u)/β³` — exact.
//! Peak coefficients (`max |S^(k)|`) are the textbook values checked by the tests:
//!
//! | law | `S(u)` | `C_v` | `C_a` | `C_j` |
//! | --- | --- | --- | --- | --- |
//! | cycloidal | `u − sin(2πu)/(2π)` | 2 | 2π | 4π² |
//! | 3-4-5 polynomial | `10u³ − 15u⁴ + 6u⁵` | 15/8 | 10/√3 | 60 |
//! | 4-5-6-7 polynomial | `35u⁴ − 84u⁵ + 70u⁶ − 20u⁷` | 35/16 | 7.513 | 52.5 |
//! | simple harmonic | `(1 − cos πu)/2` | π/2 | π²/2 | π³/2 (acceleration jumps at the ends) |

use super::jet::Jet;
use serde::{Deserialize, Serialize};
use std::f64::consts::{PI, TAU};

/// A normalised rise law.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum LiftLaw {
    /// Cycloidal: continuous acceleration, zero at both ends (seed 003's cam).
    Cycloidal,
    /// 3-4-5 polynomial: continuous acceleration, finite jerk at the ends.
    #[serde(rename = "polynomial_345")]
    Polynomial345,
    /// 4-5-6-7 polynomial: continuous jerk, zero at both ends.
    #[serde(rename = "polynomial_4567")]
    Polynomial4567,
    /// Simple harmonic: acceleration jumps at both ends (infinite jerk there).
    SimpleHarmonic,
}

impl LiftLaw {
    /// `[S, S', S'', S''']` at `u` (clamped to `[0, 1]`).
    pub fn eval(self, u: f64) -> [f64; 4] {
        let u = u.clamp(0.0, 1.0);
        match self {
            LiftLaw::Cycloidal => {
                let (s, c) = (TAU * u).sin_cos();
                [u - s / TAU, 1.0 - c, TAU * s, TAU * TAU * c]
            }
            LiftLaw::Polynomial345 => {
                let (u2, u3) = (u * u, u * u * u);
                [
                    u3 * (10.0 - 15.0 * u + 6.0 * u2),
                    u2 * (30.0 - 60.0 * u + 30.0 * u2),
                    u * (60.0 - 180.0 * u + 120.0 * u2),
                    60.0 - 360.0 * u + 360.0 * u2,
                ]
            }
            LiftLaw::Polynomial4567 => {
                let (u2, u3) = (u * u, u * u * u);
                [
                    u2 * u2 * (35.0 - 84.0 * u + 70.0 * u2 - 20.0 * u3),
                    u3 * (140.0 - 420.0 * u + 420.0 * u2 - 140.0 * u3),
                    u2 * (420.0 - 1680.0 * u + 2100.0 * u2 - 840.0 * u3),
                    u * (840.0 - 5040.0 * u + 8400.0 * u2 - 4200.0 * u3),
                ]
            }
            LiftLaw::SimpleHarmonic => {
                let (s, c) = (PI * u).sin_cos();
                [0.5 * (1.0 - c), 0.5 * PI * s, 0.5 * PI * PI * c, -0.5 * PI * PI * PI * s]
            }
        }
    }
}

/// Rise – top dwell – return – base dwell, one revolution.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LiftProgram {
    /// Total lift `h`, m.
    pub lift: f64,
    /// Cam angle at which the rise starts, rad.
    pub rise_start: f64,
    /// Rise angle β_r, rad (> 0).
    pub rise: f64,
    /// Dwell at full lift, rad (≥ 0).
    pub top_dwell: f64,
    /// Return angle β_d, rad (> 0). `rise + top_dwell + return ≤ 2π`; the rest is the base dwell.
    pub fall: f64,
    pub rise_law: LiftLaw,
    pub return_law: LiftLaw,
}

impl LiftProgram {
    /// Lift `s(θ)` with its exact derivatives with respect to the cam angle `θ` (rad).
    pub fn lift(&self, theta: f64) -> Jet {
        let phi = (theta - self.rise_start).rem_euclid(TAU);
        let h = self.lift;
        if phi < self.rise {
            let [s0, s1, s2, s3] = self.rise_law.eval(phi / self.rise);
            let b = self.rise;
            Jet::new(h * s0, h * s1 / b, h * s2 / (b * b), h * s3 / (b * b * b))
        } else if phi < self.rise + self.top_dwell {
            Jet::constant(h)
        } else if phi < self.rise + self.top_dwell + self.fall {
            let u = (phi - self.rise - self.top_dwell) / self.fall;
            let [s0, s1, s2, s3] = self.return_law.eval(u);
            let b = self.fall;
            Jet::new(h * (1.0 - s0), -h * s1 / b, -h * s2 / (b * b), -h * s3 / (b * b * b))
        } else {
            Jet::constant(0.0)
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Maximum of |S^(k)| over a fine grid refined by golden section around the best node.
    fn peak(law: LiftLaw, k: usize) -> f64 {
        let n = 20_000;
        let f = |u: f64| law.eval(u)[k].abs();
        let (mut best_u, mut best) = (0.0, f(0.0));
        for i in 0..=n {
            let u = i as f64 / n as f64;
            if f(u) > best {
                best = f(u);
                best_u = u;
            }
        }
        // Refine.
        let (mut lo, mut hi) = ((best_u - 1.0 / n as f64).max(0.0), (best_u + 1.0 / n as f64).min(1.0));
        for _ in 0..100 {
            let m1 = lo + (hi - lo) / 3.0;
            let m2 = hi - (hi - lo) / 3.0;
            if f(m1) < f(m2) { lo = m1 } else { hi = m2 }
        }
        best.max(f(0.5 * (lo + hi)))
    }

    #[test]
    fn peak_coefficients_are_the_textbook_values() {
        let cases = [
            (LiftLaw::Cycloidal, [2.0, TAU, TAU * TAU]),
            (LiftLaw::Polynomial345, [15.0 / 8.0, 10.0 / 3f64.sqrt(), 60.0]),
            // 4-5-6-7: C_a at u* = (5 − √5)/10 (root of S''' = 0), evaluated from the polynomial
            // written out independently below; C_j = |S'''(1/2)| = 52.5.
            (LiftLaw::Polynomial4567, [35.0 / 16.0, c_a_4567(), 52.5]),
            (LiftLaw::SimpleHarmonic, [PI / 2.0, PI * PI / 2.0, PI * PI * PI / 2.0]),
        ];
        for (law, [cv, ca, cj]) in cases {
            assert!((peak(law, 1) / cv - 1.0).abs() < 1e-9, "{law:?} C_v {}", peak(law, 1));
            assert!((peak(law, 2) / ca - 1.0).abs() < 1e-9, "{law:?} C_a {}", peak(law, 2));
            assert!((peak(law, 3) / cj - 1.0).abs() < 1e-9, "{law:?} C_j {}", peak(law, 3));
        }
        assert!((c_a_4567() - 7.5132).abs() < 1e-4, "{}", c_a_4567());
    }

    fn c_a_4567() -> f64 {
        let u: f64 = (5.0 - 5f64.sqrt()) / 10.0;
        420.0 * u.powi(2) - 1680.0 * u.powi(3) + 2100.0 * u.powi(4) - 840.0 * u.powi(5)
    }

    #[test]
    fn laws_are_normalised_and_derivatives_consistent() {
        for law in [LiftLaw::Cycloidal, LiftLaw::Polynomial345, LiftLaw::Polynomial4567, LiftLaw::SimpleHarmonic] {
            let s0 = law.eval(0.0);
            let s1 = law.eval(1.0);
            assert!(s0[0].abs() < 1e-15 && (s1[0] - 1.0).abs() < 1e-15);
            assert!(s0[1].abs() < 1e-12 && s1[1].abs() < 1e-12, "{law:?} velocity at ends");
            // Derivative k+1 is the derivative of k (central differences).
            let h = 1e-5;
            for u in [0.13, 0.5, 0.77] {
                for k in 0..3 {
                    let fd = (law.eval(u + h)[k] - law.eval(u - h)[k]) / (2.0 * h);
                    let exact = law.eval(u)[k + 1];
                    assert!((fd - exact).abs() < 1e-5 * exact.abs().max(1.0), "{law:?} k={k} u={u}");
                }
            }
        }
    }

    #[test]
    fn program_is_periodic_and_continuous() {
        let p = LiftProgram {
            lift: 0.008,
            rise_start: 1.0,
            rise: 1.2,
            top_dwell: 0.3,
            fall: 1.4,
            rise_law: LiftLaw::Polynomial345,
            return_law: LiftLaw::Cycloidal,
        };
        for th in [1.0, 2.2, 2.5, 3.9] {
            let a = p.lift(th - 1e-9);
            let b = p.lift(th + 1e-9);
            assert!((a.v - b.v).abs() < 1e-10 && (a.d1 - b.d1).abs() < 1e-7, "at {th}");
        }
        assert_eq!(p.lift(0.5).v, p.lift(0.5 + TAU).v);
        assert!((p.lift(2.2 + 0.1).v - 0.008).abs() < 1e-15);
    }
}
