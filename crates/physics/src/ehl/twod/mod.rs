//! Steady and transient isothermal EHL of point contacts (elliptic, spherical followers) and
//! finite line contacts (the crowned roller of seed 000), solved over a 2-D grid.
//!
//! # Equations (dimensionless with a Hertzian length `a` and pressure `p_ref`)
//! `X = x/a`, `Y = y/a`, `P = p/p_ref`, `H = h R_x/a²`, `ρ̄ = ρ/ρ0`, `η̄ = η/η(0, T)`; the
//! entrainment is along `x` (a negative `u_m` mirrors the solution in `x`):
//! * compressible Reynolds (seed 000 eq. 2, isothermal):
//!   `∂/∂X(ε ∂P/∂X) + ∂/∂Y(ε ∂P/∂Y) − λ ∂(ρ̄H)/∂X − κ (ρ̄H − (ρ̄H)_old) = 0`, `ε = ρ̄H³/η̄`,
//!   `λ = 12 η0 u_m R_x²/(a³ p_ref)`; steady: `κ = 0`; a transient step ([`solve_transient`]):
//!   backward Euler in `t` with `κ = 12 η0 R_x²/(a² p_ref Δt)` and `(ρ̄H)_old` the previous time
//!   level's `ρ̄h` at the same physical position (`solver::transient::previous_mass`) over
//!   `a²/R_x`;
//! * film (seed 000 eq. 3): `H = H0 + X²/2 + S(Y) + c ∫∫ P(X', Y')/sqrt((X−X')² + (Y−Y')²)`,
//!   `c = 2 p_ref R_x/(π E' a)` with `E' = 2/Σ(1−ν²)/E` (Hamrock–Dowson); `S = (R_x/R_y) Y²/2`
//!   for a point contact, `S = g(aY) R_x/a²` for the crowned roller (`physics::geometry::Crown::gap`,
//!   seed 000 eq. 3 read as a convex crown, or as printed: `CrownProfile`);
//! * load balance (seed 000 eq. 6): `∫∫ P dX dY = F/(p_ref a²)`;
//! * cavitation as complementarity: `P ≥ 0`, Reynolds residual `≤ 0`, product zero; `P = 0` on
//!   the domain boundary (for the roller: at its end faces, seed 000's boundary condition);
//! * rheology: the 1-D solver's pressure laws (`super::rheology`, Roelands or Barus viscosity,
//!   Dowson–Higginson density, seed 000 eq. 4–5) at the uniform temperature.
//!
//! Scales: point contact — `a` the Hertzian semi-axis along `x`, `p_ref` the Hertzian peak
//! (Johnson eq. 4.39–4.41); roller — `a`, `p_ref` the line-contact Hertz values at the peak load
//! per length of the slice model (`physics::geometry::Crown::distribute`).
//!
//! # Method
//! A uniform `nx × ny` grid; second-order upwind wedge term (first order next to the inlet
//! boundary), central Poiseuille terms with the face coefficient the geometric mean of the two
//! nodes' `ε` (`solver::face_of`: the arithmetic mean's error where the pressure rises into the
//! contact was the cause of the slow grid convergence, measured); the deflection by DC-FFT
//! ([`elastic`]). The discrete system — one complementarity function `min(P, −c F, s (H − floor))`
//! per interior node (cavitated, lubricated, or held at the film floor with `P` free; `c = 1/|J_ii|`,
//! `s` the inverse deflection self-coefficient) and the load balance, unknowns `P` and `H0` — is
//! solved by a damped semismooth
//! Newton method ([`solver`]) whose steps are computed by restarted GMRES with the exact Jacobian
//! product (two FFTs) and a sparse preconditioner: the Jacobian with the elastic kernel truncated
//! to a `(2r+1)²` near field, factorised by faer's supernodal sparse LU (the `H0` border by its Schur
//! complement) with a nested-dissection column ordering and a symbolic factorisation computed once
//! per grid (`solver::near::NearPattern`). Nested iteration from the coarsest grid that resolves
//! the film (when none does but the half grid resolves it along `x`, a 15-step cold trial on the finest
//! grid first, then that half grid); on each grid the
//! arithmetic-mean problem first, then continuation in the weight of the geometric mean; when
//! Newton fails, pseudo-time continuation: backward-Euler steps of the transient problem (squeeze
//! term) with a growing step.
//!
//! # Resolution check
//! A converged solution is refused (`SolveError::InvalidInput` naming `Ehl2dOptions.nx`, "the
//! grid does not resolve the film") when its minimum film is below `solver::PINCH` of the
//! central film, or when the central film changes by more than `Ehl2dOptions::grid_tolerance`
//! (the minimum film by more than three times that) from the grid with half the intervals (the
//! nested iteration's previous level, or a check solve from the injected solution). The change
//! is reported as [`Ehl2dSolution::grid_error`].
//!
//! # Transient steps
//! [`solve_transient`] solves one backward-Euler step from a previous level ([`Squeeze2d`]: its
//! [`Warm2d`], which carries the mass per area, and `Δt`) at the step's end load, speed and
//! geometry: Newton from the previous level's pressure on the finest grid, the continuation of a
//! warm start when that fails (its pseudo-time steps added on top of the physical squeeze term),
//! and, when that fails too, the step split into 2, 4, 8 backward-Euler sub-steps
//! ([`Ehl2dSolution::substeps`]). `Δt → ∞` is the steady problem, `Δt → 0` freezes `ρ̄h`.
//!
//! # Status (issue 16)
//! Grid convergence (`BENCHMARKS.md`, "Finite-length and point EHL"): on the circular M ≈ 300,
//! L ≈ 11 contact the central film is within −5 % (65²), −1.6 % (129²), −0.4 % (257²) of the
//! Richardson value (arithmetic means before: −28 %, −7 %, −1.8 %); observed order 1.5 along x on
//! 65…257 nodes, 2 across. Newton's stalls at a node whose film the discrete problem wants
//! non-positive are gone (a film floor in the Reynolds terms, `solver::FILM_FLOOR`): 1.7 GPa
//! converges on 129² (on 65² it is refused by the resolution check), a long straight roller with
//! relieved ends matches the 1-D line solution to 0.84 %. Still failing (`NotConverged`, typed,
//! test ignored): near-dry (M ≈ 3000) on 97².
//! Transient steps (`ehl2d-14`): `Δt → ∞` is the steady solve to first order in `1/ΔT`
//! (1.4e-5 at `ΔT = Δt u_m/a = 1e4`); the long straight roller's mid-section follows the 1-D
//! transient line solution through a +30 % load step within 1.23 % (steady: 0.84 %); a step costs
//! about a warm steady solve (4–10 Newton steps).
//!
//! Dry limit (`ehl2d-15`): [`solve_dry`] solves the dry contact on the same nodes ([`dry`],
//! Polonsky–Keer conjugate gradient); the seed 000 roller's EHL pressure approaches it as M grows
//! (`∫|p − p_dry|/F` 0.46 → 0.16 → 0.05 at M 2.9 → 8.9 → 28 on 65×129).
//!
//! # Not modelled
//! Grid grading and mixed lubrication are the 1-D solver's only: this solver is Newtonian and
//! smooth, isothermal unless [`crate::ehl::thermal_finite`] couples it to the energy equations
//! through generalized Reynolds multipliers ([`Factors2d`], [`solve_factored`]); its transient steps are first order in
//! time (backward Euler) with the load held at the step's end value.

