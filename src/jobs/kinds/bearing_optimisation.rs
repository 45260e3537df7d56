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

use super::bearing::{resolve_load_in, solve_spec, validate_bearing, BearingSpec, BearingProfileSpec};
use crate::jobs::cost::Cost;
use crate::jobs::kind::{Kind, Limits, Validation};
use crate::physics::journal::taguchi::{level_means, nelder_mead, sn_larger_better, Array, Criteria, Reference, Weights};
use crate::physics::journal::{Guess, Operating, Workspace};
use crate::physics::{Convergence, Observer, SolveError, Termination};
use rayon::prelude::*;
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};
use std::sync::Mutex;
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
}

/// One analysed design.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, ToSchema)]
pub struct Design {
    pub order: u32,
    /// ξ
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
    /// Bearing analyses spent by the search.
    pub evaluations: usize,
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
    n
}

/// Analyse one profile on the base (the load is already resolved).
struct Evaluator {
    friction: FrictionDefinition,
    op: Operating,
    guess: Option<Guess>,
}

impl Evaluator {
    fn design(&self, spec: &BearingSpec, p: Option<BearingProfileSpec>, ws: Option<&mut Workspace>, observer: &dyn Observer) -> Result<(Design, Guess), SolveError> {
        let mut s = spec.clone();
        s.profile = p;
        let (a, r) = solve_spec(&s, (self.op, self.guess, None), ws, observer)?;
        let f = match self.friction {
            FrictionDefinition::Seed002 => r.friction_variable_seed002,
            FrictionDefinition::RaimondiBoyd => r.friction_variable,
        }
        .ok_or_else(|| SolveError::physical(crate::physics::PhysicalFailure::NoLoad, "the design carries no load"))?;
        Ok((
            Design {
                order: p.map_or(0, |p| p.order),
                height: p.map_or(0.0, |p| p.height),
                length_fraction: p.map_or(0.0, |p| p.length_fraction),
                max_pressure_dimensionless: a.max_pressure,
                min_film_dimensionless: a.min_film,
                friction_variable: f,
                score: 0.0,
                eccentricity_ratio: a.eccentricity,
                max_pressure: r.max_pressure,
                min_film: r.min_film,
            },
            Guess { eccentricity: a.eccentricity, attitude: a.attitude },
        ))
    }
}

fn criteria(d: &Design) -> Criteria {
    Criteria { pressure: d.max_pressure_dimensionless, film: d.min_film_dimensionless, friction: d.friction_variable }
}

impl Kind for BearingOptimisation {
    const NAME: &'static str = "bearing_optimisation";
    const SOLVER_VERSION: &'static str = "bearing_optimisation-11";
    const DESCRIPTION: &'static str = "Axial edge profile design of a journal bearing (seed 002): Taguchi \
        L4/L9/L27 array with the weighted-sum score of eq. (19), main effects and S/N ratios, then a \
        continuous Nelder–Mead search over height and length fraction for each profile order.";
    const TABLES: &'static [&'static str] = &["runs", "main_effects"];
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

