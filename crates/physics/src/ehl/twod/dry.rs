//! The dry, frictionless contact of two elastic bodies over the 2-D EHL grid: the limit of the
//! EHL problem as the film vanishes (issue 16, the dry limit of the crowned roller and of point
//! contacts).
//!
//! In the Hertzian units of [`super`] (the same scales, domain, nodes and undeformed gap
//! `X²/2 + S(Y)` as the EHL solver: [`super::geometry`]), find `P ≥ 0` at the interior nodes and
//! the rigid-body term `H0` with the gap `G = H0 + X²/2 + S(Y) + W[P] ≥ 0`, `P·G = 0` and
//! `∫∫ P dX dY = F/(p_ref a²)`; `W` is the DC-FFT deflection ([`super::elastic::Deflection`],
//! seed 000 eq. 3's `2/(πE') ∫∫ p/r`), `P = 0` on the domain boundary as in the EHL solver. The
//! approach of distant points is `δ = −H0 a²/R_x` (for Hertz, Johnson eq. 3.41/4.39: `a²/R` on a
//! circle).
//!
//! # Method
//! The constrained conjugate-gradient method of Polonsky & Keer (Wear 231 (1999) 206–219,
//! section 3, steps 1–11): conjugate directions over the current contact set with the mean gap
//! removed (the load constraint's multiplier is `−H0`), negative pressures dropped, the nodes
//! with a negative gap outside the contact added by a steepest-descent step (the conjugacy is
//! reset then), and the pressure rescaled to the load. Each iteration costs two DC-FFT products.
//! Stopping: the relative pressure change `Σ|P − P_old| / Σ P` of one iteration below the
//! tolerance (the paper's criterion).

use super::elastic::Deflection;
use super::geometry::{domain, node_grid, scales, NodeGrid};
use super::solver::{edge_peak_node, frame_sign, mirror_tie, validate};
use super::{Ehl2dInput, Ehl2dOptions, Fields2d, Geometry2d, Located};
use crate::{ensure_finite, Convergence, Observer, SolveError, Termination};

/// Tolerance and iteration cap of the dry solve (the grid is the EHL options').
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DryOptions {
    /// Largest accepted relative pressure change of one iteration, `Σ|P − P_old| / Σ P` (> 0).
    pub tolerance: f64,
    /// Most conjugate-gradient iterations (≥ 1).
    pub max_iterations: u32,
}

impl Default for DryOptions {
    fn default() -> Self {
        DryOptions { tolerance: 1e-10, max_iterations: 2000 }
    }
}

/// The dry contact on the EHL grid.
#[derive(Debug, Clone, PartialEq)]
pub struct DrySolution {
    /// The EHL solver's length scale `a`, m, and pressure scale, Pa ([`super::Ehl2dSolution`]).
    pub hertz_half_width: f64,
    pub hertz_pressure: f64,
    /// Largest pressure and where.
    pub max_pressure: Located,
    /// Finite line contacts: the largest off-centre maximum of `max_x p(x, y)` along the roller
    /// above the centre's pressure (as [`super::Ehl2dSolution::edge_pressure_peak`]).
    pub edge_pressure_peak: Option<Located>,
    /// Area of the nodes' cells with a positive pressure, m².
    pub contact_area: f64,
    /// Mutual approach of distant points, m (`−H0 a²/R_x`).
    pub approach: f64,
    /// Load carried by the pressure, N.
    pub load: f64,
    pub nx: usize,
    pub ny: usize,
    /// Pressure (Pa) and gap (m, `film`: zero in the contact, ≥ 0 at the interior nodes; the
    /// boundary's pressure is 0 by the boundary condition, as in the EHL solver — a roller's end
    /// faces — so its gap is not constrained) on the EHL solver's nodes (m, the same frame and
    /// orientation as its fields).
    pub fields: Fields2d,
    /// Iterations, the last relative pressure change, the tolerance.
    pub convergence: Convergence,
}

