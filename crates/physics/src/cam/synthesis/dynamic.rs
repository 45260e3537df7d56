//! The polydyne's dynamic correction (Dudley 1948; Stoddart, "Polydyne cam design", *Machine
//! Design* 1953; Norton, *Cam Design and Manufacturing Handbook*, ch. "Polydyne cams"): the law
//! designed is the *valve's* lift `y(θ)`, and the cam is cut to the lift that makes a single
//! mass `m` driven through the train's stiffness `k` against the valve spring `k_s` follow it at
//! the design speed ω — the train's force `k (s − y) = m ÿ + k_s y` (+ the preload, carried on
//! the base circle alike) gives
//!
//! `s = y + (k_s/k) y + (m ω²/k) y''` (y'' = d²y/dθ²),
//!
//! so the cam's lift needs the valve law's derivatives to the fifth for its own to the third. The
//! pieces are then the *smooth* set ([`smooth_blend`], [`smooth_ramp_correction`]): each
//! meets its neighbours with the fourth derivative continuous as well (the plain set's fourth
//! derivative steps where the ramp blend starts and ends and where the rise leaves the ramp,
//! which the correction would turn into steps of the cam's acceleration). The polydyne itself
//! has `y'''' = 0` where it meets the ramp and is smooth at the nose.

/// The correction's coefficients.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DynamicCorrection {
    /// `m ω²/k`, rad² (the cam leads the valve by this times y'').
    pub inertia: f64,
    /// `k_s/k` (the train's static deflection under the spring).
    pub compliance: f64,
}

impl DynamicCorrection {
    /// From the train's effective mass `m` (kg), stiffness `k` (N/m), the valve spring's rate
    /// `k_s` (N/m) and the design speed ω (rad/s).
    pub fn new(mass: f64, stiffness: f64, spring_rate: f64, omega: f64) -> Self {
        DynamicCorrection { inertia: mass * omega * omega / stiffness, compliance: spring_rate / stiffness }
    }

    /// The cam's `[s, s', s'', s''']` from the valve law's `[y, …, y⁽⁵⁾]`.
    pub fn cam(&self, y: [f64; 6]) -> [f64; 4] {
        let a = 1.0 + self.compliance;
        let c = self.inertia;
        [a * y[0] + c * y[2], a * y[1] + c * y[3], a * y[2] + c * y[4], a * y[3] + c * y[5]]
    }
}

/// Value and first five derivatives of the polynomial `Σ c_i u^i`.
pub fn poly6(c: &[f64], u: f64) -> [f64; 6] {
    let mut out = [0.0; 6];
    for (k, o) in out.iter_mut().enumerate() {
        let mut sum = 0.0;
        for i in (k..c.len()).rev() {
            let falling: f64 = (0..k).map(|j| (i - j) as f64).product();
            sum = sum * u + c[i] * falling;
        }
        *o = sum;
    }
    out
}

/// The ramp's velocity blend as the 4-5-6-7 step `B = 35t⁴ − 84t⁵ + 70t⁶ − 20t⁷`
/// (`B' = B'' = B''' = 0` at both ends; `∫₀¹ B = 1/2` as the 3-4-5 blend's, so the ramp keeps its
/// angles). Returns `[∫₀ᵗ B, B, B', B'', B''', B'''']` at `t ∈ [0, 1]` (clamped).
pub fn smooth_blend(t: f64) -> [f64; 6] {
    let t = t.clamp(0.0, 1.0);
    poly6(&[0.0, 0.0, 0.0, 0.0, 0.0, 7.0, -14.0, 10.0, -2.5], t)
}

