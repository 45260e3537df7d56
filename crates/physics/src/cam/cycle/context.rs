use super::*;

impl<'a> Context<'a> {
    pub(super) fn input(&self, i: usize, entrainment: f64, sliding: f64, time: f64, dt: f64) -> ContactInput<'a> {
        let spec = self.spec;
        ContactInput {
            load: self.loads[i].contact,
            shape: self.shapes[i],
            entrainment_velocity: entrainment,
            sliding_velocity: sliding,
            time,
            time_step: dt,
            contact_modulus: spec.contact_modulus,
            temperature: spec.temperature,
            lubricant: &spec.lubricant,
            roughness: &spec.roughness,
            traction_law: &spec.traction_law,
            asperity_friction: &spec.asperity_friction,
            interrupts: crate::Interrupts(self.observer),
        }
    }

    pub(super) fn steady(&self) -> bool {
        matches!(self.spec.schedule, SpeedSchedule::Steady { .. })
    }

    pub(super) fn period(&self) -> f64 {
        self.spec.schedule.at(TAU).time
    }

    /// Time step from angle i−1 to i (wrapping for steady running).
    pub(super) fn dt(&self, i: usize) -> f64 {
        if i == 0 {
            if self.steady() { self.period() - self.kin[self.kin.len() - 1].speed.time } else { 0.0 }
        } else {
            self.kin[i].speed.time - self.kin[i - 1].speed.time
        }
    }

    /// Followers whose surface speed is fixed by the kinematics (flat, spherical, or a roller in
    /// pure rolling).
    pub(super) fn march_fixed(&self, friction: bool, observer: &dyn Observer) -> Result<Vec<PointState>, SolveError> {
        let n = self.kin.len();
        let roller = match &self.spec.follower {
            FollowerKind::Roller { roller, .. } => Some(roller),
            _ => None,
        };
        let surface = |i: usize| -> (f64, f64) {
            let k = &self.kin[i];
            match roller {
                Some(r) => (k.cam_surface_velocity, (k.cam_surface_velocity - k.follower_surface_base) / r.radius),
                None => (k.follower_surface_base, 0.0),
            }
        };
        let solve_at = |i: usize, prev: Option<&FilmSolution>| -> Result<(FilmSolution, ContactInput<'a>), SolveError> {
            let k = &self.kin[i];
            let (uf, _) = surface(i);
            let input = self.input(i, k.entrainment(uf), k.cam_surface_velocity - uf, k.speed.time, self.dt(i));
            Ok((self.model.solve(&input, prev)?, input))
        };
        // Periodic start: the last angle's film seeds the squeeze estimate at the first.
        let mut prev = if self.steady() && n > 1 { Some(solve_at(n - 1, None)?.0) } else { None };
        let mut out = Vec::with_capacity(n);
        for i in 0..n {
            observer.check()?;
            if i % 256 == 0 {
                observer.progress(0.2 + 0.7 * i as f64 / n as f64, "film");
            }
            let (film, input) = solve_at(i, prev.as_ref())?;
            let (_, omega) = surface(i);
            let traction = if friction {
                self.model.traction(&film, &input, input.sliding_velocity)
            } else {
                Traction { force: 0.0, slope: 0.0, stick_limit: 0.0, viscous: 0.0 }
            };
            let pin = match roller {
                Some(r) if friction => pin_torque(&r.pin, omega, self.loads[i].contact, 0).0,
                _ => 0.0,
            };
            prev = Some(film.clone());
            out.push(PointState { film, traction, omega, pin_torque: pin, pin_temperature: None });
        }
        Ok(out)
    }

    /// Join the roller states with their films.
    pub(super) fn with_films(states: Vec<Option<Slip>>, cache: Vec<Option<(f64, FilmSolution)>>) -> Vec<PointState> {
        states
            .into_iter()
            .zip(cache)
            .map(|(s, c)| {
                let (s, (_, film)) = (s.expect("every angle stepped"), c.expect("every angle has a film"));
                PointState { film, traction: s.traction, omega: s.omega, pin_torque: s.pin_torque, pin_temperature: s.pin_temperature }
            })
            .collect()
    }

    /// Index of the last angle of the longest run of consecutive angles over which the rolling
    /// speed, the contact load and the reduced radius do not change (relative 1e-9), or 0 when
    /// no such run is longer than two angles.
    pub(super) fn settled_start(&self) -> usize {
        let n = self.kin.len();
        let same = |a: f64, b: f64| (a - b).abs() <= 1e-9 * a.abs().max(b.abs()).max(1e-300);
        let steady_from = |i: usize, j: usize| {
            let (a, b) = (&self.kin[i], &self.kin[j]);
            // The rolling speed as a whole: the follower's own surface velocity on a dwell is
            // round-off (~1e-32 m/s), which a relative test alone would see as changing.
            same(a.cam_surface_velocity - a.follower_surface_base, b.cam_surface_velocity - b.follower_surface_base)
                && same(a.reduced_radius, b.reduced_radius)
                && same(self.loads[i].contact, self.loads[j].contact)
        };
        // Start scanning just after a change, so that a run across the wrap is counted whole.
        let Some(first_change) = (0..n).find(|&i| !steady_from(i, (i + 1) % n)) else {
            return 0; // nothing changes at all: any start is as good
        };
        let (mut best, mut best_len, mut len) = (0, 0, 0);
        for m in 1..=n {
            let i = (first_change + m) % n;
            if steady_from((i + n - 1) % n, i) {
                len += 1;
                if len > best_len {
                    (best, best_len) = (i, len);
                }
            } else {
                len = 0;
            }
        }
        if best_len >= 2 { best } else { 0 }
    }

    /// Roller torque balance marched through the cycle.
    pub(super) fn march_roller(
        &self,
        roller: &RollerParams,
        tolerance: f64,
        max_cycles: usize,
        observer: &dyn Observer,
    ) -> Result<(Vec<PointState>, Convergence), SolveError> {
        let n = self.kin.len();
        let rf = roller.radius;
        let steady = self.steady();
        let rolling = |i: usize| (self.kin[i].cam_surface_velocity - self.kin[i].follower_surface_base) / rf;
        let mut cache: Vec<Option<(f64, FilmSolution)>> = vec![None; n];
        // Warm start of the hydrodynamic pin's eccentricity, carried from angle to angle.
        let pin_warm = std::cell::Cell::new(f64::NAN);
        // Per angle: the roller's state; its film is the one in `cache` (kept there, not copied).
        let mut states: Vec<Option<Slip>> = vec![None; n];
        // History: (Ω, t) of the last two accepted steps.
        let mut hist: Vec<(f64, f64)> = Vec::new();
        let history_free = self.model.history_free();

        // One implicit step to angle i at absolute time t; returns the state.
        let step = |i: usize,
                        t: f64,
                        hist: &[(f64, f64)],
                        guess: f64,
                        fixed_inertia: Option<f64>,
                        prev: Option<usize>,
                        cache: &mut Vec<Option<(f64, FilmSolution)>>|
         -> Result<Slip, SolveError> {
            let k = &self.kin[i];
            let (c_i, o_i) = if let Some(torque) = fixed_inertia {
                (0.0, torque)
            } else if roller.inertia == 0.0 || hist.is_empty() {
                (0.0, 0.0)
            } else {
                let (w1, t1) = hist[hist.len() - 1];
                let h = t - t1;
                if hist.len() >= 2 {
                    let (w2, t2) = hist[hist.len() - 2];
                    let r = h / (t1 - t2);
                    let (a0, a1, a2) = ((1.0 + 2.0 * r) / (1.0 + r), -(1.0 + r), r * r / (1.0 + r));
                    (roller.inertia * a0 / h, roller.inertia * (a1 * w1 + a2 * w2) / h)
                } else {
                    (roller.inertia / h, -roller.inertia * w1 / h)
                }
            };
            let dt = hist.last().map_or(0.0, |&(_, t1)| t - t1);
            let entrainment = |omega: f64| k.entrainment(rf * omega + k.follower_surface_base);
            // Film consistency: the cached film's entrainment within the model's tolerance of the
            // solution's (closed forms 1e-6: the film error, ~7e-7, stays below the
            // discretisation error at any resolution).
            let consistency = self.model.entrainment_tolerance();
            let close = |a: f64, b: f64| (a - b).abs() <= consistency * b.abs().max(1e-9);
            // Start from the cached film of this angle (previous cycle) when there is one and the
            // guess's entrainment is within the tolerance of it; the film is re-solved when the
            // converged entrainment moved away from it.
            // Every film starts from the previous angle's (the squeeze history of transient
            // models; the warm start of the 2-D model). Starting a history-free model from this
            // angle's own film of a previous pass or cycle instead was tried (`ehl2d-6`): the
            // film then depends on the path at the Newton tolerance and the seed 000 finite
            // cycle's periodic roller speed stalled at 1.2e-6 against 1e-8.
            work::add(&work::MARCH_STEPS, 1);
            if cache[i].as_ref().is_none_or(|(ue, _)| !close(entrainment(guess), *ue)) {
                let ue = entrainment(guess);
                // On a stretch of unchanging conditions (a dwell) a history-free model's film at
                // the previous angle stands for this one when its entrainment is close enough; so
                // does a transient film that has settled there (`FilmSolution::settled`: its last
                // step moved it by less than the model's settling tolerance).
                let reuse = prev
                    .filter(|&j| self.loads[j].contact == self.loads[i].contact && self.shapes[j] == self.shapes[i])
                    .and_then(|j| cache[j].as_ref())
                    .filter(|(_, film)| history_free || film.settled())
                    .filter(|(ue_j, _)| close(ue, *ue_j))
                    .cloned();
                cache[i] = Some(match reuse {
                    Some(entry) => {
                        work::add(&work::MARCH_FILM_DWELL, 1);
                        entry
                    }
                    None => {
                        work::add(&work::MARCH_FILM_NEW, 1);
                        let input = self.input(i, ue, k.cam_surface_velocity - (rf * guess + k.follower_surface_base), t, dt);
                        (ue, self.model.solve(&input, prev.and_then(|j| cache[j].as_ref().map(|c| &c.1)))?)
                    }
                });
            }
            let mut guess = guess;
            let mut last = None;
            for pass in 0..6 {
                let (film_ue, ref film) = *cache[i].as_ref().unwrap();
                let input = self.input(i, film_ue, k.cam_surface_velocity - (rf * guess + k.follower_surface_base), t, dt);
                let problem = SlipStep {
                    model: self.model,
                    film,
                    input: &input,
                    cam_surface_velocity: k.cam_surface_velocity,
                    follower_surface_base: k.follower_surface_base,
                    roller,
                    pin_load: self.loads[i].contact,
                    inertia_coefficient: c_i,
                    inertia_offset: o_i,
                    pin_warm: std::cell::Cell::new(pin_warm.get()),
                };
                let sol = problem.solve(guess)?;
                work::add(&work::MARCH_SLIP_SOLVES, 1);
                pin_warm.set(problem.pin_warm.get());
                let ue_sol = entrainment(sol.omega);
                let done = close(ue_sol, film_ue) || pass == 5;
                if done {
                    last = Some(Slip { traction: sol.traction, omega: sol.omega, pin_torque: sol.pin_torque, pin_temperature: sol.pin_temperature });
                    break;
                }
                let input = self.input(i, ue_sol, k.cam_surface_velocity - (rf * sol.omega + k.follower_surface_base), t, dt);
                work::add(&work::MARCH_FILM_PASS, 1);
                let film = self.model.solve(&input, prev.and_then(|j| cache[j].as_ref().map(|c| &c.1)))?;
                cache[i] = Some((ue_sol, film));
                guess = sol.omega;
            }
            Ok(last.expect("at least one pass"))
        };

        let period = self.period();
        // Steady running starts from the quasi-static balance at the end of the longest stretch
        // of unchanging operating conditions (the base-circle dwell: constant rolling speed,
        // load and curvature), where the roller has had longest to settle and the quasi-static
        // speed is closest to the periodic one; the periodic iteration does the rest. Startup
        // begins at θ = 0 as specified.
        let i0 = if steady { self.settled_start() } else { 0 };
        let index = |m: usize| (i0 + m) % n;
        // Absolute time of the m-th step after the start.
        let time = |m: usize| {
            if steady { self.kin[i0].speed.time + m as f64 * period / n as f64 } else { self.kin[m].speed.time }
        };
        // Initial condition.
        let first = if steady {
            // Inertia torque as if the roller followed its rolling speed (central difference).
            let dt = period / n as f64;
            let accel = (rolling((i0 + 1) % n) - rolling((i0 + n - 1) % n)) / (2.0 * dt);
            step(i0, time(0), &[], rolling(i0), Some(roller.inertia * accel), None, &mut cache)?
        } else {
            // Startup: the roller is at rest; nothing turns at t = 0.
            let ue = 0.5 * self.kin[0].cam_surface_velocity;
            let input = self.input(0, ue, self.kin[0].cam_surface_velocity, 0.0, 0.0);
            cache[0] = Some((ue, self.model.solve(&input, None)?));
            Slip { traction: Traction { force: 0.0, slope: 0.0, stick_limit: 0.0, viscous: 0.0 }, omega: 0.0, pin_torque: 0.0, pin_temperature: None }
        };
        hist.push((first.omega, time(0)));
        // Slip ω − ω_roll of the steps in `hist` (for the predictor).
        let mut slips: Vec<(f64, f64)> = vec![(time(0), first.omega - rolling(i0))];
        states[i0] = Some(first);
        let mut omega0 = states[i0].as_ref().unwrap().omega;
        let mut residuals = Vec::new();
        let mut starts = vec![omega0];
        let cycles = if steady { max_cycles.max(1) } else { 1 };
        let last_step = if steady { n } else { n - 1 };
        // Later cycles stop where they rejoin the previous one: once two consecutive speeds (the
        // BDF2 history) agree with the previous cycle's within the periodicity tolerance
        // (relative to the rolling speed at the start, as the periodicity test), the rest of the cycle
        // would repeat the previous one to that accuracy — the linearised balance
        // `I δΩ' = −(R_f² ∂F_t/∂u_s + ∂T_pin/∂Ω) δΩ` only damps differences, and BDF2 is A-stable —
        // so the previous cycle's remaining states are kept and the speed at the start changes by
        // less than the tolerance. The residual reported is the larger of the two differences.
        // (Seed 000 at 3600 angles, start 46°, the end of the base circle: the start error,
        // 4.4e-5, falls below 1e-8 about 144° into the second revolution; from θ = 0, 160° into
        // the base circle, it was 2.7e-4 and took 190°.)
        let merge = tolerance;
        let scale0 = rolling(i0).abs().max(1e-12);
        for cycle in 0..cycles {
            let mut residual = f64::INFINITY;
            // Differences to the previous cycle at the last two steps (relative to the rolling
            // speed; NaN: none yet) and the last signed difference.
            let mut diffs = [f64::NAN, f64::NAN];
            let mut last_diff = f64::NAN;
            for m in 1..=last_step {
                observer.check()?;
                if m % 256 == 0 {
                    observer.progress(0.2 + 0.7 * (m as f64 / n as f64 + cycle as f64) / cycles as f64, "roller slip");
                }
                let (i, ip) = (index(m), index(m - 1));
                let t = time(cycle * n + m);
                let old = if cycle > 0 && m < n { states[i].as_ref().map(|s| s.omega) } else { None };
                // Predict. In a later cycle: the previous cycle's speed plus the last difference
                // to it (which decays smoothly). Otherwise extrapolate the slip ω − ω_roll in time
                // through the last three steps (Lagrange; fewer after a restart of the history).
                let guess = match old {
                    Some(o) if last_diff.is_finite() => o + last_diff,
                    _ => rolling(i) + extrapolate(&slips, t),
                };
                // The previous angle's film (for squeeze terms) is the one in the cache there.
                let s = step(i, t, &hist, guess, None, Some(ip), &mut cache)?;
                hist.push((s.omega, t));
                slips.push((t, s.omega - rolling(i)));
                if hist.len() > 2 {
                    hist.remove(0);
                }
                if slips.len() > 3 {
                    slips.remove(0);
                }
                if steady && m == n {
                    residual = (s.omega - omega0).abs() / scale0;
                    residuals.push(residual);
                    starts.push(s.omega);
                    omega0 = s.omega;
                }
                let merged = match old {
                    Some(o) => {
                        last_diff = s.omega - o;
                        diffs = [diffs[1], last_diff.abs() / scale0];
                        diffs[0] <= merge && diffs[1] <= merge
                    }
                    None => false,
                };
                states[i] = Some(s);
                if merged {
                    residual = diffs[0].max(diffs[1]);
                    residuals.push(residual);
                    break;
                }
            }
            if !steady {
                break;
            }
            // Slow relaxation (weak traction, heavy roller): the start-of-cycle speed converges
            // geometrically; every third cycle, jump to the Aitken Δ² limit and restart the BDF
            // history from it.
            let m = starts.len();
            if residual > tolerance && m >= 3 && m % 3 == 0 {
                let (x0, x1, x2) = (starts[m - 3], starts[m - 2], starts[m - 1]);
                let (d1, d2) = (x1 - x0, x2 - x1);
                let ratio = d2 / d1;
                if d1 != 0.0 && ratio.abs() < 0.99 && ratio.abs() > 0.05 {
                    let limit = x2 + ratio / (1.0 - ratio) * d2;
                    let t0 = time((cycle + 1) * n);
                    if let Some(st) = states[i0].as_mut() {
                        st.omega = limit;
                    }
                    omega0 = limit;
                    starts.push(limit);
                    hist.clear();
                    hist.push((limit, t0));
                    slips.clear();
                    slips.push((t0, limit - rolling(i0)));
                }
            }
            if residual <= tolerance {
                let conv = Convergence {
                    iterations: (cycle + 1) as u32,
                    residual,
                    tolerance,
                    termination: Termination::Converged,
                };
                return Ok((Self::with_films(states, cache), conv));
            }
        }
        if !steady {
            return Ok((Self::with_films(states, cache), Convergence::closed_form()));
        }
        Err(SolveError::NotConverged {
            solver: "periodic roller speed",
            iterations: cycles as u32,
            residual: *residuals.last().unwrap_or(&f64::NAN),
            tolerance,
            history: residuals.iter().rev().take(10).rev().copied().collect(),
        })
    }
}

