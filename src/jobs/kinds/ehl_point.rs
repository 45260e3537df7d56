//! `ehl_point`: one lubricated line contact solved numerically (`physics::ehl`): film, pressure
//! spike, traction, and on request the pressure and film profiles.

use crate::jobs::cost::{self, Cost};
use crate::jobs::quantity as Q;
use crate::jobs::kind::{Kind, Limits, OutputInfo, Validation};
use crate::physics::contact::effective_modulus;
use crate::physics::ehl::formulas::{
    moes_central_film, pan_hamrock_central_film, pan_hamrock_minimum_film, Groups,
};
use crate::physics::ehl::thermal::{self, FilmHeat, ThermalBodies, ThermalInput, ThermalOptions};
use crate::physics::ehl::thermal_finite;
use crate::physics::ehl::{solve, EhlInput, EhlOptions, Rheology, Upwind};
use super::common::{ExtrapolationSpec, LubricantSpec, Material, ThermalSpec};
use crate::physics::ehl::twod::{self, Ehl2dInput, Ehl2dOptions, Geometry2d};
use crate::physics::ehl::ReusableSolver;
use crate::physics::geometry::Crown;
use super::cam_cycle::CrownProfileSpec;
use crate::physics::{Convergence, Observer, SolveError};
use serde::{Deserialize, Serialize};
use serde_json::{json, Value};
use utoipa::ToSchema;

pub struct EhlPoint;

/// Shear law for the traction (the film itself is Newtonian and isothermal).
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct EhlRheologySpec {
    /// Eyring stress τ0, Pa (seed 001 eq. 25; seed 001 Table 1 uses 5e6). Absent: Newtonian.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub eyring_stress: Option<f64>,
    /// Limiting shear stress pressure coefficient Λ (`τ_L = τ_L0 + Λ p`). Absent: no limit.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub limiting_shear_coefficient: Option<f64>,
    /// Limiting shear stress at ambient pressure τ_L0, Pa. Default 0.
    #[serde(default)]
    pub limiting_shear_stress: f64,
}

/// Optional outputs of an `ehl_point` job.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, ToSchema)]
#[serde(rename_all = "snake_case")]
pub enum EhlPointOutput {
    /// Pressure and film along the rolling direction.
    Profile,
}

/// Contact geometry of an `ehl_point` job (issue 16). `line` (default): the contact is uniform
/// along `length` (1-D solver, Richardson extrapolation); `point` and `finite`: the 2-D solver
/// (`physics::ehl::twod`, Newtonian, one grid), isothermal or with `thermal` the thermal
/// finite-line / point model (`physics::ehl::thermal_finite`, issue 43).
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize, ToSchema)]
#[serde(tag = "type", rename_all = "snake_case", deny_unknown_fields)]
pub enum EhlGeometrySpec {
    /// Infinitely long line contact (the load spread uniformly over `length`).
    #[default]
    Line,
    /// Elliptic point contact (spherical or barrel follower); `reduced_radius` and `length` are
    /// not used.
    Point {
        /// Reduced radius along the entrainment `1/R_x = 1/r_1x + 1/r_2x`, m.
        rx: f64,
        /// Reduced radius across the entrainment, m (`rx = ry`: circular contact).
        ry: f64,
        /// Nodes along the entrainment. Default 65.
        #[serde(default = "d_nx")]
        nx: usize,
        /// Nodes across. Default 65.
        #[serde(default = "d_nx")]
        ny: usize,
    },
    /// Finite-length roller of `length` and reduced radius `reduced_radius` with seed 000's
    /// crowned profile (eq. 3, Table 1): straight middle, crown drop, end radius.
    Finite {
        /// Length of the straight middle section L1, m (`≤ length`).
        middle_length: f64,
        /// Crown drop h_td at the ends of the middle section, m.
        crown_height: f64,
        /// End profile radius R_d, m.
        end_radius: f64,
        /// `convex` (default) or `seed000_eq3` (eq. 3 as printed: the centre relieved by
        /// `crown_height`, the roller touching first at `±middle_length/2`); see the cam kinds'
        /// `crown.profile`.
        #[serde(default, skip_serializing_if = "CrownProfileSpec::is_convex")]
        profile: CrownProfileSpec,
        /// Nodes along the entrainment. Default 65.
        #[serde(default = "d_nx")]
        nx: usize,
        /// Nodes along the roller axis. Default 129.
        #[serde(default = "d_ny_finite")]
        ny: usize,
    },
}

fn d_nx() -> usize {
    65
}
fn d_ny_finite() -> usize {
    129
}

