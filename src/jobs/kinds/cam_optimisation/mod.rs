//! `cam_optimisation`: design of a cam–follower pair over its cycle. Design variables are JSON
//! pointers into a base `cam_cycle` spec (continuous with bounds, or categorical: the lift law),
//! objectives and constraints named quantities or pointers into the cycle's result; the search is
//! a seeded Latin hypercube and Nelder–Mead from its best designs, every design a `cam_cycle`
//! run on the worker pool. Reports the baseline, the best design with its constraints' margins,
//! every design, and the Pareto front of the first two objectives.
//!
//! Files: `spec.rs` (the request), `result.rs` (the answer), `evaluate.rs` (one design),
//! `search.rs` (the search); this file is the kind: example, validation, cost, the result.

mod evaluate;
mod report;
mod result;
mod search;
mod spec;

pub use result::*;
pub use spec::*;

use crate::jobs::cost::Cost;
use crate::jobs::kind::{Kind, Limits, Validation};
use crate::physics::{Observer, SolveError};
use serde_json::{json, Value};

pub struct CamOptimisation;

/// Named quantities beside the cycle's summary numbers.
const NAMED: &[&str] = &["friction_power", "wear_depth", "no_separation", "no_undercut"];
/// Named constraints (not objectives).
const SPECIAL: &[&str] = &["no_separation", "no_undercut"];

impl Kind for CamOptimisation {
    const NAME: &'static str = "cam_optimisation";
    const SOLVER_VERSION: &'static str = "cam_optimisation-5";
    const DESCRIPTION: &'static str = "Cam design over the cycle: design variables are JSON pointers into a base \
        cam_cycle spec (bounds or listed values), objectives and constraints are cycle quantities (friction power, \
        film, Hertz, separation up to a speed, …); a seeded Latin hypercube then Nelder–Mead, every design a cam_cycle \
        run in parallel; the best design, its constraint margins, every design and the Pareto front.";
    const TABLES: &'static [&'static str] = &["designs"];
    const KEY_FIGURES: &'static [&'static str] =
        &["/best/friction_power", "/baseline/friction_power", "/friction_power_change", "/best/score", "/feasible_count", "/evaluations"];
    type Spec = CamOptimisationSpec;
    type Output = CamOptimisationResult;

    fn solver_version() -> &'static str {
        static V: std::sync::LazyLock<String> =
            std::sync::LazyLock::new(|| format!("{}({},{})", CamOptimisation::SOLVER_VERSION, evaluate::cycle_kind().solver_version(), evaluate::wear_kind().solver_version()));
        V.as_str()
    }

    fn example() -> Value {
        let mut base = <crate::jobs::kinds::cam_cycle::CamCycle as Kind>::example();
        base["fidelity"] = json!("fast");
        base["angles"] = json!(180);
        json!({
            "base": base,
            "variables": [
                {"path": "/load/spring_preload", "min": 200.0, "max": 400.0},
                {"path": "/cam/profile/law", "values": ["cycloidal", "polynomial_345"]}
            ],
            "objectives": [{"quantity": "friction_power"}, {"quantity": "max_hertz_pressure"}],
            "constraints": [
                {"quantity": "no_separation", "at_rpm": 3300.0},
                {"quantity": "max_hertz_pressure", "max": 1.0, "relative": true}
            ],
            "search": {"samples": 6, "iterations": 6, "starts": 2, "seed": 1}
        })
    }

    fn validate(spec: &CamOptimisationSpec, limits: &Limits, v: &mut Validation) {
        validate_spec(spec, limits, v);
    }

    fn cost(spec: &CamOptimisationSpec) -> Cost {
        // Every planned design: one cycle at the base speed and one per constraint speed.
        let one = match evaluate::cycle_kind().prepare(&spec.base, &Limits::UNLIMITED) {
            Ok(p) => p.cost,
            Err(_) => return Cost::new(0.0, 0.0),
        };
        let n = search::planned(spec);
        let cycles = n.saturating_mul(1 + evaluate::speeds(spec).len());
        let wear = match &spec.wear {
            Some(_) if evaluate::needs_wear(spec) => evaluate::wear_kind()
                .prepare(&evaluate::wear_spec(spec, &spec.base), &Limits::UNLIMITED)
                .map_or(Cost::new(0.0, 0.0), |p| p.cost),
            _ => Cost::new(0.0, 0.0),
        };
        let workers = std::thread::available_parallelism().map_or(1, |p| p.get()).min(n.max(1)) as f64;
        let seconds = cycles as f64 * one.cpu_seconds() + n as f64 * wear.cpu_seconds();
        Cost::new(crate::jobs::cost::JOB_OVERHEAD_S + seconds, workers * one.memory_bytes().max(wear.memory_bytes()))
            .work_at("/search", format!("{n} designs, {cycles} cam cycles"))
            .memory_at("/base", format!("{workers} cam cycles at once"))
    }

    fn solve(spec: &CamOptimisationSpec, observer: &dyn Observer) -> Result<CamOptimisationResult, SolveError> {
        let searched = search::search(spec, observer)?;
        report::result(spec, searched)
    }
}

