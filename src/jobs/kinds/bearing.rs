//! `bearing`: one finite-length hydrodynamic journal bearing (seed 002): Reynolds equation with
//! Reynolds (Swift–Stieber) cavitation, optional shaft misalignment and axial edge profile, fixed
//! position or load balance; dimensionless figures and, with dimensions, SI values.
//!
//! Conventions (also in the OpenAPI field docs):
//! - Angles: measured around the bearing from the *unloaded side* (the point opposite the
//!   direction of the applied load), positive in the direction of journal rotation. The attitude
//!   angle is the angle from the load line to the line of centres of the mid-plane, positive in
//!   the direction of rotation; the mid-plane's largest film is at `attitude`, its smallest film
//!   at `attitude + 180°`.
//! - `P = p (c/R)²/(6ηω)` (seed 002), `H = h/c`, `Z = z/L`, `W̄ = w (c/R)²/(6ηωRL)`,
//!   Sommerfeld number `S = (R/c)² μN/P_avg = 1/(6πW̄)` with `P_avg = w/(LD)`.
//! - Friction: `friction_variable` is Raimondi & Boyd's `(R/c) f` of the journal: Couette shear
//!   over the whole circumference (the clearance taken as full of oil) plus the pressure-gradient
//!   term — it reproduces their tables. `friction_variable_seed002` reads seed 002 eq. (9)
//!   (Lund & Thomsen's power loss) with the cavitated zone filled by streamers: there only the
//!   fraction `h_c/h` of the gap is sheared, `h_c` being the film at the rupture line; it
//!   reproduces the paper's aligned f = 2.2178 (Table 2) within 0.4 %.
//! - Dynamic coefficients (`outputs: ["dynamic_coefficients"]`): x along the applied load, y
//!   perpendicular to it, 90° ahead in the direction of rotation; `K_ij = −∂F_i/∂x_j`,
//!   `C_ij = −∂F_i/∂ẋ_j` (F: film force on the journal), N/m and N·s/m; dimensionless
//!   `K̄ = K c/W`, `C̄ = C c ω/W` (W the film load, Lund's convention). From the Reynolds equation
//!   linearised about the equilibrium with its cavitation set (the rupture boundary's motion has
//!   no first-order effect); a supply groove stays where the equilibrium put it.
//! - Force and moment coefficients (`outputs: ["moment_coefficients"]`): the 4×4 stiffness and
//!   damping of the coordinates `(x, y, tilt_x, tilt_y)` — the mid-plane centre and the slopes
//!   `dx/dz`, `dy/dz` of the journal axis — against `(F_x, F_y, M_x, M_y)`, the film force and
//!   its moments about the mid-plane `M = ∫ (z − L/2) dF`; the same linearisation with a tilt as
//!   a translation varying as `z − L/2`, twice the linear solves of `dynamic_coefficients`.
//! - Heat balance (`thermal`): bulk model of ISO 7902-1 / DIN 31652-2, temperatures in K
//!   (`physics::journal::heat`); `checks` (with `limits`) compare the minimum film, the specific
//!   load and the maximum bulk temperature with configurable limits.

use crate::jobs::cost::Cost;
use crate::jobs::quantity as Q;
use crate::jobs::kind::{Kind, Limits, OutputInfo, Validation};
use crate::physics::journal::{self, Analysis, Bearing, Guess, Misalignment, Operating, Profile, Settings, Supply, Workspace};
use crate::physics::{Convergence, Observer, SolveError};
use serde::{Deserialize, Serialize};
use serde_json::{json, Value};
use std::f64::consts::PI;
use utoipa::ToSchema;

pub struct BearingKind;

/// Bearing geometry. Give `length_to_diameter`, or `radius` and `length` (then L/D follows);
/// `radius`, `length` and `radial_clearance` together (with `operating`) switch on SI outputs.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct GeometrySpec {
    /// Length-to-diameter ratio L/D (0.05 to 10).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    #[schema(example = 1.25)]
    pub length_to_diameter: Option<f64>,
    /// Journal radius R, m.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub radius: Option<f64>,
    /// Bearing length L, m.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub length: Option<f64>,
    /// Radial clearance c, m.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub radial_clearance: Option<f64>,
}

/// Operating conditions (isoviscous lubricant).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct OperatingSpec {
    /// Journal speed, rev/min.
    #[schema(example = 3000.0)]
    pub speed_rpm: f64,
    /// Dynamic viscosity of the film, Pa·s. Required unless `thermal` is given (then the heat
    /// balance finds it; a viscosity given alongside is not allowed).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    #[schema(example = 0.0293)]
    pub viscosity: Option<f64>,
}

/// One point of a viscosity–temperature curve.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct BearingViscosityPoint {
    /// K.
    pub temperature: f64,
    /// Dynamic viscosity, Pa·s.
    pub viscosity: f64,
}

fn default_density() -> f64 {
    870.0
}
fn default_specific_heat() -> f64 {
    2000.0
}

/// Lubricant of the heat balance: an ISO VG grade or a two-point curve, both through Walther's
/// law (ASTM D341) `log10 log10(ν + 0.7) = a − b log10 T` (ν mm²/s, T K).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct BearingLubricantSpec {
    /// ISO VG grade (ISO 3448: ν at 40 °C, mm²/s): 10, 15, 22, 32, 46, 68, 100, 150, 220, 320,
    /// 460, 680, 1000. The 100 °C point is the typical value of a VI ≈ 95–100 mineral oil
    /// (e.g. VG 32: 5.4, VG 46: 6.8, VG 68: 8.7 mm²/s) unless `viscosity_100c` gives it.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    #[schema(example = 46)]
    pub iso_vg: Option<u32>,
    /// With `iso_vg`: kinematic viscosity at 100 °C, mm²/s (from the oil's data sheet).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub viscosity_100c: Option<f64>,
    /// Instead of `iso_vg`: two (temperature, dynamic viscosity) points.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub viscosity_curve: Option<Vec<BearingViscosityPoint>>,
    /// Density, kg/m³ (taken constant). Default 870.
    #[serde(default = "default_density")]
    pub density: f64,
    /// Specific heat, J/(kg·K). Default 2000.
    #[serde(default = "default_specific_heat")]
    pub specific_heat: f64,
}

/// Heat conducted through the housing to the ambient: `k_A (T_eff − T_amb)`.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct BearingHousingSpec {
    /// `k_A`: heat transfer coefficient times area, W/K.
    pub heat_transfer: f64,
    /// K.
    pub ambient_temperature: f64,
}

fn default_thermal_tolerance() -> f64 {
    0.01
}
fn default_thermal_iterations() -> u32 {
    30
}

/// Heat balance (ISO 7902-1 / DIN 31652-2 bulk model, see the kind's description): the film's
/// effective temperature `T_eff = (T_1 + T_2)/2` from the friction power against the heat the
/// oil flows carry (side leakage at `T_eff`, drained recirculation at `T_2`) and the housing
/// conducts; the film inlet `T_1 = T_s + κ (Q − Q_s)/Q (T_2 − T_s)` mixes supply oil with the
/// carried-over hot oil. Iterated with the viscosity–temperature law. Needs `geometry.radius`,
/// `length`, `radial_clearance`, `operating.speed_rpm` and a `load.force` or
/// `load.eccentricity_ratio`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct BearingThermalSpec {
    /// Oil supply temperature, K.
    #[schema(example = 313.15)]
    pub supply_temperature: f64,
    pub lubricant: BearingLubricantSpec,
    /// Hot-oil carry-over factor κ, 0 to 1: the share of the recirculating flow `Q − Q_s` that
    /// re-enters the film at the outlet temperature instead of being replaced by supply oil.
    /// Default 0 (the film is fed with supply oil only: Raimondi & Boyd's temperature rise
    /// `ΔT = P/(ρ c_p (Q − Q_s/2))`).
    #[serde(default)]
    pub carry_over: f64,
    /// Optional heat path through the housing (default: none, adiabatic bearing).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub housing: Option<BearingHousingSpec>,
    /// Tolerance on the effective temperature, K (1e-6 to 1). Default 0.01.
    #[serde(default = "default_thermal_tolerance")]
    pub tolerance: f64,
    /// Cap on bearing analyses of the balance (2 to 200). Default 30.
    #[serde(default = "default_thermal_iterations")]
    pub max_iterations: u32,
}

