//! Spec types of the valve train's springs and lash (`load.spring.design`, `load.spring_checks`,
//! `load.lash`), apart from their logic (`springs.rs`, `lash.rs`) so that `spec.rs` imports no
//! module that imports it.

use serde::{Deserialize, Serialize};
use utoipa::ToSchema;

/// End treatment of the coils (Shigley Table 10-1: total coils and solid length).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize, ToSchema)]
#[serde(rename_all = "snake_case")]
pub enum SpringEndsSpec {
    /// Plain: total = active coils, solid length d (N_t + 1).
    Plain,
    /// Plain and ground: total = active + 1, solid length d N_t.
    PlainGround,
    /// Squared (closed): total = active + 2, solid length d (N_t + 1).
    Squared,
    /// Squared and ground (usual for valve springs): total = active + 2, solid length d N_t.
    #[default]
    SquaredGround,
}

/// Spring wire (Shigley Table 10-4: minimum tensile strength `A/d^m`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize, ToSchema)]
#[serde(rename_all = "snake_case")]
pub enum SpringWireSpec {
    /// Music wire A228.
    MusicWire,
    /// Oil-tempered wire A229.
    OilTempered,
    /// Chrome-vanadium A232 (valve-spring quality).
    ChromeVanadium,
    /// Chrome-silicon A401 (valve-spring quality).
    #[default]
    ChromeSilicon,
}

/// The spring's design data: lengths, coils, wire. With it the spring's installed preload is
/// `rate × (free_length − installed_length)` (give it instead of `spring_preload`) and the
/// result has `spring_checks`.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct SpringDesignSpec {
    /// Free length, m.
    pub free_length: f64,
    /// Installed length (valve closed), m (< free length, > solid length).
    pub installed_length: f64,
    /// Total coils. Absent: from `ends` (Shigley Table 10-1).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub total_coils: Option<f64>,
    /// End treatment. Default `squared_ground`.
    #[serde(default)]
    pub ends: SpringEndsSpec,
    /// Wire grade for the tensile strength. Default `chrome_silicon`.
    #[serde(default)]
    pub wire: SpringWireSpec,
    /// Minimum tensile strength S_ut, Pa (replaces the wire grade's `A/d^m`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub tensile_strength: Option<f64>,
    /// Shot-peened wire (Zimmerli's peened endurance: 398 MPa alternating at 534 MPa mean,
    /// unpeened 241 at 379 MPa). Default false.
    #[serde(default)]
    pub shot_peened: bool,
}

/// A group of coils of one pitch of a progressive (variable-pitch) spring. The groups are in
/// series and carry the same force; a group closes when its coils touch, at the force
/// `G d⁴ (pitch − d)/(8 D³)`, and the rate `G d⁴/(8 D³ n_open)` rises as the open coils
/// `n_open` fall (Wahl, *Mechanical Springs*; SAE HS-795).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct CoilGroupSpec {
    /// Active coils of the group (a count; the groups' coils sum to `active_coils`).
    pub coils: f64,
    /// Pitch of the free spring (axial distance between successive coils' centres), m
    /// (> wire diameter).
    pub pitch: f64,
}

/// Stress-correction (curvature) factor on the shear stress.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize, ToSchema)]
#[serde(rename_all = "snake_case")]
pub enum StressFactorSpec {
    /// Wahl, `(4C − 1)/(4C − 4) + 0.615/C`.
    #[default]
    Wahl,
    /// Bergsträsser, `(4C + 2)/(4C − 3)`.
    Bergstrasser,
}

fn default_static_fraction() -> f64 {
    0.5
}
fn default_min_solid_safety() -> f64 {
    1.2
}
fn default_min_fatigue_safety() -> f64 {
    1.2
}
fn default_min_overrun() -> f64 {
    0.15
}
fn default_min_surge_ratio() -> f64 {
    15.0
}

