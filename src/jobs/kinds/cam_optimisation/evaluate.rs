//! One design through the `cam_cycle` kind: its spec (the variables placed at their pointers),
//! its cycle at the base speed and at every constraint speed, the objectives' and constraints'
//! values, and the score against the baseline.

use super::spec::{CamOptimisationSpec, Constraint, Goal};
use crate::jobs::kind::{DynKind, Limits, Registered};
use crate::jobs::kinds::cam_cycle::CamCycle;
use crate::jobs::kinds::wear::Wear;
use crate::jobs::kinds::sweep::set_pointer;
use crate::physics::{Interrupt, Observer, SolveError};
use serde_json::{json, Value};

pub static CYCLE: Registered<CamCycle> = Registered::new();

/// The cycle kind every design runs.
pub fn cycle_kind() -> &'static dyn DynKind {
    &CYCLE
}

pub static WEAR: Registered<Wear> = Registered::new();

/// The wear kind a design's wear quantities come from.
pub fn wear_kind() -> &'static dyn DynKind {
    &WEAR
}

/// Whether a quantity is read from the design's `wear` run (`wear_depth`, `wear:<name>`,
/// `wear:<pointer>`) rather than its cycle.
pub fn is_wear(quantity: &str) -> bool {
    quantity == "wear_depth" || quantity.starts_with("wear:")
}

/// Whether any objective or constraint needs the wear run.
pub fn needs_wear(spec: &CamOptimisationSpec) -> bool {
    spec.objectives.iter().any(|o| is_wear(&o.quantity)) || spec.constraints.iter().any(|c| is_wear(&c.quantity))
}

/// The result units a quantity is read against (the wear kind's or the cycle's).
pub fn units_of(quantity: &str) -> &'static std::collections::BTreeMap<String, String> {
    if is_wear(quantity) { wear_kind().result_units() } else { cycle_kind().result_units() }
}

/// The `wear` spec of a design: the spec's `wear` fields with the design's cycle (less what a
/// wear cycle leaves out).
pub fn wear_spec(spec: &CamOptimisationSpec, design: &Value) -> Value {
    let mut w = spec.wear.clone().unwrap_or_else(|| json!({}));
    let mut cycle = design.clone();
    if let Some(o) = cycle.as_object_mut() {
        o.remove("outputs");
        o.remove("profile_angles_deg");
    }
    if let Some(o) = w.as_object_mut() {
        o.insert("cycle".into(), cycle);
    }
    w
}

/// The pointer into the `cam_cycle` (or, for a wear quantity, the `wear`) result of a named
/// quantity or a pointer.
pub fn pointer_of(quantity: &str) -> String {
    match quantity {
        "wear_depth" => "/summary/max_wear_depth".into(),
        q if q.starts_with("wear:") => match &q[5..] {
            r if r.starts_with('/') => r.to_string(),
            name => format!("/summary/{name}"),
        },
        q if q.starts_with('/') => q.to_string(),
        "friction_power" => "/summary/mean_power_loss".into(),
        "no_separation" => "/summary/min_axial_load".into(),
        "no_undercut" => "/summary/min_cam_radius_of_curvature".into(),
        name => format!("/summary/{name}"),
    }
}

/// A quantity's label (a column name): the name, or the pointer with `/` → `.`.
pub fn label_of(quantity: &str) -> String {
    quantity.trim_start_matches('/').replace('/', ".")
}

/// A constraint's label: its quantity's, `@<rpm>rpm` at another speed.
pub fn constraint_label(c: &Constraint) -> String {
    match c.at_rpm {
        Some(r) => format!("{}@{}rpm", label_of(&c.quantity), crate::jobs::units::short_number(r)),
        None => label_of(&c.quantity),
    }
}

/// Where a design sits: a value per variable (a number for continuous ones, the chosen value
/// for categorical ones) and the categorical choices' indices.
#[derive(Debug, Clone, PartialEq)]
pub struct Point {
    /// Normalised coordinates in [0, 1] of the continuous variables, in variable order.
    pub u: Vec<f64>,
    /// Index of the choice of every categorical variable, in variable order.
    pub choice: Vec<usize>,
}

