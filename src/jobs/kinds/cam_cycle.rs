//! `cam_cycle`: a cam–follower pair over one revolution — kinematics, loads, Hertz contact and
//! sub-surface shear, lubricant film, friction and power loss, roller slip (steady or startup),
//! flash temperature. Physics in `physics::cam`, `physics::film`, `physics::friction`,
//! `physics::roller`, `physics::thermal`.
//!
//! Only what `outputs` asks for is computed (with its dependencies): a kinematics-only request
//! runs no contact, film or slip.

use super::common::{composite_sigma, AsperitySpec, Material, EhlSpec, FilmSpec, LubricantSpec, TractionSpec};
use crate::jobs::kind::{Kind, Limits, OutputInfo, Validation};
use crate::physics::cam::cycle::{run_cycle, CycleSpec, FollowerKind, Needs, SlipMode};
use crate::physics::cam::{CamProfile, FollowerGeometry, FollowerShape, LiftLaw, LiftProgram, LoadModel, MultiArc, PeriodicSpline, PeriodicTable, SpeedSchedule};
use crate::physics::contact::{contact_modulus, Elastic};
use crate::physics::film::{model_for, Fidelity, FilmModelId};
use std::collections::BTreeMap;
use crate::physics::roller::{Crown, PinFriction, RollerParams};
use crate::physics::thermal::ThermalSolid;
use crate::physics::{Convergence, Observer, SolveError};
use serde::{Deserialize, Serialize};
use serde_json::{json, Value};
use std::f64::consts::PI;
use utoipa::ToSchema;

pub struct CamCycle;

// ---------------------------------------------------------------- spec

/// One circular arc of a multi-arc cam.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct ArcSpec {
    /// Radius of curvature, m.
    pub radius: f64,
    /// Central angle of the arc (angle its normal turns), degrees.
    pub angle_deg: f64,
}

/// Cam profile. Profiles are given in the order the follower meets them as the cam turns.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, ToSchema)]
#[serde(tag = "type", rename_all = "snake_case", deny_unknown_fields)]
pub enum ProfileSpec {
    /// Rise – top dwell – return – base dwell with a lift law (the follower's motion).
    RiseReturn {
        /// Base circle radius, m.
        base_radius: f64,
        /// Total lift, m.
        lift: f64,
        /// Cam angle where the rise starts, degrees. Default 0.
        #[serde(default)]
        rise_start_deg: f64,
        /// Rise angle, degrees.
        rise_deg: f64,
        /// Dwell at full lift, degrees. Default 0.
        #[serde(default)]
        top_dwell_deg: f64,
        /// Return angle, degrees.
        return_deg: f64,
        /// Lift law of the rise (and of the return unless `return_law` is given).
        law: LiftLaw,
        #[serde(default, skip_serializing_if = "Option::is_none")]
        return_law: Option<LiftLaw>,
    },
    /// Tangent circular arcs `(radius, angle)`; the first is the base circle (centred on the
    /// rotation axis, centred on cam angle 0). They must close (angles sum to 360°, the chain of
    /// centres returns to the axis).
    MultiArc { arcs: Vec<ArcSpec> },
    /// A cam symmetric about its nose (at 180°): base circle over `base_angle_deg`, then `flanks`
    /// from the base circle towards the nose; the nose radius is computed to close the cam.
    SymmetricArcs {
        /// Base circle radius, m.
        base_radius: f64,
        /// Angle of the base circle arc, degrees.
        base_angle_deg: f64,
        flanks: Vec<ArcSpec>,
    },
    /// A measured follower lift table, interpolated by a periodic cubic spline.
    Table {
        /// Base circle radius, m.
        base_radius: f64,
        /// Cam angles, degrees, increasing, within one revolution.
        angle_deg: Vec<f64>,
        /// Follower lift at each angle, m.
        lift: Vec<f64>,
    },
}

/// Direction the cam turns (matters only with an offset follower).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize, ToSchema)]
#[serde(rename_all = "snake_case")]
pub enum Direction {
    #[default]
    Ccw,
    Cw,
}

/// The cam lobe.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct CamSpec {
    pub profile: ProfileSpec,
    /// Axial width of the lobe, m: the line-contact length of a flat follower (required for
    /// `flat_faced`); limits a roller's contact length when smaller than the roller.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub width: Option<f64>,
    /// Elastic constants. Default: steel.
    #[serde(default)]
    pub material: Material,
    /// RMS surface roughness Rq, m. Default 0 (smooth).
    #[serde(default)]
    pub roughness_rq: f64,
}

/// Roller–pin friction.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize, ToSchema)]
#[serde(tag = "model", rename_all = "snake_case", deny_unknown_fields)]
pub enum PinSpec {
    /// Constant friction coefficient on the pin radius (seed 001).
    Coefficient { coefficient: f64 },
    /// Short hydrodynamic journal bearing (Ocvirk) with the spec's lubricant at its inlet
    /// temperature. `length` defaults to the roller length.
    Hydrodynamic {
        #[serde(default, skip_serializing_if = "Option::is_none")]
        length: Option<f64>,
    },
}

/// Crowned roller profile (seed 000 Table 1). See `physics::roller::crown`.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct CrownSpec {
    /// Middle length L1, m.
    pub middle_length: f64,
    /// Crown height h_td at the ends of the middle section, m.
    pub crown_height: f64,
    /// End profile radius R_d, m.
    pub end_radius: f64,
}

fn default_clearance() -> f64 {
    10e-6
}
fn default_roller_density() -> f64 {
    7850.0
}

/// The follower.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, ToSchema)]
#[serde(tag = "type", rename_all = "snake_case", deny_unknown_fields)]
pub enum FollowerSpec {
    /// Translating flat-faced tappet (seed 003).
    FlatFaced {
        /// Offset of the follower axis from the cam centre, m (does not change a flat face's
        /// kinematics). Default 0.
        #[serde(default)]
        offset: f64,
        /// Radius of the face, m: the contact must stay on it (`contact_off_face` otherwise).
        #[serde(default, skip_serializing_if = "Option::is_none")]
        face_radius: Option<f64>,
        /// Elastic constants. Default: steel.
        #[serde(default)]
        material: Material,
        #[serde(default)]
        roughness_rq: f64,
    },
    /// Translating roller follower (seeds 000, 001).
    Roller {
        /// Outer radius R_f, m.
        radius: f64,
        /// Roller length, m.
        length: f64,
        /// Pin radius, m.
        pin_radius: f64,
        /// Radial roller–pin clearance, m. Default 10e-6.
        #[serde(default = "default_clearance")]
        clearance: f64,
        /// Moment of inertia about the pin, kg·m². Default: a steel ring of the given radii
        /// and length.
        #[serde(default, skip_serializing_if = "Option::is_none")]
        inertia: Option<f64>,
        /// Density used for the default inertia, kg/m³. Default 7850.
        #[serde(default = "default_roller_density")]
        density: f64,
        pin: PinSpec,
        #[serde(default, skip_serializing_if = "Option::is_none")]
        crown: Option<CrownSpec>,
        /// Offset of the follower axis from the cam centre, m. Default 0.
        #[serde(default)]
        offset: f64,
        /// Elastic constants. Default: steel.
        #[serde(default)]
        material: Material,
        #[serde(default)]
        roughness_rq: f64,
    },
    /// Translating tappet with a spherical face (seed 004): point contact, no tappet spin.
    Spherical {
        /// Radius of the spherical face, m.
        radius: f64,
        #[serde(default)]
        offset: f64,
        /// Elastic constants. Default: steel.
        #[serde(default)]
        material: Material,
        #[serde(default)]
        roughness_rq: f64,
    },
}

