//! The semismooth Newton solver of the line-contact EHL problem (equations in [`super`]).
//!
//! Unknowns: the pressure at the interior nodes and the rigid approach `H0`. Rows: one
//! complementarity function per interior node, `φ_i = min(P_i, −F_i/|J_ii|)`, where `F_i` is the
//! discrete Reynolds residual and `J_ii` its full diagonal derivative (elastic coupling included),
//! and the load balance `(∫P dX)/(π/2) − 1`. Each step linearises every row — the film at every
//! node depends on every pressure, so the Jacobian is dense. A backtracking line search on
//! `Σ φ_i² Δ + L²` and a fraction-to-boundary rule that keeps the film positive damp the steps.
//! When a cold start fails (very heavy loads or low speeds), the solution is continued from a
//! faster entrainment speed (lower Moes M) in steps of four.
//!
//! # Linear solves: a kept factorisation as preconditioner
//! The Jacobian `J = D_a + D_g K` (banded Reynolds derivatives `D_a`, `D_g` times the dense,
//! constant influence matrix `K`) changes little from one Newton step to the next and from one cam
//! angle to the next. Each step first solves `J δ = −φ` by GMRES, right-preconditioned with the LU
//! factors of the last Jacobian factorised *on the same grid* (possibly several steps or angles
//! old), with a matrix-free product (`K v` plus banded terms, `O(n²)`); only when GMRES does not
//! reach its tolerance in [`GMRES_MAX`] iterations (or needed more than [`GMRES_REFRESH`] in the
//! step before) is the current Jacobian assembled and factorised (`O(n³)`), and the step solved
//! with the fresh factors. An inexact Newton step (relative linear residual ≤ [`forcing`], loose
//! far from the solution, Eisenstat–Walker) keeps the Newton convergence; [`Engine`] keeps the
//! factors, the workspace and the grids across solves.

use super::formulas::{moes_central, Groups};
use super::grid::{Grid, GridCache, Layout};
use super::linear::{assemble, forcing, gmres, Factor, Krylov, System, GMRES_MAX, GMRES_REFRESH, GMRES_TOL};
use super::rheology::PressureRheology;
use super::traction::traction;
use super::{EhlInput, EhlOptions, EhlSolution, EhlState, PressureSpike, Profiles, Upwind};
use crate::contact::hertz_line;
use crate::{ensure_finite, Convergence, Observer, SolveError, Termination};
use std::sync::Arc;

pub use super::grid::graded_grid;

mod discretisation;
mod workspace;
mod iteration;
mod engine;
mod entry;

use workspace::*;
use iteration::*;
pub(crate) use engine::*;
pub use entry::*;

const PI: f64 = std::f64::consts::PI;
/// Most halvings of a Newton step in the line search.
const MAX_HALVINGS: u32 = 30;
/// Largest `ln(η/η0)` used: keeps `ρH³/η` and the traction finite at absurd trial pressures.
const LN_ETA_CAP: f64 = 600.0;

/// Mixed lubrication in dimensionless form: `P_a(H) = p_a(H b²/R)/p_h` and `dP_a/dH`.
#[derive(Clone, Copy)]
struct AsperityScale<'a> {
    law: &'a dyn super::AsperityPressure,
    /// Film scale `b²/R`, m.
    film_scale: f64,
    /// Hertzian pressure, Pa.
    ph: f64,
}

/// Discrete problem in the dimensionless variables of [`super`] on one grid.
///
/// With mixed lubrication the unknown `P` of the Newton iteration is the *total* pressure (fluid
/// plus asperity, seed 001 eq. 7): it alone deflects the surfaces and carries the load, so the
/// film stays an explicit function of the unknowns, `H = H0 + X²/2 − K P`; the fluid pressure
/// `P_f = P − P_a(H)` enters the Reynolds equation, the rheology and the cavitation condition.
/// The Jacobian keeps its banded-plus-`K` structure: `∂F/∂H` gains `−(∂F/∂P_f) dP_a/dH`.
struct Discretisation<'a> {
    grid: Arc<Grid>,
    /// Couette coefficient `λ` (signed).
    lambda: f64,
    /// Squeeze coefficient `κ = 12 η0 R²/(b² p_h Δt)`; 0 in steady state.
    kappa: f64,
    /// `(ρ̄H)` of the previous time step at the nodes.
    q_old: Vec<f64>,
    /// Wedge stencils of the nodes ([`discretisation::wedge_stencils`] for `grid`, the sign of
    /// `lambda` and the upwind scheme).
    wedge: Vec<[(isize, f64); 3]>,
    rheology: PressureRheology,
    /// Hertzian pressure, Pa.
    ph: f64,
    /// Thermal corrections at the nodes (generalized Reynolds equation, seed 000 eq. 2), held
    /// fixed during a Newton solve; `None`: isothermal.
    thermal: Option<NodeFactors>,
    /// Load-sharing asperity pressure; `None`: smooth surfaces.
    asperity: Option<AsperityScale<'a>>,
}

