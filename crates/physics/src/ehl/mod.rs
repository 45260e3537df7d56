//! Isothermal line-contact elastohydrodynamic lubrication (EHL), solved numerically.
//!
//! # Equations (dimensionless with the Hertzian half-width `b` and peak pressure `p_h`)
//! `X = x/b`, `P = p/p_h`, `H = h R/b²`, `ρ̄ = ρ/ρ0`, `η̄ = η/η(0, T)`:
//! * compressible Reynolds with squeeze (seed 000 eq. 2, seed 001 eq. 5, seed 003 eq. 7 reduced
//!   to one dimension):
//!   `d/dX(ρ̄H³/η̄ dP/dX) − λ d(ρ̄H)/dX − κ ∂(ρ̄H)/∂t̂ = 0`, with
//!   `λ = 12 η0 u_m R²/(b³ p_h)` (signed: entrainment reversal flips the upwind direction) and
//!   `κ = 12 η0 R²/(b² p_h Δt)` (backward Euler in time);
//! * film (seed 000 eq. 3, seed 001 eq. 6, seed 003 eq. 11):
//!   `H = H0 + X²/2 − (1/π) ∫ ln|X − X'| P(X') dX'` ([`elastic`]);
//! * load balance (seed 000 eq. 6, seed 001 eq. 7): `∫ P dX = π/2`;
//! * cavitation as a complementarity problem: `P ≥ 0`, Reynolds residual `≤ 0`, product zero;
//! * rheology from [`Lubricant`]: Barus or Roelands viscosity (seed 000 eq. 4), Dowson–Higginson
//!   density (seed 000 eq. 5, seed 003 eq. 10), both at the given (uniform) temperature.
//!
//! # Method
//! A damped semismooth Newton method on the fully coupled system `(P, H0)` ([`newton`]):
//! second-order upwind finite differences for the wedge term (first order selectable), central
//! differences for the Poiseuille term, exact cell integrals for the elastic kernel, and the
//! complementarity handled by the `min(P, −F/|J_ii|)` reformulation (a primal–dual active set).
//! The Jacobian is dense (the elastic coupling is global); each Newton step solves it by GMRES
//! preconditioned with the LU factors of an earlier Jacobian on the same grid, and factorises
//! afresh (faer, partial pivoting) only when that stops converging. Chosen over Venner–Lubrecht
//! multigrid by measurement of what the service needs (see `BENCHMARKS.md`, "Numerical EHL"):
//! at the 128–512 nodes that resolve the films to well under 1 % the direct method is robust from
//! light loads to the dry limit, and a cam angle warm-started from the previous one costs 1–2
//! Newton steps.
//!
//! # Sequences of problems
//! [`TransientSolver`] solves the angles of a cycle one after the other and keeps what does not
//! change between them: the grid in Hertzian coordinates and its influence matrix
//! ([`grid`]), the LU factors, the workspace, and the last two solutions for a time predictor.
//! With [`Extrapolation::Richardson`] it marches two grids side by side (two threads) and
//! extrapolates the films; a 720-angle cycle then takes about half a second with the films within
//! 0.5 % of the grid-converged cycle. Use it rather than calling [`solve`] per angle.
//!
//! # Not modelled
//! The solver itself is isothermal at [`EhlInput::temperature`]; [`thermal`] couples it to the
//! film and solid energy equations (seed 000 eq. 2, 7–8) through the generalized Reynolds
//! equation's effective coefficients. The Reynolds equation is Newtonian (seed 001 makes the same
//! choice); non-Newtonian behaviour enters only the traction ([`traction`]). Rough surfaces enter
//! through load sharing ([`EhlInput::asperity`], seed 001 eq. 1, 7): the mean asperity pressure
//! of the local film adds to the fluid pressure in the load balance and the deflection (the
//! Newton unknown is then the total pressure; see [`newton`]); the film is the smooth-surface
//! Reynolds film of the mean gap (no flow factors).

pub mod elastic;
pub mod formulas;
pub mod grid;
mod linear;
pub mod newton;
pub(crate) mod rheology;
pub mod thermal;
pub mod thermal_finite;
pub mod traction;
pub mod transient;
pub mod twod;

pub use newton::{solve, SolverStats};
pub use traction::{Rheology, TractionResult};
pub use transient::{Extrapolation, ReusableSolver, RichardsonSolution, TransientSolver};

use crate::lubricant::Lubricant;
use crate::Convergence;
use serde::{Deserialize, Serialize};

/// Discretisation of the wedge (Couette) term `d(ρ̄H)/dX`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Upwind {
    /// First-order upwind: the most diffusive and robust, `O(Δ)`.
    First,
    /// Second-order upwind (`(3q_i − 4q_{i−1} + q_{i−2})/2Δ`), `O(Δ²)`.
    #[default]
    Second,
}

