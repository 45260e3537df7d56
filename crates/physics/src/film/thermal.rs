//! The thermal `accurate` film model (`ehl.thermal`): the thermal line-contact EHL model
//! ([`crate::ehl::thermal`], seed 000 eq. 2, 4–5, 7–9) at every contact point.
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
//!   slope is the interpolant's. Only the entries around the point's own slip are solved with
//!   it, the others where the balance needs them ([`super::traction_table`]). The asperity share of rough surfaces is as in the isothermal
//!   numerical model (Greenwood–Tripp with the local film, fluid traction scaled by
//!   `1 − W_a/W`).
//! * **Carried thermal factors** (`carry_tolerance`, key points). The thermal state changes
//!   slowly with the operating conditions: the full solve runs only at a point whose conditions
//!   `(w', u_m, R, SRR)` are farther than the tolerance (the largest of `|Δ ln w'|`, `|Δ ln u_m|`,
//!   `|Δ ln R|`, `|Δ SRR|`) from every key point solved so far in the run; elsewhere the nearest
//!   key's thermal factors are carried. Every point of the run (keys too) marches the isothermal
//!   numerical film (smooth surfaces, Richardson of the thermal grid and its half, squeeze
//!   history from the previous point); its films, peak pressure and spike are multiplied by the
//!   key's thermal factors — the thermal solution over the isothermal one, both steady at the
//!   key's conditions, on the same isothermal grid layout (a key on another layout is not
//!   carried: the factor would mix two discretisation errors — a 1 % step in the central film
//!   where the isothermal layout changed at seed 000's 118.5°). The key also carries its
//!   temperatures and its traction table at the same slide-to-roll ratios times the closed
//!   form's traction ratio at each, raised to an exponent calibrated between the key and the
//!   nearest earlier key (`γ = ln(f_key/f_prev)/ln(closed-form ratio)` per entry,
//!   [`super::traction_table::Calibration`]): the closed form overstates how the thermal
//!   traction changes with the radius, and the roller's inertia integrates the difference into
//!   the slip (seed 000 at carry 0.05: SRR 3.5 % → 0.6 % off). So the isothermal
//!   march carries the change of conditions and the squeeze (the film's lag behind fast load
//!   and entrainment changes, which a quasi-steady key cannot see), the key the thermal
//!   correction; the error is first order in the distance for the factors (BENCHMARKS.md,
//!   "Thermal EHL": against the full cycle). Key points are solved quasi-steady (no squeeze or
//!   ∂T/∂t history), warm-started from the nearest key. Periodic passes revisit the same
//!   conditions and reuse the keys.
//! * **Lag** (carried mode). Where the conditions jump — seed 000's opening ramp takes the load
//!   from 600 to 2241 N within 3.5° — the film's temperatures lag behind the steady keys'
//!   (`∂T/∂t`, eq. 7) and the carried film was 1–2 % thinner than the every-angle cycle's over
//!   the next 6° (BENCHMARKS.md, "Thermal EHL"). There the full transient thermal solve runs at
//!   every point, from a steady key at the previous point's conditions, until its film agrees
//!   with the carried one ([`ThermalNumerical::transient_window`]).
//! * **Point contacts** and a contact at rest without history keep the closed form.
//!
//! Cost: one coupled solve (a few Newton and energy solves) and the table's energy solves around
//! the point's slip (four to seven; the others when the balance reaches them) per full point; a
//! carried point costs an isothermal Newton solve on two grids
//! (warm-started, typically two steps each) and a closed-form solve — see BENCHMARKS.md,
//! "Thermal EHL".

use super::closed_form::ClosedForm;
use super::numerical::{asperity_load, line_contact, traction_nodes, LineContact, Numerical};
use super::{ContactInput, ContactShape, FilmModel, FilmModelId, FilmProfile, FilmSolution, Traction};
use crate::contact::hertz_line;
use crate::ehl::grid::{cells, Layout};
use super::traction_table::{candidate_sliding, Calibration, TableProblem, TableView, TractionTable};
use crate::ehl::thermal::{TemperatureField, ThermalBodies, ThermalEngine, ThermalFactors, ThermalInput, ThermalOptions, ThermalSummary};
use crate::ehl::{EhlInput, EhlOptions, Extrapolation, Rheology, Transient};
use crate::friction::Roughness;
use crate::friction::Rheology as Shear;
use crate::{ensure_finite, SolveError};
use std::sync::{Arc, Mutex};

