//! Dynamic coefficients of the film at an equilibrium: the 2×2 stiffness and damping matrices
//! of the journal's small motions, from the linearised perturbation of the discrete Reynolds
//! equation (Lund, "Review of the concept of dynamic coefficients for fluid film journal
//! bearings", ASME J. Tribol. 109, 1987).
//!
//! Frame: `X` along the applied load (the analysis' load line), `Y` perpendicular to it, 90°
//! ahead in the direction of rotation (so the journal turns from `X` towards `Y`). The film force
//! on the journal changes by `ΔF = −K Δx − C Δẋ` for a small displacement `Δx` and velocity `Δẋ`
//! of the journal centre: `K_ij = −∂F_i/∂x_j`, `C_ij = −∂F_i/∂ẋ_j`.
//!
//! Method: at the converged pressure `P0` the cavitation set is frozen (the pressurised nodes
//! stay the unknowns) and four linear problems with the equilibrium's matrix give
//! `∂P/∂X`, `∂P/∂Y` (displacements, `∂A/∂X` from `c = H³k` on the faces) and `∂P/∂X'`, `∂P/∂Y'`
//! (velocities `X' = dX/d(ωt)`, the squeeze term). Only the forces of these are needed, so they
//! are computed through the adjoint: `A_II` is symmetric, and two solves `A_II y_i = g_i` with
//! the force quadrature `g_i` (`F_i = g_iᵀ P`) give every coefficient as `−y_iᵀ b_j` for the four
//! right-hand sides `b_j` — the same numbers, half the linear solves. For the discrete
//! complementarity problem with strict complementarity this is its exact derivative; in the continuous problem the moving
//! Reynolds boundary contributes nothing to first order (`P = ∂P/∂n = 0` there). A supply line
//! stays where the equilibrium put it (a groove is fixed in the bearing). Caveat: a film
//! *reformation* boundary (periodic supply, no groove) has `P = 0` but a non-zero gradient; its
//! motion is a first-order effect the frozen set leaves out (still the exact derivative of the
//! discrete problem, but not grid-convergent to the continuum one there). The validation
//! (BENCHMARKS.md) uses the max-film groove for the short-bearing limit and two axial grooves
//! at ±90° from the load ([`super::problem::Supply::TwoGrooves`]) against Someya's
//! *Journal-Bearing Databook* (L/D = 0.5: ε within 0.005, K̄ and C̄ within 2–8 % of the largest
//! coefficient from ε ≈ 0.37 on, 13–20 % at ε ≈ 0.2, where the groove width matters most).
//!
//! Units: `stiffness` and `damping` are `−∂F̄/∂X` and `−∂F̄/∂X'` in the analysis' scaling
//! (`F̄` in `W̄` units, `X = x/c`, `X' = ẋ/(cω)`); then `K = stiffness · 6ηωRL(R/c)²/c`,
//! `C = damping · 6ηωRL(R/c)²/(cω)`, and the usual dimensionless coefficients
//! `K̄ = K c/W = stiffness/W̄`, `C̄ = C c ω/W = damping/W̄`.

use super::problem::{Analysis, Bearing, Settings, Workspace};
use crate::{ensure_finite, Convergence, Observer, SolveError, Termination};

/// Stiffness and damping at an equilibrium (see the module docs for frame and scaling).
#[derive(Debug, Clone, PartialEq)]
pub struct Coefficients {
    /// `[[kxx, kxy], [kyx, kyy]]`, `−∂F̄_i/∂X_j`.
    pub stiffness: [[f64; 2]; 2],
    /// `[[cxx, cxy], [cyx, cyy]]`, `−∂F̄_i/∂X'_j`.
    pub damping: [[f64; 2]; 2],
    /// The two adjoint linear solves: CG iterations (total), the largest relative residual, the tolerance.
    pub convergence: Convergence,
}

/// Stability of a rigid, symmetric rotor on the film (Lund 1987): per bearing, the rotor mass
/// above which the equilibrium is unstable and the whirl frequency ratio at that threshold.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Stability {
    /// `Ω/ω` of the whirl at the threshold.
    pub whirl_ratio: f64,
    /// `M̄ = m c ω²/W` at the threshold; `None`: stable for any mass (`K_eq ≤ 0` or whirl ratio² ≤ 0).
    pub critical_mass: Option<f64>,
    /// `K̄_eq`, the effective stiffness at the threshold, `K c/W` units.
    pub equivalent_stiffness: f64,
}

impl Coefficients {
    /// `K̄ = K c/W` and `C̄ = C c ω/W` for the film load `W̄`.
    pub fn dimensionless(&self, load: f64) -> Option<([[f64; 2]; 2], [[f64; 2]; 2])> {
        if !(load > 0.0) {
            return None;
        }
        let s = |m: [[f64; 2]; 2]| [[m[0][0] / load, m[0][1] / load], [m[1][0] / load, m[1][1] / load]];
        Some((s(self.stiffness), s(self.damping)))
    }
}