/// Solves the dry contact of `input` (its load, geometry and modulus; the speed and lubricant
/// only size the domain, as in the EHL solve) on the nodes the EHL solver uses for `grid` (its
/// `nx`, `ny`, `inlet`, `outlet`, `side`; its tolerance and caps are the EHL solver's).
pub fn solve_dry(input: &Ehl2dInput, grid: &Ehl2dOptions, options: &DryOptions, observer: &dyn Observer) -> Result<DrySolution, SolveError> {
    validate(input, grid)?;
    if !(options.tolerance.is_finite() && options.tolerance > 0.0) {
        return Err(SolveError::invalid("DryOptions.tolerance", "must be finite and > 0"));
    }
    if options.max_iterations == 0 {
        return Err(SolveError::invalid("DryOptions.max_iterations", "must be ≥ 1"));
    }
    let s = scales(input)?;
    let d = domain(input, grid, &s);
    let (nx, ny) = (grid.nx, grid.ny);
    let g = node_grid(input, &s, d, nx, ny);
    let mut defl = Deflection::new(nx, ny, g.dx, g.dy, s.c_def);
    let cell = g.dx * g.dy;
    let mut cg = ConjugateGradient::new(&g, nx, ny, s.load / cell);
    let mut history = Vec::new();
    let mut change = f64::INFINITY;
    let mut iterations = 0;
    while iterations < options.max_iterations {
        if iterations % 50 == 0 {
            observer.check()?;
        }
        change = cg.iterate(&mut defl)?;
        iterations += 1;
        history.push(change);
        if change <= options.tolerance {
            break;
        }
    }
    if !(change <= options.tolerance) {
        let keep = history.len().saturating_sub(20);
        return Err(SolveError::NotConverged { solver: "dry 2-D contact (Polonsky–Keer conjugate gradient)", iterations, residual: change, tolerance: options.tolerance, history: history.split_off(keep) });
    }
    let (gap, h0) = cg.gap(&mut defl);
    let film_scale = s.a * s.a / s.rx;
    let sign = frame_sign(input);
    let p = &cg.p;
    let kmax = mirror_tie(nx, ny, (0..nx * ny).max_by(|&a, &b| p[a].total_cmp(&p[b])).unwrap_or(0), p);
    let loc = |k: usize| Located { value: p[k] * s.p_ref, x: sign * g.x[k % nx] * s.a, y: g.y[k / nx] * s.a };
    let edge = match input.geometry {
        Geometry2d::Finite { .. } => edge_peak_node(&g.x, &g.y, p, s.ky).map(loc),
        Geometry2d::Point { .. } => None,
    };
    let fields = Fields2d {
        x: g.x.iter().map(|x| sign * x * s.a).collect(),
        y: g.y.iter().map(|y| y * s.a).collect(),
        pressure: p.iter().map(|v| v * s.p_ref).collect(),
        film: gap.iter().map(|v| v * film_scale).collect(),
    };
    let sol = DrySolution {
        hertz_half_width: s.a,
        hertz_pressure: s.p_ref,
        max_pressure: loc(kmax),
        edge_pressure_peak: edge,
        contact_area: p.iter().filter(|v| **v > 0.0).count() as f64 * cell * s.a * s.a,
        approach: -h0 * film_scale,
        load: p.iter().sum::<f64>() * cell * s.p_ref * s.a * s.a,
        nx,
        ny,
        fields,
        convergence: Convergence { iterations, residual: change, tolerance: options.tolerance, termination: Termination::Converged },
    };
    ensure_finite("dry 2-D contact", [sol.approach, sol.load, sol.contact_area, sol.max_pressure.value].iter())?;
    ensure_finite("dry 2-D contact fields", sol.fields.pressure.iter().chain(&sol.fields.film))?;
    Ok(sol)
}

/// The state of Polonsky & Keer's iteration: the pressure `P`, the conjugate direction `T`, the
/// previous squared gap norm and whether the last step kept the conjugacy (their `δ`).
struct ConjugateGradient<'a> {
    geom: &'a [f64],
    /// Interior nodes (the boundary's pressure is 0).
    interior: Vec<bool>,
    /// Target `Σ P` over the nodes (the load over the cell area).
    total: f64,
    p: Vec<f64>,
    t: Vec<f64>,
    u: Vec<f64>,
    r: Vec<f64>,
    g_old: f64,
    conjugate: bool,
}

impl<'a> ConjugateGradient<'a> {
    /// Starts from a uniform pressure over the interior nodes where the undeformed gap is within
    /// the range of a Hertzian contact of the domain's scale (`X²/2 + S ≤ 1`, or everywhere if
    /// that is empty), scaled to the load.
    fn new(g: &'a NodeGrid, nx: usize, ny: usize, total: f64) -> Self {
        let interior: Vec<bool> = (0..nx * ny).map(|k| (1..nx - 1).contains(&(k % nx)) && (1..ny - 1).contains(&(k / nx))).collect();
        let low = g.geom.iter().zip(&interior).any(|(v, &i)| i && *v <= 1.0);
        let mut p: Vec<f64> = g.geom.iter().zip(&interior).map(|(v, &i)| if i && (!low || *v <= 1.0) { 1.0 } else { 0.0 }).collect();
        let sum: f64 = p.iter().sum();
        p.iter_mut().for_each(|v| *v *= total / sum);
        let n = nx * ny;
        ConjugateGradient { geom: &g.geom, interior, total, p, t: vec![0.0; n], u: vec![0.0; n], r: vec![0.0; n], g_old: 1.0, conjugate: false }
    }

