use super::*;

/// Kinematics of every angle (no contact): cheap, always computed.
pub fn cycle_kinematics(spec: &CycleSpec) -> Result<(Vec<KinematicState>, f64), SolveError> {
    let n = spec.angles;
    let mut out = Vec::with_capacity(n);
    for k in 0..n {
        let theta = TAU * k as f64 / n as f64;
        out.push(kinematics(&spec.profile, &spec.geometry, theta, spec.schedule.at(theta))?);
    }
    let duration = spec.schedule.at(TAU).time;
    Ok((out, duration))
}

pub(super) fn roller_radius(spec: &CycleSpec) -> Option<f64> {
    match &spec.follower {
        FollowerKind::Roller { roller, .. } => Some(roller.radius),
        _ => None,
    }
}

/// Run the cycle computing `needs` (closed over dependencies) with film model `model`.
pub fn run_cycle(spec: &CycleSpec, needs: Needs, model: &dyn FilmModel, observer: &dyn Observer) -> Result<CycleOutput, SolveError> {
    let is_roller = matches!(spec.follower, FollowerKind::Roller { .. });
    let needs = needs.closed(is_roller);
    observer.progress(0.0, "kinematics");
    let (kin, duration) = cycle_kinematics(spec)?;
    observer.check()?;
    let mut events = CycleEvents::default();
    let rf = roller_radius(spec);
    let mut series = kinematic_series(&kin, rf.is_some());
    if !needs.loads {
        return Ok(output_without_film(series, events, duration));
    }

    // Loads and separation.
    let loads = cycle_loads(spec, &kin, &mut series, &mut events)?;
    if !needs.contact {
        return Ok(output_without_film(series, events, duration));
    }
    if let Some(&(a, b)) = events.separation.first() {
        return Err(separation_error(&spec.load, &kin, &loads, (a, b), events.separation.len()));
    }

    // Hertz contact per angle.
    observer.progress(0.1, "contact");
    let shapes = hertz_contact(spec, &kin, &loads, &mut series)?;
    if !needs.film {
        return Ok(output_without_film(series, events, duration));
    }

    // Film, traction, slip.
    observer.progress(0.2, "film");
    let ctx = Context { spec, kin: &kin, loads: &loads, shapes: &shapes, model, observer };
    let (states, convergence) = match (&spec.follower, spec.slip, needs.slip) {
        (FollowerKind::Roller { roller, .. }, SlipMode::TorqueBalance { tolerance, max_cycles }, true) => {
            ctx.march_roller(roller, tolerance, max_cycles, observer)?
        }
        _ => (ctx.march_fixed(needs.friction, observer)?, Convergence::closed_form()),
    };

    let profiles = film_series(spec, &states, &loads, &mut series);
    if let Some(rf) = rf
        && needs.slip
    {
        slip_series(spec, &kin, &states, rf, &mut series);
    }
    if needs.friction {
        friction_series(spec, &kin, &loads, &states, needs.temperature, &mut series);
    }
    let fields = requested_fields(&ctx, &states, &series)?;
    events.zero_entrainment = sign_changes(&series.angle, &series.entrainment_velocity);
    for v in [
        &series.film_central, &series.film_min, &series.friction_force, &series.power_loss,
        &series.roller_speed, &series.slide_roll_ratio, &series.flash_temperature,
    ]
    .into_iter()
    .flatten()
    {
        ensure_finite("cam cycle series", v)?;
    }
    observer.progress(1.0, "done");
    Ok(CycleOutput { series, events, convergence, duration, profiles, fields })
}

/// The output of a run that stops before the film: the series so far and where the entrainment
/// changes sign.
fn output_without_film(series: CycleSeries, mut events: CycleEvents, duration: f64) -> CycleOutput {
    events.zero_entrainment = sign_changes(&series.angle, &series.entrainment_velocity);
    CycleOutput { series, events, convergence: Convergence::closed_form(), duration, profiles: Vec::new(), fields: Vec::new() }
}