/// Spec of an `ehl_point` job: a smooth, fully flooded contact in steady state — a line contact,
/// isothermal or thermal (`thermal`), or (`geometry`) an isothermal point or finite-length one.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct EhlPointSpec {
    /// Normal load, N.
    pub load: f64,
    /// Contact length, m (the load is spread uniformly along it).
    pub length: f64,
    /// Reduced radius of curvature in the rolling direction `1/R = 1/r1 + 1/r2`, m.
    pub reduced_radius: f64,
    /// Entrainment (mean rolling) velocity `(u1 + u2)/2`, m/s; its sign sets the inlet side.
    pub entrainment_velocity: f64,
    /// Sliding velocity `u1 − u2`, m/s (traction only). Default 0.
    #[serde(default)]
    pub sliding_velocity: f64,
    #[serde(default)]
    pub body_1: Material,
    #[serde(default)]
    pub body_2: Material,
    /// The oil, as for the cam kinds; its `temperature` is the film temperature of the isothermal
    /// model and the inlet temperature of the thermal one. Absent: the seed 000 oil (η0 = 0.152 Pa·s,
    /// α = 2.2e-8 1/Pa, β = 0.042 1/K, T0 = 303 K, ρ0 = 870 kg/m³, Roelands, Dowson–Higginson).
    #[serde(default = "LubricantSpec::seed000")]
    pub lubricant: LubricantSpec,
    #[serde(default)]
    pub rheology: EhlRheologySpec,
    /// `{"type": "line"}` (default), `{"type": "point", "rx", "ry"}` or `{"type": "finite",
    /// "middle_length", "crown_height", "end_radius"}`, each 2-D one with optional `nx`, `ny`.
    #[serde(default)]
    pub geometry: EhlGeometrySpec,
    /// Grid nodes across the domain (graded towards inlet and exit); with Richardson
    /// extrapolation the fine grid. Default 385: with the default extrapolation the central film
    /// is within 0.1 % and the minimum film within 0.6 % of the grid-converged solution over
    /// Moes M = 5–200, L = 5–15 (Barus and Roelands), and the exit spike is found, at the cost of
    /// one 512-node solve (BENCHMARKS.md, "One contact point: the defaults").
    #[serde(default = "d_nodes")]
    pub nodes: usize,
    /// `richardson` (default): solve on `nodes` and `(nodes − 1)/2 + 1` nodes of one grid layout
    /// (two threads) and extrapolate the second-order discretisation error out of the central,
    /// minimum and exit films and the traction (pressures, spike and profile are the fine
    /// grid's); `none`: one grid of `nodes`. The thermal model always runs on one grid.
    #[serde(default)]
    pub extrapolation: ExtrapolationSpec,
    /// Residual tolerance (relative). Default 1e-8.
    #[serde(default = "d_tol")]
    pub tolerance: f64,
    /// Most Newton steps per stage. Default 60.
    #[serde(default = "d_iter")]
    pub max_iterations: u32,
    /// Optional outputs: `profile`.
    #[serde(default)]
    pub outputs: Vec<EhlPointOutput>,
    /// The thermal model (seed 000 eq. 2, 4–5, 7–9: generalized Reynolds, film and solid energy
    /// equations, traction from the sheared film). Absent: isothermal at the lubricant's
    /// `temperature`; present, that temperature is the inlet (ambient) temperature `T0`. With a
    /// `point` or `finite` geometry the 2-D thermal model: the energy equations at each row of the
    /// grid across the roller, coupled to the 2-D Reynolds equation (result `thermal_finite`);
    /// the traction law is `rheology` (Newtonian without an Eyring stress, as seed 000).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub thermal: Option<EhlPointThermalSpec>,
}

/// Thermal model of an `ehl_point` (see `physics::ehl::thermal`).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct EhlPointThermalSpec {
    /// Oil conductivity k_f, W/(m·K). Default 0.14 (seed 000 Table 1).
    #[serde(default = "d_kf")]
    pub oil_conductivity: f64,
    /// Oil specific heat c_f, J/(kg·K). Default 1700 (seed 000 Table 1).
    #[serde(default = "d_cf")]
    pub oil_specific_heat: f64,
    /// Body 1 (surface z = 0, moving at `u_m + u_s/2`). Default: steel.
    #[serde(default)]
    pub body_1: ThermalSpec,
    /// Body 2 (surface z = h, moving at `u_m − u_s/2`). Default: steel.
    #[serde(default)]
    pub body_2: ThermalSpec,
    /// Temperature levels across the film, 3–41. Default 7 (traction within 1.5 % of 11 levels).
    #[serde(default = "d_film_points")]
    pub film_points: usize,
    /// Nodes in each solid from the surface to the depth 3.15 b, 4–81. Default 16.
    #[serde(default = "d_solid_points")]
    pub solid_points: usize,
}

fn d_kf() -> f64 {
    0.14
}
fn d_cf() -> f64 {
    1700.0
}
fn d_film_points() -> usize {
    7
}
fn d_solid_points() -> usize {
    16
}

