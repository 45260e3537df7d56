use super::*;

/// What the spec's `load` asks for, resolved to the solver's operating point (the aligned
/// reference is solved here when needed). Returns the operating point and a starting guess.
pub fn resolve_load(
    spec: &BearingSpec,
    observer: &dyn Observer,
) -> Result<(Operating, Option<Guess>, Option<f64>), SolveError> {
    resolve_load_in(spec, None, observer)
}

/// [`resolve_load`] with a workspace for the reference analysis (the grids are reused; the
/// result does not depend on what the workspace held).
pub fn resolve_load_in(
    spec: &BearingSpec,
    workspace: Option<&mut Workspace>,
    observer: &dyn Observer,
) -> Result<(Operating, Option<Guess>, Option<f64>), SolveError> {
    let l = &spec.load;
    if let Some(e) = l.eccentricity_ratio {
        return Ok(match l.attitude_angle_deg {
            Some(a) => (Operating::Position { eccentricity: e, attitude: a.to_radians() }, None, None),
            None => (Operating::Eccentricity(e), None, None),
        });
    }
    if let Some(e) = l.aligned_eccentricity_ratio {
        let (w, guess) = aligned_reference_in(spec, e, workspace, observer)?;
        return Ok((Operating::Load(w), Some(guess), Some(w)));
    }
    if let Some(f) = l.force {
        let d = spec.dimensions().ok_or_else(|| SolveError::invalid("/load/force", "needs dimensions"))?;
        let w = f / d.load_scale();
        return Ok((Operating::Load(w), None, Some(w)));
    }
    if let Some(s) = l.sommerfeld_number {
        let w = 1.0 / (6.0 * PI * s);
        return Ok((Operating::Load(w), None, Some(w)));
    }
    Err(SolveError::invalid("/load", "no operating point given"))
}

/// The load (W̄) an aligned, unprofiled bearing with the spec's L/D, supply and grid carries at
/// eccentricity ratio `e`, and its position.
pub fn aligned_reference(spec: &BearingSpec, e: f64, observer: &dyn Observer) -> Result<(f64, Guess), SolveError> {
    aligned_reference_in(spec, e, None, observer)
}

pub(super) fn aligned_reference_in(spec: &BearingSpec, e: f64, workspace: Option<&mut Workspace>, observer: &dyn Observer) -> Result<(f64, Guess), SolveError> {
    let mut b = spec.bearing();
    b.misalignment = Misalignment::default();
    b.profile = None;
    // aligned and unprofiled: symmetric about the mid-plane, solved on half the axial grid
    // (the same discrete equations; an even axial node count takes the full grid)
    journal::symmetric_load(&b, &Operating::Eccentricity(e), &spec.settings(), workspace, None, observer)
}

