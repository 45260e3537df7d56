//! Valve trains through a lever (issue 17 deliverable 1: rocker arm with or without a pushrod,
//! end-pivot finger follower) against closed forms: the rigid train's contact load against the
//! quasi-static load reduced to the cam side, the energy balance without damping, the natural
//! frequency of a rocker on its contact and spring, and the rocker example through the job.

use crate::in_process::{example, run, Failure};
use serde_json::{json, Value};
use std::f64::consts::TAU;
use tribod::physics::cam::{LiftLaw, LiftProgram};
use tribod::physics::valvetrain::{
    damping_from_ratio, periodic_response, transient, Drive, DynamicsOptions, Lever, Link, Pushrod, SpringChain, ValveTrain,
};
use tribod::physics::Silent;

fn program(law: LiftLaw, lift: f64, rise_deg: f64) -> LiftProgram {
    LiftProgram { lift, rise_start: 90f64.to_radians(), rise: rise_deg.to_radians(), top_dwell: 0.0, fall: rise_deg.to_radians(), rise_law: law, return_law: law }
}

/// A lever train with a rigid valve side and a massless spring (Rayleigh's third on the valve).
fn rigid_lever_train(lever: Lever, contact_stiffness: f64, contact_damping: f64) -> ValveTrain {
    ValveTrain {
        lash: None,
        follower_mass: 0.055,
        valve_mass: 0.095,
        train: None,
        spring: SpringChain { rate: 45e3, mass: 0.047, elements: 0, damping_ratio: 0.0, groups: Vec::new() },
        inner_spring: None,
        preload: 350.0,
        contact: Link { stiffness: contact_stiffness, damping: contact_damping },
        seat: None,
        lever: Some(lever),
    }
}

/// Rigid rocker (with and without a stiff pushrod) and finger follower on a stiff contact: the
/// contact load is the quasi-static `r P + r² k s + m_c s̈`, `m_c = m_f + m_p + I/l_c² +
/// r² (m_v + m_s/3)` (the lever reduced to its cam side), within 1e-4 of the largest load; the
/// valve lifts `r s` and the spring at the retainer carries `P + k r s` (its own, valve-side force).
#[test]
fn rigid_lever_trains_give_the_reduced_quasi_static_load() {
    let (h, omega) = (6.5e-3, 2500.0 * TAU / 60.0);
    // The 4-5-6-7 polynomial's jerk is continuous: a cycloid's jerk steps at the ends of the rise
    // ring the pushrod mode (residual vibration ~ m Δjerk/ω_n, a few N here), which is dynamics,
    // not the rigid limit.
    let p = program(LiftLaw::Polynomial4567, h, 75.0);
    let lift = move |th: f64| {
        let j = p.lift(th);
        (j.v, j.d1)
    };
    let kc = 5e10;
    let cases = [
        ("rocker", Lever { cam_arm: 0.030, valve_arm: 0.045, inertia: 3e-5, pushrod: None }),
        (
            "rocker + pushrod",
            Lever { cam_arm: 0.030, valve_arm: 0.045, inertia: 3e-5, pushrod: Some(Pushrod { mass: 0.045, link: Link { stiffness: 1e10, damping: 0.0 } }) },
        ),
        ("finger", Lever { cam_arm: 0.018, valve_arm: 0.036, inertia: 1.2e-5, pushrod: None }),
    ];
    for (name, mut lever) in cases {
        let r = lever.valve_arm / lever.cam_arm;
        let m_c = 0.055 + lever.pushrod.map_or(0.0, |p| p.mass) + lever.inertia / lever.cam_arm.powi(2) + r * r * (0.095 + 0.047 / 3.0);
        if let Some(p) = &mut lever.pushrod {
            // Damp the stiff pushrod's own mode (ζ = 0.3 on the tappet).
            p.link.damping = damping_from_ratio(0.3, p.link.stiffness, 0.055 + 0.5 * p.mass);
        }
        let tappet = if lever.pushrod.is_some() { 0.055 + 0.0225 } else { m_c };
        let train = rigid_lever_train(lever, kc, damping_from_ratio(0.3, kc, tappet));
        let (pc, kcs, mc) = train.quasi_static_equivalent();
        assert!((pc - r * 350.0).abs() < 1e-9 && (kcs - r * r * 45e3).abs() < 1e-6 && (mc / m_c - 1.0).abs() < 1e-12, "{name}");
        let drive = Drive { lift: &lift, omega, max_lift: h };
        // The elements' force errors are about stiffness × tolerance × lift: 1e-9 keeps the stiff
        // contact's and pushrod's within 1e-5 of the load.
        let resp = periodic_response(&train, drive, 720, &DynamicsOptions { tolerance: 1e-9, ..Default::default() }, &Silent).unwrap();
        let (mut worst, mut peak, mut lift_err, mut spring_err): (f64, f64, f64, f64) = (0.0, 0.0, 0.0, 0.0);
        for k in 0..720 {
            let j = p.lift(TAU * k as f64 / 720.0);
            let qs = r * 350.0 + r * r * 45e3 * j.v + m_c * j.d2 * omega * omega;
            worst = worst.max((resp.contact_force[k] - qs).abs());
            peak = peak.max(qs.abs());
            lift_err = lift_err.max((resp.valve_lift[k] - r * j.v).abs());
            spring_err = spring_err.max((resp.spring_force_moving[k] - (350.0 + 45e3 * resp.valve_lift[k])).abs());
        }
        println!(
            "{name}: r = {r}, m_c = {m_c:.4} kg, largest load difference {worst:.4} N of {peak:.1} N; valve lift − r s ≤ {lift_err:.2e} m; \
             spring force error {spring_err:.2e} N ({} revolutions)",
            resp.convergence.iterations
        );
        assert!(worst < 1e-4 * peak, "{name}: {worst} N");
        // The contact and the pushrod deflect by about load/stiffness at the cam, r times that at
        // the valve.
        let compliance = 1.0 / kc + lever.pushrod.map_or(0.0, |p| 1.0 / p.link.stiffness);
        assert!(lift_err < 1.2 * r * peak * compliance, "{name}: {lift_err}");
        assert!(spring_err < 1e-9 * 350.0 * 10.0, "{name}: {spring_err}");
        assert!(resp.separation.is_empty());
        // The closed-form jump speed uses the same reduction.
        let samples = || (0..3600).map(|k| {
            let j = p.lift(TAU * k as f64 / 3600.0);
            (j.v, j.d2)
        });
        let wj = train.rigid_jump_speed(samples()).unwrap();
        let by_hand = samples().filter(|s| s.1 < 0.0).map(|(s, d2)| ((r * 350.0 + r * r * 45e3 * s) / (m_c * -d2)).sqrt()).fold(f64::INFINITY, f64::min);
        assert!((wj / by_hand - 1.0).abs() < 1e-12);
    }
}

