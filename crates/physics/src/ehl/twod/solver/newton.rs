use super::*;

/// `TRIBOD_EHL2D_TRACE` set: print each Newton step, the line search and (first step) a
/// finite-difference check of the Jacobian product to stderr (development aid).
pub(super) fn trace() -> bool {
    std::env::var_os("TRIBOD_EHL2D_TRACE").is_some()
}

/// Report norm: the larger of `max|φ|/max P` and `|G|`.
pub(super) fn residual_norm(p: &[f64], phi: &[f64], g: f64) -> f64 {
    let pmax = p.iter().cloned().fold(0.0_f64, f64::max).max(1e-12);
    let pr = phi.iter().fold(0.0_f64, |a, v| a.max(v.abs())) / pmax;
    pr.max(g.abs())
}

/// Damped semismooth Newton from `(p, h0)`, in place.
pub(super) fn newton(prob: &mut Problem, p: &mut [f64], h0: &mut f64, tol: f64, max_iter: u32, observer: &dyn Observer) -> Result<Run, SolveError> {
    let m = prob.nodes.len();
    let mut v = Fields::default();
    let mut trial = Fields::default();
    let mut history = Vec::new();
    let mut gm_total = 0;
    if !prob.evaluate(p, *h0, &mut v) {
        return Ok(Run { iterations: 0, residual: f64::INFINITY, history, converged: false, gmres: 0 });
    }
    let mut active = vec![FLUID; m];
    let mut c = vec![0.0; m];
    let mut phi = Vec::with_capacity(m);
    let mut phi_t = Vec::with_capacity(m);
    let mut buf = Buffers::default();
    let cell = prob.dx * prob.dy;
    let mut rhs = vec![0.0; m + 1];
    let mut sol = vec![0.0; m + 1];
    let mut p_trial = p.to_vec();
    let mut dw = vec![0.0; p.len()];
    let mut dpn = vec![0.0; p.len()];
    // Factorise afresh at the next step (the kept factor needed too many GMRES iterations or its
    // step failed the line search).
    let mut refresh = false;
    // The last step's right-hand side norm and forcing term ([`Forcing`]).
    let mut last_forcing: Option<(f64, f64)> = None;
    for iter in 0..=max_iter {
        observer.check()?;
        // Row scales and active set first: the residual needs them, the factorisation only an
        // unconverged step (the last, converged evaluation of every solve factorised for nothing:
        // ≈ 1 of 5 factorisations of a warm solve in the cam cycle, `ehl2d-6`).
        prob.precondition(p, &v, &mut active, &mut c, false, observer)?;
        prob.phi(p, &v, &c, &mut phi);
        let res = residual_norm(p, &phi, v.g);
        history.push(res);
        if res <= tol {
            return Ok(Run { iterations: iter, residual: res, history, converged: true, gmres: gm_total });
        }
        if iter == max_iter {
            return Ok(Run { iterations: iter, residual: res, history, converged: false, gmres: gm_total });
        }
        for (u, &k) in prob.nodes.iter().enumerate() {
            rhs[u] = match active[u] {
                CAVITATED => -p[k],
                CONTACT => -prob.contact_scale() * (v.hraw[k] - prob.floor),
                _ => -c[u] * v.f[k],
            };
        }
        rhs[m] = -v.g;
        // Forcing term: 1e-3, tighter near the solution (the inexact step stalled the line
        // search at residuals ≈ 6e-7, measured on the circular Barus case at 97²); a warm-started
        // solve's: `Problem::forcing` ([`WARM_FORCING`]).
        let bn = dot(&rhs, &rhs).sqrt();
        let gtol = match prob.forcing {
            None => GMRES_TOL.min(0.1 * res.sqrt()).max(1e-10),
            Some(fp) => {
                let eta = fp.eta(last_forcing, bn, res, tol);
                last_forcing = Some((bn, eta));
                eta
            }
        };
        // The linear solve: GMRES with the kept preconditioner (an older Jacobian's near field on
        // this grid, scaled and with the active set of its own step; the operator applied is
        // always the current one, so only the iteration count depends on it) for at most
        // `REUSE_MAX` iterations; else, or when there is none, the current near field factorised
        // afresh (chord-preconditioned Newton–Krylov, as the 1-D solver, `super::super::newton`).
        let (mut t_lu, mut t_gm) = (0.0, 0.0);
        let (mut its, mut rel);
        let mut fresh = false;
        let (reuse_max, reuse_refresh, _) = reuse_policy();
        let mut from_x = false;
        loop {
            let kept = prob.kept.clone().filter(|k| !refresh && k.bu.len() == m);
            let pc = match kept {
                Some(pc) => pc,
                None => {
                    observer.check()?;
                    let t = std::time::Instant::now();
                    let lu = prob.precondition(p, &v, &mut active, &mut c, true, observer)?;
                    t_lu += t.elapsed().as_secs_f64();
                    let Some(lu) = lu else {
                        return Ok(Run { iterations: iter, residual: res, history, converged: false, gmres: gm_total });
                    };
                    prob.factorisations += 1;
                    crate::work::add(&crate::work::FINITE_FACTORISATIONS, 1);
                    fresh = true;
                    refresh = false;
                    let pc = std::sync::Arc::new(lu);
                    prob.kept = Some(pc.clone());
                    pc
                }
            };
            let t = std::time::Instant::now();
            (its, rel) = gmres(prob, p, &v, &active, &c, &pc, &rhs, &mut sol, &mut buf, gtol, if fresh { GMRES_MAX } else { reuse_max }, from_x, observer)?;
            t_gm += t.elapsed().as_secs_f64();
            gm_total += its;
            crate::work::add(&crate::work::FINITE_GMRES_ITERATIONS, its as u64);
            if fresh || rel <= gtol {
                break;
            }
            // The fresh factor's GMRES goes on from the kept one's iterate.
            refresh = true;
            from_x = true;
        }
        // Active (cavitated) rows are the identity: their exact step is `δP = −P`. GMRES meets it
        // only to its tolerance — closely with a fresh factor (its own identity rows), loosely
        // with a kept one factorised at another active set — and a cavitated node left at
        // `P ≈ ±1e-12` instead of 0 would count as a loaded traction node. So set it exactly.
        for (u, &k) in prob.nodes.iter().enumerate() {
            if active[u] == CAVITATED {
                sol[u] = -p[k];
            }
        }
        // A kept factor that needed many iterations is replaced at the next step.
        if !fresh && its > reuse_refresh {
            refresh = true;
        }
        if trace() {
            eprintln!("ehl2d {}x{} κ {:.3e} iter {iter} res {res:.3e} g {:.2e} gtol {gtol:.1e} gmres {its} rel {rel:.2e} fresh {fresh} active {} contact {} lu {t_lu:.3} s gmres {t_gm:.3} s", prob.nx, prob.ny, prob.kappa, v.g, active.iter().filter(|a| **a == CAVITATED).count(), active.iter().filter(|a| **a == CONTACT).count());
            if iter == 0 {
                let (u, _) = phi.iter().enumerate().fold((0, 0.0f64), |b, (u, v)| if v.abs() > b.1 { (u, v.abs()) } else { b });
                let k = prob.nodes[u];
                eprintln!("ehl2d worst node i {} j {} X {:.3} Y {:.3} P {:.3e} phi {:.3e} active {}", k % prob.nx, k / prob.nx, prob.x[k % prob.nx], prob.y[k / prob.nx], p[k], phi[u], active[u]);
                // Directional-derivative check of the Jacobian product.
                let mut x: Vec<f64> = (0..m + 1).map(|u| (((u * 7919) % 13) as f64 - 6.0) * 1e-3).collect();
                for (u, &k) in prob.nodes.iter().enumerate() {
                    if p[k] <= 0.0 { x[u] = 0.0; }
                }
                let mut jx = vec![0.0; m + 1];
                let mut inactive = active.clone();
                inactive.iter_mut().for_each(|a| *a = FLUID);
                prob.apply(p, &v, &inactive, &c, &x, &mut jx, &mut buf);
                let t = 1e-4;
                let mut pt = p.to_vec();
                for (u, &k) in prob.nodes.iter().enumerate() { pt[k] += t * x[u]; }
                let mut vt = Fields::default();
                if prob.evaluate(&pt, *h0 + t * x[m], &mut vt) {
                    let mut num = 0.0; let mut den = 0.0;
                    for (u, &k) in prob.nodes.iter().enumerate() {
                        let fd = c[u] * (vt.f[k] - v.f[k]) / t;
                        num += (fd - jx[u]).powi(2); den += fd * fd;
                    }
                    eprintln!("ehl2d jacobian check: rel diff {:.3e}", (num / den.max(1e-300)).sqrt());
                }
            }
        }
        if !sol.iter().all(|s| s.is_finite()) {
            return Ok(Run { iterations: iter + 1, residual: res, history, converged: false, gmres: gm_total });
        }
        dpn.iter_mut().for_each(|d| *d = 0.0);
        for (u, &k) in prob.nodes.iter().enumerate() {
            dpn[k] = sol[u];
        }
        let dh0 = sol[m];
        let mut alpha = film_damping(prob, &v, &dpn, dh0, &mut dw);
        if trace() {
            eprintln!("   film damping alpha {alpha:.3e}");
        }
        let m0 = dot(&phi, &phi) * cell + v.g * v.g;
        let mut accepted = false;
        for _ in 0..MAX_HALVINGS {
            observer.check()?;
            for k in 0..p.len() {
                p_trial[k] = p[k] + alpha * dpn[k];
            }
            let h0_trial = *h0 + alpha * dh0;
            if prob.evaluate(&p_trial, h0_trial, &mut trial) {
                prob.phi(&p_trial, &trial, &c, &mut phi_t);
                let mt = dot(&phi_t, &phi_t) * cell + trial.g * trial.g;
                if mt <= (1.0 - 1e-4 * alpha) * m0 {
                    p.copy_from_slice(&p_trial);
                    *h0 = h0_trial;
                    std::mem::swap(&mut v, &mut trial);
                    accepted = true;
                    break;
                }
            }
            alpha *= 0.5;
        }
        if trace() {
            eprintln!("   accepted {accepted} alpha {alpha:.3e}");
        }
        if !accepted {
            // A step solved with a kept factor: once more with a fresh one (the next iteration
            // starts from the same iterate).
            if !fresh {
                refresh = true;
                continue;
            }
            return Ok(Run { iterations: iter + 1, residual: res, history, converged: false, gmres: gm_total });
        }
    }
    unreachable!("the loop returns at iter == max_iter")
}