fn optimise(spec: &OptimisationSpec, observer: &dyn Observer) -> Result<OptimisationResult, SolveError> {
    let base = &spec.base;
    observer.progress(0.0, "reference load");
    let array = spec.method.array();
    let rows = array.rows();
    let levels = array.levels();
    let f = &spec.factors;
    let weights = Weights { film: spec.weights.film, pressure: spec.weights.pressure, friction: spec.weights.friction };
    let profile = |r: &[usize; 3]| BearingProfileSpec { order: f.order[r[0]], height: f.height[r[1]], length_fraction: f.length_fraction[r[2]] };
    let cases: Vec<Option<BearingProfileSpec>> = std::iter::once(None).chain(rows.iter().map(|r| Some(profile(r)))).collect();
    let workers = rayon::current_num_threads().clamp(1, cases.len());
    // the reference analysis on one thread (aligned and unprofiled: on the mirrored half of
    // the grid, with grids of its own) while the other allocates the array's workspaces
    let (reference_load, spares) = rayon::join(
        || resolve_load_in(base, None, observer),
        || (0..workers).map(|_| Workspace::new(&base.bearing(), &base.settings())).collect::<Vec<_>>(),
    );
    let (op, guess, target) = reference_load?;
    let mut evaluations = if base.load.aligned_eccentricity_ratio.is_some() { 1 } else { 0 };
    let load = target.unwrap_or(0.0);
    let ev = Evaluator { friction: spec.friction, op, guess };
    observer.progress(0.1, "orthogonal array");
    // The array on the pool, every analysis on a reset workspace (`Workspace::reset`), so its
    // result is the same bit for bit whichever worker runs it after whichever analysis, for any
    // pool size. The order (BENCHMARKS.md, journal speed, fourteenth round):
    // 1. the runs, each worker taking the next from a shared counter;
    // 2. the unprofiled baseline, which nothing else needs, by the first worker without a run;
    // 3. the confirmation of the best-level combination (when it is not a run), by the worker
    //    that completes the array. It then overlaps the baseline instead of following the array
    //    on one thread.
    // A worker left with nothing while runs are still in flight (more workers than these
    // tasks) guesses the best levels (`predicted_best_levels`) and starts that confirmation
    // speculatively; a wrong guess is abandoned as soon as the last run is in and costs only
    // that idle worker's time.
    let runs_total = cases.len() - 1;
    let next = AtomicUsize::new(0);
    let failed = AtomicBool::new(false);
    let baseline_taken = AtomicBool::new(false);
    let done: Mutex<Vec<Option<Design>>> = Mutex::new(vec![None; cases.len()]);
    // 0: the array is not complete; else 1 + the index of its best-level combination
    let known_best = AtomicUsize::new(0);
    // 0: no speculation started; else 1 + the index of the combination speculated on
    let speculated = AtomicUsize::new(0);
    let confirmation_taken = AtomicBool::new(false);
    let confirmation: Mutex<Option<([usize; 3], Design)>> = Mutex::new(None);
    let combo_index = |c: &[usize; 3]| 1 + (c[0] * levels + c[1]) * levels + c[2];
    let combo_of = |index: usize| {
        let i = index - 1;
        [i / (levels * levels), (i / levels) % levels, i % levels]
    };
    let spare = Mutex::new(spares);
    let workspaces: Vec<Workspace> = (0..workers)
        .into_par_iter()
        .map(|_| -> Result<Workspace, SolveError> {
            let mut ws = spare.lock().ok().and_then(|mut s| s.pop()).unwrap_or_else(|| Workspace::new(&base.bearing(), &base.settings()));
            let fail = |e: SolveError| {
                failed.store(true, Ordering::SeqCst);
                e
            };
            let confirm = |ws: &mut Workspace, combo: [usize; 3], observer: &dyn Observer| -> Result<(), SolveError> {
                ws.reset();
                let (d, _) = ev.design(base, Some(profile(&combo)), Some(ws), observer)?;
                *confirmation.lock().unwrap_or_else(|e| e.into_inner()) = Some((combo, d));
                Ok(())
            };
            loop {
                if failed.load(Ordering::SeqCst) {
                    break;
                }
                let run = next.fetch_add(1, Ordering::SeqCst);
                let case = if run < runs_total {
                    Some(run + 1)
                } else if !baseline_taken.swap(true, Ordering::SeqCst) {
                    Some(0)
                } else {
                    None
                };
                if let Some(i) = case {
                    ws.reset();
                    let (d, _) = observer.check().map_err(SolveError::from).and_then(|_| ev.design(base, cases[i], Some(&mut ws), observer)).map_err(fail)?;
                    let mut all = done.lock().unwrap_or_else(|e| e.into_inner());
                    all[i] = Some(d);
                    if i > 0 && all[1..].iter().all(Option::is_some) {
                        let designs: Vec<Design> = all[1..].iter().flatten().copied().collect();
                        drop(all);
                        let best = best_levels(&rows, levels, &sn_ratios(&designs, &weights));
                        known_best.store(combo_index(&best), Ordering::SeqCst);
                    }
                    continue;
                }
                let known = known_best.load(Ordering::SeqCst);
                if known != 0 {
                    // the array is complete: its confirmation, unless it is a run or a
                    // speculation on the right combination is under way
                    let best = combo_of(known);
                    if !rows.contains(&best) && speculated.load(Ordering::SeqCst) != known && !confirmation_taken.swap(true, Ordering::SeqCst) {
                        confirm(&mut ws, best, observer).map_err(fail)?;
                    }
                    break;
                }
                if speculated.load(Ordering::SeqCst) != 0 {
                    break;
                }
                let runs_so_far: Vec<Option<Design>> = done.lock().unwrap_or_else(|e| e.into_inner())[1..].to_vec();
                let Some(combo) = predicted_best_levels(&rows, levels, &runs_so_far, &weights) else { break };
                let mine = combo_index(&combo);
                if speculated.compare_exchange(0, mine, Ordering::SeqCst, Ordering::SeqCst).is_err() {
                    break;
                }
                let known = known_best.load(Ordering::SeqCst);
                if known != 0 && known != mine {
                    // the array completed meanwhile with another best: the loop takes its
                    // confirmation
                    continue;
                }
                if confirmation_taken.swap(true, Ordering::SeqCst) {
                    // the worker that completed the array took it before seeing this guess
                    break;
                }
                let abandon = Abandon { inner: observer, known_best: &known_best, failed: &failed, mine };
                // an error here (a wrong guess abandoned, a cancel, a failure) is not kept:
                // the confirmation runs again (below or after the array) and reports it
                if confirm(&mut ws, combo, &abandon).is_err() && known_best.load(Ordering::SeqCst) != mine {
                    // abandoned for another combination: take the true confirmation
                    confirmation_taken.store(false, Ordering::SeqCst);
                    speculated.store(usize::MAX, Ordering::SeqCst);
                    continue;
                }
                break;
            }
            Ok(ws)
        })
        .collect::<Result<_, _>>()?;
    let mut ws_confirm = workspaces.into_iter().next();
    let mut all: Vec<Design> = done.into_inner().unwrap_or_else(|e| e.into_inner()).into_iter().flatten().collect();
    evaluations += all.len();
    let mut baseline = all.remove(0);
    let designs = all;
    let crit: Vec<Criteria> = designs.iter().map(criteria).collect();
    let reference = Reference::of(&crit);
    let score = |d: &Design| reference.score(&criteria(d), &weights);
    let runs: Vec<Run> = designs
        .iter()
        .enumerate()
        .map(|(i, d)| {
            let (h, p, fr) = reference.normalise(&criteria(d));
            let s = score(d);
            Run {
                run: i + 1,
                order: d.order,
                height: d.height,
                length_fraction: d.length_fraction,
                max_pressure_dimensionless: d.max_pressure_dimensionless,
                min_film_dimensionless: d.min_film_dimensionless,
                friction_variable: d.friction_variable,
                pressure_normalised: p,
                film_normalised: h,
                friction_normalised: fr,
                score: s,
                sn_ratio_db: sn_larger_better(s),
                eccentricity_ratio: d.eccentricity_ratio,
            }
        })
        .collect();
    let best_run = runs.iter().max_by(|a, b| a.score.total_cmp(&b.score)).map_or(1, |r| r.run);
    let scores: Vec<f64> = runs.iter().map(|r| r.score).collect();
    let sn: Vec<f64> = runs.iter().map(|r| r.sn_ratio_db).collect();
    let mut main_effects = Vec::new();
    for (fi, name) in ["order", "height", "length_fraction"].iter().enumerate() {
        let ms = level_means(&rows, fi, levels, &scores);
        let mn = level_means(&rows, fi, levels, &sn);
        for l in 0..levels {
            let value = match fi {
                0 => f.order[l] as f64,
                1 => f.height[l],
                _ => f.length_fraction[l],
            };
            main_effects.push(Effect { factor: name.to_string(), level: l + 1, value, mean_score: ms[l], mean_sn_ratio_db: mn[l] });
        }
    }
    let best = best_levels(&rows, levels, &sn);
    let best_combo = match rows.iter().position(|r| *r == best) {
        Some(i) => designs[i],
        None => {
            evaluations += 1;
            match confirmation.into_inner().unwrap_or_else(|e| e.into_inner()) {
                Some((combo, d)) if combo == best => d,
                _ => {
                    if let Some(ws) = ws_confirm.as_mut() {
                        ws.reset();
                    }
                    ev.design(base, Some(profile(&best)), ws_confirm.as_mut(), observer)?.0
                }
            }
        }
    };
    let mut best_design = best_combo;
    best_design.score = score(&best_combo);
    let taguchi_best = best_design.score.max(runs[best_run - 1].score);
    baseline.score = score(&baseline);

    let continuous = if spec.continuous.enabled {
        observer.progress(0.5, "continuous search");
        let c = &spec.continuous;
        let hb = c.height.unwrap_or([f.height.iter().cloned().fold(f64::INFINITY, f64::min), f.height.iter().cloned().fold(0.0, f64::max)]);
        let pb = c.length_fraction.unwrap_or([
            f.length_fraction.iter().cloned().fold(f64::INFINITY, f64::min),
            f.length_fraction.iter().cloned().fold(0.0, f64::max),
        ]);
        let lo = [hb[0], pb[0].max(1e-3)];
        let hi = [hb[1].max(hb[0] + 1e-6), pb[1].max(pb[0].max(1e-3) + 1e-6)];
        let mut orders = f.order.clone();
        orders.sort();
        orders.dedup();
        let coarse = if c.coarse_search {
            let mut s = base.clone();
            s.grid.circumferential = (base.grid.circumferential / 2).max(17) | 1;
            s.grid.axial = (base.grid.axial / 2).max(9) | 1;
            s
        } else {
            base.clone()
        };
        let per: Vec<(Design, usize)> = orders
            .par_iter()
            .map(|&n| -> Result<(Design, usize), SolveError> {
                // start from the best run of this order
                let start = designs
                    .iter()
                    .filter(|d| d.order == n)
                    .max_by(|a, b| score(a).total_cmp(&score(b)))
                    .map_or([0.5 * (lo[0] + hi[0]), 0.5 * (lo[1] + hi[1])], |d| [d.height, d.length_fraction]);
                let mut used = 0;
                let objective = |spec_: &BearingSpec, ws: &mut Workspace, x: &[f64], used: &mut usize| -> Result<f64, SolveError> {
                    observer.check()?;
                    *used += 1;
                    let p = BearingProfileSpec { order: n, height: x[0], length_fraction: x[1] };
                    match ev.design(spec_, Some(p), Some(ws), observer) {
                        Ok((d, _)) => Ok(-score(&d)),
                        Err(SolveError::Interrupted(i)) => Err(SolveError::Interrupted(i)),
                        Err(_) => Ok(f64::INFINITY),
                    }
                };
                let step = [0.15 * (hi[0] - lo[0]), 0.15 * (hi[1] - lo[1])];
                let mut ws = Workspace::new(&coarse.bearing(), &coarse.settings());
                let m = nelder_mead(|x| objective(&coarse, &mut ws, x, &mut used), &start, &step, &lo, &hi, c.evaluations_per_order, 1e-7)?;
                let mut x = m.x.clone();
                if c.coarse_search {
                    let mut ws = Workspace::new(&base.bearing(), &base.settings());
                    let small = [0.03 * (hi[0] - lo[0]), 0.03 * (hi[1] - lo[1])];
                    let m2 = nelder_mead(|x| objective(base, &mut ws, x, &mut used), &x, &small, &lo, &hi, 15, 1e-8)?;
                    x = m2.x;
                }
                let (mut d, _) = ev.design(base, Some(BearingProfileSpec { order: n, height: x[0], length_fraction: x[1] }), None, observer)?;
                used += 1;
                d.score = score(&d);
                Ok((d, used))
            })
            .collect::<Result<_, _>>()?;
        let used: usize = per.iter().map(|p| p.1).sum();
        evaluations += used;
        let per_order: Vec<Design> = per.into_iter().map(|p| p.0).collect();
        let design = *per_order.iter().max_by(|a, b| a.score.total_cmp(&b.score)).unwrap();
        Some(Continuous { design, per_order, improves_on_taguchi: design.score > taguchi_best, evaluations: used })
    } else {
        None
    };
    observer.progress(1.0, "done");
    Ok(OptimisationResult {
        runs,
        best_run,
        best_levels: BestLevels {
            order_level: best[0] + 1,
            height_level: best[1] + 1,
            length_fraction_level: best[2] + 1,
            design: best_design,
        },
        main_effects,
        baseline,
        load_dimensionless: load,
        continuous,
        evaluations,
        convergence: Convergence { iterations: evaluations as u32, residual: 0.0, tolerance: 0.0, termination: Termination::Converged },
    })
}

