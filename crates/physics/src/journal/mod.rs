//! Finite-length hydrodynamic journal bearing (seed 002): Reynolds equation with Reynolds
//! (Swift–Stieber) cavitation, misalignment, axial edge profiles, load balance.
//!
//! - [`film`]: the film geometry (seed 002 eq. 3, 10–11, 13–15) and the angle conventions.
//! - [`multigrid`]: the discrete Reynolds complementarity problem and its solver (primal–dual
//!   active set, multigrid-preconditioned conjugate gradients, nested iteration).
//! - [`analysis`]: one analysis — fixed position, fixed eccentricity ratio or load balance over
//!   nested grids — and the performance figures (load, Sommerfeld number, peak pressure, minimum
//!   film, friction by two definitions, flows, power loss).
//! - [`dynamics`]: stiffness and damping of the film at an equilibrium (linearised Reynolds),
//!   and the stability threshold of a rigid rotor from them.
//! - [`heat`]: the heat balance (effective temperature, ISO 7902 / DIN 31652 bulk model) and the
//!   Walther viscosity–temperature law with ISO VG grades.
//! - [`taguchi`]: orthogonal arrays, the weighted-sum score of eq. (19), S/N ratios, Nelder–Mead.
//!
//! - [`dimensions`]: the SI scales of the dimensionless groups for a bearing of given size, speed
//!   and viscosity.
//!
//! The analysis is dimensionless; [`Dimensions`] turns its figures into SI.

pub mod dimensions;
pub mod film;
pub mod multigrid;
pub mod analysis;
pub mod problem;
pub mod dynamics;
pub mod heat;
mod balance;
mod figures;
pub mod taguchi;
pub mod operating;
pub mod heat_balance;
pub mod threshold;
pub mod limits;
pub mod case;
pub mod optimisation;

pub use analysis::{analyse, analyse_symmetric, symmetric_load};
pub use problem::{Analysis, Bearing, Fields, Guess, Operating, Settings, Supply, Workspace};
pub use dimensions::Dimensions;
pub use film::{Film, Misalignment, Profile};

