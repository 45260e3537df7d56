//! The semismooth Newton–Krylov solver of the 2-D EHL problem (equations and method in [`super`]).
//!
//! Unknowns: `P` at the interior nodes (row-major) and `H0`. Rows: `φ = min(P, −c F)` per
//! interior node with `c = 1/|∂F/∂P|` (the diagonal of the preconditioner, elastic self term
//! included) — the complementarity reformulation of the 1-D solver (`super::super::newton`) —
//! and the load balance. A Newton step solves `J δ = −φ` by restarted GMRES, right-preconditioned
//! by the sparse LU of the near-field Jacobian; a backtracking line search on `Σ φ² ΔXΔY + G²`
//! from a fraction-to-boundary step on the film ([`film_damping`](newton::film_damping)) damps
//! it (the Reynolds terms see the film above a small floor, [`FILM_FLOOR`], so every trial point
//! is evaluable).
//!
//! The LU is kept (chord-preconditioned Newton–Krylov, as the 1-D solver): a step first runs
//! GMRES with the last factor of this grid — an earlier Newton step's, continuation step's or,
//! through [`Kept2d`], the previous contact point's — rescaled by the row scales it was
//! factorised with, for at most `REUSE_MAX` iterations (given up early when its mean reduction
//! rate cannot reach the tolerance); only then is the current near field factorised, GMRES going
//! on from the kept factor's iterate. A kept factor that needed more than `REUSE_REFRESH`
//! iterations, or whose step failed the line search, is replaced at the next step. The operator
//! is always the current Jacobian, so the converged solution is the same to the Newton tolerance
//! (measured: ≤ 7e-8 on the seed 000 finite cycle, `BENCHMARKS.md` issue 16, `ehl2d-7`).
//!
//! The files, one operation each: `problem` (the discretisation on one grid: fields, residual,
//! the matrix-free Newton matrix), `precond` and `near` (the near-field preconditioner and its
//! sparse LU), `newton` (the Newton iteration on one grid), `march` (the continuation of the
//! face means and pseudo-time marching), `levels` (cold, nested and warm starts), `solve` (the
//! steady entry points and the resolution checks), `transient` (a backward-Euler step), `finish`
//! (the solution's quantities), `validate`, `probe` (a development aid).

use super::elastic::Deflection;
use super::geometry::{domain, node_grid, scales, side_gap, Domain, NodeGrid, Scales};
use super::{Ehl2dInput, Ehl2dOptions, Ehl2dSolution, Factors2d, Fields2d, Geometry2d, Located, Squeeze2d, Warm2d};
use crate::ehl::rheology::PressureRheology;
use crate::numerics::krylov::{self, dot};
use crate::{Convergence, Observer, SolveError, Termination};
use near::NearPattern;
use precond::Precond;

mod finish;
mod levels;
mod march;
mod near;
mod newton;
mod precond;
mod probe;
mod problem;
mod solve;
mod transient;
mod validate;

pub(super) use finish::{edge_peak_node, mirror_tie};
pub use probe::truncation_probe;
pub use solve::{solve, solve_factored, solve_from, solve_kept, Kept2d};
pub(super) use solve::frame_sign;
pub use transient::solve_transient;
pub(super) use validate::validate;

/// Largest `ln(η/η0)` used (keeps `ε` finite at absurd trial pressures), as in the 1-D solver.
const LN_ETA_CAP: f64 = 600.0;
/// GMRES: restart length, most iterations per Newton step, relative tolerance.
const RESTART: usize = 40;
const GMRES_MAX: usize = 160;
const GMRES_TOL: f64 = 1e-3;
/// GMRES iterations allowed with a kept (older) preconditioner before the step is solved again
/// with a fresh factorisation; and the count above which a kept one is refactorised at the next
/// step although it reached the tolerance (measured, `BENCHMARKS.md` issue 16: 15 / 8 in
/// `ehl2d-7`; 25 / 15 since the warm path's looser forcing terms of `ehl2d-11`, seed 000 360-angle
/// cycle 20.7 → 19.1–19.7 s release, factorisations 0.89 → 0.54 per angle).
const REUSE_MAX: usize = 25;
const REUSE_REFRESH: usize = 15;

