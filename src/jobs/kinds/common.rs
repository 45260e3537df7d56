//! Spec pieces shared by the kinds — the one material type and the one lubricant type, with their
//! defaults — and by the cam kinds (`cam_cycle`, `cam_point`, `wear`): surfaces, traction, film
//! options; and their conversion to `physics` types.

use crate::jobs::quantity as Q;
use crate::jobs::kind::{Limits, Validation};
use crate::jobs::kinds::accuracy::{self, LineFamily};
use crate::physics::contact::Elastic;
use crate::physics::ehl::{EhlOptions, Extrapolation};
use crate::physics::ehl::twod::Ehl2dOptions;
use crate::physics::film::{AccurateSettings, ClosedForm, FilmFormula, FiniteSettings, ThermalFilmSettings};
use crate::physics::thermal::ThermalSolid;
use crate::physics::friction::{AsperityFriction, AsperityModel, Rheology, Roughness, TractionLaw};
use crate::physics::lubricant::{DensityModel, Lubricant, ViscosityModel};
use serde::{Deserialize, Serialize};
use utoipa::ToSchema;

pub use super::thermal_spec::EhlThermalSpec;

/// Elastic constants of one body (every kind: `hertz` bodies, `ehl_point` bodies, the cam and
/// follower of the cam kinds). Default: steel.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct Material {
    /// Young's modulus, Pa. Default 210e9 (steel).
    #[serde(default = "default_e")]
    pub youngs_modulus: f64,
    /// Poisson's ratio. Default 0.3.
    #[serde(default = "default_nu")]
    pub poisson_ratio: f64,
}

fn default_e() -> f64 {
    Elastic::STEEL.youngs_modulus
}
fn default_nu() -> f64 {
    Elastic::STEEL.poisson_ratio
}

impl Default for Material {
    fn default() -> Self {
        Material { youngs_modulus: default_e(), poisson_ratio: default_nu() }
    }
}

impl Material {
    pub fn elastic(&self) -> Elastic {
        Elastic { youngs_modulus: self.youngs_modulus, poisson_ratio: self.poisson_ratio }
    }
    /// E in (0, 1e13] Pa (far above any solid, low enough that nothing overflows); ν in [-1, 0.5).
    pub fn validate(&self, path: &str, v: &mut Validation) {
        let (e, e_path, nu_path) = (self.youngs_modulus, format!("{path}/youngs_modulus"), format!("{path}/poisson_ratio"));
        v.quantity(&e_path, e, Q::MODULUS);
        v.check(self.poisson_ratio.is_finite() && (-1.0..0.5).contains(&self.poisson_ratio), &nu_path, "must be in [-1, 0.5)");
    }
}
fn default_ref_temperature() -> f64 {
    313.0
}
fn default_density() -> f64 {
    870.0
}

/// Lubricant rheology (SI). Viscosity–pressure: Roelands (seed 000 eq. 4) or Barus;
/// density: Dowson–Higginson (seed 000 eq. 5) or incompressible.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct LubricantSpec {
    /// Dynamic viscosity at ambient pressure and `reference_temperature`, Pa·s.
    #[schema(example = 0.152)]
    pub viscosity: f64,
    /// Pressure–viscosity coefficient α (low-pressure slope), 1/Pa.
    #[schema(example = 2.2e-8)]
    pub pressure_viscosity: f64,
    /// Temperature–viscosity coefficient β, 1/K. Default 0.
    #[serde(default)]
    pub temperature_viscosity: f64,
    /// Temperature at which `viscosity` is given, K. Default 313.
    #[serde(default = "default_ref_temperature")]
    pub reference_temperature: f64,
    /// Oil temperature at the contact inlet, K (the film temperature of the isothermal models).
    /// Default: `reference_temperature`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub temperature: Option<f64>,
    /// Density at ambient pressure, kg/m³. Default 870.
    #[serde(default = "default_density")]
    pub density: f64,
    /// `roelands` (default) or `barus`.
    #[serde(default)]
    #[schema(value_type = crate::jobs::schemas::ViscosityModelDoc)]
    pub viscosity_model: ViscosityModel,
    /// `dowson_higginson` (default) or `incompressible`.
    #[serde(default)]
    #[schema(value_type = crate::jobs::schemas::DensityModelDoc)]
    pub density_model: DensityModel,
}

impl LubricantSpec {
    /// The seed 000 oil (η0 = 0.152 Pa·s, α = 2.2e-8 1/Pa, β = 0.042 1/K, T0 = 303 K,
    /// ρ0 = 870 kg/m³, Roelands, Dowson–Higginson): `ehl_point`'s lubricant when none is given.
    pub fn seed000() -> Self {
        let l = Lubricant::SEED000;
        LubricantSpec {
            viscosity: l.viscosity,
            pressure_viscosity: l.pressure_viscosity,
            temperature_viscosity: l.temperature_viscosity,
            reference_temperature: l.reference_temperature,
            temperature: None,
            density: l.density,
            viscosity_model: l.viscosity_model,
            density_model: l.density_model,
        }
    }

