//! Mechanical lash against closed forms: a stiff rigid train on a cam whose opening and closing
//! ramps have constant velocity `V` (m/rad) meets the cam at `V ω` (the follower rests on the
//! seat until the ramp takes up the clearance) and lands on the seat at `V ω`; the lift loss is
//! the lash plus the contact's deflection under the load at full lift.

use super::model::{damping_from_ratio, HydraulicLashAdjuster, Lash, Link, Seat, SpringChain, ValveTrain};
use super::periodic::{periodic_response, Drive, DynamicsOptions};
use crate::Silent;

const V: f64 = 0.6e-3; // ramp velocity, m/rad
const RAMP: f64 = 0.5; // ramp length, rad (height 0.3 mm)
const BETA: f64 = 1.5; // main rise, rad
const H: f64 = 0.008; // main rise height, m
const START: f64 = 1.0; // ramp start, rad

/// Ramp, cubic Hermite rise from (V, slope V) to (H, slope 0), mirrored return, ramp.
fn lift(theta: f64) -> (f64, f64) {
    lift_with_dwell(theta, 0.0)
}

/// [`lift`] with a top dwell of `dwell` rad.
fn lift_with_dwell(theta: f64, dwell: f64) -> (f64, f64) {
    let half = RAMP + BETA;
    let total = 2.0 * half + dwell;
    let phi = (theta - START).rem_euclid(std::f64::consts::TAU);
    if phi >= total {
        return (0.0, 0.0);
    }
    let (p, sign) = if phi <= half { (phi, 1.0) } else if phi <= half + dwell { (half, 0.0) } else { (total - phi, -1.0) };
    if p <= RAMP {
        return (V * p, sign * V);
    }
    let t = (p - RAMP) / BETA;
    let s = V * RAMP + BETA * V * (t * t * t - 2.0 * t * t + t) + H * (3.0 * t * t - 2.0 * t * t * t);
    let ds = V * (3.0 * t * t - 4.0 * t + 1.0) + H * (6.0 * t - 6.0 * t * t) / BETA;
    (s, sign * ds)
}

fn train(lash: Option<f64>) -> ValveTrain {
    let m = 0.17;
    let kc = 1e9;
    ValveTrain {
        follower_mass: 0.05,
        valve_mass: 0.11,
        train: None,
        spring: SpringChain { rate: 40_000.0, mass: 0.03, elements: 0, damping_ratio: 0.02, groups: Vec::new() },
        inner_spring: None,
        preload: 300.0,
        contact: Link { stiffness: kc, damping: damping_from_ratio(0.2, kc, m) },
        seat: Some(Seat { link: Link { stiffness: 2e8, damping: damping_from_ratio(0.3, 2e8, m) }, gap: 1e-6 }),
        lever: None,
        lash: lash.map(Lash::Mechanical),
    }
}

#[test]
fn ramp_takes_up_the_lash_at_ramp_velocity_times_speed() {
    let omega = 100.0;
    let lash = 0.2e-3;
    let drive = Drive { lift: &lift, omega, max_lift: V * RAMP + H };
    let options = DynamicsOptions { tolerance: 1e-8, ..Default::default() };
    let r = periodic_response(&train(Some(lash)), drive, 3600, &options, &Silent).unwrap();
    let opening = r.opening_impact_velocity.expect("the ramp closes the lash");
    assert!((opening - V * omega).abs() < 1e-3 * V * omega, "opening impact {opening} vs {}", V * omega);
    let seating = r.seating_velocity.expect("the valve seats");
    assert!((seating - V * omega).abs() < 1e-3 * V * omega, "seating {seating} vs {}", V * omega);
    // Lift loss: the lash plus the contact's deflection under its load at full lift.
    let top = r.valve_lift.iter().enumerate().fold((0, f64::MIN), |b, (i, &v)| if v > b.1 { (i, v) } else { b }).0;
    let expected = lash + r.contact_force[top] / 1e9;
    assert!((r.lift_loss - expected).abs() < 2e-8, "lift loss {} vs {expected}", r.lift_loss);
    // On the base circle the seat carries the preload and the contact nothing.
    assert_eq!(r.contact_force[0], 0.0);
    assert!((r.seat_force[0] - 300.0).abs() < 1e-6 * 300.0, "{}", r.seat_force[0]);
    assert!(r.contact_force.iter().chain(&r.valve_lift).all(|v| v.is_finite()));
}