/// Temperatures and heat flows of a thermal solution.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, ToSchema)]
pub struct ThermalResult {
    /// Largest film temperature, K.
    pub film_temperature_max: f64,
    /// Largest surface temperature of body 1 and body 2, K.
    pub surface_temperature_max_1: f64,
    /// Largest surface temperature of body 2, K.
    pub surface_temperature_max_2: f64,
    /// Film temperature averaged across the film and weighted by pressure along it, K.
    pub film_temperature_mean: f64,
    /// Heat generated in the film (shear and compression) per unit length, W/m.
    pub heat_generated: f64,
    /// Heat into body 1 per unit length, W/m.
    pub heat_to_body_1: f64,
    /// Heat into body 2 per unit length, W/m.
    pub heat_to_body_2: f64,
    /// Heat carried away by the oil per unit length, W/m.
    pub heat_convected: f64,
    /// |generated − removed| / generated.
    pub energy_balance_error: f64,
    /// Central film of the isothermal solution at the inlet temperature, m (for the thermal
    /// reduction `central_film / isothermal_central_film`).
    pub isothermal_central_film: f64,
    /// Coupling iterations (energy ↔ Reynolds) and the last relative change.
    #[schema(value_type = crate::jobs::schemas::ConvergenceDoc)]
    pub convergence: Convergence,
}

fn d_nodes() -> usize {
    385
}
fn d_tol() -> f64 {
    1e-8
}
fn d_iter() -> u32 {
    60
}

/// One row of the 2-D thermal solution (a section across the entrainment at `y`).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, ToSchema)]
pub struct ThermalRowResult {
    /// Position of the row along the roller axis (across the entrainment), m from the centre.
    pub y: f64,
    /// Largest film temperature of the row, K.
    pub film_temperature_max: f64,
    /// Film at the contact centre line `x = 0` in this row, m.
    pub central_film: f64,
    /// Smallest film of the row, m.
    pub min_film: f64,
    /// Largest pressure of the row, Pa.
    pub max_pressure: f64,
    /// Sliding friction coefficient of the row alone (its shear forces over its load), signed
    /// like the sliding velocity.
    pub friction_coefficient: f64,
}

/// Temperatures, heat flows and traction of the 2-D thermal model (whole contact).
#[derive(Debug, Clone, PartialEq, Serialize, ToSchema)]
pub struct ThermalFiniteResult {
    /// Largest film temperature, K.
    pub film_temperature_max: f64,
    /// Where it is along the entrainment, m from the centre.
    pub film_temperature_max_position: f64,
    /// Where it is along the roller axis, m from the centre.
    pub film_temperature_max_axial_position: f64,
    /// Largest surface temperature of body 1, K.
    pub surface_temperature_max_1: f64,
    /// Largest surface temperature of body 2, K.
    pub surface_temperature_max_2: f64,
    /// Heat generated in the film (shear and compression), W.
    pub heat_generated: f64,
    /// Heat into body 1, W.
    pub heat_to_body_1: f64,
    /// Heat into body 2, W.
    pub heat_to_body_2: f64,
    /// Heat carried out of the contact by the oil along the entrainment, W.
    pub heat_convected: f64,
    /// Heat carried out sideways by the oil each row loses to its neighbours, W.
    pub heat_side: f64,
    /// |generated − removed| / generated.
    pub energy_balance_error: f64,
    /// Shear force on body 1 along +x, N.
    pub traction_force_body_1: f64,
    /// Shear force on body 2 along +x, N.
    pub traction_force_body_2: f64,
    /// Central film of the isothermal solution at the inlet temperature, m.
    pub isothermal_central_film: f64,
    /// Smallest film of the isothermal solution, m.
    pub isothermal_min_film: f64,
    /// The row through the contact centre (`y = 0`).
    pub mid_plane: ThermalRowResult,
    /// Finite roller: the row at the crown's start (`y = middle_length/2`), where the crown
    /// relieves the load.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub crown_edge: Option<ThermalRowResult>,
    /// Coupling iterations (row energies ↔ 2-D Reynolds) and the last relative change.
    #[schema(value_type = crate::jobs::schemas::ConvergenceDoc)]
    pub convergence: Convergence,
}

/// Pressure and film along the rolling direction.
#[derive(Debug, Clone, PartialEq, Serialize, ToSchema)]
pub struct ProfileTable {
    /// Position from the contact centre, m (positive in the direction of positive entrainment).
    pub x: Vec<f64>,
    /// Pressure, Pa.
    pub pressure: Vec<f64>,
    /// Film thickness, m.
    pub film: Vec<f64>,
}

/// The exit pressure spike.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, ToSchema)]
pub struct SpikeResult {
    /// Pa.
    pub pressure: f64,
    /// m from the contact centre.
    pub position: f64,
}

/// Closed-form films for comparison (the `fast` fidelity).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, ToSchema)]
pub struct ClosedForms {
    /// Moes central film (fits Barus, incompressible solutions), m.
    pub moes_central_film: f64,
    /// Pan–Hamrock central film, m.
    pub pan_hamrock_central_film: f64,
    /// Pan–Hamrock minimum film, m.
    pub pan_hamrock_min_film: f64,
}

