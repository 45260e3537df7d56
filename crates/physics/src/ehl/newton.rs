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
//! reach its tolerance in [`GMRES_MAX`] iterations is the current Jacobian assembled and factorised
//! (`O(n³)`), and the step solved with the fresh factors. An inexact Newton step (relative linear
//! residual ≤ [`GMRES_TOL`]) keeps the Newton convergence; [`Engine`] keeps the factors, the
//! workspace and the grids across solves.

use super::formulas::{moes_central, Groups};
use super::grid::{Grid, GridCache, Layout};
use super::linear::{assemble, gmres, Factor, Krylov, System, GMRES_MAX, GMRES_TOL};
use super::rheology::PressureRheology;
use super::traction::traction;
use super::{EhlInput, EhlOptions, EhlSolution, EhlState, PressureSpike, Profiles, Upwind};
use crate::contact::hertz_line;
use crate::{ensure_finite, Convergence, Observer, SolveError, Termination};
use std::sync::Arc;

pub use super::grid::graded_grid;

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

impl AsperityScale<'_> {
    fn at(&self, h: f64) -> (f64, f64) {
        let (p, dp) = self.law.pressure(h * self.film_scale);
        (p / self.ph, dp * self.film_scale / self.ph)
    }
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
    upwind: Upwind,
    rheology: PressureRheology,
    /// Hertzian pressure, Pa.
    ph: f64,
    /// Thermal corrections at the nodes (generalized Reynolds equation, seed 000 eq. 2), held
    /// fixed during a Newton solve; `None`: isothermal.
    thermal: Option<NodeFactors>,
    /// Load-sharing asperity pressure; `None`: smooth surfaces.
    asperity: Option<AsperityScale<'a>>,
}

/// [`super::thermal::ThermalFactors`] on the nodes of one grid: multipliers of the isothermal
/// Poiseuille coefficient `ρ̄H³/η̄`, of the wedge density `ρ̄` and of the squeeze density.
struct NodeFactors {
    poiseuille: Vec<f64>,
    wedge: Vec<f64>,
    mass: Vec<f64>,
}

impl NodeFactors {
    fn on(grid_x: &[f64], b: f64, f: &super::thermal::ThermalFactors) -> Self {
        let at = |v: &[f64], x: f64| interpolate(&f.x, v, x * b);
        NodeFactors {
            poiseuille: grid_x.iter().map(|&x| at(&f.poiseuille, x)).collect(),
            wedge: grid_x.iter().map(|&x| at(&f.wedge, x)).collect(),
            mass: grid_x.iter().map(|&x| at(&f.mass, x)).collect(),
        }
    }
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

impl Fields {
    fn new(n: usize) -> Self {
        let z = vec![0.0; n];
        Fields {
            h: z.clone(),
            rho: z.clone(),
            drho: z.clone(),
            e: z.clone(),
            ep: z.clone(),
            eh: z.clone(),
            f: z.clone(),
            fp: z.clone(),
            pa: z.clone(),
            dpa: z,
            load: 0.0,
        }
    }
}

impl Discretisation<'_> {
    fn n(&self) -> usize {
        self.grid.n
    }

    /// Wedge stencil at node `i`: `(offset, weight)` of `d(ρ̄H)/dX`, upwind for the sign of `λ`
    /// (three-point one-sided derivative on the graded grid for the second-order scheme).
    fn wedge(&self, i: usize) -> [(isize, f64); 3] {
        let x = &self.grid.x;
        let second = self.upwind == Upwind::Second;
        if self.lambda >= 0.0 {
            let a = x[i] - x[i - 1];
            if second && i >= 2 {
                let b = x[i - 1] - x[i - 2];
                [(0, (2.0 * a + b) / (a * (a + b))), (-1, -(a + b) / (a * b)), (-2, a / (b * (a + b)))]
            } else {
                [(0, 1.0 / a), (-1, -1.0 / a), (0, 0.0)]
            }
        } else {
            let a = x[i + 1] - x[i];
            if second && i + 2 < self.n() {
                let b = x[i + 2] - x[i + 1];
                [(0, -(2.0 * a + b) / (a * (a + b))), (1, (a + b) / (a * b)), (2, -a / (b * (a + b)))]
            } else {
                [(0, -1.0 / a), (1, 1.0 / a), (0, 0.0)]
            }
        }
    }

