//! Follower kinematics per cam angle: lift, velocity, acceleration, jerk, pressure angle, cam
//! radius of curvature, reduced radius, and the surface velocities that drive the lubricant film.
//!
//! Geometry (cam centre at the origin, follower axis vertical at `x = e`, cam turning
//! counter-clockwise; clockwise running mirrors the offset). For a curved follower face of radius
//! `R_f` (roller, or spherical tappet in its plane of motion) the face centre is
//! `C = (e, y0 + s)`, `y0 = sqrt((r_b + R_f)² − e²)`. Its path in the cam frame (the pitch curve)
//! has, with `A = (y0 + s, s' − e)` and `A' = (s', s'')` (primes: d/dθ),
//!
//! * contact normal `N = (e − s', y0 + s)/|A|`, pressure angle `φ = atan2(s' − e, y0 + s)`;
//! * pitch curvature `κ_p = 1/ρ_p = −(A × B)/|A|³` with `B = A' − J A` (J: rotation by +90°);
//! * cam radius of curvature `ρ_c = ρ_p − R_f` (convex positive), reduced radius
//!   `1/R = 1/ρ_c + 1/R_f = 1/(R_f (1 − R_f κ_p))`;
//! * surface velocities relative to the moving contact point, positive in the direction the cam
//!   surface moves on the base circle: cam `u_c = ω |A| ρ_c/ρ_p`, follower
//!   `u_f = R_f (Ω + ψ̇)` with `ψ̇ = ω (A × A')/|A|²` the turning rate of the contact normal and
//!   `Ω` the roller's own angular velocity (0 for a non-rotating face).
//!
//! For the flat face (normal fixed along the axis): `ρ_c = r_b + s + s''`, `u_c = ω ρ_c`,
//! `u_f = ω s''`, contact at `x = s'` (standard results, e.g. Norton, *Cam Design and
//! Manufacturing Handbook*, ch. 7; seed 003 §6 describes the same entraining velocity).
//! Entrainment `u_e = (u_c + u_f)/2`, sliding `u_s = u_c − u_f`.
//!
//! A cam whose profile would need a cusp (flat face: `ρ_c ≤ 0`; curved face: `0 < ρ_p ≤ R_f`) is
//! refused with `cam_undercut`.

use super::jet::Jet;
use super::profile::{CamProfile, FollowerShape};
use crate::SolveError;
use std::f64::consts::TAU;

/// Camshaft speed at one cam angle.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CamSpeed {
    /// Angular velocity ω, rad/s (≥ 0).
    pub omega: f64,
    /// Angular acceleration, rad/s².
    pub alpha: f64,
    /// Time since the cycle began, s.
    pub time: f64,
}

/// How the camshaft speed evolves over the simulated revolution.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum SpeedSchedule {
    /// Constant angular velocity ω (rad/s).
    Steady { omega: f64 },
    /// From rest at θ = 0 with constant angular acceleration, reaching `omega` at cam angle
    /// `rated_angle` (rad), constant afterwards (seed 000 §4.2).
    Startup { omega: f64, rated_angle: f64 },
}

impl SpeedSchedule {
    /// Rated angular velocity, rad/s.
    pub fn rated_omega(&self) -> f64 {
        match *self {
            SpeedSchedule::Steady { omega } | SpeedSchedule::Startup { omega, .. } => omega,
        }
    }

    /// Speed at cam angle `theta` (rad, measured from the start of the run).
    pub fn at(&self, theta: f64) -> CamSpeed {
        match *self {
            SpeedSchedule::Steady { omega } => CamSpeed { omega, alpha: 0.0, time: theta / omega },
            SpeedSchedule::Startup { omega, rated_angle } => {
                let alpha = omega * omega / (2.0 * rated_angle);
                if theta <= rated_angle {
                    let w = (2.0 * alpha * theta.max(0.0)).sqrt();
                    CamSpeed { omega: w, alpha, time: w / alpha }
                } else {
                    CamSpeed { omega, alpha: 0.0, time: omega / alpha + (theta - rated_angle) / omega }
                }
            }
        }
    }
}

