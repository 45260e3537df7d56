//! Where a solve starts: the cold start, the nested iteration from coarse grids
//! ([`solve_levels`]) and the warm start from a neighbouring problem ([`warm_start`]).

use super::march::solve_level;
use super::newton::newton;
use super::*;

/// `H0` that puts the centre film at `target` and keeps the film positive.
pub(super) fn h0_for(prob: &mut Problem, p: &[f64], target: f64) -> f64 {
    let mut w = vec![0.0; p.len()];
    prob.defl.apply(p, &mut w);
    let rigid: Vec<f64> = (0..p.len()).map(|k| prob.geom[k] + w[k]).collect();
    let min_rigid = rigid.iter().cloned().fold(f64::INFINITY, f64::min);
    let at_centre = bilinear(&prob.x, &prob.y, &rigid, 0.0, 0.0);
    (target - at_centre).max(0.05 * target - min_rigid)
}

/// Cold start: the Hertzian (point) or slice-shaped (roller) pressure scaled to the load.
pub(super) fn cold(prob: &mut Problem, input: &Ehl2dInput, s: &Scales) -> (Vec<f64>, f64) {
    let (nx, ny) = (prob.nx, prob.ny);
    let mut p = vec![0.0; nx * ny];
    // Light loads spread the pressure over ~sqrt(2H) (as the 1-D cold start).
    let wide = 1f64.max((2.0 * s.h_est).sqrt());
    for &k in &prob.nodes {
        let (x, y) = (prob.x[k % nx] / wide, prob.y[k / nx]);
        p[k] = match input.geometry {
            Geometry2d::Point { .. } => (1.0 - x * x - (y / (s.ky * wide)).powi(2)).max(0.0).sqrt(),
            Geometry2d::Finite { .. } => (1.0 - x * x).max(0.0).sqrt() * slice_load(input, s, y),
        };
    }
    let sum: f64 = p.iter().sum::<f64>() * prob.dx * prob.dy;
    if sum > 0.0 {
        p.iter_mut().for_each(|v| *v *= prob.load / sum);
    }
    let h0 = h0_for(prob, &p, s.h_est);
    (p, h0)
}

/// The slice model's load per length at `Y` relative to the centre's (`physics::geometry::Crown::
/// distribute`: each slice carries `∝ (δ − g(y))₊`, the approach `δ` being the gap at the loaded
/// zone's edge): `1 − S(Y)/S(Y_loaded)`, uniform along a straight roller (the parabola
/// `1 − (Y/Y_loaded)²` of the crowned middle before, which loaded a straight roller's centre 1.5×
/// and left its ends unloaded: its films there started far below zero, issue 16).
/// Seed 000 eq. 3 as printed (a relieved centre, loaded zones at the transitions, not an interval
/// around the centre) takes `δ` from the slice model directly.
pub(super) fn slice_load(input: &Ehl2dInput, s: &Scales, y: f64) -> f64 {
    let printed = matches!(input.geometry, Geometry2d::Finite { crown, .. } if crown.loads_the_transitions());
    let delta = if printed { s.approach } else { side_gap(input, s, s.loaded.min(s.ky)) };
    let g = side_gap(input, s, y);
    if delta > 0.0 {
        (1.0 - g / delta).max(0.0)
    } else if g <= 0.0 {
        1.0
    } else {
        0.0
    }
}

/// The pressure of a coarser grid interpolated onto `prob`'s nodes, scaled to the load.
pub(super) fn prolong(prob: &Problem, cx: &[f64], cy: &[f64], cp: &[f64]) -> Vec<f64> {
    let (nx, ny) = (prob.nx, prob.ny);
    let mut p = vec![0.0; nx * ny];
    for &k in &prob.nodes {
        p[k] = bilinear(cx, cy, cp, prob.x[k % nx], prob.y[k / nx]);
    }
    let sum: f64 = p.iter().sum::<f64>() * prob.dx * prob.dy;
    if sum > 0.0 {
        p.iter_mut().for_each(|v| *v *= prob.load / sum);
    }
    p
}

/// A warm start's pressure on `prob`'s nodes (interpolated along a roller by the physical axial
/// position, elsewhere by `x/a`, `y/a`), scaled to the load; `None` when it carries no load.
pub(super) fn carried(prob: &Problem, s: &Scales, w: &Warm2d) -> Option<Vec<f64>> {
    let mut p = vec![0.0; prob.nx * prob.ny];
    let axial = if w.finite { s.a / w.a } else { 1.0 };
    for &k in &prob.nodes {
        p[k] = bilinear(&w.x, &w.y, &w.pressure, prob.x[k % prob.nx], prob.y[k / prob.nx] * axial).max(0.0);
    }
    let sum: f64 = p.iter().sum::<f64>() * prob.dx * prob.dy;
    (sum > 0.0).then(|| {
        p.iter_mut().for_each(|v| *v *= prob.load / sum);
        p
    })
}