/// Without damping the energy of a rocker train with a pushrod, an elastic rocker–valve link
/// and an 8-mass spring changes only by the cam's work, over 10 revolutions.
#[test]
fn rocker_with_pushrod_conserves_energy_without_damping() {
    let (h, omega) = (6.5e-3, 2000.0 * TAU / 60.0);
    let p = program(LiftLaw::Cycloidal, h, 75.0);
    let lift = move |th: f64| {
        let j = p.lift(th);
        (j.v, j.d1)
    };
    let train = ValveTrain {
        lash: None,
        follower_mass: 0.055,
        valve_mass: 0.095,
        train: Some(Link { stiffness: 3e7, damping: 0.0 }),
        spring: SpringChain { rate: 45e3, mass: 0.047, elements: 8, damping_ratio: 0.0, groups: Vec::new() },
        inner_spring: None,
        preload: 350.0,
        contact: Link { stiffness: 3e8, damping: 0.0 },
        seat: None,
        lever: Some(Lever { cam_arm: 0.030, valve_arm: 0.045, inertia: 3e-5, pushrod: Some(Pushrod { mass: 0.045, link: Link { stiffness: 1.8e7, damping: 0.0 } }) }),
    };
    let drive = Drive { lift: &lift, omega, max_lift: h };
    let period = TAU / omega;
    let times: Vec<f64> = (1..=10 * 36).map(|k| period * k as f64 / 36.0).collect();
    let options = DynamicsOptions { tolerance: 1e-8, ..Default::default() };
    let (_, probes, _) = transient(&train, drive, None, 10.0 * period, &times, &options).unwrap();
    let e0 = {
        let (_, p0, _) = transient(&train, drive, None, 1e-12, &[1e-12], &options).unwrap();
        p0[0].energy - p0[0].cam_work
    };
    let emax = probes.iter().map(|p| p.energy).fold(0.0, f64::max);
    let drift = probes.iter().map(|p| (p.energy - p.cam_work - e0).abs()).fold(0.0, f64::max);
    println!("rocker + pushrod, no damping: largest |E − E0 − W| = {drift:.3e} J of E_max {emax:.3e} J");
    assert!(drift < 1e-4 * emax, "{drift}");
    assert!(probes.iter().all(|p| p.contact > 0.0));
}

