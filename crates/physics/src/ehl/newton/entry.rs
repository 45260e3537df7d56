use super::*;

/// Solve one line-contact EHL problem (steady, or one transient step when `input.transient` is
/// set). Polls `observer` once per Newton step. For a sequence of related problems (a cam
/// cycle), [`super::super::TransientSolver`] keeps grids and factorisations between the steps.
pub fn solve(input: &EhlInput, options: &EhlOptions, observer: &dyn Observer) -> Result<EhlSolution, SolveError> {
    Engine::new().solve(input, options, None, None, observer)
}

/// `H0` that puts the centre film at `target` (and keeps the film positive everywhere).
pub(super) fn h0_for(p: &[f64], prob: &Discretisation, target: f64) -> f64 {
    let n = prob.n();
    let x = &prob.grid.x;
    let mut d = vec![0.0; n];
    prob.grid.kernel.deflection(p, &mut d);
    let centre = x.partition_point(|&x| x < 0.0).min(n - 1);
    let min_rigid = (0..n).map(|i| 0.5 * x[i] * x[i] - d[i]).fold(f64::INFINITY, f64::min);
    let at_centre = 0.5 * x[centre] * x[centre] - d[centre];
    (target - at_centre).max(0.05 * target - min_rigid)
}

/// A guess on a grid from a dimensionless pressure `gp` at `gx` and the centre film `hc`: the
/// interpolated pressure scaled to carry the load.
pub(super) fn from_guess(prob: &Discretisation, gx: &[f64], gp: &[f64], hc: f64) -> (Vec<f64>, f64) {
    let n = prob.n();
    let x = &prob.grid.x;
    let mut p: Vec<f64> = x.iter().map(|&x| if x <= gx[0] || x >= gx[gx.len() - 1] { 0.0 } else { interpolate(gx, gp, x) }).collect();
    p[0] = 0.0;
    p[n - 1] = 0.0;
    let sum: f64 = p.iter().zip(&prob.grid.cell).map(|(p, w)| p * w).sum();
    if sum > 0.0 {
        p.iter_mut().for_each(|v| *v *= 0.5 * PI / sum);
    } else {
        hertz_guess(x, &mut p, 1.0);
    }
    let h0 = h0_for(&p, prob, hc);
    (p, h0)
}

/// A cold start: a (widened, for light loads) Hertzian pressure and the centre film `hc`.
pub(super) fn cold(prob: &Discretisation, hc: f64, h_est: f64) -> (Vec<f64>, f64) {
    let mut p = vec![0.0; prob.n()];
    hertz_guess(&prob.grid.x, &mut p, 1f64.max((2.0 * h_est).sqrt()));
    let h0 = h0_for(&p, prob, hc);
    (p, h0)
}

/// Semi-elliptical pressure of half-width `a` carrying the load: `sqrt(1 − (X/a)²)/a` (Hertz for
/// `a = 1`; wider for light loads, where the pressure spreads over `~sqrt(2H)`).
pub(super) fn hertz_guess(x: &[f64], p: &mut [f64], a: f64) {
    let n = x.len();
    for i in 0..n {
        let s = x[i] / a;
        p[i] = if i == 0 || i == n - 1 { 0.0 } else { (1.0 - s * s).max(0.0).sqrt() / a };
    }
}

