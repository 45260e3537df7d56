//! The `accurate` film model: the numerical line-contact EHL solver ([`crate::ehl`]) at
//! every contact point.
//!
//! * **Line contacts** (flat-faced and roller followers): the isothermal, compressible,
//!   Roelands/Barus EHL problem with elastic deflection, load balance and cavitation is solved on
//!   [`EhlOptions::nodes`] graded nodes. Consecutive points of a run are time steps: when the
//!   previous solution carries its converged fields ([`FilmSolution::profile`]) and
//!   `input.time_step > 0`, the squeeze term `∂(ρh)/∂t` is formed from it (backward Euler) and the
//!   Newton iteration starts from it; without a time step it is only a warm start.
//! * **Point contacts** (the spherical tappet) keep the closed form (Hamrock–Dowson): the solver is
//!   one-dimensional. The solution then reports the closed form's model id.
//! * **No entrainment and no history** (the instant of rest at the start of a startup): a steady
//!   film needs entrainment, so the closed form answers (no film: dry contact).
//!
//! From the converged solution: central, minimum and exit film, peak pressure, the exit pressure
//! spike (height and position), traction nodes (every grid node with positive fluid pressure: its
//! cell times the contact length, the node's fluid pressure, viscosity and film) and the profiles.
//! Rough surfaces (σ > 0) share the load *inside* the solution ([`super::mixed`]): the solver's
//! load balance and deflection carry the fluid pressure plus `p_a(h)` of the local film, the
//! asperity load is `W_a = L ∫ p_a dx` of the converged solution and the model id
//! [`FilmModelId::NumericalMixed`].
//!
//! Thermal effects are not modelled (isothermal at the inlet temperature), like the closed forms.

use super::closed_form::{ClosedForm, FILM_FLOOR, VISCOSITY_CAP};
use super::formulas::LineGroups;
use super::{ContactInput, ContactShape, FilmModel, FilmModelId, FilmProfile, FilmSolution, Regime};
use crate::contact::hertz_line;
use crate::ehl::grid::{cells, Layout};
use crate::ehl::transient::lattice_layout;
use super::mixed::LoadSharingLaw;
use crate::ehl::{AsperityPressure, EhlInput, EhlOptions, EhlState, Extrapolation, ReusableSolver, Rheology, Transient};
use crate::friction::TractionNode;
use crate::{ensure_finite, SolveError};
use std::sync::Mutex;

/// The numerical (`accurate`) film model. See the module docs.
///
/// One model serves one run (a cycle's angles in order): it keeps the EHL solver's grids,
/// influence matrices and LU factors between calls ([`ReusableSolver`]), while the state (squeeze
/// history, warm start) comes with each call's `previous` solution. Measured on the seed 000
/// roller cycle at 192 nodes: `BENCHMARKS.md`, "Film models".
#[derive(Debug)]
pub struct Numerical {
    /// Resolution, tolerance and iteration cap of the EHL solver.
    pub options: EhlOptions,
    /// The closed form used for point contacts and for a contact at rest without history.
    pub fallback: ClosedForm,
    /// Grid extrapolation: [`Extrapolation::Richardson`] solves `options.nodes` and
    /// `(options.nodes − 1)/2 + 1` nodes and extrapolates the films and traction forces.
    pub extrapolation: Extrapolation,
    /// The solver's caches (used by one call at a time; a concurrent call solves without them).
    solver: Mutex<ReusableSolver>,
}

impl Numerical {
    /// The model with EHL `options` on one grid and the closed form `fallback`.
    pub fn new(options: EhlOptions, fallback: ClosedForm) -> Self {
        Numerical { options, fallback, extrapolation: Extrapolation::None, solver: Mutex::new(ReusableSolver::new()) }
    }

    /// The same model with grid `extrapolation`.
    pub fn with_extrapolation(self, extrapolation: Extrapolation) -> Self {
        Numerical { extrapolation, ..self }
    }

    /// The grid layout this model solves `input` on (a line contact of reduced radius `r` and
    /// length `length`, m): a pure function of the conditions
    /// ([`crate::ehl::transient::lattice_layout`]).
    pub fn layout(&self, input: &ContactInput, r: f64, length: f64) -> Layout {
        let ehl_input = EhlInput {
            load_per_length: input.load / length,
            reduced_radius: r,
            effective_modulus: 2.0 * input.contact_modulus,
            entrainment_velocity: input.entrainment_velocity,
            sliding_velocity: input.sliding_velocity,
            lubricant: *input.lubricant,
            temperature: input.temperature,
            rheology: Rheology::default(),
            transient: None,
            warm_start: None,
            asperity: None,
        };
        lattice_layout(&ehl_input, &self.options)
    }
}