/// Checks of a spec: the base is a valid `cam_cycle` spec, every variable's pointer and range
/// gives valid designs at its bounds and choices, every quantity is a documented number of the
/// cycle's result, and the planned designs are within the server's limit.
fn validate_spec(spec: &CamOptimisationSpec, limits: &Limits, v: &mut Validation) {
    let kind = evaluate::cycle_kind();
    if let Err(p) = kind.prepare(&spec.base, limits) {
        v.absorb(&p, |path| format!("/base{path}"));
        return;
    }
    v.items("/variables", spec.variables.len(), 1, Some(12));
    for (i, var) in spec.variables.iter().enumerate() {
        let at = format!("/variables/{i}");
        v.check(var.path.starts_with('/'), &format!("{at}/path"), "must be a JSON pointer starting with '/' into the base cam_cycle spec");
        match (&var.values, var.min, var.max) {
            (Some(vals), None, None) => {
                v.items(&format!("{at}/values"), vals.len(), 1, Some(32));
                v.check(var.tied.is_empty(), &format!("{at}/tied"), "only a continuous variable (min, max) can carry tied fields");
            }
            (None, Some(lo), Some(hi)) => {
                v.check(lo.is_finite() && hi.is_finite() && lo < hi, &format!("{at}/max"), format!("needs finite bounds with min < max (min {lo}, max {hi})"));
            }
            _ => {
                v.error(&at, "needs exactly one of `values` and both `min` and `max`");
            }
        }
        v.items(&format!("{at}/tied"), var.tied.len(), 0, Some(4));
        for (j, t) in var.tied.iter().enumerate() {
            v.check(t.path.starts_with('/'), &format!("{at}/tied/{j}/path"), "must be a JSON pointer starting with '/'");
            v.check(t.scale.is_finite() && t.offset.is_finite(), &format!("{at}/tied/{j}"), "scale and offset must be finite");
        }
    }
    v.items("/objectives", spec.objectives.len(), 1, Some(4));
    for (i, o) in spec.objectives.iter().enumerate() {
        check_quantity(v, &format!("/objectives/{i}/quantity"), &o.quantity, false);
        v.non_negative(&format!("/objectives/{i}/weight"), o.weight);
    }
    v.check(spec.objectives.iter().map(|o| o.weight).sum::<f64>() > 0.0, "/objectives", "at least one weight must be > 0");
    v.items("/constraints", spec.constraints.len(), 0, Some(16));
    for (i, c) in spec.constraints.iter().enumerate() {
        validate_constraint(v, i, c);
    }
    let s = &spec.search;
    v.count_in_range("/search/samples", s.samples, 0, 1000);
    v.count_in_range("/search/iterations", s.iterations, 0, 1000);
    v.count_in_range("/search/starts", s.starts, 1, 8);
    v.limit("/search", search::planned(spec), limits.max_evaluations, "the number of designs");
    validate_wear(spec, limits, v);
    if v.is_ok() {
        validate_designs(spec, limits, v);
    }
}

/// A wear quantity needs `wear`; the base's wear run must be a valid `wear` spec.
fn validate_wear(spec: &CamOptimisationSpec, limits: &Limits, v: &mut Validation) {
    let needed = evaluate::needs_wear(spec);
    match (&spec.wear, needed) {
        (None, true) => {
            v.error("/wear", "a wear quantity needs the wear run's fields (hours, wear_coefficient, …)");
        }
        (Some(w), _) => {
            v.check(w.is_object() && w.get("cycle").is_none(), "/wear", "must be a wear spec without `cycle` (the design's cycle is put there)");
            if v.is_ok() {
                if let Err(p) = evaluate::wear_kind().prepare(&evaluate::wear_spec(spec, &spec.base), limits) {
                    v.absorb(&p, |path| match path.strip_prefix("/cycle") {
                        Some(rest) => format!("/base{rest}"),
                        None => format!("/wear{path}"),
                    });
                }
            }
        }
        (None, false) => {}
    }
}

