//! Seed 003 §3.5 redone with the 2-D finite-line solver (issue 42): the runs of Table 3 and the
//! regressions eq. 17 (central film) and eq. 18 (side-constriction film).
//!
//! # The groups (seed 003 nomenclature) and how a condition becomes the solver's input
//! `W* = W/(ERL)`, `U* = uη/(ER)`, `G* = Eα`, `h* = h/R` (eq. 11, 13: lengths over `R`), and
//! `w_s*` "the squeeze-roll speed ratio". Choices (the paper does not state them; the same as
//! [`crate::ehl::formulas::regressions::seed003`]):
//! * `E` is the reduced modulus `E' = 2/Σ(1−ν²)/E` (only it puts steel and mineral oils in the
//!   G* range 5700–9650);
//! * `w_s* = ḣ/u`, the approach velocity over the entrainment velocity, negative on approach —
//!   Table 3's range −0.005…0 and eq. 17's `e^(−96.775 w_s*)` then thicken an approaching film.
//!   (Eq. 9's scaling would make `w_s* = ḣη/(ER)`, the scale of U*; with Table 3's values that is
//!   an approach of ~10⁸ m/s, so the nomenclature's ratio is taken.)
//! * The fixed quantities `R`, `E'`, `η0` and the contact length `L` ([`Seed003Setup`]) are not
//!   given for Table 3; G* is varied through `α`, U* through `u`, W* through `W`. The cam's face
//!   is shortened to a contact of 53–215 Hertz half-widths (the default `L = 0.2 R`): its central
//!   and side films depend on `L` only through `L/b`, weakly once it is large (the base run:
//!   +3.3 % from L/b 123 to 246).
//! * The cam is "unprofiled laterally" (§3.3): a straight roller with sharp ends (`p = 0` at the
//!   end faces, no relief), Barus viscosity (eq. 8's reduced pressure), Dowson–Higginson density
//!   (eq. 10), isothermal.
//! * `h0*` is the film at the contact centre (point A, eq. 11), `h_sc*` the smallest film (point C,
//!   the side constriction at the rear exit, §3.4).
//!
//! # What the runs give (tests in `tests.rs`, docs/seeds.md)
//! Fully flooded (the default setup) the films fall with W* and hardly feel G* — Table 3's
//! groups put the contact at Moes M 0.07–1.1, thick and nearly rigid–isoviscous. With the inlet
//! boundary a fixed 7 half-widths upstream (a starved inlet growing with the load) the refit has
//! eq. 17's W* and U* exponents; its G* exponent stays ≈ 0.2.
//!
//! # Prescribed squeeze
//! The 2-D solver takes squeeze as history ([`super::Squeeze2d`]: a previous level and `Δt`). A
//! uniform approach velocity `v = −w_s* u` is the fixed point `ρ̄h_prev = ρ̄h + vΔt` (the previous
//! level's mass per area set from the latest solution's): the backward-Euler term is then `−v` at
//! every node. With `Δt` many passage times `a/u` the coupling through `ρ̄h` is `O(1/Δt)` and the
//! fixed point settles in two or three solves ([`Seed003Setup::passages`]).

use super::{solve_from, solve_transient, Ehl2dInput, Ehl2dOptions, Ehl2dSolution, Geometry2d, Kept2d, Squeeze2d, Warm2d};
use crate::geometry::{Crown, CrownProfile};
use crate::lubricant::{DensityModel, Lubricant, ViscosityModel};
use crate::{Convergence, Observer, SolveError, Termination};

/// One condition of seed 003 Table 3, dimensionless (module docs).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Seed003Condition {
    /// `W* = W/(E'RL)`.
    pub load: f64,
    /// `U* = uη0/(E'R)`.
    pub speed: f64,
    /// `G* = αE'`.
    pub materials: f64,
    /// `w_s* = ḣ/u` (negative: approach).
    pub squeeze: f64,
}