fn default_journal_roughness() -> f64 {
    2e-6
}
fn default_bearing_roughness() -> f64 {
    3e-6
}
fn default_max_temperature() -> f64 {
    383.15
}
fn default_max_specific_load() -> f64 {
    5e6
}

/// Operating limits (ISO 7902-3 / DIN 31652-3 style); `{}` takes every default. The defaults
/// are conservative values for a white-metal plain bearing; put your standard's or your
/// material's values in.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct BearingLimitsSpec {
    /// Journal roughness Rz, m. Default 2e-6.
    #[serde(default = "default_journal_roughness")]
    pub journal_roughness: f64,
    /// Bearing (bore) roughness Rz, m. Default 3e-6.
    #[serde(default = "default_bearing_roughness")]
    pub bearing_roughness: f64,
    /// Extra allowance in the permissible film, m (shaft deflection, misalignment that is not
    /// modelled in `misalignment`, filtration). Default 0. The permissible minimum film is
    /// `journal_roughness + bearing_roughness + film_allowance`; a `misalignment` given in the
    /// spec is already in the computed minimum film.
    #[serde(default)]
    pub film_allowance: f64,
    /// Permissible maximum (bulk outlet) temperature, K; checked with `thermal`. Default 383.15 (110 °C).
    #[serde(default = "default_max_temperature")]
    pub max_temperature: f64,
    /// Permissible specific load `W/(L D)`, Pa. Default 5e6.
    #[serde(default = "default_max_specific_load")]
    pub max_specific_load: f64,
}

/// The operating point: exactly one of `eccentricity_ratio`, `aligned_eccentricity_ratio`,
/// `force`, `sommerfeld_number`.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct BearingLoadSpec {
    /// Fixed mid-plane eccentricity ratio ε in [0, 0.999]; the attitude angle puts the film
    /// force on the load line, unless `attitude_angle_deg` fixes it too.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub eccentricity_ratio: Option<f64>,
    /// With `eccentricity_ratio`: a fully fixed position; the film force is reported in both
    /// directions. Degrees.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub attitude_angle_deg: Option<f64>,
    /// Carry the load that an aligned, unprofiled bearing of the same L/D, supply and grid
    /// carries at this eccentricity ratio (seed 002 uses 0.6).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    #[schema(example = 0.6)]
    pub aligned_eccentricity_ratio: Option<f64>,
    /// Carry this load, N (needs `geometry.radius`, `length`, `radial_clearance` and `operating`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub force: Option<f64>,
    /// Carry the load of this Sommerfeld number `S = (R/c)² μN/P_avg`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub sommerfeld_number: Option<f64>,
}

/// Shaft misalignment (seed 002 eq. 10–11): deviations of the journal axis at the bearing edges
/// per unit radial clearance. The journal centre at the edge `Z = 0` is displaced from the
/// mid-plane centre by `−vertical` along the load direction and `+horizontal` perpendicular to
/// it (90° ahead in the direction of rotation); at `Z = 1` by the opposite amounts. This is
/// eq. (11) read literally with its side signs (a straight, tilted journal).
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct MisalignmentSpec {
    /// `Δv0 = δv/c` at the edges (−2 to 2).
    #[schema(example = 0.56)]
    pub vertical: f64,
    /// `Δh0 = δh/c` at the edges (−2 to 2).
    #[schema(example = 0.56)]
    pub horizontal: f64,
}

/// Axial edge profile of the bore (seed 002 eq. 13–15), the same at both edges.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct BearingProfileSpec {
    /// Order n: 1 linear, 2 parabolic, 3 cubic.
    #[schema(example = 2)]
    pub order: u32,
    /// ξ = m_r/c: edge opening per unit radial clearance (0 to 5).
    #[schema(example = 0.4)]
    pub height: f64,
    /// ψ = m_l/L: modified fraction of the length at each edge, (0, 0.5].
    #[schema(example = 0.2)]
    pub length_fraction: f64,
}

/// Finite-difference grid.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct GridSpec {
    /// Nodes around the circumference, counting the 360° node that repeats 0° (seed 002: 361).
    /// 17 to 4001. Default 181.
    #[schema(example = 361)]
    pub circumferential: usize,
    /// Nodes along the axis, both edges included (seed 002: 181). 5 to 2001. Default 91.
    #[schema(example = 181)]
    pub axial: usize,
}

impl Default for GridSpec {
    fn default() -> Self {
        GridSpec { circumferential: 181, axial: 91 }
    }
}

/// Oil supply: where the film is at ambient pressure.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize, ToSchema)]
#[serde(tag = "type", rename_all = "snake_case", deny_unknown_fields)]
pub enum SupplySpec {
    /// An axial line at the mid-plane's largest film (a groove that follows the journal): the
    /// assumption of the Raimondi & Boyd tables. Default.
    #[default]
    MaxFilm,
    /// An axial groove at a fixed angle, degrees from the unloaded side in the direction of rotation.
    Angle {
        angle_deg: f64,
    },
    /// No supply line: periodic film, pressure builds where the cavitation condition allows.
    Periodic,
    /// Two axial grooves 180° apart, the first at `angle_deg` (degrees from the unloaded side in
    /// the direction of rotation; 90 puts both on the horizontal plane of a vertical load, the
    /// two-axial-groove bearing of Someya's *Journal-Bearing Databook*). The grooves are lines of
    /// ambient pressure (no width); `grid.circumferential` must be odd (an even number of
    /// intervals) so that the second line falls on a node.
    TwoGrooves {
        angle_deg: f64,
    },
}

/// Solver tolerances and caps (defaults are fine for design work).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize, ToSchema)]
#[serde(deny_unknown_fields, default)]
pub struct SolverSpec {
    /// Relative residual of the pressure solves (1e-12 to 1e-4). Default 1e-6.
    pub pressure_tolerance: f64,
    /// Relative load residual `‖F + W‖/W` of the load balance (1e-10 to 1e-2). Default 1e-5.
    pub load_tolerance: f64,
    /// Load-balance steps on the finest grid (1 to 200). Default 40.
    pub max_load_iterations: u32,
    /// Multigrid cycles per pressure solve (10 to 10000). Default 400.
    pub max_cycles: u32,
    /// Smallest admissible film h/c: a position below it is a closed film (1e-6 to 0.5). Default 1e-3.
    pub min_film: f64,
}

impl Default for SolverSpec {
    fn default() -> Self {
        let s = Settings::default();
        SolverSpec {
            pressure_tolerance: s.pressure_tolerance,
            load_tolerance: s.load_tolerance,
            max_load_iterations: s.max_load_iterations,
            max_cycles: s.max_cycles,
            min_film: s.min_film,
        }
    }
}

/// Optional outputs of a `bearing` job.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, ToSchema)]
#[serde(rename_all = "snake_case")]
pub enum BearingOutput {
    /// Dimensionless pressure at every (downsampled) grid node, in the `field` table.
    PressureField,
    /// Dimensionless film at every (downsampled) grid node, in the `field` table.
    FilmField,
    /// Stiffness and damping coefficients at the equilibrium (linearised Reynolds), block
    /// `dynamic_coefficients`.
    DynamicCoefficients,
    /// The 4×4 stiffness and damping of the journal's translations and tilts (force and moment
    /// coefficients), block `moment_coefficients`; twice the linear solves of
    /// `dynamic_coefficients`, which then comes from the same solves.
    MomentCoefficients,
}

/// Keep every n-th node of the fields (the last node of each direction is always kept).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct StrideSpec {
    /// 1 to 1000.
    pub circumferential: usize,
    /// 1 to 1000.
    pub axial: usize,
}

impl Default for StrideSpec {
    fn default() -> Self {
        StrideSpec { circumferential: 1, axial: 1 }
    }
}

