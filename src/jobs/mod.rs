//! Job kinds (spec → validated → solved → result) and the machinery that runs them.

pub mod idempotency;
pub mod kind;
pub mod kinds;
pub mod queue;
pub mod registry;
pub mod runner;
pub mod table;

pub use kind::{DynKind, Kind, Limits, OutputInfo, Prepared, Validation};
/// The convergence report every result carries (defined by the solvers), for the API's schemas:
/// the API sees physics only through the job layer.
pub use crate::physics::{Convergence, Termination};