/// Multipliers of the Newton solver's isothermal coefficients at positions `x` (m), set by the
/// thermal solver (`ehl::thermal`, whose module docs derive them). Beyond the ends the end values hold.
#[derive(Debug, Clone, PartialEq)]
pub struct ThermalFactors {
    pub x: Vec<f64>,
    pub poiseuille: Vec<f64>,
    pub wedge: Vec<f64>,
    pub mass: Vec<f64>,
}

/// [`ThermalFactors`] on the nodes of one grid: multipliers of the isothermal
/// Poiseuille coefficient `ρ̄H³/η̄`, of the wedge density `ρ̄` and of the squeeze density.
struct NodeFactors {
    poiseuille: Vec<f64>,
    wedge: Vec<f64>,
    mass: Vec<f64>,
}

/// Fields at one iterate.
#[derive(Clone, Default)]
struct Fields {
    h: Vec<f64>,
    rho: Vec<f64>,
    drho: Vec<f64>,
    e: Vec<f64>,
    /// `∂e/∂P` at fixed `H`.
    ep: Vec<f64>,
    /// `∂e/∂H`.
    eh: Vec<f64>,
    /// Reynolds residual at the nodes (0 at the two boundary nodes).
    f: Vec<f64>,
    /// Fluid pressure `P − P_a(H)` (equal to `P` for smooth surfaces).
    fp: Vec<f64>,
    /// Asperity pressure `P_a(H)` and `dP_a/dH` (zero for smooth surfaces).
    pa: Vec<f64>,
    dpa: Vec<f64>,
    /// Load balance residual `(Σ P Δ)/(π/2) − 1`.
    load: f64,
}

/// Work counters of a solver (for benchmarks and diagnostics).
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct SolverStats {
    /// Newton steps taken.
    pub newton_steps: u64,
    /// Jacobians assembled and factorised.
    pub factorisations: u64,
    /// GMRES iterations (each one matrix-free product and one solve with the kept factors).
    pub gmres_iterations: u64,
    /// Grid layouts designed ([`super::TransientSolver`] only).
    pub layouts: u64,
}

/// Per-grid-size workspace of the Newton solver and the kept factorisation.
pub(crate) struct Workspace {
    n: usize,
    v: Fields,
    trial: Fields,
    c: Vec<f64>,
    ph: Vec<f64>,
    ph_trial: Vec<f64>,
    dp: Vec<f64>,
    dh: Vec<f64>,
    p_trial: Vec<f64>,
    sol: Vec<f64>,
    sys: System,
    factor: Factor,
    krylov: Krylov,
    pub(crate) stats: SolverStats,
}

/// Outcome of one Newton run.
struct Run {
    iterations: u32,
    residual: f64,
    history: Vec<f64>,
    converged: bool,
}

/// Hertzian scales and the dimensionless coefficients of one input.
struct Scales {
    b: f64,
    ph: f64,
    lambda: f64,
    kappa: f64,
    moes_m: f64,
    moes_l: f64,
    /// Film estimate `H = hR/b²`: the previous centre film or Moes, whichever is thicker.
    h_est: f64,
}

/// A reusable solver: grids (with their influence matrices), Newton workspaces and the kept
/// factorisations survive from one solve to the next. [`solve`] uses a fresh one; the transient
/// solver keeps one per grid size across a cycle.
pub(crate) struct Engine {
    grids: GridCache,
    workspaces: Vec<Workspace>,
}

/// Which start a solve tries.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Attempt {
    /// A caller's prediction on the target grid.
    Predicted,
    /// The previous state, interpolated.
    Warm,
    /// Nested iteration from a Hertzian guess.
    Cold,
}

/// A predicted solution on the grid of a solve (for instance extrapolated in time from the two
/// previous steps): dimensionless pressure `P = p/p_h` at the grid's nodes and the centre film, m.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Prediction<'a> {
    pub pressure: &'a [f64],
    pub centre_film: f64,
}

