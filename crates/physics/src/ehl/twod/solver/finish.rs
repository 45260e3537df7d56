//! The solution of a converged problem ([`finish`]): films, pressures and their positions, the
//! edge pressure peak, the fields.

use super::*;

/// The contacts are symmetric about y = 0, so an extremum at node `k` has a mirror at
/// `(i, ny − 1 − j)` that differs only by the solver's tolerance. Where the two agree to 1e-6
/// relative, the node at y ≥ 0 is reported, so the reported position does not flip sign with the
/// last digits of the solution (the roller's two ends).
pub(in crate::ehl::twod) fn mirror_tie(nx: usize, ny: usize, k: usize, f: &[f64]) -> usize {
    let (i, j) = (k % nx, k / nx);
    let m = (ny - 1 - j) * nx + i;
    if m > k && (f[m] - f[k]).abs() <= 1e-6 * f[k].abs() {
        m
    } else {
        k
    }
}

/// The node of the largest off-centre local maximum of the axial pressure profile `max_X P(X, Y)`
/// of a finite line contact (half-length `ky`, units of `a`) above the centre's pressure (the
/// edge pressure peak), the mirror-symmetric tie resolved to one side; `None` when the profile
/// has none.
pub(in crate::ehl::twod) fn edge_peak_node(xs: &[f64], ys: &[f64], p: &[f64], ky: f64) -> Option<usize> {
    let (nx, ny) = (xs.len(), ys.len());
    let line: Vec<(f64, usize)> = (0..ny)
        .map(|j| {
            let i = (0..nx).max_by(|&a, &b| p[j * nx + a].total_cmp(&p[j * nx + b])).unwrap_or(0);
            (p[j * nx + i], j * nx + i)
        })
        .collect();
    let centre = bilinear(xs, ys, p, 0.0, 0.0);
    let mut best: Option<(f64, usize)> = None;
    for j in 1..ny - 1 {
        let (pv, k) = line[j];
        let off = ys[j].abs() > 0.1 * ky;
        if off && pv >= line[j - 1].0 && pv >= line[j + 1].0 && pv > centre * (1.0 + 1e-3) && best.is_none_or(|(b, _)| pv > b) {
            best = Some((pv, k));
        }
    }
    best.map(|(_, k)| mirror_tie(nx, ny, k, p))
}

/// GMRES iterations of the last [`solve`] are not reported; this is the count of Newton steps.
#[allow(clippy::too_many_arguments)]
pub(super) fn finish(input: &Ehl2dInput, options: &Ehl2dOptions, s: &Scales, prob: &mut Problem, p: &[f64], h0: f64, iterations: u32, residual: f64) -> Result<Ehl2dSolution, SolveError> {
    let mut v = Fields::default();
    if !prob.evaluate(p, h0, &mut v) {
        return Err(SolveError::NonFinite { quantity: "2-D EHL film".into() });
    }
    let (nx, ny) = (prob.nx, prob.ny);
    let film_scale = s.a * s.a / s.rx;
    let sign = if input.entrainment_velocity >= 0.0 { 1.0 } else { -1.0 };
    let at = |k: usize| (sign * prob.x[k % nx] * s.a, prob.y[k / nx] * s.a);
    let central = bilinear(&prob.x, &prob.y, &v.h, 0.0, 0.0) * film_scale;
    let kmin = mirror_tie(nx, ny, (0..nx * ny).min_by(|&a, &b| v.h[a].total_cmp(&v.h[b])).unwrap_or(0), &v.h);
    let kmax = mirror_tie(nx, ny, (0..nx * ny).max_by(|&a, &b| p[a].total_cmp(&p[b])).unwrap_or(0), p);
    let loc = |k: usize, value: f64| {
        let (x, y) = at(k);
        Located { value, x, y }
    };
    let min_film = loc(kmin, v.h[kmin] * film_scale);
    let max_pressure = loc(kmax, p[kmax].max(0.0) * s.p_ref);
    if min_film.value <= 0.0 {
        return Err(SolveError::physical(crate::PhysicalFailure::FilmCollapse, "the converged 2-D EHL film is not positive"));
    }
    let edge = match input.geometry {
        Geometry2d::Finite { .. } => edge_peak_node(&prob.x, &prob.y, p, s.ky).map(|k| loc(k, p[k] * s.p_ref)),
        Geometry2d::Point { .. } => None,
    };
    let load = p.iter().sum::<f64>() * prob.dx * prob.dy * s.p_ref * s.a * s.a;
    let fields = options.fields.then(|| Fields2d {
        x: prob.x.iter().map(|x| sign * x * s.a).collect(),
        y: prob.y.iter().map(|y| y * s.a).collect(),
        pressure: p.iter().map(|v| v.max(0.0) * s.p_ref).collect(),
        film: v.h.iter().map(|h| h * film_scale).collect(),
    });
    let sol = Ehl2dSolution {
        hertz_half_width: s.a,
        hertz_pressure: s.p_ref,
        moes_m: s.moes_m,
        moes_l: s.moes_l,
        central_film: central,
        min_film,
        max_pressure,
        edge_pressure_peak: edge,
        load,
        nx,
        ny,
        fields,
        grid_error: None,
        warm_started: false,
        substeps: None,
        convergence: Convergence { iterations, residual, tolerance: options.tolerance, termination: Termination::Converged },
    };
    let scalars = [sol.central_film, sol.min_film.value, sol.max_pressure.value, sol.load, residual];
    crate::ensure_finite("2-D EHL result", scalars.iter())?;
    if let Some(f) = &sol.fields {
        crate::ensure_finite("2-D EHL fields", f.pressure.iter().chain(&f.film))?;
    }
    Ok(sol)
}

#[cfg(test)]
mod tests {
    use super::mirror_tie;

    /// A tie between mirrored nodes is reported at y ≥ 0 whichever of the two the scan found; a
    /// real difference keeps the extremum where it is.
    #[test]
    fn mirrored_extrema_are_reported_at_positive_y() {
        let (nx, ny) = (3, 5);
        let mut f = vec![1.0; nx * ny];
        f[nx + 1] = 0.5; // (1, 1), y < 0
        f[3 * nx + 1] = 0.5 * (1.0 + 1e-9); // its mirror (1, 3)
        assert_eq!(mirror_tie(nx, ny, nx + 1, &f), 3 * nx + 1);
        assert_eq!(mirror_tie(nx, ny, 3 * nx + 1, &f), 3 * nx + 1);
        f[3 * nx + 1] = 0.5 * (1.0 + 1e-3);
        assert_eq!(mirror_tie(nx, ny, nx + 1, &f), nx + 1);
        assert_eq!(mirror_tie(nx, ny, 2 * nx, &f), 2 * nx); // the centre line is its own mirror
    }
}
