//! Shared helpers of the validation tests that run job kinds in-process (no server): prepare and
//! run a spec as the worker would, and read the examples.

use serde_json::Value;
use tribod::jobs::{registry, Limits};
use tribod::physics::{Silent, SolveError};
use tribod::problem::Problem;

/// Why a job did not produce a result: its spec was refused, or the solver failed.
#[derive(Debug)]
pub enum Failure {
    Spec(Problem),
    Solve(SolveError),
}

/// Validate and solve `spec` of `kind` with the default limits.
pub fn run(kind: &str, spec: &Value) -> Result<Value, Failure> {
    let k = registry::find(kind).expect("registered kind");
    let prepared = k.prepare(spec, &Limits::default()).map_err(Failure::Spec)?;
    prepared.run(&Silent).map_err(Failure::Solve)
}

/// The `spec` of `examples/{name}.json`.
pub fn example(name: &str) -> Value {
    let text = std::fs::read_to_string(format!("examples/{name}.json")).unwrap();
    serde_json::from_str::<Value>(&text).unwrap()["spec"].clone()
}
