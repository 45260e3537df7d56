//! The seam every job kind plugs into.
//!
//! A kind is three types — its tag ([`Kind::NAME`]), its spec (the JSON payload, parsed with
//! unknown fields rejected, then validated) and its output (the result JSON) — plus a pure solve
//! function. The queue, the store, the HTTP API, `tribod run` and `sweep` only see kinds through the
//! object-safe [`DynKind`] that every `Kind` gets for free.

use super::cost::{describe_seconds, Cost, MIB};
use crate::physics::{Observer, SolveError};
use crate::problem::{ErrorCode, FieldError, Problem};
use serde::{de::DeserializeOwned, Serialize};
use serde_json::Value;
use std::collections::BTreeMap;
use utoipa::openapi::{schema::Schema, RefOr};
use utoipa::ToSchema;

/// Server-wide limits on problem size, so one request cannot occupy the pool for hours.
/// Each kind checks the ones that apply to it in [`Kind::validate`] and reports
/// `limit_exceeded` with the field path.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Limits {
    /// Most nodes in one solver grid (circumferential × axial, or EHL nodes).
    pub max_grid_nodes: usize,
    /// Most cam angles in one cycle.
    pub max_angles: usize,
    /// Most cases in one sweep.
    pub max_sweep_cases: usize,
    /// Most solver evaluations in one optimisation.
    pub max_evaluations: usize,
    /// Most memory one job may need by the solvers' memory models (bytes): what a spec would
    /// allocate is estimated at validation (e.g. the dense EHL influence and Newton matrices,
    /// ≈ 20·n² bytes for n nodes) and refused above this, before anything is allocated.
    pub max_job_memory: u64,
    /// Most solver time one job may need by the solvers' work models (seconds of one core on
    /// the reference machine of BENCHMARKS.md); refused at validation above this. The per-job
    /// wall-time limit (`--job-timeout`) still bounds what the models miss.
    pub max_job_seconds: f64,
}

impl Limits {
    /// No limits (offline use, and cases already checked against the server's limits).
    pub const UNLIMITED: Limits = Limits {
        max_grid_nodes: usize::MAX,
        max_angles: usize::MAX,
        max_sweep_cases: usize::MAX,
        max_evaluations: usize::MAX,
        max_job_memory: u64::MAX,
        max_job_seconds: f64::INFINITY,
    };
}

impl Default for Limits {
    fn default() -> Self {
        Limits {
            max_grid_nodes: 1_000_000,
            max_angles: 36_000,
            max_sweep_cases: 1_000,
            max_evaluations: 2_000,
            max_job_memory: 2 << 30,
            max_job_seconds: 60.0,
        }
    }
}

/// Collects field errors while a kind validates its spec. Paths are JSON pointers relative to the
/// spec (`/grid/axial`); the API prefixes `/spec`.
#[derive(Debug, Default)]
pub struct Validation {
    errors: Vec<FieldError>,
    /// Legal but implausible values (a unit slip, most often): reported, not refused.
    warnings: Vec<FieldError>,
    limit_errors: Vec<FieldError>,
    bounds: Vec<Bound>,
    /// Prepended to every path (see `under`).
    prefix: String,
}

/// A numeric rule a kind checked, with the value it checked: the OpenAPI document turns the rules
/// checked on the example spec's own fields into `minimum`/`maximum` (one source of truth).
#[derive(Debug, Clone, PartialEq)]
pub struct Bound {
    /// JSON pointer relative to the spec.
    pub path: String,
    /// The value checked (compared with the spec's field to know the rule is about the field).
    pub value: f64,
    pub min: Option<f64>,
    /// `min` itself is not allowed (`> min`).
    pub min_exclusive: bool,
    pub max: Option<f64>,
    pub integer: bool,
    /// The rule bounds the number of items of an array (`value` is its length): the document's
    /// `minItems`/`maxItems`.
    pub items: bool,
}

impl Validation {
    pub fn new() -> Self {
        Self::default()
    }

    /// Validate a nested part of the spec: inside `f`, every path is relative to `prefix` (e.g.
    /// a wear spec validates its `cycle` as `cam_cycle` does, under `/cycle`).
    pub fn under<R>(&mut self, prefix: &str, f: impl FnOnce(&mut Self) -> R) -> R {
        let outer = self.prefix.len();
        self.prefix.push_str(prefix);
        let r = f(self);
        self.prefix.truncate(outer);
        r
    }

