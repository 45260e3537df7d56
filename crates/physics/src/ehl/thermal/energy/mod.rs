//! The energy equations of one thermal EHL solve at a fixed pressure and film ([`energy`]), one
//! stage per file:
//!
//! * [`setup`]: the columns' fixed data ([`EnergyGrid`]: node layout, solid depths, pressure
//!   gradient, x weights) and the start field.
//! * [`properties`]: the film's properties across each column at its temperatures
//!   ([`FilmState`]: viscosity, density, velocity, shear stress; the held mass flows).
//! * [`convection`]: the convective heat-capacity fluxes along and across the film.
//! * [`sweep`]: one Gauss–Seidel sweep over the columns (each column's conduction–convection
//!   balance assembled and solved by [`thomas`]).
//! * [`iteration`]: the sweeps, or Anderson's outer steps, to convergence or a stall.
//! * [`heat`]: the generalized Reynolds factors, traction and heat balance of the solution.

use super::*;

mod convection;
mod heat;
mod iteration;
mod properties;
mod setup;
mod sweep;

use heat::solution;
use iteration::iterate;
use properties::FilmState;
use setup::EnergyGrid;

/// Thomas algorithm for `a_i x_{i−1} + b_i x_i + c_i x_{i+1} = r_i` (in place into `r`).
pub(super) fn thomas(a: &[f64], b: &mut [f64], c: &[f64], r: &mut [f64]) {
    let n = b.len();
    for i in 1..n {
        let w = a[i] / b[i - 1];
        b[i] -= w * c[i - 1];
        r[i] -= w * r[i - 1];
    }
    r[n - 1] /= b[n - 1];
    for i in (0..n - 1).rev() {
        r[i] = (r[i] - c[i] * r[i + 1]) / b[i];
    }
}

/// Solve the energy equations (seed 000 eq. 7–8) on the columns of `(x, p, h)` (m, Pa, m).
/// With [`EnergyIteration::Anderson`], a solve that does not converge within
/// [`ANDERSON_SWEEP_SHARE`] of `max_sweeps` (the mixing cycles, or a layer's flow runs away at
/// the fixed pressure) is solved again from the same start by [`EnergyIteration::Sweeps`].
pub fn energy(x: &[f64], p: &[f64], h: &[f64], input: &EnergyInput, options: &ThermalOptions) -> Result<EnergySolution, SolveError> {
    if options.iteration != EnergyIteration::Anderson {
        return energy_iterated(x, p, h, input, options);
    }
    let budget = ((options.max_sweeps as f64 * ANDERSON_SWEEP_SHARE) as u32).max(1);
    match energy_iterated(x, p, h, input, &ThermalOptions { max_sweeps: budget, ..*options }) {
        Ok(s) => Ok(s),
        Err(SolveError::NotConverged { .. }) => {
            energy_iterated(x, p, h, input, &ThermalOptions { iteration: EnergyIteration::Sweeps, ..*options })
        }
        Err(e) => Err(e),
    }
}

/// One energy solve by the iteration `options.iteration` selects (see [`energy`]): the columns'
/// fixed data ([`EnergyGrid`]), the film's properties at the start field, the iteration
/// ([`iterate`]), the film's properties at the converged field, then the Reynolds factors,
/// traction and heat balance ([`solution`]).
pub(super) fn energy_iterated(x: &[f64], p: &[f64], h: &[f64], input: &EnergyInput, options: &ThermalOptions) -> Result<EnergySolution, SolveError> {
    let grid = EnergyGrid::new(x, p, h, input, options)?;
    let mut field = grid.start_field();
    let mut film = FilmState::new(&grid);
    film.update_all(&grid, &field);
    let (sweeps, last_change) = iterate(&grid, &mut film, &mut field)?;
    // Final column quantities at the converged temperatures.
    film.update_all(&grid, &field);
    solution(&grid, &film, field, sweeps, last_change)
}

/// The generalized Reynolds integrals of one column (seed 000 eq. 2) at uniform levels
/// `ζ = z/h` with viscosity `η̂` (relative) and density ratio `ρ̄`, trapezoidal:
/// `((ρ/η)_e, ρ*_1, ρ*_2, ρ_e)` in units of `ρ̄/η̂`.
pub(super) fn effective_integrals(eta: &[f64], rho: &[f64]) -> (f64, f64, f64, f64) {
    let nz = eta.len();
    let dz = 1.0 / (nz - 1) as f64;
    let (mut f0, mut f1) = (0.0, 0.0);
    let (mut re, mut re1, mut re2) = (0.0, 0.0, 0.0);
    let mut prev = (rho[0], 0.0, 0.0);
    for k in 1..nz {
        let zk = k as f64 * dz;
        f0 += 0.5 * dz * (1.0 / eta[k - 1] + 1.0 / eta[k]);
        f1 += 0.5 * dz * ((zk - dz) / eta[k - 1] + zk / eta[k]);
        let cur = (rho[k], rho[k] * f0, rho[k] * f1);
        re += 0.5 * dz * (prev.0 + cur.0);
        re1 += 0.5 * dz * (prev.1 + cur.1);
        re2 += 0.5 * dz * (prev.2 + cur.2);
        prev = cur;
    }
    let eta_e = 1.0 / f0;
    let eta_e1 = 1.0 / f1;
    (12.0 * (eta_e * re1 / eta_e1 - re2), 2.0 * (re - re1 * eta_e), 2.0 * re1 * eta_e, re)
}

/// Temperature of column node `j` (column layout of [`energy`]) at column `i` of `f`.
pub(super) fn node_temperature(f: &TemperatureField, i: usize, j: usize, ns: usize, nz: usize, i_film0: usize, i_film1: usize) -> f64 {
    if j < i_film0 {
        f.body_1[i * ns + (ns - 1 - j)]
    } else if j >= i_film1 {
        f.body_2[i * ns + (j - i_film1)]
    } else {
        f.film[i * nz + (j - i_film0)]
    }
}
