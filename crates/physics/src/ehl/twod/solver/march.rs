//! Globalisation on one grid: the continuation from the arithmetic to the geometric face means
//! ([`solve_level`]) and pseudo-time marching ([`march`]) where Newton alone fails.

use super::newton::newton;
use super::*;

/// Newton from `(p, h0)`; when it fails, pseudo-time continuation ([`march`]) from the same start.
#[allow(clippy::too_many_arguments)]
pub(super) fn newton_or_march(prob: &mut Problem, p: &mut [f64], h0: &mut f64, tol: f64, cap: u32, max_iter: u32, dt0: f64, observer: &dyn Observer) -> Result<Run, SolveError> {
    let (p_start, h0_start) = (p.to_vec(), *h0);
    let first = newton(prob, p, h0, tol, cap, observer)?;
    if first.converged {
        return Ok(first);
    }
    p.copy_from_slice(&p_start);
    *h0 = h0_start;
    let mut r = march(prob, p, h0, tol, max_iter, dt0, observer)?;
    r.iterations += first.iterations;
    r.gmres += first.gmres;
    Ok(r)
}

/// One grid's problem (geometric face means, [`face_of`]) through the arithmetic-mean one: Newton
/// on the geometric-mean problem from a cold Hertzian start stalls (measured on 49² and 97² of the
/// circular M ≈ 300 contact: 40 steps at a residual ≈ 0.4, the pseudo-time fallback then takes
/// hundreds of steps). So the arithmetic-mean problem is solved first, then the weight `θ` of the
/// geometric mean is raised to 1 in steps (halved when Newton fails, doubled when it succeeds;
/// pseudo-time continuation at `θ = 1` when the step falls below 1/16). `direct`: first try
/// `θ = 1` from the start itself (a start that is already close).
#[allow(clippy::too_many_arguments)]
pub(super) fn solve_level(prob: &mut Problem, p: &mut [f64], h0: &mut f64, tol: f64, cap: u32, max_iter: u32, dt0: f64, direct: bool, observer: &dyn Observer) -> Result<Run, SolveError> {
    let (mut its, mut gm) = (0, 0);
    let mut ps = p.to_vec();
    let mut hs = *h0;
    if direct {
        prob.theta = 1.0;
        let r = newton(prob, p, h0, tol, cap, observer)?;
        if r.converged {
            return Ok(r);
        }
        its += r.iterations;
        gm += r.gmres;
        p.copy_from_slice(&ps);
        *h0 = hs;
    }
    prob.theta = 0.0;
    let a = newton_or_march(prob, p, h0, tol, cap, max_iter, dt0, observer)?;
    its += a.iterations;
    gm += a.gmres;
    if !a.converged {
        prob.theta = 1.0;
        return Ok(Run { iterations: its, gmres: gm, ..a });
    }
    let (mut theta, mut step) = (0.0f64, 0.5f64);
    loop {
        let t = (theta + step).min(1.0);
        prob.theta = t;
        ps.copy_from_slice(p);
        hs = *h0;
        let r = newton(prob, p, h0, tol, NESTED_ITER.min(max_iter), observer)?;
        its += r.iterations;
        gm += r.gmres;
        if r.converged {
            theta = t;
            if theta >= 1.0 {
                return Ok(Run { iterations: its, gmres: gm, ..r });
            }
            step *= 2.0;
            continue;
        }
        p.copy_from_slice(&ps);
        *h0 = hs;
        // Half the increment that failed (`step` was doubled after the last success, and capped
        // at θ = 1: halving it alone could retry the same θ from the same start).
        step = 0.5 * (t - theta);
        if step < 1.0 / 16.0 {
            prob.theta = 1.0;
            let mut r = newton_or_march(prob, p, h0, tol, NESTED_ITER.min(max_iter), max_iter, DT_NESTED, observer)?;
            r.iterations += its;
            r.gmres += gm;
            return Ok(r);
        }
    }
}

/// Pseudo-transient continuation (Kelley & Keyes, SIAM J. Numer. Anal. 35 (1998)) with the
/// physical squeeze term: backward-Euler steps of the transient Reynolds equation (seed 000
/// eq. 2 with `∂(ρh)/∂t`) at fixed load, each solved by [`newton`] from the last state; `ΔT`
/// doubles (quadruples after a quick step) on success and is quartered on failure; from
/// `ΔT ≥ DT_STEADY` each step first tries the problem itself (`κ = 0`, or a transient step's own
/// squeeze term, [`Problem::pseudo_step`]) and returns when it converges. The squeeze term damps
/// the changes of `ρ̄H` that stall the steady Newton iteration from a Hertzian start (see
/// `BENCHMARKS.md`, issue 16).
pub(super) fn march(prob: &mut Problem, p: &mut [f64], h0: &mut f64, tol: f64, max_iter: u32, dt0: f64, observer: &dyn Observer) -> Result<Run, SolveError> {
    let mut dt = dt0;
    let (mut its, mut gm) = (0u32, 0usize);
    let mut last = Run { iterations: 0, residual: f64::INFINITY, history: Vec::new(), converged: false, gmres: 0 };
    let mut saved = p.to_vec();
    let mut v = Fields::default();
    for _ in 0..MAX_STEPS {
        if dt >= DT_STEADY {
            saved.copy_from_slice(p);
            let h0_saved = *h0;
            prob.restore_target();
            let r = newton(prob, p, h0, tol, max_iter.min(NESTED_ITER), observer)?;
            its += r.iterations;
            gm += r.gmres;
            if r.converged {
                return Ok(Run { iterations: its, gmres: gm, ..r });
            }
            p.copy_from_slice(&saved);
            *h0 = h0_saved;
            last = r;
            if dt >= DT_MAX {
                break;
            }
        }
        if !prob.evaluate(p, *h0, &mut v) {
            break;
        }
        prob.pseudo_step(dt, &v);
        saved.copy_from_slice(p);
        let h0_saved = *h0;
        let r = newton(prob, p, h0, tol.max(STEP_TOL), STEP_ITER, observer)?;
        prob.restore_target();
        its += r.iterations;
        gm += r.gmres;
        if r.converged {
            dt *= if r.iterations <= 3 { 4.0 } else { 2.0 };
            dt = dt.min(DT_MAX);
        } else {
            p.copy_from_slice(&saved);
            *h0 = h0_saved;
            last = r;
            dt *= 0.25;
            if dt < DT_MIN {
                break;
            }
        }
    }
    prob.restore_target();
    Ok(Run { iterations: its, residual: last.residual, history: last.history, converged: false, gmres: gm })
}
