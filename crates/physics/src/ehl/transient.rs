//! Sequences of line-contact problems — the angles of a cam cycle — solved with the caches of one
//! step carried to the next.
//!
//! [`TransientSolver::step`] solves one angle: a squeeze step (backward Euler from the previous
//! angle, [`super::Transient`]) or a steady, warm-started solve. Between steps it keeps
//! * the **grid**: fixed in `X = x/b` while the film estimate stays within a factor
//!   [`LAYOUT_BAND`] of the one the grid was graded for and the entrainment keeps its direction,
//!   so the elastic influence matrix (load-independent in `X`) is computed once per layout,
//!   not once per angle;
//! * the **LU factors** of an earlier Jacobian on that grid, used as the GMRES preconditioner
//!   of every Newton step (see [`super::newton`]); a new factorisation only when it stops working;
//! * the Newton **workspace** (no allocation of matrices per step).
//!
//! With [`Extrapolation::Richardson`] it marches two grids — `n` and `(n − 1)/2 + 1` nodes, the
//! same layout and grading, so the coarse nodes are (to the accuracy of the tabulated grading) every
//! other fine node — each with its own squeeze history, the two side by side on two threads
//! (`rayon::join`), and extrapolates the second-order discretisation error away:
//! `f = f_n + (f_n − f_c)/(r² − 1)` with the grid ratio `r = (n − 1)/(n_c − 1)`. Measured on a
//! 720-angle cycle (BENCHMARKS.md, "Numerical EHL") the extrapolated films of 97 + 193 nodes are
//! within 0.23 % (central) and 0.35 % (minimum) of the grid-converged cycle at every angle, where
//! 192 nodes alone are up to 3.7 % off; the cycle takes ≈ 0.4 s.

use super::grid::Layout;
use super::newton::{film_estimate, Engine, Prediction, SolverStats};
use super::{EhlInput, EhlOptions, EhlSolution, EhlState, Transient};
use crate::{Observer, SolveError};

/// Largest ratio between the film estimate of a step and the film a grid was graded for before
/// the grid is redesigned.
pub const LAYOUT_BAND: f64 = 1.25;

/// How [`TransientSolver`] turns grids into a result.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Extrapolation {
    /// One grid of `options.nodes` nodes.
    #[default]
    None,
    /// Richardson extrapolation of `options.nodes` and `(options.nodes − 1)/2 + 1` nodes. The
    /// extrapolated fields of the result are the central, minimum and exit films and the
    /// traction forces; pressures, the spike, the profiles and the state are the fine grid's.
    Richardson,
}

/// A converged step in Hertzian-scaled form, for the predictor.
struct Past {
    layout: Layout,
    /// `p/p_h` at the grid nodes.
    pressure: Vec<f64>,
    /// Centre film, m.
    centre_film: f64,
    /// Time step that led to it (`None`: steady).
    time_step: Option<f64>,
}

/// Keep the solution `s` on `layout` (reached with `time_step`) as the newest of the last two
/// steps `past`.
fn push_past(past: &mut Vec<Past>, layout: Layout, s: &EhlSolution, time_step: Option<f64>) {
    if past.len() == 2 {
        past.remove(0);
    }
    let ph = s.hertz_pressure;
    past.push(Past { layout, pressure: s.state.pressure.iter().map(|p| p / ph).collect(), centre_film: s.central_film, time_step });
}

/// Linear extrapolation of the last two steps `past` (on the grid of `layout`) to the next one, in
/// Hertzian-scaled pressure (the pressure shape follows the contact width) and centre film.
fn predict(past: &[Past], layout: Layout, time_step: Option<f64>) -> Option<(Vec<f64>, f64)> {
    let [a, b] = past else { return None };
    if a.layout != layout || b.layout != layout {
        return None;
    }
    // Step ratio: Δt_next/Δt_last for squeeze steps, 1 for a steady continuation.
    let s = match (time_step, b.time_step) {
        (Some(t), Some(tb)) => t / tb,
        (None, None) => 1.0,
        _ => return None,
    };
    let p = a.pressure.iter().zip(&b.pressure).map(|(pa, pb)| pb + s * (pb - pa)).collect();
    let hc = b.centre_film + s * (b.centre_film - a.centre_film);
    Some((p, if hc > 0.0 { hc } else { b.centre_film }))
}

