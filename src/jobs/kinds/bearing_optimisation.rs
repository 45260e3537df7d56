//! `bearing_optimisation`: axial edge profile design by Taguchi orthogonal arrays (seed 002 §3–4,
//! eq. 19, Tables 3–4), then a continuous Nelder–Mead search over the profile height ξ and length
//! fraction ψ for each profile order, on the same score and load.
//!
//! Score (seed 002 eq. 19 with the normalisation of Table 3): every criterion is divided by the
//! best value among the array's runs and oriented so that 1 is best — `H0/H0_best`,
//! `P0_best/P0`, `f_best/f` — and weighted (default 0.5 film, 0.25 pressure, 0.25 friction).
//! The continuous search keeps the array's normalisation, so its scores compare directly (a score
//! above 1 beats the best run in every weighted criterion). Friction is seed 002's eq. (9) as
//! read by the `bearing` kind (`friction: seed002`, default) or Raimondi & Boyd's journal friction. S/N ratios are larger-the-better, `20 log10(score)`, dB; the best
//! level of each factor is the one with the largest mean S/N.

use super::bearing::{validate_bearing, BearingSpec};
use crate::jobs::cost::Cost;
use crate::jobs::kind::{Kind, Limits, Validation};
use crate::physics::journal::optimisation::{self as opt, ContinuousSearch, FrictionFigure, Problem, ProfileDesign};
use crate::physics::journal::taguchi::{Array, Weights};
use crate::physics::{Convergence, Observer, SolveError};
use serde::{Deserialize, Serialize};
use serde_json::{json, Value};
use utoipa::ToSchema;

pub struct BearingOptimisation;

/// Orthogonal array.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize, ToSchema)]
#[serde(rename_all = "snake_case")]
pub enum Method {
    /// L4(2³): two levels per factor.
    TaguchiL4,
    /// L9(3⁴), seed 002 Table 4 order: three levels per factor.
    #[default]
    TaguchiL9,
    /// L27(3¹³) columns 1, 2, 5: three levels per factor (all 27 combinations).
    TaguchiL27,
}

impl Method {
    fn array(self) -> Array {
        match self {
            Method::TaguchiL4 => Array::L4,
            Method::TaguchiL9 => Array::L9,
            Method::TaguchiL27 => Array::L27,
        }
    }
}

/// Factor levels (two for L4, three for L9 and L27).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct Factors {
    /// Profile orders n (1, 2 or 3).
    #[schema(example = json!([1, 2, 3]))]
    pub order: Vec<u32>,
    /// Heights ξ = m_r/c (0 to 5).
    #[schema(example = json!([0.1, 0.4, 1.0]))]
    pub height: Vec<f64>,
    /// Length fractions ψ = m_l/L, (0, 0.5].
    #[schema(example = json!([0.01, 0.2, 0.4]))]
    pub length_fraction: Vec<f64>,
}

/// Weights of seed 002 eq. (19).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct WeightsSpec {
    /// Default 0.5.
    pub film: f64,
    /// Default 0.25.
    pub pressure: f64,
    /// Default 0.25.
    pub friction: f64,
}

impl Default for WeightsSpec {
    fn default() -> Self {
        WeightsSpec { film: 0.5, pressure: 0.25, friction: 0.25 }
    }
}

/// Which friction figure the score uses.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize, ToSchema)]
#[serde(rename_all = "snake_case")]
pub enum FrictionDefinition {
    /// Seed 002 eq. (9) as read by the `bearing` kind (`friction_variable_seed002`: streamers in
    /// the cavitated zone). Default, as in the paper's Table 3.
    #[default]
    Seed002,
    /// Raimondi & Boyd's journal friction (`friction_variable`).
    RaimondiBoyd,
}