fn default_rated_angle() -> f64 {
    180.0
}

/// Startup from rest (seed 000 §4.2): constant cam acceleration reaching the rated speed at
/// `rated_angle_deg`; the roller starts at rest; one revolution is simulated.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct StartupSpec {
    /// Cam angle at which the rated speed is reached, degrees. Default 180.
    #[serde(default = "default_rated_angle")]
    pub rated_angle_deg: f64,
}

/// Running condition.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct OperationSpec {
    /// Camshaft speed (rated speed for a startup), rev/min.
    #[schema(example = 950.0)]
    pub speed_rpm: f64,
    /// `ccw` (default) or `cw`.
    #[serde(default)]
    pub direction: Direction,
    /// Present: simulate a startup instead of steady running.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub startup: Option<StartupSpec>,
}

/// A periodic force table versus cam angle (linear interpolation).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct ForceTable {
    /// Cam angles, degrees.
    pub angle_deg: Vec<f64>,
    /// Force, N.
    pub force: Vec<f64>,
}

/// How the follower is loaded.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, ToSchema)]
#[serde(tag = "type", rename_all = "snake_case", deny_unknown_fields)]
pub enum LoadSpec {
    /// Spring preload + rate × lift + moving mass × acceleration (+ external force table),
    /// along the follower axis; the contact force is that over cos(pressure angle).
    ValveTrain {
        /// Spring force at zero lift, N.
        spring_preload: f64,
        /// Spring rate, N/m.
        spring_stiffness: f64,
        /// Moving mass reduced to the follower, kg.
        moving_mass: f64,
        /// External force along the follower axis pushing it onto the cam (e.g. gas force), N.
        #[serde(default, skip_serializing_if = "Option::is_none")]
        external: Option<ForceTable>,
    },
    /// A measured contact-load spectrum (seed 000 Fig. 4).
    Spectrum {
        /// Cam angles, degrees.
        angle_deg: Vec<f64>,
        /// Normal contact load, N.
        load: Vec<f64>,
        /// Constant added to the table (seed 000's modified load w1), N. Default 0.
        #[serde(default)]
        offset: f64,
    },
}

/// Roller speed model.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize, ToSchema)]
#[serde(rename_all = "snake_case")]
pub enum SlipModeSpec {
    /// Torque balance: traction drives the roller against pin friction and inertia.
    #[default]
    TorqueBalance,
    /// The roller rolls without slip (no traction): seed 000's comparison case.
    PureRolling,
}

fn default_slip_tol() -> f64 {
    1e-8
}
fn default_max_cycles() -> usize {
    50
}

/// Roller slip options.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct SlipSpec {
    #[serde(default)]
    pub mode: SlipModeSpec,
    /// Steady running: change of the roller speed between cycles, relative to the rolling
    /// speed, that ends the periodic iteration — at the angle where the march starts (the end of
    /// the longest stretch of constant conditions, usually the base-circle dwell; 0° if there is
    /// none) and where a later cycle rejoins the previous one. Default 1e-8.
    #[serde(default = "default_slip_tol")]
    pub tolerance: f64,
    /// Most cycles of the periodic iteration. Default 50.
    #[serde(default = "default_max_cycles")]
    pub max_cycles: usize,
}

impl Default for SlipSpec {
    fn default() -> Self {
        SlipSpec { mode: SlipModeSpec::TorqueBalance, tolerance: default_slip_tol(), max_cycles: default_max_cycles() }
    }
}

fn default_k() -> f64 {
    46.0
}
fn default_rho_s() -> f64 {
    7850.0
}
fn default_c() -> f64 {
    470.0
}

/// Thermal properties of a solid (defaults: steel of seed 000 Table 1).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct ThermalSpec {
    /// W/(m·K). Default 46.
    #[serde(default = "default_k")]
    pub conductivity: f64,
    /// kg/m³. Default 7850.
    #[serde(default = "default_rho_s")]
    pub density: f64,
    /// J/(kg·K). Default 470.
    #[serde(default = "default_c")]
    pub specific_heat: f64,
}

impl Default for ThermalSpec {
    fn default() -> Self {
        ThermalSpec { conductivity: default_k(), density: default_rho_s(), specific_heat: default_c() }
    }
}

impl ThermalSpec {
    fn to_physics(self) -> ThermalSolid {
        ThermalSolid { conductivity: self.conductivity, density: self.density, specific_heat: self.specific_heat }
    }
}

/// Thermal properties of cam and follower (flash temperature).
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct ThermalPair {
    #[serde(default)]
    pub cam: ThermalSpec,
    #[serde(default)]
    pub follower: ThermalSpec,
}

/// Optional outputs (with what they need). Default: all.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, ToSchema)]
#[serde(rename_all = "snake_case")]
pub enum CamOutput {
    /// Lift, velocity, acceleration, jerk, pressure angle, curvature, surface velocities.
    Kinematics,
    /// Axial and contact loads, separation.
    Loads,
    /// Hertz pressure and width, sub-surface shear.
    Contact,
    /// Central and minimum film, λ, asperity load share.
    Film,
    /// Friction force and coefficient, torques, power loss (rollers: needs slip).
    Friction,
    /// Roller speed, slide-to-roll ratio, pin torque (roller followers).
    Slip,
    /// Flash temperature.
    Temperature,
    /// Pressure and film profiles at `profile_angles_deg` (numerical film model only; not in the
    /// default list).
    Profiles,
}

fn default_angles() -> usize {
    720
}
pub fn default_outputs() -> Vec<CamOutput> {
    vec![
        CamOutput::Kinematics,
        CamOutput::Loads,
        CamOutput::Contact,
        CamOutput::Film,
        CamOutput::Friction,
        CamOutput::Slip,
        CamOutput::Temperature,
    ]
}