    pub fn to_physics(&self) -> Lubricant {
        Lubricant {
            viscosity: self.viscosity,
            pressure_viscosity: self.pressure_viscosity,
            temperature_viscosity: self.temperature_viscosity,
            reference_temperature: self.reference_temperature,
            density: self.density,
            viscosity_model: self.viscosity_model,
            density_model: self.density_model,
        }
    }
    pub fn inlet_temperature(&self) -> f64 {
        self.temperature.unwrap_or(self.reference_temperature)
    }
    pub fn validate(&self, path: &str, v: &mut Validation) {
        v.quantity(&format!("{path}/viscosity"), self.viscosity, Q::VISCOSITY);
        v.in_range(&format!("{path}/pressure_viscosity"), self.pressure_viscosity, 0.0, 1e-7);
        v.check(
            self.pressure_viscosity == 0.0 || self.pressure_viscosity >= 1e-12,
            &format!("{path}/pressure_viscosity"),
            "must be 0 (isoviscous) or between 1e-12 and 1e-7 1/Pa",
        );
        v.in_range(&format!("{path}/temperature_viscosity"), self.temperature_viscosity, 0.0, 1.0);
        v.in_range(&format!("{path}/reference_temperature"), self.reference_temperature, 200.0, 700.0);
        if let Some(t) = self.temperature {
            v.in_range(&format!("{path}/temperature"), t, 200.0, 700.0);
        }
        v.in_range(&format!("{path}/density"), self.density, 100.0, 5000.0);
    }
}

/// Asperity friction law of the rough surfaces.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize, ToSchema)]
#[serde(rename_all = "snake_case")]
pub enum AsperityModelSpec {
    /// Gross sliding: constant boundary friction coefficient (asperities stick at zero sliding).
    #[default]
    Coulomb,
    /// Partial slip of the asperity share by Carter's creep law (gross sliding at creep μ_b b/R).
    Carter,
    /// Seed 001's micro-slip map (eq. 14–23): every point of the contact is displaced by
    /// `δx = SRR (x − x_in)` since the inlet, its asperities stick–slip below the rough surface's
    /// gross-sliding displacement (`gross_sliding_displacement`, or `micro_slip_map` per film)
    /// and slide beyond it; integrated over the contact (no traction jump at zero sliding;
    /// `slip_regime` is `gross_sliding` from 99 % of the limiting asperity traction). Fidelity
    /// `accurate` integrates over the solved asperity pressure node by node, each node with its
    /// own film (`x_in` where the asperity pressure first reaches 1e-3 of its peak); the closed
    /// forms over a semi-elliptic pressure on the Hertz width (`x_in = −a`) at the central film.
    MicroSlip,
}

fn default_ebs() -> f64 {
    0.04
}
fn default_sob() -> f64 {
    0.001
}
fn default_mub() -> f64 {
    0.1
}
fn default_micro_slip_exponent() -> f64 {
    3.0
}
fn is_default_micro_slip_exponent(n: &f64) -> bool {
    *n == default_micro_slip_exponent()
}

