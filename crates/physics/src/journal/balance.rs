//! The load balance of one analysis: the journal position (ε, β) whose film force carries the
//! load — a coarse scan, then Newton on nested grids, or the attitude search at a given ε.

use super::problem::*;
use super::film::wrap_angle;
use super::multigrid::{Hierarchy, LcpReport};
use crate::numerics::newton::backtrack;
use crate::{Convergence, Observer, SolveError, Termination};
use std::f64::consts::{PI, TAU};

pub(super) struct Eval {
    pub(super) fv: f64,
    pub(super) fh: f64,
    pub(super) rep: LcpReport,
}

pub(super) struct BalanceSearch<'a> {
    pub(super) bearing: &'a Bearing,
    pub(super) settings: &'a Settings,
    pub(super) h: &'a mut Hierarchy,
    /// Coarse grids serve only as starting guesses (no load balance): solve them loosely.
    pub(super) coarse_loose: bool,
    /// The grid on which the position search starts (finite-difference Jacobians are taken
    /// there; the grids between it and the finest are reached by Broyden/secant updates).
    pub(super) start_level: usize,
    /// Warm solves keep the coarser levels' coefficients of a position within 1e-3 (in `X`,
    /// `Y`, and the angle of node 0) as the preconditioner instead of rebuilding them
    /// ([`Hierarchy::set_film_near`]); the load balances set it, the fixed-eccentricity and
    /// fixed-position analyses do not (the roller–pin tables of the cam kinds are built on them).
    pub(super) reuse_coarse: bool,
}

impl BalanceSearch<'_> {
    pub(super) fn feasible(&self, eps: f64, beta: f64) -> bool {
        eps >= 0.0 && self.bearing.film(eps, beta).min_film().0 > self.settings.min_film
    }

    /// Pressure tolerance on level `k`: the requested one on the finest grid; coarser grids only
    /// start the next grid (and, in a load balance, steer it), so they stop earlier.
    pub(super) fn tol_at(&self, k: usize) -> f64 {
        if k == 0 {
            self.settings.pressure_tolerance
        } else if self.coarse_loose {
            self.settings.pressure_tolerance.max(1e-5)
        } else if k < self.start_level {
            // between the start grid and the finest: only steers the next grid's start, and no
            // difference Jacobian is taken here
            self.settings.pressure_tolerance.max(1e-6)
        } else {
            self.settings.pressure_tolerance.max(1e-7)
        }
    }

    /// Pressure solve on level `k` at the position, warm-started from the level's current pressure.
    pub(super) fn eval(&mut self, k: usize, eps: f64, beta: f64, cold: bool) -> Result<Eval, SolveError> {
        let tol = self.tol_at(k);
        self.eval_tol(k, eps, beta, cold, tol)
    }

    /// [`BalanceSearch::eval`] with an explicit pressure tolerance (inexact Newton steps).
    pub(super) fn eval_tol(&mut self, k: usize, eps: f64, beta: f64, cold: bool, tol: f64) -> Result<Eval, SolveError> {
        let film = self.bearing.film(eps, beta);
        let (_, theta0) = self.bearing.groove_angle(beta);
        if cold || !self.reuse_coarse {
            self.h.set_film_from(k, &film, theta0);
        } else {
            // the coarse levels only precondition the solve on level `k`: a nearby position's
            // operators do (misaligned 361×181: 1 % fewer instructions, the same V-cycles)
            self.h.set_film_near(k, &film, theta0, 1e-3);
        }
        let rep = if cold {
            self.h.nested_solve(k, tol, 60, self.settings.max_cycles)
        } else {
            self.h.solve_lcp(k, tol, 60, self.settings.max_cycles)
        };
        if !rep.converged {
            return Err(SolveError::NotConverged {
                solver: "journal pressure (active set + multigrid CG)",
                iterations: rep.cycles,
                residual: rep.residual,
                tolerance: tol,
                history: vec![rep.residual],
            });
        }
        let l = &self.h.levels[k];
        let (mut fv, mut fh) = (0.0, 0.0);
        // a mirrored half (rows up to the mid-plane `m = nz − 2`, a ghost row above it): the
        // rows below the mid-plane count twice (their mirror images), the mid-plane once
        let last = if l.mirror { l.nz - 2 } else { l.nz - 1 };
        for j in 1..last {
            let row = &l.u[j * l.nt..(j + 1) * l.nt];
            for i in 0..l.nt {
                fv += row[i] * l.cos_n[i];
                fh += row[i] * l.sin_n[i];
            }
        }
        if l.mirror {
            let row = &l.u[last * l.nt..(last + 1) * l.nt];
            let (mut mv, mut mh) = (0.0, 0.0);
            for i in 0..l.nt {
                mv += row[i] * l.cos_n[i];
                mh += row[i] * l.sin_n[i];
            }
            fv = 2.0 * fv + mv;
            fh = 2.0 * fh + mh;
        }
        let s = l.dt * l.dz;
        // seed 002 eq. (6)-(7): film force components on the journal
        Ok(Eval { fv: fv * s, fh: fh * s, rep })
    }
}