/// Spec of a `bearing` job.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct BearingSpec {
    pub geometry: GeometrySpec,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub operating: Option<OperatingSpec>,
    pub load: BearingLoadSpec,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub misalignment: Option<MisalignmentSpec>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub profile: Option<BearingProfileSpec>,
    #[serde(default)]
    pub grid: GridSpec,
    #[serde(default)]
    pub supply: SupplySpec,
    #[serde(default)]
    pub solver: SolverSpec,
    /// Heat balance: the film viscosity from the energy balance and the lubricant's
    /// viscosity–temperature law (then `operating.viscosity` is left out).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub thermal: Option<BearingThermalSpec>,
    /// Operating limits: with them the result has a `checks` block.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub limits: Option<BearingLimitsSpec>,
    /// Optional outputs: `pressure_field`, `film_field`, `dynamic_coefficients`.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub outputs: Vec<BearingOutput>,
    /// Downsampling of the fields.
    #[serde(default)]
    pub field_stride: StrideSpec,
}

/// A location on the bearing surface.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, ToSchema)]
pub struct Location {
    /// Degrees from the unloaded side in the direction of rotation, [0, 360).
    pub angle_deg: f64,
    /// Z = z/L, 0 to 1.
    pub z: f64,
}

/// Load carried by the film.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, ToSchema)]
pub struct LoadResult {
    /// |W̄| = |w| (c/R)²/(6ηωRL).
    pub dimensionless: f64,
    /// Film force on the journal along the load direction (negative: it holds the load), W̄ units.
    pub along_load_dimensionless: f64,
    /// Film force perpendicular to the load (positive 90° ahead in the rotation direction), W̄ units.
    pub across_load_dimensionless: f64,
    /// |w|, N (with dimensions).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub force: Option<f64>,
    /// Target W̄ of the load balance (absent for a fixed position).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub target_dimensionless: Option<f64>,
}

/// How the pressure was solved on the finest grid.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, ToSchema)]
pub struct PressureConvergence {
    /// Active-set (semismooth Newton) steps of the last pressure solve.
    pub active_set_steps: u32,
    /// Multigrid-preconditioned CG iterations of the last pressure solve.
    pub cycles: u32,
    /// Complementarity residual `‖min(P, λ/d)‖/‖f/d‖` of the reported pressure.
    pub residual: f64,
}

/// Load-balance steps on one grid of the nested sequence.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, ToSchema)]
pub struct GridSteps {
    pub circumferential: usize,
    pub axial: usize,
    pub steps: u32,
}

/// Pressure and film at the grid nodes (one row per node, circumferential index fastest).
#[derive(Debug, Clone, PartialEq, Serialize, ToSchema)]
pub struct FieldTable {
    /// Degrees from the unloaded side in the direction of rotation.
    pub angle_deg: Vec<f64>,
    /// Z = z/L.
    pub z: Vec<f64>,
    /// P = p (c/R)²/(6ηω).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub pressure_dimensionless: Option<Vec<f64>>,
    /// H = h/c.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub film_dimensionless: Option<Vec<f64>>,
}

/// Stiffness coefficients `K_ij = −∂F_i/∂x_j`: x along the load, y perpendicular to it, 90°
/// ahead in the direction of rotation; F the film force on the journal, x the journal centre.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, ToSchema)]
pub struct StiffnessResult {
    pub kxx: f64,
    pub kxy: f64,
    pub kyx: f64,
    pub kyy: f64,
}

/// Damping coefficients `C_ij = −∂F_i/∂ẋ_j`, same frame as the stiffness.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, ToSchema)]
pub struct DampingResult {
    pub cxx: f64,
    pub cxy: f64,
    pub cyx: f64,
    pub cyy: f64,
}

/// Dynamic coefficients of the film at the equilibrium (`outputs: ["dynamic_coefficients"]`),
/// from the linearised perturbation of the Reynolds equation on the equilibrium's cavitation set
/// (Lund 1987); a supply groove stays where the equilibrium put it. Frame: x along the applied
/// load, y perpendicular, 90° ahead in the direction of rotation (the journal turns from x to y);
/// for small motions `ΔF = −K Δx − C Δẋ`.
#[derive(Debug, Clone, PartialEq, Serialize, ToSchema)]
pub struct DynamicCoefficientsResult {
    /// N/m (with dimensions).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub stiffness: Option<StiffnessResult>,
    /// N·s/m (with dimensions).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub damping: Option<DampingResult>,
    /// `K̄ = K c/W` (W the film load); absent at zero load.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub stiffness_dimensionless: Option<StiffnessResult>,
    /// `C̄ = C c ω/W`; absent at zero load.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub damping_dimensionless: Option<DampingResult>,
    /// Rigid symmetric rotor on this film (Lund): whirl frequency / running speed at the
    /// stability threshold; absent at zero load.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub whirl_ratio: Option<f64>,
    /// Threshold rotor mass per bearing `M̄ = m c ω²/W` above which the rigid rotor whirls
    /// (oil whip); absent when the film is stable for any mass or at zero load.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub critical_mass_dimensionless: Option<f64>,
    /// The threshold mass per bearing, kg (with dimensions).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub critical_mass: Option<f64>,
    /// For a rotor whose weight is the load (m = W/g): the threshold speed at this Sommerfeld
    /// number, `ω_th = √(M̄ g/c)`, rev/min (with dimensions). At another speed the Sommerfeld
    /// number and the coefficients change; repeat the analysis there to confirm.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub threshold_speed_rpm: Option<f64>,
    /// The four linear solves: CG iterations, largest relative residual, tolerance.
    #[schema(value_type = crate::jobs::schemas::ConvergenceDoc)]
    pub convergence: Convergence,
}

/// Force and moment coefficients of the film at the equilibrium (`outputs:
/// ["moment_coefficients"]`): the journal's four small motions, the translations `x`, `y` of the
/// mid-plane centre (the frame of `dynamic_coefficients`) and the tilts `tilt_x = dx/dz`,
/// `tilt_y = dy/dz` of the journal axis (rad), against the film force `F_x`, `F_y` and its
/// moments about the mid-plane, `M_x = ∫ (z − L/2) dF_x`, `M_y = ∫ (z − L/2) dF_y` (each moment
/// the generalised force of its tilt). For small motions `ΔQ = −K Δq − C Δq̇` with
/// `q = (x, y, tilt_x, tilt_y)` and `Q = (F_x, F_y, M_x, M_y)`. Rows and columns in that order;
/// the upper-left 2×2 blocks are `dynamic_coefficients`' numbers. Linearised Reynolds on the
/// equilibrium's cavitation set, a tilt being a translation that varies as `(z − L/2)` along
/// the bearing.
#[derive(Debug, Clone, PartialEq, Serialize, ToSchema)]
pub struct MomentCoefficientsResult {
    /// `["x", "y", "tilt_x", "tilt_y"]`: the rows and columns of the matrices.
    pub coordinates: Vec<String>,
    /// `K_ij = −∂Q_i/∂q_j` (with dimensions): N/m in the force–translation block, N/rad in the
    /// force–tilt block, N (N·m/m) in the moment–translation block, N·m/rad in the moment–tilt block.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub stiffness: Option<Vec<Vec<f64>>>,
    /// `C_ij = −∂Q_i/∂q̇_j` (with dimensions): the units of `stiffness` times s.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub damping: Option<Vec<Vec<f64>>>,
    /// `K̄ = K_ij c/(W l_i l_j)` with `l = (1, 1, L, L)`: the coefficients of the dimensionless
    /// coordinates `(x/c, y/c, tilt_x L/c, tilt_y L/c)` per unit load (`K̄ = K c/W` in the
    /// translation block, as in `dynamic_coefficients`); absent at zero load.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub stiffness_dimensionless: Option<Vec<Vec<f64>>>,
    /// `C̄ = C_ij c ω/(W l_i l_j)`; absent at zero load.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub damping_dimensionless: Option<Vec<Vec<f64>>>,
    /// The four adjoint linear solves: CG iterations, largest relative residual, tolerance.
    #[schema(value_type = crate::jobs::schemas::ConvergenceDoc)]
    pub convergence: Convergence,
}