/// Asperity contact: its pressure–gap relation (Greenwood–Tripp statistics, or a tabulated
/// curve), plastic limit and friction. The composite roughness is `σ = sqrt(σ_cam² +
/// σ_follower²)` from the bodies' `roughness_rq`; with σ > 0 the asperities share the load inside
/// the film solution (mixed lubrication, seed 001 eq. 1, 7, 12: `film_model` ends in `_mixed`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct AsperitySpec {
    /// Roughness parameter ηβσ (summit density × summit radius × σ), dimensionless. Default 0.04.
    #[serde(default = "default_ebs")]
    pub eta_beta_sigma: f64,
    /// Summit slope parameter σ/β, a ratio. Default 0.001.
    #[serde(default = "default_sob")]
    pub sigma_over_beta: f64,
    /// Boundary (asperity) friction coefficient μ_b. Default 0.1.
    #[serde(default = "default_mub")]
    pub boundary_friction: f64,
    /// `coulomb` (default), `carter` or `micro_slip`.
    #[serde(default)]
    pub model: AsperityModelSpec,
    /// Gross-sliding displacement δx_gs of the asperity contact, m (seed 001 eq. 19–21: the
    /// tangential rigid-body displacement at which the whole real contact area slides; a
    /// `rough_contact` job with `friction_limit` reports it per film). Required by `micro_slip`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub gross_sliding_displacement: Option<f64>,
    /// Exponent n of `micro_slip`'s local shape `μ_a/μ_lim = 1 − (1 − δx/δx_gs)^n`, 2–8
    /// (2 is Carter's 2-D shape; below 2 the law's curvature is unbounded). Default 3, the fit to
    /// the rough-contact maps of a seed 001 surface at its working films; it depends on the
    /// surface and the film (`rough_contact` with `friction_limit` reports it per film;
    /// BENCHMARKS.md, "Mixed lubrication: the micro-slip map").
    #[serde(default = "default_micro_slip_exponent", skip_serializing_if = "is_default_micro_slip_exponent")]
    pub micro_slip_exponent: f64,
    /// The micro-slip map per film (seed 001 eq. 19, 23): gross-sliding displacement and shape
    /// exponent against film, in place of `gross_sliding_displacement` and `micro_slip_exponent`
    /// (`micro_slip` only). A `rough_contact` job with `friction_limit` reports it as
    /// `micro_slip_map`: paste it here.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub micro_slip_map: Option<MicroSlipMapSpec>,
    /// Plastic limit of the asperity contact pressure, Pa (seed 001 Table 1: 6e9). Absent:
    /// elastic asperities.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub plastic_limit: Option<f64>,
    /// Mean asperity pressure against film (the "h–p̄_a curve" of seed 001 eq. 12, e.g. from a
    /// `rough_contact` job or a measurement): replaces Greenwood–Tripp in the load sharing.
    /// Still needs `roughness_rq` on a body (σ > 0 switches mixed lubrication on and sets λ).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub pressure_gap_curve: Option<PressureGapSpec>,
}

/// A tabulated pressure–gap relation: `film` ascending (m), `pressure` the mean asperity pressure
/// at each film (Pa, positive, non-increasing); interpolated monotonically in `ln p`, continued
/// exponentially beyond the ends.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct PressureGapSpec {
    /// Films (mean gaps), m, strictly ascending, 2 to 1000 points.
    pub film: Vec<f64>,
    /// Mean asperity pressures, Pa.
    pub pressure: Vec<f64>,
}

/// `δx_gs(h)` and `n(h)` of the micro-slip law: `film` strictly ascending (m), 1 to 1000 rows;
/// `gross_sliding_displacement` in [1e-12, 1e-3] m and `exponent` in [2, 8] per film. Between
/// films `ln δx_gs` and `n` are linear in the film; beyond the ends the end rows hold.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct MicroSlipMapSpec {
    /// Films (mean gaps), m.
    pub film: Vec<f64>,
    /// Gross-sliding displacement δx_gs at each film, m.
    pub gross_sliding_displacement: Vec<f64>,
    /// Exponent n of `μ_a/μ_lim = 1 − (1 − δx/δx_gs)^n` at each film.
    pub exponent: Vec<f64>,
}

impl MicroSlipMapSpec {
    pub fn to_physics(&self) -> Result<crate::physics::friction::MicroSlipMap, (&'static str, String)> {
        crate::physics::friction::MicroSlipMap::new(self.film.clone(), self.gross_sliding_displacement.clone(), self.exponent.clone())
    }
}

impl Default for AsperitySpec {
    fn default() -> Self {
        AsperitySpec {
            eta_beta_sigma: default_ebs(),
            sigma_over_beta: default_sob(),
            boundary_friction: default_mub(),
            model: AsperityModelSpec::Coulomb,
            gross_sliding_displacement: None,
            micro_slip_exponent: default_micro_slip_exponent(),
            micro_slip_map: None,
            plastic_limit: None,
            pressure_gap_curve: None,
        }
    }
}

