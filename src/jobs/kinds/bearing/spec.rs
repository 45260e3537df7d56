//! The `bearing` request: geometry, operating point, lubricant and heat balance, limits, grid,
//! solver settings and outputs (the types of the OpenAPI document), and the spec's own
//! figures (L/D, whether it has a size and speed).

use crate::physics::journal::Settings;
use serde::{Deserialize, Serialize};
use utoipa::ToSchema;

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
}
