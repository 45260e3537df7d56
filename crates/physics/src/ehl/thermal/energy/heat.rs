//! What an energy solve hands back: the generalized Reynolds factors and the traction (seed 000
//! eq. 2, 9) of the film's properties at the converged field, the heat balance (generated,
//! convected out of the domain, conducted to the depth, stored) and the summary.

use super::convection::Convection;
use super::properties::FilmState;
use super::setup::EnergyGrid;
use super::*;

/// The solution of an energy solve that ended after `sweeps` with the change `last_change`,
/// from the film's properties at the final `field`.
pub(super) fn solution(g: &EnergyGrid, film: &FilmState, field: TemperatureField, sweeps: u32, last_change: f64) -> Result<EnergySolution, SolveError> {
    let n = g.n;
    let factors = reynolds_factors(g, film);
    // eq. 9: shear on body 1 (τ at z = 0) and on body 2 (−τ at z = h).
    let (mut f1, mut f2, mut roll) = (0.0, 0.0, 0.0);
    for i in 0..n {
        let col = &film.columns[i];
        f1 += g.wx[i] * col.tau[0];
        f2 -= g.wx[i] * col.tau[g.nz - 1];
        roll -= g.wx[i] * 0.5 * g.h[i] * g.dpdx[i];
    }
    let generated = heat_generated(g, film, &field);
    // Heat leaving: convected out through the domain ends (where each node's flow leaves), through
    // the depth boundaries, and stored (transient).
    let (a1, af, a2) = out_flux(g, film, &field, n - 1, 1.0);
    let (c1, cf_, c2) = out_flux(g, film, &field, 0, -1.0);
    let (deep_1, deep_2) = heat_to_depth(g, &field);
    let (store_1, store_2, store_f) = heat_stored(g, film, &field);
    let heat_to_body_1 = a1 + c1 + deep_1 + store_1;
    let heat_to_body_2 = a2 + c2 + deep_2 + store_2;
    let heat_convected = af + cf_ + store_f;
    let heat_side = heat_side(g, film, &field);
    let total_out = heat_to_body_1 + heat_to_body_2 + heat_convected;
    let energy_balance_error = if generated.abs() > 0.0 { ((generated - total_out) / generated).abs() } else { 0.0 };
    let (s1, s2) = field.surface_max();
    let (mut pw, mut pt) = (0.0, 0.0);
    for i in 0..n {
        let tm = field.film_column(i).iter().sum::<f64>() / g.nz as f64;
        pw += g.wx[i] * g.p[i].max(0.0);
        pt += g.wx[i] * g.p[i].max(0.0) * tm;
    }
    let film_temperature_mean = if pw > 0.0 { pt / pw } else { g.t0 };
    let summary = ThermalSummary {
        film_temperature_max: field.film_max(),
        surface_temperature_max_1: s1,
        surface_temperature_max_2: s2,
        film_temperature_mean,
        heat_generated: generated,
        heat_to_body_1,
        heat_to_body_2,
        heat_convected,
        heat_side,
        energy_balance_error,
        sweeps,
        sweep_change: last_change,
    };
    let traction = TractionResult {
        force_body_1: f1,
        force_body_2: f2,
        friction_coefficient: (f2 - f1) / (2.0 * g.input.load_per_length),
        rolling_force: roll,
    };
    crate::ensure_finite("thermal ehl", [&traction.force_body_1, &traction.force_body_2, &summary.film_temperature_max, &summary.heat_generated])?;
    Ok(EnergySolution { field, factors, traction, summary })
}

/// Generalized Reynolds factors of the columns (normalized column integrals).
fn reynolds_factors(g: &EnergyGrid, film: &FilmState) -> ThermalFactors {
    let (n, nz, u1, u2) = (g.n, g.nz, g.u1, g.u2);
    let mut factors = ThermalFactors { x: g.x.to_vec(), poiseuille: vec![1.0; n], wedge: vec![1.0; n], mass: vec![1.0; n] };
    let um = 0.5 * (u1 + u2);
    for i in 0..n {
        let col = &film.columns[i];
        let pi = g.p[i].max(0.0);
        let rho_iso = g.lub.density_ratio(pi, g.t0);
        // The effective integrals of the column and of the isothermal column (η̂ = 1, ρ = ρ_iso)
        // by the same quadrature: their ratios are exactly 1 at uniform temperature.
        let th = effective_integrals(&col.eta, &col.rho);
        let iso = effective_integrals(&vec![1.0; nz], &vec![rho_iso; nz]);
        let (rho_over_eta, rs1, rs2, re) = (th.0 / iso.0 * rho_iso, th.1 / iso.1 * rho_iso, th.2 / iso.2 * rho_iso, th.3 / iso.3 * rho_iso);
        factors.poiseuille[i] = (rho_over_eta / rho_iso).max(1e-12);
        factors.wedge[i] = if um.abs() > 1e-9 * (u1.abs() + u2.abs()) { (u1 * rs1 + u2 * rs2) / (2.0 * um * rho_iso) } else { re / rho_iso };
        factors.mass[i] = re / rho_iso;
    }
    factors
}

