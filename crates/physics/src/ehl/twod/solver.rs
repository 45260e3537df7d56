//! The semismooth Newton–Krylov solver of the 2-D EHL problem (equations and method in [`super`]).
//!
//! Unknowns: `P` at the interior nodes (row-major) and `H0`. Rows: `φ = min(P, −c F)` per
//! interior node with `c = 1/|∂F/∂P|` (the diagonal of the preconditioner, elastic self term
//! included) — the complementarity reformulation of the 1-D solver (`super::super::newton`) —
//! and the load balance. A Newton step solves `J δ = −φ` by restarted GMRES, right-preconditioned
//! by the sparse LU of the near-field Jacobian; a backtracking line search on `Σ φ² ΔXΔY + G²`
//! from a fraction-to-boundary step on the film ([`film_damping`]) damps it (the Reynolds terms
//! see the film above a small floor, [`FILM_FLOOR`], so every trial point is evaluable).
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

use super::elastic::Deflection;
use super::geometry::{domain, node_grid, scales, side_gap, Domain, NodeGrid, Scales};
use super::{Ehl2dInput, Ehl2dOptions, Ehl2dSolution, Fields2d, Geometry2d, Located, Squeeze2d, Warm2d};
use crate::ehl::rheology::PressureRheology;
use crate::numerics::krylov::{self, dot};
use crate::{Convergence, Observer, SolveError, Termination};
use faer::sparse::linalg::lu::supernodal::{self, SupernodalLu, SymbolicSupernodalLu};
use faer::dyn_stack::{MemBuffer, MemStack, StackReq};
use faer::perm::PermRef;
use faer::sparse::linalg::{qr, SymbolicSupernodalParams};
use faer::sparse::{SparseColMatRef, SymbolicSparseColMatRef};

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

