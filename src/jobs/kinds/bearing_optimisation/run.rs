use super::*;

impl Evaluator {
    pub(super) fn design(&self, spec: &BearingSpec, p: Option<BearingProfileSpec>, ws: Option<&mut Workspace>, observer: &dyn Observer) -> Result<(Design, Guess), SolveError> {
        let mut s = spec.clone();
        s.profile = p;
        let (a, r) = solve_spec(&s, (self.op, self.guess, None), ws, observer)?;
        let f = match self.friction {
            FrictionDefinition::Seed002 => r.friction_variable_seed002,
            FrictionDefinition::RaimondiBoyd => r.friction_variable,
        }
        .ok_or_else(|| SolveError::physical(crate::physics::PhysicalFailure::NoLoad, "the design carries no load"))?;
        Ok((
            Design {
                order: p.map_or(0, |p| p.order),
                height: p.map_or(0.0, |p| p.height),
                length_fraction: p.map_or(0.0, |p| p.length_fraction),
                max_pressure_dimensionless: a.max_pressure,
                min_film_dimensionless: a.min_film,
                friction_variable: f,
                score: 0.0,
                eccentricity_ratio: a.eccentricity,
                max_pressure: r.max_pressure,
                min_film: r.min_film,
            },
            Guess { eccentricity: a.eccentricity, attitude: a.attitude },
        ))
    }
}

pub(super) fn criteria(d: &Design) -> Criteria {
    Criteria { pressure: d.max_pressure_dimensionless, film: d.min_film_dimensionless, friction: d.friction_variable }
}

