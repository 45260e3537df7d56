//! Job kinds (spec → validated → solved → result) and the machinery that runs them.

pub mod cost;
mod failure;
pub mod idempotency;
pub mod kind;
pub mod kinds;
pub mod label;
pub mod quantity;
pub mod queue;
pub mod registry;
pub mod runner;
pub mod schemas;
pub mod table;
pub mod units;

pub use cost::{Cost, Estimate};

/// Build the solvers' process-wide tables (≈ 0.12 s of one core) before the first job: the
/// work models leave them out (`jobs::cost::PROCESS_TABLES_S`). `serve`, `worker` and `run` call it.
pub fn warm_up() {
    crate::physics::friction::greenwood_tripp::warm_up();
}
pub use kind::{DynKind, Kind, Limits, OutputInfo, Prepared, Validation};
/// The convergence report every result carries (defined by the solvers), for the API's schemas:
/// the API sees physics only through the job layer.
pub use crate::physics::{Convergence, Termination};
