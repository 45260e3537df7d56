//! The valve-train run-up over HTTP: `GET /v1/jobs/{id}/result?format=csv&table=run_up` serves
//! the run-up's per-sample columns (the separation intervals are `events.run_up_separation_deg`
//! in the JSON), `series` stays the default table, and a result without a run-up answers 406.

use crate::common::*;

on_both_backends!(run_up_table_is_served_as_csv);
use serde_json::{json, Value};
use std::time::Duration;

async fn run_up_table_is_served_as_csv() {
    let s = start().await;
    let text = std::fs::read_to_string("examples/seed003_dynamic.json").unwrap();
    let mut job = serde_json::from_str::<Value>(&text).unwrap();
    job["spec"]["outputs"] = json!(["kinematics", "loads"]);
    job["spec"]["angles"] = json!(90);
    // 3600 rpm: separates on the ramp's last revolutions.
    job["spec"]["operation"]["speed_rpm"] = json!(3600.0);
    job["spec"]["load"]["run_up"] = json!({"from_rpm": 3000.0, "revolutions": 6, "samples_per_revolution": 36});
    let res = s.client.post(s.url("/v1/jobs")).header("prefer", "wait=60").json(&job).send().await.unwrap();
    let mut done: Value = res.json().await.unwrap();
    let id = done["id"].as_str().unwrap().to_string();
    if done["status"] != "succeeded" {
        done = s.wait_finished(&id, Duration::from_secs(300)).await;
    }
    assert_eq!(done["status"], "succeeded", "{done}");
    let (_, result) = s.get_json(&format!("/v1/jobs/{id}/result")).await;

    let csv_of = |table: Option<&str>| {
        let url = match table {
            Some(t) => format!("/v1/jobs/{id}/result?format=csv&table={t}"),
            None => format!("/v1/jobs/{id}/result?format=csv"),
        };
        let client = s.client.clone();
        let url = s.url(&url);
        async move {
            let res = client.get(url).send().await.unwrap();
            let status = res.status().as_u16();
            let ct = res.headers().get("content-type").map(|v| v.to_str().unwrap().to_string()).unwrap_or_default();
            (status, ct, res.text().await.unwrap())
        }
    };
    let (status, ct, csv) = csv_of(Some("run_up")).await;
    assert_eq!(status, 200, "{csv}");
    assert!(ct.starts_with("text/csv"), "{ct}");
    let lines: Vec<&str> = csv.lines().collect();
    assert_eq!(lines[0], "angle_deg [°],speed_rpm [rpm],contact_load [N],valve_lift [m],valve_velocity [m/s],spring_force_fixed_end [N]");
    assert_eq!(lines.len(), 1 + 6 * 36);
    // Every row parses, and the columns are the JSON's.
    let rows: Vec<Vec<f64>> = lines[1..].iter().map(|l| l.split(',').map(|c| c.parse::<f64>().unwrap()).collect()).collect();
    assert!(rows.iter().all(|r| r.len() == 6));
    let json_speed = result["run_up"]["speed_rpm"].as_array().unwrap();
    for (k, row) in rows.iter().enumerate() {
        assert_eq!(row[1], json_speed[k].as_f64().unwrap(), "row {k}");
    }
    assert!(rows[0][1] > 3000.0 && (rows.last().unwrap()[1] - 3600.0).abs() < 1e-9);
    assert!((rows.last().unwrap()[0] - 6.0 * 360.0).abs() < 1e-9);
    // The intervals are in the events, not in the table.
    let sep = result["events"]["run_up_separation_deg"].as_array().unwrap();
    eprintln!("run-up 3000→3600 rpm over 6 revolutions: {} separation intervals, first at {:?} rpm", sep.len(), result["summary"]["run_up_first_separation_rpm"]);
    assert!(result["run_up"].get("separation").is_none());

    // Default table: the series, one row per cycle angle.
    let (status, _, csv) = csv_of(None).await;
    assert_eq!(status, 200);
    assert!(csv.starts_with("angle_deg [°],"));
    assert_eq!(csv.lines().count(), 1 + 90);

    // A cycle without a run-up has no such table: 404 naming it.
    job["spec"]["load"].as_object_mut().unwrap().remove("run_up");
    let res = s.client.post(s.url("/v1/jobs")).header("prefer", "wait=60").json(&job).send().await.unwrap();
    let mut done: Value = res.json().await.unwrap();
    let id2 = done["id"].as_str().unwrap().to_string();
    if done["status"] != "succeeded" {
        done = s.wait_finished(&id2, Duration::from_secs(300)).await;
    }
    assert_eq!(done["status"], "succeeded", "{done}");
    let res = s.client.get(s.url(&format!("/v1/jobs/{id2}/result?format=csv&table=run_up"))).send().await.unwrap();
    let p = expect_problem(res, 404, "table_not_found").await;
    assert!(p["detail"].as_str().unwrap().contains("run_up"), "{p}");
    s.stop().await;
}