/// A rigid rocker on its contact spring `k_c` (cam side) and the valve spring `k` (valve side),
/// cam on its base circle, released from a small displacement: it rings at
/// `ω_n = √((k_c + r² k)/(m_f + I/l_c² + r² (m_v + m_s/3)))`; the follower's motion against
/// `x₀ cos ω_n t` over five periods, and the valve's is `r` times it.
#[test]
fn rocker_natural_frequency_matches_the_closed_form() {
    let zero = |_: f64| (0.0, 0.0);
    let (kc, k, r, lc) = (2e8, 45e3, 1.5, 0.030);
    let (mf, mv, ms, inertia) = (0.055, 0.095, 0.047, 3e-5);
    let lever = Lever { cam_arm: lc, valve_arm: r * lc, inertia, pushrod: None };
    let train = ValveTrain {
        lash: None,
        follower_mass: mf,
        valve_mass: mv,
        train: None,
        spring: SpringChain { rate: k, mass: ms, elements: 0, damping_ratio: 0.0, groups: Vec::new() },
        inner_spring: None,
        preload: 350.0,
        contact: Link { stiffness: kc, damping: 0.0 },
        seat: None,
        lever: Some(lever),
    };
    let m = mf + inertia / (lc * lc) + r * r * (mv + ms / 3.0);
    let wn = ((kc + r * r * k) / m).sqrt();
    // Released 1 µm above the static position: the contact (preload r P = 525 N, 2.6 µm of
    // deflection) stays closed.
    let x0 = 1e-6;
    assert_eq!(train.assemble().dofs(), 1);
    let drive = Drive { lift: &zero, omega: 100.0, max_lift: 1e-5 };
    let t_end = 5.0 * TAU / wn;
    let times: Vec<f64> = (1..=500).map(|k| t_end * k as f64 / 500.0).collect();
    let options = DynamicsOptions { tolerance: 1e-10, ..Default::default() };
    let (_, probes, _) = transient(&train, drive, Some(&[x0, 0.0, 0.0][..]), t_end, &times, &options).unwrap();
    let mut worst: f64 = 0.0;
    for (t, p) in times.iter().zip(&probes) {
        let expected = x0 * (wn * t).cos();
        worst = worst.max((p.follower - expected).abs());
        assert!((p.valve_lift - r * p.follower).abs() < 1e-12 * x0);
        assert!(p.contact > 0.0);
    }
    println!("rocker SDOF: f_n = {:.2} Hz, largest deviation from x0 cos(ω_n t) over 5 periods {:.2e} of x0", wn / TAU, worst / x0);
    // A 1e-4 error in ω_n would show as 2π·5·1e-4 = 3e-3 of x0 at the end.
    assert!(worst < 5e-4 * x0, "{}", worst / x0);
}

fn col(out: &Value, name: &str) -> Vec<f64> {
    out["series"][name].as_array().unwrap_or_else(|| panic!("{name}")).iter().map(|v| v.as_f64().unwrap()).collect()
}