/// Result of an `ehl_point` job.
#[derive(Debug, Clone, PartialEq, Serialize, ToSchema)]
pub struct EhlPointResult {
    /// `E' = 2E*`, Pa.
    pub effective_modulus: f64,
    /// Load per unit length, N/m (absent for a point contact).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub load_per_length: Option<f64>,
    /// Hertzian half-width (2-D: the semi-axis along the entrainment, for a finite roller at the
    /// peak load per length of the slice model), m.
    pub hertz_half_width: f64,
    /// Hertzian peak pressure, Pa.
    pub hertz_pressure: f64,
    /// Moes load parameter M (sum-velocity convention).
    pub moes_m: f64,
    /// Moes material parameter L.
    pub moes_l: f64,
    /// Film at the contact centre, m.
    pub central_film: f64,
    /// Smallest film, m.
    pub min_film: f64,
    /// Where the smallest film is, m from the centre along the entrainment.
    pub min_film_position: f64,
    /// 2-D: where the smallest film is across the entrainment (along the roller axis), m from the
    /// centre.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub min_film_axial_position: Option<f64>,
    /// Smallest film downstream of the centre (exit constriction), m (line contacts).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub exit_film: Option<f64>,
    /// Largest pressure, Pa.
    pub max_pressure: f64,
    /// Where the largest pressure is, m.
    pub max_pressure_position: f64,
    /// 2-D: where the largest pressure is across the entrainment, m from the centre.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub max_pressure_axial_position: Option<f64>,
    /// Finite roller: the largest off-centre maximum along the roller axis of the pressure
    /// (`max_x p(x, y)` against `y`), Pa — the edge peak at the crown transition; absent when the
    /// pressure falls monotonically from the centre to the ends, and for other geometries.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub edge_pressure_peak: Option<f64>,
    /// Where the edge peak is along the roller axis, m from the centre (positive side).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub edge_pressure_peak_axial_position: Option<f64>,
    /// The exit pressure spike; absent when the solution has none.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub pressure_spike: Option<SpikeResult>,
    /// Sliding friction coefficient `(F2 − F1)/(2w')`, signed like the sliding velocity (line
    /// contacts; 2-D with `thermal`: `(F2 − F1)/(2F)` of the forces over the whole contact).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub friction_coefficient: Option<f64>,
    /// Shear force on body 1 along +x, N/m (line contacts).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub traction_body_1: Option<f64>,
    /// Shear force on body 2 along +x, N/m (line contacts).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub traction_body_2: Option<f64>,
    /// Rolling (Poiseuille) resistance on each body, N/m (line contacts).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub rolling_force: Option<f64>,
    /// Line-contact closed forms (line contacts).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub closed_forms: Option<ClosedForms>,
    /// Grid nodes used (the fine grid when extrapolated; 2-D: along the entrainment).
    pub nodes: usize,
    /// 2-D: grid nodes across the entrainment.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub nodes_across: Option<usize>,
    /// Whether the films and traction are Richardson-extrapolated from two grids (`false` with
    /// `extrapolation: none`, with the thermal model, or when the coarse grid did not converge).
    pub extrapolated: bool,
    /// Newton steps (all grid levels) and the final relative residual.
    #[schema(value_type = crate::jobs::schemas::ConvergenceDoc)]
    pub convergence: Convergence,
    /// Pressure and film along the rolling direction (2-D: along the centre line `y = 0`).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub profile: Option<ProfileTable>,
    /// The thermal solution's temperatures and heat flows, when `thermal` was requested (the
    /// films, pressures and traction above are then the thermal ones).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub thermal: Option<ThermalResult>,
    /// Largest film temperature of the thermal model, K (with `thermal`; also in `thermal` or
    /// `thermal_finite`).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub film_temperature_max: Option<f64>,
    /// The 2-D thermal model's temperatures, heat flows and traction (`thermal` with a `point` or
    /// `finite` geometry).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub thermal_finite: Option<ThermalFiniteResult>,
}

