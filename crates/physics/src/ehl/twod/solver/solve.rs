//! The entry points of a steady solve ([`solve`], [`solve_from`], [`solve_kept`]), the kept
//! preconditioner between solves ([`Kept2d`]) and the resolution checks of a converged problem
//! ([`conclude`]).

use super::finish::finish;
use super::levels::{solve_levels, warm_start};
use super::march::solve_level;
use super::near::NearPattern;
use super::precond::Precond;
use super::validate::validate;
use super::*;

/// Solve one 2-D EHL problem. Polls `observer` once per Newton step.
pub fn solve(input: &Ehl2dInput, options: &Ehl2dOptions, observer: &dyn Observer) -> Result<Ehl2dSolution, SolveError> {
    solve_from(input, options, None, observer).map(|(s, _)| s)
}

/// The Newton preconditioner (near-field LU) of the last solve on a grid, kept for the next
/// solve on the same grid (a cam cycle's next angle, [`solve_kept`]): an older Jacobian's factor
/// only changes how many GMRES iterations a Newton step takes, not what it converges to (the
/// operator applied is always the current one), so the solution moves only within the Newton
/// tolerance. Opaque; empty by default.
#[derive(Clone, Default)]
pub struct Kept2d {
    pc: Option<std::sync::Arc<Precond>>,
    /// The grid's sparsity pattern and symbolic LU (the same for every solve on the grid).
    pattern: Option<std::sync::Arc<NearPattern>>,
    nx: usize,
    ny: usize,
}

impl Kept2d {
    /// The factor when it was computed on an `nx × ny` grid.
    pub(super) fn take_for(&mut self, nx: usize, ny: usize) -> Option<std::sync::Arc<Precond>> {
        let pc = self.pc.take();
        pc.filter(|_| self.nx == nx && self.ny == ny)
    }

    /// The symbolic pattern when it was computed on an `nx × ny` grid.
    pub(super) fn pattern_for(&self, nx: usize, ny: usize) -> Option<std::sync::Arc<NearPattern>> {
        self.pattern.clone().filter(|_| self.nx == nx && self.ny == ny)
    }
}

impl std::fmt::Debug for Kept2d {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "Kept2d({}×{}, {})", self.nx, self.ny, if self.pc.is_some() { "factor" } else { "empty" })
    }
}

/// [`solve_from`] with `kept`'s preconditioner (when it is for this grid) used for the finest
/// grid's Newton steps until GMRES needs a fresh one; `kept` then holds the last factor of this
/// solve's finest grid. `prior`: the warm start `warm` was itself solved from (the point before
/// the previous one along a chain); the start is then the better, by the Newton merit, of `warm`
/// and the secant extrapolation through both (`warm_start`).
pub fn solve_kept(input: &Ehl2dInput, options: &Ehl2dOptions, warm: Option<&Warm2d>, prior: Option<&Warm2d>, kept: &mut Kept2d, observer: &dyn Observer) -> Result<(Ehl2dSolution, Warm2d), SolveError> {
    solve_inner(input, options, None, warm, prior, kept, observer)
}

/// [`solve_kept`] with the thermal model's generalized Reynolds multipliers `factors` (held
/// fixed; [`Factors2d`]) on every grid the solve uses, the resolution check's included. `None`
/// is [`solve_kept`] itself.
pub fn solve_factored(input: &Ehl2dInput, options: &Ehl2dOptions, factors: Option<&Factors2d>, warm: Option<&Warm2d>, kept: &mut Kept2d, observer: &dyn Observer) -> Result<(Ehl2dSolution, Warm2d), SolveError> {
    solve_inner(input, options, factors, warm, None, kept, observer)
}

/// Solve one 2-D EHL problem starting from `warm` (a neighbouring problem's converged solution,
/// e.g. the previous cam angle's) when given: its dimensionless pressure is interpolated onto this
/// problem's grid in the new Hertzian scales (along a roller by the physical axial position, the
/// crown being fixed in space; elsewhere by `x/a`, `y/a`) and scaled to the load, and `H0` is set
/// so that the central film is the warm start's central film times the change of the closed-form
/// estimate. Newton then runs on the finest grid directly (geometric face means; the continuation
/// from the arithmetic means when that fails); when the warm start fails altogether the cold nested
/// iteration runs. Returns the solution and its own warm start for the next problem. The
/// resolution check runs as in [`solve`] (with a warm start: always a check solve on the grid with
/// half the intervals, unless `options.grid_check` is off).
pub fn solve_from(input: &Ehl2dInput, options: &Ehl2dOptions, warm: Option<&Warm2d>, observer: &dyn Observer) -> Result<(Ehl2dSolution, Warm2d), SolveError> {
    solve_inner(input, options, None, warm, None, &mut Kept2d::default(), observer)
}