pub mod dry;
pub mod elastic;
mod geometry;
pub mod seed003;
pub mod solver;

pub use dry::{solve_dry, DryOptions, DrySolution};
pub use solver::{solve, solve_factored, solve_from, solve_kept, solve_transient, Kept2d};

use crate::lubricant::Lubricant;
use crate::geometry::Crown;
use crate::Convergence;
use serde::{Deserialize, Serialize};

/// The contact's undeformed shape. Entrainment is along `x`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Geometry2d {
    /// Elliptic point contact with principal reduced radii `rx` (in the entrainment direction) and
    /// `ry` (across), m. `rx = ry`: circular (spherical follower).
    Point { rx: f64, ry: f64 },
    /// Finite line contact: a roller of reduced radius `rx` (m) in the entrainment direction with
    /// the axial profile `crown` (seed 000 Table 1: total length, middle length, crown height, end
    /// radius). A straight roller is a crown of zero height with middle length = length.
    Finite { rx: f64, crown: Crown },
}

/// One 2-D EHL problem, SI units.
#[derive(Debug, Clone, Copy)]
pub struct Ehl2dInput {
    /// Normal load, N (> 0).
    pub load: f64,
    pub geometry: Geometry2d,
    /// `E' = 2/Σ(1−ν²)/E`, Pa (Hamrock–Dowson convention).
    pub effective_modulus: f64,
    /// Entrainment velocity `u_m = (u1 + u2)/2` along x, m/s (≠ 0; the sign mirrors the field).
    pub entrainment_velocity: f64,
    pub lubricant: Lubricant,
    /// Film temperature, K (isothermal).
    pub temperature: f64,
}

