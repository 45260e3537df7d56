//! `sweep`: one base spec of any kind, one or more parameters varied (JSON pointer + values or a
//! linspace), every case solved in parallel on the worker pool, and a table of chosen result
//! quantities per case. A failing case is data (its error code is in its row), not a failed sweep.

use crate::jobs::cost::Cost;
use crate::jobs::kind::{Kind, Limits, Validation};
use crate::physics::{Interrupt, Observer, SolveError};
use crate::problem::Problem;
use rayon::prelude::*;
use serde::{Deserialize, Serialize};
use serde_json::{json, Map, Value};
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::LazyLock;
use utoipa::ToSchema;

pub struct Sweep;

/// Evenly spaced values from `start` to `stop` inclusive.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct Linspace {
    pub start: f64,
    pub stop: f64,
    /// Number of values (≥ 2).
    pub num: usize,
}

/// One varied parameter: where in the base spec, and which values.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct Parameter {
    /// JSON pointer (RFC 6901) into the base spec, e.g. `/lubricant/viscosity`. Missing
    /// intermediate objects are created.
    #[schema(example = "/lubricant/viscosity")]
    pub path: String,
    /// The values (any JSON: numbers, strings, objects). Exactly one of `values`, `linspace`.
    /// Items are any JSON value (the schema `{}`): `[0.1, 0.2]`, `["cycloidal", "polynomial_345"]`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub values: Option<Vec<Value>>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub linspace: Option<Linspace>,
}

/// How the parameters' values combine into cases.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize, ToSchema)]
#[serde(rename_all = "snake_case")]
pub enum Combine {
    /// Every combination (cartesian product; the first parameter varies slowest).
    #[default]
    Grid,
    /// The i-th values of all parameters together (equal lengths).
    Zip,
}

/// Spec of a `sweep` job.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct SweepSpec {
    /// Kind of every case (any kind but `sweep`).
    #[schema(example = "hertz")]
    pub kind: String,
    /// The spec every case starts from.
    #[schema(value_type = Object)]
    pub base: Value,
    /// The varied parameters (1–8).
    pub parameters: Vec<Parameter>,
    #[serde(default)]
    pub combine: Combine,
    /// JSON pointers into each case's result to tabulate, e.g. `/summary/min_film`. Default:
    /// every number in the result's `summary` object, or every top-level number if it has none.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub quantities: Vec<String>,
}

/// Result of a `sweep` job.
#[derive(Debug, Clone, PartialEq, Serialize, ToSchema)]
pub struct SweepResult {
    pub kind: String,
    /// Column names of `cases`: `case`, the parameters (pointer with `/` → `.`), `status`,
    /// `error_code`, then the quantities (a value of a per-angle series is named by its angle:
    /// `/series/slide_roll_ratio/200` of a 720-angle cycle is `slide_roll_ratio@100deg`).
    pub columns: Vec<String>,
    /// The unit of every dimensional column (`1` for pure numbers), from the case kind's spec
    /// and result units (`GET /v1/kinds`).
    pub units: std::collections::BTreeMap<String, String>,
    /// One row per case: the parameter values, `status` (`succeeded` / `failed`), the
    /// quantities (absent when the case failed or the result lacks them) and `error_code`. A
    /// sweep whose cases ran as jobs of their own (cases above `--fan-out-min-case-seconds`, on
    /// every instance sharing the store) adds to each row `instance` (the instance that solved the
    /// case) and `reused` (an identical case solved before was reused).
    #[schema(value_type = Vec<Object>)]
    pub cases: Vec<Map<String, Value>>,
    pub succeeded: usize,
    pub failed: usize,
}

fn column(pointer: &str) -> String {
    pointer.trim_start_matches('/').replace('/', ".")
}