/// Development aid (policy scan): `TRIBOD_EHL2D_REUSE=max,refresh,across` overrides the two
/// thresholds above and whether a factor is kept across solves (1) or not (0).
fn reuse_policy() -> (usize, usize, bool) {
    static P: std::sync::OnceLock<(usize, usize, bool)> = std::sync::OnceLock::new();
    *P.get_or_init(|| {
        let v: Vec<usize> = std::env::var("TRIBOD_EHL2D_REUSE").ok().map(|s| s.split(',').filter_map(|x| x.trim().parse().ok()).collect()).unwrap_or_default();
        if v.len() == 3 {
            (v[0], v[1], v[2] != 0)
        } else {
            (REUSE_MAX, REUSE_REFRESH, true)
        }
    })
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

/// [`WARM_FORCING`], or (development aid) `TRIBOD_EHL2D_FORCING=first,max,gamma,alpha,over`
/// (`γ < 0`: the fixed rule with the `over` floor); `TRIBOD_EHL2D_FORCING=off`: the fixed rule.
fn warm_forcing() -> Option<Forcing> {
    static F: std::sync::OnceLock<Option<Forcing>> = std::sync::OnceLock::new();
    *F.get_or_init(|| match std::env::var("TRIBOD_EHL2D_FORCING") {
        Err(_) => Some(WARM_FORCING),
        Ok(s) => {
            let v: Vec<f64> = s.split(',').filter_map(|x| x.trim().parse().ok()).collect();
            (v.len() == 5).then(|| Forcing { first: v[0], max: v[1], gamma: v[2], alpha: v[3], over: v[4] })
        }
    })
}

/// Whether the near-field preconditioner carries the Poiseuille terms' film dependence
/// ([`Problem::precondition`]); development aid: `TRIBOD_EHL2D_PFILM=0` leaves it out (the
/// wedge-only near field before `ehl2d-12`).
fn poiseuille_film() -> bool {
    static B: std::sync::OnceLock<bool> = std::sync::OnceLock::new();
    *B.get_or_init(|| std::env::var("TRIBOD_EHL2D_PFILM").map(|s| s.trim() != "0").unwrap_or(true))
}

/// Whether a node whose film is at the floor may take the contact row `H = floor` (the film
/// floor as a complementarity, [`Problem::row_kind`]); development aid: `TRIBOD_EHL2D_CONTACT=0`
/// keeps every non-cavitated row a Reynolds row (before `ehl2d-13`).
fn floor_contact() -> bool {
    static B: std::sync::OnceLock<bool> = std::sync::OnceLock::new();
    *B.get_or_init(|| std::env::var("TRIBOD_EHL2D_CONTACT").map(|s| s.trim() != "0").unwrap_or(true))
}

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
/// 2.4e-5); the rule now only damps ([`film_damping`]). A converged film at the floor is refused
/// by the pinch check ([`PINCH`] ≫ 1e-3).
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

impl Problem {
    fn new(input: &Ehl2dInput, s: &Scales, d: Domain, nx: usize, ny: usize, near: usize) -> Self {
        let NodeGrid { dx, dy, x, y, geom } = node_grid(input, s, d, nx, ny);
        let mut unk = vec![usize::MAX; nx * ny];
        let mut nodes = Vec::with_capacity((nx - 2) * (ny - 2));
        for j in 1..ny - 1 {
            for i in 1..nx - 1 {
                unk[j * nx + i] = nodes.len();
                nodes.push(j * nx + i);
            }
        }
        Problem {
            nx,
            ny,
            dx,
            dy,
            x,
            y,
            geom,
            lambda: s.lambda,
            kappa: 0.0,
            q_old: vec![0.0; nx * ny],
            target: None,
            load: s.load,
            p_ref: s.p_ref,
            rheo: PressureRheology::new(&input.lubricant, input.temperature),
            defl: Deflection::new(nx, ny, dx, dy, s.c_def),
            near,
            floor: FILM_FLOOR * s.h_est,
            second: true,
            theta: 1.0,
            unk,
            nodes,
            pattern: std::cell::RefCell::new(None),
            kept: None,
            factorisations: 0,
            forcing: None,
        }
    }

    /// The squeeze term of the problem itself: none (`κ = 0`, steady) or the transient step's
    /// ([`Problem::target`]).
    fn restore_target(&mut self) {
        match &self.target {
            None => self.kappa = 0.0,
            Some((kappa, q)) => {
                self.kappa = *kappa;
                self.q_old.copy_from_slice(q);
            }
        }
    }

    /// A pseudo-time step `ΔT` ([`march`]) from the iterate with fields `v`: `κ_ps = λ/ΔT`,
    /// `(ρ̄H)_ps` the iterate's, on top of the problem's own squeeze term `(κ_t, q_t)`, if any:
    /// `κ = κ_t + κ_ps`, `q_old = (κ_t q_t + κ_ps (ρ̄H)_ps)/κ` (the residual's
    /// `−κ_t (ρ̄H − q_t) − κ_ps (ρ̄H − (ρ̄H)_ps)` in one term).
    fn pseudo_step(&mut self, dt: f64, v: &Fields) {
        for (q, (r, h)) in self.q_old.iter_mut().zip(v.rho.iter().zip(&v.h)) {
            *q = r * h;
        }
        self.kappa = self.lambda / dt;
        if let Some((kt, qt)) = &self.target {
            let kp = self.kappa;
            self.kappa = kt + kp;
            for (q, b) in self.q_old.iter_mut().zip(qt) {
                *q = (kt * b + kp * *q) / self.kappa;
            }
        }
    }

    /// `ρ̄H` at the nodes (the film the Reynolds terms see) at `(p, h0)`; `None` when not finite.
    fn mass(&mut self, p: &[f64], h0: f64) -> Option<Vec<f64>> {
        let mut v = Fields::default();
        self.evaluate(p, h0, &mut v).then(|| v.rho.iter().zip(&v.h).map(|(r, h)| r * h).collect())
    }

    /// Upwind stencil of `∂Q/∂X` at column `i`: `(offset back, weight)`.
    fn wedge(&self, i: usize) -> [(usize, f64); 3] {
        if i >= 2 && self.second {
            [(0, 1.5 / self.dx), (1, -2.0 / self.dx), (2, 0.5 / self.dx)]
        } else {
            [(0, 1.0 / self.dx), (1, -1.0 / self.dx), (0, 0.0)]
        }
    }

    /// Weights of `ρ̄H` at `(offset back, weight)` in the convective and squeeze terms of column
    /// `i`: `λ ∂(ρ̄H)/∂X + κ ρ̄H` (the residual subtracts `Σ w ρ̄H` and adds `κ (ρ̄H)_old`).
    fn stencil(&self, i: usize) -> [(usize, f64); 3] {
        let mut w = self.wedge(i);
        for e in w.iter_mut() {
            e.1 *= self.lambda;
        }
        w[0].1 += self.kappa;
        w
    }

    /// Fields at `(p, h0)` (the film held at the floor where it falls below); `false` when a value
    /// is not finite.
    fn evaluate(&mut self, p: &[f64], h0: f64, v: &mut Fields) -> bool {
        let n = self.nx * self.ny;
        for a in [&mut v.w, &mut v.h, &mut v.rho, &mut v.drho, &mut v.eps, &mut v.deps, &mut v.f, &mut v.on, &mut v.hraw] {
            a.resize(n, 0.0);
        }
        self.defl.apply(p, &mut v.w);
        for k in 0..n {
            let mut h = h0 + self.geom[k] + v.w[k];
            v.hraw[k] = h;
            v.on[k] = 1.0;
            if h < self.floor {
                h = self.floor;
                v.on[k] = 0.0;
            }
            if !(h > 0.0 && h.is_finite()) {
                return false;
            }
            let (ln_eta, dln, rho, drho) = self.rheo.at(p[k] * self.p_ref);
            let ln_eta = ln_eta.min(LN_ETA_CAP);
            let eps = rho * h * h * h * (-ln_eta).exp();
            v.h[k] = h;
            v.rho[k] = rho;
            v.drho[k] = drho * self.p_ref;
            v.eps[k] = eps;
            v.deps[k] = eps * (drho / rho - dln) * self.p_ref;
        }
        let (nx, dx2, dy2) = (self.nx, self.dx * self.dx, self.dy * self.dy);
        let mut sum = 0.0;
        for &k in &self.nodes {
            let i = k % nx;
            let e = &v.eps;
            let exp_ = face_of(self.theta, e[k], e[k + 1]).0;
            let exm = face_of(self.theta, e[k], e[k - 1]).0;
            let eyp = face_of(self.theta, e[k], e[k + nx]).0;
            let eym = face_of(self.theta, e[k], e[k - nx]).0;
            let pois = (exp_ * (p[k + 1] - p[k]) - exm * (p[k] - p[k - 1])) / dx2
                + (eyp * (p[k + nx] - p[k]) - eym * (p[k] - p[k - nx])) / dy2;
            let mut wedge = 0.0;
            for (s, wt) in self.stencil(i) {
                wedge += wt * v.rho[k - s] * v.h[k - s];
            }
            v.f[k] = pois - wedge + self.kappa * self.q_old[k];
            sum += p[k];
        }
        v.g = sum * self.dx * self.dy / self.load - 1.0;
        v.f.iter().all(|x| x.is_finite()) && v.g.is_finite()
    }

    /// `out = A x`: the scaled Newton matrix applied to `x` (`dP` at the unknowns, then `dH0`).
    fn apply(&mut self, p: &[f64], v: &Fields, active: &[u8], c: &[f64], x: &[f64], out: &mut [f64], buf: &mut Buffers) {
        let n = self.nx * self.ny;
        let m = self.nodes.len();
        buf.dp.resize(n, 0.0);
        buf.dw.resize(n, 0.0);
        buf.dq.resize(n, 0.0);
        buf.de.resize(n, 0.0);
        buf.dp.iter_mut().for_each(|d| *d = 0.0);
        for (u, &k) in self.nodes.iter().enumerate() {
            buf.dp[k] = x[u];
        }
        let dh0 = x[m];
        self.defl.apply(&buf.dp, &mut buf.dw);
        for k in 0..n {
            let dh = (dh0 + buf.dw[k]) * v.on[k];
            buf.dq[k] = v.drho[k] * buf.dp[k] * v.h[k] + v.rho[k] * dh;
            buf.de[k] = v.deps[k] * buf.dp[k] + 3.0 * v.eps[k] / v.h[k] * dh;
        }
        let (nx, dx2, dy2) = (self.nx, self.dx * self.dx, self.dy * self.dy);
        let mut sum = 0.0;
        for (u, &k) in self.nodes.iter().enumerate() {
            let dp = &buf.dp;
            sum += dp[k];
            if active[u] == CAVITATED {
                out[u] = dp[k];
                continue;
            }
            if active[u] == CONTACT {
                out[u] = self.contact_scale() * (dh0 + buf.dw[k]);
                continue;
            }
            let i = k % nx;
            let (e, de) = (&v.eps, &buf.de);
            let mut df = 0.0;
            for (nb, d2) in [(k + 1, dx2), (k - 1, dx2), (k + nx, dy2), (k - nx, dy2)] {
                let (ef, w1, w2) = face_of(self.theta, e[k], e[nb]);
                let def = w1 * de[k] + w2 * de[nb];
                df += (def * (p[nb] - p[k]) + ef * (dp[nb] - dp[k])) / d2;
            }
            let mut wedge = 0.0;
            for (s, wt) in self.stencil(i) {
                wedge += wt * buf.dq[k - s];
            }
            out[u] = c[u] * (df - wedge);
        }
        out[m] = sum * self.dx * self.dy / self.load;
    }

    /// The near-field preconditioner (scaled like the Newton matrix) and the row scales `c`;
    /// `factor` false: the row scales and the active set only (`None`).
    /// `observer`: a large factorisation runs beside the caller, which polls it
    /// ([`NearLu::new_watched`]); an interrupt there is `Err`.
    fn precondition(&self, p: &[f64], v: &Fields, active: &mut [u8], c: &mut [f64], factor: bool, observer: &dyn Observer) -> Result<Option<Precond>, SolveError> {
        let (nx, ny, dx2, dy2) = (self.nx, self.ny, self.dx * self.dx, self.dy * self.dy);
        let m = self.nodes.len();
        let r = self.near as isize;
        if !factor {
            // The diagonal alone, summed in the order the rows below push its entries (the same
            // row scales to the last bit): the Poiseuille terms, then per wedge point its own
            // `ρ̄'H` term and the deflection self-coefficient reaching this node.
            for (u, &k) in self.nodes.iter().enumerate() {
                let i = k % nx;
                let e = &v.eps;
                let mut diag = 0.0;
                for (nb, d2) in [(k + 1, dx2), (k - 1, dx2), (k + nx, dy2), (k - nx, dy2)] {
                    let (ef, w1, _) = face_of(self.theta, e[k], e[nb]);
                    diag += -ef / d2 + w1 * v.deps[k] * (p[nb] - p[k]) / d2;
                }
                for (s, wt) in self.stencil(i) {
                    if wt == 0.0 {
                        continue;
                    }
                    let kk = k - s;
                    if s == 0 {
                        diag += -wt * v.drho[kk] * v.h[kk];
                    }
                    if s <= self.near {
                        diag += -wt * v.on[kk] * v.rho[kk] * self.defl.coefficient(s, 0);
                    }
                }
                let cu = 1.0 / diag.abs().max(1e-300);
                c[u] = cu;
                active[u] = self.row_kind(p, v, cu, k);
            }
            return Ok(None);
        }
        // Every row's entries (column, value), cavitated rows too: the pattern is then that of the
        // grid alone, its symbolic LU computed once ([`NearPattern`]).
        let mut ent: Vec<(usize, f64)> = Vec::with_capacity(m * (10 + (2 * self.near + 3) * (2 * self.near + 1)));
        let mut row_ptr: Vec<usize> = Vec::with_capacity(m + 1);
        row_ptr.push(0);
        let mut row: Vec<(usize, f64)> = Vec::with_capacity(64);
        for (u, &k) in self.nodes.iter().enumerate() {
            let (i, j) = (k % nx, k / nx);
            row.clear();
            let e = &v.eps;
            for (nb, d2) in [(k + 1, dx2), (k - 1, dx2), (k + nx, dy2), (k - nx, dy2)] {
                let (ef, w1, w2) = face_of(self.theta, e[k], e[nb]);
                let dpf = p[nb] - p[k];
                row.push((u, -ef / d2 + w1 * v.deps[k] * dpf / d2));
                if self.unk[nb] != usize::MAX {
                    row.push((self.unk[nb], ef / d2 + w2 * v.deps[nb] * dpf / d2));
                }
            }
            for (s, wt) in self.stencil(i) {
                if wt == 0.0 {
                    continue;
                }
                let kk = k - s;
                let (ki, kj) = (i - s, j);
                let lw = -wt;
                if self.unk[kk] != usize::MAX {
                    row.push((self.unk[kk], lw * v.drho[kk] * v.h[kk]));
                }
                let lw = lw * v.on[kk];
                row.push((m, lw * v.rho[kk]));
                for dj in -r..=r {
                    let lj = kj as isize + dj;
                    if lj < 1 || lj >= ny as isize - 1 {
                        continue;
                    }
                    for di in -r..=r {
                        let li = ki as isize + di;
                        if li < 1 || li >= nx as isize - 1 {
                            continue;
                        }
                        let l = lj as usize * nx + li as usize;
                        row.push((self.unk[l], lw * v.rho[kk] * self.defl.coefficient(di.unsigned_abs(), dj.unsigned_abs())));
                    }
                }
            }
            let diag: f64 = row.iter().filter(|(col, _)| *col == u).map(|(_, val)| val).sum();
            if poiseuille_film() {
                // The Poiseuille terms' film dependence `∂ε_f/∂H = w·3ε/H` at the row's node and
                // its four neighbours, through the near-field deflection, within the columns the
                // wedge terms already occupy (the pattern's box `i − 2 − r … i + r`,
                // `j − r … j + r`): with the geometric face mean (`θ → 1`) a face between an
                // inlet node (large ε) and a contact node (small ε) weighs the contact node's film
                // by `1.5 sqrt(ε_b/ε_a)`, which the wedge-only near field left out. The row scale
                // `c` (above) is unchanged, so is the residual.
                let lo = (if i >= 2 && self.second { 2 } else { 1 }) + r;
                let mut pts = [(k, 0.0); 5];
                for (q, (nb, d2)) in [(k + 1, dx2), (k - 1, dx2), (k + nx, dy2), (k - nx, dy2)].into_iter().enumerate() {
                    let (_, w1, w2) = face_of(self.theta, e[k], e[nb]);
                    let dpf = (p[nb] - p[k]) / d2;
                    pts[0].1 += w1 * 3.0 * e[k] / v.h[k] * v.on[k] * dpf;
                    pts[q + 1] = (nb, w2 * 3.0 * e[nb] / v.h[nb] * v.on[nb] * dpf);
                }
                for &(q, a) in &pts {
                    if a == 0.0 || !a.is_finite() {
                        continue;
                    }
                    let (qi, qj) = ((q % nx) as isize, (q / nx) as isize);
                    row.push((m, a));
                    for dj in -r..=r {
                        let lj = j as isize + dj;
                        if lj < 1 || lj >= ny as isize - 1 || (lj - qj).abs() > r {
                            continue;
                        }
                        for di in -lo..=r {
                            let li = i as isize + di;
                            if li < 1 || li >= nx as isize - 1 || (li - qi).abs() > r {
                                continue;
                            }
                            let l = lj as usize * nx + li as usize;
                            row.push((self.unk[l], a * self.defl.coefficient((li - qi).unsigned_abs(), (lj - qj).unsigned_abs())));
                        }
                    }
                }
            }
            let cu = 1.0 / diag.abs().max(1e-300);
            c[u] = cu;
            active[u] = self.row_kind(p, v, cu, k);
            ent.extend(row.iter().map(|&(col, val)| (col, cu * val)));
            row_ptr.push(ent.len());
        }
        // The bordered system `[B u; wᵀ 0]` (the `H0` column `u`, the load row `w`) by its Schur
        // complement: factorising it with the dense border made the sparse LU fill in (35 s at
        // 97², measured), the block `B` alone factorises in a fraction of a second.
        let pattern = {
            let mut cache = self.pattern.borrow_mut();
            match cache.as_ref().filter(|pat| pat.covers(m, &row_ptr, &ent)) {
                Some(pat) => pat.clone(),
                None => {
                    let order = nested_dissection(nx - 2, ny - 2, 2 + 2 * self.near, 2 * self.near.max(1));
                    let Some(pat) = NearPattern::new(m, &row_ptr, &ent, order) else { return Ok(None) };
                    let pat = std::sync::Arc::new(pat);
                    *cache = Some(pat.clone());
                    pat
                }
            }
        };
        let mut ucol = vec![0.0; m];
        let mut values = vec![0.0; pattern.row_idx.len()];
        let mut slot = vec![usize::MAX; m];
        for u in 0..m {
            let (a, b) = (pattern.row_ptr[u], pattern.row_ptr[u + 1]);
            for (&col, &pos) in pattern.row_col[a..b].iter().zip(&pattern.row_pos[a..b]) {
                slot[col] = pos;
            }
            if active[u] == CAVITATED {
                values[slot[u]] = 1.0;
                continue;
            }
            if active[u] == CONTACT {
                // `s (H0 + W_k)`: the deflection's near field about the node (inside the box the
                // row's wedge terms occupy) and the `H0` border.
                let sc = self.contact_scale();
                let k = self.nodes[u];
                let (i, j) = ((k % nx) as isize, (k / nx) as isize);
                ucol[u] += sc;
                for lj in (j - r).max(1)..=(j + r).min(ny as isize - 2) {
                    for li in (i - r).max(1)..=(i + r).min(nx as isize - 2) {
                        let l = lj as usize * nx + li as usize;
                        values[slot[self.unk[l]]] += sc * self.defl.coefficient((li - i).unsigned_abs(), (lj - j).unsigned_abs());
                    }
                }
                continue;
            }
            for &(col, val) in &ent[row_ptr[u]..row_ptr[u + 1]] {
                if col == m {
                    ucol[u] += val;
                } else {
                    values[slot[col]] += val;
                }
            }
        }
        let Some(lu) = NearLu::new_watched(pattern, values, observer)? else { return Ok(None) };
        lu.solve_in_place(&mut ucol);
        let sum_bu = ucol.iter().sum::<f64>();
        Ok((sum_bu.is_finite() && ucol.iter().all(|x| x.is_finite())).then_some(Precond { lu, bu: ucol, sum_bu, c: c.to_vec(), active: active.to_vec() }))
    }

    /// The load row's weight `ΔX ΔY / W` (the `wᵀ` of [`Precond`]).
    fn load_weight(&self) -> f64 {
        self.dx * self.dy / self.load
    }

    fn phi(&self, p: &[f64], v: &Fields, c: &[f64], out: &mut Vec<f64>) {
        out.clear();
        let contact = floor_contact();
        let sc = self.contact_scale();
        for (u, &k) in self.nodes.iter().enumerate() {
            let r = p[k].min(-c[u] * v.f[k]);
            out.push(if contact { r.min(sc * (v.hraw[k] - self.floor)) } else { r });
        }
    }

    /// Scale of the contact row `s (H − floor)`: `1/C₀₀` (the deflection's self-coefficient), so
    /// that its derivative in the node's own pressure is 1, as a cavitated row's.
    fn contact_scale(&self) -> f64 {
        1.0 / self.defl.coefficient(0, 0)
    }

    /// The row of node `k` in the semismooth Newton matrix: the complementarity
    /// `min(P, −c F, s (H − floor)) = 0` of the three regimes — cavitated (`P = 0`, `F ≤ 0`),
    /// lubricated (`F = 0`, `P ≥ 0`, `H ≥ floor`) and in contact at the film floor (`H = floor`,
    /// the pressure free and set by it, `F ≤ 0`: the film carries less than the node's pressure,
    /// the rest is the floor's, as in the unified mixed-lubrication treatments, Hu & Zhu, ASME
    /// J. Tribol. 122 (2000)). The Reynolds terms keep `max(H, floor)`; without the contact row a
    /// node at the floor had no film feedback in the Jacobian and Newton asked for pressure
    /// changes of 100× P there (issue 16, `ehl2d-12`'s roller trace). Ties: cavitated, then
    /// lubricated.
    fn row_kind(&self, p: &[f64], v: &Fields, cu: f64, k: usize) -> u8 {
        let (a, b) = (p[k], -cu * v.f[k]);
        if !floor_contact() {
            return if a <= b { CAVITATED } else { FLUID };
        }
        let h = self.contact_scale() * (v.hraw[k] - self.floor);
        if a <= b && a <= h {
            CAVITATED
        } else if h < b {
            CONTACT
        } else {
            FLUID
        }
    }
}

/// The preconditioner: the near-field Newton matrix `[B u; wᵀ 0]` (unknowns `P`, then `H0`),
/// solved by the sparse LU of `B` and the Schur complement `s = wᵀB⁻¹u` (`w` the constant
/// load-row weight, taken from the problem at each use: a kept factor may come from another load).
struct Precond {
    lu: NearLu,
    /// `B⁻¹u`.
    bu: Vec<f64>,
    /// `Σ B⁻¹u` (the Schur complement is `w` times it).
    sum_bu: f64,
    /// The row scales and the active set it was factorised with.
    c: Vec<f64>,
    active: Vec<u8>,
}

impl Precond {
    /// `z ← M⁻¹ z`: `x1 = B⁻¹f`, `y = (wᵀx1 − g)/s`, `x = x1 − y B⁻¹u`.
    fn apply(&self, z: &mut [f64], w: f64, rescale: &[f64]) {
        let m = self.bu.len();
        let g = z[m];
        if !rescale.is_empty() {
            for (zi, s) in z[..m].iter_mut().zip(rescale) {
                *zi *= s;
            }
        }
        self.lu.solve_in_place(&mut z[..m]);
        let schur = w * self.sum_bu;
        let y = if schur != 0.0 { (w * z[..m].iter().sum::<f64>() - g) / schur } else { 0.0 };
        for (zi, bi) in z[..m].iter_mut().zip(&self.bu) {
            *zi -= y * bi;
        }
        z[m] = y;
    }
}

/// The sparsity pattern of the near-field matrix `B` of a grid and its symbolic LU (a
/// nested-dissection column ordering of the grid, [`nested_dissection`], and the supernodal
/// elimination structure). Every row carries its full stencil, cavitated rows too (their values
/// are the identity and structural zeros), so the pattern depends on the grid only and its
/// symbolic LU is computed once per grid, not at every change of the active set and every new
/// solve: faer's default ordering (colamd) of each pattern cost 1.4× a numeric factorisation on
/// 65×129 (`BENCHMARKS.md` issue 16, `ehl2d-10`).
struct NearPattern {
    /// CSC of `B` (row indices sorted in each column).
    col_ptr: Vec<usize>,
    row_idx: Vec<usize>,
    /// Per row `u`, `row_ptr[u]..row_ptr[u + 1]`: its columns (sorted) and their positions in
    /// the CSC arrays.
    row_ptr: Vec<usize>,
    row_col: Vec<usize>,
    row_pos: Vec<usize>,
    /// Column ordering (position → column) and its inverse.
    col_fwd: Vec<usize>,
    col_inv: Vec<usize>,
    symbolic: SymbolicSupernodalLu<usize>,
}

impl NearPattern {
    /// The pattern of rows `ent[row_ptr[u]..row_ptr[u + 1]]` (column `m`, the `H0` border, left
    /// out); `None` when the symbolic factorisation fails.
    fn new(m: usize, row_ptr: &[usize], ent: &[(usize, f64)], col_fwd: Vec<usize>) -> Option<Self> {
        if col_fwd.len() != m {
            return None;
        }
        let mut rp = Vec::with_capacity(m + 1);
        let mut row_col: Vec<usize> = Vec::with_capacity(ent.len());
        rp.push(0);
        for u in 0..m {
            let start = row_col.len();
            row_col.extend(ent[row_ptr[u]..row_ptr[u + 1]].iter().map(|e| e.0).filter(|&col| col < m));
            row_col[start..].sort_unstable();
            let mut w = start;
            for r in start..row_col.len() {
                if r == start || row_col[r] != row_col[w - 1] {
                    row_col[w] = row_col[r];
                    w += 1;
                }
            }
            row_col.truncate(w);
            rp.push(row_col.len());
        }
        // Transpose to CSC: rows visited in order, so each column's row indices come sorted.
        let mut col_ptr = vec![0usize; m + 1];
        for &col in &row_col {
            col_ptr[col + 1] += 1;
        }
        for cc in 0..m {
            col_ptr[cc + 1] += col_ptr[cc];
        }
        let mut next = col_ptr.clone();
        let mut row_idx = vec![0usize; row_col.len()];
        let mut row_pos = vec![0usize; row_col.len()];
        for u in 0..m {
            for q in rp[u]..rp[u + 1] {
                let col = row_col[q];
                row_idx[next[col]] = u;
                row_pos[q] = next[col];
                next[col] += 1;
            }
        }
        let mut col_inv = vec![0usize; m];
        for (pos, &col) in col_fwd.iter().enumerate() {
            col_inv[col] = pos;
        }
        // faer's supernodal LU with partial pivoting, symbolic part with a given column ordering:
        // the column elimination tree (that of `BᵀB`), its postorder, the column counts of `BᵀB`
        // and the supernodal structure.
        let a = SymbolicSparseColMatRef::new_checked(m, m, &col_ptr, None, &row_idx);
        let values = vec![0.0; row_idx.len()];
        let at = SparseColMatRef::new(a, &values).transpose().to_col_major().ok()?;
        let perm = PermRef::new_checked(&col_fwd, &col_inv, m);
        let (mut etree, mut post, mut col_counts, mut min_col) = (vec![0usize; m], vec![0usize; m], vec![0usize; m], vec![0usize; m]);
        let et = qr::col_etree(a, Some(perm), &mut etree, MemStack::new(&mut MemBuffer::new(qr::col_etree_scratch::<usize>(m, m))));
        qr::postorder(&mut post, et, MemStack::new(&mut MemBuffer::new(qr::postorder_scratch::<usize>(m))));
        qr::column_counts_ata(&mut col_counts, &mut min_col, at.symbolic(), Some(perm), et, &post, MemStack::new(&mut MemBuffer::new(StackReq::new::<usize>(6 * m))));
        let symbolic = supernodal::factorize_supernodal_symbolic_lu::<usize>(a, Some(perm), &min_col, et, &col_counts, MemStack::new(&mut MemBuffer::new(supernodal::factorize_supernodal_symbolic_lu_scratch::<usize>(m, m))), SymbolicSupernodalParams::default()).ok()?;
        Some(NearPattern { col_ptr, row_idx, row_ptr: rp, row_col, row_pos, col_fwd, col_inv, symbolic })
    }

    /// Whether every entry of the rows is in the pattern (same size, each row's columns a subset).
    fn covers(&self, m: usize, row_ptr: &[usize], ent: &[(usize, f64)]) -> bool {
        if self.row_ptr.len() != m + 1 {
            return false;
        }
        (0..m).all(|u| {
            let cols = &self.row_col[self.row_ptr[u]..self.row_ptr[u + 1]];
            ent[row_ptr[u]..row_ptr[u + 1]].iter().all(|&(col, _)| col == m || cols.binary_search(&col).is_ok())
        })
    }
}

/// Unknowns from which the near-field factorisation runs beside its caller ([`NearLu::new_watched`]):
/// ≈ 0.3 s at 257² (66k unknowns), a thread start is noise beside it.
const WATCHED_LU_UNKNOWNS: usize = 60_000;

/// The numeric LU (faer's supernodal, partial pivoting) of a near-field matrix on its
/// [`NearPattern`].
struct NearLu {
    pattern: std::sync::Arc<NearPattern>,
    lu: SupernodalLu<usize, f64>,
    row_fwd: Vec<usize>,
    row_inv: Vec<usize>,
}

impl NearLu {
    /// Factorise the matrix with `values` on `pattern`'s CSC; `None` when it is singular.
    fn new(pattern: std::sync::Arc<NearPattern>, values: &[f64]) -> Option<Self> {
        let m = pattern.col_fwd.len();
        let a = SparseColMatRef::new(SymbolicSparseColMatRef::new_checked(m, m, &pattern.col_ptr, None, &pattern.row_idx), values);
        let at = a.transpose().to_col_major().ok()?;
        let (mut row_fwd, mut row_inv) = (vec![0usize; m], vec![0usize; m]);
        let mut lu = SupernodalLu::<usize, f64>::new();
        let perm = PermRef::new_checked(&pattern.col_fwd, &pattern.col_inv, m);
        let mut mem = MemBuffer::new(supernodal::factorize_supernodal_numeric_lu_scratch::<usize, f64>(&pattern.symbolic, Default::default()));
        supernodal::factorize_supernodal_numeric_lu(&mut row_fwd, &mut row_inv, &mut lu, a, at.as_ref(), perm, &pattern.symbolic, faer::get_global_parallelism(), MemStack::new(&mut mem), Default::default()).ok()?;
        Some(NearLu { pattern, lu, row_fwd, row_inv })
    }

    /// [`NearLu::new`], run beside the caller when the matrix is large ([`WATCHED_LU_UNKNOWNS`]
    /// or more unknowns: 3–3.5 s at 513², release): the caller polls `observer` every 50 ms and
    /// returns an interrupt at once, leaving the factorisation to finish (and be dropped) on its
    /// own thread, so a cancel, time limit or shutdown does not wait for it.
    fn new_watched(pattern: std::sync::Arc<NearPattern>, values: Vec<f64>, observer: &dyn Observer) -> Result<Option<Self>, SolveError> {
        if pattern.col_fwd.len() < WATCHED_LU_UNKNOWNS {
            return Ok(NearLu::new(pattern, &values));
        }
        let (tx, rx) = std::sync::mpsc::channel();
        let spawned = std::thread::Builder::new().name("ehl2d-lu".into()).spawn(move || {
            let _ = tx.send(NearLu::new(pattern, &values));
        });
        if spawned.is_err() {
            // No thread to be had (a process at its limit): no preconditioner this step.
            return Ok(None);
        }
        loop {
            match rx.recv_timeout(std::time::Duration::from_millis(50)) {
                Ok(lu) => return Ok(lu),
                Err(std::sync::mpsc::RecvTimeoutError::Timeout) => observer.check()?,
                Err(std::sync::mpsc::RecvTimeoutError::Disconnected) => return Ok(None),
            }
        }
    }

    /// `x ← B⁻¹ x`.
    fn solve_in_place(&self, x: &mut [f64]) {
        let m = self.row_fwd.len();
        let par = faer::get_global_parallelism();
        let rows = PermRef::new_checked(&self.row_fwd, &self.row_inv, m);
        let cols = PermRef::new_checked(&self.pattern.col_fwd, &self.pattern.col_inv, m);
        let mut mem = MemBuffer::new(supernodal::solve_in_place_scratch::<usize, f64>(m, 1, par));
        self.lu.solve_in_place_with_conj(rows, cols, faer::Conj::No, faer::MatMut::from_column_major_slice_mut(x, m, 1), par, MemStack::new(&mut mem));
    }
}

/// A nested-dissection ordering of the `mx × my` interior grid (unknown `j·mx + i`): the
/// rectangle is cut by a separator `wx` columns wide (a cut across x) or `wy` rows wide, whichever
/// is smaller, the halves ordered first (recursively), the separator last; blocks of at most 32
/// unknowns in natural order. The widths are the reach of the column-intersection graph of the
/// near-field matrix (`BᵀB`, whose Cholesky structure bounds the LU with partial pivoting):
/// a row's columns span `i − 2 − r … i + r` and `j − r … j + r` (upwind wedge and near field `r`),
/// so `wx = 2 + 2r`, `wy = 2r`. George, SIAM J. Numer. Anal. 10 (1973) for the method; against
/// colamd on the seed 000 roller's 63×127 unknowns (full pattern): numeric factorisation
/// 139 against 157 M instructions, triangular solve 6.25 against 6.5 M (`ehl2d-10`).
fn nested_dissection(mx: usize, my: usize, wx: usize, wy: usize) -> Vec<usize> {
    const LEAF: usize = 32;
    #[allow(clippy::too_many_arguments)]
    fn part(x0: usize, x1: usize, y0: usize, y1: usize, mx: usize, wx: usize, wy: usize, out: &mut Vec<usize>) {
        let (lx, ly) = (x1 - x0, y1 - y0);
        let (cut_x, cut_y) = (lx > 2 * wx + 2, ly > 2 * wy + 2);
        if lx * ly <= LEAF || !(cut_x || cut_y) {
            for j in y0..y1 {
                out.extend((x0..x1).map(|i| j * mx + i));
            }
            return;
        }
        if cut_x && (!cut_y || wx * ly <= wy * lx) {
            let c = x0 + (lx - wx) / 2;
            part(x0, c, y0, y1, mx, wx, wy, out);
            part(c + wx, x1, y0, y1, mx, wx, wy, out);
            for j in y0..y1 {
                out.extend((c..c + wx).map(|i| j * mx + i));
            }
        } else {
            let c = y0 + (ly - wy) / 2;
            part(x0, x1, y0, c, mx, wx, wy, out);
            part(x0, x1, c + wy, y1, mx, wx, wy, out);
            for j in c..c + wy {
                out.extend((x0..x1).map(|i| j * mx + i));
            }
        }
    }
    let mut out = Vec::with_capacity(mx * my);
    part(0, mx, 0, my, mx, wx, wy.max(1), &mut out);
    out
}

#[derive(Default)]
struct Buffers {
    dp: Vec<f64>,
    dw: Vec<f64>,
    dq: Vec<f64>,
    de: Vec<f64>,
    /// GMRES' work arrays.
    krylov: krylov::Workspace,
}

/// Restarted GMRES for `A x = b` right-preconditioned by `lu`, at most `max_its` iterations;
/// `x` starts at 0 (`from_x`: at its own value, when finite). Returns the iterations and the final
/// relative residual. The shared GMRES ([`krylov::gmres`]) in this solver's arithmetic: restarts
/// every [`RESTART`] iterations, zero rotations the identity, `|g|/‖b‖ ≤ tol` (also at a cycle's
/// start), the preconditioned directions kept (`x += Σ y_i M⁻¹v_i`).
#[allow(clippy::too_many_arguments)]
fn gmres(prob: &mut Problem, p: &[f64], v: &Fields, active: &[u8], c: &[f64], lu: &Precond, b: &[f64], x: &mut [f64], buf: &mut Buffers, tol: f64, max_its: usize, from_x: bool, observer: &dyn Observer) -> Result<(usize, f64), SolveError> {
    let lw = prob.load_weight();
    // A kept factor carries its own row scales `c_old`: `M⁻¹ = (C_old J_old)⁻¹ C_old C⁻¹` keeps
    // `C J M⁻¹ ≈ I` where the scales moved (rows inactive in both; others unscaled).
    let rescale: Vec<f64> = if lu.c.as_slice() == c && lu.active.as_slice() == active {
        Vec::new()
    } else {
        (0..c.len()).map(|u| if active[u] == FLUID && lu.active[u] == FLUID { lu.c[u] / c[u] } else { 1.0 }).collect()
    };
    let settings = krylov::Settings {
        restart: RESTART,
        max_iterations: max_its,
        tolerance: tol,
        from_x,
        rotation: krylov::Rotation::Sqrt,
        test: krylov::Test::Ratio,
        update: krylov::Update::Flexible,
    };
    let mut ws = std::mem::take(&mut buf.krylov);
    let out = krylov::gmres(&mut |z, y| prob.apply(p, v, active, c, z, y, buf), &mut |z| lu.apply(z, lw, &rescale), b, x, &settings, &mut ws, observer);
    buf.krylov = ws;
    let out = out?;
    Ok((out.iterations, out.residual))
}

/// `TRIBOD_EHL2D_TRACE` set: print each Newton step, the line search and (first step) a
/// finite-difference check of the Jacobian product to stderr (development aid).
fn trace() -> bool {
    std::env::var_os("TRIBOD_EHL2D_TRACE").is_some()
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

/// Damped semismooth Newton from `(p, h0)`, in place.
fn newton(prob: &mut Problem, p: &mut [f64], h0: &mut f64, tol: f64, max_iter: u32, observer: &dyn Observer) -> Result<Run, SolveError> {
    let m = prob.nodes.len();
    let mut v = Fields::default();
    let mut trial = Fields::default();
    let mut history = Vec::new();
    let mut gm_total = 0;
    if !prob.evaluate(p, *h0, &mut v) {
        return Ok(Run { iterations: 0, residual: f64::INFINITY, history, converged: false, gmres: 0 });
    }
    let mut active = vec![FLUID; m];
    let mut c = vec![0.0; m];
    let mut phi = Vec::with_capacity(m);
    let mut phi_t = Vec::with_capacity(m);
    let mut buf = Buffers::default();
    let cell = prob.dx * prob.dy;
    let mut rhs = vec![0.0; m + 1];
    let mut sol = vec![0.0; m + 1];
    let mut p_trial = p.to_vec();
    let mut dw = vec![0.0; p.len()];
    let mut dpn = vec![0.0; p.len()];
    // Factorise afresh at the next step (the kept factor needed too many GMRES iterations or its
    // step failed the line search).
    let mut refresh = false;
    // The last step's right-hand side norm and forcing term ([`Forcing`]).
    let mut last_forcing: Option<(f64, f64)> = None;
    for iter in 0..=max_iter {
        observer.check()?;
        // Row scales and active set first: the residual needs them, the factorisation only an
        // unconverged step (the last, converged evaluation of every solve factorised for nothing:
        // ≈ 1 of 5 factorisations of a warm solve in the cam cycle, `ehl2d-6`).
        prob.precondition(p, &v, &mut active, &mut c, false, observer)?;
        prob.phi(p, &v, &c, &mut phi);
        let res = residual_norm(p, &phi, v.g);
        history.push(res);
        if res <= tol {
            return Ok(Run { iterations: iter, residual: res, history, converged: true, gmres: gm_total });
        }
        if iter == max_iter {
            return Ok(Run { iterations: iter, residual: res, history, converged: false, gmres: gm_total });
        }
        for (u, &k) in prob.nodes.iter().enumerate() {
            rhs[u] = match active[u] {
                CAVITATED => -p[k],
                CONTACT => -prob.contact_scale() * (v.hraw[k] - prob.floor),
                _ => -c[u] * v.f[k],
            };
        }
        rhs[m] = -v.g;
        // Forcing term: 1e-3, tighter near the solution (the inexact step stalled the line
        // search at residuals ≈ 6e-7, measured on the circular Barus case at 97²); a warm-started
        // solve's: `Problem::forcing` ([`WARM_FORCING`]).
        let bn = dot(&rhs, &rhs).sqrt();
        let gtol = match prob.forcing {
            None => GMRES_TOL.min(0.1 * res.sqrt()).max(1e-10),
            Some(fp) => {
                let eta = fp.eta(last_forcing, bn, res, tol);
                last_forcing = Some((bn, eta));
                eta
            }
        };
        // The linear solve: GMRES with the kept preconditioner (an older Jacobian's near field on
        // this grid, scaled and with the active set of its own step; the operator applied is
        // always the current one, so only the iteration count depends on it) for at most
        // `REUSE_MAX` iterations; else, or when there is none, the current near field factorised
        // afresh (chord-preconditioned Newton–Krylov, as the 1-D solver, `super::super::newton`).
        let (mut t_lu, mut t_gm) = (0.0, 0.0);
        let (mut its, mut rel);
        let mut fresh = false;
        let (reuse_max, reuse_refresh, _) = reuse_policy();
        let mut from_x = false;
        loop {
            let kept = prob.kept.clone().filter(|k| !refresh && k.bu.len() == m);
            let pc = match kept {
                Some(pc) => pc,
                None => {
                    observer.check()?;
                    let t = std::time::Instant::now();
                    let lu = prob.precondition(p, &v, &mut active, &mut c, true, observer)?;
                    t_lu += t.elapsed().as_secs_f64();
                    let Some(lu) = lu else {
                        return Ok(Run { iterations: iter, residual: res, history, converged: false, gmres: gm_total });
                    };
                    prob.factorisations += 1;
                    crate::film::work::add(&crate::film::work::FINITE_FACTORISATIONS, 1);
                    fresh = true;
                    refresh = false;
                    let pc = std::sync::Arc::new(lu);
                    prob.kept = Some(pc.clone());
                    pc
                }
            };
            let t = std::time::Instant::now();
            (its, rel) = gmres(prob, p, &v, &active, &c, &pc, &rhs, &mut sol, &mut buf, gtol, if fresh { GMRES_MAX } else { reuse_max }, from_x, observer)?;
            t_gm += t.elapsed().as_secs_f64();
            gm_total += its;
            crate::film::work::add(&crate::film::work::FINITE_GMRES_ITERATIONS, its as u64);
            if fresh || rel <= gtol {
                break;
            }
            // The fresh factor's GMRES goes on from the kept one's iterate.
            refresh = true;
            from_x = true;
        }
        // Active (cavitated) rows are the identity: their exact step is `δP = −P`. GMRES meets it
        // only to its tolerance — closely with a fresh factor (its own identity rows), loosely
        // with a kept one factorised at another active set — and a cavitated node left at
        // `P ≈ ±1e-12` instead of 0 would count as a loaded traction node. So set it exactly.
        for (u, &k) in prob.nodes.iter().enumerate() {
            if active[u] == CAVITATED {
                sol[u] = -p[k];
            }
        }
        // A kept factor that needed many iterations is replaced at the next step.
        if !fresh && its > reuse_refresh {
            refresh = true;
        }
        if trace() {
            eprintln!("ehl2d {}x{} κ {:.3e} iter {iter} res {res:.3e} g {:.2e} gtol {gtol:.1e} gmres {its} rel {rel:.2e} fresh {fresh} active {} contact {} lu {t_lu:.3} s gmres {t_gm:.3} s", prob.nx, prob.ny, prob.kappa, v.g, active.iter().filter(|a| **a == CAVITATED).count(), active.iter().filter(|a| **a == CONTACT).count());
            if iter == 0 {
                let (u, _) = phi.iter().enumerate().fold((0, 0.0f64), |b, (u, v)| if v.abs() > b.1 { (u, v.abs()) } else { b });
                let k = prob.nodes[u];
                eprintln!("ehl2d worst node i {} j {} X {:.3} Y {:.3} P {:.3e} phi {:.3e} active {}", k % prob.nx, k / prob.nx, prob.x[k % prob.nx], prob.y[k / prob.nx], p[k], phi[u], active[u]);
                // Directional-derivative check of the Jacobian product.
                let mut x: Vec<f64> = (0..m + 1).map(|u| (((u * 7919) % 13) as f64 - 6.0) * 1e-3).collect();
                for (u, &k) in prob.nodes.iter().enumerate() {
                    if p[k] <= 0.0 { x[u] = 0.0; }
                }
                let mut jx = vec![0.0; m + 1];
                let mut inactive = active.clone();
                inactive.iter_mut().for_each(|a| *a = FLUID);
                prob.apply(p, &v, &inactive, &c, &x, &mut jx, &mut buf);
                let t = 1e-4;
                let mut pt = p.to_vec();
                for (u, &k) in prob.nodes.iter().enumerate() { pt[k] += t * x[u]; }
                let mut vt = Fields::default();
                if prob.evaluate(&pt, *h0 + t * x[m], &mut vt) {
                    let mut num = 0.0; let mut den = 0.0;
                    for (u, &k) in prob.nodes.iter().enumerate() {
                        let fd = c[u] * (vt.f[k] - v.f[k]) / t;
                        num += (fd - jx[u]).powi(2); den += fd * fd;
                    }
                    eprintln!("ehl2d jacobian check: rel diff {:.3e}", (num / den.max(1e-300)).sqrt());
                }
            }
        }
        if !sol.iter().all(|s| s.is_finite()) {
            return Ok(Run { iterations: iter + 1, residual: res, history, converged: false, gmres: gm_total });
        }
        dpn.iter_mut().for_each(|d| *d = 0.0);
        for (u, &k) in prob.nodes.iter().enumerate() {
            dpn[k] = sol[u];
        }
        let dh0 = sol[m];
        let mut alpha = film_damping(prob, &v, &dpn, dh0, &mut dw);
        if trace() {
            eprintln!("   film damping alpha {alpha:.3e}");
        }
        let m0 = dot(&phi, &phi) * cell + v.g * v.g;
        let mut accepted = false;
        for _ in 0..MAX_HALVINGS {
            observer.check()?;
            for k in 0..p.len() {
                p_trial[k] = p[k] + alpha * dpn[k];
            }
            let h0_trial = *h0 + alpha * dh0;
            if prob.evaluate(&p_trial, h0_trial, &mut trial) {
                prob.phi(&p_trial, &trial, &c, &mut phi_t);
                let mt = dot(&phi_t, &phi_t) * cell + trial.g * trial.g;
                if mt <= (1.0 - 1e-4 * alpha) * m0 {
                    p.copy_from_slice(&p_trial);
                    *h0 = h0_trial;
                    std::mem::swap(&mut v, &mut trial);
                    accepted = true;
                    break;
                }
            }
            alpha *= 0.5;
        }
        if trace() {
            eprintln!("   accepted {accepted} alpha {alpha:.3e}");
        }
        if !accepted {
            // A step solved with a kept factor: once more with a fresh one (the next iteration
            // starts from the same iterate).
            if !fresh {
                refresh = true;
                continue;
            }
            return Ok(Run { iterations: iter + 1, residual: res, history, converged: false, gmres: gm_total });
        }
    }
    unreachable!("the loop returns at iter == max_iter")
}

/// First trial length of a Newton step: the fraction-to-boundary rule on the film (no node's film
/// shrinks below `1 − FTB` of itself), unless it would cut the step below `FTB_MIN`: then the full
/// step, the film passing below the floor ([`FILM_FLOOR`]) where the discrete problem wants it
/// non-positive, and the line search's merit function decides. The rule alone stalled Newton
/// there (the limiting film shrank 5× per step and the step with it, issue 16).
fn film_damping(prob: &mut Problem, v: &Fields, dpn: &[f64], dh0: f64, dw: &mut [f64]) -> f64 {
    prob.defl.apply(dpn, dw);
    let mut alpha: f64 = 1.0;
    for (k, d) in dw.iter().enumerate() {
        let d = dh0 + d;
        if d < 0.0 && v.on[k] > 0.0 && FTB * v.h[k] / -d < alpha {
            alpha = FTB * v.h[k] / -d;
        }
    }
    if alpha < FTB_MIN {
        1.0
    } else {
        alpha
    }
}

/// Newton from `(p, h0)`; when it fails, pseudo-time continuation ([`march`]) from the same start.
#[allow(clippy::too_many_arguments)]
fn newton_or_march(prob: &mut Problem, p: &mut [f64], h0: &mut f64, tol: f64, cap: u32, max_iter: u32, dt0: f64, observer: &dyn Observer) -> Result<Run, SolveError> {
    let (p_start, h0_start) = (p.to_vec(), *h0);
    let first = newton(prob, p, h0, tol, cap, observer)?;
    if first.converged {
        return Ok(first);
    }
    p.copy_from_slice(&p_start);
    *h0 = h0_start;
    let mut r = march(prob, p, h0, tol, max_iter, dt0, observer)?;
    r.iterations += first.iterations;
    r.gmres += first.gmres;
    Ok(r)
}

/// One grid's problem (geometric face means, [`face_of`]) through the arithmetic-mean one: Newton
/// on the geometric-mean problem from a cold Hertzian start stalls (measured on 49² and 97² of the
/// circular M ≈ 300 contact: 40 steps at a residual ≈ 0.4, the pseudo-time fallback then takes
/// hundreds of steps). So the arithmetic-mean problem is solved first, then the weight `θ` of the
/// geometric mean is raised to 1 in steps (halved when Newton fails, doubled when it succeeds;
/// pseudo-time continuation at `θ = 1` when the step falls below 1/16). `direct`: first try
/// `θ = 1` from the start itself (a start that is already close).
#[allow(clippy::too_many_arguments)]
fn solve_level(prob: &mut Problem, p: &mut [f64], h0: &mut f64, tol: f64, cap: u32, max_iter: u32, dt0: f64, direct: bool, observer: &dyn Observer) -> Result<Run, SolveError> {
    let (mut its, mut gm) = (0, 0);
    let mut ps = p.to_vec();
    let mut hs = *h0;
    if direct {
        prob.theta = 1.0;
        let r = newton(prob, p, h0, tol, cap, observer)?;
        if r.converged {
            return Ok(r);
        }
        its += r.iterations;
        gm += r.gmres;
        p.copy_from_slice(&ps);
        *h0 = hs;
    }
    prob.theta = 0.0;
    let a = newton_or_march(prob, p, h0, tol, cap, max_iter, dt0, observer)?;
    its += a.iterations;
    gm += a.gmres;
    if !a.converged {
        prob.theta = 1.0;
        return Ok(Run { iterations: its, gmres: gm, ..a });
    }
    let (mut theta, mut step) = (0.0f64, 0.5f64);
    loop {
        let t = (theta + step).min(1.0);
        prob.theta = t;
        ps.copy_from_slice(p);
        hs = *h0;
        let r = newton(prob, p, h0, tol, NESTED_ITER.min(max_iter), observer)?;
        its += r.iterations;
        gm += r.gmres;
        if r.converged {
            theta = t;
            if theta >= 1.0 {
                return Ok(Run { iterations: its, gmres: gm, ..r });
            }
            step *= 2.0;
            continue;
        }
        p.copy_from_slice(&ps);
        *h0 = hs;
        // Half the increment that failed (`step` was doubled after the last success, and capped
        // at θ = 1: halving it alone could retry the same θ from the same start).
        step = 0.5 * (t - theta);
        if step < 1.0 / 16.0 {
            prob.theta = 1.0;
            let mut r = newton_or_march(prob, p, h0, tol, NESTED_ITER.min(max_iter), max_iter, DT_NESTED, observer)?;
            r.iterations += its;
            r.gmres += gm;
            return Ok(r);
        }
    }
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

/// Pseudo-transient continuation (Kelley & Keyes, SIAM J. Numer. Anal. 35 (1998)) with the
/// physical squeeze term: backward-Euler steps of the transient Reynolds equation (seed 000
/// eq. 2 with `∂(ρh)/∂t`) at fixed load, each solved by [`newton`] from the last state; `ΔT`
/// doubles (quadruples after a quick step) on success and is quartered on failure; from
/// `ΔT ≥ DT_STEADY` each step first tries the problem itself (`κ = 0`, or a transient step's own
/// squeeze term, [`Problem::pseudo_step`]) and returns when it converges. The squeeze term damps
/// the changes of `ρ̄H` that stall the steady Newton iteration from a Hertzian start (see
/// `BENCHMARKS.md`, issue 16).
fn march(prob: &mut Problem, p: &mut [f64], h0: &mut f64, tol: f64, max_iter: u32, dt0: f64, observer: &dyn Observer) -> Result<Run, SolveError> {
    let mut dt = dt0;
    let (mut its, mut gm) = (0u32, 0usize);
    let mut last = Run { iterations: 0, residual: f64::INFINITY, history: Vec::new(), converged: false, gmres: 0 };
    let mut saved = p.to_vec();
    let mut v = Fields::default();
    for step in 0..MAX_STEPS {
        if dt >= DT_STEADY {
            saved.copy_from_slice(p);
            let h0_saved = *h0;
            prob.restore_target();
            let r = newton(prob, p, h0, tol, max_iter.min(NESTED_ITER), observer)?;
            its += r.iterations;
            gm += r.gmres;
            if trace() {
                eprintln!("ehl2d march {}x{} step {step} steady try: converged {} res {:.3e} in {}", prob.nx, prob.ny, r.converged, r.residual, r.iterations);
            }
            if r.converged {
                return Ok(Run { iterations: its, gmres: gm, ..r });
            }
            p.copy_from_slice(&saved);
            *h0 = h0_saved;
            last = r;
            if dt >= DT_MAX {
                break;
            }
        }
        if !prob.evaluate(p, *h0, &mut v) {
            break;
        }
        prob.pseudo_step(dt, &v);
        saved.copy_from_slice(p);
        let h0_saved = *h0;
        let r = newton(prob, p, h0, tol.max(STEP_TOL), STEP_ITER, observer)?;
        prob.restore_target();
        its += r.iterations;
        gm += r.gmres;
        if trace() {
            eprintln!("ehl2d march {}x{} step {step} dT {dt:.3e}: converged {} res {:.3e} in {} (H0 {:.4e})", prob.nx, prob.ny, r.converged, r.residual, r.iterations, *h0);
        }
        if r.converged {
            dt *= if r.iterations <= 3 { 4.0 } else { 2.0 };
            dt = dt.min(DT_MAX);
        } else {
            p.copy_from_slice(&saved);
            *h0 = h0_saved;
            last = r;
            dt *= 0.25;
            if dt < DT_MIN {
                break;
            }
        }
    }
    prob.restore_target();
    Ok(Run { iterations: its, residual: last.residual, history: last.history, converged: false, gmres: gm })
}

pub(super) fn validate(input: &Ehl2dInput, options: &Ehl2dOptions) -> Result<(), SolveError> {
    let pos = |v: f64, path: &str| if v.is_finite() && v > 0.0 { Ok(()) } else { Err(SolveError::invalid(path, "must be a finite number > 0")) };
    pos(input.load, "Ehl2dInput.load")?;
    pos(input.effective_modulus, "Ehl2dInput.effective_modulus")?;
    pos(input.temperature, "Ehl2dInput.temperature")?;
    pos(input.entrainment_velocity.abs(), "Ehl2dInput.entrainment_velocity")?;
    pos(input.lubricant.viscosity, "Ehl2dInput.lubricant.viscosity")?;
    if !(input.lubricant.pressure_viscosity.is_finite() && input.lubricant.pressure_viscosity >= 0.0) {
        return Err(SolveError::invalid("Ehl2dInput.lubricant.pressure_viscosity", "must be finite and ≥ 0"));
    }
    match input.geometry {
        Geometry2d::Point { rx, ry } => {
            pos(rx, "Ehl2dInput.geometry.rx")?;
            pos(ry, "Ehl2dInput.geometry.ry")?;
            if !(0.02..=50.0).contains(&(rx / ry)) {
                return Err(SolveError::invalid("Ehl2dInput.geometry", "R_x/R_y must be within 0.02–50"));
            }
        }
        Geometry2d::Finite { rx, crown } => {
            pos(rx, "Ehl2dInput.geometry.rx")?;
            pos(crown.length, "Ehl2dInput.geometry.crown.length")?;
            pos(crown.end_radius, "Ehl2dInput.geometry.crown.end_radius")?;
            if !(crown.middle_length > 0.0 && crown.middle_length <= crown.length) {
                return Err(SolveError::invalid("Ehl2dInput.geometry.crown.middle_length", "must be in (0, length]"));
            }
            if !(crown.crown_height.is_finite() && crown.crown_height >= 0.0) {
                return Err(SolveError::invalid("Ehl2dInput.geometry.crown.crown_height", "must be finite and ≥ 0"));
            }
        }
    }
    for (n, path) in [(options.nx, "Ehl2dOptions.nx"), (options.ny, "Ehl2dOptions.ny")] {
        if !(9..=1025).contains(&n) {
            return Err(SolveError::invalid(path, "must be within 9–1025"));
        }
    }
    if !(options.tolerance.is_finite() && options.tolerance > 0.0) {
        return Err(SolveError::invalid("Ehl2dOptions.tolerance", "must be finite and > 0"));
    }
    if options.max_iterations == 0 {
        return Err(SolveError::invalid("Ehl2dOptions.max_iterations", "must be ≥ 1"));
    }
    if !(options.grid_tolerance.is_finite() && options.grid_tolerance > 0.0) {
        return Err(SolveError::invalid("Ehl2dOptions.grid_tolerance", "must be finite and > 0"));
    }
    if !(1..=3).contains(&options.near_field) {
        return Err(SolveError::invalid("Ehl2dOptions.near_field", "must be within 1–3"));
    }
    for (v, path) in [(options.inlet, "Ehl2dOptions.inlet"), (options.outlet, "Ehl2dOptions.outlet"), (options.side, "Ehl2dOptions.side")] {
        if let Some(v) = v {
            if !(v.is_finite() && v >= 0.5 && v <= 100.0) {
                return Err(SolveError::invalid(path, "must be within 0.5–100 (units of the Hertzian semi-axis)"));
            }
        }
    }
    Ok(())
}

/// `H0` that puts the centre film at `target` and keeps the film positive.
fn h0_for(prob: &mut Problem, p: &[f64], target: f64) -> f64 {
    let mut w = vec![0.0; p.len()];
    prob.defl.apply(p, &mut w);
    let rigid: Vec<f64> = (0..p.len()).map(|k| prob.geom[k] + w[k]).collect();
    let min_rigid = rigid.iter().cloned().fold(f64::INFINITY, f64::min);
    let at_centre = bilinear(&prob.x, &prob.y, &rigid, 0.0, 0.0);
    (target - at_centre).max(0.05 * target - min_rigid)
}

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

/// Cold start: the Hertzian (point) or slice-shaped (roller) pressure scaled to the load.
fn cold(prob: &mut Problem, input: &Ehl2dInput, s: &Scales) -> (Vec<f64>, f64) {
    let (nx, ny) = (prob.nx, prob.ny);
    let mut p = vec![0.0; nx * ny];
    // Light loads spread the pressure over ~sqrt(2H) (as the 1-D cold start).
    let wide = 1f64.max((2.0 * s.h_est).sqrt());
    for &k in &prob.nodes {
        let (x, y) = (prob.x[k % nx] / wide, prob.y[k / nx]);
        p[k] = match input.geometry {
            Geometry2d::Point { .. } => (1.0 - x * x - (y / (s.ky * wide)).powi(2)).max(0.0).sqrt(),
            Geometry2d::Finite { .. } => (1.0 - x * x).max(0.0).sqrt() * slice_load(input, s, y),
        };
    }
    let sum: f64 = p.iter().sum::<f64>() * prob.dx * prob.dy;
    if sum > 0.0 {
        p.iter_mut().for_each(|v| *v *= prob.load / sum);
    }
    let h0 = h0_for(prob, &p, s.h_est);
    (p, h0)
}

/// The slice model's load per length at `Y` relative to the centre's (`physics::roller::Crown::
/// distribute`: each slice carries `∝ (δ − g(y))₊`, the approach `δ` being the gap at the loaded
/// zone's edge): `1 − S(Y)/S(Y_loaded)`, uniform along a straight roller (the parabola
/// `1 − (Y/Y_loaded)²` of the crowned middle before, which loaded a straight roller's centre 1.5×
/// and left its ends unloaded: its films there started far below zero, issue 16).
/// Seed 000 eq. 3 as printed (a relieved centre, loaded zones at the transitions, not an interval
/// around the centre) takes `δ` from the slice model directly.
fn slice_load(input: &Ehl2dInput, s: &Scales, y: f64) -> f64 {
    let printed = matches!(input.geometry, Geometry2d::Finite { crown, .. } if crown.loads_the_transitions());
    let delta = if printed { s.approach } else { side_gap(input, s, s.loaded.min(s.ky)) };
    let g = side_gap(input, s, y);
    if delta > 0.0 {
        (1.0 - g / delta).max(0.0)
    } else if g <= 0.0 {
        1.0
    } else {
        0.0
    }
}

/// The pressure of a coarser grid interpolated onto `prob`'s nodes, scaled to the load.
fn prolong(prob: &Problem, cx: &[f64], cy: &[f64], cp: &[f64]) -> Vec<f64> {
    let (nx, ny) = (prob.nx, prob.ny);
    let mut p = vec![0.0; nx * ny];
    for &k in &prob.nodes {
        p[k] = bilinear(cx, cy, cp, prob.x[k % nx], prob.y[k / nx]);
    }
    let sum: f64 = p.iter().sum::<f64>() * prob.dx * prob.dy;
    if sum > 0.0 {
        p.iter_mut().for_each(|v| *v *= prob.load / sum);
    }
    p
}

/// A warm start's pressure on `prob`'s nodes (interpolated along a roller by the physical axial
/// position, elsewhere by `x/a`, `y/a`), scaled to the load; `None` when it carries no load.
fn carried(prob: &Problem, s: &Scales, w: &Warm2d) -> Option<Vec<f64>> {
    let mut p = vec![0.0; prob.nx * prob.ny];
    let axial = if w.finite { s.a / w.a } else { 1.0 };
    for &k in &prob.nodes {
        p[k] = bilinear(&w.x, &w.y, &w.pressure, prob.x[k % prob.nx], prob.y[k / prob.nx] * axial).max(0.0);
    }
    let sum: f64 = p.iter().sum::<f64>() * prob.dx * prob.dy;
    (sum > 0.0).then(|| {
        p.iter_mut().for_each(|v| *v *= prob.load / sum);
        p
    })
}

/// Merit `Σ φ² ΔXΔY + G²` of the Newton iteration ([`newton`]'s line search) at `(p, h0)`.
fn merit_at(prob: &mut Problem, p: &[f64], h0: f64) -> f64 {
    let mut v = Fields::default();
    if !prob.evaluate(p, h0, &mut v) {
        return f64::INFINITY;
    }
    let m = prob.nodes.len();
    let (mut active, mut c, mut phi) = (vec![FLUID; m], vec![0.0; m], Vec::with_capacity(m));
    // Without a factorisation nothing can be interrupted.
    let _ = prob.precondition(p, &v, &mut active, &mut c, false, &crate::Silent);
    prob.phi(p, &v, &c, &mut phi);
    dot(&phi, &phi) * prob.dx * prob.dy + v.g * v.g
}

/// Extrapolation ratios tried by [`warm_start`] besides 0 (the warm start alone); development
/// aid: `TRIBOD_EHL2D_EXTRAP=r1,r2,…` overrides them (empty: none).
fn extrapolation_ratios() -> &'static [f64] {
    static R: std::sync::OnceLock<Vec<f64>> = std::sync::OnceLock::new();
    R.get_or_init(|| match std::env::var("TRIBOD_EHL2D_EXTRAP") {
        Ok(v) => v.split(',').filter_map(|x| x.trim().parse().ok()).collect(),
        Err(_) => EXTRAPOLATION.to_vec(),
    })
}

/// Ratios of the secant extrapolation along a chain of neighbouring problems ([`warm_start`]).
const EXTRAPOLATION: [f64; 1] = [1.0];

/// The start of a warm solve: the warm start's pressure ([`carried`]) with `H0` putting the
/// central film at the warm start's central film times the change of the closed-form estimate;
/// with `prior` (the problem `w` itself was started from, e.g. the angle before the previous
/// one) also the secant extrapolation `P_w + r (P_w − P_prior)` (clipped at 0, scaled to the
/// load; the central film's ratio to the estimate extrapolated alike) for the ratios
/// [`extrapolation_ratios`] — along a cam cycle's uniform angle steps the previous step
/// repeated is `r = 1`. The candidate with the smallest Newton merit ([`merit_at`]) is taken.
fn warm_start(prob: &mut Problem, s: &Scales, w: &Warm2d, prior: Option<&Warm2d>) -> Option<(Vec<f64>, f64)> {
    let p1 = carried(prob, s, w)?;
    let q1 = w.central / w.h_est;
    let h1 = h0_for(prob, &p1, q1 * s.h_est);
    let ratios = extrapolation_ratios();
    let Some(p0) = prior.filter(|_| !ratios.is_empty()).and_then(|w0| carried(prob, s, w0).map(|p| (p, w0.central / w0.h_est))) else {
        return Some((p1, h1));
    };
    let (p0, q0) = p0;
    let mut best = (merit_at(prob, &p1, h1), p1.clone(), h1, 0.0);
    let m1 = best.0;
    for &r in ratios {
        let mut p: Vec<f64> = p1.iter().zip(&p0).map(|(a, b)| (a + r * (a - b)).max(0.0)).collect();
        let sum: f64 = p.iter().sum::<f64>() * prob.dx * prob.dy;
        let q = q1 + r * (q1 - q0);
        if !(sum > 0.0 && q > 0.0) {
            continue;
        }
        p.iter_mut().for_each(|v| *v *= prob.load / sum);
        let h0 = h0_for(prob, &p, q * s.h_est);
        let mr = merit_at(prob, &p, h0);
        if mr < best.0 {
            best = (mr, p, h0, r);
        }
    }
    if trace() {
        eprintln!("ehl2d warm start: merit {m1:.3e} carried, {:.3e} extrapolated r {}", best.0, best.3);
    }
    Some((best.1, best.2))
}

/// Solve one 2-D EHL problem. Polls `observer` once per Newton step.
pub fn solve(input: &Ehl2dInput, options: &Ehl2dOptions, observer: &dyn Observer) -> Result<Ehl2dSolution, SolveError> {
    solve_from(input, options, None, observer).map(|(s, _)| s)
}

/// The Newton preconditioner (near-field LU) of the last solve on a grid, kept for the next
/// solve on the same grid (a cam cycle's next angle, [`solve_kept`]): an older Jacobian's factor
/// only changes how many GMRES iterations a Newton step takes, not what it converges to (the
/// operator applied is always the current one), so the solution moves only within the Newton
/// tolerance. Opaque; empty by default.
#[derive(Clone, Default)]
pub struct Kept2d {
    pc: Option<std::sync::Arc<Precond>>,
    /// The grid's sparsity pattern and symbolic LU (the same for every solve on the grid).
    pattern: Option<std::sync::Arc<NearPattern>>,
    nx: usize,
    ny: usize,
}

impl Kept2d {
    /// The factor when it was computed on an `nx × ny` grid.
    fn take_for(&mut self, nx: usize, ny: usize) -> Option<std::sync::Arc<Precond>> {
        let pc = self.pc.take();
        pc.filter(|_| self.nx == nx && self.ny == ny)
    }

    /// The symbolic pattern when it was computed on an `nx × ny` grid.
    fn pattern_for(&self, nx: usize, ny: usize) -> Option<std::sync::Arc<NearPattern>> {
        self.pattern.clone().filter(|_| self.nx == nx && self.ny == ny)
    }
}

impl std::fmt::Debug for Kept2d {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "Kept2d({}×{}, {})", self.nx, self.ny, if self.pc.is_some() { "factor" } else { "empty" })
    }
}

