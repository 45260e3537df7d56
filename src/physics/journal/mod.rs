//! Finite-length hydrodynamic journal bearing (seed 002): Reynolds equation with Reynolds
//! (Swift–Stieber) cavitation, misalignment, axial edge profiles, load balance.

pub mod film;
pub mod multigrid;