/// A quantity's column name: a value of a per-angle series by its angle
/// (`slide_roll_ratio@100deg`, read from the first result's `angle_deg` beside it), otherwise
/// the pointer with `/` → `.`.
fn quantity_column(pointer: &str, first: Option<&Value>) -> String {
    let Some((parent, index)) = pointer.rsplit_once('/') else { return column(pointer) };
    let (Ok(i), Some((table, name))) = (index.parse::<usize>(), parent.rsplit_once('/')) else { return column(pointer) };
    let angle = first.and_then(|r| r.pointer(&format!("{table}/angle_deg/{i}"))).and_then(Value::as_f64);
    match angle {
        Some(a) => format!("{name}@{}deg", crate::jobs::units::short_number(a)),
        None => column(pointer),
    }
}

/// The units of the sweep's columns: parameters from the case kind's spec units, quantities
/// from its result units (a series value has its series' unit).
fn column_units(k: &dyn crate::jobs::kind::DynKind, spec: &SweepSpec, quantities: &[String], names: &[String]) -> std::collections::BTreeMap<String, String> {
    let spec_units = k.spec_units();
    let result_units = k.result_units();
    let mut out = std::collections::BTreeMap::new();
    for p in &spec.parameters {
        if let Some(u) = crate::jobs::units::unit_at(spec_units, &p.path) {
            out.insert(column(&p.path), u.to_string());
        }
    }
    for (q, name) in quantities.iter().zip(names) {
        if let Some(u) = crate::jobs::units::unit_at(result_units, q) {
            out.insert(name.clone(), u.to_string());
        }
    }
    out
}

impl Parameter {
    /// Number of values, counted without building them (a hostile `num` must not allocate).
    fn len(&self) -> usize {
        match (&self.values, &self.linspace) {
            (Some(v), _) => v.len(),
            (None, Some(l)) => l.num,
            (None, None) => 0,
        }
    }

    fn values(&self) -> Vec<Value> {
        match (&self.values, &self.linspace) {
            (Some(v), _) => v.clone(),
            (None, Some(l)) => (0..l.num)
                .map(|i| {
                    let t = if l.num > 1 { i as f64 / (l.num - 1) as f64 } else { 0.0 };
                    // Exact at both ends.
                    json!(l.start * (1.0 - t) + l.stop * t)
                })
                .collect(),
            (None, None) => Vec::new(),
        }
    }
}

/// Set `value` at JSON pointer `ptr` in `target`, creating missing objects on the way.
pub fn set_pointer(target: &mut Value, ptr: &str, value: Value) -> Result<(), String> {
    if ptr.is_empty() || !ptr.starts_with('/') {
        return Err("must be a JSON pointer starting with '/'".into());
    }
    let tokens: Vec<String> = ptr[1..].split('/').map(|t| t.replace("~1", "/").replace("~0", "~")).collect();
    let mut cur = target;
    for (i, tok) in tokens.iter().enumerate() {
        let last = i + 1 == tokens.len();
        cur = match cur {
            Value::Object(map) => {
                if last {
                    map.insert(tok.clone(), value);
                    return Ok(());
                }
                map.entry(tok.clone()).or_insert_with(|| Value::Object(Map::new()))
            }
            Value::Array(items) => {
                let idx: usize = tok.parse().map_err(|_| format!("'{tok}' is not an array index"))?;
                let len = items.len();
                let slot = items.get_mut(idx).ok_or_else(|| format!("index {idx} is past the array's end ({len})"))?;
                if last {
                    *slot = value;
                    return Ok(());
                }
                slot
            }
            _ => return Err(format!("'{tok}' goes through a value that is not an object or array")),
        };
    }
    Ok(())
}

/// The cases: for each, the (parameter index, value) list.
pub fn cases(spec: &SweepSpec) -> Vec<Vec<Value>> {
    let lists: Vec<Vec<Value>> = spec.parameters.iter().map(Parameter::values).collect();
    if lists.is_empty() || lists.iter().any(Vec::is_empty) {
        return Vec::new();
    }
    match spec.combine {
        Combine::Zip => (0..lists[0].len()).map(|i| lists.iter().map(|l| l[i].clone()).collect()).collect(),
        Combine::Grid => {
            let mut out: Vec<Vec<Value>> = vec![Vec::new()];
            for list in &lists {
                out = out.into_iter().flat_map(|prefix| list.iter().map(move |v| {
                    let mut p = prefix.clone();
                    p.push(v.clone());
                    p
                })).collect();
            }
            out
        }
    }
}