fn solve_inner(input: &Ehl2dInput, options: &Ehl2dOptions, factors: Option<&Factors2d>, warm: Option<&Warm2d>, prior: Option<&Warm2d>, kept: &mut Kept2d, observer: &dyn Observer) -> Result<(Ehl2dSolution, Warm2d), SolveError> {
    validate(input, options)?;
    let mut kept_pc = kept.take_for(options.nx, options.ny);
    let kept_pattern = kept.pattern_for(options.nx, options.ny);
    let s = scales(input)?;
    let d = domain(input, options, &s);
    let finite = matches!(input.geometry, Geometry2d::Finite { .. });
    let mut warm_run = None;
    let mut failed_steps = 0;
    if let Some(w) = warm.filter(|w| w.finite == finite && w.central > 0.0 && w.h_est > 0.0) {
        let mut prob = Problem::new(input, &s, d, options.nx, options.ny, options.near_field).with_thermal(factors, s.a, frame_sign(input));
        prob.kept = kept_pc.take();
        prob.pattern = std::cell::RefCell::new(kept_pattern.clone());
        prob.forcing = warm_forcing();
        if let Some((mut p, mut h0)) = warm_start(&mut prob, &s, w, prior.filter(|w0| w0.finite == finite && w0.central > 0.0 && w0.h_est > 0.0)) {
            let run = solve_level(&mut prob, &mut p, &mut h0, options.tolerance, options.max_iterations.min(NESTED_ITER), options.max_iterations, DT_NESTED, true, observer)?;
            if run.converged {
                warm_run = Some((prob, p, h0, run.iterations, run.residual));
            } else {
                failed_steps = run.iterations;
            }
        }
    }
    let solved = match warm_run {
        Some((prob, p, h0, iterations, residual)) => Solved { prob, p, h0, iterations, residual, coarse: None, warm_used: true },
        None => {
            let (prob, p, h0, its, residual, coarse) = solve_levels(input, options, &s, d, factors, observer)?;
            Solved { prob, p, h0, iterations: its + failed_steps, residual, coarse, warm_used: false }
        }
    };
    conclude(input, options, &s, d, solved, kept, kept_pattern, factors, observer)
}

/// A converged problem on the finest grid: its pressure, `H0`, the Newton steps and the final
/// residual, the previous level's films ([`solve_levels`]) and whether a warm start was used.
pub(super) struct Solved {
    pub(super) prob: Problem,
    pub(super) p: Vec<f64>,
    pub(super) h0: f64,
    pub(super) iterations: u32,
    pub(super) residual: f64,
    pub(super) coarse: Option<(f64, f64, usize, usize)>,
    pub(super) warm_used: bool,
}

