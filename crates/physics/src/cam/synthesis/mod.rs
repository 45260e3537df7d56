//! Cam synthesis: a follower lift law built from a specification — total lift, event duration,
//! opening/closing ramps (height and velocity), top dwell and the law of the main rise — as
//! piecewise polynomials in the cam angle; its peaks checked against acceleration and jerk
//! limits. The cam contour for manufacture is [`crate::cam::contour`].
//!
//! The event, from the start of the opening ramp (`φ = 0`) to the end of the closing ramp
//! (`φ = D`), centred on the nose angle, is symmetric; its rise half is (angles in rad, lift in
//! m, `V` the ramp velocity in m/rad, `H` the ramp height):
//!
//! 1. **Ramp blend** `φ ∈ [0, β_b]`, `t = φ/β_b`: the velocity rises from 0 to `V` as the 3-4-5
//!    step, `s = V β_b ∫₀ᵗB`, so acceleration and jerk start from zero (finite jerk at the base
//!    circle).
//! 2. **Constant-velocity ramp** `φ ∈ [β_b, 2β_b]`: `s = V β_b/2 + V(φ − β_b)`. With both parts
//!    of equal angle, `H = 3Vβ_b/2`, so `β_b = 2H/(3V)` and each ramp spans `β_r = 4H/(3V)`.
//! 3. **Main rise** `φ ∈ [β_r, β_r + β_m]`, `u = (φ − β_r)/β_m`:
//!    `s = H + (h − H) S(u) + V β_m G(u)` with `S` the law ([`laws::RiseLaw`]) and `G` the ramp
//!    correction ([`laws::ramp_correction`]): the rise leaves the ramp at velocity `V` with no
//!    step in acceleration (nor in jerk where `S'''(0) = 0`: 4-5-6-7, polydyne) and ends at
//!    `h` at rest (polydyne: at the nose).
//! 4. **Top dwell** of `β_d` at `s = h`; then the return mirrors the rise.
//!
//! `β_m = (D − β_d)/2 − β_r`. Without ramps the rise is `h S(u)` over `β_m = (D − β_d)/2`, so the
//! peak velocity, acceleration and jerk are the textbook coefficients `C_v h/β_m`,
//! `C_a h/β_m²`, `C_j h/β_m³` (Norton, *Cam Design and Manufacturing Handbook*; Rothbart, *Cam
//! Design Handbook*; table in [`crate::cam::lift`]).
//!
//! A specification that cannot be built (ramps longer than the event, a ramp as high as the
//! lift, a ramp so fast that the rise would fall back) is refused with a typed
//! `InvalidInput` naming the `LiftSpec` field.

pub mod dynamic;
pub mod laws;

use super::jet::Jet;
use crate::{Convergence, SolveError, Termination};
pub use dynamic::DynamicCorrection;
pub use laws::RiseLaw;
use std::f64::consts::TAU;

/// Opening and closing ramp.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Ramp {
    /// Lift at the end of the ramp, m (> 0, below the total lift).
    pub height: f64,
    /// Constant velocity of the ramp, ds/dθ in m/rad (> 0).
    pub velocity: f64,
}

/// What the lift law must do.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LiftSpec {
    /// Total lift (ramp included), m.
    pub lift: f64,
    /// Event duration from the start of the opening ramp to the end of the closing ramp, rad
    /// (≤ 2π).
    pub duration: f64,
    /// Cam angle of the middle of the event (the nose), rad.
    pub nose: f64,
    /// Dwell at full lift, rad (≥ 0; 0 for the polydyne).
    pub top_dwell: f64,
    pub ramp: Option<Ramp>,
    pub law: RiseLaw,
}

/// Optional limits on the law's peaks (geometric: per cam angle).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct LawLimits {
    /// Largest |d²s/dθ²|, m/rad².
    pub max_acceleration: Option<f64>,
    /// Largest |d³s/dθ³|, m/rad³.
    pub max_jerk: Option<f64>,
}

/// A peak of the law and the cam angle (rad) where it occurs (first occurrence on the rise).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Peak {
    pub value: f64,
    pub angle: f64,
}