    fn at(&self, path: &str) -> String {
        format!("{}{path}", self.prefix)
    }

    /// Record an error at `path` unless `ok`.
    pub fn check(&mut self, ok: bool, path: &str, message: impl Into<String>) -> &mut Self {
        if !ok {
            self.errors.push(FieldError::new(self.at(path), message));
        }
        self
    }

    /// Record a warning at `path` when `implausible` says so (the value stays accepted).
    pub fn warn(&mut self, path: &str, implausible: Option<String>) -> &mut Self {
        if let Some(message) = implausible {
            self.warnings.push(FieldError::new(self.at(path), message));
        }
        self
    }

    /// A legal value of quantity `q` far above what a valve train or bearing has: a warning.
    pub fn plausible(&mut self, path: &str, value: f64, q: super::quantity::Quantity) -> &mut Self {
        self.warn(path, q.implausible(value))
    }

    fn bound(&mut self, path: &str, value: f64, min: Option<f64>, min_exclusive: bool, max: Option<f64>, integer: bool) {
        self.bounds.push(Bound { path: self.at(path), value, min, min_exclusive, max, integer, items: false });
    }

    /// The numeric rules checked so far.
    pub fn bounds(&self) -> &[Bound] {
        &self.bounds
    }

    /// `value` must be finite and `> 0`.
    pub fn positive(&mut self, path: &str, value: f64) -> &mut Self {
        self.bound(path, value, Some(0.0), true, None, false);
        self.check(value.is_finite() && value > 0.0, path, "must be a finite number > 0")
    }

    /// `value` must be finite and `≥ 0`.
    pub fn non_negative(&mut self, path: &str, value: f64) -> &mut Self {
        self.bound(path, value, Some(0.0), false, None, false);
        self.check(value.is_finite() && value >= 0.0, path, "must be a finite number >= 0")
    }

    /// `value` must lie in the closed interval `[lo, hi]`.
    pub fn in_range(&mut self, path: &str, value: f64, lo: f64, hi: f64) -> &mut Self {
        self.bound(path, value, Some(lo), false, Some(hi), false);
        self.check(
            value.is_finite() && value >= lo && value <= hi,
            path,
            format!("must be in [{lo}, {hi}]"),
        )
    }

    /// A physical quantity within its bounds (`jobs::quantity`): finite and in `[min, max]`; the
    /// message names the unit.
    pub fn quantity(&mut self, path: &str, value: f64, q: super::quantity::Quantity) -> &mut Self {
        self.bound(path, value, Some(q.min), false, Some(q.max), false);
        let ok = value.is_finite() && value >= q.min && value <= q.max;
        if ok {
            self.plausible(path, value, q);
        }
        self.check(ok, path, format!("{}; {} in {} was given {}", q.rule(), q.name, q.unit, super::quantity::format_number(value)))
    }

    /// An integer count in `[lo, hi]`.
    pub fn count_in_range(&mut self, path: &str, value: usize, lo: usize, hi: usize) -> &mut Self {
        self.bound(path, value as f64, Some(lo as f64), false, Some(hi as f64), true);
        self.check(value >= lo && value <= hi, path, format!("must be an integer in [{lo}, {hi}]"))
    }

    /// An array of `len` items must have `lo` to `hi` of them (`None`: no upper bound). A fixed
    /// rule of the spec (it becomes the document's `minItems`/`maxItems`); a server limit that
    /// is configurable is a [`Validation::limit`] instead.
    pub fn items(&mut self, path: &str, len: usize, lo: usize, hi: Option<usize>) -> &mut Self {
        self.bounds.push(Bound {
            path: self.at(path),
            value: len as f64,
            min: Some(lo as f64),
            min_exclusive: false,
            max: hi.map(|h| h as f64),
            integer: true,
            items: true,
        });
        let message = match hi {
            Some(h) if h == lo => format!("must have exactly {lo} items"),
            Some(h) if lo == 0 => format!("must have at most {h} items"),
            Some(h) => format!("must have {lo} to {h} items"),
            None if lo == 1 => "must have at least 1 item".to_string(),
            None => format!("must have at least {lo} items"),
        };
        self.check(len >= lo && hi.is_none_or(|h| len <= h), path, message)
    }