/// The follower, as far as the kinematics are concerned.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FollowerGeometry {
    pub shape: FollowerShape,
    /// `true` when the cam runs clockwise (the offset is mirrored).
    pub clockwise: bool,
}

/// Kinematic state at one cam angle. Velocities are tangential components relative to the
/// moving contact point (see the module docs for signs).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct KinematicState {
    /// Cam angle, rad.
    pub theta: f64,
    pub speed: CamSpeed,
    /// `s, ds/dθ, d²s/dθ², d³s/dθ³` (m, m/rad^k).
    pub lift: Jet,
    /// Follower velocity, m/s.
    pub velocity: f64,
    /// Follower acceleration, m/s².
    pub acceleration: f64,
    /// Follower jerk, m/s³.
    pub jerk: f64,
    /// Pressure angle, rad (0 for a flat face).
    pub pressure_angle: f64,
    /// Cam curvature at the contact, 1/m (convex positive, concave negative, 0 on a straight
    /// flank): the radius of curvature is its inverse.
    pub cam_curvature: f64,
    /// Reduced radius of curvature in the plane of motion, m.
    pub reduced_radius: f64,
    /// Cam surface velocity, m/s.
    pub cam_surface_velocity: f64,
    /// Follower surface velocity without its own rotation, m/s: the full value for a flat or
    /// spherical face; a roller adds `R_f Ω`.
    pub follower_surface_base: f64,
    /// Contact point position along the follower face measured from the follower axis, m (flat
    /// face); for curved faces the horizontal position of the contact point relative to the axis.
    pub contact_offset: f64,
    /// `K × N`: moment arm of the normal contact force about the cam centre, m. The camshaft
    /// torque of a normal force F is `F · normal_arm`.
    pub normal_arm: f64,
    /// Moment arm of the tangential (friction) force on the cam, m: the camshaft torque of a
    /// traction `F_t` (positive when it resists the cam's sliding) is `F_t · friction_arm`.
    pub friction_arm: f64,
    /// `cos φ`: axial component of the unit contact normal.
    pub axial_cosine: f64,
}

impl KinematicState {
    /// Entrainment velocity for a follower surface velocity `u_f`.
    pub fn entrainment(&self, follower_surface_velocity: f64) -> f64 {
        0.5 * (self.cam_surface_velocity + follower_surface_velocity)
    }
}

