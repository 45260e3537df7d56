//! One grid's damped semismooth Newton iteration ([`newton`]): the linear solve of each step by
//! GMRES with a kept or fresh preconditioner ([`gmres`]), the film damping and the line search.

use super::precond::Precond;
use super::*;
use crate::numerics::krylov;

/// Restarted GMRES for `A x = b` right-preconditioned by `lu`, at most `max_its` iterations;
/// `x` starts at 0 (`from_x`: at its own value, when finite). Returns the iterations and the final
/// relative residual. The shared GMRES ([`krylov::gmres`]) in this solver's arithmetic: restarts
/// every [`RESTART`] iterations, zero rotations the identity, `|g|/‖b‖ ≤ tol` (also at a cycle's
/// start), the preconditioned directions kept (`x += Σ y_i M⁻¹v_i`).
#[allow(clippy::too_many_arguments)]
pub(super) fn gmres(prob: &mut Problem, p: &[f64], v: &Fields, active: &[u8], c: &[f64], lu: &Precond, b: &[f64], x: &mut [f64], buf: &mut Buffers, tol: f64, max_its: usize, from_x: bool, observer: &dyn Observer) -> Result<(usize, f64), SolveError> {
    let lw = prob.load_weight();
    // A kept factor carries its own row scales `c_old`: `M⁻¹ = (C_old J_old)⁻¹ C_old C⁻¹` keeps
    // `C J M⁻¹ ≈ I` where the scales moved (rows inactive in both; others unscaled).
    let rescale: Vec<f64> = if lu.c.as_slice() == c && lu.active.as_slice() == active {
        Vec::new()
    } else {
        (0..c.len()).map(|u| if active[u] == FLUID && lu.active[u] == FLUID { lu.c[u] / c[u] } else { 1.0 }).collect()
    };
    let settings = krylov::Settings {
        restart: RESTART,
        max_iterations: max_its,
        tolerance: tol,
        from_x,
        rotation: krylov::Rotation::Sqrt,
        test: krylov::Test::Ratio,
        update: krylov::Update::Flexible,
    };
    let mut ws = std::mem::take(&mut buf.krylov);
    let out = krylov::gmres(&mut |z, y| prob.apply(p, v, active, c, z, y, buf), &mut |z| lu.apply(z, lw, &rescale), b, x, &settings, &mut ws, observer);
    buf.krylov = ws;
    let out = out?;
    Ok((out.iterations, out.residual))
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
                    crate::film::work::add(&crate::film::work::FINITE_FACTORISATIONS, 1);
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
            crate::film::work::add(&crate::film::work::FINITE_GMRES_ITERATIONS, its as u64);
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
