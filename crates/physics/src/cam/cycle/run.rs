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
    let n = spec.angles;
    observer.progress(0.0, "kinematics");
    let (kin, duration) = cycle_kinematics(spec)?;
    observer.check()?;
    let mut series = CycleSeries::default();
    let mut events = CycleEvents::default();
    let mut convergence = Convergence::closed_form();

    // Follower surface velocity before slip: roller at its rolling speed.
    let rf = roller_radius(spec);
    let rolling_uf = |k: &KinematicState| if rf.is_some() { k.cam_surface_velocity } else { k.follower_surface_base };
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
    if !needs.loads {
        events.zero_entrainment = sign_changes(&series.angle, &series.entrainment_velocity);
        return Ok(CycleOutput { series, events, convergence, duration, profiles: Vec::new(), fields: Vec::new() });
    }

    // Loads and separation.
    let loads: Vec<FollowerLoad> = kin.iter().map(|k| spec.load.at(k)).collect();
    let axial: Vec<f64> = loads.iter().map(|l| l.axial).collect();
    events.min_axial_load = axial.iter().copied().reduce(f64::min);
    events.separation = negative_ranges(&series.angle, &loads.iter().map(|l| l.contact).collect::<Vec<_>>());
    series.axial_load = Some(axial);
    series.contact_load = Some(loads.iter().map(|l| l.contact).collect());
    ensure_finite("follower loads", series.contact_load.as_ref().unwrap())?;
    if !needs.contact {
        events.zero_entrainment = sign_changes(&series.angle, &series.entrainment_velocity);
        return Ok(CycleOutput { series, events, convergence, duration, profiles: Vec::new(), fields: Vec::new() });
    }
    if let Some(&(a, b)) = events.separation.first() {
        let worst = loads.iter().map(|l| l.contact).fold(f64::INFINITY, f64::min);
        return Err(SolveError::physical(
            crate::PhysicalFailure::FollowerSeparation,
            format!(
                "the follower leaves the cam between {:.1}° and {:.1}° ({} range(s); the contact load \
                 falls to {:.1} N): raise the spring preload by at least {:.1} N, stiffen the spring or \
                 lower the speed. Request only `kinematics` and `loads` outputs to see the loads.",
                a.to_degrees(),
                b.to_degrees(),
                events.separation.len(),
                worst,
                -worst.min(0.0) / kin.iter().map(|k| k.axial_cosine).fold(1.0, f64::min).max(1e-9)
            ),
        ));
    }

    // Hertz contact per angle.
    observer.progress(0.1, "contact");
    let es = spec.contact_modulus;
    let unit_line = hertz_line(1.0, 1.0, 1.0);
    let stress = line_stress_maxima(&unit_line, spec.poisson_ratio);
    let (tau_factor, depth_factor) = (stress.max_shear.value / unit_line.max_pressure, stress.max_shear.depth / unit_line.half_width);
    let mut shapes = Vec::with_capacity(n);
    let (mut p0s, mut bs) = (Vec::with_capacity(n), Vec::with_capacity(n));
    let mut wl: Option<Vec<f64>> = None;
    let mut eff: Option<Vec<f64>> = None;
    let mut taus: Option<Vec<f64>> = None;
    let mut depths: Option<Vec<f64>> = None;
    match &spec.follower {
        FollowerKind::Flat { contact_length } | FollowerKind::Roller { contact_length, crown: None, .. } => {
            let (mut w_v, mut t_v, mut d_v) = (Vec::with_capacity(n), Vec::with_capacity(n), Vec::with_capacity(n));
            for (k, l) in kin.iter().zip(&loads) {
                let w = l.contact / contact_length;
                let c = hertz_line(w, k.reduced_radius, es);
                shapes.push(ContactShape::Line { reduced_radius: k.reduced_radius, length: *contact_length });
                p0s.push(c.max_pressure);
                bs.push(c.half_width);
                w_v.push(w);
                t_v.push(tau_factor * c.max_pressure);
                d_v.push(depth_factor * c.half_width);
            }
            (wl, taus, depths) = (Some(w_v), Some(t_v), Some(d_v));
        }
        FollowerKind::Roller { crown: Some(crown), .. } => {
            let (mut w_v, mut e_v, mut t_v, mut d_v) = (Vec::new(), Vec::new(), Vec::new(), Vec::new());
            // Consecutive angles with the same load and radius (the base circle) reuse the
            // distribution: the same inputs give the same result.
            let mut last: Option<((f64, f64), (crate::geometry::CrownedContact, crate::contact::LineContact))> = None;
            let mut hint = [f64::NAN; 3];
            for (k, l) in kin.iter().zip(&loads) {
                let key = (l.contact, k.reduced_radius);
                let (cc, c) = match last {
                    Some((lk, v)) if lk == key => v,
                    _ => {
                        let cc = crown.distribute_warm(l.contact, k.reduced_radius, es, &mut hint);
                        let v = (cc, hertz_line(cc.peak_load_per_length, k.reduced_radius, es));
                        last = Some((key, v));
                        v
                    }
                };
                shapes.push(ContactShape::Line { reduced_radius: k.reduced_radius, length: cc.equivalent_length });
                p0s.push(c.max_pressure);
                bs.push(c.half_width);
                w_v.push(cc.peak_load_per_length);
                e_v.push(cc.effective_length);
                t_v.push(tau_factor * c.max_pressure);
                d_v.push(depth_factor * c.half_width);
            }
            (wl, eff, taus, depths) = (Some(w_v), Some(e_v), Some(t_v), Some(d_v));
        }
        FollowerKind::Spherical { face_radius } => {
            for (k, l) in kin.iter().zip(&loads) {
                let c = hertz_point(l.contact, k.reduced_radius, *face_radius, es)?;
                let ax = if k.reduced_radius <= *face_radius { c.semi_minor } else { c.semi_major };
                shapes.push(ContactShape::Point { rx: k.reduced_radius, ry: *face_radius });
                p0s.push(c.max_pressure);
                bs.push(ax);
            }
        }
    }
    ensure_finite("hertz contact", p0s.iter().chain(&bs))?;
    series.hertz_max_pressure = Some(p0s);
    series.hertz_half_width = Some(bs);
    series.load_per_length = wl;
    series.effective_length = eff;
    series.max_shear_stress = taus;
    series.max_shear_depth = depths;
    if !needs.film {
        events.zero_entrainment = sign_changes(&series.angle, &series.entrainment_velocity);
        return Ok(CycleOutput { series, events, convergence, duration, profiles: Vec::new(), fields: Vec::new() });
    }

    // Film, traction, slip.
    observer.progress(0.2, "film");
    let ctx = Context { spec, kin: &kin, loads: &loads, shapes: &shapes, model, observer };
    let states = match (&spec.follower, spec.slip, needs.slip) {
        (FollowerKind::Roller { roller, .. }, SlipMode::TorqueBalance { tolerance, max_cycles }, true) => {
            let (states, conv) = ctx.march_roller(roller, tolerance, max_cycles, observer)?;
            convergence = conv;
            states
        }
        _ => ctx.march_fixed(needs.friction, observer)?,
    };

    let mut film_c = Vec::with_capacity(n);
    let mut film_m = Vec::with_capacity(n);
    let mut lam = Vec::with_capacity(n);
    let mut asp = Vec::with_capacity(n);
    for (s, l) in states.iter().zip(&loads) {
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
    if states.iter().any(|s| s.film.thermal.is_some()) {
        let pick = |f: fn(&crate::ehl::thermal::ThermalSummary) -> f64| -> Vec<f64> {
            // A closed form (a contact at rest without history) is isothermal at the inlet.
            states.iter().map(|s| s.film.thermal.as_deref().map_or(spec.temperature, |t| f(&t.summary))).collect()
        };
        series.film_temperature_max = Some(pick(|t| t.film_temperature_max));
        series.surface_temperature_cam = Some(pick(|t| t.surface_temperature_max_1));
        series.surface_temperature_follower = Some(pick(|t| t.surface_temperature_max_2));
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
    if let Some(rf) = rf {
        if needs.slip {
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
    }
    if needs.friction {
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
            if needs.temperature {
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
        if needs.temperature {
            series.flash_temperature = Some(flash);
        }
    }
    // The 2-D fields at the requested angles (only what is asked for: the model keeps no fields).
    let mut fields = Vec::new();
    for &i in &spec.profile_angles {
        if let Some(s) = states.get(i).filter(|s| s.film.finite.is_some()) {
            let input = ctx.input(i, series.entrainment_velocity[i], series.sliding_velocity[i], kin[i].speed.time, 0.0);
            if let Some(f) = model.fields(&s.film, &input)? {
                ensure_finite("2-D fields", f.pressure.iter().chain(&f.film))?;
                fields.push((i, f));
            }
        }
    }
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
