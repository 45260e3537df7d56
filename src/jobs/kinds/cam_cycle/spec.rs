//! The `cam_cycle` request: the pair (cam, follower, operation, load, lubricant, surfaces),
//! the film and slip options, and what to compute.

use crate::jobs::kinds::common::{AsperitySpec, Material, EhlSpec, FilmSpec, LubricantSpec, ThermalSpec, TractionSpec};
use crate::physics::cam::LiftLaw;
use crate::physics::film::Fidelity;
use super::synthesis_spec::{LawLimitsSpec, RampSpec, SynthesisLaw};
use serde::{Deserialize, Serialize};
use utoipa::ToSchema;

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
        #[schema(value_type = crate::jobs::schemas::LiftLawDoc)]
        law: LiftLaw,
        #[serde(default, skip_serializing_if = "Option::is_none")]
        #[schema(value_type = Option<crate::jobs::schemas::LiftLawDoc>)]
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
    /// A lift law synthesised from its specification (`physics::cam::synthesis`): opening ramp
    /// (velocity blend, then constant velocity), main rise of `law`, dwell at full lift, and the
    /// mirrored return and closing ramp, centred on `nose_deg`. Lift, velocity and acceleration
    /// are continuous, the jerk finite (continuous with `polydyne` and `polynomial_4567`). The
    /// result adds `synthesis` and the `contour` table.
    Synthesised {
        /// Base circle radius, m.
        base_radius: f64,
        /// Total lift from the base circle to the nose (ramp included), m.
        lift: f64,
        /// Event duration from the start of the opening ramp to the end of the closing ramp,
        /// degrees.
        duration_deg: f64,
        /// Opening and closing ramp. Absent: none (the rise starts from the base circle).
        #[serde(default, skip_serializing_if = "Option::is_none")]
        ramp: Option<RampSpec>,
        /// Law of the main rise. Default `polydyne`.
        #[serde(default)]
        law: SynthesisLaw,
        /// Dwell at full lift, degrees. Default 0 (none with the polydyne).
        #[serde(default)]
        dwell_deg: f64,
        /// Cam angle of the nose (middle of the event), degrees. Default 180.
        #[serde(default = "super::synthesis_spec::default_nose")]
        nose_deg: f64,
        /// Peak limits. Absent: none.
        #[serde(default, skip_serializing_if = "Option::is_none")]
        limits: Option<LawLimitsSpec>,
        /// The polydyne's dynamic correction for a design speed: the law is then the valve's and
        /// the cam leads it (`physics::cam::synthesis::dynamic`). Absent: none.
        #[serde(default, skip_serializing_if = "Option::is_none")]
        dynamic_correction: Option<super::synthesis_spec::DynamicCorrectionSpec>,
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
    /// Finite-length hydrodynamic journal bearing (seed 000 eq. 10–13): the journal solver's
    /// Reynolds solutions with Reynolds cavitation (as the `bearing` kind), tabulated over the
    /// eccentricity ratio once per run at the pin's L/D, the roller turning on a stationary pin.
    /// With `thermal` (default) the film is isoviscous at an effective temperature from the
    /// bearing's energy balance: the power loss leaves with the side-leakage oil
    /// (`oil_specific_heat` and the lubricant's `density`) and by convection from the roller's
    /// outer surfaces (cylinder and end faces) at `convection_coefficient` to ambient at the
    /// lubricant's inlet temperature; without it the film is at the inlet temperature. The
    /// balance is quasi-static at each cam angle (the roller's heat capacity is not modelled),
    /// and it is not the full 3-D energy equation of seed 000 eq. 12. L/D = length/(2
    /// pin_radius) must lie in [0.05, 4].
    Finite {
        /// Bearing length, m. Default: the roller length.
        #[serde(default, skip_serializing_if = "Option::is_none")]
        length: Option<f64>,
        /// Effective film temperature from the energy balance. Default true.
        #[serde(default = "default_true")]
        thermal: bool,
        /// Oil specific heat c_f, J/(kg·K). Default 1700 (seed 000 Table 1).
        #[serde(default = "default_oil_specific_heat")]
        oil_specific_heat: f64,
        /// Convective heat-transfer coefficient k_r from the roller to ambient, W/(m²·K).
        /// Default 80 (seed 000 Table 1).
        #[serde(default = "default_convection_coefficient")]
        convection_coefficient: f64,
    },
}

fn default_true() -> bool {
    true
}
fn default_oil_specific_heat() -> f64 {
    1700.0
}
fn default_convection_coefficient() -> f64 {
    80.0
}

