//! The finite-length / point film model (`ehl.geometry: finite`): the 2-D isothermal EHL solver
//! ([`crate::ehl::twod`], seed 000 eq. 2–6 over `x` and `y`) at every contact point.
//!
//! * **Roller followers**: the finite line contact of the roller's axial profile (the crowned
//!   roller of seed 000 eq. 3 when the follower has a crown; otherwise a straight roller of the
//!   contact length with square ends), reduced radius from the input's shape.
//! * **Spherical followers**: the elliptic point contact `R_x`, `R_y` of the input's shape.
//! * **No entrainment** (a contact at rest): the steady 2-D film needs entrainment; the closed
//!   form answers, as for the 1-D [`super::Numerical`].
//!
//! Warm start: each point starts from the previous point's converged 2-D pressure (carried in
//! [`FilmSolution::finite`]) rescaled to the new Hertzian scales ([`twod::solve_from`]), or from
//! the secant extrapolation through it and the point before (the film carries the warm start it
//! was solved from, [`FiniteFilm::prior`]) when that has the smaller Newton residual
//! ([`twod::solve_kept`]); the
//! cold nested iteration runs only at the first point or when the warm start fails.
//!
//! Squeeze ([`Finite::squeeze`], `ehl.squeeze`, on in the cam kinds by default): a point with a
//! time step and a previous 2-D film is one backward-Euler step of the transient problem (seed 000
//! eq. 2's `12 ∂(ρh)/∂t`) from that film ([`twod::solve_transient`]), as the 1-D line model steps
//! along a cycle; the first point (and a point after a closed-form one) is steady. Without it the
//! model is steady (quasi-steady along a cycle) and Newtonian; its film then does not depend on
//! the sliding velocity or on the previous point beyond the Newton tolerance, so it is
//! history-free (a dwell reuses a film).
//! Optional (off by default, [`Finite::with_rescale_range`]): a film at the same load and shape
//! and an entrainment within [`RESCALE_RANGE`] is rescaled `h ∝ u^0.69` instead of solved.
//!
//! From the converged fields: central film (centre of the contact), minimum film and where it
//! sits (axial position `y`), the exit film (the smallest film on the centre line), peak pressure,
//! the edge pressure peak of a finite roller (`max_x p` along the roller, its largest off-centre
//! maximum above the centre value) and its axial position, and traction nodes (every grid node
//! with positive pressure: cell area `Δx Δy`, pressure, viscosity, film, Poiseuille stress
//! `−(h/2) ∂p/∂x`, seed 001 eq. 24). Rough surfaces: the asperity load is the Greenwood–Tripp
//! pressure of the local film summed over the grid *after* the smooth solve (not in its load
//! balance, unlike the 1-D `numerical_mixed`), capped at the load; the fluid nodes then carry the
//! remaining share.

use super::closed_form::{ClosedForm, FILM_FLOOR, VISCOSITY_CAP};
use super::formulas::LineGroups;
use super::{ContactInput, ContactShape, FilmModel, FilmModelId, FilmSolution, Regime};
use crate::ehl::twod::{self, Ehl2dInput, Ehl2dOptions, Fields2d, Geometry2d, Kept2d, Warm2d};
use crate::friction::TractionNode;
use crate::geometry::Crown;
use crate::{ensure_finite, SolveError};
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{Arc, Mutex};

