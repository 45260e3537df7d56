use super::*;

pub(super) fn scales(input: &EhlInput) -> Scales {
    let w = input.load_per_length;
    let r = input.reduced_radius;
    let ep = input.effective_modulus;
    let t = input.temperature;
    let um = input.entrainment_velocity;
    let lub = input.lubricant;
    // Hertz with E* = E'/2 (contact::hertz_line takes Johnson's E*).
    let hz = hertz_line(w, r, 0.5 * ep);
    let (b, ph) = (hz.half_width, hz.max_pressure);
    let eta0 = lub.viscosity_at(0.0, t);
    let lambda = 12.0 * eta0 * um * r * r / (b * b * b * ph);
    let groups = Groups::of(w, r, ep, um, &lub, t);
    let (moes_m, moes_l) = if um != 0.0 { (groups.moes_m, groups.moes_l) } else { (0.0, 0.0) };
    let previous = input.transient.map(|s| s.previous).or(input.warm_start);
    let h_moes = if um != 0.0 { PI * moes_central(moes_m, moes_l) / (8.0 * moes_m) } else { 0.0 };
    let h_est = match previous {
        Some(s) => (s.film_at(0.0, r) * r / (b * b)).max(h_moes),
        None => h_moes,
    };
    let kappa = match input.transient {
        Some(s) => 12.0 * eta0 * r * r / (b * b * ph * s.time_step),
        None => 0.0,
    };
    Scales { b, ph, lambda, kappa, moes_m, moes_l, h_est }
}

/// The film estimate `H = hR/b²` a solve of `input` designs its grid for (the previous state's
/// centre film or Moes' central film, whichever is thicker), and the entrainment direction.
pub(crate) fn film_estimate(input: &EhlInput) -> (f64, f64) {
    let s = scales(input);
    (s.h_est, if input.entrainment_velocity >= 0.0 { 1.0 } else { -1.0 })
}

impl Engine {
    pub(crate) fn new() -> Self {
        Engine { grids: GridCache::default(), workspaces: Vec::new() }
    }

    /// Linear-algebra counters summed over the workspaces.
    pub(crate) fn stats(&self) -> SolverStats {
        let mut s = SolverStats::default();
        for w in &self.workspaces {
            s.newton_steps += w.stats.newton_steps;
            s.factorisations += w.stats.factorisations;
            s.gmres_iterations += w.stats.gmres_iterations;
        }
        s
    }

    pub(super) fn workspace(&mut self, n: usize) -> &mut Workspace {
        let k = match self.workspaces.iter().position(|w| w.n == n) {
            Some(k) => k,
            None => {
                if self.workspaces.len() == 3 {
                    self.workspaces.remove(0);
                }
                let mut w = Workspace::new();
                w.ensure(n);
                self.workspaces.push(w);
                self.workspaces.len() - 1
            }
        };
        &mut self.workspaces[k]
    }

    /// Solve one problem (steady, or one transient step when `input.transient` is set). `layout`
    /// fixes the grid's domain and grading (its direction must be the entrainment's); `None`
    /// designs it from the film estimate. A `prediction` on that grid is tried first; when Newton
    /// does not converge from it, the solve falls back to the warm start and then to a cold start.
    pub(crate) fn solve(
        &mut self,
        input: &EhlInput,
        options: &EhlOptions,
        layout: Option<Layout>,
        prediction: Option<Prediction>,
        observer: &dyn Observer,
    ) -> Result<EhlSolution, SolveError> {
        self.solve_with(input, options, layout, prediction, None, observer)
    }