/// The whole optimisation of one spec (public for the tests of its scheduling).
pub fn optimise(spec: &OptimisationSpec, observer: &dyn Observer) -> Result<OptimisationResult, SolveError> {
    let base = &spec.base;
    observer.progress(0.0, "reference load");
    let array = spec.method.array();
    let rows = array.rows();
    let levels = array.levels();
    let f = &spec.factors;
    let weights = Weights { film: spec.weights.film, pressure: spec.weights.pressure, friction: spec.weights.friction };
    let profile = |r: &[usize; 3]| BearingProfileSpec { order: f.order[r[0]], height: f.height[r[1]], length_fraction: f.length_fraction[r[2]] };
    let cases: Vec<Option<BearingProfileSpec>> = std::iter::once(None).chain(rows.iter().map(|r| Some(profile(r)))).collect();
    let workers = rayon::current_num_threads().clamp(1, cases.len());
    // the reference analysis on one thread (aligned and unprofiled: on the mirrored half of
    // the grid, with grids of its own) while the other allocates the array's workspaces
    let (reference_load, spares) = rayon::join(
        || resolve_load_in(base, None, observer),
        || (0..workers).map(|_| Workspace::new(&base.bearing(), &base.settings())).collect::<Vec<_>>(),
    );
    let (op, guess, target) = reference_load?;
    let mut evaluations = if base.load.aligned_eccentricity_ratio.is_some() { 1 } else { 0 };
    let load = target.unwrap_or(0.0);
    let ev = Evaluator { friction: spec.friction, op, guess };
    observer.progress(0.1, "orthogonal array");
    // The array on the pool, every analysis on a reset workspace (`Workspace::reset`), so its
    // result is the same bit for bit whichever worker runs it after whichever analysis, for any
    // pool size. The order (BENCHMARKS.md, journal speed, fourteenth round):
    // 1. the runs, each worker taking the next from a shared counter;
    // 2. the unprofiled baseline, which nothing else needs, by the first worker without a run;
    // 3. the confirmation of the best-level combination (when it is not a run), by the worker
    //    that completes the array. It then overlaps the baseline instead of following the array
    //    on one thread.
    // A worker left with nothing while runs are still in flight (more workers than these
    // tasks) guesses the best levels (`predicted_best_levels`) and starts that confirmation
    // speculatively; a wrong guess is abandoned as soon as the last run is in and costs only
    // that idle worker's time.
    let runs_total = cases.len() - 1;
    let next = AtomicUsize::new(0);
    let failed = AtomicBool::new(false);
    let baseline_taken = AtomicBool::new(false);
    let done: Mutex<Vec<Option<Design>>> = Mutex::new(vec![None; cases.len()]);
    // 0: the array is not complete; else 1 + the index of its best-level combination
    let known_best = AtomicUsize::new(0);
    // 0: no speculation started; else 1 + the index of the combination speculated on
    let speculated = AtomicUsize::new(0);
    let confirmation_taken = AtomicBool::new(false);
    let confirmation: Mutex<Option<([usize; 3], Design)>> = Mutex::new(None);
    let combo_index = |c: &[usize; 3]| 1 + (c[0] * levels + c[1]) * levels + c[2];
    let combo_of = |index: usize| {
        let i = index - 1;
        [i / (levels * levels), (i / levels) % levels, i % levels]
    };
    let spare = Mutex::new(spares);
    let workspaces: Vec<Workspace> = (0..workers)
        .into_par_iter()
        .map(|_| -> Result<Workspace, SolveError> {
            let mut ws = spare.lock().ok().and_then(|mut s| s.pop()).unwrap_or_else(|| Workspace::new(&base.bearing(), &base.settings()));
            let fail = |e: SolveError| {
                failed.store(true, Ordering::SeqCst);
                e
            };
            let confirm = |ws: &mut Workspace, combo: [usize; 3], observer: &dyn Observer| -> Result<(), SolveError> {
                ws.reset();
                let (d, _) = ev.design(base, Some(profile(&combo)), Some(ws), observer)?;
                *confirmation.lock().unwrap_or_else(|e| e.into_inner()) = Some((combo, d));
                Ok(())
            };
            loop {
                if failed.load(Ordering::SeqCst) {
                    break;
                }
                let run = next.fetch_add(1, Ordering::SeqCst);
                let case = if run < runs_total {
                    Some(run + 1)
                } else if !baseline_taken.swap(true, Ordering::SeqCst) {
                    Some(0)
                } else {
                    None
                };
                if let Some(i) = case {
                    ws.reset();
                    let (d, _) = observer.check().map_err(SolveError::from).and_then(|_| ev.design(base, cases[i], Some(&mut ws), observer)).map_err(fail)?;
                    let mut all = done.lock().unwrap_or_else(|e| e.into_inner());
                    all[i] = Some(d);
                    if i > 0 && all[1..].iter().all(Option::is_some) {
                        let designs: Vec<Design> = all[1..].iter().flatten().copied().collect();
                        drop(all);
                        let best = best_levels(&rows, levels, &sn_ratios(&designs, &weights));
                        known_best.store(combo_index(&best), Ordering::SeqCst);
                    }
                    continue;
                }
                let known = known_best.load(Ordering::SeqCst);
                if known != 0 {
                    // the array is complete: its confirmation, unless it is a run or a
                    // speculation on the right combination is under way
                    let best = combo_of(known);
                    if !rows.contains(&best) && speculated.load(Ordering::SeqCst) != known && !confirmation_taken.swap(true, Ordering::SeqCst) {
                        confirm(&mut ws, best, observer).map_err(fail)?;
                    }
                    break;
                }
                if speculated.load(Ordering::SeqCst) != 0 {
                    break;
                }
                let runs_so_far: Vec<Option<Design>> = done.lock().unwrap_or_else(|e| e.into_inner())[1..].to_vec();
                let Some(combo) = predicted_best_levels(&rows, levels, &runs_so_far, &weights) else { break };
                let mine = combo_index(&combo);
                if speculated.compare_exchange(0, mine, Ordering::SeqCst, Ordering::SeqCst).is_err() {
                    break;
                }
                let known = known_best.load(Ordering::SeqCst);
                if known != 0 && known != mine {
                    // the array completed meanwhile with another best: the loop takes its
                    // confirmation
                    continue;
                }
                if confirmation_taken.swap(true, Ordering::SeqCst) {
                    // the worker that completed the array took it before seeing this guess
                    break;
                }
                let abandon = Abandon { inner: observer, known_best: &known_best, failed: &failed, mine };
                // an error here (a wrong guess abandoned, a cancel, a failure) is not kept:
                // the confirmation runs again (below or after the array) and reports it
                if confirm(&mut ws, combo, &abandon).is_err() && known_best.load(Ordering::SeqCst) != mine {
                    // abandoned for another combination: take the true confirmation
                    confirmation_taken.store(false, Ordering::SeqCst);
                    speculated.store(usize::MAX, Ordering::SeqCst);
                    continue;
                }
                break;
            }
            Ok(ws)
        })
        .collect::<Result<_, _>>()?;
    let mut ws_confirm = workspaces.into_iter().next();
    let mut all: Vec<Design> = done.into_inner().unwrap_or_else(|e| e.into_inner()).into_iter().flatten().collect();
    evaluations += all.len();
    let mut baseline = all.remove(0);
    let designs = all;
    let crit: Vec<Criteria> = designs.iter().map(criteria).collect();
    let reference = Reference::of(&crit);
    let score = |d: &Design| reference.score(&criteria(d), &weights);
    let runs: Vec<Run> = designs
        .iter()
        .enumerate()
        .map(|(i, d)| {
            let (h, p, fr) = reference.normalise(&criteria(d));
            let s = score(d);
            Run {
                run: i + 1,
                order: d.order,
                height: d.height,
                length_fraction: d.length_fraction,
                max_pressure_dimensionless: d.max_pressure_dimensionless,
                min_film_dimensionless: d.min_film_dimensionless,
                friction_variable: d.friction_variable,
                pressure_normalised: p,
                film_normalised: h,
                friction_normalised: fr,
                score: s,
                sn_ratio_db: sn_larger_better(s),
                eccentricity_ratio: d.eccentricity_ratio,
            }
        })
        .collect();
    let best_run = runs.iter().max_by(|a, b| a.score.total_cmp(&b.score)).map_or(1, |r| r.run);
    let scores: Vec<f64> = runs.iter().map(|r| r.score).collect();
    let sn: Vec<f64> = runs.iter().map(|r| r.sn_ratio_db).collect();
    let mut main_effects = Vec::new();
    for (fi, name) in ["order", "height", "length_fraction"].iter().enumerate() {
        let ms = level_means(&rows, fi, levels, &scores);
        let mn = level_means(&rows, fi, levels, &sn);
        for l in 0..levels {
            let value = match fi {
                0 => f.order[l] as f64,
                1 => f.height[l],
                _ => f.length_fraction[l],
            };
            main_effects.push(Effect { factor: name.to_string(), level: l + 1, value, mean_score: ms[l], mean_sn_ratio_db: mn[l] });
        }
    }
    let best = best_levels(&rows, levels, &sn);
    let best_combo = match rows.iter().position(|r| *r == best) {
        Some(i) => designs[i],
        None => {
            evaluations += 1;
            match confirmation.into_inner().unwrap_or_else(|e| e.into_inner()) {
                Some((combo, d)) if combo == best => d,
                _ => {
                    if let Some(ws) = ws_confirm.as_mut() {
                        ws.reset();
                    }
                    ev.design(base, Some(profile(&best)), ws_confirm.as_mut(), observer)?.0
                }
            }
        }
    };
    let mut best_design = best_combo;
    best_design.score = score(&best_combo);
    let taguchi_best = best_design.score.max(runs[best_run - 1].score);
    baseline.score = score(&baseline);

    let continuous = if spec.continuous.enabled {
        observer.progress(0.5, "continuous search");
        let c = &spec.continuous;
        let hb = c.height.unwrap_or([f.height.iter().cloned().fold(f64::INFINITY, f64::min), f.height.iter().cloned().fold(0.0, f64::max)]);
        let pb = c.length_fraction.unwrap_or([
            f.length_fraction.iter().cloned().fold(f64::INFINITY, f64::min),
            f.length_fraction.iter().cloned().fold(0.0, f64::max),
        ]);
        let lo = [hb[0], pb[0].max(1e-3)];
        let hi = [hb[1].max(hb[0] + 1e-6), pb[1].max(pb[0].max(1e-3) + 1e-6)];
        let mut orders = f.order.clone();
        orders.sort();
        orders.dedup();
        let coarse = if c.coarse_search {
            let mut s = base.clone();
            s.grid.circumferential = (base.grid.circumferential / 2).max(17) | 1;
            s.grid.axial = (base.grid.axial / 2).max(9) | 1;
            s
        } else {
            base.clone()
        };
        let per: Vec<(Design, usize)> = orders
            .par_iter()
            .map(|&n| -> Result<(Design, usize), SolveError> {
                // start from the best run of this order
                let start = designs
                    .iter()
                    .filter(|d| d.order == n)
                    .max_by(|a, b| score(a).total_cmp(&score(b)))
                    .map_or([0.5 * (lo[0] + hi[0]), 0.5 * (lo[1] + hi[1])], |d| [d.height, d.length_fraction]);
                let mut used = 0;
                let objective = |spec_: &BearingSpec, ws: &mut Workspace, x: &[f64], used: &mut usize| -> Result<f64, SolveError> {
                    observer.check()?;
                    *used += 1;
                    let p = BearingProfileSpec { order: n, height: x[0], length_fraction: x[1] };
                    match ev.design(spec_, Some(p), Some(ws), observer) {
                        Ok((d, _)) => Ok(-score(&d)),
                        Err(SolveError::Interrupted(i)) => Err(SolveError::Interrupted(i)),
                        Err(_) => Ok(f64::INFINITY),
                    }
                };
                let step = [0.15 * (hi[0] - lo[0]), 0.15 * (hi[1] - lo[1])];
                let mut ws = Workspace::new(&coarse.bearing(), &coarse.settings());
                let m = nelder_mead(|x| objective(&coarse, &mut ws, x, &mut used), &start, &step, &lo, &hi, c.evaluations_per_order, 1e-7)?;
                let mut x = m.x.clone();
                if c.coarse_search {
                    let mut ws = Workspace::new(&base.bearing(), &base.settings());
                    let small = [0.03 * (hi[0] - lo[0]), 0.03 * (hi[1] - lo[1])];
                    let m2 = nelder_mead(|x| objective(base, &mut ws, x, &mut used), &x, &small, &lo, &hi, 15, 1e-8)?;
                    x = m2.x;
                }
                let (mut d, _) = ev.design(base, Some(BearingProfileSpec { order: n, height: x[0], length_fraction: x[1] }), None, observer)?;
                used += 1;
                d.score = score(&d);
                Ok((d, used))
            })
            .collect::<Result<_, _>>()?;
        let used: usize = per.iter().map(|p| p.1).sum();
        evaluations += used;
        let per_order: Vec<Design> = per.into_iter().map(|p| p.0).collect();
        let design = *per_order.iter().max_by(|a, b| a.score.total_cmp(&b.score)).unwrap();
        Some(Continuous { design, per_order, improves_on_taguchi: design.score > taguchi_best, evaluations: used })
    } else {
        None
    };
    observer.progress(1.0, "done");
    Ok(OptimisationResult {
        runs,
        best_run,
        best_levels: BestLevels {
            order_level: best[0] + 1,
            height_level: best[1] + 1,
            length_fraction_level: best[2] + 1,
            design: best_design,
        },
        main_effects,
        baseline,
        load_dimensionless: load,
        continuous,
        evaluations,
        convergence: Convergence { iterations: evaluations as u32, residual: 0.0, tolerance: 0.0, termination: Termination::Converged },
    })
}

