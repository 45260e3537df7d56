//! One backward-Euler step of the transient problem ([`solve_transient`]).

use super::levels::warm_start;
use super::march::solve_level;
use super::solve::{conclude, frame_sign, Kept2d, Solved};
use super::validate::{validate, validate_squeeze};
use super::*;

/// Most halvings of a transient step that does not converge whole ([`solve_transient`]):
/// 1, 2, 4 or 8 backward-Euler sub-steps.
pub(super) const MAX_SUBSTEP_HALVINGS: u32 = 3;

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
            let (mut sol, next) = conclude(input, options, &s, d, solved, kept, kept_pattern, None, observer)?;
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

/// The dimensionless squeeze coefficient `κ = 12 η0 R_x²/(a² p_ref Δt)` of the backward-Euler
/// term `−κ (ρ̄H − (ρ̄H)_old)` (seed 000 eq. 2's `∂(ρh)/∂t`). Dimensions: the Poiseuille term
/// `∂/∂x(ρh³/(12η) ∂p/∂x)` is `ρ0 a⁴ p_ref/(12 η0 R_x³)·∂/∂X(ε ∂P/∂X)` (kg m⁻² s⁻¹) with
/// `h = H a²/R_x`, `x = X a`; the squeeze term `(ρ0 a²/R_x)(ρ̄H − (ρ̄H)_old)/Δt` (kg m⁻² s⁻¹);
/// their ratio `12 η0 R_x²/(a² p_ref Δt)` is dimensionless (Pa s · m² / (m² · Pa · s)). It is
/// the wedge's `λ = 12 η0 u_m R_x²/(a³ p_ref)` times the passage time `a/u_m` over `Δt`, the
/// pseudo-time `κ = λ/ΔT` of [`march`] with `ΔT = Δt u_m/a`; as the 1-D solver's
/// (`super::super::newton`, `12 η0 R²/(b² p_h Δt)`).
pub(super) fn squeeze_kappa(input: &Ehl2dInput, s: &Scales, time_step: f64) -> f64 {
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
pub(super) fn previous_mass(prob: &Problem, input: &Ehl2dInput, s: &Scales, w: &Warm2d) -> Vec<f64> {
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