/// Relative load error on the first grid above the start grid (at the position carried from the
/// start grid) above which that grid takes a fresh difference Jacobian before its Newton step
/// ([`load_balance`]). L9 at 361×181 (91×46 grid): the cases with one finest Newton step show
/// 5.1e-4 … 6.7e-4 there (the seed case 5.1e-4), the six with two or three 3.3e-3 … 9.5e-3;
/// with the fresh Jacobian the nine cases take 105 finest V-cycles instead of 115 and 4 % fewer
/// instructions, the cases below the threshold are untouched (BENCHMARKS.md, speed tenth round).
const FRESH_JACOBIAN_ABOVE: f64 = 1e-3;

/// Residual of the load balance: (ln(|F|/W), angle of F from the required direction).
pub(super) fn load_residual(e: &Eval, w: f64) -> [f64; 2] {
    let mag = e.fv.hypot(e.fh);
    let ang = wrap_pm(e.fh.atan2(e.fv) - PI);
    [if mag > 0.0 { (mag / w).ln() } else { -50.0 }, ang]
}

pub(super) fn relative_load_error(e: &Eval, w: f64) -> f64 {
    (e.fv + w).hypot(e.fh) / w
}

pub(super) fn wrap_pm(a: f64) -> f64 {
    let w = wrap_angle(a + PI) - PI;
    if w <= -PI { w + TAU } else { w }
}

pub(super) fn no_attitude(eps: f64) -> SolveError {
    SolveError::physical(
        crate::PhysicalFailure::NoEquilibriumAttitude,
        format!("with this misalignment no attitude angle puts the film force on the load line at eccentricity ratio {eps}"),
    )
}

pub(super) fn film_closed(settings: &Settings) -> SolveError {
    SolveError::physical(
        crate::PhysicalFailure::FilmClosed,
        format!(
            "the journal would touch the bearing: no position with a film above h/c = {} carries this load with this misalignment",
            settings.min_film
        ),
    )
}

/// Short-bearing (Ocvirk) estimate of the eccentricity ratio that carries `w`, corrected for
/// L/D; only a starting point.
pub(super) fn initial_eccentricity(w: f64, ld: f64) -> f64 {
    // Ocvirk: W̄ = (L/D)² ε/(1−ε²)² · π/4·sqrt(π²(1−ε²)+16ε²)/... in seed-002 scaling ≈
    // W̄ ≈ (L/D)²/6 · ε π sqrt(1 − ε² + (16/π²) ε²) / (1−ε²)² ; solved by bisection.
    let f = |e: f64| {
        let g = (ld * ld).min(1.0) / 6.0 * e * PI * (1.0 - e * e + 16.0 / (PI * PI) * e * e).sqrt() / (1.0 - e * e).powi(2);
        g - w
    };
    let (mut a, mut b) = (1e-6, 0.98);
    if f(b) < 0.0 {
        return 0.9;
    }
    if f(a) > 0.0 {
        return 1e-4;
    }
    for _ in 0..60 {
        let m = 0.5 * (a + b);
        if f(m) > 0.0 { b = m } else { a = m }
    }
    (0.5 * (a + b)).clamp(1e-4, 0.95)
}

/// A rough attitude angle for `ε` (between the long- and short-bearing curves).
pub(super) fn initial_attitude(e: f64) -> f64 {
    let e = e.clamp(0.0, 0.999);
    (PI / 4.0 * (1.0 - e * e).sqrt() / e.max(1e-9)).atan()
}