/// The solution and warm start of a converged problem, after the resolution check (the pinch
/// and, unless the nested iteration measured it or `options.grid_check` is off after a warm
/// start, the check solve on the grid with half the intervals — of the same problem, a transient
/// step's squeeze term included); `kept` takes the problem's preconditioner.
#[allow(clippy::too_many_arguments)]
pub(super) fn conclude(input: &Ehl2dInput, options: &Ehl2dOptions, s: &Scales, d: Domain, solved: Solved, kept: &mut Kept2d, kept_pattern: Option<std::sync::Arc<NearPattern>>, factors: Option<&Factors2d>, observer: &dyn Observer) -> Result<(Ehl2dSolution, Warm2d), SolveError> {
    let Solved { mut prob, p, h0, iterations: total, residual, coarse, warm_used } = solved;
    let finite = matches!(input.geometry, Geometry2d::Finite { .. });
    let pattern = prob.pattern.borrow().clone().or(kept_pattern);
    *kept = Kept2d { pc: prob.kept.take().filter(|_| reuse_policy().2), pattern, nx: prob.nx, ny: prob.ny };
    let mut sol = finish(input, options, s, &mut prob, &p, h0, total, residual)?;
    sol.warm_started = warm_used;
    let next = {
        let mut v = Fields::default();
        let film_scale = s.a * s.a / s.rx;
        let (hc, mass) = if prob.evaluate(&p, h0, &mut v) {
            (bilinear(&prob.x, &prob.y, &v.h, 0.0, 0.0), v.rho.iter().zip(&v.h).map(|(r, h)| r * h * film_scale).collect())
        } else {
            (sol.central_film / film_scale, Vec::new())
        };
        Warm2d { x: prob.x.clone(), y: prob.y.clone(), pressure: p.clone(), a: s.a, central: hc, h_est: s.h_est, finite, mass, sign: frame_sign(input) }
    };
    let unresolved = |what: String| SolveError::invalid("Ehl2dOptions.nx", format!("the {}×{} grid does not resolve the film: {what}; refine the grid (nx, ny)", prob.nx, prob.ny));
    // A film pinched at a node is the discrete problem's, not the contact's (seed-free check:
    // smooth EHL films keep h_min/h_c ≳ 0.3).
    if sol.min_film.value < PINCH * sol.central_film {
        return Err(unresolved(format!("the film pinches to {:.1} % of the central film at x = {:.3e} m, y = {:.3e} m", 100.0 * sol.min_film.value / sol.central_film, sol.min_film.x, sol.min_film.y)));
    }
    let coarse = match coarse {
        Some(c) => Some(c),
        None if options.grid_check || !warm_used => check_half(s, d, input, options, &p, h0, prob.target.as_ref(), factors, observer)?,
        None => None,
    };
    if let Some((hc, hm, cnx, cny)) = coarse {
        let film_scale = s.a * s.a / s.rx;
        let (dc, dm) = ((hc * film_scale / sol.central_film - 1.0).abs(), (hm * film_scale / sol.min_film.value - 1.0).abs());
        // The minimum film sits in the exit constriction, a few cells wide on a coarse grid: its
        // change is allowed three times the tolerance (measured on the circular M ≈ 300 contact:
        // 33² → 65² moves h_min by 9.7 % while 65² is within 0.4 % of 257²).
        sol.grid_error = Some(dc);
        if dc > options.grid_tolerance || dm > 3.0 * options.grid_tolerance {
            return Err(unresolved(format!(
                "the central film changes by {:.1} % and the minimum film by {:.1} % from the {cnx}×{cny} grid (grid tolerance {:.1} %, three times that for the minimum film)",
                100.0 * dc,
                100.0 * dm,
                100.0 * options.grid_tolerance
            )));
        }
    }
    Ok((sol, next))
}

/// The solver frame's orientation: `+1` when `u_m ≥ 0`, else `−1` (the inlet is always at
/// negative `X`; physical `x = sign·X·a`).
pub(in crate::ehl::twod) fn frame_sign(input: &Ehl2dInput) -> f64 {
    if input.entrainment_velocity >= 0.0 {
        1.0
    } else {
        -1.0
    }
}

/// Central and minimum film (units of `a²/R_x`) and grid of a check solve on the grid with half
/// the intervals, started from the injected solution; `None` when that grid has fewer than 9
/// nodes per side, the node counts are even, or Newton does not converge there.
#[allow(clippy::too_many_arguments)]
pub(super) fn check_half(s: &Scales, d: Domain, input: &Ehl2dInput, options: &Ehl2dOptions, p: &[f64], h0: f64, target: Option<&(f64, Vec<f64>)>, factors: Option<&Factors2d>, observer: &dyn Observer) -> Result<Option<(f64, f64, usize, usize)>, SolveError> {
    let (nx, ny) = (options.nx, options.ny);
    if (nx - 1) % 2 != 0 || (ny - 1) % 2 != 0 || (nx - 1) / 2 + 1 < 9 || (ny - 1) / 2 + 1 < 9 {
        return Ok(None);
    }
    let (cx, cy) = ((nx - 1) / 2 + 1, (ny - 1) / 2 + 1);
    let mut prob = Problem::new(input, s, d, cx, cy, options.near_field).with_thermal(factors, s.a, frame_sign(input));
    let inject = |f: &[f64]| -> Vec<f64> { (0..cx * cy).map(|k| f[(k / cx) * 2 * nx + (k % cx) * 2]).collect() };
    let mut pc = inject(p);
    // A transient step's squeeze term, at the coinciding nodes.
    if let Some((kappa, q)) = target {
        prob.target = Some((*kappa, inject(q)));
        prob.restore_target();
    }
    let mut h0c = h0;
    let run = solve_level(&mut prob, &mut pc, &mut h0c, options.tolerance.max(1e-6), options.max_iterations.min(NESTED_ITER), options.max_iterations, DT_NESTED, true, observer)?;
    let mut v = Fields::default();
    if !run.converged || !prob.evaluate(&pc, h0c, &mut v) {
        return Ok(None);
    }
    let hmin = v.h.iter().cloned().fold(f64::INFINITY, f64::min);
    Ok(Some((bilinear(&prob.x, &prob.y, &v.h, 0.0, 0.0), hmin, cx, cy)))
}