/// What one design gave.
#[derive(Debug, Clone, PartialEq)]
pub struct Measured {
    pub spec: Value,
    /// Values placed, by variable.
    pub values: Vec<Value>,
    /// The cycle at the base speed (`summary` only kept).
    pub summary: Value,
    pub friction_power: Option<f64>,
    /// Objective values, by objective (absent: the cycle lacks it).
    pub objectives: Vec<Option<f64>>,
    /// Constraint values, by constraint.
    pub constraints: Vec<Option<f64>>,
    /// `no_separation` constraints that saw a separation interval (by constraint).
    pub separated: Vec<bool>,
}

/// A design's outcome: measured, or the failure's code and message.
#[derive(Debug, Clone, PartialEq)]
pub enum Outcome {
    Measured(Box<Measured>),
    Failed { code: String, detail: String, values: Vec<Value> },
}

/// Forwards cancellation to the job's observer; progress is the optimisation's.
struct Inner<'a>(&'a dyn Observer);

impl Observer for Inner<'_> {
    fn check(&self) -> Result<(), Interrupt> {
        self.0.check()
    }
}

/// The values of the variables at `p`.
pub fn values_at(spec: &CamOptimisationSpec, p: &Point) -> Vec<Value> {
    let (mut c, mut k) = (0, 0);
    spec.variables
        .iter()
        .map(|v| match (&v.values, v.min, v.max) {
            (Some(vals), _, _) => {
                let x = vals[p.choice[k].min(vals.len() - 1)].clone();
                k += 1;
                x
            }
            (None, Some(lo), Some(hi)) => {
                let x = lo + p.u[c].clamp(0.0, 1.0) * (hi - lo);
                c += 1;
                json!(x)
            }
            _ => Value::Null,
        })
        .collect()
}

/// The base spec with `values` placed (and the tied fields of continuous variables).
pub fn design_spec(spec: &CamOptimisationSpec, values: &[Value]) -> Result<Value, (usize, String)> {
    let mut s = spec.base.clone();
    for (i, (v, x)) in spec.variables.iter().zip(values).enumerate() {
        set_pointer(&mut s, &v.path, x.clone()).map_err(|e| (i, e))?;
        if let Some(x) = x.as_f64() {
            for t in &v.tied {
                set_pointer(&mut s, &t.path, json!(t.offset + t.scale * x)).map_err(|e| (i, e))?;
            }
        }
    }
    Ok(s)
}

/// The distinct constraint speeds, in first-seen order.
pub fn speeds(spec: &CamOptimisationSpec) -> Vec<f64> {
    let mut out: Vec<f64> = Vec::new();
    for r in spec.constraints.iter().filter_map(|c| c.at_rpm) {
        if !out.contains(&r) {
            out.push(r);
        }
    }
    out
}

/// Run one cycle; a failure is data, an interrupt stops the job.
fn cycle(s: &Value, observer: &dyn Observer) -> Result<Result<Value, crate::problem::Problem>, SolveError> {
    run_kind(cycle_kind(), s, observer)
}

/// Run one job of `kind` (a cycle or a wear run); a failure is data, an interrupt stops the job.
fn run_kind(kind: &'static dyn DynKind, s: &Value, observer: &dyn Observer) -> Result<Result<Value, crate::problem::Problem>, SolveError> {
    observer.check()?;
    let prepared = match kind.prepare(s, &Limits::UNLIMITED) {
        Ok(p) => p,
        Err(p) => return Ok(Err(p)),
    };
    match prepared.run(&Inner(observer)) {
        Ok(v) => Ok(Ok(v)),
        Err(SolveError::Interrupted(i)) => Err(SolveError::Interrupted(i)),
        Err(e) => Ok(Err(crate::problem::Problem::from_solve_error(&e))),
    }
}

/// Evaluate the design at `p`: the cycle at the base speed, then at each constraint speed.
pub fn evaluate(spec: &CamOptimisationSpec, p: &Point, observer: &dyn Observer) -> Result<Outcome, SolveError> {
    let values = values_at(spec, p);
    evaluate_values(spec, values, true, observer)
}

/// The baseline: the base spec as it is (the variables' values read from it).
pub fn evaluate_baseline(spec: &CamOptimisationSpec, observer: &dyn Observer) -> Result<Outcome, SolveError> {
    let values = spec.variables.iter().map(|v| spec.base.pointer(&v.path).cloned().unwrap_or(Value::Null)).collect();
    evaluate_values(spec, values, false, observer)
}

