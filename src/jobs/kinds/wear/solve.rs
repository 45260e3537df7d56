use super::*;
use crate::physics::wear::WearEvolution;

pub(super) fn role_name(r: ArcRole) -> &'static str {
    match r {
        ArcRole::Base => "base",
        ArcRole::Nose => "nose",
        ArcRole::Flank { rising: true } => "flank_rising",
        ArcRole::Flank { rising: false } => "flank_falling",
    }
}

pub(super) fn max_at(v: &[f64]) -> (usize, f64) {
    v.iter().copied().enumerate().fold((0, f64::NEG_INFINITY), |b, (i, x)| if x > b.1 { (i, x) } else { b })
}

pub(super) fn min_of(v: &[f64]) -> f64 {
    v.iter().copied().fold(f64::INFINITY, f64::min)
}

pub(super) fn max_of(v: &[f64]) -> f64 {
    v.iter().copied().fold(f64::NEG_INFINITY, f64::max)
}

/// The spec path of a solver input field of a wear run.
pub(super) fn wear_spec_path(field: &str) -> Option<String> {
    match field {
        "IrgashevInput.slip" => Some("/irgashev/slip".into()),
        "WearRun.hours" => Some("/hours".into()),
        _ => cam_spec_path(field),
    }
}

/// An input error about the pair names its field inside the wear spec's `cycle` (the cam cycle's
/// conversion names the pair's fields as a `cam_cycle` spec does).
pub(super) fn in_cycle(e: SolveError) -> SolveError {
    pub(super) const PAIR: [&str; 5] = ["/cam", "/follower", "/load", "/operation", "/lubricant"];
    match e {
        SolveError::InvalidInput { field, message } if PAIR.iter().any(|p| field == *p || field.starts_with(&format!("{p}/"))) => {
            SolveError::InvalidInput { field: format!("/cycle{field}"), message }
        }
        e => e,
    }
}

pub(super) fn solve_archard(spec: &WearSpec, observer: &dyn Observer) -> Result<WearResult, SolveError> {
    let cc = spec.cycle_spec();
    let cycle = cc.cycle_spec()?;
    let needs = cc.needs();
    let model = spec.cycle.film_model(spec.cycle.ehl.to_physics(spec.cycle.line_family()));
    let mut cycle = cycle;
    if spec.cycle.fidelity != Fidelity::Fast {
        // The wear model reads the numerical film's pressure at every angle where it ran.
        cycle.profile_angles = (0..cycle.angles).collect();
    }
    let k_cam = spec.wear_coefficient.map_or(0.0, |c| c.k());
    let k_follower = spec.follower_wear_coefficient.map_or(k_cam, |c| c.k());
    // A flat face is centred on the follower axis, `offset` from the cam centre line.
    let face = match spec.cycle.follower {
        FollowerSpec::FlatFaced { face_radius: Some(radius), offset, .. } => Some(FlatFace { centre: offset, radius }),
        _ => None,
    };
    let run = WearRun {
        cycle,
        needs,
        archard: ArchardParams {
            cam_coefficient: k_cam,
            follower_coefficient: k_follower,
            load_share: match spec.load_share {
                LoadShareSpec::Asperity if spec.cycle.lubricant.is_some() => LoadShare::Asperity,
                _ => LoadShare::Full,
            },
        },
        hours: spec.running_hours(),
        update_hours: spec.update_hours(),
        wear_limit: spec.wear_limit,
        snapshots: spec.snapshots,
        face,
        face_bins: spec.cycle.angles,
        max_updates: spec.max_updates(),
    };
    let ev = evolve(&run, model.as_ref(), observer)?;
    let termination = termination_of(&ev.stop);
    let numerical = spec.cycle.fidelity != Fidelity::Fast;
    let summary = archard_summary(spec, &ev, numerical);
    let film_model = if numerical {
        // The model that ran, when one model ran at every angle of every cycle.
        match ev.film_models.as_slice() {
            [(m, _)] => Some(*m),
            _ => None,
        }
    } else {
        needs.film.then(|| match (&spec.cycle.follower, spec.cycle.film.formula) {
            (FollowerSpec::Spherical { .. }, _) => FilmModelId::HamrockDowson,
            (_, FilmFormula::PanHamrock) => FilmModelId::PanHamrock,
            (_, FilmFormula::DowsonHigginson) => FilmModelId::DowsonHigginson,
            (_, FilmFormula::Seed003) => FilmModelId::Seed003,
        })
        .map(|m| if spec.composite_sigma() > 0.0 { m.mixed() } else { m })
    };
    Ok(WearResult {
        model: WearModel::Archard,
        fidelity_used: spec.cycle.fidelity,
        film_model,
        wear_coefficient: Some(k_cam),
        termination,
        hours: ev.hours,
        cycles: ev.hours * 3600.0 / ev.period,
        updates: ev.updates,
        angles: spec.cycle.angles,
        series: archard_series(&ev, numerical),
        rows: None,
        history: Some(history_rows(&ev)),
        follower_face: ev.face.as_ref().map(|(p, d)| FaceWear { position: p.clone(), wear_depth: d.clone() }),
        snapshots: (spec.snapshots > 0)
            .then(|| ev.snapshots.iter().map(|(h, d)| WearSnapshot { hours: *h, wear_depth: d.clone() }).collect()),
        summary,
        convergence: crate::physics::wear::evolution::convergence(ev.updates),
    })
}

