//! `wear`: how a cam profile wears over running hours.
//!
//! * `model: "archard"` (default): Archard wear `dh/dt = k p v_s` per cam-surface point over the
//!   steady cam cycle of `cam_cycle` (same pair, same physics: kinematics, loads, Hertz contact,
//!   film and Greenwood–Tripp load share, roller slip), with worn-profile evolution every update
//!   interval until the running time or the wear limit. Physics: `physics::wear::{archard,
//!   deposit, evolution}`.
//!   Fidelity `accurate` (and the numerical angles of `auto`): the numerical line-contact EHL film
//!   at every angle of every cycle, whose pressure (spike and exit constriction included) and
//!   local Greenwood–Tripp asperity pressure replace the Hertz band (`physics::wear::archard`);
//!   the cost is bounded by a budget of numerical work (see `validate`).
//! * `model: "irgashev"`: seed 004's method (Tables 1–5, eq. 1–15) on the paper's multi-arc cam and
//!   spherical tappet, reproduced as printed; its inconsistencies are documented in
//!   `physics::wear::irgashev`. Physics: `physics::wear::irgashev`.

use super::cam_cycle::{CamCycle, CamCycleSpec, CamOutput, FollowerSpec, LoadSpec, ProfileSpec, ThermalPair};
use super::common::{cam_spec_path, composite_sigma};
use crate::jobs::cost::Cost;
use crate::jobs::kind::{Kind, Limits, Validation};
use crate::physics::cam::summary::FlatFace;
use crate::physics::contact::contact_modulus;
use crate::physics::film::{model_for, FilmFormula, FilmModelId, Fidelity};
use crate::physics::wear::irgashev::{self, ArcRole, IrgashevSi};
use crate::physics::wear::{evolve, ArchardParams, LoadShare, Stop, WearRun};
use crate::physics::{ensure_finite, Convergence, Observer, SolveError};
use serde::{Deserialize, Serialize};
use serde_json::{json, Value};
use std::collections::BTreeMap;
use utoipa::ToSchema;

pub struct Wear;

/// Most profile updates of one run at fidelity `fast`, including the ones added for stability
/// (each is one cam cycle).
pub const MAX_UPDATES: usize = 5_000;

/// At fidelity `accurate`/`auto` a run takes at most this many times its planned updates
/// (`ceil(hours / update_interval_hours)`): the stability cut may shorten intervals, but the
/// numerical work stays within the validated budget.
pub const NUMERICAL_UPDATE_FACTOR: usize = 2;

/// The unit of numerical work of the budget: one cam cycle of 720 angles on 192-node EHL grids
/// (`cam_cycle`'s default accurate cycle, ≈ 1–2.5 s in release on the seed cases).
pub const STANDARD_CYCLE_WORK: usize = 720 * 192;

// ---------------------------------------------------------------- spec

/// Wear model.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize, ToSchema)]
#[serde(rename_all = "snake_case")]
pub enum WearModel {
    /// Archard wear over the cam cycle with worn-profile evolution.
    #[default]
    Archard,
    /// Seed 004's empirical method (multi-arc cam, spherical tappet, eq. 15).
    Irgashev,
}

/// A wear coefficient: either the dimensional `k` or the dimensionless `K` with the hardness `H`
/// of the wearing body (`k = K/H`).
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct WearCoefficientSpec {
    /// Dimensional wear coefficient k, m³/(N·m) (= 1/Pa): worn volume per unit load and sliding
    /// distance. Typical lubricated steel cams: 1e-18 … 1e-16.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub dimensional: Option<f64>,
    /// Dimensionless Archard coefficient K (with `hardness`). Typical lubricated steel: 1e-9 … 1e-6.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub dimensionless: Option<f64>,
    /// Hardness H of the wearing body, Pa (Vickers HV × 9.807e6; 60 HRC ≈ 7e9 Pa).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub hardness: Option<f64>,
}

impl WearCoefficientSpec {
    /// k in 1/Pa.
    pub fn k(&self) -> f64 {
        match (self.dimensional, self.dimensionless, self.hardness) {
            (Some(k), _, _) => k,
            (None, Some(kk), Some(h)) => kk / h,
            _ => 0.0,
        }
    }
    fn validate(&self, path: &str, v: &mut Validation) {
        match (self.dimensional, self.dimensionless, self.hardness) {
            (Some(k), None, None) => {
                v.in_range(&format!("{path}/dimensional"), k, 0.0, 1e-9);
            }
            (None, Some(kk), Some(h)) => {
                v.in_range(&format!("{path}/dimensionless"), kk, 0.0, 1.0);
                v.in_range(&format!("{path}/hardness"), h, 1e6, 1e11);
            }
            _ => {
                v.error(path, "give either `dimensional` (k, m³/(N·m)) or `dimensionless` (K) with `hardness` (Pa)");
            }
        }
    }
}

/// Which part of the contact load wears the surfaces.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize, ToSchema)]
#[serde(rename_all = "snake_case")]
pub enum LoadShareSpec {
    /// Only the asperity-carried share (Greenwood–Tripp, from the cycle's film): needs a
    /// lubricant and rough surfaces.
    #[default]
    Asperity,
    /// The whole contact load (dry or boundary contact; or a k measured under the same
    /// lubrication).
    Full,
}

/// Which contact widths (eq. 2) and areas (eq. 3) seed 004's method uses.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize, ToSchema)]
#[serde(rename_all = "snake_case")]
pub enum WidthReadingSpec {
    /// Eq. 2–3 at the cam material's Young's modulus, unrounded (the consistent reading).
    #[default]
    Material,
    /// The paper's tables: eq. 2 at E = 215 GPa (the modulus with which eq. 2 gives every width of
    /// Table 3 to its printed 0.001 mm; 210 GPa leaves them 0.8 % wide and eq. 15 2.4 % low),
    /// rounded to 0.001 mm as Table 5 feeds them into eq. 15; eq. 3 at the cam's modulus rounded
    /// to 0.001 mm². Reproduces Table 5's rows from its printed inputs.
    Paper,
}

impl From<WidthReadingSpec> for irgashev::WidthReading {
    fn from(w: WidthReadingSpec) -> Self {
        match w {
            WidthReadingSpec::Material => irgashev::WidthReading::Material,
            WidthReadingSpec::Paper => irgashev::WidthReading::Paper,
        }
    }
}

