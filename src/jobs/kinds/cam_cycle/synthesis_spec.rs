//! The `synthesised` cam profile's spec (issue 45 item 3): lift, event duration, ramps, law,
//! dwell, limits; its validation and the physics law it builds (`physics::cam::synthesis`).
//! What the result adds is in `synthesis.rs`.
//!
//! Units: lift and heights in m, angles in degrees (`*_deg`), the law's derivatives per cam
//! angle in m/rad, m/rad², m/rad³ (1 mm/° = 0.0573 m/rad; the `series` columns are the same
//! law per time at the run's speed).

use crate::jobs::kind::Validation;
use crate::jobs::quantity::{self as Q, Quantity};
use crate::physics::cam::synthesis::{DynamicCorrection, LiftSpec, Ramp, RiseLaw};
use crate::physics::cam::SynthesisedLift;
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

/// A stiffness, N/m.
const STIFFNESS: Quantity = Quantity { name: "a stiffness", unit: "N/m", min: 1.0, max: 1e13, typical: 1e9, slip: "N/mm or N/µm: SI expects N/m" };

/// The polydyne's dynamic correction (Stoddart 1953; Norton, *Cam Design and Manufacturing
/// Handbook*): the law is the *valve's* lift `y`, and the cam is cut to
/// `y + (k_s/k) y + (m ω²/k) y''` so that the train, a mass `m` behind the stiffness `k` against
/// the valve spring `k_s`, follows the law at the design speed ω. Law `polydyne` only; the ramps
/// then take 4-5-6-7 velocity blends (continuous to the fourth derivative). The result's
/// `synthesis.dynamic_correction` reports what was used, `contour.valve_lift` the designed law
/// (`lift` and `summary.max_lift` are the cam's).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct DynamicCorrectionSpec {
    /// Camshaft speed the cam is corrected for, rpm.
    pub design_speed_rpm: f64,
    /// Effective mass m, kg. Absent: from the `dynamic` load — each link of the train carries
    /// the masses beyond it (`m = k Σ M_i/k_i`, cam side; `physics::valvetrain::polydyne`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub mass: Option<f64>,
    /// Effective stiffness k between cam and valve, N/m. Absent: the `dynamic` load's links in
    /// series (cam contact, pushrod, train link, lash adjuster).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub stiffness: Option<f64>,
    /// Valve spring rate k_s, N/m. Absent: the `dynamic` load's springs (cam side), 0 without
    /// one.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub spring_rate: Option<f64>,
}

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

pub fn default_nose() -> f64 {
    180.0
}

/// The fields of a `synthesised` profile (`ProfileSpec::Synthesised`, documented there).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SynthesisedSpec {
    pub base_radius: f64,
    pub lift: f64,
    pub duration_deg: f64,
    pub ramp: Option<RampSpec>,
    pub law: SynthesisLaw,
    pub dwell_deg: f64,
    pub nose_deg: f64,
    pub limits: Option<LawLimitsSpec>,
    pub dynamic_correction: Option<DynamicCorrectionSpec>,
}

/// The spec path of a `LiftSpec` field.
fn spec_path(field: &str) -> &'static str {
    match field {
        "LiftSpec.duration" => "/cam/profile/duration_deg",
        "LiftSpec.top_dwell" => "/cam/profile/dwell_deg",
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
            top_dwell: self.dwell_deg.to_radians(),
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
        v.in_range("/cam/profile/dwell_deg", self.dwell_deg, 0.0, 360.0);
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
        if let Some(c) = self.dynamic_correction {
            let at = "/cam/profile/dynamic_correction";
            v.check(self.law == SynthesisLaw::Polydyne, at, "the dynamic correction is the polydyne's: needs law polydyne");
            v.quantity(&format!("{at}/design_speed_rpm"), c.design_speed_rpm, Q::SPEED_RPM);
            if let Some(m) = c.mass {
                v.quantity(&format!("{at}/mass"), m, Q::MASS.from(1e-6));
            }
            if let Some(k) = c.stiffness {
                v.quantity(&format!("{at}/stiffness"), k, STIFFNESS);
            }
            if let Some(k) = c.spring_rate {
                v.quantity(&format!("{at}/spring_rate"), k, STIFFNESS.from(0.0));
            }
        }
        if v.is_ok() {
            match self.law() {
                Err(SolveError::InvalidInput { field, message }) => {
                    v.error(&field, message);
                }
                // With every coefficient given the corrected cam is checked here too.
                Ok(law) => {
                    if let Some(DynamicCorrectionSpec { design_speed_rpm, mass: Some(m), stiffness: Some(k), spring_rate: Some(ks) }) = self.dynamic_correction {
                        let c = DynamicCorrection::new(m, k, ks, design_speed_rpm * std::f64::consts::PI / 30.0);
                        if let Err(SolveError::InvalidInput { message, .. }) = law.with_correction(c) {
                            v.error("/cam/profile/dynamic_correction", message);
                        }
                    }
                }
                Err(_) => {}
            }
        }
    }
}

