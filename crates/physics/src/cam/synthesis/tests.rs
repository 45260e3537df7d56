use super::*;
use proptest::prelude::*;
use std::f64::consts::PI;

fn spec(law: RiseLaw, ramp: Option<Ramp>, top_dwell_deg: f64) -> LiftSpec {
    LiftSpec { lift: 0.01, duration: 240f64.to_radians(), nose: PI, top_dwell: top_dwell_deg.to_radians(), ramp, law }
}

/// Continuity of s, s', s'' (and of s''' where `jerk`) across `theta` by one-sided limits.
fn continuous_at(l: &SynthesisedLift, theta: f64, jerk: bool) -> Result<(), String> {
    // One-sided limits a small fraction of the shortest piece away.
    let pieces = [l.blend_angle, l.rise_angle, l.spec.top_dwell, 1.0];
    let delta = 1e-9 * pieces.iter().copied().filter(|p| *p > 0.0).fold(1.0, f64::min);
    let (a, b) = (l.lift(theta - delta), l.lift(theta + delta));
    let scale = l.spec.lift;
    let tol = |k: i32| 1e-6 * scale / l.rise_angle.powi(k);
    let mut bad = Vec::new();
    if (a.v - b.v).abs() > 1e-9 * scale + 4.0 * delta * a.d1.abs() {
        bad.push(format!("lift {} vs {}", a.v, b.v));
    }
    if (a.d1 - b.d1).abs() > tol(1) {
        bad.push(format!("velocity {} vs {}", a.d1, b.d1));
    }
    if (a.d2 - b.d2).abs() > tol(2) {
        bad.push(format!("acceleration {} vs {}", a.d2, b.d2));
    }
    if jerk && (a.d3 - b.d3).abs() > tol(3) {
        bad.push(format!("jerk {} vs {}", a.d3, b.d3));
    }
    if bad.is_empty() { Ok(()) } else { Err(format!("at {:.4}°: {}", theta.to_degrees(), bad.join(", "))) }
}

/// The junctions of the law: ramp blend end, ramp end, rise end, return start, …, event ends.
fn junctions(l: &SynthesisedLift) -> Vec<f64> {
    let (s, d) = (l.start(), l.spec.duration);
    let half = [0.0, l.blend_angle, l.ramp_angle, l.ramp_angle + l.rise_angle];
    half.iter().flat_map(|&x| [s + x, s + d - x]).collect()
}

#[test]
fn ramp_free_laws_have_the_textbook_peak_coefficients() {
    // Norton / Rothbart: 3-4-5 C_v 15/8, C_a 10/√3, C_j 60; 4-5-6-7 C_v 35/16, C_a 7.513,
    // C_j 52.5; cycloidal 2, 2π, 4π². Over the rise angle β_m = (D − dwell)/2 = 100°.
    let c_a_4567 = {
        let u: f64 = (5.0 - 5f64.sqrt()) / 10.0;
        420.0 * u.powi(2) - 1680.0 * u.powi(3) + 2100.0 * u.powi(4) - 840.0 * u.powi(5)
    };
    for (law, [cv, ca, cj]) in [
        (RiseLaw::Polynomial345, [15.0 / 8.0, 10.0 / 3f64.sqrt(), 60.0]),
        (RiseLaw::Polynomial4567, [35.0 / 16.0, c_a_4567, 52.5]),
        (RiseLaw::Cycloidal, [2.0, 2.0 * PI, 4.0 * PI * PI]),
    ] {
        let l = SynthesisedLift::new(spec(law, None, 40.0)).unwrap();
        let b = l.rise_angle;
        assert!((b - 100f64.to_radians()).abs() < 1e-15);
        let p = l.peaks();
        let h = 0.01;
        assert!((p.max_velocity.value * b / h / cv - 1.0).abs() < 1e-9, "{law:?} C_v {}", p.max_velocity.value * b / h);
        assert!((p.max_acceleration.value * b * b / h / ca - 1.0).abs() < 1e-9, "{law:?} C_a");
        assert!((-p.min_acceleration.value * b * b / h / ca - 1.0).abs() < 1e-9, "{law:?} C_a (deceleration)");
        assert!((p.max_abs_jerk.value * b.powi(3) / h / cj - 1.0).abs() < 1e-9, "{law:?} C_j {}", p.max_abs_jerk.value * b.powi(3) / h);
        // Peak velocity at mid-rise: 50° after the rise starts at 180° − 120° = 60°.
        assert!((p.max_velocity.angle.to_degrees() - 110.0).abs() < 1e-6, "{law:?} at {}", p.max_velocity.angle.to_degrees());
    }
    assert!((c_a_4567 - 7.5132).abs() < 1e-4);
}

