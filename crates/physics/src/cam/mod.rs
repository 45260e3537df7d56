//! Cam–follower geometry and kinematics: lift laws and programs, multi-arc and tabulated cams,
//! follower kinematics per cam angle, and the loads on the follower.
//!
//! Everything here is pure and per-angle; the cycle (film, friction, roller slip over a
//! revolution) lives in [`cycle`].

pub mod contour;
pub mod cycle;
pub mod jet;
pub mod kinematics;
pub mod lift;
pub mod loads;
pub mod profile;
pub mod seed003_fit;
pub mod seed004;
pub mod spline;
pub mod summary;
pub mod synthesis;

pub use jet::Jet;
pub use kinematics::{kinematics, CamSpeed, FollowerGeometry, KinematicState, SpeedSchedule};
pub use lift::{LiftLaw, LiftProgram};
pub use loads::{FollowerLoad, LoadModel, PeriodicTable};
pub use profile::{Arc, CamProfile, FollowerShape, MultiArc};
pub use spline::PeriodicSpline;
pub use synthesis::{LiftSpec, SynthesisedLift};
