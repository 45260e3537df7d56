//! The `cam_optimisation` answer: the baseline and the best design (variables, objectives,
//! constraint margins, the design's `cam_cycle` spec and cycle summary), every evaluated design
//! as a table, and the Pareto front of the first two objectives.

use serde::Serialize;
use serde_json::{Map, Value};
use std::collections::BTreeMap;
use utoipa::ToSchema;

/// One constraint of a design.
#[derive(Debug, Clone, PartialEq, Serialize, ToSchema)]
pub struct ConstraintOutcome {
    /// The constraint's label: its quantity, `@<rpm>rpm` when evaluated at another speed.
    pub name: String,
    /// JSON pointer of the quantity in the `cam_cycle` result.
    pub pointer: String,
    /// The unit of `value`, `limit` and `margin`.
    pub unit: String,
    /// The quantity's value, in the row's `unit` (absent when the cycle failed or lacks it).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub value: Option<f64>,
    /// The limit (a `relative` constraint's factor times the baseline's value), in the row's `unit`.
    pub limit: f64,
    /// Which limit `limit` is: `min` (a lower limit) or `max` (an upper one; with both, the nearer).
    pub bound: String,
    /// Distance to the limit on the allowed side (negative: violated), in the row's `unit`.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub margin: Option<f64>,
    pub satisfied: bool,
}

/// One design: where it is, what it scores, how it meets the constraints.
#[derive(Debug, Clone, PartialEq, Serialize, ToSchema)]
pub struct Report {
    /// 1-based design number: the row index in `designs` plus one.
    pub design: usize,
    /// All constraints satisfied.
    pub feasible: bool,
    /// Weighted score, a pure number: Σ wᵢ fᵢ/|fᵢ(baseline)| / Σ wᵢ, maximised objectives negated
    /// (lower is better; the baseline's is the weight share of its objectives' signs).
    pub score: f64,
    /// The design variables' values by JSON pointer (each in its field's unit).
    #[schema(value_type = Object)]
    pub variables: Map<String, Value>,
    /// Cycle-mean friction power loss (`/summary/mean_power_loss` of the cycle), W.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub friction_power: Option<f64>,
    /// The objectives' values by quantity (units in the result's `units`).
    #[schema(value_type = Object)]
    pub objectives: Map<String, Value>,
    pub constraints: Vec<ConstraintOutcome>,
    /// The design's `cam_cycle` spec (run it as a `cam_cycle` job for its full cycle).
    #[schema(value_type = crate::jobs::kinds::cam_cycle::CamCycleSpec)]
    pub spec: Value,
    /// The design's cycle summary at the base speed (the `cam_cycle` result's `summary`, its units).
    #[schema(value_type = crate::jobs::kinds::cam_cycle::CamSummary)]
    pub cycle: Value,
}

/// The non-dominated feasible designs of the first two objectives.
#[derive(Debug, Clone, PartialEq, Serialize, ToSchema)]
pub struct Pareto {
    /// The two objectives' quantities.
    pub objectives: Vec<String>,
    /// Design numbers (1-based index into `designs`), ordered by the first objective.
    pub designs: Vec<usize>,
    /// The first objective's values along the front, in `units[objectives[0]]`.
    pub first: Vec<Value>,
    /// The second objective's values along the front, in `units[objectives[1]]`.
    pub second: Vec<Value>,
}

/// Result of a `cam_optimisation` job.
#[derive(Debug, Clone, PartialEq, Serialize, ToSchema)]
pub struct CamOptimisationResult {
    /// The base spec as it is.
    pub baseline: Report,
    /// The best design: the lowest score among the feasible designs (the baseline among them,
    /// so never worse than a feasible baseline); the least violating when none is feasible.
    pub best: Report,
    /// Change of the friction power from the baseline to the best design, % (−20: 20 % lower).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub friction_power_change: Option<f64>,
    /// Change of the score from the baseline to the best design, % of the baseline's
    /// (negative: better).
    pub score_change: f64,
    /// With two or more objectives.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub pareto: Option<Pareto>,
    /// Column names of `designs`: `design`, `phase` (`baseline`, `sample`, `search`), `status`
    /// (`succeeded`, `failed`, `undercut`: the cam undercuts, its `no_undercut` constraints at
    /// the signed undercut margin), `feasible`, `score`, the variables (pointer with `/` → `.`), the objectives, each
    /// constraint's value and `<name>.margin`, `error_code`.
    pub columns: Vec<String>,
    /// The unit of every dimensional column (`1` for pure numbers).
    pub units: BTreeMap<String, String>,
    /// Every evaluated design, in evaluation order.
    #[schema(value_type = Vec<Object>)]
    pub designs: Vec<Map<String, Value>>,
    /// Designs evaluated (each one cycle, plus one per distinct `at_rpm`).
    pub evaluations: usize,
    /// Number of feasible designs.
    pub feasible_count: usize,
    /// Number of designs whose cycle failed.
    pub failed_count: usize,
}
