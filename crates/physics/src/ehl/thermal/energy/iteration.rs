//! The iteration of one energy solve: Gauss–Seidel sweeps with an adaptively under-relaxed
//! viscosity ([`EnergyIteration::Sweeps`]), or outer fixed-point steps of linear sweeps with
//! Anderson mixing ([`EnergyIteration::Anderson`]), to convergence or an accepted stall.

use super::convection::Convection;
use super::properties::FilmState;
use super::setup::EnergyGrid;
use super::sweep::{sweep, ColumnWork};
use super::*;

/// Iterate the energy equations from `field` (in place) with the film's properties in `film`.
/// Returns the sweeps taken and the last change (the sweep's, or the outer step's residual).
pub(super) fn iterate(g: &EnergyGrid, film: &mut FilmState, field: &mut TemperatureField) -> Result<(u32, f64), SolveError> {
    let options = g.options;
    let mut conv = Convection::new(g);
    let mut work = ColumnWork::new(g);
    let mut sweeps = 0;
    let mut converged = false;
    let mut progress = SweepProgress { last_change: f64::INFINITY, same_direction: f64::INFINITY };
    let mut outer = OuterStep { start: None, inner_sweeps: 0, inner_tolerance: 0.1, mixer: AndersonMixer::new(ANDERSON_DEPTH), best_residual: f64::INFINITY };
    while sweeps < options.max_sweeps {
        let forward = sweeps % 2 == 0;
        sweeps += 1;
        if g.anderson && outer.start.is_none() {
            // A new outer step: the film's properties once at the current field, then frozen.
            film.update_all(g, field);
            outer.start = Some(field.clone());
            outer.inner_sweeps = 0;
        }
        if !(g.anderson && outer.inner_sweeps > 0) {
            conv.update(g, &film.columns);
        }
        let change = sweep(g, film, &conv, &mut work, field, outer.start.as_ref(), forward, sweeps)?;
        let done = if g.anderson { outer.after_sweep(g, field, change, &mut progress.last_change) } else { progress.after_sweep(film, change, options) };
        if done {
            converged = true;
            break;
        }
    }
    let last_change = progress.last_change;
    // A stall within 500× the tolerance is accepted (reported in the summary): the inlet's
    // recirculating backflow can keep a sweep-to-sweep wobble of a fraction of a kelvin far
    // upstream, where it does not move the films.
    // (Anderson: within 10× the tolerance; beyond, `energy` falls back to the sweeps.)
    let stall_factor = if g.anderson { 10.0 } else { 500.0 };
    let stalled = !converged && last_change < stall_factor * options.sweep_tolerance;
    if !converged && !stalled {
        return Err(SolveError::NotConverged {
            solver: "thermal ehl energy equation (Gauss–Seidel)",
            iterations: sweeps,
            residual: last_change,
            tolerance: options.sweep_tolerance,
            history: Vec::new(),
        });
    }
    Ok((sweeps, last_change))
}

/// The sweeps' last changes: the last one and the one before (in the same direction as the next).
struct SweepProgress {
    last_change: f64,
    same_direction: f64,
}

impl SweepProgress {
    /// After a sweep of [`EnergyIteration::Sweeps`] with the largest change `change`: the
    /// viscosity's under-relaxation adapted. Whether the sweeps have converged.
    fn after_sweep(&mut self, film: &mut FilmState, change: f64, options: &ThermalOptions) -> bool {
        // Adaptive under-relaxation of the viscosity: a sweep that changes more than the last
        // one reduces the step (strong shear heating localises in the hot mid-film and can
        // oscillate).
        // (Compared with the sweep in the same direction: alternating sweeps change by different
        // amounts.)
        if change > self.same_direction {
            film.relax = (film.relax * 0.7).max(0.2);
        } else {
            film.relax = (film.relax * 1.1).min(1.0);
        }
        self.same_direction = self.last_change;
        self.last_change = change;
        change < options.sweep_tolerance
    }
}

/// Anderson iteration state: the outer iterate x_k the current linear sweeps started from (its
/// temperatures linearise the shear heating), the sweeps of the current outer step and their
/// tolerance, the mixing history.
struct OuterStep {
    start: Option<TemperatureField>,
    inner_sweeps: u32,
    inner_tolerance: f64,
    mixer: AndersonMixer,
    best_residual: f64,
}

impl OuterStep {
    /// After a linear sweep with the largest change `change`: the outer step ends once the
    /// sweeps meet its tolerance (or its sweep cap), with `G(x_k)` the field then, its residual
    /// into `last_change` and the mixed next iterate into `field`. Whether the outer iteration
    /// has converged.
    fn after_sweep(&mut self, g: &EnergyGrid, field: &mut TemperatureField, change: f64, last_change: &mut f64) -> bool {
        let options = g.options;
        self.inner_sweeps += 1;
        if change >= self.inner_tolerance && self.inner_sweeps < ANDERSON_INNER_SWEEPS {
            return false;
        }
        // The outer step ends: G(x_k) = the field now; residual relative to the rise.
        let start = self.start.take().expect("set at the outer step's start");
        let x = start.flat();
        let gx = field.flat();
        let rise = g.scale_rise(field);
        let residual = x.iter().zip(&gx).fold(0.0f64, |m, (a, b)| m.max((b - a).abs())) / rise;
        *last_change = residual;
        if residual < options.sweep_tolerance {
            return true;
        }
        // A step that grows the residual well past the best restarts the mixing from G.
        // (The reference then restarts at this residual.)
        if residual > 4.0 * self.best_residual {
            self.mixer.clear();
            self.best_residual = residual;
        }
        self.best_residual = self.best_residual.min(residual);
        let mut next = self.mixer.next(&x, &gx);
        // Keep the mixed field within the range G spans (with a margin): an extrapolating
        // mix must not leave the physical range.
        let (lo, hi) = gx.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(l, u), &v| (l.min(v), u.max(v)));
        let margin = 0.25 * (hi - lo).max(1e-3);
        for v in next.iter_mut() {
            *v = v.clamp(lo - margin, hi + margin);
        }
        field.set_flat(&next);
        self.inner_tolerance = (0.01 * residual).max(0.01 * options.sweep_tolerance);
        false
    }
}
