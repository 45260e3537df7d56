//! The roller's torque balance marched through the cycle: the start, the sweep of a cycle
//! angle by angle, and (steady running) the repeated cycles until the roller speed at the start
//! repeats, with their convergence bookkeeping.

use super::*;

impl<'a> Context<'a> {
    /// Roller torque balance marched through the cycle.
    pub(super) fn march_roller(
        &self,
        roller: &RollerParams,
        tolerance: f64,
        max_cycles: usize,
        observer: &dyn Observer,
    ) -> Result<(Vec<PointState>, Convergence), SolveError> {
        let mut march = RollerMarch::start(self, roller)?;
        let steady = march.steady;
        let cycles = if steady { max_cycles.max(1) } else { 1 };
        for cycle in 0..cycles {
            let residual = march.sweep(cycle, cycles, tolerance, observer)?;
            if !steady {
                break;
            }
            march.accelerate(cycle, residual, tolerance);
            if residual <= tolerance {
                let conv = Convergence {
                    iterations: (cycle + 1) as u32,
                    residual,
                    tolerance,
                    termination: Termination::Converged,
                };
                return Ok((march.finish(), conv));
            }
        }
        if !steady {
            return Ok((march.finish(), Convergence::closed_form()));
        }
        Err(SolveError::NotConverged {
            solver: "periodic roller speed",
            iterations: cycles as u32,
            residual: *march.residuals.last().unwrap_or(&f64::NAN),
            tolerance,
            history: march.residuals.iter().rev().take(10).rev().copied().collect(),
        })
    }
}

/// Where the march stands.
struct RollerMarch<'c, 'a> {
    ctx: &'c Context<'a>,
    stepper: RollerStepper<'c, 'a>,
    /// Per angle: the roller's state; its film is the one in the stepper's cache.
    states: Vec<Option<Slip>>,
    /// (Ω, t) of the last two accepted steps.
    hist: Vec<(f64, f64)>,
    /// (t, ω − ω_roll): the slip of the last three steps (for the predictor).
    slips: Vec<(f64, f64)>,
    /// Roller radius, m.
    rf: f64,
    steady: bool,
    n: usize,
    period: f64,
    /// The angle the march starts from.
    i0: usize,
    /// Roller speed at the start of the current cycle.
    omega0: f64,
    /// Rolling speed at the start (the scale of the periodicity test), never below 1e-12.
    scale0: f64,
    /// Residual of every periodicity test so far.
    residuals: Vec<f64>,
    /// The roller speeds at the start, cycle by cycle (and the Aitken limits jumped to).
    starts: Vec<f64>,
}

impl<'c, 'a> RollerMarch<'c, 'a> {
    /// The march at its initial condition.
    ///
    /// Steady running starts from the quasi-static balance at the end of the longest stretch
    /// of unchanging operating conditions (the base-circle dwell: constant rolling speed,
    /// load and curvature), where the roller has had longest to settle and the quasi-static
    /// speed is closest to the periodic one; the periodic iteration does the rest. Startup
    /// begins at θ = 0 as specified.
    fn start(ctx: &'c Context<'a>, roller: &'c RollerParams) -> Result<Self, SolveError> {
        let n = ctx.kin.len();
        let steady = ctx.steady();
        let stepper = RollerStepper::new(ctx, roller);
        let period = ctx.period();
        let i0 = if steady { ctx.settled_start() } else { 0 };
        let mut march = RollerMarch {
            ctx,
            stepper,
            states: vec![None; n],
            hist: Vec::new(),
            slips: Vec::new(),
            rf: roller.radius,
            steady,
            n,
            period,
            i0,
            omega0: f64::NAN,
            scale0: f64::NAN,
            residuals: Vec::new(),
            starts: Vec::new(),
        };
        let first = if steady {
            // Inertia torque as if the roller followed its rolling speed (central difference).
            let dt = period / n as f64;
            let accel = (march.rolling((i0 + 1) % n) - march.rolling((i0 + n - 1) % n)) / (2.0 * dt);
            let (t, guess) = (march.time(0), march.rolling(i0));
            march.stepper.step(i0, t, &[], guess, Some(roller.inertia * accel), None)?
        } else {
            // Startup: the roller is at rest; nothing turns at t = 0.
            let ue = 0.5 * ctx.kin[0].cam_surface_velocity;
            let input = ctx.input(0, ue, ctx.kin[0].cam_surface_velocity, 0.0, 0.0);
            march.stepper.cache[0] = Some((ue, ctx.model.solve(&input, None)?));
            Slip { traction: Traction { force: 0.0, slope: 0.0, stick_limit: 0.0, viscous: 0.0 }, omega: 0.0, pin_torque: 0.0, pin_temperature: None }
        };
        march.hist.push((first.omega, march.time(0)));
        march.slips = vec![(march.time(0), first.omega - march.rolling(i0))];
        march.states[i0] = Some(first);
        march.omega0 = march.states[i0].as_ref().unwrap().omega;
        march.starts = vec![march.omega0];
        march.scale0 = march.rolling(i0).abs().max(1e-12);
        Ok(march)
    }

    /// Rolling speed of the roller at angle `i` (no slip), rad/s.
    fn rolling(&self, i: usize) -> f64 {
        let k = &self.ctx.kin[i];
        (k.cam_surface_velocity - k.follower_surface_base) / self.rf
    }