/// [`solve_from`] with `kept`'s preconditioner (when it is for this grid) used for the finest
/// grid's Newton steps until GMRES needs a fresh one; `kept` then holds the last factor of this
/// solve's finest grid. `prior`: the warm start `warm` was itself solved from (the point before
/// the previous one along a chain); the start is then the better, by the Newton merit, of `warm`
/// and the secant extrapolation through both (`warm_start`).
pub fn solve_kept(input: &Ehl2dInput, options: &Ehl2dOptions, warm: Option<&Warm2d>, prior: Option<&Warm2d>, kept: &mut Kept2d, observer: &dyn Observer) -> Result<(Ehl2dSolution, Warm2d), SolveError> {
    solve_inner(input, options, warm, prior, kept, observer)
}

/// Solve one 2-D EHL problem starting from `warm` (a neighbouring problem's converged solution,
/// e.g. the previous cam angle's) when given: its dimensionless pressure is interpolated onto this
/// problem's grid in the new Hertzian scales (along a roller by the physical axial position, the
/// crown being fixed in space; elsewhere by `x/a`, `y/a`) and scaled to the load, and `H0` is set
/// so that the central film is the warm start's central film times the change of the closed-form
/// estimate. Newton then runs on the finest grid directly (geometric face means; the continuation
/// from the arithmetic means when that fails); when the warm start fails altogether the cold nested
/// iteration runs. Returns the solution and its own warm start for the next problem. The
/// resolution check runs as in [`solve`] (with a warm start: always a check solve on the grid with
/// half the intervals, unless `options.grid_check` is off).
pub fn solve_from(input: &Ehl2dInput, options: &Ehl2dOptions, warm: Option<&Warm2d>, observer: &dyn Observer) -> Result<(Ehl2dSolution, Warm2d), SolveError> {
    solve_inner(input, options, warm, None, &mut Kept2d::default(), observer)
}

