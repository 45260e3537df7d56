//! The `synthesised` cam profile (issue 45 item 3): the spec (lift, event duration, ramps, law,
//! dwell, limits), its validation, the physics law it builds (`physics::cam::synthesis`), and
//! what the result adds — the `synthesis` summary (peaks per cam angle against the limits,
//! radii of curvature, undercut) and the `contour` table (the law per cam angle and the cam
//! contour for manufacture; its `angle_deg` and `lift` columns are a `table` profile's input).
//!
//! Units: lift and heights in m, angles in degrees (`*_deg`), the law's derivatives per cam
//! angle in m/rad, m/rad², m/rad³ (1 mm/° = 0.0573 m/rad; the `series` columns are the same
//! law per time at the run's speed).

use super::result::CamCycleResult;
use super::spec::{CamCycleSpec, FollowerSpec, ProfileSpec};
use crate::jobs::kind::Validation;
use crate::jobs::quantity::{self as Q, Quantity};
use crate::physics::cam::contour::contour;
use crate::physics::cam::synthesis::{LawLimits, LiftSpec, Ramp, RiseLaw};
use crate::physics::cam::{CamProfile, FollowerShape, SynthesisedLift};
use crate::physics::SolveError;
use serde::{Deserialize, Serialize};
use utoipa::ToSchema;

/// Lift per cam angle (a ramp velocity), m/rad.
const LIFT_RATE: Quantity = Quantity {
    name: "a lift per cam angle",
    unit: "m/rad",
    min: 1e-9,
    max: 1.0,
    typical: 5e-3,
    slip: "mm/° or mm/rad: SI expects m/rad (1 mm/° = 0.0573 m/rad)",
};
/// An acceleration per cam angle squared, m/rad².
const LIFT_ACCELERATION: Quantity = Quantity { name: "an acceleration per cam angle²", unit: "m/rad²", min: 1e-9, max: 1e3, typical: 1.0, slip: "mm/rad²: SI expects m/rad²" };
/// A jerk per cam angle cubed, m/rad³.
const LIFT_JERK: Quantity = Quantity { name: "a jerk per cam angle³", unit: "m/rad³", min: 1e-9, max: 1e5, typical: 100.0, slip: "mm/rad³: SI expects m/rad³" };

/// Law of the main rise of a synthesised profile.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize, ToSchema)]
#[serde(rename_all = "snake_case")]
pub enum SynthesisLaw {
    /// 2-6-10-14-18 polydyne (Stoddart): symmetric about the nose, no top dwell, continuous jerk.
    #[default]
    Polydyne,
    /// 3-4-5 polynomial (jerk steps at its ends).
    #[serde(rename = "polynomial_345")]
    Polynomial345,
    /// 4-5-6-7 polynomial (continuous jerk).
    #[serde(rename = "polynomial_4567")]
    Polynomial4567,
    /// Cycloidal (jerk steps at its ends).
    Cycloidal,
}

/// Opening and closing ramp: the velocity blends from 0 to `velocity` (3-4-5 step) over the
/// first half of the ramp angle and stays constant over the second, so each ramp spans
/// `4 height/(3 velocity)` rad.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct RampSpec {
    /// Lift at the end of the ramp, m.
    pub height: f64,
    /// Constant ramp velocity ds/dθ, m/rad (1 mm/° = 0.0573 m/rad).
    pub velocity: f64,
}

/// Limits on the law's peaks, per cam angle (reported with margins; exceeding one is a warning).
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct LawLimitsSpec {
    /// Largest |d²s/dθ²|, m/rad².
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub max_acceleration: Option<f64>,
    /// Largest |d³s/dθ³|, m/rad³.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub max_jerk: Option<f64>,
}

fn default_nose() -> f64 {
    180.0
}

/// A lift law synthesised from its specification (`physics::cam::synthesis`): opening ramp,
/// main rise of `law`, top dwell, and the mirrored return and closing ramp, centred on
/// `nose_deg`. Lift, velocity and acceleration are continuous and the jerk finite (continuous
/// with `polydyne` and `polynomial_4567`). The result adds `synthesis` and the `contour` table.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct SynthesisedSpec {
    /// Base circle radius, m.
    pub base_radius: f64,
    /// Total lift from the base circle to the nose (ramp included), m.
    pub lift: f64,
    /// Event duration from the start of the opening ramp to the end of the closing ramp,
    /// degrees.
    pub duration_deg: f64,
    /// Opening and closing ramp. Absent: none (the rise starts from the base circle).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub ramp: Option<RampSpec>,
    /// Law of the main rise. Default `polydyne`.
    #[serde(default)]
    pub law: SynthesisLaw,
    /// Dwell at full lift, degrees. Default 0 (none with the polydyne).
    #[serde(default)]
    pub top_dwell_deg: f64,
    /// Cam angle of the nose (middle of the event), degrees. Default 180.
    #[serde(default = "default_nose")]
    pub nose_deg: f64,
    /// Peak limits. Absent: none.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub limits: Option<LawLimitsSpec>,
}

