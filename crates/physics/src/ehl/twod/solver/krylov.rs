use super::*;

pub(super) fn dot(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| x * y).sum()
}

/// Restarted GMRES for `A x = b` right-preconditioned by `lu`, at most `max_its` iterations;
/// `x` starts at 0. Returns the iterations and the final relative residual.
#[allow(clippy::too_many_arguments)]
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
    let n = b.len();
    let bnorm = dot(b, b).sqrt();
    if bnorm == 0.0 {
        x.iter_mut().for_each(|v| *v = 0.0);
        return Ok((0, 0.0));
    }
    let mut w = vec![0.0; n];
    let mut z = vec![0.0; n];
    let mut r = b.to_vec();
    if from_x && x.iter().all(|v| v.is_finite()) {
        prob.apply(p, v, active, c, x, &mut w, buf);
        for ii in 0..n {
            r[ii] = b[ii] - w[ii];
        }
    } else {
        x.iter_mut().for_each(|v| *v = 0.0);
    }
    let mut iters = 0;
    let mut rel = 1.0;
    let mut gave_up = false;
    while iters < max_its {
        let beta = dot(&r, &r).sqrt();
        rel = beta / bnorm;
        if rel <= tol {
            break;
        }
        let mut basis: Vec<Vec<f64>> = vec![r.iter().map(|v| v / beta).collect()];
        let mut hess: Vec<Vec<f64>> = Vec::new();
        let (mut cs, mut sn): (Vec<f64>, Vec<f64>) = (Vec::new(), Vec::new());
        let mut g = vec![beta];
        let mut zs: Vec<Vec<f64>> = Vec::new();
        let mut k = 0;
        while k < RESTART && iters < max_its {
            // One operator application (FFT of the padded grid) per iteration: a cancel takes
            // effect within one (≈ 50 ms at 513²).
            observer.check()?;
            z.copy_from_slice(&basis[k]);
            lu.apply(&mut z, lw, &rescale);
            prob.apply(p, v, active, c, &z, &mut w, buf);
            zs.push(z.clone());
            let mut h = vec![0.0; k + 2];
            for (jj, bj) in basis.iter().enumerate() {
                let d = dot(&w, bj);
                h[jj] = d;
                for (wv, bv) in w.iter_mut().zip(bj) {
                    *wv -= d * bv;
                }
            }
            let wn = dot(&w, &w).sqrt();
            h[k + 1] = wn;
            for jj in 0..k {
                let t = cs[jj] * h[jj] + sn[jj] * h[jj + 1];
                h[jj + 1] = -sn[jj] * h[jj] + cs[jj] * h[jj + 1];
                h[jj] = t;
            }
            let den = (h[k] * h[k] + h[k + 1] * h[k + 1]).sqrt();
            let (cc, ss) = if den > 0.0 { (h[k] / den, h[k + 1] / den) } else { (1.0, 0.0) };
            cs.push(cc);
            sn.push(ss);
            h[k] = den;
            h[k + 1] = 0.0;
            g.push(-ss * g[k]);
            g[k] *= cc;
            hess.push(h);
            iters += 1;
            k += 1;
            rel = g[k].abs() / bnorm;
            if rel <= tol || wn == 0.0 || !rel.is_finite() {
                break;
            }
            // With a kept factor (a cap below a restart): give up early when the mean reduction
            // per iteration so far would not reach the tolerance within the cap.
            if max_its < RESTART && iters >= 4 && iters < max_its && rel.ln() * max_its as f64 > tol.ln() * iters as f64 {
                gave_up = true;
                break;
            }
            basis.push(w.iter().map(|v| v / wn).collect());
        }
        // Back substitution for the combination of the preconditioned directions.
        let mut yk = vec![0.0; k];
        for ii in (0..k).rev() {
            let mut s = g[ii];
            for jj in ii + 1..k {
                s -= hess[jj][ii] * yk[jj];
            }
            yk[ii] = if hess[ii][ii] != 0.0 { s / hess[ii][ii] } else { 0.0 };
        }
        for (ii, zi) in zs.iter().enumerate() {
            for (xv, zv) in x.iter_mut().zip(zi) {
                *xv += yk[ii] * zv;
            }
        }
        if rel <= tol || !rel.is_finite() || gave_up {
            break;
        }
        // True residual for the restart.
        prob.apply(p, v, active, c, x, &mut w, buf);
        for ii in 0..n {
            r[ii] = b[ii] - w[ii];
        }
    }
    Ok((iters, rel))
}
