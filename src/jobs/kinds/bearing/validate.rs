//! Validation of a bearing spec: one named check per block of the spec, run in the spec's order
//! (the order of the problems in an answer).

use super::*;
use crate::jobs::kind::{Limits, Validation};
use crate::jobs::quantity as Q;

/// A path under the spec's prefix (`/base` for the optimisation's base spec).
type Px<'a> = &'a dyn Fn(&str) -> String;

/// Validate the shared parts of a bearing spec (also used by `bearing_optimisation`'s base).
/// `prefix` is prepended to every path (`/base` for the optimisation's base spec).
pub fn validate_bearing(spec: &BearingSpec, limits: &Limits, v: &mut Validation, needs_load: bool, prefix: &str) {
    let px = |s: &str| format!("{prefix}{s}");
    geometry(spec, v, &px);
    operating(spec, v, &px);
    load(spec, v, needs_load, &px);
    shape(spec, v, &px);
    grid(spec, limits, v, &px);
    solver(spec, v, &px);
    if !prefix.is_empty() {
        v.check(spec.thermal.is_none(), &px("/thermal"), "not available in an optimisation");
        v.check(spec.limits.is_none(), &px("/limits"), "not available in an optimisation");
        v.check(!spec.outputs.contains(&BearingOutput::DynamicCoefficients), &px("/outputs"), "dynamic_coefficients is not available in an optimisation");
        v.check(!spec.outputs.contains(&BearingOutput::MomentCoefficients), &px("/outputs"), "moment_coefficients is not available in an optimisation");
    }
    if let Some(t) = &spec.thermal {
        thermal(spec, t, v, &px);
    }
    if let Some(lim) = &spec.limits {
        operating_limits(spec, lim, v, &px);
    }
    v.count_in_range(&px("/field_stride/circumferential"), spec.field_stride.circumferential, 1, 1000);
    v.count_in_range(&px("/field_stride/axial"), spec.field_stride.axial, 1, 1000);
}

/// L/D or radius and length (consistent when both), positive sizes, the clearance below the radius.
fn geometry(spec: &BearingSpec, v: &mut Validation, px: Px) {
    let g = &spec.geometry;
    match (g.length_to_diameter, g.radius, g.length) {
        (Some(ld), r, l) => {
            v.in_range(&px("/geometry/length_to_diameter"), ld, 0.05, 10.0);
            if let (Some(r), Some(l)) = (r, l) {
                if r > 0.0 && l > 0.0 {
                    v.check(
                        ((l / (2.0 * r)) - ld).abs() <= 1e-9 * ld.abs().max(1.0),
                        &px("/geometry/length_to_diameter"),
                        "disagrees with length/(2·radius); give one or the other",
                    );
                }
            }
        }
        (None, Some(_), Some(_)) => {}
        _ => {
            v.error(&px("/geometry/length_to_diameter"), "is required unless radius and length are given");
        }
    }
    for (path, val) in [(px("/geometry/radius"), g.radius), (px("/geometry/length"), g.length), (px("/geometry/radial_clearance"), g.radial_clearance)] {
        if let Some(x) = val {
            v.positive(&path, x);
        }
    }
    if let (Some(r), Some(l)) = (g.radius, g.length) {
        if r > 0.0 && l > 0.0 {
            v.in_range(&px("/geometry/length"), l / (2.0 * r), 0.05, 10.0);
        }
    }
    if let (Some(r), Some(c)) = (g.radius, g.radial_clearance) {
        v.check(c < r, &px("/geometry/radial_clearance"), "must be smaller than the radius");
    }
}

/// Speed, and a viscosity exactly when there is no heat balance.
fn operating(spec: &BearingSpec, v: &mut Validation, px: Px) {
    if let Some(o) = &spec.operating {
        v.quantity(&px("/operating/speed_rpm"), o.speed_rpm, Q::SPEED_RPM);
        match (o.viscosity, &spec.thermal) {
            (Some(eta), None) => {
                v.quantity(&px("/operating/viscosity"), eta, Q::VISCOSITY);
            }
            (None, None) => {
                v.error(&px("/operating/viscosity"), "is required (or give a thermal block)");
            }
            (Some(_), Some(_)) => {
                v.error(&px("/operating/viscosity"), "leave it out with thermal: the heat balance finds the viscosity");
            }
            (None, Some(_)) => {}
        }
    }
}