/// Heat generated in the film (shear and compression), W/m.
fn heat_generated(g: &EnergyGrid, film: &FilmState, field: &TemperatureField) -> f64 {
    let (nz, lub) = (g.nz, g.lub);
    let mut generated = 0.0;
    for i in 0..g.n {
        let col = &film.columns[i];
        let dz = 1.0 / (nz - 1) as f64;
        let dzd = g.h[i] * dz;
        let temps = field.film_column(i);
        for k in 0..nz {
            let wz = if k == 0 || k == nz - 1 { 0.5 * dzd } else { dzd };
            let rho = lub.density * col.rho[k];
            let shear = col.tau[k] * col.tau[k] / (col.eta[k] * film.eta_ref[i]);
            let comp = if g.compressive { temps[k] * lub.density * DH_C3 / rho * col.u[k] * g.dpdx[i] } else { 0.0 };
            generated += g.wx[i] * wz * (shear + comp);
        }
    }
    generated
}

/// `(body 1, film, body 2)` of `ρ c u (T − T0)` through the end column `i`, counted where the
/// velocity points out (`sign`: +1 at the downstream end `x_max`, −1 at `x_min`), W/m.
fn out_flux(g: &EnergyGrid, film: &FilmState, field: &TemperatureField, i: usize, sign: f64) -> (f64, f64, f64) {
    let (ns, nz, t0) = (g.ns, g.nz, g.t0);
    let col = &film.columns[i];
    let solid = |z: &[f64], rc: f64, u: f64, v: &[f64]| {
        if u * sign <= 0.0 {
            return 0.0;
        }
        let mut s = 0.0;
        for k in 1..ns {
            s += 0.5 * (z[k] - z[k - 1]) * ((v[i * ns + k - 1] - t0) + (v[i * ns + k] - t0));
        }
        rc * u.abs() * s
    };
    let b1 = solid(&g.z1, g.rc1, g.u1, &field.body_1);
    let b2 = solid(&g.z2, g.rc2, g.u2, &field.body_2);
    let dzd = g.h[i] / (nz - 1) as f64;
    let temps = field.film_column(i);
    let mut fl = 0.0;
    for k in 0..nz {
        if col.u[k] * sign > 0.0 {
            let wz = if k == 0 || k == nz - 1 { 0.5 * dzd } else { dzd };
            fl += wz * g.lub.density * col.rho[k] * g.cf * col.u[k].abs() * (temps[k] - t0);
        }
    }
    (b1, fl, b2)
}

/// Heat carried across the columns' sides by the flow they lose, W/m. The film's flow across its
/// levels follows from continuity ([`Convection`]) and leaves a column's net loss at its top level,
/// whose node convects it out at its own temperature (the donor-cell form): `Σ Δx (−leak)⁺ (T_top − T0)`.
fn heat_side(g: &EnergyGrid, film: &FilmState, field: &TemperatureField) -> f64 {
    let mut conv = Convection::new(g);
    conv.update(g, &film.columns);
    let mut side = 0.0;
    for i in 0..g.n {
        let lost = (-conv.leak[i]).max(0.0);
        side += g.wx[i] * lost * (field.film_column(i)[g.nz - 1] - g.t0);
    }
    side
}

/// Heat conducted through the depth boundaries of body 1 and body 2, W/m.
fn heat_to_depth(g: &EnergyGrid, field: &TemperatureField) -> (f64, f64) {
    let (ns, t0, bodies) = (g.ns, g.t0, g.bodies);
    let (z1, z2) = (&g.z1, &g.z2);
    let (mut deep_1, mut deep_2) = (0.0, 0.0);
    for i in 0..g.n {
        deep_1 += g.wx[i] * bodies.body_1.conductivity * (field.body_1[i * ns + ns - 2] - t0) / (z1[ns - 1] - z1[ns - 2]);
        deep_2 += g.wx[i] * bodies.body_2.conductivity * (field.body_2[i * ns + ns - 2] - t0) / (z2[ns - 1] - z2[ns - 2]);
    }
    (deep_1, deep_2)
}

/// Heat stored in body 1, body 2 and the film over the time step (transient; 0 steady), W/m.
fn heat_stored(g: &EnergyGrid, film: &FilmState, field: &TemperatureField) -> (f64, f64, f64) {
    let (ns, nz) = (g.ns, g.nz);
    let (z1, z2) = (&g.z1, &g.z2);
    let (mut store_1, mut store_2, mut store_f) = (0.0, 0.0, 0.0);
    let Some((of, dt)) = &g.old else { return (store_1, store_2, store_f) };
    for i in 0..g.n {
        for k in 0..ns {
            let w = 0.5 * (z1[(k + 1).min(ns - 1)] - z1[k.saturating_sub(1)]);
            store_1 += g.wx[i] * w * g.rc1 * (field.body_1[i * ns + k] - of.body_1[i * ns + k]) / dt;
            let w = 0.5 * (z2[(k + 1).min(ns - 1)] - z2[k.saturating_sub(1)]);
            store_2 += g.wx[i] * w * g.rc2 * (field.body_2[i * ns + k] - of.body_2[i * ns + k]) / dt;
        }
        let dzd = g.h[i] / (nz - 1) as f64;
        for k in 0..nz {
            let wz = if k == 0 || k == nz - 1 { 0.5 * dzd } else { dzd };
            store_f += g.wx[i] * wz * g.lub.density * film.columns[i].rho[k] * g.cf * (field.film[i * nz + k] - of.film[i * nz + k]) / dt;
        }
    }
    (store_1, store_2, store_f)
}