/// The factor-reuse policy: at most [`REUSE_MAX`] GMRES iterations with a kept factor, refreshed
/// after [`REUSE_REFRESH`], and a factor kept across solves.
const fn reuse_policy() -> (usize, usize, bool) {
    (REUSE_MAX, REUSE_REFRESH, true)
}
/// Forcing terms of the inexact Newton steps after Eisenstat & Walker (SIAM J. Sci. Comput. 17
/// (1996), choice 2): the first step's GMRES tolerance `first`, then
/// `η = γ (‖F_k‖/‖F_{k−1}‖)^α` (‖F‖ the 2-norm of the scaled right-hand side), kept from falling
/// faster than `γ η_{k−1}^α` while that exceeds 0.1, at most `max`, and at least `over·tol/res`
/// (no more accuracy than the Newton tolerance asks of this step; `res` the report norm).
#[derive(Clone, Copy, Debug)]
struct Forcing {
    first: f64,
    max: f64,
    gamma: f64,
    alpha: f64,
    over: f64,
}

impl Forcing {
    fn eta(&self, last: Option<(f64, f64)>, bn: f64, res: f64, tol: f64) -> f64 {
        let eta = match last {
            // γ < 0: the fixed rule (`GMRES_TOL`, tighter near the solution) with the floor below.
            _ if self.gamma < 0.0 => GMRES_TOL.min(0.1 * res.sqrt()),
            None => self.first,
            Some((b0, e0)) => {
                let mut e = self.gamma * (bn / b0).powf(self.alpha);
                let guard = self.gamma * e0.powf(self.alpha);
                if guard > 0.1 {
                    e = e.max(guard);
                }
                e
            }
        };
        eta.min(self.max).max(self.over * tol / res).min(self.max).max(1e-10)
    }
}

/// The forcing terms of a warm-started solve ([`solve_kept`], [`solve_from`]; a cold solve keeps
/// `GMRES_TOL`, tighter near the solution): first step 0.1, then Eisenstat–Walker with `γ = 0.9`,
/// `α = 2`, at most 0.1, and no tighter than half the reduction the Newton tolerance asks.
/// Measured on the seed 000 finite cycle, 360 angles, 65×129 (`BENCHMARKS.md` issue 16,
/// `ehl2d-11`): GMRES iterations −19 %, factorisations −19 %, Newton steps +16 % against the
/// fixed rule (first steps at 0.3: fewer factorisations but more steps and GMRES iterations), the
/// films unchanged to the printed digits.
const WARM_FORCING: Forcing = Forcing { first: 0.1, max: 0.1, gamma: 0.9, alpha: 2.0, over: 0.5 };

/// The warm path's forcing terms: [`WARM_FORCING`].
const fn warm_forcing() -> Option<Forcing> {
    Some(WARM_FORCING)
}

/// Whether the near-field preconditioner carries the Poiseuille terms' film dependence
/// ([`Problem::precondition`]): yes since `ehl2d-12` (before, the wedge-only near field).
const fn poiseuille_film() -> bool {
    true
}

/// Whether a node whose film is at the floor may take the contact row `H = floor` (the film
/// floor as a complementarity, [`Problem::row_kind`]): yes since `ehl2d-13`.
const fn floor_contact() -> bool {
    true
}

/// The near-field zone: rows at `X < −NEAR_ZONE` (units of `a`; the far inlet, where the film is
/// thick and the Poiseuille terms dominate) carry the Reynolds terms and the deflection's self
/// term only, not the deflection near field of their neighbours nor the Poiseuille terms' film
/// dependence, so their part of the sparse LU stays narrow. The seed 000 roller's inlet reaches
/// `−12 a`: measured on its 360-angle finite cycle, 65×129 (`BENCHMARKS.md` issue 46), CPU −12 %
/// (f32 factor), GMRES iterations and factorisations within 1 % and +4 %, films within 3.1e-7
/// (zone at `−3 a`: the same time).
const NEAR_ZONE: f64 = 2.0;

/// Row kinds of the semismooth Newton matrix ([`Problem::row_kind`]).
const FLUID: u8 = 0;
const CAVITATED: u8 = 1;
const CONTACT: u8 = 2;

/// Most halvings in the line search.
const MAX_HALVINGS: u32 = 25;
/// The film floor of the Reynolds terms, as a fraction of the closed-form film estimate: the
/// Poiseuille and wedge terms see `max(H, floor)` (`∂/∂H` zero below it), so a Newton iterate may
/// pass through a non-positive film at a node without leaving the domain of the residual. The
/// fraction-to-boundary rule that kept every iterate's film positive before stalled Newton where
/// the discrete problem of the current stage wants a non-positive film at one node (issue 16,
/// measured: 1.7 GPa on 65², the arithmetic-mean stage of the continuation pinches in a side
/// lobe; each step then shrank that film 5× and the step with it, 190 steps to a residual of
/// 2.4e-5); the rule now only damps ([`film_damping`](newton::film_damping)). A converged film at
/// the floor is refused by the pinch check ([`PINCH`] ≫ 1e-3).
pub const FILM_FLOOR: f64 = 1e-3;
/// Fraction-to-boundary rule of [`film_damping`]: largest fraction of a node's film one step may
/// remove, and the smallest step it may impose.
const FTB: f64 = 0.8;
const FTB_MIN: f64 = 0.1;