#[test]
fn zero_lash_is_no_lash() {
    let drive = Drive { lift: &lift, omega: 100.0, max_lift: V * RAMP + H };
    let options = DynamicsOptions::default();
    let a = periodic_response(&train(None), drive, 360, &options, &Silent).unwrap();
    let b = periodic_response(&train(Some(0.0)), drive, 360, &options, &Silent).unwrap();
    assert_eq!(a.contact_force, b.contact_force);
    // Without lash the cam carries the preload on the base circle.
    assert!((a.contact_force[0] - 300.0).abs() < 1e-6 * 300.0);
}

/// A direct-acting bucket with a hydraulic lash adjuster (plunger 8 mm, radial clearance 5 µm,
/// leak length 5 mm, oil 10 mPa·s, β 1.5 GPa, chamber 0.2 cm³, supply 0.3 MPa, plunger spring
/// 20 N): on the base circle the cam carries the adjuster's base force `P_h + A p_s` and the seat
/// the rest of the preload; on a top dwell the valve sinks at the leak-down test's velocity
/// `G_L (F − P_h)/A²`, `G_L = π D c³/(12 μ L)`; the check valve refills the chamber on the base
/// circle so that the state repeats.
#[test]
fn hydraulic_adjuster_leaks_down_at_the_closed_form_rate() {
    let hla = HydraulicLashAdjuster {
        plunger_diameter: 8e-3,
        clearance: 5e-6,
        leak_length: 5e-3,
        viscosity: 0.01,
        bulk_modulus: 1.5e9,
        chamber_volume: 2e-7,
        supply_pressure: 3e5,
        spring_preload: 20.0,
        check_conductance: 1e-11,
        damping: damping_from_ratio(0.3, 1.5e9 * (std::f64::consts::PI * 16e-6).powi(2) / 2e-7, 0.11),
    };
    let mut t = train(None);
    t.follower_mass = 0.05;
    t.valve_mass = 0.11;
    t.lash = Some(Lash::Hydraulic(hla));
    let omega = 100.0;
    let dwell = 1.0;
    let lift = move |theta: f64| lift_with_dwell(theta, dwell);
    let drive = Drive { lift: &lift, omega, max_lift: V * RAMP + H };
    let angles = 3600;
    let r = periodic_response(&t, drive, angles, &DynamicsOptions::default(), &Silent).unwrap();
    assert!(r.contact_force.iter().chain(&r.valve_lift).chain(&r.valve_velocity).all(|v| v.is_finite()));
    // Base circle: the cam carries P_h + A p_s (35.08 N), the seat the rest of the 300 N.
    let base = hla.base_force();
    assert!((r.contact_force[0] - base).abs() < 1e-3 * base, "{} vs {base}", r.contact_force[0]);
    assert!((r.seat_force[0] - (300.0 - base)).abs() < 1e-3 * 300.0, "{}", r.seat_force[0]);
    // Mid-dwell: the valve sinks at the leak-down velocity under the contact force.
    let mid = START + RAMP + BETA + dwell / 2.0;
    let k = (mid / std::f64::consts::TAU * angles as f64).round() as usize;
    let expected = -hla.leak_down_velocity(r.contact_force[k]);
    assert!((r.valve_velocity[k] - expected).abs() < 0.01 * expected.abs(), "{} vs {expected}", r.valve_velocity[k]);
    assert!(r.convergence.iterations < 50, "{:?}", r.convergence);
}
