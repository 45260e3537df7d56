//! The cam contour for manufacture: the cam surface (and, for a roller or spherical follower,
//! the pitch curve its centre traces) in the cam frame against the cam angle, with the
//! curvature of both and the undercut check. Any [`CamProfile`] with any follower.
//!
//! Frame and conventions as [`super::kinematics`] (cam turning counter-clockwise, cam
//! frame `= Rot(−θ)` × fixed frame, the follower axis along `+y` at `x = e`; standard results,
//! Norton, *Cam Design and Manufacturing Handbook*, cam profile and radius of curvature):
//!
//! * flat face: the contact is at `(s', r_b + s)` in the fixed frame; the surface's radius of
//!   curvature is `ρ = r_b + s + s''` (undercut — a cusp — when `ρ ≤ 0`);
//! * curved face of radius `R_f` (roller; spherical tappet in its plane of motion), offset `e`:
//!   pitch point `C = (e, y0 + s)`, `y0 = √((r_b + R_f)² − e²)`, surface point `C − R_f N`
//!   with the unit normal `N = (e − s', y0 + s)/|A|`, `A = (y0 + s, s' − e)`; pitch curvature
//!   `κ_p = −(A × B)/|A|³`, `B = (2s' − e, s'' − y0 − s)`; surface curvature
//!   `κ_c = κ_p/(1 − R_f κ_p)`. Undercut where the pitch curve is convex with
//!   `ρ_p = 1/κ_p ≤ R_f` (`1 − R_f κ_p ≤ 0`).
//!
//! Curvatures (1/m, convex positive) rather than radii are tabulated: a straight flank has
//! zero curvature and no finite radius.

use super::jet::Jet;
use super::profile::{CamProfile, FollowerShape};
use std::f64::consts::TAU;

/// The contour at one cam angle.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ContourPoint {
    /// Cam angle, rad.
    pub theta: f64,
    /// Follower lift and its derivatives (m, m/rad^k).
    pub lift: Jet,
    /// Cam surface point in the cam frame, m.
    pub surface: (f64, f64),
    /// Follower centre (pitch curve) in the cam frame, m; `None` for a flat face.
    pub pitch: Option<(f64, f64)>,
    /// Curvature of the cam surface, 1/m (convex positive).
    pub surface_curvature: f64,
    /// Curvature of the pitch curve, 1/m (curved faces).
    pub pitch_curvature: Option<f64>,
    /// The surface has a cusp here (undercut).
    pub undercut: bool,
}

/// The whole contour with its figures.
#[derive(Debug, Clone, PartialEq)]
pub struct Contour {
    pub points: Vec<ContourPoint>,
    /// Smallest convex radius of curvature of the cam surface, m (`None` without convex points
    /// or when undercut).
    pub min_convex_radius: Option<f64>,
    /// Smallest concave radius of curvature of the cam surface, m (`None`: nowhere concave):
    /// the largest grinding wheel or cutter that can finish it.
    pub min_concave_radius: Option<f64>,
    /// Smallest convex radius of curvature of the pitch curve, m (curved faces): must exceed the
    /// follower radius.
    pub min_pitch_radius: Option<f64>,
    /// Whether any point is undercut.
    pub undercut: bool,
    /// Smallest and largest distance of the surface from the cam centre, m.
    pub min_radius: f64,
    pub max_radius: f64,
}

/// `Rot(−θ) (x, y)`.
fn to_cam(theta: f64, (x, y): (f64, f64)) -> (f64, f64) {
    let (s, c) = theta.sin_cos();
    (x * c + y * s, -x * s + y * c)
}

/// The contour at one cam angle.
pub fn contour_point(profile: &CamProfile, shape: FollowerShape, theta: f64) -> ContourPoint {
    let l = profile.lift(theta, shape);
    let rb = profile.base_radius();
    match shape {
        FollowerShape::Flat => {
            let rho = rb + l.v + l.d2;
            ContourPoint {
                theta,
                lift: l,
                surface: to_cam(theta, (l.d1, rb + l.v)),
                pitch: None,
                surface_curvature: if rho > 0.0 { 1.0 / rho } else { 0.0 },
                pitch_curvature: None,
                undercut: !(rho > 0.0),
            }
        }
        FollowerShape::Curved { radius: rf, offset: e } => {
            let y0 = ((rb + rf).powi(2) - e * e).sqrt();
            let (ax, ay) = (y0 + l.v, l.d1 - e);
            let a2 = ax * ax + ay * ay;
            let a = a2.sqrt();
            let (bx, by) = (2.0 * l.d1 - e, l.d2 - ax);
            let kappa_p = -(ax * by - ay * bx) / (a * a2);
            let shrink = 1.0 - rf * kappa_p;
            let (nx, ny) = (-ay / a, ax / a);
            let centre = (e, y0 + l.v);
            ContourPoint {
                theta,
                lift: l,
                surface: to_cam(theta, (centre.0 - rf * nx, centre.1 - rf * ny)),
                pitch: Some(to_cam(theta, centre)),
                surface_curvature: if shrink > 0.0 { kappa_p / shrink } else { 0.0 },
                pitch_curvature: Some(kappa_p),
                undercut: !(shrink > 0.0),
            }
        }
    }
}