    /// Evaluate the film, rheology and residuals at `(p, h0)`. `false` when the film is not
    /// positive everywhere or a value is not finite.
    fn evaluate(&self, p: &[f64], h0: f64, v: &mut Fields) -> bool {
        let n = self.n();
        let x = &self.grid.x;
        self.grid.kernel.deflection(p, &mut v.h);
        for i in 0..n {
            let h = h0 + 0.5 * x[i] * x[i] - v.h[i];
            if !(h > 0.0 && h.is_finite()) {
                return false;
            }
            v.h[i] = h;
            let (pa, dpa) = match &self.asperity {
                Some(a) => a.at(h),
                None => (0.0, 0.0),
            };
            if !(pa.is_finite() && dpa.is_finite()) {
                return false;
            }
            v.pa[i] = pa;
            v.dpa[i] = dpa;
            v.fp[i] = p[i] - pa;
            let (ln_eta, dln, rho, drho) = self.rheology.at(v.fp[i] * self.ph);
            let ln_eta = ln_eta.min(LN_ETA_CAP);
            let ce = self.thermal.as_ref().map_or(1.0, |t| t.poiseuille[i]);
            v.rho[i] = rho;
            v.drho[i] = drho * self.ph;
            v.e[i] = ce * rho * h * h * h * (-ln_eta).exp();
            v.ep[i] = v.e[i] * (v.drho[i] / rho - dln * self.ph);
            v.eh[i] = 3.0 * v.e[i] / h;
        }
        v.f[0] = 0.0;
        v.f[n - 1] = 0.0;
        let p = &v.fp;
        for i in 1..n - 1 {
            let er = 0.5 * (v.e[i] + v.e[i + 1]);
            let el = 0.5 * (v.e[i - 1] + v.e[i]);
            let (hl, hr) = (x[i] - x[i - 1], x[i + 1] - x[i]);
            let mut f = (er * (p[i + 1] - p[i]) / hr - el * (p[i] - p[i - 1]) / hl) / (0.5 * (hl + hr));
            if self.lambda != 0.0 {
                let mut d = 0.0;
                for (off, w) in self.wedge(i) {
                    let m = (i as isize + off) as usize;
                    d += w * v.rho[m] * self.wedge_factor(m) * v.h[m];
                }
                f -= self.lambda * d;
            }
            if self.kappa != 0.0 {
                f -= self.kappa * (self.mass_density(v, i) * v.h[i] - self.q_old[i]);
            }
            v.f[i] = f;
        }
        let sum: f64 = (0..n).map(|i| (v.fp[i] + v.pa[i]) * self.grid.cell[i]).sum();
        v.load = sum / (0.5 * PI) - 1.0;
        v.f.iter().all(|f| f.is_finite()) && v.load.is_finite()
    }

    /// Local derivatives of `F_i` with respect to the unknown (total) pressure `P` (offsets
    /// −2..=2) and through the film `H` (offsets −2..=2); with asperities `P_f = P − P_a(H)`, so
    /// `∂F/∂H` includes `−(∂F/∂P_f) dP_a/dH`.
    fn local_derivatives(&self, v: &Fields, i: usize) -> ([f64; 5], [f64; 5]) {
        let (a, mut g) = self.fluid_derivatives(&v.fp, v, i);
        if self.asperity.is_some() {
            for o in 0..5 {
                let m = i as isize + o as isize - 2;
                if a[o] != 0.0 && m >= 0 && (m as usize) < self.n() {
                    g[o] -= a[o] * v.dpa[m as usize];
                }
            }
        }
        (a, g)
    }

    /// Local derivatives of `F_i`: direct in the fluid pressure (offsets −2..=2) and through the
    /// film `H` at fixed fluid pressure (offsets −2..=2).
    fn fluid_derivatives(&self, p: &[f64], v: &Fields, i: usize) -> ([f64; 5], [f64; 5]) {
        let x = &self.grid.x;
        let mut a = [0.0; 5];
        let mut g = [0.0; 5];
        let er = 0.5 * (v.e[i] + v.e[i + 1]);
        let el = 0.5 * (v.e[i - 1] + v.e[i]);
        let (hl, hr) = (x[i] - x[i - 1], x[i + 1] - x[i]);
        let hc = 0.5 * (hl + hr);
        // Slopes (P_{i+1} − P_i)/h_R and (P_i − P_{i−1})/h_L.
        let sr = (p[i + 1] - p[i]) / hr;
        let sl = (p[i] - p[i - 1]) / hl;
        a[3] += (er / hr + 0.5 * v.ep[i + 1] * sr) / hc;
        a[2] += (0.5 * v.ep[i] * (sr - sl) - er / hr - el / hl) / hc;
        a[1] += (el / hl - 0.5 * v.ep[i - 1] * sl) / hc;
        g[3] += 0.5 * v.eh[i + 1] * sr / hc;
        g[2] += 0.5 * v.eh[i] * (sr - sl) / hc;
        g[1] += -0.5 * v.eh[i - 1] * sl / hc;
        if self.lambda != 0.0 {
            for (off, w) in self.wedge(i) {
                let m = (i as isize + off) as usize;
                let k = (off + 2) as usize;
                let cw = self.wedge_factor(m);
                a[k] -= self.lambda * w * v.drho[m] * cw * v.h[m];
                g[k] -= self.lambda * w * v.rho[m] * cw;
            }
        }
        if self.kappa != 0.0 {
            let cm = self.mass_factor(i);
            a[2] -= self.kappa * v.drho[i] * cm * v.h[i];
            g[2] -= self.kappa * v.rho[i] * cm;
        }
        (a, g)
    }

    /// Multiplier of `ρ̄` in the wedge term: 1, or the thermal `(u1 ρ*_1 + u2 ρ*_2)/(2 u_m ρ)`
    /// (seed 000 eq. 2).
    fn wedge_factor(&self, i: usize) -> f64 {
        self.thermal.as_ref().map_or(1.0, |t| t.wedge[i])
    }

    /// Multiplier of `ρ̄` in the squeeze term: 1, or the thermal `ρ_e/ρ` (seed 000 eq. 2).
    fn mass_factor(&self, i: usize) -> f64 {
        self.thermal.as_ref().map_or(1.0, |t| t.mass[i])
    }