/// The spec path of a `LiftSpec` field.
fn spec_path(field: &str) -> &'static str {
    match field {
        "LiftSpec.duration" => "/cam/profile/duration_deg",
        "LiftSpec.top_dwell" => "/cam/profile/top_dwell_deg",
        "LiftSpec.ramp.velocity" => "/cam/profile/ramp/velocity",
        "LiftSpec.ramp.height" => "/cam/profile/ramp/height",
        _ => "/cam/profile/lift",
    }
}

impl SynthesisedSpec {
    /// The physics law, its errors named by the spec's paths.
    pub fn law(&self) -> Result<SynthesisedLift, SolveError> {
        SynthesisedLift::new(LiftSpec {
            lift: self.lift,
            duration: self.duration_deg.to_radians(),
            nose: self.nose_deg.to_radians(),
            top_dwell: self.top_dwell_deg.to_radians(),
            ramp: self.ramp.map(|r| Ramp { height: r.height, velocity: r.velocity }),
            law: match self.law {
                SynthesisLaw::Polydyne => RiseLaw::Polydyne,
                SynthesisLaw::Polynomial345 => RiseLaw::Polynomial345,
                SynthesisLaw::Polynomial4567 => RiseLaw::Polynomial4567,
                SynthesisLaw::Cycloidal => RiseLaw::Cycloidal,
            },
        })
        .map_err(|e| match e {
            SolveError::InvalidInput { field, message } => SolveError::invalid(spec_path(&field), message),
            other => other,
        })
    }

    /// The fields, then the law itself (a law that cannot be built is refused at submission,
    /// naming the field).
    pub fn validate(&self, v: &mut Validation) {
        v.quantity("/cam/profile/lift", self.lift, Q::HEIGHT.from(1e-7));
        v.in_range("/cam/profile/duration_deg", self.duration_deg, 1e-3, 360.0);
        v.in_range("/cam/profile/top_dwell_deg", self.top_dwell_deg, 0.0, 360.0);
        v.in_range("/cam/profile/nose_deg", self.nose_deg, -360.0, 360.0);
        if let Some(r) = self.ramp {
            v.quantity("/cam/profile/ramp/height", r.height, Q::HEIGHT.from(1e-9));
            v.quantity("/cam/profile/ramp/velocity", r.velocity, LIFT_RATE);
        }
        if let Some(l) = self.limits {
            if let Some(a) = l.max_acceleration {
                v.quantity("/cam/profile/limits/max_acceleration", a, LIFT_ACCELERATION);
            }
            if let Some(j) = l.max_jerk {
                v.quantity("/cam/profile/limits/max_jerk", j, LIFT_JERK);
            }
        }
        if v.is_ok() {
            if let Err(SolveError::InvalidInput { field, message }) = self.law() {
                v.error(&field, message);
            }
        }
    }
}

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
    /// Limits exceeded, said in words.
    pub warnings: Vec<String>,
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

/// Add `synthesis` and `contour` to the result of a `synthesised` profile.
pub(super) fn add_synthesis(result: &mut CamCycleResult, spec: &CamCycleSpec, profile: &CamProfile, shape: FollowerShape) {
    let ProfileSpec::Synthesised(s) = &spec.cam.profile else { return };
    let CamProfile::Synthesised { law, .. } = profile else { return };
    // Clockwise running: the mirror image of the counter-clockwise cam for the mirrored offset.
    let cw = spec.operation.direction == super::spec::Direction::Cw;
    let shape = match shape {
        FollowerShape::Curved { radius, offset } if cw => FollowerShape::Curved { radius, offset: -offset },
        s => s,
    };
    let mirror = if cw { -1.0 } else { 1.0 };
    let c = contour(profile, shape, spec.angles);
    let p = law.peaks();
    let (acc, jerk) = law.check(LawLimits {
        max_acceleration: s.limits.and_then(|l| l.max_acceleration),
        max_jerk: s.limits.and_then(|l| l.max_jerk),
    });
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
    result.synthesis = Some(SynthesisReport {
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
        min_radius_of_curvature: c.min_convex_radius,
        min_concave_radius_of_curvature: c.min_concave_radius,
        min_pitch_radius_of_curvature: rf.and(c.min_pitch_radius),
        undercut_margin: rf.zip(c.min_pitch_radius).map(|(r, p)| p / r - 1.0),
        min_face_radius: rf.is_none().then(|| c.points.iter().map(|q| (q.lift.d1 - e).abs()).fold(0.0, f64::max)),
        undercut: c.undercut,
        warnings,
    });
    let col = |f: &dyn Fn(&crate::physics::cam::contour::ContourPoint) -> f64| c.points.iter().map(f).collect::<Vec<f64>>();
    let curved = rf.is_some();
    result.contour = Some(ContourTable {
        angle_deg: col(&|q| q.theta.to_degrees()),
        lift: col(&|q| q.lift.v),
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
    });
}
