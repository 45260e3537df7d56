//! Contact geometry shared by the solvers and the film models: shapes and profiles of the bodies,
//! below the films that use them (no solver or film types in here).
//!
//! * [`crown`]: the crowned roller's axial profile and its slice-model load distribution.

pub mod crown;

pub use crown::{Crown, CrownProfile, CrownedContact};