/// A key point of the carried mode: its operating conditions, its full thermal solution and the
/// closed form's film and table traction there.
#[derive(Debug, Clone)]
struct Key {
    /// The nearest earlier key on the same layout, within three carry tolerances: calibrates
    /// the traction carried from this key ([`super::traction_table::Calibration`]).
    previous: Option<Arc<Key>>,
    load_per_length: f64,
    entrainment: f64,
    radius: f64,
    slide_to_roll: f64,
    /// The isothermal model's grid layout at the key's conditions: a key carries its factors
    /// only to points on the same layout (module docs, "Carried thermal factors").
    layout: Layout,
    film: FilmSolution,
    /// The isothermal numerical film at the key's conditions, steady, on the same grid.
    isothermal: FilmSolution,
    closed_form: FilmSolution,
    /// The closed form's fluid traction at the key's table sliding velocities (every candidate
    /// of every entry, [`candidate_sliding`]), N.
    closed_form_table: Vec<Vec<f64>>,
}

/// `a/b`, or 1 where `b` is zero or `a` is not finite.
fn ratio(a: f64, b: f64) -> f64 {
    if b.abs() > 0.0 && a.is_finite() { a / b } else { 1.0 }
}

/// What a key carries to a point ([`ThermalNumerical::carry`]): thermal factors (thermal over
/// isothermal film at the key), the traction table at the point's entrainment and the asperity
/// load.
#[derive(Debug)]
struct Carry {
    central: f64,
    min: f64,
    pressure: f64,
    spike: f64,
    /// Shift of the pressure spike's position, m.
    spike_shift: f64,
    table: TableView,
    asperity_load: f64,
}

impl Key {
    fn conditions(&self) -> (f64, f64, f64, f64) {
        (self.load_per_length, self.entrainment, self.radius, self.slide_to_roll)
    }
}

/// The isothermal film a carried-mode point keeps ([`FilmThermal::isothermal`]): the next
/// point's squeeze history and warm start.
fn isothermal_history(previous: Option<&FilmSolution>) -> Option<&FilmSolution> {
    previous.and_then(|p| p.thermal.as_deref()).and_then(|t| t.isothermal.as_deref())
}

/// `a/b` per table entry and candidate, 1 where `b` is below 1e-12 of `load` (N): the closed
/// form's traction change between two points.
fn table_ratio(a: &[Vec<f64>], b: &[Vec<f64>], load: f64) -> Vec<Vec<f64>> {
    a.iter().zip(b).map(|(x, y)| x.iter().zip(y).map(|(p, q)| if q.abs() > 1e-12 * load { p / q } else { 1.0 }).collect()).collect()
}

/// Operating conditions of a line-contact point: `(w', u_m, R, SRR)`.
fn conditions(input: &ContactInput, r: f64, length: f64) -> (f64, f64, f64, f64) {
    let um = input.entrainment_velocity;
    (input.load / length, um, r, input.sliding_velocity / um.abs().max(1e-6))
}

/// Distance between two points' conditions: the largest of `|Δ ln w'|`, `|Δ ln u_m|`,
/// `|Δ ln R|`, `|Δ SRR|` (infinite when the entrainment changes sign).
fn distance(a: (f64, f64, f64, f64), b: (f64, f64, f64, f64)) -> f64 {
    if a.1 * b.1 <= 0.0 {
        return f64::INFINITY;
    }
    (a.0 / b.0).ln().abs().max((a.1 / b.1).ln().abs()).max((a.2 / b.2).ln().abs()).max((a.3 - b.3).abs())
}