/// Threshold of a rigid rotor from dimensionless coefficients `K̄`, `C̄` (Lund 1987, eq. for the
/// stability of a rigid rotor in two identical bearings):
/// `K̄_eq = (K̄xx C̄yy + K̄yy C̄xx − K̄xy C̄yx − K̄yx C̄xy)/(C̄xx + C̄yy)`,
/// `γ² = ((K̄xx − K̄_eq)(K̄yy − K̄_eq) − K̄xy K̄yx)/(C̄xx C̄yy − C̄xy C̄yx)`, `M̄_c = K̄_eq/γ²`.
pub fn stability(k: [[f64; 2]; 2], c: [[f64; 2]; 2]) -> Stability {
    let (kxx, kxy, kyx, kyy) = (k[0][0], k[0][1], k[1][0], k[1][1]);
    let (cxx, cxy, cyx, cyy) = (c[0][0], c[0][1], c[1][0], c[1][1]);
    let keq = (kxx * cyy + kyy * cxx - kxy * cyx - kyx * cxy) / (cxx + cyy);
    let g2 = ((kxx - keq) * (kyy - keq) - kxy * kyx) / (cxx * cyy - cxy * cyx);
    let critical = (g2 > 0.0 && keq > 0.0 && g2.is_finite() && keq.is_finite()).then(|| keq / g2);
    Stability { whirl_ratio: if g2 > 0.0 && g2.is_finite() { g2.sqrt() } else { 0.0 }, critical_mass: critical, equivalent_stiffness: if keq.is_finite() { keq } else { 0.0 } }
}

/// Dynamic coefficients at the equilibrium of `analysis` (found by [`super::analyse`] with the
/// same bearing and settings). `workspace` is reused: when it holds the equilibrium pressure
/// (the one given to `analyse`) the equilibrium is not solved again.
pub fn coefficients(
    bearing: &Bearing,
    analysis: &Analysis,
    settings: &Settings,
    workspace: &mut Workspace,
    observer: &dyn Observer,
) -> Result<Coefficients, SolveError> {
    let (stiffness, damping, convergence) = matrices::<2>(bearing, analysis, settings, workspace, observer)?;
    Ok(Coefficients { stiffness, damping, convergence })
}

/// Stiffness and damping of the journal's four small motions at an equilibrium: the two
/// translations of [`Coefficients`] and the two tilts of the journal axis about the mid-plane.
///
/// Coordinates `q = (X, Y, Γx, Γy)`: the mid-plane centre `X = x/c`, `Y = y/c` in the frame of
/// [`Coefficients`], and the tilts `Γx = ψx L/c`, `Γy = ψy L/c`, where `ψx = dx/dz` and `ψy = dy/dz`
/// are the slopes of the journal axis (rad): a tilt moves the centre of the cross-section at
/// `Z = z/L` by `(Z − ½) Γ` clearances, so `Γ` is the difference of the displacements of the two
/// edges. (Seed 002's misalignment is such a tilt: `Γx = 2 Δv0`, `Γy = −2 Δh0`.)
/// Generalised forces `Q = (F̄x, F̄y, M̄x, M̄y)`, conjugate to `q`: the film force and its moments
/// about the mid-plane, `M̄x = ∫∫ P cos θ (Z − ½) dθ dZ` (the lever in `L` units), so
/// `Mx = ∫ (z − L/2) dFx`. For small motions `ΔQ = −K Δq − C Δq'` with `q' = dq/d(ωt)`.
/// Scaling as in [`Coefficients`], with a factor `L` for each moment row and each tilt column.
///
/// Method: four adjoint solves (one per generalised force) instead of two, dotted with eight
/// right-hand sides; the tilt sources are the translation's with the axial shape `Z − ½`
/// ([`super::multigrid::Level::linearised_sources`]). The first two rows and columns are
/// [`coefficients`] bit for bit from the same workspace state.
#[derive(Debug, Clone, PartialEq)]
pub struct TiltCoefficients {
    /// `−∂Q_i/∂q_j`, rows and columns `(X, Y, Γx, Γy)`.
    pub stiffness: [[f64; 4]; 4],
    /// `−∂Q_i/∂q'_j`.
    pub damping: [[f64; 4]; 4],
    /// The four adjoint linear solves: CG iterations (total), the largest relative residual, the tolerance.
    pub convergence: Convergence,
}

impl TiltCoefficients {
    /// `K̄ = K/W̄` and `C̄ = C/W̄` in the coordinates `q` for the film load `W̄`.
    pub fn dimensionless(&self, load: f64) -> Option<([[f64; 4]; 4], [[f64; 4]; 4])> {
        if !(load > 0.0) {
            return None;
        }
        let s = |m: [[f64; 4]; 4]| m.map(|row| row.map(|v| v / load));
        Some((s(self.stiffness), s(self.damping)))
    }
    /// The translations' block: [`coefficients`]' numbers.
    pub fn translation(&self) -> Coefficients {
        let block = |m: &[[f64; 4]; 4]| [[m[0][0], m[0][1]], [m[1][0], m[1][1]]];
        Coefficients { stiffness: block(&self.stiffness), damping: block(&self.damping), convergence: self.convergence.clone() }
    }
}

