//! The work and memory model of a cam cycle (`jobs::cost`): the angles times the film model's
//! cost per angle, the roller march's passes, and the valve-train dynamics' revolutions.

use super::{CamCycleSpec, DynamicLoadSpec, FollowerSpec, LoadSpec, StartupSpec};
use crate::jobs::cost::{self, Cost};
use crate::jobs::kinds::film_cost::{film_cost, ContactKind};

/// Revolutions the valve-train dynamics typically needs to become periodic (bounded by
/// `load.max_revolutions`).
const DYNAMIC_REVOLUTIONS: f64 = 12.0;

/// The cost of the cycle `spec` (paths relative to it): the cycle's fixed cost, the closed
/// forms at every angle, and the film model's cold solve and its cost per angle at the cycle's
/// step. `per_angle_fast` is the closed forms' cost per angle (a wear run's cycles keep no
/// series and cost less).
pub fn cycle_cost_with(spec: &CamCycleSpec, per_angle_fast: f64) -> Cost {
    let angles = spec.angles as f64;
    let step = 360.0 / angles.max(1.0);
    let needs = spec.needs();
    let contact = match spec.follower {
        FollowerSpec::Spherical { .. } => ContactKind::Point,
        FollowerSpec::Roller { .. } | FollowerSpec::FlatFaced { .. } => ContactKind::Line(spec.line_family()),
    };
    let mut seconds = cost::JOB_OVERHEAD_S + cost::CYCLE_BASE_S + angles * per_angle_fast;
    let mut bytes = cost::CAM_BASE_BYTES + angles * 2_000.0;
    let (mut work_path, mut what) = ("/angles".to_string(), format!("{} angles by the closed forms", spec.angles));
    let (mut memory_path, mut memory_what) = ("/angles".to_string(), format!("{} angles", spec.angles));
    if needs.film {
        let film = film_cost(spec.fidelity, &spec.ehl, contact);
        let numeric = angles * film.numeric_share;
        seconds += film.cold + numeric * (film.angle(step) + film.thermal_share * film.thermal_angle);
        bytes += film.bytes + numeric * film.kept_per_angle;
        if film.numeric_share > 0.0 {
            what = format!("{} angles of {}", spec.angles, film.what);
            memory_path = film.path.into();
            memory_what = format!("{} over {} angles", film.what, spec.angles);
        }
    }
    if let Some(LoadSpec::Dynamic(d)) = &spec.load {
        if needs.loads {
            let dynamics = dynamics_seconds(spec.operation.speed_rpm, spec.operation.startup.as_ref(), d);
            if dynamics > seconds {
                work_path = "/load/max_revolutions".into();
                what = "the valve-train revolutions".into();
            }
            seconds += dynamics;
        }
    }
    Cost::new(seconds, bytes).work_at(work_path, what).memory_at(memory_path, memory_what)
}

/// The cost of a `cam_cycle` job.
pub fn cycle_cost(spec: &CamCycleSpec) -> Cost {
    cycle_cost_with(spec, cost::FAST_ANGLE_S)
}

/// The valve-train dynamics: about 9 ms per revolution at the default tolerance 1e-8 with 8
/// spring elements (release, BENCHMARKS.md "Valve-train dynamics"), growing with the elements and
/// as tolerance^(-1/3) (second-order steps); a run-up's revolutions cost as many periodic ones at
/// the faster end (step ∝ 1/ω). A nested inner spring adds its elements (its own chain).
fn dynamics_seconds(speed_rpm: f64, _startup: Option<&StartupSpec>, d: &DynamicLoadSpec) -> f64 {
    let elements = d.spring.elements + d.inner_spring.as_ref().map_or(0, |s| s.elements);
    let per_rev = 1.2e-2 * (elements as f64 + 2.0) / 10.0 * (1e-8 / d.tolerance.max(1e-12)).powf(1.0 / 3.0).max(1.0);
    let mut seconds = per_rev * DYNAMIC_REVOLUTIONS.min(d.max_revolutions as f64);
    if let Some(r) = &d.run_up {
        let speed = speed_rpm.max(1.0);
        let slow = (r.from_rpm.max(speed) / speed).max(1.0);
        seconds += per_rev * slow * r.revolutions as f64;
    }
    seconds
}
