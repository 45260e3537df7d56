//! The `synthesised` cam profile (issue 45 item 3): the contract through the real server
//! (`summary.max_lift` equals the requested lift to 0.1 %, the jerk is finite), the textbook
//! peak coefficients through the kind, the export as a `table` profile, agreement with the
//! `rise_return` profile it generalises, the contour of a roller, and refusals naming the field.

use crate::common::*;
use crate::in_process::{example, run, Failure};
use serde_json::{json, Value};
use std::time::Duration;
use tribod::physics::SolveError;

on_both_backends!(synthesised_profile_meets_the_contract_over_http);

fn numbers(v: &Value) -> Vec<f64> {
    v.as_array().unwrap().iter().map(|x| x.as_f64().unwrap()).collect()
}

async fn synthesised_profile_meets_the_contract_over_http() {
    let s = start().await;
    let text = std::fs::read_to_string("examples/seed003_synthesised.json").unwrap();
    let mut job: Value = serde_json::from_str(&text).unwrap();
    job["spec"]["angles"] = json!(360);
    let res = s.post_job(&job).await;
    assert!(res.status().is_success(), "{}", res.text().await.unwrap());
    let body: Value = res.json().await.unwrap();
    let id = body["id"].as_str().unwrap().to_string();
    let done = s.wait_finished(&id, Duration::from_secs(120)).await;
    assert_eq!(done["status"], "succeeded", "{done}");
    let (_, result) = s.get_json(&format!("/v1/jobs/{id}/result")).await;
    let lift = job["spec"]["cam"]["profile"]["lift"].as_f64().unwrap();
    let max_lift = result["summary"]["max_lift"].as_f64().unwrap();
    assert!((max_lift / lift - 1.0).abs() < 1e-3, "max_lift {max_lift} vs {lift}");
    assert!(numbers(&result["series"]["jerk"]).iter().all(|j| j.is_finite()));
    assert!(result["summary"]["max_abs_jerk"].as_f64().unwrap().is_finite());
    let syn = &result["synthesis"];
    assert!(syn["max_abs_jerk"].as_f64().unwrap().is_finite() && syn["undercut"] == false, "{syn}");
    assert!(syn["acceleration_margin"].as_f64().unwrap() > 0.0);
    // The contour is a table (CSV with units in the header).
    let csv = s.client.get(s.url(&format!("/v1/jobs/{id}/result?format=csv&table=contour"))).send().await.unwrap();
    assert_eq!(csv.status().as_u16(), 200);
    let text = csv.text().await.unwrap();
    let header = text.lines().next().unwrap();
    assert!(header.starts_with("angle_deg [°],lift [m],lift_velocity [m/rad],lift_acceleration [m/rad²],lift_jerk [m/rad³]"), "{header}");
    assert_eq!(text.lines().count(), 361);
    // The plots of the law (with its limits) and of the contour.
    let (_, plots) = s.get_json(&format!("/v1/jobs/{id}/plots")).await;
    let names = plots.to_string();
    for name in ["lift_law", "lift_law_acceleration", "lift_law_jerk", "cam_contour"] {
        assert!(names.contains(&format!("\"{name}\"")), "{name} in {names}");
    }
    let svg = s.client.get(s.url(&format!("/v1/jobs/{id}/plots/lift_law_acceleration"))).send().await.unwrap();
    assert_eq!(svg.status().as_u16(), 200);
    assert!(svg.text().await.unwrap().contains("limit"));
    // A ramp so fast that the rise would run backwards is refused, naming the field and unit.
    let mut bad = job.clone();
    bad["spec"]["cam"]["profile"]["ramp"] = json!({"height": 0.001, "velocity": 0.05});
    let problem = expect_problem(s.post_job(&bad).await, 422, "invalid_spec").await;
    let errors = problem["errors"].to_string();
    assert!(errors.contains("/spec/cam/profile/ramp/velocity") && errors.contains("m/rad"), "{errors}");
}

/// A kinematics-only cam_cycle spec with this profile on seed 003's flat tappet.
fn kinematics_spec(profile: Value) -> Value {
    let mut spec = example("seed003_synthesised");
    spec["cam"]["profile"] = profile;
    spec["outputs"] = json!(["kinematics"]);
    spec["angles"] = json!(720);
    spec
}