/// The last two steps one grid of a [`ReusableSolver`] solved, and the pressure of the last
/// state it returned: a call whose previous state is that one continues the march, and starts
/// from the extrapolation of the two ([`predict`]).
#[derive(Default)]
struct History {
    past: Vec<Past>,
    last: Vec<f64>,
}

impl History {
    /// The prediction for `input` on `layout` when `input`'s previous state is the last one
    /// returned (else `None`: the solve starts from the previous state itself).
    fn predict(&self, input: &EhlInput, layout: Layout) -> Option<(Vec<f64>, f64)> {
        let previous = input.transient.map(|t| t.previous).or(input.warm_start)?;
        if self.last.is_empty() || previous.pressure != self.last {
            return None;
        }
        predict(&self.past, layout, input.transient.map(|t| t.time_step))
    }

    /// Record the solution `s` of `input` on `layout`.
    fn record(&mut self, input: &EhlInput, layout: Layout, s: &EhlSolution) {
        let continues = self.predict_ok(input);
        if !continues {
            self.past.clear();
        }
        push_past(&mut self.past, layout, s, input.transient.map(|t| t.time_step));
        self.last.clone_from(&s.state.pressure);
    }

    /// Whether `input` starts from the last state returned.
    fn predict_ok(&self, input: &EhlInput) -> bool {
        let previous = input.transient.map(|t| t.previous).or(input.warm_start);
        matches!(previous, Some(p) if !self.last.is_empty() && p.pressure == self.last)
    }
}

/// One grid's march through the sequence.
struct Track {
    engine: Engine,
    options: EhlOptions,
    state: Option<EhlState>,
    /// The last two steps (oldest first).
    past: Vec<Past>,
}

impl Track {
    fn new(options: EhlOptions) -> Self {
        Track { engine: Engine::new(), options, state: None, past: Vec::new() }
    }

    fn reset(&mut self) {
        self.state = None;
        self.past.clear();
    }

    /// Linear extrapolation of the last two steps to the next one ([`predict`]).
    fn predict(&self, layout: Layout, time_step: Option<f64>) -> Option<(Vec<f64>, f64)> {
        predict(&self.past, layout, time_step)
    }

    fn step(&mut self, input: &EhlInput, time_step: Option<f64>, layout: Layout, observer: &dyn Observer) -> Result<EhlSolution, SolveError> {
        let mut inp = *input;
        inp.transient = None;
        inp.warm_start = None;
        if let Some(prev) = &self.state {
            match time_step {
                Some(dt) => inp.transient = Some(Transient { previous: prev, time_step: dt }),
                None => inp.warm_start = Some(prev),
            }
        }
        let predicted = if self.state.is_some() { self.predict(layout, time_step) } else { None };
        let prediction = predicted.as_ref().map(|(p, hc)| Prediction { pressure: p, centre_film: *hc });
        let s = self.engine.solve(&inp, &self.options, Some(layout), prediction, observer)?;
        self.state = Some(s.state.clone());
        push_past(&mut self.past, layout, &s, time_step);
        Ok(s)
    }
}

/// Solves a sequence of line-contact problems (the angles of a cycle) with caches kept between
/// steps; see the [module documentation](self).
///
/// ```
/// use tribod_physics::ehl::{EhlInput, EhlOptions, Extrapolation, Rheology, TransientSolver};
/// use tribod_physics::lubricant::Lubricant;
/// use tribod_physics::Silent;
/// let lubricant = Lubricant::SEED000;
/// let mut solver = TransientSolver::new(EhlOptions { nodes: 96, tolerance: 1e-6, ..Default::default() }, Extrapolation::Richardson);
/// for k in 0..3 {
///     let input = EhlInput {
///         load_per_length: 2e5 + 1e4 * k as f64,
///         reduced_radius: 0.01,
///         effective_modulus: 2.3e11,
///         entrainment_velocity: 1.0,
///         sliding_velocity: 0.0,
///         lubricant,
///         temperature: lubricant.reference_temperature,
///         rheology: Rheology::default(),
///         transient: None,  // ignored: the solver keeps the previous state
///         warm_start: None, // ignored
///         asperity: None,
///     };
///     // The first step has no previous state: a steady solve. Then squeeze steps of 0.1 ms.
///     let s = solver.step(&input, Some(1e-4), &Silent).unwrap();
///     assert!(s.min_film > 0.0);
/// }
/// ```
pub struct TransientSolver {
    extrapolation: Extrapolation,
    fine: Track,
    coarse: Option<Track>,
    layout: Option<Layout>,
    layout_changes: u64,
}

