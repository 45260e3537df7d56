use super::*;
use crate::numerics::newton::armijo_backtrack;
use std::convert::Infallible;

/// Scaled complementarity residuals `φ_i = min(P_f, −c F)` (0 at boundaries) for scalings `c`.
pub(super) fn phi(v: &Fields, c: &[f64], out: &mut [f64]) {
    let n = v.fp.len();
    out[0] = 0.0;
    out[n - 1] = 0.0;
    for i in 1..n - 1 {
        out[i] = v.fp[i].min(-c[i] * v.f[i]);
    }
}

pub(super) fn merit(phi: &[f64], load: f64, cell: &[f64]) -> f64 {
    phi.iter().zip(cell).map(|(v, w)| v * v * w).sum::<f64>() + load * load
}

/// Residual norm of the report: the larger of `max|φ|/max P` and `|load|`.
pub(super) fn residual_norm(p: &[f64], phi: &[f64], load: f64) -> f64 {
    let pmax = p.iter().cloned().fold(0.0_f64, f64::max).max(1e-12);
    let pr = phi.iter().fold(0.0_f64, |a, v| a.max(v.abs())) / pmax;
    pr.max(load.abs())
}

/// Damped semismooth Newton from `(p, h0)`, in place.
pub(super) fn newton(
    prob: &Discretisation,
    ws: &mut Workspace,
    p: &mut [f64],
    h0: &mut f64,
    tol: f64,
    max_iter: u32,
    observer: &dyn Observer,
) -> Result<Run, SolveError> {
    let grid = prob.grid.clone();
    let n = grid.n;
    let m = n - 2;
    ws.ensure(n);
    let mut history = Vec::new();
    if !prob.evaluate(p, *h0, &mut ws.v) {
        return Ok(Run { iterations: 0, residual: f64::INFINITY, history, converged: false });
    }
    let inv_pi = 1.0 / PI;
    let kernel = &grid.kernel;
    // Whether the last step's line search damped it.
    let mut struggling = false;
    for iter in 0..max_iter {
        observer.check()?;
        // Local derivatives, the full diagonal for the row scaling, and the scaled system.
        for i in 1..n - 1 {
            let (a, g) = prob.local_derivatives(&ws.v, i);
            let kc = kernel.column(i);
            let mut d = a[2];
            for (o, gv) in g.iter().enumerate() {
                let mm = i + o;
                if *gv != 0.0 && mm >= 2 && mm - 2 < n {
                    d -= inv_pi * gv * kc[mm - 2];
                }
            }
            let c = 1.0 / d.abs().max(1e-300);
            ws.c[i] = c;
            let fp = ws.v.fp[i];
            let active = fp <= -c * ws.v.f[i];
            let sys = &mut ws.sys;
            let mut gs = 0.0;
            for o in 0..5 {
                let in_range = i + o >= 2 && i + o - 2 < n;
                if active {
                    // The row `P_f = P − P_a(H) = 0`.
                    sys.aa[o][i] = if o == 2 { 1.0 } else { 0.0 };
                    sys.cg[o][i] = if o == 2 { -ws.v.dpa[i] } else { 0.0 };
                } else {
                    sys.aa[o][i] = c * a[o];
                    sys.cg[o][i] = if in_range { c * g[o] } else { 0.0 };
                }
                gs += sys.cg[o][i];
            }
            sys.gsum[i] = gs;
            sys.rhs[i - 1] = if active { -fp } else { -c * ws.v.f[i] };
        }
        phi(&ws.v, &ws.c, &mut ws.ph);
        let res = residual_norm(p, &ws.ph, ws.v.load);
        history.push(res);
        if res <= tol {
            return Ok(Run { iterations: iter, residual: res, history, converged: true });
        }
        ws.sys.rhs[m] = -ws.v.load;
        ws.stats.newton_steps += 1;
        // Eisenstat–Walker forcing (loose linear solves) only near the solution: while the
        // residual is above 1e-2, or after a step the line search had to damp, tight ones. Loose
        // directions far from the solution stalled the line search on hard cases (ehl_stability:
        // a transient step took 330 steps and failed where tight solves take 12; 5 of 1500
        // random steady cases at Moes L 28–39 failed, none with this safeguard).
        let eta = if struggling || res > 0.1 { GMRES_TOL } else { forcing(res, tol) };
        if !linear_solve(ws, &grid, eta) {
            return Ok(Run { iterations: iter + 1, residual: res, history, converged: false });
        }
        let dh0 = ws.sol[m];
        ws.dp[0] = 0.0;
        ws.dp[n - 1] = 0.0;
        ws.dp[1..n - 1].copy_from_slice(&ws.sol[..m]);
        if !ws.dp.iter().all(|d| d.is_finite()) || !dh0.is_finite() {
            ws.factor.grid_id = 0;
            return Ok(Run { iterations: iter + 1, residual: res, history, converged: false });
        }
        // Fraction to the boundary: the film may shrink at most to 20 % in one step.
        kernel.deflection(&ws.dp, &mut ws.dh);
        let mut alpha: f64 = 1.0;
        for i in 0..n {
            let d = dh0 - ws.dh[i];
            if d < 0.0 {
                alpha = alpha.min(0.8 * ws.v.h[i] / -d);
            }
        }
        let m0 = merit(&ws.ph, ws.v.load, &grid.cell);
        // The trial point at `alpha` into `ws.p_trial`/`ws.trial`, its merit (`None`: not evaluable).
        let Ok(accepted) = armijo_backtrack(alpha, MAX_HALVINGS, m0, |alpha| {
            for i in 0..n {
                ws.p_trial[i] = p[i] + alpha * ws.dp[i];
            }
            let h0_trial = *h0 + alpha * dh0;
            if !prob.evaluate(&ws.p_trial, h0_trial, &mut ws.trial) {
                return Ok::<_, Infallible>(None);
            }
            phi(&ws.trial, &ws.c, &mut ws.ph_trial);
            Ok(Some(merit(&ws.ph_trial, ws.trial.load, &grid.cell)))
        });
        let Some(accepted_alpha) = accepted else {
            return Ok(Run { iterations: iter + 1, residual: res, history, converged: false });
        };
        struggling = accepted_alpha < alpha;
        let alpha = accepted_alpha;
        // The accepted trial is the last one evaluated.
        p.copy_from_slice(&ws.p_trial);
        *h0 += alpha * dh0;
        std::mem::swap(&mut ws.v, &mut ws.trial);
    }
    // Final check after the last step.
    for i in 1..n - 1 {
        let (a, g) = prob.local_derivatives(&ws.v, i);
        let kc = kernel.column(i);
        let mut d = a[2];
        for (o, gv) in g.iter().enumerate() {
            let mm = i + o;
            if *gv != 0.0 && mm >= 2 && mm - 2 < n {
                d -= inv_pi * gv * kc[mm - 2];
            }
        }
        ws.c[i] = 1.0 / d.abs().max(1e-300);
    }
    phi(&ws.v, &ws.c, &mut ws.ph);
    let res = residual_norm(p, &ws.ph, ws.v.load);
    history.push(res);
    Ok(Run { iterations: max_iter, residual: res, history, converged: res <= tol })
}
