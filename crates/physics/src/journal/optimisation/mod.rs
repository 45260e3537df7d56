//! Axial edge profile design by Taguchi orthogonal arrays (seed 002 §3–4, eq. 19, Tables 3–4),
//! then a continuous Nelder–Mead search over the profile height ξ and length fraction ψ for each
//! profile order, on the same score and load.
//!
//! Score (seed 002 eq. 19 with the normalisation of Table 3): every criterion is divided by the
//! best value among the array's runs and oriented so that 1 is best — `H0/H0_best`,
//! `P0_best/P0`, `f_best/f` — and weighted. The continuous search keeps the array's
//! normalisation, so its scores compare directly (a score above 1 beats the best run in every
//! weighted criterion). S/N ratios are larger-the-better, `20 log10(score)`, dB; the best level
//! of each factor is the one with the largest mean S/N.
//!
//! - [`array`]: the array's runs, the unprofiled baseline and the confirmation of the best-level
//!   combination, scheduled over the rayon pool (the result is the same for any pool size).
//! - [`continuous`]: the search per profile order.

mod array;
mod continuous;
mod grid;

use super::operating::{resolve_load, LoadDemand};
use super::taguchi::{level_means, sn_larger_better, Array, Criteria, Reference, Weights};
use super::{analyse, Bearing, Dimensions, Guess, Operating, Profile, Settings, Workspace};
use crate::{Convergence, Observer, SolveError, Termination};

/// Which friction figure the score uses.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum FrictionFigure {
    /// Seed 002 eq. (9) as read by the analysis (`friction_variable_seed002`: streamers in the
    /// cavitated zone).
    Seed002,
    /// Raimondi & Boyd's journal friction (`friction_variable`).
    RaimondiBoyd,
}

/// The continuous search after the array.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ContinuousSearch {
    /// Bounds of ξ; default the range of the height levels.
    pub height: Option<[f64; 2]>,
    /// Bounds of ψ; default the range of the length-fraction levels.
    pub length_fraction: Option<[f64; 2]>,
    /// Simplex evaluations per order on the search grid.
    pub evaluations_per_order: usize,
    /// Search on a grid with about half the nodes in each direction, then polish on the
    /// problem's grid; false searches on the problem's grid directly.
    pub coarse_search: bool,
}

/// A profile design problem.
#[derive(Debug, Clone, PartialEq)]
pub struct Problem {
    /// The base bearing; each design replaces its profile.
    pub bearing: Bearing,
    pub settings: Settings,
    /// The load every design carries (resolved once, on the base).
    pub load: LoadDemand,
    /// SI scales (for the designs' SI figures and a force).
    pub dimensions: Option<Dimensions>,
    /// Keep the fields of each analysis.
    pub want_fields: bool,
    pub array: Array,
    /// Factor levels: profile orders, heights ξ, length fractions ψ.
    pub orders: Vec<u32>,
    pub heights: Vec<f64>,
    pub length_fractions: Vec<f64>,
    pub weights: Weights,
    pub friction: FrictionFigure,
    /// The continuous search (none: the array only).
    pub continuous: Option<ContinuousSearch>,
    /// Points per continuous axis of the score maps over two factors (none: no maps).
    pub score_grid_points: Option<usize>,
}

impl Problem {
    /// The profile of a row of level indices.
    fn profile(&self, r: &[usize; 3]) -> Profile {
        Profile { order: self.orders[r[0]], height: self.heights[r[1]], length_fraction: self.length_fractions[r[2]] }
    }
}

/// One analysed design.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Design {
    pub order: u32,
    pub height: f64,
    pub length_fraction: f64,
    /// P0
    pub max_pressure_dimensionless: f64,
    /// H0
    pub min_film_dimensionless: f64,
    /// (R/c) f of the problem's friction figure.
    pub friction_variable: f64,
    /// Weighted score, eq. (19), on the array's normalisation.
    pub score: f64,
    pub eccentricity_ratio: f64,
    /// p_max, Pa (with dimensions).
    pub max_pressure: Option<f64>,
    /// h_min, m (with dimensions).
    pub min_film: Option<f64>,
}