/// Exactly one operating point (when `needs_load`), each in its range.
fn load(spec: &BearingSpec, v: &mut Validation, needs_load: bool, px: Px) {
    let l = &spec.load;
    let given = [l.eccentricity_ratio.is_some(), l.aligned_eccentricity_ratio.is_some(), l.force.is_some(), l.sommerfeld_number.is_some()]
        .iter()
        .filter(|b| **b)
        .count();
    if needs_load {
        v.check(
            given == 1,
            &px("/load"),
            "give exactly one of eccentricity_ratio, aligned_eccentricity_ratio, force, sommerfeld_number",
        );
    }
    if let Some(e) = l.eccentricity_ratio {
        v.in_range(&px("/load/eccentricity_ratio"), e, 0.0, 0.999);
    }
    if let Some(a) = l.attitude_angle_deg {
        v.check(a.is_finite(), &px("/load/attitude_angle_deg"), "must be a finite number");
        v.check(l.eccentricity_ratio.is_some(), &px("/load/attitude_angle_deg"), "only with eccentricity_ratio");
    }
    if let Some(e) = l.aligned_eccentricity_ratio {
        v.in_range(&px("/load/aligned_eccentricity_ratio"), e, 1e-4, 0.999);
    }
    if let Some(f) = l.force {
        v.quantity(&px("/load/force"), f, Q::FORCE);
        v.check(spec.has_size_and_speed(), &px("/load/force"), "needs geometry.radius, geometry.length, geometry.radial_clearance and operating");
    }
    if let Some(s) = l.sommerfeld_number {
        v.positive(&px("/load/sommerfeld_number"), s);
    }
}

/// Misalignment and edge profile in their ranges.
fn shape(spec: &BearingSpec, v: &mut Validation, px: Px) {
    if let Some(m) = &spec.misalignment {
        v.in_range(&px("/misalignment/vertical"), m.vertical, -2.0, 2.0);
        v.in_range(&px("/misalignment/horizontal"), m.horizontal, -2.0, 2.0);
    }
    if let Some(p) = &spec.profile {
        v.check((1..=3).contains(&p.order), &px("/profile/order"), "must be 1, 2 or 3");
        v.in_range(&px("/profile/height"), p.height, 0.0, 5.0);
        v.check(
            p.length_fraction.is_finite() && p.length_fraction > 0.0 && p.length_fraction <= 0.5,
            &px("/profile/length_fraction"),
            "must be in (0, 0.5]",
        );
    }
}

/// Grid sizes within the server's limit, and a supply the grid can place.
fn grid(spec: &BearingSpec, limits: &Limits, v: &mut Validation, px: Px) {
    v.count_in_range(&px("/grid/circumferential"), spec.grid.circumferential, 17, 4001);
    v.count_in_range(&px("/grid/axial"), spec.grid.axial, 5, 2001);
    v.limit(&px("/grid"), spec.grid.circumferential.saturating_mul(spec.grid.axial), limits.max_grid_nodes, "circumferential × axial nodes");
    if let SupplySpec::Angle { angle_deg } | SupplySpec::TwoGrooves { angle_deg } = spec.supply {
        v.check(angle_deg.is_finite(), &px("/supply/angle_deg"), "must be a finite number");
    }
    if let SupplySpec::TwoGrooves { .. } = spec.supply {
        v.check(
            spec.grid.circumferential % 2 == 1,
            &px("/grid/circumferential"),
            "must be odd with two grooves (an even number of intervals puts the second groove on a node)",
        );
    }
}

/// Solver tolerances and caps in their ranges.
fn solver(spec: &BearingSpec, v: &mut Validation, px: Px) {
    let s = &spec.solver;
    v.in_range(&px("/solver/pressure_tolerance"), s.pressure_tolerance, 1e-12, 1e-4);
    v.in_range(&px("/solver/load_tolerance"), s.load_tolerance, 1e-10, 1e-2);
    v.count_in_range(&px("/solver/max_load_iterations"), s.max_load_iterations as usize, 1, 200);
    v.count_in_range(&px("/solver/max_cycles"), s.max_cycles as usize, 10, 10_000);
    v.in_range(&px("/solver/min_film"), s.min_film, 1e-6, 0.5);
}

