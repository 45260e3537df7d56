//! Film geometry of a journal bearing: aligned film, shaft misalignment and axial edge profiles.
//!
//! Frame (all angles in radians here): `θ` is measured around the bearing from the *unloaded*
//! side (the point opposite the direction of the applied load), positive in the direction of
//! journal rotation. The journal centre in the cross-section at axial position `Z = z/L` is
//! displaced from the bearing centre by `c·(X(Z), Y(Z))`, where `X` is the component along the
//! applied load ("vertical") and `Y` the component perpendicular to it, positive 90° ahead in
//! the direction of rotation ("horizontal"). Then
//! `H = h/c = 1 + X cos θ + Y sin θ + Γ(Z)` — for an aligned journal `X = ε cos β`,
//! `Y = ε sin β`, which is seed 002 eq. (3) `H = 1 + ε cos(θ − β)` with `β` the attitude angle
//! (maximum film at `θ = β`, minimum film at `θ = β + π`).

use serde::{Deserialize, Serialize};

/// Shaft misalignment (seed 002 eq. 10–11), dimensionless deviations `Δ = δ/c` at the bearing
/// edges. The journal axis is straight and tilted about the mid-plane: the journal centre at the
/// edge `Z = 0` is displaced from the mid-plane centre by `(−vertical, +horizontal)` and at
/// `Z = 1` by `(+vertical, −horizontal)`, linearly in between (`(1 − 2Z)` law of eq. 10):
/// eq. (11) read literally with its side signs, `X(Z) = X_m − Δv0 (1 − 2Z)`,
/// `Y(Z) = Y_m + Δh0 (1 − 2Z)`.
///
/// Why this reading: of the straight-tilt readings (each sign of each component, any tilt
/// direction) it is the only one that keeps the film open at Δv0 = Δh0 = 0.56 under the aligned
/// ε = 0.6 load of seed 002, and with it the paper's L9 array picks the paper's best levels
/// (n = 2, ξ = 0.4, ψ = 0.2). It does not reproduce the paper's misaligned Table 2 values
/// (here P0 = 1.396, H0 = 0.0403 against 0.8735, 0.0820); no reading tried did (a scan of tilt
/// directions and magnitudes, a bent-shaft |1 − 2Z| reading, a balance of the load magnitude
/// only), see the note in BENCHMARKS.md.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
pub struct Misalignment {
    /// `Δv0`: deviation along the load line at the edges, per unit radial clearance.
    pub vertical: f64,
    /// `Δh0`: deviation perpendicular to the load line at the edges, per unit radial clearance.
    pub horizontal: f64,
}

impl Misalignment {
    /// Offset `(dX, dY)` of the journal centre at `Z` relative to the mid-plane centre.
    #[inline]
    pub fn offset(&self, z: f64) -> (f64, f64) {
        let s = 1.0 - 2.0 * z; // seed 002 eq. (10)-(11): |1 − 2Z| with the side signs of eq. (11)
        (-self.vertical * s, self.horizontal * s)
    }
    pub fn is_zero(&self) -> bool {
        self.vertical == 0.0 && self.horizontal == 0.0
    }
}

/// Axial edge profile of the bearing bore (seed 002 eq. 13–15): the bore is opened by
/// `Γ(Z) = ξ (1 − Z/ψ)^n` for `Z ≤ ψ`, `ξ ((Z − 1 + ψ)/ψ)^n` for `Z ≥ 1 − ψ`, 0 in between.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Profile {
    /// `n`: 1 linear, 2 parabolic, 3 cubic.
    pub order: u32,
    /// `ξ = m_r/c`: edge opening per unit radial clearance (≥ 0).
    pub height: f64,
    /// `ψ = m_l/L`: fraction of the length modified at each edge, in (0, 0.5].
    pub length_fraction: f64,
}

impl Profile {
    /// `Γ(Z)`, the film added by the profile at `Z` (seed 002 eq. 13–15).
    #[inline]
    pub fn opening(&self, z: f64) -> f64 {
        let psi = self.length_fraction;
        let t = if z <= psi {
            1.0 - z / psi
        } else if z >= 1.0 - psi {
            (z - 1.0 + psi) / psi
        } else {
            return 0.0;
        };
        let t = t.clamp(0.0, 1.0);
        self.height * t.powi(self.order as i32)
    }
}

/// The film of one journal position: mid-plane centre `(X_m, Y_m)` plus misalignment and profile.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Film {
    pub x_mid: f64,
    pub y_mid: f64,
    pub misalignment: Misalignment,
    pub profile: Option<Profile>,
}

/// Per-axial-position film data: `H = 1 + gamma + x cos θ + y sin θ`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Row {
    pub x: f64,
    pub y: f64,
    pub gamma: f64,
}

impl Film {
    pub fn aligned(eccentricity: f64, attitude: f64) -> Film {
        Film {
            x_mid: eccentricity * attitude.cos(),
            y_mid: eccentricity * attitude.sin(),
            misalignment: Misalignment::default(),
            profile: None,
        }
    }

    /// Film coefficients of the cross-section at `Z` (seed 002 eq. 3, 10, 11, 13–15).
    #[inline]
    pub fn row(&self, z: f64) -> Row {
        let (dx, dy) = self.misalignment.offset(z);
        Row {
            x: self.x_mid + dx,
            y: self.y_mid + dy,
            gamma: self.profile.map_or(0.0, |p| p.opening(z)),
        }
    }