#[test]
fn ramp_free_polynomials_have_the_textbook_coefficients() {
    // Norton/Rothbart: 3-4-5 C_v 15/8, C_a 10/√3 = 5.7735, C_j 60; 4-5-6-7 C_v 35/16, C_a 7.5132,
    // C_j 52.5. Rise angle (duration − dwell)/2 = 110°.
    let (h, beta) = (0.01, 110f64.to_radians());
    for (law, cv, ca, cj) in [("polynomial_345", 15.0 / 8.0, 10.0 / 3f64.sqrt(), 60.0), ("polynomial_4567", 35.0 / 16.0, 7.513_2, 52.5)] {
        let spec = kinematics_spec(json!({"type": "synthesised", "base_radius": 0.02, "lift": h, "duration_deg": 250.0, "dwell_deg": 30.0, "law": law}));
        let r = run("cam_cycle", &spec).unwrap();
        let s = &r["synthesis"];
        let got = |k: &str| s[k].as_f64().unwrap();
        assert!((got("max_velocity") * beta / h / cv - 1.0).abs() < 1e-9, "{law} C_v");
        assert!((got("max_acceleration") * beta * beta / h / ca - 1.0).abs() < 2e-5, "{law} C_a {}", got("max_acceleration") * beta * beta / h);
        assert!((got("max_abs_jerk") * beta.powi(3) / h / cj - 1.0).abs() < 1e-9, "{law} C_j");
        // The series is the same law per time: peak velocity C_v h ω/β at 2672 rpm, sampled.
        let omega = 2672.0 * std::f64::consts::PI / 30.0;
        let v = r["summary"]["max_velocity"].as_f64().unwrap();
        assert!((v / (cv * h * omega / beta) - 1.0).abs() < 1e-4, "{law} series velocity {v}");
        assert!((r["summary"]["max_lift"].as_f64().unwrap() - h).abs() < 1e-12);
    }
}

#[test]
fn synthesised_without_ramps_is_the_rise_return_program() {
    // 3-4-5 rise of 100°, 20° dwell, centred on 180°: the rise starts at 70°.
    let synth = kinematics_spec(json!({"type": "synthesised", "base_radius": 0.02, "lift": 0.009, "duration_deg": 220.0, "dwell_deg": 20.0, "law": "polynomial_345"}));
    let program = kinematics_spec(json!({"type": "rise_return", "base_radius": 0.02, "lift": 0.009, "rise_start_deg": 70.0, "rise_deg": 100.0, "top_dwell_deg": 20.0, "return_deg": 100.0, "law": "polynomial_345"}));
    let (a, b) = (run("cam_cycle", &synth).unwrap(), run("cam_cycle", &program).unwrap());
    for col in ["lift", "velocity", "acceleration", "cam_curvature"] {
        let (x, y) = (numbers(&a["series"][col]), numbers(&b["series"][col]));
        let scale = y.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        let worst = x.iter().zip(&y).map(|(p, q)| (p - q).abs()).fold(0.0, f64::max);
        assert!(worst <= 1e-9 * scale, "{col}: {worst:e} of {scale:e}");
    }
}

#[test]
fn exported_table_reproduces_the_law_as_a_table_profile() {
    let synth = kinematics_spec(json!({"type": "synthesised", "base_radius": 0.016, "lift": 0.009, "duration_deg": 250.0,
        "ramp": {"height": 2.5e-4, "velocity": 8e-4}}));
    let a = run("cam_cycle", &synth).unwrap();
    let contour = &a["contour"];
    let table = kinematics_spec(json!({"type": "table", "base_radius": 0.016, "angle_deg": contour["angle_deg"], "lift": contour["lift"]}));
    let b = run("cam_cycle", &table).unwrap();
    let err = |col: &str| {
        let (x, y) = (numbers(&a["series"][col]), numbers(&b["series"][col]));
        let scale = x.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        x.iter().zip(&y).map(|(p, q)| (p - q).abs()).fold(0.0, f64::max) / scale
    };
    // At the table's own angles the spline passes through the points; velocity and acceleration
    // are the spline's (0.5° spacing).
    assert!(err("lift") < 1e-12, "lift {:e}", err("lift"));
    assert!(err("velocity") < 1e-4, "velocity {:e}", err("velocity"));
    assert!(err("acceleration") < 5e-3, "acceleration {:e}", err("acceleration"));
}