/// Spec of a `cam_cycle` job. SI units; angles in degrees where the name says so.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct CamCycleSpec {
    pub cam: CamSpec,
    pub follower: FollowerSpec,
    pub operation: OperationSpec,
    /// Required unless only `kinematics` is requested.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub load: Option<LoadSpec>,
    /// Required when `film`, `friction`, `slip` or `temperature` is requested.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub lubricant: Option<LubricantSpec>,
    /// Greenwood–Tripp statistics and boundary friction (used when a surface is rough).
    #[serde(default)]
    pub asperities: AsperitySpec,
    #[serde(default)]
    pub traction: TractionSpec,
    #[serde(default)]
    pub film: FilmSpec,
    #[serde(default)]
    pub slip: SlipSpec,
    #[serde(default)]
    pub thermal: ThermalPair,
    /// Film model: `fast` (closed forms, default), `accurate` (the numerical line-contact EHL
    /// solver at every angle, with squeeze between consecutive angles; point contacts of a
    /// spherical tappet keep the closed form), `auto` (the closed form where its estimated error
    /// is within `ehl.auto_tolerance`, the numerical solver elsewhere: near zero entrainment,
    /// outside the closed form's load range, strong squeeze, closed-form traction off at light
    /// loads; rules in `physics::film::auto`). The series column `model` says which ran at each
    /// angle. The instant of rest at the start of a startup (no entrainment, no film history) has
    /// no lubricated solution and reports the closed form there. Thermal effects are not modelled
    /// by either model.
    #[serde(default)]
    pub fidelity: Fidelity,
    /// Numerical EHL options (`accurate`, `auto`).
    #[serde(default)]
    pub ehl: EhlSpec,
    /// Cam angles (degrees) of the pressure and film profiles (output `profiles`); each is taken
    /// at the nearest computed angle.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub profile_angles_deg: Vec<f64>,
    /// Cam angles per revolution (uniform). Default 720.
    #[serde(default = "default_angles")]
    pub angles: usize,
    /// What to compute (with dependencies). Default: everything.
    #[serde(default = "default_outputs")]
    pub outputs: Vec<CamOutput>,
}

// ---------------------------------------------------------------- result

/// Per-angle results, columnar, SI units, angles in degrees. A column is absent when it was not
/// requested or does not apply; velocities are tangential components relative to the moving
/// contact point, positive in the direction of the cam surface's motion on the base circle.
#[derive(Debug, Clone, PartialEq, Default, Serialize, ToSchema)]
pub struct CamSeries {
    /// Cam angle, degrees.
    pub angle_deg: Vec<f64>,
    /// Time since the start of the revolution, s.
    pub time: Vec<f64>,
    /// Camshaft angular speed, rad/s.
    pub cam_speed: Vec<f64>,
    /// Follower lift, m.
    pub lift: Vec<f64>,
    /// Follower velocity, m/s.
    pub velocity: Vec<f64>,
    /// Follower acceleration, m/s².
    pub acceleration: Vec<f64>,
    /// Follower jerk, m/s³.
    pub jerk: Vec<f64>,
    /// Pressure angle, degrees.
    pub pressure_angle_deg: Vec<f64>,
    /// Cam curvature at the contact, 1/m (convex positive; radius = 1/curvature).
    pub cam_curvature: Vec<f64>,
    /// Reduced radius of curvature in the plane of motion, m.
    pub reduced_radius: Vec<f64>,
    /// Contact point position relative to the follower axis, m.
    pub contact_offset: Vec<f64>,
    /// Cam surface velocity, m/s.
    pub cam_surface_velocity: Vec<f64>,
    /// Follower surface velocity, m/s (rollers: from the slip solution when computed, else pure
    /// rolling).
    pub follower_surface_velocity: Vec<f64>,
    /// Mean entrainment velocity (u_c + u_f)/2, m/s.
    pub entrainment_velocity: Vec<f64>,
    /// Sliding velocity u_c − u_f, m/s.
    pub sliding_velocity: Vec<f64>,
    /// Force along the follower axis, N.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub axial_load: Option<Vec<f64>>,
    /// Normal contact load, N.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub contact_load: Option<Vec<f64>>,
    /// Peak load per unit length, N/m (line contacts).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub load_per_length: Option<Vec<f64>>,
    /// Axially loaded length of a crowned roller, m.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub effective_length: Option<Vec<f64>>,
    /// Hertz peak pressure p0, Pa.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub hertz_max_pressure: Option<Vec<f64>>,
    /// Hertz semi-width along the rolling direction, m.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub hertz_half_width: Option<Vec<f64>>,
    /// Maximum sub-surface principal shear stress (0.300 p0 for ν = 0.3), Pa (line contacts).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub max_shear_stress: Option<Vec<f64>>,
    /// Its depth (0.786 b), m.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub max_shear_depth: Option<Vec<f64>>,
    /// Central film thickness, m.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub film_central: Option<Vec<f64>>,
    /// Minimum film thickness, m.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub film_min: Option<Vec<f64>>,
    /// Film model that ran at each angle (`numerical` or the closed form's name).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub model: Option<Vec<FilmModelId>>,
    /// Smallest film downstream of the contact centre (exit constriction), m; the closed forms'
    /// minimum film at their angles.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub exit_film: Option<Vec<f64>>,
    /// Height (peak pressure) of the exit pressure spike, Pa, resolved by the numerical model.
    /// Present when any angle resolved one; `null` at angles where none was computed or found
    /// (closed-form angles, and numerical solutions without a secondary exit maximum, e.g. light
    /// loads). Empty cells in CSV.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub pressure_spike: Option<Vec<Option<f64>>>,
    /// Position of the spike, m from the contact centre along the entrainment direction of
    /// positive entrainment velocity; `null` where `pressure_spike` is.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub pressure_spike_position: Option<Vec<Option<f64>>>,
    /// Newton steps of the numerical EHL solver at each angle (0 at closed-form angles). Present
    /// when the numerical model ran.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub newton_steps: Option<Vec<f64>>,
    /// λ = h_min/σ (rough surfaces).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub lambda: Option<Vec<f64>>,
    /// Share of the load carried by asperities (Greenwood–Tripp).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub asperity_load_fraction: Option<Vec<f64>>,
    /// Tangential (traction) force on the follower, N, positive when it drags the follower
    /// surface forward.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub friction_force: Option<Vec<f64>>,
    /// friction_force / contact_load.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub friction_coefficient: Option<Vec<f64>>,
    /// Camshaft torque of the friction force, N·m.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub friction_torque: Option<Vec<f64>>,
    /// Camshaft torque of all contact forces (normal + friction), N·m.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub camshaft_torque: Option<Vec<f64>>,
    /// Dissipated power: contact sliding + roller–pin, W.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub power_loss: Option<Vec<f64>>,
    /// Roller angular speed, rad/s.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub roller_speed: Option<Vec<f64>>,
    /// Slide-to-roll ratio 2(u_c − u_r)/(u_c + u_r).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub slide_roll_ratio: Option<Vec<f64>>,
    /// Roller–pin friction torque, N·m.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub pin_torque: Option<Vec<f64>>,
    /// Maximum flash temperature rise (Blok/Jaeger), K.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub flash_temperature: Option<Vec<f64>>,
}

