//! Pure numerics: plain structs in, plain structs out, SI units, no I/O, no async, no HTTP types.
//!
//! Every solver in here reports how it converged ([`Convergence`]), polls an [`Observer`] for
//! progress and cancellation, and fails with a typed [`SolveError`]. Nothing non-finite leaves a
//! solver: results pass through [`ensure_finite`] (or an equivalent check) before they are returned.

pub mod cam;
pub mod contact;
pub mod ehl;
pub mod film;
pub mod friction;
pub mod geometry;
pub mod journal;
pub mod lubricant;
pub mod numerics;
pub mod rough;
pub mod roller;
pub mod solver;
pub mod thermal;
pub mod units;
pub mod valvetrain;
pub mod wear;
pub mod work;

pub use solver::{
    ensure_finite, Convergence, Interrupt, Interrupts, Observer, PhysicalFailure, Silent, SolveError, Stage, Termination,
};