/// Kinematics at cam angle `theta` (rad, from the start of the run) with camshaft speed `speed`.
pub fn kinematics(
    profile: &CamProfile,
    follower: &FollowerGeometry,
    theta: f64,
    speed: CamSpeed,
) -> Result<KinematicState, SolveError> {
    let shape = match follower.shape {
        FollowerShape::Curved { radius, offset } if follower.clockwise => {
            FollowerShape::Curved { radius, offset: -offset }
        }
        s => s,
    };
    let lift = profile.lift(theta, shape);
    if !lift.is_finite() {
        return Err(SolveError::NonFinite { quantity: format!("follower lift at {:.3}°", theta.to_degrees()) });
    }
    let (w, al) = (speed.omega, speed.alpha);
    let velocity = lift.d1 * w;
    let acceleration = lift.d2 * w * w + lift.d1 * al;
    let jerk = lift.d3 * w * w * w + 3.0 * lift.d2 * w * al;
    let rb = profile.base_radius();
    let deg = theta.rem_euclid(TAU).to_degrees();
    match shape {
        FollowerShape::Flat => {
            let rho = rb + lift.v + lift.d2;
            if !(rho > 0.0) {
                return Err(SolveError::physical(
                    crate::PhysicalFailure::CamUndercut,
                    format!(
                        "the cam undercuts at {deg:.2}°: a flat follower needs r_b + s + s'' > 0 but it is \
                         {:.4} mm (increase the base radius or lengthen the rise/return angles)",
                        rho * 1e3
                    ),
                ));
            }
            let y = rb + lift.v;
            Ok(KinematicState {
                theta,
                speed,
                lift,
                velocity,
                acceleration,
                jerk,
                pressure_angle: 0.0,
                cam_curvature: 1.0 / rho,
                reduced_radius: rho,
                cam_surface_velocity: w * rho,
                follower_surface_base: w * lift.d2,
                contact_offset: lift.d1,
                normal_arm: lift.d1,
                friction_arm: y,
                axial_cosine: 1.0,
            })
        }
        FollowerShape::Curved { radius: rf, offset: e } => {
            let y0 = ((rb + rf).powi(2) - e * e).sqrt();
            let (ax, ay) = (y0 + lift.v, lift.d1 - e);
            let (dax, day) = (lift.d1, lift.d2);
            let a2 = ax * ax + ay * ay;
            let a_norm = a2.sqrt();
            let a_cross_da = ax * day - ay * dax;
            // B = A' − J A, J(x, y) = (−y, x).
            let (bx, by) = (dax + ay, day - ax);
            let a_cross_b = ax * by - ay * bx;
            // Pitch curvature κ_p = 1/ρ_p (convex positive; 0 on a straight flank).
            let kappa_p = -a_cross_b / (a_norm * a2);
            // 1 − R_f κ_p = ρ_c/ρ_p: the cam undercuts (cusp) when it is ≤ 0.
            let shrink = 1.0 - rf * kappa_p;
            if !(shrink > 0.0) {
                return Err(SolveError::physical(
                    crate::PhysicalFailure::CamUndercut,
                    format!(
                        "the cam undercuts at {deg:.2}°: the pitch curve's radius of curvature \
                         {:.4} mm is not larger than the follower radius {:.4} mm (use a smaller \
                         roller, a larger base circle or gentler lift)",
                        1e3 / kappa_p,
                        rf * 1e3
                    ),
                ));
            }
            // Unit normal N = J A/|A| (from the cam into the follower), tangent t = A/|A|.
            let (nx, ny) = (-ay / a_norm, ax / a_norm);
            let (tx, ty) = (ax / a_norm, ay / a_norm);
            let (kx, ky) = (e - rf * nx, y0 + lift.v - rf * ny);
            let psi_dot = w * a_cross_da / a2;
            Ok(KinematicState {
                theta,
                speed,
                lift,
                velocity,
                acceleration,
                jerk,
                pressure_angle: ay.atan2(ax),
                cam_curvature: kappa_p / shrink,
                // 1/R = κ_c + 1/R_f = 1/(R_f (1 − R_f κ_p)).
                reduced_radius: rf * shrink,
                cam_surface_velocity: w * a_norm * shrink,
                follower_surface_base: rf * psi_dot,
                contact_offset: kx - e,
                normal_arm: kx * ny - ky * nx,
                friction_arm: -(kx * ty - ky * tx),
                axial_cosine: ny,
            })
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::cam::lift::{LiftLaw, LiftProgram};
    use std::f64::consts::PI;

    fn cycloidal(base: f64) -> CamProfile {
        CamProfile::Program {
            base_radius: base,
            program: LiftProgram {
                lift: 0.008,
                rise_start: 0.5 * PI,
                rise: 0.5 * PI,
                top_dwell: 0.0,
                fall: 0.5 * PI,
                rise_law: LiftLaw::Cycloidal,
                return_law: LiftLaw::Cycloidal,
            },
        }
    }

    /// The flat-faced cam profile as the envelope of the follower face, in the cam frame:
    /// point = R(−θ)(s', r_b + s). Its radius of curvature by finite differences must equal
    /// r_b + s + s''.
    #[test]
    fn flat_follower_radius_matches_numerical_differentiation_of_the_profile() {
        let cam = cycloidal(0.02);
        let f = FollowerGeometry { shape: FollowerShape::Flat, clockwise: false };
        let point = |th: f64| {
            let j = cam.lift(th, FollowerShape::Flat);
            let (x, y) = (j.d1, 0.02 + j.v);
            let (s, c) = th.sin_cos();
            (c * x + s * y, -s * x + c * y)
        };
        let h = 1e-4;
        // (Away from θ = π, where the cycloidal jerk jumps and the differences lose an order.)
        for th in [0.3, 1.7, 2.4, 3.0, 3.6, 4.5] {
            let (p0, pp, pm) = (point(th), point(th + h), point(th - h));
            let d1 = ((pp.0 - pm.0) / (2.0 * h), (pp.1 - pm.1) / (2.0 * h));
            let d2 = ((pp.0 - 2.0 * p0.0 + pm.0) / (h * h), (pp.1 - 2.0 * p0.1 + pm.1) / (h * h));
            let speed = d1.0.hypot(d1.1);
            let rho_fd = speed.powi(3) / (d1.0 * d2.1 - d1.1 * d2.0).abs();
            let k = kinematics(&cam, &f, th, CamSpeed { omega: 100.0, alpha: 0.0, time: 0.0 }).unwrap();
            assert!(((1.0 / k.cam_curvature) - rho_fd).abs() < 1e-6 * rho_fd, "θ={th}: {} vs {}", (1.0 / k.cam_curvature), rho_fd);
            // Contact point moves along the cam at u_c = ω ρ_c: arc speed |dP/dθ| = ρ_c.
            assert!((speed - (1.0 / k.cam_curvature)).abs() < 1e-6 * speed);
        }
    }

    /// Roller: compare ρ_c, the pressure angle and u_c with an independent construction of the
    /// pitch curve P(θ) = R(−θ)(e, y0 + s) and the cam profile P − R_f n by finite differences.
    #[test]
    fn roller_geometry_matches_an_independent_pitch_curve_construction() {
        let cam = cycloidal(0.02);
        let (rf, e) = (0.012, 0.004);
        let f = FollowerGeometry { shape: FollowerShape::Curved { radius: rf, offset: e }, clockwise: false };
        let y0 = ((0.02f64 + rf).powi(2) - e * e).sqrt();
        let pitch = |th: f64| {
            let s = cam.lift(th, FollowerShape::Curved { radius: rf, offset: e }).v;
            let (sn, c) = th.sin_cos();
            (c * e + sn * (y0 + s), -sn * e + c * (y0 + s))
        };
        let h = 1e-4;
        let omega = 100.0;
        for th in [0.2, 1.9, 2.6, 3.0, 3.8, 4.6] {
            let (p0, pp, pm) = (pitch(th), pitch(th + h), pitch(th - h));
            let d1 = ((pp.0 - pm.0) / (2.0 * h), (pp.1 - pm.1) / (2.0 * h));
            let d2 = ((pp.0 - 2.0 * p0.0 + pm.0) / (h * h), (pp.1 - 2.0 * p0.1 + pm.1) / (h * h));
            let speed = d1.0.hypot(d1.1);
            let rho_p = speed.powi(3) / -(d1.0 * d2.1 - d1.1 * d2.0); // clockwise traversal
            let k = kinematics(&cam, &f, th, CamSpeed { omega, alpha: 0.0, time: 0.0 }).unwrap();
            assert!(((1.0 / k.cam_curvature) - (rho_p - rf)).abs() < 1e-6 * rho_p.abs(), "θ={th}");
            // Pressure angle: angle between the follower axis and the pitch-curve normal.
            let (sn, c) = th.sin_cos();
            // Rotate the tangent back to the ground frame: R(θ) d1.
            let tg = (c * d1.0 - sn * d1.1, sn * d1.0 + c * d1.1);
            let phi = tg.1.atan2(tg.0);
            assert!((k.pressure_angle - phi).abs() < 1e-7, "θ={th}: {} vs {}", k.pressure_angle, phi);
            // Cam surface speed relative to the contact point: |d(profile)/dt|.
            let u_c = omega * speed * (rho_p - rf) / rho_p;
            assert!((k.cam_surface_velocity - u_c).abs() < 1e-6 * u_c.abs().max(1e-3));
        }
    }

    #[test]
    fn base_circle_values_and_pure_rolling() {
        let cam = cycloidal(0.02);
        let rf = 0.0125;
        let f = FollowerGeometry { shape: FollowerShape::Curved { radius: rf, offset: 0.0 }, clockwise: false };
        let k = kinematics(&cam, &f, 0.1, CamSpeed { omega: 100.0, alpha: 0.0, time: 0.0 }).unwrap();
        assert!((k.cam_surface_velocity - 100.0 * 0.02).abs() < 1e-12);
        assert!(k.follower_surface_base.abs() < 1e-12);
        assert!((k.reduced_radius - 0.02 * rf / (0.02 + rf)).abs() < 1e-15);
        assert!(k.pressure_angle.abs() < 1e-15 && (k.axial_cosine - 1.0).abs() < 1e-15);
        // Flat follower: entrainment ω(r_b + s + 2s'')/2 and sliding ω(r_b + s).
        let flat = FollowerGeometry { shape: FollowerShape::Flat, clockwise: false };
        let k = kinematics(&cam, &flat, 2.0, CamSpeed { omega: 100.0, alpha: 0.0, time: 0.0 }).unwrap();
        let j = k.lift;
        assert!((k.entrainment(k.follower_surface_base) - 50.0 * (0.02 + j.v + 2.0 * j.d2)).abs() < 1e-12);
        assert!((k.cam_surface_velocity - k.follower_surface_base - 100.0 * (0.02 + j.v)).abs() < 1e-12);
    }

    #[test]
    fn undercut_is_refused() {
        // 8 mm cycloidal lift over 30° on a 5 mm base circle: r_b + s + s'' < 0 near the nose.
        let cam = CamProfile::Program {
            base_radius: 0.005,
            program: LiftProgram {
                lift: 0.008,
                rise_start: 0.0,
                rise: 30f64.to_radians(),
                top_dwell: 0.0,
                fall: 30f64.to_radians(),
                rise_law: LiftLaw::Cycloidal,
                return_law: LiftLaw::Cycloidal,
            },
        };
        let f = FollowerGeometry { shape: FollowerShape::Flat, clockwise: false };
        let sp = CamSpeed { omega: 1.0, alpha: 0.0, time: 0.0 };
        let any_err = (0..360).any(|d| matches!(
            kinematics(&cam, &f, (d as f64).to_radians(), sp),
            Err(SolveError::Physical { code: crate::PhysicalFailure::CamUndercut, .. })
        ));
        assert!(any_err);
        let roller = FollowerGeometry { shape: FollowerShape::Curved { radius: 0.02, offset: 0.0 }, clockwise: false };
        let any_err = (0..360).any(|d| matches!(
            kinematics(&cam, &roller, (d as f64).to_radians(), sp),
            Err(SolveError::Physical { code: crate::PhysicalFailure::CamUndercut, .. })
        ));
        assert!(any_err);
    }

    #[test]
    fn startup_schedule_reaches_rated_speed() {
        let s = SpeedSchedule::Startup { omega: 100.0, rated_angle: PI };
        let a = s.at(PI);
        assert!((a.omega - 100.0).abs() < 1e-9);
        // θ = ω²/(2α) and t = ω/α at the rated angle.
        let alpha = 100.0f64.powi(2) / (2.0 * PI);
        assert!((a.time - 100.0 / alpha).abs() < 1e-12);
        assert_eq!(s.at(0.0).omega, 0.0);
        let b = s.at(1.5 * PI);
        assert!((b.time - (a.time + 0.5 * PI / 100.0)).abs() < 1e-12 && b.alpha == 0.0);
    }
}
