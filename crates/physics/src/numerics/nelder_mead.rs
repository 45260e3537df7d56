//! Nelder–Mead simplex minimisation in a box (Nelder & Mead, Comput. J. 7, 1965): the
//! continuous design step of the bearing optimisation and the seed 003 cam fit share it.

/// Outcome of a Nelder–Mead search.
#[derive(Debug, Clone, PartialEq)]
pub struct Minimum {
    pub x: Vec<f64>,
    pub value: f64,
    pub evaluations: usize,
    /// Simplex spread in value at the end.
    pub spread: f64,
}

/// Nelder–Mead simplex minimisation in a box (points are projected onto the box), with at most
/// `max_evals` evaluations of `f`. `step` is the initial simplex edge per coordinate. An error
/// from `f` ends the search with that error: an infeasible point should return `Ok(f64::INFINITY)`.
pub fn nelder_mead<E>(
    mut f: impl FnMut(&[f64]) -> Result<f64, E>,
    x0: &[f64],
    step: &[f64],
    lo: &[f64],
    hi: &[f64],
    max_evals: usize,
    ftol: f64,
) -> Result<Minimum, E> {
    let n = x0.len();
    let clamp = |x: &mut Vec<f64>| {
        for i in 0..n {
            x[i] = x[i].clamp(lo[i], hi[i]);
        }
    };
    let mut evals = 0;
    let mut eval = |x: &[f64], evals: &mut usize| -> Result<f64, E> {
        *evals += 1;
        f(x)
    };
    let mut simplex: Vec<(Vec<f64>, f64)> = Vec::with_capacity(n + 1);
    let mut p = x0.to_vec();
    clamp(&mut p);
    let v = eval(&p, &mut evals)?;
    simplex.push((p.clone(), v));
    for i in 0..n {
        let mut q = p.clone();
        q[i] += step[i];
        if q[i] > hi[i] {
            q[i] = p[i] - step[i];
        }
        clamp(&mut q);
        let v = eval(&q, &mut evals)?;
        simplex.push((q, v));
    }
    loop {
        simplex.sort_by(|a, b| a.1.total_cmp(&b.1));
        let spread = simplex[n].1 - simplex[0].1;
        if evals >= max_evals || (spread.is_finite() && spread.abs() <= ftol) {
            let (x, value) = simplex[0].clone();
            return Ok(Minimum { x, value, evaluations: evals, spread });
        }
        let mut c = vec![0.0; n];
        for (x, _) in &simplex[..n] {
            for i in 0..n {
                c[i] += x[i] / n as f64;
            }
        }
        let worst = simplex[n].clone();
        let point = |t: f64| {
            let mut x: Vec<f64> = (0..n).map(|i| c[i] + t * (worst.0[i] - c[i])).collect();
            clamp(&mut x);
            x
        };
        let xr = point(-1.0);
        let fr = eval(&xr, &mut evals)?;
        if fr < simplex[0].1 {
            let xe = point(-2.0);
            let fe = eval(&xe, &mut evals)?;
            simplex[n] = if fe < fr { (xe, fe) } else { (xr, fr) };
        } else if fr < simplex[n - 1].1 {
            simplex[n] = (xr, fr);
        } else {
            let (xc, fc) = if fr < worst.1 {
                let x = point(-0.5);
                let v = eval(&x, &mut evals)?;
                (x, v)
            } else {
                let x = point(0.5);
                let v = eval(&x, &mut evals)?;
                (x, v)
            };
            if fc < worst.1.min(fr) {
                simplex[n] = (xc, fc);
            } else {
                // shrink towards the best point
                let best = simplex[0].0.clone();
                for s in simplex.iter_mut().skip(1) {
                    let mut x: Vec<f64> = (0..n).map(|i| best[i] + 0.5 * (s.0[i] - best[i])).collect();
                    clamp(&mut x);
                    let v = eval(&x, &mut evals)?;
                    *s = (x, v);
                    if evals >= max_evals {
                        break;
                    }
                }
            }
        }
    }
}