impl FilmProfile {
    /// The EHL solver's state (warm start, squeeze history) held by this profile.
    pub fn to_ehl_state(&self) -> EhlState {
        EhlState { x: self.x.clone(), pressure: self.pressure.clone(), film: self.film.clone(), density_ratio: self.density_ratio.clone(), asperity_pressure: self.asperity_pressure.clone() }
    }
}

impl FilmModel for Numerical {
    /// 1e-4: the film moves by < 1e-4 relative, against a discretisation error of ≈ 1e-2.
    fn entrainment_tolerance(&self) -> f64 {
        1e-4
    }

    fn solve(&self, input: &ContactInput, previous: Option<&FilmSolution>) -> Result<FilmSolution, SolveError> {
        let Some(LineContact { r, length, load, state }) = line_contact(input, previous)? else {
            return self.fallback.solve(input, previous);
        };
        let transient = state.as_ref().filter(|_| input.time_step > 0.0).map(|s| Transient { previous: s, time_step: input.time_step });
        let w = load / length;
        let es = input.contact_modulus;
        let sigma = input.roughness.sigma;
        // Mixed lubrication: the asperities share the load inside the solution.
        let law = LoadSharingLaw { roughness: input.roughness.clone(), contact_modulus: es };
        let ehl_input = EhlInput {
            load_per_length: w,
            reduced_radius: r,
            effective_modulus: 2.0 * es,
            entrainment_velocity: input.entrainment_velocity,
            sliding_velocity: input.sliding_velocity,
            lubricant: *input.lubricant,
            temperature: input.temperature,
            // The solver's own traction is not used: traction comes from the nodes below.
            rheology: Rheology::default(),
            transient,
            warm_start: state.as_ref(),
            asperity: (sigma > 0.0).then_some(&law as &dyn AsperityPressure),
        };
        let options = EhlOptions { profiles: false, ..self.options };
        let mut fresh = ReusableSolver::new();
        let mut cached = self.solver.try_lock();
        let solver = match &mut cached {
            Ok(guard) => &mut **guard,
            Err(_) => &mut fresh,
        };
        let (s, coarse) = match self.extrapolation {
            Extrapolation::None => (solver.solve(&ehl_input, &options, &input.interrupts)?, None),
            Extrapolation::Richardson => {
                let coarse_previous = previous.and_then(|p| p.profile.as_deref()).and_then(|p| p.coarse.as_ref());
                let r = solver.solve_richardson(&ehl_input, coarse_previous, &options, &input.interrupts)?;
                (r.solution, r.coarse_state)
            }
        };
        drop(cached);
        // The closed form's steady film: what `steady_central_film` means (the next point's
        // squeeze estimate of a closed form or of `auto` reads it).
        let steady = self.fallback.solve(input, None)?.steady_central_film;
        let st = &s.state;
        let cell = cells(&st.x);
        let w_a = (s.asperity_load_per_length * length).clamp(0.0, load);
        let t = input.temperature;
        let nodes = traction_nodes(input, st, &cell, length, 1.0, t);
        // The local micro-slip map (seed 001 eq. 22–23): the solved p_a(x) with its own film.
        let asperity_nodes = input.asperity_friction.asperity_nodes(&st.x, &st.film, &st.asperity_pressure, &cell, length, input.entrainment_velocity);
        let hz = hertz_line(w, r, es);
        let eta0 = input.lubricant.viscosity_at(0.0, t);
        let g = LineGroups::new(w, r, input.entrainment_velocity, eta0, input.lubricant.pressure_viscosity, 2.0 * es);
        let regime = (g.speed > 0.0).then(|| Regime { viscous: g.viscous_parameter(), elastic: g.elastic_parameter() });
        ensure_finite("numerical film", [&s.central_film, &s.min_film, &s.exit_film, &s.max_pressure, &w_a])?;
        ensure_finite("traction nodes", nodes.iter().flat_map(|n| [&n.area, &n.pressure, &n.viscosity, &n.film]))?;
        Ok(FilmSolution {
            model: if sigma > 0.0 { FilmModelId::NumericalMixed } else { FilmModelId::Numerical },
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
            asperity_nodes,
            lambda: (sigma > 0.0).then(|| s.min_film / sigma),
            regime,
            nodes,
            rolling_force: 0.0,
            viscosity_law: None,
            profile: Some(Box::new(FilmProfile {
                x: s.state.x,
                pressure: s.state.pressure,
                film: s.state.film,
                density_ratio: s.state.density_ratio,
                coarse,
                asperity_pressure: s.state.asperity_pressure,
            })),
            iterations: Some(s.convergence.iterations),
            thermal: None,
            finite: None,
        })
    }
}