/// The law's peaks over the event (per cam angle: m/rad, m/rad², m/rad³).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Peaks {
    pub max_velocity: Peak,
    pub max_acceleration: Peak,
    /// Most negative acceleration (value ≤ 0).
    pub min_acceleration: Peak,
    /// Largest |jerk|.
    pub max_abs_jerk: Peak,
}

/// One limit against the law's peak: `margin = 1 − peak/limit` (negative: exceeded).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LimitCheck {
    pub limit: f64,
    pub peak: f64,
    pub margin: f64,
}

/// A lift law synthesised from a [`LiftSpec`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SynthesisedLift {
    pub spec: LiftSpec,
    /// Angle of the ramp's velocity blend β_b, rad (0 without ramps).
    pub blend_angle: f64,
    /// Angle of each ramp β_r = 2β_b, rad.
    pub ramp_angle: f64,
    /// Angle of the main rise (and return) β_m, rad.
    pub rise_angle: f64,
    /// The polydyne's dynamic correction ([`dynamic`]): `lift` is then the cam's, the designed
    /// valve law is [`SynthesisedLift::valve`]. `None`: the cam lift is the designed law.
    pub correction: Option<DynamicCorrection>,
}

/// Samples per piece of the peak search (then refined by golden section).
const PEAK_SAMPLES: usize = 2000;

impl SynthesisedLift {
    /// Build the law, or say which field makes it impossible.
    pub fn new(spec: LiftSpec) -> Result<Self, SolveError> {
        let finite = [spec.lift, spec.duration, spec.nose, spec.top_dwell].iter().all(|x| x.is_finite());
        if !finite || spec.lift <= 0.0 {
            return Err(SolveError::invalid("LiftSpec.lift", "lift, duration, nose and top dwell must be finite, the lift > 0"));
        }
        if !(spec.duration > 0.0 && spec.duration <= TAU * (1.0 + 1e-12)) {
            return Err(SolveError::invalid("LiftSpec.duration", "the event duration must be in (0°, 360°]"));
        }
        if !(spec.top_dwell >= 0.0 && spec.top_dwell < spec.duration) {
            return Err(SolveError::invalid("LiftSpec.top_dwell", "the top dwell must be ≥ 0 and shorter than the event"));
        }
        if spec.law == RiseLaw::Polydyne && spec.top_dwell > 0.0 {
            return Err(SolveError::invalid(
                "LiftSpec.top_dwell",
                "the polydyne is a rise–return law that ends at the nose with its nose acceleration: a top dwell \
                 would put a step in acceleration there (use polynomial_4567 with a dwell)",
            ));
        }
        let (blend, ramp) = match spec.ramp {
            None => (0.0, 0.0),
            Some(r) => {
                if !(r.velocity.is_finite() && r.velocity > 0.0) {
                    return Err(SolveError::invalid("LiftSpec.ramp.velocity", "the ramp velocity must be a finite number > 0 (m/rad)"));
                }
                if !(r.height.is_finite() && r.height > 0.0 && r.height < spec.lift) {
                    return Err(SolveError::invalid(
                        "LiftSpec.ramp.height",
                        format!("the ramp height ({:e} m) must be > 0 m and below the total lift ({:e} m)", r.height, spec.lift),
                    ));
                }
                let blend = 2.0 * r.height / (3.0 * r.velocity);
                (blend, 2.0 * blend)
            }
        };
        let rise = 0.5 * (spec.duration - spec.top_dwell) - ramp;
        if !(rise > 1e-3 * spec.duration) {
            return Err(SolveError::invalid(
                "LiftSpec.ramp.velocity",
                format!(
                    "each ramp spans 4H/(3V) = {:.3}°, which leaves no main rise (at least 0.1 % of the event) in the event of {:.3}° (top dwell {:.3}°): \
                     raise the ramp velocity, lower the ramp height or lengthen the event",
                    ramp.to_degrees(),
                    spec.duration.to_degrees(),
                    spec.top_dwell.to_degrees()
                ),
            ));
        }
        let law = SynthesisedLift { spec, blend_angle: blend, ramp_angle: ramp, rise_angle: rise, correction: None };
        law.check_monotonic()?;
        Ok(law)
    }