/// Heat balance result.
#[derive(Debug, Clone, PartialEq, Serialize, ToSchema)]
pub struct BearingThermalResult {
    /// Effective film temperature, K: the viscosity law gives `viscosity` at it, and it
    /// reproduces `(T_1 + T_2)/2` of the balance within the tolerance.
    pub effective_temperature: f64,
    /// The film viscosity used, Pa·s (at `effective_temperature`).
    pub viscosity: f64,
    /// mm²/s.
    pub kinematic_viscosity: f64,
    /// `T_1`, film inlet after mixing with carried-over oil, K.
    pub inlet_temperature: f64,
    /// `T_2`, film outlet, K.
    pub outlet_temperature: f64,
    /// Maximum bulk temperature (= `T_2` in the bulk model), K.
    pub max_temperature: f64,
    /// K.
    pub supply_temperature: f64,
    /// Friction power at `T_eff`, W.
    pub power_loss: f64,
    /// Film inflow at the supply line `Q`, m³/s.
    pub film_inflow: f64,
    /// Side leakage `Q_s`, m³/s.
    pub side_flow: f64,
    /// Supply oil needed: `Q_s + (1 − κ)(Q − Q_s)`, m³/s.
    pub supply_flow: f64,
    /// The balance: bearing analyses, |T_eff − T| in K, tolerance.
    #[schema(value_type = crate::jobs::schemas::ConvergenceDoc)]
    pub convergence: Convergence,
}

/// One operating-limit check.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, ToSchema)]
pub struct BearingCheck {
    pub value: f64,
    pub limit: f64,
    pub pass: bool,
    /// Relative margin: `(value − limit)/limit` for a lower limit, `(limit − value)/limit` for
    /// an upper one; negative when the check fails.
    pub margin: f64,
}

/// Operating-limit checks (with `limits`).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, ToSchema)]
pub struct BearingChecks {
    /// Minimum film, m, against `journal_roughness + bearing_roughness + film_allowance`.
    pub min_film: BearingCheck,
    /// Specific load `W/(L D)`, Pa.
    pub specific_load: BearingCheck,
    /// Maximum bulk temperature, K (with `thermal`).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub max_temperature: Option<BearingCheck>,
    /// Every check passes.
    pub pass: bool,
}

/// Result of a `bearing` job.
#[derive(Debug, Clone, PartialEq, Serialize, ToSchema)]
pub struct BearingResult {
    /// Mid-plane eccentricity ratio ε.
    pub eccentricity_ratio: f64,
    /// Mid-plane attitude angle, degrees (see the kind's conventions).
    pub attitude_angle_deg: f64,
    /// S = (R/c)² μN/P_avg = 1/(6πW̄); absent when the film carries no load (ε = 0).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub sommerfeld_number: Option<f64>,
    pub load: LoadResult,
    /// P_max = p_max (c/R)²/(6ηω) (seed 002's P0), refined between nodes by a parabola.
    pub max_pressure_dimensionless: f64,
    pub max_pressure_location: Location,
    /// p_max, Pa (with dimensions).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub max_pressure: Option<f64>,
    /// H_min = h_min/c (seed 002's H0), exact for the film geometry.
    pub min_film_dimensionless: f64,
    pub min_film_location: Location,
    /// h_min, m (with dimensions).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub min_film: Option<f64>,
    /// (R/c) f of the journal (Raimondi & Boyd; = seed 002 eq. 9 with the journal's sign).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub friction_variable: Option<f64>,
    /// (R/c) f as seed 002 eq. (9) is read here: streamers in the cavitated zone shear only the
    /// fraction h_c/h of the gap (h_c: film at the rupture line), plus the pressure term.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub friction_variable_seed002: Option<f64>,
    /// Friction coefficient f of the journal (with dimensions).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub friction_coefficient: Option<f64>,
    /// Q/(R c N L): oil flow into the film across the supply line (periodic film: across the
    /// mid-plane's largest-film line). N in rev/s.
    pub flow_variable: f64,
    /// Q_s/(R c N L): axial outflow through both edges.
    pub side_flow_variable: f64,
    /// Q_s/Q.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub side_flow_ratio: Option<f64>,
    /// Q, m³/s (with dimensions).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub flow: Option<f64>,
    /// Q_s, m³/s (with dimensions).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub side_flow: Option<f64>,
    /// Power loss / (η ω² R³ L / c): the journal's friction force F c/(ηωR²L).
    pub power_loss_dimensionless: f64,
    /// Power loss, W (with dimensions).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub power_loss: Option<f64>,
    /// Load balance (or attitude search) on the finest grid: iterations, relative load residual.
    #[schema(value_type = crate::jobs::schemas::ConvergenceDoc)]
    pub convergence: Convergence,
    pub pressure_convergence: PressureConvergence,
    /// The nested grid sequence, coarsest first.
    pub grids: Vec<GridSteps>,
    /// Requested fields (`outputs`).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub field: Option<FieldTable>,
    /// Stiffness and damping (`outputs: ["dynamic_coefficients"]`).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub dynamic_coefficients: Option<DynamicCoefficientsResult>,
    /// Force and moment coefficients of translations and tilts (`outputs: ["moment_coefficients"]`).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub moment_coefficients: Option<MomentCoefficientsResult>,
    /// Heat balance (with `thermal`).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub thermal: Option<BearingThermalResult>,
    /// Operating-limit checks (with `limits` and dimensions).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub checks: Option<BearingChecks>,
}

pub use crate::physics::journal::Dimensions;

impl BearingSpec {
    /// L/D from the geometry.
    pub fn length_to_diameter(&self) -> f64 {
        match (self.geometry.length_to_diameter, self.geometry.radius, self.geometry.length) {
            (Some(ld), _, _) => ld,
            (None, Some(r), Some(l)) => l / (2.0 * r),
            _ => f64::NAN,
        }
    }

    /// Radius, length, clearance and speed are given (the viscosity may come from `thermal`).
    pub fn has_size_and_speed(&self) -> bool {
        let g = &self.geometry;
        g.radius.is_some() && g.length.is_some() && g.radial_clearance.is_some() && self.operating.is_some()
    }

    /// The spec with the film viscosity `eta` (Pa·s) in place of the heat balance.
    pub fn with_viscosity(&self, eta: f64) -> BearingSpec {
        let mut s = self.clone();
        if let Some(o) = &mut s.operating {
            o.viscosity = Some(eta);
        }
        s.thermal = None;
        s
    }

    pub fn dimensions(&self) -> Option<Dimensions> {
        let g = &self.geometry;
        let o = self.operating?;
        Some(Dimensions {
            radius: g.radius?,
            length: g.length?,
            clearance: g.radial_clearance?,
            omega: crate::physics::units::rpm_to_rad_per_s(o.speed_rpm),
            viscosity: o.viscosity?,
        })
    }

    pub fn bearing(&self) -> Bearing {
        Bearing {
            length_to_diameter: self.length_to_diameter(),
            misalignment: self
                .misalignment
                .map_or(Misalignment::default(), |m| Misalignment { vertical: m.vertical, horizontal: m.horizontal }),
            profile: self.profile.map(|p| Profile { order: p.order, height: p.height, length_fraction: p.length_fraction }),
            supply: match self.supply {
                SupplySpec::MaxFilm => Supply::MaxFilm,
                SupplySpec::Angle { angle_deg } => Supply::Angle(angle_deg.to_radians()),
                SupplySpec::Periodic => Supply::Periodic,
                SupplySpec::TwoGrooves { angle_deg } => Supply::TwoGrooves(angle_deg.to_radians()),
            },
        }
    }

    pub fn settings(&self) -> Settings {
        Settings {
            circumferential: self.grid.circumferential,
            axial: self.grid.axial,
            pressure_tolerance: self.solver.pressure_tolerance,
            load_tolerance: self.solver.load_tolerance,
            max_load_iterations: self.solver.max_load_iterations,
            max_cycles: self.solver.max_cycles,
            min_film: self.solver.min_film,
        }
    }
}

