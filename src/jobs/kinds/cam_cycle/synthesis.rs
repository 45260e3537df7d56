//! What a `synthesised` cam profile adds to the `cam_cycle` result (issue 45 item 3): the
//! `synthesis` summary (the law's peaks per cam angle against the limits, radii of curvature,
//! undercut) and the `contour` table (the law per cam angle and the cam contour for
//! manufacture; its `angle_deg` and `lift` columns are a `table` profile's input).
//!
//! Units: lift in m, angles in degrees (`*_deg`), the law's derivatives per cam angle in m/rad,
//! m/rad², m/rad³ (the `series` columns are the same law per time at the run's speed).

use super::spec::{CamCycleSpec, Direction, FollowerSpec, ProfileSpec};
use super::synthesis_spec::SynthesisedSpec;
use crate::physics::cam::contour::{contour, ContourPoint};
use crate::physics::cam::synthesis::{shortest_duration, LawLimits};
use crate::physics::cam::{CamProfile, FollowerShape};
use crate::physics::valvetrain::polydyne::PolydyneTrain;
use serde::Serialize;
use utoipa::ToSchema;

/// The synthesised law and its checks (profile `synthesised`). Derivatives are per cam angle.
#[derive(Debug, Clone, PartialEq, Serialize, ToSchema)]
pub struct SynthesisReport {
    /// Cam angle where the opening ramp starts, degrees.
    pub start_deg: f64,
    /// Angle of each ramp, degrees (0 without ramps).
    pub ramp_angle_deg: f64,
    /// Angle of the main rise (and of the main return), degrees.
    pub rise_angle_deg: f64,
    /// Peak velocity ds/dθ, m/rad.
    pub max_velocity: f64,
    pub max_velocity_angle_deg: f64,
    /// Largest acceleration d²s/dθ², m/rad².
    pub max_acceleration: f64,
    pub max_acceleration_angle_deg: f64,
    /// Most negative acceleration d²s/dθ², m/rad².
    pub min_acceleration: f64,
    pub min_acceleration_angle_deg: f64,
    /// Largest |d³s/dθ³|, m/rad³.
    pub max_abs_jerk: f64,
    pub max_abs_jerk_angle_deg: f64,
    /// `limits.max_acceleration`, m/rad².
    #[serde(skip_serializing_if = "Option::is_none")]
    pub acceleration_limit: Option<f64>,
    /// Relative margin 1 − peak/limit of the larger of both accelerations (negative: exceeded).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub acceleration_margin: Option<f64>,
    /// `limits.max_jerk`, m/rad³.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub jerk_limit: Option<f64>,
    /// Relative margin 1 − peak/limit of |jerk| (negative: exceeded).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub jerk_margin: Option<f64>,
    /// With `limits`: the shortest event duration whose law meets them (same lift, ramps, law
    /// and dwell), degrees, to 1e-4°; absent when none up to 360° does.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub shortest_duration_deg: Option<f64>,
    /// Smallest convex radius of curvature of the cam surface, m.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub min_radius_of_curvature: Option<f64>,
    /// Smallest concave radius of curvature of the cam surface, m (the largest grinding wheel
    /// that finishes it); absent where the cam is nowhere concave.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub min_concave_radius_of_curvature: Option<f64>,
    /// Roller or spherical follower: smallest convex radius of curvature of the pitch curve, m.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub min_pitch_radius_of_curvature: Option<f64>,
    /// Roller or spherical follower: relative undercut margin, that pitch radius over the
    /// follower radius minus 1 (≤ 0: undercut).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub undercut_margin: Option<f64>,
    /// Flat face: the smallest face radius that keeps the contact on the face, max |s' − e|, m.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub min_face_radius: Option<f64>,
    /// The cam surface has a cusp somewhere (it cannot be made for this follower).
    pub undercut: bool,
    /// With `dynamic_correction`: what the cam was corrected with.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub dynamic_correction: Option<CorrectionReport>,
    /// Limits exceeded, said in words.
    pub warnings: Vec<String>,
}

