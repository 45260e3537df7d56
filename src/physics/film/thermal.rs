//! The thermal `accurate` film model (`ehl.thermal`): the thermal line-contact EHL model
//! ([`crate::physics::ehl::thermal`], seed 000 eq. 2, 4–5, 7–9) at every contact point.
//!
//! * **Film.** At each point the coupled generalized Reynolds / energy problem is solved at the
//!   point's sliding velocity (the roller balance's guess), body 1 the cam (`z = 0`, moving at
//!   `u_m + u_s/2`) and body 2 the follower. Consecutive points are time steps: the squeeze term
//!   and the temperature's `∂T/∂t` use the previous point's pressure, film and temperature field,
//!   which also warm-start the Newton solver, the sweeps and the generalized Reynolds factors.
//! * **Traction.** The roller balance evaluates the traction at many trial sliding velocities.
//!   With the pressure and film of the point held, the energy equation is solved at a table of
//!   slide-to-roll ratios ([`SLIDE_TO_ROLL_TABLE`], both signs) over the pressurised zone (from
//!   half a Hertzian half-width ahead of the first loaded node; the oil and the solids enter it at
//!   the inlet temperature — the inlet's own heating is left out of the traction table, not out
//!   of the film), and the follower's surface stress integral (eq. 9) is interpolated between
//!   them by a monotone cubic (Steffen 1990: no overshoot, C¹), linear beyond the ends. The
//!   slope is the interpolant's. The asperity share of rough surfaces is as in the isothermal
//!   numerical model (Greenwood–Tripp with the local film, fluid traction scaled by
//!   `1 − W_a/W`).
//! * **Point contacts** and a contact at rest without history keep the closed form.
//!
//! Cost: one coupled solve (a few Newton and energy solves) and [`SLIDE_TO_ROLL_TABLE`]`.len()`
//! energy solves per point — see BENCHMARKS.md, "Thermal EHL".

use super::closed_form::ClosedForm;
use super::numerical::{asperity_load, line_contact, traction_nodes, LineContact};
use super::{ContactInput, ContactShape, FilmModel, FilmModelId, FilmProfile, FilmSolution, Traction};
use crate::physics::contact::hertz_line;
use crate::physics::ehl::grid::cells;
use crate::physics::ehl::thermal::{energy, EnergyInput, TemperatureField, ThermalBodies, ThermalEngine, ThermalFactors, ThermalInput, ThermalOptions, ThermalSummary};
use crate::physics::ehl::{EhlInput, EhlOptions, Rheology, Transient};
use crate::physics::friction::{AsperityContact, Rheology as Shear};
use crate::physics::{ensure_finite, Silent, SolveError};
use std::sync::Mutex;

/// Slide-to-roll ratios `u_s/u_m` of the traction table (both signs and zero). Points beyond
/// ±0.15 whose energy solve fails are left out (the interpolant then extends linearly).
pub const SLIDE_TO_ROLL_TABLE: [f64; 13] = [-2.0, -0.5, -0.15, -0.05, -0.015, -0.004, 0.0, 0.004, 0.015, 0.05, 0.15, 0.5, 2.0];

/// Settings of the thermal model.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ThermalFilmSettings {
    pub options: ThermalOptions,
    pub bodies: ThermalBodies,
}

/// What a thermal point keeps: temperatures, factors and the traction table.
#[derive(Debug, Clone, PartialEq)]
pub struct FilmThermal {
    pub summary: ThermalSummary,
    pub field: TemperatureField,
    pub factors: ThermalFactors,
    /// Sliding velocities of the table, m/s (increasing), and the follower's fluid traction per
    /// unit length at each, N/m.
    pub sliding: Vec<f64>,
    pub force_per_length: Vec<f64>,
}

/// The thermal numerical film model. See the module docs.
#[derive(Debug)]
pub struct ThermalNumerical {
    pub options: EhlOptions,
    pub settings: ThermalFilmSettings,
    pub fallback: ClosedForm,
    engine: Mutex<ThermalEngine>,
}

impl ThermalNumerical {
    pub fn new(options: EhlOptions, settings: ThermalFilmSettings, fallback: ClosedForm) -> Self {
        ThermalNumerical { options, settings, fallback, engine: Mutex::new(ThermalEngine::new()) }
    }
}

