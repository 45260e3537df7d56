//! The continuous search after the array: for each profile order (in parallel), a bounded
//! Nelder–Mead search over (ξ, ψ) on the array's score — on a grid with about half the nodes in
//! each direction and then a short polish on the problem's grid, or on the problem's grid
//! directly — and the best point analysed on the problem's grid.
//!
//! Each order starts from the best already analysed design of that order: its runs, the
//! confirmation of the best levels when it has that order, and the unprofiled baseline when
//! ξ = 0 lies inside the bounds (ξ = 0 is the baseline at any order and ψ). The point found is
//! kept only if it scores above that start on the problem's grid, so the search never ends
//! below the best of the array, the confirmation and (within the bounds) the baseline.

use super::*;
use crate::journal::taguchi::nelder_mead;
use rayon::prelude::*;

/// The best design per order of `search` (scored with `score`) and the bearing analyses spent.
pub(super) fn search(
    ev: &Evaluator,
    search: &ContinuousSearch,
    starts: &[Design],
    score: &(dyn Fn(&Design) -> f64 + Sync),
    observer: &dyn Observer,
) -> Result<(Vec<Design>, usize), SolveError> {
    let pr = ev.problem;
    let c = search;
    let hb = c.height.unwrap_or([pr.heights.iter().cloned().fold(f64::INFINITY, f64::min), pr.heights.iter().cloned().fold(0.0, f64::max)]);
    let pb = c.length_fraction.unwrap_or([
        pr.length_fractions.iter().cloned().fold(f64::INFINITY, f64::min),
        pr.length_fractions.iter().cloned().fold(0.0, f64::max),
    ]);
    let lo = [hb[0], pb[0].max(1e-3)];
    let hi = [hb[1].max(hb[0] + 1e-6), pb[1].max(pb[0].max(1e-3) + 1e-6)];
    let mut orders = pr.orders.clone();
    orders.sort();
    orders.dedup();
    let base = &pr.settings;
    let coarse = if c.coarse_search {
        let mut s = *base;
        s.circumferential = (base.circumferential / 2).max(17) | 1;
        s.axial = (base.axial / 2).max(9) | 1;
        s
    } else {
        *base
    };
    let per: Vec<(Design, usize)> = orders
        .par_iter()
        .map(|&n| -> Result<(Design, usize), SolveError> {
            // start from the best analysed design of this order (scored on the problem's grid);
            // the baseline is ξ = 0 at this order, when the bounds admit it
            let start_design = starts
                .iter()
                .filter_map(|d| match d.order {
                    0 if lo[0] <= 0.0 => Some(Design { order: n, height: 0.0, length_fraction: 0.5 * (lo[1] + hi[1]), ..*d }),
                    o if o == n => Some(*d),
                    _ => None,
                })
                .max_by(|a, b| score(a).total_cmp(&score(b)));
            let start = start_design.map_or([0.5 * (lo[0] + hi[0]), 0.5 * (lo[1] + hi[1])], |d| [d.height, d.length_fraction]);
            let mut used = 0;
            let objective = |settings: &Settings, ws: &mut Workspace, x: &[f64], used: &mut usize| -> Result<f64, SolveError> {
                observer.check()?;
                *used += 1;
                let p = Profile { order: n, height: x[0], length_fraction: x[1] };
                match ev.design(settings, Some(p), Some(ws), observer) {
                    Ok((d, _)) => Ok(-score(&d)),
                    Err(SolveError::Interrupted(i)) => Err(SolveError::Interrupted(i)),
                    Err(_) => Ok(f64::INFINITY),
                }
            };
            let step = [0.15 * (hi[0] - lo[0]), 0.15 * (hi[1] - lo[1])];
            let mut ws = Workspace::new(&pr.bearing, &coarse);
            let m = nelder_mead(|x| objective(&coarse, &mut ws, x, &mut used), &start, &step, &lo, &hi, c.evaluations_per_order, 1e-7)?;
            let mut x = m.x.clone();
            if c.coarse_search {
                let mut ws = Workspace::new(&pr.bearing, base);
                let small = [0.03 * (hi[0] - lo[0]), 0.03 * (hi[1] - lo[1])];
                let m2 = nelder_mead(|x| objective(base, &mut ws, x, &mut used), &x, &small, &lo, &hi, 15, 1e-8)?;
                x = m2.x;
            }
            let (mut d, _) = ev.design(base, Some(Profile { order: n, height: x[0], length_fraction: x[1] }), None, observer)?;
            used += 1;
            d.score = score(&d);
            // never below the start (the coarse grid's optimum can score lower on the fine one)
            if let Some(mut s) = start_design {
                s.score = score(&s);
                if s.score >= d.score {
                    d = s;
                }
            }
            Ok((d, used))
        })
        .collect::<Result<_, _>>()?;
    let used: usize = per.iter().map(|p| p.1).sum();
    let per_order: Vec<Design> = per.into_iter().map(|p| p.0).collect();
    Ok((per_order, used))
}