/// Value at `t` of the Lagrange polynomial through the points `(t_j, y_j)` (one to three).
pub(super) fn extrapolate(points: &[(f64, f64)], t: f64) -> f64 {
    let mut sum = 0.0;
    for (j, &(tj, yj)) in points.iter().enumerate() {
        let mut l = 1.0;
        for (k, &(tk, _)) in points.iter().enumerate() {
            if k != j {
                l *= (t - tk) / (tj - tk);
            }
        }
        sum += yj * l;
    }
    sum
}

/// Angles (interpolated) where `values` changes sign, including across the wrap.
pub(super) fn sign_changes(angles: &[f64], values: &[f64]) -> Vec<f64> {
    let n = values.len();
    let mut out = Vec::new();
    for i in 0..n {
        let j = (i + 1) % n;
        let (a, b) = (values[i], values[j]);
        if a == 0.0 {
            out.push(angles[i]);
        } else if a * b < 0.0 {
            let aj = if j == 0 { TAU } else { angles[j] };
            out.push((angles[i] + (aj - angles[i]) * a / (a - b)).rem_euclid(TAU));
        }
    }
    out
}

/// Angle ranges where `values` ≤ 0.
pub(super) fn negative_ranges(angles: &[f64], values: &[f64]) -> Vec<(f64, f64)> {
    let mut out = Vec::new();
    let mut start: Option<f64> = None;
    for (a, v) in angles.iter().zip(values) {
        match (start, *v <= 0.0) {
            (None, true) => start = Some(*a),
            (Some(s), false) => {
                out.push((s, *a));
                start = None;
            }
            _ => {}
        }
    }
    if let Some(s) = start {
        out.push((s, TAU));
    }
    out
}