/// `examples/rocker_dynamic.json` (an overhead-valve pushrod rocker, ratio 1.5) through the job:
/// the lever figures in the summary; the valve lifts about 1.5 × the cam lift (less the train's
/// deflection); made rigid (stiff pushrod, contact, rigid link, massless spring), the job's
/// contact load is the reduced quasi-static load — the spec's lengths, inertia and masses reach
/// the physics as documented.
#[test]
fn rocker_example_through_the_job() {
    let spec = example("rocker_dynamic");
    let out = run("cam_cycle", &spec).unwrap();
    let r = 0.045 / 0.03;
    assert!((out["summary"]["lever_ratio"].as_f64().unwrap() - r).abs() < 1e-12);
    let coil_mass = out["summary"]["spring_mass"].as_f64().unwrap();
    let coil_rate = out["summary"]["spring_rate"].as_f64().unwrap();
    let m_c = 0.055 + 0.045 + 3e-5 / 0.03f64.powi(2) + r * r * (0.095 + coil_mass / 3.0);
    assert!((out["summary"]["equivalent_mass"].as_f64().unwrap() / m_c - 1.0).abs() < 1e-12);
    assert_eq!(out["summary"]["separation"], json!([]));
    let valve = col(&out, "valve_lift");
    let vmax = valve.iter().copied().fold(f64::NEG_INFINITY, f64::max);
    let load = col(&out, "contact_load");
    println!(
        "rocker example: valve lift {:.3} mm (r h = {:.3} mm), contact load {:.1}…{:.1} N, equivalent mass {m_c:.4} kg, \
         rigid jump speed {:.0} rpm, seating velocity {:.3} m/s, {} revolutions",
        vmax * 1e3,
        r * 6.5,
        load.iter().copied().fold(f64::INFINITY, f64::min),
        load.iter().copied().fold(f64::NEG_INFINITY, f64::max),
        out["summary"]["rigid_jump_speed_rpm"].as_f64().unwrap(),
        out["summary"]["seating_velocity"].as_f64().unwrap(),
        out["dynamics_convergence"]["iterations"]
    );
    assert!((vmax / (r * 6.5e-3) - 1.0).abs() < 0.05, "{vmax}");
    // Base circle (0°): the cam carries r × the preload, the spring's fixed end the preload.
    assert!((load[0] / (r * 350.0) - 1.0).abs() < 0.1, "{}", load[0]);
    assert!((col(&out, "spring_force_fixed_end")[0] / 350.0 - 1.0).abs() < 0.1);

    // Rigid: the job's load against the closed form.
    let mut rigid = spec.clone();
    rigid["outputs"] = json!(["kinematics", "loads"]);
    rigid["cam"]["profile"]["law"] = json!("polynomial_4567");
    rigid["load"]["arrangement"]["pushrod"]["stiffness"] = json!(1e10);
    rigid["load"]["tolerance"] = json!(1e-9);
    rigid["load"]["arrangement"]["pushrod"]["damping_ratio"] = json!(0.3);
    rigid["load"].as_object_mut().unwrap().remove("train_stiffness");
    rigid["load"].as_object_mut().unwrap().remove("seat");
    rigid["load"]["spring"]["elements"] = json!(0);
    rigid["load"]["spring"]["damping_ratio"] = json!(0.0);
    rigid["load"]["contact_stiffness"] = json!(5e10);
    rigid["load"]["contact_damping_ratio"] = json!(0.3);
    let out = run("cam_cycle", &rigid).unwrap();
    let (s, a, w) = (col(&out, "lift"), col(&out, "acceleration"), col(&out, "contact_load"));
    let (mut worst, mut peak): (f64, f64) = (0.0, 0.0);
    for k in 0..s.len() {
        let qs = r * 350.0 + r * r * coil_rate * s[k] + m_c * a[k];
        worst = worst.max((w[k] - qs).abs());
        peak = peak.max(qs);
    }
    println!("rigid rocker through the job: largest difference {worst:.4} N of {peak:.1} N");
    assert!(worst < 1e-4 * peak, "{worst}");
}

/// Bad arrangements are refused naming the field.
#[test]
fn lever_arrangements_are_validated_by_field() {
    let mut spec = example("rocker_dynamic");
    spec["load"]["arrangement"]["inertia"] = json!(-1.0);
    spec["load"]["arrangement"]["pushrod"]["stiffness"] = json!(0.0);
    let fails = |spec: &Value, paths: &[&str]| match run("cam_cycle", spec) {
        Err(Failure::Spec(p)) => {
            let text = format!("{p:?}");
            for path in paths {
                assert!(text.contains(path), "{path}: {text}");
            }
        }
        other => panic!("{other:?}"),
    };
    fails(&spec, &["/load/arrangement/inertia", "/load/arrangement/pushrod/stiffness"]);
    let mut spec = example("rocker_dynamic");
    spec["load"]["arrangement"] = json!({"type": "finger", "cam_arm": 0.04, "valve_arm": 0.03, "inertia": 1e-5});
    fails(&spec, &["/load/arrangement/cam_arm"]);
    // A massless cam side: no follower mass, no inertia.
    spec["load"]["arrangement"] = json!({"type": "finger", "cam_arm": 0.02, "valve_arm": 0.04, "inertia": 0.0});
    spec["load"]["follower_mass"] = json!(0.0);
    fails(&spec, &["/load/arrangement/inertia"]);
    // Unknown fields are rejected.
    let mut spec = example("rocker_dynamic");
    spec["load"]["arrangement"]["ratio"] = json!(1.5);
    assert!(matches!(run("cam_cycle", &spec), Err(Failure::Spec(_))));
    // `direct` is the default: the seed 003 example with it explicit gives the same load.
    let mut spec = example("seed003_dynamic");
    spec["outputs"] = json!(["kinematics", "loads"]);
    spec["angles"] = json!(360);
    let a = run("cam_cycle", &spec).unwrap();
    spec["load"]["arrangement"] = json!({"type": "direct"});
    let b = run("cam_cycle", &spec).unwrap();
    assert_eq!(a["series"]["contact_load"], b["series"]["contact_load"]);
    assert!(a["summary"].get("lever_ratio").is_none());
}

