//! The performance figures of one analysis at its equilibrium: load components, peak pressure
//! and minimum film with their places, friction (with the striated cavitated zone of seed 002
//! eq. 9), flows and power.

use super::problem::*;
use super::balance::{wrap_pm, Eval};
use super::film::{wrap_angle, Film};
use super::multigrid::Level;
use crate::{ensure_finite, Convergence, SolveError};
use std::f64::consts::{PI, TAU};

/// The figures of an analysis from the finest grid's pressure and film `l` at the equilibrium
/// `(eps, beta)` with the film `film`, its last evaluation `ev` and the search's convergence.
#[allow(clippy::too_many_arguments)]
pub(super) fn figures(
    l: &Level,
    bearing: &Bearing,
    film: &Film,
    eps: f64,
    beta: f64,
    ev: &Eval,
    convergence: Convergence,
    steps_per_grid: Vec<(usize, usize, u32)>,
    want_fields: bool,
) -> Result<Analysis, SolveError> {
    let (nt, nz, dz) = (l.nt, l.nz, l.dz);
    let u = &l.u;
    let load = ev.fv.hypot(ev.fh);
    let (p_peak, th_peak, z_peak) = peak_pressure(l);
    let (hmin, th_min, z_min) = film.min_film();
    let (couette, press) = friction(l, film)?;
    let friction_force = couette + press;
    let striated = striated_couette(l, film);
    let (friction_variable, friction_variable_seed002, sommerfeld) = if load > 0.0 {
        (Some(friction_force / (6.0 * load)), Some((striated + press) / (6.0 * load)), Some(1.0 / (6.0 * PI * load)))
    } else {
        (None, None, None)
    };
    let flow = supply_flow(l, bearing, beta);
    let side = side_flow(l, bearing.alpha());
    let side_flow_ratio = if flow > 0.0 { Some(side / flow) } else { None };

    let fields = want_fields.then(|| Fields {
        theta: (0..nt).map(|i| wrap_angle(l.theta(i))).collect(),
        z: (0..nz).map(|j| j as f64 * dz).collect(),
        pressure: u.clone(),
        film: l.h.clone(),
    });
    let out = Analysis {
        film: *film,
        eccentricity: eps,
        attitude: wrap_pm(beta),
        load,
        force_along_load: ev.fv,
        force_across_load: ev.fh,
        sommerfeld,
        max_pressure: p_peak,
        max_pressure_theta: wrap_angle(th_peak),
        max_pressure_z: z_peak,
        min_film: hmin,
        min_film_theta: th_min,
        min_film_z: z_min,
        friction_force,
        couette_force: couette,
        friction_variable,
        friction_variable_seed002,
        striated_couette_force: striated,
        flow_variable: flow,
        side_flow_variable: side,
        side_flow_ratio,
        convergence,
        pressure_solve: ev.rep,
        steps_per_grid,
        fields,
    };
    ensure_finite(
        "journal bearing result",
        [
            &out.eccentricity, &out.attitude, &out.load, &out.max_pressure, &out.min_film, &out.friction_force,
            &out.flow_variable, &out.side_flow_variable, &out.force_along_load, &out.force_across_load,
        ],
    )?;
    if let Some(f) = &out.fields {
        ensure_finite("pressure field", f.pressure.iter())?;
    }
    Ok(out)
}

/// The peak pressure `(P, θ, Z)`, refined by a parabola through the neighbours in each direction.
fn peak_pressure(l: &Level) -> (f64, f64, f64) {
    let (nt, nz, dt, dz) = (l.nt, l.nz, l.dt, l.dz);
    let u = &l.u;
    let (mut kmax, mut pmax) = (0, 0.0);
    for (k, &v) in u.iter().enumerate() {
        if v > pmax {
            pmax = v;
            kmax = k;
        }
    }
    let (im, jm) = (kmax % nt, kmax / nt);
    let (mut p_peak, mut th_peak, mut z_peak) = (pmax, l.theta(im), jm as f64 * dz);
    if pmax > 0.0 && jm > 0 && jm + 1 < nz {
        let at = |i: usize, j: usize| u[j * nt + i];
        let (pw, pe) = (at((im + nt - 1) % nt, jm), at((im + 1) % nt, jm));
        let (ps, pn) = (at(im, jm - 1), at(im, jm + 1));
        let mut extra = 0.0;
        let ct = pw - 2.0 * pmax + pe;
        if ct < 0.0 {
            let d = (0.5 * (pw - pe) / ct).clamp(-0.5, 0.5);
            th_peak += d * dt;
            extra += -0.125 * (pe - pw).powi(2) / ct;
        }
        let cz = ps - 2.0 * pmax + pn;
        if cz < 0.0 {
            let d = (0.5 * (ps - pn) / cz).clamp(-0.5, 0.5);
            z_peak += d * dz;
            extra += -0.125 * (pn - ps).powi(2) / cz;
        }
        p_peak += extra;
    }
    (p_peak, th_peak, z_peak)
}

