//! One revolution of a cam–follower pair: kinematics → loads → Hertz contact → film → friction →
//! roller slip → flash temperature, per cam angle, computing only what is asked for.
//!
//! Angles are uniform, `θ_k = 2πk/N`. Consecutive angles are time steps (steady running:
//! `Δt = Δθ/ω`; startup: the schedule's times). Roller slip is integrated through the cycle by
//! variable-step BDF2 (see [`crate::roller`]); steady running repeats cycles until the
//! roller speed at θ = 0 repeats (relative change below the tolerance) — a repeated cycle stops
//! early where its speeds rejoin the previous cycle's within that tolerance —, startup runs one
//! revolution from rest.

use crate::contact::slide_roll_ratio;
use super::kinematics::{kinematics, FollowerGeometry, KinematicState, SpeedSchedule};
use super::loads::{FollowerLoad, LoadModel};
use super::profile::CamProfile;
use crate::contact::{hertz_line, hertz_point, line_contact_deflection, line_stress_maxima};
use crate::film::{ContactInput, ContactShape, FilmModel, FilmModelId, FilmProfile, FilmSolution, Traction};
use crate::ehl::twod::Fields2d;
use crate::friction::{AsperityFriction, Roughness, TractionLaw};
use crate::lubricant::Lubricant;
use crate::work;
use crate::geometry::Crown;
use crate::roller::{pin_torque, RollerParams, SlipStep};
use crate::thermal::{flash_temperature, ThermalSolid};
use crate::{ensure_finite, Convergence, Observer, SolveError, Termination};
use std::f64::consts::TAU;

mod run;
mod context;
mod hertz;
mod series;
mod roller_step;
mod roller_march;
pub use run::*;
use context::*;
use hertz::*;
use series::*;
use roller_step::*;

/// The follower, as far as contact and friction are concerned.
#[derive(Debug, Clone, PartialEq)]
pub enum FollowerKind {
    /// Flat face: line contact of `contact_length` (m), pure sliding surface.
    Flat { contact_length: f64 },
    /// Roller: line contact of `contact_length` (m) or a crowned profile; rotates on its pin.
    Roller { roller: RollerParams, contact_length: f64, crown: Option<Crown> },
    /// Spherical face of radius `face_radius` (m) on an axially straight cam: point contact with
    /// `R_y = face_radius`; the tappet does not spin.
    Spherical { face_radius: f64 },
}

/// How the roller's speed is found.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum SlipMode {
    /// The roller rolls without sliding (kinematic speed): no traction.
    PureRolling,
    /// Torque balance with traction, pin friction and inertia.
    TorqueBalance {
        /// Relative change of the roller speed at θ = 0 between cycles that ends the iteration.
        tolerance: f64,
        /// Most cycles (steady running).
        max_cycles: usize,
    },
}

/// Everything a cycle needs.
#[derive(Debug, Clone)]
pub struct CycleSpec {
    pub profile: CamProfile,
    pub geometry: FollowerGeometry,
    pub follower: FollowerKind,
    pub schedule: SpeedSchedule,
    /// Angles per revolution.
    pub angles: usize,
    pub load: LoadModel,
    /// Contact modulus E*, Pa.
    pub contact_modulus: f64,
    /// Poisson's ratio for the sub-surface stresses (the cam's).
    pub poisson_ratio: f64,
    pub lubricant: Lubricant,
    /// Oil inlet temperature, K.
    pub temperature: f64,
    pub roughness: Roughness,
    pub traction_law: TractionLaw,
    pub asperity_friction: AsperityFriction,
    pub cam_thermal: ThermalSolid,
    pub follower_thermal: ThermalSolid,
    pub slip: SlipMode,
    /// Indices of the angles whose film profiles (numerical model only) are returned.
    pub profile_angles: Vec<usize>,
}

/// What to compute. Dependencies are added by [`Needs::closed`].
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct Needs {
    pub loads: bool,
    pub contact: bool,
    pub film: bool,
    pub friction: bool,
    pub slip: bool,
    pub temperature: bool,
}

impl Needs {
    /// Add what the requested quantities depend on. Friction of a roller needs its slip.
    pub fn closed(mut self, roller: bool) -> Self {
        if self.temperature {
            self.friction = true;
        }
        if self.friction && roller {
            self.slip = true;
        }
        if !roller {
            self.slip = false;
        }
        if self.slip || self.friction {
            self.film = true;
        }
        if self.film {
            self.contact = true;
        }
        if self.contact {
            self.loads = true;
        }
        self
    }
}