/// Cycle summary: flat numbers (what a sweep tabulates). Absent when not computed.
#[derive(Debug, Clone, PartialEq, Default, Serialize, ToSchema)]
pub struct CamSummary {
    /// m.
    pub max_lift: f64,
    /// m/s.
    pub max_velocity: f64,
    /// m/s².
    pub max_acceleration: f64,
    /// m/s².
    pub min_acceleration: f64,
    /// m/s³.
    pub max_abs_jerk: f64,
    /// Degrees.
    pub max_abs_pressure_angle_deg: f64,
    /// Smallest convex cam radius of curvature, m.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub min_cam_radius_of_curvature: Option<f64>,
    /// m.
    pub min_reduced_radius: f64,
    /// Number of entrainment reversals (zero-entrainment angles) in the cycle.
    pub zero_entrainment_count: usize,
    /// N.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub max_contact_load: Option<f64>,
    /// N (negative: the follower separates).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub min_axial_load: Option<f64>,
    /// Pa.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub max_hertz_pressure: Option<f64>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub max_hertz_pressure_angle_deg: Option<f64>,
    /// Largest sub-surface principal shear stress over the cycle, Pa.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub max_subsurface_shear: Option<f64>,
    /// m.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub min_film: Option<f64>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub min_film_angle_deg: Option<f64>,
    /// m.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub min_central_film: Option<f64>,
    /// Per-angle counts of the film models that ran (`numerical`, `pan_hamrock`, …).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub fidelity_used: Option<BTreeMap<String, usize>>,
    /// Smallest exit-constriction film, m.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub min_exit_film: Option<f64>,
    /// Highest exit pressure spike, Pa, and its angle (numerical model).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub max_pressure_spike: Option<f64>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub max_pressure_spike_angle_deg: Option<f64>,
    /// Newton steps of the numerical EHL solver over the cycle (all solves, including the
    /// roller's re-solves and extra cycles).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub newton_steps: Option<f64>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub min_lambda: Option<f64>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub min_lambda_angle_deg: Option<f64>,
    /// Largest asperity load share.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub max_asperity_load_fraction: Option<f64>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub max_friction_coefficient: Option<f64>,
    /// Time-averaged friction coefficient |F_t|/F.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub mean_friction_coefficient: Option<f64>,
    /// Time-averaged camshaft friction torque, N·m.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub mean_friction_torque: Option<f64>,
    /// Time-averaged dissipated power, W.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub mean_power_loss: Option<f64>,
    /// Energy dissipated over the revolution, J.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub energy_loss: Option<f64>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub max_abs_slide_roll_ratio: Option<f64>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub max_abs_slide_roll_ratio_angle_deg: Option<f64>,
    /// Time-averaged slide-to-roll ratio.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub mean_slide_roll_ratio: Option<f64>,
    /// K.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub max_flash_temperature: Option<f64>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub max_flash_temperature_angle_deg: Option<f64>,
}

/// Events of the cycle.
#[derive(Debug, Clone, PartialEq, Default, Serialize, ToSchema)]
pub struct CamEvents {
    /// Cam angles where the entrainment velocity changes sign, degrees.
    pub zero_entrainment_angles_deg: Vec<f64>,
    /// Angle ranges `[start, end]` (degrees) where the follower would leave the cam.
    pub separation_ranges_deg: Vec<[f64; 2]>,
}

/// Pressure and film along the rolling direction at one cam angle.
#[derive(Debug, Clone, PartialEq, Serialize, ToSchema)]
pub struct FilmProfileAtAngle {
    /// Cam angle, degrees.
    pub angle_deg: f64,
    /// Position from the contact centre, m (positive in the direction of positive entrainment).
    pub x: Vec<f64>,
    /// Pressure, Pa.
    pub pressure: Vec<f64>,
    /// Film thickness, m.
    pub film: Vec<f64>,
}

/// Result of a `cam_cycle` job.
#[derive(Debug, Clone, PartialEq, Serialize, ToSchema)]
pub struct CamCycleResult {
    /// Fidelity that ran.
    pub fidelity_used: Fidelity,
    /// Film model that ran, when one model ran at every angle (absent when `auto` mixed models:
    /// see the series column `model` and `summary.fidelity_used`).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub film_model: Option<FilmModelId>,
    /// E* = 1/Σ(1−ν²)/E, Pa (Hertz, Greenwood–Tripp).
    pub contact_modulus: f64,
    /// E' = 2E*, Pa (film formulas).
    pub effective_modulus: f64,
    /// Angles per revolution.
    pub angles: usize,
    /// Duration of the simulated revolution, s.
    pub duration: f64,
    pub series: CamSeries,
    pub summary: CamSummary,
    pub events: CamEvents,
    /// Profiles at the requested angles where the numerical model ran (output `profiles`).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub profiles: Option<Vec<FilmProfileAtAngle>>,
    /// Periodicity of the roller speed (steady torque balance) or closed form.
    pub convergence: Convergence,
}

// ---------------------------------------------------------------- conversion

fn deg(x: f64) -> f64 {
    x * PI / 180.0
}

impl CamCycleSpec {
    /// What the spec's `outputs` ask the cycle to compute (dependencies included).
    pub fn needs(&self) -> Needs {
        let has = |o| self.outputs.contains(&o);
        Needs {
            loads: has(CamOutput::Loads),
            contact: has(CamOutput::Contact),
            film: has(CamOutput::Film) || has(CamOutput::Profiles),
            friction: has(CamOutput::Friction),
            slip: has(CamOutput::Slip),
            temperature: has(CamOutput::Temperature),
        }
        .closed(self.is_roller())
    }

    fn is_roller(&self) -> bool {
        matches!(self.follower, FollowerSpec::Roller { .. })
    }

    fn follower_elastic(&self) -> (Elastic, f64) {
        let (e, nu, rq) = match self.follower {
            FollowerSpec::FlatFaced { material, roughness_rq, .. }
            | FollowerSpec::Roller { material, roughness_rq, .. }
            | FollowerSpec::Spherical { material, roughness_rq, .. } => (material.youngs_modulus, material.poisson_ratio, roughness_rq),
        };
        (Elastic { youngs_modulus: e, poisson_ratio: nu }, rq)
    }

    fn profile(&self) -> Result<CamProfile, SolveError> {
        Ok(match &self.cam.profile {
            ProfileSpec::RiseReturn { base_radius, lift, rise_start_deg, rise_deg, top_dwell_deg, return_deg, law, return_law } => {
                CamProfile::Program {
                    base_radius: *base_radius,
                    program: LiftProgram {
                        lift: *lift,
                        rise_start: deg(*rise_start_deg),
                        rise: deg(*rise_deg),
                        top_dwell: deg(*top_dwell_deg),
                        fall: deg(*return_deg),
                        rise_law: *law,
                        return_law: return_law.unwrap_or(*law),
                    },
                }
            }
            ProfileSpec::MultiArc { arcs } => {
                let a: Vec<(f64, f64)> = arcs.iter().map(|a| (a.radius, deg(a.angle_deg))).collect();
                CamProfile::MultiArc(MultiArc::new(&a)?)
            }
            ProfileSpec::SymmetricArcs { base_radius, base_angle_deg, flanks } => {
                let f: Vec<(f64, f64)> = flanks.iter().map(|a| (a.radius, deg(a.angle_deg))).collect();
                CamProfile::MultiArc(MultiArc::symmetric(*base_radius, deg(*base_angle_deg), &f)?)
            }
            ProfileSpec::Table { base_radius, angle_deg, lift } => {
                let x: Vec<f64> = angle_deg.iter().map(|a| deg(*a)).collect();
                let spline = PeriodicSpline::new(&x, lift).map_err(|e| match e {
                    SolveError::InvalidInput { message, .. } => SolveError::invalid("/cam/profile", message),
                    other => other,
                })?;
                CamProfile::Tabulated { base_radius: *base_radius, spline }
            }
        })
    }

