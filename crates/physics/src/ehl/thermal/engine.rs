use super::*;

/// The columns `[a, e]` of a film profile on which the energy equation is solved: the contiguous
/// columns around the minimum film where the film is at most `extent` times it
/// ([`ThermalOptions::film_extent`]), at least three.
pub fn thermal_range(film: &[f64], extent: f64) -> (usize, usize) {
    let n = film.len();
    let imin = (0..n).fold(0, |j, i| if film[i] < film[j] { i } else { j });
    let limit = extent * film[imin];
    let mut a = imin;
    while a > 0 && film[a - 1] <= limit {
        a -= 1;
    }
    let mut e = imin;
    while e + 1 < n && film[e + 1] <= limit {
        e += 1;
    }
    while e - a < 2 {
        if a > 0 {
            a -= 1;
        }
        if e - a < 2 && e + 1 < n {
            e += 1;
        }
    }
    (a, e)
}

pub(super) fn blend(old: &ThermalFactors, new: &ThermalFactors, w: f64) -> ThermalFactors {
    if w >= 1.0 {
        return new.clone();
    }
    let at = |v: &[f64], x: f64| {
        let m = old.x.len();
        let i = old.x.partition_point(|&a| a <= x).clamp(1, m - 1);
        let t = ((x - old.x[i - 1]) / (old.x[i] - old.x[i - 1])).clamp(0.0, 1.0);
        v[i - 1] * (1.0 - t) + v[i] * t
    };
    let mut out = new.clone();
    for (k, &x) in new.x.iter().enumerate() {
        out.poiseuille[k] = (at(&old.poiseuille, x).max(1e-300).ln() * (1.0 - w) + new.poiseuille[k].ln() * w).exp();
        out.wedge[k] = at(&old.wedge, x) * (1.0 - w) + new.wedge[k] * w;
        out.mass[k] = at(&old.mass, x) * (1.0 - w) + new.mass[k] * w;
    }
    out
}

/// Surface velocities `(u1, u2)` of an input: `u_m ± u_s/2`.
pub(super) fn surface_velocities(input: &EhlInput) -> (f64, f64) {
    let (um, us) = (input.entrainment_velocity, input.sliding_velocity);
    (um + 0.5 * us, um - 0.5 * us)
}

/// Solve one thermal line-contact EHL problem.
pub fn solve(input: &ThermalInput, options: &EhlOptions, thermal: &ThermalOptions, observer: &dyn Observer) -> Result<ThermalSolution, SolveError> {
    ThermalEngine::new().solve(input, options, thermal, None, None, observer)
}

impl Default for ThermalEngine {
    fn default() -> Self {
        Self::new()
    }
}

impl std::fmt::Debug for ThermalEngine {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str("ThermalEngine")
    }
}

impl ThermalEngine {
    pub fn new() -> Self {
        ThermalEngine { engine: Engine::new() }
    }