/// S/N ratio of each run (larger the better, dB) on the runs' own normalisation (eq. 19).
fn sn_ratios(designs: &[Design], weights: &Weights) -> Vec<f64> {
    let crit: Vec<Criteria> = designs.iter().map(criteria).collect();
    let reference = Reference::of(&crit);
    crit.iter().map(|c| sn_larger_better(reference.score(c, weights))).collect()
}

/// The level of each factor with the largest mean S/N (0-based).
fn best_levels(rows: &[[usize; 3]], levels: usize, sn: &[f64]) -> [usize; 3] {
    let mut best = [0usize; 3];
    for (fi, b) in best.iter_mut().enumerate() {
        let mn = level_means(rows, fi, levels, sn);
        *b = (0..levels).max_by(|a, b| mn[*a].total_cmp(&mn[*b])).unwrap_or(0);
    }
    best
}

/// A guess of the array's best-level combination while some runs are still running, for
/// starting the confirmation run early: the S/N ratios of the runs done (on their own
/// normalisation), the missing runs' S/N set to one value `s` scanned from below the lowest to
/// above the highest known ratio, and of the combinations that come out and are not runs of
/// the array (only those need a confirmation run) the one that does for the widest range of
/// `s`. `None` when every outcome is a run or too few runs are done. Only a guess: a wrong
/// one costs the idle worker's time, never a result.
fn predicted_best_levels(rows: &[[usize; 3]], levels: usize, runs: &[Option<Design>], weights: &Weights) -> Option<[usize; 3]> {
    let done: Vec<Design> = runs.iter().flatten().copied().collect();
    if done.len() < 2 {
        return None;
    }
    let known = sn_ratios(&done, weights);
    let (lo, hi) = known.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), x| (a.min(*x), b.max(*x)));
    if !(lo.is_finite() && hi.is_finite()) {
        return None;
    }
    let margin = 0.5 * (hi - lo) + 1e-3;
    let mut tally: Vec<([usize; 3], usize)> = Vec::new();
    const SAMPLES: usize = 64;
    for k in 0..=SAMPLES {
        let s = lo - margin + (hi - lo + 2.0 * margin) * k as f64 / SAMPLES as f64;
        let mut it = known.iter();
        let sn: Vec<f64> = runs.iter().map(|r| if r.is_some() { *it.next().unwrap_or(&s) } else { s }).collect();
        let combo = best_levels(rows, levels, &sn);
        if rows.contains(&combo) {
            continue;
        }
        match tally.iter_mut().find(|t| t.0 == combo) {
            Some(t) => t.1 += 1,
            None => tally.push((combo, 1)),
        }
    }
    tally.iter().max_by_key(|t| t.1).map(|t| t.0)
}