/// Validate the shared parts of a bearing spec (also used by `bearing_optimisation`'s base).
/// `prefix` is prepended to every path (`/base` for the optimisation's base spec).
pub fn validate_bearing(spec: &BearingSpec, limits: &Limits, v: &mut Validation, needs_load: bool, prefix: &str) {
    let px = |s: &str| format!("{prefix}{s}");
    let g = &spec.geometry;
    match (g.length_to_diameter, g.radius, g.length) {
        (Some(ld), r, l) => {
            v.in_range(&px("/geometry/length_to_diameter"), ld, 0.05, 10.0);
            if let (Some(r), Some(l)) = (r, l) {
                if r > 0.0 && l > 0.0 {
                    v.check(
                        ((l / (2.0 * r)) - ld).abs() <= 1e-9 * ld.abs().max(1.0),
                        &px("/geometry/length_to_diameter"),
                        "disagrees with length/(2·radius); give one or the other",
                    );
                }
            }
        }
        (None, Some(_), Some(_)) => {}
        _ => {
            v.error(&px("/geometry/length_to_diameter"), "is required unless radius and length are given");
        }
    }
    for (path, val) in [(px("/geometry/radius"), g.radius), (px("/geometry/length"), g.length), (px("/geometry/radial_clearance"), g.radial_clearance)] {
        if let Some(x) = val {
            v.positive(&path, x);
        }
    }
    if let (Some(r), Some(l)) = (g.radius, g.length) {
        if r > 0.0 && l > 0.0 {
            v.in_range(&px("/geometry/length"), l / (2.0 * r), 0.05, 10.0);
        }
    }
    if let (Some(r), Some(c)) = (g.radius, g.radial_clearance) {
        v.check(c < r, &px("/geometry/radial_clearance"), "must be smaller than the radius");
    }
    if let Some(o) = &spec.operating {
        v.quantity(&px("/operating/speed_rpm"), o.speed_rpm, Q::SPEED_RPM);
        match (o.viscosity, &spec.thermal) {
            (Some(eta), None) => {
                v.quantity(&px("/operating/viscosity"), eta, Q::VISCOSITY);
            }
            (None, None) => {
                v.error(&px("/operating/viscosity"), "is required (or give a thermal block)");
            }
            (Some(_), Some(_)) => {
                v.error(&px("/operating/viscosity"), "leave it out with thermal: the heat balance finds the viscosity");
            }
            (None, Some(_)) => {}
        }
    }
    let l = &spec.load;
    let given = [l.eccentricity_ratio.is_some(), l.aligned_eccentricity_ratio.is_some(), l.force.is_some(), l.sommerfeld_number.is_some()]
        .iter()
        .filter(|b| **b)
        .count();
    if needs_load {
        v.check(
            given == 1,
            &px("/load"),
            "give exactly one of eccentricity_ratio, aligned_eccentricity_ratio, force, sommerfeld_number",
        );
    }
    if let Some(e) = l.eccentricity_ratio {
        v.in_range(&px("/load/eccentricity_ratio"), e, 0.0, 0.999);
    }
    if let Some(a) = l.attitude_angle_deg {
        v.check(a.is_finite(), &px("/load/attitude_angle_deg"), "must be a finite number");
        v.check(l.eccentricity_ratio.is_some(), &px("/load/attitude_angle_deg"), "only with eccentricity_ratio");
    }
    if let Some(e) = l.aligned_eccentricity_ratio {
        v.in_range(&px("/load/aligned_eccentricity_ratio"), e, 1e-4, 0.999);
    }
    if let Some(f) = l.force {
        v.quantity(&px("/load/force"), f, Q::FORCE);
        v.check(spec.has_size_and_speed(), &px("/load/force"), "needs geometry.radius, geometry.length, geometry.radial_clearance and operating");
    }
    if let Some(s) = l.sommerfeld_number {
        v.positive(&px("/load/sommerfeld_number"), s);
    }
    if let Some(m) = &spec.misalignment {
        v.in_range(&px("/misalignment/vertical"), m.vertical, -2.0, 2.0);
        v.in_range(&px("/misalignment/horizontal"), m.horizontal, -2.0, 2.0);
    }
    if let Some(p) = &spec.profile {
        v.check((1..=3).contains(&p.order), &px("/profile/order"), "must be 1, 2 or 3");
        v.in_range(&px("/profile/height"), p.height, 0.0, 5.0);
        v.check(
            p.length_fraction.is_finite() && p.length_fraction > 0.0 && p.length_fraction <= 0.5,
            &px("/profile/length_fraction"),
            "must be in (0, 0.5]",
        );
    }
    v.count_in_range(&px("/grid/circumferential"), spec.grid.circumferential, 17, 4001);
    v.count_in_range(&px("/grid/axial"), spec.grid.axial, 5, 2001);
    v.limit(&px("/grid"), spec.grid.circumferential.saturating_mul(spec.grid.axial), limits.max_grid_nodes, "circumferential × axial nodes");
    if let SupplySpec::Angle { angle_deg } | SupplySpec::TwoGrooves { angle_deg } = spec.supply {
        v.check(angle_deg.is_finite(), &px("/supply/angle_deg"), "must be a finite number");
    }
    if let SupplySpec::TwoGrooves { .. } = spec.supply {
        v.check(
            spec.grid.circumferential % 2 == 1,
            &px("/grid/circumferential"),
            "must be odd with two grooves (an even number of intervals puts the second groove on a node)",
        );
    }
    let s = &spec.solver;
    v.in_range(&px("/solver/pressure_tolerance"), s.pressure_tolerance, 1e-12, 1e-4);
    v.in_range(&px("/solver/load_tolerance"), s.load_tolerance, 1e-10, 1e-2);
    v.count_in_range(&px("/solver/max_load_iterations"), s.max_load_iterations as usize, 1, 200);
    v.count_in_range(&px("/solver/max_cycles"), s.max_cycles as usize, 10, 10_000);
    v.in_range(&px("/solver/min_film"), s.min_film, 1e-6, 0.5);
    if !prefix.is_empty() {
        v.check(spec.thermal.is_none(), &px("/thermal"), "not available in an optimisation");
        v.check(spec.limits.is_none(), &px("/limits"), "not available in an optimisation");
        v.check(!spec.outputs.contains(&BearingOutput::DynamicCoefficients), &px("/outputs"), "dynamic_coefficients is not available in an optimisation");
        v.check(!spec.outputs.contains(&BearingOutput::MomentCoefficients), &px("/outputs"), "moment_coefficients is not available in an optimisation");
    }
    if let Some(t) = &spec.thermal {
        v.check(spec.has_size_and_speed(), &px("/thermal"), "needs geometry.radius, geometry.length, geometry.radial_clearance and operating.speed_rpm");
        v.check(
            l.force.is_some() || l.eccentricity_ratio.is_some(),
            &px("/thermal"),
            "needs load.force or load.eccentricity_ratio (a dimensionless load would change the force with the viscosity)",
        );
        v.in_range(&px("/thermal/supply_temperature"), t.supply_temperature, 200.0, 600.0);
        v.in_range(&px("/thermal/carry_over"), t.carry_over, 0.0, 1.0);
        v.in_range(&px("/thermal/tolerance"), t.tolerance, 1e-6, 1.0);
        v.count_in_range(&px("/thermal/max_iterations"), t.max_iterations as usize, 2, 200);
        let lu = &t.lubricant;
        v.in_range(&px("/thermal/lubricant/density"), lu.density, 100.0, 3000.0);
        v.in_range(&px("/thermal/lubricant/specific_heat"), lu.specific_heat, 100.0, 10000.0);
        v.check(
            lu.iso_vg.is_some() != lu.viscosity_curve.is_some(),
            &px("/thermal/lubricant"),
            "give exactly one of iso_vg, viscosity_curve",
        );
        if let Some(g) = lu.iso_vg {
            v.check(
                journal::heat::ISO_VG_100C.iter().any(|(x, _)| *x == g),
                &px("/thermal/lubricant/iso_vg"),
                "one of 10, 15, 22, 32, 46, 68, 100, 150, 220, 320, 460, 680, 1000",
            );
        }
        if let Some(n) = lu.viscosity_100c {
            v.check(lu.iso_vg.is_some(), &px("/thermal/lubricant/viscosity_100c"), "only with iso_vg");
            v.in_range(&px("/thermal/lubricant/viscosity_100c"), n, 0.5, (lu.iso_vg.unwrap_or(1000) as f64) * 0.999);
        }
        if let Some(c) = &lu.viscosity_curve {
            v.items(&px("/thermal/lubricant/viscosity_curve"), c.len(), 2, Some(2));
            for (i, pt) in c.iter().enumerate() {
                v.in_range(&px(&format!("/thermal/lubricant/viscosity_curve/{i}/temperature")), pt.temperature, 200.0, 600.0);
                v.in_range(&px(&format!("/thermal/lubricant/viscosity_curve/{i}/viscosity")), pt.viscosity, 1e-5, 100.0);
            }
            if c.len() == 2 {
                let (a, b) = (c[0], c[1]);
                v.check(
                    (a.temperature - b.temperature).abs() > 1.0 && (a.temperature - b.temperature) * (a.viscosity - b.viscosity) < 0.0,
                    &px("/thermal/lubricant/viscosity_curve"),
                    "two temperatures at least 1 K apart, the viscosity falling with temperature",
                );
            }
        }
        if let Some(h) = &t.housing {
            v.in_range(&px("/thermal/housing/heat_transfer"), h.heat_transfer, 0.0, 1e6);
            v.in_range(&px("/thermal/housing/ambient_temperature"), h.ambient_temperature, 200.0, 600.0);
        }
    }
    if let Some(lim) = &spec.limits {
        v.check(spec.has_size_and_speed(), &px("/limits"), "needs geometry.radius, geometry.length, geometry.radial_clearance and operating");
        v.in_range(&px("/limits/journal_roughness"), lim.journal_roughness, 0.0, 1e-3);
        v.in_range(&px("/limits/bearing_roughness"), lim.bearing_roughness, 0.0, 1e-3);
        v.in_range(&px("/limits/film_allowance"), lim.film_allowance, 0.0, 1e-3);
        v.in_range(&px("/limits/max_temperature"), lim.max_temperature, 200.0, 800.0);
        v.positive(&px("/limits/max_specific_load"), lim.max_specific_load);
    }
    v.count_in_range(&px("/field_stride/circumferential"), spec.field_stride.circumferential, 1, 1000);
    v.count_in_range(&px("/field_stride/axial"), spec.field_stride.axial, 1, 1000);
}