#[test]
fn polydyne_peaks_follow_from_its_coefficients() {
    // Ramp-free 2-6-10-14-18 polydyne over β = 120° each side of the nose: the nose
    // acceleration is 2C₂h/β² = −(315/64) h/β², the largest deceleration; the velocity and jerk
    // peaks are computed independently here from the polynomial in x (sampled at 1e5 points).
    let l = SynthesisedLift::new(spec(RiseLaw::Polydyne, None, 0.0)).unwrap();
    let (b, h) = (l.rise_angle, 0.01);
    let nose = l.lift(PI);
    assert!((nose.v - h).abs() < 1e-15 && nose.d1.abs() < 1e-12 && nose.d3.abs() < 1e-9);
    assert!((nose.d2 * b * b / h + 315.0 / 64.0).abs() < 1e-9, "{}", nose.d2 * b * b / h);
    let c = laws::polydyne_coefficients(laws::POLYDYNE_POWERS);
    let (mut cv, mut cj) = (0.0f64, 0.0f64);
    for i in 0..=100_000 {
        let x = i as f64 / 1e5;
        let mut v = 0.0;
        let mut j = 0.0;
        for (ck, &p) in c.iter().zip(laws::POLYDYNE_POWERS.iter()) {
            let n = f64::from(p);
            v += ck * n * x.powi(p - 1);
            if p > 2 {
                j += ck * n * (n - 1.0) * (n - 2.0) * x.powi(p - 3);
            }
        }
        cv = cv.max(v.abs());
        cj = cj.max(j.abs());
    }
    let p = l.peaks();
    assert!((p.max_velocity.value * b / h / cv - 1.0).abs() < 1e-8, "{} vs {cv}", p.max_velocity.value * b / h);
    assert!((p.max_abs_jerk.value * b.powi(3) / h / cj - 1.0).abs() < 1e-6, "{} vs {cj}", p.max_abs_jerk.value * b.powi(3) / h);
    assert!((-p.min_acceleration.value * b * b / h - 315.0 / 64.0).abs() < 1e-9, "the nose has the largest deceleration");
}

