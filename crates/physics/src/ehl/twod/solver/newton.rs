//! One grid's damped semismooth Newton iteration ([`newton`]): the linear solve of each step by
//! GMRES with a kept or fresh preconditioner ([`gmres`]), the film damping and the line search.

use super::precond::Precond;
use super::*;
use crate::numerics::krylov;
use crate::numerics::newton::armijo_backtrack;

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
    prob.faces(v, buf);
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
    if !prob.evaluate(p, *h0, &mut v) {
        return Ok(Run { iterations: 0, residual: f64::INFINITY, history: Vec::new(), converged: false, gmres: 0 });
    }
    let mut st = Newton::new(v, m, p);
    let cell = prob.dx * prob.dy;
    for iter in 0..=max_iter {
        observer.check()?;
        // Row scales and active set first: the residual needs them, the factorisation only an
        // unconverged step (the last, converged evaluation of every solve factorised for nothing:
        // ≈ 1 of 5 factorisations of a warm solve in the cam cycle, `ehl2d-6`).
        prob.precondition(p, &st.v, &mut st.active, &mut st.c, false, observer)?;
        prob.phi(p, &st.v, &st.c, &mut st.phi);
        let res = residual_norm(p, &st.phi, st.v.g);
        st.history.push(res);
        if res <= tol {
            return Ok(st.run(iter, res, true));
        }
        if iter == max_iter {
            return Ok(st.run(iter, res, false));
        }
        let gtol = st.right_hand_side(prob, p, res, tol);
        let Some(lin) = st.linear_solve(prob, p, gtol, observer)? else {
            return Ok(st.run(iter, res, false));
        };
        // Active (cavitated) rows are the identity: their exact step is `δP = −P`. GMRES meets it
        // only to its tolerance — closely with a fresh factor (its own identity rows), loosely
        // with a kept one factorised at another active set — and a cavitated node left at
        // `P ≈ ±1e-12` instead of 0 would count as a loaded traction node. So set it exactly.
        for (u, &k) in prob.nodes.iter().enumerate() {
            if st.active[u] == CAVITATED {
                st.sol[u] = -p[k];
            }
        }
        // A kept factor that needed many iterations is replaced at the next step.
        if !lin.fresh && lin.its > reuse_policy().1 {
            st.refresh = true;
        }
        if !st.sol.iter().all(|s| s.is_finite()) {
            return Ok(st.run(iter + 1, res, false));
        }
        if !st.line_search(prob, p, h0, cell, observer)? {
            // A step solved with a kept factor: once more with a fresh one (the next iteration
            // starts from the same iterate).
            if !lin.fresh {
                st.refresh = true;
                continue;
            }
            return Ok(st.run(iter + 1, res, false));
        }
    }
    unreachable!("the loop returns at iter == max_iter")
}

/// The state of one [`newton`] run: the fields at the iterate and at a trial point, the row scales
/// and active set, the residuals, the Newton system and its solution, the line search's arrays,
/// and what carries from one step to the next.
struct Newton {
    v: Fields,
    trial: Fields,
    active: Vec<u8>,
    c: Vec<f64>,
    phi: Vec<f64>,
    phi_t: Vec<f64>,
    buf: Buffers,
    rhs: Vec<f64>,
    sol: Vec<f64>,
    p_trial: Vec<f64>,
    dw: Vec<f64>,
    dpn: Vec<f64>,
    /// Factorise afresh at the next step (the kept factor needed too many GMRES iterations or its
    /// step failed the line search).
    refresh: bool,
    /// The last step's right-hand side norm and forcing term ([`Forcing`]).
    last_forcing: Option<(f64, f64)>,
    history: Vec<f64>,
    gm_total: usize,
}

/// What the linear solve of a Newton step did: GMRES iterations of its last run and whether a
/// fresh factor was used.
struct Linear {
    its: usize,
    fresh: bool,
}

impl Newton {
    /// The state at an iterate with fields `v` (`m` unknown pressures, node pressures `p`).
    fn new(v: Fields, m: usize, p: &[f64]) -> Self {
        Newton {
            v,
            trial: Fields::default(),
            active: vec![FLUID; m],
            c: vec![0.0; m],
            phi: Vec::with_capacity(m),
            phi_t: Vec::with_capacity(m),
            buf: Buffers::default(),
            rhs: vec![0.0; m + 1],
            sol: vec![0.0; m + 1],
            p_trial: p.to_vec(),
            dw: vec![0.0; p.len()],
            dpn: vec![0.0; p.len()],
            refresh: false,
            last_forcing: None,
            history: Vec::new(),
            gm_total: 0,
        }
    }

    /// The outcome after `iterations` steps at the residual `residual`.
    fn run(&mut self, iterations: u32, residual: f64, converged: bool) -> Run {
        Run { iterations, residual, history: std::mem::take(&mut self.history), converged, gmres: self.gm_total }
    }

