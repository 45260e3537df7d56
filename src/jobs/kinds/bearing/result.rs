//! The `bearing` answer (the types of the OpenAPI document).

use crate::physics::Convergence;
use serde::Serialize;
use utoipa::ToSchema;

/// A location on the bearing surface.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, ToSchema)]
pub struct Location {
    /// Degrees from the unloaded side in the direction of rotation, [0, 360).
    pub angle_deg: f64,
    /// Z = z/L, 0 to 1 (a dimensionless axial position).
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
    /// Z = z/L (a dimensionless axial position).
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
    /// `C_ij = −∂Q_i/∂q̇_j` (with dimensions), in N·s/m in the force–translation block (the units of `stiffness` times s: N·s/rad, N·s and N·m·s/rad in the other blocks).
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
    /// The checked quantity, in its check's unit.
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
