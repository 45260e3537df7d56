//! Fan-out on SQLite (issue 44): a SQLite file has one instance (`tribod worker` refuses it, and a
//! start re-queues every job the file shows running), so its sweeps fan out over that instance's
//! workers — the same code as on PostgreSQL: the case cache, `instance` and `reused` in every
//! row, `children` in GET and SSE, a cancel that reaches the cases, and a kill -9 and restart that
//! re-runs only the cases the killed process held. Real `tribod serve` processes on a temp file.

use crate::fan_out::*;
use crate::multi_instance::Instance;
use serde_json::Value;
use std::time::{Duration, Instant};

/// One instance of two workers, fan-out from 0.05 s per case.
const SQLITE_OPTS: &[&str] = &["--workers", "2", "--fan-out-min-case-seconds", "0.05"];

/// The case jobs of `parent` (`GET /v1/jobs?parent=`).
async fn cases_of(client: &reqwest::Client, base: &str, parent: &str) -> Vec<Value> {
    let page: Value = client.get(format!("{base}/v1/jobs?parent={parent}&limit=500")).send().await.unwrap().json().await.unwrap();
    page["jobs"].as_array().unwrap().clone()
}

/// Poll `GET /v1/jobs/{id}` until `ok` holds of it; the job.
async fn until(client: &reqwest::Client, base: &str, id: &str, what: &str, ok: impl Fn(&Value) -> bool) -> Value {
    let deadline = Instant::now() + Duration::from_secs(30);
    loop {
        let j = get(client, base, id).await;
        if ok(&j) {
            return j;
        }
        assert!(Instant::now() < deadline, "{what}: {j}");
        tokio::time::sleep(Duration::from_millis(20)).await;
    }
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn sqlite_a_sweep_fans_out_with_progress_and_equals_the_in_process_result() {
    let dir = tempfile::tempdir().unwrap();
    let db = dir.path().join("fan.db");
    let one = Instance::serve(db.to_str().unwrap(), SQLITE_OPTS);
    let client = reqwest::Client::new();
    let job = sleep_sweep(12, 0.2, 1);
    let id = post(&client, &one.base, &job, "").await["id"].as_str().unwrap().to_string();
    let running = until(&client, &one.base, &id, "no children seen", |j| j["children"]["total"] == 12 && j["status"] == "running").await;
    assert!(running["children"]["succeeded"].as_i64().unwrap() < 12, "{running}");
    let mut events = client.get(format!("{}/v1/jobs/{id}/events", one.base)).send().await.unwrap();
    let mut seen = String::new();
    while !seen.contains("\"children\":{\"total\":12") {
        let chunk = tokio::time::timeout(Duration::from_secs(5), events.chunk()).await.expect("an event").unwrap().expect("open stream");
        seen.push_str(&String::from_utf8_lossy(&chunk));
    }
    drop(events);
    // Fairness: a tiny job submitted now waits for one case (0.2 s), not for the sweep.
    let asked = Instant::now();
    let tiny = post(&client, &one.base, &crate::common::hertz_job(777.0), "").await["id"].as_str().unwrap().to_string();
    assert_eq!(finished(&client, &one.base, &tiny, Duration::from_secs(20)).await["status"], "succeeded");
    let latency = asked.elapsed();
    eprintln!("SQLite: tiny job latency during the fan-out: {latency:?}");
    assert!(latency < Duration::from_secs(2), "tiny job waited {latency:?}");
    let done = finished(&client, &one.base, &id, Duration::from_secs(60)).await;
    assert_eq!(done["status"], "succeeded", "{done}");
    assert_eq!(done["children"]["succeeded"], 12, "{done}");
    let fanned = result(&client, &one.base, &id).await;
    let rows = fanned["cases"].as_array().unwrap();
    assert_eq!(rows.len(), 12);
    assert!(rows.iter().all(|r| r["reused"] == false && r["instance"].is_string()), "{fanned}");
    assert_eq!(fanned["meta"]["fan_out"]["instances"], 1);
    // The list hides the cases unless asked.
    assert_eq!(listed(&client, &one.base, "").await.len(), 2, "the sweep and the tiny job");
    assert_eq!(cases_of(&client, &one.base, &id).await.len(), 12);
    assert_eq!(comparable(fanned), comparable(single_instance_result(&client, &job).await));
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn sqlite_a_sweep_rerun_with_one_more_value_solves_one_case() {
    let dir = tempfile::tempdir().unwrap();
    let db = dir.path().join("cache.db");
    let one = Instance::serve(db.to_str().unwrap(), SQLITE_OPTS);
    let client = reqwest::Client::new();
    let solved = || listed(&client, &one.base, "?kind=test_sleep&cases=true");
    let first = post(&client, &one.base, &sleep_sweep(10, 0.1, 300), "").await["id"].as_str().unwrap().to_string();
    assert_eq!(finished(&client, &one.base, &first, Duration::from_secs(30)).await["status"], "succeeded");
    let second = post(&client, &one.base, &sleep_sweep(11, 0.1, 300), "").await["id"].as_str().unwrap().to_string();
    let done = finished(&client, &one.base, &second, Duration::from_secs(30)).await;
    assert_eq!(done["status"], "succeeded", "{done}");
    assert_eq!(done["children"]["reused"], 10, "{done}");
    let r = result(&client, &one.base, &second).await;
    let reused: Vec<bool> = r["cases"].as_array().unwrap().iter().map(|c| c["reused"].as_bool().unwrap()).collect();
    assert_eq!(reused, [vec![true; 10], vec![false]].concat());
    assert!(r["cases"].as_array().unwrap().iter().all(|c| c["instance"].is_string()), "a reused case names who solved it");
    assert_eq!(solved().await.len(), 11, "eleven cases solved for 21 rows");
    // `?fresh=true` reuses nothing.
    let third = post(&client, &one.base, &sleep_sweep(3, 0.1, 300), "?fresh=true").await["id"].as_str().unwrap().to_string();
    assert_eq!(finished(&client, &one.base, &third, Duration::from_secs(30)).await["status"], "succeeded");
    let r = result(&client, &one.base, &third).await;
    assert!(r["cases"].as_array().unwrap().iter().all(|c| c["reused"] == false), "{r}");
    assert_eq!(solved().await.len(), 14);
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn sqlite_a_cancel_mid_sweep_stops_every_case() {
    let dir = tempfile::tempdir().unwrap();
    let db = dir.path().join("cancel.db");
    let one = Instance::serve(db.to_str().unwrap(), SQLITE_OPTS);
    let client = reqwest::Client::new();
    let id = post(&client, &one.base, &sleep_sweep(10, 2.0, 200), "").await["id"].as_str().unwrap().to_string();
    until(&client, &one.base, &id, "cases never ran", |j| j["children"]["running"] == 2).await;
    let asked = Instant::now();
    let res = client.delete(format!("{}/v1/jobs/{id}", one.base)).send().await.unwrap();
    assert!(res.status().is_success(), "{}", res.status());
    let job = until(&client, &one.base, &id, "cases still open", |j| j["children"]["queued"] == 0 && j["children"]["running"] == 0).await;
    let took = asked.elapsed();
    eprintln!("SQLite: cancel of the sweep reached its cases in {took:?}");
    assert!(took < Duration::from_millis(1500), "cancel took {took:?}");
    assert_eq!(job["status"], "canceled", "{job}");
    assert_eq!(job["children"]["failed"], 10, "{job}");
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn sqlite_kill_9_mid_sweep_and_restart_reruns_only_the_held_cases() {
    let dir = tempfile::tempdir().unwrap();
    let db = dir.path().join("kill.db");
    let path = db.to_str().unwrap().to_string();
    let mut one = Instance::serve(&path, SQLITE_OPTS);
    let client = reqwest::Client::new();
    let job = sleep_sweep(12, 0.3, 100);
    let id = post(&client, &one.base, &job, "").await["id"].as_str().unwrap().to_string();
    until(&client, &one.base, &id, "cases never ran", |j| {
        j["children"]["succeeded"].as_i64().unwrap_or(0) >= 3 && j["children"]["running"].as_i64().unwrap_or(0) >= 1
    })
    .await;
    one.child.kill().unwrap();
    one.child.wait().unwrap();
    let again = Instance::serve(&path, SQLITE_OPTS);
    let done = finished(&client, &again.base, &id, Duration::from_secs(60)).await;
    assert_eq!(done["status"], "succeeded", "{done}");
    let r = result(&client, &again.base, &id).await;
    assert_eq!(r["succeeded"], 12, "no case lost: {r}");
    let cases = cases_of(&client, &again.base, &id).await;
    assert_eq!(cases.len(), 12, "no case made twice");
    let rerun = cases.iter().filter(|c| c["attempts"].as_i64().unwrap() > 1).count();
    assert!(rerun <= 2, "only the cases the killed process held (2 workers) ran again: {rerun}");
    let instances: std::collections::BTreeSet<&str> = r["cases"].as_array().unwrap().iter().map(|c| c["instance"].as_str().unwrap()).collect();
    assert_eq!(instances.len(), 2, "solved before and after the restart: {instances:?}");
    assert_eq!(comparable(r), comparable(single_instance_result(&client, &job).await));
}