/// The fixed dimensional quantities the conditions are mapped with, and the numerics.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Seed003Setup {
    /// Reduced radius `R`, m.
    pub reduced_radius: f64,
    /// `E'`, Pa.
    pub effective_modulus: f64,
    /// `η0`, Pa·s.
    pub viscosity: f64,
    /// Contact length `L`, m.
    pub length: f64,
    /// The 2-D solver's grid, tolerance and cap.
    pub options: Ehl2dOptions,
    /// The squeeze term's time step in passage times `a/u` (> 0; large: the fixed point settles
    /// fast).
    pub passages: f64,
    /// Tolerance of the squeeze fixed point: relative change of the central film.
    pub tolerance: f64,
    /// Most fixed-point solves.
    pub max_iterations: u32,
}

impl Default for Seed003Setup {
    /// `R = 20 mm`, steel on steel (`E' = 230.8 GPa`: E = 210 GPa, ν = 0.3), `η0 = 0.04 Pa·s`,
    /// `L = 4 mm` (`L/b` 53–215 over Table 3's W*), 129 × 257 nodes (x × along the contact) on
    /// an inlet of 40 and an outlet of 12 Hertz half-widths (Table 3's films are thick, M 0.1–1:
    /// the pressure builds far upstream; the solver's default inlet of ≤ 12 half-widths thins
    /// the base run by 16 % on L = 1 mm), `Δt = 1000 a/u`, fixed point to 1e-4 in at most 8 solves.
    fn default() -> Self {
        let options = Ehl2dOptions { nx: 129, ny: 257, inlet: Some(40.0), outlet: Some(12.0), grid_tolerance: 1.0, grid_check: false, ..Ehl2dOptions::default() };
        Seed003Setup { reduced_radius: 0.02, effective_modulus: 2.308e11, viscosity: 0.04, length: 4e-3, options, passages: 1e3, tolerance: 1e-4, max_iterations: 8 }
    }
}

/// The solved film of one condition.
#[derive(Debug, Clone, PartialEq)]
pub struct Seed003Film {
    /// `h0* = h_c/R` (point A).
    pub central: f64,
    /// `h_sc* = h_min/R` (point C, the side constriction).
    pub side: f64,
    /// The 2-D solution (the last fixed-point solve under squeeze).
    pub solution: Ehl2dSolution,
    /// The squeeze fixed point: solves and the last relative change of the central film
    /// (closed form, 0 solves, without squeeze).
    pub fixed_point: Convergence,
}

fn positive(v: f64, field: &str, unit: &str) -> Result<f64, SolveError> {
    if v.is_finite() && v > 0.0 {
        Ok(v)
    } else {
        Err(SolveError::invalid(field, format!("must be finite and > 0 ({unit})")))
    }
}

/// The solver's input for a condition: `α = G*/E'`, `u = U* E'R/η0`, `W = W* E'RL` on a straight
/// sharp-ended roller of length `L` (module docs).
pub fn seed003_input(c: &Seed003Condition, setup: &Seed003Setup) -> Result<Ehl2dInput, SolveError> {
    let (r, ep) = (positive(setup.reduced_radius, "Seed003Setup.reduced_radius", "m")?, positive(setup.effective_modulus, "Seed003Setup.effective_modulus", "Pa")?);
    let (eta, l) = (positive(setup.viscosity, "Seed003Setup.viscosity", "Pa·s")?, positive(setup.length, "Seed003Setup.length", "m")?);
    let (w, u, g) = (positive(c.load, "Seed003Condition.load", "1")?, positive(c.speed, "Seed003Condition.speed", "1")?, positive(c.materials, "Seed003Condition.materials", "1")?);
    if !(c.squeeze.is_finite() && c.squeeze.abs() < 0.1) {
        return Err(SolveError::invalid("Seed003Condition.squeeze", "must be finite with |w_s*| < 0.1 (1)"));
    }
    let lubricant = Lubricant { viscosity: eta, pressure_viscosity: g / ep, viscosity_model: ViscosityModel::Barus, density_model: DensityModel::DowsonHigginson, ..Lubricant::SEED000 };
    let crown = Crown { length: l, middle_length: l, crown_height: 0.0, end_radius: r, profile: CrownProfile::Convex };
    Ok(Ehl2dInput {
        // seed 003 nomenclature: W* = W/(ERL), U* = uη/(ER), G* = Eα with E = E'
        load: w * ep * r * l,
        geometry: Geometry2d::Finite { rx: r, crown },
        effective_modulus: ep,
        entrainment_velocity: u * ep * r / eta,
        lubricant,
        temperature: lubricant.reference_temperature,
    })
}