/// Per-angle results; a field is `None` when it was not computed or does not apply.
#[derive(Debug, Clone, Default)]
pub struct CycleSeries {
    pub angle: Vec<f64>,
    pub time: Vec<f64>,
    pub cam_speed: Vec<f64>,
    pub lift: Vec<f64>,
    pub velocity: Vec<f64>,
    pub acceleration: Vec<f64>,
    pub jerk: Vec<f64>,
    pub pressure_angle: Vec<f64>,
    pub cam_curvature: Vec<f64>,
    pub reduced_radius: Vec<f64>,
    pub contact_offset: Vec<f64>,
    pub cam_surface_velocity: Vec<f64>,
    pub follower_surface_velocity: Vec<f64>,
    pub entrainment_velocity: Vec<f64>,
    pub sliding_velocity: Vec<f64>,
    pub axial_load: Option<Vec<f64>>,
    pub contact_load: Option<Vec<f64>>,
    pub load_per_length: Option<Vec<f64>>,
    pub effective_length: Option<Vec<f64>>,
    pub hertz_max_pressure: Option<Vec<f64>>,
    pub hertz_half_width: Option<Vec<f64>>,
    pub max_shear_stress: Option<Vec<f64>>,
    pub max_shear_depth: Option<Vec<f64>>,
    /// Central elastic deflection of a line contact (seed 003 eq. 6, `b` read as the line's
    /// half-length), m; straight line contacts only.
    pub contact_deflection: Option<Vec<f64>>,
    pub film_central: Option<Vec<f64>>,
    pub film_min: Option<Vec<f64>>,
    /// Film model that ran at each angle.
    pub film_model: Option<Vec<FilmModelId>>,
    /// Exit-constriction film (the closed forms' minimum film), m.
    pub exit_film: Option<Vec<f64>>,
    /// Exit pressure spike height and position (present when any angle resolved one; `None` at
    /// the angles without).
    pub pressure_spike: Option<Vec<Option<(f64, f64)>>>,
    /// Edge pressure peak (Pa, axial position m) of the 2-D finite model, and where its minimum
    /// film sits axially (m); present when that model ran at any angle.
    pub edge_pressure_peak: Option<Vec<Option<(f64, f64)>>>,
    pub min_film_axial_position: Option<Vec<Option<f64>>>,
    /// Newton steps of the numerical model at each angle (present when it ran at any angle).
    pub newton_steps: Option<Vec<u32>>,
    pub lambda: Option<Vec<f64>>,
    pub asperity_load_fraction: Option<Vec<f64>>,
    pub friction_force: Option<Vec<f64>>,
    pub friction_coefficient: Option<Vec<f64>>,
    pub friction_torque: Option<Vec<f64>>,
    pub camshaft_torque: Option<Vec<f64>>,
    pub power_loss: Option<Vec<f64>>,
    pub roller_speed: Option<Vec<f64>>,
    pub slide_roll_ratio: Option<Vec<f64>>,
    /// Rolling, micro-slip or gross sliding at each angle (roller followers).
    pub slip_regime: Option<Vec<crate::friction::SlipRegime>>,
    pub pin_torque: Option<Vec<f64>>,
    /// Effective film temperature of a thermal roller–pin bearing, K.
    pub pin_temperature: Option<Vec<f64>>,
    pub flash_temperature: Option<Vec<f64>>,
    /// Thermal EHL model: largest film temperature and largest surface temperatures of cam and
    /// follower at each angle, K (the inlet temperature where a closed form answered).
    pub film_temperature_max: Option<Vec<f64>>,
    pub surface_temperature_cam: Option<Vec<f64>>,
    pub surface_temperature_follower: Option<Vec<f64>>,
}

/// What happened over the cycle besides the series.
#[derive(Debug, Clone, Default)]
pub struct CycleEvents {
    /// Cam angles (rad) where the entrainment velocity changes sign (interpolated).
    pub zero_entrainment: Vec<f64>,
    /// Angle ranges (rad, start–end) where the follower would separate from the cam.
    pub separation: Vec<(f64, f64)>,
    /// Smallest axial load over the cycle, N (negative: separation).
    pub min_axial_load: Option<f64>,
}

/// Result of [`run_cycle`].
#[derive(Debug, Clone)]
pub struct CycleOutput {
    pub series: CycleSeries,
    pub events: CycleEvents,
    /// Convergence of the roller speed's periodicity (closed form otherwise).
    pub convergence: Convergence,
    /// Time of one revolution (steady) or of the simulated revolution (startup), s.
    pub duration: f64,
    /// Film profiles at [`CycleSpec::profile_angles`] where the model has one: `(index, profile)`.
    pub profiles: Vec<(usize, FilmProfile)>,
    /// 2-D pressure and film fields at [`CycleSpec::profile_angles`] where the finite-length/point
    /// model ran: `(index, fields)`.
    pub fields: Vec<(usize, Fields2d)>,
}

/// State of the contact at one angle after film, traction and slip.
#[derive(Debug, Clone)]
struct PointState {
    film: FilmSolution,
    traction: Traction,
    /// Roller speed (rad/s), 0 for non-rotating followers.
    omega: f64,
    pin_torque: f64,
    pin_temperature: Option<f64>,
}

/// The roller's part of [`PointState`] while the cycle is marched.
#[derive(Debug, Clone, Copy)]
struct Slip {
    traction: Traction,
    omega: f64,
    pin_torque: f64,
    pin_temperature: Option<f64>,
}

struct Context<'a> {
    spec: &'a CycleSpec,
    kin: &'a [KinematicState],
    loads: &'a [FollowerLoad],
    shapes: &'a [ContactShape],
    model: &'a dyn FilmModel,
    /// The run's observer: film solves poll it through their input's `interrupts`.
    observer: &'a dyn Observer,
}