pub fn case_count(spec: &SweepSpec) -> usize {
    let lens: Vec<usize> = spec.parameters.iter().map(Parameter::len).collect();
    match spec.combine {
        Combine::Zip => lens.first().copied().unwrap_or(0),
        Combine::Grid => lens.iter().fold(1usize, |a, &n| a.saturating_mul(n)),
    }
}

fn case_spec(spec: &SweepSpec, values: &[Value]) -> Result<Value, (usize, String)> {
    let mut s = spec.base.clone();
    for (i, (p, v)) in spec.parameters.iter().zip(values).enumerate() {
        set_pointer(&mut s, &p.path, v.clone()).map_err(|e| (i, e))?;
    }
    Ok(s)
}

static VERSION: LazyLock<String> = LazyLock::new(|| {
    let inner: Vec<String> =
        super::CASE_KINDS.iter().map(|k| k.solver_version().to_string()).collect();
    format!("{}({})", Sweep::SOLVER_VERSION, inner.join(","))
});

/// Forwards cancellation; progress is the fraction of cases done.
struct CaseObserver<'a> {
    outer: &'a dyn Observer,
}

impl Observer for CaseObserver<'_> {
    fn check(&self) -> Result<(), Interrupt> {
        self.outer.check()
    }
}

impl Kind for Sweep {
    const NAME: &'static str = "sweep";
    const SOLVER_VERSION: &'static str = "sweep-2";
    const DESCRIPTION: &'static str = "Run one base spec of any kind over varied parameters \
        (JSON pointer + values or linspace, grid or zip), cases in parallel; a table of chosen \
        result quantities per case.";
    const TABLES: &'static [&'static str] = &["cases"];
    type Spec = SweepSpec;
    type Output = SweepResult;

    fn solver_version() -> &'static str {
        VERSION.as_str()
    }

    fn example() -> Value {
        json!({
            "kind": "hertz",
            "base": {"contact": "line", "load": 5000.0, "length": 0.014,
                     "body_1": {"shape": "cylinder", "radius": 0.0255},
                     "body_2": {"shape": "cylinder", "radius": 0.02}},
            "parameters": [{"path": "/load", "linspace": {"start": 1000.0, "stop": 10000.0, "num": 10}}],
            "quantities": ["/max_pressure", "/half_width", "/max_shear/value"]
        })
    }

    fn bound_examples() -> Vec<Value> {
        // Listed values instead of a linspace.
        vec![crate::jobs::kind::example_with::<Self>(json!({"parameters": [{"path": "/load", "values": [1000.0, 5000.0]}]}))]
    }

    fn validate(spec: &SweepSpec, limits: &Limits, v: &mut Validation) {
        let inner = super::case_kind(&spec.kind);
        match inner {
            None => {
                let names: Vec<&str> = super::CASE_KINDS.iter().map(|k| k.name()).collect();
                let message = if spec.kind == Self::NAME {
                    "a sweep cannot run sweeps".to_string()
                } else {
                    format!("unknown kind; kinds a sweep can run: {}", names.join(", "))
                };
                v.error("/kind", message);
            }
            Some(_) => {}
        }
        v.items("/parameters", spec.parameters.len(), 1, Some(8));
        for (i, p) in spec.parameters.iter().enumerate() {
            let at = format!("/parameters/{i}");
            v.check(p.path.starts_with('/'), &format!("{at}/path"), "must be a JSON pointer starting with '/'");
            match (&p.values, &p.linspace) {
                (Some(vals), None) => {
                    v.items(&format!("{at}/values"), vals.len(), 1, None);
                }
                (None, Some(l)) => {
                    v.check(l.start.is_finite() && l.stop.is_finite(), &format!("{at}/linspace"), "start and stop must be finite");
                    v.count_in_range(&format!("{at}/linspace/num"), l.num, 2, limits.max_sweep_cases);
                }
                _ => {
                    v.error(&at, "needs exactly one of `values` and `linspace`");
                }
            }
        }
        if spec.combine == Combine::Zip {
            let lens: Vec<usize> = spec.parameters.iter().map(Parameter::len).collect();
            v.check(lens.windows(2).all(|w| w[0] == w[1]), "/parameters", "`zip` needs the same number of values for every parameter");
        }
        for (i, q) in spec.quantities.iter().enumerate() {
            v.check(q.starts_with('/'), &format!("/quantities/{i}"), "must be a JSON pointer starting with '/'");
        }
        let n = case_count(spec);
        v.limit("/parameters", n, limits.max_sweep_cases, "the number of cases");
        let (Some(k), true) = (inner, v.is_ok()) else { return };
        if k.name() == Self::NAME {
            return;
        }
        // Every case must be a valid spec of its kind; report each distinct problem once.
        let mut seen = std::collections::HashSet::new();
        for values in cases(spec) {
            let s = match case_spec(spec, &values) {
                Ok(s) => s,
                Err((i, e)) => {
                    v.error(&format!("/parameters/{i}/path"), e);
                    return;
                }
            };
            if let Err(problem) = k.prepare(&s, limits) {
                let key = serde_json::to_string(&problem.errors).unwrap_or_default();
                if seen.insert(key) {
                    let label: Vec<String> =
                        spec.parameters.iter().zip(&values).map(|(p, v)| format!("{} = {v}", p.path)).collect();
                    let mut p = problem.clone();
                    for e in &mut p.errors {
                        e.message = format!("{} (case {})", e.message, label.join(", "));
                    }
                    v.absorb(&p, |path| {
                        match spec.parameters.iter().position(|q| q.path == path) {
                            Some(i) => format!("/parameters/{i}"),
                            None => format!("/base{path}"),
                        }
                    });
                }
            }
        }
    }

    fn cost(spec: &SweepSpec) -> Cost {
        // The sum of the cases' work; memory: the largest case on every worker thread at once.
        let Some(k) = super::case_kind(&spec.kind) else { return Cost::new(0.0, 0.0) };
        let (mut seconds, mut largest, mut n) = (crate::jobs::cost::JOB_OVERHEAD_S, 0.0_f64, 0usize);
        for values in cases(spec) {
            let Ok(s) = case_spec(spec, &values) else { continue };
            if let Ok(p) = k.prepare(&s, &Limits::UNLIMITED) {
                seconds += p.cost.cpu_seconds();
                largest = largest.max(p.cost.memory_bytes());
                n += 1;
            }
        }
        let workers = std::thread::available_parallelism().map_or(1, |p| p.get()).min(n.max(1)) as f64;
        Cost::new(seconds, workers * largest)
            .work_at("/parameters", format!("{n} cases of {}", spec.kind))
            .memory_at("/base", format!("{} cases of {} at once", workers, spec.kind))
    }

    fn solve(spec: &SweepSpec, observer: &dyn Observer) -> Result<SweepResult, SolveError> {
        let k = super::case_kind(&spec.kind).ok_or_else(|| SolveError::invalid("/kind", "unknown kind"))?;
        let all = cases(spec);
        let total = all.len();
        let done = AtomicUsize::new(0);
        let outcomes: Vec<Result<Value, Problem>> = all
            .par_iter()
            .map(|values| {
                observer.check().map_err(|i| Problem::from_solve_error(&SolveError::Interrupted(i)))?;
                let s = case_spec(spec, values).map_err(|(_, e)| Problem::from_solve_error(&SolveError::invalid("/parameters", e)))?;
                // The server's limits were enforced on every case at submission.
                let prepared = k.prepare(&s, &Limits::UNLIMITED)?;
                let out = prepared.run(&CaseObserver { outer: observer }).map_err(|e| Problem::from_solve_error(&e));
                let n = done.fetch_add(1, Ordering::Relaxed) + 1;
                observer.progress(n as f64 / total.max(1) as f64, "cases");
                out
            })
            .collect();
        // A cancel or shutdown stops the sweep as a whole.
        observer.check()?;
        Ok(assemble(spec, k, &all, &outcomes))
    }
}