/// What the 2-D model adds to a [`FilmSolution`].
#[derive(Debug, Clone, PartialEq)]
pub struct FiniteFilm {
    /// Largest off-centre maximum of the pressure along the roller (finite line contacts):
    /// `(pressure Pa, axial position m from the roller centre)`; `None` when the pressure falls
    /// monotonically from the centre or for point contacts.
    pub edge_pressure_peak: Option<(f64, f64)>,
    /// Where the minimum film sits: `(x, y)`, m from the contact centre (`x` along the rolling
    /// direction, positive downstream; `y` along the roller axis / across the rolling).
    pub min_film_position: (f64, f64),
    /// Grid `nx × ny`.
    pub grid: (usize, usize),
    /// The resolution check's estimate of the central film's discretisation error, when it ran.
    pub grid_error: Option<f64>,
    /// Whether the warm start from the previous point converged (false: cold nested solve).
    pub warm_started: bool,
    /// The converged pressure in the solver's scales: the next point's warm start.
    pub warm: Arc<Warm2d>,
    /// The warm start this film was solved from (the previous point's `warm`, shared): with
    /// `warm` the next point's start is extrapolated along the chain ([`twod::solve_kept`]).
    pub prior: Option<Arc<Warm2d>>,
    /// The entrainment velocity (m/s) of the Newton solve this film comes from; it differs from
    /// the film's own entrainment when the film was rescaled ([`Finite`]'s entrainment rescale).
    pub solved_entrainment: f64,
    /// The entrainment velocity of this film, m/s.
    pub entrainment: f64,
    /// Load (N), shape and temperature (K) of that solve: a rescale needs them equal.
    pub solved_at: (f64, ContactShape, f64),
    /// The time step (s) of the backward-Euler squeeze step this film was solved by, from the
    /// film `prior` was taken from (`None`: a steady solve).
    pub squeeze_step: Option<f64>,
    /// The relative change of the central/minimum film (the larger) by this squeeze step from the
    /// previous film, when that film was solved at the same load, shape, temperature and time step
    /// and an entrainment within the model's tolerance (a stretch of unchanging conditions);
    /// `None` otherwise.
    pub step_change: Option<f64>,
    /// The squeeze step has settled ([`SETTLED`]): the second or later step of a stretch of
    /// unchanging conditions, it moved the films by less than [`SETTLED`] and, from the third
    /// step on, by no more than the step before it did (a film still rising or swinging after a
    /// change is not settled). The roller march reuses a settled film on a dwell
    /// ([`FilmSolution::settled`]) as it reuses a quasi-steady one.
    pub settled: bool,
    /// The thermal finite-line / point model ([`super::thermal_finite`]): the largest film
    /// temperature and the largest surface temperatures of body 1 (cam) and body 2, K.
    pub temperatures: Option<FiniteTemperatures>,
}

/// Temperatures of a thermal 2-D film, K.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FiniteTemperatures {
    pub film_max: f64,
    pub surface_max_1: f64,
    pub surface_max_2: f64,
}

/// Largest relative step-to-step change of the central and minimum films at which a squeeze
/// step on unchanging conditions counts as settled ([`FiniteFilm::settled`]). Backward Euler
/// relaxes the film towards the steady one by a factor `r = τ/(τ + Δt)` per step, so a step that
/// moved it by δ leaves `δ r/(1 − r) = δ τ/Δt` to go; a film drifting with slowly changing
/// conditions (the entrainment on a dwell follows the roller's speed) lags the steady one by the
/// same `δ τ/Δt`. Measured on the seed 000 roller at 600 N, 2 m/s and the cycle's 1° step at
/// 950 rpm: r ≈ 0.33 (τ/Δt ≈ 0.5), the first settled film (δ = 8e-4 after 2.4e-3) 3e-4 from the
/// steady one (`a_settled_squeeze_step_stands_for_the_next_on_a_dwell`); at δ = 2e-3 it would be
/// ≈ 1e-3. That is inside what the march
/// already accepts on a dwell (a film within its entrainment tolerance, 5e-3 ≈ 3.5e-3 in film)
/// and far below the 2-D grid's 1–2 % discretisation error. Much finer angle steps (τ/Δt ≫ 1)
/// settle later (smaller δ per step) but accept up to `SETTLED τ/Δt`.
pub const SETTLED: f64 = 2e-3;