/// The heat balance: dimensions and a dimensional load, temperatures and factors in range.
fn thermal(spec: &BearingSpec, t: &BearingThermalSpec, v: &mut Validation, px: Px) {
    let l = &spec.load;
    v.check(spec.has_size_and_speed(), &px("/thermal"), "needs geometry.radius, geometry.length, geometry.radial_clearance and operating.speed_rpm");
    v.check(
        l.force.is_some() || l.eccentricity_ratio.is_some(),
        &px("/thermal"),
        "needs load.force or load.eccentricity_ratio (a dimensionless load would change the force with the viscosity)",
    );
    v.in_range(&px("/thermal/supply_temperature"), t.supply_temperature, 200.0, 600.0);
    v.in_range(&px("/thermal/carry_over"), t.carry_over, 0.0, 1.0);
    v.in_range(&px("/thermal/tolerance"), t.tolerance, 1e-6, 1.0);
    v.count_in_range(&px("/thermal/max_iterations"), t.max_iterations as usize, 2, 200);
    lubricant(&t.lubricant, v, px);
    if let Some(h) = &t.housing {
        v.in_range(&px("/thermal/housing/heat_transfer"), h.heat_transfer, 0.0, 1e6);
        v.in_range(&px("/thermal/housing/ambient_temperature"), h.ambient_temperature, 200.0, 600.0);
    }
}

/// The heat balance's lubricant: an ISO VG grade or a two-point curve falling with temperature.
fn lubricant(lu: &BearingLubricantSpec, v: &mut Validation, px: Px) {
    v.in_range(&px("/thermal/lubricant/density"), lu.density, 100.0, 3000.0);
    v.in_range(&px("/thermal/lubricant/specific_heat"), lu.specific_heat, 100.0, 10000.0);
    v.check(
        lu.iso_vg.is_some() != lu.viscosity_curve.is_some(),
        &px("/thermal/lubricant"),
        "give exactly one of iso_vg, viscosity_curve",
    );
    if let Some(g) = lu.iso_vg {
        v.check(
            crate::physics::journal::heat::ISO_VG_100C.iter().any(|(x, _)| *x == g),
            &px("/thermal/lubricant/iso_vg"),
            "one of 10, 15, 22, 32, 46, 68, 100, 150, 220, 320, 460, 680, 1000",
        );
    }
    if let Some(n) = lu.viscosity_100c {
        v.check(lu.iso_vg.is_some(), &px("/thermal/lubricant/viscosity_100c"), "only with iso_vg");
        v.in_range(&px("/thermal/lubricant/viscosity_100c"), n, 0.5, (lu.iso_vg.unwrap_or(1000) as f64) * 0.999);
    }
    if let Some(c) = &lu.viscosity_curve {
        v.items(&px("/thermal/lubricant/viscosity_curve"), c.len(), 2, Some(2));
        for (i, pt) in c.iter().enumerate() {
            v.in_range(&px(&format!("/thermal/lubricant/viscosity_curve/{i}/temperature")), pt.temperature, 200.0, 600.0);
            v.in_range(&px(&format!("/thermal/lubricant/viscosity_curve/{i}/viscosity")), pt.viscosity, 1e-5, 100.0);
        }
        if c.len() == 2 {
            let (a, b) = (c[0], c[1]);
            v.check(
                (a.temperature - b.temperature).abs() > 1.0 && (a.temperature - b.temperature) * (a.viscosity - b.viscosity) < 0.0,
                &px("/thermal/lubricant/viscosity_curve"),
                "two temperatures at least 1 K apart, the viscosity falling with temperature",
            );
        }
    }
}

/// Operating limits: dimensions, and each limit in its range.
fn operating_limits(spec: &BearingSpec, lim: &BearingLimitsSpec, v: &mut Validation, px: Px) {
    v.check(spec.has_size_and_speed(), &px("/limits"), "needs geometry.radius, geometry.length, geometry.radial_clearance and operating");
    v.in_range(&px("/limits/journal_roughness"), lim.journal_roughness, 0.0, 1e-3);
    v.in_range(&px("/limits/bearing_roughness"), lim.bearing_roughness, 0.0, 1e-3);
    v.in_range(&px("/limits/film_allowance"), lim.film_allowance, 0.0, 1e-3);
    v.in_range(&px("/limits/max_temperature"), lim.max_temperature, 200.0, 800.0);
    v.positive(&px("/limits/max_specific_load"), lim.max_specific_load);
}
