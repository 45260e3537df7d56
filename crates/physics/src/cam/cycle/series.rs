//! Assembling the cycle's output series from the marched contact states: film, roller slip,
//! friction and flash temperature, and the requested film profiles and 2-D fields.

use super::*;

/// The film series; returns the film profiles at the requested angles.
pub(super) fn film_series(spec: &CycleSpec, states: &[PointState], loads: &[FollowerLoad], series: &mut CycleSeries) -> Vec<(usize, FilmProfile)> {
    let n = states.len();
    let mut film_c = Vec::with_capacity(n);
    let mut film_m = Vec::with_capacity(n);
    let mut lam = Vec::with_capacity(n);
    let mut asp = Vec::with_capacity(n);
    for (s, l) in states.iter().zip(loads) {
        film_c.push(s.film.central_film);
        film_m.push(s.film.min_film);
        lam.push(s.film.lambda.unwrap_or(f64::NAN));
        asp.push(s.film.asperity.load / l.contact);
    }
    series.film_central = Some(film_c);
    series.film_min = Some(film_m);
    series.film_model = Some(states.iter().map(|s| s.film.model).collect());
    series.exit_film = Some(states.iter().map(|s| s.film.exit_film.unwrap_or(s.film.min_film)).collect());
    if states.iter().any(|s| s.film.pressure_spike.is_some()) {
        series.pressure_spike = Some(
            states.iter().map(|s| s.film.pressure_spike.zip(s.film.pressure_spike_position)).collect(),
        );
    }
    if states.iter().any(|s| s.film.finite.is_some()) {
        let edge: Vec<Option<(f64, f64)>> = states.iter().map(|s| s.film.finite.as_ref().and_then(|f| f.edge_pressure_peak)).collect();
        series.edge_pressure_peak = edge.iter().any(Option::is_some).then_some(edge);
        series.min_film_axial_position = Some(states.iter().map(|s| s.film.finite.as_ref().map(|f| f.min_film_position.1)).collect());
    }
    let finite_temperatures = |s: &PointState| s.film.finite.as_deref().and_then(|f| f.temperatures);
    if states.iter().any(|s| s.film.thermal.is_some() || finite_temperatures(s).is_some()) {
        // (film max, cam surface max, follower surface max) of the 1-D or 2-D thermal model; a
        // closed form (a contact at rest without history) or an isothermal film is at the inlet.
        let temperatures = |s: &PointState| -> [f64; 3] {
            if let Some(t) = s.film.thermal.as_deref() {
                let t = &t.summary;
                [t.film_temperature_max, t.surface_temperature_max_1, t.surface_temperature_max_2]
            } else if let Some(t) = finite_temperatures(s) {
                [t.film_max, t.surface_max_1, t.surface_max_2]
            } else {
                [spec.temperature; 3]
            }
        };
        let pick = |k: usize| -> Vec<f64> { states.iter().map(|s| temperatures(s)[k]).collect() };
        series.film_temperature_max = Some(pick(0));
        series.surface_temperature_cam = Some(pick(1));
        series.surface_temperature_follower = Some(pick(2));
    }
    if states.iter().any(|s| s.film.iterations.is_some()) {
        series.newton_steps = Some(states.iter().map(|s| s.film.iterations.unwrap_or(0)).collect());
    }
    let profiles: Vec<(usize, FilmProfile)> = spec
        .profile_angles
        .iter()
        .filter_map(|&i| states.get(i).and_then(|s| s.film.profile.as_deref().cloned()).map(|p| (i, p)))
        .collect();
    if spec.roughness.sigma > 0.0 {
        series.lambda = Some(lam);
        series.asperity_load_fraction = Some(asp);
    }
    profiles
}