    /// The physics description of this spec.
    pub fn cycle_spec(&self) -> Result<CycleSpec, SolveError> {
        let profile = self.profile()?;
        let (follower_elastic, follower_rq) = self.follower_elastic();
        let cam_elastic = self.cam.material.elastic();
        let es = contact_modulus(cam_elastic, follower_elastic);
        let lub = self.lubricant.clone().unwrap_or(LubricantSpec {
            viscosity: 0.01,
            pressure_viscosity: 2e-8,
            temperature_viscosity: 0.0,
            reference_temperature: 313.0,
            temperature: None,
            density: 870.0,
            viscosity_model: Default::default(),
            density_model: Default::default(),
        });
        let lubricant = lub.to_physics();
        let temperature = lub.inlet_temperature();
        let (shape, follower) = match &self.follower {
            FollowerSpec::FlatFaced { .. } => (FollowerShape::Flat, FollowerKind::Flat { contact_length: self.cam.width.unwrap_or(0.0) }),
            FollowerSpec::Roller { radius, length, pin_radius, clearance, inertia, density, pin, crown, offset, .. } => {
                let inertia = inertia.unwrap_or_else(|| 0.5 * density * PI * length * (radius.powi(4) - pin_radius.powi(4)));
                let pin = match pin {
                    PinSpec::Coefficient { coefficient } => PinFriction::Coefficient { coefficient: *coefficient, pin_radius: *pin_radius },
                    PinSpec::Hydrodynamic { length: l } => PinFriction::ShortBearing {
                        pin_radius: *pin_radius,
                        clearance: *clearance,
                        length: l.unwrap_or(*length),
                        viscosity: lubricant.viscosity_at(0.0, temperature),
                    },
                };
                let contact_length = self.cam.width.map_or(*length, |w| w.min(*length));
                (
                    FollowerShape::Curved { radius: *radius, offset: *offset },
                    FollowerKind::Roller {
                        roller: RollerParams { radius: *radius, inertia, pin },
                        contact_length,
                        crown: crown.map(|c| Crown { length: *length, middle_length: c.middle_length, crown_height: c.crown_height, end_radius: c.end_radius }),
                    },
                )
            }
            FollowerSpec::Spherical { radius, offset, .. } => {
                (FollowerShape::Curved { radius: *radius, offset: *offset }, FollowerKind::Spherical { face_radius: *radius })
            }
        };
        let omega = crate::physics::units::rpm_to_rad_per_s(self.operation.speed_rpm);
        let schedule = match self.operation.startup {
            None => SpeedSchedule::Steady { omega },
            Some(s) => SpeedSchedule::Startup { omega, rated_angle: deg(s.rated_angle_deg) },
        };
        let load = match &self.load {
            None => LoadModel::ValveTrain { preload: 0.0, stiffness: 0.0, mass: 0.0, external: None },
            Some(LoadSpec::ValveTrain { spring_preload, spring_stiffness, moving_mass, external }) => LoadModel::ValveTrain {
                preload: *spring_preload,
                stiffness: *spring_stiffness,
                mass: *moving_mass,
                external: match external {
                    Some(t) => Some(table(&t.angle_deg, &t.force, "/load/external")?),
                    None => None,
                },
            },
            Some(LoadSpec::Spectrum { angle_deg, load, offset }) => LoadModel::Spectrum { table: table(angle_deg, load, "/load")?, offset: *offset },
        };
        Ok(CycleSpec {
            profile,
            geometry: FollowerGeometry { shape, clockwise: self.operation.direction == Direction::Cw },
            follower,
            schedule,
            angles: self.angles,
            load,
            contact_modulus: es,
            poisson_ratio: self.cam.material.poisson_ratio,
            lubricant,
            temperature,
            roughness: self.asperities.roughness(composite_sigma(self.cam.roughness_rq, follower_rq)),
            traction_law: self.traction.to_physics(),
            asperity_friction: self.asperities.friction(),
            cam_thermal: self.thermal.cam.to_physics(),
            follower_thermal: self.thermal.follower.to_physics(),
            slip: match self.slip.mode {
                SlipModeSpec::PureRolling => SlipMode::PureRolling,
                SlipModeSpec::TorqueBalance => SlipMode::TorqueBalance { tolerance: self.slip.tolerance, max_cycles: self.slip.max_cycles },
            },
            profile_angles: if self.outputs.contains(&CamOutput::Profiles) {
                let n = self.angles;
                let mut v: Vec<usize> = self
                    .profile_angles_deg
                    .iter()
                    .map(|a| ((a.rem_euclid(360.0) / 360.0 * n as f64).round() as usize) % n)
                    .collect();
                v.sort_unstable();
                v.dedup();
                v
            } else {
                Vec::new()
            },
        })
    }
}

fn table(angles_deg: &[f64], values: &[f64], path: &str) -> Result<PeriodicTable, SolveError> {
    let a: Vec<f64> = angles_deg.iter().map(|x| deg(*x)).collect();
    PeriodicTable::new(&a, values).map_err(|e| match e {
        SolveError::InvalidInput { message, .. } => SolveError::invalid(path, message),
        other => other,
    })
}

/// Index and value of the extreme of `v` by `better`.
fn extreme(v: &[f64], better: impl Fn(f64, f64) -> bool) -> (usize, f64) {
    let mut best = (0, v[0]);
    for (i, &x) in v.iter().enumerate() {
        if better(x, best.1) {
            best = (i, x);
        }
    }
    best
}

/// Time-average of `v` over the revolution: trapezoid in time with the wrap for steady running;
/// for a startup, the value at the end of each step over that step (what the implicit step
/// computes), so that the instant of rest at t = 0 carries no weight.
fn time_mean(v: &[f64], time: &[f64], duration: f64, periodic: bool) -> f64 {
    let n = v.len();
    if n == 1 {
        return v[0];
    }
    let mut integral = 0.0;
    if periodic {
        for i in 0..n - 1 {
            integral += 0.5 * (v[i] + v[i + 1]) * (time[i + 1] - time[i]);
        }
        integral += 0.5 * (v[n - 1] + v[0]) * (duration - time[n - 1]);
        integral / duration
    } else {
        for i in 1..n {
            integral += v[i] * (time[i] - time[i - 1]);
        }
        integral / (time[n - 1] - time[0])
    }
}

