//! Score maps over two factors (seed 002 Figs. 8–10: the paper's worksheet contour plots of the
//! weighted score against (n, ξ), (ξ, ψ) and (n, ψ)). The paper interpolates its nine runs;
//! here every cell is a bearing analysis on the problem's grid, the third factor held at its
//! best level, scored on the array's normalisation. The order axis takes the order levels; the
//! height and length-fraction axes `points` values evenly over their levels' range and the
//! levels themselves (so the best-level combination and the runs' levels are cells).

use super::*;
use rayon::prelude::*;

/// The three factors in the array's column order.
const FACTORS: [&str; 3] = ["order", "height", "length_fraction"];

/// The pairs drawn: Fig. 8 (n, ξ), Fig. 9 (ξ, ψ), Fig. 10 (n, ψ).
const PAIRS: [(usize, usize); 3] = [(0, 1), (1, 2), (0, 2)];

/// The values of factor `f` along a map's axis.
fn axis(problem: &Problem, f: usize, points: usize) -> Vec<f64> {
    let levels: Vec<f64> = match f {
        0 => {
            let mut o: Vec<u32> = problem.orders.clone();
            o.sort();
            o.dedup();
            return o.into_iter().map(f64::from).collect();
        }
        1 => problem.heights.clone(),
        _ => problem.length_fractions.clone(),
    };
    let lo = levels.iter().cloned().fold(f64::INFINITY, f64::min);
    let hi = levels.iter().cloned().fold(f64::NEG_INFINITY, f64::max);
    let n = points.max(2);
    let mut v: Vec<f64> = (0..n).map(|i| lo + (hi - lo) * i as f64 / (n - 1) as f64).chain(levels).collect();
    v.sort_by(f64::total_cmp);
    v.dedup_by(|a, b| (*a - *b).abs() <= 1e-12 * (hi - lo).abs().max(1e-300));
    v
}

/// The score maps of the three pairs; `best` holds the best level of each factor (0-based).
pub(super) fn score_grids(
    ev: &Evaluator,
    best: [usize; 3],
    points: usize,
    score: &(dyn Fn(&Design) -> f64 + Sync),
    observer: &dyn Observer,
) -> Result<(Vec<ScoreGrid>, usize), SolveError> {
    let pr = ev.problem;
    let held = [f64::from(pr.orders[best[0]]), pr.heights[best[1]], pr.length_fractions[best[2]]];
    let mut grids = Vec::with_capacity(PAIRS.len());
    let mut used = 0;
    for (a, b) in PAIRS {
        let (x, y) = (axis(pr, a, points), axis(pr, b, points));
        let cells: Vec<(usize, usize)> = (0..y.len()).flat_map(|j| (0..x.len()).map(move |i| (j, i))).collect();
        let scores: Vec<f64> = cells
            .par_iter()
            .map(|&(j, i)| -> Result<f64, SolveError> {
                observer.check()?;
                let mut v = held;
                v[a] = x[i];
                v[b] = y[j];
                let p = Profile { order: v[0].round() as u32, height: v[1], length_fraction: v[2] };
                let (d, _) = ev.design(&pr.settings, Some(p), None, observer)?;
                Ok(score(&d))
            })
            .collect::<Result<_, _>>()?;
        used += cells.len();
        let third = 3 - a - b;
        grids.push(ScoreGrid {
            x_factor: FACTORS[a],
            y_factor: FACTORS[b],
            x,
            y: y.clone(),
            score: scores.chunks(scores.len() / y.len()).map(<[f64]>::to_vec).collect(),
            held_factor: FACTORS[third],
            held_value: held[third],
        });
    }
    Ok((grids, used))
}