fn default_steps() -> usize {
    9
}
fn default_theta() -> f64 {
    4.23e-12
}
fn default_yield() -> f64 {
    1.3e9
}
fn default_c() -> f64 {
    3.0
}
fn default_np() -> f64 {
    24.0
}

/// Inputs of seed 004's method besides the pair (defaults: the paper's values listed after
/// eq. 15).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct IrgashevSpec {
    /// Slip δ per arc (Table 4: 0.0111, 0.1211, 0.2360, 0.2360, 0.1285, 0.113), dimensionless.
    pub slip: Vec<f64>,
    /// Follower lift at the nose, m (the paper's 10 mm: 440 N over 44 N/mm).
    pub nose_lift: f64,
    /// Rows per flank arc, each a step of equal angle and equal lift increment. Default 9.
    #[serde(default = "default_steps")]
    pub flank_steps: usize,
    /// Elasticity constant θ, 1/Pa. Default 4.23e-12 (the paper's 4.23e-6 1/MPa).
    #[serde(default = "default_theta")]
    pub elasticity_constant: f64,
    /// Yield strength σ_t of the cam, Pa. Default 1.3e9.
    #[serde(default = "default_yield")]
    pub yield_strength: f64,
    /// Deformation coefficient c. Default 3.
    #[serde(default = "default_c")]
    pub deformation_coefficient: f64,
    /// Loadings that fail the deformed volume, n_p. Default 24.
    #[serde(default = "default_np")]
    pub cycles_to_failure: f64,
    /// Contact widths and areas: `material` (default: eq. 2–3 at the cam's modulus) or `paper`
    /// (Table 3's reading: eq. 2 at 215 GPa, rounded to 0.001 mm; reproduces Table 5).
    #[serde(default)]
    pub width_reading: WidthReadingSpec,
}

fn default_snapshots() -> usize {
    10
}

/// Spec of a `wear` job. The cam–follower pair is exactly `cam_cycle`'s (steady running only).
/// SI units; angles in degrees where the name says so.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct WearSpec {
    /// The cam–follower pair and its running, as a `cam_cycle` spec: steady running only; the
    /// wear model decides what each cycle computes, so `outputs`, `profile_angles_deg` and
    /// `thermal` stay out. Its `fidelity` is the film model of every cycle (archard): `fast`
    /// (closed forms: Hertz pressure, Greenwood–Tripp share at the central film; default),
    /// `accurate` (the numerical line-contact EHL solver at every angle of every cycle: the
    /// wearing pressure is the EHL pressure, or with `load_share: asperity` the Greenwood–Tripp
    /// asperity pressure at the local film, which peaks at the exit constriction; spherical
    /// tappets keep the closed form), `auto` (per angle the closed form where its estimated error
    /// is within `ehl.auto_tolerance`, the numerical solver elsewhere; each angle wears with the
    /// model that ran there). `accurate` and `auto` need a lubricant, and their work — angles ×
    /// (2 × planned updates + 1) × `ehl.nodes` — counted in cycles of 720 angles × 192 nodes, must
    /// stay within the server's evaluation limit; a run takes at most twice its planned updates
    /// (stability cuts included). Its `angles` are also the resolution of the wear profile. A
    /// lubricant is required for the asperity load share and for roller followers (slip); without
    /// one the contact is dry.
    pub cycle: CamCycleSpec,
    /// `archard` (default) or `irgashev`.
    #[serde(default)]
    pub model: WearModel,
    /// Running time, h (give `hours` or `cycles`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub hours: Option<f64>,
    /// Running time in camshaft revolutions (give `hours` or `cycles`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub cycles: Option<f64>,
    /// Archard: running time between profile updates, h. Default: a tenth of the running time.
    /// Updates that would wear more than 0.1·ρ·Δθ² somewhere (ρ the cam's radius of curvature,
    /// Δθ the angle step) are shortened automatically: larger steps make the explicit update
    /// unstable.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub update_interval_hours: Option<f64>,
    /// Wear coefficient of the cam (required by `archard`; with `irgashev` it adds an Archard
    /// column to the rows).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub wear_coefficient: Option<WearCoefficientSpec>,
    /// Wear coefficient of the follower. Default: the cam's.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub follower_wear_coefficient: Option<WearCoefficientSpec>,
    /// `asperity` (default) or `full`.
    #[serde(default)]
    pub load_share: LoadShareSpec,
    /// Cam wear depth that ends the run, m.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub wear_limit: Option<f64>,
    /// Archard: wear-depth profiles kept over time (evenly spaced). Default 10; 0 for none.
    #[serde(default = "default_snapshots")]
    pub snapshots: usize,
    /// Required by `model: irgashev`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub irgashev: Option<IrgashevSpec>,
}

// ---------------------------------------------------------------- result

/// Why the run ended.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, ToSchema)]
#[serde(rename_all = "snake_case")]
pub enum WearStopReason {
    /// The requested running time was reached.
    Completed,
    /// The cam wear depth reached `wear_limit`.
    WearLimit,
    /// The next worn profile would undercut the cam (cusp).
    CamUndercut,
    /// On the next worn profile the follower would leave the cam.
    FollowerSeparation,
    /// On the next worn profile the contact would run off the flat face.
    ContactOffFace,
    /// Another typed failure of the cycle on the next worn profile (see `code`).
    ProfileFailure,
    /// Stable updates would need more than the most updates a run may take (`update_limit`).
    UpdateLimit,
}

/// How the run ended. A run that ends on a failed profile still returns everything up to the
/// last valid profile.
#[derive(Debug, Clone, PartialEq, Serialize, ToSchema)]
pub struct WearTermination {
    pub reason: WearStopReason,
    /// The cycle's error code when the profile failed (`cam_undercut`, `follower_separation`, …).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub code: Option<String>,
    /// Its message.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub message: Option<String>,
    /// Running time of the profile update that failed, h.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub at_hours: Option<f64>,
}