/// Resolution, tolerance and iteration cap of the solver.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct EhlOptions {
    /// Grid nodes across the computational domain (including both boundary nodes), ≥ 16.
    pub nodes: usize,
    /// Tolerance on the residual: the larger of the relative load-balance error and the largest
    /// scaled Reynolds/complementarity residual `|min(P, −F/|J_ii|)|` divided by the peak pressure.
    pub tolerance: f64,
    /// Most Newton steps (per continuation stage).
    pub max_iterations: u32,
    /// Inlet distance from the contact centre in Hertzian half-widths, upstream; `None` chooses
    /// `max(4.5, 16 sqrt(2 H_est))` from a film estimate (far enough for a fully flooded inlet).
    pub inlet: Option<f64>,
    /// Outlet distance in half-widths, downstream; `None` chooses `max(1.5, 1.5 sqrt(2 H_est))`.
    pub outlet: Option<f64>,
    /// Wedge-term discretisation.
    pub upwind: Upwind,
    /// Grade the grid towards the inlet edge and the exit constriction (see
    /// [`newton::graded_grid`]); `false`: uniform.
    pub grading: bool,
    /// Return the pressure and film profiles.
    pub profiles: bool,
}

impl Default for EhlOptions {
    fn default() -> Self {
        EhlOptions {
            nodes: 256,
            tolerance: 1e-8,
            max_iterations: 60,
            inlet: None,
            outlet: None,
            upwind: Upwind::Second,
            grading: true,
            profiles: false,
        }
    }
}

/// The converged fields of one solve, kept to warm-start the next one and to form the squeeze
/// term of a transient step. Dimensional, in the contact frame (x = 0 at the contact centre).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct EhlState {
    /// Node positions, m (increasing, graded).
    pub x: Vec<f64>,
    /// Pressure, Pa.
    pub pressure: Vec<f64>,
    /// Film thickness, m.
    pub film: Vec<f64>,
    /// Density ratio `ρ/ρ0`.
    pub density_ratio: Vec<f64>,
    /// Asperity part of `pressure`, Pa, when the asperities share the load
    /// ([`EhlInput::asperity`]); empty for smooth surfaces. `pressure` is the total (fluid plus
    /// asperity) pressure that deflects the surfaces; the fluid's is the difference.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub asperity_pressure: Vec<f64>,
}

impl EhlState {
    /// Fluid (hydrodynamic) pressure at node `i`, Pa.
    pub fn fluid_pressure(&self, i: usize) -> f64 {
        (self.pressure[i] - self.asperity_pressure.get(i).copied().unwrap_or(0.0)).max(0.0)
    }

    /// Index `i ≥ 1` with `x[i−1] ≤ at ≤ x[i]` and the weight of `x[i]`, for `at` inside the grid.
    fn locate(&self, at: f64) -> (usize, f64) {
        let n = self.x.len();
        let i = self.x.partition_point(|&v| v <= at).clamp(1, n - 1);
        let t = ((at - self.x[i - 1]) / (self.x[i] - self.x[i - 1])).clamp(0.0, 1.0);
        (i, t)
    }

    /// `(ρ/ρ0) h` at `x` (m), linear between nodes; beyond the stored domain the film follows the
    /// undeformed parabola of radius `radius` from the nearest end, at the end's density.
    pub fn mass_per_area(&self, x: f64, radius: f64) -> f64 {
        let n = self.x.len();
        if x <= self.x[0] || x >= self.x[n - 1] {
            let k = if x <= self.x[0] { 0 } else { n - 1 };
            return self.density_ratio[k] * self.film_at(x, radius);
        }
        let (i, t) = self.locate(x);
        let q = |k: usize| self.density_ratio[k] * self.film[k];
        q(i - 1) * (1.0 - t) + q(i) * t
    }

    /// Pressure at `x` (m), linear between nodes, 0 outside the stored domain.
    pub fn pressure_at(&self, x: f64) -> f64 {
        let n = self.x.len();
        if x <= self.x[0] || x >= self.x[n - 1] {
            return 0.0;
        }
        let (i, t) = self.locate(x);
        self.pressure[i - 1] * (1.0 - t) + self.pressure[i] * t
    }

    /// Film at `x` (m), linear between nodes; the undeformed parabola beyond the ends.
    pub fn film_at(&self, x: f64, radius: f64) -> f64 {
        let n = self.x.len();
        let (x0, x1) = (self.x[0], self.x[n - 1]);
        if x <= x0 {
            return self.film[0] + (x * x - x0 * x0) / (2.0 * radius);
        }
        if x >= x1 {
            return self.film[n - 1] + (x * x - x1 * x1) / (2.0 * radius);
        }
        let (i, t) = self.locate(x);
        self.film[i - 1] * (1.0 - t) + self.film[i] * t
    }
}

/// A transient step: the state at the previous time and the time elapsed since.
#[derive(Debug, Clone, Copy)]
pub struct Transient<'a> {
    /// Converged state of the previous step.
    pub previous: &'a EhlState,
    /// Time step, s (> 0).
    pub time_step: f64,
}

