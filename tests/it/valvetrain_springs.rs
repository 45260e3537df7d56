//! Valve springs of a `dynamic` load over HTTP (issue 45 item 2): `spring.design` gives the
//! installed preload (instead of `spring_preload`, never both) and the result's `spring_checks`
//! (rate, stresses with the Wahl factor, solid and Goodman safety, coil clash, surge and its cam
//! orders) against their closed forms (Shigley ch. 10); nested springs are checked one by one
//! and add their rates; implausible coils draw warnings. The Shigley worked example (Example
//! 10-4) is the physics crate's `valvetrain::spring` test. A mechanical lash taken up by
//! constant-velocity ramps (`examples/seed003_dynamic_lash.json`) meets the cam at ramp velocity
//! × ω and loses the lash (plus the contact's deflection) from the valve's lift. A hydraulic lash
//! adjuster leaves the cam its base force `P_h + A p_s` on the base circle.

use crate::common::*;
use serde_json::{json, Value};
use std::f64::consts::PI;
use std::time::Duration;

on_both_backends!(spring_checks_over_http, lash_over_http, hydraulic_adjuster_over_http);

fn springs_job() -> Value {
    let text = std::fs::read_to_string("examples/seed003_dynamic_springs.json").unwrap();
    let mut job = serde_json::from_str::<Value>(&text).unwrap();
    job["spec"]["outputs"] = json!(["kinematics", "loads"]);
    job["spec"]["angles"] = json!(90);
    // 1000 rpm: the residual surge on the base circle stays within 1e-4 of the preload (at
    // 3000 rpm it is 3 %); the surge orders still span `speed_range_rpm` 1000–3000.
    job["spec"]["operation"]["speed_rpm"] = json!(1000.0);
    job
}

async fn run(s: &TestServer, job: &Value) -> Value {
    let res = s.client.post(s.url("/v1/jobs")).header("prefer", "wait=60").json(job).send().await.unwrap();
    let mut done: Value = res.json().await.unwrap();
    let id = done["id"].as_str().unwrap().to_string();
    if done["status"] != "succeeded" {
        done = s.wait_finished(&id, Duration::from_secs(120)).await;
    }
    assert_eq!(done["status"], "succeeded", "{done}");
    s.get_json(&format!("/v1/jobs/{id}/result")).await.1
}

fn close(got: &Value, want: f64, rtol: f64, what: &str) {
    let g = got.as_f64().unwrap_or_else(|| panic!("{what}: {got}"));
    assert!((g - want).abs() <= rtol * want.abs(), "{what}: {g} vs {want}");
}