    /// A problem-size limit of the server: reported as `limit_exceeded` rather than `invalid_spec`.
    pub fn limit(&mut self, path: &str, value: usize, max: usize, what: &str) -> &mut Self {
        if value > max {
            self.limit_errors.push(FieldError::new(
                self.at(path),
                format!("{what} is {value}; this server accepts at most {max} (configurable)"),
            ));
        }
        self
    }

    /// Record an error unconditionally.
    pub fn error(&mut self, path: &str, message: impl Into<String>) -> &mut Self {
        self.errors.push(FieldError::new(self.at(path), message));
        self
    }

    /// Take over the field errors of a nested problem (e.g. a sweep case's own validation),
    /// each path rewritten by `map`. Limit problems stay limit errors.
    pub fn absorb(&mut self, problem: &Problem, map: impl Fn(&str) -> String) -> &mut Self {
        let prefix = self.prefix.clone();
        let map = |p: &str| format!("{prefix}{}", map(p));
        let target = if problem.code == ErrorCode::LimitExceeded.as_str() {
            &mut self.limit_errors
        } else {
            &mut self.errors
        };
        if problem.errors.is_empty() {
            target.push(FieldError::new(map(""), problem.detail.clone()));
        }
        for e in &problem.errors {
            target.push(FieldError::new(map(&e.path), e.message.clone()));
        }
        self
    }

    pub fn is_ok(&self) -> bool {
        self.errors.is_empty() && self.limit_errors.is_empty()
    }

    /// `Ok` or the problem naming every offending field (paths relative to the spec).
    /// The warnings (legal but implausible values) recorded so far.
    pub fn warnings(&self) -> &[FieldError] {
        &self.warnings
    }

    /// The spec's verdict: a problem (`invalid_spec`, or `limit_exceeded` when only server
    /// limits were broken), or the warnings of an accepted spec.
    pub fn finish(self) -> Result<Vec<FieldError>, Problem> {
        if !self.errors.is_empty() {
            let n = self.errors.len() + self.limit_errors.len();
            let mut errors = self.errors;
            errors.extend(self.limit_errors);
            return Err(Problem::new(ErrorCode::InvalidSpec, format!("{n} field(s) broke a rule"))
                .with_errors(errors));
        }
        if !self.limit_errors.is_empty() {
            return Err(Problem::new(
                ErrorCode::LimitExceeded,
                "the problem is larger than this server accepts",
            )
            .with_errors(self.limit_errors));
        }
        Ok(self.warnings)
    }
}

/// One optional output a client can request through a spec's `outputs` list.
#[derive(Debug, Clone, Copy, Serialize)]
pub struct OutputInfo {
    pub name: &'static str,
    pub description: &'static str,
}

/// A job kind. Implement this; registration is one line in `jobs::registry`.
pub trait Kind: Send + Sync + 'static {
    /// The tag clients send as `kind` (snake_case).
    const NAME: &'static str;
    /// Bump when a change alters results: finished jobs are reused only with the same version.
    const SOLVER_VERSION: &'static str;
    /// One-line description for `GET /v1/kinds`.
    const DESCRIPTION: &'static str;
    /// Result fields that are tables, servable as CSV (`?table=` picks one; first is default).
    /// A table is an object of equal-length arrays (columnar) or an array of flat objects.
    const TABLES: &'static [&'static str] = &[];
    /// The figures an engineer checks first (JSON pointers into the result, most important
    /// first): the dashboard's key-results card, `GET /v1/kinds` `key_figures`.
    const KEY_FIGURES: &'static [&'static str] = &[];

    /// The payload. Derive `Deserialize` with `#[serde(deny_unknown_fields)]` and defaults.
    /// Every field documented with its unit (doc comments become the OpenAPI description).
    type Spec: DeserializeOwned + Serialize + ToSchema + Send + Sync + 'static;
    /// The result. Absent quantities are skipped, never `null` (see [`check_finite_json`]).
    type Output: Serialize + ToSchema + Send + 'static;

    /// An example spec: shown by `GET /v1/kinds`, and must validate.
    fn example() -> Value;
    /// More valid specs, for the OpenAPI bounds only: the rules `validate` checks on their
    /// fields become bounds too, for fields (variants, optional lists) the example leaves out.
    fn bound_examples() -> Vec<Value> {
        Vec::new()
    }
    /// Optional outputs selectable in the spec's `outputs` list (empty when the kind has none).
    fn outputs() -> &'static [OutputInfo] {
        &[]
    }
    /// The version that decides reuse: `SOLVER_VERSION`, except for composite kinds (`sweep`),
    /// which fold in the versions of the kinds they run.
    fn solver_version() -> &'static str {
        Self::SOLVER_VERSION
    }
    /// Range and consistency checks the types cannot express.
    fn validate(spec: &Self::Spec, limits: &Limits, v: &mut Validation);
    /// The work and memory the solve will need, by the solvers' models (`jobs::cost`), from a
    /// spec that passed `validate`. The server refuses a spec over its limits with the fields
    /// named here, and stores the estimate with the job.
    fn cost(spec: &Self::Spec) -> Cost;
    /// The pure solve: no I/O. Poll `observer.check()` once per outer iteration.
    fn solve(spec: &Self::Spec, observer: &dyn Observer) -> Result<Self::Output, SolveError>;
}