impl TransientSolver {
    /// A solver for `options.nodes` nodes (the fine grid with Richardson extrapolation).
    pub fn new(options: EhlOptions, extrapolation: Extrapolation) -> Self {
        let coarse = match extrapolation {
            Extrapolation::None => None,
            Extrapolation::Richardson => {
                let nc = (options.nodes - 1) / 2 + 1;
                Some(Track::new(EhlOptions { nodes: nc, profiles: false, ..options }))
            }
        };
        TransientSolver { extrapolation, fine: Track::new(options), coarse, layout: None, layout_changes: 0 }
    }

    /// The extrapolation in use.
    pub fn extrapolation(&self) -> Extrapolation {
        self.extrapolation
    }

    /// The state of the last step (the fine grid's).
    pub fn state(&self) -> Option<&EhlState> {
        self.fine.state.as_ref()
    }

    /// Forget the previous state: the next step is a steady (cold) solve. Grids and
    /// factorisations are kept.
    pub fn reset(&mut self) {
        self.fine.reset();
        if let Some(c) = &mut self.coarse {
            c.reset();
        }
    }

    /// Work counters of all grids so far: Newton steps, factorisations, GMRES iterations and
    /// how many grid layouts were designed.
    pub fn stats(&self) -> SolverStats {
        let mut s = self.fine.engine.stats();
        if let Some(c) = &self.coarse {
            let t = c.engine.stats();
            s.newton_steps += t.newton_steps;
            s.factorisations += t.factorisations;
            s.gmres_iterations += t.gmres_iterations;
        }
        s.layouts = self.layout_changes;
        s
    }

    /// Solve the next problem of the sequence. `input.transient` and `input.warm_start` are
    /// ignored: with a previous state, `time_step: Some(Δt)` (s, > 0) is a squeeze step from it
    /// (backward Euler) and `None` a steady solve warm-started from it; without one (the first
    /// step, or after [`reset`](Self::reset)) the step is a steady cold solve.
    pub fn step(&mut self, input: &EhlInput, time_step: Option<f64>, observer: &dyn Observer) -> Result<EhlSolution, SolveError> {
        if self.coarse.is_some() && self.fine.options.nodes < 31 {
            return Err(SolveError::invalid("EhlOptions.nodes", "Richardson extrapolation needs at least 31 nodes (16 on the coarse grid)"));
        }
        if let Some(dt) = time_step {
            if !(dt.is_finite() && dt > 0.0) {
                return Err(SolveError::invalid("TransientSolver.time_step", "must be a finite number > 0"));
            }
        }
        let layout = self.layout_for(input, time_step);
        let Some(coarse) = &mut self.coarse else {
            return self.fine.step(input, time_step, layout, observer);
        };
        let fine = &mut self.fine;
        let (f, c) = rayon::join(
            || fine.step(input, time_step, layout, observer),
            || coarse.step(input, time_step, layout, observer),
        );
        let mut f = f?;
        match c {
            Ok(c) => extrapolate(&mut f, &c),
            Err(SolveError::Interrupted(i)) => return Err(SolveError::Interrupted(i)),
            Err(_) => {
                // The coarse grid failed where the fine one converged: continue its march from
                // the fine state (interpolated); this step is not extrapolated.
                coarse.reset();
                coarse.state = self.fine.state.clone();
            }
        }
        Ok(f)
    }

    /// The grid layout of the next step (see [`next_layout`]).
    fn layout_for(&mut self, input: &EhlInput, time_step: Option<f64>) -> Layout {
        let mut inp = *input;
        inp.transient = None;
        inp.warm_start = None;
        if let (Some(prev), Some(dt)) = (&self.fine.state, time_step) {
            inp.transient = Some(Transient { previous: prev, time_step: dt });
        } else if let Some(prev) = &self.fine.state {
            inp.warm_start = Some(prev);
        }
        next_layout(&mut self.layout, &mut self.layout_changes, &inp, &self.fine.options)
    }
}