#[allow(clippy::too_many_arguments)]
pub(super) fn attitude_search(
    p: &mut BalanceSearch,
    k: usize,
    eps: f64,
    beta: &mut f64,
    cold: bool,
    tol: f64,
    cap: u32,
    observer: &dyn Observer,
) -> Result<(Eval, Convergence, u32), SolveError> {
    let mut ev = p.eval(k, eps, *beta, cold)?;
    let resid = |e: &Eval| {
        let m = e.fv.hypot(e.fh);
        if m > 0.0 { wrap_pm(e.fh.atan2(e.fv) - PI) } else { 0.0 }
    };
    let mut r = resid(&ev);
    let mut it = 0;
    let mut history = vec![r.abs()];
    if eps == 0.0 {
        return Ok((ev, Convergence { iterations: 0, residual: 0.0, tolerance: tol, termination: Termination::Converged }, 0));
    }
    if p.bearing.rotation_invariant() {
        // aligned film, supply following the journal or none: turning the journal turns the
        // pressure field and the force rigidly, so one exact step puts the force on the load line
        let mag = ev.fv.hypot(ev.fh);
        *beta = wrap_pm(*beta - r);
        ev.fv = -mag;
        ev.fh = 0.0;
        return Ok((ev, Convergence { iterations: 1, residual: 0.0, tolerance: tol, termination: Termination::Converged }, 1));
    }
    let mut scanned = false;
    let mut slope = 1.0f64;
    while r.abs() > tol {
        observer.check()?;
        if it >= cap {
            return Err(SolveError::NotConverged { solver: "journal attitude search", iterations: it, residual: r.abs(), tolerance: tol, history });
        }
        it += 1;
        // Newton on the force angle with a secant slope: the force turns with the journal,
        // d(angle)/dβ = 1 exactly without misalignment and with a groove that follows the
        // journal, otherwise the slope is learnt from the steps taken.
        // The step halved (at most 30 times) until the angle's residual falls.
        let taken = backtrack::<_, SolveError>((-r / slope).clamp(-1.0, 1.0), 30, |step| {
            let b = *beta + step;
            if !p.feasible(eps, b) {
                return Ok(None);
            }
            let e2 = p.eval(k, eps, b, false)?;
            let r2 = resid(&e2);
            Ok((r2.abs() < r.abs()).then_some((b, e2, r2)))
        })?;
        let accepted = taken.is_some();
        if let Some((b, e2, r2)) = taken {
            let s_new = (r2 - r) / (b - *beta);
            if s_new.is_finite() && s_new.abs() > 1e-3 {
                slope = s_new;
            }
            *beta = b;
            ev = e2;
            r = r2;
        }
        history.push(r.abs());
        if !accepted {
            if scanned {
                return Err(no_attitude(eps));
            }
            // misalignment can make the force angle a non-monotone function of β: scan the
            // circle for a sign change of the residual and bisect it
            scanned = true;
            let n = 72;
            let mut prev: Option<(f64, f64)> = None;
            let mut bracket = None;
            for m in 0..=n {
                let b = m as f64 * TAU / n as f64;
                if !p.feasible(eps, b) {
                    prev = None;
                    continue;
                }
                let e2 = p.eval(k, eps, b, false)?;
                let r2 = resid(&e2);
                if let Some((b0, r0)) = prev {
                    if r0 * r2 <= 0.0 && (r0 - r2).abs() < PI {
                        bracket = Some((b0, r0, b));
                        break;
                    }
                }
                prev = Some((b, r2));
            }
            let (mut a, ra, mut b) = bracket.ok_or_else(|| no_attitude(eps))?;
            for _ in 0..60 {
                let m = 0.5 * (a + b);
                let e2 = p.eval(k, eps, m, false)?;
                let rm = resid(&e2);
                ev = e2;
                r = rm;
                *beta = m;
                if rm.abs() <= tol {
                    break;
                }
                if (rm > 0.0) == (ra > 0.0) { a = m } else { b = m }
            }
            history.push(r.abs());
            if r.abs() > tol {
                return Err(no_attitude(eps));
            }
        }
    }
    *beta = wrap_pm(*beta);
    Ok((ev, Convergence { iterations: it, residual: r.abs(), tolerance: tol, termination: Termination::Converged }, it))
}