/// Coupling tolerance of a key point ([`ThermalFilmSettings::carry_tolerance`]) relative to
/// `ThermalOptions::tolerance`. A key point starts from the nearest key (other conditions), not
/// from the previous angle's converged state as the every-angle cycle does, and a coupling
/// stopped at the default 1e-3 stays biased towards its start: the seed 000 base-circle SRR
/// settled at 0.21–0.24 against 0.204 (the traction curve is flat at its thermal maximum there,
/// so a small traction bias moves the SRR far); at 1e-4 within 0.4 %. A key whose coupling
/// stalls above the tighter tolerance is solved again at the default one.
const KEY_TOLERANCE_FACTOR: f64 = 0.1;

/// Settings of the thermal model.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ThermalFilmSettings {
    pub options: ThermalOptions,
    pub bodies: ThermalBodies,
    /// Key angles ([`ThermalNumerical`] module docs, "Carried thermal factors"): the largest
    /// distance in operating conditions (`|Δ ln w'|`, `|Δ ln u_m|`, `|Δ ln R|`, `|Δ SRR|`) over
    /// which a key point's thermal factors are carried. `None`: the full thermal solve at every
    /// point.
    pub carry_tolerance: Option<f64>,
}

/// What a thermal point keeps: temperatures, factors and the traction table.
#[derive(Debug, Clone, PartialEq)]
pub struct FilmThermal {
    pub summary: ThermalSummary,
    pub field: TemperatureField,
    pub factors: ThermalFactors,
    /// The follower's fluid traction per unit length against the sliding velocity.
    pub table: TableView,
    /// Carried mode: the isothermal numerical film at this point (its fields are the next
    /// point's squeeze history and warm start of the isothermal march).
    pub isothermal: Option<Box<FilmSolution>>,
    /// Carried mode: the point's operating conditions `(w', u_m, R, SRR)`.
    pub conditions: Option<(f64, f64, f64, f64)>,
    /// Carried mode: the point's transient thermal film still differs from the carried one, so
    /// the next point is solved transient too ([`ThermalNumerical`] module docs, "Lag").
    pub lagging: bool,
}

/// The thermal numerical film model. See the module docs.
#[derive(Debug)]
pub struct ThermalNumerical {
    pub options: EhlOptions,
    pub settings: ThermalFilmSettings,
    pub fallback: ClosedForm,
    engine: Mutex<ThermalEngine>,
    /// Key points of the carried mode (this run's).
    keys: Mutex<Vec<Arc<Key>>>,
    /// Carried mode: the isothermal numerical model (same grid and options, smooth surfaces)
    /// whose transient film carries the keys' thermal factors.
    isothermal: Numerical,
}

impl ThermalNumerical {
    pub fn new(options: EhlOptions, settings: ThermalFilmSettings, fallback: ClosedForm) -> Self {
        let isothermal = Numerical::new(options, fallback).with_extrapolation(Extrapolation::Richardson);
        ThermalNumerical { options, settings, fallback, engine: Mutex::new(ThermalEngine::new()), keys: Mutex::new(Vec::new()), isothermal }
    }

    /// The closed form's fluid traction at sliding velocities `sliding` (per table entry, every
    /// candidate; for the carried table).
    fn closed_form_table(&self, cf: &FilmSolution, input: &ContactInput, sliding: &[Vec<f64>]) -> Vec<Vec<f64>> {
        sliding.iter().map(|c| c.iter().map(|&us| self.fallback.traction(cf, input, us).viscous).collect()).collect()
    }

    /// The isothermal numerical film at `input` on the thermal model's grid, smooth surfaces (as
    /// the thermal solve: its asperity share is post hoc), from `history`'s fields (squeeze
    /// history when `input.time_step > 0`, else a warm start).
    fn isothermal_film(&self, input: &ContactInput, history: Option<&FilmSolution>) -> Result<FilmSolution, SolveError> {
        let smooth = Roughness { sigma: 0.0, curve: None, ..input.roughness.clone() };
        self.isothermal.solve(&ContactInput { roughness: &smooth, ..*input }, history)
    }