/// The discretisation on one grid.
struct Problem {
    nx: usize,
    ny: usize,
    dx: f64,
    dy: f64,
    x: Vec<f64>,
    y: Vec<f64>,
    /// `X²/2 + S(Y)` at each node.
    geom: Vec<f64>,
    lambda: f64,
    /// Pseudo-time coefficient `κ = λ/ΔT` of the squeeze term `−κ (ρ̄H − (ρ̄H)_old)` (backward
    /// Euler in the time `T = t u_m/a`, seed 000 eq. 2's `∂(ρh)/∂t`); 0: steady.
    kappa: f64,
    /// `ρ̄H` of the previous pseudo-time step at the nodes.
    q_old: Vec<f64>,
    /// The problem's own squeeze term, `(κ, (ρ̄H)_old)`: a physical transient step's
    /// ([`solve_transient`]); `None`: steady. The pseudo-time steps of [`march`] add theirs on
    /// top of it and [`Problem::restore_target`] puts it back.
    target: Option<(f64, Vec<f64>)>,
    load: f64,
    p_ref: f64,
    rheo: PressureRheology,
    defl: Deflection,
    near: usize,
    /// Second-order upwind wedge term (else first order).
    second: bool,
    /// Weight of the geometric face mean of `ε` ([`face_of`]): 1, or less during the
    /// continuation from the arithmetic mean.
    theta: f64,
    /// Film floor in units of `a²/R_x` ([`FILM_FLOOR`] times the film estimate): below it the
    /// film is held constant in the Reynolds terms.
    floor: f64,
    /// Unknown index of each node (`usize::MAX`: boundary).
    unk: Vec<usize>,
    /// Node of each unknown (interior nodes).
    nodes: Vec<usize>,
    /// The preconditioner's sparsity pattern and symbolic LU ([`NearPattern`]): one per grid,
    /// kept across Newton steps and — through [`Kept2d`] — across solves.
    pattern: std::cell::RefCell<Option<std::sync::Arc<NearPattern>>>,
    /// The kept preconditioner: the last one factorised on this grid (possibly several Newton
    /// steps, continuation steps or — through [`Kept2d`] — cam angles old), used for GMRES until
    /// it needs more than [`REUSE_MAX`] iterations (see [`newton`]).
    kept: Option<std::sync::Arc<Precond>>,
    /// Numeric factorisations of the preconditioner (work counter).
    factorisations: usize,
    /// The forcing terms of the Newton steps ([`Forcing`]; `None`: `GMRES_TOL`, tighter near the
    /// solution).
    forcing: Option<Forcing>,
    /// The thermal model's generalized Reynolds multipliers at the nodes ([`Factors2d`]):
    /// `(Poiseuille, wedge)`; `None`: isothermal.
    thermal: Option<(Vec<f64>, Vec<f64>)>,
}

/// The Poiseuille coefficient at a cell face from its two nodes' `ε = ρ̄H³/η̄`, with its
/// derivatives: the geometric mean `sqrt(ε_a ε_b)`, i.e. `ln ε` interpolated linearly to the face
/// (for Barus viscosity and an incompressible film of equal thickness, `ε` at the face's mean
/// pressure). Second order like the arithmetic mean for smooth `ε`, but `ε` falls by orders of
/// magnitude within a cell where the pressure rises into the contact, and there the arithmetic
/// mean (dominated by the upstream node) overstates the back-flow and thins the film: measured on
/// the circular M ≈ 300, L ≈ 11 contact (`BENCHMARKS.md`, issue 16) the central film's error on
/// 65² is −28 % with the arithmetic mean and −5 % with the geometric one (harmonic +16 %,
/// logarithmic −14 %), all converging to the same fine-grid limit.
/// `theta < 1`: the blend `(1 − θ)·arithmetic + θ·geometric` of the continuation ([`solve_level`]).
#[inline]
fn face_of(theta: f64, a: f64, b: f64) -> (f64, f64, f64) {
    let g = (a * b).sqrt();
    let t = 1.0 - theta;
    (t * 0.5 * (a + b) + theta * g, 0.5 * t + theta * 0.5 * g / a, 0.5 * t + theta * 0.5 * g / b)
}