    /// Angle of the m-th step after the start.
    fn index(&self, m: usize) -> usize {
        (self.i0 + m) % self.n
    }

    /// Absolute time of the m-th step after the start.
    fn time(&self, m: usize) -> f64 {
        if self.steady { self.ctx.kin[self.i0].speed.time + m as f64 * self.period / self.n as f64 } else { self.ctx.kin[m].speed.time }
    }

    /// One pass through the cycle (steps 1 to n after the start; startup: to the last angle);
    /// returns the cycle's residual (infinite when it had none).
    ///
    /// Later cycles stop where they rejoin the previous one: once two consecutive speeds (the
    /// BDF2 history) agree with the previous cycle's within the periodicity tolerance
    /// (relative to the rolling speed at the start, as the periodicity test), the rest of the cycle
    /// would repeat the previous one to that accuracy — the linearised balance
    /// `I δΩ' = −(R_f² ∂F_t/∂u_s + ∂T_pin/∂Ω) δΩ` only damps differences, and BDF2 is A-stable —
    /// so the previous cycle's remaining states are kept and the speed at the start changes by
    /// less than the tolerance. The residual reported is the larger of the two differences.
    /// (Seed 000 at 3600 angles, start 46°, the end of the base circle: the start error,
    /// 4.4e-5, falls below 1e-8 about 144° into the second revolution; from θ = 0, 160° into
    /// the base circle, it was 2.7e-4 and took 190°.)
    fn sweep(&mut self, cycle: usize, cycles: usize, tolerance: f64, observer: &dyn Observer) -> Result<f64, SolveError> {
        let n = self.n;
        let last_step = if self.steady { n } else { n - 1 };
        let merge = tolerance;
        let mut residual = f64::INFINITY;
        // Differences to the previous cycle at the last two steps (relative to the rolling
        // speed; NaN: none yet) and the last signed difference.
        let mut diffs = [f64::NAN, f64::NAN];
        let mut last_diff = f64::NAN;
        for m in 1..=last_step {
            observer.check()?;
            observer.progress(0.2 + 0.7 * (m as f64 / n as f64 + cycle as f64) / cycles as f64, "roller slip");
            let (i, ip) = (self.index(m), self.index(m - 1));
            let t = self.time(cycle * n + m);
            let old = if cycle > 0 && m < n { self.states[i].as_ref().map(|s| s.omega) } else { None };
            // Predict. In a later cycle: the previous cycle's speed plus the last difference
            // to it (which decays smoothly). Otherwise extrapolate the slip ω − ω_roll in time
            // through the last three steps (Lagrange; fewer after a restart of the history).
            let guess = match old {
                Some(o) if last_diff.is_finite() => o + last_diff,
                _ => self.rolling(i) + extrapolate(&self.slips, t),
            };
            // The previous angle's film (for squeeze terms) is the one in the cache there.
            let s = self.stepper.step(i, t, &self.hist, guess, None, Some(ip))?;
            self.record(i, t, s.omega);
            if self.steady && m == n {
                residual = (s.omega - self.omega0).abs() / self.scale0;
                self.residuals.push(residual);
                self.starts.push(s.omega);
                self.omega0 = s.omega;
            }
            let merged = match old {
                Some(o) => {
                    last_diff = s.omega - o;
                    diffs = [diffs[1], last_diff.abs() / self.scale0];
                    diffs[0] <= merge && diffs[1] <= merge
                }
                None => false,
            };
            self.states[i] = Some(s);
            if merged {
                residual = diffs[0].max(diffs[1]);
                self.residuals.push(residual);
                break;
            }
        }
        Ok(residual)
    }

    /// Add the step to angle `i` at time `t`, speed `omega`, to the BDF2 history (two steps)
    /// and the predictor's (three).
    fn record(&mut self, i: usize, t: f64, omega: f64) {
        self.hist.push((omega, t));
        self.slips.push((t, omega - self.rolling(i)));
        if self.hist.len() > 2 {
            self.hist.remove(0);
        }
        if self.slips.len() > 3 {
            self.slips.remove(0);
        }
    }

    /// Slow relaxation (weak traction, heavy roller): the start-of-cycle speed converges
    /// geometrically; every third cycle, jump to the Aitken Δ² limit and restart the BDF
    /// history from it.
    fn accelerate(&mut self, cycle: usize, residual: f64, tolerance: f64) {
        let m = self.starts.len();
        if residual > tolerance && m >= 3 && m.is_multiple_of(3) {
            let (x0, x1, x2) = (self.starts[m - 3], self.starts[m - 2], self.starts[m - 1]);
            let (d1, d2) = (x1 - x0, x2 - x1);
            let ratio = d2 / d1;
            if d1 != 0.0 && ratio.abs() < 0.99 && ratio.abs() > 0.05 {
                let limit = x2 + ratio / (1.0 - ratio) * d2;
                let t0 = self.time((cycle + 1) * self.n);
                if let Some(st) = self.states[self.i0].as_mut() {
                    st.omega = limit;
                }
                self.omega0 = limit;
                self.starts.push(limit);
                self.hist.clear();
                self.hist.push((limit, t0));
                self.slips.clear();
                self.slips.push((t0, limit - self.rolling(self.i0)));
            }
        }
    }

    /// The states of all angles with their films.
    fn finish(self) -> Vec<PointState> {
        Context::with_films(self.states, self.stepper.cache)
    }
}