/// Richardson extrapolation of the fine solution `f` with the coarse solution `c` on the same
/// layout (second-order discretisation error): `f_n + (f_n − f_c)/(r² − 1)`, `r` the grid ratio,
/// for the central, minimum and exit films and the traction forces. Kept unextrapolated when an
/// extrapolated film would not be positive and finite.
fn extrapolate(f: &mut EhlSolution, c: &EhlSolution) {
    let r = (f.nodes - 1) as f64 / (c.nodes - 1) as f64;
    let k = 1.0 / (r * r - 1.0);
    let ex = |a: f64, b: f64| a + (a - b) * k;
    let (hc, hm, he) = (ex(f.central_film, c.central_film), ex(f.min_film, c.min_film), ex(f.exit_film, c.exit_film));
    // Extrapolate when the films stay positive; keep the minimum the smallest film (the two
    // grids may place a flat minimum at different nodes).
    if hm > 0.0 && hc > 0.0 && he > 0.0 && hc.is_finite() && hm.is_finite() && he.is_finite() {
        f.central_film = hc;
        f.exit_film = he;
        f.min_film = hm.min(hc).min(he);
        let (tf, tc) = (&mut f.traction, &c.traction);
        tf.force_body_1 = ex(tf.force_body_1, tc.force_body_1);
        tf.force_body_2 = ex(tf.force_body_2, tc.force_body_2);
        tf.friction_coefficient = ex(tf.friction_coefficient, tc.friction_coefficient);
        tf.rolling_force = ex(tf.rolling_force, tc.rolling_force);
    }
}

/// The grid layout for `input`: the `current` one while the entrainment direction is unchanged
/// and the film estimate stays within [`LAYOUT_BAND`] of its design film; otherwise a new one
/// (stored in `current`, counted in `changes`).
fn next_layout(current: &mut Option<Layout>, changes: &mut u64, input: &EhlInput, options: &EhlOptions) -> Layout {
    let (h_est, dir) = film_estimate(input);
    if let Some(l) = *current {
        let ratio = h_est / l.h_design;
        if l.dir == dir && ratio <= LAYOUT_BAND && ratio >= 1.0 / LAYOUT_BAND && l.grading == options.grading {
            return l;
        }
    }
    let l = Layout::for_film(h_est, dir, options.inlet, options.outlet, options.grading);
    *current = Some(l);
    *changes += 1;
    l
}

/// The layout for `input` graded for its film estimate rounded to the geometric lattice
/// `LAYOUT_BAND^(2k)`: a pure function of the input.
pub fn lattice_layout(input: &EhlInput, options: &EhlOptions) -> Layout {
    let (h_est, dir) = film_estimate(input);
    let q = (LAYOUT_BAND * LAYOUT_BAND).ln();
    let h_design = ((h_est.ln() / q).round() * q).exp();
    Layout::for_film(h_design, dir, options.inlet, options.outlet, options.grading)
}

/// One solver reused for independent problems whose state travels with the input (the
/// `accurate` film model of a cam cycle, which receives the previous angle's solution with each
/// call): grids and their influence matrices, the Newton workspaces and the kept LU factors
/// survive between calls — what [`TransientSolver`] does, without holding the state itself (so a
/// caller may re-solve a step or skip angles). The grid is graded for the film estimate rounded
/// to a geometric lattice of ratio [`LAYOUT_BAND`]² ([`lattice_layout`]): within a factor
/// [`LAYOUT_BAND`] of the estimate, the same grid for neighbouring angles, and — unlike the
/// transient solver's band around the last design — independent of earlier calls. When a call's
/// previous state is the state the last call returned (the caller marches on), Newton starts from
/// the linear extrapolation of the last two solutions (as [`TransientSolver`] does), else from the
/// previous state: the start, and so the result to within the Newton tolerance, may depend on the
/// calls before (the same sequence of calls always gives the same results). Results agree with
/// [`super::solve`] to the discretisation error of the grid. [`solve_richardson`](Self::solve_richardson) marches a second, coarse grid
/// whose state the caller carries too.
#[derive(Default)]
pub struct ReusableSolver {
    fine: Option<Engine>,
    coarse: Option<Engine>,
    fine_history: History,
    coarse_history: History,
    layout: Option<Layout>,
    layout_changes: u64,
}

/// A Richardson-extrapolated solve of [`ReusableSolver::solve_richardson`].
#[derive(Debug, Clone)]
pub struct RichardsonSolution {
    /// The fine grid's solution with extrapolated films and traction forces (fields, pressures,
    /// spike and state are the fine grid's).
    pub solution: EhlSolution,
    /// The coarse grid's state, to pass back with the next step (`None` when the coarse grid
    /// failed; the step is then not extrapolated).
    pub coarse_state: Option<EhlState>,
}