/// Merit `Σ φ² ΔXΔY + G²` of the Newton iteration ([`newton`]'s line search) at `(p, h0)`.
pub(super) fn merit_at(prob: &mut Problem, p: &[f64], h0: f64) -> f64 {
    let mut v = Fields::default();
    if !prob.evaluate(p, h0, &mut v) {
        return f64::INFINITY;
    }
    let m = prob.nodes.len();
    let (mut active, mut c, mut phi) = (vec![FLUID; m], vec![0.0; m], Vec::with_capacity(m));
    // Without a factorisation nothing can be interrupted.
    let _ = prob.precondition(p, &v, &mut active, &mut c, false, &crate::Silent);
    prob.phi(p, &v, &c, &mut phi);
    dot(&phi, &phi) * prob.dx * prob.dy + v.g * v.g
}

/// Extrapolation ratios tried by [`warm_start`] besides 0 (the warm start alone).
pub(super) fn extrapolation_ratios() -> &'static [f64] {
    &EXTRAPOLATION
}

/// Ratios of the secant extrapolation along a chain of neighbouring problems ([`warm_start`]).
pub(super) const EXTRAPOLATION: [f64; 1] = [1.0];

/// The start of a warm solve: the warm start's pressure ([`carried`]) with `H0` putting the
/// central film at the warm start's central film times the change of the closed-form estimate;
/// with `prior` (the problem `w` itself was started from, e.g. the angle before the previous
/// one) also the secant extrapolation `P_w + r (P_w − P_prior)` (clipped at 0, scaled to the
/// load; the central film's ratio to the estimate extrapolated alike) for the ratios
/// [`extrapolation_ratios`] — along a cam cycle's uniform angle steps the previous step
/// repeated is `r = 1`. The candidate with the smallest Newton merit ([`merit_at`]) is taken.
pub(super) fn warm_start(prob: &mut Problem, s: &Scales, w: &Warm2d, prior: Option<&Warm2d>) -> Option<(Vec<f64>, f64)> {
    let p1 = carried(prob, s, w)?;
    let q1 = w.central / w.h_est;
    let h1 = h0_for(prob, &p1, q1 * s.h_est);
    let ratios = extrapolation_ratios();
    let Some(p0) = prior.filter(|_| !ratios.is_empty()).and_then(|w0| carried(prob, s, w0).map(|p| (p, w0.central / w0.h_est))) else {
        return Some((p1, h1));
    };
    let (p0, q0) = p0;
    let mut best = (merit_at(prob, &p1, h1), p1.clone(), h1, 0.0);
    for &r in ratios {
        let mut p: Vec<f64> = p1.iter().zip(&p0).map(|(a, b)| (a + r * (a - b)).max(0.0)).collect();
        let sum: f64 = p.iter().sum::<f64>() * prob.dx * prob.dy;
        let q = q1 + r * (q1 - q0);
        if !(sum > 0.0 && q > 0.0) {
            continue;
        }
        p.iter_mut().for_each(|v| *v *= prob.load / sum);
        let h0 = h0_for(prob, &p, q * s.h_est);
        let mr = merit_at(prob, &p, h0);
        if mr < best.0 {
            best = (mr, p, h0, r);
        }
    }
    Some((best.1, best.2))
}