impl AsperitySpec {
    pub fn roughness(&self, sigma: f64) -> Roughness {
        let curve = self
            .pressure_gap_curve
            .as_ref()
            .and_then(|c| crate::physics::friction::PressureGapCurve::new(&c.film, &c.pressure).ok())
            .map(std::sync::Arc::new);
        Roughness {
            sigma,
            eta_beta_sigma: self.eta_beta_sigma,
            sigma_over_beta: self.sigma_over_beta,
            plastic_limit: self.plastic_limit.unwrap_or(f64::INFINITY),
            curve,
        }
    }
    pub fn friction(&self) -> AsperityFriction {
        AsperityFriction {
            coefficient: self.boundary_friction,
            model: match self.model {
                AsperityModelSpec::Coulomb => AsperityModel::Coulomb,
                AsperityModelSpec::Carter => AsperityModel::Carter,
                AsperityModelSpec::MicroSlip => AsperityModel::MicroSlip {
                    gross_sliding_displacement: self.gross_sliding_displacement.unwrap_or(0.0),
                    exponent: self.micro_slip_exponent,
                },
            },
            map: match self.model {
                AsperityModelSpec::MicroSlip => self.micro_slip_map.as_ref().and_then(|m| m.to_physics().ok()).map(std::sync::Arc::new),
                _ => None,
            },
        }
    }
    pub fn validate(&self, path: &str, v: &mut Validation) {
        v.in_range(&format!("{path}/eta_beta_sigma"), self.eta_beta_sigma, 0.0, 1.0);
        v.in_range(&format!("{path}/sigma_over_beta"), self.sigma_over_beta, 0.0, 1.0);
        v.in_range(&format!("{path}/boundary_friction"), self.boundary_friction, 0.0, 2.0);
        match (self.model, self.gross_sliding_displacement, &self.micro_slip_map) {
            (AsperityModelSpec::MicroSlip, None, None) => {
                v.check(false, &format!("{path}/gross_sliding_displacement"), "required by model micro_slip (or a micro_slip_map)");
            }
            (AsperityModelSpec::MicroSlip, Some(_), Some(_)) => {
                v.check(false, &format!("{path}/gross_sliding_displacement"), "give either gross_sliding_displacement or micro_slip_map");
            }
            (AsperityModelSpec::MicroSlip, Some(d), None) => {
                v.in_range(&format!("{path}/gross_sliding_displacement"), d, 1e-12, 1e-3);
                v.in_range(&format!("{path}/micro_slip_exponent"), self.micro_slip_exponent, 2.0, 8.0);
            }
            (AsperityModelSpec::MicroSlip, None, Some(m)) => {
                let rows = Some(crate::physics::friction::micro_slip::MAX_MAP_ROWS);
                v.items(&format!("{path}/micro_slip_map/film"), m.film.len(), 1, rows);
                v.items(&format!("{path}/micro_slip_map/gross_sliding_displacement"), m.gross_sliding_displacement.len(), 1, rows);
                v.items(&format!("{path}/micro_slip_map/exponent"), m.exponent.len(), 1, rows);
                v.check(
                    is_default_micro_slip_exponent(&self.micro_slip_exponent),
                    &format!("{path}/micro_slip_exponent"),
                    "the micro_slip_map gives the exponent per film",
                );
                if let Err((column, rule)) = m.to_physics() {
                    v.check(false, &format!("{path}/micro_slip_map/{column}"), rule);
                }
            }
            (_, d, m) => {
                if d.is_some() {
                    v.check(false, &format!("{path}/gross_sliding_displacement"), "only used by model micro_slip");
                }
                if m.is_some() {
                    v.check(false, &format!("{path}/micro_slip_map"), "only used by model micro_slip");
                }
            }
        }
        if let Some(p) = self.plastic_limit {
            v.in_range(&format!("{path}/plastic_limit"), p, 1e6, 1e11);
        }
        if let Some(c) = &self.pressure_gap_curve {
            let at = format!("{path}/pressure_gap_curve");
            v.items(&format!("{at}/film"), c.film.len(), 2, Some(1000));
            v.items(&format!("{at}/pressure"), c.pressure.len(), 2, Some(1000));
            if c.film.len() <= 1000 {
                if let Err(e) = crate::physics::friction::PressureGapCurve::new(&c.film, &c.pressure) {
                    v.check(false, &at, e);
                }
            }
        }
    }
}

/// Shear law of the film.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize, ToSchema)]
#[serde(rename_all = "snake_case")]
pub enum RheologySpec {
    /// Eyring: τ = τ0 asinh(ηu_s/(hτ0)) (seed 001 eq. 25).
    #[default]
    Eyring,
    /// Newtonian: τ = ηu_s/h.
    Newtonian,
}

fn default_tau0() -> f64 {
    5e6
}

/// Film traction law.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct TractionSpec {
    /// `eyring` (default) or `newtonian`.
    #[serde(default)]
    pub model: RheologySpec,
    /// Eyring stress τ0, Pa. Default 5e6 (seed 001 Table 1).
    #[serde(default = "default_tau0")]
    pub eyring_stress: f64,
    /// Limiting shear stress coefficient Λ (|τ| ≤ Λp); absent: no limit.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub limiting_shear_coefficient: Option<f64>,
}

impl Default for TractionSpec {
    fn default() -> Self {
        TractionSpec { model: RheologySpec::Eyring, eyring_stress: default_tau0(), limiting_shear_coefficient: None }
    }
}

