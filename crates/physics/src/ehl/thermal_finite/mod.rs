//! Thermal EHL of finite line (crowned roller) and point contacts: seed 000's cam–roller model
//! (eq. 2–9 on the crowned roller of eq. 3), the 2-D solver of [`super::twod`] coupled to the film
//! and solid energy equations of [`super::thermal`].
//!
//! # Model
//! * **Pressure and film** (seed 000 eq. 2, 3, 6): the 2-D compressible Reynolds equation of
//!   [`super::twod`] with the generalized Reynolds coefficients of a film whose viscosity and
//!   density vary across it ([`Factors2d`]: the Poiseuille coefficient `(ρ/η)_e` in both
//!   directions — the flow across the entrainment has no shear-driven part — and the wedge density
//!   `(u1 ρ*_1 + u2 ρ*_2)/(2u_m)`, Yang & Wen 1990), the crowned roller's gap, the elastic
//!   half-space and the load balance.
//! * **Temperatures** (seed 000 eq. 7–8): at each row `y = const` of the 2-D grid the temperature
//!   across the film and along `x`, with the two solids below and above, from that row's `p(x)`,
//!   `h(x)` and the surface speeds — the 1-D energy solver [`super::thermal::energy`] unchanged.
//!   Seed 000 neglects conduction along `x` and `y` (eq. 7); this model also neglects convection
//!   along `y`. The flow along `y` is pure Poiseuille and small against the entrainment inside the
//!   contact; the flow a row loses to its neighbours leaves it at the row's temperature (counted in
//!   the heat balance, [`ThermalSummary::heat_side`]), and the flow it gains enters at the inlet
//!   temperature. Chosen over a 3-D field because it reuses the 1-D solver as it is (its sweeps,
//!   solids and Eyring columns), the rows are independent (one thread each) and a straight roller's
//!   mid-plane is then the 1-D thermal line contact in the limit of a long roller (checked:
//!   `thermal_finite::long_roller_mid_plane_is_the_line_contact`). Rows carrying less than
//!   [`ROW_PRESSURE`] of the peak pressure (the unloaded ends of a crowned roller) keep the inlet
//!   temperature.
//! * **Traction** (seed 000 eq. 9): each row's surface shear stresses integrated along `x`, then
//!   the rows along `y` (trapezoidal): forces on the cam and the roller, N, and the friction
//!   coefficient `(F2 − F1)/(2W)` of the whole contact.
//! * **Rheology**: Newtonian as seed 000, or the Eyring stress of [`Rheology`] in the energy
//!   columns (the generalized Newtonian fluid of [`super::thermal`]).
//!
//! # Method
//! The isothermal 2-D solution first; then the fixed point of the 1-D thermal engine: the row
//! energies at the current pressure and film give new factors, under-relaxed (geometric mean for
//! the Poiseuille factor) with a step that shrinks when the change grows, and the 2-D solve
//! restarts warm from the last solution (and its preconditioner) with the factors fixed, until
//! the central and minimum films change by less than [`ThermalOptions::tolerance`] (and the
//! largest temperature rise by less than 100× it). A row's energy solve starts from its field of
//! the previous iteration. With every factor 1 the 2-D problem is the isothermal one bit for bit
//! (`thermal_finite::factors_of_one_are_the_isothermal_solution`).

use super::thermal::{energy, thermal_range, EnergyInput, EnergyIteration, TemperatureField, ThermalBodies, ThermalOptions, ThermalSummary};
use super::twod::{solve_factored, Ehl2dInput, Ehl2dOptions, Ehl2dSolution, Factors2d, Kept2d, Located, Warm2d};
use super::{Rheology, TractionResult};
use crate::{Convergence, Observer, SolveError, Termination};

mod coupling;
mod rows;

pub use coupling::*;
use rows::*;