/// A spec that parsed and validated, ready to run. `canonical` is the spec re-serialised from its
/// typed form (defaults filled, keys sorted): the dedup hash is taken of it.
pub struct Prepared {
    pub kind: &'static dyn DynKind,
    pub canonical: Value,
    /// Legal but implausible values of the spec (paths relative to the spec).
    pub warnings: Vec<FieldError>,
    /// The estimated cost (work and memory models), checked against the limits.
    pub cost: Cost,
    run: Box<dyn FnOnce(&dyn Observer) -> Result<Value, SolveError> + Send>,
}

impl Prepared {
    /// Run the solver; the output serialised to JSON.
    pub fn run(self, observer: &dyn Observer) -> Result<Value, SolveError> {
        (self.run)(observer)
    }
}

impl std::fmt::Debug for Prepared {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Prepared").field("kind", &self.kind.name()).finish_non_exhaustive()
    }
}

/// Object-safe view of a [`Kind`], used by everything outside the kind itself.
pub trait DynKind: Send + Sync {
    fn name(&self) -> &'static str;
    fn solver_version(&self) -> &'static str;
    fn description(&self) -> &'static str;
    fn tables(&self) -> &'static [&'static str];
    fn key_figures(&self) -> &'static [&'static str];
    fn example(&self) -> Value;
    fn outputs(&self) -> &'static [OutputInfo];
    /// OpenAPI component names of the spec and output schemas.
    fn schema_names(&self) -> (String, String);
    /// Push the spec and output schemas and everything they reference.
    fn schemas(&self, out: &mut Vec<(String, RefOr<Schema>)>);
    /// The example and the further specs whose validation rules document the spec's fields.
    fn bound_examples(&self) -> Vec<Value>;
    /// The numeric and item-count rules `validate` checks on those specs' own fields (a rule on a
    /// derived quantity is left out: its value differs from the field's). For the OpenAPI bounds.
    fn bounds(&self) -> Vec<Bound>;
    /// Parse (unknown fields rejected, JSON paths in errors) and validate a spec.
    /// Error paths are relative to the spec.
    fn prepare(&'static self, spec: &Value, limits: &Limits) -> Result<Prepared, Problem>;
    /// The warnings of a stored (valid) spec: legal but implausible values, paths relative to
    /// the spec. Validation is pure, so a job's warnings are recomputed when it is read.
    fn warnings(&self, spec: &Value) -> Vec<FieldError> {
        let _ = spec;
        Vec::new()
    }
}

/// Units of a kind's fields, read from its schemas' doc comments (`jobs::units`).
impl dyn DynKind + '_ {
    /// The kind's schemas and the names of its spec and result roots.
    pub fn documents(&self) -> crate::jobs::units::Documents {
        let mut schemas = Vec::new();
        self.schemas(&mut schemas);
        let (spec, result) = self.schema_names();
        crate::jobs::units::Documents { schemas, spec, result }
    }
    /// Every numeric result field (or, `spec`, spec field) and its unit, `None` where the doc
    /// gives none (a test holds results to having one).
    pub fn documented_units(&self, spec: bool) -> BTreeMap<String, Option<&'static str>> {
        crate::jobs::units::walk(self.documents(), spec)
    }
    /// `result_units` of `GET /v1/kinds`: JSON pointer → unit.
    pub fn result_units(&self) -> &'static BTreeMap<String, String> {
        crate::jobs::units::cached(self.name(), false, || self.documents())
    }
    /// The units of the spec's fields (a sweep's parameters, range messages).
    pub fn spec_units(&self) -> &'static BTreeMap<String, String> {
        crate::jobs::units::cached(self.name(), true, || self.documents())
    }
}