impl ReusableSolver {
    /// An empty solver (caches are built by the first solve).
    pub fn new() -> Self {
        Self::default()
    }

    /// Solve `input` (steady, or a squeeze step when `input.transient` is set) like
    /// [`super::solve`], with the caches of earlier calls.
    pub fn solve(&mut self, input: &EhlInput, options: &EhlOptions, observer: &dyn Observer) -> Result<EhlSolution, SolveError> {
        let layout = self.layout_for(input, options);
        let predicted = self.fine_history.predict(input, layout);
        let prediction = predicted.as_ref().map(|(p, hc)| Prediction { pressure: p, centre_film: *hc });
        let s = self.fine.get_or_insert_with(Engine::new).solve(input, options, Some(layout), prediction, observer)?;
        self.fine_history.record(input, layout, &s);
        Ok(s)
    }

    /// Solve `input` on `options.nodes` and `(options.nodes − 1)/2 + 1` nodes of one layout (two
    /// threads) and extrapolate (as [`Extrapolation::Richardson`] of [`TransientSolver`]).
    /// `coarse_previous` is the coarse grid's state of the previous step (the
    /// `coarse_state` it returned); without it the coarse grid starts from the fine state of
    /// `input` (interpolated).
    pub fn solve_richardson(
        &mut self,
        input: &EhlInput,
        coarse_previous: Option<&EhlState>,
        options: &EhlOptions,
        observer: &dyn Observer,
    ) -> Result<RichardsonSolution, SolveError> {
        if options.nodes < 31 {
            return Err(SolveError::invalid("EhlOptions.nodes", "Richardson extrapolation needs at least 31 nodes (16 on the coarse grid)"));
        }
        let layout = self.layout_for(input, options);
        let coarse_options = EhlOptions { nodes: (options.nodes - 1) / 2 + 1, profiles: false, ..*options };
        let mut coarse_input = *input;
        if let Some(prev) = coarse_previous {
            match &mut coarse_input.transient {
                Some(t) => t.previous = prev,
                None => coarse_input.warm_start = Some(prev),
            }
        }
        let fine_predicted = self.fine_history.predict(input, layout);
        let coarse_predicted = self.coarse_history.predict(&coarse_input, layout);
        fn as_prediction(g: &Option<(Vec<f64>, f64)>) -> Option<Prediction<'_>> {
            g.as_ref().map(|(p, hc)| Prediction { pressure: p, centre_film: *hc })
        }
        let (fine_prediction, coarse_prediction) = (as_prediction(&fine_predicted), as_prediction(&coarse_predicted));
        let fine = self.fine.get_or_insert_with(Engine::new);
        let coarse = self.coarse.get_or_insert_with(Engine::new);
        let (f, c) = rayon::join(
            || fine.solve(input, options, Some(layout), fine_prediction, observer),
            || coarse.solve(&coarse_input, &coarse_options, Some(layout), coarse_prediction, observer),
        );
        let mut f = f?;
        self.fine_history.record(input, layout, &f);
        let coarse_state = match c {
            Ok(c) => {
                self.coarse_history.record(&coarse_input, layout, &c);
                extrapolate(&mut f, &c);
                Some(c.state)
            }
            Err(SolveError::Interrupted(i)) => return Err(SolveError::Interrupted(i)),
            Err(_) => None,
        };
        Ok(RichardsonSolution { solution: f, coarse_state })
    }

    fn layout_for(&mut self, input: &EhlInput, options: &EhlOptions) -> Layout {
        let l = lattice_layout(input, options);
        if self.layout != Some(l) {
            self.layout = Some(l);
            self.layout_changes += 1;
        }
        l
    }

    /// Work counters so far (Newton steps, factorisations, GMRES iterations of both grids;
    /// layout changes).
    pub fn stats(&self) -> SolverStats {
        let mut s = SolverStats::default();
        for e in self.fine.iter().chain(&self.coarse) {
            let t = e.stats();
            s.newton_steps += t.newton_steps;
            s.factorisations += t.factorisations;
            s.gmres_iterations += t.gmres_iterations;
        }
        s.layouts = self.layout_changes;
        s
    }
}

impl std::fmt::Debug for ReusableSolver {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("ReusableSolver").field("layout", &self.layout).field("layout_changes", &self.layout_changes).finish()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_transient_solver_can_move_between_threads() {
        fn send<T: Send>() {}
        send::<TransientSolver>();
        send::<ReusableSolver>();
    }
}
