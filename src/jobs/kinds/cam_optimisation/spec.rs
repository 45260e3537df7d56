//! The `cam_optimisation` request: a base `cam_cycle` spec, design variables (JSON pointers into
//! it with bounds or listed values), objectives and constraints (named quantities or pointers
//! into the cycle's result), and the search's budget.

use serde::{Deserialize, Serialize};
use serde_json::Value;
use utoipa::ToSchema;

/// Another field set from a variable's value `x`: `offset + scale·x` (e.g. the top dwell that
/// keeps the event duration when the rise and return angles vary).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct Tie {
    /// JSON pointer into the base spec.
    #[schema(example = "/cam/profile/top_dwell_deg")]
    pub path: String,
    /// Factor on the variable's value (a ratio of the two fields' units).
    #[serde(default = "one")]
    pub scale: f64,
    /// Added constant, in the tied field's unit.
    #[serde(default)]
    pub offset: f64,
}

fn one() -> f64 {
    1.0
}

/// One design variable: where in the base spec, and its range (`min`/`max`, continuous) or its
/// choices (`values`, categorical: strings, numbers or objects, e.g. the lift law).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct Variable {
    /// JSON pointer (RFC 6901) into the base `cam_cycle` spec, e.g. `/load/spring_preload`.
    /// Missing intermediate objects are created.
    #[schema(example = "/load/spring_preload")]
    pub path: String,
    /// Lower bound, in the field's unit (continuous variable).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub min: Option<f64>,
    /// Upper bound, in the field's unit (continuous variable).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub max: Option<f64>,
    /// The choices of a categorical variable (1–32). Exactly one of `values` and `min`+`max`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub values: Option<Vec<Value>>,
    /// Fields that follow a continuous variable linearly (at most 4).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub tied: Vec<Tie>,
}

impl Variable {
    pub fn is_continuous(&self) -> bool {
        self.values.is_none()
    }
}

/// Minimise or maximise.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize, ToSchema)]
#[serde(rename_all = "snake_case")]
pub enum Goal {
    #[default]
    Minimise,
    Maximise,
}

/// One objective: a named quantity of the cycle (`friction_power`: the cycle-mean power loss,
/// W; `min_film`, `min_lambda`, `max_hertz_pressure`, `max_subsurface_shear`,
/// `max_flash_temperature`, `mean_friction_torque`, … any number of the cycle's `summary`), a
/// JSON pointer into the `cam_cycle` result (`/summary/min_film`), or a wear quantity
/// (`wear_depth`: the cam's largest wear depth, m; `wear:<name or pointer>` of the `wear`
/// result; needs `wear`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct Objective {
    #[schema(example = "friction_power")]
    pub quantity: String,
    #[serde(default)]
    pub goal: Goal,
    /// Weight in the score (≥ 0, a pure number). Default 1.
    #[serde(default = "one")]
    pub weight: f64,
}

/// One constraint on a design: `quantity` (as an objective's, or `no_separation`: the
/// follower keeps contact — the cycle's minimum contact load above `min`, default 0 N, and no
/// separation interval of a dynamic train; or `no_undercut`: the cam's smallest convex radius of
/// curvature above `min`, default 0 m), with `min` and/or `max` in the quantity's unit (factors
/// of the baseline's value when `relative`), evaluated at `at_rpm` when given (the base spec's
/// speed replaced; `no_separation` needs it: the speed limit times a margin).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct Constraint {
    #[schema(example = "no_separation")]
    pub quantity: String,
    /// Lower limit, in the quantity's unit (a factor of the baseline's value when `relative`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub min: Option<f64>,
    /// Upper limit, in the quantity's unit (a factor of the baseline's value when `relative`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub max: Option<f64>,
    /// `min` and `max` are factors of the baseline design's value (1: not above/below the
    /// baseline). Default false.
    #[serde(default, skip_serializing_if = "std::ops::Not::not")]
    pub relative: bool,
    /// Camshaft speed the quantity is evaluated at, rpm (another cycle per design and speed).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub at_rpm: Option<f64>,
}

/// The search: a seeded Latin hypercube over the variables, then Nelder–Mead searches (penalty
/// on the constraints) from the best designs of the sample.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize, ToSchema)]
#[serde(deny_unknown_fields, default)]
pub struct SearchSpec {
    /// Designs of the Latin hypercube (0 to 1000). Default 24.
    pub samples: usize,
    /// Nelder–Mead evaluations per start (0 to 1000; 0: the sample only). Default 30.
    pub iterations: usize,
    /// Nelder–Mead starts (1 to 8): the best design of each distinct combination of the
    /// categorical variables, best first. Default 3.
    pub starts: usize,
    /// Seed of the hypercube (same seed, same designs). Default 1.
    pub seed: u64,
}

impl Default for SearchSpec {
    fn default() -> Self {
        SearchSpec { samples: 24, iterations: 30, starts: 3, seed: 1 }
    }
}

/// Spec of a `cam_optimisation` job.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct CamOptimisationSpec {
    /// The `cam_cycle` spec every design starts from; it is also the baseline design.
    #[schema(value_type = Object)]
    pub base: Value,
    /// Design variables (1–12).
    pub variables: Vec<Variable>,
    /// Objectives (1–4): the score is the weighted sum of each objective over its baseline value
    /// (maximised ones negated); with two or more, `pareto` holds the non-dominated feasible
    /// designs of the first two.
    pub objectives: Vec<Objective>,
    /// Constraints (0–16).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub constraints: Vec<Constraint>,
    #[serde(default)]
    pub search: SearchSpec,
    /// A `wear` spec without its `cycle` (e.g. `{"hours": 1000, "wear_coefficient": {…}}`): each
    /// design also runs this wear job on its cycle when a quantity is `wear_depth` (the cam's
    /// largest wear depth after the running time, m) or `wear:<summary name or pointer>` of the
    /// `wear` result.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    #[schema(value_type = Option<Object>)]
    pub wear: Option<Value>,
}