/// The finite-length / point film model. See the module docs.
#[derive(Debug)]
pub struct Finite {
    /// Grid, tolerance, iteration cap and resolution check of the 2-D solver.
    pub options: Ehl2dOptions,
    /// The roller's axial profile (`None`: a straight roller of the input's contact length).
    pub crown: Option<Crown>,
    /// The closed form for a contact at rest and for `steady_central_film`.
    pub fallback: ClosedForm,
    /// Run the resolution check at the first solve only (then `options.grid_check` is cleared
    /// for warm-started solves): a cycle's grid is checked where it starts. False: every solve
    /// as `options` say.
    pub check_first_only: bool,
    /// Largest relative entrainment change taken by [`Finite::rescaled`] instead of a Newton
    /// solve when the previous film has the same load and shape (0, the default: always solve;
    /// [`RESCALE_RANGE`] is the measured candidate — off by default because inside the cam
    /// cycle a film that is sometimes rescaled and sometimes solved is not a smooth function of
    /// the entrainment: at 0.5 % the seed 000 cycle's periodic roller speed stalled at a
    /// residual of 1.5e-6 against 1e-8, BENCHMARKS.md issue 16, `ehl2d-6`).
    pub rescale_range: f64,
    /// The squeeze term of seed 000 eq. 2 (`12 ∂(ρh)/∂t`): a point with a time step and a previous
    /// 2-D film is solved as one backward-Euler step from that film ([`twod::solve_transient`]);
    /// false: every point steady (quasi-steady, history-free). [`Finite::with_squeeze`].
    pub squeeze: bool,
    checked: AtomicBool,
    /// The 2-D Newton preconditioner of the last solve, for the next one on the same grid (the
    /// next contact point; [`twod::solve_kept`]). Taken out for a solve and put back after it: a
    /// concurrent solve on the same model just starts without one.
    kept: Mutex<Kept2d>,
}

impl Finite {
    pub fn new(options: Ehl2dOptions, crown: Option<Crown>, fallback: ClosedForm) -> Self {
        Finite { options, crown, fallback, check_first_only: false, rescale_range: 0.0, squeeze: false, checked: AtomicBool::new(false), kept: Mutex::new(Kept2d::default()) }
    }

    /// The same model with the squeeze term on (`true`) or off.
    pub fn with_squeeze(self, squeeze: bool) -> Self {
        Finite { squeeze, ..self }
    }

    /// The same model with the entrainment rescale over `range` (0: off, every film solved).
    pub fn with_rescale_range(self, range: f64) -> Self {
        Finite { rescale_range: range, ..self }
    }

    /// The same model checking the grid at its first solve only.
    pub fn check_first_only(self) -> Self {
        Finite { check_first_only: true, ..self }
    }

    /// The 2-D problem of `input` (isothermal at the input's temperature, `E' = 2E*`).
    pub(super) fn problem(&self, input: &ContactInput) -> Ehl2dInput {
        Ehl2dInput {
            load: input.load,
            geometry: self.geometry(input),
            effective_modulus: 2.0 * input.contact_modulus,
            entrainment_velocity: input.entrainment_velocity,
            lubricant: *input.lubricant,
            temperature: input.temperature,
        }
    }

    /// The 2-D geometry of `input`.
    pub fn geometry(&self, input: &ContactInput) -> Geometry2d {
        match input.shape {
            ContactShape::Line { reduced_radius, length } => {
                let crown = self.crown.unwrap_or(Crown { length, middle_length: length, crown_height: 0.0, end_radius: 1.0, profile: Default::default() });
                Geometry2d::Finite { rx: reduced_radius, crown }
            }
            ContactShape::Point { rx, ry } => Geometry2d::Point { rx, ry },
        }
    }
}

/// Largest relative entrainment change over which [`Finite`] rescales a neighbouring film instead
/// of solving (see [`Finite::rescaled`]).
///
/// 0.5 %: measured against Newton solves on seed 000's roller at the nose (`tests/it/ehl_2d_cam.rs`
/// `entrainment_rescale_matches_the_solve`, 33×65) the rescale's error grows linearly with the
/// change — at 1.9 %: central film 1.0e-3, minimum film 3.2e-3, viscous traction 9e-3 (the 2-D
/// film's local exponent there is ≈ 0.76, not the formulas' 0.69, and the pressure field moves
/// too); at 0.5 % a quarter of that, below the 2-D grid's own error (1–5 %) by an order of
/// magnitude.
pub const RESCALE_RANGE: f64 = 0.005;

/// Exponents of the film on the entrainment velocity at constant load, shape and lubricant:
/// central and minimum film, `h ∝ u^k`. Line contacts: Pan & Hamrock (1989) `H_c ∝ U^0.692`,
/// `H_min ∝ U^0.694`; point contacts: Hamrock & Dowson (1977) `H_c ∝ U^0.67`, `H_min ∝ U^0.68`.
/// The 2-D roller is a line contact with ends: the line values.
const RESCALE_EXPONENT_LINE: (f64, f64) = (0.692, 0.694);
const RESCALE_EXPONENT_POINT: (f64, f64) = (0.67, 0.68);

