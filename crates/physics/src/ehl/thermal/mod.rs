//! Thermal line-contact EHL (seed 000 eq. 2, 4–5, 7–9): the generalized Reynolds equation with
//! effective density/viscosity integrals across the film, the film energy equation and heat
//! conduction into the two moving solids, coupled to the Newton solver of [`super::newton`].
//!
//! # Equations
//! Body 1 (the cam) is the surface `z = 0` moving at `u1`, body 2 (the roller) `z = h` at `u2`.
//! * **Film velocity** of a Newtonian (or Eyring, see below) film with viscosity varying across
//!   it: `τ(z) = τ_1 + z ∂p/∂x`, `∂u/∂z = τ/η`, so with `F0(z) = ∫0^z dz'/η` and
//!   `F1(z) = ∫0^z z'/η dz'`: `u = u1 + τ_1 F0 + ∂p/∂x F1`, `τ_1 = (u2 − u1 − ∂p/∂x F1(h))/F0(h)`.
//! * **Generalized Reynolds** (seed 000 eq. 2, Yang & Wen 1990): the mass flow is
//!   `m = (h/2)(u1 ρ*_1 + u2 ρ*_2) − (ρ/η)_e h³/12 ∂p/∂x` with `ρ_e = (1/h)∫ρ`,
//!   `ρ'_e = (1/h²)∫ρ F0`, `ρ''_e = (1/h³)∫ρ F1`, `η_e = h/F0(h)`, `η'_e = h²/F1(h)`,
//!   `(ρ/η)_e = 12(η_e ρ'_e/η'_e − ρ''_e)`, `ρ*_1 = 2(ρ_e − ρ'_e η_e)`, `ρ*_2 = 2ρ'_e η_e`. The
//!   Newton solver takes them as multipliers of its isothermal coefficients
//!   ([`ThermalFactors`]): `(ρ/η)_e/(ρ/η)_iso`, `(u1 ρ*_1 + u2 ρ*_2)/(2 u_m ρ_iso)` and
//!   `ρ_e/ρ_iso`, where `iso` is the lubricant at the inlet temperature and the node's pressure.
//!   Isothermal columns give exactly 1, 1, 1.
//! * **Film energy** (seed 000 eq. 7): `c_f ρ (u ∂T/∂x + ∂T/∂t) = k_f ∂²T/∂z² +
//!   (T ρ0 C3/ρ) u ∂p/∂x + η (∂u/∂z)²`: convection along the film, conduction across it,
//!   compressive heating of the Dowson–Higginson density (eq. 5, `∂ρ/∂T = −ρ0 C3`) and shear
//!   heating, with the vertical convection `−q ∂T/∂z` of eq. 7 from continuity. On the film's
//!   stretched levels `ζ = z/h` the two convection terms become
//!   `ρu ∂T/∂x|_ζ − (1/h) ∂M/∂x|_ζ ∂T/∂ζ` with `M = h ∫0^ζ ρu dζ'`.
//! * **Solids** (seed 000 eq. 8): `c_s ρ_s (u_s ∂T/∂x + ∂T/∂t) = k_s ∂²T/∂z²` in each body to
//!   the depth `d` (seed 000: `d = 3.15 b`) where `T = T0`; `T = T0` where the film and the
//!   solids enter the domain; temperature and heat flux continuous at the surfaces.
//! * **Viscosity and density** at each point: Roelands/Barus with temperature (eq. 4) and
//!   Dowson–Higginson with the thermal term (eq. 5), from [`Lubricant`].
//! * **Traction** (eq. 9): the surface shear stresses `τ_1` and `τ(h)` integrated along `x`.
//!
//! With an Eyring stress `τ_E` the film is the generalized Newtonian fluid of Yang & Wen: the
//! viscosity in every integral above is the effective `η* = η (τ/τ_E)/sinh(τ/τ_E)` at the
//! point's shear stress. Each column's stress `τ_1 + z ∂p/∂x` is solved exactly at the current
//! temperatures (the shear rates integrate to `u2 − u1`, [`eyring_column`]); an earlier form
//! lagged the stress by one sweep, which cannot converge where `τ > 1.9 τ_E` (the map
//! `s ← A s/sinh s` has the slope `1 − s coth s` at its fixed point) and ran away at the seed 001
//! nose. A limiting shear stress is not applied; a film hotter than the inlet by
//! [`MAX_TEMPERATURE_RISE`] ends the solve as a runaway (typed error).
//!
//! # Method
//! A column of nodes across cam, film and roller at every grid node of the EHL solution (the
//! solids graded geometrically from the surface towards the depth `d`, the film on
//! [`ThermalOptions::film_points`] uniform levels). Each column's equation is a finite-volume
//! conduction balance across it (flux continuity at the surfaces is built in), with upwind
//! convection along `x` by the sign of each node's velocity; columns are solved by the Thomas
//! algorithm in alternating Gauss–Seidel sweeps along `x` (reverse flow in the inlet and
//! surfaces moving in opposite directions need both sweep directions), the temperature-dependent
//! viscosity and heating updated between sweeps. The pressure and film come from the Newton
//! solver with the current [`ThermalFactors`]; the two are iterated until the films and the
//! temperature stop changing ([`ThermalOptions::tolerance`]).

