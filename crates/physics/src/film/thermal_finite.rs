//! The thermal finite-line / point film model (`ehl.thermal` with `ehl.geometry: finite`): the
//! thermal 2-D EHL model ([`crate::ehl::thermal_finite`], seed 000 eq. 2–9 on the crowned roller
//! of eq. 3) at every contact point of a cam cycle.
//!
//! * **Film.** At each point the coupled problem (row energies ↔ 2-D generalized Reynolds) is
//!   solved at the point's sliding velocity (the roller balance's guess), body 1 the cam. One
//!   [`ThermalFiniteEngine`] per run carries the warm start, the 2-D preconditioner, the
//!   generalized Reynolds factors and the rows' temperature fields from one solve to the next
//!   (the previous angle, or the same angle at the balance's new entrainment). Quasi-steady: the
//!   thermal 2-D model has no squeeze or `∂T/∂t` term (the isothermal [`super::Finite`] steps the
//!   squeeze; the 1-D [`super::ThermalNumerical`] both).
//! * **Traction for the roller balance.** The balance evaluates the traction at many trial
//!   sliding velocities. The film's traction nodes (every loaded node of the 2-D grid, as
//!   [`super::Finite`]) take the isothermal viscosity at the inlet temperature times one factor
//!   `C`, calibrated so that the nodes' viscous force (the spec's shear law, Newtonian or Eyring,
//!   plus the Poiseuille stresses) equals the thermal model's follower force integrated over the
//!   whole contact (seed 000 eq. 9, rows then `y`) at the calibration slip: the point's own
//!   sliding velocity, or [`PROBE_SRR`]` · |u_m|` (one more energy pass over the rows at the held
//!   pressure and film) where the point's own slip is smaller. So the traction equals the
//!   thermal whole-contact traction at the calibration slip and follows the shear law's slip
//!   dependence with the thermal viscosity reduction held around it: the stronger heating of
//!   larger slips is not in the slope (stated in docs/seeds.md).
//! * A contact at rest (no entrainment) keeps the closed form, as [`super::Finite`].

use super::closed_form::ClosedForm;
use super::finite::{field_nodes, regime_of, Finite, FiniteFilm, FiniteTemperatures};
use super::{ContactInput, FilmModel, FilmModelId, FilmSolution, ThermalFilmSettings, Traction};
use crate::ehl::thermal_finite::{traction_at, ThermalFiniteEngine, ThermalFiniteInput};
use crate::ehl::twod::{Ehl2dOptions, Geometry2d};
use crate::ehl::Rheology;
use crate::friction::{viscous_traction_local, Rheology as Shear, TractionNode};
use crate::geometry::Crown;
use crate::{ensure_finite, SolveError};
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{Arc, Mutex};

/// Slide-to-roll ratio of the calibration probe where the point's own slip is smaller: the
/// viscous traction there is well above the rolling (Poiseuille) part, so the factor is well
/// conditioned.
pub const PROBE_SRR: f64 = 0.01;

/// Relative entrainment change beyond which the roller balance re-solves the film (a change of
/// the slide-to-roll ratio by twice it): the calibration holds the thermal viscosity reduction of
/// the solved slip, so the film is re-solved closer to the converged slip than the isothermal
/// 2-D model's 5e-3 (at which seed 000's nose traction was 8 % below the thermal traction at the
/// converged slip, solved 0.17 m/s against 0.144 m/s).
pub const ENTRAINMENT_TOLERANCE: f64 = 1e-3;

/// Bounds of the viscosity factor `C` (the thermal film is thinner in viscosity, not thicker:
/// above 1 only by the discretisation of the two integrals).
const FACTOR_RANGE: (f64, f64) = (1e-3, 2.0);

/// The thermal finite-line / point film model. See the module docs.
#[derive(Debug)]
pub struct ThermalFinite {
    /// The isothermal 2-D model's grid, crown and fallback (its problem and geometry).
    pub finite: Finite,
    pub settings: ThermalFilmSettings,
    engine: Mutex<ThermalFiniteEngine>,
    checked: AtomicBool,
}

impl ThermalFinite {
    pub fn new(options: Ehl2dOptions, crown: Option<Crown>, settings: ThermalFilmSettings, fallback: ClosedForm) -> Self {
        ThermalFinite { finite: Finite::new(options, crown, fallback), settings, engine: Mutex::new(ThermalFiniteEngine::new()), checked: AtomicBool::new(false) }
    }

    /// The film's shear law (seed 000's is Newtonian; Eyring from the spec's traction law).
    fn rheology(input: &ContactInput) -> Rheology {
        let eyring = match input.traction_law.rheology {
            Shear::Eyring { tau0 } => Some(tau0),
            Shear::Newtonian => None,
        };
        Rheology { eyring_stress: eyring, limiting_shear_coefficient: None, limiting_shear_stress: 0.0 }
    }
}