impl Finite {
    /// The entrainment rescale: `previous`, a 2-D film solved at the same load, shape, lubricant
    /// and temperature and an entrainment `u0` within [`RESCALE_RANGE`] of `input`'s (same sign),
    /// taken to `input`'s entrainment `u` by the film's known dependence `h ∝ u^k` (the exponents
    /// above; the central film's at every node, the minimum film's for the minimum and exit
    /// film) with the pressure field unchanged (it moves with `u` only through the inlet and
    /// exit details, second order here). The model is steady and isothermal: a small entrainment
    /// change, as the roller's slip balance makes when the converged sliding moves the
    /// entrainment by `u_s/2`, needs no new Newton solve. Traction nodes: films scaled, the
    /// Poiseuille stress `−(h/2) ∂p/∂x` with them. `None`: not applicable (different load or
    /// shape, out of range, or an asperity load above 1e-9 of the load, which would move with the
    /// film).
    pub fn rescaled(&self, input: &ContactInput, previous: &FilmSolution) -> Option<FilmSolution> {
        let f = previous.finite.as_deref()?;
        let (load, shape, temperature) = f.solved_at;
        let (u0, u) = (f.solved_entrainment, input.entrainment_velocity);
        let ratio = u / u0;
        if load != input.load || shape != input.shape || temperature != input.temperature || !(ratio > 0.0) || (ratio - 1.0).abs() > self.rescale_range {
            return None;
        }
        if previous.asperity.load > 1e-9 * load {
            return None;
        }
        let (kc, km) = match shape {
            ContactShape::Line { .. } => RESCALE_EXPONENT_LINE,
            ContactShape::Point { .. } => RESCALE_EXPONENT_POINT,
        };
        // From the film as it is (possibly already rescaled, at its own entrainment): power laws
        // compose, so a chain of rescales equals one from the solve.
        let from = f.entrainment;
        let (sc, sm) = ((u / from).powf(kc), (u / from).powf(km));
        let mut out = previous.clone();
        out.central_film *= sc;
        out.min_film *= sm;
        out.exit_film = out.exit_film.map(|h| h * sm);
        out.steady_central_film = self.fallback.solve(input, None).ok()?.steady_central_film;
        out.regime = regime_of(input);
        out.lambda = previous.lambda.map(|l| l * sm);
        for n in &mut out.nodes {
            let film = (n.film * sc).max(FILM_FLOOR);
            n.poiseuille *= film / n.film;
            n.film = film;
        }
        out.iterations = Some(0);
        if let Some(ff) = out.finite.as_deref_mut() {
            ff.entrainment = u;
        }
        ensure_finite("rescaled 2-D film", [&out.central_film, &out.min_film, &out.steady_central_film]).ok()?;
        super::work::add(&super::work::FINITE_RESCALED, 1);
        Some(out)
    }
}

/// Moes' line-contact groups of `input` (line contacts with entrainment), as the 1-D models report.
pub(super) fn regime_of(input: &ContactInput) -> Option<Regime> {
    match input.shape {
        ContactShape::Line { reduced_radius, length } => {
            let eta0 = input.lubricant.viscosity_at(0.0, input.temperature);
            let g = LineGroups::new(input.load / length, reduced_radius, input.entrainment_velocity, eta0, input.lubricant.pressure_viscosity, 2.0 * input.contact_modulus);
            (g.speed > 0.0).then(|| Regime { viscous: g.viscous_parameter(), elastic: g.elastic_parameter() })
        }
        ContactShape::Point { .. } => None,
    }
}

impl FilmModel for Finite {
    /// 5e-3: the film moves by < 4e-3 relative (∝ u^0.7–0.76), against the 2-D grid's
    /// discretisation error of ≈ 1–5 % (BENCHMARKS.md, issue 16). Measured on the seed 000 cycle
    /// (65×129, 8 angles): the cycle's films within 1.8e-3 of Newton solves at its converged
    /// entrainment (3.9e-4 with 1e-3), 35 % fewer Newton steps (re-solves of the roller march);
    /// against 1e-3 the films move by ≤ 0.22 %, sliding velocity ≤ 0.38 %, friction ≤ 0.41 %.
    fn entrainment_tolerance(&self) -> f64 {
        5e-3
    }