fn solve_inner(input: &Ehl2dInput, options: &Ehl2dOptions, warm: Option<&Warm2d>, prior: Option<&Warm2d>, kept: &mut Kept2d, observer: &dyn Observer) -> Result<(Ehl2dSolution, Warm2d), SolveError> {
    validate(input, options)?;
    let mut kept_pc = kept.take_for(options.nx, options.ny);
    let kept_pattern = kept.pattern_for(options.nx, options.ny);
    let s = scales(input)?;
    let d = domain(input, options, &s);
    let finite = matches!(input.geometry, Geometry2d::Finite { .. });
    let mut warm_run = None;
    let mut failed_steps = 0;
    if let Some(w) = warm.filter(|w| w.finite == finite && w.central > 0.0 && w.h_est > 0.0) {
        let mut prob = Problem::new(input, &s, d, options.nx, options.ny, options.near_field);
        prob.kept = kept_pc.take();
        prob.pattern = std::cell::RefCell::new(kept_pattern.clone());
        prob.forcing = warm_forcing();
        if let Some((mut p, mut h0)) = warm_start(&mut prob, &s, w, prior.filter(|w0| w0.finite == finite && w0.central > 0.0 && w0.h_est > 0.0)) {
            let run = solve_level(&mut prob, &mut p, &mut h0, options.tolerance, options.max_iterations.min(NESTED_ITER), options.max_iterations, DT_NESTED, true, observer)?;
            if run.converged {
                warm_run = Some((prob, p, h0, run.iterations, run.residual));
            } else {
                failed_steps = run.iterations;
            }
        }
    }
    let solved = match warm_run {
        Some((prob, p, h0, iterations, residual)) => Solved { prob, p, h0, iterations, residual, coarse: None, warm_used: true },
        None => {
            let (prob, p, h0, its, residual, coarse) = solve_levels(input, options, &s, d, observer)?;
            Solved { prob, p, h0, iterations: its + failed_steps, residual, coarse, warm_used: false }
        }
    };
    conclude(input, options, &s, d, solved, kept, kept_pattern, observer)
}