/// The two-dimensional load balance on level `k`: Newton in (ε, β) with a difference Jacobian
/// (carried in `jac`, Broyden-updated), damped by step halving ([`damped_step`]). With
/// `predict_only` and a carried Jacobian, one step only ([`predict_next_start`]).
///
/// Inexact Newton: trial pressures are solved to a tolerance tied to the load error, the
/// accepted point is then re-solved to the full tolerance before convergence is declared.
///
/// Stagnation guard: a light load on a strongly misaligned journal is the small difference of
/// large opposing forces (the tilt's pressure peaks at the two edges), so the pressure
/// tolerance, relative to the pressure field, can leave a load error above `tol` relative to
/// the load. When the error stops falling, tighten the pressure tolerance (to 1e-12 at most)
/// and rebuild the Jacobian. (Proptest case: L/D 1.59, W = 0.0017, vertical tilt 0.74.)
#[allow(clippy::too_many_arguments)]
pub(super) fn load_balance(
    p: &mut BalanceSearch,
    k: usize,
    w: f64,
    eps: &mut f64,
    beta: &mut f64,
    jac: &mut Option<[[f64; 2]; 2]>,
    cold: bool,
    predict_only: bool,
    tol: f64,
    cap: u32,
    observer: &dyn Observer,
) -> Result<(Eval, Convergence, u32), SolveError> {
    let mut full = p.tol_at(k);
    // a grid that only predicts the next one's start (below) solves to 1e-4: its one Newton step
    // steers the finest grid's start as well as from 1e-5 (misaligned 361×181: the same finest
    // V-cycles, 2 % fewer instructions; BENCHMARKS.md, speed fifth round)
    let t0 = if predict_only && jac.is_some() { full.max(1e-4) } else { inexact_tolerance(1e-2, full) };
    let mut ev = p.eval_tol(k, *eps, *beta, cold, if cold { full } else { t0 })?;
    let mut exact = cold || t0 <= full;
    let mut r = load_residual(&ev, w);
    let mut err = relative_load_error(&ev, w);
    if predict_only && let Some(j) = jac.as_mut() {
        return predict_next_start(p, k, w, eps, beta, j, (ev, r, err), full, tol);
    }
    let mut history = vec![err];
    let mut it = 0;
    let mut blocked = 0;
    // the stagnation guard's best error and the steps since
    let mut best = err;
    let mut stalled = 0;
    let mut last = LastStep::default();
    loop {
        if err < 0.5 * best {
            best = err;
            stalled = 0;
        } else {
            stalled += 1;
        }
        if stalled >= 4 && err < 1e-3 && full > 1e-12 && err > tol {
            full = (full * 1e-2).max(1e-12);
            stalled = 0;
            (ev, r, err) = resolve(p, k, w, *eps, *beta, full)?;
            exact = true;
            best = err;
            *jac = Some(fd_jacobian(p, k, w, *eps, *beta, &r)?);
            continue;
        }
        if err <= tol {
            if exact {
                break;
            }
            (ev, r, err) = resolve(p, k, w, *eps, *beta, full)?;
            exact = true;
            continue;
        }
        observer.check()?;
        if it >= cap {
            return Err(balance_failure(p, *eps, *beta, &r, it, err, tol, history));
        }
        it += 1;
        if jac.is_none() {
            *jac = Some(fd_jacobian(p, k, w, *eps, *beta, &r)?);
        }
        let j = jac.unwrap();
        let (de, db) = newton_step(&j, &r, *eps);
        last.keep_base(&p.h.levels[k].u);
        // near convergence the trial is likely the answer: solve it fully at once
        let t_p = if err < 1e3 * tol { full } else { inexact_tolerance(err, full) };
        let mut seen = Trials::default();
        let taken = damped_step(p, k, w, (*eps, *beta), (de, db), r[0].hypot(r[1]), t_p, last.last(), &mut seen)?;
        if seen.evaluated {
            exact = t_p <= full;
        }
        let accepted = taken.is_some();
        if let Some((e1, b1, ev1, r1)) = taken {
            // Broyden update of the Jacobian with the step actually taken
            if let Some(jn) = broyden_update(&j, [e1 - *eps, b1 - *beta], [r1[0] - r[0], r1[1] - r[1]]) {
                *jac = Some(jn);
            }
            last.accepted_from((*eps, *beta));
            *eps = e1;
            *beta = b1;
            ev = ev1;
            r = r1;
        }
        err = relative_load_error(&ev, w);
        history.push(err);
        if !accepted {
            if seen.infeasible && r[0] < 0.0 {
                return Err(film_closed(p.settings));
            }
            // a stale Jacobian: rebuild it once before giving up
            blocked += 1;
            if blocked > 2 {
                return Err(balance_failure(p, *eps, *beta, &r, it, err, tol, history));
            }
            *jac = Some(fd_jacobian(p, k, w, *eps, *beta, &r)?);
            ev = p.eval(k, *eps, *beta, false)?;
        }
    }
    *beta = wrap_pm(*beta);
    Ok((ev, Convergence { iterations: it, residual: err, tolerance: tol, termination: Termination::Converged }, it))
}