/// Turn an analysis into the result document.
pub fn to_result(spec: &BearingSpec, a: &Analysis, target: Option<f64>) -> BearingResult {
    let d = spec.dimensions();
    let stride = spec.field_stride;
    let want_p = spec.outputs.contains(&BearingOutput::PressureField);
    let want_h = spec.outputs.contains(&BearingOutput::FilmField);
    let field = a.fields.as_ref().filter(|_| want_p || want_h).map(|f| {
        let nt = f.theta.len();
        let nz = f.z.len();
        // columns 0..nt (the 360° column repeats 0°), rows 0..nz, every stride-th plus the last
        let pick = |n: usize, s: usize| {
            let mut v: Vec<usize> = (0..n).step_by(s).collect();
            if *v.last().unwrap() != n - 1 {
                v.push(n - 1);
            }
            v
        };
        let cols = pick(nt + 1, stride.circumferential);
        let rows = pick(nz, stride.axial);
        let mut t = FieldTable {
            angle_deg: Vec::new(),
            z: Vec::new(),
            pressure_dimensionless: want_p.then(Vec::new),
            film_dimensionless: want_h.then(Vec::new),
        };
        for &j in &rows {
            for &c in &cols {
                let i = c % nt;
                let ang = if c == nt { f.theta[0].to_degrees() + 360.0 } else { f.theta[i].to_degrees() };
                t.angle_deg.push(ang);
                t.z.push(f.z[j]);
                if let Some(p) = &mut t.pressure_dimensionless {
                    p.push(f.pressure[j * nt + i]);
                }
                if let Some(h) = &mut t.film_dimensionless {
                    h.push(f.film[j * nt + i]);
                }
            }
        }
        t
    });
    BearingResult {
        eccentricity_ratio: a.eccentricity,
        attitude_angle_deg: a.attitude.to_degrees(),
        sommerfeld_number: a.sommerfeld,
        load: LoadResult {
            dimensionless: a.load,
            along_load_dimensionless: a.force_along_load,
            across_load_dimensionless: a.force_across_load,
            force: d.map(|d| a.load * d.load_scale()),
            target_dimensionless: target,
        },
        max_pressure_dimensionless: a.max_pressure,
        max_pressure_location: Location { angle_deg: a.max_pressure_theta.to_degrees(), z: a.max_pressure_z },
        max_pressure: d.map(|d| a.max_pressure * d.pressure_scale()),
        min_film_dimensionless: a.min_film,
        min_film_location: Location { angle_deg: a.min_film_theta.to_degrees(), z: a.min_film_z },
        min_film: d.map(|d| d.film(a.min_film)),
        friction_variable: a.friction_variable,
        friction_variable_seed002: a.friction_variable_seed002,
        friction_coefficient: d.and_then(|d| a.friction_variable.map(|f| d.friction_coefficient(f))),
        flow_variable: a.flow_variable,
        side_flow_variable: a.side_flow_variable,
        side_flow_ratio: a.side_flow_ratio,
        flow: d.map(|d| d.flow(a.flow_variable)),
        side_flow: d.map(|d| d.flow(a.side_flow_variable)),
        power_loss_dimensionless: a.friction_force,
        power_loss: d.map(|d| d.power(a.friction_force)),
        convergence: a.convergence.clone(),
        pressure_convergence: PressureConvergence {
            active_set_steps: a.pressure_solve.steps,
            cycles: a.pressure_solve.cycles,
            residual: a.pressure_solve.residual,
        },
        grids: a
            .steps_per_grid
            .iter()
            .map(|&(c, z, s)| GridSteps { circumferential: c, axial: z, steps: s })
            .collect(),
        field,
        dynamic_coefficients: None,
        moment_coefficients: None,
        thermal: None,
        checks: None,
    }
}

/// Solve one bearing spec (shared with the optimisation, which passes a workspace and a guess).
pub fn solve_spec(
    spec: &BearingSpec,
    load: (Operating, Option<Guess>, Option<f64>),
    workspace: Option<&mut Workspace>,
    observer: &dyn Observer,
) -> Result<(Analysis, BearingResult), SolveError> {
    let want_fields = spec.outputs.iter().any(|o| matches!(o, BearingOutput::PressureField | BearingOutput::FilmField));
    let a = journal::analyse(&spec.bearing(), &load.0, &spec.settings(), workspace, load.1, want_fields, observer)?;
    let r = to_result(spec, &a, load.2);
    Ok((a, r))
}

/// Analyses a heat balance typically needs (each a warm-started load-balanced analysis).
pub(super) const HEAT_BALANCE_ANALYSES: f64 = 1.5;

/// The work and memory model of one `bearing` job: load-balanced analyses on the grid
/// (`jobs::cost::bearing_analysis_seconds`), times the heat balance's iterations, plus the
/// coefficients' adjoint solves (2 for the 2×2 set, 4 for the 4×4 set, each about one analysis).
pub fn bearing_cost(spec: &BearingSpec) -> Cost {
    let nodes = spec.grid.circumferential.saturating_mul(spec.grid.axial);
    let one = crate::jobs::cost::bearing_analysis_seconds(nodes);
    let mut analyses = if spec.thermal.is_some() { HEAT_BALANCE_ANALYSES } else { 1.0 };
    // A misaligned journal's film is not symmetric about the mid-plane: the whole grid, twice
    // the work of the aligned half (seed 002's misaligned case).
    if spec.misalignment.is_some() {
        analyses *= 2.0;
    }
    if spec.outputs.contains(&BearingOutput::MomentCoefficients) {
        analyses += 4.0 * 0.5;
    } else if spec.outputs.contains(&BearingOutput::DynamicCoefficients) {
        analyses += 2.0 * 0.5;
    }
    // The multigrid hierarchy (≈ 4/3 of the fine grid) of about 16 arrays of the grid (peak
    // resident memory: 43 MB at 721×361).
    let bytes = 16.0 * 8.0 * 4.0 / 3.0 * nodes as f64 + crate::jobs::cost::MIB;
    let what = format!("{analyses:.0} bearing analyses on {} × {} nodes", spec.grid.circumferential, spec.grid.axial);
    Cost::new(crate::jobs::cost::JOB_OVERHEAD_S + analyses * one, bytes)
        .work_at("/grid", what.clone())
        .memory_at("/grid", what)
}