/// The baseline's point in the design space, when its values lie in it.
pub fn baseline_point(spec: &CamOptimisationSpec) -> Option<Point> {
    let (mut u, mut choice) = (Vec::new(), Vec::new());
    for v in &spec.variables {
        let x = spec.base.pointer(&v.path)?;
        match (&v.values, v.min, v.max) {
            (Some(vals), _, _) => choice.push(vals.iter().position(|c| c == x)?),
            (None, Some(lo), Some(hi)) => {
                let x = x.as_f64().filter(|x| (lo..=hi).contains(x))?;
                u.push((x - lo) / (hi - lo));
            }
            _ => return None,
        }
    }
    Some(Point { u, choice })
}

/// Evaluate the design with the variables at `values` (placed into the base spec when `place`).
fn evaluate_values(spec: &CamOptimisationSpec, values: Vec<Value>, place: bool, observer: &dyn Observer) -> Result<Outcome, SolveError> {
    let failed = |code: &str, detail: String, values: Vec<Value>| Ok(Outcome::Failed { code: code.into(), detail, values });
    let placed = if place { design_spec(spec, &values) } else { Ok(spec.base.clone()) };
    let s = match placed {
        Ok(s) => s,
        Err((i, e)) => return failed("invalid_spec", format!("variable {i}: {e}"), values),
    };
    let main = match cycle(&s, observer)? {
        Ok(r) => r,
        Err(p) if p.code == "cam_undercut" => {
            let kept = values.clone();
            return Ok(undercut_design(spec, s, values).unwrap_or(Outcome::Failed { code: p.code, detail: p.detail, values: kept }));
        }
        Err(p) => return failed(&p.code, p.detail, values),
    };
    let mut at_speed: Vec<(f64, Option<Value>)> = Vec::new();
    for rpm in speeds(spec) {
        let mut t = s.clone();
        let _ = set_pointer(&mut t, "/operation/speed_rpm", json!(rpm));
        let only_separation = spec.constraints.iter().filter(|c| c.at_rpm == Some(rpm)).all(|c| c.quantity == "no_separation");
        if only_separation {
            let _ = set_pointer(&mut t, "/outputs", json!(["loads"]));
        }
        at_speed.push((rpm, cycle(&t, observer)?.ok()));
    }
    let wear = if needs_wear(spec) { run_kind(wear_kind(), &wear_spec(spec, &s), observer)?.ok() } else { None };
    let get = |r: &Value, q: &str| {
        let r = if is_wear(q) { wear.as_ref()? } else { r };
        r.pointer(&pointer_of(q)).and_then(Value::as_f64)
    };
    let objectives = spec.objectives.iter().map(|o| get(&main, &o.quantity)).collect();
    let mut constraints = Vec::new();
    let mut separated = Vec::new();
    for c in &spec.constraints {
        let r = match c.at_rpm {
            None => Some(&main),
            Some(rpm) => at_speed.iter().find(|(s, _)| *s == rpm).and_then(|(_, r)| r.as_ref()),
        };
        constraints.push(r.and_then(|r| get(r, &c.quantity)));
        let apart = c.quantity == "no_separation"
            && r.is_some_and(|r| r.pointer("/summary/separation_duration").and_then(Value::as_f64).is_some_and(|d| d > 0.0));
        separated.push(apart);
    }
    let friction_power = main.pointer("/summary/mean_power_loss").and_then(Value::as_f64);
    let summary = main.get("summary").cloned().unwrap_or(json!({}));
    Ok(Outcome::Measured(Box::new(Measured { spec: s, values, summary, friction_power, objectives, constraints, separated })))
}

/// A design whose cam undercuts (the cycle refuses it with `cam_undercut`): measured from its
/// profile alone, with the `no_undercut` constraints at the signed undercut margin (zero or
/// negative: how far the cam is from manufacturable, m) and every other quantity missing, so
/// that the design is infeasible with a named margin rather than a lost evaluation. `None`
/// without a `no_undercut` constraint (the design then stays a failure).
fn undercut_design(spec: &CamOptimisationSpec, s: Value, values: Vec<Value>) -> Option<Outcome> {
    if !spec.constraints.iter().any(|c| c.quantity == "no_undercut") {
        return None;
    }
    let cam: crate::jobs::kinds::cam_cycle::CamCycleSpec = serde_json::from_value(s.clone()).ok()?;
    let margin = cam.undercut_margin()?;
    let constraints = spec.constraints.iter().map(|c| (c.quantity == "no_undercut").then_some(margin)).collect();
    Some(Outcome::Measured(Box::new(Measured {
        spec: s,
        values,
        summary: json!({"min_cam_radius_of_curvature": margin, "undercut": true}),
        friction_power: None,
        objectives: vec![None; spec.objectives.len()],
        constraints,
        separated: vec![false; spec.constraints.len()],
    })))
}

