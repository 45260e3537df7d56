//! Progressive (variable-pitch) and nested valve springs of a `dynamic` load over HTTP (issue
//! 45): `spring.pitch_groups` gives the coil groups; the checks report the rate, open coils and
//! surge at installed length and full lift against the hand calculation (groups in series,
//! each closing at `K (p − d)`, `K = G d⁴/(8 D³)`; Wahl, *Mechanical Springs*), and the dynamics
//! carry the progressive force at the retainer; a nested inner spring is its own chain, the
//! forces adding. Bad groups are refused naming the field, the rule and the unit.

use crate::common::*;
use serde_json::{json, Value};
use std::time::Duration;

on_both_backends!(progressive_and_nested_springs_over_http);

/// The springs example at 1000 rpm with `outputs` kept small.
fn job() -> Value {
    let text = std::fs::read_to_string("examples/seed003_dynamic_springs.json").unwrap();
    let mut job = serde_json::from_str::<Value>(&text).unwrap();
    job["spec"]["outputs"] = json!(["kinematics", "loads"]);
    job["spec"]["angles"] = json!(180);
    job["spec"]["operation"]["speed_rpm"] = json!(1000.0);
    job
}

async fn run(s: &TestServer, job: &Value) -> Value {
    let res = s.client.post(s.url("/v1/jobs")).header("prefer", "wait=60").json(job).send().await.unwrap();
    let mut done: Value = res.json().await.unwrap();
    let id = done["id"].as_str().unwrap().to_string();
    if done["status"] != "succeeded" {
        done = s.wait_finished(&id, Duration::from_secs(180)).await;
    }
    assert_eq!(done["status"], "succeeded", "{done}");
    s.get_json(&format!("/v1/jobs/{id}/result")).await.1
}

fn close(got: &Value, want: f64, rtol: f64, what: &str) {
    let g = got.as_f64().unwrap_or_else(|| panic!("{what}: {got}"));
    assert!((g - want).abs() <= rtol * want.abs(), "{what}: {g} vs {want}");
}

/// The retainer's spring force at the sample of largest valve lift.
fn force_at_top(r: &Value) -> f64 {
    let lift = r["series"]["valve_lift"].as_array().unwrap();
    let i = (0..lift.len()).max_by(|&a, &b| lift[a].as_f64().unwrap().total_cmp(&lift[b].as_f64().unwrap())).unwrap();
    r["series"]["spring_force_retainer"][i].as_f64().unwrap()
}