/// Per cam angle, columnar, SI. Archard: at the end of the run; `angle_deg` is the cam angle at
/// which that cam point meets the follower. Irgashev: `angle_deg` is the position along the
/// profile (the arcs laid end to end from the start of arc 1).
#[derive(Debug, Clone, PartialEq, Default, Serialize, ToSchema)]
pub struct WearSeries {
    /// Degrees.
    pub angle_deg: Vec<f64>,
    /// Cam wear depth along the surface normal, m.
    pub wear_depth: Vec<f64>,
    /// Cam wear rate at the end of the run, m/s.
    pub wear_rate: Vec<f64>,
    /// Drop of the follower lift at this cam angle (wear/cos φ), m.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub lift_loss: Option<Vec<f64>>,
    /// Arc length along the cam surface from the point of 0°, m.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub surface_position: Option<Vec<f64>>,
    /// Follower lift of the original profile, m.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub initial_lift: Option<Vec<f64>>,
    /// Follower lift of the worn profile, m.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub final_lift: Option<Vec<f64>>,
    /// Share of the contact load that wears (asperity share or 1), end of the run.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub worn_load_share: Option<Vec<f64>>,
    /// Sliding velocity u_c − u_f at the end of the run, m/s.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub sliding_velocity: Option<Vec<f64>>,
    /// Hertz peak pressure on the original and on the worn profile, Pa.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub initial_hertz_pressure: Option<Vec<f64>>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub final_hertz_pressure: Option<Vec<f64>>,
    /// Minimum film on the original and on the worn profile, m.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub initial_film_min: Option<Vec<f64>>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub final_film_min: Option<Vec<f64>>,
    /// Film model that ran at each angle on the worn profile (fidelity accurate/auto).
    #[serde(skip_serializing_if = "Option::is_none")]
    #[schema(value_type = Option<Vec<crate::jobs::schemas::FilmModelIdDoc>>)]
    pub film_model: Option<Vec<FilmModelId>>,
}

/// One row of seed 004's Tables 1–5 (SI, except where the name says otherwise).
#[derive(Debug, Clone, PartialEq, Serialize, ToSchema)]
pub struct WearRow {
    /// Profile part (arc) number, from 1.
    pub part: usize,
    /// Step within a flank arc, from 1; 0 for base and nose arcs.
    pub step: usize,
    /// `base`, `flank_rising`, `nose` or `flank_falling`.
    pub role: String,
    /// Start and end of the row along the profile, degrees.
    pub position_start_deg: f64,
    pub position_end_deg: f64,
    /// Table 5's "current deflection angle" of the part, degrees.
    pub angle_deg: f64,
    /// Arc radius, m.
    pub radius: f64,
    /// Reduced radius with the tappet sphere (Table 1), m.
    pub reduced_radius: f64,
    /// Follower lift of the row, m.
    pub lift: f64,
    /// Spring force (Tables 3–5), N.
    pub spring_force: f64,
    /// Arc length by eq. 1 as printed, 2αr/360 (Tables 2 and 5), m.
    pub profile_length_as_printed: f64,
    /// True arc length παr/180, m.
    pub profile_length: f64,
    /// Contact width by eq. 2 (Table 3), m.
    pub contact_width: f64,
    /// Contact area by eq. 3 (Table 3), m².
    pub contact_area: f64,
    /// Slip δ (Table 4).
    pub slip: f64,
    /// Wear rate by eq. 15 as printed (Table 5's withheld column), mm/h.
    pub wear_rate_mm_per_h: f64,
    /// Wear rate by eq. 6 with eq. 7–14 substituted (what eq. 15 claims to simplify), mm/h.
    pub chain_wear_rate_mm_per_h: f64,
    /// Hertz contact width 2a along the rolling direction (sphere on the arc), m.
    pub hertz_contact_width: f64,
    /// Hertz peak pressure, Pa.
    pub hertz_pressure: f64,
    /// Archard: k δ (π/2) p0 a per pass × passes per hour (when `wear_coefficient` is given), mm/h.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub archard_wear_rate_mm_per_h: Option<f64>,
}

/// The state after each profile update (and at the start).
#[derive(Debug, Clone, PartialEq, Serialize, ToSchema)]
pub struct WearHistoryRow {
    /// Running time, h.
    pub hours: f64,
    /// Camshaft revolutions.
    pub cycles: f64,
    /// Largest cam wear depth, m.
    pub max_wear_depth: f64,
    /// Its cam angle, degrees.
    pub max_wear_angle_deg: f64,
    /// Largest cam wear rate on this profile, m/s.
    pub max_wear_rate: f64,
    /// Cam volume worn so far, m³.
    pub worn_volume: f64,
    /// Follower volume worn so far, m³.
    pub follower_worn_volume: f64,
    /// Drop of the peak follower lift, m.
    pub valve_lift_loss: f64,
    /// Smallest minimum film over the revolution, m (when a film is computed).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub min_film: Option<f64>,
    /// Largest Hertz pressure over the revolution, Pa.
    pub max_pressure: f64,
    /// Largest pressure of the numerical EHL film over the revolution (exit spike included), Pa
    /// (fidelity accurate/auto, where the numerical model ran).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub max_film_pressure: Option<f64>,
}

/// Flat follower face wear, columnar.
#[derive(Debug, Clone, PartialEq, Serialize, ToSchema)]
pub struct FaceWear {
    /// Position on the face, m, measured like the cycle's `contact_offset`: from the cam centre
    /// line (the follower axis when `offset` is 0).
    pub position: Vec<f64>,
    /// Face wear depth, m.
    pub wear_depth: Vec<f64>,
}

/// The cam wear depth at one time.
#[derive(Debug, Clone, PartialEq, Serialize, ToSchema)]
pub struct WearSnapshot {
    /// h.
    pub hours: f64,
    /// Per cam angle (the series' `angle_deg`), m.
    pub wear_depth: Vec<f64>,
}