impl Kind for EhlPoint {
    const NAME: &'static str = "ehl_point";
    const SOLVER_VERSION: &'static str = "ehl_point-13";
    const DESCRIPTION: &'static str = "Numerical elastohydrodynamic line contact (compressible \
        Reynolds, elastic half-space, cavitation; isothermal or, with `thermal`, the thermal model \
        of seed 000), or with `geometry` a point or finite-length (crowned roller) contact on a 2-D \
        grid, isothermal or with `thermal` the thermal finite-line model: central and minimum film, pressure spike, edge pressure peak, \
        traction, temperatures, optional pressure/film profile.";
    const TABLES: &'static [&'static str] = &["profile"];
    const KEY_FIGURES: &'static [&'static str] = &["/central_film", "/min_film", "/max_pressure", "/pressure_spike/pressure", "/edge_pressure_peak", "/friction_coefficient", "/thermal/film_temperature_max"];
    type Spec = EhlPointSpec;
    type Output = EhlPointResult;

    fn example() -> Value {
        // Seed 001 nose position: F = 12.5 kN over 21 mm, R = 10.5 mm, u = 3.98 m/s.
        json!({
            "load": 12500.0,
            "length": 0.021,
            "reduced_radius": 0.0105,
            "entrainment_velocity": 3.98,
            "sliding_velocity": 0.04,
            "body_1": {"youngs_modulus": 200e9, "poisson_ratio": 0.3},
            "body_2": {"youngs_modulus": 200e9, "poisson_ratio": 0.3},
            "lubricant": {"viscosity": 0.013, "pressure_viscosity": 1.84e-8},
            "rheology": {"eyring_stress": 5e6},
            "outputs": ["profile"]
        })
    }

    fn outputs() -> &'static [OutputInfo] {
        &[OutputInfo { name: "profile", description: "pressure and film thickness along the rolling direction" }]
    }

    fn validate(spec: &EhlPointSpec, limits: &Limits, v: &mut Validation) {
        v.quantity("/load", spec.load, Q::FORCE);
        v.quantity("/length", spec.length, Q::LENGTH);
        v.quantity("/reduced_radius", spec.reduced_radius, Q::RADIUS);
        v.quantity("/entrainment_velocity", spec.entrainment_velocity, Q::VELOCITY);
        v.check(spec.entrainment_velocity.is_finite() && spec.entrainment_velocity.abs() >= 1e-6,
            "/entrainment_velocity", "must be at least 1e-6 m/s in magnitude (a steady film needs entrainment)");
        v.quantity("/sliding_velocity", spec.sliding_velocity, Q::VELOCITY);
        spec.body_1.validate("/body_1", v);
        spec.body_2.validate("/body_2", v);
        spec.lubricant.validate("/lubricant", v);
        if let Some(t0) = spec.rheology.eyring_stress {
            v.quantity("/rheology/eyring_stress", t0, Q::STRESS);
        }
        if let Some(c) = spec.rheology.limiting_shear_coefficient {
            v.in_range("/rheology/limiting_shear_coefficient", c, 0.0, 1.0);
        }
        v.quantity("/rheology/limiting_shear_stress", spec.rheology.limiting_shear_stress, Q::STRESS.from(0.0));
        v.count_in_range("/nodes", spec.nodes, 32, 4096);
        v.limit("/nodes", spec.nodes, limits.max_grid_nodes, "the number of grid nodes");
        v.in_range("/tolerance", spec.tolerance, 1e-14, 1e-2);
        v.count_in_range("/max_iterations", spec.max_iterations as usize, 1, 1000);
        let two_d = |nx: usize, ny: usize, v: &mut Validation| {
            v.count_in_range("/geometry/nx", nx, 17, 1025);
            v.count_in_range("/geometry/ny", ny, 17, 1025);
            v.limit("/geometry/nx", nx.saturating_mul(ny), limits.max_grid_nodes, "the number of grid nodes (nx·ny)");
        };
        match spec.geometry {
            EhlGeometrySpec::Line => {}
            EhlGeometrySpec::Point { rx, ry, nx, ny } => {
                v.quantity("/geometry/rx", rx, Q::RADIUS);
                v.quantity("/geometry/ry", ry, Q::RADIUS);
                if rx > 0.0 && ry > 0.0 {
                    v.in_range("/geometry/ry", rx / ry, 0.02, 50.0);
                }
                two_d(nx, ny, v);
            }
            EhlGeometrySpec::Finite { middle_length, crown_height, end_radius, nx, ny, .. } => {
                v.check(middle_length > 0.0 && middle_length <= spec.length, "/geometry/middle_length", "must be in (0, length]");
                v.in_range("/geometry/crown_height", crown_height, 0.0, 1e-3);
                v.quantity("/geometry/end_radius", end_radius, Q::RADIUS);
                two_d(nx, ny, v);
            }
        }
        if let Some(t) = &spec.thermal {
            v.quantity("/thermal/oil_conductivity", t.oil_conductivity, Q::CONDUCTIVITY);
            v.quantity("/thermal/oil_specific_heat", t.oil_specific_heat, Q::SPECIFIC_HEAT);
            for (path, b) in [("/thermal/body_1", &t.body_1), ("/thermal/body_2", &t.body_2)] {
                v.quantity(&format!("{path}/conductivity"), b.conductivity, Q::CONDUCTIVITY);
                v.quantity(&format!("{path}/density"), b.density, Q::DENSITY);
                v.quantity(&format!("{path}/specific_heat"), b.specific_heat, Q::SPECIFIC_HEAT);
            }
            v.count_in_range("/thermal/film_points", t.film_points, 3, 41);
            v.count_in_range("/thermal/solid_points", t.solid_points, 4, 81);
        }
    }

    fn cost(spec: &EhlPointSpec) -> Cost {
        match spec.geometry {
            EhlGeometrySpec::Point { nx, ny, .. } | EhlGeometrySpec::Finite { nx, ny, .. } => {
                let what = format!("the 2-D EHL solver on {nx}×{ny} nodes");
                let thermal = spec.thermal.as_ref().map_or(0.0, |t| cost::ehl_thermal_2d_seconds(nx, ny, t.film_points, t.solid_points));
                Cost::new(cost::JOB_OVERHEAD_S + cost::ehl_2d_seconds(nx, ny) + thermal, cost::ehl_2d_bytes(nx, ny))
                    .work_at("/geometry/nx", what.clone())
                    .memory_at("/geometry/nx", what)
            }
            EhlGeometrySpec::Line => {
                let n = spec.nodes;
                let richardson = spec.extrapolation == ExtrapolationSpec::Richardson;
                let (seconds, what) = match &spec.thermal {
                    // The thermal solve starts from the isothermal one.
                    Some(t) => (
                        cost::ehl_line_seconds(n, false) + cost::ehl_thermal_seconds(n, t.film_points, t.solid_points),
                        format!("the thermal EHL solver on {n} nodes"),
                    ),
                    None => (cost::ehl_line_seconds(n, richardson), format!("the dense EHL solver on {n} nodes")),
                };
                let bytes = cost::ehl_line_bytes(n);
                Cost::new(cost::JOB_OVERHEAD_S + seconds, bytes).work_at("/nodes", what.clone()).memory_at("/nodes", what)
            }
        }
    }

    fn solve(spec: &EhlPointSpec, observer: &dyn Observer) -> Result<EhlPointResult, SolveError> {
        solve_point(spec, observer).map_err(|e| e.in_spec(spec_path))
    }
}