/// A converged problem on the finest grid: its pressure, `H0`, the Newton steps and the final
/// residual, the previous level's films ([`solve_levels`]) and whether a warm start was used.
struct Solved {
    prob: Problem,
    p: Vec<f64>,
    h0: f64,
    iterations: u32,
    residual: f64,
    coarse: Option<(f64, f64, usize, usize)>,
    warm_used: bool,
}

/// The solution and warm start of a converged problem, after the resolution check (the pinch
/// and, unless the nested iteration measured it or `options.grid_check` is off after a warm
/// start, the check solve on the grid with half the intervals — of the same problem, a transient
/// step's squeeze term included); `kept` takes the problem's preconditioner.
#[allow(clippy::too_many_arguments)]
fn conclude(input: &Ehl2dInput, options: &Ehl2dOptions, s: &Scales, d: Domain, solved: Solved, kept: &mut Kept2d, kept_pattern: Option<std::sync::Arc<NearPattern>>, observer: &dyn Observer) -> Result<(Ehl2dSolution, Warm2d), SolveError> {
    let Solved { mut prob, p, h0, iterations: total, residual, coarse, warm_used } = solved;
    let finite = matches!(input.geometry, Geometry2d::Finite { .. });
    let pattern = prob.pattern.borrow().clone().or(kept_pattern);
    *kept = Kept2d { pc: prob.kept.take().filter(|_| reuse_policy().2), pattern, nx: prob.nx, ny: prob.ny };
    let mut sol = finish(input, options, s, &mut prob, &p, h0, total, residual)?;
    sol.warm_started = warm_used;
    let next = {
        let mut v = Fields::default();
        let film_scale = s.a * s.a / s.rx;
        let (hc, mass) = if prob.evaluate(&p, h0, &mut v) {
            (bilinear(&prob.x, &prob.y, &v.h, 0.0, 0.0), v.rho.iter().zip(&v.h).map(|(r, h)| r * h * film_scale).collect())
        } else {
            (sol.central_film / film_scale, Vec::new())
        };
        Warm2d { x: prob.x.clone(), y: prob.y.clone(), pressure: p.clone(), a: s.a, central: hc, h_est: s.h_est, finite, mass, sign: frame_sign(input) }
    };
    let unresolved = |what: String| SolveError::invalid("Ehl2dOptions.nx", format!("the {}×{} grid does not resolve the film: {what}; refine the grid (nx, ny)", prob.nx, prob.ny));
    // A film pinched at a node is the discrete problem's, not the contact's (seed-free check:
    // smooth EHL films keep h_min/h_c ≳ 0.3).
    if sol.min_film.value < PINCH * sol.central_film {
        return Err(unresolved(format!("the film pinches to {:.1} % of the central film at x = {:.3e} m, y = {:.3e} m", 100.0 * sol.min_film.value / sol.central_film, sol.min_film.x, sol.min_film.y)));
    }
    let coarse = match coarse {
        Some(c) => Some(c),
        None if options.grid_check || !warm_used => check_half(s, d, input, options, &p, h0, prob.target.as_ref(), observer)?,
        None => None,
    };
    if let Some((hc, hm, cnx, cny)) = coarse {
        let film_scale = s.a * s.a / s.rx;
        let (dc, dm) = ((hc * film_scale / sol.central_film - 1.0).abs(), (hm * film_scale / sol.min_film.value - 1.0).abs());
        // The minimum film sits in the exit constriction, a few cells wide on a coarse grid: its
        // change is allowed three times the tolerance (measured on the circular M ≈ 300 contact:
        // 33² → 65² moves h_min by 9.7 % while 65² is within 0.4 % of 257²).
        sol.grid_error = Some(dc);
        if dc > options.grid_tolerance || dm > 3.0 * options.grid_tolerance {
            return Err(unresolved(format!(
                "the central film changes by {:.1} % and the minimum film by {:.1} % from the {cnx}×{cny} grid (grid tolerance {:.1} %, three times that for the minimum film)",
                100.0 * dc,
                100.0 * dm,
                100.0 * options.grid_tolerance
            )));
        }
    }
    Ok((sol, next))
}