impl TractionSpec {
    pub fn to_physics(&self) -> TractionLaw {
        TractionLaw {
            rheology: match self.model {
                RheologySpec::Eyring => Rheology::Eyring { tau0: self.eyring_stress },
                RheologySpec::Newtonian => Rheology::Newtonian,
            },
            limiting_shear_coefficient: self.limiting_shear_coefficient,
        }
    }
    pub fn validate(&self, path: &str, v: &mut Validation) {
        v.in_range(&format!("{path}/eyring_stress"), self.eyring_stress, 1e3, 1e9);
        if let Some(l) = self.limiting_shear_coefficient {
            v.in_range(&format!("{path}/limiting_shear_coefficient"), l, 1e-4, 1.0);
        }
    }
}

/// Closed-form film options (`fast` fidelity).
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct FilmSpec {
    /// Line-contact formula: `pan_hamrock` (default), `dowson_higginson` or `seed003`
    /// (seed 003 eq. 17–18). Point contacts (spherical tappet) always use Hamrock–Dowson.
    #[serde(default)]
    #[schema(value_type = crate::jobs::schemas::FilmFormulaDoc)]
    pub formula: FilmFormula,
    /// Seed 003's squeeze term (only with `formula: seed003`). Default false.
    #[serde(default)]
    pub squeeze: bool,
}

impl FilmSpec {
    pub fn to_physics(&self) -> ClosedForm {
        ClosedForm { formula: self.formula, squeeze: self.squeeze }
    }
    pub fn validate(&self, path: &str, v: &mut Validation) {
        v.check(
            !self.squeeze || self.formula == FilmFormula::Seed003,
            &format!("{path}/squeeze"),
            "the squeeze term belongs to the seed003 formula",
        );
    }
}

/// Composite RMS roughness of two surfaces, m.
pub fn composite_sigma(a: f64, b: f64) -> f64 {
    (a * a + b * b).sqrt()
}

/// The line grid where the accuracy ladders do not apply and the spec gives none: the thermal
/// model (its grid error is not tabulated) and a single contact point without `accuracy`.
const UNLADDERED_NODES: usize = 192;
fn default_ehl_tolerance() -> f64 {
    1e-6
}
fn default_ehl_iterations() -> u32 {
    60
}
fn default_auto_tolerance() -> f64 {
    0.05
}