use super::newton::{Engine, Prediction};
pub use super::newton::ThermalFactors;
use super::{EhlInput, EhlOptions, EhlSolution, Rheology, TractionResult};
use crate::lubricant::{DensityModel, Lubricant, DH_C3};
use crate::thermal::ThermalSolid;
use crate::{Convergence, Observer, SolveError, Termination};
use serde::{Deserialize, Serialize};

mod energy;
mod columns;
mod engine;
pub use energy::*;
use columns::*;
pub use engine::*;

/// Thermal properties of the lubricant.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct FilmHeat {
    /// Conductivity `k_f`, W/(m·K).
    pub conductivity: f64,
    /// Specific heat `c_f`, J/(kg·K).
    pub specific_heat: f64,
}

impl FilmHeat {
    /// Seed 000 Table 1: `k_f = 0.14` W/(m·K), `c_f = 1700` J/(kg·K).
    pub const SEED000: FilmHeat = FilmHeat { conductivity: 0.14, specific_heat: 1700.0 };
}

/// Thermal properties of the film and the two bodies (body 1 at `z = 0`, body 2 at `z = h`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ThermalBodies {
    pub film: FilmHeat,
    pub body_1: ThermalSolid,
    pub body_2: ThermalSolid,
}

impl ThermalBodies {
    /// Seed 000 Table 1: the oil and two steel bodies.
    pub const SEED000: ThermalBodies = ThermalBodies { film: FilmHeat::SEED000, body_1: ThermalSolid::STEEL, body_2: ThermalSolid::STEEL };
}

/// Resolution, tolerance and iteration caps of the thermal model.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct ThermalOptions {
    /// Levels across the film, both surfaces included (≥ 3).
    pub film_points: usize,
    /// Nodes in each solid from its surface to the depth `d`, both included (≥ 4).
    pub solid_points: usize,
    /// Depth `d` of the solids' thermal layer in Hertzian half-widths (seed 000: 3.15).
    pub solid_depth: f64,
    /// Relative change of the films (and 100× it of the largest temperature rise) between two
    /// coupling iterations at which the coupled solve stops.
    pub tolerance: f64,
    /// Most coupling iterations (energy ↔ Reynolds).
    pub max_iterations: u32,
    /// Most Gauss–Seidel sweeps of one energy solve.
    pub max_sweeps: u32,
    /// Largest temperature change of a sweep, relative to the largest temperature rise, at which
    /// an energy solve stops.
    pub sweep_tolerance: f64,
    /// The energy equation is solved where the film is at most this multiple of the minimum film
    /// (the contact and the near inlet and outlet); beyond, the oil and the solids are at the inlet
    /// temperature. The far inlet of a thick film (the Newton domain reaches 40 half-widths
    /// upstream) only recirculates heat: measured effect on the films below 0.1 % at 10.
    pub film_extent: f64,
    /// How the nonlinear energy equations are iterated (see [`EnergyIteration`]).
    pub iteration: EnergyIteration,
}

