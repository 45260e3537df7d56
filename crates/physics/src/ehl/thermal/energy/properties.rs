//! The film's properties across each column at its current temperatures: viscosity (under-relaxed
//! between sweeps, Eyring where the rheology has a stress), density, velocity and shear stress.

use super::setup::EnergyGrid;
use super::*;

/// The film's state over the columns of one energy solve.
pub(super) struct FilmState {
    pub(super) columns: Vec<Column>,
    /// Reference viscosity of each column (the lubricant at the inlet temperature and the
    /// column's pressure), Pa·s.
    pub(super) eta_ref: Vec<f64>,
    /// Under-relaxation weight of the viscosity (the sweeps' adaptive step; 1 otherwise).
    pub(super) relax: f64,
    /// The mass flow a column holds ([`EnergyGrid::holds_flow`]), NaN until the column is first
    /// evaluated.
    ///
    /// Columns below `HOLD_FLOW_PRESSURE` of the peak pressure (the inlet and the exit) hold their
    /// mass flow at its value when this solve first evaluates them (Anderson iteration only): at
    /// a fixed pressure gradient a heated layer at the exit would draw an unbounded Poiseuille flow
    /// (a runaway to 4× the surface speeds was measured at w' = 2e5 N/m, u_m = 5 m/s, S = 0.3),
    /// which the coupled Reynolds solution would not carry, and the inlet's backflow kept the
    /// mixing from settling. The gradient then follows the viscosity, never beyond the pressure's
    /// own (same sign, at most its size).
    flow_target: Vec<f64>,
}

impl FilmState {
    pub(super) fn new(g: &EnergyGrid) -> Self {
        let nz = g.nz;
        FilmState {
            columns: (0..g.n).map(|_| Column { eta: vec![1.0; nz], eta_n: vec![1.0; nz], rho: vec![1.0; nz], u: vec![0.0; nz], tau: vec![0.0; nz], beta: vec![0.0; nz] }).collect(),
            eta_ref: vec![1.0; g.n],
            relax: 1.0,
            flow_target: vec![f64::NAN; g.n],
        }
    }

    /// Every column's properties at the film temperatures of `field`.
    pub(super) fn update_all(&mut self, g: &EnergyGrid, field: &TemperatureField) {
        for i in 0..g.n {
            self.update(g, i, field.film_column(i));
        }
    }

    /// Film properties of column `i` at the film temperatures `temps` (and, for the Eyring
    /// viscosity, the stress solved at them).
    pub(super) fn update(&mut self, g: &EnergyGrid, i: usize, temps: &[f64]) {
        let nz = g.nz;
        let lub = g.lub;
        let (u1, u2) = (g.u1, g.u2);
        let col = &mut self.columns[i];
        let eta_ref = &mut self.eta_ref[i];
        let hi = g.h[i];
        let dz = hi / (nz - 1) as f64;
        let pi = g.p[i].max(0.0);
        let law = lub.pressure_law(pi);
        // Reference viscosity: the lubricant at the inlet temperature and this pressure.
        let ln_ref = (g.ln_eta0 + law.ln_ratio_and_temperature_slope(g.t0).0).min(600.0 + g.ln_eta0);
        *eta_ref = ln_ref.exp();
        for k in 0..nz {
            let (ln_ratio, ln_slope) = law.ln_ratio_and_temperature_slope(temps[k]);
            let ln_e = (g.ln_eta0 + ln_ratio).min(600.0 + g.ln_eta0);
            let w = self.relax;
            let ln_new = ln_e - ln_ref;
            let ln_rel = if w < 1.0 && col.eta_n[k] > 0.0 && col.u.iter().any(|&u| u != 0.0) { (1.0 - w) * col.eta_n[k].ln() + w * ln_new } else { ln_new };
            col.eta_n[k] = ln_rel.exp().max(1e-300);
            col.eta[k] = col.eta_n[k];
            col.beta[k] = -ln_slope;
            col.rho[k] = lub.density_ratio(pi, temps[k]);
        }
        if let Some(te) = g.eyring {
            // The column's Eyring stress solved exactly at these viscosities: the lagged form
            // (η* from the previous sweep's stress) is unstable wherever τ > 1.9 τ_E — its
            // fixed-point map s ← A s/sinh s has the slope 1 − s coth s at s = asinh A — and ran
            // away in the first sweep at the seed 001 nose (1.4 GPa, τ_E = 5 MPa).
            eyring_column(&col.eta_n, *eta_ref, dz, u2 - u1, g.dpdx[i], te, &mut col.eta);
        }
        // F0, F1 in units of dz/η_ref.
        let mut f0 = vec![0.0; nz];
        let mut f1 = vec![0.0; nz];
        for k in 1..nz {
            f0[k] = f0[k - 1] + 0.5 * dz * (1.0 / col.eta[k - 1] + 1.0 / col.eta[k]);
            f1[k] = f1[k - 1] + 0.5 * dz * (dz * (k - 1) as f64 / col.eta[k - 1] + dz * k as f64 / col.eta[k]);
        }
        let mut px = g.dpdx[i];
        if g.holds_flow(i) {
            px = held_gradient(g, col, *eta_ref, dz, &f0, &f1, px, &mut self.flow_target[i]);
        }
        // Dimensional: F0 = f0/η_ref, F1 = f1/η_ref.
        let tau1 = ((u2 - u1) * *eta_ref - px * f1[nz - 1]) / f0[nz - 1];
        for k in 0..nz {
            col.u[k] = u1 + (tau1 * f0[k] + px * f1[k]) / *eta_ref;
            col.tau[k] = tau1 + px * dz * k as f64;
        }
    }
}

/// The pressure gradient of a column that holds its mass flow `target` (set to the flow at `px`
/// when still NaN): the gradient giving that flow at the column's viscosities, within `[0, px]`
/// (or `[px, 0]`).
#[allow(clippy::too_many_arguments)]
fn held_gradient(g: &EnergyGrid, col: &Column, eta_ref: f64, dz: f64, f0: &[f64], f1: &[f64], px: f64, target: &mut f64) -> f64 {
    let nz = g.nz;
    let (u1, u2) = (g.u1, g.u2);
    // Mass flow per unit width (trapezoidal over the levels, units ρ0·m²/s) as
    // `A + px·B`: u_k = u1 + (u2 − u1) f0_k/f0_h + px (f1_k − f1_h f0_k/f0_h)/η_ref.
    let (f0h, f1h) = (f0[nz - 1], f1[nz - 1]);
    let (mut a, mut bcoef) = (0.0, 0.0);
    for k in 0..nz {
        let w = if k == 0 || k == nz - 1 { 0.5 * dz } else { dz };
        a += w * col.rho[k] * (u1 + (u2 - u1) * f0[k] / f0h);
        bcoef += w * col.rho[k] * (f1[k] - f1h * f0[k] / f0h) / eta_ref;
    }
    if target.is_nan() {
        *target = a + px * bcoef;
        px
    } else if bcoef.abs() > 0.0 {
        let want = (*target - a) / bcoef;
        if px > 0.0 { want.clamp(0.0, px) } else { want.clamp(px, 0.0) }
    } else {
        px
    }
}
