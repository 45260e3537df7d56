//! Stability of the valve-train dynamics (issue 17 item 5): over masses, stiffnesses, damping
//! and cam speeds up to separation and beyond, a transient run of three revolutions ends with
//! finite numbers and an energy no larger than the start's plus the cam's work (damping only
//! dissipates), or a typed error — never a panic, never NaN.

use proptest::prelude::*;
use std::f64::consts::TAU;
use tribod::physics::cam::{LiftLaw, LiftProgram};
use tribod::physics::valvetrain::{damping_from_ratio, transient, Drive, DynamicsOptions, Lever, Link, Pushrod, Seat, SpringChain, ValveTrain};
use tribod::physics::SolveError;

proptest! {
    #![proptest_config(ProptestConfig { cases: 48, ..ProptestConfig::default() })]

    #[test]
    fn transient_runs_stay_finite_with_bounded_energy(
        follower_mass in 0.005f64..0.5,
        valve_mass in 0.0f64..0.5,
        elastic_train in any::<bool>(),
        train_stiffness in 1e6f64..1e9,
        rate in 1e3f64..2e5,
        spring_mass in 0.005f64..0.2,
        elements in 0usize..12,
        surge_damping in 0.0f64..0.3,
        contact_stiffness in 1e6f64..1e10,
        contact_damping in 0.0f64..1.0,
        preload in 1.0f64..2000.0,
        seat in any::<bool>(),
        rpm in 100.0f64..12000.0,
        law_index in 0usize..4,
        lift in 1e-4f64..0.015,
    ) {
        let law = [LiftLaw::Cycloidal, LiftLaw::Polynomial345, LiftLaw::Polynomial4567, LiftLaw::SimpleHarmonic][law_index];
        let p = LiftProgram { lift, rise_start: 1.0, rise: 1.2, top_dwell: 0.2, fall: 1.2, rise_law: law, return_law: law };
        let cam = move |th: f64| { let j = p.lift(th); (j.v, j.d1) };
        let valve_mass = if elastic_train { valve_mass.max(1e-3) } else { valve_mass };
        let m_side = if elastic_train { follower_mass } else { follower_mass + valve_mass };
        let train = ValveTrain {
            lash: None,
            follower_mass,
            valve_mass,
            train: elastic_train.then(|| Link { stiffness: train_stiffness, damping: damping_from_ratio(0.05, train_stiffness, follower_mass.min(valve_mass)) }),
            spring: SpringChain { rate, mass: spring_mass, elements, damping_ratio: surge_damping, groups: Vec::new() },
            inner_spring: None,
            preload,
            contact: Link { stiffness: contact_stiffness, damping: damping_from_ratio(contact_damping, contact_stiffness, m_side) },
            seat: seat.then(|| Seat { link: Link { stiffness: 1e8, damping: damping_from_ratio(0.1, 1e8, valve_mass.max(m_side)) }, gap: 1e-6 }),
            lever: None,
        };
        let omega = rpm * TAU / 60.0;
        let drive = Drive { lift: &cam, omega, max_lift: lift };
        let period = TAU / omega;
        let times: Vec<f64> = (1..=3 * 72).map(|k| period * k as f64 / 72.0).collect();
        let options = DynamicsOptions { max_steps: 200_000, ..Default::default() };
        match transient(&train, drive, None, 3.0 * period, &times, &options) {
            Ok((y, probes, _)) => {
                prop_assert!(y.iter().all(|v| v.is_finite()));
                let e0 = transient(&train, drive, None, 1e-12, &[1e-12], &options).unwrap().1[0].energy;
                for p in &probes {
                    prop_assert!(p.contact.is_finite() && p.contact >= 0.0 && p.valve_lift.is_finite());
                    // Damping only dissipates: E(t) ≤ E(0) + W(t), within the integration error.
                    let slack = 1e-3 * (e0 + p.cam_work.abs() + p.energy) + 1e-9;
                    prop_assert!(p.energy <= e0 + p.cam_work + slack, "E {} > E0 {} + W {}", p.energy, e0, p.cam_work);
                }
            }
            Err(SolveError::NotConverged { .. }) => {}
            Err(e) => prop_assert!(false, "untyped failure {e:?}"),
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 24, ..ProptestConfig::default() })]

    /// The same through a lever (rocker with or without a pushrod, finger): ratios 0.5–3, the
    /// lever's inertia, pushrod mass and stiffness, speeds up to separation and beyond.
    #[test]
    fn lever_trains_stay_finite_with_bounded_energy(
        follower_mass in 0.0f64..0.3,
        valve_mass in 0.01f64..0.3,
        cam_arm in 0.01f64..0.06,
        ratio in 0.5f64..3.0,
        inertia in 1e-6f64..1e-4,
        pushrod in any::<bool>(),
        pushrod_mass in 0.0f64..0.1,
        pushrod_stiffness in 1e6f64..1e9,
        elastic_train in any::<bool>(),
        train_stiffness in 1e6f64..1e9,
        rate in 1e3f64..1e5,
        elements in 0usize..8,
        contact_stiffness in 1e6f64..1e10,
        preload in 10.0f64..1000.0,
        seat in any::<bool>(),
        rpm in 100.0f64..8000.0,
        lift in 1e-3f64..0.012,
    ) {
        let p = LiftProgram { lift, rise_start: 1.0, rise: 1.2, top_dwell: 0.2, fall: 1.2, rise_law: LiftLaw::Cycloidal, return_law: LiftLaw::Cycloidal };
        let cam = move |th: f64| { let j = p.lift(th); (j.v, j.d1) };
        // Every lumped body keeps some mass (the physics refuses a massless one, tested apart).
        let follower_mass = if pushrod { follower_mass.max(0.005) } else { follower_mass };
        let r = ratio;
        let cam_side = follower_mass + inertia / (cam_arm * cam_arm) + r * r * valve_mass;
        let train = ValveTrain {
            lash: None,
            follower_mass,
            valve_mass,
            train: elastic_train.then(|| Link { stiffness: train_stiffness, damping: damping_from_ratio(0.05, train_stiffness, valve_mass) }),
            spring: SpringChain { rate, mass: 0.04, elements, damping_ratio: 0.05, groups: Vec::new() },
            inner_spring: None,
            preload,
            contact: Link { stiffness: contact_stiffness, damping: damping_from_ratio(0.1, contact_stiffness, cam_side) },
            seat: seat.then(|| Seat { link: Link { stiffness: 1e8, damping: damping_from_ratio(0.1, 1e8, valve_mass) }, gap: 1e-6 }),
            lever: Some(Lever {
                cam_arm,
                valve_arm: r * cam_arm,
                inertia,
                pushrod: pushrod.then(|| Pushrod { mass: pushrod_mass, link: Link { stiffness: pushrod_stiffness, damping: damping_from_ratio(0.05, pushrod_stiffness, follower_mass) } }),
            }),
        };
        let omega = rpm * TAU / 60.0;
        let drive = Drive { lift: &cam, omega, max_lift: lift };
        let period = TAU / omega;
        let times: Vec<f64> = (1..=3 * 72).map(|k| period * k as f64 / 72.0).collect();
        let options = DynamicsOptions { max_steps: 200_000, ..Default::default() };
        match transient(&train, drive, None, 3.0 * period, &times, &options) {
            Ok((y, probes, _)) => {
                prop_assert!(y.iter().all(|v| v.is_finite()));
                let e0 = transient(&train, drive, None, 1e-12, &[1e-12], &options).unwrap().1[0].energy;
                for p in &probes {
                    prop_assert!(p.contact.is_finite() && p.contact >= 0.0 && p.valve_lift.is_finite() && p.spring_fixed.is_finite());
                    let slack = 1e-3 * (e0 + p.cam_work.abs() + p.energy) + 1e-9;
                    prop_assert!(p.energy <= e0 + p.cam_work + slack, "E {} > E0 {} + W {}", p.energy, e0, p.cam_work);
                }
            }
            Err(SolveError::NotConverged { .. }) => {}
            Err(e) => prop_assert!(false, "untyped failure {e:?}"),
        }
    }
}