/// A constraint's limits made absolute (`relative` ones on the baseline's value) and its sense.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Limit {
    pub min: Option<f64>,
    pub max: Option<f64>,
    /// Scale of a violation (the limit's magnitude, or the baseline's value, or 1).
    pub scale: f64,
}

/// The constraints' absolute limits from the baseline's values.
pub fn limits(spec: &CamOptimisationSpec, baseline: &Measured) -> Result<Vec<Limit>, SolveError> {
    let mut out = Vec::new();
    for (i, (c, b)) in spec.constraints.iter().zip(&baseline.constraints).enumerate() {
        let special = matches!(c.quantity.as_str(), "no_separation" | "no_undercut");
        let (mut min, mut max) = (c.min, c.max);
        if special && min.is_none() {
            min = Some(0.0);
        }
        if c.relative {
            let b = b.ok_or_else(|| SolveError::invalid(format!("/constraints/{i}/relative"), "the baseline design lacks this quantity, so a relative limit has no value"))?;
            min = min.map(|f| f * b);
            max = max.map(|f| f * b);
        }
        let limit = min.or(max).unwrap_or(0.0).abs();
        let base = b.map(f64::abs).unwrap_or(0.0);
        let scale = if limit > 0.0 { limit } else if base > 0.0 { base } else { 1.0 };
        out.push(Limit { min, max, scale });
    }
    Ok(out)
}

/// Score and constraints of a measured design.
#[derive(Debug, Clone, PartialEq)]
pub struct Judged {
    pub score: f64,
    /// Per constraint: (limit, sense, margin, satisfied).
    pub margins: Vec<(f64, f64, Option<f64>, bool)>,
    pub feasible: bool,
    /// Sum of the constraints' violations over their scales.
    pub violation: f64,
}

impl Judged {
    /// What Nelder–Mead minimises: the score when feasible, a penalty above every feasible score
    /// otherwise (the violation still points the way back).
    pub fn penalised(&self) -> f64 {
        if self.feasible {
            self.score
        } else {
            1e3 + 1e2 * self.violation
        }
    }
}

/// The weighted score of objective values against the baseline's.
pub fn score(spec: &CamOptimisationSpec, values: &[Option<f64>], baseline: &[Option<f64>]) -> f64 {
    let total: f64 = spec.objectives.iter().map(|o| o.weight).sum::<f64>().max(f64::MIN_POSITIVE);
    let mut s = 0.0;
    for ((o, v), b) in spec.objectives.iter().zip(values).zip(baseline) {
        let scale = b.map(f64::abs).filter(|b| *b > 0.0).unwrap_or(1.0);
        let sign = if o.goal == Goal::Maximise { -1.0 } else { 1.0 };
        // A missing objective counts as far worse than the baseline.
        let x = v.map_or(10.0 * sign, |v| v / scale);
        s += o.weight * sign * x;
    }
    s / total
}

/// Judge a measured design against the constraints' limits.
pub fn judge(spec: &CamOptimisationSpec, m: &Measured, baseline: &Measured, limits: &[Limit]) -> Judged {
    let score = score(spec, &m.objectives, &baseline.objectives);
    let mut margins = Vec::new();
    let (mut feasible, mut violation) = (true, 0.0);
    for ((l, v), apart) in limits.iter().zip(&m.constraints).zip(&m.separated) {
        let (limit, sense) = match (l.min, l.max) {
            (Some(lo), Some(hi)) => match v {
                Some(x) if hi - x < x - lo => (hi, -1.0),
                _ => (lo, 1.0),
            },
            (Some(lo), None) => (lo, 1.0),
            (None, Some(hi)) => (hi, -1.0),
            (None, None) => (0.0, 1.0),
        };
        let margin = v.map(|x| match (l.min, l.max) {
            (Some(lo), Some(hi)) => (x - lo).min(hi - x),
            _ => sense * (x - limit),
        } + 0.0); // −0.0 (at the limit) reads as 0
        let ok = margin.is_some_and(|g| g >= 0.0) && !apart;
        if !ok {
            feasible = false;
            violation += margin.map_or(1.0, |g| (-g).max(0.0) / l.scale) + if *apart { 0.1 } else { 0.0 };
        }
        margins.push((limit, sense, margin, ok));
    }
    Judged { score, margins, feasible, violation }
}