/// Numerical EHL options (fidelities `accurate` and `auto`; see `physics::film::Numerical` and
/// `physics::film::auto`). The solver is the isothermal line-contact EHL of `physics::ehl`
/// (compressible Reynolds with squeeze, elastic half-space, load balance, cavitation); point
/// contacts (spherical tappets) always keep the closed form.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct EhlSpec {
    /// Grid nodes per contact (graded towards the inlet and the exit constriction), 32 … the
    /// server's grid limit; with Richardson extrapolation the fine grid. Absent: the cheapest
    /// grid whose measured error is within `accuracy` (isothermal line model at the default 1 %: 288
    /// for a roller, 208 for a flat-faced follower; `kinds::accuracy`), and 192 with `thermal`
    /// (its grid error is not in the ladder). Measured on 720-angle cycles against the
    /// grid-converged cycle, the largest central or minimum film error at any angle, roller /
    /// flat: 96 nodes 4.8 / 5.1 %, 128 2.7 / 2.3 %, 192 1.9 / 1.2 %, 208 1.5 / 0.83 %, 288 0.88 /
    /// 0.39 %, 384 0.40 / 0.20 % (BENCHMARKS.md, "Accuracy targets"). The cost grows like nodes^1.5–2.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub nodes: Option<usize>,
    /// The films' target accuracy: the largest relative error of the central and the minimum
    /// film at any angle against the grid-converged solution, 0.001–0.2. Default 0.01. It chooses
    /// what the spec leaves out: `nodes` (line model) and `thermal.carry_tolerance` (the thermal
    /// cycle's key points), from tables measured on seed 000's roller and seed 003's flat
    /// follower; `result.ehl_settings` reports the choice and its measured error. Not the
    /// Newton iteration's `tolerance`; the 2-D model's grid has its own check (`grid_tolerance`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub accuracy: Option<f64>,
    /// Residual tolerance of the Newton iteration (relative load balance and scaled Reynolds
    /// residual). Default 1e-6.
    #[serde(default = "default_ehl_tolerance")]
    pub tolerance: f64,
    /// Most Newton steps per solve (per continuation stage). Default 60.
    #[serde(default = "default_ehl_iterations")]
    pub max_iterations: u32,
    /// `auto`: largest estimated relative error of the closed-form film accepted; the numerical
    /// solver runs where the estimate exceeds it. Default 0.05.
    #[serde(default = "default_auto_tolerance")]
    pub auto_tolerance: f64,
    /// `richardson` (default): solve every contact on `nodes` and `(nodes − 1)/2 + 1` nodes of
    /// one grid layout (two threads) and extrapolate the second-order discretisation error out of
    /// the central, minimum and exit films and the traction; `none`: one grid of `nodes`.
    #[serde(default)]
    pub extrapolation: ExtrapolationSpec,
    /// The thermal model of the `accurate` fidelity (seed 000 eq. 2, 4–5, 7–9): generalized
    /// Reynolds equation, film and cam/follower energy equations (their heat properties from the
    /// spec's `thermal`), traction of the sheared film. Absent: isothermal at the lubricant's
    /// temperature. With `fidelity: accurate` at every angle; with `auto` where the closed form is
    /// not accurate enough and the estimated thermal error of the isothermal solution (film
    /// reduction and traction, `physics::film::auto::thermal_error`) exceeds `auto_tolerance`
    /// (`summary.fidelity_used` counts the angles of each model). Line contacts only (roller
    /// and flat-faced followers). Costly: one coupled solve per angle and periodic iteration,
    /// and the traction table's energy solves around the angle's slip (the rest when the roller
    /// balance reaches them) — the seed 000 cycle at 36 angles takes ≈ 1.8 s in a debug build
    /// (`examples/seed000_thermal_steady.json`), 720 angles ≈ 11 s in release (1.6 s with
    /// `carry_tolerance` 0.05, the default); see BENCHMARKS.md, "Thermal EHL". The film's
    /// shear law is the spec's `traction` (default Eyring, seed 001); seed 000's own model is
    /// Newtonian, which its examples set (`traction.model: newtonian`). A contact
    /// the model cannot settle fails with a typed `not_converged`. `cam_point` uses steel bodies.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub thermal: Option<EhlThermalSpec>,
    /// The contact model of the numerical fidelities: `line` (default) the 1-D line-contact solver
    /// above; `finite` the 2-D finite-length / point solver (`physics::ehl::twod`, isothermal,
    /// Newtonian; transient along a cycle, see `squeeze`): a roller follower as a finite line contact with its `crown` profile
    /// (without a crown: a straight roller of the contact length), a spherical follower as a point
    /// contact (which the line model leaves to the closed form). Each angle starts from the
    /// previous angle's 2-D solution. Results gain the edge pressure peak along the roller and
    /// where the minimum film sits (series `edge_pressure_peak`, `edge_pressure_peak_position`,
    /// `min_film_axial_position`). With `auto` the 2-D model runs only where the contact's ends
    /// matter (point contacts; a crowned roller whose loaded length reaches the crown transition;
    /// `physics::film::finite::ends_matter`), the line-contact `auto` choice elsewhere. With
    /// `thermal` the thermal 2-D model (`physics::film::thermal_finite`: quasi-steady, row
    /// energies coupled to the 2-D generalized Reynolds equation; the roller balance's traction
    /// from the grid's nodes with their viscosity calibrated to the whole-contact thermal traction
    /// at the solved slip; `carry_tolerance` does not apply). Not with flat-faced followers or
    /// mixed-lubrication load sharing inside the solution (the asperity load is evaluated from the
    /// smooth film). Cost: BENCHMARKS.md, issue 16.
    #[serde(default, skip_serializing_if = "EhlGeometry::is_line")]
    pub geometry: EhlGeometry,
    /// `finite`: the number of grid nodes along the rolling direction, 17–513 (odd numbers `2^k + 1` allow the
    /// resolution check and the nested start). Default 65.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub nx: Option<usize>,
    /// `finite`: the number of grid nodes across the rolling direction (along the roller), 17–513. Default 129
    /// for a roller, 65 for a point contact.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub ny: Option<usize>,
    /// `finite`: the resolution check's tolerance — the largest accepted change of the central
    /// film from the grid with half the intervals (the minimum film may change three times as
    /// much), checked at the first angle; a grid above it is refused naming `/ehl/nx`. 0.005–0.5,
    /// default 0.05 (seed 000's roller: 33×65 changes by 6.8 % from 17×33, 65×129 by ≈ 3 %).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub grid_tolerance: Option<f64>,
    /// `finite`: the squeeze term of seed 000 eq. 2 (`12 ∂(ρh)/∂t`) along a cam cycle — each
    /// angle one backward-Euler step of the transient 2-D problem from the previous angle's film,
    /// as the line model always does. `false`: quasi-steady (each angle a steady solve started
    /// from the previous one; a dwell reuses its film). Default true. A single contact point
    /// (`cam_point`, `ehl_point`) has no time step and is steady either way.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub squeeze: Option<bool>,
}

/// The contact model of the numerical fidelities (see [`EhlSpec::geometry`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize, ToSchema)]
#[serde(rename_all = "snake_case")]
pub enum EhlGeometry {
    /// 1-D line contact (default).
    #[default]
    Line,
    /// 2-D finite-length roller or point contact.
    Finite,
}