/// One run of the array.
#[derive(Debug, Clone, Copy, PartialEq)]
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
#[derive(Debug, Clone, PartialEq)]
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
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BestLevels {
    /// 1-based levels.
    pub order_level: usize,
    pub height_level: usize,
    pub length_fraction_level: usize,
    /// The combination, analysed (a confirmation run when it is not one of the runs).
    pub design: Design,
}

/// Result of the continuous search.
#[derive(Debug, Clone, PartialEq)]
pub struct Continuous {
    /// The best design over all orders, analysed on the problem's grid.
    pub design: Design,
    /// Best design per order.
    pub per_order: Vec<Design>,
    /// Whether `design` scores above the best of the runs and the best-level combination.
    pub improves_on_taguchi: bool,
    /// Whether `design` scores above the best run of the array.
    pub beats_best_run: bool,
    /// Bearing analyses spent by the search.
    pub evaluations: usize,
}

/// The score over two factors, the third held at its best level (seed 002 Figs. 8–10).
#[derive(Debug, Clone, PartialEq)]
pub struct ScoreGrid {
    /// `order`, `height` or `length_fraction`.
    pub x_factor: &'static str,
    pub y_factor: &'static str,
    pub x: Vec<f64>,
    pub y: Vec<f64>,
    /// `score[j][i]` at (`x[i]`, `y[j]`), eq. (19) on the array's normalisation.
    pub score: Vec<Vec<f64>>,
    pub held_factor: &'static str,
    pub held_value: f64,
}

/// Where the recommended design comes from.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum DesignSource {
    /// The best run of the array.
    ArrayRun,
    /// The combination of the best levels (the confirmation run).
    BestLevels,
    /// The continuous search.
    Continuous,
    /// The unprofiled base bearing.
    Baseline,
}

/// The design to build: the highest score among the best run, the best-level combination, the
/// continuous search's design and the baseline (ties go to the earlier in that order).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Recommended {
    pub source: DesignSource,
    /// 1-based run number when the source is a run of the array.
    pub run: Option<usize>,
    pub design: Design,
}

/// The outcome of a profile design.
#[derive(Debug, Clone, PartialEq)]
pub struct ProfileDesign {
    pub runs: Vec<Run>,
    /// 1-based number of the best run.
    pub best_run: usize,
    pub best_levels: BestLevels,
    pub main_effects: Vec<Effect>,
    /// The base bearing without a profile, on the same load.
    pub baseline: Design,
    /// Dimensionless load W̄ every design carries.
    pub load_dimensionless: f64,
    pub continuous: Option<Continuous>,
    /// The best of the candidates (see [`Recommended`]).
    pub recommended: Recommended,
    /// Score maps over (n, ξ), (ξ, ψ), (n, ψ) (empty unless asked for).
    pub score_grids: Vec<ScoreGrid>,
    /// Bearing analyses in total.
    pub evaluations: usize,
    pub convergence: Convergence,
}

/// Analyse one profile on the base (the load is already resolved).
struct Evaluator<'a> {
    problem: &'a Problem,
    op: Operating,
    guess: Option<Guess>,
}

impl Evaluator<'_> {
    /// The design of profile `p` on the grid of `settings`, and its position.
    fn design(&self, settings: &Settings, p: Option<Profile>, ws: Option<&mut Workspace>, observer: &dyn Observer) -> Result<(Design, Guess), SolveError> {
        let pr = self.problem;
        let mut bearing = pr.bearing;
        bearing.profile = p;
        let a = analyse(&bearing, &self.op, settings, ws, self.guess, pr.want_fields, observer)?;
        let d = pr.dimensions;
        let f = match pr.friction {
            FrictionFigure::Seed002 => a.friction_variable_seed002,
            FrictionFigure::RaimondiBoyd => a.friction_variable,
        }
        .ok_or_else(|| SolveError::physical(crate::PhysicalFailure::NoLoad, "the design carries no load"))?;
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
                max_pressure: d.map(|d| a.max_pressure * d.pressure_scale()),
                min_film: d.map(|d| d.film(a.min_film)),
            },
            Guess { eccentricity: a.eccentricity, attitude: a.attitude },
        ))
    }
}