    /// What key `key` carries to `input` (closed form `cf` there): its thermal factors
    /// (thermal over isothermal film at the key) and its traction table at the same
    /// slide-to-roll ratios, scaled by the closed form's traction change at each (where the
    /// closed form has no traction, the key's value stands).
    fn carry(&self, key: &Key, input: &ContactInput, cf: &FilmSolution, length: f64) -> Carry {
        let (k, ki) = (&key.film, &key.isothermal);
        let kth = k.thermal.as_deref().expect("a key is a thermal solution");
        let speed = ratio(input.entrainment_velocity, key.entrainment);
        let sliding: Vec<Vec<f64>> = candidate_sliding(kth.table.problem().scale).iter().map(|c| c.iter().map(|us| us * speed).collect()).collect();
        let cf_table = self.closed_form_table(cf, input, &sliding);
        let force_ratio = table_ratio(&cf_table, &key.closed_form_table, input.load);
        let calibration = key.previous.as_ref().and_then(|a| {
            let ath = a.film.thermal.as_deref()?;
            Some(Calibration { table: ath.table.table.clone(), closed_form_ratio: table_ratio(&key.closed_form_table, &a.closed_form_table, input.load) })
        });
        let table = TableView { table: kth.table.table.clone(), speed: kth.table.speed * speed, ratio: Some(force_ratio), calibration };
        let asperity_load = if key.closed_form.asperity.load > 0.0 {
            k.asperity.load * ratio(cf.asperity.load, key.closed_form.asperity.load)
        } else {
            k.asperity.load * input.load / (key.load_per_length * length)
        };
        let both = |a: Option<f64>, b: Option<f64>| a.zip(b);
        Carry {
            central: ratio(k.central_film, ki.central_film),
            min: ratio(k.min_film, ki.min_film),
            pressure: ratio(k.max_pressure, ki.max_pressure),
            spike: both(k.pressure_spike, ki.pressure_spike).map_or(1.0, |(a, b)| ratio(a, b)),
            spike_shift: both(k.pressure_spike_position, ki.pressure_spike_position).map_or(0.0, |(a, b)| a - b),
            table,
            asperity_load,
        }
    }

    /// The carried solution at `input` from key `key` (module docs): the isothermal numerical
    /// film marched from `previous` (its squeeze history) times the key's thermal factors, the
    /// key's temperatures, and its traction table carried by the closed form.
    fn carried(&self, key: &Key, input: &ContactInput, previous: Option<&FilmSolution>, r: f64, length: f64) -> Result<FilmSolution, SolveError> {
        let iso = self.isothermal_film(input, isothermal_history(previous))?;
        let cf = self.fallback.solve(input, None)?;
        let c = self.carry(key, input, &cf, length);
        let kth = key.film.thermal.as_deref().expect("a key is a thermal solution");
        let w = input.load / length;
        let hz = hertz_line(w, r, input.contact_modulus);
        let w_a = c.asperity_load.min(input.load);
        let central_film = iso.central_film * c.central;
        let min_film = iso.min_film * c.min;
        ensure_finite("carried thermal film", [&central_film, &min_film, &c.pressure, &c.spike, &c.spike_shift, &w_a])?;
        let sigma = input.roughness.sigma;
        Ok(FilmSolution {
            model: FilmModelId::ThermalCarried,
            central_film,
            min_film,
            steady_central_film: cf.steady_central_film,
            max_pressure: iso.max_pressure * c.pressure,
            pressure_spike: iso.pressure_spike.map(|p| p * c.spike),
            pressure_spike_position: iso.pressure_spike_position.map(|x| x + c.spike_shift),
            exit_film: iso.exit_film.map(|h| h * c.central),
            half_width: hz.half_width,
            contact_area: 2.0 * hz.half_width * length,
            asperity: input.asperity_friction.contact(w_a, hz.half_width, r, central_film),
            // The thermal model keeps the post-hoc asperity share: semi-elliptic micro-slip.
            asperity_nodes: Vec::new(),
            lambda: (sigma > 0.0).then(|| min_film / sigma),
            regime: None,
            nodes: cf.nodes,
            // The carried table includes the key's surface stresses (Poiseuille part too).
            rolling_force: 0.0,
            viscosity_law: None,
            // No thermal profile of its own (a new key warm-starts from the nearest key).
            profile: None,
            iterations: iso.iterations,
            thermal: Some(Box::new(FilmThermal {
                table: c.table,
                isothermal: Some(Box::new(iso)),
                conditions: Some(conditions(input, r, length)),
                lagging: false,
                ..kth.clone()
            })),
            finite: None,
        })
    }

