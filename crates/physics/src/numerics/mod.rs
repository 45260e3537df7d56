//! Shared numerics of the solvers: methods that more than one solver uses, written once.
//!
//! * [`krylov`]: restarted, right-preconditioned GMRES (matrix-free).
//! * [`newton`]: the backtracking line search of the damped Newton iterations (step halving,
//!   Armijo's sufficient decrease).
//! * [`nelder_mead`]: simplex minimisation in a box (the bearing optimisation, the seed 003 cam
//!   fit).

pub mod krylov;
pub mod nelder_mead;
pub mod newton;