#[test]
fn roller_contour_and_undercut() {
    let profile = json!({"type": "synthesised", "base_radius": 0.016, "lift": 0.009, "duration_deg": 240.0, "ramp": {"height": 2.5e-4, "velocity": 8e-4}, "law": "polynomial_4567"});
    let mut spec = kinematics_spec(profile);
    let rf = 0.01;
    spec["follower"] = json!({"type": "roller", "radius": rf, "length": 0.012, "pin_radius": 0.004, "pin": {"model": "coefficient", "coefficient": 0.05}});
    let r = run("cam_cycle", &spec).unwrap();
    let s = &r["synthesis"];
    let pitch = s["min_pitch_radius_of_curvature"].as_f64().unwrap();
    assert!((s["undercut_margin"].as_f64().unwrap() - (pitch / rf - 1.0)).abs() < 1e-12 && pitch > rf, "{s}");
    let c = &r["contour"];
    let (x, y, px, py) = (numbers(&c["x"]), numbers(&c["y"]), numbers(&c["pitch_x"]), numbers(&c["pitch_y"]));
    for k in 0..x.len() {
        assert!(((px[k] - x[k]).hypot(py[k] - y[k]) - rf).abs() < 1e-12, "row {k}");
    }
    // The base circle: surface at r_b, pitch at r_b + R_f.
    assert!((numbers(&c["radius"])[0] - 0.016).abs() < 1e-12);
    // A short event on a small cam with a large roller undercuts: refused with cam_undercut.
    spec["cam"]["profile"]["base_radius"] = json!(0.004);
    spec["cam"]["profile"]["duration_deg"] = json!(160.0);
    spec["follower"]["radius"] = json!(0.02);
    spec["follower"]["pin_radius"] = json!(0.008);
    match run("cam_cycle", &spec) {
        Err(Failure::Solve(SolveError::Physical { code, message })) => {
            assert_eq!(code, tribod::physics::PhysicalFailure::CamUndercut, "{message}")
        }
        other => panic!("expected cam_undercut, got {other:?}"),
    }
}

#[test]
fn impossible_laws_are_refused_naming_the_field() {
    let refused = |profile: Value| match run("cam_cycle", &kinematics_spec(profile)) {
        Err(Failure::Spec(p)) => p.errors.iter().map(|e| format!("{}: {}", e.path, e.message)).collect::<Vec<_>>().join("; "),
        other => panic!("expected a refusal, got {other:?}"),
    };
    let base = json!({"type": "synthesised", "base_radius": 0.016, "lift": 0.009, "duration_deg": 250.0});
    let with = |patch: Value| {
        let mut p = base.clone();
        p.as_object_mut().unwrap().extend(patch.as_object().unwrap().clone());
        p
    };
    assert!(refused(with(json!({"dwell_deg": 20.0}))).starts_with("/cam/profile/dwell_deg: the polydyne"));
    // Ramps of 4·0.002/(3·0.0005) rad = 306° each.
    assert!(refused(with(json!({"ramp": {"height": 0.002, "velocity": 5e-4}}))).starts_with("/cam/profile/ramp/velocity: each ramp spans"));
    assert!(refused(with(json!({"ramp": {"height": 0.009, "velocity": 5e-4}}))).starts_with("/cam/profile/ramp/height"));
    let m = refused(with(json!({"lift": 9.0})));
    assert!(m.contains("/cam/profile/lift") && m.contains(" m "), "{m}");
    let m = refused(with(json!({"limits": {"max_jerk": -1.0}})));
    assert!(m.contains("/cam/profile/limits/max_jerk") && m.contains("m/rad³"), "{m}");
    // An exceeded limit is a warning in the result, not a refusal.
    let r = run("cam_cycle", &kinematics_spec(with(json!({"limits": {"max_acceleration": 8e-3}})))).unwrap();
    let s = &r["synthesis"];
    assert!(s["acceleration_margin"].as_f64().unwrap() < 0.0 && s["warnings"][0].as_str().unwrap().contains("peak acceleration"), "{s}");
    // …and the shortest event that would meet it: the polydyne's peak acceleration scales as
    // 1/β², so the limit is met at β_min = β √(peak/limit) each side (no ramps, no dwell).
    let beta = s["rise_angle_deg"].as_f64().unwrap();
    let ratio = s["max_acceleration"].as_f64().unwrap().max(-s["min_acceleration"].as_f64().unwrap()) / 8e-3;
    let shortest = s["shortest_duration_deg"].as_f64().unwrap();
    assert!((shortest - 2.0 * beta * ratio.sqrt()).abs() < 1e-3, "{shortest} vs {}", 2.0 * beta * ratio.sqrt());
}