/// What the spec's `load` asks for, resolved to the solver's operating point (the aligned
/// reference is solved here when needed). Returns the operating point and a starting guess.
pub fn resolve_load(
    spec: &BearingSpec,
    observer: &dyn Observer,
) -> Result<(Operating, Option<Guess>, Option<f64>), SolveError> {
    resolve_load_in(spec, None, observer)
}

/// [`resolve_load`] with a workspace for the reference analysis (the grids are reused; the
/// result does not depend on what the workspace held).
pub fn resolve_load_in(
    spec: &BearingSpec,
    workspace: Option<&mut Workspace>,
    observer: &dyn Observer,
) -> Result<(Operating, Option<Guess>, Option<f64>), SolveError> {
    let l = &spec.load;
    if let Some(e) = l.eccentricity_ratio {
        return Ok(match l.attitude_angle_deg {
            Some(a) => (Operating::Position { eccentricity: e, attitude: a.to_radians() }, None, None),
            None => (Operating::Eccentricity(e), None, None),
        });
    }
    if let Some(e) = l.aligned_eccentricity_ratio {
        let (w, guess) = aligned_reference_in(spec, e, workspace, observer)?;
        return Ok((Operating::Load(w), Some(guess), Some(w)));
    }
    if let Some(f) = l.force {
        let d = spec.dimensions().ok_or_else(|| SolveError::invalid("/load/force", "needs dimensions"))?;
        let w = f / d.load_scale();
        return Ok((Operating::Load(w), None, Some(w)));
    }
    if let Some(s) = l.sommerfeld_number {
        let w = 1.0 / (6.0 * PI * s);
        return Ok((Operating::Load(w), None, Some(w)));
    }
    Err(SolveError::invalid("/load", "no operating point given"))
}

/// The load (W̄) an aligned, unprofiled bearing with the spec's L/D, supply and grid carries at
/// eccentricity ratio `e`, and its position.
pub fn aligned_reference(spec: &BearingSpec, e: f64, observer: &dyn Observer) -> Result<(f64, Guess), SolveError> {
    aligned_reference_in(spec, e, None, observer)
}

fn aligned_reference_in(spec: &BearingSpec, e: f64, workspace: Option<&mut Workspace>, observer: &dyn Observer) -> Result<(f64, Guess), SolveError> {
    let mut b = spec.bearing();
    b.misalignment = Misalignment::default();
    b.profile = None;
    // aligned and unprofiled: symmetric about the mid-plane, solved on half the axial grid
    // (the same discrete equations; an even axial node count takes the full grid)
    journal::symmetric_load(&b, &Operating::Eccentricity(e), &spec.settings(), workspace, None, observer)
}

/// Turn an analysis into the result document.
pub fn to_result(spec: &BearingSpec, a: &Analysis, target: Option<f64>) -> BearingResult {
    let d = spec.dimensions();
    let stride = spec.field_stride;
    let want_p = spec.outputs.contains(&BearingOutput::PressureField);
    let want_h = spec.outputs.contains(&BearingOutput::FilmField);
    let field = a.fields.as_ref().filter(|_| want_p || want_h).map(|f| {
        let nt = f.theta.len();
        let nz = f.z.len();
        // columns 0..nt (the 360° column repeats 0°), rows 0..nz, every stride-th plus the last
        let pick = |n: usize, s: usize| {
            let mut v: Vec<usize> = (0..n).step_by(s).collect();
            if *v.last().unwrap() != n - 1 {
                v.push(n - 1);
            }
            v
        };
        let cols = pick(nt + 1, stride.circumferential);
        let rows = pick(nz, stride.axial);
        let mut t = FieldTable {
            angle_deg: Vec::new(),
            z: Vec::new(),
            pressure_dimensionless: want_p.then(Vec::new),
            film_dimensionless: want_h.then(Vec::new),
        };
        for &j in &rows {
            for &c in &cols {
                let i = c % nt;
                let ang = if c == nt { f.theta[0].to_degrees() + 360.0 } else { f.theta[i].to_degrees() };
                t.angle_deg.push(ang);
                t.z.push(f.z[j]);
                if let Some(p) = &mut t.pressure_dimensionless {
                    p.push(f.pressure[j * nt + i]);
                }
                if let Some(h) = &mut t.film_dimensionless {
                    h.push(f.film[j * nt + i]);
                }
            }
        }
        t
    });
    BearingResult {
        eccentricity_ratio: a.eccentricity,
        attitude_angle_deg: a.attitude.to_degrees(),
        sommerfeld_number: a.sommerfeld,
        load: LoadResult {
            dimensionless: a.load,
            along_load_dimensionless: a.force_along_load,
            across_load_dimensionless: a.force_across_load,
            force: d.map(|d| a.load * d.load_scale()),
            target_dimensionless: target,
        },
        max_pressure_dimensionless: a.max_pressure,
        max_pressure_location: Location { angle_deg: a.max_pressure_theta.to_degrees(), z: a.max_pressure_z },
        max_pressure: d.map(|d| a.max_pressure * d.pressure_scale()),
        min_film_dimensionless: a.min_film,
        min_film_location: Location { angle_deg: a.min_film_theta.to_degrees(), z: a.min_film_z },
        min_film: d.map(|d| d.film(a.min_film)),
        friction_variable: a.friction_variable,
        friction_variable_seed002: a.friction_variable_seed002,
        friction_coefficient: d.and_then(|d| a.friction_variable.map(|f| d.friction_coefficient(f))),
        flow_variable: a.flow_variable,
        side_flow_variable: a.side_flow_variable,
        side_flow_ratio: a.side_flow_ratio,
        flow: d.map(|d| d.flow(a.flow_variable)),
        side_flow: d.map(|d| d.flow(a.side_flow_variable)),
        power_loss_dimensionless: a.friction_force,
        power_loss: d.map(|d| d.power(a.friction_force)),
        convergence: a.convergence.clone(),
        pressure_convergence: PressureConvergence {
            active_set_steps: a.pressure_solve.steps,
            cycles: a.pressure_solve.cycles,
            residual: a.pressure_solve.residual,
        },
        grids: a
            .steps_per_grid
            .iter()
            .map(|&(c, z, s)| GridSteps { circumferential: c, axial: z, steps: s })
            .collect(),
        field,
        dynamic_coefficients: None,
        moment_coefficients: None,
        thermal: None,
        checks: None,
    }
}

