//! Mechanical lash of a `dynamic` load (issue 45 item 1): the spec section, its validation and
//! the summary figures (physics: `ValveTrain::lash` in `physics::valvetrain::model`); the spec
//! type is in `train_spec.rs`.

use super::spec::DynamicLoadSpec;
use super::train_spec::HydraulicAdjusterSpec;
use crate::jobs::kind::Validation;
use crate::physics::valvetrain::{damping_from_ratio, HydraulicLashAdjuster};

/// Validate `load.lash` and `load.hydraulic_lash_adjuster` (paths under `/load`).
pub fn validate_lash(d: &DynamicLoadSpec, v: &mut Validation) {
    validate_adjuster(d, v);
    let Some(l) = d.lash else { return };
    v.in_range("/load/lash/clearance", l.clearance, 0.0, 0.005);
    v.check(d.seat.is_some(), "/load/seat", "is required with a lash: the seat carries the spring preload while the clearance is open");
    v.warn("/load/lash/clearance", (l.clearance > 1e-3).then(|| format!("a valve lash of {:.3} mm is large (typically 0.1 to 0.5 mm)", l.clearance * 1e3)));
}

fn validate_adjuster(d: &DynamicLoadSpec, v: &mut Validation) {
    let Some(h) = d.hydraulic_lash_adjuster else { return };
    let p = "/load/hydraulic_lash_adjuster";
    v.in_range(&format!("{p}/plunger_diameter"), h.plunger_diameter, 1e-4, 0.1);
    v.in_range(&format!("{p}/clearance"), h.clearance, 1e-8, 1e-3);
    v.in_range(&format!("{p}/leak_length"), h.leak_length, 1e-5, 0.1);
    v.in_range(&format!("{p}/chamber_volume"), h.chamber_volume, 1e-12, 1e-3);
    v.in_range(&format!("{p}/viscosity"), h.viscosity, 1e-5, 10.0);
    v.in_range(&format!("{p}/bulk_modulus"), h.bulk_modulus, 1e6, 1e11);
    v.in_range(&format!("{p}/supply_pressure"), h.supply_pressure, 0.0, 1e8);
    v.in_range(&format!("{p}/plunger_spring"), h.plunger_spring, 0.0, 1e4);
    v.in_range(&format!("{p}/check_conductance"), h.check_conductance, 1e-16, 1e-6);
    v.in_range(&format!("{p}/damping_ratio"), h.damping_ratio, 0.0, 10.0);
    v.warn(
        &format!("{p}/clearance"),
        (!(1e-6..=2e-5).contains(&h.clearance)).then(|| format!("a radial plunger clearance of {:.1} µm is unusual for a lash adjuster (typically 2 to 10 µm)", h.clearance * 1e6)),
    );
    v.check(d.lash.is_none(), "/load/lash", "give either a mechanical lash or a hydraulic_lash_adjuster, not both");
    v.check(d.seat.is_some(), "/load/seat", "is required with a hydraulic lash adjuster: the seat carries the spring preload on the base circle");
    v.check(d.train_stiffness.is_none(), "/load/train_stiffness", "the hydraulic lash adjuster is the follower–valve link: leave train_stiffness out");
    v.check(matches!(d.arrangement, None | Some(super::ArrangementSpec::Direct)), "/load/arrangement", "a hydraulic lash adjuster is modelled in a direct-acting bucket only");
    v.check(d.valve_mass > 0.0, "/load/valve_mass", "must be > 0 (kg) with a hydraulic lash adjuster");
    let base = h.plunger_spring + h.supply_pressure * std::f64::consts::PI * h.plunger_diameter.powi(2) / 4.0;
    v.check(
        d.preload() > base,
        "/load/hydraulic_lash_adjuster/plunger_spring",
        format!("the adjuster's base force (plunger spring + supply pressure × plunger area) {base:.1} N must stay below the valve-spring preload {:.1} N", d.preload()),
    );
}

/// The physics adjuster of a spec (its damping ratio on the valve mass `valve_mass`, kg).
pub fn adjuster(h: &HydraulicAdjusterSpec, valve_mass: f64) -> HydraulicLashAdjuster {
    let mut a = HydraulicLashAdjuster {
        plunger_diameter: h.plunger_diameter,
        clearance: h.clearance,
        leak_length: h.leak_length,
        viscosity: h.viscosity,
        bulk_modulus: h.bulk_modulus,
        chamber_volume: h.chamber_volume,
        supply_pressure: h.supply_pressure,
        spring_preload: h.plunger_spring,
        check_conductance: h.check_conductance,
        damping: 0.0,
    };
    a.damping = damping_from_ratio(h.damping_ratio, a.stiffness(), valve_mass);
    a
}