/// A pressure solve at a position with its load residual and relative load error.
type Solved = (Eval, [f64; 2], f64);

/// The pressure tolerance of an inexact Newton trial at the relative load error `err`: 1e-3 of
/// it, within `full` (the level's tolerance) and `max(full, 1e-5)`.
fn inexact_tolerance(err: f64, full: f64) -> f64 {
    (1e-3 * err).clamp(full, full.max(1e-5))
}

/// The pressure on level `k` at `(eps, beta)` solved (warm) to `tol`, with its load residual and
/// relative load error.
fn resolve(p: &mut BalanceSearch, k: usize, w: f64, eps: f64, beta: f64, tol: f64) -> Result<Solved, SolveError> {
    let ev = p.eval_tol(k, eps, beta, false, tol)?;
    let r = load_residual(&ev, w);
    let err = relative_load_error(&ev, w);
    Ok((ev, r, err))
}

/// [`load_balance`] on a grid between the start grid and the finest: one pressure solve at the
/// coarser grid's equilibrium (`at`) and one Newton step with the carried Jacobian `jac` give the
/// next grid its start (its own equilibrium is not needed).
#[allow(clippy::too_many_arguments)]
fn predict_next_start(
    p: &mut BalanceSearch,
    k: usize,
    w: f64,
    eps: &mut f64,
    beta: &mut f64,
    jac: &mut [[f64; 2]; 2],
    at: Solved,
    full: f64,
    tol: f64,
) -> Result<(Eval, Convergence, u32), SolveError> {
    let (mut ev, mut r, mut err) = at;
    if k + 1 == p.start_level && err > FRESH_JACOBIAN_ABOVE {
        // the first grid above the start grid finds the load off by more than 1e-3 at the
        // carried position: the carried Jacobian (the start grid's differences) is stale for
        // this film, and with it the finest grid would need two or three Newton steps.
        // Re-solve here to this grid's tolerance and take fresh difference columns first.
        (ev, r, err) = resolve(p, k, w, *eps, *beta, full)?;
        *jac = fd_jacobian(p, k, w, *eps, *beta, &r)?;
    }
    let (de, db) = newton_step(jac, &r, *eps);
    if *eps + de > 0.0 && p.feasible(*eps + de, *beta + db) {
        *eps += de;
        *beta = wrap_pm(*beta + db);
    }
    Ok((ev, Convergence { iterations: 0, residual: err, tolerance: tol, termination: Termination::Converged }, 0))
}

/// The accepted point of [`load_balance`] before the current one, its position and pressure: the
/// next full Newton trial starts from the current pressure extrapolated along the last step
/// ([`damped_step`]). `base` keeps the current pressure while a step is tried.
#[derive(Default)]
struct LastStep {
    at: Option<(f64, f64)>,
    pressure: Vec<f64>,
    base: Vec<f64>,
}

impl LastStep {
    /// Keep the current pressure `u` before a step is tried.
    fn keep_base(&mut self, u: &[f64]) {
        self.base.clear();
        self.base.extend_from_slice(u);
    }

    /// The previous accepted position and its pressure, if any.
    fn last(&self) -> Option<((f64, f64), &[f64])> {
        self.at.map(|at| (at, self.pressure.as_slice()))
    }

    /// A step from `at` was accepted: `at` and its kept pressure become the last step.
    fn accepted_from(&mut self, at: (f64, f64)) {
        std::mem::swap(&mut self.pressure, &mut self.base);
        self.at = Some(at);
    }
}

/// A trial [`damped_step`] accepted: the position `(ε, β)`, its pressure solve and load residual.
type Trial = (f64, f64, Eval, [f64; 2]);