/// The continuous search after the array.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize, ToSchema)]
#[serde(deny_unknown_fields, default)]
pub struct ContinuousSpec {
    /// Run it. Default true.
    pub enabled: bool,
    /// Bounds of ξ; default the range of the height levels.
    #[serde(skip_serializing_if = "Option::is_none")] #[schema(min_items = 2, max_items = 2)]
    pub height: Option<[f64; 2]>,
    /// Bounds of ψ; default the range of the length-fraction levels.
    #[serde(skip_serializing_if = "Option::is_none")] #[schema(min_items = 2, max_items = 2)]
    pub length_fraction: Option<[f64; 2]>,
    /// Simplex evaluations per order on the search grid (5 to 500). Default 40.
    pub evaluations_per_order: usize,
    /// Search on a grid with about half the nodes in each direction, then polish on the job's
    /// grid (default true); false searches on the job's grid directly.
    pub coarse_search: bool,
}

impl Default for ContinuousSpec {
    fn default() -> Self {
        ContinuousSpec { enabled: true, height: None, length_fraction: None, evaluations_per_order: 40, coarse_search: true }
    }
}

/// Optional outputs of a `bearing_optimisation` job.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, ToSchema)]
#[serde(rename_all = "snake_case")]
pub enum OptimisationOutput {
    /// Score maps over (n, ξ), (ξ, ψ) and (n, ψ), the third factor at its best level (seed 002
    /// Figs. 8–10): every cell a bearing analysis.
    ScoreGrid,
}

fn d_grid_points() -> usize {
    5
}

/// Spec of a `bearing_optimisation` job.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct OptimisationSpec {
    /// The bearing and operating point every design is analysed at (no `profile`, no `outputs`).
    pub base: BearingSpec,
    #[serde(default)]
    pub method: Method,
    pub factors: Factors,
    #[serde(default)]
    pub weights: WeightsSpec,
    /// Friction figure of the score. Default `seed002`.
    #[serde(default)]
    pub friction: FrictionDefinition,
    #[serde(default)]
    pub continuous: ContinuousSpec,
    /// Optional outputs: `score_grid`.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub outputs: Vec<OptimisationOutput>,
    /// `score_grid`: values evenly along each continuous axis (ξ, ψ), 2 to 15, besides the
    /// factor's levels; the order axis takes the order levels. Default 5.
    #[serde(default = "d_grid_points")]
    pub score_grid_points: usize,
}

/// One analysed design.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, ToSchema)]
pub struct Design {
    pub order: u32,
    /// ξ = m_r/c, a dimensionless edge opening.
    pub height: f64,
    /// ψ
    pub length_fraction: f64,
    /// P0
    pub max_pressure_dimensionless: f64,
    /// H0
    pub min_film_dimensionless: f64,
    /// (R/c) f of the spec's `friction` definition.
    pub friction_variable: f64,
    /// Weighted score, eq. (19), on the array's normalisation.
    pub score: f64,
    /// Mid-plane eccentricity ratio at the balanced position.
    pub eccentricity_ratio: f64,
    /// p_max, Pa (with dimensions).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub max_pressure: Option<f64>,
    /// h_min, m (with dimensions).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub min_film: Option<f64>,
}

/// One run of the array (flat: the `runs` CSV table).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, ToSchema)]
pub struct Run {
    /// 1-based run number in the array's standard order.
    pub run: usize,
    pub order: u32,
    /// ξ = m_r/c, a dimensionless edge opening.
    pub height: f64,
    pub length_fraction: f64,
    pub max_pressure_dimensionless: f64,
    pub min_film_dimensionless: f64,
    pub friction_variable: f64,
    /// Normalised criteria of Table 3: P0_best/P0, H0/H0_best, f_best/f.
    pub pressure_normalised: f64,
    pub film_normalised: f64,
    pub friction_normalised: f64,
    /// Eq. (19).
    pub score: f64,
    /// 20 log10(score), dB.
    pub sn_ratio_db: f64,
    pub eccentricity_ratio: f64,
}

