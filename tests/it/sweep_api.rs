//! `sweep` end to end over HTTP: cases in parallel, CSV table, failing cases as data, validation of
//! every case at submission.


use crate::common::*;

on_both_backends!(
    sweep_tabulates_cases_and_serves_csv,
    every_case_is_validated_at_submission_and_limits_apply,
    canceling_a_sweep_stops_its_cases,
    a_speed_sweep_of_a_dynamic_cam_cycle_gives_the_jump_speed,
);
use serde_json::{json, Value};

async fn sweep_tabulates_cases_and_serves_csv() {
    let s = start().await;
    let job = json!({"kind": "sweep", "spec": {
        "kind": "hertz",
        "base": hertz_job(1000.0)["spec"],
        "parameters": [
            {"path": "/load", "values": [1000.0, 4000.0]},
            {"path": "/body_1/radius", "linspace": {"start": 0.01, "stop": 0.03, "num": 3}}
        ],
        "quantities": ["/max_pressure", "/half_width"]}});
    let res = s.client.post(s.url("/v1/jobs")).header("prefer", "wait=20").json(&job).send().await.unwrap();
    let done: Value = res.json().await.unwrap();
    assert_eq!(done["status"], "succeeded", "{done}");
    let id = done["id"].as_str().unwrap();
    let (_, result) = s.get_json(&format!("/v1/jobs/{id}/result")).await;
    let cases = result["cases"].as_array().unwrap();
    assert_eq!(cases.len(), 6);
    assert_eq!(result["succeeded"], 6);
    // p0 ∝ sqrt(load): the 4 kN cases have twice the pressure of the 1 kN ones at equal radius.
    for i in 0..3 {
        let (a, b) = (cases[i]["max_pressure"].as_f64().unwrap(), cases[i + 3]["max_pressure"].as_f64().unwrap());
        assert!((b / a - 2.0).abs() < 1e-12, "case {i}: {a} {b}");
        assert_eq!(cases[i]["body_1.radius"], cases[i + 3]["body_1.radius"]);
    }
    let csv = s
        .client
        .get(s.url(&format!("/v1/jobs/{id}/result")))
        .header("accept", "text/csv")
        .send()
        .await
        .unwrap()
        .text()
        .await
        .unwrap();
    assert_eq!(csv.lines().next().unwrap(), "case,load [N],body_1.radius [m],status,max_pressure [Pa],half_width [m]");
    assert_eq!(csv.lines().count(), 7);
    s.stop().await;
}

async fn every_case_is_validated_at_submission_and_limits_apply() {
    let s = start_with(|c| c.queue.limits.max_sweep_cases = 50).await;
    let job = json!({"kind": "sweep", "spec": {"kind": "hertz", "base": hertz_job(1000.0)["spec"],
        "parameters": [{"path": "/load", "values": [1000.0, -1.0]}]}});
    let p = expect_problem(s.post_job(&job).await, 422, "invalid_spec").await;
    assert_eq!(p["errors"][0]["path"], "/spec/parameters/0", "{p}");
    assert!(p["errors"][0]["message"].as_str().unwrap().contains("/load = -1"), "{p}");

    let job = json!({"kind": "sweep", "spec": {"kind": "hertz", "base": hertz_job(1000.0)["spec"],
        "parameters": [{"path": "/length", "values": ["long"]}]}});
    let p = expect_problem(s.post_job(&job).await, 422, "invalid_spec").await;
    assert_eq!(p["errors"][0]["path"], "/spec/parameters/0", "{p}");

    let job = json!({"kind": "sweep", "spec": {"kind": "hertz", "base": hertz_job(1000.0)["spec"],
        "parameters": [{"path": "/load", "linspace": {"start": 1.0, "stop": 2.0, "num": 10}},
                       {"path": "/length", "linspace": {"start": 0.01, "stop": 0.02, "num": 10}}]}});
    let p = expect_problem(s.post_job(&job).await, 422, "limit_exceeded").await;
    assert!(p["errors"][0]["message"].as_str().unwrap().contains("100"), "{p}");

    let job = json!({"kind": "sweep", "spec": {"kind": "sweep", "base": {}, "parameters": [{"path": "/x", "values": [1]}]}});
    let p = expect_problem(s.post_job(&job).await, 422, "invalid_spec").await;
    assert_eq!(p["errors"][0]["path"], "/spec/kind");
    s.stop().await;
}