/// What the trials of a [`damped_step`] met: whether any was solved, whether any was infeasible.
#[derive(Default)]
struct Trials {
    evaluated: bool,
    infeasible: bool,
}

/// The damped Newton step of [`load_balance`] from `from = (ε, β)` along `step = (Δε, Δβ)`: the
/// step halved (at most 40 times) until a feasible trial's load residual norm falls below `norm0`
/// (or the step is below 1e-3 of the full one), each trial's pressure solved to `t_p`. The full
/// step starts from the current pressure extrapolated along the last step (`last`: the previous
/// accepted position and its pressure): the steps of a converging Newton iteration are nearly
/// collinear, so `P(x + δ) ≈ P(x) + s (P(x) − P(x_prev))` with `s` the new step projected on the
/// last one, a start closer to the trial's solution than the current pressure alone (L9 at
/// 361×181: V-cycles on the finest grid −4 %, on the 46×24 start grid −4 %; BENCHMARKS.md, speed
/// sixth round; results move at the tolerances). Returns the accepted position, its pressure solve
/// and load residual.
#[allow(clippy::too_many_arguments)]
fn damped_step(
    p: &mut BalanceSearch,
    k: usize,
    w: f64,
    (eps, beta): (f64, f64),
    (de, db): (f64, f64),
    norm0: f64,
    t_p: f64,
    last: Option<((f64, f64), &[f64])>,
    seen: &mut Trials,
) -> Result<Option<Trial>, SolveError> {
    backtrack(1.0, 40, |t| {
        let (e1, b1) = (eps + t * de, beta + t * db);
        if !(e1 > 0.0 && p.feasible(e1, b1)) {
            seen.infeasible = true;
            return Ok(None);
        }
        if t == 1.0
            && let Some(((pe, pb), prev_u)) = last
        {
            let (le, lb) = (eps - pe, beta - pb);
            let ll = le * le + lb * lb;
            let s = if ll > 0.0 { ((e1 - eps) * le + (b1 - beta) * lb) / ll } else { 0.0 };
            if s.is_finite() && s.abs() <= 1.0 && s != 0.0 {
                for (u, q) in p.h.levels[k].u.iter_mut().zip(prev_u) {
                    *u = (*u + s * (*u - q)).max(0.0);
                }
            }
        }
        let ev1 = p.eval_tol(k, e1, b1, false, t_p)?;
        seen.evaluated = true;
        let r1 = load_residual(&ev1, w);
        let norm1 = r1[0].hypot(r1[1]);
        Ok((norm1 < norm0 || t < 1e-3).then_some((e1, b1, ev1, r1)))
    })
}

/// Broyden's update of the Jacobian `j` with the step `s` taken and the residual's change `y`;
/// `None` for a zero step.
fn broyden_update(j: &[[f64; 2]; 2], s: [f64; 2], y: [f64; 2]) -> Option<[[f64; 2]; 2]> {
    let ss = s[0] * s[0] + s[1] * s[1];
    if ss > 0.0 {
        let mut jn = *j;
        for a in 0..2 {
            let js = j[a][0] * s[0] + j[a][1] * s[1];
            for b in 0..2 {
                jn[a][b] += (y[a] - js) * s[b] / ss;
            }
        }
        Some(jn)
    } else {
        None
    }
}

/// The load balance's failure after `it` steps at `(eps, beta)`: a closed film where the load
/// is not reached near the closure floor ([`near_closure`]), else not converged.
#[allow(clippy::too_many_arguments)]
fn balance_failure(p: &BalanceSearch, eps: f64, beta: f64, r: &[f64; 2], it: u32, err: f64, tol: f64, history: Vec<f64>) -> SolveError {
    if r[0] < 0.0 && near_closure(p, eps, beta) {
        return film_closed(p.settings);
    }
    SolveError::NotConverged { solver: "journal load balance", iterations: it, residual: err, tolerance: tol, history }
}