async fn spring_checks_over_http() {
    let s = start().await;
    let job = springs_job();
    let r = run(&s, &job).await;
    // Closed forms for d = 4 mm, D = 25 mm, 4.27 active coils, G = 79.3 GPa, ρ = 7850 kg/m³,
    // L0 = 44 mm, installed 36.1 mm, lift 8 mm, squared and ground, Cr-Si S_ut = 1974/d^0.108 MPa.
    let (d, dm, n, g, rho): (f64, f64, f64, f64, f64) = (0.004, 0.025, 4.27, 79.3e9, 7850.0);
    let k = g * d.powi(4) / (8.0 * dm.powi(3) * n);
    let (f_inst, f_full) = (k * (0.044 - 0.0361), k * (0.044 - 0.0361 + 0.008));
    let c = dm / d;
    let kw = (4.0 * c - 1.0) / (4.0 * c - 4.0) + 0.615 / c;
    let tau = |f: f64| kw * 8.0 * f * dm / (PI * d.powi(3));
    let ch = &r["spring_checks"][0];
    assert_eq!(ch["spring"], "spring");
    close(&ch["rate"], k, 1e-12, "rate");
    close(&ch["installed_force"], f_inst, 1e-12, "installed force");
    close(&ch["full_lift_force"], f_full, 1e-9, "full-lift force");
    close(&ch["stress_full_lift"], tau(f_full), 1e-9, "τ at full lift");
    close(&ch["stress_installed"], tau(f_inst), 1e-9, "τ installed");
    // Goodman (Zimmerli peened 398/534 MPa, S_su = 0.67 S_ut, load line through the origin).
    let ssu = 0.67 * 1974e6 / 4f64.powf(0.108);
    let sse = 398e6 / (1.0 - 534e6 / ssu);
    let (ta, tm) = ((tau(f_full) - tau(f_inst)) / 2.0, (tau(f_full) + tau(f_inst)) / 2.0);
    let ratio = ta / tm;
    close(&ch["fatigue_safety_factor"], ratio * sse * ssu / (ratio * ssu + sse) / ta, 1e-9, "Goodman n_f");
    // Solid length d N_t = 4 mm × 6.27; clash margin at full lift.
    close(&ch["coil_clash_margin"], 0.0361 - 0.008 - 0.004 * 6.27, 1e-9, "clash margin");
    // Surge f = d/(2π n D²) √(G/(2ρ)) = 536 Hz; the cam at 1000–3000 rpm meets it at orders 11..=32.
    let fnat = d / (2.0 * PI * n * dm * dm) * (g / (2.0 * rho)).sqrt();
    close(&ch["surge_frequency"], fnat, 1e-12, "surge");
    let orders: Vec<u64> = ch["exciting_orders"].as_array().unwrap().iter().map(|o| o.as_u64().unwrap()).collect();
    assert_eq!(orders, ((fnat / 50.0).ceil() as u64..=(fnat / (1000.0 / 60.0)).floor() as u64).collect::<Vec<_>>());
    assert_eq!(ch["surge_pass"], false, "536 Hz is 10.7 × the cam at 3000 rpm, below Shigley's 15");
    assert_eq!(ch["fatigue_pass"], true);
    assert_eq!(r["summary"]["spring_checks_pass"], false);
    close(&r["summary"]["min_spring_fatigue_safety_factor"], ch["fatigue_safety_factor"].as_f64().unwrap(), 0.0, "key figure");
    // The design's preload is the spring preload of the dynamics: the base-circle contact load.
    close(&r["series"]["contact_load"][0], f_inst, 1e-3, "base-circle load = installed force");

    // spring_preload and the design together: refused, naming the field and the units.
    let mut both = springs_job();
    both["spec"]["load"]["spring_preload"] = json!(300.0);
    let p = expect_problem(s.post_job(&both).await, 422, "invalid_spec").await;
    assert_eq!(p["errors"][0]["path"], "/spec/load/spring_preload", "{p}");
    assert!(p["errors"][0]["message"].as_str().unwrap().contains("not both"), "{p}");
    // Neither: refused.
    let mut neither = springs_job();
    neither["spec"]["load"]["spring"].as_object_mut().unwrap().remove("design");
    neither["spec"]["load"].as_object_mut().unwrap().remove("spring_checks");
    let p = expect_problem(s.post_job(&neither).await, 422, "invalid_spec").await;
    assert_eq!(p["errors"][0]["path"], "/spec/load/spring_preload", "{p}");
    // Installed at or below solid length: refused with the solid length in metres.
    let mut solid = springs_job();
    solid["spec"]["load"]["spring"]["design"]["installed_length"] = json!(0.02);
    let p = expect_problem(s.post_job(&solid).await, 422, "invalid_spec").await;
    assert_eq!(p["errors"][0]["path"], "/spec/load/spring/design/installed_length", "{p}");
    assert!(p["errors"][0]["message"].as_str().unwrap().contains(" m "), "{p}");

    // Nested springs: checked one by one, rates added in the dynamics.
    let mut nested = springs_job();
    nested["spec"]["load"]["inner_spring"] = json!({"wire_diameter": 0.0025, "mean_diameter": 0.016, "active_coils": 6.0, "elements": 4,
        "design": {"free_length": 0.042, "installed_length": 0.0361}});
    let r2 = run(&s, &nested).await;
    let checks = r2["spring_checks"].as_array().unwrap();
    assert_eq!(checks.len(), 2);
    assert_eq!(checks[1]["spring"], "inner_spring");
    let k_inner = g * 0.0025f64.powi(4) / (8.0 * 0.016f64.powi(3) * 6.0);
    close(&checks[1]["rate"], k_inner, 1e-12, "inner rate");
    close(&r2["summary"]["spring_rate"], k + k_inner, 1e-12, "nested rate");
    close(&r2["series"]["contact_load"][0], f_inst + k_inner * (0.042 - 0.0361), 1e-3, "nested preload");

    // A legal but implausible spring index (D/d = 15): accepted with a warning.
    let mut odd = springs_job();
    odd["spec"]["load"]["spring"]["mean_diameter"] = json!(0.06);
    odd["spec"]["load"]["spring"]["design"]["installed_length"] = json!(0.0435);
    let res = s.post_job(&odd).await;
    assert!(res.status().is_success(), "{}", res.status());
    let body: Value = res.json().await.unwrap();
    let warned: Vec<&str> = body["warnings"].as_array().map(|w| w.iter().filter_map(|x| x["path"].as_str()).collect()).unwrap_or_default();
    assert!(warned.contains(&"/spec/load/spring/mean_diameter"), "{body}");
}