/// The kinematic series; the follower's surface velocity before slip (a roller at its rolling
/// speed when `roller`).
fn kinematic_series(kin: &[KinematicState], roller: bool) -> CycleSeries {
    let mut series = CycleSeries::default();
    // Follower surface velocity before slip: roller at its rolling speed.
    let rolling_uf = |k: &KinematicState| if roller { k.cam_surface_velocity } else { k.follower_surface_base };
    // One exactly sized column at a time (no growth copies).
    let column = |f: &dyn Fn(&KinematicState) -> f64| -> Vec<f64> { kin.iter().map(f).collect() };
    series.angle = column(&|k| k.theta);
    series.time = column(&|k| k.speed.time);
    series.cam_speed = column(&|k| k.speed.omega);
    series.lift = column(&|k| k.lift.v);
    series.velocity = column(&|k| k.velocity);
    series.acceleration = column(&|k| k.acceleration);
    series.jerk = column(&|k| k.jerk);
    series.pressure_angle = column(&|k| k.pressure_angle);
    series.cam_curvature = column(&|k| k.cam_curvature);
    series.reduced_radius = column(&|k| k.reduced_radius);
    series.contact_offset = column(&|k| k.contact_offset);
    series.cam_surface_velocity = column(&|k| k.cam_surface_velocity);
    series.follower_surface_velocity = column(&|k| rolling_uf(k));
    series.entrainment_velocity = column(&|k| k.entrainment(rolling_uf(k)));
    series.sliding_velocity = column(&|k| k.cam_surface_velocity - rolling_uf(k));
    series
}

/// The follower loads at every angle, their series, the smallest axial load and the
/// separation ranges.
fn cycle_loads(spec: &CycleSpec, kin: &[KinematicState], series: &mut CycleSeries, events: &mut CycleEvents) -> Result<Vec<FollowerLoad>, SolveError> {
    let loads: Vec<FollowerLoad> = kin.iter().map(|k| spec.load.at(k)).collect();
    let axial: Vec<f64> = loads.iter().map(|l| l.axial).collect();
    events.min_axial_load = axial.iter().copied().reduce(f64::min);
    events.separation = negative_ranges(&series.angle, &loads.iter().map(|l| l.contact).collect::<Vec<_>>());
    series.axial_load = Some(axial);
    series.contact_load = Some(loads.iter().map(|l| l.contact).collect());
    ensure_finite("follower loads", series.contact_load.as_ref().unwrap())?;
    Ok(loads)
}

/// The follower leaves the cam between `a` and `b` (the first of `ranges` ranges): what to do.
///
/// With a kinematic valve-train load the missing force is the deficit of the contact load
/// (preload + k·y + m·ÿ, Norton, "Cam Design and Manufacturing Handbook", the follower-jump
/// condition of the spring–mass follower), so the message gives the preload increase that
/// closes it. With the dynamic load (the train's periodic response) the contact force is
/// zero while the follower is off the cam: no preload figure follows from it, and the message
/// says that the train's dynamics (jump or bounce), not the static spring force, lift it off.
fn separation_error(load: &LoadModel, kin: &[KinematicState], loads: &[FollowerLoad], (a, b): (f64, f64), ranges: usize) -> SolveError {
    let worst = loads.iter().map(|l| l.contact).fold(f64::INFINITY, f64::min);
    let at = format!("the follower leaves the cam between {:.1}° and {:.1}° ({} range(s)", a.to_degrees(), b.to_degrees(), ranges);
    let what = match load {
        LoadModel::Dynamic { .. } => format!(
            "{at}; the dynamic contact force is zero there): the valve train's dynamic response (follower \
             jump or valve bounce of the elastic train), not a shortfall of the static spring force, lifts it \
             off, so no preload increase follows from the loads. Stiffen the spring or raise its preload, \
             lighten the moving parts, stiffen the train or lower the speed; request only `kinematics`, \
             `loads` and `dynamics` outputs to see the response."
        ),
        _ => {
            let cosine = kin.iter().map(|k| k.axial_cosine).fold(1.0, f64::min).max(1e-9);
            let needed = -worst.min(0.0) / cosine;
            let force = if needed >= 0.05 { format!("{needed:.1} N") } else { format!("{needed:.2e} N") };
            let verb = if needed > 0.0 { "at least" } else { "more than" };
            format!(
                "{at}; the contact load falls to {:.1} N): raise the spring preload by {verb} {force}, \
                 stiffen the spring or lower the speed. Request only `kinematics` and `loads` outputs to \
                 see the loads.",
                worst + 0.0
            )
        }
    };
    SolveError::physical(crate::PhysicalFailure::FollowerSeparation, what)
}