    /// Steady and Newtonian: the film depends on load, shape and entrainment alone (the warm start
    /// changes it by less than the Newton tolerance; the optional entrainment rescale by ≲ 1e-3, see
    /// [`RESCALE_RANGE`]).
    /// With the squeeze term the film depends on the previous point's: not history-free.
    fn history_free(&self) -> bool {
        !self.squeeze
    }

    /// Re-enters the converged solution at the film's entrainment (its warm start at its own
    /// problem: no Newton step moves it; a rescaled film is solved there) with the fields on; a
    /// squeeze step re-enters the same step (from the film it started from).
    fn fields(&self, film: &FilmSolution, input: &ContactInput) -> Result<Option<Fields2d>, SolveError> {
        let Some(f) = film.finite.as_deref() else { return Ok(None) };
        let ehl = Ehl2dInput { entrainment_velocity: f.entrainment, ..self.problem(input) };
        let options = Ehl2dOptions { fields: true, grid_check: false, ..self.options };
        let solved = match (f.squeeze_step, f.prior.as_deref()) {
            (Some(time_step), Some(previous)) => {
                let squeeze = twod::Squeeze2d { previous, time_step };
                twod::solve_transient(&ehl, &options, squeeze, Some(&*f.warm), None, &mut Kept2d::default(), &input.interrupts)?
            }
            _ => twod::solve_from(&ehl, &options, Some(&*f.warm), &input.interrupts)?,
        };
        Ok(solved.0.fields)
    }

    /// The default nodal traction, counted ([`super::work`]).
    fn traction_local(&self, film: &FilmSolution, input: &ContactInput, sliding: f64) -> (super::Traction, (f64, f64)) {
        super::work::add(&super::work::FINITE_TRACTION_EVALUATIONS, 1);
        super::work::add(&super::work::FINITE_TRACTION_NODES, film.nodes.len() as u64);
        super::nodal_traction_local(film, input, sliding, self.stick_limit(film, input))
    }

