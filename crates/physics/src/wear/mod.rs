//! Cam wear: Archard wear over the cam cycle with worn-profile evolution, and seed 004's
//! empirical wear-rate method.
//!
//! * [`archard`]: wear of one steady revolution from the cycle's kinematics, loads, Hertz contact
//!   (or the numerical EHL pressure where that film model ran), roller slip and film (only the
//!   Greenwood–Tripp asperity share wears in mixed lubrication).
//! * [`deposit`]: the closed-form spreading of a moving Hertzian pass over surface cells (exact
//!   volume conservation at any cell size).
//! * [`evolution`]: update interval by update interval, wear the cam, rebuild its profile, rerun
//!   the pair; stop at the running time, the wear limit, or a profile the pair cannot run on
//!   (partial history with the typed reason).
//! * [`irgashev`]: seed 004 (Tables 1–5, eq. 1–15), reproduced as printed with its
//!   inconsistencies documented.

pub mod archard;
pub mod deposit;
pub mod evolution;
pub mod irgashev;

pub use archard::{revolution_wear, ArchardParams, LoadShare, RevolutionWear};
pub use evolution::{evolve, HistoryPoint, Stop, WearEvolution, WearRun};
