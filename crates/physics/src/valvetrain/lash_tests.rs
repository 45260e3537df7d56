//! Mechanical lash against closed forms: a stiff rigid train on a cam whose opening and closing
//! ramps have constant velocity `V` (m/rad) meets the cam at `V ω` (the follower rests on the
//! seat until the ramp takes up the clearance) and lands on the seat at `V ω`; the lift loss is
//! the lash plus the contact's deflection under the load at full lift.

use super::model::{damping_from_ratio, Link, Seat, SpringChain, ValveTrain};
use super::periodic::{periodic_response, Drive, DynamicsOptions};
use crate::Silent;

const V: f64 = 0.6e-3; // ramp velocity, m/rad
const RAMP: f64 = 0.5; // ramp length, rad (height 0.3 mm)
const BETA: f64 = 1.5; // main rise, rad
const H: f64 = 0.008; // main rise height, m
const START: f64 = 1.0; // ramp start, rad

/// Ramp, cubic Hermite rise from (V, slope V) to (H, slope 0), mirrored return, ramp.
fn lift(theta: f64) -> (f64, f64) {
    let total = 2.0 * (RAMP + BETA);
    let phi = (theta - START).rem_euclid(std::f64::consts::TAU);
    if phi >= total {
        return (0.0, 0.0);
    }
    let (p, sign) = if phi <= total / 2.0 { (phi, 1.0) } else { (total - phi, -1.0) };
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
        spring: SpringChain { rate: 40_000.0, mass: 0.03, elements: 0, damping_ratio: 0.02 },
        preload: 300.0,
        contact: Link { stiffness: kc, damping: damping_from_ratio(0.2, kc, m) },
        seat: Some(Seat { link: Link { stiffness: 2e8, damping: damping_from_ratio(0.3, 2e8, m) }, gap: 1e-6 }),
        lever: None,
        lash,
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