impl EhlGeometry {
    pub fn is_line(&self) -> bool {
        *self == EhlGeometry::Line
    }
}

/// Grid extrapolation of the numerical EHL solver.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize, ToSchema)]
#[serde(rename_all = "snake_case")]
pub enum ExtrapolationSpec {
    /// Richardson extrapolation of two grids (default).
    #[default]
    Richardson,
    /// One grid.
    None,
}

impl Default for EhlSpec {
    fn default() -> Self {
        EhlSpec {
            nodes: None,
            accuracy: None,
            tolerance: default_ehl_tolerance(),
            max_iterations: default_ehl_iterations(),
            auto_tolerance: default_auto_tolerance(),
            extrapolation: ExtrapolationSpec::default(),
            thermal: None,
            geometry: EhlGeometry::Line,
            nx: None,
            ny: None,
            grid_tolerance: None,
            squeeze: None,
        }
    }
}

impl EhlSpec {
    /// The films' target accuracy ([`accuracy::DEFAULT_ACCURACY`] unless the spec says).
    pub fn accuracy(&self) -> f64 {
        self.accuracy.unwrap_or(accuracy::DEFAULT_ACCURACY)
    }

    /// The line model's grid for a contact of `family`: the spec's, else chosen by the accuracy
    /// (192 with `thermal`).
    pub fn nodes(&self, family: LineFamily) -> usize {
        match (self.nodes, &self.thermal) {
            (Some(n), _) => n,
            (None, Some(_)) => UNLADDERED_NODES,
            (None, None) => accuracy::line_rung(self.accuracy(), family).nodes,
        }
    }

    /// A single contact point's settings (`cam_point`): the ladders were measured on cycles'
    /// films, and the seed 001 nose's friction balance (film rolling resistance against asperity
    /// friction) moves by up to 10 % between 192 and 288 nodes, so a point keeps its 192 nodes
    /// unless the spec gives `nodes` or `accuracy` (BENCHMARKS.md, "Accuracy targets").
    pub fn for_point(&self) -> EhlSpec {
        let nodes = match (self.nodes, self.accuracy) {
            (None, None) => Some(UNLADDERED_NODES),
            (n, _) => n,
        };
        EhlSpec { nodes, ..*self }
    }

    /// The thermal line model's settings with the heat properties of body 1 and body 2 (key
    /// points by the spec's `carry_tolerance`, else by the accuracy).
    pub fn thermal_settings(&self, body_1: ThermalSolid, body_2: ThermalSolid) -> Option<ThermalFilmSettings> {
        self.thermal.map(|t| t.settings(body_1, body_2, self.accuracy()))
    }

    /// What the numerical film ran with, for the result (`ehl_settings`).
    pub fn settings_used(&self, family: LineFamily) -> accuracy::EhlSettingsUsed {
        let nodes = self.nodes(family);
        let carry = self.thermal.and_then(|t| t.key_point_tolerance(self.accuracy()));
        let grid_error = accuracy::rung_error(nodes, self.extrapolation == ExtrapolationSpec::Richardson && self.thermal.is_none(), family);
        let carry_error = match carry {
            Some(c) => accuracy::carry_error(c),
            None => Some(0.0),
        };
        accuracy::EhlSettingsUsed {
            accuracy: self.accuracy(),
            nodes,
            nodes_from_accuracy: self.nodes.is_none() && self.thermal.is_none(),
            carry_tolerance: carry,
            measured_error: grid_error.zip(carry_error).map(|(g, c)| g + c),
        }
    }

    pub fn to_physics(&self, family: LineFamily) -> AccurateSettings {
        AccurateSettings {
            options: EhlOptions {
                nodes: self.nodes(family),
                tolerance: self.tolerance,
                max_iterations: self.max_iterations,
                ..EhlOptions::default()
            },
            auto_tolerance: self.auto_tolerance,
            extrapolation: match self.extrapolation {
                ExtrapolationSpec::Richardson => Extrapolation::Richardson,
                ExtrapolationSpec::None => Extrapolation::None,
            },
            thermal: None,
            finite: (self.geometry == EhlGeometry::Finite).then(|| FiniteSettings { options: self.grid_options(false), crown: None, squeeze: self.squeeze.unwrap_or(true) }),
        }
    }

    /// The 2-D solver's options of `geometry: finite` (`point`: a point contact's default grid).
    pub fn grid_options(&self, point: bool) -> Ehl2dOptions {
        Ehl2dOptions {
            nx: self.nx.unwrap_or(65),
            ny: self.ny.unwrap_or(if point { 65 } else { 129 }),
            tolerance: self.tolerance,
            max_iterations: self.max_iterations,
            grid_tolerance: self.grid_tolerance.unwrap_or(0.05),
            ..Ehl2dOptions::default()
        }
    }

