//! A cam cycle's physics output ([`CycleOutput`]) as the `cam_cycle` result's fields: the
//! series (angles in degrees), the events, the profiles and 2-D fields, the film models that ran.

use super::result::*;
use crate::physics::cam::cycle::{CycleEvents, CycleOutput, CycleSeries};
use crate::physics::film::FilmModelId;
use std::collections::BTreeMap;

fn degs(v: &[f64]) -> Vec<f64> {
    v.iter().map(|x| x.to_degrees()).collect()
}

/// The film model when one model ran at every angle (absent when `auto` mixed them).
pub(super) fn single_film_model(s: &CycleSeries) -> Option<FilmModelId> {
    s.film_model.as_ref().and_then(|v| {
        let first = *v.first()?;
        v.iter().all(|m| *m == first).then_some(first)
    })
}

/// How many angles each film model ran at (`summary.fidelity_used`).
pub(super) fn film_model_counts(s: &CycleSeries) -> Option<BTreeMap<String, usize>> {
    s.film_model.as_ref().map(|v| {
        let mut counts = BTreeMap::new();
        for m in v {
            *counts.entry(m.name().to_string()).or_insert(0) += 1;
        }
        counts
    })
}

pub(super) fn events_of(e: &CycleEvents) -> CamEvents {
    CamEvents {
        zero_entrainment_angles_deg: degs(&e.zero_entrainment),
        separation_ranges_deg: e.separation.iter().map(|(a, b)| [a.to_degrees(), b.to_degrees()]).collect(),
        run_up_separation_deg: None,
    }
}

/// The film profiles at the requested angles (output `profiles`).
pub(super) fn profiles_of(out: &CycleOutput) -> Vec<FilmProfileAtAngle> {
    out.profiles
        .iter()
        .map(|(i, p)| FilmProfileAtAngle { angle_deg: out.series.angle[*i].to_degrees(), x: p.x.clone(), pressure: p.pressure.clone(), film: p.film.clone() })
        .collect()
}

/// The 2-D fields at the requested angles as one table, a row per node and angle.
pub(super) fn fields_of(out: &CycleOutput) -> FieldsTable {
    let mut t = FieldsTable { angle_deg: Vec::new(), x: Vec::new(), y: Vec::new(), pressure: Vec::new(), film: Vec::new() };
    for (i, f) in &out.fields {
        let angle = out.series.angle[*i].to_degrees();
        for &y in &f.y {
            for &x in &f.x {
                t.angle_deg.push(angle);
                t.x.push(x);
                t.y.push(y);
            }
        }
        t.pressure.extend_from_slice(&f.pressure);
        t.film.extend_from_slice(&f.film);
    }
    t
}

/// The cycle's series as the result's columns (angles in degrees; the dynamic columns are
/// added by the valve-train response).
pub(super) fn series_of(s: CycleSeries) -> CamSeries {
    let (spike, spike_position) = match &s.pressure_spike {
        Some(v) => (Some(v.iter().map(|x| x.map(|x| x.0)).collect()), Some(v.iter().map(|x| x.map(|x| x.1)).collect())),
        None => (None, None),
    };
    CamSeries {
        angle_deg: degs(&s.angle),
        time: s.time,
        cam_speed: s.cam_speed,
        lift: s.lift,
        velocity: s.velocity,
        acceleration: s.acceleration,
        jerk: s.jerk,
        pressure_angle_deg: degs(&s.pressure_angle),
        cam_curvature: s.cam_curvature,
        reduced_radius: s.reduced_radius,
        contact_offset: s.contact_offset,
        cam_surface_velocity: s.cam_surface_velocity,
        follower_surface_velocity: s.follower_surface_velocity,
        entrainment_velocity: s.entrainment_velocity,
        sliding_velocity: s.sliding_velocity,
        axial_load: s.axial_load,
        contact_load: s.contact_load,
        load_per_length: s.load_per_length,
        effective_length: s.effective_length,
        hertz_max_pressure: s.hertz_max_pressure,
        hertz_half_width: s.hertz_half_width,
        max_shear_stress: s.max_shear_stress,
        max_shear_depth: s.max_shear_depth,
        contact_deflection: s.contact_deflection,
        film_central: s.film_central,
        film_min: s.film_min,
        model: s.film_model,
        exit_film: s.exit_film,
        pressure_spike: spike,
        pressure_spike_position: spike_position,
        edge_pressure_peak: s.edge_pressure_peak.as_ref().map(|v| v.iter().map(|e| e.map(|e| e.0)).collect()),
        edge_pressure_peak_position: s.edge_pressure_peak.as_ref().map(|v| v.iter().map(|e| e.map(|e| e.1)).collect()),
        min_film_axial_position: s.min_film_axial_position,
        newton_steps: s.newton_steps.map(|v| v.into_iter().map(f64::from).collect()),
        lambda: s.lambda,
        asperity_load_fraction: s.asperity_load_fraction,
        friction_force: s.friction_force,
        friction_coefficient: s.friction_coefficient,
        friction_torque: s.friction_torque,
        camshaft_torque: s.camshaft_torque,
        power_loss: s.power_loss,
        roller_speed: s.roller_speed,
        slide_roll_ratio: s.slide_roll_ratio,
        slip_regime: s.slip_regime,
        pin_torque: s.pin_torque,
        flash_temperature: s.flash_temperature,
        film_temperature_max: s.film_temperature_max,
        surface_temperature_cam: s.surface_temperature_cam,
        surface_temperature_follower: s.surface_temperature_follower,
        pin_temperature: s.pin_temperature,
        ..Default::default()
    }
}