/// Crowned roller profile (seed 000 Table 1). See `physics::geometry::crown`.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct CrownSpec {
    /// Middle length L1, m.
    pub middle_length: f64,
    /// Crown height h_td at the ends of the middle section, m.
    pub crown_height: f64,
    /// End profile radius R_d, m.
    pub end_radius: f64,
    /// `convex` (default): a crown, `h_td (2y/L1)²` on the middle and `h_td + (|y| − L1/2)²/(2R_d)`
    /// beyond. `seed000_eq3`: seed 000 eq. 3 exactly as printed, `h_td (1 − (2y/L1)²)` on the middle
    /// (the centre relieved by h_td, the roller touching first at the transitions `±L1/2`) and
    /// `(|y| − L1/2)²/(2R_d)` beyond.
    #[serde(default, skip_serializing_if = "CrownProfileSpec::is_convex")]
    pub profile: CrownProfileSpec,
}

/// Axial profile of the crown parameters (see [`CrownSpec::profile`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize, ToSchema)]
#[serde(rename_all = "snake_case")]
pub enum CrownProfileSpec {
    #[default]
    Convex,
    Seed000Eq3,
}

impl CrownProfileSpec {
    pub fn is_convex(&self) -> bool {
        *self == CrownProfileSpec::Convex
    }
}

impl From<CrownProfileSpec> for crate::physics::geometry::CrownProfile {
    fn from(p: CrownProfileSpec) -> Self {
        match p {
            CrownProfileSpec::Convex => Self::Convex,
            CrownProfileSpec::Seed000Eq3 => Self::Seed000Eq3,
        }
    }
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
        /// RMS surface roughness Rq of the follower, m. Default 0 (smooth).
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
        /// RMS surface roughness Rq of the follower, m. Default 0 (smooth).
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
        /// RMS surface roughness Rq of the follower, m. Default 0 (smooth).
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
    /// Valve-train dynamics (flat or roller follower, whose `follower_mass` includes the roller;
    /// direct-acting as in seed 003, or through a rocker arm
    /// or finger follower: `arrangement`): the contact load comes from a lumped multibody model —
    /// follower, (pushrod, lever,) valve, the train's links, the valve spring as a chain of masses
    /// (surge), a unilateral compliant cam contact and an optional valve seat — integrated to its
    /// periodic steady state (`physics::valvetrain`). The spring preload is carried by the cam on
    /// the base circle (as in `valve_train`; times the lever ratio with a lever). Steady running
    /// only. The result adds the valve's motion, the spring forces at both ends, and
    /// `summary.separation` / `seating_velocity` / bounce.
    Dynamic(DynamicLoadSpec),
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

fn default_shear_modulus() -> f64 {
    79.3e9
}
fn default_spring_density() -> f64 {
    7850.0
}
fn default_spring_elements() -> usize {
    8
}
fn default_surge_damping() -> f64 {
    0.02
}
fn default_train_damping() -> f64 {
    0.05
}
fn default_contact_damping() -> f64 {
    0.1
}
fn default_seat_damping() -> f64 {
    0.1
}
fn default_seat_gap() -> f64 {
    1e-6
}
fn default_dyn_tolerance() -> f64 {
    1e-8
}
fn default_periodic_tolerance() -> f64 {
    1e-6
}
fn default_max_revolutions() -> usize {
    200
}

/// A helical valve spring of round wire: its rate `G d⁴/(8 D³ n)`, active mass
/// `ρ π² d² D n/4` and surge come from the coils.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct ValveSpringSpec {
    /// Wire diameter d, m.
    pub wire_diameter: f64,
    /// Mean coil diameter D, m.
    pub mean_diameter: f64,
    /// Active coils n.
    pub active_coils: f64,
    /// Shear modulus G, Pa. Default 79.3e9 (spring steel).
    #[serde(default = "default_shear_modulus")]
    pub shear_modulus: f64,
    /// Wire density ρ, kg/m³. Default 7850.
    #[serde(default = "default_spring_density")]
    pub density: f64,
    /// Interior masses of the spring chain (0: massless spring with a third of its mass on the
    /// valve). Default 8.
    #[serde(default = "default_spring_elements")]
    pub elements: usize,
    /// Damping ratio of the first surge mode (stiffness-proportional internal damping).
    /// Default 0.02.
    #[serde(default = "default_surge_damping")]
    pub damping_ratio: f64,
    /// Design data (lengths, coils, wire): the installed preload and the spring checks.
    /// Absent: `spring_preload` is required and the spring is not checked.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub design: Option<super::train_spec::SpringDesignSpec>,
    /// A progressive (variable-pitch) spring: its coil groups from the fixed end (cylinder
    /// head) to the retainer, the coils summing to `active_coils` (at most 8 groups, and with
    /// interior `elements` at least one segment each: `elements + 1 ≥` groups). The rate,
    /// preload, checks and surge follow the groups closing in turn; in the dynamics each group
    /// is its own segments of the chain, whose stiffness rises 1000-fold when its coils touch.
    /// Absent: uniform pitch.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub pitch_groups: Option<Vec<super::train_spec::CoilGroupSpec>>,
}