/// Resolution, tolerance and iteration cap.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Ehl2dOptions {
    /// Nodes in the entrainment direction (including both boundary nodes), 9–1025.
    pub nx: usize,
    /// Nodes across (including both boundary nodes), 9–1025.
    pub ny: usize,
    /// Tolerance on the larger of the relative load-balance error and the largest scaled
    /// complementarity residual `|min(P, −F/|J_ii|)|` divided by the peak pressure.
    pub tolerance: f64,
    /// Most Newton steps per stage (a grid level or a continuation step).
    pub max_iterations: u32,
    /// Inlet distance in units of `a`; `None`: `clamp(10 sqrt(2 H_est), 3.5, 12)`.
    pub inlet: Option<f64>,
    /// Outlet distance in units of `a`; `None`: `clamp(1.5 sqrt(2 H_est), 1.5, 4)`.
    pub outlet: Option<f64>,
    /// Half-width of the domain across the entrainment for point contacts, units of `a`;
    /// `None`: `max(1.8 b/a + 0.5 sqrt(2 H_est), 1.5)` (`b` the other semi-axis). A roller's
    /// domain is its length.
    pub side: Option<f64>,
    /// Near-field radius `r` of the preconditioner's elastic kernel (1–3).
    pub near_field: usize,
    /// Return the pressure and film fields.
    pub fields: bool,
    /// Largest accepted estimate of the central film's discretisation error: its relative change
    /// from the grid with half the intervals ([`Ehl2dSolution::grid_error`]; the minimum film's
    /// change may be three times larger). A solution above it, or whose film pinches below
    /// [`solver::PINCH`] of the central film, is refused with `SolveError::InvalidInput` naming
    /// `Ehl2dOptions.nx` (the grid does not resolve the film).
    pub grid_tolerance: f64,
    /// Run the resolution check's solve on the grid with half the intervals also after a warm
    /// start ([`solve_from`]; a cold solve always checks). Default true; a cam cycle may check
    /// its first angle only.
    #[serde(default = "yes")]
    pub grid_check: bool,
}

fn yes() -> bool {
    true
}

impl Default for Ehl2dOptions {
    fn default() -> Self {
        Ehl2dOptions { nx: 65, ny: 65, tolerance: 1e-7, max_iterations: 40, inlet: None, outlet: None, side: None, near_field: 1, fields: false, grid_tolerance: 0.05, grid_check: true }
    }
}

/// A located pressure or film value.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Located {
    /// Value (Pa or m).
    pub value: f64,
    /// Position along the entrainment from the contact centre, m (positive downstream).
    pub x: f64,
    /// Position across (along the roller axis), m from the centre.
    pub y: f64,
}

/// Pressure and film over the grid, row-major `[j·nx + i]`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Fields2d {
    /// Node positions, m.
    pub x: Vec<f64>,
    pub y: Vec<f64>,
    /// Pressure, Pa.
    pub pressure: Vec<f64>,
    /// Film thickness, m.
    pub film: Vec<f64>,
}

/// The solution of one 2-D problem.
#[derive(Debug, Clone, PartialEq)]
pub struct Ehl2dSolution {
    /// Length scale `a` (Hertzian semi-axis along x, or half-width), m.
    pub hertz_half_width: f64,
    /// Hertzian peak pressure used as the pressure scale, Pa.
    pub hertz_pressure: f64,
    /// Moes `M`, `L` (point contact: Nijenbanning's point groups; roller: line groups at the
    /// peak load per length).
    pub moes_m: f64,
    pub moes_l: f64,
    /// Film at the contact centre, m.
    pub central_film: f64,
    /// Smallest film and where.
    pub min_film: Located,
    /// Largest pressure and where.
    pub max_pressure: Located,
    /// Finite line contacts: the largest off-centre maximum of the pressure along the roller
    /// (`max_x p(x, y)` as a function of `y`), when the profile has one (`None`: the pressure
    /// falls monotonically from the centre to the ends).
    pub edge_pressure_peak: Option<Located>,
    /// Load carried by the converged pressure, N (equals the input within the tolerance).
    pub load: f64,
    pub nx: usize,
    pub ny: usize,
    pub fields: Option<Fields2d>,
    /// Estimated relative discretisation error of the central film: its relative change from the
    /// grid with half the intervals (the nested
    /// iteration's previous level, or a check solve started from the solution); `None` when that
    /// grid is too small (< 9 nodes) or its solve did not converge.
    pub grid_error: Option<f64>,
    /// Whether the warm start of [`solve_from`] converged (false: the cold nested iteration ran).
    pub warm_started: bool,
    /// A transient step ([`solve_transient`]): the backward-Euler sub-steps it took (1: the
    /// whole time step at once; 2, 4, 8: the step split after a failed solve); `None`: steady.
    pub substeps: Option<u32>,
    pub convergence: Convergence,
}