/// A quantity must be a named one or a documented number of the `cam_cycle` result.
fn check_quantity(v: &mut Validation, at: &str, q: &str, constraint: bool) {
    let special = SPECIAL.contains(&q);
    if special && !constraint {
        v.error(at, format!("`{q}` is a constraint, not an objective"));
        return;
    }
    let pointer = evaluate::pointer_of(q);
    let known = crate::jobs::units::unit_at(evaluate::units_of(q), &pointer).is_some();
    let summary: Vec<String> = evaluate::cycle_kind()
        .result_units()
        .keys()
        .filter_map(|k| k.strip_prefix("/summary/").map(str::to_string))
        // Scalars only (`separation` is a list of intervals).
        .filter(|k| !k.contains('/') && *k != "separation")
        .collect();
    v.check(
        known || NAMED.contains(&q),
        at,
        format!(
            "unknown quantity `{q}` (read as {pointer}): give a JSON pointer to a number of the cam_cycle result, `wear:` and a number of the wear result, or one of {}, {}",
            NAMED.join(", "),
            summary.join(", ")
        ),
    );
}

fn validate_constraint(v: &mut Validation, i: usize, c: &Constraint) {
    let at = format!("/constraints/{i}");
    check_quantity(v, &format!("{at}/quantity"), &c.quantity, true);
    let special = SPECIAL.contains(&c.quantity.as_str());
    v.check(special || c.min.is_some() || c.max.is_some(), &at, "needs `min` or `max` (or both)");
    for (name, x) in [("min", c.min), ("max", c.max)] {
        if let Some(x) = x {
            v.check(x.is_finite(), &format!("{at}/{name}"), "must be a finite number");
        }
    }
    if let (Some(lo), Some(hi)) = (c.min, c.max) {
        v.check(lo <= hi, &format!("{at}/max"), "must be >= min");
    }
    if let Some(r) = c.at_rpm {
        v.quantity(&format!("{at}/at_rpm"), r, crate::jobs::quantity::SPEED_RPM);
    }
    v.check(!(evaluate::is_wear(&c.quantity) && c.at_rpm.is_some()), &format!("{at}/at_rpm"), "a wear quantity runs at the base speed");
    v.check(c.quantity != "no_separation" || c.at_rpm.is_some(), &format!("{at}/at_rpm"), "no_separation needs the speed to check it at (rpm): the speed limit times a margin");
}

/// The designs at the variables' bounds and choices must be valid `cam_cycle` specs: each
/// distinct problem reported once, at the variable that caused it.
fn validate_designs(spec: &CamOptimisationSpec, limits: &Limits, v: &mut Validation) {
    let kind = evaluate::cycle_kind();
    let mut seen = std::collections::HashSet::new();
    let n = spec.variables.len();
    let corners: Vec<(usize, Vec<Value>)> = spec
        .variables
        .iter()
        .enumerate()
        .flat_map(|(i, var)| {
            let picks: Vec<Value> = match (&var.values, var.min, var.max) {
                (Some(vals), _, _) => vals.clone(),
                (None, Some(lo), Some(hi)) => vec![json!(lo), json!(hi)],
                _ => Vec::new(),
            };
            picks.into_iter().map(move |x| (i, x))
        })
        .map(|(i, x)| {
            let mut values: Vec<Value> = spec.variables.iter().map(|w| spec.base.pointer(&w.path).cloned().unwrap_or(Value::Null)).collect();
            values[i] = x;
            (i, values)
        })
        .collect();
    for (i, values) in corners {
        let mut values = values;
        // Variables absent from the base take their lower bound or first choice.
        for (j, w) in spec.variables.iter().enumerate().take(n) {
            if values[j].is_null() {
                values[j] = w.values.as_ref().and_then(|c| c.first().cloned()).or(w.min.map(|m| json!(m))).unwrap_or(Value::Null);
            }
        }
        let s = match evaluate::design_spec(spec, &values) {
            Ok(s) => s,
            Err((j, e)) => {
                v.error(&format!("/variables/{j}/path"), e);
                return;
            }
        };
        if let Err(problem) = kind.prepare(&s, limits) {
            let key = serde_json::to_string(&problem.errors).unwrap_or_default();
            if seen.insert(key) {
                let mut p = problem.clone();
                for e in &mut p.errors {
                    e.message = format!("{} (design with {} = {})", e.message, spec.variables[i].path, values[i]);
                }
                v.absorb(&p, |path| match spec.variables.iter().position(|w| w.path == path || w.tied.iter().any(|t| t.path == path)) {
                    Some(j) => format!("/variables/{j}"),
                    None => format!("/base{path}"),
                });
            }
        }
    }
}
