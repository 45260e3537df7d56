//! Shared numerics of the solvers: methods that more than one solver uses, written once.
//!
//! * [`krylov`]: restarted, right-preconditioned GMRES (matrix-free).

pub mod krylov;