/// The polydyne's dynamic correction used: `s = y + (k_s/k) y + (m ω²/k) y''`.
#[derive(Debug, Clone, PartialEq, Serialize, ToSchema)]
pub struct CorrectionReport {
    /// Design camshaft speed, rpm.
    pub design_speed_rpm: f64,
    /// Effective mass m (cam side), kg.
    pub mass: f64,
    /// Effective stiffness k between cam and valve (cam side), N/m.
    pub stiffness: f64,
    /// Valve spring rate k_s (cam side), N/m.
    pub spring_rate: f64,
    /// Largest lift of the corrected cam, m (the designed valve law reaches `lift`).
    pub cam_max_lift: f64,
    /// Largest difference between cam lift and designed valve lift over the event, m.
    pub max_correction: f64,
}

/// The law per cam angle and the cam contour (cam frame, cam turning as `operation.direction`,
/// follower axis along +y at cam angle 0), at the cycle's angles. Columns of equal length; CSV
/// with `?table=contour`.
#[derive(Debug, Clone, PartialEq, Serialize, ToSchema)]
pub struct ContourTable {
    /// Cam angle, degrees.
    pub angle_deg: Vec<f64>,
    /// Follower lift, m.
    pub lift: Vec<f64>,
    /// With `dynamic_correction`: the designed valve law (cam side), m; `lift` is the cam's.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub valve_lift: Option<Vec<f64>>,
    /// ds/dθ, m/rad.
    pub lift_velocity: Vec<f64>,
    /// d²s/dθ², m/rad².
    pub lift_acceleration: Vec<f64>,
    /// d³s/dθ³, m/rad³.
    pub lift_jerk: Vec<f64>,
    /// Cam surface point, x in m.
    pub x: Vec<f64>,
    /// Cam surface point, y in m.
    pub y: Vec<f64>,
    /// Distance of the surface point from the cam centre, m.
    pub radius: Vec<f64>,
    /// Curvature of the cam surface, 1/m (convex positive).
    pub curvature: Vec<f64>,
    /// Follower centre (pitch curve), x in m (roller and spherical followers).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub pitch_x: Option<Vec<f64>>,
    /// Follower centre (pitch curve), y in m.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub pitch_y: Option<Vec<f64>>,
    /// Curvature of the pitch curve, 1/m.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub pitch_curvature: Option<Vec<f64>>,
}

/// The fields of a `synthesised` profile.
pub fn synthesised(p: &ProfileSpec) -> Option<SynthesisedSpec> {
    match *p {
        ProfileSpec::Synthesised { base_radius, lift, duration_deg, ramp, law, dwell_deg, nose_deg, limits, dynamic_correction } => {
            Some(SynthesisedSpec { base_radius, lift, duration_deg, ramp, law, dwell_deg, nose_deg, limits, dynamic_correction })
        }
        _ => None,
    }
}