    /// The same valve law with the polydyne's dynamic correction: the cam lift leads it by
    /// `(k_s/k) y + (m ω²/k) y''` ([`dynamic`]; the ramps take the smooth pieces). Only for the
    /// polydyne (its derivatives are continuous to the fourth; the other laws' would put steps in
    /// the cam's acceleration), and the corrected cam must still rise monotonically.
    pub fn with_correction(self, correction: DynamicCorrection) -> Result<Self, SolveError> {
        if self.spec.law != RiseLaw::Polydyne {
            return Err(SolveError::invalid("LiftSpec.law", "the dynamic correction is the polydyne's: its law must be polydyne"));
        }
        if !(correction.inertia.is_finite() && correction.inertia >= 0.0 && correction.compliance.is_finite() && correction.compliance >= 0.0) {
            return Err(SolveError::invalid("DynamicCorrection", "m ω²/k and k_s/k must be finite and ≥ 0"));
        }
        let law = SynthesisedLift { correction: Some(correction), ..self };
        law.check_monotonic()?;
        Ok(law)
    }

    /// The main rise must not fall back (a fast ramp into a short rise would make it).
    fn check_monotonic(&self) -> Result<(), SolveError> {
        let n = 4 * PEAK_SAMPLES;
        let scale = self.spec.lift / self.rise_angle;
        for i in 0..=n {
            let phi = self.ramp_angle + self.rise_angle * i as f64 / n as f64;
            let j = self.piece(2, phi);
            if j.d1 < -1e-9 * scale {
                return Err(SolveError::invalid(
                    "LiftSpec.ramp.velocity",
                    format!(
                        "with this ramp velocity the main rise would run backwards (ds/dθ = {:.4e} m/rad at {:.2}° into the event): \
                         lower the ramp velocity or lengthen the event",
                        j.d1,
                        phi.to_degrees()
                    ),
                ));
            }
        }
        Ok(())
    }

    /// Cam angle where the opening ramp starts, rad in `[0, 2π)`.
    pub fn start(&self) -> f64 {
        (self.spec.nose - 0.5 * self.spec.duration).rem_euclid(TAU)
    }

    /// Piece `k` of the rise half (0 ramp blend, 1 constant-velocity ramp, 2 main rise, 3 top
    /// dwell) at `phi` from the event start, evaluated by its own formula: the cam's lift (with
    /// the correction: from the smooth valve law's derivatives to the fifth).
    fn piece(&self, k: usize, phi: f64) -> Jet {
        match self.correction {
            None => self.plain_piece(k, phi),
            Some(c) => {
                let [s0, s1, s2, s3] = c.cam(self.smooth_piece(k, phi));
                Jet::new(s0, s1, s2, s3)
            }
        }
    }

    /// The valve law's piece to the fifth derivative from the smooth set (module [`dynamic`]).
    fn smooth_piece(&self, k: usize, phi: f64) -> [f64; 6] {
        let h = self.spec.lift;
        let (hr, v) = self.spec.ramp.map_or((0.0, 0.0), |r| (r.height, r.velocity));
        let bb = self.blend_angle;
        match k {
            0 => {
                let b = dynamic::smooth_blend(phi / bb);
                [v * bb * b[0], v * b[1], v * b[2] / bb, v * b[3] / bb.powi(2), v * b[4] / bb.powi(3), v * b[5] / bb.powi(4)]
            }
            1 => [0.5 * v * bb + v * (phi - bb), v, 0.0, 0.0, 0.0, 0.0],
            2 => {
                let bm = self.rise_angle;
                let u = ((phi - self.ramp_angle) / bm).clamp(0.0, 1.0);
                // x = 1 − u from the nose: odd derivatives change sign.
                let p = dynamic::polydyne6(1.0 - u);
                let g = dynamic::smooth_ramp_correction(u);
                let mut y = [0.0; 6];
                for n in 0..6 {
                    let sign = if n % 2 == 0 { 1.0 } else { -1.0 };
                    y[n] = ((h - hr) * sign * p[n] + v * bm * g[n]) / bm.powi(n as i32);
                }
                y[0] += hr;
                y
            }
            _ => [h, 0.0, 0.0, 0.0, 0.0, 0.0],
        }
    }

    /// The designed valve law `y(θ)` (with the correction: the smooth set's; without, the cam's
    /// own lift), m and its derivatives per cam angle.
    pub fn valve(&self, theta: f64) -> Jet {
        if self.correction.is_none() {
            return self.lift(theta);
        }
        self.mirrored(theta, &|k, phi| {
            let y = self.smooth_piece(k, phi);
            Jet::new(y[0], y[1], y[2], y[3])
        })
    }