    /// The right-hand side `−φ` (per row kind) and `−G` of the Newton system, and the step's
    /// GMRES tolerance: 1e-3, tighter near the solution (the inexact step stalled the line
    /// search at residuals ≈ 6e-7, measured on the circular Barus case at 97²); a warm-started
    /// solve's: `Problem::forcing` ([`WARM_FORCING`]).
    fn right_hand_side(&mut self, prob: &Problem, p: &[f64], res: f64, tol: f64) -> f64 {
        let m = prob.nodes.len();
        let v = &self.v;
        for (u, &k) in prob.nodes.iter().enumerate() {
            self.rhs[u] = match self.active[u] {
                CAVITATED => -p[k],
                CONTACT => -prob.contact_scale() * (v.hraw[k] - prob.floor),
                _ => -self.c[u] * v.f[k],
            };
        }
        self.rhs[m] = -v.g;
        let bn = dot(&self.rhs, &self.rhs).sqrt();
        match prob.forcing {
            None => GMRES_TOL.min(0.1 * res.sqrt()).max(1e-10),
            Some(fp) => {
                let eta = fp.eta(self.last_forcing, bn, res, tol);
                self.last_forcing = Some((bn, eta));
                eta
            }
        }
    }

    /// The linear solve of a step into `sol`: GMRES with the kept preconditioner (an older
    /// Jacobian's near field on this grid, scaled and with the active set of its own step; the
    /// operator applied is always the current one, so only the iteration count depends on it) for
    /// at most `REUSE_MAX` iterations; else, or when there is none, the current near field
    /// factorised afresh (chord-preconditioned Newton–Krylov, as the 1-D solver,
    /// `super::super::newton`). `None` when the factorisation fails.
    fn linear_solve(&mut self, prob: &mut Problem, p: &[f64], gtol: f64, observer: &dyn Observer) -> Result<Option<Linear>, SolveError> {
        let m = prob.nodes.len();
        let (mut its, mut rel);
        let mut fresh = false;
        let (reuse_max, _, _) = reuse_policy();
        let mut from_x = false;
        loop {
            let kept = prob.kept.clone().filter(|k| !self.refresh && k.bu.len() == m);
            let pc = match kept {
                Some(pc) => pc,
                None => {
                    observer.check()?;
                    let lu = prob.precondition(p, &self.v, &mut self.active, &mut self.c, true, observer)?;
                    let Some(lu) = lu else { return Ok(None) };
                    prob.factorisations += 1;
                    crate::work::add(&crate::work::FINITE_FACTORISATIONS, 1);
                    fresh = true;
                    self.refresh = false;
                    let pc = std::sync::Arc::new(lu);
                    prob.kept = Some(pc.clone());
                    pc
                }
            };
            let max_its = if fresh { GMRES_MAX } else { reuse_max };
            (its, rel) = gmres(prob, p, &self.v, &self.active, &self.c, &pc, &self.rhs, &mut self.sol, &mut self.buf, gtol, max_its, from_x, observer)?;
            self.gm_total += its;
            crate::work::add(&crate::work::FINITE_GMRES_ITERATIONS, its as u64);
            if fresh || rel <= gtol {
                break;
            }
            // The fresh factor's GMRES goes on from the kept one's iterate.
            self.refresh = true;
            from_x = true;
        }
        Ok(Some(Linear { its, fresh }))
    }

    /// The damped step from `(p, h0)` along `sol`: the first trial length from [`film_damping`],
    /// halved until the merit `Σ φ² ΔXΔY + G²` falls by the Armijo fraction (at most
    /// [`MAX_HALVINGS`]; [`armijo_backtrack`], the cancellation checked before each trial); the
    /// accepted point replaces `(p, h0)` and `v`. Whether one was accepted.
    fn line_search(&mut self, prob: &mut Problem, p: &mut [f64], h0: &mut f64, cell: f64, observer: &dyn Observer) -> Result<bool, SolveError> {
        let m = prob.nodes.len();
        self.dpn.iter_mut().for_each(|d| *d = 0.0);
        for (u, &k) in prob.nodes.iter().enumerate() {
            self.dpn[k] = self.sol[u];
        }
        let dh0 = self.sol[m];
        let alpha0 = film_damping(prob, &self.v, &self.dpn, dh0, &mut self.dw);
        let m0 = dot(&self.phi, &self.phi) * cell + self.v.g * self.v.g;
        // The trial point at `alpha` into `p_trial`/`trial`, its merit (`None`: not evaluable).
        let accepted = armijo_backtrack(alpha0, MAX_HALVINGS, m0, |alpha| -> Result<Option<f64>, SolveError> {
            observer.check()?;
            for k in 0..p.len() {
                self.p_trial[k] = p[k] + alpha * self.dpn[k];
            }
            let h0_trial = *h0 + alpha * dh0;
            if !prob.evaluate(&self.p_trial, h0_trial, &mut self.trial) {
                return Ok(None);
            }
            prob.phi(&self.p_trial, &self.trial, &self.c, &mut self.phi_t);
            Ok(Some(dot(&self.phi_t, &self.phi_t) * cell + self.trial.g * self.trial.g))
        })?;
        if let Some(alpha) = accepted {
            // The accepted trial is the last one evaluated.
            p.copy_from_slice(&self.p_trial);
            *h0 += alpha * dh0;
            std::mem::swap(&mut self.v, &mut self.trial);
        }
        Ok(accepted.is_some())
    }
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