/// S/N ratio of each run (larger the better, dB) on the runs' own normalisation (eq. 19).
pub(super) fn sn_ratios(designs: &[Design], weights: &Weights) -> Vec<f64> {
    let crit: Vec<Criteria> = designs.iter().map(criteria).collect();
    let reference = Reference::of(&crit);
    crit.iter().map(|c| sn_larger_better(reference.score(c, weights))).collect()
}

/// The level of each factor with the largest mean S/N (0-based).
pub(super) fn best_levels(rows: &[[usize; 3]], levels: usize, sn: &[f64]) -> [usize; 3] {
    let mut best = [0usize; 3];
    for (fi, b) in best.iter_mut().enumerate() {
        let mn = level_means(rows, fi, levels, sn);
        *b = (0..levels).max_by(|a, b| mn[*a].total_cmp(&mn[*b])).unwrap_or(0);
    }
    best
}

/// A guess of the array's best-level combination while some runs are still running, for
/// starting the confirmation run early: the S/N ratios of the runs done (on their own
/// normalisation), the missing runs' S/N set to one value `s` scanned from below the lowest to
/// above the highest known ratio, and of the combinations that come out and are not runs of
/// the array (only those need a confirmation run) the one that does for the widest range of
/// `s`. `None` when every outcome is a run or too few runs are done. Only a guess: a wrong
/// one costs the idle worker's time, never a result.
pub(super) fn predicted_best_levels(rows: &[[usize; 3]], levels: usize, runs: &[Option<Design>], weights: &Weights) -> Option<[usize; 3]> {
    let done: Vec<Design> = runs.iter().flatten().copied().collect();
    if done.len() < 2 {
        return None;
    }
    let known = sn_ratios(&done, weights);
    let (lo, hi) = known.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), x| (a.min(*x), b.max(*x)));
    if !(lo.is_finite() && hi.is_finite()) {
        return None;
    }
    let margin = 0.5 * (hi - lo) + 1e-3;
    let mut tally: Vec<([usize; 3], usize)> = Vec::new();
    pub(super) const SAMPLES: usize = 64;
    for k in 0..=SAMPLES {
        let s = lo - margin + (hi - lo + 2.0 * margin) * k as f64 / SAMPLES as f64;
        let mut it = known.iter();
        let sn: Vec<f64> = runs.iter().map(|r| if r.is_some() { *it.next().unwrap_or(&s) } else { s }).collect();
        let combo = best_levels(rows, levels, &sn);
        if rows.contains(&combo) {
            continue;
        }
        match tally.iter_mut().find(|t| t.0 == combo) {
            Some(t) => t.1 += 1,
            None => tally.push((combo, 1)),
        }
    }
    tally.iter().max_by_key(|t| t.1).map(|t| t.0)
}

impl Observer for Abandon<'_> {
    fn progress(&self, fraction: f64, stage: &str) {
        self.inner.progress(fraction, stage);
    }
    fn check(&self) -> Result<(), crate::physics::Interrupt> {
        let known = self.known_best.load(Ordering::Relaxed);
        if (known != 0 && known != self.mine) || self.failed.load(Ordering::Relaxed) {
            return Err(crate::physics::Interrupt::Canceled);
        }
        self.inner.check()
    }
}