/// Flat numbers.
#[derive(Debug, Clone, PartialEq, Default, Serialize, ToSchema)]
pub struct WearSummary {
    /// Largest cam wear depth, m.
    pub max_wear_depth: f64,
    /// Where, degrees (cam angle; irgashev: profile position).
    pub max_wear_angle_deg: f64,
    /// Largest cam wear rate at the end, m/s.
    pub max_wear_rate: f64,
    /// Running time at which the cam wear reached `wear_limit`, h (absent when not reached).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub hours_to_limit: Option<f64>,
    /// When the limit was not reached: the time it would be at the final wear rates, h.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub hours_to_limit_extrapolated: Option<f64>,
    /// Cam volume worn, m³ (`k ∫ F_worn |v_s| dt`).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub worn_volume: Option<f64>,
    /// Follower volume worn, m³.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub follower_worn_volume: Option<f64>,
    /// Flat face: largest face wear depth, m, and its position from the axis, m.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub max_follower_wear_depth: Option<f64>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub max_follower_wear_position: Option<f64>,
    /// Roller: wear depth spread evenly over its circumference, m.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub roller_wear_depth: Option<f64>,
    /// Loss of peak valve lift with mechanical lash (drop of the peak follower lift), m.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub valve_lift_loss: Option<f64>,
    /// Loss of peak valve lift with a lash adjuster (drop of the peak lift over the base circle's
    /// mean lift, the base circle being where the original lift is lowest), m.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub valve_lift_loss_lash_adjusted: Option<f64>,
    /// Smallest minimum film on the original and on the final profile, m.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub initial_min_film: Option<f64>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub final_min_film: Option<f64>,
    /// Largest Hertz pressure on the original and on the final profile, Pa.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub initial_max_pressure: Option<f64>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub final_max_pressure: Option<f64>,
    /// Largest numerical EHL film pressure (exit spike included) on the original and on the final
    /// profile, Pa (fidelity accurate/auto, where the numerical model ran).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub initial_max_film_pressure: Option<f64>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub final_max_film_pressure: Option<f64>,
    /// Fidelity accurate/auto: angles at which each film model ran (`numerical`, `pan_hamrock`,
    /// …), summed over every cycle of the run (the unworn profile and each update).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub fidelity_used: Option<BTreeMap<String, usize>>,
}

/// Result of a `wear` job.
#[derive(Debug, Clone, PartialEq, Serialize, ToSchema)]
pub struct WearResult {
    pub model: WearModel,
    /// Fidelity requested (per-model counts: `summary.fidelity_used`).
    #[schema(value_type = crate::jobs::schemas::FidelityDoc)]
    pub fidelity_used: Fidelity,
    /// Film model of the cycles (when a film was computed and one model ran at every angle;
    /// absent when `auto` mixed models or a point contact kept the closed form).
    #[serde(skip_serializing_if = "Option::is_none")]
    #[schema(value_type = Option<crate::jobs::schemas::FilmModelIdDoc>)]
    pub film_model: Option<FilmModelId>,
    /// Cam wear coefficient used, m³/(N·m).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub wear_coefficient: Option<f64>,
    pub termination: WearTermination,
    /// Running time reached, h.
    pub hours: f64,
    /// Camshaft revolutions run.
    pub cycles: f64,
    /// Profile updates performed (archard).
    pub updates: usize,
    /// Angles per revolution.
    pub angles: usize,
    pub series: WearSeries,
    /// Seed 004's Tables 1–5, one row per spring force (irgashev).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub rows: Option<Vec<WearRow>>,
    /// After each update (archard).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub history: Option<Vec<WearHistoryRow>>,
    /// Flat follower face wear (archard, flat-faced follower).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub follower_face: Option<FaceWear>,
    /// Cam wear-depth profiles over time (archard).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub snapshots: Option<Vec<WearSnapshot>>,
    pub summary: WearSummary,
    /// Archard: the profile updates (a fixed-step march: no tolerance); irgashev: closed form.
    #[schema(value_type = crate::jobs::schemas::ConvergenceDoc)]
    pub convergence: Convergence,
}

// ---------------------------------------------------------------- conversion

impl WearSpec {
    fn is_roller(&self) -> bool {
        matches!(self.cycle.follower, FollowerSpec::Roller { .. })
    }

    /// The pair as a `cam_cycle` spec computing what the wear model needs.
    pub fn cycle_spec(&self) -> CamCycleSpec {
        let mut outputs = match self.model {
            WearModel::Archard => vec![CamOutput::Kinematics, CamOutput::Loads, CamOutput::Contact],
            WearModel::Irgashev => vec![CamOutput::Kinematics],
        };
        if self.model == WearModel::Archard {
            // Accurate/auto: the film's pressure wears, whatever the load share.
            let film_pressure = self.cycle.fidelity != Fidelity::Fast;
            if self.cycle.lubricant.is_some() && (self.load_share == LoadShareSpec::Asperity || self.is_roller() || film_pressure) {
                outputs.push(CamOutput::Film);
            }
            if self.is_roller() {
                outputs.push(CamOutput::Slip);
            }
        }
        CamCycleSpec { outputs, ..self.cycle.clone() }
    }

    fn omega(&self) -> f64 {
        crate::physics::units::rpm_to_rad_per_s(self.cycle.operation.speed_rpm)
    }

    /// Running time, h.
    pub fn running_hours(&self) -> f64 {
        match (self.hours, self.cycles) {
            (Some(h), _) => h,
            (None, Some(c)) => crate::physics::units::hours_for_revolutions(c, self.cycle.operation.speed_rpm),
            _ => 0.0,
        }
    }

    fn update_hours(&self) -> f64 {
        self.update_interval_hours.unwrap_or(self.running_hours() / 10.0)
    }

    /// Profile updates the running time and interval ask for (0 when either is not usable).
    fn planned_updates(&self) -> usize {
        let (hours, u) = (self.running_hours(), self.update_hours());
        if hours > 0.0 && u > 0.0 && u.is_finite() { (hours / u).ceil().min(1e15) as usize } else { 0 }
    }

    /// Most profile updates of a run (see [`NUMERICAL_UPDATE_FACTOR`]).
    fn max_updates(&self) -> usize {
        match self.cycle.fidelity {
            Fidelity::Fast => MAX_UPDATES,
            _ => self.planned_updates().max(1).saturating_mul(NUMERICAL_UPDATE_FACTOR),
        }
    }

    fn composite_sigma(&self) -> f64 {
        let rq = match &self.cycle.follower {
            FollowerSpec::FlatFaced { roughness_rq, .. }
            | FollowerSpec::Roller { roughness_rq, .. }
            | FollowerSpec::Spherical { roughness_rq, .. } => *roughness_rq,
        };
        composite_sigma(self.cycle.cam.roughness_rq, rq)
    }
}