/// The `DynKind` of a `Kind` type.
pub struct Registered<K: Kind>(std::marker::PhantomData<K>);

impl<K: Kind> Registered<K> {
    pub const fn new() -> Self {
        Registered(std::marker::PhantomData)
    }
}

impl<K: Kind> Default for Registered<K> {
    fn default() -> Self {
        Self::new()
    }
}

impl<K: Kind> DynKind for Registered<K> {
    fn name(&self) -> &'static str {
        K::NAME
    }
    fn solver_version(&self) -> &'static str {
        K::solver_version()
    }
    fn description(&self) -> &'static str {
        K::DESCRIPTION
    }
    fn tables(&self) -> &'static [&'static str] {
        K::TABLES
    }
    fn key_figures(&self) -> &'static [&'static str] {
        K::KEY_FIGURES
    }
    fn example(&self) -> Value {
        K::example()
    }
    fn outputs(&self) -> &'static [OutputInfo] {
        K::outputs()
    }
    fn schema_names(&self) -> (String, String) {
        (K::Spec::name().into_owned(), K::Output::name().into_owned())
    }
    fn schemas(&self, out: &mut Vec<(String, RefOr<Schema>)>) {
        out.push((K::Spec::name().into_owned(), <K::Spec as utoipa::PartialSchema>::schema()));
        K::Spec::schemas(out);
        out.push((K::Output::name().into_owned(), <K::Output as utoipa::PartialSchema>::schema()));
        K::Output::schemas(out);
    }
    fn bound_examples(&self) -> Vec<Value> {
        std::iter::once(K::example()).chain(K::bound_examples()).collect()
    }
    fn bounds(&self) -> Vec<Bound> {
        let mut out: Vec<Bound> = Vec::new();
        for spec in self.bound_examples() {
            let Ok(typed) = parse_spec::<K::Spec>(&spec) else { continue };
            let Ok(example) = serde_json::to_value(&typed) else { continue };
            let mut v = Validation::new();
            K::validate(&typed, &Limits::UNLIMITED, &mut v);
            let own = |b: &Bound| match example.pointer(&b.path) {
                Some(Value::Array(items)) => b.items && items.len() as f64 == b.value,
                Some(x) => !b.items && x.as_f64() == Some(b.value),
                None => false,
            };
            for b in v.bounds.into_iter().filter(own) {
                let same = |o: &Bound| o.path == b.path && o.min == b.min && o.min_exclusive == b.min_exclusive && o.max == b.max;
                if !out.iter().any(same) {
                    out.push(b);
                }
            }
        }
        out
    }
    fn warnings(&self, spec: &Value) -> Vec<FieldError> {
        let Ok(typed) = parse_spec::<K::Spec>(spec) else { return Vec::new() };
        let mut v = Validation::new();
        K::validate(&typed, &Limits::UNLIMITED, &mut v);
        v.warnings
    }
    fn prepare(&'static self, spec: &Value, limits: &Limits) -> Result<Prepared, Problem> {
        let typed: K::Spec = parse_spec(spec)?;
        let mut v = Validation::new();
        K::validate(&typed, limits, &mut v);
        let warnings = v.finish().map_err(|p| with_units(self, p))?;
        let cost = K::cost(&typed);
        check_cost(&cost, limits)?;
        let canonical = canonicalize(serde_json::to_value(&typed).map_err(|e| {
            Problem::new(ErrorCode::InternalError, format!("spec did not serialise: {e}"))
        })?);
        Ok(Prepared {
            kind: self,
            canonical,
            warnings,
            cost,
            run: Box::new(move |observer| {
                let out = K::solve(&typed, observer)?;
                let value = serde_json::to_value(&out)
                    .map_err(|e| SolveError::NonFinite { quantity: format!("result ({e})") })?;
                crate::jobs::kind::check_finite_json(&value)?;
                Ok(value)
            }),
        })
    }
}