    fn solve(&self, input: &ContactInput, previous: Option<&FilmSolution>) -> Result<FilmSolution, SolveError> {
        let load = input.load;
        if !(load > 0.0 && load.is_finite()) {
            return Err(SolveError::physical(crate::PhysicalFailure::NoContactLoad, format!("contact load {load} N is not positive")));
        }
        if input.entrainment_velocity == 0.0 {
            return self.fallback.solve(input, previous);
        }
        if let Some(r) = previous.filter(|_| self.rescale_range > 0.0 && !self.squeeze).and_then(|p| self.rescaled(input, p)) {
            return Ok(r);
        }
        let geometry = self.geometry(input);
        let ehl = self.problem(input);
        let previous_finite = previous.and_then(|p| p.finite.as_deref());
        let warm = previous_finite.map(|f| &*f.warm);
        let prior = previous_finite.and_then(|f| f.prior.as_deref());
        let first = !self.checked.swap(true, Ordering::Relaxed);
        let grid_check = self.options.grid_check && (!self.check_first_only || first || warm.is_none());
        let options = Ehl2dOptions { fields: true, grid_check, ..self.options };
        let mut kept = self.kept.lock().map(|mut k| std::mem::take(&mut *k)).unwrap_or_default();
        // The squeeze step from the previous point's 2-D film (seed 000 eq. 2's ∂(ρh)/∂t).
        let squeeze_step = (self.squeeze && input.time_step > 0.0 && warm.is_some()).then_some(input.time_step);
        let solved = match (squeeze_step, warm) {
            (Some(time_step), Some(previous)) => twod::solve_transient(&ehl, &options, twod::Squeeze2d { previous, time_step }, warm, prior, &mut kept, &input.interrupts),
            _ => twod::solve_kept(&ehl, &options, warm, prior, &mut kept, &input.interrupts),
        };
        if let Ok(mut k) = self.kept.lock() {
            *k = kept;
        }
        let (s, next) = solved?;
        // The step's change on a stretch of unchanging conditions, and whether it has settled.
        let previous_step = previous.and_then(|p| p.finite.as_deref());
        let step_change = squeeze_step.and(previous).filter(|_| {
            previous_step.is_some_and(|pf| {
                pf.squeeze_step == squeeze_step
                    && pf.solved_at == (load, input.shape, input.temperature)
                    && (pf.entrainment - input.entrainment_velocity).abs() <= self.entrainment_tolerance() * input.entrainment_velocity.abs()
            })
        });
        let step_change = step_change.map(|p| ((p.central_film - s.central_film) / s.central_film).abs().max(((p.min_film - s.min_film.value) / s.min_film.value).abs()));
        let settled = match (step_change, previous_step.and_then(|pf| pf.step_change)) {
            (Some(now), Some(before)) => now < SETTLED && now <= before,
            (Some(now), None) => now < SETTLED,
            _ => false,
        };
        super::work::add(&super::work::FINITE_SOLVES, 1);
        super::work::add(&super::work::FINITE_COLD, (!s.warm_started) as u64);
        super::work::add(&super::work::FINITE_NEWTON_STEPS, s.convergence.iterations as u64);
        let f = s.fields.as_ref().ok_or_else(|| SolveError::NonFinite { quantity: "2-D EHL fields".into() })?;
        let (nx, ny) = (f.x.len(), f.y.len());
        let sigma = input.roughness.sigma;
        let (nodes, area, w_a) = field_nodes(input, f);
        let centre_row = (ny - 1) / 2;
        let exit_film = (0..nx).map(|i| f.film[centre_row * nx + i]).fold(f64::INFINITY, f64::min);
        let steady = self.fallback.solve(input, None)?.steady_central_film;
        let regime = regime_of(input);
        let r_roll = match geometry {
            Geometry2d::Finite { rx, .. } | Geometry2d::Point { rx, .. } => rx,
        };
        ensure_finite("2-D film", [&s.central_film, &s.min_film.value, &exit_film, &s.max_pressure.value, &w_a, &area])?;
        ensure_finite("traction nodes", nodes.iter().flat_map(|n| [&n.area, &n.pressure, &n.viscosity, &n.film, &n.poiseuille]))?;
        Ok(FilmSolution {
            model: FilmModelId::Finite,
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
            regime,
            nodes,
            rolling_force: 0.0,
            viscosity_law: None,
            profile: None,
            iterations: Some(s.convergence.iterations),
            thermal: None,
            finite: Some(Box::new(FiniteFilm {
                edge_pressure_peak: s.edge_pressure_peak.map(|e| (e.value, e.y)),
                min_film_position: (s.min_film.x, s.min_film.y),
                grid: (s.nx, s.ny),
                grid_error: s.grid_error,
                warm_started: s.warm_started,
                warm: Arc::new(next),
                prior: previous_finite.map(|f| f.warm.clone()),
                solved_entrainment: input.entrainment_velocity,
                entrainment: input.entrainment_velocity,
                solved_at: (load, input.shape, input.temperature),
                squeeze_step,
                step_change,
                settled,
                temperatures: None,
            })),
        })
    }
}

/// Traction nodes of a converged 2-D field (module docs): every interior node with positive
/// pressure (cell area `Δx Δy`, viscosity at the input's temperature, Poiseuille stress
/// `−(h/2) ∂p/∂x`, seed 001 eq. 24), the loaded area (m²) and the asperity load (N,
/// Greenwood–Tripp of the local film after the smooth solve, capped at the load); the fluid
/// nodes carry the remaining share.
pub(super) fn field_nodes(input: &ContactInput, f: &Fields2d) -> (Vec<TractionNode>, f64, f64) {
    let load = input.load;
    let es = input.contact_modulus;
    let (nx, ny) = (f.x.len(), f.y.len());
    let dx = (f.x[1] - f.x[0]).abs();
    let dy = f.y[1] - f.y[0];
    let cell = dx * dy;
    let sigma = input.roughness.sigma;
    let w_a = if sigma > 0.0 { (f.film.iter().map(|h| input.roughness.asperity_pressure(*h, es)).sum::<f64>() * cell).min(load) } else { 0.0 };
    let fluid_share = 1.0 - w_a / load;
    let law = input.lubricant.viscosity_law(input.temperature);
    let mut nodes = Vec::new();
    let mut area = 0.0;
    for j in 1..ny - 1 {
        for i in 1..nx - 1 {
            let k = j * nx + i;
            let p = f.pressure[k];
            if p <= 0.0 {
                continue;
            }
            area += cell;
            // x is signed with the entrainment (positive downstream of positive u_m).
            let dpdx = fluid_share * (f.pressure[k + 1] - f.pressure[k - 1]) / (f.x[i + 1] - f.x[i - 1]);
            let film = f.film[k].max(FILM_FLOOR);
            nodes.push(TractionNode { area: cell, pressure: fluid_share * p, viscosity: law.at(p).min(VISCOSITY_CAP), film, poiseuille: -0.5 * film * dpdx });
        }
    }
    (nodes, area, w_a)
}

