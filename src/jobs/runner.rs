//! Running one prepared job to an outcome: the shared path of the worker pool and `tribod run`.
//! Catches panics (a panicking solver fails its job with `internal_error`; the thread lives on)
//! and adds the `meta` block every result carries.

use super::kind::Prepared;
use crate::physics::{Interrupt, Observer, SolveError};
use crate::problem::{ErrorCode, Problem};
use serde_json::{json, Value};
use sha2::{Digest, Sha256};
use std::panic::{catch_unwind, AssertUnwindSafe};
use std::time::Instant;

/// How a job ended.
#[derive(Debug)]
pub enum Outcome {
    /// The result JSON, with `meta`.
    Succeeded(Value),
    /// The problem stored with the job.
    Failed(Problem),
    /// Stopped on request (cancel or shutdown). Timeouts are failures, not interrupts.
    Interrupted(Interrupt),
}

/// Hash of a kind and its canonical spec text (hex sha256): the dedup key. `canonical_text` is
/// the serialised [`Prepared::canonical`](super::kind::Prepared) (keys already sorted).
pub fn spec_hash(kind: &str, canonical_text: &str) -> String {
    let mut h = Sha256::new();
    h.update(kind.as_bytes());
    h.update(b"\n");
    h.update(canonical_text.as_bytes());
    h.finalize().iter().map(|b| format!("{b:02x}")).collect()
}

/// Run `prepared` under `observer`. `wall_time_seconds` and the solver version go into `meta`.
pub fn run(prepared: Prepared, observer: &dyn Observer) -> (Outcome, f64) {
    let kind = prepared.kind;
    let estimate = prepared.cost.estimate;
    let start = Instant::now();
    let result = catch_unwind(AssertUnwindSafe(|| prepared.run(observer)));
    let wall = start.elapsed().as_secs_f64();
    let outcome = match result {
        Ok(Ok(mut value)) => {
            if let Value::Object(map) = &mut value {
                map.insert(
                    "meta".into(),
                    json!({
                        "kind": kind.name(),
                        "solver_version": kind.solver_version(),
                        "wall_time_seconds": wall,
                        "estimate": estimate,
                    }),
                );
            }
            Outcome::Succeeded(value)
        }
        Ok(Err(SolveError::Interrupted(Interrupt::TimedOut))) => {
            Outcome::Failed(Problem::from_solve_error(&SolveError::Interrupted(Interrupt::TimedOut)))
        }
        Ok(Err(SolveError::Interrupted(i))) => Outcome::Interrupted(i),
        Ok(Err(e)) => Outcome::Failed(Problem::from_solve_error(&e)),
        Err(panic) => {
            let msg = panic
                .downcast_ref::<&str>()
                .map(|s| s.to_string())
                .or_else(|| panic.downcast_ref::<String>().cloned())
                .unwrap_or_else(|| "unknown panic".into());
            tracing::error!(kind = kind.name(), panic = %msg, "solver panicked");
            Outcome::Failed(Problem::new(ErrorCode::InternalError, format!("the solver panicked: {msg}")))
        }
    };
    (outcome, wall)
}