/// Solves one condition: the steady problem, then (with squeeze) the prescribed-approach fixed
/// point of the module docs. Errors: the solver's, or `NotConverged` when the fixed point does
/// not settle within `max_iterations` solves.
pub fn seed003_run(c: &Seed003Condition, setup: &Seed003Setup, observer: &dyn Observer) -> Result<Seed003Film, SolveError> {
    let input = seed003_input(c, setup)?;
    positive(setup.passages, "Seed003Setup.passages", "a/u")?;
    positive(setup.tolerance, "Seed003Setup.tolerance", "1")?;
    let r = setup.reduced_radius;
    let (s0, w0) = solve_from(&input, &setup.options, None, observer)?;
    let film = |solution: Ehl2dSolution, fixed_point: Convergence| Seed003Film { central: solution.central_film / r, side: solution.min_film.value / r, solution, fixed_point };
    if c.squeeze == 0.0 {
        return Ok(film(s0, Convergence::closed_form()));
    }
    // w_s* = ḣ/u: the approach velocity v = −ḣ (m/s, positive on approach).
    let v = -c.squeeze * input.entrainment_velocity;
    let (s, _, fixed_point) = solve_prescribed_squeeze(&input, &setup.options, (&s0, &w0), v, setup.passages, setup.tolerance, setup.max_iterations, observer)?;
    Ok(film(s, fixed_point))
}

/// A uniform approach velocity `approach` (m/s, positive: the surfaces close) imposed on a 2-D
/// problem whose steady solution is `steady`: the fixed point `ρ̄h_prev = ρ̄h + vΔt` of
/// backward-Euler steps with `Δt = passages · a/u_m` (module docs), to a relative change of the
/// central film below `tolerance` within `max_iterations` solves. Returns the solution, its warm
/// start and the fixed point's report; `NotConverged` when it does not settle.
#[allow(clippy::too_many_arguments)]
pub fn solve_prescribed_squeeze(input: &Ehl2dInput, options: &Ehl2dOptions, steady: (&Ehl2dSolution, &Warm2d), approach: f64, passages: f64, tolerance: f64, max_iterations: u32, observer: &dyn Observer) -> Result<(Ehl2dSolution, Warm2d, Convergence), SolveError> {
    if !approach.is_finite() {
        return Err(SolveError::invalid("approach", "must be finite (m/s)"));
    }
    positive(passages, "passages", "a/u")?;
    positive(tolerance, "tolerance", "1")?;
    let dt = passages * steady.0.hertz_half_width / input.entrainment_velocity.abs();
    let (mut latest, mut last) = (steady.1.clone(), steady.0.central_film);
    let mut kept = Kept2d::default();
    let mut history = Vec::new();
    for it in 1..=max_iterations.max(1) {
        let mut previous = latest.clone();
        // The fixed point ρ̄h_prev = ρ̄h + vΔt: the squeeze term −(ρ̄h − ρ̄h_prev)/Δt is v.
        previous.mass.iter_mut().for_each(|m| *m += approach * dt);
        let (s, next) = solve_transient(input, options, Squeeze2d { previous: &previous, time_step: dt }, Some(&latest), None, &mut kept, observer)?;
        let change = (s.central_film - last).abs() / s.central_film;
        history.push(change);
        last = s.central_film;
        latest = next;
        if change < tolerance {
            return Ok((s, latest, Convergence { iterations: it, residual: change, tolerance, termination: Termination::Converged }));
        }
    }
    Err(SolveError::NotConverged { solver: "prescribed squeeze", iterations: max_iterations, residual: *history.last().unwrap_or(&f64::INFINITY), tolerance, history })
}