    /// [`Self::solve`] with the generalized Reynolds equation's thermal corrections `thermal`
    /// (held fixed; [`super::super::thermal`] iterates them with the energy equation).
    pub(crate) fn solve_with(
        &mut self,
        input: &EhlInput,
        options: &EhlOptions,
        layout: Option<Layout>,
        prediction: Option<Prediction>,
        thermal: Option<&ThermalFactors>,
        observer: &dyn Observer,
    ) -> Result<EhlSolution, SolveError> {
        validate(input, options)?;
        let r = input.reduced_radius;
        let t = input.temperature;
        let um = input.entrainment_velocity;
        let lub = input.lubricant;
        let sc = scales(input);
        let (b, ph, h_est) = (sc.b, sc.ph, sc.h_est);
        let previous = input.transient.map(|s| s.previous).or(input.warm_start);
        let dir = if um >= 0.0 { 1.0 } else { -1.0 };
        if sc.lambda == 0.0 && sc.kappa == 0.0 {
            return Err(SolveError::physical(
                crate::PhysicalFailure::NoEntrainment,
                "a steady film needs entrainment: u_m = 0 without squeeze (no previous state) has no lubricated solution",
            ));
        }
        let layout = layout.unwrap_or_else(|| Layout::for_film(h_est, dir, options.inlet, options.outlet, options.grading));
        let rheology = PressureRheology::new(&lub, t);
        let build = |grids: &mut GridCache, n: usize| {
            let grid = grids.get(n, layout);
            let q_old = match input.transient {
                Some(s) => grid.x.iter().map(|&xi| s.previous.mass_per_area(xi * b, r) * r / (b * b)).collect(),
                None => Vec::new(),
            };
            let thermal = thermal.map(|f| NodeFactors::on(&grid.x, b, f));
            let asperity = input.asperity.map(|law| AsperityScale { law, film_scale: b * b / r, ph });
            let wedge = super::discretisation::wedge_stencils(&grid.x, sc.lambda, options.upwind);
            Discretisation { grid, lambda: sc.lambda, kappa: sc.kappa, q_old, wedge, rheology, ph, thermal, asperity }
        };
        // Nested iteration: from the previous state straight on the target grid; from a cold
        // start (or when the warm start fails), solve on grids of n/2^k ≥ 64 nodes first and
        // interpolate each solution as the next guess.
        let n = options.nodes;
        let tol = options.tolerance;
        let mut total_iter = 0;
        let mut failure = None;
        let prediction = prediction.filter(|g| g.pressure.len() == n && g.centre_film > 0.0);
        for attempt in [Attempt::Predicted, Attempt::Warm, Attempt::Cold] {
            let warm = attempt != Attempt::Cold;
            if (attempt == Attempt::Warm && previous.is_none()) || (attempt == Attempt::Predicted && prediction.is_none()) {
                continue;
            }
            let mut levels = vec![n];
            if !warm {
                while levels[levels.len() - 1] / 2 >= 64 {
                    let next = levels[levels.len() - 1] / 2;
                    levels.push(next);
                }
                levels.reverse();
            }
            let mut guess: Option<(Vec<f64>, Vec<f64>, f64)> = if warm {
                previous.map(|s| {
                    let gx: Vec<f64> = s.x.iter().map(|x| x / b).collect();
                    let gp: Vec<f64> = s.pressure.iter().map(|p| p / ph).collect();
                    (gx, gp, (s.film_at(0.0, r) * r / (b * b)).max(1e-9))
                })
            } else {
                None
            };
            let nlev = levels.len();
            for (li, &nl) in levels.iter().enumerate() {
                let finest = li + 1 == nlev;
                let mut prob = build(&mut self.grids, nl);
                let (mut p, mut h0) = match (&guess, &prediction) {
                    (_, Some(g)) if attempt == Attempt::Predicted => {
                        let mut p: Vec<f64> = g.pressure.iter().map(|p| p.max(0.0)).collect();
                        p[0] = 0.0;
                        p[nl - 1] = 0.0;
                        let h0 = h0_for(&p, &prob, g.centre_film * r / (b * b));
                        (p, h0)
                    }
                    (Some((gx, gp, hc)), _) => from_guess(&prob, gx, gp, *hc),
                    (None, _) => cold(&prob, h_est.max(1e-6), h_est),
                };
                let ws = self.workspace(nl);
                let mut run = newton(&prob, ws, &mut p, &mut h0, tol, options.max_iterations, observer)?;
                total_iter += run.iterations;
                if attempt == Attempt::Predicted && !run.converged {
                    break;
                }
                if !run.converged && finest {
                    // Continuation from faster entrainment (thicker film, smaller M): λ·4^k → λ.
                    let (lambda_target, kappa_target) = (prob.lambda, prob.kappa);
                    for start in [2, 4, 7] {
                        let mut good = true;
                        for k in (0..=start).rev() {
                            let f = 4f64.powi(k);
                            prob.lambda = lambda_target * f;
                            prob.kappa = kappa_target * f;
                            if k == start {
                                (p, h0) = cold(&prob, h_est.max(1e-6) * f.powf(0.7), h_est);
                            }
                            let stage_tol = if k == 0 { tol } else { tol.max(1e-6) };
                            let r2 = newton(&prob, ws, &mut p, &mut h0, stage_tol, options.max_iterations, observer)?;
                            total_iter += r2.iterations;
                            if k == 0 {
                                run = r2;
                            } else if !r2.converged {
                                good = false;
                                break;
                            }
                        }
                        if good && run.converged {
                            break;
                        }
                    }
                    prob.lambda = lambda_target;
                    prob.kappa = kappa_target;
                }
                if finest {
                    if !run.converged {
                        let mut history = run.history.clone();
                        if history.len() > 20 {
                            history.drain(..history.len() - 20);
                        }
                        failure = Some(SolveError::NotConverged {
                            solver: "ehl line contact (Newton)",
                            iterations: total_iter,
                            residual: run.residual,
                            tolerance: tol,
                            history,
                        });
                        break;
                    }
                    let meta = Meta { b, ph, moes_m: sc.moes_m, moes_l: sc.moes_l, iterations: total_iter, residual: run.residual };
                    // `ws.v` holds Newton's evaluation at the converged `(p, h0)`.
                    return finish(input, options, &prob, &p, &ws.v, &meta);
                }
                // A coarse level: its solution (converged or the last finite iterate) is the next guess.
                let mut v = Fields::new(nl);
                guess = if prob.evaluate(&p, h0, &mut v) && p.iter().all(|p| p.is_finite()) {
                    let hc = interpolate(&prob.grid.x, &v.h, 0.0);
                    Some((prob.grid.x.clone(), p, hc))
                } else {
                    None
                };
            }
        }
        Err(failure.expect("at least one attempt ran"))
    }
}
