//! Finite-length hydrodynamic journal bearing (seed 002): Reynolds equation with Reynolds
//! (Swift–Stieber) cavitation, misalignment, axial edge profiles, load balance.

pub mod film;
pub mod multigrid;
pub mod analysis;
pub mod taguchi;

pub use analysis::{analyse, Analysis, Bearing, Fields, Guess, Operating, Settings, Supply, Workspace};
pub use film::{Film, Misalignment, Profile};