async fn canceling_a_sweep_stops_its_cases() {
    let s = start().await;
    let values: Vec<u64> = (1..=40).collect();
    let job = json!({"kind": "sweep", "spec": {"kind": "test_sleep", "base": {"seconds": 0.5},
        "parameters": [{"path": "/nonce", "values": values}]}});
    let created: Value = s.post_job(&job).await.json().await.unwrap();
    let id = created["id"].as_str().unwrap().to_string();
    s.wait_status(&id, "running", std::time::Duration::from_secs(10)).await;
    tokio::time::sleep(std::time::Duration::from_millis(300)).await;
    let t0 = std::time::Instant::now();
    let res = s.client.delete(s.url(&format!("/v1/jobs/{id}"))).send().await.unwrap();
    assert_eq!(res.status().as_u16(), 202);
    let done = s.wait_finished(&id, std::time::Duration::from_secs(20)).await;
    assert_eq!(done["status"], "canceled");
    assert!(t0.elapsed().as_secs_f64() < 3.0, "took {:?} (40 cases × 0.5 s would be 10 s)", t0.elapsed());
    s.stop().await;
}

/// Issue 17: a `sweep` over cam speed of a dynamic `cam_cycle` (seed 003's train) gives the jump
/// speed — the lowest speed whose `separation_duration` is positive — end to end over HTTP; every
/// case also reports the rigid train's closed-form `rigid_jump_speed_rpm`, and the CSV carries
/// both columns (the recipe of README "Jump speed").
async fn a_speed_sweep_of_a_dynamic_cam_cycle_gives_the_jump_speed() {
    let s = start().await;
    let text = std::fs::read_to_string("examples/seed003_dynamic.json").unwrap();
    let mut base = serde_json::from_str::<Value>(&text).unwrap()["spec"].clone();
    base["outputs"] = json!(["kinematics", "loads"]);
    base["angles"] = json!(360);
    let job = json!({"kind": "sweep", "spec": {
        "kind": "cam_cycle",
        "base": base,
        "parameters": [{"path": "/operation/speed_rpm", "linspace": {"start": 3000.0, "stop": 3600.0, "num": 7}}],
        "quantities": ["/summary/separation_duration", "/summary/rigid_jump_speed_rpm"]}});
    let res = s.client.post(s.url("/v1/jobs")).header("prefer", "wait=120").json(&job).send().await.unwrap();
    let mut done: Value = res.json().await.unwrap();
    if done["status"] != "succeeded" {
        let id = done["id"].as_str().unwrap().to_string();
        done = s.wait_finished(&id, std::time::Duration::from_secs(300)).await;
    }
    assert_eq!(done["status"], "succeeded", "{done}");
    let id = done["id"].as_str().unwrap();
    let (_, result) = s.get_json(&format!("/v1/jobs/{id}/result")).await;
    assert_eq!(result["succeeded"], 7, "{result}");
    let cases = result["cases"].as_array().unwrap();
    let rows: Vec<(f64, f64, f64)> = cases
        .iter()
        .map(|c| {
            (
                c["operation.speed_rpm"].as_f64().unwrap(),
                c["summary.separation_duration"].as_f64().unwrap(),
                c["summary.rigid_jump_speed_rpm"].as_f64().unwrap(),
            )
        })
        .collect();
    eprintln!("seed 003 speed sweep (rpm, separation s, rigid jump rpm): {rows:?}");
    // Contact kept at 3000 rpm (the example's speed), lost at 3600 rpm; once lost it stays lost.
    assert_eq!(rows[0].1, 0.0);
    assert!(rows[6].1 > 0.0);
    let first = rows.iter().position(|r| r.1 > 0.0).unwrap();
    assert!(rows[first..].iter().all(|r| r.1 > 0.0), "{rows:?}");
    // The rigid figure is a property of the train and cam, the same in every case.
    assert!(rows.iter().all(|r| (r.2 / rows[0].2 - 1.0).abs() < 1e-12));
    let csv = s.client.get(s.url(&format!("/v1/jobs/{id}/result"))).header("accept", "text/csv").send().await.unwrap().text().await.unwrap();
    assert_eq!(csv.lines().next().unwrap(), "case,operation.speed_rpm [rpm],status,summary.separation_duration [s],summary.rigid_jump_speed_rpm [rpm]");
    s.stop().await;
}