/// The case specs of a sweep (the base with each case's values set), in case order.
pub fn case_specs(spec: &SweepSpec) -> Result<Vec<Value>, String> {
    cases(spec).iter().map(|values| case_spec(spec, values).map_err(|(_, e)| e)).collect()
}

/// The sweep's table from its cases' outcomes (results or problems, in case order): shared by the
/// in-process solve and the assembly of a fanned-out sweep, so that both give the same result.
pub fn assemble(spec: &SweepSpec, k: &dyn crate::jobs::kind::DynKind, all: &[Vec<Value>], outcomes: &[Result<Value, Problem>]) -> SweepResult {
    let first = outcomes.iter().find_map(|o| o.as_ref().ok());
    let (quantities, names) = quantities(spec, first);
    let values: Vec<Result<Vec<Option<Value>>, Problem>> =
        outcomes.iter().map(|o| o.as_ref().map(|r| extract(r, &quantities)).map_err(Clone::clone)).collect();
    table(spec, k, all, &quantities, &names, &values)
}

/// The quantities a sweep tabulates (pointers) and their column names: explicit, or every number
/// of the first successful result's summary (`first`: that result).
pub fn quantities(spec: &SweepSpec, first: Option<&Value>) -> (Vec<String>, Vec<String>) {
    let quantities: Vec<String> = if !spec.quantities.is_empty() {
        spec.quantities.clone()
    } else {
        first
            .map(|r| match r.get("summary").and_then(Value::as_object) {
                Some(summary) => summary.iter().filter(|(_, v)| v.is_number()).map(|(k, _)| format!("/summary/{k}")).collect(),
                None => r.as_object().map(|o| o.iter().filter(|(_, v)| v.is_number()).map(|(k, _)| format!("/{k}")).collect()).unwrap_or_default(),
            })
            .unwrap_or_default()
    };
    let names: Vec<String> = quantities.iter().map(|q| quantity_column(q, first)).collect();
    (quantities, names)
}