/// The solver frame's orientation: `+1` when `u_m ≥ 0`, else `−1` (the inlet is always at
/// negative `X`; physical `x = sign·X·a`).
pub(super) fn frame_sign(input: &Ehl2dInput) -> f64 {
    if input.entrainment_velocity >= 0.0 {
        1.0
    } else {
        -1.0
    }
}

/// Most halvings of a transient step that does not converge whole ([`solve_transient`]):
/// 1, 2, 4 or 8 backward-Euler sub-steps.
const MAX_SUBSTEP_HALVINGS: u32 = 3;

/// One backward-Euler step of the transient problem (seed 000 eq. 2 with `∂(ρh)/∂t`): from the
/// previous time level `squeeze.previous` over `squeeze.time_step`, at this input's load, speed
/// and geometry (held over the step). The squeeze term's `(ρ̄h)_old` is the previous level's
/// mass per area at the same **physical** position ([`previous_mass`]), `κ` the dimensionless
/// coefficient of [`squeeze_kappa`]. Newton starts from `warm` (default: the previous level;
/// with `prior`, the secant extrapolation of [`solve_kept`]) on the finest grid, with the
/// continuation of [`solve_from`]'s warm start (geometric face means, else from the arithmetic
/// ones; pseudo-time steps — on top of the physical squeeze term — when Newton fails). When that
/// fails, the step is split into 2, 4, 8 equal sub-steps, each a full backward-Euler step from the
/// last ([`Ehl2dSolution::substeps`]); the load is the step's end value in each. The resolution
/// check runs as after a warm start (the check solve on the half grid is of the same step: its
/// last sub-step's squeeze term injected) unless `options.grid_check` is off.
/// `kept`: as in [`solve_kept`].
pub fn solve_transient(input: &Ehl2dInput, options: &Ehl2dOptions, squeeze: Squeeze2d, warm: Option<&Warm2d>, prior: Option<&Warm2d>, kept: &mut Kept2d, observer: &dyn Observer) -> Result<(Ehl2dSolution, Warm2d), SolveError> {
    validate(input, options)?;
    let finite = matches!(input.geometry, Geometry2d::Finite { .. });
    validate_squeeze(&squeeze, finite)?;
    let kept_pc = kept.take_for(options.nx, options.ny);
    let kept_pattern = kept.pattern_for(options.nx, options.ny);
    let s = scales(input)?;
    let d = domain(input, options, &s);
    let mut prob = Problem::new(input, &s, d, options.nx, options.ny, options.near_field);
    prob.kept = kept_pc;
    prob.pattern = std::cell::RefCell::new(kept_pattern.clone());
    prob.forcing = warm_forcing();
    let kappa = squeeze_kappa(input, &s, squeeze.time_step);
    let q_prev = previous_mass(&prob, input, &s, squeeze.previous);
    let usable = |w: &&Warm2d| w.finite == finite && w.central > 0.0 && w.h_est > 0.0;
    let start = warm.filter(usable).unwrap_or(squeeze.previous);
    let prior = prior.filter(usable);
    let (mut iterations, mut last) = (0u32, None);
    for halvings in 0..=MAX_SUBSTEP_HALVINGS {
        let n = 1u32 << halvings;
        // κ ∝ 1/Δt: the sub-step's is n times the step's.
        let kappa_n = kappa * n as f64;
        prob.target = Some((kappa_n, q_prev.clone()));
        prob.restore_target();
        let Some((mut p, mut h0)) = warm_start(&mut prob, &s, start, prior) else { break };
        let mut converged = false;
        for sub in 0..n {
            if sub > 0 {
                prob.restore_target();
            }
            let run = solve_level(&mut prob, &mut p, &mut h0, options.tolerance, options.max_iterations.min(NESTED_ITER), options.max_iterations, DT_NESTED, true, observer)?;
            iterations += run.iterations;
            if trace() {
                eprintln!("ehl2d transient: {n} sub-steps, κ {kappa_n:.3e}: converged {} in {} steps", run.converged, run.iterations);
            }
            converged = run.converged;
            last = Some(run);
            if !converged {
                break;
            }
            if sub + 1 < n {
                // The next sub-step's previous level: this one's `ρ̄H` on the same grid (the
                // last sub-step's target stays for the resolution check).
                match prob.mass(&p, h0) {
                    Some(m) => prob.target = Some((kappa_n, m)),
                    None => {
                        converged = false;
                        break;
                    }
                }
            }
        }
        if converged {
            let residual = last.as_ref().map_or(0.0, |r| r.residual);
            let solved = Solved { prob, p, h0, iterations, residual, coarse: None, warm_used: true };
            let (mut sol, next) = conclude(input, options, &s, d, solved, kept, kept_pattern, observer)?;
            sol.substeps = Some(n);
            return Ok((sol, next));
        }
    }
    let (residual, mut history) = last.map_or((f64::INFINITY, Vec::new()), |r| (r.residual, r.history));
    if history.len() > 20 {
        history.drain(..history.len() - 20);
    }
    Err(SolveError::NotConverged { solver: "ehl 2-D transient step (Newton–Krylov, 1–8 sub-steps)", iterations, residual, tolerance: options.tolerance, history })
}