/// The spec path of an EHL solver input field.
fn spec_path(field: &str) -> Option<String> {
    let path = match field {
        "EhlOptions.nodes" => "/nodes",
        "EhlOptions.tolerance" => "/tolerance",
        "EhlInput.entrainment_velocity" => "/entrainment_velocity",
        "EhlInput.sliding_velocity" => "/sliding_velocity",
        "EhlInput.temperature" => "/lubricant/temperature",
        "Ehl2dOptions.nx" => "/geometry/nx",
        "Ehl2dOptions.ny" => "/geometry/ny",
        "Ehl2dOptions.tolerance" => "/tolerance",
        "Ehl2dInput.entrainment_velocity" => "/entrainment_velocity",
        "Ehl2dInput.temperature" => "/lubricant/temperature",
        "Ehl2dInput.geometry" | "Ehl2dInput.geometry.rx" => "/geometry",
        _ if field.starts_with("Ehl2dInput.lubricant.") => return field.strip_prefix("Ehl2dInput.lubricant.").map(|f| format!("/lubricant/{f}")),
        _ => return field.strip_prefix("EhlInput.lubricant.").map(|f| format!("/lubricant/{f}")),
    };
    Some(path.to_string())
}

/// A point or finite-length contact by the 2-D solver.
fn solve_2d(spec: &EhlPointSpec, observer: &dyn Observer) -> Result<EhlPointResult, SolveError> {
    let ep = effective_modulus(spec.body_1.elastic(), spec.body_2.elastic());
    let lubricant = spec.lubricant.to_physics();
    let temperature = spec.lubricant.inlet_temperature();
    let (geometry, nx, ny) = match spec.geometry {
        EhlGeometrySpec::Point { rx, ry, nx, ny } => (Geometry2d::Point { rx, ry }, nx, ny),
        EhlGeometrySpec::Finite { middle_length, crown_height, end_radius, profile, nx, ny } => {
            let crown = Crown { length: spec.length, middle_length, crown_height, end_radius, profile: profile.into() };
            (Geometry2d::Finite { rx: spec.reduced_radius, crown }, nx, ny)
        }
        EhlGeometrySpec::Line => unreachable!("line contacts take the 1-D solver"),
    };
    let input = Ehl2dInput { load: spec.load, geometry, effective_modulus: ep, entrainment_velocity: spec.entrainment_velocity, lubricant, temperature };
    let profile = spec.outputs.contains(&EhlPointOutput::Profile);
    let options = Ehl2dOptions { nx, ny, tolerance: spec.tolerance, max_iterations: spec.max_iterations, fields: profile, ..Ehl2dOptions::default() };
    // Progress moves with the solver's checks (Newton steps, Krylov restarts, grid levels).
    let stage = crate::physics::Stage::new(observer, 0.0, 0.95, 60.0, "2-D film");
    let (s, thermal_finite, friction) = match &spec.thermal {
        None => (twod::solve(&input, &options, &stage)?, None, None),
        Some(t) => {
            let th = solve_thermal_2d(spec, t, input, &options, &stage)?;
            let mu = th.traction.friction_coefficient;
            let result = thermal_finite_result(spec, &th);
            (th.ehl, Some(result), Some(mu))
        }
    };
    let profile = s.fields.as_ref().map(|f| {
        // The row nearest the centre line y = 0.
        let j = (0..f.y.len()).min_by(|&a, &b| f.y[a].abs().total_cmp(&f.y[b].abs())).unwrap_or(0);
        let n = f.x.len();
        ProfileTable { x: f.x.clone(), pressure: f.pressure[j * n..(j + 1) * n].to_vec(), film: f.film[j * n..(j + 1) * n].to_vec() }
    });
    let finite = matches!(spec.geometry, EhlGeometrySpec::Finite { .. });
    Ok(EhlPointResult {
        effective_modulus: ep,
        load_per_length: finite.then(|| spec.load / spec.length),
        hertz_half_width: s.hertz_half_width,
        hertz_pressure: s.hertz_pressure,
        moes_m: s.moes_m,
        moes_l: s.moes_l,
        central_film: s.central_film,
        min_film: s.min_film.value,
        min_film_position: s.min_film.x,
        min_film_axial_position: Some(s.min_film.y),
        exit_film: None,
        max_pressure: s.max_pressure.value,
        max_pressure_position: s.max_pressure.x,
        max_pressure_axial_position: Some(s.max_pressure.y),
        edge_pressure_peak: s.edge_pressure_peak.map(|e| e.value),
        edge_pressure_peak_axial_position: s.edge_pressure_peak.map(|e| e.y.abs()),
        pressure_spike: None,
        friction_coefficient: friction,
        traction_body_1: None,
        traction_body_2: None,
        rolling_force: None,
        closed_forms: None,
        nodes: s.nx,
        nodes_across: Some(s.ny),
        extrapolated: false,
        convergence: s.convergence,
        profile,
        thermal: None,
        film_temperature_max: thermal_finite.as_ref().map(|t| t.film_temperature_max),
        thermal_finite,
    })
}