    pub fn validate(&self, path: &str, limits: &Limits, v: &mut Validation) {
        if let Some(nodes) = self.nodes {
            v.count_in_range(&format!("{path}/nodes"), nodes, 32, 1 << 16);
        }
        if let Some(a) = self.accuracy {
            v.in_range(&format!("{path}/accuracy"), a, 0.001, 0.2);
        }
        // The finer of the two ladders' choices (the family is the kind's to say).
        let nodes = self.nodes(LineFamily::Roller).max(self.nodes(LineFamily::FlatFaced));
        v.limit(&format!("{path}/nodes"), nodes, limits.max_grid_nodes, "the number of EHL grid nodes");
        v.in_range(&format!("{path}/tolerance"), self.tolerance, 1e-13, 1e-2);
        v.count_in_range(&format!("{path}/max_iterations"), self.max_iterations as usize, 1, 1000);
        v.in_range(&format!("{path}/auto_tolerance"), self.auto_tolerance, 0.0, 10.0);
        if let Some(t) = &self.thermal {
            t.validate(&format!("{path}/thermal"), v);
        }
        if self.geometry == EhlGeometry::Finite {
            let carried = self.thermal.is_some_and(|t| t.carry_tolerance.is_some());
            v.check(!carried, &format!("{path}/thermal/carry_tolerance"), "key points are a scheme of the thermal line model: not with geometry finite");
            let o = self.grid_options(false);
            if let Some(t) = self.grid_tolerance {
                v.in_range(&format!("{path}/grid_tolerance"), t, 0.005, 0.5);
            }
            v.count_in_range(&format!("{path}/nx"), o.nx, 17, 513);
            v.count_in_range(&format!("{path}/ny"), o.ny, 17, 513);
            v.limit(&format!("{path}/nx"), o.nx.saturating_mul(o.ny), limits.max_grid_nodes, "the number of 2-D grid nodes (nx·ny)");
        } else {
            v.check(self.nx.is_none() && self.ny.is_none() && self.grid_tolerance.is_none(), &format!("{path}/nx"), "nx, ny and grid_tolerance set the grid of geometry finite");
            v.check(self.squeeze.is_none(), &format!("{path}/squeeze"), "squeeze is an option of geometry finite (the line model always carries the squeeze term along a cycle)");
        }
    }
}

/// `[2]` → `/2`: an index of a solver field as a JSON-pointer segment.
fn index_segment(rest: &str) -> String {
    rest.strip_prefix('[').and_then(|r| r.strip_suffix(']')).map_or_else(String::new, |i| format!("/{i}"))
}

/// The spec path (in a `cam_cycle`-shaped spec) of a solver input field the cam kinds fill in
/// from the spec; `None` for derived inputs (they have no field of their own in the spec).
pub fn cam_spec_path(field: &str) -> Option<String> {
    for solver_field in ["MultiArc.arcs", "IrgashevInput.arcs"] {
        if let Some(rest) = field.strip_prefix(solver_field) {
            return Some(format!("/cam/profile/arcs{}", index_segment(rest)));
        }
    }
    let path = match field {
        "EhlOptions.nodes" => "/ehl/nodes",
        "EhlOptions.tolerance" => "/ehl/tolerance",
        "Ehl2dOptions.nx" => "/ehl/nx",
        "Ehl2dOptions.ny" => "/ehl/ny",
        "Ehl2dOptions.tolerance" => "/ehl/tolerance",
        "EhlInput.lubricant.viscosity" => "/lubricant/viscosity",
        "EhlInput.lubricant.pressure_viscosity" => "/lubricant/pressure_viscosity",
        "EhlInput.lubricant.density" => "/lubricant/density",
        "ValveTrain.follower_mass" => "/load/follower_mass",
        "ValveTrain.valve_mass" => "/load/valve_mass",
        "ValveTrain.train" => "/load/train_stiffness",
        "ValveTrain.spring" => "/load/spring",
        "ValveTrain.contact" => "/load/contact_stiffness",
        "ValveTrain.preload" => "/load/spring_preload",
        "ValveTrain.seat" => "/load/seat",
        "ValveTrain.lever" => "/load/arrangement",
        "ValveTrain.lever.pushrod" => "/load/arrangement/pushrod",
        "ValveTrain.lash" => "/load/lash/clearance",
        _ => return None,
    };
    Some(path.to_string())
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
    pub fn to_physics(self) -> ThermalSolid {
        ThermalSolid { conductivity: self.conductivity, density: self.density, specific_heat: self.specific_heat }
    }
}