/// A converged solution kept as the warm start of a neighbouring problem ([`solve_from`]) and as
/// the previous time level of a transient step ([`solve_transient`]): the dimensionless pressure
/// `P = p/p_ref` on the nodes `X = x/a`, `Y = y/a` (the solver's frame: inlet at negative `X`),
/// the length scale `a` (m), the central film and the closed-form film estimate in units of
/// `a²/R_x`, whether it is a finite line contact, the mass per area `ρ̄h` (m, `ρ̄ = ρ/ρ0`, the
/// film the Reynolds terms see) at the nodes, and the solver frame's orientation `sign` (±1: the
/// physical position along the entrainment axis is `x = sign·X·a`, negative for `u_m < 0`).
#[derive(Debug, Clone, PartialEq)]
pub struct Warm2d {
    pub x: Vec<f64>,
    pub y: Vec<f64>,
    pub pressure: Vec<f64>,
    pub a: f64,
    pub central: f64,
    pub h_est: f64,
    pub finite: bool,
    pub mass: Vec<f64>,
    pub sign: f64,
}

/// The previous time level of a transient step ([`solve_transient`]): its converged solution and
/// the time elapsed since, s (finite, > 0).
#[derive(Debug, Clone, Copy)]
pub struct Squeeze2d<'a> {
    pub previous: &'a Warm2d,
    pub time_step: f64,
}

/// Generalized Reynolds multipliers over the contact plane (the thermal finite-line model,
/// [`crate::ehl::thermal_finite`]; seed 000 eq. 2): at each node of the grid `x` × `y` (m, both
/// ascending; row-major `[j·nx + i]`) the Poiseuille coefficient `(ρ/η)_e` and the wedge density
/// `(u1 ρ*_1 + u2 ρ*_2)/(2u_m)` relative to the isothermal film's at the node's pressure
/// ([`crate::ehl::thermal::ThermalFactors`]). The solver takes them as multipliers of `ε` in both
/// directions (the flow across the entrainment is pure Poiseuille) and of `ρ̄` in the wedge term;
/// they are held fixed during a solve (the coupling iterates them) and interpolated bilinearly
/// (the Poiseuille factor in its logarithm) onto each grid level. All ones is the isothermal
/// problem to the last bit; `None` skips the multiplication.
#[derive(Debug, Clone, PartialEq)]
pub struct Factors2d {
    pub x: Vec<f64>,
    pub y: Vec<f64>,
    pub poiseuille: Vec<f64>,
    pub wedge: Vec<f64>,
}

impl Factors2d {
    /// The factors at the physical point `(x, y)`, m (bilinear; held at the grid's edges).
    pub fn at(&self, x: f64, y: f64) -> (f64, f64) {
        let loc = |v: &[f64], at: f64| {
            let n = v.len();
            if n < 2 {
                return (0, 0, 0.0);
            }
            let i = v.partition_point(|&a| a <= at).clamp(1, n - 1);
            let t = ((at - v[i - 1]) / (v[i] - v[i - 1])).clamp(0.0, 1.0);
            (i - 1, i, t)
        };
        let (i0, i1, tx) = loc(&self.x, x);
        let (j0, j1, ty) = loc(&self.y, y);
        let nx = self.x.len();
        let mix = |f: &dyn Fn(usize) -> f64| {
            let a = f(j0 * nx + i0) * (1.0 - tx) + f(j0 * nx + i1) * tx;
            let b = f(j1 * nx + i0) * (1.0 - tx) + f(j1 * nx + i1) * tx;
            a * (1.0 - ty) + b * ty
        };
        (mix(&|k| self.poiseuille[k].max(1e-300).ln()).exp(), mix(&|k| self.wedge[k]))
    }
}

/// Memory estimate of a solve on `nx × ny` nodes, bytes: about 40 node arrays, the padded FFT
/// buffers (≈ 4·(2nx)(2ny) complex) and the sparse LU of the preconditioner (≈ 60 nonzeros per
/// node after fill for `r = 1`, measured order of magnitude), plus GMRES' 40 basis vectors.
pub fn memory_bytes(nx: usize, ny: usize) -> f64 {
    let n = (nx * ny) as f64;
    8.0 * n * (40.0 + 4.0 * 4.0 * 2.0 + 60.0 * 2.0 + 41.0)
}