    /// Solve one problem. `warm_field` (a temperature field of a nearby problem, any grid) starts
    /// the energy sweeps; `warm_factors` (that problem's generalized Reynolds factors) the first
    /// pressure solve, which is otherwise isothermal; `input.ehl.warm_start`/`transient` the
    /// Newton solver.
    pub fn solve(
        &mut self,
        input: &ThermalInput,
        options: &EhlOptions,
        thermal: &ThermalOptions,
        warm_field: Option<&TemperatureField>,
        warm_factors: Option<&ThermalFactors>,
        observer: &dyn Observer,
    ) -> Result<ThermalSolution, SolveError> {
        if !(thermal.film_points >= 3 && thermal.solid_points >= 4 && thermal.solid_depth > 0.0 && thermal.tolerance > 0.0) {
            return Err(SolveError::invalid("ThermalOptions", "film_points ≥ 3, solid_points ≥ 4, solid_depth > 0, tolerance > 0"));
        }
        let ehl = &input.ehl;
        let (u1, u2) = surface_velocities(ehl);
        let (h_est, dir) = super::super::newton::film_estimate(ehl);
        let layout = super::super::grid::Layout::for_film(h_est, dir, options.inlet, options.outlet, options.grading);
        let previous = match (input.previous_temperature, ehl.transient) {
            (Some(f), Some(t)) => Some((f, t.time_step)),
            _ => None,
        };
        let energy_at = |sol: &EhlSolution, warm: Option<&TemperatureField>| {
            let ein = EnergyInput {
                limited_gradient: false,
                velocity_1: u1,
                velocity_2: u2,
                lubricant: &ehl.lubricant,
                inlet_temperature: ehl.temperature,
                bodies: &input.bodies,
                half_width: sol.hertz_half_width,
                load_per_length: ehl.load_per_length,
                rheology: &ehl.rheology,
                previous,
                warm,
            };
            let (a, e) = thermal_range(&sol.state.film, thermal.film_extent);
            let st = &sol.state;
            energy(&st.x[a..=e], &st.pressure[a..=e], &st.film[a..=e], &ein, thermal)
        };
        let mut sol = self.engine.solve_with(ehl, options, Some(layout), None, warm_factors, observer)?;
        let mut field: Option<TemperatureField> = warm_field.cloned();
        let mut iterations = 0;
        let mut history = Vec::new();
        let mut last: Option<EnergySolution> = None;
        let mut used: Option<ThermalFactors> = warm_factors.cloned();
        let mut termination = Termination::Converged;
        let mut relax: f64 = 1.0;
        loop {
            observer.check()?;
            let mut en = energy_at(&sol, field.as_ref())?;
            iterations += 1;
            // Under-relaxed factors (the last ones used, interpolated onto this grid, blended
            // with the new): the energy ↔ Reynolds fixed point can oscillate where the heating
            // is strong; the step shrinks when the change grows.
            let raw = en.factors.clone();
            let unit = || ThermalFactors { x: raw.x.clone(), poiseuille: vec![1.0; raw.x.len()], wedge: vec![1.0; raw.x.len()], mass: vec![1.0; raw.x.len()] };
            en.factors = match &used {
                Some(old) => blend(old, &raw, relax),
                None => raw.clone(),
            };
            let ph = sol.hertz_pressure;
            let pred: Vec<f64> = sol.state.pressure.iter().map(|p| p / ph).collect();
            let prediction = Prediction { pressure: &pred, centre_film: sol.central_film };
            // Where the Reynolds solve fails on the new factors (strong heating: the film's
            // Poiseuille coefficient moves by orders of magnitude between iterations), the step
            // towards them is halved (from the isothermal factors on the first iteration).
            let next = loop {
                match self.engine.solve_with(ehl, options, Some(layout), Some(prediction), Some(&en.factors), observer) {
                    Ok(next) => break next,
                    Err(SolveError::NotConverged { .. }) if relax > MIN_FACTOR_STEP => {
                        relax *= 0.5;
                        en.factors = match &used {
                            Some(old) => blend(old, &raw, relax),
                            None => blend(&unit(), &raw, relax),
                        };
                    }
                    Err(e) => return Err(e),
                }
            };
            used = Some(en.factors.clone());
            let rel = |a: f64, b: f64| ((a - b) / b.abs().max(1e-30)).abs();
            // Change of the largest temperature rise, relative to the rise (at least 0.1 K).
            let rise = en.summary.film_temperature_max - ehl.temperature;
            let t_change = match (&last, warm_field) {
                (Some(l), _) => (rise - (l.summary.film_temperature_max - ehl.temperature)).abs() / rise.abs().max(0.1),
                (None, Some(w)) => (rise - (w.film_max() - ehl.temperature)).abs() / rise.abs().max(0.1),
                (None, None) => f64::INFINITY,
            };
            // Films to the tolerance; the temperature rise to 100× it (the energy sweeps themselves
            // stop at `sweep_tolerance`, or stall above it, so the rise carries that noise).
            let change = rel(next.central_film, sol.central_film).max(rel(next.min_film, sol.min_film)).max(0.01 * t_change);
            if let Some(&before) = history.last() {
                relax = if change > before { (relax * 0.6).max(0.15) } else { (relax * 1.2).min(1.0) };
            }
            history.push(change);
            sol = next;
            field = Some(en.field.clone());
            last = Some(en);
            if change < thermal.tolerance {
                break;
            }
            if iterations >= thermal.max_iterations {
                // Within 10× the tolerance the coupling has stalled on the energy sweeps' noise:
                // the result is usable and reported as stalled.
                if change < 10.0 * thermal.tolerance {
                    termination = Termination::Stalled;
                    break;
                }
                return Err(SolveError::NotConverged {
                    solver: "thermal ehl coupling (energy ↔ Reynolds)",
                    iterations,
                    residual: change,
                    tolerance: thermal.tolerance,
                    history,
                });
            }
        }
        let en = last.expect("one iteration ran");
        // The final temperatures on the final pressure and film.
        let fin = energy_at(&sol, Some(&en.field))?;
        sol.traction = fin.traction;
        let residual = history.last().copied().unwrap_or(0.0);
        Ok(ThermalSolution {
            ehl: sol,
            temperature: fin.field,
            summary: fin.summary,
            factors: fin.factors,
            convergence: Convergence { iterations, residual, tolerance: thermal.tolerance, termination },
        })
    }
}