/// The observer of a speculative confirmation run: stops it once the array is complete and its
/// best-level combination is another one (`known_best`: 0 while unknown, else 1 + its index),
/// or a case of the array failed.
struct Abandon<'a> {
    inner: &'a dyn Observer,
    known_best: &'a AtomicUsize,
    failed: &'a AtomicBool,
    mine: usize,
}

impl Observer for Abandon<'_> {
    fn progress(&self, fraction: f64, stage: &str) {
        self.inner.progress(fraction, stage);
    }
    fn check(&self) -> Result<(), crate::physics::Interrupt> {
        let known = self.known_best.load(Ordering::Relaxed);
        if (known != 0 && known != self.mine) || self.failed.load(Ordering::Relaxed) {
            return Err(crate::physics::Interrupt::Canceled);
        }
        self.inner.check()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::physics::Silent;

    /// Seed 002's L9 (misaligned, the paper's factor levels, no continuous search) on a grid.
    fn seed002_l9(circumferential: usize, axial: usize) -> OptimisationSpec {
        serde_json::from_value(json!({
            "base": {
                "geometry": {"length_to_diameter": 1.25},
                "load": {"aligned_eccentricity_ratio": 0.6},
                "misalignment": {"vertical": 0.56, "horizontal": 0.56},
                "grid": {"circumferential": circumferential, "axial": axial}
            },
            "method": "taguchi_l9",
            "factors": {"order": [1, 2, 3], "height": [0.1, 0.4, 1.0], "length_fraction": [0.01, 0.2, 0.4]},
            "continuous": {"enabled": false}
        }))
        .unwrap()
    }

    /// The array's result does not depend on the pool size or on which worker ran which case
    /// (each case on a reset workspace; the early confirmation kept only when it is the same
    /// analysis): equal to the last bit with 1, 2 and 3 threads, run twice each. (Without the
    /// reset before each case this fails at 181×91, not at 61×31.)
    #[test]
    fn the_l9_result_is_the_same_for_every_pool_size() {
        let spec = seed002_l9(181, 91);
        let run = |threads: usize| {
            let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build().unwrap();
            serde_json::to_string(&pool.install(|| optimise(&spec, &Silent).unwrap())).unwrap()
        };
        let one = run(1);
        for threads in [2, 3, 2, 3] {
            assert_eq!(run(threads), one, "{threads} threads");
        }
    }

    /// A cancel at any point of the array (after the n-th `check()` of any worker, across the
    /// runs, the baseline, a speculation and the confirmation) ends the optimisation with
    /// `Interrupted`, on 1, 2 and 3 threads; none hangs, and past the last check it succeeds
    /// with the uncanceled result.
    #[test]
    fn a_cancel_anywhere_in_the_array_interrupts_it() {
        use crate::physics::Interrupt;
        struct CancelAfter(AtomicUsize, usize);
        impl Observer for CancelAfter {
            fn progress(&self, _: f64, _: &str) {}
            fn check(&self) -> Result<(), Interrupt> {
                if self.0.fetch_add(1, Ordering::SeqCst) >= self.1 { Err(Interrupt::Canceled) } else { Ok(()) }
            }
        }
        let spec = seed002_l9(61, 31);
        let whole = serde_json::to_string(&optimise(&spec, &Silent).unwrap()).unwrap();
        for threads in [1, 2, 3] {
            let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build().unwrap();
            // the checks of a whole run on this pool (a speculation adds its own)
            let counter = CancelAfter(AtomicUsize::new(0), usize::MAX);
            pool.install(|| optimise(&spec, &counter)).unwrap();
            let checks = counter.0.load(Ordering::SeqCst);
            assert!(checks > 20, "{checks} checks");
            for n in (0..checks).step_by((checks / 25).max(1)) {
                match pool.install(|| optimise(&spec, &CancelAfter(AtomicUsize::new(0), n))) {
                    Err(SolveError::Interrupted(Interrupt::Canceled)) => {}
                    // with several workers the checks are shared out differently: a late cancel may
                    // come after the last check
                    Ok(r) if threads > 1 => assert_eq!(serde_json::to_string(&r).unwrap(), whole),
                    other => panic!("{threads} threads, cancel after {n} checks: {:?}", other.map(|r| r.evaluations)),
                }
            }
            let r = pool.install(|| optimise(&spec, &CancelAfter(AtomicUsize::new(0), checks + 1000))).unwrap();
            assert_eq!(serde_json::to_string(&r).unwrap(), whole);
        }
    }
}