/// Steffen's (1990) slopes of the data `(x, y)`: monotone where the data are, no overshoot.
fn steffen_slopes(x: &[f64], y: &[f64]) -> Vec<f64> {
    let n = x.len();
    let d: Vec<f64> = (0..n - 1).map(|i| (y[i + 1] - y[i]) / (x[i + 1] - x[i])).collect();
    let mut m = vec![0.0; n];
    m[0] = d[0];
    m[n - 1] = d[n - 2];
    for i in 1..n - 1 {
        let (h0, h1) = (x[i] - x[i - 1], x[i + 1] - x[i]);
        let p = (d[i - 1] * h1 + d[i] * h0) / (h0 + h1);
        m[i] = if d[i - 1] * d[i] <= 0.0 { 0.0 } else { d[i - 1].signum() * d[i - 1].abs().min(d[i].abs()).min(0.5 * p.abs()) * 2.0 };
        if d[i - 1] * d[i] > 0.0 && m[i].abs() > p.abs() {
            m[i] = p;
        }
    }
    m
}

/// Value and slope of the monotone cubic through `(x, y)` with slopes `m` at `at`; linear
/// beyond the ends.
fn hermite(x: &[f64], y: &[f64], m: &[f64], at: f64) -> (f64, f64) {
    let n = x.len();
    if at <= x[0] {
        return (y[0] + m[0] * (at - x[0]), m[0]);
    }
    if at >= x[n - 1] {
        return (y[n - 1] + m[n - 1] * (at - x[n - 1]), m[n - 1]);
    }
    let i = x.partition_point(|&v| v <= at).clamp(1, n - 1) - 1;
    let h = x[i + 1] - x[i];
    let t = (at - x[i]) / h;
    let (t2, t3) = (t * t, t * t * t);
    let v = (2.0 * t3 - 3.0 * t2 + 1.0) * y[i] + (t3 - 2.0 * t2 + t) * h * m[i] + (-2.0 * t3 + 3.0 * t2) * y[i + 1] + (t3 - t2) * h * m[i + 1];
    let dv = ((6.0 * t2 - 6.0 * t) * y[i] + (3.0 * t2 - 4.0 * t + 1.0) * h * m[i] + (-6.0 * t2 + 6.0 * t) * y[i + 1] + (3.0 * t2 - 2.0 * t) * h * m[i + 1]) / h;
    (v, dv)
}

impl FilmModel for ThermalNumerical {
    fn entrainment_tolerance(&self) -> f64 {
        1e-4
    }

    fn solve(&self, input: &ContactInput, previous: Option<&FilmSolution>) -> Result<FilmSolution, SolveError> {
        let Some(LineContact { r, length, load, state }) = line_contact(input, previous)? else {
            return self.fallback.solve(input, previous);
        };
        let prev_thermal = previous.and_then(|p| p.thermal.as_deref());
        let transient = state.as_ref().filter(|_| input.time_step > 0.0).map(|s| Transient { previous: s, time_step: input.time_step });
        let w = load / length;
        let es = input.contact_modulus;
        let eyring = match input.traction_law.rheology {
            Shear::Eyring { tau0 } => Some(tau0),
            Shear::Newtonian => None,
        };
        let rheology = Rheology { eyring_stress: eyring, limiting_shear_coefficient: None, limiting_shear_stress: 0.0 };
        let ehl = EhlInput {
            load_per_length: w,
            reduced_radius: r,
            effective_modulus: 2.0 * es,
            entrainment_velocity: input.entrainment_velocity,
            sliding_velocity: input.sliding_velocity,
            lubricant: *input.lubricant,
            temperature: input.temperature,
            rheology,
            transient,
            warm_start: state.as_ref(),
            asperity: None,
        };
        let tin = ThermalInput {
            ehl,
            bodies: self.settings.bodies,
            previous_temperature: prev_thermal.filter(|_| transient.is_some()).map(|t| &t.field),
        };
        let options = EhlOptions { profiles: false, ..self.options };
        let mut fresh = ThermalEngine::new();
        let mut cached = self.engine.try_lock();
        let engine = match &mut cached {
            Ok(guard) => &mut **guard,
            Err(_) => &mut fresh,
        };
        let th = engine.solve(&tin, &options, &self.settings.options, prev_thermal.map(|t| &t.field), prev_thermal.map(|t| &t.factors), &Silent)?;
        drop(cached);
        let s = &th.ehl;
        let st = &s.state;
        let cell = cells(&st.x);
        let sigma = input.roughness.sigma;
        let w_a = asperity_load(input, st, &cell, length, load);
        // Traction table over the pressurised zone at the point's pressure and film.
        let hz = hertz_line(w, r, es);
        let um = input.entrainment_velocity;
        let first = st.pressure.iter().position(|&p| p > 0.0).unwrap_or(0);
        let start = st.x.partition_point(|&x| x < st.x[first] - 0.5 * hz.half_width).min(st.x.len().saturating_sub(3));
        let (x, p, h) = (&st.x[start..], &st.pressure[start..], &st.film[start..]);
        let mut sliding = Vec::with_capacity(SLIDE_TO_ROLL_TABLE.len());
        let mut force = Vec::with_capacity(SLIDE_TO_ROLL_TABLE.len());
        let scale = um.abs().max(1e-6);
        let mut warm = th.temperature.clone();
        for &srr in &SLIDE_TO_ROLL_TABLE {
            let us = srr * scale;
            let ein = EnergyInput {
                velocity_1: um + 0.5 * us,
                velocity_2: um - 0.5 * us,
                lubricant: input.lubricant,
                inlet_temperature: input.temperature,
                bodies: &self.settings.bodies,
                half_width: s.hertz_half_width,
                load_per_length: w,
                rheology: &rheology,
                previous: None,
                warm: Some(&warm),
            };
            // A point beyond the traction maximum whose Newtonian film runs away (or whose sweeps
            // do not settle) is left out of the table; the points within ±0.15 must succeed.
            match energy(x, p, h, &ein, &self.settings.options) {
                Ok(en) => {
                    sliding.push(us);
                    force.push(en.traction.force_body_2);
                    warm = en.field;
                }
                Err(e) if srr.abs() <= 0.15 => return Err(e),
                Err(_) => {}
            }
        }
        ensure_finite("thermal traction table", &force)?;
        ensure_finite("thermal film", [&s.central_film, &s.min_film, &s.exit_film, &s.max_pressure, &w_a])?;
        // Nodes (for consumers that read them; the traction comes from the table).
        let t = th.summary.film_temperature_mean;
        let nodes = traction_nodes(input, st, &cell, length, 1.0 - w_a / load, t);
        let steady = self.fallback.solve(input, None)?.steady_central_film;
        Ok(FilmSolution {
            model: FilmModelId::Thermal,
            central_film: s.central_film,
            min_film: s.min_film,
            steady_central_film: steady,
            max_pressure: s.max_pressure,
            pressure_spike: s.pressure_spike.map(|p| p.pressure),
            pressure_spike_position: s.pressure_spike.map(|p| p.position),
            exit_film: Some(s.exit_film),
            half_width: hz.half_width,
            contact_area: 2.0 * hz.half_width * length,
            asperity: AsperityContact { load: w_a, gross_sliding_creep: input.asperity_friction.creep_scale(hz.half_width, r) },
            lambda: (sigma > 0.0).then(|| s.min_film / sigma),
            regime: None,
            nodes,
            rolling_force: 0.0,
            viscosity_law: None,
            profile: Some(Box::new(FilmProfile {
                x: st.x.clone(),
                pressure: st.pressure.clone(),
                film: st.film.clone(),
                density_ratio: st.density_ratio.clone(),
                coarse: None,
                asperity_pressure: Vec::new(),
            })),
            iterations: Some(th.convergence.iterations),
            thermal: Some(Box::new(FilmThermal {
                summary: th.summary,
                field: th.temperature,
                factors: th.factors,
                sliding,
                force_per_length: force,
            })),
        })
    }

