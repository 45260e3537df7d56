//! Job kinds (spec → validated → solved → result) and the machinery that runs them.

pub mod kind;
pub mod kinds;
pub mod registry;

pub use kind::{DynKind, Kind, Limits, OutputInfo, Prepared, Validation};