/// The contour at `n` uniform cam angles from 0 (`n ≥ 4`).
pub fn contour(profile: &CamProfile, shape: FollowerShape, n: usize) -> Contour {
    let points: Vec<ContourPoint> = (0..n.max(4)).map(|i| contour_point(profile, shape, TAU * i as f64 / n.max(4) as f64)).collect();
    let max_k = points.iter().map(|p| p.surface_curvature).fold(0.0, f64::max);
    let min_k = points.iter().map(|p| p.surface_curvature).fold(0.0, f64::min);
    let max_kp = points.iter().filter_map(|p| p.pitch_curvature).fold(0.0, f64::max);
    let undercut = points.iter().any(|p| p.undercut);
    let radius = |p: &ContourPoint| p.surface.0.hypot(p.surface.1);
    Contour {
        min_convex_radius: (max_k > 0.0 && !undercut).then(|| 1.0 / max_k),
        min_concave_radius: (min_k < 0.0).then(|| -1.0 / min_k),
        min_pitch_radius: (max_kp > 0.0).then(|| 1.0 / max_kp),
        undercut,
        min_radius: points.iter().map(radius).fold(f64::INFINITY, f64::min),
        max_radius: points.iter().map(radius).fold(0.0, f64::max),
        points,
    }
}

/// The signed margin against undercut at `n` uniform cam angles, m: the smallest
/// `r_b + s + s''` (flat face) or `ρ_p − R_f` over the convex pitch points (curved face of
/// radius `R_f`). Where the cam does not undercut it is the smallest convex radius of curvature
/// of the cam surface (`ρ_c = ρ_p − R_f`); at an undercut it is zero or negative, and how
/// negative says how far the design is from a manufacturable cam (the same relations as
/// [`contour_point`]). Infinite when no point is convex (not reached by a closed cam).
pub fn undercut_margin(profile: &CamProfile, shape: FollowerShape, n: usize) -> f64 {
    let n = n.max(4);
    (0..n)
        .map(|i| {
            let p = contour_point(profile, shape, TAU * i as f64 / n as f64);
            match (shape, p.pitch_curvature) {
                (FollowerShape::Curved { radius, .. }, Some(k)) if k > 0.0 => 1.0 / k - radius,
                (FollowerShape::Curved { .. }, _) => f64::INFINITY,
                (FollowerShape::Flat, _) => profile.base_radius() + p.lift.v + p.lift.d2,
            }
        })
        .fold(f64::INFINITY, f64::min)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::cam::synthesis::{LiftSpec, Ramp, RiseLaw, SynthesisedLift};

    fn cam(base: f64) -> CamProfile {
        cam_of(base, 250.0)
    }

    fn cam_of(base: f64, duration_deg: f64) -> CamProfile {
        let law = SynthesisedLift::new(LiftSpec {
            lift: 0.009,
            duration: duration_deg.to_radians(),
            nose: std::f64::consts::PI,
            top_dwell: 0.0,
            ramp: Some(Ramp { height: 2.5e-4, velocity: 0.015e-3 * 180.0 / std::f64::consts::PI }),
            law: RiseLaw::Polydyne,
        })
        .unwrap();
        CamProfile::Synthesised { base_radius: base, law }
    }

    /// Curvature of a plane curve from central differences of its points.
    fn fd_curvature(f: &dyn Fn(f64) -> (f64, f64), t: f64) -> f64 {
        let h = 1e-4;
        let (p0, p1, p2) = (f(t - h), f(t), f(t + h));
        let d1 = ((p2.0 - p0.0) / (2.0 * h), (p2.1 - p0.1) / (2.0 * h));
        let d2 = ((p2.0 - 2.0 * p1.0 + p0.0) / (h * h), (p2.1 - 2.0 * p1.1 + p0.1) / (h * h));
        // Counter-clockwise traversal in θ is clockwise in the cam frame: a convex cam turns right.
        -(d1.0 * d2.1 - d1.1 * d2.0) / (d1.0 * d1.0 + d1.1 * d1.1).powf(1.5)
    }

    #[test]
    fn flat_face_contour_has_the_stated_curvature_and_support() {
        let c = cam(0.016);
        let shape = FollowerShape::Flat;
        for theta in [0.3, 1.7, 2.6, 3.1, 3.6, 4.4] {
            let p = contour_point(&c, shape, theta);
            let fd = fd_curvature(&|t| contour_point(&c, shape, t).surface, theta);
            assert!((fd / p.surface_curvature - 1.0).abs() < 1e-4, "θ {theta}: {fd} vs {}", p.surface_curvature);
            // The support function along n(θ) = (sin θ, cos θ) is r_b + s.
            let h = p.surface.0 * theta.sin() + p.surface.1 * theta.cos();
            assert!((h - 0.016 - p.lift.v).abs() < 1e-15);
        }
    }

    #[test]
    fn roller_contour_is_offset_from_the_pitch_curve() {
        let c = cam(0.016);
        for shape in [FollowerShape::Curved { radius: 0.01, offset: 0.0 }, FollowerShape::Curved { radius: 0.008, offset: 0.003 }] {
            let FollowerShape::Curved { radius, .. } = shape else { unreachable!() };
            for theta in [0.3, 1.7, 2.6, 3.1, 3.6, 4.4] {
                let p = contour_point(&c, shape, theta);
                let pitch = p.pitch.unwrap();
                let d = (pitch.0 - p.surface.0).hypot(pitch.1 - p.surface.1);
                assert!((d - radius).abs() < 1e-15, "{d}");
                let kp = fd_curvature(&|t| contour_point(&c, shape, t).pitch.unwrap(), theta);
                assert!((kp / p.pitch_curvature.unwrap() - 1.0).abs() < 1e-4, "pitch θ {theta}: {kp} vs {:?}", p.pitch_curvature);
                let ks = fd_curvature(&|t| contour_point(&c, shape, t).surface, theta);
                assert!((ks - p.surface_curvature).abs() < 1e-4 * p.surface_curvature.abs().max(1.0), "surface θ {theta}: {ks} vs {}", p.surface_curvature);
            }
        }
    }

    #[test]
    fn base_circle_is_round_and_undercut_is_flagged() {
        let c = cam(0.016);
        let all = contour(&c, FollowerShape::Flat, 720);
        assert!((all.min_radius - 0.016).abs() < 1e-12, "{}", all.min_radius);
        assert!(!all.undercut && all.min_convex_radius.is_some());
        // A large roller on a small, short cam: the nose's pitch radius is below the roller
        // radius (ρ_p ≈ r²/(r − s'') at the nose, r = r_b + R_f + h: 14.5 mm < 20 mm).
        let small = cam_of(0.004, 160.0);
        let r = contour(&small, FollowerShape::Curved { radius: 0.02, offset: 0.0 }, 720);
        assert!(r.undercut && r.min_pitch_radius.unwrap() < 0.02, "{:?}", r.min_pitch_radius);
    }

    #[test]
    fn undercut_margin_is_the_radius_of_curvature_or_negative() {
        // Not undercut: the margin is the smallest convex radius of the surface (to the
        // sampling: both from the same 720 points).
        let c = cam(0.016);
        for shape in [FollowerShape::Flat, FollowerShape::Curved { radius: 0.01, offset: 0.0 }] {
            let m = undercut_margin(&c, shape, 720);
            let r = contour(&c, shape, 720).min_convex_radius.unwrap();
            assert!((m / r - 1.0).abs() < 1e-9, "{m} vs {r}");
        }
        // Undercut (the case above): negative, ρ_p − R_f.
        let small = cam_of(0.004, 160.0);
        let shape = FollowerShape::Curved { radius: 0.02, offset: 0.0 };
        let m = undercut_margin(&small, shape, 720);
        let r = contour(&small, shape, 720);
        assert!(m < 0.0 && (m - (r.min_pitch_radius.unwrap() - 0.02)).abs() < 1e-12, "{m}");
    }
}