/// First trial length of a Newton step: the fraction-to-boundary rule on the film (no node's film
/// shrinks below `1 − FTB` of itself), unless it would cut the step below `FTB_MIN`: then the full
/// step, the film passing below the floor ([`FILM_FLOOR`]) where the discrete problem wants it
/// non-positive, and the line search's merit function decides. The rule alone stalled Newton
/// there (the limiting film shrank 5× per step and the step with it, issue 16).
pub(super) fn film_damping(prob: &mut Problem, v: &Fields, dpn: &[f64], dh0: f64, dw: &mut [f64]) -> f64 {
    prob.defl.apply(dpn, dw);
    let mut alpha: f64 = 1.0;
    for (k, d) in dw.iter().enumerate() {
        let d = dh0 + d;
        if d < 0.0 && v.on[k] > 0.0 && FTB * v.h[k] / -d < alpha {
            alpha = FTB * v.h[k] / -d;
        }
    }
    if alpha < FTB_MIN {
        1.0
    } else {
        alpha
    }
}

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
    for step in 0..MAX_STEPS {
        if dt >= DT_STEADY {
            saved.copy_from_slice(p);
            let h0_saved = *h0;
            prob.restore_target();
            let r = newton(prob, p, h0, tol, max_iter.min(NESTED_ITER), observer)?;
            its += r.iterations;
            gm += r.gmres;
            if trace() {
                eprintln!("ehl2d march {}x{} step {step} steady try: converged {} res {:.3e} in {}", prob.nx, prob.ny, r.converged, r.residual, r.iterations);
            }
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
        if trace() {
            eprintln!("ehl2d march {}x{} step {step} dT {dt:.3e}: converged {} res {:.3e} in {} (H0 {:.4e})", prob.nx, prob.ny, r.converged, r.residual, r.iterations, *h0);
        }
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