#[test]
fn ramps_have_the_requested_height_velocity_and_a_continuous_law() {
    // 0.3 mm ramps at 0.015 mm/° (0.859 mm/rad): each ramp 4H/(3V) = 26.67°.
    let v = 0.015e-3 * 180.0 / PI;
    let ramp = Ramp { height: 3e-4, velocity: v };
    for (law, dwell, jerk) in
        [(RiseLaw::Polydyne, 0.0, true), (RiseLaw::Polynomial4567, 20.0, true), (RiseLaw::Polynomial345, 20.0, false), (RiseLaw::Cycloidal, 0.0, false)]
    {
        let l = SynthesisedLift::new(spec(law, Some(ramp), dwell)).unwrap();
        assert!((l.ramp_angle.to_degrees() - 80.0 / 3.0).abs() < 1e-9);
        let end = l.lift(l.start() + l.ramp_angle);
        assert!((end.v - 3e-4).abs() < 1e-15 && (end.d1 - v).abs() < 1e-15, "{law:?} ramp end {end:?}");
        let mid = l.lift(l.start() + 1.5 * l.blend_angle);
        assert!((mid.d1 - v).abs() < 1e-15 && mid.d2 == 0.0, "constant-velocity ramp");
        assert!((l.lift(PI).v - 0.01).abs() < 1e-15, "{law:?} top");
        assert!(l.lift(l.start() - 1e-3).v == 0.0 && l.lift(l.start() + l.spec.duration + 1e-3).v == 0.0);
        for t in junctions(&l) {
            // 3-4-5 and cycloidal step in jerk where the main rise meets the ramp or dwell.
            continuous_at(&l, t, jerk).unwrap_or_else(|e| panic!("{law:?} {e}"));
        }
        let p = l.peaks();
        assert!(p.max_abs_jerk.value.is_finite() && p.max_velocity.value > v);
        // Derivatives consistent (central differences of the lift).
        let h = 1e-6;
        for k in 1..40 {
            let t = l.start() + l.spec.duration * k as f64 / 40.0 + 1e-3;
            let fd = (l.lift(t + h).v - l.lift(t - h).v) / (2.0 * h);
            assert!((fd - l.lift(t).d1).abs() < 1e-9, "{law:?} at {t}");
        }
    }
}

#[test]
fn impossible_specs_name_the_field() {
    let field = |s: LiftSpec| match SynthesisedLift::new(s) {
        Err(SolveError::InvalidInput { field, .. }) => field,
        other => panic!("expected an error, got {other:?}"),
    };
    assert_eq!(field(spec(RiseLaw::Polydyne, None, 10.0)), "LiftSpec.top_dwell");
    // Ramps of 4·0.003/(3·0.001) rad = 229° each.
    assert_eq!(field(spec(RiseLaw::Polydyne, Some(Ramp { height: 3e-3, velocity: 1e-3 }), 0.0)), "LiftSpec.ramp.velocity");
    assert_eq!(field(spec(RiseLaw::Polydyne, Some(Ramp { height: 0.01, velocity: 1e-2 }), 0.0)), "LiftSpec.ramp.height");
    // A ramp as fast as the mean rise: the rise would run backwards.
    assert_eq!(field(spec(RiseLaw::Polynomial345, Some(Ramp { height: 1e-3, velocity: 0.04 }), 0.0)), "LiftSpec.ramp.velocity");
    let mut s = spec(RiseLaw::Cycloidal, None, 0.0);
    s.duration = 7.0;
    assert_eq!(field(s), "LiftSpec.duration");
}

#[test]
fn limits_report_margins() {
    let l = SynthesisedLift::new(spec(RiseLaw::Polynomial4567, None, 0.0)).unwrap();
    let p = l.peaks();
    let (acc, jerk) = l.check(LawLimits { max_acceleration: Some(2.0 * p.max_acceleration.value), max_jerk: Some(0.5 * p.max_abs_jerk.value) });
    let (acc, jerk) = (acc.unwrap(), jerk.unwrap());
    assert!((acc.margin - 0.5).abs() < 1e-12 && (jerk.margin + 1.0).abs() < 1e-12, "{acc:?} {jerk:?}");
}