/// Refuse a cost over the server's limits: `limit_exceeded` naming the fields that drive it,
/// the estimate and the limit.
pub fn check_cost(cost: &Cost, limits: &Limits) -> Result<(), Problem> {
    let mut errors = Vec::new();
    let seconds = cost.cpu_seconds();
    if !(seconds <= limits.max_job_seconds) {
        errors.push(FieldError::new(
            cost.work_path.clone(),
            format!(
                "{} would take about {} of solver time (estimate {seconds:.3e} s of one core); this server accepts at most {} s per job (--max-job-seconds)",
                cost.work_what,
                describe_seconds(seconds),
                limits.max_job_seconds
            ),
        ));
    }
    let bytes = cost.memory_bytes();
    if !(bytes <= limits.max_job_memory as f64) {
        errors.push(FieldError::new(
            cost.memory_path.clone(),
            format!(
                "{} would need about {:.0} MiB of memory; this server accepts at most {:.0} MiB per job (--max-job-memory-mb)",
                cost.memory_what,
                bytes / MIB,
                limits.max_job_memory as f64 / MIB
            ),
        ));
    }
    if errors.is_empty() {
        return Ok(());
    }
    let detail = format!(
        "the job is larger than this server accepts: estimated {} of solver time and {:.0} MiB of memory; limits {} s and {:.0} MiB per job",
        describe_seconds(seconds),
        bytes / MIB,
        limits.max_job_seconds,
        limits.max_job_memory as f64 / MIB
    );
    Err(Problem::new(ErrorCode::LimitExceeded, detail).with_errors(errors))
}

/// Deserialise a spec, turning serde's error into a field error with a JSON pointer.
pub fn parse_spec<T: DeserializeOwned>(spec: &Value) -> Result<T, Problem> {
    parse_value(spec).map_err(|e| {
        Problem::new(ErrorCode::InvalidSpec, "the spec does not match the kind's schema").with_errors(vec![e])
    })
}

/// Deserialise any JSON value; on failure the JSON pointer of the offending field and serde's
/// message.
pub fn parse_value<T: DeserializeOwned>(value: &Value) -> Result<T, FieldError> {
    serde_path_to_error::deserialize(value).map_err(|err| {
        let mut pointer = path_to_pointer(err.path());
        let message = plain_words(&err.inner().to_string());
        // serde names a missing field in its message only; point at the field itself.
        if let Some(name) = message.strip_prefix("missing field `").and_then(|m| m.split('`').next()) {
            pointer = format!("{pointer}/{name}");
        }
        FieldError::new(pointer, message)
    })
}

/// A range rule's message with the field's unit (from the spec schema's docs, `jobs::units`):
/// "must be in [0.0001, 10]" → "must be between 0.0001 m and 10 m".
fn with_units(k: &dyn DynKind, mut problem: Problem) -> Problem {
    let units = k.spec_units();
    for e in &mut problem.errors {
        let Some(unit) = crate::jobs::units::unit_at(units, &e.path).filter(|u| *u != "1") else { continue };
        if let Some(range) = e.message.strip_prefix("must be in [").and_then(|r| r.strip_suffix(']')) {
            if let Some((lo, hi)) = range.split_once(", ") {
                e.message = format!("must be between {lo} {unit} and {hi} {unit}");
            }
        }
    }
    problem
}

/// serde's message in an engineer's words: "expected a number", not "expected f64".
fn plain_words(message: &str) -> String {
    const WORDS: &[(&str, &str)] = &[
        ("expected f64", "expected a number"),
        ("expected f32", "expected a number"),
        ("expected usize", "expected a whole number ≥ 0"),
        ("expected u64", "expected a whole number ≥ 0"),
        ("expected u32", "expected a whole number ≥ 0"),
        ("expected u16", "expected a whole number ≥ 0"),
        ("expected u8", "expected a whole number ≥ 0"),
        ("expected i64", "expected a whole number"),
        ("expected i32", "expected a whole number"),
        ("expected a sequence", "expected a list [ … ]"),
        ("expected a map", "expected an object { … }"),
        ("expected a boolean", "expected true or false"),
        ("invalid type: floating point", "invalid type: the number"),
        ("invalid type: integer", "invalid type: the number"),
        ("invalid type: sequence", "invalid type: a list"),
        ("invalid type: map", "invalid type: an object"),
    ];
    let mut out = message.to_string();
    for (from, to) in WORDS {
        out = out.replace(from, to);
    }
    // "expected struct FooSpec" → "expected an object".
    if let Some(i) = out.find("expected struct ") {
        let end = out[i + 16..].find(|c: char| !c.is_alphanumeric() && c != '_').map_or(out.len(), |j| i + 16 + j);
        out.replace_range(i..end, "expected an object { … }");
    }
    out
}