/// How the run ended, as the result reports it.
fn termination_of(stop: &Stop) -> WearTermination {
    match stop {
        Stop::Completed => WearTermination { reason: WearStopReason::Completed, code: None, message: None, at_hours: None },
        Stop::WearLimit => WearTermination { reason: WearStopReason::WearLimit, code: None, message: None, at_hours: None },
        Stop::Failed { code, message, at_hours } => WearTermination {
            reason: match *code {
                crate::physics::PhysicalFailure::CamUndercut => WearStopReason::CamUndercut,
                crate::physics::PhysicalFailure::FollowerSeparation => WearStopReason::FollowerSeparation,
                crate::physics::PhysicalFailure::ContactOffFace => WearStopReason::ContactOffFace,
                crate::physics::PhysicalFailure::UpdateLimit => WearStopReason::UpdateLimit,
                _ => WearStopReason::ProfileFailure,
            },
            code: Some(code.code().to_string()),
            message: Some(message.clone()),
            at_hours: Some(*at_hours),
        },
    }
}

/// The figures of an Archard run: deepest wear and where, worn volumes, lift loss (plain and
/// with the lash adjusted), films and pressures before and after, the time to the wear limit.
fn archard_summary(spec: &WearSpec, ev: &WearEvolution, numerical: bool) -> WearSummary {
    let (imax, dmax) = max_at(&ev.depth);
    let last = ev.history.last().expect("history starts with the unworn state");
    let first = &ev.history[0];
    let mut summary = WearSummary {
        max_wear_depth: dmax,
        max_wear_angle_deg: ev.angle[imax].to_degrees(),
        max_wear_rate: max_of(&ev.rate),
        hours_to_limit: ev.hours_to_limit,
        worn_volume: Some(last.cam_volume),
        follower_worn_volume: Some(last.follower_volume),
        valve_lift_loss: Some(max_of(&ev.initial_lift) - max_of(&ev.final_lift)),
        valve_lift_loss_lash_adjusted: Some({
            // The adjuster takes up the lash on the base circle: the angles of the original's
            // lowest lift.
            let low = min_of(&ev.initial_lift);
            let base: Vec<usize> = (0..ev.angle.len()).filter(|&i| ev.initial_lift[i] <= low + 1e-9).collect();
            let mean = |v: &[f64]| base.iter().map(|&i| v[i]).sum::<f64>() / base.len() as f64;
            (max_of(&ev.initial_lift) - mean(&ev.initial_lift)) - (max_of(&ev.final_lift) - mean(&ev.final_lift))
        }),
        initial_min_film: first.min_film,
        final_min_film: last.min_film,
        initial_max_pressure: Some(first.max_pressure),
        final_max_pressure: Some(last.max_pressure),
        ..Default::default()
    };
    if let (Some(limit), None) = (spec.wear_limit, ev.hours_to_limit) {
        summary.hours_to_limit_extrapolated = crate::physics::wear::evolution::time_to_limit(&ev.depth, &ev.rate, limit).map(|t| ev.hours + crate::physics::units::seconds_to_hours(t));
    }
    if let Some((pos, d)) = &ev.face {
        let (j, m) = max_at(d);
        summary.max_follower_wear_depth = Some(m);
        summary.max_follower_wear_position = Some(pos[j]);
    }
    if let FollowerSpec::Roller { radius, length, .. } = spec.cycle.follower {
        let l = spec.cycle.cam.width.map_or(length, |w| w.min(length));
        summary.roller_wear_depth = Some(last.follower_volume / (2.0 * std::f64::consts::PI * radius * l));
    }
    if numerical {
        summary.fidelity_used = Some(ev.film_models.iter().map(|(m, c)| (m.name().to_string(), *c)).collect());
        summary.initial_max_film_pressure = first.max_film_pressure;
        summary.final_max_film_pressure = last.max_film_pressure;
    }
    summary
}