/// Main effect of one level of one factor.
#[derive(Debug, Clone, PartialEq, Serialize, ToSchema)]
pub struct Effect {
    /// `order`, `height` or `length_fraction`.
    pub factor: String,
    /// 1-based level.
    pub level: usize,
    /// The level's value of the factor (its own unit: ξ and the length fraction are dimensionless, the order a count).
    pub value: f64,
    pub mean_score: f64,
    pub mean_sn_ratio_db: f64,
}

/// The best level of each factor (largest mean S/N).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, ToSchema)]
pub struct BestLevels {
    /// 1-based levels.
    pub order_level: usize,
    pub height_level: usize,
    pub length_fraction_level: usize,
    /// The combination, analysed (a confirmation run when it is not one of the runs).
    pub design: Design,
}

/// Result of the continuous search.
#[derive(Debug, Clone, PartialEq, Serialize, ToSchema)]
pub struct Continuous {
    /// The best design over all orders, analysed on the job's grid.
    pub design: Design,
    /// Best design per order.
    pub per_order: Vec<Design>,
    /// Whether `design` scores above the best of the runs and the best-level combination.
    pub improves_on_taguchi: bool,
    /// Whether `design` scores above the best run of the array (`best_run`). The search starts
    /// from the best of the array's runs, the best-level confirmation and the baseline, and keeps
    /// its start unless it finds a higher score, so it never ends below them.
    pub beats_best_run: bool,
    /// Bearing analyses spent by the search.
    pub evaluations: usize,
}

/// Where the recommended design comes from.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, ToSchema)]
#[serde(rename_all = "snake_case")]
pub enum DesignSource {
    /// The best run of the array (`best_run`).
    ArrayRun,
    /// The best-level combination (`best_levels`, its confirmation run).
    BestLevels,
    /// The continuous search (`continuous`).
    Continuous,
    /// The unprofiled base bearing (`baseline`).
    Baseline,
}

/// The design to build: the highest score among the best run, the best-level combination, the
/// continuous search's design and the baseline (on a tie, the earlier in that list).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, ToSchema)]
pub struct Recommended {
    pub source: DesignSource,
    /// 1-based run number (a count), when the source is `array_run`.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub run: Option<usize>,
    pub design: Design,
}

/// The score over two factors, the third held at its best level (seed 002 Figs. 8–10).
#[derive(Debug, Clone, PartialEq, Serialize, ToSchema)]
pub struct ScoreGrid {
    /// Factor along x: `order`, `height` or `length_fraction`.
    pub x_factor: String,
    /// Factor along y.
    pub y_factor: String,
    /// Values of the x factor (dimensionless: an order, ξ or ψ).
    pub x: Vec<f64>,
    /// Values of the y factor (dimensionless: an order, ξ or ψ).
    pub y: Vec<f64>,
    /// Score (dimensionless, eq. 19 on the array's normalisation): `score[j][i]` at (`x[i]`, `y[j]`).
    pub score: Vec<Vec<f64>>,
    /// The factor held at its best level.
    pub held_factor: String,
    /// Its value (dimensionless).
    pub held_value: f64,
}

/// Result of a `bearing_optimisation` job.
#[derive(Debug, Clone, PartialEq, Serialize, ToSchema)]
pub struct OptimisationResult {
    pub runs: Vec<Run>,
    /// 1-based number of the best run.
    pub best_run: usize,
    pub best_levels: BestLevels,
    pub main_effects: Vec<Effect>,
    /// The base bearing without a profile (e.g. misaligned), on the same load.
    pub baseline: Design,
    /// Dimensionless load W̄ every design carries.
    pub load_dimensionless: f64,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub continuous: Option<Continuous>,
    /// The better of the best run, the best-level confirmation and the continuous design (and
    /// the baseline): what to build.
    pub recommended: Recommended,
    /// `outputs: ["score_grid"]`: the score maps of Figs. 8–10.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub score_grids: Option<Vec<ScoreGrid>>,
    /// Bearing analyses in total.
    pub evaluations: usize,
    #[schema(value_type = crate::jobs::schemas::ConvergenceDoc)]
    pub convergence: Convergence,
}

