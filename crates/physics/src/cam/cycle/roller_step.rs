//! One implicit step of the roller's torque balance to one cam angle: the inertia torque by
//! BDF2, the film at the angle kept consistent with the roller speed solved for.

use super::*;

/// Film of each angle: the entrainment velocity it was solved at, and the film.
pub(super) type FilmCache = Vec<Option<(f64, FilmSolution)>>;

/// Steps the roller from angle to angle and keeps each angle's film.
pub(super) struct RollerStepper<'c, 'a> {
    ctx: &'c Context<'a>,
    roller: &'c RollerParams,
    /// Warm start of the hydrodynamic pin's eccentricity, carried from angle to angle.
    pin_warm: f64,
    history_free: bool,
    /// Per angle: the film the roller's state at that angle goes with (kept here, not copied).
    pub(super) cache: FilmCache,
}

impl<'c, 'a> RollerStepper<'c, 'a> {
    pub(super) fn new(ctx: &'c Context<'a>, roller: &'c RollerParams) -> Self {
        let cache: FilmCache = vec![None; ctx.kin.len()];
        RollerStepper { ctx, roller, pin_warm: f64::NAN, history_free: ctx.model.history_free(), cache }
    }

    /// Entrainment velocity at angle `i` with the roller turning at `omega`.
    fn entrainment(&self, i: usize, omega: f64) -> f64 {
        let k = &self.ctx.kin[i];
        k.entrainment(self.roller.radius * omega + k.follower_surface_base)
    }

    /// Sliding velocity at angle `i` with the roller turning at `omega`.
    fn sliding(&self, i: usize, omega: f64) -> f64 {
        let k = &self.ctx.kin[i];
        k.cam_surface_velocity - (self.roller.radius * omega + k.follower_surface_base)
    }

    /// Film consistency: the cached film's entrainment `b` within the model's tolerance of the
    /// solution's `a` (closed forms 1e-6: the film error, ~7e-7, stays below the discretisation
    /// error at any resolution).
    fn close(&self, a: f64, b: f64) -> bool {
        let consistency = self.ctx.model.entrainment_tolerance();
        (a - b).abs() <= consistency * b.abs().max(1e-9)
    }

    /// The film of the previous angle `prev` (the squeeze history, the warm start).
    fn prev_film(&self, prev: Option<usize>) -> Option<&FilmSolution> {
        prev.and_then(|j| self.cache[j].as_ref().map(|c| &c.1))
    }

    /// One implicit step to angle `i` at absolute time `t` from `hist`, the (Ω, t) of the last
    /// two accepted steps, starting from the speed `guess`. `fixed_inertia` replaces the inertia
    /// torque (the quasi-static start); `prev` is the previous angle, whose film the film here
    /// starts from. Returns the roller's state; its film is the one in `cache[i]`.
    pub(super) fn step(
        &mut self,
        i: usize,
        t: f64,
        hist: &[(f64, f64)],
        guess: f64,
        fixed_inertia: Option<f64>,
        prev: Option<usize>,
    ) -> Result<Slip, SolveError> {
        let inertia = inertia_terms(self.roller.inertia, hist, t, fixed_inertia);
        let dt = hist.last().map_or(0.0, |&(_, t1)| t - t1);
        work::add(&work::MARCH_STEPS, 1);
        self.ensure_film(i, t, dt, guess, prev)?;
        self.balance(i, t, dt, guess, prev, inertia)
    }