/// The valve seat: a unilateral spring–damper stop.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct SeatSpec {
    /// Seat contact stiffness, N/m.
    pub stiffness: f64,
    /// Damping ratio of the seat on the valve mass (2ζ√(k m_v)). Default 0.1.
    #[serde(default = "default_seat_damping")]
    pub damping_ratio: f64,
    /// Distance of the seat below the valve's closed position (cam on the base circle, which
    /// carries the preload), m. Default 1e-6.
    #[serde(default = "default_seat_gap")]
    pub gap: f64,
}

fn default_run_up_revolutions() -> usize {
    20
}
fn default_run_up_samples() -> usize {
    360
}

/// A run-up of the valve train: the cam accelerated uniformly in angle from `from_rpm` to the
/// operation's `speed_rpm` over `revolutions` revolutions, from the static state (integrated
/// with the same tolerance; the tribology still uses the periodic state at `speed_rpm`).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct RunUpSpec {
    /// Cam speed at the start, rpm (> 0; above `speed_rpm` gives a run-down).
    pub from_rpm: f64,
    /// Revolutions of the ramp. Default 20.
    #[serde(default = "default_run_up_revolutions")]
    pub revolutions: usize,
    /// Samples per revolution of the `run_up` table. Default 360.
    #[serde(default = "default_run_up_samples")]
    pub samples_per_revolution: usize,
}

fn default_pushrod_damping() -> f64 {
    0.05
}

/// A pushrod between the tappet (the follower) and the rocker (overhead-valve train).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct PushrodSpec {
    /// Pushrod mass, kg (lumped half on the tappet, half on the rocker's cam-side end).
    pub mass: f64,
    /// Axial stiffness (E A / length for a tube), N/m.
    pub stiffness: f64,
    /// Damping ratio of the pushrod on the reduced mass of the bodies it joins. Default 0.05.
    #[serde(default = "default_pushrod_damping")]
    pub damping_ratio: f64,
}

/// How the cam drives the valve. With a lever (`rocker`, `finger`) of ratio
/// `r = valve_arm/cam_arm`, the load's `follower_mass` is what moves with the cam's lift outside
/// the lever (the tappet; 0 when the cam acts on the lever's own pad or roller, whose mass is
/// then in `inertia`), and `valve_mass`, `train_stiffness` (the lever–valve link: arm bending
/// and valve stem), `spring`, `spring_preload` and `seat` are on the valve side. The ratio is
/// constant (first order in the lever's angle: arms perpendicular to the lines of action at
/// mid-lift err by at most `1 − cos(φ_max/2) ≈ φ_max²/8` in the ratio, `φ_max` = cam lift /
/// `cam_arm`; pad travel along the arm is not modelled). The cam's lift is that of a
/// translating flat or roller follower (a finger's roller moving on its arc is taken as
/// translating, within the same bound). `series.follower_displacement` is the cam side, `valve_*` and the
/// spring forces the valve side.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize, ToSchema)]
#[serde(tag = "type", rename_all = "snake_case", deny_unknown_fields)]
pub enum ArrangementSpec {
    /// Direct-acting follower (bucket tappet) on the valve axis, seed 003's arrangement.
    Direct,
    /// Rocker arm pivoted between its cam side and its valve side; the cam acts through a
    /// `pushrod` (overhead valve) or directly on the rocker's pad or roller (overhead cam).
    Rocker {
        /// Pivot to the cam side's line of action (the pushrod's or the cam contact's), m.
        cam_arm: f64,
        /// Pivot to the valve's line of action, m.
        valve_arm: f64,
        /// Rocker's moment of inertia about its pivot, kg·m².
        inertia: f64,
        /// Pushrod from the tappet to the rocker. Absent: the cam acts on the rocker.
        #[serde(default, skip_serializing_if = "Option::is_none")]
        pushrod: Option<PushrodSpec>,
    },
    /// End-pivot finger follower: pivot (lash adjuster) at one end, valve pad at the other, the
    /// cam's slipper or roller in between (`cam_arm < valve_arm`).
    Finger {
        /// Pivot to the cam contact, m.
        cam_arm: f64,
        /// Pivot to the valve pad, m.
        valve_arm: f64,
        /// Finger's moment of inertia about its pivot (roller included), kg·m².
        inertia: f64,
    },
}