/// The thermal finite-line / point model of a 2-D `ehl_point` (`physics::ehl::thermal_finite`).
fn solve_thermal_2d(spec: &EhlPointSpec, t: &EhlPointThermalSpec, input: Ehl2dInput, options: &Ehl2dOptions, observer: &dyn Observer) -> Result<thermal_finite::ThermalFiniteSolution, SolveError> {
    let bodies = ThermalBodies {
        film: FilmHeat { conductivity: t.oil_conductivity, specific_heat: t.oil_specific_heat },
        body_1: t.body_1.to_physics(),
        body_2: t.body_2.to_physics(),
    };
    let rheology = Rheology {
        eyring_stress: spec.rheology.eyring_stress,
        limiting_shear_coefficient: spec.rheology.limiting_shear_coefficient,
        limiting_shear_stress: spec.rheology.limiting_shear_stress,
    };
    let tin = thermal_finite::ThermalFiniteInput { ehl: input, sliding_velocity: spec.sliding_velocity, rheology, bodies };
    let topts = ThermalOptions { film_points: t.film_points, solid_points: t.solid_points, ..ThermalOptions::default() };
    thermal_finite::solve(&tin, options, &topts, observer)
}

/// The result part of a 2-D thermal solution.
fn thermal_finite_result(spec: &EhlPointSpec, th: &thermal_finite::ThermalFiniteSolution) -> ThermalFiniteResult {
    let row = |r: &thermal_finite::RowThermal| ThermalRowResult {
        y: r.y,
        film_temperature_max: r.summary.film_temperature_max,
        central_film: r.central_film,
        min_film: r.min_film,
        max_pressure: r.max_pressure,
        friction_coefficient: r.traction.friction_coefficient,
    };
    let t0 = spec.lubricant.inlet_temperature();
    let unsolved = |y: f64| ThermalRowResult { y, film_temperature_max: t0, central_film: 0.0, min_film: 0.0, max_pressure: 0.0, friction_coefficient: 0.0 };
    let crown_edge = match spec.geometry {
        EhlGeometrySpec::Finite { middle_length, .. } => Some(th.row_near(0.5 * middle_length).map_or(unsolved(0.5 * middle_length), row)),
        _ => None,
    };
    ThermalFiniteResult {
        film_temperature_max: th.film_temperature_max.value,
        film_temperature_max_position: th.film_temperature_max.x,
        film_temperature_max_axial_position: th.film_temperature_max.y,
        surface_temperature_max_1: th.surface_temperature_max_1,
        surface_temperature_max_2: th.surface_temperature_max_2,
        heat_generated: th.heat.generated,
        heat_to_body_1: th.heat.to_body_1,
        heat_to_body_2: th.heat.to_body_2,
        heat_convected: th.heat.convected,
        heat_side: th.heat.side,
        energy_balance_error: th.heat.error,
        traction_force_body_1: th.traction.force_body_1,
        traction_force_body_2: th.traction.force_body_2,
        isothermal_central_film: th.isothermal_central_film.unwrap_or(th.ehl.central_film),
        isothermal_min_film: th.isothermal_min_film.unwrap_or(th.ehl.min_film.value),
        mid_plane: th.row_near(0.0).map_or(unsolved(0.0), row),
        crown_edge,
        convergence: th.convergence.clone(),
    }
}