    /// A new key point at `input` (conditions `here`), warm-started from the nearest key
    /// `nearest` (its thermal fields) or the previous point, and the point's own solution: the
    /// key's factors on the isothermal film marched to it (the same squeeze history as every
    /// carried point), its thermal profile.
    #[allow(clippy::too_many_arguments)]
    fn new_key(&self, input: &ContactInput, previous: Option<&FilmSolution>, nearest: Option<Arc<Key>>, here: (f64, f64, f64, f64), layout: Layout, r: f64, length: f64) -> Result<FilmSolution, SolveError> {
        let steady = ContactInput { time_step: 0.0, ..*input };
        let warm = nearest.as_ref().map(|k| &k.film).or(previous.filter(|p| p.profile.is_some()));
        let reach = 3.0 * self.settings.carry_tolerance.unwrap_or(0.0);
        let previous_key = nearest.as_ref().filter(|k| distance(here, k.conditions()) <= reach).cloned();
        // Where the tighter coupling stalls above it (energy sweeps' noise), the key takes the
        // default tolerance.
        let film = match self.full_with(&steady, warm, KEY_TOLERANCE_FACTOR) {
            Err(SolveError::NotConverged { .. }) => self.full_with(&steady, warm, 1.0)?,
            other => other?,
        };
        let Some(thermal) = film.thermal.as_deref() else {
            return Ok(film);
        };
        let cf = self.fallback.solve(input, None)?;
        let table = self.closed_form_table(&cf, input, &candidate_sliding(thermal.table.problem().scale));
        // Steady, warm-started from the previous point's isothermal film.
        let isothermal = self.isothermal_film(&steady, isothermal_history(previous))?;
        let key = Arc::new(Key { previous: previous_key, load_per_length: here.0, entrainment: here.1, radius: here.2, slide_to_roll: here.3, layout, film, isothermal, closed_form: cf, closed_form_table: table });
        let mut out = self.carried(&key, input, previous, r, length)?;
        out.model = FilmModelId::Thermal;
        out.profile = key.film.profile.clone();
        out.iterations = key.film.iterations;
        self.keys.lock().unwrap_or_else(|e| e.into_inner()).push(key);
        Ok(out)
    }

    /// The transient window of the carried mode (module docs, "Lag"): `carried` (the point's
    /// carried or new-key solution), or the full transient thermal solve at `input` when the
    /// conditions moved faster than the film's thermal state can follow — by more than the carry
    /// tolerance `tol` within the film's transit time `2b/|u_m|` — or the previous point's
    /// transient film still differed from its carried one. The window's first point starts
    /// from the key nearest the previous point's conditions (a steady state at them, to within
    /// the tolerance), the next from its predecessor's transient solution. A window point keeps
    /// the isothermal march going, and the window closes once its transient film agrees with the
    /// carried one to within a tenth of the tolerance.
    fn transient_window(&self, input: &ContactInput, previous: Option<&FilmSolution>, carried: FilmSolution, here: (f64, f64, f64, f64), r: f64, tol: f64) -> Result<FilmSolution, SolveError> {
        let Some((prev, prev_thermal)) = previous.and_then(|p| p.thermal.as_deref().map(|t| (p, t))) else {
            return Ok(carried);
        };
        if !(input.time_step > 0.0) {
            return Ok(carried);
        }
        let transit = 2.0 * hertz_line(here.0, r, input.contact_modulus).half_width / here.1.abs();
        let fast = prev_thermal.conditions.is_some_and(|c| distance(here, c) * transit / input.time_step > tol);
        if !(fast || prev_thermal.lagging) {
            return Ok(carried);
        }
        let history_key;
        let history = if prev.profile.is_some() {
            prev
        } else {
            let Some(c) = prev_thermal.conditions else {
                return Ok(carried);
            };
            let keys = self.keys.lock().unwrap_or_else(|e| e.into_inner());
            let Some(key) = keys.iter().min_by(|a, b| distance(c, a.conditions()).total_cmp(&distance(c, b.conditions()))).cloned() else {
                return Ok(carried);
            };
            drop(keys);
            history_key = key;
            &history_key.film
        };
        let mut film = self.full(input, Some(history))?;
        let lag = ratio(film.central_film, carried.central_film).ln().abs().max(ratio(film.min_film, carried.min_film).ln().abs());
        let Some(th) = film.thermal.as_deref_mut() else {
            return Ok(carried);
        };
        th.isothermal = carried.thermal.and_then(|t| t.isothermal);
        th.conditions = Some(here);
        th.lagging = lag > 0.1 * tol;
        Ok(film)
    }