/// A line contact the numerical models solve: reduced radius and length (m), load (N) and the
/// previous point's converged state.
pub(super) struct LineContact {
    pub r: f64,
    pub length: f64,
    pub load: f64,
    pub state: Option<EhlState>,
}

/// The line contact of `input`, or `None` where the closed form answers: a point contact, or no
/// entrainment without a transient history. A non-positive load is an error.
pub(super) fn line_contact(input: &ContactInput, previous: Option<&FilmSolution>) -> Result<Option<LineContact>, SolveError> {
    let (r, length) = match input.shape {
        ContactShape::Line { reduced_radius, length } => (reduced_radius, length),
        ContactShape::Point { .. } => return Ok(None),
    };
    let load = input.load;
    if !(load > 0.0 && load.is_finite()) {
        return Err(SolveError::physical(crate::PhysicalFailure::NoContactLoad, format!("contact load {load} N is not positive")));
    }
    let state: Option<EhlState> = previous.and_then(|p| p.profile.as_deref()).map(FilmProfile::to_ehl_state);
    if input.entrainment_velocity == 0.0 && !(state.is_some() && input.time_step > 0.0) {
        return Ok(None);
    }
    Ok(Some(LineContact { r, length, load, state }))
}

/// Greenwood–Tripp load sharing with the local film: `W_a = L Σ p_a(h_i) Δx_i`, capped at the load.
pub(super) fn asperity_load(input: &ContactInput, st: &EhlState, cell: &[f64], length: f64, load: f64) -> f64 {
    if input.roughness.sigma <= 0.0 {
        return 0.0;
    }
    let es = input.contact_modulus;
    let per_length: f64 = st.film.iter().zip(cell).map(|(h, dx)| input.roughness.asperity_pressure(*h, es) * dx).sum();
    (per_length * length).min(load)
}