/// The nested iteration up to `options`' grid: the finest problem, its pressure, `H0`, the Newton
/// steps and the final residual.
/// Also the central and minimum film (units of `a²/R_x`) and grid of the previous level, if any.
#[allow(clippy::type_complexity)]
pub(super) fn solve_levels(input: &Ehl2dInput, options: &Ehl2dOptions, s: &Scales, d: Domain, factors: Option<&Factors2d>, observer: &dyn Observer) -> Result<(Problem, Vec<f64>, f64, u32, f64, Option<(f64, f64, usize, usize)>), SolveError> {
    let s = s.clone();
    // Nested iteration: grids of (n − 1)/2^k + 1 nodes down to ≥ 17 per side, the coarsest
    // one that resolves the film: a grid whose spacing is not small against sqrt(H) carries a
    // deflection discretisation error (O(h²), cell-constant pressure) as large as the film, and
    // its discrete problem pinches the film to zero (measured: 25² at M ≈ 60 stalls, 49² converges
    // in 9 Newton steps; `BENCHMARKS.md`, issue 16).
    let spacing = |lx: usize, ly: usize| ((d.x_out - d.x_in) / (lx - 1) as f64).max((d.y_hi - d.y_lo) / (ly - 1) as f64);
    // The grid with half the intervals, if both node counts allow it and it keeps `MIN_LEVEL`.
    let half = |(lx, ly): (usize, usize)| {
        let (cx, cy) = ((lx - 1) / 2 + 1, (ly - 1) / 2 + 1);
        ((lx - 1) % 2 == 0 && (ly - 1) % 2 == 0 && cx >= MIN_LEVEL && cy >= MIN_LEVEL).then_some((cx, cy))
    };
    let mut levels = vec![(options.nx, options.ny)];
    while let Some((cx, cy)) = half(levels[levels.len() - 1]).filter(|&(cx, cy)| levels.len() < 4 && spacing(cx, cy).powi(2) <= RESOLVED * s.h_est) {
        levels.push((cx, cy));
    }
    levels.reverse();
    let tol = options.tolerance;
    let mut total = 0u32;
    let mut gmres_total = 0usize;
    // No coarse level passes the check, but the half grid resolves the film along x (cells long
    // across a long roller: only y fails): the cold start is tried on the finest grid for a few
    // Newton steps (at θ = 0, [`solve_level`]); if it does not converge, the solve goes through
    // that half grid instead. Measured (issue 16, ehl2d-13): the 129² long straight roller takes
    // 140 steps cold and 44 through 65² with the same films; the seed 000 nose on 65×129 converges
    // cold in 18–20 steps and takes 25–65 through its half grid, so it keeps the cold start.
    let mut trial: Option<(Problem, Vec<f64>, f64)> = None;
    if levels.len() == 1 {
        let (lx, ly) = levels[0];
        let along_x = |&(cx, _): &(usize, usize)| ((d.x_out - d.x_in) / (cx - 1) as f64).powi(2) <= RESOLVED * s.h_est;
        if let Some((cx, cy)) = half((lx, ly)).filter(along_x) {
            let mut prob = Problem::new(input, &s, d, lx, ly, options.near_field).with_thermal(factors, s.a, if input.entrainment_velocity >= 0.0 { 1.0 } else { -1.0 });
            let (mut p, mut h0) = cold(&mut prob, input, &s);
            prob.theta = 0.0;
            match newton(&mut prob, &mut p, &mut h0, tol, COLD_TRIAL.min(options.max_iterations), observer) {
                Ok(r) if r.converged => {
                    total += r.iterations;
                    trial = Some((prob, p, h0));
                }
                Ok(r) => {
                    total += r.iterations;
                    levels.insert(0, (cx, cy));
                }
                Err(e @ SolveError::Interrupted(_)) => return Err(e),
                Err(_) => levels.insert(0, (cx, cy)),
            }
        }
    }
    // Coarse solution: nodes, pressure and central film.
    let mut guess: Option<(Vec<f64>, Vec<f64>, Vec<f64>, f64)> = None;
    let mut coarse = None;
    let nlev = levels.len();
    // Progress: each level's share of the work (≈ nodes^1.4).
    let work: Vec<f64> = levels.iter().map(|&(lx, ly)| ((lx * ly) as f64).powf(1.4)).collect();
    let total_work: f64 = work.iter().sum::<f64>().max(1.0);
    for (li, &(lx, ly)) in levels.iter().enumerate() {
        let finest = li + 1 == nlev;
        let lo = work[..li].iter().sum::<f64>() / total_work;
        let name = format!("2-D EHL on {lx}×{ly}");
        let stage = crate::Stage::new(observer, 0.9 * lo, 0.9 * (lo + work[li] / total_work), 200.0, &name);
        let observer: &dyn Observer = &stage;
        let level_tol = if finest { tol } else { tol.max(1e-5) };
        let (mut prob, mut p, mut h0) = match trial.take() {
            // The cold start's θ = 0 solution from the trial above (the only level).
            Some(t) => t,
            None => {
                let mut prob = Problem::new(input, &s, d, lx, ly, options.near_field).with_thermal(factors, s.a, if input.entrainment_velocity >= 0.0 { 1.0 } else { -1.0 });
                let (p, h0) = match &guess {
                    // The coarse pressure, and `H0` that keeps the coarse central film (the coarse
                    // grid's `H0` carries its deflection discretisation error).
                    Some((gx, gy, gp, hc)) => {
                        let p = prolong(&prob, gx, gy, gp);
                        let h0 = h0_for(&mut prob, &p, *hc);
                        (p, h0)
                    }
                    None => cold(&mut prob, input, &s),
                };
                (prob, p, h0)
            }
        };
        let cap = if guess.is_some() { options.max_iterations.min(NESTED_ITER) } else { options.max_iterations };
        let dt0 = if guess.is_some() { DT_NESTED } else { DT_COLD };
        let run = solve_level(&mut prob, &mut p, &mut h0, level_tol, cap, options.max_iterations, dt0, false, observer)?;
        total += run.iterations;
        gmres_total += run.gmres;
        if finest {
            if !run.converged {
                let mut history = run.history;
                if history.len() > 20 {
                    history.drain(..history.len() - 20);
                }
                return Err(SolveError::NotConverged { solver: "ehl 2-D (pseudo-time Newton–Krylov)", iterations: total, residual: run.residual, tolerance: tol, history });
            }
            let _ = gmres_total;
            return Ok((prob, p, h0, total, run.residual, coarse));
        }
        let mut v = Fields::default();
        let hc = if prob.evaluate(&p, h0, &mut v) {
            let hc = bilinear(&prob.x, &prob.y, &v.h, 0.0, 0.0);
            coarse = Some((hc, v.h.iter().cloned().fold(f64::INFINITY, f64::min), lx, ly));
            hc
        } else {
            coarse = None;
            s.h_est
        };
        guess = Some((prob.x.clone(), prob.y.clone(), p, hc));
    }
    unreachable!("the finest level returns")
}