/// One line-contact EHL problem. SI units; `E'` is the EHL modulus `2E*`.
#[derive(Debug, Clone, Copy)]
pub struct EhlInput<'a> {
    /// Normal load per unit length `w'`, N/m (> 0).
    pub load_per_length: f64,
    /// Reduced radius of curvature `R` in the rolling direction, m (> 0).
    pub reduced_radius: f64,
    /// `E' = 2/Σ(1−ν²)/E`, Pa (Hamrock–Dowson convention).
    pub effective_modulus: f64,
    /// Entrainment (mean rolling) velocity `u_m = (u1 + u2)/2`, m/s; negative reverses the flow.
    pub entrainment_velocity: f64,
    /// Sliding velocity `u_s = u1 − u2`, m/s (enters the traction only).
    pub sliding_velocity: f64,
    pub lubricant: Lubricant,
    /// Film temperature, K (isothermal).
    pub temperature: f64,
    /// Shear rheology for the traction.
    pub rheology: Rheology,
    /// Squeeze: the previous state and time step (a transient step). `None`: steady state.
    pub transient: Option<Transient<'a>>,
    /// Warm start from a state (usually the previous cam angle); ignored when `transient` is
    /// set (the previous state is the warm start then).
    pub warm_start: Option<&'a EhlState>,
    /// Mixed lubrication: the asperities share the load inside the solution (seed 001 eq. 1, 7):
    /// the mean asperity pressure `p_a(h)` of the local film adds to the fluid pressure in the
    /// load balance and in the elastic deflection. `None`: smooth surfaces.
    pub asperity: Option<&'a dyn AsperityPressure>,
}

/// Mean asperity contact pressure as a function of the local film (seed 001 eq. 12: the
/// "h–p̄_a curve"; Greenwood–Tripp is one such relation). Must be finite, non-negative and
/// non-increasing in `film`.
pub trait AsperityPressure: std::fmt::Debug + Send + Sync {
    /// `(p_a, dp_a/dh)` at film `h` (m): Pa and Pa/m.
    fn pressure(&self, film: f64) -> (f64, f64);
}

/// A pressure spike (the secondary maximum in the exit region).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct PressureSpike {
    /// Peak pressure of the spike, Pa.
    pub pressure: f64,
    /// Position, m from the contact centre (positive downstream in the direction of `x`).
    pub position: f64,
}

/// Pressure and film profiles.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Profiles {
    /// Position from the contact centre, m.
    pub x: Vec<f64>,
    /// Pressure, Pa.
    pub pressure: Vec<f64>,
    /// Film thickness, m.
    pub film: Vec<f64>,
    /// Asperity part of `pressure`, Pa (mixed lubrication only; else empty).
    pub asperity_pressure: Vec<f64>,
}

/// The solution of one line-contact EHL problem.
#[derive(Debug, Clone, PartialEq)]
pub struct EhlSolution {
    /// Hertzian half-width `b`, m.
    pub hertz_half_width: f64,
    /// Hertzian peak pressure `p_h`, Pa.
    pub hertz_pressure: f64,
    /// Moes load parameter `M` (0 when `u_m = 0`: undefined).
    pub moes_m: f64,
    /// Moes material parameter `L`.
    pub moes_l: f64,
    /// Film at the contact centre `x = 0`, m.
    pub central_film: f64,
    /// Smallest film, m, and where, m.
    pub min_film: f64,
    pub min_film_position: f64,
    /// Smallest film downstream of the centre (the exit constriction), m.
    pub exit_film: f64,
    /// Largest pressure, Pa, and where, m.
    pub max_pressure: f64,
    pub max_pressure_position: f64,
    /// The exit pressure spike, when the solution has one.
    pub pressure_spike: Option<PressureSpike>,
    /// Load per length carried by the asperities inside the load balance, N/m (0 for smooth
    /// surfaces).
    pub asperity_load_per_length: f64,
    /// Traction from the converged pressure and film.
    pub traction: TractionResult,
    /// Profiles, when requested.
    pub profiles: Option<Profiles>,
    /// Converged fields for warm starts and transient steps.
    pub state: EhlState,
    /// Grid nodes used.
    pub nodes: usize,
    pub convergence: Convergence,
}

/// Memory model of the dense line-contact solver with `nodes` nodes, bytes: the influence matrix
/// (`elastic::Kernel`, n² doubles) and the Newton matrix factorised in place (`newton`, (n + 1)²
/// doubles) on the fine grid, and the same on the half grid of the Richardson pair — about
/// 20·n² bytes — with 10 % for scratch space, since `tribod run` of the seed 001 nose contact
/// measured 353 MiB above the idle process at 4096 nodes against 320 MiB counted here (21 MiB
/// against 20 MiB at 1024). Vectors are O(n) and ignored. Used by validation to refuse a spec
/// before it allocates (issue 10).
pub fn dense_memory_bytes(nodes: usize) -> f64 {
    let n = nodes as f64;
    let half = (n - 1.0) / 2.0 + 1.0;
    1.1 * 8.0 * (n * n + (n + 1.0) * (n + 1.0) + half * half + (half + 1.0) * (half + 1.0))
}