/// The heat balance: bearing analyses at trial viscosities until the effective temperature
/// reproduces itself. Returns the spec at the final viscosity, its analysis, the load target and
/// the thermal block.
pub(super) fn thermal_balance(
    spec: &BearingSpec,
    t: &BearingThermalSpec,
    ws: &mut Workspace,
    observer: &dyn Observer,
) -> Result<(BearingSpec, Analysis, Option<f64>, BearingThermalResult), SolveError> {
    use journal::heat::{balance, Cooling, Flows, Oil, Walther};
    let lu = &t.lubricant;
    let law = match (&lu.iso_vg, &lu.viscosity_curve) {
        (Some(g), _) => Walther::iso_vg(*g, lu.viscosity_100c)?,
        (None, Some(c)) if c.len() == 2 => {
            let nu = |p: &BearingViscosityPoint| p.viscosity / lu.density * 1e6;
            Walther::through(c[0].temperature, nu(&c[0]), c[1].temperature, nu(&c[1]))?
        }
        _ => return Err(SolveError::invalid("Lubricant", "an ISO VG grade or a two-point viscosity curve")),
    };
    let oil = Oil { law, density: lu.density, specific_heat: lu.specific_heat };
    let cool = Cooling {
        supply_temperature: t.supply_temperature,
        carry_over: t.carry_over,
        housing: t.housing.map(|h| (h.heat_transfer, h.ambient_temperature)),
        tolerance: t.tolerance,
        max_iterations: t.max_iterations,
    };
    let mut guess: Option<Guess> = None;
    let mut last: Option<(BearingSpec, Analysis, Option<f64>)> = None;
    let b = balance(&oil, &cool, observer, |eta| {
        let s = spec.with_viscosity(eta);
        let d = s.dimensions().ok_or_else(|| SolveError::invalid("/thermal", "needs dimensions"))?;
        let (op, g0, target) = resolve_load(&s, observer)?;
        let (a, _) = solve_spec(&s, (op, guess.or(g0), target), Some(&mut *ws), observer)?;
        guess = Some(Guess { eccentricity: a.eccentricity, attitude: a.attitude });
        let f = Flows { power: d.power(a.friction_force), inflow: d.flow(a.flow_variable), side_flow: d.flow(a.side_flow_variable) };
        last = Some((s, a, target));
        Ok(f)
    })?;
    let (s, a, target) = last.expect("the balance ran at least one analysis");
    let tt = b.temperatures;
    let th = BearingThermalResult {
        effective_temperature: b.temperature,
        viscosity: b.viscosity,
        kinematic_viscosity: b.viscosity / oil.density * 1e6,
        inlet_temperature: tt.inlet,
        outlet_temperature: tt.outlet,
        max_temperature: tt.outlet,
        supply_temperature: t.supply_temperature,
        power_loss: b.flows.power,
        film_inflow: b.flows.inflow,
        side_flow: b.flows.side_flow,
        supply_flow: tt.supply_flow,
        convergence: b.convergence,
    };
    crate::physics::ensure_finite(
        "heat balance",
        [th.effective_temperature, th.viscosity, th.inlet_temperature, th.outlet_temperature, th.power_loss, th.film_inflow, th.side_flow, th.supply_flow].iter(),
    )?;
    Ok((s, a, target, th))
}