/// Which group a Table 3 run sweeps.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Seed003Group {
    /// The common base condition of the four sweeps.
    Base,
    Materials,
    Squeeze,
    Load,
    Speed,
}

/// `n` values from `lo` to `hi`, evenly spaced (`log`: in the logarithm).
fn spaced(lo: f64, hi: f64, n: usize, log: bool) -> Vec<f64> {
    (0..n)
        .map(|k| {
            let t = k as f64 / (n - 1) as f64;
            if log {
                (lo.ln() + t * (hi.ln() - lo.ln())).exp()
            } else {
                lo + t * (hi - lo)
            }
        })
        .collect()
}

/// Seed 003 Table 3 as runs: its ranges and numbers of values — G* 5700–9650 (4), w_s* −0.005–0
/// (5), W* 0.34e-6–5.6e-6 (6), U* 0.63e-11–3.3e-11 (8) — as one-factor sweeps through a common
/// base (W* 1.04e-6, U* 1.28e-11, G* 7017, w_s* 0: a value of each sweep). Choices: W* and U*
/// spaced evenly in the logarithm, G* and w_s* evenly; 23 values through one shared base are 20
/// runs (the paper says 18 and does not list them).
pub fn seed003_table3() -> Vec<(Seed003Group, Seed003Condition)> {
    let g = spaced(5700.0, 9650.0, 4, false);
    let s = spaced(-0.005, 0.0, 5, false);
    let w = spaced(0.34e-6, 5.6e-6, 6, true);
    let u = spaced(0.63e-11, 3.3e-11, 8, true);
    let base = Seed003Condition { load: w[2], speed: u[3], materials: g[1], squeeze: 0.0 };
    let mut runs = vec![(Seed003Group::Base, base)];
    runs.extend(g.iter().enumerate().filter(|(k, _)| *k != 1).map(|(_, &v)| (Seed003Group::Materials, Seed003Condition { materials: v, ..base })));
    runs.extend(s.iter().take(4).map(|&v| (Seed003Group::Squeeze, Seed003Condition { squeeze: v, ..base })));
    runs.extend(w.iter().enumerate().filter(|(k, _)| *k != 2).map(|(_, &v)| (Seed003Group::Load, Seed003Condition { load: v, ..base })));
    runs.extend(u.iter().enumerate().filter(|(k, _)| *k != 3).map(|(_, &v)| (Seed003Group::Speed, Seed003Condition { speed: v, ..base })));
    runs
}

/// A regression `h* = a W*^b U*^c G*^d e^(e w_s*)` (seed 003 eq. 17–18's form).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Seed003Fit {
    pub coefficient: f64,
    pub load: f64,
    pub speed: f64,
    pub materials: f64,
    pub squeeze: f64,
}

impl Seed003Fit {
    /// Seed 003 eq. (17), the central film.
    pub const EQ17: Seed003Fit = Seed003Fit { coefficient: 1.67, load: 0.059, speed: 0.541, materials: 0.421, squeeze: -96.775 };
    /// Seed 003 eq. (18), the side-constriction film.
    pub const EQ18: Seed003Fit = Seed003Fit { coefficient: 1150.0, load: -0.037, speed: 0.857, materials: 0.406, squeeze: -138.059 };

    /// `h*` at a condition.
    pub fn film(&self, c: &Seed003Condition) -> f64 {
        self.coefficient * (self.load * c.load.ln() + self.speed * c.speed.ln() + self.materials * c.materials.ln() + self.squeeze * c.squeeze).exp()
    }
}