fn role_name(r: ArcRole) -> &'static str {
    match r {
        ArcRole::Base => "base",
        ArcRole::Nose => "nose",
        ArcRole::Flank { rising: true } => "flank_rising",
        ArcRole::Flank { rising: false } => "flank_falling",
    }
}

fn max_at(v: &[f64]) -> (usize, f64) {
    v.iter().copied().enumerate().fold((0, f64::NEG_INFINITY), |b, (i, x)| if x > b.1 { (i, x) } else { b })
}

fn min_of(v: &[f64]) -> f64 {
    v.iter().copied().fold(f64::INFINITY, f64::min)
}

fn max_of(v: &[f64]) -> f64 {
    v.iter().copied().fold(f64::NEG_INFINITY, f64::max)
}

/// The spec path of a solver input field of a wear run.
fn wear_spec_path(field: &str) -> Option<String> {
    match field {
        "IrgashevInput.slip" => Some("/irgashev/slip".into()),
        "WearRun.hours" => Some("/hours".into()),
        _ => cam_spec_path(field),
    }
}

/// An input error about the pair names its field inside the wear spec's `cycle` (the cam cycle's
/// conversion names the pair's fields as a `cam_cycle` spec does).
fn in_cycle(e: SolveError) -> SolveError {
    const PAIR: [&str; 5] = ["/cam", "/follower", "/load", "/operation", "/lubricant"];
    match e {
        SolveError::InvalidInput { field, message } if PAIR.iter().any(|p| field == *p || field.starts_with(&format!("{p}/"))) => {
            SolveError::InvalidInput { field: format!("/cycle{field}"), message }
        }
        e => e,
    }
}

fn solve_archard(spec: &WearSpec, observer: &dyn Observer) -> Result<WearResult, SolveError> {
    let cc = spec.cycle_spec();
    let cycle = cc.cycle_spec()?;
    let needs = cc.needs();
    let model = model_for(spec.cycle.fidelity, spec.cycle.film.to_physics(), spec.cycle.ehl.to_physics());
    let mut cycle = cycle;
    if spec.cycle.fidelity != Fidelity::Fast {
        // The wear model reads the numerical film's pressure at every angle where it ran.
        cycle.profile_angles = (0..cycle.angles).collect();
    }
    let k_cam = spec.wear_coefficient.map_or(0.0, |c| c.k());
    let k_follower = spec.follower_wear_coefficient.map_or(k_cam, |c| c.k());
    // A flat face is centred on the follower axis, `offset` from the cam centre line.
    let face = match spec.cycle.follower {
        FollowerSpec::FlatFaced { face_radius: Some(radius), offset, .. } => Some(FlatFace { centre: offset, radius }),
        _ => None,
    };
    let run = WearRun {
        cycle,
        needs,
        archard: ArchardParams {
            cam_coefficient: k_cam,
            follower_coefficient: k_follower,
            load_share: match spec.load_share {
                LoadShareSpec::Asperity if spec.cycle.lubricant.is_some() => LoadShare::Asperity,
                _ => LoadShare::Full,
            },
        },
        hours: spec.running_hours(),
        update_hours: spec.update_hours(),
        wear_limit: spec.wear_limit,
        snapshots: spec.snapshots,
        face,
        face_bins: spec.cycle.angles,
        max_updates: spec.max_updates(),
    };
    let ev = evolve(&run, model.as_ref(), observer)?;
    let degs = |v: &[f64]| v.iter().map(|x| x.to_degrees()).collect::<Vec<_>>();
    let (imax, dmax) = max_at(&ev.depth);
    let termination = match &ev.stop {
        Stop::Completed => WearTermination { reason: WearStopReason::Completed, code: None, message: None, at_hours: None },
        Stop::WearLimit => WearTermination { reason: WearStopReason::WearLimit, code: None, message: None, at_hours: None },
        Stop::Failed { code, message, at_hours } => WearTermination {
            reason: match *code {
                crate::physics::PhysicalFailure::CamUndercut => WearStopReason::CamUndercut,
                crate::physics::PhysicalFailure::FollowerSeparation => WearStopReason::FollowerSeparation,
                crate::physics::PhysicalFailure::ContactOffFace => WearStopReason::ContactOffFace,
                crate::physics::PhysicalFailure::UpdateLimit => WearStopReason::UpdateLimit,
                _ => WearStopReason::ProfileFailure,
            },
            code: Some(code.code().to_string()),
            message: Some(message.clone()),
            at_hours: Some(*at_hours),
        },
    };
    let last = ev.history.last().expect("history starts with the unworn state");
    let first = &ev.history[0];
    let fs = &ev.final_cycle.series;
    let is_series = &ev.initial_cycle.series;
    let mut summary = WearSummary {
        max_wear_depth: dmax,
        max_wear_angle_deg: ev.angle[imax].to_degrees(),
        max_wear_rate: max_of(&ev.rate),
        hours_to_limit: ev.hours_to_limit,
        worn_volume: Some(last.cam_volume),
        follower_worn_volume: Some(last.follower_volume),
        valve_lift_loss: Some(max_of(&ev.initial_lift) - max_of(&ev.final_lift)),
        valve_lift_loss_lash_adjusted: Some({
            // The adjuster takes up the lash on the base circle: the angles of the original's
            // lowest lift.
            let low = min_of(&ev.initial_lift);
            let base: Vec<usize> = (0..ev.angle.len()).filter(|&i| ev.initial_lift[i] <= low + 1e-9).collect();
            let mean = |v: &[f64]| base.iter().map(|&i| v[i]).sum::<f64>() / base.len() as f64;
            (max_of(&ev.initial_lift) - mean(&ev.initial_lift)) - (max_of(&ev.final_lift) - mean(&ev.final_lift))
        }),
        initial_min_film: first.min_film,
        final_min_film: last.min_film,
        initial_max_pressure: Some(first.max_pressure),
        final_max_pressure: Some(last.max_pressure),
        ..Default::default()
    };
    if let (Some(limit), None) = (spec.wear_limit, ev.hours_to_limit) {
        summary.hours_to_limit_extrapolated = crate::physics::wear::evolution::time_to_limit(&ev.depth, &ev.rate, limit).map(|t| ev.hours + crate::physics::units::seconds_to_hours(t));
    }
    if let Some((pos, d)) = &ev.face {
        let (j, m) = max_at(d);
        summary.max_follower_wear_depth = Some(m);
        summary.max_follower_wear_position = Some(pos[j]);
    }
    if let FollowerSpec::Roller { radius, length, .. } = spec.cycle.follower {
        let l = spec.cycle.cam.width.map_or(length, |w| w.min(length));
        summary.roller_wear_depth = Some(last.follower_volume / (2.0 * std::f64::consts::PI * radius * l));
    }
    let numerical = spec.cycle.fidelity != Fidelity::Fast;
    let film_model = if numerical {
        // The model that ran, when one model ran at every angle of every cycle.
        match ev.film_models.as_slice() {
            [(m, _)] => Some(*m),
            _ => None,
        }
    } else {
        needs.film.then(|| match (&spec.cycle.follower, spec.cycle.film.formula) {
            (FollowerSpec::Spherical { .. }, _) => FilmModelId::HamrockDowson,
            (_, FilmFormula::PanHamrock) => FilmModelId::PanHamrock,
            (_, FilmFormula::DowsonHigginson) => FilmModelId::DowsonHigginson,
            (_, FilmFormula::Seed003) => FilmModelId::Seed003,
        })
        .map(|m| if spec.composite_sigma() > 0.0 { m.mixed() } else { m })
    };
    if numerical {
        summary.fidelity_used = Some(ev.film_models.iter().map(|(m, c)| (m.name().to_string(), *c)).collect());
        summary.initial_max_film_pressure = first.max_film_pressure;
        summary.final_max_film_pressure = last.max_film_pressure;
    }
    let history = ev
        .history
        .iter()
        .map(|h| WearHistoryRow {
            hours: h.hours,
            cycles: h.cycles,
            max_wear_depth: h.max_depth,
            max_wear_angle_deg: h.max_depth_angle.to_degrees(),
            max_wear_rate: h.max_rate,
            worn_volume: h.cam_volume,
            follower_worn_volume: h.follower_volume,
            valve_lift_loss: h.peak_lift_loss,
            min_film: h.min_film,
            max_pressure: h.max_pressure,
            max_film_pressure: h.max_film_pressure,
        })
        .collect();
    Ok(WearResult {
        model: WearModel::Archard,
        fidelity_used: spec.cycle.fidelity,
        film_model,
        wear_coefficient: Some(k_cam),
        termination,
        hours: ev.hours,
        cycles: ev.hours * 3600.0 / ev.period,
        updates: ev.updates,
        angles: spec.cycle.angles,
        series: WearSeries {
            angle_deg: degs(&ev.angle),
            wear_depth: ev.depth.clone(),
            wear_rate: ev.rate.clone(),
            lift_loss: Some(ev.lift_drop.clone()),
            surface_position: Some(ev.surface_position.clone()),
            initial_lift: Some(ev.initial_lift.clone()),
            final_lift: Some(ev.final_lift.clone()),
            worn_load_share: Some(ev.worn_share.clone()),
            sliding_velocity: Some(fs.sliding_velocity.clone()),
            initial_hertz_pressure: is_series.hertz_max_pressure.clone(),
            final_hertz_pressure: fs.hertz_max_pressure.clone(),
            initial_film_min: is_series.film_min.clone(),
            final_film_min: fs.film_min.clone(),
            film_model: if numerical { fs.film_model.clone() } else { None },
        },
        rows: None,
        history: Some(history),
        follower_face: ev.face.as_ref().map(|(p, d)| FaceWear { position: p.clone(), wear_depth: d.clone() }),
        snapshots: (spec.snapshots > 0)
            .then(|| ev.snapshots.iter().map(|(h, d)| WearSnapshot { hours: *h, wear_depth: d.clone() }).collect()),
        summary,
        convergence: crate::physics::wear::evolution::convergence(ev.updates),
    })
}