/// Whether the contact's ends matter at `input` — where `auto` with `ehl.geometry: finite` runs
/// the 2-D model ([`AutoFinite`]). An estimate (issue 16):
/// * point contacts: always (the 1-D model does not apply; the closed form has no pressure field);
/// * a crowned roller: when the slice model's loaded length (`Crown::distribute`, the thin-slice
///   estimate of how far the load spreads along the roller) reaches within two Hertzian
///   half-widths of the crown transition `L1/2` — there the axial slope of the profile jumps and
///   the edge pressure peak forms (seed 000); also when it reaches the roller's ends; always for
///   seed 000 eq. 3 as printed (`CrownProfile::Seed000Eq3`: the transitions carry the load);
/// * a straight roller (no crown): when twice the Hertzian half-width is more than
///   `tolerance` of the contact length (the end zones, a few half-widths long, are then a
///   noticeable part of the contact).
pub fn ends_matter(crown: Option<&Crown>, input: &ContactInput, tolerance: f64) -> bool {
    let es = input.contact_modulus;
    match input.shape {
        ContactShape::Point { .. } => true,
        ContactShape::Line { reduced_radius, length } => match crown {
            Some(c) => {
                let cc = c.distribute(input.load, reduced_radius, es);
                let b = crate::contact::hertz_line(cc.peak_load_per_length.max(input.load / c.length), reduced_radius, es).half_width;
                let reach = 0.5 * cc.effective_length + 2.0 * b;
                // Seed 000 eq. 3 as printed touches first at the transitions: always there.
                let printed = c.loads_the_transitions() && c.middle_length < c.length;
                printed || (c.crown_height > 0.0 && c.middle_length < c.length && reach >= 0.5 * c.middle_length) || reach >= 0.5 * c.length
            }
            None => {
                let b = crate::contact::hertz_line(input.load / length, reduced_radius, es).half_width;
                2.0 * b > tolerance * length
            }
        },
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::film::SmoothContact;

    /// The `auto` estimate on seed 000's crowned roller (L = 14 mm, L1 = 12 mm, h_td = 4.5 µm,
    /// R_d = 12.5 mm; R = 10.37 mm, E* = 105 GPa): the load reaches the crown transition at the
    /// cycle's peak loads (`ends_matter`), not at light loads; a long straight roller's ends
    /// do not matter, a point contact's always do. Run with `--nocapture` for the loaded lengths.
    #[test]
    fn ends_matter_on_the_seed000_roller_at_heavy_loads_only() {
        let smooth = SmoothContact::seed000();
        let es = smooth.contact_modulus;
        let crown = Crown::SEED000;
        let input = |load: f64, shape: ContactShape| smooth.input(load, shape, 2.77);
        let line = ContactShape::Line { reduced_radius: 0.01037, length: 0.014 };
        for load in [100.0, 600.0, 954.0, 2241.0] {
            let cc = crown.distribute(load, 0.01037, es);
            println!("{load} N: loaded length {:.3} mm, ends matter {}", cc.effective_length * 1e3, ends_matter(Some(&crown), &input(load, line), 0.05));
        }
        assert!(!ends_matter(Some(&crown), &input(100.0, line), 0.05));
        assert!(ends_matter(Some(&crown), &input(2241.0, line), 0.05));
        // A straight roller 150 half-widths long: its ends do not matter; a point contact's do.
        assert!(!ends_matter(None, &input(1000.0, line), 0.05));
        assert!(ends_matter(None, &input(100.0, ContactShape::Point { rx: 0.01, ry: 0.01 }), 0.05));
    }
}