    /// Start from the cached film of this angle (previous cycle) when there is one and the
    /// guess's entrainment is within the tolerance of it; the film is re-solved when the
    /// converged entrainment moved away from it.
    // Every film starts from the previous angle's (the squeeze history of transient
    // models; the warm start of the 2-D model). Starting a history-free model from this
    // angle's own film of a previous pass or cycle instead was tried (`ehl2d-6`): the
    // film then depends on the path at the Newton tolerance and the seed 000 finite
    // cycle's periodic roller speed stalled at 1.2e-6 against 1e-8.
    fn ensure_film(&mut self, i: usize, t: f64, dt: f64, guess: f64, prev: Option<usize>) -> Result<(), SolveError> {
        if self.cache[i].as_ref().is_none_or(|(ue, _)| !self.close(self.entrainment(i, guess), *ue)) {
            let ue = self.entrainment(i, guess);
            let (loads, shapes) = (self.ctx.loads, self.ctx.shapes);
            // On a stretch of unchanging conditions (a dwell) a history-free model's film at
            // the previous angle stands for this one when its entrainment is close enough; so
            // does a transient film that has settled there (`FilmSolution::settled`: its last
            // step moved it by less than the model's settling tolerance).
            let reuse = prev
                .filter(|&j| loads[j].contact == loads[i].contact && shapes[j] == shapes[i])
                .and_then(|j| self.cache[j].as_ref())
                .filter(|(_, film)| self.history_free || film.settled())
                .filter(|(ue_j, _)| self.close(ue, *ue_j))
                .cloned();
            let entry = match reuse {
                Some(entry) => {
                    work::add(&work::MARCH_FILM_DWELL, 1);
                    entry
                }
                None => {
                    work::add(&work::MARCH_FILM_NEW, 1);
                    let input = self.ctx.input(i, ue, self.sliding(i, guess), t, dt);
                    (ue, self.ctx.model.solve(&input, self.prev_film(prev))?)
                }
            };
            self.cache[i] = Some(entry);
        }
        Ok(())
    }

    /// The torque balance at angle `i` on the cached film, re-solving the film at the balance's
    /// entrainment until the two agree (at most six passes). `(c, o)`: the inertia torque
    /// `c Ω + o`.
    fn balance(
        &mut self,
        i: usize,
        t: f64,
        dt: f64,
        guess: f64,
        prev: Option<usize>,
        (c_i, o_i): (f64, f64),
    ) -> Result<Slip, SolveError> {
        let k = &self.ctx.kin[i];
        let mut guess = guess;
        let mut last = None;
        for pass in 0..6 {
            let (film_ue, ref film) = *self.cache[i].as_ref().unwrap();
            let input = self.ctx.input(i, film_ue, self.sliding(i, guess), t, dt);
            let problem = SlipStep {
                model: self.ctx.model,
                film,
                input: &input,
                cam_surface_velocity: k.cam_surface_velocity,
                follower_surface_base: k.follower_surface_base,
                roller: self.roller,
                pin_load: self.ctx.loads[i].contact,
                inertia_coefficient: c_i,
                inertia_offset: o_i,
                pin_warm: std::cell::Cell::new(self.pin_warm),
            };
            let sol = problem.solve(guess)?;
            work::add(&work::MARCH_SLIP_SOLVES, 1);
            self.pin_warm = problem.pin_warm.get();
            let ue_sol = self.entrainment(i, sol.omega);
            let done = self.close(ue_sol, film_ue) || pass == 5;
            if done {
                last = Some(Slip { traction: sol.traction, omega: sol.omega, pin_torque: sol.pin_torque, pin_temperature: sol.pin_temperature });
                break;
            }
            let input = self.ctx.input(i, ue_sol, self.sliding(i, sol.omega), t, dt);
            work::add(&work::MARCH_FILM_PASS, 1);
            let film = self.ctx.model.solve(&input, self.prev_film(prev))?;
            self.cache[i] = Some((ue_sol, film));
            guess = sol.omega;
        }
        Ok(last.expect("at least one pass"))
    }
}

/// The inertia torque `I Ω'` at time `t` as `c Ω + o` (returned as `(c, o)`): variable-step
/// BDF2 through the (Ω, t) of the last two steps in `hist`, backward Euler after one, none
/// before; `fixed` stands for the whole torque when given.
fn inertia_terms(inertia: f64, hist: &[(f64, f64)], t: f64, fixed: Option<f64>) -> (f64, f64) {
    if let Some(torque) = fixed {
        (0.0, torque)
    } else if inertia == 0.0 || hist.is_empty() {
        (0.0, 0.0)
    } else {
        let (w1, t1) = hist[hist.len() - 1];
        let h = t - t1;
        if hist.len() >= 2 {
            let (w2, t2) = hist[hist.len() - 2];
            let r = h / (t1 - t2);
            let (a0, a1, a2) = ((1.0 + 2.0 * r) / (1.0 + r), -(1.0 + r), r * r / (1.0 + r));
            (inertia * a0 / h, inertia * (a1 * w1 + a2 * w2) / h)
        } else {
            (inertia / h, -inertia * w1 / h)
        }
    }
}