/// A case result's values of the quantities (`None`: absent or null): all of a result a sweep's
/// table keeps.
pub fn extract(result: &Value, quantities: &[String]) -> Vec<Option<Value>> {
    quantities.iter().map(|q| result.pointer(q).filter(|x| !x.is_null()).cloned()).collect()
}

/// The table from each case's quantity values (see [`extract`]) or problem, in case order.
pub fn table(
    spec: &SweepSpec,
    k: &dyn crate::jobs::kind::DynKind,
    all: &[Vec<Value>],
    quantities: &[String],
    names: &[String],
    values: &[Result<Vec<Option<Value>>, Problem>],
) -> SweepResult {
    let total = all.len();
    let mut columns = vec!["case".to_string()];
    columns.extend(spec.parameters.iter().map(|p| column(&p.path)));
    columns.push("status".into());
    columns.push("error_code".into());
    columns.extend(names.iter().cloned());
    let units = column_units(k, spec, quantities, names);
    let mut rows = Vec::with_capacity(total);
    let (mut succeeded, mut failed) = (0, 0);
    for (i, (values, outcome)) in all.iter().zip(values).enumerate() {
        let mut row = Map::new();
        row.insert("case".into(), json!(i + 1));
        for (p, v) in spec.parameters.iter().zip(values) {
            row.insert(column(&p.path), v.clone());
        }
        match outcome {
            Ok(found) => {
                succeeded += 1;
                row.insert("status".into(), json!("succeeded"));
                for (x, name) in found.iter().zip(names) {
                    if let Some(x) = x {
                        row.insert(name.clone(), x.clone());
                    }
                }
            }
            Err(problem) => {
                failed += 1;
                row.insert("status".into(), json!("failed"));
                row.insert("error_code".into(), json!(problem.code));
                row.insert("error".into(), json!(problem.detail));
            }
        }
        rows.push(row);
    }
    if failed > 0 && !columns.contains(&"error".to_string()) {
        columns.push("error".into());
    }
    SweepResult { kind: spec.kind.clone(), columns, units, cases: rows, succeeded, failed }
}