/// A transient step's time step and previous level: `time_step` finite and > 0, the previous
/// level a converged solution of the same contact kind with its pressure and mass per area.
fn validate_squeeze(squeeze: &Squeeze2d, finite: bool) -> Result<(), SolveError> {
    if !(squeeze.time_step.is_finite() && squeeze.time_step > 0.0) {
        return Err(SolveError::invalid("Squeeze2d.time_step", "must be a finite number > 0 (s)"));
    }
    let w = squeeze.previous;
    let sized = w.x.len() >= 2 && w.y.len() >= 2 && w.mass.len() == w.x.len() * w.y.len() && w.pressure.len() == w.mass.len();
    let finite_values = w.a.is_finite() && w.a > 0.0 && w.mass.iter().all(|m| m.is_finite() && *m >= 0.0) && (w.sign == 1.0 || w.sign == -1.0);
    if !(sized && finite_values) {
        return Err(SolveError::invalid("Squeeze2d.previous", "must be a converged 2-D solution with its mass per area at every node"));
    }
    if w.finite != finite {
        return Err(SolveError::invalid("Squeeze2d.previous", "must be of the same contact kind (point or finite line) as the input"));
    }
    Ok(())
}

/// The dimensionless squeeze coefficient `κ = 12 η0 R_x²/(a² p_ref Δt)` of the backward-Euler
/// term `−κ (ρ̄H − (ρ̄H)_old)` (seed 000 eq. 2's `∂(ρh)/∂t`). Dimensions: the Poiseuille term
/// `∂/∂x(ρh³/(12η) ∂p/∂x)` is `ρ0 a⁴ p_ref/(12 η0 R_x³)·∂/∂X(ε ∂P/∂X)` (kg m⁻² s⁻¹) with
/// `h = H a²/R_x`, `x = X a`; the squeeze term `(ρ0 a²/R_x)(ρ̄H − (ρ̄H)_old)/Δt` (kg m⁻² s⁻¹);
/// their ratio `12 η0 R_x²/(a² p_ref Δt)` is dimensionless (Pa s · m² / (m² · Pa · s)). It is
/// the wedge's `λ = 12 η0 u_m R_x²/(a³ p_ref)` times the passage time `a/u_m` over `Δt`, the
/// pseudo-time `κ = λ/ΔT` of [`march`] with `ΔT = Δt u_m/a`; as the 1-D solver's
/// (`super::super::newton`, `12 η0 R²/(b² p_h Δt)`).
fn squeeze_kappa(input: &Ehl2dInput, s: &Scales, time_step: f64) -> f64 {
    let eta0 = input.lubricant.viscosity_at(0.0, input.temperature);
    12.0 * eta0 * s.rx * s.rx / (s.a * s.a * s.p_ref * time_step)
}

/// The previous level's mass per area on `prob`'s nodes in units of `a²/R_x`: `ρ̄h` of `w` at
/// the node's physical position (`x = sign·X·a`, `y = Y·a` of this problem; `X_old = sign_old·x/a_old`,
/// `Y_old = y/a_old`), bilinear. Outside the old domain (a larger contact reaches further up the
/// inlet or to the sides): the nearest boundary node's value plus the change of the undeformed
/// gap `x²/(2R_x) + S(y)` of this geometry from there — the old boundary's pressure is 0
/// (`ρ̄ = 1`), so this is the 1-D solver's `EhlState::mass_per_area` (the end film continued along
/// the undeformed parabola at `ρ̄ = 1`), not a frozen boundary value that would put a thinner film
/// far up the inlet than at its edge; the deflection's change beyond the old edge is neglected
/// (there `q_old` barely matters: the squeeze term is small against the inlet's wedge term).
fn previous_mass(prob: &Problem, input: &Ehl2dInput, s: &Scales, w: &Warm2d) -> Vec<f64> {
    let film_scale = s.a * s.a / s.rx;
    let sign = frame_sign(input);
    let gap = |x: f64, y: f64| x * x / (2.0 * s.rx) + side_gap(input, s, y / s.a) * film_scale;
    let (xl, xh) = (w.x[0], w.x[w.x.len() - 1]);
    let (yl, yh) = (w.y[0], w.y[w.y.len() - 1]);
    let mut q = vec![0.0; prob.nx * prob.ny];
    for (k, qk) in q.iter_mut().enumerate() {
        let (x, y) = (sign * prob.x[k % prob.nx] * s.a, prob.y[k / prob.nx] * s.a);
        let (xo, yo) = (w.sign * x / w.a, y / w.a);
        let (xc, yc) = (xo.clamp(xl, xh), yo.clamp(yl, yh));
        let mut m = bilinear(&w.x, &w.y, &w.mass, xc, yc);
        if xc != xo || yc != yo {
            m += gap(x, y) - gap(w.sign * xc * w.a, yc * w.a);
        }
        *qk = m.max(0.0) / film_scale;
    }
    q
}

/// Smallest accepted ratio of the minimum to the central film: below it the film is pinched at a
/// node by the discretisation (measured: the arithmetic-mean scheme's 33² solution of the
/// circular M ≈ 300 contact had h_min/h_c ≈ 0.9 at 4.9 nm against 220 nm converged).
pub const PINCH: f64 = 0.1;

/// Central and minimum film (units of `a²/R_x`) and grid of a check solve on the grid with half
/// the intervals, started from the injected solution; `None` when that grid has fewer than 9
/// nodes per side, the node counts are even, or Newton does not converge there.
#[allow(clippy::too_many_arguments)]
fn check_half(s: &Scales, d: Domain, input: &Ehl2dInput, options: &Ehl2dOptions, p: &[f64], h0: f64, target: Option<&(f64, Vec<f64>)>, observer: &dyn Observer) -> Result<Option<(f64, f64, usize, usize)>, SolveError> {
    let (nx, ny) = (options.nx, options.ny);
    if (nx - 1) % 2 != 0 || (ny - 1) % 2 != 0 || (nx - 1) / 2 + 1 < 9 || (ny - 1) / 2 + 1 < 9 {
        return Ok(None);
    }
    let (cx, cy) = ((nx - 1) / 2 + 1, (ny - 1) / 2 + 1);
    let mut prob = Problem::new(input, s, d, cx, cy, options.near_field);
    let inject = |f: &[f64]| -> Vec<f64> { (0..cx * cy).map(|k| f[(k / cx) * 2 * nx + (k % cx) * 2]).collect() };
    let mut pc = inject(p);
    // A transient step's squeeze term, at the coinciding nodes.
    if let Some((kappa, q)) = target {
        prob.target = Some((*kappa, inject(q)));
        prob.restore_target();
    }
    let mut h0c = h0;
    let run = solve_level(&mut prob, &mut pc, &mut h0c, options.tolerance.max(1e-6), options.max_iterations.min(NESTED_ITER), options.max_iterations, DT_NESTED, true, observer)?;
    let mut v = Fields::default();
    if !run.converged || !prob.evaluate(&pc, h0c, &mut v) {
        return Ok(None);
    }
    let hmin = v.h.iter().cloned().fold(f64::INFINITY, f64::min);
    Ok(Some((bilinear(&prob.x, &prob.y, &v.h, 0.0, 0.0), hmin, cx, cy)))
}

/// The nested iteration up to `options`' grid: the finest problem, its pressure, `H0`, the Newton
/// steps and the final residual.
/// Also the central and minimum film (units of `a²/R_x`) and grid of the previous level, if any.
#[allow(clippy::type_complexity)]
fn solve_levels(input: &Ehl2dInput, options: &Ehl2dOptions, s: &Scales, d: Domain, observer: &dyn Observer) -> Result<(Problem, Vec<f64>, f64, u32, f64, Option<(f64, f64, usize, usize)>), SolveError> {
    let s = s.clone();
    // Nested iteration: grids of (n − 1)/2^k + 1 nodes down to ≥ 17 per side, the coarsest
    // one that resolves the film: a grid whose spacing is not small against sqrt(H) carries a
    // deflection discretisation error (O(h²), cell-constant pressure) as large as the film, and
    // its discrete problem pinches the film to zero (measured: 25² at M ≈ 60 stalls, 49² converges
    // in 9 Newton steps; `BENCHMARKS.md`, issue 16).
    let spacing = |lx: usize, ly: usize| ((d.x_out - d.x_in) / (lx - 1) as f64).max((d.y_hi - d.y_lo) / (ly - 1) as f64);
    // The grid with half the intervals, if both node counts allow it and it keeps `MIN_LEVEL`.
    let half = |(lx, ly): (usize, usize)| {
        let (cx, cy) = ((lx - 1) / 2 + 1, (ly - 1) / 2 + 1);
        ((lx - 1) % 2 == 0 && (ly - 1) % 2 == 0 && cx >= MIN_LEVEL && cy >= MIN_LEVEL).then_some((cx, cy))
    };
    let mut levels = vec![(options.nx, options.ny)];
    while let Some((cx, cy)) = half(levels[levels.len() - 1]).filter(|&(cx, cy)| levels.len() < 4 && spacing(cx, cy).powi(2) <= RESOLVED * s.h_est) {
        levels.push((cx, cy));
    }
    levels.reverse();
    let tol = options.tolerance;
    let mut total = 0u32;
    let mut gmres_total = 0usize;
    // No coarse level passes the check, but the half grid resolves the film along x (cells long
    // across a long roller: only y fails): the cold start is tried on the finest grid for a few
    // Newton steps (at θ = 0, [`solve_level`]); if it does not converge, the solve goes through
    // that half grid instead. Measured (issue 16, ehl2d-13): the 129² long straight roller takes
    // 140 steps cold and 44 through 65² with the same films; the seed 000 nose on 65×129 converges
    // cold in 18–20 steps and takes 25–65 through its half grid, so it keeps the cold start.
    let mut trial: Option<(Problem, Vec<f64>, f64)> = None;
    if levels.len() == 1 {
        let (lx, ly) = levels[0];
        let along_x = |&(cx, _): &(usize, usize)| ((d.x_out - d.x_in) / (cx - 1) as f64).powi(2) <= RESOLVED * s.h_est;
        if let Some((cx, cy)) = half((lx, ly)).filter(along_x) {
            let mut prob = Problem::new(input, &s, d, lx, ly, options.near_field);
            let (mut p, mut h0) = cold(&mut prob, input, &s);
            prob.theta = 0.0;
            match newton(&mut prob, &mut p, &mut h0, tol, COLD_TRIAL.min(options.max_iterations), observer) {
                Ok(r) if r.converged => {
                    total += r.iterations;
                    trial = Some((prob, p, h0));
                }
                Ok(r) => {
                    total += r.iterations;
                    levels.insert(0, (cx, cy));
                }
                Err(e @ SolveError::Interrupted(_)) => return Err(e),
                Err(_) => levels.insert(0, (cx, cy)),
            }
        }
    }
    // Coarse solution: nodes, pressure and central film.
    let mut guess: Option<(Vec<f64>, Vec<f64>, Vec<f64>, f64)> = None;
    let mut coarse = None;
    let nlev = levels.len();
    // Progress: each level's share of the work (≈ nodes^1.4).
    let work: Vec<f64> = levels.iter().map(|&(lx, ly)| ((lx * ly) as f64).powf(1.4)).collect();
    let total_work: f64 = work.iter().sum::<f64>().max(1.0);
    for (li, &(lx, ly)) in levels.iter().enumerate() {
        let finest = li + 1 == nlev;
        let lo = work[..li].iter().sum::<f64>() / total_work;
        let name = format!("2-D EHL on {lx}×{ly}");
        let stage = crate::Stage::new(observer, 0.9 * lo, 0.9 * (lo + work[li] / total_work), 200.0, &name);
        let observer: &dyn Observer = &stage;
        let level_tol = if finest { tol } else { tol.max(1e-5) };
        let (mut prob, mut p, mut h0) = match trial.take() {
            // The cold start's θ = 0 solution from the trial above (the only level).
            Some(t) => t,
            None => {
                let mut prob = Problem::new(input, &s, d, lx, ly, options.near_field);
                let (p, h0) = match &guess {
                    // The coarse pressure, and `H0` that keeps the coarse central film (the coarse
                    // grid's `H0` carries its deflection discretisation error).
                    Some((gx, gy, gp, hc)) => {
                        let p = prolong(&prob, gx, gy, gp);
                        let h0 = h0_for(&mut prob, &p, *hc);
                        (p, h0)
                    }
                    None => cold(&mut prob, input, &s),
                };
                (prob, p, h0)
            }
        };
        let cap = if guess.is_some() { options.max_iterations.min(NESTED_ITER) } else { options.max_iterations };
        let dt0 = if guess.is_some() { DT_NESTED } else { DT_COLD };
        let run = solve_level(&mut prob, &mut p, &mut h0, level_tol, cap, options.max_iterations, dt0, false, observer)?;
        total += run.iterations;
        gmres_total += run.gmres;
        if finest {
            if !run.converged {
                let mut history = run.history;
                if history.len() > 20 {
                    history.drain(..history.len() - 20);
                }
                return Err(SolveError::NotConverged { solver: "ehl 2-D (pseudo-time Newton–Krylov)", iterations: total, residual: run.residual, tolerance: tol, history });
            }
            let _ = gmres_total;
            return Ok((prob, p, h0, total, run.residual, coarse));
        }
        let mut v = Fields::default();
        let hc = if prob.evaluate(&p, h0, &mut v) {
            let hc = bilinear(&prob.x, &prob.y, &v.h, 0.0, 0.0);
            coarse = Some((hc, v.h.iter().cloned().fold(f64::INFINITY, f64::min), lx, ly));
            if trace() {
                eprintln!("ehl2d level {lx}x{ly}: Hc {hc:.4e} Hmin {:.4e} floor {:.4e} at floor {}", v.h.iter().cloned().fold(f64::INFINITY, f64::min), prob.floor, v.on.iter().filter(|o| **o == 0.0).count());
            }
            hc
        } else {
            coarse = None;
            s.h_est
        };
        guess = Some((prob.x.clone(), prob.y.clone(), p, hc));
    }
    unreachable!("the finest level returns")
}

/// The contacts are symmetric about y = 0, so an extremum at node `k` has a mirror at
/// `(i, ny − 1 − j)` that differs only by the solver's tolerance. Where the two agree to 1e-6
/// relative, the node at y ≥ 0 is reported, so the reported position does not flip sign with the
/// last digits of the solution (the roller's two ends).
pub(super) fn mirror_tie(nx: usize, ny: usize, k: usize, f: &[f64]) -> usize {
    let (i, j) = (k % nx, k / nx);
    let m = (ny - 1 - j) * nx + i;
    if m > k && (f[m] - f[k]).abs() <= 1e-6 * f[k].abs() {
        m
    } else {
        k
    }
}