    fn plain_piece(&self, k: usize, phi: f64) -> Jet {
        let h = self.spec.lift;
        let (hr, v) = self.spec.ramp.map_or((0.0, 0.0), |r| (r.height, r.velocity));
        let bb = self.blend_angle;
        match k {
            0 => {
                let [p, b, b1, b2] = laws::ramp_blend(phi / bb);
                Jet::new(v * bb * p, v * b, v * b1 / bb, v * b2 / (bb * bb))
            }
            1 => Jet::new(0.5 * v * bb + v * (phi - bb), v, 0.0, 0.0),
            2 => {
                let bm = self.rise_angle;
                let u = (phi - self.ramp_angle) / bm;
                let [s0, s1, s2, s3] = self.spec.law.eval(u);
                let [g0, g1, g2, g3] = laws::ramp_correction(u);
                let dh = h - hr;
                Jet::new(
                    hr + dh * s0 + v * bm * g0,
                    dh * s1 / bm + v * g1,
                    dh * s2 / (bm * bm) + v * g2 / bm,
                    dh * s3 / (bm * bm * bm) + v * g3 / (bm * bm),
                )
            }
            _ => Jet::constant(h),
        }
    }

    /// Angle range `[a, b]` of piece `k` (empty pieces have `a == b`).
    fn piece_range(&self, k: usize) -> (f64, f64) {
        let ends = [0.0, self.blend_angle, self.ramp_angle, self.ramp_angle + self.rise_angle, 0.5 * self.spec.duration];
        (ends[k], ends[k + 1])
    }

    /// The rise half at `phi ∈ [0, D/2]` from the event start.
    fn rise_half(&self, phi: f64, piece: &dyn Fn(usize, f64) -> Jet) -> Jet {
        // The main rise owns its end (the polydyne's nose acceleration at the nose).
        let k = if phi < self.blend_angle {
            0
        } else if phi < self.ramp_angle {
            1
        } else if phi <= self.ramp_angle + self.rise_angle {
            2
        } else {
            3
        };
        piece(k, phi)
    }

    /// Lift `s(θ)` with its exact derivatives with respect to the cam angle `θ` (rad).
    pub fn lift(&self, theta: f64) -> Jet {
        self.mirrored(theta, &|k, phi| self.piece(k, phi))
    }

    /// The event from its pieces: the rise half, the return its mirror image.
    fn mirrored(&self, theta: f64, piece: &dyn Fn(usize, f64) -> Jet) -> Jet {
        let phi = (theta - self.start()).rem_euclid(TAU);
        let d = self.spec.duration;
        if phi >= d {
            return Jet::constant(0.0);
        }
        if phi <= 0.5 * d {
            self.rise_half(phi, piece)
        } else {
            let j = self.rise_half(d - phi, piece);
            Jet::new(j.v, -j.d1, j.d2, -j.d3)
        }
    }

    /// Peak velocity, acceleration (both signs) and |jerk| of the law (the return mirrors the
    /// rise: same magnitudes), each piece sampled at 2000 points and the best refined by golden
    /// section to 1e-12 of the piece.
    pub fn peaks(&self) -> Peaks {
        let mut best = [Peak { value: 0.0, angle: self.start() }; 4];
        for k in 0..3 {
            let (a, b) = self.piece_range(k);
            if b <= a {
                continue;
            }
            let quantities: [&dyn Fn(Jet) -> f64; 4] = [&|j| j.d1, &|j| j.d2, &|j| -j.d2, &|j| j.d3.abs()];
            for (q, f) in quantities.iter().enumerate() {
                let g = |phi: f64| f(self.piece(k, phi));
                let (phi, value) = maximise(&g, a, b);
                if value > best[q].value {
                    best[q] = Peak { value, angle: (self.start() + phi).rem_euclid(TAU) };
                }
            }
        }
        Peaks {
            max_velocity: best[0],
            max_acceleration: best[1],
            min_acceleration: Peak { value: -best[2].value, angle: best[2].angle },
            max_abs_jerk: best[3],
        }
    }