/// Rows whose largest pressure is below this fraction of the contact's peak keep the inlet
/// temperature (their factors are 1): the unloaded ends of a roller, whose thick film hardly heats.
pub const ROW_PRESSURE: f64 = 1e-3;

/// One thermal finite-line or point EHL problem, SI units.
#[derive(Debug, Clone, Copy)]
pub struct ThermalFiniteInput {
    /// The isothermal problem; its `temperature` is the inlet temperature `T0`.
    pub ehl: Ehl2dInput,
    /// Sliding velocity `u1 − u2` along the entrainment, m/s (body 1 at `z = 0`: the cam).
    pub sliding_velocity: f64,
    /// Shear law of the film (Newtonian: no Eyring stress).
    pub rheology: Rheology,
    pub bodies: ThermalBodies,
}

/// The temperatures, heat and traction of one row `y = const` of the grid.
#[derive(Debug, Clone, PartialEq)]
pub struct RowThermal {
    /// Position along the roller axis (across the entrainment), m.
    pub y: f64,
    /// Temperatures and heat flows per unit length of the row (W/m).
    pub summary: ThermalSummary,
    /// Surface shear forces per unit length of the row, N/m.
    pub traction: TractionResult,
    /// Film at `x = 0` and smallest film of the row, m; largest pressure of the row, Pa.
    pub central_film: f64,
    pub min_film: f64,
    pub max_pressure: f64,
}

/// Heat flows of the whole contact, W.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct HeatBalance {
    /// Generated in the film (shear and compression).
    pub generated: f64,
    /// Taken up by body 1 and body 2 (conducted to the depth and carried out of the domain).
    pub to_body_1: f64,
    pub to_body_2: f64,
    /// Carried out of the rows' ends by the film.
    pub convected: f64,
    /// Carried across the rows' sides by the flow they lose ([`ThermalSummary::heat_side`]).
    pub side: f64,
    /// `|generated − (to bodies + convected + side)| / generated` (0 without heat).
    pub error: f64,
}

/// Forces on the two bodies from the film shear integrated over the contact (seed 000 eq. 9).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct ContactTraction {
    /// Shear force on body 1 (cam) and on body 2 along +x, N.
    pub force_body_1: f64,
    pub force_body_2: f64,
    /// Sliding friction coefficient `(F2 − F1)/(2W)`, signed like the sliding velocity.
    pub friction_coefficient: f64,
    /// Rolling (Poiseuille) resistance on each body, N.
    pub rolling_force: f64,
}

/// The solution of a thermal finite-line or point problem.
#[derive(Debug, Clone)]
pub struct ThermalFiniteSolution {
    /// Films and pressures of the thermal solution (its `fields` when the options ask for them).
    pub ehl: Ehl2dSolution,
    /// Central film of the isothermal solution at the inlet temperature, m (a cold start only:
    /// a solve carried from a neighbouring problem's factors has none).
    pub isothermal_central_film: Option<f64>,
    /// Smallest film of the isothermal solution, m (likewise).
    pub isothermal_min_film: Option<f64>,
    /// Largest film temperature, K, and where.
    pub film_temperature_max: Located,
    /// Largest surface temperatures of body 1 and body 2, K.
    pub surface_temperature_max_1: f64,
    pub surface_temperature_max_2: f64,
    /// The rows whose energy was solved, ascending in `y`.
    pub rows: Vec<RowThermal>,
    pub heat: HeatBalance,
    pub traction: ContactTraction,
    /// The generalized Reynolds factors of the converged temperatures.
    pub factors: Factors2d,
    /// Coupling iterations (energy ↔ Reynolds) and the last relative change.
    pub convergence: Convergence,
}

impl ThermalFiniteSolution {
    /// The solved row nearest `y` (m).
    pub fn row_near(&self, y: f64) -> Option<&RowThermal> {
        self.rows.iter().min_by(|a, b| (a.y - y).abs().total_cmp(&(b.y - y).abs()))
    }
}

#[cfg(test)]
mod tests;
