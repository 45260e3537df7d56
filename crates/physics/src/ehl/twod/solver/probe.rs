//! Development aid: the truncation error of the discretisation on coarser grids.

use super::levels::solve_levels;
use super::validate::validate;
use super::*;

/// Development aid (issue 16): the truncation error of the discretisation on coarser grids,
/// measured by injecting the solution of `options`' grid into grids `stride` times coarser
/// (same domain, coinciding nodes): the deflection error `τ_W = W_coarse(P) − W_fine(P)`, the
/// Poiseuille and wedge errors of the Reynolds operator, the film error `Σ (τ_pois − τ_wedge) ΔX/λ`
/// they would cause if only the wedge answered, and the actual coarse solution's film error,
/// along the centre line, as a printable report.
#[doc(hidden)]
pub fn truncation_probe(input: &Ehl2dInput, options: &Ehl2dOptions, strides: &[usize]) -> Result<String, SolveError> {
    use std::fmt::Write;
    let mut out = String::new();
    use crate::Silent;
    validate(input, options)?;
    let s = scales(input)?;
    let d = domain(input, options, &s);
    let (mut pf, p, h0, _, _, _) = solve_levels(input, options, &s, d, None, &Silent)?;
    let mut vf = Fields::default();
    pf.evaluate(&p, h0, &mut vf);
    let (pois_f, wedge_f) = pf.pieces(&p, &vf.h, &vf.rho, &vf.eps);
    let (nx, ny) = (pf.nx, pf.ny);
    writeln!(out, "probe fine {nx}x{ny}: H0 {h0:.5e} Hc {:.5e} Hmin {:.5e} lambda {:.4e} c {:.4e} dx {:.4e}", bilinear(&pf.x, &pf.y, &vf.h, 0.0, 0.0), vf.h.iter().cloned().fold(f64::INFINITY, f64::min), pf.lambda, s.c_def, pf.dx).ok();
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
        let actual = solve_levels(input, &co, &s, d, None, &Silent).ok().map(|(mut q, pp, hh, _, _, _)| {
            let mut v = Fields::default();
            q.evaluate(&pp, hh, &mut v);
            (v.h, pp, hh)
        });
        let j = (cy - 1) / 2;
        let hc_f = bilinear(&pc.x, &pc.y, &h_c, 0.0, 0.0);
        let tw0 = bilinear(&pc.x, &pc.y, &w_c.iter().zip(&w_cf).map(|(a, b)| a - b).collect::<Vec<_>>(), 0.0, 0.0);
        writeln!(out, "stride {st}: {cx}x{cy}, dx {:.4e}; tauW at centre {tw0:.4e} (Hc {hc_f:.4e}); actual coarse Hc {:.5e} Hmin {:.5e} H0 {:.5e}", pc.dx, actual.as_ref().map_or(f64::NAN, |(h, _, _)| bilinear(&pc.x, &pc.y, h, 0.0, 0.0)), actual.as_ref().map_or(f64::NAN, |(h, _, _)| h.iter().cloned().fold(f64::INFINITY, f64::min)), actual.as_ref().map_or(f64::NAN, |a| a.2)).ok();
        writeln!(out, "   i       X        P_f        H_f       tauW     tauPois    tauWedge     cumdH   dH_actual   P_actual").ok();
        let mut cum = 0.0;
        for i in 0..cx {
            let k = j * cx + i;
            let (tp, tq) = (pois_c[k] - pois_fi[k], wedge_c[k] - wedge_fi[k]);
            if i > 0 && i < cx - 1 && p_c[k] > 0.0 {
                cum += (tp - tq) * pc.dx / pc.lambda / rho_c[k];
            }
            let (dh, pa) = actual.as_ref().map_or((f64::NAN, f64::NAN), |(h, pp, _)| (h[k] - h_c[k], pp[k]));
            writeln!(out, "{i:4} {:8.4} {:10.4e} {:10.4e} {:10.3e} {:10.3e} {:10.3e} {:10.3e} {:10.3e} {:10.4e}", pc.x[i], p_c[k], h_c[k], w_c[k] - w_cf[k], tp, tq, cum, dh, pa).ok();
        }
        // The deflection error over the pressurised zone and across the centre line.
        let mut worst = (0.0f64, 0usize);
        for k in 0..cx * cy {
            let t = (w_c[k] - w_cf[k]).abs();
            if t > worst.0 {
                worst = (t, k);
            }
        }
        writeln!(out, "   max |tauW| {:.4e} at X {:.3} Y {:.3} (P {:.3e})", worst.0, pc.x[worst.1 % cx], pc.y[worst.1 / cx], p_c[worst.1]).ok();
        let i0 = pc.x.iter().position(|&x| x >= 0.0).unwrap_or(0);
        writeln!(out, "   across (X = {:.3}): Y, tauW, dH_actual", pc.x[i0]).ok();
        for jj in (0..cy).step_by((cy / 16).max(1)) {
            let k = jj * cx + i0;
            writeln!(out, "   {:8.4} {:10.3e} {:10.3e}", pc.y[jj], w_c[k] - w_cf[k], actual.as_ref().map_or(f64::NAN, |(h, _, _)| h[k] - h_c[k])).ok();
        }
    }
    Ok(out)
}

#[cfg(test)]
mod probe {
    use super::*;
    use crate::lubricant::Lubricant;

    /// The truncation probe on the bench's circular contact (`TRIBOD_EHL2D_PROBE_FINE`, default 129).
    #[test]
    #[ignore = "development aid: prints the truncation errors of coarser grids (issue 16)"]
    fn truncation_probe_circular() {
        let fine: usize = std::env::var("TRIBOD_EHL2D_PROBE_FINE").ok().and_then(|v| v.parse().ok()).unwrap_or(129);
        let lub = Lubricant { viscosity: 0.04, pressure_viscosity: 2e-8, ..Lubricant::SEED000 };
        let input = Ehl2dInput { load: 100.0, geometry: Geometry2d::Point { rx: 0.01, ry: 0.01 }, effective_modulus: 210e9 / 0.91, entrainment_velocity: 1.0, lubricant: lub, temperature: 313.0 };
        let o = Ehl2dOptions { nx: fine, ny: fine, inlet: Some(3.5), outlet: Some(1.5), side: Some(2.0), ..Default::default() };
        let strides: Vec<usize> = [2, 4, 8].into_iter().filter(|s| (fine - 1) / s >= 16).collect();
        println!("{}", truncation_probe(&input, &o, &strides).unwrap());
    }
}