/// The ramp-velocity correction of degree 9, `G = u (1 − u)⁵ (1 + 5u + 15u² + 35u³)`:
/// `G'(0) = 1`, `G = G'' = G''' = G'''' = 0` at `u = 0` and `G … G'''' = 0` at `u = 1` (the
/// plain set's septic `u (1 − u)⁴ (1 + 4u + 10u²)` one order smoother; `(1 + 5u + 15u² + 35u³)`
/// is `(1 − u)⁻⁵` to third order, so `G = u + O(u⁵)`).
pub fn smooth_ramp_correction(u: f64) -> [f64; 6] {
    let u = u.clamp(0.0, 1.0);
    poly6(&SMOOTH_G, u)
}

/// Coefficients of `u (1 − u)⁵ (1 + 5u + 15u² + 35u³)`, ascending powers.
const SMOOTH_G: [f64; 10] = [0.0, 1.0, 0.0, 0.0, 0.0, -70.0, 224.0, -280.0, 160.0, -35.0];

/// Value and five derivatives in `x` of the polydyne `1 + Σ C_k x^k` (powers 2-6-10-14-18).
pub fn polydyne6(x: f64) -> [f64; 6] {
    let c = super::laws::polydyne_coefficients(super::laws::POLYDYNE_POWERS);
    let mut coeffs = [0.0; 19];
    coeffs[0] = 1.0;
    for (ck, p) in c.iter().zip(super::laws::POLYDYNE_POWERS) {
        coeffs[p as usize] = *ck;
    }
    poly6(&coeffs, x)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The expansions against their closed forms and boundary conditions.
    #[test]
    fn smooth_pieces() {
        for u in [0.0, 0.13, 0.5, 0.77, 1.0] {
            let g = u * (1.0f64 - u).powi(5) * (1.0 + 5.0 * u + 15.0 * u * u + 35.0 * u * u * u);
            assert!((smooth_ramp_correction(u)[0] - g).abs() < 1e-12, "{u}");
            let b = 35.0 * u.powi(4) - 84.0 * u.powi(5) + 70.0 * u.powi(6) - 20.0 * u.powi(7);
            assert!((smooth_blend(u)[1] - b).abs() < 1e-12, "{u}");
        }
        let (g0, g1) = (smooth_ramp_correction(0.0), smooth_ramp_correction(1.0));
        assert!(g0[0] == 0.0 && g0[1] == 1.0 && g0[2..5].iter().all(|v| *v == 0.0), "{g0:?}");
        assert!(g1[..5].iter().all(|v| v.abs() < 1e-9), "{g1:?}");
        let (b0, b1) = (smooth_blend(0.0), smooth_blend(1.0));
        // B'''' steps at the ends (840 at t = 0): a finite step of the cam's jerk.
        assert!(b0[..5].iter().all(|v| *v == 0.0) && b0[5] == 840.0 && (b1[0] - 0.5).abs() < 1e-12 && (b1[1] - 1.0).abs() < 1e-12, "{b1:?}");
        assert!(b1[2..5].iter().all(|v| v.abs() < 1e-9), "{b1:?}");
        // The polydyne: its fourth derivative vanishes where it meets the ramp (x = 1), and the
        // lower orders agree with `laws`.
        let p = polydyne6(1.0);
        assert!(p[..5].iter().all(|v| v.abs() < 1e-9), "{p:?}");
        let q = super::super::RiseLaw::Polydyne.eval(0.3);
        let r = polydyne6(0.7);
        assert!((q[0] - r[0]).abs() < 1e-12 && (q[1] + r[1]).abs() < 1e-12 && (q[2] - r[2]).abs() < 1e-12 && (q[3] + r[3]).abs() < 1e-9);
        // Finite differences of the fourth derivative give the fifth.
        let h = 1e-5;
        for f in [&smooth_blend as &dyn Fn(f64) -> [f64; 6], &smooth_ramp_correction, &polydyne6] {
            let fd = (f(0.4 + h)[4] - f(0.4 - h)[4]) / (2.0 * h);
            assert!((fd - f(0.4)[5]).abs() < 1e-4 * f(0.4)[5].abs().max(1.0));
        }
    }
}