/// The valve train of a `dynamic` load.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct DynamicLoadSpec {
    /// Spring force at zero lift, N (> 0). Absent: from `spring.design` (rate × (free −
    /// installed length), with `inner_spring` the sum); give one of the two.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub spring_preload: Option<f64>,
    pub spring: ValveSpringSpec,
    /// A nested inner spring in parallel with `spring` (both with a `design`): the checks are
    /// per spring; in the dynamics each spring is its own chain (its own surge) between the
    /// valve and the fixed end, the forces adding at the retainer.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub inner_spring: Option<ValveSpringSpec>,
    /// Criteria of the valve-spring checks (speed range for the surge orders, curvature factor,
    /// required safety factors). The checks run whenever `spring.design` is given.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub spring_checks: Option<super::train_spec::SpringChecksSpec>,
    /// Mechanical valve lash (clearance) taken up by the lift law's ramps. Absent: none.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub lash: Option<super::train_spec::LashSpec>,
    /// Hydraulic lash adjuster (direct-acting; instead of `lash` and `train_stiffness`). Absent:
    /// none.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub hydraulic_lash_adjuster: Option<super::train_spec::HydraulicAdjusterSpec>,
    /// Arrangement of the train. Absent: `direct`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub arrangement: Option<ArrangementSpec>,
    /// Mass of the part the cam touches (tappet; seed 003: the retainer), kg. With a lever: the
    /// part moving with the cam's lift outside the lever (the tappet under a pushrod; ≥ 0).
    pub follower_mass: f64,
    /// Mass of the valve with what moves rigidly with it (retainer, keepers), kg.
    pub valve_mass: f64,
    /// Stiffness of the follower–valve link (with a lever: the lever–valve link on the valve
    /// side), N/m. Absent: rigid (one body).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub train_stiffness: Option<f64>,
    /// Damping ratio of that link on the reduced mass. Default 0.05.
    #[serde(default = "default_train_damping")]
    pub train_damping_ratio: f64,
    /// Cam–follower contact stiffness along the follower axis, N/m. Default: the line contact's
    /// secant stiffness at the spring preload (times the lever ratio) on the base circle (seed 003
    /// eq. 6; a roller: with the reduced radius of base circle and roller). The stiffness is taken
    /// constant along the axis (the normal stiffness projected by cos² of the pressure angle is
    /// not modelled).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub contact_stiffness: Option<f64>,
    /// Damping ratio of the contact on the mass it carries (the follower, rigid train or lever
    /// with the valve side reduced to the cam side; the oil film's damping). Default 0.1.
    #[serde(default = "default_contact_damping")]
    pub contact_damping_ratio: f64,
    /// Valve seat. Absent: no seat (the valve may swing below its closed position).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub seat: Option<SeatSpec>,
    /// Relative local error tolerance of the integrator (TR-BDF2; absolute part: this times the
    /// lift and lift × ω). Default 1e-8: the contact load within ~1e-4 of a tight run (seed 003,
    /// BENCHMARKS.md); the load error is ~100× the tolerance because the contact stiffness
    /// multiplies position errors.
    #[serde(default = "default_dyn_tolerance")]
    pub tolerance: f64,
    /// Change of the state at the start of a revolution (relative to lift and lift × ω) that
    /// ends the periodic iteration. Default 1e-6.
    #[serde(default = "default_periodic_tolerance")]
    pub periodic_tolerance: f64,
    /// Most revolutions integrated to reach the periodic state. Default 200.
    #[serde(default = "default_max_revolutions")]
    pub max_revolutions: usize,
    /// Also integrate a run-up over a speed ramp ending at `speed_rpm` (result table `run_up`,
    /// `summary.run_up_first_separation_rpm`). Absent: none.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub run_up: Option<RunUpSpec>,
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
    #[schema(value_type = crate::jobs::schemas::FidelityDoc)]
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