    /// The peaks against `limits`: `(acceleration, jerk)` checks (the acceleration against the
    /// larger of the two signs).
    pub fn check(&self, limits: LawLimits) -> (Option<LimitCheck>, Option<LimitCheck>) {
        let p = self.peaks();
        let check = |limit: f64, peak: f64| LimitCheck { limit, peak, margin: 1.0 - peak / limit };
        let acc = p.max_acceleration.value.max(-p.min_acceleration.value);
        (limits.max_acceleration.map(|l| check(l, acc)), limits.max_jerk.map(|l| check(l, p.max_abs_jerk.value)))
    }

    /// The law as the `table` profile input: `n` uniform cam angles (rad) from 0 and the lift
    /// at each (m).
    pub fn table(&self, n: usize) -> (Vec<f64>, Vec<f64>) {
        (0..n).map(|i| {
            let a = TAU * i as f64 / n as f64;
            (a, self.lift(a).v)
        }).unzip()
    }
}

/// The shortest event duration whose law meets `limits` (the rest of `spec` kept), found on
/// `grid` uniform durations from the shortest that leaves a main rise up to 2π, then by bisection
/// to `tolerance` (rad) within `max_iterations`. `Ok(None)` without limits or when no duration
/// up to 2π meets them (e.g. a ramp whose blend alone exceeds the acceleration limit:
/// `2.81 V²/H`). For one law without ramps the answer is the closed form
/// `2 max(√(C_a h/A), ∛(C_j h/J)) + dwell`.
pub fn shortest_duration(
    spec: LiftSpec,
    limits: LawLimits,
    grid: usize,
    tolerance: f64,
    max_iterations: u32,
) -> Result<Option<(f64, Convergence)>, SolveError> {
    if limits.max_acceleration.is_none() && limits.max_jerk.is_none() {
        return Ok(None);
    }
    let meets = |duration: f64| -> bool {
        match SynthesisedLift::new(LiftSpec { duration, ..spec }) {
            Ok(l) => {
                let (a, j) = l.check(limits);
                a.is_none_or(|c| c.margin >= 0.0) && j.is_none_or(|c| c.margin >= 0.0)
            }
            Err(_) => false,
        }
    };
    let ramp = spec.ramp.map_or(0.0, |r| 8.0 * r.height / (3.0 * r.velocity));
    let lo = (ramp + spec.top_dwell).min(TAU);
    let grid = grid.max(2);
    let at = |k: usize| lo + (TAU - lo) * k as f64 / grid as f64;
    let Some(first) = (1..=grid).find(|&k| meets(at(k))) else { return Ok(None) };
    let (mut a, mut b) = (at(first - 1), at(first));
    let mut iterations = 0;
    while b - a > tolerance {
        if iterations >= max_iterations {
            return Err(SolveError::NotConverged {
                solver: "shortest_duration",
                iterations,
                residual: b - a,
                tolerance,
                history: Vec::new(),
            });
        }
        let m = 0.5 * (a + b);
        if meets(m) { b = m } else { a = m }
        iterations += 1;
    }
    Ok(Some((b, Convergence { iterations, residual: b - a, tolerance, termination: Termination::Converged })))
}

/// Largest value of `f` on `[a, b]`: a uniform scan, then golden section around the best node.
fn maximise(f: &dyn Fn(f64) -> f64, a: f64, b: f64) -> (f64, f64) {
    let n = PEAK_SAMPLES;
    let h = (b - a) / n as f64;
    let (mut at, mut best) = (a, f(a));
    for i in 1..=n {
        let x = if i == n { b } else { a + h * i as f64 };
        let y = f(x);
        if y > best {
            (at, best) = (x, y);
        }
    }
    let (mut lo, mut hi) = ((at - h).max(a), (at + h).min(b));
    for _ in 0..100 {
        if hi - lo <= 1e-12 * (b - a) {
            break;
        }
        let m1 = lo + (hi - lo) * 0.381_966_011_250_105;
        let m2 = hi - (hi - lo) * 0.381_966_011_250_105;
        if f(m1) < f(m2) { lo = m1 } else { hi = m2 }
    }
    let mid = 0.5 * (lo + hi);
    let y = f(mid);
    if y > best { (mid, y) } else { (at, best) }
}

#[cfg(test)]
mod tests;