/// The seed 004 inputs of a spec (validated), in SI.
fn irgashev_input(spec: &WearSpec) -> Result<IrgashevSi, SolveError> {
    let ir = spec.irgashev.as_ref().ok_or_else(|| SolveError::invalid("/irgashev", "is required by model irgashev"))?;
    let ProfileSpec::MultiArc { arcs } = &spec.cycle.cam.profile else {
        return Err(SolveError::invalid("/cycle/cam/profile", "model irgashev needs a multi_arc profile"));
    };
    let FollowerSpec::Spherical { radius, material, .. } = spec.cycle.follower else {
        return Err(SolveError::invalid("/cycle/follower", "model irgashev needs a spherical follower"));
    };
    let Some(LoadSpec::ValveTrain { spring_preload, spring_stiffness, .. }) = spec.cycle.load else {
        return Err(SolveError::invalid("/cycle/load", "model irgashev needs a valve_train load"));
    };
    let es = contact_modulus(spec.cycle.cam.material.elastic(), material.elastic());
    Ok(IrgashevSi {
        arcs: arcs.iter().map(|a| (a.radius, a.angle_deg)).collect(),
        tappet_radius: radius,
        cam: spec.cycle.cam.material.elastic(),
        preload: spring_preload,
        spring_rate: spring_stiffness,
        nose_lift: ir.nose_lift,
        slip: ir.slip.clone(),
        flank_steps: ir.flank_steps,
        elasticity_constant: ir.elasticity_constant,
        yield_strength: ir.yield_strength,
        deformation_coefficient: ir.deformation_coefficient,
        cycles_to_failure: ir.cycles_to_failure,
        speed: crate::physics::units::rpm_to_rev_per_s(spec.cycle.operation.speed_rpm),
        archard: spec.wear_coefficient.map(|c| (c.k(), es)),
        width_reading: ir.width_reading.into(),
    })
}