pub(super) fn validate(input: &EhlInput, options: &EhlOptions) -> Result<(), SolveError> {
    let pos = |v: f64, path: &str| {
        if v.is_finite() && v > 0.0 { Ok(()) } else { Err(SolveError::invalid(path, "must be a finite number > 0")) }
    };
    pos(input.load_per_length, "EhlInput.load_per_length")?;
    pos(input.reduced_radius, "EhlInput.reduced_radius")?;
    pos(input.effective_modulus, "EhlInput.effective_modulus")?;
    pos(input.temperature, "EhlInput.temperature")?;
    pos(input.lubricant.viscosity, "EhlInput.lubricant.viscosity")?;
    pos(input.lubricant.density, "EhlInput.lubricant.density")?;
    if !(input.lubricant.pressure_viscosity.is_finite() && input.lubricant.pressure_viscosity >= 0.0) {
        return Err(SolveError::invalid("EhlInput.lubricant.pressure_viscosity", "must be a finite number >= 0"));
    }
    if !input.entrainment_velocity.is_finite() {
        return Err(SolveError::invalid("EhlInput.entrainment_velocity", "must be finite"));
    }
    if !input.sliding_velocity.is_finite() {
        return Err(SolveError::invalid("EhlInput.sliding_velocity", "must be finite"));
    }
    if let Some(s) = input.transient {
        pos(s.time_step, "EhlInput.transient.time_step")?;
        if s.previous.x.len() < 2 {
            return Err(SolveError::invalid("EhlInput.transient.previous", "a previous state needs at least two nodes"));
        }
    }
    if options.nodes < 16 {
        return Err(SolveError::invalid("EhlOptions.nodes", "at least 16 nodes"));
    }
    if !(options.tolerance.is_finite() && options.tolerance > 0.0) {
        return Err(SolveError::invalid("EhlOptions.tolerance", "must be a finite number > 0"));
    }
    for (v, path) in [(options.inlet, "EhlOptions.inlet"), (options.outlet, "EhlOptions.outlet")] {
        if let Some(v) = v {
            if !(v.is_finite() && v > 1.0) {
                return Err(SolveError::invalid(path, "must exceed one Hertzian half-width"));
            }
        }
    }
    Ok(())
}

/// Vertex `(x, f)` of the parabola through the nodes `i − 1, i, i + 1` (an extremum's refined
/// position and value), kept within the neighbouring nodes; the node itself at the ends.
pub(super) fn vertex(x: &[f64], f: &[f64], i: usize) -> (f64, f64) {
    if i == 0 || i + 1 >= f.len() {
        return (x[i], f[i]);
    }
    let (x0, x1, x2) = (x[i - 1], x[i], x[i + 1]);
    let (f0, f1, f2) = (f[i - 1], f[i], f[i + 1]);
    // Divided differences: f ≈ f1 + d1 (x − x1) + d2 (x − x1)(x − x0) ... in Newton form.
    let a = (f2 - f1) / (x2 - x1);
    let c = (f1 - f0) / (x1 - x0);
    let curv = (a - c) / (x2 - x0); // f''/2
    if curv == 0.0 || !curv.is_finite() {
        return (x1, f1);
    }
    // Slope at x1 of the parabola: (c (x2 − x1) + a (x1 − x0)) / (x2 − x0).
    let slope = (c * (x2 - x1) + a * (x1 - x0)) / (x2 - x0);
    let dx = (-slope / (2.0 * curv)).clamp(x0 - x1, x2 - x1);
    (x1 + dx, f1 + slope * dx + curv * dx * dx)
}

/// Linear interpolation of `f(x)` at `at` (clamped to the ends).
pub(super) fn interpolate(x: &[f64], f: &[f64], at: f64) -> f64 {
    let n = x.len();
    let i = x.partition_point(|&v| v <= at).clamp(1, n - 1);
    let t = ((at - x[i - 1]) / (x[i] - x[i - 1])).clamp(0.0, 1.0);
    f[i - 1] * (1.0 - t) + f[i] * t
}