    /// `H(θ, Z)`.
    #[inline]
    pub fn h(&self, theta: f64, z: f64) -> f64 {
        let r = self.row(z);
        1.0 + r.gamma + r.x * theta.cos() + r.y * theta.sin()
    }

    /// Mid-plane eccentricity ratio.
    pub fn eccentricity(&self) -> f64 {
        self.x_mid.hypot(self.y_mid)
    }

    /// Mid-plane attitude angle in (−π, π], from the load line in the direction of rotation.
    pub fn attitude(&self) -> f64 {
        self.y_mid.atan2(self.x_mid)
    }

    /// Angle `θ` of the largest film in the cross-section at `Z` (the aligned max-film line is
    /// `θ = β`). For a film without eccentricity the answer is 0.
    pub fn max_film_angle(&self, z: f64) -> f64 {
        let r = self.row(z);
        if r.x == 0.0 && r.y == 0.0 { 0.0 } else { r.y.atan2(r.x) }
    }

    /// Smallest film `H` over the cross-section at `Z` and its angle.
    #[inline]
    pub fn min_in_row(&self, z: f64) -> (f64, f64) {
        let r = self.row(z);
        let e = r.x.hypot(r.y);
        let theta = if e == 0.0 { std::f64::consts::PI } else { r.y.atan2(r.x) + std::f64::consts::PI };
        (1.0 + r.gamma - e, wrap_angle(theta))
    }

    /// Exact minimum of `H` over the whole bearing: `(H_min, θ, Z)`. The film is analytic in θ
    /// (minimum in closed form per cross-section); in Z it is piecewise smooth, so it is sampled
    /// densely and refined by golden-section search.
    pub fn min_film(&self) -> (f64, f64, f64) {
        const SAMPLES: usize = 512;
        let f = |z: f64| self.min_in_row(z).0;
        let mut best_k = 0;
        let mut best = f64::INFINITY;
        for k in 0..=SAMPLES {
            let v = f(k as f64 / SAMPLES as f64);
            if v < best {
                best = v;
                best_k = k;
            }
        }
        let lo = (best_k.max(1) - 1) as f64 / SAMPLES as f64;
        let hi = (best_k + 1).min(SAMPLES) as f64 / SAMPLES as f64;
        let (mut a, mut b) = (lo, hi);
        let g = 0.5 * (5f64.sqrt() - 1.0);
        let mut c = b - g * (b - a);
        let mut d = a + g * (b - a);
        let (mut fc, mut fd) = (f(c), f(d));
        for _ in 0..60 {
            if fc < fd {
                b = d;
                d = c;
                fd = fc;
                c = b - g * (b - a);
                fc = f(c);
            } else {
                a = c;
                c = d;
                fc = fd;
                d = a + g * (b - a);
                fd = f(d);
            }
        }
        let zr = 0.5 * (a + b);
        let mut cands = [(best, best_k as f64 / SAMPLES as f64), (f(zr), zr), (f(0.0), 0.0), (f(1.0), 1.0)];
        cands.sort_by(|p, q| p.0.total_cmp(&q.0));
        let (h, z) = cands[0];
        (h, self.min_in_row(z).1, z)
    }
}

/// Angle wrapped to [0, 2π).
#[inline]
pub fn wrap_angle(a: f64) -> f64 {
    let t = std::f64::consts::TAU;
    let r = a.rem_euclid(t);
    if r >= t { 0.0 } else { r }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn profile_matches_seed_002_boundary_conditions() {
        for order in 1..=3 {
            let p = Profile { order, height: 0.4, length_fraction: 0.2 };
            assert!((p.opening(0.0) - 0.4).abs() < 1e-15);
            assert!((p.opening(1.0) - 0.4).abs() < 1e-15);
            assert_eq!(p.opening(0.2), 0.0);
            assert!(p.opening(0.8).abs() < 1e-15);
            assert_eq!(p.opening(0.5), 0.0);
            // eq. (13)-(15) halfway into the modified zone
            let expect = 0.4 * 0.5f64.powi(order as i32);
            assert!((p.opening(0.1) - expect).abs() < 1e-15);
            assert!((p.opening(0.9) - expect).abs() < 1e-15);
        }
    }

    #[test]
    fn aligned_min_film_is_one_minus_eps() {
        let f = Film::aligned(0.6, 0.9);
        let (h, theta, _) = f.min_film();
        assert!((h - 0.4).abs() < 1e-14);
        assert!((theta - (0.9 + std::f64::consts::PI)).abs() < 1e-12);
        assert!((f.h(theta, 0.3) - 0.4).abs() < 1e-14);
    }

    #[test]
    fn misaligned_min_film_at_an_edge() {
        let f = Film {
            x_mid: 0.3,
            y_mid: 0.4,
            misalignment: Misalignment { vertical: 0.2, horizontal: 0.1 },
            profile: None,
        };
        // Z = 1: (0.5, 0.3); Z = 0: (0.1, 0.5)
        let (h, _, z) = f.min_film();
        assert!((h - (1.0 - 0.5f64.hypot(0.3))).abs() < 1e-12, "{h}");
        assert!((z - 1.0).abs() < 1e-12);
    }
}