#[test]
fn shortest_duration_is_the_closed_form_without_ramps() {
    // 4-5-6-7, h = 10 mm, A = 0.05 m/rad², J = 0.3 m/rad³, dwell 20°:
    // β_a = √(7.5132 h/A), β_j = ∛(52.5 h/J); D = 2 max + dwell.
    let c_a = {
        let u: f64 = (5.0 - 5f64.sqrt()) / 10.0;
        420.0 * u.powi(2) - 1680.0 * u.powi(3) + 2100.0 * u.powi(4) - 840.0 * u.powi(5)
    };
    let s = spec(RiseLaw::Polynomial4567, None, 20.0);
    for (a, j) in [(0.05, 0.3), (0.2, 0.3), (0.05, 1e3)] {
        let limits = LawLimits { max_acceleration: Some(a), max_jerk: Some(j) };
        let (d, conv) = shortest_duration(s, limits, 64, 1e-10, 100).unwrap().unwrap();
        let beta = (c_a * 0.01 / a).sqrt().max((52.5 * 0.01 / j).cbrt());
        let expect = 2.0 * beta + 20f64.to_radians();
        assert!((d - expect).abs() < 1e-8, "A {a} J {j}: {} vs {}", d.to_degrees(), expect.to_degrees());
        assert!(conv.residual <= 1e-10 && conv.iterations < 100);
    }
    // A ramp whose blend alone exceeds the limit: 2.81 V²/H = 0.6 m/rad² > 0.5.
    let ramped = spec(RiseLaw::Polydyne, Some(Ramp { height: 3e-4, velocity: 8e-3 }), 0.0);
    assert_eq!(shortest_duration(ramped, LawLimits { max_acceleration: Some(0.5), max_jerk: None }, 64, 1e-10, 100).unwrap(), None);
    // An iteration cap too small is a typed error.
    let limits = LawLimits { max_acceleration: Some(0.05), max_jerk: None };
    assert!(matches!(shortest_duration(s, limits, 64, 1e-12, 3), Err(SolveError::NotConverged { .. })));
}

#[test]
fn exported_table_reproduces_the_law() {
    let l = SynthesisedLift::new(spec(RiseLaw::Polydyne, Some(Ramp { height: 2e-4, velocity: 8e-4 }), 0.0)).unwrap();
    let (a, s) = l.table(720);
    let spline = crate::cam::PeriodicSpline::new(&a, &s).unwrap();
    for k in 0..997 {
        let t = TAU * k as f64 / 997.0;
        assert!((spline.eval(t).v - l.lift(t).v).abs() < 2e-8, "at {t}");
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(200))]
    /// Any lift, duration, dwell and ramp: a law continuous in lift, velocity and acceleration
    /// with finite jerk reaching the requested lift, or a typed error naming a field.
    #[test]
    fn any_spec_gives_a_continuous_law_or_a_typed_error(
        lift in 1e-4f64..0.03, duration_deg in 20.0f64..360.0, dwell in 0.0f64..0.5, law in 0usize..4,
        ramp in proptest::option::of((0.0f64..0.3, 1e-5f64..0.02)),
    ) {
        let law = [RiseLaw::Polydyne, RiseLaw::Polynomial345, RiseLaw::Polynomial4567, RiseLaw::Cycloidal][law];
        let dwell = if law == RiseLaw::Polydyne { 0.0 } else { dwell * duration_deg };
        let ramp = ramp.map(|(f, v)| Ramp { height: f * lift, velocity: v });
        let s = LiftSpec { lift, duration: duration_deg.to_radians(), nose: 2.0, top_dwell: dwell.to_radians(), ramp, law };
        match SynthesisedLift::new(s) {
            Err(SolveError::InvalidInput { field, .. }) => prop_assert!(field.starts_with("LiftSpec.")),
            Err(e) => prop_assert!(false, "untyped {e:?}"),
            Ok(l) => {
                for t in junctions(&l) {
                    if let Err(e) = continuous_at(&l, t, false) {
                        prop_assert!(false, "{}", e);
                    }
                }
                let top = l.lift(2.0);
                prop_assert!((top.v - lift).abs() < 1e-12 * lift.max(1.0));
                let p = l.peaks();
                prop_assert!(p.max_abs_jerk.value.is_finite() && p.max_velocity.value.is_finite());
                for k in 0..360 {
                    let j = l.lift(TAU * k as f64 / 360.0);
                    prop_assert!(j.is_finite() && j.v >= -1e-15 && j.v <= lift * (1.0 + 1e-12));
                }
            }
        }
    }
}