proptest::proptest! {
    #![proptest_config(proptest::prelude::ProptestConfig::with_cases(48))]
    /// Through the kind, any lift, duration, ramp, law and follower: the contract (max_lift to
    /// 0.1 %, finite jerk, a finite contour) or a typed refusal — invalid_spec naming a field
    /// under /cam/profile, cam_undercut, or contact_off_face (seed 003's 17 mm face).
    #[test]
    fn any_synthesised_cam_meets_the_contract_or_is_refused(
        lift in 1e-3f64..0.02, duration in 90.0f64..360.0, law in 0usize..4, dwell in 0.0f64..0.3,
        ramp in proptest::option::of((0.01f64..0.2, 1e-4f64..0.02)), roller in proptest::bool::ANY,
    ) {
        let law = ["polydyne", "polynomial_345", "polynomial_4567", "cycloidal"][law];
        let dwell = if law == "polydyne" { 0.0 } else { dwell * duration };
        let mut profile = json!({"type": "synthesised", "base_radius": 0.02, "lift": lift, "duration_deg": duration, "law": law, "dwell_deg": dwell});
        if let Some((f, v)) = ramp {
            profile["ramp"] = json!({"height": f * lift, "velocity": v});
        }
        let mut spec = kinematics_spec(profile);
        spec["angles"] = json!(360);
        if roller {
            spec["follower"] = json!({"type": "roller", "radius": 0.012, "length": 0.012, "pin_radius": 0.005, "pin": {"model": "coefficient", "coefficient": 0.05}});
        }
        match run("cam_cycle", &spec) {
            Ok(r) => {
                let max_lift = r["summary"]["max_lift"].as_f64().unwrap();
                proptest::prop_assert!((max_lift / lift - 1.0).abs() < 1e-3, "max_lift {} of {}", max_lift, lift);
                proptest::prop_assert!(numbers(&r["series"]["jerk"]).iter().all(|j| j.is_finite()));
                for col in ["x", "y", "curvature", "lift_jerk"] {
                    proptest::prop_assert!(numbers(&r["contour"][col]).iter().all(|v| v.is_finite()), "{}", col);
                }
            }
            Err(Failure::Spec(p)) => proptest::prop_assert!(p.errors.iter().all(|e| e.path.starts_with("/cam/profile")), "{:?}", p.errors),
            Err(Failure::Solve(SolveError::Physical { code, .. })) => {
                use tribod::physics::PhysicalFailure::{CamUndercut, ContactOffFace};
                proptest::prop_assert!(matches!(code, CamUndercut | ContactOffFace), "{:?}", code)
            }
            Err(other) => proptest::prop_assert!(false, "{:?}", other),
        }
    }
}

#[test]
fn wear_runs_on_a_synthesised_cam() {
    // Seed 003's Archard wear run with the synthesised cam in place of the cycloidal one.
    let mut spec = example("seed003_flat_archard");
    spec["cycle"]["cam"]["profile"] = example("seed003_synthesised")["cam"]["profile"].clone();
    let r = run("wear", &spec).unwrap();
    let lift = numbers(&r["series"]["initial_lift"]);
    assert!((lift.iter().fold(0.0f64, |m, v| m.max(*v)) / 0.013998 - 1.0).abs() < 1e-3);
    assert!(r["summary"]["max_wear_depth"].as_f64().unwrap() > 0.0);
}