/// The iteration of the energy equations' nonlinearity (viscosity, velocities and heating
/// depend on the temperature).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
pub enum EnergyIteration {
    /// Gauss–Seidel sweeps updating the film's properties column by column, frozen after
    /// [`FREEZE_AFTER`] sweeps (stops on a noise floor of ≈ 2 % of the rise where the heating
    /// feeds back strongly).
    Sweeps,
    /// Outer fixed-point iteration on the temperature field with Anderson mixing (Walker & Ni,
    /// SIAM J. Numer. Anal. 49 (2011), type II, depth [`ANDERSON_DEPTH`]): each outer step
    /// updates every column's properties once at the current field and solves the then linear
    /// equations by sweeps (shear heating linearised about the outer iterate); the mixing cures
    /// the period-2 alternation of the hot mid-film and converges to the self-consistent field.
    /// The inlet and exit columns hold their mass flow (see [`HOLD_FLOW_PRESSURE`]); a solve that
    /// does not settle falls back to the sweeps. Not the default: on single contacts it agrees
    /// with the sweeps to 1e-4 (`thermal_ehl::energy_iterations_agree`), but on the seed 000
    /// cycle's traction tables (energy at a fixed pressure, other sliding) Newtonian layers in the
    /// Hertzian zone run away (|u| up to 66 m/s with surfaces at ≈ 2.5 m/s) and most solves fell
    /// back (BENCHMARKS.md, "Thermal EHL", issue 14 fourth session).
    Anderson,
}

impl Default for ThermalOptions {
    fn default() -> Self {
        ThermalOptions { film_points: 7, solid_points: 16, solid_depth: 3.15, tolerance: 1e-3, max_iterations: 40, max_sweeps: 200, sweep_tolerance: 1e-4, film_extent: 30.0, iteration: EnergyIteration::Sweeps }
    }
}

/// The temperature field, K, on the columns of one EHL grid.
#[derive(Debug, Clone, PartialEq)]
pub struct TemperatureField {
    /// Column positions, m.
    pub x: Vec<f64>,
    /// Film temperature at `film_points` uniform levels `ζ = z/h` (row-major: `x` then `ζ`).
    pub film: Vec<f64>,
    /// Body 1 temperature from its surface (first) to the depth `d`, at `solid_points` levels.
    pub body_1: Vec<f64>,
    /// Body 2 likewise.
    pub body_2: Vec<f64>,
    pub film_points: usize,
    pub solid_points: usize,
}

/// Heat flows per unit contact length, W/m, and temperatures of one energy solve.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct ThermalSummary {
    /// Largest film temperature, K.
    pub film_temperature_max: f64,
    /// Largest surface temperature of body 1 (cam) and body 2, K.
    pub surface_temperature_max_1: f64,
    pub surface_temperature_max_2: f64,
    /// Mean film temperature weighted by pressure, K (the film's temperature where it carries load).
    pub film_temperature_mean: f64,
    /// Heat generated in the film (shear + compression), W/m.
    pub heat_generated: f64,
    /// Heat taken up by body 1 and body 2 (carried out of the domain and conducted to the depth
    /// `d`, plus stored in a transient step), W/m.
    pub heat_to_body_1: f64,
    pub heat_to_body_2: f64,
    /// Heat carried out of the domain by the film, W/m.
    pub heat_convected: f64,
    /// Heat carried away across the columns' sides by the flow they lose (`ρ c` times the loss
    /// times the film's top-level temperature rise, summed along `x`), W/m: a row of a 2-D
    /// contact loses flow to its neighbours ([`crate::ehl::thermal_finite`]); in a line contact
    /// it is the pressure solution's discrete mass defect (not in `energy_balance_error`).
    pub heat_side: f64,
    /// `|generated − (to bodies + convected)| / generated` (0 without heat).
    pub energy_balance_error: f64,
    /// Gauss–Seidel sweeps of the last energy solve.
    pub sweeps: u32,
    /// The last sweep's largest temperature change relative to the largest rise (below
    /// `sweep_tolerance` when converged; up to 500× that when the sweeps stalled).
    pub sweep_change: f64,
}

/// One energy solve at a fixed pressure and film.
#[derive(Debug, Clone)]
pub struct EnergySolution {
    pub field: TemperatureField,
    pub factors: ThermalFactors,
    /// Surface shear forces per unit length (eq. 9) and the sliding friction coefficient.
    pub traction: TractionResult,
    pub summary: ThermalSummary,
}