/// The coefficients block: dimensionless always (at a positive load), SI with dimensions.
pub(super) fn dynamic_result(spec: &BearingSpec, a: &Analysis, c: &journal::dynamics::Coefficients) -> DynamicCoefficientsResult {
    let d = spec.dimensions();
    let kmat = |m: [[f64; 2]; 2], s: f64| StiffnessResult { kxx: m[0][0] * s, kxy: m[0][1] * s, kyx: m[1][0] * s, kyy: m[1][1] * s };
    let cmat = |m: [[f64; 2]; 2], s: f64| DampingResult { cxx: m[0][0] * s, cxy: m[0][1] * s, cyx: m[1][0] * s, cyy: m[1][1] * s };
    let nondim = c.dimensionless(a.load);
    let stab = nondim.map(|(k, cc)| journal::dynamics::stability(k, cc));
    // K = (−∂F̄/∂X) · 6ηωRL(R/c)²/c, C = (−∂F̄/∂X') · 6ηωRL(R/c)²/(cω)
    let critical_mass = match (d, stab.and_then(|s| s.critical_mass)) {
        (Some(d), Some(m)) => Some(m * a.load * d.load_scale() / (d.clearance * d.omega * d.omega)),
        _ => None,
    };
    let threshold_speed_rpm = match (d, stab.and_then(|s| s.critical_mass)) {
        (Some(d), Some(m)) => Some(crate::physics::units::rad_per_s_to_rpm((m * 9.80665 / d.clearance).sqrt())),
        _ => None,
    };
    DynamicCoefficientsResult {
        stiffness: d.map(|d| kmat(c.stiffness, d.load_scale() / d.clearance)),
        damping: d.map(|d| cmat(c.damping, d.load_scale() / (d.clearance * d.omega))),
        stiffness_dimensionless: nondim.map(|(k, _)| kmat(k, 1.0)),
        damping_dimensionless: nondim.map(|(_, cc)| cmat(cc, 1.0)),
        whirl_ratio: stab.map(|s| s.whirl_ratio),
        critical_mass_dimensionless: stab.and_then(|s| s.critical_mass),
        critical_mass,
        threshold_speed_rpm,
        convergence: c.convergence.clone(),
    }
}

/// The force and moment coefficients block: dimensionless always (at a positive load), SI with
/// dimensions. Generalised coordinates `(X, Y, Γx, Γy)` with `Γ = ψ L/c` and forces
/// `(F̄, M̄/L)` in the solver (`journal::dynamics::TiltCoefficients`), so
/// `K_ij = stiffness_ij · (W_scale/c) · l_i l_j` with `l = (1, 1, L, L)`, `C_ij` the same over ω.
pub(super) fn moment_result(spec: &BearingSpec, a: &Analysis, c: &journal::dynamics::TiltCoefficients) -> MomentCoefficientsResult {
    let d = spec.dimensions();
    let scaled = |m: &[[f64; 4]; 4], s: f64, length: f64| -> Vec<Vec<f64>> {
        let l = [1.0, 1.0, length, length];
        (0..4).map(|i| (0..4).map(|j| m[i][j] * s * l[i] * l[j]).collect()).collect()
    };
    let nondim = c.dimensionless(a.load);
    MomentCoefficientsResult {
        coordinates: ["x", "y", "tilt_x", "tilt_y"].iter().map(|s| s.to_string()).collect(),
        stiffness: d.map(|d| scaled(&c.stiffness, d.load_scale() / d.clearance, d.length)),
        damping: d.map(|d| scaled(&c.damping, d.load_scale() / (d.clearance * d.omega), d.length)),
        stiffness_dimensionless: nondim.map(|(k, _)| scaled(&k, 1.0, 1.0)),
        damping_dimensionless: nondim.map(|(_, cc)| scaled(&cc, 1.0, 1.0)),
        convergence: c.convergence.clone(),
    }
}

/// The operating-limit checks of a result (needs its SI values).
pub(super) fn checks(spec: &BearingSpec, r: &BearingResult, lim: &BearingLimitsSpec) -> Option<BearingChecks> {
    let g = &spec.geometry;
    let (radius, length) = (g.radius?, g.length?);
    let lower = |value: f64, limit: f64| BearingCheck { value, limit, pass: value >= limit, margin: if limit > 0.0 { (value - limit) / limit } else { 0.0 } };
    let upper = |value: f64, limit: f64| BearingCheck { value, limit, pass: value <= limit, margin: (limit - value) / limit };
    let min_film = lower(r.min_film?, lim.journal_roughness + lim.bearing_roughness + lim.film_allowance);
    let specific_load = upper(r.load.force? / (2.0 * radius * length), lim.max_specific_load);
    let max_temperature = r.thermal.as_ref().map(|t| upper(t.max_temperature, lim.max_temperature));
    let pass = min_film.pass && specific_load.pass && max_temperature.is_none_or(|c| c.pass);
    Some(BearingChecks { min_film, specific_load, max_temperature, pass })
}