    /// The full thermal solve at `input` (module docs); `previous` the previous point's
    /// solution (squeeze and ∂T/∂t history when `input.time_step > 0`, warm starts).
    fn full(&self, input: &ContactInput, previous: Option<&FilmSolution>) -> Result<FilmSolution, SolveError> {
        self.full_with(input, previous, 1.0)
    }

    /// [`Self::full`] with the coupling tolerance scaled by `tolerance_factor` (≤ 1; below 1
    /// the iteration cap doubles).
    fn full_with(&self, input: &ContactInput, previous: Option<&FilmSolution>, tolerance_factor: f64) -> Result<FilmSolution, SolveError> {
        let o = self.settings.options;
        let cap = if tolerance_factor < 1.0 { 2 * o.max_iterations } else { o.max_iterations };
        let thermal_options = ThermalOptions { tolerance: o.tolerance * tolerance_factor, max_iterations: cap, ..o };
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
        let th = engine.solve(&tin, &options, &thermal_options, prev_thermal.map(|t| &t.field), prev_thermal.map(|t| &t.factors), &input.interrupts)?;
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
        let problem = TableProblem {
            x: x.to_vec(),
            pressure: p.to_vec(),
            film: h.to_vec(),
            entrainment: um,
            scale: um.abs().max(1e-6),
            lubricant: *input.lubricant,
            inlet_temperature: input.temperature,
            bodies: self.settings.bodies,
            half_width: s.hertz_half_width,
            load_per_length: w,
            rheology,
            options: self.settings.options,
        };
        let table = TableView { table: Arc::new(TractionTable::new(problem, th.temperature.clone(), input.sliding_velocity)?), speed: 1.0, ratio: None, calibration: None };
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
            asperity: input.asperity_friction.contact(w_a, hz.half_width, r, s.central_film),
            // The thermal model keeps the post-hoc asperity share: semi-elliptic micro-slip.
            asperity_nodes: Vec::new(),
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
                table,
                isothermal: None,
                conditions: None,
                lagging: false,
            })),
            finite: None,
        })
    }
}

impl FilmModel for ThermalNumerical {
    fn entrainment_tolerance(&self) -> f64 {
        1e-4
    }

    fn solve(&self, input: &ContactInput, previous: Option<&FilmSolution>) -> Result<FilmSolution, SolveError> {
        let Some(tol) = self.settings.carry_tolerance else {
            return self.full(input, previous);
        };
        // Carried mode: quasi-steady key points (no squeeze or ∂T/∂t history).
        let (r, length) = match input.shape {
            ContactShape::Line { reduced_radius, length } if input.entrainment_velocity != 0.0 => (reduced_radius, length),
            _ => return self.full(&ContactInput { time_step: 0.0, ..*input }, None),
        };
        let here = conditions(input, r, length);
        let layout = self.isothermal.layout(input, r, length);
        let nearest = {
            let keys = self.keys.lock().unwrap_or_else(|e| e.into_inner());
            let far = |k: &Key| if k.layout == layout { distance(here, k.conditions()) } else { f64::INFINITY };
            keys.iter().map(|k| (far(k), k)).min_by(|a, b| a.0.total_cmp(&b.0)).map(|(d, k)| (d, k.clone()))
        };
        let out = match nearest {
            Some((d, key)) if d <= tol => self.carried(&key, input, previous, r, length)?,
            other => self.new_key(input, previous, other.map(|(_, k)| k), here, layout, r, length)?,
        };
        self.transient_window(input, previous, out, here, r, tol)
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
        let (f, df) = th.table.force(sliding);
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
