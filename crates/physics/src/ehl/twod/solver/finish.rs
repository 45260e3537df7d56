use super::*;

/// The contacts are symmetric about y = 0, so an extremum at node `k` has a mirror at
/// `(i, ny − 1 − j)` that differs only by the solver's tolerance. Where the two agree to 1e-6
/// relative, the node at y ≥ 0 is reported, so the reported position does not flip sign with the
/// last digits of the solution (the roller's two ends).
pub(crate) fn mirror_tie(nx: usize, ny: usize, k: usize, f: &[f64]) -> usize {
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
pub(crate) fn edge_peak_node(xs: &[f64], ys: &[f64], p: &[f64], ky: f64) -> Option<usize> {
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

/// Development aid (issue 16): the truncation error of the discretisation on coarser grids,
/// measured by injecting the solution of `options`' grid into grids `stride` times coarser
/// (same domain, coinciding nodes): the deflection error `τ_W = W_coarse(P) − W_fine(P)`, the
/// Poiseuille and wedge errors of the Reynolds operator, the film error `Σ (τ_pois − τ_wedge) ΔX/λ`
/// they would cause if only the wedge answered, and the actual coarse solution's film error,
/// along the centre line. Printed to stderr.
#[doc(hidden)]
pub fn truncation_probe(input: &Ehl2dInput, options: &Ehl2dOptions, strides: &[usize]) -> Result<(), SolveError> {
    use crate::Silent;
    validate(input, options)?;
    let s = scales(input)?;
    let d = domain(input, options, &s);
    let (mut pf, p, h0, _, _, _) = solve_levels(input, options, &s, d, &Silent)?;
    let mut vf = Fields::default();
    pf.evaluate(&p, h0, &mut vf);
    let (pois_f, wedge_f) = pf.pieces(&p, &vf.h, &vf.rho, &vf.eps);
    let (nx, ny) = (pf.nx, pf.ny);
    eprintln!("probe fine {nx}x{ny}: H0 {h0:.5e} Hc {:.5e} Hmin {:.5e} lambda {:.4e} c {:.4e} dx {:.4e}", bilinear(&pf.x, &pf.y, &vf.h, 0.0, 0.0), vf.h.iter().cloned().fold(f64::INFINITY, f64::min), pf.lambda, s.c_def, pf.dx);
    for &st in strides {
        let (cx, cy) = ((nx - 1) / st + 1, (ny - 1) / st + 1);
        let mut pc = Problem::new(input, &s, d, cx, cy, options.near_field);
        let inj = |f: &[f64]| -> Vec<f64> { (0..cx * cy).map(|k| f[(k / cx) * st * nx + (k % cx) * st]).collect() };
        let (p_c, h_c, w_cf, rho_c, eps_c) = (inj(&p), inj(&vf.h), inj(&vf.w), inj(&vf.rho), inj(&vf.eps));
        let mut w_c = vec![0.0; cx * cy];
        pc.defl.apply(&p_c, &mut w_c);
        let (pois_c, wedge_c) = pc.pieces(&p_c, &h_c, &rho_c, &eps_c);
        let (pois_fi, wedge_fi) = (inj(&pois_f), inj(&wedge_f));
        let co = Ehl2dOptions { nx: cx, ny: cy, ..*options };
        let actual = solve_levels(input, &co, &s, d, &Silent).ok().map(|(mut q, pp, hh, _, _, _)| {
            let mut v = Fields::default();
            q.evaluate(&pp, hh, &mut v);
            (v.h, pp, hh)
        });
        let j = (cy - 1) / 2;
        let hc_f = bilinear(&pc.x, &pc.y, &h_c, 0.0, 0.0);
        let tw0 = bilinear(&pc.x, &pc.y, &w_c.iter().zip(&w_cf).map(|(a, b)| a - b).collect::<Vec<_>>(), 0.0, 0.0);
        eprintln!("stride {st}: {cx}x{cy}, dx {:.4e}; tauW at centre {tw0:.4e} (Hc {hc_f:.4e}); actual coarse Hc {:.5e} Hmin {:.5e} H0 {:.5e}", pc.dx, actual.as_ref().map_or(f64::NAN, |(h, _, _)| bilinear(&pc.x, &pc.y, h, 0.0, 0.0)), actual.as_ref().map_or(f64::NAN, |(h, _, _)| h.iter().cloned().fold(f64::INFINITY, f64::min)), actual.as_ref().map_or(f64::NAN, |a| a.2));
        eprintln!("   i       X        P_f        H_f       tauW     tauPois    tauWedge     cumdH   dH_actual   P_actual");
        let mut cum = 0.0;
        for i in 0..cx {
            let k = j * cx + i;
            let (tp, tq) = (pois_c[k] - pois_fi[k], wedge_c[k] - wedge_fi[k]);
            if i > 0 && i < cx - 1 && p_c[k] > 0.0 {
                cum += (tp - tq) * pc.dx / pc.lambda / rho_c[k];
            }
            let (dh, pa) = actual.as_ref().map_or((f64::NAN, f64::NAN), |(h, pp, _)| (h[k] - h_c[k], pp[k]));
            eprintln!("{i:4} {:8.4} {:10.4e} {:10.4e} {:10.3e} {:10.3e} {:10.3e} {:10.3e} {:10.3e} {:10.4e}", pc.x[i], p_c[k], h_c[k], w_c[k] - w_cf[k], tp, tq, cum, dh, pa);
        }
        // The deflection error over the pressurised zone and across the centre line.
        let mut worst = (0.0f64, 0usize);
        for k in 0..cx * cy {
            let t = (w_c[k] - w_cf[k]).abs();
            if t > worst.0 {
                worst = (t, k);
            }
        }
        eprintln!("   max |tauW| {:.4e} at X {:.3} Y {:.3} (P {:.3e})", worst.0, pc.x[worst.1 % cx], pc.y[worst.1 / cx], p_c[worst.1]);
        let i0 = pc.x.iter().position(|&x| x >= 0.0).unwrap_or(0);
        eprintln!("   across (X = {:.3}): Y, tauW, dH_actual", pc.x[i0]);
        for jj in (0..cy).step_by((cy / 16).max(1)) {
            let k = jj * cx + i0;
            eprintln!("   {:8.4} {:10.3e} {:10.3e}", pc.y[jj], w_c[k] - w_cf[k], actual.as_ref().map_or(f64::NAN, |(h, _, _)| h[k] - h_c[k]));
        }
    }
    Ok(())
}