/// The solution from the converged pressure `p` and the fields `v` Newton evaluated at it (its
/// last evaluation: the film is positive and every value finite — not evaluated again).
pub(super) fn finish(input: &EhlInput, options: &EhlOptions, prob: &Discretisation, p: &[f64], v: &Fields, meta: &Meta) -> Result<EhlSolution, SolveError> {
    let &Meta { b, ph, moes_m, moes_l, iterations, residual } = meta;
    let n = prob.n();
    let r = input.reduced_radius;
    let hs = b * b / r; // film scale
    let x: Vec<f64> = prob.grid.x.iter().map(|&x| x * b).collect();
    let pressure: Vec<f64> = p.iter().map(|&p| p.max(0.0) * ph).collect();
    let film: Vec<f64> = v.h.iter().map(|&h| h * hs).collect();
    let asperity_pressure: Vec<f64> = match prob.asperity {
        Some(_) => (0..n).map(|i| v.pa[i].max(0.0).min(p[i].max(0.0)) * ph).collect(),
        None => Vec::new(),
    };
    let fluid_pressure: Vec<f64> = match prob.asperity {
        Some(_) => (0..n).map(|i| pressure[i] - asperity_pressure[i]).collect(),
        None => pressure.clone(),
    };
    let asperity_load_per_length: f64 = asperity_pressure.iter().zip(&prob.grid.cell).map(|(p, c)| p * c * b).sum();
    ensure_finite("ehl asperity pressure", &asperity_pressure)?;
    ensure_finite("ehl pressure", &pressure)?;
    ensure_finite("ehl film", &film)?;
    let dir = if input.entrainment_velocity >= 0.0 { 1.0 } else { -1.0 };
    let central_film = interpolate(&x, &film, 0.0);
    let argmin = |range: &mut dyn Iterator<Item = usize>| {
        range.fold(None, |best: Option<usize>, i| match best {
            Some(j) if film[j] <= film[i] => Some(j),
            _ => Some(i),
        })
    };
    let imin = argmin(&mut (0..n)).unwrap_or(0);
    // The parabolic vertex refines the minimum between nodes. Where the grid does not resolve a
    // sharp exit constriction (very large M on a coarse grid) the parabola overshoots — even below
    // zero (regression: p0 = 2.7 GPa, u = 0.2 mm/s, 128 nodes) — so it is trusted only within a
    // factor of two of the node value; and no minimum exceeds the central film.
    let refined_min = |i: usize| match vertex(&x, &film, i) {
        (pos, h) if h >= 0.5 * film[i] => (pos, h),
        _ => (x[i], film[i]),
    };
    let (min_film_position, min_film) = refined_min(imin);
    let min_film = min_film.min(central_film);
    let downstream = |i: &usize| prob.grid.x[*i] * dir > 0.0;
    let iexit = argmin(&mut (0..n).filter(downstream)).unwrap_or(imin);
    let (_, exit_film) = refined_min(iexit);
    let imax = (0..n).fold(0, |j, i| if pressure[i] > pressure[j] { i } else { j });
    let (max_pressure_position, max_pressure) = vertex(&x, &pressure, imax);
    // Spike: the most downstream local maximum beyond the centre that exceeds the Hertzian
    // pressure at its position and a fifth of the peak pressure.
    let mut spike = None;
    for i in 1..n - 1 {
        let local_max = pressure[i] > pressure[i - 1] && pressure[i] >= pressure[i + 1];
        let hertz = (1.0 - prob.grid.x[i] * prob.grid.x[i]).max(0.0).sqrt() * ph;
        if local_max && downstream(&i) && pressure[i] > hertz && pressure[i] >= 0.2 * pressure[imax] {
            let (position, val) = vertex(&x, &pressure, i);
            let cand = PressureSpike { pressure: val, position };
            spike = match spike {
                Some(PressureSpike { position, .. }) if position * dir > cand.position * dir => spike,
                _ => Some(cand),
            };
        }
    }
    let traction = traction(
        &x,
        &fluid_pressure,
        &film,
        &input.lubricant,
        input.temperature,
        input.sliding_velocity,
        input.load_per_length,
        &input.rheology,
    );
    ensure_finite(
        "ehl traction",
        [&traction.force_body_1, &traction.force_body_2, &traction.friction_coefficient, &traction.rolling_force],
    )?;
    ensure_finite("ehl films", [&central_film, &min_film, &exit_film, &max_pressure])?;
    let density_ratio = (0..n).map(|i| prob.mass_density(v, i)).collect();
    let state = EhlState { x: x.clone(), pressure: pressure.clone(), film: film.clone(), density_ratio, asperity_pressure: asperity_pressure.clone() };
    let profiles = options.profiles.then(|| Profiles { x, pressure, film, asperity_pressure });
    Ok(EhlSolution {
        hertz_half_width: b,
        hertz_pressure: ph,
        moes_m,
        moes_l,
        central_film,
        min_film,
        min_film_position,
        exit_film,
        max_pressure,
        max_pressure_position,
        pressure_spike: spike,
        asperity_load_per_length,
        traction,
        profiles,
        state,
        nodes: n,
        convergence: Convergence { iterations, residual, tolerance: options.tolerance, termination: Termination::Converged },
    })
}