async fn lash_over_http() {
    let s = start().await;
    let text = std::fs::read_to_string("examples/seed003_dynamic_lash.json").unwrap();
    let mut job = serde_json::from_str::<Value>(&text).unwrap();
    let r = run(&s, &job).await;
    // The table's ramps: 0.6 mm/rad from 0 to 0.3 mm; 3000 rpm; lash 0.2 mm (closed mid-ramp).
    let omega = 3000.0 * PI / 30.0;
    let v_ramp = 0.6e-3 * omega;
    let sm = &r["summary"];
    close(&sm["opening_impact_velocity"], v_ramp, 0.01, "opening impact = V ω");
    close(&sm["seating_velocity"], v_ramp, 0.05, "seating on the closing ramp ≈ V ω");
    let loss = sm["lift_loss"].as_f64().unwrap();
    assert!(loss > 0.2e-3 && loss < 0.2e-3 + 2e-5, "lift loss {loss}: the lash plus the train's deflection");
    // On the base circle the seat carries the preload, the cam nothing.
    assert_eq!(r["series"]["contact_load"][0].as_f64().unwrap(), 0.0);
    // (300 N within the residual surge after the impacts: 304 N at 0°.)
    close(&r["series"]["seat_force"][0], 300.0, 0.03, "seat carries the preload");
    // The open lash counts as separation: one interval over the base circle.
    assert!(sm["separation"].as_array().unwrap().iter().any(|iv| iv[1].as_f64().unwrap() - iv[0].as_f64().unwrap() > 150.0), "{sm}");
    // A lash without a seat is refused, naming the field.
    job["spec"]["load"].as_object_mut().unwrap().remove("seat");
    let p = expect_problem(s.post_job(&job).await, 422, "invalid_spec").await;
    assert_eq!(p["errors"][0]["path"], "/spec/load/seat", "{p}");
}

async fn hydraulic_adjuster_over_http() {
    let s = start().await;
    let text = std::fs::read_to_string("examples/seed003_dynamic_hla.json").unwrap();
    let mut job = serde_json::from_str::<Value>(&text).unwrap();
    let r = run(&s, &job).await;
    // Plunger 8 mm, supply 0.3 MPa, plunger spring 20 N: 20 + 3e5 π 0.008²/4 = 35.08 N.
    let base = 20.0 + 3e5 * PI * 0.008f64.powi(2) / 4.0;
    close(&r["series"]["contact_load"][0], base, 2e-3, "base-circle load = the adjuster's base force");
    close(&r["series"]["seat_force"][0], 300.0 - base, 0.02, "the seat carries the rest");
    let loss = r["summary"]["lift_loss"].as_f64().unwrap();
    assert!(loss > 0.0 && loss < 2e-4, "lift loss {loss}: oil column and leak-down");
    // A legal but unusual plunger clearance (50 µm): accepted with a warning.
    let mut loose = job.clone();
    loose["spec"]["load"]["hydraulic_lash_adjuster"]["clearance"] = json!(5e-5);
    let body: Value = s.post_job(&loose).await.json().await.unwrap();
    let warned: Vec<&str> = body["warnings"].as_array().map(|w| w.iter().filter_map(|x| x["path"].as_str()).collect()).unwrap_or_default();
    assert!(warned.contains(&"/spec/load/hydraulic_lash_adjuster/clearance"), "{body}");
    // With a mechanical lash as well: refused.
    job["spec"]["load"]["lash"] = json!({"clearance": 2e-4});
    let p = expect_problem(s.post_job(&job).await, 422, "invalid_spec").await;
    assert_eq!(p["errors"][0]["path"], "/spec/load/lash", "{p}");
}
