//! The `cam_cycle` result: per-angle series, summary, events, film profiles.

use crate::physics::friction::SlipRegime;
use crate::physics::film::{Fidelity, FilmModelId};
use std::collections::BTreeMap;
use crate::physics::Convergence;
use serde::Serialize;
use utoipa::ToSchema;

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
    /// Contact point position across the follower, m: from the follower axis for roller and
    /// spherical followers; from the cam centre line for a flat face (dh/dθ, whatever the
    /// offset: subtract `offset` for the position relative to the follower axis).
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
    /// Central elastic deflection of the line contact (seed 003 eq. 6; the `b` of its logarithm
    /// read as the contact's half-length), m. Straight line contacts (flat faces, uncrowned
    /// rollers). With `hertz_half_width` it is seed 003's Fig. 11 (deflection and contact width
    /// over the cycle).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub contact_deflection: Option<Vec<f64>>,
    /// Central film thickness, m.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub film_central: Option<Vec<f64>>,
    /// Minimum film thickness, m.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub film_min: Option<Vec<f64>>,
    /// Film model that ran at each angle (`numerical` or the closed form's name).
    #[serde(skip_serializing_if = "Option::is_none")]
    #[schema(value_type = Option<Vec<crate::jobs::schemas::FilmModelIdDoc>>)]
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
    /// `ehl.geometry: finite` on a roller: the edge pressure peak, Pa — the largest off-centre
    /// maximum along the roller of the pressure (`max_x p`) above the centre value, typically at a
    /// crown transition. Present when the 2-D model found one at any angle; `null` where it did
    /// not run or the pressure falls monotonically from the centre (and for point contacts).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub edge_pressure_peak: Option<Vec<Option<f64>>>,
    /// Its axial position, m from the roller centre; `null` where `edge_pressure_peak` is.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub edge_pressure_peak_position: Option<Vec<Option<f64>>>,
    /// `ehl.geometry: finite`: where the minimum film sits across the rolling direction (along a
    /// roller's axis), m from the contact centre (0: on the centre line). Present when the 2-D model
    /// ran at any angle; `null` where it did not.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub min_film_axial_position: Option<Vec<Option<f64>>>,
    /// Newton steps of the numerical EHL solver at each angle (0 at closed-form angles). Present
    /// when the numerical model ran.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub newton_steps: Option<Vec<f64>>,
    /// λ = h_min/σ (rough surfaces).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub lambda: Option<Vec<f64>>,
    /// Share of the load carried by the asperities inside the load balance of the film solution
    /// (mixed lubrication: `film_model` ends in `_mixed`); the fluid carries the rest.
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
    /// Roller followers: `rolling` (asperities stick, or a full film below 1 % SRR),
    /// `micro_slip` (partial slip of the asperity contact) or `gross_sliding` (the asperities
    /// slide, or a full film at ≥ 1 % SRR) at each angle.
    #[serde(skip_serializing_if = "Option::is_none")]
    #[schema(value_type = Option<Vec<crate::jobs::schemas::SlipRegimeDoc>>)]
    pub slip_regime: Option<Vec<SlipRegime>>,
    /// Roller–pin friction torque, N·m.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub pin_torque: Option<Vec<f64>>,
    /// Maximum flash temperature rise (Blok/Jaeger), K.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub flash_temperature: Option<Vec<f64>>,
    /// Thermal EHL (`ehl.thermal`): largest film temperature, K.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub film_temperature_max: Option<Vec<f64>>,
    /// Thermal EHL: largest surface temperature of the cam and of the follower, K.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub surface_temperature_cam: Option<Vec<f64>>,
    /// The same of the follower, K.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub surface_temperature_follower: Option<Vec<f64>>,
    /// Effective film temperature of a thermal finite roller–pin bearing, K.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub pin_temperature: Option<Vec<f64>>,
    /// Valve lift from the valve-train dynamics (`dynamic` load), m.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub valve_lift: Option<Vec<f64>>,
    /// Valve velocity (`dynamic` load), m/s.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub valve_velocity: Option<Vec<f64>>,
    /// Valve acceleration (`dynamic` load), m/s².
    #[serde(skip_serializing_if = "Option::is_none")]
    pub valve_acceleration: Option<Vec<f64>>,
    /// Follower displacement (`dynamic` load; the cam's lift minus the contact and train
    /// compliance, or the flight while separated), m.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub follower_displacement: Option<Vec<f64>>,
    /// Valve spring force at the retainer (moving end), N (`dynamic` load).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub spring_force_retainer: Option<Vec<f64>>,
    /// Valve spring force at its fixed end (cylinder head), N (`dynamic` load).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub spring_force_fixed_end: Option<Vec<f64>>,
    /// Valve seat force, N (`dynamic` load with a seat).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub seat_force: Option<Vec<f64>>,
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
    /// `dynamic` load: cam angle intervals `[start, end]` (degrees; `end` may exceed 360 when an
    /// interval runs past 0°) where the follower has left the cam (no contact load), from the
    /// integration's located events; empty when contact is never lost.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub separation: Option<Vec<[f64; 2]>>,
    /// `dynamic` load: time without contact per revolution, s.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub separation_duration: Option<f64>,
    /// `dynamic` load: valve speed (m/s, ≥ 0) when it first returns to its closed position after
    /// the lift (the seat impact velocity with a seat); absent when it never closes.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub seating_velocity: Option<f64>,
    /// Cam angle of that seating, degrees.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub seating_angle_deg: Option<f64>,
    /// `dynamic` load with a seat: seat impacts per revolution after the first (valve bounce).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub bounces: Option<usize>,
    /// `dynamic` load with a seat: highest rebound of the valve above its closed position after
    /// the first seat impact (sampled at the cycle's angles), m.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub max_bounce_height: Option<f64>,
    /// `dynamic` load: valve spring rate from its coils (nested springs: the sum; progressive: with
    /// every coil open), N/m.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub spring_rate: Option<f64>,
    /// `dynamic` load: active spring mass (nested springs: the sum), kg.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub spring_mass: Option<f64>,
    /// `dynamic` load: first surge frequency with both ends fixed, ½√(k/m), Hz.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub spring_surge_frequency: Option<f64>,
    /// `dynamic` load: cam–follower contact stiffness used, N/m.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub contact_stiffness: Option<f64>,
    /// `dynamic` load: the rigid train's separation ("jump") speed, rpm — the closed form
    /// `min √((P + k s)/(m (−s'')))` over the decelerating lift, `m` the follower, valve and a
    /// third of the spring's mass (with a lever: `P`, `k`, `m` reduced to the cam side,
    /// `r P`, `r² k` and `equivalent_mass`). The dynamic train's jump speed (the lowest speed with a
    /// non-empty `separation`) is found by a `sweep` over `/operation/speed_rpm` with the
    /// quantity `/summary/separation_duration` (README: jump speed); compliance and surge usually
    /// put it below this figure.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub rigid_jump_speed_rpm: Option<f64>,
    /// `dynamic` load with `run_up`: cam speed at the first loss of contact on the ramp, rpm.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub run_up_first_separation_rpm: Option<f64>,
    /// `dynamic` load with `run_up`: integrator steps accepted over the ramp.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub run_up_steps: Option<usize>,
    /// `dynamic` load: the rigid train's moving mass reduced to the cam contact, kg —
    /// `m_f + m_v + m_s/3` direct-acting; with a lever of ratio r,
    /// `m_f + m_pushrod + I/cam_arm² + r² (m_v + m_s/3)` (the quasi-static load is
    /// `r P + r² k s + this × acceleration`).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub equivalent_mass: Option<f64>,
    /// `dynamic` load with a rocker or finger: the lever ratio `valve_arm/cam_arm`.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub lever_ratio: Option<f64>,
    /// `dynamic` load with `spring.design`: every valve-spring check passed (`spring_checks`).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub spring_checks_pass: Option<bool>,
    /// `dynamic` load with `spring.design`: the least Goodman fatigue safety factor of the
    /// springs.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub min_spring_fatigue_safety_factor: Option<f64>,
    /// `dynamic` load with `spring.design`: the least clearance to solid length at full lift
    /// (coil-clash margin) of the springs, m.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub min_coil_clash_margin: Option<f64>,
    /// `dynamic` load with a `lash`: relative velocity of cam and follower, reduced to the
    /// valve, when the clearance closes on the opening ramp (≈ ramp velocity × cam speed when the
    /// train rests), m/s.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub opening_impact_velocity: Option<f64>,
    /// `dynamic` load with a `lash`: the largest cam lift times the lever ratio less the largest
    /// valve lift (the lash and the train's deflection), m.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub lift_loss: Option<f64>,
}