/// What the energy equation needs besides the pressure and film.
#[derive(Debug, Clone, Copy)]
pub struct EnergyInput<'a> {
    /// Surface velocities of body 1 (`z = 0`) and body 2 (`z = h`), m/s.
    pub velocity_1: f64,
    pub velocity_2: f64,
    pub lubricant: &'a Lubricant,
    /// Inlet (ambient) temperature `T0`, K.
    pub inlet_temperature: f64,
    pub bodies: &'a ThermalBodies,
    /// Hertzian half-width `b`, m (sets the solids' depth).
    pub half_width: f64,
    /// Load per unit length, N/m (friction coefficient).
    pub load_per_length: f64,
    pub rheology: &'a Rheology,
    /// The previous time step's field and the time step, s (transient); `None`: steady.
    pub previous: Option<(&'a TemperatureField, f64)>,
    /// A field to start the sweeps from (any grid); `None`: the inlet temperature.
    pub warm: Option<&'a TemperatureField>,
    /// The pressure gradient at a column: `false` the central difference; `true` the smaller in
    /// magnitude of the two one-sided differences, zero where they differ in sign (minmod): a row
    /// of a coarse 2-D grid whose pressure drops by most of its peak within one cell at the exit
    /// would otherwise drive the low-pressure column's thin, hot oil with the drop's gradient
    /// (measured on seed 000's nose on 65×129: a 1280 K runaway at that column with the central
    /// difference; [`crate::ehl::thermal_finite`]).
    pub limited_gradient: bool,
}

/// Film quantities of one column at the current temperatures.
struct Column {
    /// Effective viscosity at the film levels, Pa·s, relative to `eta_ref`.
    eta: Vec<f64>,
    /// The Newtonian viscosity at the levels' temperatures (under-relaxed between sweeps),
    /// relative to `eta_ref`; `eta` is this times the Eyring factor.
    eta_n: Vec<f64>,
    rho: Vec<f64>,
    u: Vec<f64>,
    /// Shear stress at the film levels, Pa.
    tau: Vec<f64>,
    /// `−∂ ln η/∂T` at the film levels, 1/K.
    beta: Vec<f64>,
}

/// Sweeps after which an energy solve freezes the film's properties (see [`energy`]).
const FREEZE_AFTER: u32 = 40;

/// Mixing depth of [`EnergyIteration::Anderson`].
const ANDERSON_DEPTH: usize = 5;
/// Columns below this fraction of the peak pressure hold their mass flow (Anderson).
const HOLD_FLOW_PRESSURE: f64 = 0.3;
/// Share of `ThermalOptions::max_sweeps` an Anderson solve may use before the sweeps take over.
const ANDERSON_SWEEP_SHARE: f64 = 0.5;
/// Most linear sweeps of one Anderson outer step.
const ANDERSON_INNER_SWEEPS: u32 = 30;

/// Anderson mixing, type II (Walker & Ni 2011): from the last `depth + 1` pairs `(x_i, g_i =
/// G(x_i))` with residuals `f_i = g_i − x_i`, `γ = argmin ‖f_k − ΔF γ‖₂` (column-pivoted QR,
/// which also handles a rank-deficient history) and `x_{k+1} = g_k − ΔG γ`.
struct AndersonMixer {
    depth: usize,
    g: std::collections::VecDeque<Vec<f64>>,
    f: std::collections::VecDeque<Vec<f64>>,
}

/// A thermal EHL problem: the isothermal problem's input (its `temperature` is the inlet
/// temperature `T0`) and the thermal properties.
#[derive(Debug, Clone, Copy)]
pub struct ThermalInput<'a> {
    pub ehl: EhlInput<'a>,
    pub bodies: ThermalBodies,
    /// The previous time step's temperature field (with `ehl.transient`); `None`: steady
    /// temperatures.
    pub previous_temperature: Option<&'a TemperatureField>,
}

/// The solution of a thermal EHL problem.
#[derive(Debug, Clone)]
pub struct ThermalSolution {
    /// Films, pressures and state of the thermal solution; its `traction` is the thermal one.
    pub ehl: EhlSolution,
    pub temperature: TemperatureField,
    pub summary: ThermalSummary,
    /// The generalized Reynolds factors of the converged temperature field.
    pub factors: ThermalFactors,
    /// Coupling iterations; `residual` is the last relative change.
    pub convergence: Convergence,
}

