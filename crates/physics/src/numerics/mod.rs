//! Shared numerics of the solvers: methods that more than one solver uses, written once.
//!
//! * [`krylov`]: restarted, right-preconditioned GMRES (matrix-free).
//! * [`newton`]: the backtracking line search of the damped Newton iterations (step halving,
//!   Armijo's sufficient decrease).

pub mod krylov;
pub mod newton;