/// Newton step `−J⁻¹ r` in (ε, β), shortened so that the eccentricity moves at most halfway
/// to 0 or to 1 and the attitude at most 0.5 rad.
fn newton_step(j: &[[f64; 2]; 2], r: &[f64; 2], eps: f64) -> (f64, f64) {
    let det = j[0][0] * j[1][1] - j[0][1] * j[1][0];
    let (mut de, mut db) = if det.abs() > 1e-300 {
        ((-r[0] * j[1][1] + r[1] * j[0][1]) / det, (r[0] * j[1][0] - r[1] * j[0][0]) / det)
    } else {
        (-r[0] / j[0][0].max(1e-12), -r[1])
    };
    let lim_e = 0.5 * if de > 0.0 { 1.0 - eps } else { eps };
    if de.abs() > lim_e {
        let s = lim_e / de.abs();
        de *= s;
        db *= s;
    }
    if db.abs() > 0.5 {
        let s = 0.5 / db.abs();
        de *= s;
        db *= s;
    }
    (de, db)
}

/// `d ln W̄/dε` of the short-bearing estimate used by [`initial_eccentricity`]: the starting
/// slope of the secant iteration in [`load_balance_invariant`].
pub(super) fn initial_log_slope(eps: f64) -> f64 {
    let g = |e: f64| {
        let e = e.clamp(1e-6, 0.999);
        (e * (1.0 - e * e + 16.0 / (PI * PI) * e * e).sqrt() / (1.0 - e * e).powi(2)).ln()
    };
    let d = 1e-4;
    (g(eps + d) - g(eps - d)) / (2.0 * d)
}

/// Load balance of a bearing whose solution turns rigidly with the journal
/// ([`Bearing::rotation_invariant`]): the pressure field, relative to the supply line, depends on
/// ε only, and turning the journal turns the force. So the attitude is exact after every
/// pressure solve (β turned by the force's angle from the load line) and the balance is one
/// equation, `ln|F(ε)| = ln W̄`, solved by the secant method (slope carried between grids in
/// `slope`; the first from the short-bearing law). One pressure solve per step, no Jacobian
/// columns. Returns `None` if the iteration does not make progress (the caller falls back to
/// the two-dimensional Newton iteration).
#[allow(clippy::too_many_arguments)]
pub(super) fn load_balance_invariant(
    p: &mut BalanceSearch,
    k: usize,
    w: f64,
    eps: &mut f64,
    beta: &mut f64,
    slope: &mut Option<f64>,
    cold: bool,
    predict_only: bool,
    tol: f64,
    cap: u32,
    observer: &dyn Observer,
) -> Result<Option<(Eval, Convergence, u32)>, SolveError> {
    let full = p.tol_at(k);
    let inexact = |err: f64| (1e-3 * err).clamp(full, full.max(1e-5));
    // turn the journal so that the force of `e` lies on the load line (exact, see above)
    let turn = |e: &mut Eval, beta: &mut f64| {
        let mag = e.fv.hypot(e.fh);
        if mag > 0.0 {
            *beta = wrap_pm(*beta - wrap_pm(e.fh.atan2(e.fv) - PI));
        }
        e.fv = -mag;
        e.fh = 0.0;
        mag
    };
    let mut t_used = if cold { full } else { inexact(1e-2) };
    let mut ev = p.eval_tol(k, *eps, *beta, cold, t_used)?;
    let mut mag = turn(&mut ev, beta);
    let mut r = if mag > 0.0 { (mag / w).ln() } else { return Ok(None) };
    let mut err = (mag - w).abs() / w;
    if predict_only {
        // between the start grid and the finest: one solve and one secant step with the
        // carried slope start the next grid
        if let Some(m) = *slope {
            let mut de = -r / m;
            let lim = 0.5 * if de > 0.0 { 1.0 - *eps } else { *eps };
            if de.abs() > lim {
                de = lim.copysign(de);
            }
            if m > 0.0 && m.is_finite() && *eps + de > 0.0 && p.feasible(*eps + de, *beta) {
                *eps += de;
            }
            return Ok(Some((ev, Convergence { iterations: 0, residual: err, tolerance: tol, termination: Termination::Converged }, 0)));
        }
    }
    let mut history = vec![err];
    let mut it = 0;
    let mut m = slope.unwrap_or_else(|| initial_log_slope(*eps));
    loop {
        if err <= tol {
            if t_used <= full {
                break;
            }
            // the accepted point again, to the full pressure tolerance
            t_used = full;
            ev = p.eval_tol(k, *eps, *beta, false, full)?;
            mag = turn(&mut ev, beta);
            r = (mag / w).ln();
            err = (mag - w).abs() / w;
            continue;
        }
        observer.check()?;
        if it >= cap || !(m > 0.0 && m.is_finite()) {
            return Ok(None);
        }
        it += 1;
        let mut de = -r / m;
        let lim = 0.5 * if de > 0.0 { 1.0 - *eps } else { *eps };
        if de.abs() > lim {
            de = lim.copysign(de);
        }
        // The step halved (at most 30 times) until |ln(|F|/W)| falls. (Every solved trial turns
        // the journal, an accepted one or not.)
        let taken = backtrack::<_, SolveError>(de, 30, |de| {
            let e1 = *eps + de;
            if !(e1 > 0.0 && p.feasible(e1, *beta)) {
                return Ok(None);
            }
            let t = if err < 1e3 * tol { full } else { inexact(err) };
            let mut ev1 = p.eval_tol(k, e1, *beta, false, t)?;
            let mag1 = turn(&mut ev1, beta);
            if mag1 > 0.0 {
                let r1 = (mag1 / w).ln();
                Ok((r1.abs() < r.abs()).then_some((e1, ev1, r1, mag1, t)))
            } else {
                Ok(None)
            }
        })?;
        let Some((e1, ev1, r1, mag1, t)) = taken else {
            return Ok(None);
        };
        let m1 = (r1 - r) / (e1 - *eps);
        if m1 > 0.0 && m1.is_finite() {
            m = m1;
        }
        *eps = e1;
        ev = ev1;
        r = r1;
        mag = mag1;
        t_used = t;
        err = (mag - w).abs() / w;
        history.push(err);
    }
    *slope = Some(m);
    let _ = history;
    Ok(Some((ev, Convergence { iterations: it, residual: err, tolerance: tol, termination: Termination::Converged }, it)))
}