/// A translating roller follower under a dynamic load (seed 003's train with a roller in place of
/// the bucket): the default contact stiffness uses the reduced radius of base circle and roller;
/// made rigid, the job's contact load equals the quasi-static `valve_train` load with the
/// equivalent mass (both projected onto the contact normal by the same pressure angle); with the
/// example's compliances the roller's tribology (slip, films) runs on the dynamic load.
#[test]
fn roller_follower_under_a_dynamic_load() {
    let mut spec = example("seed003_dynamic");
    spec["follower"] = json!({"type": "roller", "radius": 0.0125, "length": 0.012, "pin_radius": 0.005, "clearance": 1e-5, "pin": {"model": "hydrodynamic"}, "roughness_rq": 1e-7});
    spec["angles"] = json!(360);
    let out = run("cam_cycle", &spec).unwrap();
    assert_eq!(out["summary"]["separation"], json!([]));
    let kc = out["summary"]["contact_stiffness"].as_f64().unwrap();
    // Seed 003 eq. 6 at 300 N on the reduced radius 18·12.5/30.5 mm (against 18 mm for the bucket).
    let flat = run("cam_cycle", &example("seed003_dynamic")).unwrap()["summary"]["contact_stiffness"].as_f64().unwrap();
    // Steel on steel (the spec's default materials): E* = E/(2(1 − ν²)).
    let e_star = 210e9 / (2.0 * (1.0 - 0.3f64.powi(2)));
    let expected = |r: f64| tribod::physics::valvetrain::line_contact_stiffness(300.0, 0.012, r, e_star);
    let r_red = 0.018 * 0.0125 / (0.018 + 0.0125);
    println!("roller contact stiffness {kc:.4e} N/m (closed form {:.4e}); flat face {flat:.4e} N/m ({:.4e})", expected(r_red), expected(0.018));
    assert!((flat / expected(0.018) - 1.0).abs() < 1e-9);
    assert!((kc / expected(r_red) - 1.0).abs() < 1e-9);
    let srr = col(&out, "slide_roll_ratio");
    assert_eq!(srr.len(), 360);
    assert!(srr.iter().all(|v| v.is_finite()));
    assert!(col(&out, "film_central").iter().all(|h| *h > 0.0));

    // Rigid: against the quasi-static load with the equivalent mass.
    let mut rigid = spec.clone();
    rigid["outputs"] = json!(["kinematics", "loads"]);
    rigid["cam"]["profile"]["law"] = json!("polynomial_4567");
    rigid["load"]["tolerance"] = json!(1e-9);
    rigid["load"].as_object_mut().unwrap().remove("seat");
    rigid["load"]["spring"]["elements"] = json!(0);
    rigid["load"]["spring"]["damping_ratio"] = json!(0.0);
    rigid["load"]["contact_stiffness"] = json!(5e10);
    rigid["load"]["contact_damping_ratio"] = json!(0.3);
    let dynamic = run("cam_cycle", &rigid).unwrap();
    let mut qs = rigid.clone();
    qs["load"] = json!({
        "type": "valve_train",
        "spring_preload": 300.0,
        "spring_stiffness": dynamic["summary"]["spring_rate"],
        "moving_mass": dynamic["summary"]["equivalent_mass"],
    });
    let quasi = run("cam_cycle", &qs).unwrap();
    let (wd, wq) = (col(&dynamic, "contact_load"), col(&quasi, "contact_load"));
    let peak = wq.iter().copied().fold(0.0, f64::max);
    let worst = wd.iter().zip(&wq).map(|(a, b)| (a - b).abs()).fold(0.0, f64::max);
    println!("rigid roller train through the job: largest difference {worst:.4} N of {peak:.1} N");
    assert!(worst < 1e-4 * peak, "{worst}");
}