fn solve_irgashev(spec: &WearSpec, observer: &dyn Observer) -> Result<WearResult, SolveError> {
    observer.check()?;
    let input = irgashev_input(spec)?;
    let rows = irgashev::rows(&input.paper_units())?;
    let n = spec.cycle.angles;
    let wear = irgashev::cam_wear(&rows, n, spec.running_hours(), spec.wear_limit);
    let (angle_deg, rate, depth, hours) = (wear.angle_deg, wear.rate, wear.depth, wear.hours);
    let max_rate = max_of(&rate);
    let mut termination = WearTermination { reason: WearStopReason::Completed, code: None, message: None, at_hours: None };
    let mut summary = WearSummary::default();
    if wear.reached_limit {
        summary.hours_to_limit = wear.hours_to_limit;
        termination.reason = WearStopReason::WearLimit;
    } else {
        summary.hours_to_limit_extrapolated = wear.hours_to_limit;
    }
    let (i, d) = max_at(&depth);
    summary.max_wear_depth = d;
    summary.max_wear_angle_deg = angle_deg[i];
    summary.max_wear_rate = max_rate;
    ensure_finite("seed 004 wear", depth.iter().chain(&rate))?;
    let out_rows = rows
        .iter()
        .map(|r| WearRow {
            part: r.part,
            step: r.step,
            role: role_name(r.role).to_string(),
            position_start_deg: r.position_start_deg,
            position_end_deg: r.position_end_deg,
            angle_deg: r.angle_deg,
            radius: r.radius * 1e-3,
            reduced_radius: r.reduced_radius * 1e-3,
            lift: r.lift * 1e-3,
            spring_force: r.spring_force,
            profile_length_as_printed: r.length_as_printed * 1e-3,
            profile_length: r.length * 1e-3,
            contact_width: r.contact_width * 1e-3,
            contact_area: r.contact_area * 1e-6,
            slip: r.slip,
            wear_rate_mm_per_h: r.wear_rate,
            chain_wear_rate_mm_per_h: r.wear_rate_chain,
            hertz_contact_width: r.hertz_width * 1e-3,
            hertz_pressure: r.hertz_pressure * 1e6,
            archard_wear_rate_mm_per_h: r.archard_wear_rate,
        })
        .collect();
    Ok(WearResult {
        model: WearModel::Irgashev,
        fidelity_used: spec.cycle.fidelity,
        film_model: None,
        wear_coefficient: spec.wear_coefficient.map(|c| c.k()),
        termination,
        hours,
        cycles: hours * 3600.0 * spec.omega() / std::f64::consts::TAU,
        updates: 0,
        angles: n,
        series: WearSeries { angle_deg, wear_depth: depth, wear_rate: rate, ..Default::default() },
        rows: Some(out_rows),
        history: None,
        follower_face: None,
        snapshots: None,
        summary,
        convergence: Convergence::closed_form(),
    })
}