/// [`TiltCoefficients`] at the equilibrium of `analysis` (as [`coefficients`], twice the
/// linear solves).
pub fn tilt_coefficients(
    bearing: &Bearing,
    analysis: &Analysis,
    settings: &Settings,
    workspace: &mut Workspace,
    observer: &dyn Observer,
) -> Result<TiltCoefficients, SolveError> {
    let (stiffness, damping, convergence) = matrices::<4>(bearing, analysis, settings, workspace, observer)?;
    Ok(TiltCoefficients { stiffness, damping, convergence })
}

/// The `N × N` stiffness and damping in the coordinates `(X, Y, Γx, Γy)[..N]` (N = 2 or 4).
#[allow(clippy::type_complexity)]
fn matrices<const N: usize>(
    bearing: &Bearing,
    analysis: &Analysis,
    settings: &Settings,
    workspace: &mut Workspace,
    observer: &dyn Observer,
) -> Result<([[f64; N]; N], [[f64; N]; N], Convergence), SolveError> {
    let film = analysis.film;
    let h = workspace.hierarchy_mut(bearing, settings);
    let (_, theta0) = bearing.groove_angle(analysis.attitude);
    // the equilibrium pressure and its cavitation set on the finest grid (warm start)
    h.set_film(&film, theta0);
    let rep = h.solve_lcp(0, settings.pressure_tolerance, 60, settings.max_cycles);
    if !rep.converged {
        return Err(SolveError::NotConverged {
            solver: "journal pressure (active set + multigrid CG)",
            iterations: rep.cycles,
            residual: rep.residual,
            tolerance: settings.pressure_tolerance,
            history: vec![rep.residual],
        });
    }
    observer.check()?;
    let alpha = bearing.alpha();
    let l = &h.levels[0];
    let n = l.u.len();
    let p0 = l.u.clone();
    let (nt, nz, ds, dz) = (l.nt, l.nz, l.dt * l.dz, l.dz);
    // The generalised forces are linear in the pressure, `Q_i = g_iᵀ P` (seed 002 eq. (6)-(7)
    // as quadrature over the interior rows; a moment row has the lever `Z − ½`), and the
    // perturbed pressure is `δP = A_II⁻¹ b` for each right-hand side `b` (displacement and
    // velocity of each coordinate). `A_II` is symmetric (face conductances shared by both
    // nodes), so `g_iᵀ A_II⁻¹ b = (A_II⁻¹ g_i)ᵀ b`: N adjoint solves `y_i = A_II⁻¹ g_i` (one per
    // generalised force) give all 2N² coefficients as dot products — the same numbers as 2N
    // forward solves, at half the linear solves.
    let lever = |c: usize, j: usize| if c < 2 { 1.0 } else { j as f64 * dz - 0.5 };
    let mut g: Vec<Vec<f64>> = vec![vec![0.0; n]; N];
    for (c, gc) in g.iter_mut().enumerate() {
        for j in 1..nz - 1 {
            for i in 0..nt {
                let trig = if c % 2 == 0 { l.cos_n[i] } else { l.sin_n[i] };
                gc[j * nt + i] = if c < 2 { trig * ds } else { trig * ds * lever(c, j) };
            }
        }
    }
    // linear solves to the pressure tolerance (relative residual of each adjoint problem)
    let tol = settings.pressure_tolerance.max(1e-12);
    let one = |_: f64| 1.0;
    let tilt = |z: f64| z - 0.5;
    let mut disp: Vec<Vec<f64>> = vec![vec![0.0; n]; N];
    let mut vel: Vec<Vec<f64>> = vec![vec![0.0; n]; N];
    for (c, (d, v)) in disp.iter_mut().zip(vel.iter_mut()).enumerate() {
        let shape: &dyn Fn(f64) -> f64 = if c < 2 { &one } else { &tilt };
        h.levels[0].linearised_sources(&film, alpha, c % 2, shape, &p0, d, v);
    }
    let mut y = vec![0.0; n];
    let mut k = [[0.0; N]; N];
    let mut c = [[0.0; N]; N];
    let (mut iters, mut worst) = (0u32, 0.0f64);
    let dot = |a: &[f64], b: &[f64]| a.iter().zip(b).map(|(x, y)| x * y).sum::<f64>();
    for comp in 0..N {
        let (it, ok, res) = h.solve_free(0, &g[comp], &mut y, tol, settings.max_cycles);
        iters += it;
        worst = worst.max(res);
        if !ok {
            return Err(SolveError::NotConverged {
                solver: "journal dynamic coefficients (linearised Reynolds, multigrid CG)",
                iterations: it,
                residual: res,
                tolerance: tol,
                history: vec![res],
            });
        }
        // K_ij = −∂Q_i/∂q_j = −y_iᵀ b_j (the sources vanish at fixed nodes, `y` too)
        for dir in 0..N {
            k[comp][dir] = -dot(&y, &disp[dir]);
            c[comp][dir] = -dot(&y, &vel[dir]);
        }
        observer.check()?;
    }
    ensure_finite("dynamic coefficients", k.iter().chain(c.iter()).flatten())?;
    Ok((k, c, Convergence { iterations: iters, residual: worst, tolerance: tol, termination: Termination::Converged }))
}