/// The roller's slip series (roller of radius `rf`); the follower's surface, entrainment and
/// sliding velocities become those of the roller's solved speed.
pub(super) fn slip_series(spec: &CycleSpec, kin: &[KinematicState], states: &[PointState], rf: f64, series: &mut CycleSeries) {
    let n = states.len();
    let mut speed = Vec::with_capacity(n);
    let mut srr = Vec::with_capacity(n);
    let mut pins = Vec::with_capacity(n);
    let mut regime = Vec::with_capacity(n);
    for (i, s) in states.iter().enumerate() {
        let k = &kin[i];
        let uf = rf * s.omega + k.follower_surface_base;
        series.follower_surface_velocity[i] = uf;
        series.entrainment_velocity[i] = k.entrainment(uf);
        series.sliding_velocity[i] = k.cam_surface_velocity - uf;
        speed.push(s.omega);
        srr.push(slide_roll_ratio(k.cam_surface_velocity, uf));
        pins.push(s.pin_torque);
        regime.push(spec.asperity_friction.regime(&s.film.asperity, &s.film.asperity_nodes, series.sliding_velocity[i], series.entrainment_velocity[i]));
    }
    series.roller_speed = Some(speed);
    series.slide_roll_ratio = Some(srr);
    series.slip_regime = Some(regime);
    series.pin_torque = Some(pins);
    if states.iter().any(|s| s.pin_temperature.is_some()) {
        series.pin_temperature = Some(states.iter().map(|s| s.pin_temperature.unwrap_or(spec.temperature)).collect());
    }
}

/// The friction series (force, coefficient, torques, power loss) and, with `temperature`, the
/// flash temperature.
pub(super) fn friction_series(
    spec: &CycleSpec,
    kin: &[KinematicState],
    loads: &[FollowerLoad],
    states: &[PointState],
    temperature: bool,
    series: &mut CycleSeries,
) {
    let n = states.len();
    let mut force = Vec::with_capacity(n);
    let mut coef = Vec::with_capacity(n);
    let mut torque = Vec::with_capacity(n);
    let mut shaft = Vec::with_capacity(n);
    let mut power = Vec::with_capacity(n);
    let mut flash = Vec::with_capacity(n);
    for (i, s) in states.iter().enumerate() {
        let k = &kin[i];
        let f_t = s.traction.force;
        let us = series.sliding_velocity[i];
        force.push(f_t);
        coef.push(f_t / loads[i].contact);
        let tf = f_t * k.friction_arm;
        torque.push(tf);
        shaft.push(loads[i].contact * k.normal_arm + tf);
        let contact_loss = (f_t * us).abs();
        let pin_loss = (s.pin_torque * s.omega).abs();
        power.push(contact_loss + pin_loss);
        if temperature {
            let b = series.hertz_half_width.as_ref().unwrap()[i];
            flash.push(flash_temperature(
                contact_loss,
                b,
                s.film.contact_area,
                k.cam_surface_velocity,
                series.follower_surface_velocity[i],
                &spec.cam_thermal,
                &spec.follower_thermal,
            ));
        }
    }
    series.friction_force = Some(force);
    series.friction_coefficient = Some(coef);
    series.friction_torque = Some(torque);
    series.camshaft_torque = Some(shaft);
    series.power_loss = Some(power);
    if temperature {
        series.flash_temperature = Some(flash);
    }
}

/// The 2-D fields at the requested angles (only what is asked for: the model keeps no fields).
pub(super) fn requested_fields(ctx: &Context, states: &[PointState], series: &CycleSeries) -> Result<Vec<(usize, Fields2d)>, SolveError> {
    let mut fields = Vec::new();
    for &i in &ctx.spec.profile_angles {
        if let Some(s) = states.get(i).filter(|s| s.film.finite.is_some()) {
            let input = ctx.input(i, series.entrainment_velocity[i], series.sliding_velocity[i], ctx.kin[i].speed.time, 0.0);
            if let Some(f) = ctx.model.fields(&s.film, &input)? {
                ensure_finite("2-D fields", f.pressure.iter().chain(&f.film))?;
                fields.push((i, f));
            }
        }
    }
    Ok(fields)
}
