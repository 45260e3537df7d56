//! Progressive and nested springs in the dynamic model against the hand calculation of
//! `progressive`'s test: driven slowly (quasi-static), the spring force at the retainer follows
//! the variable-pitch spring's force–deflection curve, lumped or as a chain of coil groups, and
//! nested springs add.

use super::chain::{ClosingGroup, SOLID_STIFFNESS_FACTOR};
use super::model::{damping_from_ratio, HelicalSpring, Link, NestedSpring, Seat, SpringChain, ValveTrain};
use super::periodic::{periodic_response, Drive, DynamicsOptions};
use super::progressive::{closing_forces, coil_constant, state_at, CoilGroup};
use crate::Silent;

const H: f64 = 0.008;
const BETA: f64 = 1.5;

/// A cubic Hermite rise of `H` over `BETA` rad and its mirror from θ = 1 rad.
fn lift(theta: f64) -> (f64, f64) {
    let phi = (theta - 1.0).rem_euclid(std::f64::consts::TAU);
    if phi >= 2.0 * BETA {
        return (0.0, 0.0);
    }
    let (p, sign) = if phi <= BETA { (phi, 1.0) } else { (2.0 * BETA - phi, -1.0) };
    let t = p / BETA;
    (H * (3.0 * t * t - 2.0 * t * t * t), sign * H * (6.0 * t - 6.0 * t * t) / BETA)
}

fn coil() -> HelicalSpring {
    HelicalSpring { wire_diameter: 4e-3, mean_diameter: 24e-3, active_coils: 6.0, shear_modulus: 79.3e9, density: 7850.0 }
}

fn groups() -> Vec<CoilGroup> {
    vec![CoilGroup { coils: 2.0, pitch: 5e-3 }, CoilGroup { coils: 4.0, pitch: 7.5e-3 }]
}

/// The chain of the hand-calculated spring (groups listed from the fixed end).
fn chain(elements: usize, progressive: bool) -> SpringChain {
    let c = coil();
    let groups = if progressive {
        groups().iter().map(|g| ClosingGroup { share: g.coils / c.active_coils, closing_force: coil_constant(&c) * (g.pitch - c.wire_diameter) }).collect()
    } else {
        Vec::new()
    };
    SpringChain { rate: c.rate(), mass: c.active_mass(), elements, damping_ratio: 0.02, groups }
}

fn train(spring: SpringChain, preload: f64, inner: Option<NestedSpring>) -> ValveTrain {
    let kc = 1e9;
    ValveTrain {
        follower_mass: 0.05,
        valve_mass: 0.11,
        train: None,
        spring,
        inner_spring: inner,
        preload,
        contact: Link { stiffness: kc, damping: damping_from_ratio(0.2, kc, 0.17) },
        seat: Some(Seat { link: Link { stiffness: 2e8, damping: damping_from_ratio(0.3, 2e8, 0.17) }, gap: 1e-6 }),
        lever: None,
        lash: None,
    }
}

/// Installed 4 mm below free (122.38 N, all coils open); at full lift (δ = 12 mm) the 5 mm coils
/// are closed (at δ = 6 mm, 183.56 N) and F = 183.56 + K/4 × 6 mm = 458.9 N. At 5 rad/s the
/// inertia and damping forces are below 0.05 N.
#[test]
fn slow_cam_follows_the_progressive_curve() {
    let installed = 4e-3;
    let preload = state_at(&coil(), &groups(), installed).force;
    assert!((preload - 122.38).abs() < 0.01);
    let drive = Drive { lift: &lift, omega: 5.0, max_lift: H };
    for elements in [0, 5] {
        let r = periodic_response(&train(chain(elements, true), preload, None), drive, 720, &DynamicsOptions::default(), &Silent).unwrap();
        let mut worst: f64 = 0.0;
        for (f, l) in r.spring_force_moving.iter().zip(&r.valve_lift) {
            let expected = state_at(&coil(), &groups(), installed + l).force;
            worst = worst.max((f - expected).abs());
        }
        // The closed coils' finite stiffness (SOLID_STIFFNESS_FACTOR × open) takes 0.14 N off
        // at full lift; the chain's coils closing one segment after another ring briefly.
        assert!(worst < 0.3, "{elements} elements: worst {worst} N");
        // At the top sample: the open four coils and the closed two in series.
        let i = (0..r.valve_lift.len()).max_by(|&a, &b| r.valve_lift[a].total_cmp(&r.valve_lift[b])).unwrap();
        let beyond = installed + r.valve_lift[i] - 6e-3;
        let solid = 2.0 / 6.0 / (SOLID_STIFFNESS_FACTOR * coil().rate());
        let with_closed = 183.564 + beyond / (4.0 / 6.0 / coil().rate() + solid);
        let f = r.spring_force_moving[i];
        assert!((f - with_closed).abs() < 0.01, "{elements} elements: {f} vs {with_closed}");
        let by_hand = 183.564 + coil_constant(&coil()) / 4.0 * beyond;
        assert!((by_hand - with_closed - 0.137).abs() < 0.002 && (by_hand - 458.9).abs() < 0.05, "{by_hand} {with_closed}");
        assert!((by_hand - 458.9).abs() < 0.05);
        // The closing forces are the groups', lowest first.
        assert!((closing_forces(&coil(), &groups())[0].0 - 183.564).abs() < 1e-2);
    }
}

/// Nested springs: an inner spring of half the outer's rate, each its own chain: slowly driven,
/// the retainer carries the sum `P + (k_o + k_i) s`; the same as one chain of the summed rate.
#[test]
fn nested_springs_add() {
    let outer = chain(4, false);
    let inner = SpringChain { rate: 0.5 * outer.rate, mass: 0.5 * outer.mass, elements: 3, damping_ratio: 0.02, groups: Vec::new() };
    let (p_o, p_i) = (250.0, 100.0);
    let t = train(outer.clone(), p_o + p_i, Some(NestedSpring { spring: inner.clone(), preload: p_i }));
    let drive = Drive { lift: &lift, omega: 5.0, max_lift: H };
    let r = periodic_response(&t, drive, 360, &DynamicsOptions::default(), &Silent).unwrap();
    let k = outer.rate + inner.rate;
    for (f, l) in r.spring_force_moving.iter().zip(&r.valve_lift) {
        assert!((f - (p_o + p_i + k * l)).abs() < 0.1, "{f} vs {}", p_o + p_i + k * l);
    }
    assert_eq!(t.quasi_static_equivalent().1, k);
    // The assembly has both chains' interior nodes (4 + 3) besides follower and valve (rigid
    // train: one body).
    assert_eq!(t.assemble().dofs(), 1 + 4 + 3);
}