/// Traction nodes of a converged film: every node with positive fluid pressure, its cell times
/// the contact length, `fluid_share` times its fluid pressure ([`EhlState::fluid_pressure`]), its
/// viscosity at temperature `t` and that fluid pressure, its film, and the Poiseuille stress
/// `−(h/2) dp/dx` of that pressure (seed 001 eq. 24; central differences on the nonuniform grid,
/// one-sided at the ends).
pub(super) fn traction_nodes(input: &ContactInput, st: &EhlState, cell: &[f64], length: f64, fluid_share: f64, t: f64) -> Vec<TractionNode> {
    let n = st.x.len();
    (0..n)
        .filter(|&i| st.fluid_pressure(i) > 0.0)
        .map(|i| {
            let (a, b) = (i.saturating_sub(1), (i + 1).min(n - 1));
            let dpdx = if b > a { fluid_share * (st.fluid_pressure(b) - st.fluid_pressure(a)) / (st.x[b] - st.x[a]) } else { 0.0 };
            let film = st.film[i].max(FILM_FLOOR);
            TractionNode {
                area: cell[i] * length,
                pressure: fluid_share * st.fluid_pressure(i),
                viscosity: input.lubricant.viscosity_at(st.fluid_pressure(i), t).min(VISCOSITY_CAP),
                film,
                poiseuille: -0.5 * film * dpdx,
            }
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::film::FilmFormula;
    use crate::friction::{AsperityFriction, AsperityModel, Rheology as Shear, Roughness, TractionLaw};
    use crate::lubricant::Lubricant;

    fn model() -> Numerical {
        Numerical::new(
            EhlOptions { nodes: 96, tolerance: 1e-8, ..EhlOptions::default() },
            ClosedForm { formula: FilmFormula::PanHamrock, squeeze: false },
        )
    }

    #[test]
    fn nodes_carry_the_load_and_a_reversal_keeps_a_squeeze_film() {
        let lub = Lubricant { viscosity: 0.013, pressure_viscosity: 1.84e-8, ..Lubricant::SEED000 };
        let rough = Roughness { sigma: 0.0, eta_beta_sigma: 0.04, sigma_over_beta: 0.001, plastic_limit: f64::INFINITY, curve: None };
        let law = TractionLaw { rheology: Shear::Eyring { tau0: 5e6 }, limiting_shear_coefficient: None };
        let asp = AsperityFriction { coefficient: 0.1, model: AsperityModel::Coulomb, map: None };
        // Seed 001 nose (12.5 kN over 21 mm, R = 10.5 mm, 3.98 m/s).
        let input = ContactInput {
            load: 12_500.0,
            shape: ContactShape::Line { reduced_radius: 0.0105, length: 0.021 },
            entrainment_velocity: 3.98,
            sliding_velocity: 0.04,
            time: 0.0,
            time_step: 0.0,
            contact_modulus: 100e9 / 0.91,
            temperature: lub.reference_temperature,
            lubricant: &lub,
            roughness: &rough,
            traction_law: &law,
            asperity_friction: &asp,
            interrupts: crate::Interrupts::NONE,
        };
        let m = model();
        let f = m.solve(&input, None).unwrap();
        assert_eq!(f.model, FilmModelId::Numerical);
        let load: f64 = f.nodes.iter().map(|n| n.area * n.pressure).sum();
        assert!((load / 12_500.0 - 1.0).abs() < 0.02, "{load}");
        assert!(f.pressure_spike.is_some() && f.exit_film.unwrap() >= f.min_film);
        assert!(f.iterations.is_some() && f.profile.is_some());
        // Entrainment stops 0.1 ms later: without history a steady film has no solution (the
        // closed form answers: no film); with history the squeeze film remains.
        let stop = ContactInput { entrainment_velocity: 0.0, time_step: 1e-4, ..input };
        let dry = m.solve(&ContactInput { time_step: 0.0, ..stop }, None).unwrap();
        assert_eq!(dry.model, FilmModelId::PanHamrock);
        let squeeze = m.solve(&stop, Some(&f)).unwrap();
        assert_eq!(squeeze.model, FilmModelId::Numerical);
        assert!(squeeze.central_film > 0.3 * f.central_film && squeeze.central_film < f.central_film, "{} vs {}", squeeze.central_film, f.central_film);
        // Point contacts keep the closed form.
        let point = ContactInput { shape: ContactShape::Point { rx: 0.0142, ry: 0.042 }, load: 500.0, ..input };
        assert_eq!(m.solve(&point, None).unwrap().model, FilmModelId::HamrockDowson);
    }

    /// The closed forms' Goksem–Hargreaves rolling force against the numerical film's own
    /// `Σ A (−(h/2) dp/dx)` (seed 001 eq. 24, Newtonian) over seed 001's load and speed range, a
    /// light-load case and a reversal: same sign (against the entrainment) and within 16 % (measured
    /// −15 % … +14 %: the regression was fitted to Barus solutions of 1978, ours is Roelands).
    /// Run with `--nocapture` for the table.
    #[test]
    fn goksem_hargreaves_matches_the_numerical_rolling_force() {
        use super::super::closed_form::test_inputs::{oil, seed001_nose};
        use crate::friction::poiseuille_force;
        let lub = oil();
        let rough = Roughness { sigma: 0.0, eta_beta_sigma: 0.04, sigma_over_beta: 0.001, plastic_limit: f64::INFINITY, curve: None };
        let law = TractionLaw { rheology: Shear::Newtonian, limiting_shear_coefficient: None };
        let asp = AsperityFriction { coefficient: 0.1, model: AsperityModel::Coulomb, map: None };
        let nose = seed001_nose(&lub, &rough, &law, &asp);
        let numerical = Numerical::new(EhlOptions { nodes: 384, tolerance: 1e-9, ..EhlOptions::default() }, ClosedForm { formula: FilmFormula::PanHamrock, squeeze: false });
        let closed = ClosedForm { formula: FilmFormula::PanHamrock, squeeze: false };
        let mut worst: f64 = 0.0;
        for (load, r, u) in [(12_500.0, 0.0105, 3.98), (2_250.0, 0.0152, 1.5), (2_250.0, 0.0152, 6.0), (6_000.0, 0.012, 0.5), (300.0, 0.02, 2.0), (12_500.0, 0.0105, -3.98)] {
            let input = ContactInput { load, shape: ContactShape::Line { reduced_radius: r, length: 0.021 }, entrainment_velocity: u, ..nose };
            let f = numerical.solve(&input, None).unwrap();
            let c = closed.solve(&input, None).unwrap();
            let (fr_n, fr_c) = (poiseuille_force(&f.nodes), c.rolling_force);
            let err = fr_c / fr_n - 1.0;
            println!("W {load} N R {r} u {u}: numerical {fr_n:.4} N closed form {fr_c:.4} N ({:+.1} %), {:.2e} of the load", 100.0 * err, fr_n.abs() / load);
            assert!(fr_n * u < 0.0 && fr_c * u < 0.0, "against the entrainment");
            worst = worst.max(err.abs());
        }
        assert!(worst < 0.16, "{worst}");
    }

}