impl Kind for Wear {
    const NAME: &'static str = "wear";
    const SOLVER_VERSION: &'static str = "wear-7";
    const DESCRIPTION: &'static str = "Cam wear over running hours: Archard wear over the cam cycle (asperity load share in \
        mixed lubrication, roller slip) with worn-profile evolution, or seed 004's method (model irgashev).";
    const TABLES: &'static [&'static str] = &["series", "rows", "history", "follower_face"];
    type Spec = WearSpec;
    type Output = WearResult;

    fn example() -> Value {
        json!({
            "cycle": {
                "cam": {
                    "profile": {"type": "rise_return", "base_radius": 0.018, "lift": 0.008, "rise_start_deg": 90.0,
                                "rise_deg": 90.0, "return_deg": 90.0, "law": "cycloidal"},
                    "width": 0.012,
                    "roughness_rq": 2e-7
                },
                "follower": {"type": "flat_faced", "roughness_rq": 1e-7},
                "operation": {"speed_rpm": 3000.0},
                "load": {"type": "valve_train", "spring_preload": 450.0, "spring_stiffness": 38000.0, "moving_mass": 0.25},
                "lubricant": {"viscosity": 0.01, "pressure_viscosity": 2.2e-8},
                "angles": 720
            },
            "hours": 1000.0,
            "update_interval_hours": 100.0,
            "wear_coefficient": {"dimensionless": 1e-7, "hardness": 7e9}
        })
    }

    fn validate(spec: &WearSpec, limits: &Limits, v: &mut Validation) {
        // The pair, as cam_cycle validates it.
        v.under("/cycle", |v| {
            CamCycle::validate(&spec.cycle_spec(), limits, v);
            v.check(
                spec.cycle.outputs == super::cam_cycle::default_outputs(),
                "/outputs",
                "the wear model chooses what its cycles compute: leave `outputs` out",
            );
            v.check(spec.cycle.profile_angles_deg.is_empty(), "/profile_angles_deg", "wear keeps no pressure profiles: leave it out");
            v.check(spec.cycle.ehl.thermal.is_none(), "/ehl/thermal", "the wear model does not run the thermal EHL model yet");
            v.check(spec.cycle.ehl.geometry.is_line(), "/ehl/geometry", "the wear model reads line-contact pressure profiles: geometry finite is not supported");
            v.check(spec.cycle.thermal == ThermalPair::default(), "/thermal", "wear computes no temperatures: leave `thermal` out");
        });
        if spec.cycle.fidelity != Fidelity::Fast {
            match spec.model {
                WearModel::Irgashev => {
                    v.error("/cycle/fidelity", "model irgashev is an empirical method without a film model: use fidelity fast");
                }
                WearModel::Archard => {
                    v.check(
                        spec.cycle.lubricant.is_some(),
                        "/cycle/fidelity",
                        "accurate and auto solve the lubricant film: give a lubricant (without one the contact is dry: use fast)",
                    );
                    // Budget of numerical work: every angle of every cycle may run the EHL solver.
                    let cycles = spec.max_updates().saturating_add(1);
                    let work = (spec.cycle.angles as f64) * (cycles as f64) * (spec.cycle.ehl.nodes as f64);
                    let units = (work / STANDARD_CYCLE_WORK as f64).ceil().min(1e15) as usize;
                    v.limit(
                        "/cycle/ehl/nodes",
                        units,
                        limits.max_evaluations,
                        &format!(
                            "the numerical EHL work of this run — {} angles × {cycles} cycles (at most {NUMERICAL_UPDATE_FACTOR} × the planned \
                             updates, plus the unworn cycle) × {} nodes, counted in cycles of 720 angles × 192 nodes (fewer nodes, \
                             angles or updates reduce it)",
                            spec.cycle.angles, spec.cycle.ehl.nodes
                        ),
                    );
                }
            }
        }
        v.check(spec.cycle.operation.startup.is_none(), "/cycle/operation/startup", "wear needs steady running (no startup)");
        match (spec.hours, spec.cycles) {
            (Some(h), None) => {
                v.in_range("/hours", h, 1e-6, 1e6);
            }
            (None, Some(c)) => {
                v.in_range("/cycles", c, 1.0, 1e12);
            }
            _ => {
                v.error("/hours", "give the running time as `hours` or as `cycles` (one of them)");
            }
        }
        if let Some(l) = spec.wear_limit {
            v.in_range("/wear_limit", l, 1e-9, 0.01);
        }
        v.count_in_range("/snapshots", spec.snapshots, 0, 100);
        let sigma = spec.composite_sigma();
        match spec.model {
            WearModel::Archard => {
                match &spec.wear_coefficient {
                    Some(c) => c.validate("/wear_coefficient", v),
                    None => {
                        v.error("/wear_coefficient", "is required by the archard model");
                    }
                }
                if let Some(c) = &spec.follower_wear_coefficient {
                    c.validate("/follower_wear_coefficient", v);
                }
                v.check(spec.irgashev.is_none(), "/irgashev", "belongs to model irgashev");
                if spec.load_share == LoadShareSpec::Asperity {
                    v.check(
                        spec.cycle.lubricant.is_some(),
                        "/load_share",
                        "the asperity share needs a lubricant (without one the contact is dry: use `full`)",
                    );
                    v.check(
                        spec.cycle.lubricant.is_none() || sigma > 0.0,
                        "/load_share",
                        "smooth surfaces carry no asperity load: give roughness_rq of cam or follower, or use `full`",
                    );
                }
                if spec.is_roller() {
                    v.check(spec.cycle.lubricant.is_some(), "/cycle/lubricant", "is required with a roller follower (its slip)");
                }
                if let Some(u) = spec.update_interval_hours {
                    v.check(u.is_finite() && u > 0.0, "/update_interval_hours", "must be a finite number > 0");
                }
                let updates = spec.planned_updates();
                if updates > 0 {
                    v.limit("/update_interval_hours", updates, limits.max_evaluations, "the number of profile updates");
                }
                if let FollowerSpec::Spherical { .. } = spec.cycle.follower {
                    // fine: point contact, no follower-face table
                }
            }
            WearModel::Irgashev => {
                v.check(spec.update_interval_hours.is_none(), "/update_interval_hours", "belongs to model archard");
                if let Some(c) = &spec.wear_coefficient {
                    c.validate("/wear_coefficient", v);
                }
                match &spec.irgashev {
                    None => {
                        v.error("/irgashev", "is required by model irgashev");
                    }
                    Some(ir) => {
                        v.positive("/irgashev/nose_lift", ir.nose_lift);
                        v.count_in_range("/irgashev/flank_steps", ir.flank_steps, 1, 1000);
                        v.positive("/irgashev/elasticity_constant", ir.elasticity_constant);
                        v.positive("/irgashev/yield_strength", ir.yield_strength);
                        v.positive("/irgashev/deformation_coefficient", ir.deformation_coefficient);
                        v.positive("/irgashev/cycles_to_failure", ir.cycles_to_failure);
                        for (i, s) in ir.slip.iter().enumerate() {
                            v.in_range(&format!("/irgashev/slip/{i}"), *s, 0.0, 10.0);
                        }
                        if let ProfileSpec::MultiArc { arcs } = &spec.cycle.cam.profile {
                            v.check(ir.slip.len() == arcs.len(), "/irgashev/slip", "needs one value per arc");
                        }
                    }
                }
                match &spec.cycle.cam.profile {
                    ProfileSpec::MultiArc { arcs } => {
                        v.check(arcs.len() >= 6 && arcs.len() % 2 == 0, "/cycle/cam/profile/arcs", "the seed 004 method needs an even number (≥ 6) of arcs: base, flank(s), nose, nose, flank(s), base");
                        let total: f64 = arcs.iter().map(|a| a.angle_deg).sum();
                        v.check((total - 360.0).abs() < 1e-6, "/cycle/cam/profile/arcs", format!("the arc angles must add up to 360° (they add up to {total}°)"));
                    }
                    _ => {
                        v.error("/cycle/cam/profile", "model irgashev needs a multi_arc profile (seed 004 Tables 1–2)");
                    }
                }
                v.check(matches!(spec.cycle.follower, FollowerSpec::Spherical { .. }), "/cycle/follower", "model irgashev needs a spherical follower (the tappet sphere)");
                match spec.cycle.load {
                    Some(LoadSpec::ValveTrain { spring_stiffness, .. }) => {
                        v.check(spring_stiffness > 0.0, "/cycle/load/spring_stiffness", "must be > 0 for model irgashev");
                    }
                    _ => {
                        v.error("/cycle/load", "model irgashev needs a valve_train load (spring preload and rate)");
                    }
                }
            }
        }
    }

    fn cost(spec: &WearSpec) -> Cost {
        // The unworn cycle and one cycle per profile update (the stability rule may add updates,
        // up to `max_updates`: the estimate counts the planned ones); seed 004's method runs
        // one cycle. Memory: one cycle at a time, plus the wear depth and history per angle.
        let cycle = super::cam_cycle::cycle_cost_with(&spec.cycle_spec(), crate::jobs::cost::WEAR_ANGLE_S);
        let cycles = match spec.model {
            WearModel::Archard => spec.planned_updates().max(1) as f64 + 1.0,
            // Seed 004's method: closed forms over the profile's angles, no film.
            WearModel::Irgashev => {
                let seconds = crate::jobs::cost::JOB_OVERHEAD_S + spec.cycle.angles as f64 * crate::jobs::cost::WEAR_ANGLE_S;
                return Cost::new(seconds, crate::jobs::cost::CAM_BASE_BYTES).work_at("/cycle/angles", format!("{} angles", spec.cycle.angles));
            }
        };
        let what = format!("{cycles:.0} cam cycles ({})", cycle.work_what);
        // The cycle's fixed cost is paid once.
        let once = crate::jobs::cost::CYCLE_BASE_S;
        cycle.plus_seconds(-once).repeated(cycles).plus_seconds(once).under("/cycle").work_at("/update_interval_hours", what)
    }

    fn solve(spec: &WearSpec, observer: &dyn Observer) -> Result<WearResult, SolveError> {
        let solved = match spec.model {
            WearModel::Archard => solve_archard(spec, observer),
            WearModel::Irgashev => solve_irgashev(spec, observer),
        };
        solved.map_err(|e| in_cycle(e.in_spec(wear_spec_path)))
    }
}