fn planned_evaluations(spec: &OptimisationSpec) -> usize {
    let runs = spec.method.array().rows().len();
    // reference + baseline + runs + confirmation
    let mut n = 3usize.saturating_add(runs);
    if spec.continuous.enabled {
        let orders = spec.factors.order.len();
        let per_order = spec.continuous.evaluations_per_order.saturating_add(if spec.continuous.coarse_search { 15 } else { 0 });
        n = n.saturating_add(orders.saturating_mul(per_order));
    }
    if spec.outputs.contains(&OptimisationOutput::ScoreGrid) {
        let (orders, k) = (spec.factors.order.len(), spec.score_grid_points);
        let k = k.saturating_add(3); // the levels join the even values
        n = n.saturating_add(k.saturating_mul(k).saturating_add(2usize.saturating_mul(orders).saturating_mul(k)));
    }
    n
}

impl Kind for BearingOptimisation {
    const NAME: &'static str = "bearing_optimisation";
    const SOLVER_VERSION: &'static str = "bearing_optimisation-12";
    const DESCRIPTION: &'static str = "Axial edge profile design of a journal bearing (seed 002): Taguchi \
        L4/L9/L27 array with the weighted-sum score of eq. (19), main effects and S/N ratios, then a \
        continuous Nelder–Mead search over height and length fraction for each profile order.";
    const TABLES: &'static [&'static str] = &["runs", "main_effects"];
    const KEY_FIGURES: &'static [&'static str] = &["/recommended/design/score", "/recommended/design/min_film", "/best_run", "/best_levels/design/score", "/best_levels/design/min_film", "/continuous/design/score", "/continuous/design/min_film", "/baseline/score", "/baseline/min_film"];
    type Spec = OptimisationSpec;
    type Output = OptimisationResult;

    fn example() -> Value {
        json!({
            "base": {
                "geometry": {"length_to_diameter": 1.25},
                "operating": {"speed_rpm": 3000, "viscosity": 0.0293},
                "load": {"aligned_eccentricity_ratio": 0.6},
                "misalignment": {"vertical": 0.56, "horizontal": 0.56},
                "grid": {"circumferential": 181, "axial": 91}
            },
            "method": "taguchi_l9",
            "factors": {"order": [1, 2, 3], "height": [0.1, 0.4, 1.0], "length_fraction": [0.01, 0.2, 0.4]},
            "weights": {"film": 0.5, "pressure": 0.25, "friction": 0.25}
        })
    }

    fn outputs() -> &'static [crate::jobs::kind::OutputInfo] {
        &[crate::jobs::kind::OutputInfo { name: "score_grid", description: "score maps over (n, ξ), (ξ, ψ), (n, ψ), the third factor at its best level (seed 002 Figs. 8–10)" }]
    }

    fn validate(spec: &OptimisationSpec, limits: &Limits, v: &mut Validation) {
        validate_bearing(&spec.base, limits, v, true, "/base");
        v.check(spec.base.profile.is_none(), "/base/profile", "the profile is what is optimised: leave it out of the base");
        v.check(spec.base.outputs.is_empty(), "/base/outputs", "fields are not produced by an optimisation");
        let n = spec.method.array().levels();
        let f = &spec.factors;
        for (path, len) in [("/factors/order", f.order.len()), ("/factors/height", f.height.len()), ("/factors/length_fraction", f.length_fraction.len())] {
            v.items(path, len, 2, Some(3)).check(len == n, path, format!("needs {n} levels for this array"));
        }
        for (i, o) in f.order.iter().enumerate() {
            v.count_in_range(&format!("/factors/order/{i}"), *o as usize, 1, 3);
        }
        for (i, h) in f.height.iter().enumerate() {
            v.in_range(&format!("/factors/height/{i}"), *h, 0.0, 5.0);
        }
        for (i, p) in f.length_fraction.iter().enumerate() {
            v.check(p.is_finite() && *p > 0.0 && *p <= 0.5, &format!("/factors/length_fraction/{i}"), "must be in (0, 0.5]");
        }
        let w = &spec.weights;
        for (path, x) in [("/weights/film", w.film), ("/weights/pressure", w.pressure), ("/weights/friction", w.friction)] {
            v.non_negative(path, x);
        }
        v.check(w.film + w.pressure + w.friction > 0.0, "/weights", "at least one weight must be > 0");
        let c = &spec.continuous;
        v.count_in_range("/continuous/evaluations_per_order", c.evaluations_per_order, 5, 500);
        if let Some([lo, hi]) = c.height {
            v.check(lo.is_finite() && hi.is_finite() && 0.0 <= lo && lo < hi && hi <= 5.0, "/continuous/height", "needs 0 <= lo < hi <= 5");
        }
        if let Some([lo, hi]) = c.length_fraction {
            v.check(lo.is_finite() && hi.is_finite() && 0.0 < lo && lo < hi && hi <= 0.5, "/continuous/length_fraction", "needs 0 < lo < hi <= 0.5");
        }
        v.count_in_range("/score_grid_points", spec.score_grid_points, 2, 15);
        v.limit("/continuous/evaluations_per_order", planned_evaluations(spec), limits.max_evaluations, "planned bearing analyses");
    }

    fn cost(spec: &OptimisationSpec) -> Cost {
        // Every planned analysis is a bearing job's work on the base grid; memory: one workspace
        // per worker thread of the array, and the reference, baseline and best kept beside them.
        let one = super::bearing::bearing_cost(&spec.base);
        let n = planned_evaluations(spec);
        let workers = std::thread::available_parallelism().map_or(1, |p| p.get()).min(n.max(1)) as f64;
        let what = format!("{n} bearing analyses on {} × {} nodes", spec.base.grid.circumferential, spec.base.grid.axial);
        // The array's analyses start from their neighbours' solutions and share workspaces:
        // ≈ 0.25 of a bearing job's (the seed 002 misaligned L9 with its continuous search: 177
        // analyses in 1.65 s at 181×91; 360 at 3001×181 in 27 s, 460 MB).
        Cost::new(crate::jobs::cost::JOB_OVERHEAD_S + 0.25 * n as f64 * one.cpu_seconds(), (workers + 3.0) * one.memory_bytes())
            .work_at("/base/grid", what.clone())
            .memory_at("/base/grid", what)
    }

    fn solve(spec: &OptimisationSpec, observer: &dyn Observer) -> Result<OptimisationResult, SolveError> {
        // The base bearing's fields sit under /base; a candidate's profile comes from /factors.
        optimise(spec, observer).map_err(|e| {
            e.in_spec(|field| match field {
                "Bearing.profile" => Some("/factors".into()),
                _ => super::bearing::bearing_spec_path(field).map(|p| format!("/base{p}")),
            })
        })
    }
}