/// The `synthesis` and `contour` of a `synthesised` profile (`None` for other profiles).
/// `correction`: the design speed (rpm) and the train the cam was corrected with, if it was.
pub(super) fn synthesis_of(spec: &CamCycleSpec, profile: &CamProfile, shape: FollowerShape, correction: Option<(f64, PolydyneTrain)>) -> Option<(SynthesisReport, ContourTable)> {
    let s = synthesised(&spec.cam.profile)?;
    let CamProfile::Synthesised { law, .. } = profile else { return None };
    // Clockwise running: the mirror image of the counter-clockwise cam for the mirrored offset.
    let cw = spec.operation.direction == Direction::Cw;
    let shape = match shape {
        FollowerShape::Curved { radius, offset } if cw => FollowerShape::Curved { radius, offset: -offset },
        s => s,
    };
    let mirror = if cw { -1.0 } else { 1.0 };
    let c = contour(profile, shape, spec.angles);
    let p = law.peaks();
    let limits = LawLimits { max_acceleration: s.limits.and_then(|l| l.max_acceleration), max_jerk: s.limits.and_then(|l| l.max_jerk) };
    let (acc, jerk) = law.check(limits);
    let mut warnings = Vec::new();
    for (what, unit, check) in [("acceleration", "m/rad²", acc), ("jerk", "m/rad³", jerk)] {
        if let Some(k) = check.filter(|k| k.margin < 0.0) {
            warnings.push(format!(
                "peak {what} {:.4e} {unit} exceeds the limit {:.4e} {unit} by {:.1} %: lengthen the event, lower the lift or \
                 use a gentler law",
                k.peak,
                k.limit,
                -100.0 * k.margin
            ));
        }
    }
    let (rf, e) = match spec.follower {
        FollowerSpec::Roller { radius, .. } | FollowerSpec::Spherical { radius, .. } => (Some(radius), 0.0),
        FollowerSpec::FlatFaced { offset, .. } => (None, offset),
    };
    if c.undercut {
        warnings.push("the cam surface has a cusp (undercut): see contour.curvature and the pitch curvature".into());
    }
    let deg = |a: f64| a.to_degrees();
    let report = SynthesisReport {
        start_deg: deg(law.start()),
        ramp_angle_deg: deg(law.ramp_angle),
        rise_angle_deg: deg(law.rise_angle),
        max_velocity: p.max_velocity.value,
        max_velocity_angle_deg: deg(p.max_velocity.angle),
        max_acceleration: p.max_acceleration.value,
        max_acceleration_angle_deg: deg(p.max_acceleration.angle),
        min_acceleration: p.min_acceleration.value,
        min_acceleration_angle_deg: deg(p.min_acceleration.angle),
        max_abs_jerk: p.max_abs_jerk.value,
        max_abs_jerk_angle_deg: deg(p.max_abs_jerk.angle),
        acceleration_limit: acc.map(|k| k.limit),
        acceleration_margin: acc.map(|k| k.margin),
        jerk_limit: jerk.map(|k| k.limit),
        jerk_margin: jerk.map(|k| k.margin),
        shortest_duration_deg: shortest_duration(law.spec, limits, 64, 1e-6, 60).ok().flatten().map(|(d, _)| deg(d)),
        min_radius_of_curvature: c.min_convex_radius,
        min_concave_radius_of_curvature: c.min_concave_radius,
        min_pitch_radius_of_curvature: rf.and(c.min_pitch_radius),
        undercut_margin: rf.zip(c.min_pitch_radius).map(|(r, p)| p / r - 1.0),
        min_face_radius: rf.is_none().then(|| c.points.iter().map(|q| (q.lift.d1 - e).abs()).fold(0.0, f64::max)),
        undercut: c.undercut,
        warnings,
        dynamic_correction: correction.filter(|_| law.correction.is_some()).map(|(rpm, t)| {
            let diff = c.points.iter().map(|q| (q.lift.v - law.valve(q.theta).v).abs()).fold(0.0, f64::max);
            CorrectionReport {
                design_speed_rpm: rpm,
                mass: t.mass,
                stiffness: t.stiffness,
                spring_rate: t.spring_rate,
                cam_max_lift: c.points.iter().map(|q| q.lift.v).fold(0.0, f64::max),
                max_correction: diff,
            }
        }),
    };
    let col = |f: &dyn Fn(&ContourPoint) -> f64| c.points.iter().map(f).collect::<Vec<f64>>();
    let curved = rf.is_some();
    let table = ContourTable {
        angle_deg: col(&|q| q.theta.to_degrees()),
        lift: col(&|q| q.lift.v),
        valve_lift: law.correction.is_some().then(|| col(&|q| law.valve(q.theta).v)),
        lift_velocity: col(&|q| q.lift.d1),
        lift_acceleration: col(&|q| q.lift.d2),
        lift_jerk: col(&|q| q.lift.d3),
        x: col(&|q| mirror * q.surface.0),
        y: col(&|q| q.surface.1),
        radius: col(&|q| q.surface.0.hypot(q.surface.1)),
        curvature: col(&|q| q.surface_curvature),
        pitch_x: curved.then(|| col(&|q| mirror * q.pitch.map_or(0.0, |p| p.0))),
        pitch_y: curved.then(|| col(&|q| q.pitch.map_or(0.0, |p| p.1))),
        pitch_curvature: curved.then(|| col(&|q| q.pitch_curvature.unwrap_or(0.0))),
    };
    Some((report, table))
}