async fn progressive_and_nested_springs_over_http() {
    let s = start().await;
    // d = 4 mm, D = 25 mm, G = 79.3 GPa: K = G d⁴/(8 D³) = 162 406 N/m per coil. 1.27 coils of
    // pitch 6.5 mm (gap 2.5 mm) close at F₁ = K × 2.5 mm = 406.0 N, after δ₁ = 4.27 F₁/K =
    // 10.675 mm; 3 coils of pitch 9 mm close at K × 5 mm = 812 N (not reached). Installed 7.9 mm
    // below free: 300.5 N at K/4.27 = 38 034 N/m; full lift (δ = 15.9 mm): F₁ + K/3 × 5.225 mm
    // = 688.9 N at K/3 = 54 135 N/m, three coils open, the surge 4.27/3 times the installed one.
    let (d, dm, g): (f64, f64, f64) = (0.004, 0.025, 79.3e9);
    let k = g * d.powi(4) / (8.0 * dm.powi(3));
    let f1 = k * 2.5e-3;
    let delta1 = 4.27 * f1 / k;
    let (f_inst, f_full) = (k / 4.27 * 7.9e-3, f1 + k / 3.0 * (15.9e-3 - delta1));
    assert!((k - 162_406.0).abs() < 1.0 && (f_full - 688.9).abs() < 0.1, "{k} {f_full}");
    let mut prog = job();
    prog["spec"]["load"]["spring"]["pitch_groups"] = json!([{"coils": 1.27, "pitch": 0.0065}, {"coils": 3.0, "pitch": 0.009}]);
    let r = run(&s, &prog).await;
    let ch = &r["spring_checks"][0];
    close(&ch["rate"], k / 4.27, 1e-12, "installed rate");
    close(&ch["rate_full_lift"], k / 3.0, 1e-12, "full-lift rate");
    close(&ch["installed_force"], f_inst, 1e-12, "installed force");
    close(&ch["full_lift_force"], f_full, 1e-9, "full-lift force");
    close(&ch["active_coils_installed"], 4.27, 1e-12, "open coils installed");
    close(&ch["active_coils_full_lift"], 3.0, 1e-12, "open coils at full lift");
    close(&ch["surge_frequency_full_lift"], ch["surge_frequency"].as_f64().unwrap() * 4.27 / 3.0, 1e-12, "surge at full lift");
    // On the base circle: the installed force, with a surge ringing of ±2 N left by the coils
    // closing and reopening (the uniform spring's residual is below 0.3 N).
    close(&r["series"]["contact_load"][0], f_inst, 0.01, "base-circle load = installed force");
    // The dynamics at 1000 rpm: the retainer's force at full lift is the progressive one (the
    // closed coils' finite stiffness and the spring's inertia within 1 %), 84 N above the
    // uniform spring's.
    let uniform = run(&s, &job()).await;
    let (fp, fu) = (force_at_top(&r), force_at_top(&uniform));
    close(&json!(fp), f_full, 0.01, "progressive force at the top");
    close(&json!(fp - fu), f_full - k / 4.27 * 15.9e-3, 0.05, "progressive − uniform at the top");

    // Nested: the inner spring its own chain; the forces add at the retainer.
    let mut nested = prog.clone();
    nested["spec"]["load"]["inner_spring"] = json!({"wire_diameter": 0.0025, "mean_diameter": 0.016, "active_coils": 6.0, "elements": 4,
        "design": {"free_length": 0.042, "installed_length": 0.0361}});
    let rn = run(&s, &nested).await;
    let k_inner = g * 0.0025f64.powi(4) / (8.0 * 0.016f64.powi(3) * 6.0);
    assert_eq!(rn["spring_checks"].as_array().unwrap().len(), 2);
    close(&rn["spring_checks"][1]["full_lift_force"], k_inner * (0.042 - 0.0361 + 0.008), 1e-9, "inner full-lift force");
    close(&rn["series"]["contact_load"][0], f_inst + k_inner * (0.042 - 0.0361), 0.01, "nested preload");
    close(&json!(force_at_top(&rn)), f_full + k_inner * (0.042 - 0.0361 + 0.008), 0.01, "nested force at the top");

    // Refused: coils that do not add up, a pitch at the wire diameter, too few chain segments.
    let mut bad = prog.clone();
    bad["spec"]["load"]["spring"]["pitch_groups"][0]["coils"] = json!(1.0);
    let p = expect_problem(s.post_job(&bad).await, 422, "invalid_spec").await;
    assert_eq!(p["errors"][0]["path"], "/spec/load/spring/pitch_groups", "{p}");
    let mut bad = prog.clone();
    bad["spec"]["load"]["spring"]["pitch_groups"][1]["pitch"] = json!(0.004);
    let p = expect_problem(s.post_job(&bad).await, 422, "invalid_spec").await;
    assert_eq!(p["errors"][0]["path"], "/spec/load/spring/pitch_groups/1/pitch", "{p}");
    assert!(p["errors"][0]["message"].as_str().unwrap().contains(" m "), "{p}");
    let mut bad = prog.clone();
    bad["spec"]["load"]["spring"]["elements"] = json!(0);
    assert!(s.post_job(&bad).await.status().is_success(), "a massless progressive spring is one element with the series curve");
    bad["spec"]["load"]["spring"]["pitch_groups"] = json!([{"coils": 1.0, "pitch": 0.0065}, {"coils": 1.0, "pitch": 0.007}, {"coils": 2.27, "pitch": 0.009}]);
    bad["spec"]["load"]["spring"]["elements"] = json!(1);
    let p = expect_problem(s.post_job(&bad).await, 422, "invalid_spec").await;
    assert_eq!(p["errors"][0]["path"], "/spec/load/spring/elements", "{p}");
    // More closing segments than the integrator's regimes hold: refused at submission.
    let mut bad = prog.clone();
    bad["spec"]["load"]["spring"]["elements"] = json!(40);
    let p = expect_problem(s.post_job(&bad).await, 422, "invalid_spec").await;
    assert_eq!(p["errors"][0]["path"], "/spec/load/spring/elements", "{p}");
    assert!(p["errors"][0]["message"].as_str().unwrap().contains("28"), "{p}");
}
