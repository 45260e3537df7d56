//! Valve-train dynamics: the cam–follower contact load from a lumped multibody model instead of
//! quasi-statics (seed 003 §2, §4: the valve train's parts, Table 1–2, and Lagrange's equations
//! eq. (19)–(31), here for translating lumped masses with compliant links).
//!
//! * [`model`]: the train — follower, valve (+ retainer), follower–valve link, the valve spring as
//!   a chain of masses (surge), a unilateral compliant cam contact (seed 003 eq. (6) for its
//!   stiffness) and a unilateral valve seat; direct-acting, or through a lever ([`Lever`]: rocker
//!   arm with an optional pushrod, end-pivot finger follower) of constant ratio.
//! * [`integrator`]: TR-BDF2 with error control, dense output and event location (contact loss,
//!   re-contact, seat impact), for systems affine between such events.
//! * [`periodic`]: the train driven at constant cam speed; the periodic steady state (revolutions
//!   until the state at the start repeats) sampled at uniform cam angles, with separation
//!   intervals, seating velocity and bounce.
//!
//! Not modelled: gravity, guide friction, the film's own stiffness and squeeze damping (the
//! contact's damping stands for them), the lever's changing ratio with its angle (first order in
//! the angle, error bound in [`Lever`]).
//! * [`spring`]: valve-spring design checks (rate, stresses, Goodman fatigue, coil clash, surge;
//!   Shigley ch. 10); [`progressive`]: variable-pitch springs (coil groups closing in turn);
//!   [`chain`]: the spring(s) in the assembly — uniform or progressive chains, nested springs
//!   as parallel chains.
//!
//! A run-up over a speed ramp is [`periodic::run_up`].

pub mod integrator;
pub mod model;
pub mod periodic;
pub mod progressive;
pub mod spring;
pub mod chain;
pub mod polydyne;
#[cfg(test)]
mod lash_tests;
#[cfg(test)]
mod progressive_tests;

pub use chain::ClosingGroup;
pub use model::{damping_from_ratio, line_contact_stiffness, HelicalSpring, HydraulicLashAdjuster, Lash, Lever, Link, NestedSpring, Pushrod, Seat, SpringChain, ValveTrain};
pub use periodic::{periodic_response, run_up, transient, RunUpResponse, Drive, DynamicsOptions, PeriodicResponse, Probe};