fn path_to_pointer(path: &serde_path_to_error::Path) -> String {
    use serde_path_to_error::Segment;
    let mut out = String::new();
    for seg in path.iter() {
        match seg {
            Segment::Seq { index } => out.push_str(&format!("/{index}")),
            Segment::Map { key } | Segment::Enum { variant: key } => {
                out.push('/');
                out.push_str(&key.replace('~', "~0").replace('/', "~1"));
            }
            Segment::Unknown => out.push_str("/?"),
        }
    }
    out
}

/// `target` with `patch` merged in (RFC 7386 JSON merge patch: objects merge key by key, `null`
/// removes a key, anything else replaces). Builds a kind's bound examples from its example.
pub fn merge_patch(target: &mut Value, patch: Value) {
    match (target, patch) {
        (Value::Object(t), Value::Object(p)) => {
            for (k, v) in p {
                if v.is_null() {
                    t.remove(&k);
                } else {
                    merge_patch(t.entry(k).or_insert(Value::Null), v);
                }
            }
        }
        (t, p) => *t = p,
    }
}

/// The kind's example with `patch` merged in ([`merge_patch`]).
pub fn example_with<K: Kind>(patch: Value) -> Value {
    let mut spec = K::example();
    merge_patch(&mut spec, patch);
    spec
}

/// Sort object keys recursively so that equal specs serialise to equal bytes.
pub fn canonicalize(value: Value) -> Value {
    match value {
        Value::Object(map) => {
            let mut entries: Vec<(String, Value)> = map.into_iter().collect();
            entries.sort_by(|a, b| a.0.cmp(&b.0));
            Value::Object(entries.into_iter().map(|(k, v)| (k, canonicalize(v))).collect())
        }
        Value::Array(items) => Value::Array(items.into_iter().map(canonicalize).collect()),
        other => other,
    }
}

/// serde_json turns NaN and infinities into `null`, so no field of a result may be `null`:
/// outputs leave absent quantities out (`#[serde(skip_serializing_if = "Option::is_none")]`)
/// instead of writing `null`. The one place `null` is allowed is an element of a per-angle (or
/// per-case) column that was not computed at that index (an `Option<f64>` element, e.g. the
/// pressure spike at angles where the closed-form film ran); such columns are built from
/// `Option`s by the solver, whose own numbers pass `ensure_finite`. Solvers check their own
/// numbers; this is the last chokepoint before a result is stored.
pub fn check_finite_json(value: &Value) -> Result<(), SolveError> {
    fn walk(v: &Value, path: &mut String) -> Result<(), SolveError> {
        match v {
            Value::Null => {
                return Err(SolveError::NonFinite { quantity: format!("result{path}") });
            }
            Value::Array(items) if items.iter().any(Value::is_number) => {
                // A numeric column: `null` elements are "not computed here".
                for item in items {
                    if let Value::Number(n) = item {
                        if n.as_f64().is_some_and(|x| !x.is_finite()) {
                            return Err(SolveError::NonFinite { quantity: format!("result{path}") });
                        }
                    }
                }
            }
            Value::Array(items) => {
                for (i, item) in items.iter().enumerate() {
                    let len = path.len();
                    path.push_str(&format!("/{i}"));
                    walk(item, path)?;
                    path.truncate(len);
                }
            }
            Value::Object(map) => {
                for (k, item) in map {
                    let len = path.len();
                    path.push('/');
                    path.push_str(k);
                    walk(item, path)?;
                    path.truncate(len);
                }
            }
            _ => {}
        }
        Ok(())
    }
    walk(value, &mut String::new())
}