    /// The density of the squeeze term `∂(ρ̄H)/∂t` at node `i`.
    fn mass_density(&self, v: &Fields, i: usize) -> f64 {
        v.rho[i] * self.mass_factor(i)
    }
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

impl Workspace {
    pub(crate) fn new() -> Self {
        Workspace {
            n: 0,
            v: Fields::default(),
            trial: Fields::default(),
            c: Vec::new(),
            ph: Vec::new(),
            ph_trial: Vec::new(),
            dp: Vec::new(),
            dh: Vec::new(),
            p_trial: Vec::new(),
            sol: Vec::new(),
            sys: System::default(),
            factor: Factor::empty(),
            krylov: Krylov::default(),
            stats: SolverStats::default(),
        }
    }

    /// Size every buffer for `n` nodes (keeps the kept factors when `n` is unchanged).
    fn ensure(&mut self, n: usize) {
        if self.n == n {
            return;
        }
        self.n = n;
        let dim = n - 1; // n − 2 interior pressures and H0
        let z = vec![0.0; n];
        self.v = Fields::new(n);
        self.trial = Fields::new(n);
        self.c = z.clone();
        self.ph = z.clone();
        self.ph_trial = z.clone();
        self.dp = z.clone();
        self.dh = z.clone();
        self.p_trial = z.clone();
        self.sol = vec![0.0; dim];
        self.sys = System {
            aa: std::array::from_fn(|_| z.clone()),
            cg: std::array::from_fn(|_| z.clone()),
            gsum: z.clone(),
            rhs: vec![0.0; dim],
        };
        self.factor.resize(dim);
        let k = GMRES_MAX + 1;
        self.krylov = Krylov {
            basis: vec![0.0; k * dim],
            hess: vec![0.0; k * GMRES_MAX],
            cs: vec![0.0; GMRES_MAX],
            sn: vec![0.0; GMRES_MAX],
            g: vec![0.0; k],
            w: vec![0.0; dim],
            z: vec![0.0; dim],
            dp: vec![0.0; n + 4],
            dh: vec![0.0; n + 4],
            defl: vec![0.0; n],
        };
    }
}

/// Solve the Newton system in `ws.sys` into `ws.sol`: GMRES with the kept factors when they
/// belong to this grid, else (or when GMRES stalls) a fresh factorisation. `false` when the
/// Jacobian is singular.
fn linear_solve(ws: &mut Workspace, grid: &Grid) -> bool {
    if ws.factor.grid_id == grid.id {
        if let Some(it) = gmres(&ws.sys, grid, &mut ws.factor, &mut ws.krylov, &mut ws.sol, GMRES_TOL) {
            ws.stats.gmres_iterations += it as u64;
            return true;
        }
        ws.stats.gmres_iterations += GMRES_MAX as u64;
    }
    let mut lu = std::mem::take(&mut ws.factor.lu);
    assemble(&ws.sys, grid, &mut ws.krylov, &mut lu);
    ws.factor.lu = lu;
    ws.stats.factorisations += 1;
    if !ws.factor.factorise(grid.id) {
        return false;
    }
    ws.sol.copy_from_slice(&ws.sys.rhs);
    let mut sol = std::mem::take(&mut ws.sol);
    ws.factor.solve(&mut sol);
    ws.sol = sol;
    true
}

/// Outcome of one Newton run.
struct Run {
    iterations: u32,
    residual: f64,
    history: Vec<f64>,
    converged: bool,
}

/// Scaled complementarity residuals `φ_i = min(P_f, −c F)` (0 at boundaries) for scalings `c`.
fn phi(v: &Fields, c: &[f64], out: &mut [f64]) {
    let n = v.fp.len();
    out[0] = 0.0;
    out[n - 1] = 0.0;
    for i in 1..n - 1 {
        out[i] = v.fp[i].min(-c[i] * v.f[i]);
    }
}

fn merit(phi: &[f64], load: f64, cell: &[f64]) -> f64 {
    phi.iter().zip(cell).map(|(v, w)| v * v * w).sum::<f64>() + load * load
}

/// Residual norm of the report: the larger of `max|φ|/max P` and `|load|`.
fn residual_norm(p: &[f64], phi: &[f64], load: f64) -> f64 {
    let pmax = p.iter().cloned().fold(0.0_f64, f64::max).max(1e-12);
    let pr = phi.iter().fold(0.0_f64, |a, v| a.max(v.abs())) / pmax;
    pr.max(load.abs())
}

/// Damped semismooth Newton from `(p, h0)`, in place.
fn newton(
    prob: &Discretisation,
    ws: &mut Workspace,
    p: &mut [f64],
    h0: &mut f64,
    tol: f64,
    max_iter: u32,
    observer: &dyn Observer,
) -> Result<Run, SolveError> {
    let grid = prob.grid.clone();
    let n = grid.n;
    let m = n - 2;
    ws.ensure(n);
    let mut history = Vec::new();
    if !prob.evaluate(p, *h0, &mut ws.v) {
        return Ok(Run { iterations: 0, residual: f64::INFINITY, history, converged: false });
    }
    let inv_pi = 1.0 / PI;
    let kernel = &grid.kernel;
    for iter in 0..max_iter {
        observer.check()?;
        // Local derivatives, the full diagonal for the row scaling, and the scaled system.
        for i in 1..n - 1 {
            let (a, g) = prob.local_derivatives(&ws.v, i);
            let kc = kernel.column(i);
            let mut d = a[2];
            for (o, gv) in g.iter().enumerate() {
                let mm = i + o;
                if *gv != 0.0 && mm >= 2 && mm - 2 < n {
                    d -= inv_pi * gv * kc[mm - 2];
                }
            }
            let c = 1.0 / d.abs().max(1e-300);
            ws.c[i] = c;
            let fp = ws.v.fp[i];
            let active = fp <= -c * ws.v.f[i];
            let sys = &mut ws.sys;
            let mut gs = 0.0;
            for o in 0..5 {
                let in_range = i + o >= 2 && i + o - 2 < n;
                if active {
                    // The row `P_f = P − P_a(H) = 0`.
                    sys.aa[o][i] = if o == 2 { 1.0 } else { 0.0 };
                    sys.cg[o][i] = if o == 2 { -ws.v.dpa[i] } else { 0.0 };
                } else {
                    sys.aa[o][i] = c * a[o];
                    sys.cg[o][i] = if in_range { c * g[o] } else { 0.0 };
                }
                gs += sys.cg[o][i];
            }
            sys.gsum[i] = gs;
            sys.rhs[i - 1] = if active { -fp } else { -c * ws.v.f[i] };
        }
        phi(&ws.v, &ws.c, &mut ws.ph);
        let res = residual_norm(p, &ws.ph, ws.v.load);
        history.push(res);
        if res <= tol {
            return Ok(Run { iterations: iter, residual: res, history, converged: true });
        }
        ws.sys.rhs[m] = -ws.v.load;
        ws.stats.newton_steps += 1;
        if !linear_solve(ws, &grid) {
            return Ok(Run { iterations: iter + 1, residual: res, history, converged: false });
        }
        let dh0 = ws.sol[m];
        ws.dp[0] = 0.0;
        ws.dp[n - 1] = 0.0;
        ws.dp[1..n - 1].copy_from_slice(&ws.sol[..m]);
        if !ws.dp.iter().all(|d| d.is_finite()) || !dh0.is_finite() {
            ws.factor.grid_id = 0;
            return Ok(Run { iterations: iter + 1, residual: res, history, converged: false });
        }
        // Fraction to the boundary: the film may shrink at most to 20 % in one step.
        kernel.deflection(&ws.dp, &mut ws.dh);
        let mut alpha: f64 = 1.0;
        for i in 0..n {
            let d = dh0 - ws.dh[i];
            if d < 0.0 {
                alpha = alpha.min(0.8 * ws.v.h[i] / -d);
            }
        }
        let m0 = merit(&ws.ph, ws.v.load, &grid.cell);
        let mut accepted = false;
        for _ in 0..MAX_HALVINGS {
            for i in 0..n {
                ws.p_trial[i] = p[i] + alpha * ws.dp[i];
            }
            let h0_trial = *h0 + alpha * dh0;
            if prob.evaluate(&ws.p_trial, h0_trial, &mut ws.trial) {
                phi(&ws.trial, &ws.c, &mut ws.ph_trial);
                let mt = merit(&ws.ph_trial, ws.trial.load, &grid.cell);
                if mt <= (1.0 - 1e-4 * alpha) * m0 {
                    p.copy_from_slice(&ws.p_trial);
                    *h0 = h0_trial;
                    std::mem::swap(&mut ws.v, &mut ws.trial);
                    accepted = true;
                    break;
                }
            }
            alpha *= 0.5;
        }
        if !accepted {
            return Ok(Run { iterations: iter + 1, residual: res, history, converged: false });
        }
    }
    // Final check after the last step.
    for i in 1..n - 1 {
        let (a, g) = prob.local_derivatives(&ws.v, i);
        let kc = kernel.column(i);
        let mut d = a[2];
        for (o, gv) in g.iter().enumerate() {
            let mm = i + o;
            if *gv != 0.0 && mm >= 2 && mm - 2 < n {
                d -= inv_pi * gv * kc[mm - 2];
            }
        }
        ws.c[i] = 1.0 / d.abs().max(1e-300);
    }
    phi(&ws.v, &ws.c, &mut ws.ph);
    let res = residual_norm(p, &ws.ph, ws.v.load);
    history.push(res);
    Ok(Run { iterations: max_iter, residual: res, history, converged: res <= tol })
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

fn scales(input: &EhlInput) -> Scales {
    let w = input.load_per_length;
    let r = input.reduced_radius;
    let ep = input.effective_modulus;
    let t = input.temperature;
    let um = input.entrainment_velocity;
    let lub = input.lubricant;
    // Hertz with E* = E'/2 (contact::hertz_line takes Johnson's E*).
    let hz = hertz_line(w, r, 0.5 * ep);
    let (b, ph) = (hz.half_width, hz.max_pressure);
    let eta0 = lub.viscosity_at(0.0, t);
    let lambda = 12.0 * eta0 * um * r * r / (b * b * b * ph);
    let groups = Groups::of(w, r, ep, um, &lub, t);
    let (moes_m, moes_l) = if um != 0.0 { (groups.moes_m, groups.moes_l) } else { (0.0, 0.0) };
    let previous = input.transient.map(|s| s.previous).or(input.warm_start);
    let h_moes = if um != 0.0 { PI * moes_central(moes_m, moes_l) / (8.0 * moes_m) } else { 0.0 };
    let h_est = match previous {
        Some(s) => (s.film_at(0.0, r) * r / (b * b)).max(h_moes),
        None => h_moes,
    };
    let kappa = match input.transient {
        Some(s) => 12.0 * eta0 * r * r / (b * b * ph * s.time_step),
        None => 0.0,
    };
    Scales { b, ph, lambda, kappa, moes_m, moes_l, h_est }
}

/// The film estimate `H = hR/b²` a solve of `input` designs its grid for (the previous state's
/// centre film or Moes' central film, whichever is thicker), and the entrainment direction.
pub(crate) fn film_estimate(input: &EhlInput) -> (f64, f64) {
    let s = scales(input);
    (s.h_est, if input.entrainment_velocity >= 0.0 { 1.0 } else { -1.0 })
}

/// A reusable solver: grids (with their influence matrices), Newton workspaces and the kept
/// factorisations survive from one solve to the next. [`solve`] uses a fresh one; the transient
/// solver keeps one per grid size across a cycle.
pub(crate) struct Engine {
    grids: GridCache,
    workspaces: Vec<Workspace>,
}

impl Engine {
    pub(crate) fn new() -> Self {
        Engine { grids: GridCache::default(), workspaces: Vec::new() }
    }

    /// Linear-algebra counters summed over the workspaces.
    pub(crate) fn stats(&self) -> SolverStats {
        let mut s = SolverStats::default();
        for w in &self.workspaces {
            s.newton_steps += w.stats.newton_steps;
            s.factorisations += w.stats.factorisations;
            s.gmres_iterations += w.stats.gmres_iterations;
        }
        s
    }

    fn workspace(&mut self, n: usize) -> &mut Workspace {
        let k = match self.workspaces.iter().position(|w| w.n == n) {
            Some(k) => k,
            None => {
                if self.workspaces.len() == 3 {
                    self.workspaces.remove(0);
                }
                let mut w = Workspace::new();
                w.ensure(n);
                self.workspaces.push(w);
                self.workspaces.len() - 1
            }
        };
        &mut self.workspaces[k]
    }

    /// Solve one problem (steady, or one transient step when `input.transient` is set). `layout`
    /// fixes the grid's domain and grading (its direction must be the entrainment's); `None`
    /// designs it from the film estimate. A `prediction` on that grid is tried first; when Newton
    /// does not converge from it, the solve falls back to the warm start and then to a cold start.
    pub(crate) fn solve(
        &mut self,
        input: &EhlInput,
        options: &EhlOptions,
        layout: Option<Layout>,
        prediction: Option<Prediction>,
        observer: &dyn Observer,
    ) -> Result<EhlSolution, SolveError> {
        self.solve_with(input, options, layout, prediction, None, observer)
    }

    /// [`Self::solve`] with the generalized Reynolds equation's thermal corrections `thermal`
    /// (held fixed; [`super::thermal`] iterates them with the energy equation).
    pub(crate) fn solve_with(
        &mut self,
        input: &EhlInput,
        options: &EhlOptions,
        layout: Option<Layout>,
        prediction: Option<Prediction>,
        thermal: Option<&super::thermal::ThermalFactors>,
        observer: &dyn Observer,
    ) -> Result<EhlSolution, SolveError> {
        validate(input, options)?;
        let r = input.reduced_radius;
        let t = input.temperature;
        let um = input.entrainment_velocity;
        let lub = input.lubricant;
        let sc = scales(input);
        let (b, ph, h_est) = (sc.b, sc.ph, sc.h_est);
        let previous = input.transient.map(|s| s.previous).or(input.warm_start);
        let dir = if um >= 0.0 { 1.0 } else { -1.0 };
        if sc.lambda == 0.0 && sc.kappa == 0.0 {
            return Err(SolveError::physical(
                crate::PhysicalFailure::NoEntrainment,
                "a steady film needs entrainment: u_m = 0 without squeeze (no previous state) has no lubricated solution",
            ));
        }
        let layout = layout.unwrap_or_else(|| Layout::for_film(h_est, dir, options.inlet, options.outlet, options.grading));
        let rheology = PressureRheology::new(&lub, t);
        let build = |grids: &mut GridCache, n: usize| {
            let grid = grids.get(n, layout);
            let q_old = match input.transient {
                Some(s) => grid.x.iter().map(|&xi| s.previous.mass_per_area(xi * b, r) * r / (b * b)).collect(),
                None => Vec::new(),
            };
            let thermal = thermal.map(|f| NodeFactors::on(&grid.x, b, f));
            let asperity = input.asperity.map(|law| AsperityScale { law, film_scale: b * b / r, ph });
            Discretisation { grid, lambda: sc.lambda, kappa: sc.kappa, q_old, upwind: options.upwind, rheology, ph, thermal, asperity }
        };
        // Nested iteration: from the previous state straight on the target grid; from a cold
        // start (or when the warm start fails), solve on grids of n/2^k ≥ 64 nodes first and
        // interpolate each solution as the next guess.
        let n = options.nodes;
        let tol = options.tolerance;
        let mut total_iter = 0;
        let mut failure = None;
        let prediction = prediction.filter(|g| g.pressure.len() == n && g.centre_film > 0.0);
        for attempt in [Attempt::Predicted, Attempt::Warm, Attempt::Cold] {
            let warm = attempt != Attempt::Cold;
            if (attempt == Attempt::Warm && previous.is_none()) || (attempt == Attempt::Predicted && prediction.is_none()) {
                continue;
            }
            let mut levels = vec![n];
            if !warm {
                while levels[levels.len() - 1] / 2 >= 64 {
                    let next = levels[levels.len() - 1] / 2;
                    levels.push(next);
                }
                levels.reverse();
            }
            let mut guess: Option<(Vec<f64>, Vec<f64>, f64)> = if warm {
                previous.map(|s| {
                    let gx: Vec<f64> = s.x.iter().map(|x| x / b).collect();
                    let gp: Vec<f64> = s.pressure.iter().map(|p| p / ph).collect();
                    (gx, gp, (s.film_at(0.0, r) * r / (b * b)).max(1e-9))
                })
            } else {
                None
            };
            let nlev = levels.len();
            for (li, &nl) in levels.iter().enumerate() {
                let finest = li + 1 == nlev;
                let mut prob = build(&mut self.grids, nl);
                let (mut p, mut h0) = match (&guess, &prediction) {
                    (_, Some(g)) if attempt == Attempt::Predicted => {
                        let mut p: Vec<f64> = g.pressure.iter().map(|p| p.max(0.0)).collect();
                        p[0] = 0.0;
                        p[nl - 1] = 0.0;
                        let h0 = h0_for(&p, &prob, g.centre_film * r / (b * b));
                        (p, h0)
                    }
                    (Some((gx, gp, hc)), _) => from_guess(&prob, gx, gp, *hc),
                    (None, _) => cold(&prob, h_est.max(1e-6), h_est),
                };
                let ws = self.workspace(nl);
                let mut run = newton(&prob, ws, &mut p, &mut h0, tol, options.max_iterations, observer)?;
                total_iter += run.iterations;
                if attempt == Attempt::Predicted && !run.converged {
                    break;
                }
                if !run.converged && finest {
                    // Continuation from faster entrainment (thicker film, smaller M): λ·4^k → λ.
                    let (lambda_target, kappa_target) = (prob.lambda, prob.kappa);
                    for start in [2, 4, 7] {
                        let mut good = true;
                        for k in (0..=start).rev() {
                            let f = 4f64.powi(k);
                            prob.lambda = lambda_target * f;
                            prob.kappa = kappa_target * f;
                            if k == start {
                                (p, h0) = cold(&prob, h_est.max(1e-6) * f.powf(0.7), h_est);
                            }
                            let stage_tol = if k == 0 { tol } else { tol.max(1e-6) };
                            let r2 = newton(&prob, ws, &mut p, &mut h0, stage_tol, options.max_iterations, observer)?;
                            total_iter += r2.iterations;
                            if k == 0 {
                                run = r2;
                            } else if !r2.converged {
                                good = false;
                                break;
                            }
                        }
                        if good && run.converged {
                            break;
                        }
                    }
                    prob.lambda = lambda_target;
                    prob.kappa = kappa_target;
                }
                if finest {
                    if !run.converged {
                        let mut history = run.history.clone();
                        if history.len() > 20 {
                            history.drain(..history.len() - 20);
                        }
                        failure = Some(SolveError::NotConverged {
                            solver: "ehl line contact (Newton)",
                            iterations: total_iter,
                            residual: run.residual,
                            tolerance: tol,
                            history,
                        });
                        break;
                    }
                    let meta = Meta { b, ph, moes_m: sc.moes_m, moes_l: sc.moes_l, iterations: total_iter, residual: run.residual };
                    return finish(input, options, &prob, &p, h0, &meta);
                }
                // A coarse level: its solution (converged or the last finite iterate) is the next guess.
                let mut v = Fields::new(nl);
                guess = if prob.evaluate(&p, h0, &mut v) && p.iter().all(|p| p.is_finite()) {
                    let hc = interpolate(&prob.grid.x, &v.h, 0.0);
                    Some((prob.grid.x.clone(), p, hc))
                } else {
                    None
                };
            }
        }
        Err(failure.expect("at least one attempt ran"))
    }
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

/// Solve one line-contact EHL problem (steady, or one transient step when `input.transient` is
/// set). Polls `observer` once per Newton step. For a sequence of related problems (a cam
/// cycle), [`super::TransientSolver`] keeps grids and factorisations between the steps.
pub fn solve(input: &EhlInput, options: &EhlOptions, observer: &dyn Observer) -> Result<EhlSolution, SolveError> {
    Engine::new().solve(input, options, None, None, observer)
}

/// `H0` that puts the centre film at `target` (and keeps the film positive everywhere).
fn h0_for(p: &[f64], prob: &Discretisation, target: f64) -> f64 {
    let n = prob.n();
    let x = &prob.grid.x;
    let mut d = vec![0.0; n];
    prob.grid.kernel.deflection(p, &mut d);
    let centre = x.partition_point(|&x| x < 0.0).min(n - 1);
    let min_rigid = (0..n).map(|i| 0.5 * x[i] * x[i] - d[i]).fold(f64::INFINITY, f64::min);
    let at_centre = 0.5 * x[centre] * x[centre] - d[centre];
    (target - at_centre).max(0.05 * target - min_rigid)
}

/// A guess on a grid from a dimensionless pressure `gp` at `gx` and the centre film `hc`: the
/// interpolated pressure scaled to carry the load.
fn from_guess(prob: &Discretisation, gx: &[f64], gp: &[f64], hc: f64) -> (Vec<f64>, f64) {
    let n = prob.n();
    let x = &prob.grid.x;
    let mut p: Vec<f64> = x.iter().map(|&x| if x <= gx[0] || x >= gx[gx.len() - 1] { 0.0 } else { interpolate(gx, gp, x) }).collect();
    p[0] = 0.0;
    p[n - 1] = 0.0;
    let sum: f64 = p.iter().zip(&prob.grid.cell).map(|(p, w)| p * w).sum();
    if sum > 0.0 {
        p.iter_mut().for_each(|v| *v *= 0.5 * PI / sum);
    } else {
        hertz_guess(x, &mut p, 1.0);
    }
    let h0 = h0_for(&p, prob, hc);
    (p, h0)
}

/// A cold start: a (widened, for light loads) Hertzian pressure and the centre film `hc`.
fn cold(prob: &Discretisation, hc: f64, h_est: f64) -> (Vec<f64>, f64) {
    let mut p = vec![0.0; prob.n()];
    hertz_guess(&prob.grid.x, &mut p, 1f64.max((2.0 * h_est).sqrt()));
    let h0 = h0_for(&p, prob, hc);
    (p, h0)
}
/// Semi-elliptical pressure of half-width `a` carrying the load: `sqrt(1 − (X/a)²)/a` (Hertz for
/// `a = 1`; wider for light loads, where the pressure spreads over `~sqrt(2H)`).
fn hertz_guess(x: &[f64], p: &mut [f64], a: f64) {
    let n = x.len();
    for i in 0..n {
        let s = x[i] / a;
        p[i] = if i == 0 || i == n - 1 { 0.0 } else { (1.0 - s * s).max(0.0).sqrt() / a };
    }
}

fn validate(input: &EhlInput, options: &EhlOptions) -> Result<(), SolveError> {
    let pos = |v: f64, path: &str| {
        if v.is_finite() && v > 0.0 { Ok(()) } else { Err(SolveError::invalid(path, "must be a finite number > 0")) }
    };
    pos(input.load_per_length, "EhlInput.load_per_length")?;
    pos(input.reduced_radius, "EhlInput.reduced_radius")?;
    pos(input.effective_modulus, "EhlInput.effective_modulus")?;
    pos(input.temperature, "EhlInput.temperature")?;
    pos(input.lubricant.viscosity, "EhlInput.lubricant.viscosity")?;
    pos(input.lubricant.density, "EhlInput.lubricant.density")?;
    if !(input.lubricant.pressure_viscosity.is_finite() && input.lubricant.pressure_viscosity >= 0.0) {
        return Err(SolveError::invalid("EhlInput.lubricant.pressure_viscosity", "must be a finite number >= 0"));
    }
    if !input.entrainment_velocity.is_finite() {
        return Err(SolveError::invalid("EhlInput.entrainment_velocity", "must be finite"));
    }
    if !input.sliding_velocity.is_finite() {
        return Err(SolveError::invalid("EhlInput.sliding_velocity", "must be finite"));
    }
    if let Some(s) = input.transient {
        pos(s.time_step, "EhlInput.transient.time_step")?;
        if s.previous.x.len() < 2 {
            return Err(SolveError::invalid("EhlInput.transient.previous", "a previous state needs at least two nodes"));
        }
    }
    if options.nodes < 16 {
        return Err(SolveError::invalid("EhlOptions.nodes", "at least 16 nodes"));
    }
    if !(options.tolerance.is_finite() && options.tolerance > 0.0) {
        return Err(SolveError::invalid("EhlOptions.tolerance", "must be a finite number > 0"));
    }
    for (v, path) in [(options.inlet, "EhlOptions.inlet"), (options.outlet, "EhlOptions.outlet")] {
        if let Some(v) = v {
            if !(v.is_finite() && v > 1.0) {
                return Err(SolveError::invalid(path, "must exceed one Hertzian half-width"));
            }
        }
    }
    Ok(())
}

/// Vertex `(x, f)` of the parabola through the nodes `i − 1, i, i + 1` (an extremum's refined
/// position and value), kept within the neighbouring nodes; the node itself at the ends.
fn vertex(x: &[f64], f: &[f64], i: usize) -> (f64, f64) {
    if i == 0 || i + 1 >= f.len() {
        return (x[i], f[i]);
    }
    let (x0, x1, x2) = (x[i - 1], x[i], x[i + 1]);
    let (f0, f1, f2) = (f[i - 1], f[i], f[i + 1]);
    // Divided differences: f ≈ f1 + d1 (x − x1) + d2 (x − x1)(x − x0) ... in Newton form.
    let a = (f2 - f1) / (x2 - x1);
    let c = (f1 - f0) / (x1 - x0);
    let curv = (a - c) / (x2 - x0); // f''/2
    if curv == 0.0 || !curv.is_finite() {
        return (x1, f1);
    }
    // Slope at x1 of the parabola: (c (x2 − x1) + a (x1 − x0)) / (x2 − x0).
    let slope = (c * (x2 - x1) + a * (x1 - x0)) / (x2 - x0);
    let dx = (-slope / (2.0 * curv)).clamp(x0 - x1, x2 - x1);
    (x1 + dx, f1 + slope * dx + curv * dx * dx)
}

/// Linear interpolation of `f(x)` at `at` (clamped to the ends).
fn interpolate(x: &[f64], f: &[f64], at: f64) -> f64 {
    let n = x.len();
    let i = x.partition_point(|&v| v <= at).clamp(1, n - 1);
    let t = ((at - x[i - 1]) / (x[i] - x[i - 1])).clamp(0.0, 1.0);
    f[i - 1] * (1.0 - t) + f[i] * t
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

fn finish(input: &EhlInput, options: &EhlOptions, prob: &Discretisation, p: &[f64], h0: f64, meta: &Meta) -> Result<EhlSolution, SolveError> {
    let &Meta { b, ph, moes_m, moes_l, iterations, residual } = meta;
    let n = prob.n();
    let r = input.reduced_radius;
    let mut v = Fields::new(n);
    if !prob.evaluate(p, h0, &mut v) {
        return Err(SolveError::physical(crate::PhysicalFailure::FilmCollapse, "the converged film is not positive"));
    }
    let hs = b * b / r; // film scale
    let x: Vec<f64> = prob.grid.x.iter().map(|&x| x * b).collect();
    let pressure: Vec<f64> = p.iter().map(|&p| p.max(0.0) * ph).collect();
    let film: Vec<f64> = v.h.iter().map(|&h| h * hs).collect();
    let asperity_pressure: Vec<f64> = match prob.asperity {
        Some(_) => (0..n).map(|i| v.pa[i].max(0.0).min(p[i].max(0.0)) * ph).collect(),
        None => Vec::new(),
    };
    let fluid_pressure: Vec<f64> = match prob.asperity {
        Some(_) => (0..n).map(|i| pressure[i] - asperity_pressure[i]).collect(),
        None => pressure.clone(),
    };
    let asperity_load_per_length: f64 = asperity_pressure.iter().zip(&prob.grid.cell).map(|(p, c)| p * c * b).sum();
    ensure_finite("ehl asperity pressure", &asperity_pressure)?;
    ensure_finite("ehl pressure", &pressure)?;
    ensure_finite("ehl film", &film)?;
    let dir = if input.entrainment_velocity >= 0.0 { 1.0 } else { -1.0 };
    let central_film = interpolate(&x, &film, 0.0);
    let argmin = |range: &mut dyn Iterator<Item = usize>| {
        range.fold(None, |best: Option<usize>, i| match best {
            Some(j) if film[j] <= film[i] => Some(j),
            _ => Some(i),
        })
    };
    let imin = argmin(&mut (0..n)).unwrap_or(0);
    // The parabolic vertex refines the minimum between nodes. Where the grid does not resolve a
    // sharp exit constriction (very large M on a coarse grid) the parabola overshoots — even below
    // zero (regression: p0 = 2.7 GPa, u = 0.2 mm/s, 128 nodes) — so it is trusted only within a
    // factor of two of the node value; and no minimum exceeds the central film.
    let refined_min = |i: usize| match vertex(&x, &film, i) {
        (pos, h) if h >= 0.5 * film[i] => (pos, h),
        _ => (x[i], film[i]),
    };
    let (min_film_position, min_film) = refined_min(imin);
    let min_film = min_film.min(central_film);
    let downstream = |i: &usize| prob.grid.x[*i] * dir > 0.0;
    let iexit = argmin(&mut (0..n).filter(downstream)).unwrap_or(imin);
    let (_, exit_film) = refined_min(iexit);
    let imax = (0..n).fold(0, |j, i| if pressure[i] > pressure[j] { i } else { j });
    let (max_pressure_position, max_pressure) = vertex(&x, &pressure, imax);
    // Spike: the most downstream local maximum beyond the centre that exceeds the Hertzian
    // pressure at its position and a fifth of the peak pressure.
    let mut spike = None;
    for i in 1..n - 1 {
        let local_max = pressure[i] > pressure[i - 1] && pressure[i] >= pressure[i + 1];
        let hertz = (1.0 - prob.grid.x[i] * prob.grid.x[i]).max(0.0).sqrt() * ph;
        if local_max && downstream(&i) && pressure[i] > hertz && pressure[i] >= 0.2 * pressure[imax] {
            let (position, val) = vertex(&x, &pressure, i);
            let cand = PressureSpike { pressure: val, position };
            spike = match spike {
                Some(PressureSpike { position, .. }) if position * dir > cand.position * dir => spike,
                _ => Some(cand),
            };
        }
    }
    let traction = traction(
        &x,
        &fluid_pressure,
        &film,
        &input.lubricant,
        input.temperature,
        input.sliding_velocity,
        input.load_per_length,
        &input.rheology,
    );
    ensure_finite(
        "ehl traction",
        [&traction.force_body_1, &traction.force_body_2, &traction.friction_coefficient, &traction.rolling_force],
    )?;
    ensure_finite("ehl films", [&central_film, &min_film, &exit_film, &max_pressure])?;
    let density_ratio = (0..n).map(|i| prob.mass_density(&v, i)).collect();
    let state = EhlState { x: x.clone(), pressure: pressure.clone(), film: film.clone(), density_ratio, asperity_pressure: asperity_pressure.clone() };
    let profiles = options.profiles.then(|| Profiles { x, pressure, film, asperity_pressure });
    Ok(EhlSolution {
        hertz_half_width: b,
        hertz_pressure: ph,
        moes_m,
        moes_l,
        central_film,
        min_film,
        min_film_position,
        exit_film,
        max_pressure,
        max_pressure_position,
        pressure_spike: spike,
        asperity_load_per_length,
        traction,
        profiles,
        state,
        nodes: n,
        convergence: Convergence { iterations, residual, tolerance: options.tolerance, termination: Termination::Converged },
    })
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
        let prob = Discretisation { grid: grid.clone(), lambda: sc.lambda, kappa: 0.0, q_old: Vec::new(), upwind: Upwind::Second, rheology: PressureRheology::new(&lub, input.temperature), ph: sc.ph, thermal: None, asperity: None };
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