/// The viscosity factor `C` on `nodes` whose viscous force at `sliding` (m/s) equals `target`
/// (N): bisection on `ln C` (the force is monotone in `C` at a fixed slip), clamped to
/// [`FACTOR_RANGE`].
fn viscosity_factor(nodes: &[TractionNode], input: &ContactInput, sliding: f64, target: f64) -> f64 {
    let force = |c: f64| {
        let scaled: Vec<TractionNode> = nodes.iter().map(|n| TractionNode { viscosity: n.viscosity * c, ..*n }).collect();
        viscous_traction_local(&scaled, input.traction_law, sliding).force
    };
    let (mut lo, mut hi) = (FACTOR_RANGE.0.ln(), FACTOR_RANGE.1.ln());
    let s = sliding.signum();
    if s * (force(lo.exp()) - target) >= 0.0 {
        return lo.exp();
    }
    if s * (force(hi.exp()) - target) <= 0.0 {
        return hi.exp();
    }
    for _ in 0..40 {
        let mid = 0.5 * (lo + hi);
        if s * (force(mid.exp()) - target) < 0.0 {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    (0.5 * (lo + hi)).exp()
}

impl FilmModel for ThermalFinite {
    /// [`ENTRAINMENT_TOLERANCE`].
    fn entrainment_tolerance(&self) -> f64 {
        ENTRAINMENT_TOLERANCE
    }

    fn solve(&self, input: &ContactInput, previous: Option<&FilmSolution>) -> Result<FilmSolution, SolveError> {
        let load = input.load;
        if !(load > 0.0 && load.is_finite()) {
            return Err(SolveError::physical(crate::PhysicalFailure::NoContactLoad, format!("contact load {load} N is not positive")));
        }
        let um = input.entrainment_velocity;
        if um == 0.0 {
            return self.finite.fallback.solve(input, previous);
        }
        let first = !self.checked.swap(true, Ordering::Relaxed);
        let o = self.finite.options;
        let options = Ehl2dOptions { fields: true, grid_check: o.grid_check && first, ..o };
        let tin = ThermalFiniteInput { ehl: self.finite.problem(input), sliding_velocity: input.sliding_velocity, rheology: Self::rheology(input), bodies: self.settings.bodies };
        let thermal = self.settings.options;
        let mut engine = self.engine.lock().unwrap_or_else(|e| e.into_inner());
        // A solve that does not converge from the carried state is retried cold (isothermal start).
        let th = match engine.solve(&tin, &options, &thermal, &input.interrupts) {
            Err(SolveError::NotConverged { .. }) => {
                engine.reset();
                engine.solve(&tin, &options, &thermal, &input.interrupts)?
            }
            other => other?,
        };
        let warm = engine.warm().cloned().ok_or_else(|| SolveError::NonFinite { quantity: "thermal 2-D warm start".into() })?;
        drop(engine);
        let s = &th.ehl;
        let f = s.fields.as_ref().ok_or_else(|| SolveError::NonFinite { quantity: "2-D EHL fields".into() })?;
        let (nx, ny) = (f.x.len(), f.y.len());
        let (mut nodes, area, w_a) = field_nodes(input, f);
        // Calibration of the nodes' viscosity to the whole-contact thermal traction (module docs).
        let probe = PROBE_SRR * um.abs();
        let (slip, force) = if input.sliding_velocity.abs() >= probe {
            (input.sliding_velocity, th.traction.force_body_2)
        } else {
            let at = if input.sliding_velocity < 0.0 { -probe } else { probe };
            (at, traction_at(&ThermalFiniteInput { sliding_velocity: at, ..tin }, s, &thermal)?.force_body_2)
        };
        let fluid = 1.0 - w_a / load;
        let c = viscosity_factor(&nodes, input, slip, fluid * force);
        for n in &mut nodes {
            n.viscosity *= c;
        }
        let centre_row = (ny - 1) / 2;
        let exit_film = (0..nx).map(|i| f.film[centre_row * nx + i]).fold(f64::INFINITY, f64::min);
        let steady = self.finite.fallback.solve(input, None)?.steady_central_film;
        let r_roll = match self.finite.geometry(input) {
            Geometry2d::Finite { rx, .. } | Geometry2d::Point { rx, .. } => rx,
        };
        let temperatures = FiniteTemperatures { film_max: th.film_temperature_max.value, surface_max_1: th.surface_temperature_max_1, surface_max_2: th.surface_temperature_max_2 };
        ensure_finite("thermal 2-D film", [&s.central_film, &s.min_film.value, &exit_film, &s.max_pressure.value, &w_a, &area, &c, &temperatures.film_max, &temperatures.surface_max_1, &temperatures.surface_max_2])?;
        let sigma = input.roughness.sigma;
        Ok(FilmSolution {
            model: FilmModelId::ThermalFinite,
            central_film: s.central_film,
            min_film: s.min_film.value,
            steady_central_film: steady,
            max_pressure: s.max_pressure.value,
            pressure_spike: None,
            pressure_spike_position: None,
            exit_film: Some(exit_film),
            half_width: s.hertz_half_width,
            contact_area: area,
            asperity: input.asperity_friction.contact(w_a, s.hertz_half_width, r_roll, s.central_film),
            asperity_nodes: Vec::new(),
            lambda: (sigma > 0.0).then(|| s.min_film.value / sigma),
            regime: regime_of(input),
            nodes,
            rolling_force: 0.0,
            viscosity_law: None,
            profile: None,
            iterations: Some(th.convergence.iterations),
            thermal: None,
            finite: Some(Box::new(FiniteFilm {
                edge_pressure_peak: s.edge_pressure_peak.map(|e| (e.value, e.y)),
                min_film_position: (s.min_film.x, s.min_film.y),
                grid: (s.nx, s.ny),
                grid_error: s.grid_error,
                warm_started: s.warm_started,
                warm: Arc::new(warm),
                prior: None,
                solved_entrainment: um,
                entrainment: um,
                solved_at: (load, input.shape, input.temperature),
                squeeze_step: None,
                step_change: None,
                settled: false,
                temperatures: Some(temperatures),
            })),
        })
    }

    /// The default nodal traction over the calibrated nodes (module docs).
    fn traction_local(&self, film: &FilmSolution, input: &ContactInput, sliding: f64) -> (Traction, (f64, f64)) {
        super::nodal_traction_local(film, input, sliding, self.stick_limit(film, input))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::ehl::thermal::{FilmHeat, ThermalBodies, ThermalOptions};
    use crate::film::{ContactShape, FilmFormula, SmoothContact};
    use crate::thermal::ThermalSolid;

    /// Seed 000's crowned roller at the nose (954 N, R = 10.37 mm, u_m = 2.77 m/s, SRR 0.05,
    /// 33×65, Newtonian): the calibrated nodal traction at the solved slip is the whole-contact
    /// thermal traction (to 1e-6 of it), below the isothermal nodes' (the thermal viscosity
    /// factor is below 1), and it grows with the slip; the film runs hotter than the inlet.
    #[test]
    fn calibrated_traction_is_the_thermal_traction_at_the_solved_slip() {
        let smooth = SmoothContact::seed000();
        let mut input = smooth.input(954.0, ContactShape::Line { reduced_radius: 0.01037, length: 0.014 }, 2.77);
        input.sliding_velocity = 0.05 * 2.77;
        let options = Ehl2dOptions { nx: 33, ny: 65, tolerance: 1e-6, grid_check: false, grid_tolerance: 0.5, ..Default::default() };
        let bodies = ThermalBodies { film: FilmHeat { conductivity: 0.14, specific_heat: 1700.0 }, body_1: ThermalSolid::STEEL, body_2: ThermalSolid::STEEL };
        let settings = ThermalFilmSettings { options: ThermalOptions::default(), bodies, carry_tolerance: None };
        let fallback = ClosedForm { formula: FilmFormula::PanHamrock, squeeze: false };
        let model = ThermalFinite::new(options, Some(Crown::SEED000), settings, fallback);
        let film = model.solve(&input, None).unwrap();
        let t = film.finite.as_deref().and_then(|f| f.temperatures).unwrap();
        assert!(t.film_max > input.temperature + 1.0, "{t:?}");
        // The thermal force again, from a fresh solve of the same problem.
        let tin = ThermalFiniteInput { ehl: model.finite.problem(&input), sliding_velocity: input.sliding_velocity, rheology: ThermalFinite::rheology(&input), bodies };
        let th = crate::ehl::thermal_finite::solve(&tin, &Ehl2dOptions { fields: true, ..options }, &settings.options, &crate::Silent).unwrap();
        let at = model.traction(&film, &input, input.sliding_velocity).viscous;
        assert!((at / th.traction.force_body_2 - 1.0).abs() < 1e-6, "{at} vs {}", th.traction.force_body_2);
        let iso = Finite::new(options, Some(Crown::SEED000), fallback).solve(&input, None).unwrap();
        let iso_force = model.finite.traction(&iso, &input, input.sliding_velocity).viscous;
        assert!(at < iso_force, "{at} vs isothermal {iso_force}");
        assert!(model.traction(&film, &input, 2.0 * input.sliding_velocity).viscous > at);
    }
}