/// One row per profile update.
fn history_rows(ev: &WearEvolution) -> Vec<WearHistoryRow> {
    ev
        .history
        .iter()
        .map(|h| WearHistoryRow {
            hours: h.hours,
            cycles: h.cycles,
            max_wear_depth: h.max_depth,
            max_wear_angle_deg: h.max_depth_angle.to_degrees(),
            max_wear_rate: h.max_rate,
            worn_volume: h.cam_volume,
            follower_worn_volume: h.follower_volume,
            valve_lift_loss: h.peak_lift_loss,
            min_film: h.min_film,
            max_pressure: h.max_pressure,
            max_film_pressure: h.max_film_pressure,
        })
        .collect()
}

/// The per-angle columns: wear, lift and the worn pair's pressures and films.
fn archard_series(ev: &WearEvolution, numerical: bool) -> WearSeries {
    let (fs, is_series) = (&ev.final_cycle.series, &ev.initial_cycle.series);
    WearSeries {
        angle_deg: ev.angle.iter().map(|x| x.to_degrees()).collect(),
        wear_depth: ev.depth.clone(),
        wear_rate: ev.rate.clone(),
        lift_loss: Some(ev.lift_drop.clone()),
        surface_position: Some(ev.surface_position.clone()),
        initial_lift: Some(ev.initial_lift.clone()),
        final_lift: Some(ev.final_lift.clone()),
        worn_load_share: Some(ev.worn_share.clone()),
        sliding_velocity: Some(fs.sliding_velocity.clone()),
        initial_hertz_pressure: is_series.hertz_max_pressure.clone(),
        final_hertz_pressure: fs.hertz_max_pressure.clone(),
        initial_film_min: is_series.film_min.clone(),
        final_film_min: fs.film_min.clone(),
        film_model: if numerical { fs.film_model.clone() } else { None },
    }
}