/// Events of the cycle.
#[derive(Debug, Clone, PartialEq, Default, Serialize, ToSchema)]
pub struct CamEvents {
    /// Cam angles where the entrainment velocity changes sign, degrees.
    pub zero_entrainment_angles_deg: Vec<f64>,
    /// Angle ranges `[start, end]` (degrees) where the follower would leave the cam.
    pub separation_ranges_deg: Vec<[f64; 2]>,
    /// `dynamic` load with `run_up`: intervals `[start, end]` of the cam angle from the start of
    /// the ramp (degrees, as `run_up.angle_deg`) without contact.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub run_up_separation_deg: Option<Vec<[f64; 2]>>,
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

/// The 2-D pressure and film fields of `ehl.geometry: finite` at the requested angles (output
/// `profiles` with `profile_angles_deg`), one row per grid node and angle (columns of equal
/// length; CSV with `?table=fields`). Rows run over `x` fastest, then `y`, then the angle.
#[derive(Debug, Clone, PartialEq, Serialize, ToSchema)]
pub struct FieldsTable {
    /// Cam angle, degrees.
    pub angle_deg: Vec<f64>,
    /// Position along the rolling direction from the contact centre, m (positive in the
    /// direction of positive entrainment).
    pub x: Vec<f64>,
    /// Position across the rolling direction (along the roller axis), m from the centre.
    pub y: Vec<f64>,
    /// Pressure, Pa.
    pub pressure: Vec<f64>,
    /// Film thickness, m.
    pub film: Vec<f64>,
}

/// Result of a `cam_cycle` job.
#[derive(Debug, Clone, PartialEq, Serialize, ToSchema)]
pub struct CamCycleResult {
    /// Fidelity that ran.
    #[schema(value_type = crate::jobs::schemas::FidelityDoc)]
    pub fidelity_used: Fidelity,
    /// Film model that ran, when one model ran at every angle (absent when `auto` mixed models:
    /// see the series column `model` and `summary.fidelity_used`).
    #[serde(skip_serializing_if = "Option::is_none")]
    #[schema(value_type = Option<crate::jobs::schemas::FilmModelIdDoc>)]
    pub film_model: Option<FilmModelId>,
    /// The numerical line model's settings as they ran (fidelity `accurate` or `auto`, line
    /// geometry): `ehl.accuracy`, the grid it chose where the spec gave none, the thermal key
    /// points, and the largest film error measured with them on the reference cycles.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub ehl_settings: Option<crate::jobs::kinds::accuracy::EhlSettingsUsed>,
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
    /// 2-D pressure and film fields at the requested angles where the finite-length/point model
    /// ran (output `profiles` with `ehl.geometry: finite`).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub fields: Option<FieldsTable>,
    /// Periodicity of the roller speed (steady torque balance) or closed form.
    #[schema(value_type = crate::jobs::schemas::ConvergenceDoc)]
    pub convergence: Convergence,
    /// `dynamic` load: revolutions integrated to the periodic steady state and the final change
    /// of the state between revolutions.
    #[serde(skip_serializing_if = "Option::is_none")]
    #[schema(value_type = Option<crate::jobs::schemas::ConvergenceDoc>)]
    pub dynamics_convergence: Option<Convergence>,
    /// `dynamic` load with `run_up`: the train over the speed ramp (a table: CSV with
    /// `?table=run_up`; its separation intervals are `events.run_up_separation_deg`).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub run_up: Option<RunUpTable>,
    /// Profile `synthesised`: the law's peaks per cam angle against its limits, radii of
    /// curvature, undercut.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub synthesis: Option<super::synthesis::SynthesisReport>,
    /// Profile `synthesised`: the law per cam angle and the cam contour at the cycle's angles (a
    /// table: CSV with `?table=contour`; `angle_deg` and `lift` are a `table` profile's input).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub contour: Option<super::synthesis::ContourTable>,
    /// `dynamic` load with `spring.design`: the valve-spring checks, one entry per spring
    /// (Shigley ch. 10; criteria from `load.spring_checks`).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub spring_checks: Option<Vec<super::springs::SpringCheckResult>>,
}

/// The valve train over a run-up, at uniform cam angles (columns of equal length).
#[derive(Debug, Clone, PartialEq, Serialize, ToSchema)]
pub struct RunUpTable {
    /// Cam angle from the start of the ramp, degrees.
    pub angle_deg: Vec<f64>,
    /// Cam speed, rpm.
    pub speed_rpm: Vec<f64>,
    /// Cam–follower contact load, N.
    pub contact_load: Vec<f64>,
    /// Valve lift (m) and velocity (m/s).
    pub valve_lift: Vec<f64>,
    /// Valve velocity, m/s.
    pub valve_velocity: Vec<f64>,
    /// Spring force at the fixed end, N.
    pub spring_force_fixed_end: Vec<f64>,
}