/// The node of the largest off-centre local maximum of the axial pressure profile `max_X P(X, Y)`
/// of a finite line contact (half-length `ky`, units of `a`) above the centre's pressure (the
/// edge pressure peak), the mirror-symmetric tie resolved to one side; `None` when the profile
/// has none.
pub(super) fn edge_peak_node(xs: &[f64], ys: &[f64], p: &[f64], ky: f64) -> Option<usize> {
    let (nx, ny) = (xs.len(), ys.len());
    let line: Vec<(f64, usize)> = (0..ny)
        .map(|j| {
            let i = (0..nx).max_by(|&a, &b| p[j * nx + a].total_cmp(&p[j * nx + b])).unwrap_or(0);
            (p[j * nx + i], j * nx + i)
        })
        .collect();
    let centre = bilinear(xs, ys, p, 0.0, 0.0);
    let mut best: Option<(f64, usize)> = None;
    for j in 1..ny - 1 {
        let (pv, k) = line[j];
        let off = ys[j].abs() > 0.1 * ky;
        if off && pv >= line[j - 1].0 && pv >= line[j + 1].0 && pv > centre * (1.0 + 1e-3) && best.is_none_or(|(b, _)| pv > b) {
            best = Some((pv, k));
        }
    }
    best.map(|(_, k)| mirror_tie(nx, ny, k, p))
}

/// GMRES iterations of the last [`solve`] are not reported; this is the count of Newton steps.
#[allow(clippy::too_many_arguments)]
fn finish(input: &Ehl2dInput, options: &Ehl2dOptions, s: &Scales, prob: &mut Problem, p: &[f64], h0: f64, iterations: u32, residual: f64) -> Result<Ehl2dSolution, SolveError> {
    let mut v = Fields::default();
    if !prob.evaluate(p, h0, &mut v) {
        return Err(SolveError::NonFinite { quantity: "2-D EHL film".into() });
    }
    let (nx, ny) = (prob.nx, prob.ny);
    let film_scale = s.a * s.a / s.rx;
    let sign = if input.entrainment_velocity >= 0.0 { 1.0 } else { -1.0 };
    let at = |k: usize| (sign * prob.x[k % nx] * s.a, prob.y[k / nx] * s.a);
    let central = bilinear(&prob.x, &prob.y, &v.h, 0.0, 0.0) * film_scale;
    let kmin = mirror_tie(nx, ny, (0..nx * ny).min_by(|&a, &b| v.h[a].total_cmp(&v.h[b])).unwrap_or(0), &v.h);
    let kmax = mirror_tie(nx, ny, (0..nx * ny).max_by(|&a, &b| p[a].total_cmp(&p[b])).unwrap_or(0), p);
    let loc = |k: usize, value: f64| {
        let (x, y) = at(k);
        Located { value, x, y }
    };
    let min_film = loc(kmin, v.h[kmin] * film_scale);
    let max_pressure = loc(kmax, p[kmax].max(0.0) * s.p_ref);
    if min_film.value <= 0.0 {
        return Err(SolveError::physical(crate::PhysicalFailure::FilmCollapse, "the converged 2-D EHL film is not positive"));
    }
    let edge = match input.geometry {
        Geometry2d::Finite { .. } => edge_peak_node(&prob.x, &prob.y, p, s.ky).map(|k| loc(k, p[k] * s.p_ref)),
        Geometry2d::Point { .. } => None,
    };
    let load = p.iter().sum::<f64>() * prob.dx * prob.dy * s.p_ref * s.a * s.a;
    let fields = options.fields.then(|| Fields2d {
        x: prob.x.iter().map(|x| sign * x * s.a).collect(),
        y: prob.y.iter().map(|y| y * s.a).collect(),
        pressure: p.iter().map(|v| v.max(0.0) * s.p_ref).collect(),
        film: v.h.iter().map(|h| h * film_scale).collect(),
    });
    let sol = Ehl2dSolution {
        hertz_half_width: s.a,
        hertz_pressure: s.p_ref,
        moes_m: s.moes_m,
        moes_l: s.moes_l,
        central_film: central,
        min_film,
        max_pressure,
        edge_pressure_peak: edge,
        load,
        nx,
        ny,
        fields,
        grid_error: None,
        warm_started: false,
        substeps: None,
        convergence: Convergence { iterations, residual, tolerance: options.tolerance, termination: Termination::Converged },
    };
    let scalars = [sol.central_film, sol.min_film.value, sol.max_pressure.value, sol.load, residual];
    crate::ensure_finite("2-D EHL result", scalars.iter())?;
    if let Some(f) = &sol.fields {
        crate::ensure_finite("2-D EHL fields", f.pressure.iter().chain(&f.film))?;
    }
    Ok(sol)
}

impl Problem {
    /// Poiseuille and wedge terms of the steady Reynolds operator at the interior nodes for given
    /// node fields (the truncation probe).
    fn pieces(&self, p: &[f64], h: &[f64], rho: &[f64], e: &[f64]) -> (Vec<f64>, Vec<f64>) {
        let (nx, dx2, dy2) = (self.nx, self.dx * self.dx, self.dy * self.dy);
        let mut pois = vec![0.0; p.len()];
        let mut wedge = vec![0.0; p.len()];
        for &k in &self.nodes {
            let i = k % nx;
            let f = |a: usize, b: usize| face_of(self.theta, e[a], e[b]).0;
            pois[k] = (f(k, k + 1) * (p[k + 1] - p[k]) - f(k, k - 1) * (p[k] - p[k - 1])) / dx2 + (f(k, k + nx) * (p[k + nx] - p[k]) - f(k, k - nx) * (p[k] - p[k - nx])) / dy2;
            for (s, wt) in self.wedge(i) {
                wedge[k] += self.lambda * wt * rho[k - s] * h[k - s];
            }
        }
        (pois, wedge)
    }
}

/// Development aid (issue 16): the truncation error of the discretisation on coarser grids,
/// measured by injecting the solution of `options`' grid into grids `stride` times coarser
/// (same domain, coinciding nodes): the deflection error `τ_W = W_coarse(P) − W_fine(P)`, the
/// Poiseuille and wedge errors of the Reynolds operator, the film error `Σ (τ_pois − τ_wedge) ΔX/λ`
/// they would cause if only the wedge answered, and the actual coarse solution's film error,
/// along the centre line. Printed to stderr.
#[doc(hidden)]
pub fn truncation_probe(input: &Ehl2dInput, options: &Ehl2dOptions, strides: &[usize]) -> Result<(), SolveError> {
    use crate::Silent;
    validate(input, options)?;
    let s = scales(input)?;
    let d = domain(input, options, &s);
    let (mut pf, p, h0, _, _, _) = solve_levels(input, options, &s, d, &Silent)?;
    let mut vf = Fields::default();
    pf.evaluate(&p, h0, &mut vf);
    let (pois_f, wedge_f) = pf.pieces(&p, &vf.h, &vf.rho, &vf.eps);
    let (nx, ny) = (pf.nx, pf.ny);
    eprintln!("probe fine {nx}x{ny}: H0 {h0:.5e} Hc {:.5e} Hmin {:.5e} lambda {:.4e} c {:.4e} dx {:.4e}", bilinear(&pf.x, &pf.y, &vf.h, 0.0, 0.0), vf.h.iter().cloned().fold(f64::INFINITY, f64::min), pf.lambda, s.c_def, pf.dx);
    for &st in strides {
        let (cx, cy) = ((nx - 1) / st + 1, (ny - 1) / st + 1);
        let mut pc = Problem::new(input, &s, d, cx, cy, options.near_field);
        let inj = |f: &[f64]| -> Vec<f64> { (0..cx * cy).map(|k| f[(k / cx) * st * nx + (k % cx) * st]).collect() };
        let (p_c, h_c, w_cf, rho_c, eps_c) = (inj(&p), inj(&vf.h), inj(&vf.w), inj(&vf.rho), inj(&vf.eps));
        let mut w_c = vec![0.0; cx * cy];
        pc.defl.apply(&p_c, &mut w_c);
        let (pois_c, wedge_c) = pc.pieces(&p_c, &h_c, &rho_c, &eps_c);
        let (pois_fi, wedge_fi) = (inj(&pois_f), inj(&wedge_f));
        let co = Ehl2dOptions { nx: cx, ny: cy, ..*options };
        let actual = solve_levels(input, &co, &s, d, &Silent).ok().map(|(mut q, pp, hh, _, _, _)| {
            let mut v = Fields::default();
            q.evaluate(&pp, hh, &mut v);
            (v.h, pp, hh)
        });
        let j = (cy - 1) / 2;
        let hc_f = bilinear(&pc.x, &pc.y, &h_c, 0.0, 0.0);
        let tw0 = bilinear(&pc.x, &pc.y, &w_c.iter().zip(&w_cf).map(|(a, b)| a - b).collect::<Vec<_>>(), 0.0, 0.0);
        eprintln!("stride {st}: {cx}x{cy}, dx {:.4e}; tauW at centre {tw0:.4e} (Hc {hc_f:.4e}); actual coarse Hc {:.5e} Hmin {:.5e} H0 {:.5e}", pc.dx, actual.as_ref().map_or(f64::NAN, |(h, _, _)| bilinear(&pc.x, &pc.y, h, 0.0, 0.0)), actual.as_ref().map_or(f64::NAN, |(h, _, _)| h.iter().cloned().fold(f64::INFINITY, f64::min)), actual.as_ref().map_or(f64::NAN, |a| a.2));
        eprintln!("   i       X        P_f        H_f       tauW     tauPois    tauWedge     cumdH   dH_actual   P_actual");
        let mut cum = 0.0;
        for i in 0..cx {
            let k = j * cx + i;
            let (tp, tq) = (pois_c[k] - pois_fi[k], wedge_c[k] - wedge_fi[k]);
            if i > 0 && i < cx - 1 && p_c[k] > 0.0 {
                cum += (tp - tq) * pc.dx / pc.lambda / rho_c[k];
            }
            let (dh, pa) = actual.as_ref().map_or((f64::NAN, f64::NAN), |(h, pp, _)| (h[k] - h_c[k], pp[k]));
            eprintln!("{i:4} {:8.4} {:10.4e} {:10.4e} {:10.3e} {:10.3e} {:10.3e} {:10.3e} {:10.3e} {:10.4e}", pc.x[i], p_c[k], h_c[k], w_c[k] - w_cf[k], tp, tq, cum, dh, pa);
        }
        // The deflection error over the pressurised zone and across the centre line.
        let mut worst = (0.0f64, 0usize);
        for k in 0..cx * cy {
            let t = (w_c[k] - w_cf[k]).abs();
            if t > worst.0 {
                worst = (t, k);
            }
        }
        eprintln!("   max |tauW| {:.4e} at X {:.3} Y {:.3} (P {:.3e})", worst.0, pc.x[worst.1 % cx], pc.y[worst.1 / cx], p_c[worst.1]);
        let i0 = pc.x.iter().position(|&x| x >= 0.0).unwrap_or(0);
        eprintln!("   across (X = {:.3}): Y, tauW, dH_actual", pc.x[i0]);
        for jj in (0..cy).step_by((cy / 16).max(1)) {
            let k = jj * cx + i0;
            eprintln!("   {:8.4} {:10.3e} {:10.3e}", pc.y[jj], w_c[k] - w_cf[k], actual.as_ref().map_or(f64::NAN, |(h, _, _)| h[k] - h_c[k]));
        }
    }
    Ok(())
}

#[cfg(test)]
mod probe {
    use super::*;
    use crate::lubricant::Lubricant;

    /// The truncation probe on the bench's circular contact (`TRIBOD_EHL2D_PROBE_FINE`, default 129).
    #[test]
    #[ignore = "development aid: prints the truncation errors of coarser grids (issue 16)"]
    fn truncation_probe_circular() {
        let fine: usize = std::env::var("TRIBOD_EHL2D_PROBE_FINE").ok().and_then(|v| v.parse().ok()).unwrap_or(129);
        let lub = Lubricant { viscosity: 0.04, pressure_viscosity: 2e-8, ..Lubricant::SEED000 };
        let input = Ehl2dInput { load: 100.0, geometry: Geometry2d::Point { rx: 0.01, ry: 0.01 }, effective_modulus: 210e9 / 0.91, entrainment_velocity: 1.0, lubricant: lub, temperature: 313.0 };
        let o = Ehl2dOptions { nx: fine, ny: fine, inlet: Some(3.5), outlet: Some(1.5), side: Some(2.0), ..Default::default() };
        let strides: Vec<usize> = [2, 4, 8].into_iter().filter(|s| (fine - 1) / s >= 16).collect();
        truncation_probe(&input, &o, &strides).unwrap();
    }
}

#[cfg(test)]
mod tests {
    use super::mirror_tie;

    /// A tie between mirrored nodes is reported at y ≥ 0 whichever of the two the scan found; a
    /// real difference keeps the extremum where it is.
    #[test]
    fn mirrored_extrema_are_reported_at_positive_y() {
        let (nx, ny) = (3, 5);
        let mut f = vec![1.0; nx * ny];
        f[nx + 1] = 0.5; // (1, 1), y < 0
        f[3 * nx + 1] = 0.5 * (1.0 + 1e-9); // its mirror (1, 3)
        assert_eq!(mirror_tie(nx, ny, nx + 1, &f), 3 * nx + 1);
        assert_eq!(mirror_tie(nx, ny, 3 * nx + 1, &f), 3 * nx + 1);
        f[3 * nx + 1] = 0.5 * (1.0 + 1e-3);
        assert_eq!(mirror_tie(nx, ny, nx + 1, &f), nx + 1);
        assert_eq!(mirror_tie(nx, ny, 2 * nx, &f), 2 * nx); // the centre line is its own mirror
    }
}