/// Evaluate the load residual over a polar grid of mid-plane positions on level `k` and return
/// the best feasible one.
pub(super) fn scan_positions(p: &mut BalanceSearch, k: usize, w: f64) -> Result<(f64, f64), SolveError> {
    let mut best = (f64::INFINITY, 0.5, 0.0);
    for ie in 1..=19 {
        let e = ie as f64 * 0.05;
        for ib in 0..24 {
            let b = ib as f64 * TAU / 24.0;
            if !p.feasible(e, b) {
                continue;
            }
            let ev = p.eval(k, e, b, false)?;
            let err = relative_load_error(&ev, w);
            if err < best.0 {
                best = (err, e, b);
            }
        }
    }
    if best.0.is_infinite() {
        return Err(film_closed(p.settings));
    }
    p.eval(k, best.1, best.2, false)?;
    Ok((best.1, best.2))
}

/// The film at the position is within a factor 10 of the closure floor: a load that still
/// cannot be reached there needs a closed film.
pub(super) fn near_closure(p: &BalanceSearch, eps: f64, beta: f64) -> bool {
    p.bearing.film(eps, beta).min_film().0 < 10.0 * p.settings.min_film
}

/// Forward-difference Jacobian of the load residual in (ε, β); restores the level's pressure.
pub(super) fn fd_jacobian(p: &mut BalanceSearch, k: usize, w: f64, eps: f64, beta: f64, r0: &[f64; 2]) -> Result<[[f64; 2]; 2], SolveError> {
    let saved = p.h.levels[k].u.clone();
    let mut de = 1e-4 * (1.0 - eps).min(eps).max(1e-6);
    if !p.feasible(eps + de, beta) {
        de = -de;
    }
    let e1 = p.eval(k, eps + de, beta, false)?;
    p.h.levels[k].u.copy_from_slice(&saved);
    let r1 = load_residual(&e1, w);
    let db = 1e-4;
    let db = if p.feasible(eps, beta + db) { db } else { -db };
    let e2 = p.eval(k, eps, beta + db, false)?;
    p.h.levels[k].u.copy_from_slice(&saved);
    let r2 = load_residual(&e2, w);
    // restore the coefficients of the base point
    let film = p.bearing.film(eps, beta);
    let (_, theta0) = p.bearing.groove_angle(beta);
    p.h.set_film_from(k, &film, theta0);
    Ok([[(r1[0] - r0[0]) / de, (r2[0] - r0[0]) / db], [(r1[1] - r0[1]) / de, (r2[1] - r0[1]) / db]])
}
