//! The coupled solve: the 2-D Reynolds solution with fixed generalized Reynolds factors and the
//! row energies, iterated to a fixed point ([`ThermalFiniteEngine`]).

use super::*;

/// Smallest step towards new factors after a failed 2-D solve.
const MIN_FACTOR_STEP: f64 = 1.0 / 32.0;

/// A reusable thermal finite-line solver: the 2-D solver's preconditioner, the last solution
/// (warm start), its factors and row temperatures survive between solves (a cam cycle keeps one).
#[derive(Debug, Default)]
pub struct ThermalFiniteEngine {
    kept: Kept2d,
    warm: Option<Warm2d>,
    factors: Option<Factors2d>,
    fields: Vec<Option<TemperatureField>>,
}

/// Solve one thermal finite-line or point problem (see [`super`]).
pub fn solve(input: &ThermalFiniteInput, options: &Ehl2dOptions, thermal: &ThermalOptions, observer: &dyn Observer) -> Result<ThermalFiniteSolution, SolveError> {
    ThermalFiniteEngine::new().solve(input, options, thermal, observer)
}

impl ThermalFiniteEngine {
    pub fn new() -> Self {
        Self::default()
    }

    /// The warm start the engine carries (the last solution's pressure in the solver's scales).
    pub fn warm(&self) -> Option<&Warm2d> {
        self.warm.as_ref()
    }

    /// Forget the carried solution (the next solve starts isothermal and cold).
    pub fn reset(&mut self) {
        *self = Self::default();
    }

    /// Solve one problem. The first 2-D solve starts from the engine's last solution and factors
    /// when it has them (a neighbouring problem's), else isothermal and cold; the isothermal
    /// films of the result are then reported only for a cold start.
    pub fn solve(&mut self, input: &ThermalFiniteInput, options: &Ehl2dOptions, thermal: &ThermalOptions, observer: &dyn Observer) -> Result<ThermalFiniteSolution, SolveError> {
        if !(thermal.film_points >= 3 && thermal.solid_points >= 4 && thermal.solid_depth > 0.0 && thermal.tolerance > 0.0 && thermal.max_iterations >= 1) {
            return Err(SolveError::invalid("ThermalOptions", "film_points ≥ 3, solid_points ≥ 4, solid_depth > 0, tolerance > 0, max_iterations ≥ 1"));
        }
        if !input.sliding_velocity.is_finite() {
            return Err(SolveError::invalid("ThermalFiniteInput.sliding_velocity", "must be finite"));
        }
        let opts = Ehl2dOptions { fields: true, ..*options };
        // Coupling iterations restart warm; the first solve's resolution check stands for them.
        let warm_opts = Ehl2dOptions { grid_check: false, ..opts };
        let carried = self.factors.take();
        let (mut sol, mut warm) = solve_factored(&input.ehl, &opts, carried.as_ref(), self.warm.as_ref(), &mut self.kept, observer)?;
        let grid_error = sol.grid_error;
        let iso = carried.is_none().then_some((sol.central_film, sol.min_film.value));
        let mut fields = std::mem::take(&mut self.fields);
        fields.resize(sol.ny, None);
        let mut used = carried;
        let (mut iterations, mut relax) = (0u32, 1.0f64);
        let mut history: Vec<f64> = Vec::new();
        let mut last_rise: Option<f64> = None;
        let mut termination = Termination::Converged;
        // The last energy pass: its fields start the next pass's sweeps.
        let mut last: Option<Pass> = None;
        loop {
            observer.check()?;
            let pass = energy_pass(input, &sol, thermal, last.as_ref().map_or(&fields, |p| &p.fields))?;
            iterations += 1;
            let rise = pass.film_temperature_max.value - input.ehl.temperature;
            let raw = &pass.factors;
            let mut f = blend(used.as_ref(), raw, relax);
            // Where the 2-D solve fails on the new factors, the step towards them is halved.
            let (next, next_warm) = loop {
                match solve_factored(&input.ehl, &warm_opts, Some(&f), Some(&warm), &mut self.kept, observer) {
                    Ok(n) => break n,
                    Err(SolveError::NotConverged { .. }) if relax > MIN_FACTOR_STEP => {
                        relax *= 0.5;
                        f = blend(used.as_ref(), raw, relax);
                    }
                    Err(e) => return Err(e),
                }
            };
            used = Some(f);
            let rel = |a: f64, b: f64| ((a - b) / b.abs().max(1e-30)).abs();
            let t_change = last_rise.map_or(f64::INFINITY, |r| (rise - r).abs() / rise.abs().max(0.1));
            let change = rel(next.central_film, sol.central_film).max(rel(next.min_film.value, sol.min_film.value)).max(0.01 * t_change);
            if let Some(&before) = history.last() {
                relax = if change > before { (relax * 0.6).max(0.15) } else { (relax * 1.2).min(1.0) };
            }
            history.push(change);
            last_rise = Some(rise);
            sol = next;
            warm = next_warm;
            last = Some(pass);
            if change < thermal.tolerance {
                break;
            }
            if iterations >= thermal.max_iterations {
                if change < 10.0 * thermal.tolerance {
                    termination = Termination::Stalled;
                    break;
                }
                return Err(SolveError::NotConverged { solver: "thermal finite ehl coupling (row energies ↔ 2-D Reynolds)", iterations, residual: change, tolerance: thermal.tolerance, history });
            }
        }
        // The temperatures: on convergence the last pass's, on the pressure and film before the
        // last 2-D solve (which moved the films by less than the tolerance; a further pass on the
        // final pressure and film changed seed 000's 360-angle cycle by ≤ 1e-4 in the films,
        // 0.1 K in the largest temperature and 5e-4 in the slip, at 16 % of the sweeps:
        // BENCHMARKS.md); after a stall a pass on the final pressure and film.
        let fin = match last {
            Some(pass) if termination == Termination::Converged => pass,
            other => energy_pass(input, &sol, thermal, other.as_ref().map_or(&fields, |p| &p.fields))?,
        };
        self.warm = Some(warm);
        self.factors = used;
        self.fields = fin.fields;
        sol.grid_error = grid_error;
        if !options.fields {
            sol.fields = None;
        }
        let residual = history.last().copied().unwrap_or(0.0);
        Ok(ThermalFiniteSolution {
            ehl: sol,
            isothermal_central_film: iso.map(|v| v.0),
            isothermal_min_film: iso.map(|v| v.1),
            film_temperature_max: fin.film_temperature_max,
            surface_temperature_max_1: fin.surface_max.0,
            surface_temperature_max_2: fin.surface_max.1,
            rows: fin.rows,
            heat: fin.heat,
            traction: fin.traction,
            factors: fin.factors,
            convergence: Convergence { iterations, residual, tolerance: thermal.tolerance, termination },
        })
    }
}

/// The forces over the whole contact of `sol` (a converged solution with its fields) at another
/// sliding velocity (`input.sliding_velocity`, m/s): one energy pass over the rows at the held
/// pressure and film, every row from the inlet temperature (seed 000 eq. 7–9).
pub fn traction_at(input: &ThermalFiniteInput, sol: &Ehl2dSolution, thermal: &ThermalOptions) -> Result<ContactTraction, SolveError> {
    Ok(energy_pass(input, sol, thermal, &[])?.traction)
}