/// Scales and convergence of a finished solve.
struct Meta {
    b: f64,
    ph: f64,
    moes_m: f64,
    moes_l: f64,
    iterations: u32,
    residual: f64,
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::lubricant::{DensityModel, Lubricant, ViscosityModel};
    use super::super::linear::apply;

    #[test]
    fn rheology_matches_the_lubricant() {
        for vm in [ViscosityModel::Roelands, ViscosityModel::Barus] {
            for dm in [DensityModel::DowsonHigginson, DensityModel::Incompressible] {
                let lub = Lubricant { viscosity_model: vm, density_model: dm, ..Lubricant::SEED000 };
                for t in [303.0, 353.0] {
                    let r = PressureRheology::new(&lub, t);
                    for p in [-1e6, 0.0, 1e7, 3e8, 1.2e9, 3e9] {
                        let (l, dl, rho, drho) = r.at(p);
                        let want_l = lub.ln_viscosity_ratio(p, t) - lub.ln_viscosity_ratio(0.0, t);
                        assert!((l - want_l).abs() < 1e-9 * (1.0 + want_l.abs()), "{vm:?} {t} {p}: {l} vs {want_l}");
                        let want_dl = lub.ln_viscosity_pressure_slope(p, t);
                        assert!((dl - want_dl).abs() <= 1e-9 * want_dl.abs(), "{dl} vs {want_dl}");
                        assert!((rho - lub.density_ratio(p, t)).abs() < 1e-12);
                        assert!((drho - lub.density_ratio_pressure_slope(p, t)).abs() < 1e-21);
                    }
                }
            }
        }
    }

    /// A Newton system of a real problem: the matrix-free product equals the assembled matrix,
    /// the kept LU factors solve it, and GMRES preconditioned by them converges at once.
    #[test]
    fn matrix_free_product_assembly_and_factors_agree() {
        let lub = Lubricant { viscosity: 0.04, ..Lubricant::SEED000 };
        let input = EhlInput {
            load_per_length: 3e5,
            reduced_radius: 0.01,
            effective_modulus: 2.3e11,
            entrainment_velocity: 1.0,
            sliding_velocity: 0.0,
            lubricant: lub,
            temperature: lub.reference_temperature,
            rheology: Default::default(),
            transient: None,
            warm_start: None,
            asperity: None,
        };
        let sc = scales(&input);
        let layout = Layout::for_film(sc.h_est, 1.0, None, None, true);
        let grid = Arc::new(Grid::new(80, layout));
        let wedge = discretisation::wedge_stencils(&grid.x, sc.lambda, Upwind::Second);
        let prob = Discretisation { grid: grid.clone(), lambda: sc.lambda, kappa: 0.0, q_old: Vec::new(), wedge, rheology: PressureRheology::new(&lub, input.temperature), ph: sc.ph, thermal: None, asperity: None };
        let (mut p, mut h0) = cold(&prob, sc.h_est, sc.h_est);
        let mut ws = Workspace::new();
        // Two Newton steps to get an active set with cavitated nodes, then inspect the system.
        let _ = newton(&prob, &mut ws, &mut p, &mut h0, 0.0, 2, &crate::Silent).unwrap();
        let dim = grid.n - 1;
        let mut mat = vec![0.0; dim * dim];
        assemble(&ws.sys, &grid, &mut ws.krylov, &mut mat);
        let z: Vec<f64> = (0..dim).map(|k| ((k * 7919) % 13) as f64 / 13.0 - 0.4).collect();
        let mut y = vec![0.0; dim];
        apply(&ws.sys, &grid, &mut ws.krylov, &z, &mut y);
        for r in 0..dim {
            let want: f64 = (0..dim).map(|c| mat[c * dim + r] * z[c]).sum();
            assert!((y[r] - want).abs() <= 1e-10 * (1.0 + want.abs()), "row {r}: {} vs {want}", y[r]);
        }
        ws.factor.lu.copy_from_slice(&mat);
        assert!(ws.factor.factorise(grid.id));
        let mut x = y.clone();
        ws.factor.solve(&mut x);
        for k in 0..dim {
            assert!((x[k] - z[k]).abs() < 1e-8, "{k}: {} vs {}", x[k], z[k]);
        }
        ws.sys.rhs.copy_from_slice(&y);
        let it = gmres(&ws.sys, &grid, &mut ws.factor, &mut ws.krylov, &mut x, 1e-10).unwrap();
        assert!(it <= 2, "{it} iterations with exact factors");
        for k in 0..dim {
            assert!((x[k] - z[k]).abs() < 1e-7, "{k}: {} vs {}", x[k], z[k]);
        }
    }
}