fn solve_spec(spec: &CamCycleSpec, observer: &dyn Observer) -> Result<CamCycleResult, SolveError> {
    let cycle = spec.cycle_spec()?;
    let needs = spec.needs();
    let model = needs.film.then(|| model_for(spec.fidelity, spec.film.to_physics(), spec.ehl.to_physics()));
    let fast = crate::physics::film::ClosedForm { formula: spec.film.formula, squeeze: spec.film.squeeze };
    let out = run_cycle(&cycle, needs, model.as_deref().unwrap_or(&fast), observer)?;
    let s = out.series;
    // Contact must stay on a flat face of finite radius.
    if let FollowerSpec::FlatFaced { face_radius: Some(r), offset, .. } = spec.follower {
        if let Some((i, x)) = s.contact_offset.iter().map(|x| x - offset).enumerate().find(|(_, x)| x.abs() > r) {
            return Err(SolveError::physical(
                crate::physics::PhysicalFailure::ContactOffFace,
                format!(
                    "the contact runs off the follower face at {:.2}° ({:.3} mm from its centre, face radius {:.3} mm)",
                    s.angle[i].to_degrees(),
                    x * 1e3,
                    r * 1e3
                ),
            ));
        }
    }
    let degs = |v: &[f64]| v.iter().map(|x| x.to_degrees()).collect::<Vec<_>>();
    let angle_deg = degs(&s.angle);
    let at = |i: usize| angle_deg[i];
    let periodic = spec.operation.startup.is_none();
    let mut summary = CamSummary {
        max_lift: s.lift.iter().copied().fold(f64::NEG_INFINITY, f64::max),
        max_velocity: s.velocity.iter().copied().fold(f64::NEG_INFINITY, f64::max),
        max_acceleration: s.acceleration.iter().copied().fold(f64::NEG_INFINITY, f64::max),
        min_acceleration: s.acceleration.iter().copied().fold(f64::INFINITY, f64::min),
        max_abs_jerk: s.jerk.iter().map(|x| x.abs()).fold(0.0, f64::max),
        max_abs_pressure_angle_deg: s.pressure_angle.iter().map(|x| x.abs().to_degrees()).fold(0.0, f64::max),
        min_cam_radius_of_curvature: {
            let k = s.cam_curvature.iter().copied().fold(0.0, f64::max);
            (k > 0.0).then(|| 1.0 / k)
        },
        min_reduced_radius: s.reduced_radius.iter().copied().fold(f64::INFINITY, f64::min),
        zero_entrainment_count: out.events.zero_entrainment.len(),
        min_axial_load: out.events.min_axial_load,
        ..Default::default()
    };
    if let Some(v) = &s.contact_load {
        summary.max_contact_load = Some(v.iter().copied().fold(f64::NEG_INFINITY, f64::max));
    }
    if let Some(v) = &s.hertz_max_pressure {
        let (i, p) = extreme(v, |a, b| a > b);
        summary.max_hertz_pressure = Some(p);
        summary.max_hertz_pressure_angle_deg = Some(at(i));
    }
    if let Some(v) = &s.max_shear_stress {
        summary.max_subsurface_shear = Some(v.iter().copied().fold(0.0, f64::max));
    }
    if let Some(v) = &s.film_min {
        let (i, h) = extreme(v, |a, b| a < b);
        summary.min_film = Some(h);
        summary.min_film_angle_deg = Some(at(i));
    }
    if let Some(v) = &s.film_central {
        summary.min_central_film = Some(v.iter().copied().fold(f64::INFINITY, f64::min));
    }
    if let Some(v) = &s.lambda {
        let (i, l) = extreme(v, |a, b| a < b);
        summary.min_lambda = Some(l);
        summary.min_lambda_angle_deg = Some(at(i));
    }
    if let Some(v) = &s.asperity_load_fraction {
        summary.max_asperity_load_fraction = Some(v.iter().copied().fold(0.0, f64::max));
    }
    if let Some(v) = &s.friction_coefficient {
        summary.max_friction_coefficient = Some(v.iter().map(|x| x.abs()).fold(0.0, f64::max));
        let abs: Vec<f64> = v.iter().map(|x| x.abs()).collect();
        summary.mean_friction_coefficient = Some(time_mean(&abs, &s.time, out.duration, periodic));
    }
    if let Some(v) = &s.friction_torque {
        summary.mean_friction_torque = Some(time_mean(v, &s.time, out.duration, periodic));
    }
    if let Some(v) = &s.power_loss {
        let mean = time_mean(v, &s.time, out.duration, periodic);
        summary.mean_power_loss = Some(mean);
        let span = if periodic { out.duration } else { s.time[s.time.len() - 1] - s.time[0] };
        summary.energy_loss = Some(mean * span);
    }
    if let Some(v) = &s.slide_roll_ratio {
        let (i, _) = extreme(v, |a, b| a.abs() > b.abs());
        summary.max_abs_slide_roll_ratio = Some(v[i].abs());
        summary.max_abs_slide_roll_ratio_angle_deg = Some(at(i));
        summary.mean_slide_roll_ratio = Some(time_mean(v, &s.time, out.duration, periodic));
    }
    if let Some(v) = &s.flash_temperature {
        let (i, t) = extreme(v, |a, b| a > b);
        summary.max_flash_temperature = Some(t);
        summary.max_flash_temperature_angle_deg = Some(at(i));
    }
    // The film model when one model ran at every angle (absent when `auto` mixed them).
    let film_model = s.film_model.as_ref().and_then(|v| {
        let first = *v.first()?;
        v.iter().all(|m| *m == first).then_some(first)
    });
    if let Some(v) = &s.film_model {
        let mut counts = BTreeMap::new();
        for m in v {
            *counts.entry(m.name().to_string()).or_insert(0) += 1;
        }
        summary.fidelity_used = Some(counts);
    }
    if let Some(v) = &s.exit_film {
        summary.min_exit_film = Some(v.iter().copied().fold(f64::INFINITY, f64::min));
    }
    let (spike, spike_position) = match &s.pressure_spike {
        Some(v) => {
            if let Some((i, m)) = v
                .iter()
                .enumerate()
                .filter_map(|(i, x)| x.map(|(p, _)| (i, p)))
                .max_by(|a, b| a.1.total_cmp(&b.1))
            {
                summary.max_pressure_spike = Some(m);
                summary.max_pressure_spike_angle_deg = Some(at(i));
            }
            (Some(v.iter().map(|x| x.map(|x| x.0)).collect()), Some(v.iter().map(|x| x.map(|x| x.1)).collect()))
        }
        None => (None, None),
    };
    if let Some(v) = &s.newton_steps {
        summary.newton_steps = Some(v.iter().map(|&k| k as f64).sum());
    }
    let profiles = spec.outputs.contains(&CamOutput::Profiles).then(|| {
        out.profiles
            .iter()
            .map(|(i, p)| FilmProfileAtAngle { angle_deg: at(*i), x: p.x.clone(), pressure: p.pressure.clone(), film: p.film.clone() })
            .collect()
    });
    let es = cycle.contact_modulus;
    Ok(CamCycleResult {
        fidelity_used: spec.fidelity,
        film_model,
        contact_modulus: es,
        effective_modulus: 2.0 * es,
        angles: spec.angles,
        duration: out.duration,
        series: CamSeries {
            angle_deg,
            time: s.time,
            cam_speed: s.cam_speed,
            lift: s.lift,
            velocity: s.velocity,
            acceleration: s.acceleration,
            jerk: s.jerk,
            pressure_angle_deg: degs(&s.pressure_angle),
            cam_curvature: s.cam_curvature,
            reduced_radius: s.reduced_radius,
            contact_offset: s.contact_offset,
            cam_surface_velocity: s.cam_surface_velocity,
            follower_surface_velocity: s.follower_surface_velocity,
            entrainment_velocity: s.entrainment_velocity,
            sliding_velocity: s.sliding_velocity,
            axial_load: s.axial_load,
            contact_load: s.contact_load,
            load_per_length: s.load_per_length,
            effective_length: s.effective_length,
            hertz_max_pressure: s.hertz_max_pressure,
            hertz_half_width: s.hertz_half_width,
            max_shear_stress: s.max_shear_stress,
            max_shear_depth: s.max_shear_depth,
            film_central: s.film_central,
            film_min: s.film_min,
            model: s.film_model,
            exit_film: s.exit_film,
            pressure_spike: spike,
            pressure_spike_position: spike_position,
            newton_steps: s.newton_steps.map(|v| v.into_iter().map(f64::from).collect()),
            lambda: s.lambda,
            asperity_load_fraction: s.asperity_load_fraction,
            friction_force: s.friction_force,
            friction_coefficient: s.friction_coefficient,
            friction_torque: s.friction_torque,
            camshaft_torque: s.camshaft_torque,
            power_loss: s.power_loss,
            roller_speed: s.roller_speed,
            slide_roll_ratio: s.slide_roll_ratio,
            pin_torque: s.pin_torque,
            flash_temperature: s.flash_temperature,
        },
        summary,
        events: CamEvents {
            zero_entrainment_angles_deg: degs(&out.events.zero_entrainment),
            separation_ranges_deg: out.events.separation.iter().map(|(a, b)| [a.to_degrees(), b.to_degrees()]).collect(),
        },
        profiles,
        convergence: out.convergence,
    })
}