/// The seed 004 inputs of a spec (validated), in SI.
pub(super) fn irgashev_input(spec: &WearSpec) -> Result<IrgashevSi, SolveError> {
    let ir = spec.irgashev.as_ref().ok_or_else(|| SolveError::invalid("/irgashev", "is required by model irgashev"))?;
    let ProfileSpec::MultiArc { arcs } = &spec.cycle.cam.profile else {
        return Err(SolveError::invalid("/cycle/cam/profile", "model irgashev needs a multi_arc profile"));
    };
    let FollowerSpec::Spherical { radius, material, .. } = spec.cycle.follower else {
        return Err(SolveError::invalid("/cycle/follower", "model irgashev needs a spherical follower"));
    };
    let Some(LoadSpec::ValveTrain { spring_preload, spring_stiffness, .. }) = spec.cycle.load else {
        return Err(SolveError::invalid("/cycle/load", "model irgashev needs a valve_train load"));
    };
    let es = contact_modulus(spec.cycle.cam.material.elastic(), material.elastic());
    Ok(IrgashevSi {
        arcs: arcs.iter().map(|a| (a.radius, a.angle_deg)).collect(),
        tappet_radius: radius,
        cam: spec.cycle.cam.material.elastic(),
        preload: spring_preload,
        spring_rate: spring_stiffness,
        nose_lift: ir.nose_lift,
        slip: ir.slip.clone(),
        flank_steps: ir.flank_steps,
        elasticity_constant: ir.elasticity_constant,
        yield_strength: ir.yield_strength,
        deformation_coefficient: ir.deformation_coefficient,
        cycles_to_failure: ir.cycles_to_failure,
        speed: crate::physics::units::rpm_to_rev_per_s(spec.cycle.operation.speed_rpm),
        archard: spec.wear_coefficient.map(|c| (c.k(), es)),
        width_reading: ir.width_reading.into(),
    })
}

pub(super) fn solve_irgashev(spec: &WearSpec, observer: &dyn Observer) -> Result<WearResult, SolveError> {
    observer.check()?;
    let input = irgashev_input(spec)?;
    let rows = irgashev::rows(&input.paper_units())?;
    let n = spec.cycle.angles;
    let wear = irgashev::cam_wear(&rows, n, spec.running_hours(), spec.wear_limit);
    let (angle_deg, rate, depth, hours) = (wear.angle_deg, wear.rate, wear.depth, wear.hours);
    let max_rate = max_of(&rate);
    let mut termination = WearTermination { reason: WearStopReason::Completed, code: None, message: None, at_hours: None };
    let mut summary = WearSummary::default();
    if wear.reached_limit {
        summary.hours_to_limit = wear.hours_to_limit;
        termination.reason = WearStopReason::WearLimit;
    } else {
        summary.hours_to_limit_extrapolated = wear.hours_to_limit;
    }
    let (i, d) = max_at(&depth);
    summary.max_wear_depth = d;
    summary.max_wear_angle_deg = angle_deg[i];
    summary.max_wear_rate = max_rate;
    ensure_finite("seed 004 wear", depth.iter().chain(&rate))?;
    let out_rows = rows
        .iter()
        .map(|r| WearRow {
            part: r.part,
            step: r.step,
            role: role_name(r.role).to_string(),
            position_start_deg: r.position_start_deg,
            position_end_deg: r.position_end_deg,
            angle_deg: r.angle_deg,
            radius: r.radius * 1e-3,
            reduced_radius: r.reduced_radius * 1e-3,
            lift: r.lift * 1e-3,
            spring_force: r.spring_force,
            profile_length_as_printed: r.length_as_printed * 1e-3,
            profile_length: r.length * 1e-3,
            contact_width: r.contact_width * 1e-3,
            contact_area: r.contact_area * 1e-6,
            slip: r.slip,
            wear_rate_mm_per_h: r.wear_rate,
            chain_wear_rate_mm_per_h: r.wear_rate_chain,
            hertz_contact_width: r.hertz_width * 1e-3,
            hertz_pressure: r.hertz_pressure * 1e6,
            archard_wear_rate_mm_per_h: r.archard_wear_rate,
        })
        .collect();
    Ok(WearResult {
        model: WearModel::Irgashev,
        fidelity_used: spec.cycle.fidelity,
        film_model: None,
        wear_coefficient: spec.wear_coefficient.map(|c| c.k()),
        termination,
        hours,
        cycles: hours * 3600.0 * spec.omega() / std::f64::consts::TAU,
        updates: 0,
        angles: n,
        series: WearSeries { angle_deg, wear_depth: depth, wear_rate: rate, ..Default::default() },
        rows: Some(out_rows),
        history: None,
        follower_face: None,
        snapshots: None,
        summary,
        convergence: Convergence::closed_form(),
    })
}