/// The physics problem of a spec: the base bearing and its load, the array's factor levels, the
/// score's weights and friction figure, and the continuous search.
fn problem(spec: &OptimisationSpec) -> Result<Problem, SolveError> {
    let base = &spec.base;
    let f = &spec.factors;
    let c = &spec.continuous;
    Ok(Problem {
        bearing: base.bearing(),
        settings: base.settings(),
        load: base.load_demand()?,
        dimensions: base.dimensions(),
        want_fields: base.wants_fields(),
        array: spec.method.array(),
        orders: f.order.clone(),
        heights: f.height.clone(),
        length_fractions: f.length_fraction.clone(),
        weights: Weights { film: spec.weights.film, pressure: spec.weights.pressure, friction: spec.weights.friction },
        friction: match spec.friction {
            FrictionDefinition::Seed002 => FrictionFigure::Seed002,
            FrictionDefinition::RaimondiBoyd => FrictionFigure::RaimondiBoyd,
        },
        continuous: c.enabled.then_some(ContinuousSearch {
            height: c.height,
            length_fraction: c.length_fraction,
            evaluations_per_order: c.evaluations_per_order,
            coarse_search: c.coarse_search,
        }),
        score_grid_points: spec.outputs.contains(&OptimisationOutput::ScoreGrid).then_some(spec.score_grid_points),
    })
}