/// Fields at one iterate.
#[derive(Clone, Default)]
struct Fields {
    w: Vec<f64>,
    h: Vec<f64>,
    rho: Vec<f64>,
    /// `dρ̄/dP`.
    drho: Vec<f64>,
    eps: Vec<f64>,
    /// `∂ε/∂P` at fixed `H`.
    deps: Vec<f64>,
    /// Reynolds residual at the nodes (0 on the boundary).
    f: Vec<f64>,
    /// `∂H_eff/∂H`: 1, or 0 where the film is held at the floor.
    on: Vec<f64>,
    /// The film before the floor, `H0 + X²/2 + S(Y) + W`.
    hraw: Vec<f64>,
    /// Load residual `∫∫P/target − 1`.
    g: f64,
}

#[derive(Default)]
struct Buffers {
    dp: Vec<f64>,
    dw: Vec<f64>,
    dq: Vec<f64>,
    de: Vec<f64>,
    /// The face coefficients [`face_of`] of the faces `(k, k + 1)` and `(k, k + nx)` and
    /// `3ε/H` at the nodes, at the iterate of one linear solve ([`Problem::faces`]): fixed while
    /// GMRES applies the Newton matrix.
    fx: Vec<(f64, f64, f64)>,
    fy: Vec<(f64, f64, f64)>,
    e3h: Vec<f64>,
    /// GMRES' work arrays.
    krylov: krylov::Workspace,
}

/// Report norm: the larger of `max|φ|/max P` and `|G|`.
fn residual_norm(p: &[f64], phi: &[f64], g: f64) -> f64 {
    let pmax = p.iter().cloned().fold(0.0_f64, f64::max).max(1e-12);
    let pr = phi.iter().fold(0.0_f64, |a, v| a.max(v.abs())) / pmax;
    pr.max(g.abs())
}

struct Run {
    iterations: u32,
    residual: f64,
    history: Vec<f64>,
    converged: bool,
    gmres: usize,
}

/// Pseudo-time marching: first step `ΔT` from a cold start and after a failed nested start (units
/// of the passage time `a/u_m`); `ΔT` from which a steady Newton solve is tried; smallest `ΔT`
/// before giving up; most steps; tolerance and Newton cap of one step; Newton cap of the
/// nested (interpolated) start.
const DT_COLD: f64 = 0.1;
const DT_NESTED: f64 = 1.0;
const DT_STEADY: f64 = 30.0;
const DT_MIN: f64 = 1e-4;
const DT_MAX: f64 = 1e5;
const MAX_STEPS: u32 = 60;
const STEP_TOL: f64 = 1e-5;
const STEP_ITER: u32 = 10;
const NESTED_ITER: u32 = 15;
/// Newton cap of the cold trial on a grid whose half grid resolves the film only along x
/// ([`solve_levels`]).
const COLD_TRIAL: u32 = 15;
/// Coarsest grid of the nested iteration: at least `MIN_LEVEL` nodes per side and a spacing `h`
/// with `h² ≤ RESOLVED · H_est` (the film estimate in units of `a²/R_x`).
const MIN_LEVEL: usize = 17;
const RESOLVED: f64 = 0.3;

/// Bilinear interpolation of a node field at `(x, y)` (clamped to the grid).
pub(super) fn bilinear(xs: &[f64], ys: &[f64], f: &[f64], x: f64, y: f64) -> f64 {
    let (nx, ny) = (xs.len(), ys.len());
    let loc = |v: &[f64], at: f64| {
        let n = v.len();
        let d = v[1] - v[0];
        let t = ((at - v[0]) / d).clamp(0.0, (n - 1) as f64);
        let i = (t.floor() as usize).min(n - 2);
        (i, t - i as f64)
    };
    let (i, tx) = loc(xs, x);
    let (j, ty) = loc(ys, y);
    let _ = ny;
    let g = |ii: usize, jj: usize| f[jj * nx + ii];
    (1.0 - ty) * ((1.0 - tx) * g(i, j) + tx * g(i + 1, j)) + ty * ((1.0 - tx) * g(i, j + 1) + tx * g(i + 1, j + 1))
}

/// Smallest accepted ratio of the minimum to the central film: below it the film is pinched at a
/// node by the discretisation (measured: the arithmetic-mean scheme's 33² solution of the
/// circular M ≈ 300 contact had h_min/h_c ≈ 0.9 at 4.9 nm against 220 nm converged).
pub const PINCH: f64 = 0.1;