fn criteria(d: &Design) -> Criteria {
    Criteria { pressure: d.max_pressure_dimensionless, film: d.min_film_dimensionless, friction: d.friction_variable }
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

/// Design the profile: the array's runs, main effects and best levels, then the continuous
/// search (see the module docs). Progress: 0 "reference load", 0.1 "orthogonal array",
/// 0.5 "continuous search", 1 "done".
pub fn optimise(problem: &Problem, observer: &dyn Observer) -> Result<ProfileDesign, SolveError> {
    observer.progress(0.0, "reference load");
    let rows = problem.array.rows();
    let levels = problem.array.levels();
    let cases: Vec<Option<Profile>> = std::iter::once(None).chain(rows.iter().map(|r| Some(problem.profile(r)))).collect();
    let workers = rayon::current_num_threads().clamp(1, cases.len());
    // the reference analysis on one thread (aligned and unprofiled: on the mirrored half of
    // the grid, with grids of its own) while the other allocates the array's workspaces
    let (reference_load, spares) = rayon::join(
        || resolve_load(&problem.bearing, &problem.settings, &problem.load, problem.dimensions.as_ref(), None, observer),
        || (0..workers).map(|_| Workspace::new(&problem.bearing, &problem.settings)).collect::<Vec<_>>(),
    );
    let point = reference_load?;
    let mut evaluations = if matches!(problem.load, LoadDemand::AlignedEccentricity(_)) { 1 } else { 0 };
    let load = point.target.unwrap_or(0.0);
    let ev = Evaluator { problem, op: point.operating, guess: point.guess };
    observer.progress(0.1, "orthogonal array");
    let outcome = array::run(&ev, &rows, levels, &cases, spares, workers, observer)?;
    let mut ws_confirm = outcome.workspaces.into_iter().next();
    let mut all: Vec<Design> = outcome.done.into_iter().flatten().collect();
    evaluations += all.len();
    let mut baseline = all.remove(0);
    let designs = all;
    let crit: Vec<Criteria> = designs.iter().map(criteria).collect();
    let reference = Reference::of(&crit);
    let score = |d: &Design| reference.score(&criteria(d), &problem.weights);
    let runs = runs(&designs, &reference, &score);
    let best_run = runs.iter().max_by(|a, b| a.score.total_cmp(&b.score)).map_or(1, |r| r.run);
    let sn: Vec<f64> = runs.iter().map(|r| r.sn_ratio_db).collect();
    let main_effects = main_effects(problem, &rows, levels, &runs);
    let best = best_levels(&rows, levels, &sn);
    let best_combo = match rows.iter().position(|r| *r == best) {
        Some(i) => designs[i],
        None => {
            evaluations += 1;
            match outcome.confirmation {
                Some((combo, d)) if combo == best => d,
                _ => {
                    if let Some(ws) = ws_confirm.as_mut() {
                        ws.reset();
                    }
                    ev.design(&problem.settings, Some(problem.profile(&best)), ws_confirm.as_mut(), observer)?.0
                }
            }
        }
    };
    let mut best_design = best_combo;
    best_design.score = score(&best_combo);
    let best_run_score = runs[best_run - 1].score;
    let taguchi_best = best_design.score.max(best_run_score);
    baseline.score = score(&baseline);

    let continuous = match &problem.continuous {
        Some(c) => {
            observer.progress(0.5, "continuous search");
            let starts: Vec<Design> = designs.iter().chain([&best_design, &baseline]).copied().collect();
            let (per_order, used) = continuous::search(&ev, c, &starts, &score, observer)?;
            evaluations += used;
            let design = *per_order.iter().max_by(|a, b| a.score.total_cmp(&b.score)).unwrap();
            Some(Continuous {
                design,
                per_order,
                improves_on_taguchi: design.score > taguchi_best,
                beats_best_run: design.score > best_run_score,
                evaluations: used,
            })
        }
        None => None,
    };
    let mut best_run_design = designs[best_run - 1];
    best_run_design.score = best_run_score;
    let recommended = recommend(best_run, best_run_design, best_design, continuous.as_ref().map(|c| c.design), baseline);
    let score_grids = match problem.score_grid_points {
        Some(points) => {
            observer.progress(0.9, "score maps");
            let (g, used) = grid::score_grids(&ev, best, points, &score, observer)?;
            evaluations += used;
            g
        }
        None => Vec::new(),
    };
    observer.progress(1.0, "done");
    Ok(ProfileDesign {
        runs,
        best_run,
        best_levels: BestLevels { order_level: best[0] + 1, height_level: best[1] + 1, length_fraction_level: best[2] + 1, design: best_design },
        main_effects,
        baseline,
        load_dimensionless: load,
        continuous,
        recommended,
        score_grids,
        evaluations,
        convergence: Convergence { iterations: evaluations as u32, residual: 0.0, tolerance: 0.0, termination: Termination::Converged },
    })
}

/// The candidate with the highest score, the earlier in (run, best levels, continuous,
/// baseline) on a tie.
fn recommend(best_run: usize, run: Design, best_levels: Design, continuous: Option<Design>, baseline: Design) -> Recommended {
    let mut r = Recommended { source: DesignSource::ArrayRun, run: Some(best_run), design: run };
    let others = [(DesignSource::BestLevels, Some(best_levels)), (DesignSource::Continuous, continuous), (DesignSource::Baseline, Some(baseline))];
    for (source, d) in others {
        if let Some(d) = d.filter(|d| d.score > r.design.score) {
            r = Recommended { source, run: None, design: d };
        }
    }
    r
}

/// The runs of the array on the array's normalisation.
fn runs(designs: &[Design], reference: &Reference, score: &dyn Fn(&Design) -> f64) -> Vec<Run> {
    designs
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
        .collect()
}

/// Mean score and S/N of every level of every factor.
fn main_effects(problem: &Problem, rows: &[[usize; 3]], levels: usize, runs: &[Run]) -> Vec<Effect> {
    let scores: Vec<f64> = runs.iter().map(|r| r.score).collect();
    let sn: Vec<f64> = runs.iter().map(|r| r.sn_ratio_db).collect();
    let mut main_effects = Vec::new();
    for (fi, name) in ["order", "height", "length_fraction"].iter().enumerate() {
        let ms = level_means(rows, fi, levels, &scores);
        let mn = level_means(rows, fi, levels, &sn);
        for l in 0..levels {
            let value = match fi {
                0 => problem.orders[l] as f64,
                1 => problem.heights[l],
                _ => problem.length_fractions[l],
            };
            main_effects.push(Effect { factor: name.to_string(), level: l + 1, value, mean_score: ms[l], mean_sn_ratio_db: mn[l] });
        }
    }
    main_effects
}

#[cfg(test)]
mod tests {
    use super::*;

    fn scored(order: u32, score: f64) -> Design {
        Design { order, height: 0.4, length_fraction: 0.2, max_pressure_dimensionless: 1.0, min_film_dimensionless: 0.1, friction_variable: 2.0, score, eccentricity_ratio: 0.6, max_pressure: None, min_film: None }
    }

    /// The recommendation is the highest score; a tie goes to the earlier candidate (run, best
    /// levels, continuous, baseline); without a search the run or the best levels.
    #[test]
    fn recommend_takes_the_best_and_ties_to_the_earlier() {
        let r = recommend(5, scored(2, 0.984), scored(2, 0.809), Some(scored(1, 1.011)), scored(0, 0.434));
        assert_eq!((r.source, r.run, r.design.score), (DesignSource::Continuous, None, 1.011));
        let r = recommend(5, scored(2, 0.984), scored(2, 0.809), None, scored(0, 0.434));
        assert_eq!((r.source, r.run), (DesignSource::ArrayRun, Some(5)));
        let r = recommend(5, scored(2, 0.984), scored(2, 0.984), Some(scored(2, 0.984)), scored(0, 0.2));
        assert_eq!(r.source, DesignSource::ArrayRun);
        let r = recommend(1, scored(2, 0.5), scored(2, 0.7), Some(scored(2, 0.6)), scored(0, 0.9));
        assert_eq!(r.source, DesignSource::Baseline);
    }
}