    fn traction_local(&self, film: &FilmSolution, input: &ContactInput, sliding: f64) -> (Traction, (f64, f64)) {
        let Some(th) = film.thermal.as_deref() else {
            return self.fallback.traction_local(film, input, sliding);
        };
        let length = match input.shape {
            ContactShape::Line { length, .. } => length,
            ContactShape::Point { .. } => 0.0,
        };
        let share = 1.0 - film.asperity.load / input.load;
        let m = steffen_slopes(&th.sliding, &th.force_per_length);
        let (f, df) = hermite(&th.sliding, &th.force_per_length, &m, sliding);
        let (asp, aslope) = input.asperity_friction.traction(&film.asperity, sliding, input.entrainment_velocity);
        let viscous = share * length * f;
        let traction = Traction {
            force: viscous + asp,
            slope: share * length * df + aslope,
            stick_limit: self.stick_limit(film, input),
            viscous,
        };
        // No curvature bound: the balance evaluates the (cheap) interpolant instead.
        (traction, (0.0, 0.0))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn steffen_interpolant_passes_through_the_data_without_overshoot() {
        let x = [-2.0, -0.5, 0.0, 0.5, 2.0];
        let y = [-1.0, -0.9, 0.0, 0.9, 1.0];
        let m = steffen_slopes(&x, &y);
        for (i, &xi) in x.iter().enumerate() {
            assert!((hermite(&x, &y, &m, xi).0 - y[i]).abs() < 1e-12);
        }
        for k in 0..=400 {
            let at = -2.0 + 4.0 * k as f64 / 400.0;
            let (v, _) = hermite(&x, &y, &m, at);
            assert!((-1.0 - 1e-12..=1.0 + 1e-12).contains(&v), "{at}: {v}");
        }
        // Slope against a finite difference.
        let (a, da) = hermite(&x, &y, &m, 0.3);
        let (b, _) = hermite(&x, &y, &m, 0.3 + 1e-7);
        assert!(((b - a) / 1e-7 - da).abs() < 1e-5);
    }
}