fn solve_point(spec: &EhlPointSpec, observer: &dyn Observer) -> Result<EhlPointResult, SolveError> {
    if spec.geometry != EhlGeometrySpec::Line {
        return solve_2d(spec, observer);
    }
    let ep = effective_modulus(spec.body_1.elastic(), spec.body_2.elastic());
    let lubricant = spec.lubricant.to_physics();
    let temperature = spec.lubricant.inlet_temperature();
    let w = spec.load / spec.length;
    let input = EhlInput {
        load_per_length: w,
        reduced_radius: spec.reduced_radius,
        effective_modulus: ep,
        entrainment_velocity: spec.entrainment_velocity,
        sliding_velocity: spec.sliding_velocity,
        lubricant,
        temperature,
        rheology: Rheology {
            eyring_stress: spec.rheology.eyring_stress,
            limiting_shear_coefficient: spec.rheology.limiting_shear_coefficient,
            limiting_shear_stress: spec.rheology.limiting_shear_stress,
        },
        transient: None,
        warm_start: None,
        asperity: None,
    };
    let options = EhlOptions {
        nodes: spec.nodes,
        tolerance: spec.tolerance,
        max_iterations: spec.max_iterations,
        upwind: Upwind::Second,
        profiles: spec.outputs.contains(&EhlPointOutput::Profile),
        ..EhlOptions::default()
    };
    let (s, thermal, extrapolated) = match &spec.thermal {
        None if spec.extrapolation == ExtrapolationSpec::Richardson => {
            let r = ReusableSolver::new().solve_richardson(&input, None, &options, observer)?;
            let extrapolated = r.coarse_state.is_some();
            (r.solution, None, extrapolated)
        }
        None => (solve(&input, &options, observer)?, None, false),
        Some(t) => {
            let iso = solve(&input, &options, observer)?;
            let bodies = ThermalBodies {
                film: FilmHeat { conductivity: t.oil_conductivity, specific_heat: t.oil_specific_heat },
                body_1: t.body_1.to_physics(),
                body_2: t.body_2.to_physics(),
            };
            let topts = ThermalOptions { film_points: t.film_points, solid_points: t.solid_points, ..ThermalOptions::default() };
            let th = thermal::solve(&ThermalInput { ehl: input, bodies, previous_temperature: None }, &options, &topts, observer)?;
            let m = th.summary;
            let result = ThermalResult {
                film_temperature_max: m.film_temperature_max,
                surface_temperature_max_1: m.surface_temperature_max_1,
                surface_temperature_max_2: m.surface_temperature_max_2,
                film_temperature_mean: m.film_temperature_mean,
                heat_generated: m.heat_generated,
                heat_to_body_1: m.heat_to_body_1,
                heat_to_body_2: m.heat_to_body_2,
                heat_convected: m.heat_convected,
                energy_balance_error: m.energy_balance_error,
                isothermal_central_film: iso.central_film,
                convergence: th.convergence,
            };
            (th.ehl, Some(result), false)
        }
    };
    let g = Groups::of(w, spec.reduced_radius, ep, spec.entrainment_velocity, &lubricant, temperature);
    let r = spec.reduced_radius;
    Ok(EhlPointResult {
        effective_modulus: ep,
        load_per_length: Some(w),
        hertz_half_width: s.hertz_half_width,
        hertz_pressure: s.hertz_pressure,
        moes_m: s.moes_m,
        moes_l: s.moes_l,
        central_film: s.central_film,
        min_film: s.min_film,
        min_film_position: s.min_film_position,
        min_film_axial_position: None,
        exit_film: Some(s.exit_film),
        max_pressure: s.max_pressure,
        max_pressure_position: s.max_pressure_position,
        max_pressure_axial_position: None,
        edge_pressure_peak: None,
        edge_pressure_peak_axial_position: None,
        pressure_spike: s.pressure_spike.map(|p| SpikeResult { pressure: p.pressure, position: p.position }),
        friction_coefficient: Some(s.traction.friction_coefficient),
        traction_body_1: Some(s.traction.force_body_1),
        traction_body_2: Some(s.traction.force_body_2),
        rolling_force: Some(s.traction.rolling_force),
        closed_forms: Some(ClosedForms {
            moes_central_film: moes_central_film(&g, r),
            pan_hamrock_central_film: pan_hamrock_central_film(&g, r),
            pan_hamrock_min_film: pan_hamrock_minimum_film(&g, r),
        }),
        nodes: s.nodes,
        nodes_across: None,
        extrapolated,
        convergence: s.convergence,
        profile: s.profiles.map(|p| ProfileTable { x: p.x, pressure: p.pressure, film: p.film }),
        film_temperature_max: thermal.as_ref().map(|t| t.film_temperature_max),
        thermal,
        thermal_finite: None,
    })
}