/// Friction on the journal `(Couette term, pressure term)`: F̄ = ∫∫ (1/H + 3 H ∂P/∂θ) dθ dZ, the
/// pressure term integrated by parts to −3 ∫∫ P ∂H/∂θ (P is periodic or zero on the supply line).
fn friction(l: &Level, film: &Film) -> Result<(f64, f64), SolveError> {
    let (nt, nz, dt, dz) = (l.nt, l.nz, l.dt, l.dz);
    let u = &l.u;
    let (mut couette, mut press) = (0.0, 0.0);
    for j in 0..nz {
        let z = j as f64 * dz;
        let r = film.row(z);
        let a = 1.0 + r.gamma;
        let wz = if j == 0 || j + 1 == nz { 0.5 } else { 1.0 };
        let disc = a * a - r.x * r.x - r.y * r.y;
        if disc <= 0.0 {
            return Err(SolveError::physical(crate::PhysicalFailure::FilmClosed, "the film closes in the friction integral"));
        }
        couette += wz * TAU / disc.sqrt();
        let row = &u[j * nt..(j + 1) * nt];
        let mut s = 0.0;
        for i in 0..nt {
            let dh = -r.x * l.sin_n[i] + r.y * l.cos_n[i];
            s += row[i] * dh;
        }
        press += wz * (-3.0 * s * dt);
    }
    couette *= dz;
    press *= dz;
    Ok((couette, press))
}

/// Inflow across the supply line (column 0 with a groove; otherwise the column nearest the
/// mid-plane's largest film, at the attitude `beta`): Q/(RcNL) = π ∫ (H − H³ ∂P/∂θ) dZ.
fn supply_flow(l: &Level, bearing: &Bearing, beta: f64) -> f64 {
    let (nt, nz, dt, dz) = (l.nt, l.nz, l.dt, l.dz);
    let u = &l.u;
    let (groove, _) = bearing.groove_angle(beta);
    let i0 = if groove {
        0
    } else {
        let t = wrap_angle(beta - l.theta0);
        ((t / dt).round() as usize) % nt
    };
    let mut q = 0.0;
    for j in 0..nz {
        let wz = if j == 0 || j + 1 == nz { 0.5 } else { 1.0 };
        let at = |i: usize| u[j * nt + (i % nt)];
        // inflow across a supply line at column `c`: one-sided second-order ∂P/∂θ downstream
        let line = |c: usize| {
            let dp = (-3.0 * at(c) + 4.0 * at(c + 1) - at(c + 2)) / (2.0 * dt);
            let hh = l.h[j * nt + c];
            hh - hh * hh * hh * dp
        };
        if groove {
            q += wz * line(0);
            if let Some(c) = l.second_groove {
                q += wz * line(c);
            }
        } else {
            let dp = (at(i0 + 1) - at(i0 + nt - 1)) / (2.0 * dt);
            let hh = l.h[j * nt + i0];
            q += wz * (hh - hh * hh * hh * dp);
        }
    }
    PI * q * dz
}

/// Side flow Qs/(RcNL) = πα Σ_edges ∫ H³ |∂P/∂Z| dθ (`alpha` = (R/L)², [`Bearing::alpha`]),
/// one-sided second-order differences.
fn side_flow(l: &Level, alpha: f64) -> f64 {
    let (nt, nz, dt, dz) = (l.nt, l.nz, l.dt, l.dz);
    let u = &l.u;
    let mut qs = 0.0;
    for i in 0..nt {
        let at = |j: usize| u[j * nt + i];
        let d0 = (4.0 * at(1) - at(2)) / (2.0 * dz);
        let d1 = (4.0 * at(nz - 2) - at(nz - 3)) / (2.0 * dz);
        let h0 = l.h[i];
        let h1 = l.h[(nz - 1) * nt + i];
        qs += h0 * h0 * h0 * d0 + h1 * h1 * h1 * d1;
    }
    PI * alpha * qs * dt
}

/// Couette shear `∫∫ φ/H dθ dZ` with the film fraction `φ = 1` where the film is pressurised
/// and `φ = H_c/H` in the cavitated zone of each cross-section, `H_c` being the film at the
/// rupture line (located between nodes from `√P`, which is linear in θ there because the
/// Reynolds condition makes `P` and `∂P/∂θ` vanish together). A cross-section without a
/// rupture line (the edges, or pressure up to the supply line) counts as full.
fn striated_couette(l: &super::multigrid::Level, film: &Film) -> f64 {
    let (nt, nz, dt, dz) = (l.nt, l.nz, l.dt, l.dz);
    let u = &l.u;
    let mut total = 0.0;
    for j in 0..nz {
        let wz = if j == 0 || j + 1 == nz { 0.5 } else { 1.0 };
        let row = &u[j * nt..(j + 1) * nt];
        let h = &l.h[j * nt..(j + 1) * nt];
        // rupture: a pressurised node followed by a cavitated one (not the supply node 0)
        let mut hc = None;
        for i in 0..nt {
            let i1 = (i + 1) % nt;
            if i1 != 0 && row[i] > 0.0 && row[i1] <= 0.0 {
                let iw = (i + nt - 1) % nt;
                let (s1, s2) = (row[iw].max(0.0).sqrt(), row[i].sqrt());
                let t = if s1 > s2 { (s2 / (s1 - s2)).min(1.0) } else { 1.0 };
                let theta_c = l.theta(i) + t * dt;
                let z = j as f64 * dz;
                hc = Some(film.h(theta_c, z));
            }
        }
        let mut s = 0.0;
        for i in 0..nt {
            let phi = match hc {
                Some(c) if row[i] <= 0.0 => (c / h[i]).min(1.0),
                _ => 1.0,
            };
            s += phi / h[i];
        }
        total += wz * s * dt;
    }
    total * dz
}