    /// The gap `X²/2 + S + W[P]` minus its mean over the contact set, and that mean (`−H0`).
    fn centred_gap(&mut self, defl: &mut Deflection) -> (Vec<f64>, f64) {
        defl.apply(&self.p, &mut self.u);
        let mut gap: Vec<f64> = self.geom.iter().zip(&self.u).map(|(a, b)| a + b).collect();
        let mean = mean_over_contact(&gap, &self.p);
        gap.iter_mut().for_each(|v| *v -= mean);
        (gap, mean)
    }

    /// One iteration (Polonsky & Keer 1999, steps 2–11); returns the relative pressure change.
    fn iterate(&mut self, defl: &mut Deflection) -> Result<f64, SolveError> {
        let (gap, _) = self.centred_gap(defl);
        // Steps 3–4: the new conjugate direction over the contact set.
        let g_norm: f64 = gap.iter().zip(&self.p).filter(|(_, p)| **p > 0.0).map(|(g, _)| g * g).sum();
        let beta = if self.conjugate { g_norm / self.g_old } else { 0.0 };
        for k in 0..self.p.len() {
            self.t[k] = if self.p[k] > 0.0 { gap[k] + beta * self.t[k] } else { 0.0 };
        }
        self.g_old = g_norm;
        // Steps 5–6: the step length along T.
        defl.apply(&self.t, &mut self.r);
        let r_mean = mean_over_contact(&self.r, &self.p);
        let (mut num, mut den) = (0.0, 0.0);
        for k in 0..self.p.len() {
            if self.p[k] > 0.0 {
                num += gap[k] * self.t[k];
                den += (self.r[k] - r_mean) * self.t[k];
            }
        }
        let tau = if den > 0.0 { num / den } else { 0.0 };
        // Steps 7–9: the step, negative pressures dropped, penetrated nodes outside the contact
        // added (and the conjugacy reset).
        let old = self.p.clone();
        for (p, t) in self.p.iter_mut().zip(&self.t) {
            if *p > 0.0 {
                *p = (*p - tau * t).max(0.0);
            }
        }
        let mut entered = false;
        for k in 0..self.p.len() {
            if self.interior[k] && self.p[k] == 0.0 && gap[k] < 0.0 {
                self.p[k] = -tau * gap[k];
                entered = true;
            }
        }
        self.conjugate = !entered;
        // Step 10: the load.
        let sum: f64 = self.p.iter().sum();
        if !(sum.is_finite() && sum > 0.0) {
            return Err(SolveError::NonFinite { quantity: "dry 2-D contact pressure".into() });
        }
        self.p.iter_mut().for_each(|v| *v *= self.total / sum);
        // Step 11: the relative change.
        Ok(self.p.iter().zip(&old).map(|(a, b)| (a - b).abs()).sum::<f64>() / self.total)
    }

    /// The converged gap `H0 + X²/2 + S + W` (≥ 0, zero in the contact to the tolerance) and `H0`.
    fn gap(&mut self, defl: &mut Deflection) -> (Vec<f64>, f64) {
        let (gap, mean) = self.centred_gap(defl);
        (gap, -mean)
    }
}

/// Mean of `f` over the nodes with a positive pressure (0 when there are none).
fn mean_over_contact(f: &[f64], p: &[f64]) -> f64 {
    let (sum, n) = f.iter().zip(p).filter(|(_, p)| **p > 0.0).fold((0.0, 0usize), |(s, n), (v, _)| (s + v, n + 1));
    if n > 0 {
        sum / n as f64
    } else {
        0.0
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::lubricant::Lubricant;
    use crate::Silent;

    fn ball() -> Ehl2dInput {
        Ehl2dInput { load: 100.0, geometry: Geometry2d::Point { rx: 0.01, ry: 0.01 }, effective_modulus: 2.3e11, entrainment_velocity: 1.0, lubricant: Lubricant::SEED000, temperature: 313.0 }
    }

    #[test]
    fn bad_options_and_the_iteration_cap_fail_typed() {
        let grid = Ehl2dOptions { nx: 33, ny: 33, ..Default::default() };
        let bad = DryOptions { tolerance: 0.0, ..Default::default() };
        assert!(matches!(solve_dry(&ball(), &grid, &bad, &Silent), Err(SolveError::InvalidInput { field, .. }) if field == "DryOptions.tolerance"));
        let capped = DryOptions { max_iterations: 2, ..Default::default() };
        assert!(matches!(solve_dry(&ball(), &grid, &capped, &Silent), Err(SolveError::NotConverged { iterations: 2, .. })));
        let few = Ehl2dOptions { nx: 5, ..grid };
        assert!(matches!(solve_dry(&ball(), &few, &DryOptions::default(), &Silent), Err(SolveError::InvalidInput { field, .. }) if field == "Ehl2dOptions.nx"));
    }
}
