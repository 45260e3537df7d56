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
            // Every angle (the job's observer throttles what it sends): a thermal or 2-D film
            // takes tens of milliseconds an angle, so progress moves several times a second.
            observer.progress(0.2 + 0.7 * i as f64 / n as f64, "film");
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