/// Solve one bearing spec (shared with the optimisation, which passes a workspace and a guess).
pub fn solve_spec(
    spec: &BearingSpec,
    load: (Operating, Option<Guess>, Option<f64>),
    workspace: Option<&mut Workspace>,
    observer: &dyn Observer,
) -> Result<(Analysis, BearingResult), SolveError> {
    let want_fields = spec.outputs.iter().any(|o| matches!(o, BearingOutput::PressureField | BearingOutput::FilmField));
    let a = journal::analyse(&spec.bearing(), &load.0, &spec.settings(), workspace, load.1, want_fields, observer)?;
    let r = to_result(spec, &a, load.2);
    Ok((a, r))
}

impl Kind for BearingKind {
    const NAME: &'static str = "bearing";
    const SOLVER_VERSION: &'static str = "bearing-10";
    const DESCRIPTION: &'static str = "Finite-length hydrodynamic journal bearing (seed 002): Reynolds \
        equation with Reynolds cavitation solved as a complementarity problem (active set + multigrid), \
        misalignment, axial edge profiles, load balance; Raimondi–Boyd figures and SI values; optional \
        heat balance (effective temperature, ISO VG/Walther viscosity), operating-limit checks and \
        stiffness/damping coefficients (linearised Reynolds) with the rigid-rotor stability threshold.";
    const TABLES: &'static [&'static str] = &["field"];
    type Spec = BearingSpec;
    type Output = BearingResult;

    fn example() -> Value {
        json!({
            "geometry": {"length_to_diameter": 1.25},
            "operating": {"speed_rpm": 3000, "viscosity": 0.0293},
            "load": {"aligned_eccentricity_ratio": 0.6},
            "misalignment": {"vertical": 0.56, "horizontal": 0.56},
            "profile": {"order": 2, "height": 0.4, "length_fraction": 0.2},
            "grid": {"circumferential": 361, "axial": 181}
        })
    }

    fn bound_examples() -> Vec<Value> {
        // The heat balance with a two-point viscosity curve (examples/bearing_thermal.json's case).
        let curve = json!([{"temperature": 313.15, "viscosity": 0.04}, {"temperature": 373.15, "viscosity": 0.007}]);
        vec![json!({"geometry": {"radius": 0.05, "length": 0.04, "radial_clearance": 6e-5}, "operating": {"speed_rpm": 3000}, "load": {"force": 8000},
            "thermal": {"supply_temperature": 313.15, "lubricant": {"viscosity_curve": curve}}, "grid": {"circumferential": 121, "axial": 41}})]
    }

    fn outputs() -> &'static [OutputInfo] {
        &[
            OutputInfo { name: "pressure_field", description: "dimensionless pressure at the grid nodes (table `field`, downsampled by `field_stride`)" },
            OutputInfo { name: "film_field", description: "dimensionless film at the grid nodes (table `field`, downsampled by `field_stride`)" },
            OutputInfo { name: "dynamic_coefficients", description: "stiffness and damping coefficients at the equilibrium (linearised Reynolds; x along the load, y 90° ahead in rotation), dimensionless and SI, rigid-rotor stability threshold" },
            OutputInfo { name: "moment_coefficients", description: "4×4 stiffness and damping of the journal's translations and tilts against the film force and its moments about the mid-plane (linearised Reynolds), dimensionless and SI" },
        ]
    }

    fn validate(spec: &BearingSpec, limits: &Limits, v: &mut Validation) {
        validate_bearing(spec, limits, v, true, "");
    }

    fn cost(spec: &BearingSpec) -> Cost {
        bearing_cost(spec)
    }

    fn solve(spec: &BearingSpec, observer: &dyn Observer) -> Result<BearingResult, SolveError> {
        let solved = || {
            let bearing = spec.bearing();
            let settings = spec.settings();
            let mut ws = Workspace::new(&bearing, &settings);
            let (spec_eff, a, mut r) = match &spec.thermal {
                Some(t) => {
                    observer.progress(0.0, "heat balance");
                    let (spec_eff, a, target, th) = thermal_balance(spec, t, &mut ws, observer)?;
                    let mut r = to_result(&spec_eff, &a, target);
                    r.thermal = Some(th);
                    (spec_eff, a, r)
                }
                None => {
                    observer.progress(0.0, "load");
                    let load = resolve_load(spec, observer)?;
                    observer.progress(0.3, "analysis");
                    let (a, r) = solve_spec(spec, load, Some(&mut ws), observer)?;
                    (spec.clone(), a, r)
                }
            };
            if spec.outputs.contains(&BearingOutput::MomentCoefficients) {
                // the 4×4 set; its translations block is `coefficients`' computation from the same state
                observer.progress(0.8, "moment coefficients");
                let c = journal::dynamics::tilt_coefficients(&bearing, &a, &settings, &mut ws, observer)?;
                if spec.outputs.contains(&BearingOutput::DynamicCoefficients) {
                    r.dynamic_coefficients = Some(dynamic_result(&spec_eff, &a, &c.translation()));
                }
                r.moment_coefficients = Some(moment_result(&spec_eff, &a, &c));
            } else if spec.outputs.contains(&BearingOutput::DynamicCoefficients) {
                observer.progress(0.8, "dynamic coefficients");
                let c = journal::dynamics::coefficients(&bearing, &a, &settings, &mut ws, observer)?;
                r.dynamic_coefficients = Some(dynamic_result(&spec_eff, &a, &c));
            }
            if let Some(lim) = &spec.limits {
                r.checks = checks(&spec_eff, &r, lim);
            }
            observer.progress(1.0, "done");
            Ok(r)
        };
        solved().map_err(|e: SolveError| e.in_spec(bearing_spec_path))
    }
}

/// Analyses a heat balance typically needs (each a warm-started load-balanced analysis).
const HEAT_BALANCE_ANALYSES: f64 = 1.5;

/// The work and memory model of one `bearing` job: load-balanced analyses on the grid
/// (`jobs::cost::bearing_analysis_seconds`), times the heat balance's iterations, plus the
/// coefficients' adjoint solves (2 for the 2×2 set, 4 for the 4×4 set, each about one analysis).
pub fn bearing_cost(spec: &BearingSpec) -> Cost {
    let nodes = spec.grid.circumferential.saturating_mul(spec.grid.axial);
    let one = crate::jobs::cost::bearing_analysis_seconds(nodes);
    let mut analyses = if spec.thermal.is_some() { HEAT_BALANCE_ANALYSES } else { 1.0 };
    // A misaligned journal's film is not symmetric about the mid-plane: the whole grid, twice
    // the work of the aligned half (seed 002's misaligned case).
    if spec.misalignment.is_some() {
        analyses *= 2.0;
    }
    if spec.outputs.contains(&BearingOutput::MomentCoefficients) {
        analyses += 4.0 * 0.5;
    } else if spec.outputs.contains(&BearingOutput::DynamicCoefficients) {
        analyses += 2.0 * 0.5;
    }
    // The multigrid hierarchy (≈ 4/3 of the fine grid) of about 16 arrays of the grid (peak
    // resident memory: 43 MB at 721×361).
    let bytes = 16.0 * 8.0 * 4.0 / 3.0 * nodes as f64 + crate::jobs::cost::MIB;
    let what = format!("{analyses:.0} bearing analyses on {} × {} nodes", spec.grid.circumferential, spec.grid.axial);
    Cost::new(crate::jobs::cost::JOB_OVERHEAD_S + analyses * one, bytes)
        .work_at("/grid", what.clone())
        .memory_at("/grid", what)
}