impl Kind for CamCycle {
    const NAME: &'static str = "cam_cycle";
    const SOLVER_VERSION: &'static str = "cam_cycle-4";
    const DESCRIPTION: &'static str = "Cam–follower pair over one revolution: kinematics, loads, Hertz contact, \
        lubricant film, friction and power loss, roller slip (steady or startup) and flash temperature \
        (fidelity fast: closed forms; accurate: numerical line-contact EHL with squeeze at every angle; auto: \
        closed forms where their estimated error is within tolerance).";
    const TABLES: &'static [&'static str] = &["series"];
    type Spec = CamCycleSpec;
    type Output = CamCycleResult;

    fn example() -> Value {
        json!({
            "cam": {
                "profile": {"type": "rise_return", "base_radius": 0.018, "lift": 0.008, "rise_start_deg": 90.0,
                            "rise_deg": 90.0, "return_deg": 90.0, "law": "cycloidal"},
                "width": 0.012
            },
            "follower": {"type": "flat_faced"},
            "operation": {"speed_rpm": 3000.0},
            "load": {"type": "valve_train", "spring_preload": 300.0, "spring_stiffness": 38000.0, "moving_mass": 0.25},
            "lubricant": {"viscosity": 0.01, "pressure_viscosity": 2.2e-8},
            "angles": 720
        })
    }

    fn outputs() -> &'static [OutputInfo] {
        &[
            OutputInfo { name: "kinematics", description: "lift, velocity, acceleration, jerk, pressure angle, curvature, surface velocities (always computed)" },
            OutputInfo { name: "loads", description: "axial and contact loads, follower separation" },
            OutputInfo { name: "contact", description: "Hertz pressure and half-width, sub-surface shear maximum" },
            OutputInfo { name: "film", description: "central and minimum film, lambda ratio, asperity load share" },
            OutputInfo { name: "friction", description: "traction, friction coefficient, camshaft friction torque, power loss" },
            OutputInfo { name: "slip", description: "roller speed, slide-to-roll ratio, pin torque (roller followers)" },
            OutputInfo { name: "temperature", description: "flash temperature rise (Blok/Jaeger)" },
            OutputInfo { name: "profiles", description: "pressure and film profiles at profile_angles_deg (accurate/auto; not in the default list)" },
        ]
    }

    fn validate(spec: &CamCycleSpec, limits: &Limits, v: &mut Validation) {
        v.count_in_range("/angles", spec.angles, 8, usize::MAX);
        v.limit("/angles", spec.angles, limits.max_angles, "the number of cam angles");
        spec.ehl.validate("/ehl", limits, v);
        if spec.outputs.contains(&CamOutput::Profiles) {
            v.check(spec.fidelity != Fidelity::Fast, "/outputs", "profiles need fidelity accurate or auto (the closed forms have none)");
            v.check(!spec.profile_angles_deg.is_empty(), "/profile_angles_deg", "the profiles output needs at least one angle");
            v.check(spec.profile_angles_deg.len() <= 64, "/profile_angles_deg", "at most 64 profile angles");
            v.check(spec.profile_angles_deg.iter().all(|a| a.is_finite()), "/profile_angles_deg", "angles must be finite");
        }
        // Cam.
        let base = match &spec.cam.profile {
            ProfileSpec::RiseReturn { base_radius, lift, rise_start_deg, rise_deg, top_dwell_deg, return_deg, .. } => {
                v.positive("/cam/profile/lift", *lift);
                v.in_range("/cam/profile/rise_start_deg", *rise_start_deg, -360.0, 360.0);
                v.in_range("/cam/profile/rise_deg", *rise_deg, 1e-3, 360.0);
                v.in_range("/cam/profile/top_dwell_deg", *top_dwell_deg, 0.0, 360.0);
                v.in_range("/cam/profile/return_deg", *return_deg, 1e-3, 360.0);
                v.check(
                    rise_deg + top_dwell_deg + return_deg <= 360.0 + 1e-9,
                    "/cam/profile/return_deg",
                    "rise + top dwell + return must fit in 360°",
                );
                Some(*base_radius)
            }
            ProfileSpec::MultiArc { arcs } => {
                v.check(arcs.len() >= 2 && arcs.len() <= 1000, "/cam/profile/arcs", "needs 2 to 1000 arcs");
                for (i, a) in arcs.iter().enumerate() {
                    v.positive(&format!("/cam/profile/arcs/{i}/radius"), a.radius);
                    v.in_range(&format!("/cam/profile/arcs/{i}/angle_deg"), a.angle_deg, 1e-9, 360.0);
                }
                arcs.first().map(|a| a.radius)
            }
            ProfileSpec::SymmetricArcs { base_radius, base_angle_deg, flanks } => {
                v.in_range("/cam/profile/base_angle_deg", *base_angle_deg, 1e-9, 360.0);
                v.check(flanks.len() <= 1000, "/cam/profile/flanks", "at most 1000 flank arcs");
                for (i, a) in flanks.iter().enumerate() {
                    v.positive(&format!("/cam/profile/flanks/{i}/radius"), a.radius);
                    v.in_range(&format!("/cam/profile/flanks/{i}/angle_deg"), a.angle_deg, 1e-9, 360.0);
                }
                Some(*base_radius)
            }
            ProfileSpec::Table { base_radius, angle_deg, lift } => {
                v.check(angle_deg.len() == lift.len(), "/cam/profile/lift", "must have as many entries as angle_deg");
                v.check(angle_deg.len() >= 4, "/cam/profile/angle_deg", "needs at least 4 points");
                v.limit("/cam/profile/angle_deg", angle_deg.len(), limits.max_angles, "the number of table points");
                v.check(
                    angle_deg.windows(2).all(|w| w[1] > w[0]) && angle_deg.last().zip(angle_deg.first()).is_none_or(|(l, f)| l - f < 360.0),
                    "/cam/profile/angle_deg",
                    "angles must increase strictly and span less than 360°",
                );
                v.check(lift.iter().all(|x| x.is_finite()), "/cam/profile/lift", "must be finite numbers");
                Some(*base_radius)
            }
        };
        if let Some(b) = base {
            v.in_range("/cam/profile/base_radius", b, 1e-4, 10.0);
        }
        if let Some(w) = spec.cam.width {
            v.positive("/cam/width", w);
        }
        spec.cam.material.validate("/cam/material", v);
        v.in_range("/cam/roughness_rq", spec.cam.roughness_rq, 0.0, 1e-4);
        // Follower.
        let (material, rq) = match &spec.follower {
            FollowerSpec::FlatFaced { offset, face_radius, material, roughness_rq } => {
                v.in_range("/follower/offset", *offset, -1.0, 1.0);
                if let Some(r) = face_radius {
                    v.positive("/follower/face_radius", *r);
                }
                v.check(spec.cam.width.is_some(), "/cam/width", "is required with a flat-faced follower (it is the contact length)");
                (*material, *roughness_rq)
            }
            FollowerSpec::Roller { radius, length, pin_radius, clearance, inertia, density, pin, crown, offset, material, roughness_rq } => {
                v.in_range("/follower/radius", *radius, 1e-4, 1.0);
                v.positive("/follower/length", *length);
                v.check(*pin_radius > 0.0 && pin_radius < radius, "/follower/pin_radius", "must be > 0 and smaller than the roller radius");
                v.in_range("/follower/clearance", *clearance, 1e-8, 1e-3);
                if let Some(i) = inertia {
                    v.non_negative("/follower/inertia", *i);
                }
                v.positive("/follower/density", *density);
                match pin {
                    PinSpec::Coefficient { coefficient } => {
                        v.in_range("/follower/pin/coefficient", *coefficient, 0.0, 1.0);
                    }
                    PinSpec::Hydrodynamic { length: l } => {
                        if let Some(l) = l {
                            v.positive("/follower/pin/length", *l);
                        }
                        v.check(spec.lubricant.is_some(), "/lubricant", "is required by a hydrodynamic pin");
                    }
                }
                if let Some(c) = crown {
                    v.check(c.middle_length > 0.0 && c.middle_length <= *length, "/follower/crown/middle_length", "must be in (0, length]");
                    v.in_range("/follower/crown/crown_height", c.crown_height, 0.0, 1e-3);
                    v.positive("/follower/crown/end_radius", c.end_radius);
                }
                v.in_range("/follower/offset", *offset, -1.0, 1.0);
                if let Some(b) = base {
                    v.check(offset.abs() < b + radius, "/follower/offset", "must be smaller than base radius + roller radius");
                }
                (*material, *roughness_rq)
            }
            FollowerSpec::Spherical { radius, offset, material, roughness_rq } => {
                v.in_range("/follower/radius", *radius, 1e-4, 10.0);
                v.in_range("/follower/offset", *offset, -1.0, 1.0);
                if let Some(b) = base {
                    v.check(offset.abs() < b + radius, "/follower/offset", "must be smaller than base radius + face radius");
                }
                (*material, *roughness_rq)
            }
        };
        material.validate("/follower/material", v);
        v.in_range("/follower/roughness_rq", rq, 0.0, 1e-4);
        // Operation.
        v.in_range("/operation/speed_rpm", spec.operation.speed_rpm, 1e-3, 1e5);
        if let Some(s) = spec.operation.startup {
            v.in_range("/operation/startup/rated_angle_deg", s.rated_angle_deg, 1.0, 360.0);
        }
        // Needs.
        let needs = spec.needs();
        if needs.loads {
            v.check(spec.load.is_some(), "/load", "is required unless only kinematics are requested");
        }
        if needs.film {
            v.check(spec.lubricant.is_some(), "/lubricant", "is required for film, friction, slip or temperature outputs");
        }
        match &spec.load {
            Some(LoadSpec::ValveTrain { spring_preload, spring_stiffness, moving_mass, external }) => {
                v.in_range("/load/spring_preload", *spring_preload, -1e7, 1e7);
                v.in_range("/load/spring_stiffness", *spring_stiffness, 0.0, 1e10);
                v.in_range("/load/moving_mass", *moving_mass, 0.0, 1e4);
                if let Some(t) = external {
                    check_table(v, "/load/external", &t.angle_deg, &t.force, "force", limits);
                }
            }
            Some(LoadSpec::Spectrum { angle_deg, load, offset }) => {
                check_table(v, "/load", angle_deg, load, "load", limits);
                v.in_range("/load/offset", *offset, -1e7, 1e7);
            }
            None => {}
        }
        if let Some(l) = &spec.lubricant {
            l.validate("/lubricant", v);
        }
        spec.asperities.validate("/asperities", v);
        spec.traction.validate("/traction", v);
        spec.film.validate("/film", v);
        v.in_range("/slip/tolerance", spec.slip.tolerance, 1e-14, 1e-1);
        v.count_in_range("/slip/max_cycles", spec.slip.max_cycles, 1, 10_000);
        for (name, t) in [("cam", spec.thermal.cam), ("follower", spec.thermal.follower)] {
            v.positive(&format!("/thermal/{name}/conductivity"), t.conductivity);
            v.positive(&format!("/thermal/{name}/density"), t.density);
            v.positive(&format!("/thermal/{name}/specific_heat"), t.specific_heat);
        }
    }

    fn solve(spec: &CamCycleSpec, observer: &dyn Observer) -> Result<CamCycleResult, SolveError> {
        solve_spec(spec, observer)
    }
}

fn check_table(v: &mut Validation, path: &str, angles: &[f64], values: &[f64], name: &str, limits: &Limits) {
    v.check(!angles.is_empty() && angles.len() == values.len(), &format!("{path}/{name}"), "must be non-empty and as long as angle_deg");
    v.limit(&format!("{path}/angle_deg"), angles.len(), limits.max_angles, "the number of table points");
    v.check(angles.iter().chain(values).all(|x| x.is_finite()), &format!("{path}/angle_deg"), "entries must be finite numbers");
    let mut wrapped: Vec<f64> = angles.iter().map(|a| a.rem_euclid(360.0)).collect();
    wrapped.sort_by(|a, b| a.total_cmp(b));
    v.check(wrapped.windows(2).all(|w| w[1] > w[0]), &format!("{path}/angle_deg"), "angles must be distinct within one revolution");
}