/// What the valve-spring checks require (every spring with a `design` is checked; this
/// section only changes the criteria).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct SpringChecksSpec {
    /// Camshaft speed range `[low, high]` for the surge orders, rpm. Default: the operation's
    /// speed.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub speed_range_rpm: Option<[f64; 2]>,
    /// Curvature factor of the stresses. Default `wahl`.
    #[serde(default)]
    pub stress_factor: StressFactorSpec,
    /// Allowable static torsional stress as a fraction of S_ut (Shigley Table 10-6: 0.45 music
    /// wire and cold-drawn steel, 0.50 hardened and tempered Cr-V and Cr-Si). Default 0.5.
    #[serde(default = "default_static_fraction")]
    pub static_fraction: f64,
    /// Least safety factor at solid length (Shigley: 1.2). Default 1.2.
    #[serde(default = "default_min_solid_safety")]
    pub min_solid_safety: f64,
    /// Least Goodman fatigue safety factor. Default 1.2.
    #[serde(default = "default_min_fatigue_safety")]
    pub min_fatigue_safety: f64,
    /// Least fractional overrun to closure at full lift, (L_full − L_solid)/(L_free − L_full)
    /// (Shigley: 0.15). Default 0.15.
    #[serde(default = "default_min_overrun")]
    pub min_overrun: f64,
    /// Least ratio of the surge frequency to the highest cam frequency (Shigley: 15 to 20).
    /// Default 15.
    #[serde(default = "default_min_surge_ratio")]
    pub min_surge_ratio: f64,
}

impl Default for SpringChecksSpec {
    fn default() -> Self {
        SpringChecksSpec {
            speed_range_rpm: None,
            stress_factor: StressFactorSpec::Wahl,
            static_fraction: default_static_fraction(),
            min_solid_safety: default_min_solid_safety(),
            min_fatigue_safety: default_min_fatigue_safety(),
            min_overrun: default_min_overrun(),
            min_surge_ratio: default_min_surge_ratio(),
        }
    }
}

/// A mechanical valve lash: the clearance in the train with the cam on its base circle. While
/// it is open the valve rests on its seat (required), which carries the spring preload; the
/// cam's opening ramp takes it up (impact: `summary.opening_impact_velocity`) and the closing
/// ramp opens it again (`summary.seating_velocity`). The ramps are the lift law's.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct LashSpec {
    /// Clearance at the valve, m (with a lever the model puts clearance / ratio between cam and
    /// follower).
    pub clearance: f64,
}

fn default_hla_viscosity() -> f64 {
    0.01
}
fn default_bulk_modulus() -> f64 {
    1.5e9
}
fn default_supply_pressure() -> f64 {
    3e5
}
fn default_plunger_spring() -> f64 {
    20.0
}
fn default_check_conductance() -> f64 {
    1e-11
}
fn default_hla_damping() -> f64 {
    0.3
}

/// A hydraulic lash adjuster between a direct-acting bucket and the valve (instead of a `lash`
/// and of `train_stiffness`; needs the seat): the high-pressure chamber as an oil column of
/// stiffness `β A²/V`, laminar leak-down through the plunger's clearance `π D c³/(12 μ L)`, and a
/// check valve refilling the chamber from the supply while its pressure is below it (the
/// standard lumped model; `physics::valvetrain::HydraulicLashAdjuster` cites it). On the base
/// circle the cam carries `plunger_spring + supply_pressure × A`; over the lift the adjuster
/// leaks down (`summary.lift_loss`).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct HydraulicAdjusterSpec {
    /// Plunger diameter, m.
    pub plunger_diameter: f64,
    /// Radial clearance between plunger and body, m.
    pub clearance: f64,
    /// Leak length along the plunger, m.
    pub leak_length: f64,
    /// High-pressure chamber volume, m³.
    pub chamber_volume: f64,
    /// Oil viscosity in the clearance, Pa·s. Default 0.01.
    #[serde(default = "default_hla_viscosity")]
    pub viscosity: f64,
    /// Oil bulk modulus (lower with aeration), Pa. Default 1.5e9.
    #[serde(default = "default_bulk_modulus")]
    pub bulk_modulus: f64,
    /// Oil supply pressure (gauge), Pa. Default 3e5.
    #[serde(default = "default_supply_pressure")]
    pub supply_pressure: f64,
    /// Plunger spring preload, N. Default 20.
    #[serde(default = "default_plunger_spring")]
    pub plunger_spring: f64,
    /// Check-valve conductance, m³/(s·Pa). Default 1e-11.
    #[serde(default = "default_check_conductance")]
    pub check_conductance: f64,
    /// Damping ratio of the oil column on the valve mass. Default 0.3.
    #[serde(default = "default_hla_damping")]
    pub damping_ratio: f64,
}