/// Least squares of `ln h* = ln a + b ln W* + c ln U* + d ln G* + e w_s*` over the runs (normal
/// equations of the centred and scaled columns, Gaussian elimination with partial pivoting).
/// Errors: fewer than 5 runs, a non-positive film, or a group that does not vary.
pub fn seed003_fit(conditions: &[Seed003Condition], films: &[f64]) -> Result<Seed003Fit, SolveError> {
    let n = conditions.len();
    if n < 5 || films.len() != n {
        return Err(SolveError::invalid("seed003_fit.films", "needs at least 5 runs and one film per condition (1)"));
    }
    if !films.iter().all(|h| h.is_finite() && *h > 0.0) {
        return Err(SolveError::invalid("seed003_fit.films", "must be finite and > 0 (1)"));
    }
    let rows: Vec<[f64; 4]> = conditions.iter().map(|c| [c.load.ln(), c.speed.ln(), c.materials.ln(), c.squeeze]).collect();
    let y: Vec<f64> = films.iter().map(|h| h.ln()).collect();
    let nf = n as f64;
    let mean = |k: usize| rows.iter().map(|r| r[k]).sum::<f64>() / nf;
    let means = [mean(0), mean(1), mean(2), mean(3)];
    let y_mean = y.iter().sum::<f64>() / nf;
    let scale: Vec<f64> = (0..4).map(|k| (rows.iter().map(|r| (r[k] - means[k]).powi(2)).sum::<f64>() / nf).sqrt()).collect();
    if scale.iter().any(|s| !(*s > 1e-12 * (1.0 + means.iter().fold(0.0f64, |m, v| m.max(v.abs()))))) {
        return Err(SolveError::invalid("seed003_fit.conditions", "every group must vary over the runs (1)"));
    }
    let z = |r: &[f64; 4], k: usize| (r[k] - means[k]) / scale[k];
    // Normal equations [ZᵀZ | Zᵀy], 4 × 5.
    let mut m = [[0.0f64; 5]; 4];
    for (r, yi) in rows.iter().zip(&y) {
        for i in 0..4 {
            for j in 0..4 {
                m[i][j] += z(r, i) * z(r, j);
            }
            m[i][4] += z(r, i) * (yi - y_mean);
        }
    }
    for col in 0..4 {
        let pivot = (col..4).max_by(|&a, &b| m[a][col].abs().total_cmp(&m[b][col].abs())).unwrap_or(col);
        m.swap(col, pivot);
        if m[col][col].abs() < 1e-10 * nf {
            return Err(SolveError::invalid("seed003_fit.conditions", "the groups are linearly dependent over the runs (1)"));
        }
        for row in 0..4 {
            if row != col {
                let f = m[row][col] / m[col][col];
                for k in col..5 {
                    m[row][k] -= f * m[col][k];
                }
            }
        }
    }
    let beta: Vec<f64> = (0..4).map(|k| m[k][4] / m[k][k] / scale[k]).collect();
    let ln_a = y_mean - (0..4).map(|k| beta[k] * means[k]).sum::<f64>();
    let fit = Seed003Fit { coefficient: ln_a.exp(), load: beta[0], speed: beta[1], materials: beta[2], squeeze: beta[3] };
    crate::ensure_finite("seed003_fit", &[fit.coefficient, fit.load, fit.speed, fit.materials, fit.squeeze])?;
    Ok(fit)
}

/// The largest `|fit/h − 1|` over the runs, in per cent.
pub fn seed003_max_difference(fit: &Seed003Fit, conditions: &[Seed003Condition], films: &[f64]) -> f64 {
    conditions.iter().zip(films).map(|(c, h)| 100.0 * (fit.film(c) / h - 1.0).abs()).fold(0.0, f64::max)
}

#[cfg(test)]
mod tests;