/// `old` (on its positions) blended towards `new` by `w`: the Poiseuille factor geometrically,
/// the densities linearly, on `new`'s positions.
/// Largest temperature rise over the inlet temperature an energy solve may reach, K: beyond it
/// the oil has long decomposed and the Roelands/Dowson–Higginson laws (seed 000 eq. 4–5) are far
/// outside their range; the solve ends as a runaway (typed error). (400 K was too tight: the
/// sweeps of a Newtonian film at w' = 2e5 N/m, u_m = 5 m/s, S = 0.3 pass it on their way to a
/// converged 122 K rise.)
pub const MAX_TEMPERATURE_RISE: f64 = 1000.0;

/// Smallest step towards new generalized Reynolds factors after a failed Reynolds solve.
const MIN_FACTOR_STEP: f64 = 1.0 / 32.0;

/// A reusable thermal solver (grids, factorisations and the last temperature field survive between
/// solves): a cam cycle keeps one.
pub struct ThermalEngine {
    engine: Engine,
}

#[cfg(test)]
mod tests {
    use super::eyring_column;

    /// Couette flow of a uniform film (no pressure gradient): the Eyring stress is the closed
    /// form `τ = τ_E asinh(η Δu/(h τ_E))`, far beyond τ_E where the lagged iteration diverged.
    #[test]
    fn eyring_column_is_the_couette_closed_form() {
        let (nz, h, te, eta) = (7, 2.8e-7, 5e6, 4.0e3);
        let dz = h / (nz - 1) as f64;
        for du in [1e-4, 0.04, 0.4, 4.0] {
            let mut out = vec![0.0; nz];
            eyring_column(&vec![1.0; nz], eta, dz, du, 0.0, te, &mut out);
            let tau = te * (eta * du / (h * te)).asinh();
            // η* = τ/γ̇ with γ̇ = Δu/h.
            let expect = tau / (du / h) / eta;
            println!("Δu {du}: τ/τ_E {:.3}, η*/η {:.4e} (closed form {:.4e})", tau / te, out[3], expect);
            for v in &out {
                assert!((v - expect).abs() <= 1e-9 * expect, "{v} vs {expect}");
            }
        }
    }

    /// With a pressure gradient and viscosity varying across the film, the shear rates of the
    /// solved stress integrate to the surface speed difference (the constraint it solves).
    #[test]
    fn eyring_column_meets_the_speed_difference() {
        let (nz, h, te) = (9, 3e-7, 5e6);
        let dz = h / (nz - 1) as f64;
        let eta_ref = 1e4;
        let eta_n: Vec<f64> = (0..nz).map(|k| (-(0.5 * (k as f64 - 4.0)).powi(2)).exp() * 0.2 + 0.01).collect();
        for (du, px) in [(2.0, 3e12), (-1.0, -5e13), (0.0, 1e13)] {
            let mut out = vec![0.0; nz];
            eyring_column(&eta_n, eta_ref, dz, du, px, te, &mut out);
            // τ_k = η*_k γ̇_k with γ̇_k = (τ_E/η_k) sinh(τ_k/τ_E): recover τ_1 from level 0 and check
            // the trapezoidal ∫ γ̇ dz.
            let gam = |tau: f64, k: usize| te / (eta_n[k] * eta_ref) * (tau / te).sinh();
            // τ_k from η*_k: solve η*/η = s/sinh s at level 0 by bisection on s ≥ 0 with the sign
            // of the integral's τ_1 (found as the one meeting the constraint below).
            let ratio = out[0] / eta_n[0];
            let (mut lo, mut hi) = (0.0f64, 700.0f64);
            for _ in 0..200 {
                let mid = 0.5 * (lo + hi);
                let r = if mid > 1e-8 { mid / mid.sinh() } else { 1.0 };
                if r > ratio { lo = mid } else { hi = mid }
            }
            let s0 = 0.5 * (lo + hi);
            let best = [s0, -s0].into_iter().map(|s| {
                let t1 = s * te;
                let integral: f64 = (0..nz).map(|k| { let w = if k == 0 || k == nz - 1 { 0.5 * dz } else { dz }; w * gam(t1 + px * dz * k as f64, k) }).sum();
                (integral - du).abs()
            }).fold(f64::INFINITY, f64::min);
            println!("Δu {du} px {px:e}: τ_1/τ_E = ±{s0:.4}, constraint error {best:.3e} m/s");
            assert!(best < 1e-6 * du.abs().max(1e-3), "constraint error {best}");
        }
    }
}