/// The optimisation of a spec: its problem in `physics::journal::optimisation`, the outcome as
/// the result document (public for the tests of its scheduling, `tests/it/service_units.rs`).
pub fn optimise(spec: &OptimisationSpec, observer: &dyn Observer) -> Result<OptimisationResult, SolveError> {
    let d = opt::optimise(&problem(spec)?, observer)?;
    Ok(result(&d))
}

/// A design (field for field `journal::optimisation::Design`).
fn design(d: &opt::Design) -> Design {
    Design {
        order: d.order,
        height: d.height,
        length_fraction: d.length_fraction,
        max_pressure_dimensionless: d.max_pressure_dimensionless,
        min_film_dimensionless: d.min_film_dimensionless,
        friction_variable: d.friction_variable,
        score: d.score,
        eccentricity_ratio: d.eccentricity_ratio,
        max_pressure: d.max_pressure,
        min_film: d.min_film,
    }
}

/// A run of the array (field for field `journal::optimisation::Run`).
fn run(r: &opt::Run) -> Run {
    Run {
        run: r.run,
        order: r.order,
        height: r.height,
        length_fraction: r.length_fraction,
        max_pressure_dimensionless: r.max_pressure_dimensionless,
        min_film_dimensionless: r.min_film_dimensionless,
        friction_variable: r.friction_variable,
        pressure_normalised: r.pressure_normalised,
        film_normalised: r.film_normalised,
        friction_normalised: r.friction_normalised,
        score: r.score,
        sn_ratio_db: r.sn_ratio_db,
        eccentricity_ratio: r.eccentricity_ratio,
    }
}

/// The result document of an outcome (field for field `journal::optimisation::ProfileDesign`).
fn result(d: &ProfileDesign) -> OptimisationResult {
    let b = &d.best_levels;
    OptimisationResult {
        runs: d.runs.iter().map(run).collect(),
        best_run: d.best_run,
        best_levels: BestLevels {
            order_level: b.order_level,
            height_level: b.height_level,
            length_fraction_level: b.length_fraction_level,
            design: design(&b.design),
        },
        main_effects: d
            .main_effects
            .iter()
            .map(|e| Effect { factor: e.factor.clone(), level: e.level, value: e.value, mean_score: e.mean_score, mean_sn_ratio_db: e.mean_sn_ratio_db })
            .collect(),
        baseline: design(&d.baseline),
        load_dimensionless: d.load_dimensionless,
        continuous: d.continuous.as_ref().map(|c| Continuous {
            design: design(&c.design),
            per_order: c.per_order.iter().map(design).collect(),
            improves_on_taguchi: c.improves_on_taguchi,
            beats_best_run: c.beats_best_run,
            evaluations: c.evaluations,
        }),
        recommended: Recommended {
            source: match d.recommended.source {
                opt::DesignSource::ArrayRun => DesignSource::ArrayRun,
                opt::DesignSource::BestLevels => DesignSource::BestLevels,
                opt::DesignSource::Continuous => DesignSource::Continuous,
                opt::DesignSource::Baseline => DesignSource::Baseline,
            },
            run: d.recommended.run,
            design: design(&d.recommended.design),
        },
        score_grids: (!d.score_grids.is_empty()).then(|| {
            d.score_grids
                .iter()
                .map(|g| ScoreGrid {
                    x_factor: g.x_factor.into(),
                    y_factor: g.y_factor.into(),
                    x: g.x.clone(),
                    y: g.y.clone(),
                    score: g.score.clone(),
                    held_factor: g.held_factor.into(),
                    held_value: g.held_value,
                })
                .collect()
        }),
        evaluations: d.evaluations,
        convergence: d.convergence.clone(),
    }
}