/// The heat balance: bearing analyses at trial viscosities until the effective temperature
/// reproduces itself. Returns the spec at the final viscosity, its analysis, the load target and
/// the thermal block.
fn thermal_balance(
    spec: &BearingSpec,
    t: &BearingThermalSpec,
    ws: &mut Workspace,
    observer: &dyn Observer,
) -> Result<(BearingSpec, Analysis, Option<f64>, BearingThermalResult), SolveError> {
    use journal::heat::{balance, Cooling, Flows, Oil, Walther};
    let lu = &t.lubricant;
    let law = match (&lu.iso_vg, &lu.viscosity_curve) {
        (Some(g), _) => Walther::iso_vg(*g, lu.viscosity_100c)?,
        (None, Some(c)) if c.len() == 2 => {
            let nu = |p: &BearingViscosityPoint| p.viscosity / lu.density * 1e6;
            Walther::through(c[0].temperature, nu(&c[0]), c[1].temperature, nu(&c[1]))?
        }
        _ => return Err(SolveError::invalid("Lubricant", "an ISO VG grade or a two-point viscosity curve")),
    };
    let oil = Oil { law, density: lu.density, specific_heat: lu.specific_heat };
    let cool = Cooling {
        supply_temperature: t.supply_temperature,
        carry_over: t.carry_over,
        housing: t.housing.map(|h| (h.heat_transfer, h.ambient_temperature)),
        tolerance: t.tolerance,
        max_iterations: t.max_iterations,
    };
    let mut guess: Option<Guess> = None;
    let mut last: Option<(BearingSpec, Analysis, Option<f64>)> = None;
    let b = balance(&oil, &cool, observer, |eta| {
        let s = spec.with_viscosity(eta);
        let d = s.dimensions().ok_or_else(|| SolveError::invalid("/thermal", "needs dimensions"))?;
        let (op, g0, target) = resolve_load(&s, observer)?;
        let (a, _) = solve_spec(&s, (op, guess.or(g0), target), Some(&mut *ws), observer)?;
        guess = Some(Guess { eccentricity: a.eccentricity, attitude: a.attitude });
        let f = Flows { power: d.power(a.friction_force), inflow: d.flow(a.flow_variable), side_flow: d.flow(a.side_flow_variable) };
        last = Some((s, a, target));
        Ok(f)
    })?;
    let (s, a, target) = last.expect("the balance ran at least one analysis");
    let tt = b.temperatures;
    let th = BearingThermalResult {
        effective_temperature: b.temperature,
        viscosity: b.viscosity,
        kinematic_viscosity: b.viscosity / oil.density * 1e6,
        inlet_temperature: tt.inlet,
        outlet_temperature: tt.outlet,
        max_temperature: tt.outlet,
        supply_temperature: t.supply_temperature,
        power_loss: b.flows.power,
        film_inflow: b.flows.inflow,
        side_flow: b.flows.side_flow,
        supply_flow: tt.supply_flow,
        convergence: b.convergence,
    };
    crate::physics::ensure_finite(
        "heat balance",
        [th.effective_temperature, th.viscosity, th.inlet_temperature, th.outlet_temperature, th.power_loss, th.film_inflow, th.side_flow, th.supply_flow].iter(),
    )?;
    Ok((s, a, target, th))
}

/// The coefficients block: dimensionless always (at a positive load), SI with dimensions.
fn dynamic_result(spec: &BearingSpec, a: &Analysis, c: &journal::dynamics::Coefficients) -> DynamicCoefficientsResult {
    let d = spec.dimensions();
    let kmat = |m: [[f64; 2]; 2], s: f64| StiffnessResult { kxx: m[0][0] * s, kxy: m[0][1] * s, kyx: m[1][0] * s, kyy: m[1][1] * s };
    let cmat = |m: [[f64; 2]; 2], s: f64| DampingResult { cxx: m[0][0] * s, cxy: m[0][1] * s, cyx: m[1][0] * s, cyy: m[1][1] * s };
    let nondim = c.dimensionless(a.load);
    let stab = nondim.map(|(k, cc)| journal::dynamics::stability(k, cc));
    // K = (−∂F̄/∂X) · 6ηωRL(R/c)²/c, C = (−∂F̄/∂X') · 6ηωRL(R/c)²/(cω)
    let critical_mass = match (d, stab.and_then(|s| s.critical_mass)) {
        (Some(d), Some(m)) => Some(m * a.load * d.load_scale() / (d.clearance * d.omega * d.omega)),
        _ => None,
    };
    let threshold_speed_rpm = match (d, stab.and_then(|s| s.critical_mass)) {
        (Some(d), Some(m)) => Some((m * 9.80665 / d.clearance).sqrt() * 60.0 / (2.0 * PI)),
        _ => None,
    };
    DynamicCoefficientsResult {
        stiffness: d.map(|d| kmat(c.stiffness, d.load_scale() / d.clearance)),
        damping: d.map(|d| cmat(c.damping, d.load_scale() / (d.clearance * d.omega))),
        stiffness_dimensionless: nondim.map(|(k, _)| kmat(k, 1.0)),
        damping_dimensionless: nondim.map(|(_, cc)| cmat(cc, 1.0)),
        whirl_ratio: stab.map(|s| s.whirl_ratio),
        critical_mass_dimensionless: stab.and_then(|s| s.critical_mass),
        critical_mass,
        threshold_speed_rpm,
        convergence: c.convergence.clone(),
    }
}

/// The force and moment coefficients block: dimensionless always (at a positive load), SI with
/// dimensions. Generalised coordinates `(X, Y, Γx, Γy)` with `Γ = ψ L/c` and forces
/// `(F̄, M̄/L)` in the solver (`journal::dynamics::TiltCoefficients`), so
/// `K_ij = stiffness_ij · (W_scale/c) · l_i l_j` with `l = (1, 1, L, L)`, `C_ij` the same over ω.
fn moment_result(spec: &BearingSpec, a: &Analysis, c: &journal::dynamics::TiltCoefficients) -> MomentCoefficientsResult {
    let d = spec.dimensions();
    let scaled = |m: &[[f64; 4]; 4], s: f64, length: f64| -> Vec<Vec<f64>> {
        let l = [1.0, 1.0, length, length];
        (0..4).map(|i| (0..4).map(|j| m[i][j] * s * l[i] * l[j]).collect()).collect()
    };
    let nondim = c.dimensionless(a.load);
    MomentCoefficientsResult {
        coordinates: ["x", "y", "tilt_x", "tilt_y"].iter().map(|s| s.to_string()).collect(),
        stiffness: d.map(|d| scaled(&c.stiffness, d.load_scale() / d.clearance, d.length)),
        damping: d.map(|d| scaled(&c.damping, d.load_scale() / (d.clearance * d.omega), d.length)),
        stiffness_dimensionless: nondim.map(|(k, _)| scaled(&k, 1.0, 1.0)),
        damping_dimensionless: nondim.map(|(_, cc)| scaled(&cc, 1.0, 1.0)),
        convergence: c.convergence.clone(),
    }
}

/// The operating-limit checks of a result (needs its SI values).
fn checks(spec: &BearingSpec, r: &BearingResult, lim: &BearingLimitsSpec) -> Option<BearingChecks> {
    let g = &spec.geometry;
    let (radius, length) = (g.radius?, g.length?);
    let lower = |value: f64, limit: f64| BearingCheck { value, limit, pass: value >= limit, margin: if limit > 0.0 { (value - limit) / limit } else { 0.0 } };
    let upper = |value: f64, limit: f64| BearingCheck { value, limit, pass: value <= limit, margin: (limit - value) / limit };
    let min_film = lower(r.min_film?, lim.journal_roughness + lim.bearing_roughness + lim.film_allowance);
    let specific_load = upper(r.load.force? / (2.0 * radius * length), lim.max_specific_load);
    let max_temperature = r.thermal.as_ref().map(|t| upper(t.max_temperature, lim.max_temperature));
    let pass = min_film.pass && specific_load.pass && max_temperature.is_none_or(|c| c.pass);
    Some(BearingChecks { min_film, specific_load, max_temperature, pass })
}

/// The spec path of a journal-bearing solver input field (`physics::journal`).
pub fn bearing_spec_path(field: &str) -> Option<String> {
    let path = match field {
        "Bearing.length_to_diameter" => "/geometry/length_to_diameter",
        "Bearing.profile" => "/profile",
        "Settings.grid" => "/grid",
        "Settings.tolerances" => "/solver",
        "Operating.eccentricity" => "/load/eccentricity_ratio",
        "Operating.load" => "/load",
        "Lubricant" | "Lubricant.viscosity_curve" => "/thermal/lubricant",
        "Lubricant.iso_vg" => "/thermal/lubricant/iso_vg",
        _ => return None,
    };
    Some(path.to_string())
}
