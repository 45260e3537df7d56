//! One big job on many machines (issue 44): a sweep's cases as jobs of their own that every
//! instance on one PostgreSQL database claims; the parent assembled into the result one instance
//! gives; kill -9 of an instance re-runs only its cases; a cancel reaches the cases on every
//! instance; the case cache (a re-run with one more value solves one case); a tiny job's latency
//! during a fan-out. The instances are real `tribod serve` / `tribod worker` processes.
//!
//! The PostgreSQL tests need `TRIBOD_TEST_POSTGRES_URL` (they say SKIPPED without it); the SQLite
//! test checks that a sweep below the crossover stays in-process (no cases). SQLite's fan-out:
//! `fan_out_sqlite.rs`; instances killed mid-fan-out and races of joins with cancels:
//! `fan_out_faults.rs`.

use crate::common::*;
use crate::multi_instance::Instance;
use serde_json::{json, Value};
use sqlx::{Connection, Row};
use std::collections::BTreeSet;
use std::time::{Duration, Instant};

/// Instance options of these tests: 1 worker each, short leases, fan-out from 0.05 s per case.
pub(crate) const OPTS: &[&str] = &["--workers", "1", "--lease-seconds", "2", "--fan-out-min-case-seconds", "0.05"];

/// A sweep of `n` `test_sleep` cases of `seconds` each (nonces `first..first + n`).
pub(crate) fn sleep_sweep(n: u64, seconds: f64, first: u64) -> Value {
    let nonces: Vec<u64> = (first..first + n).collect();
    json!({"kind": "sweep", "spec": {
        "kind": "test_sleep",
        "base": {"seconds": seconds},
        "parameters": [{"path": "/nonce", "values": nonces}],
        "quantities": ["/table/step/3"]
    }})
}

/// A sweep of 40 line contacts (real numbers to compare bit for bit).
fn hertz_sweep() -> Value {
    let mut job = hertz_job(1000.0);
    json!({"kind": "sweep", "spec": {
        "kind": "hertz",
        "base": job["spec"].take(),
        "parameters": [{"path": "/load", "linspace": {"start": 100.0, "stop": 20000.0, "num": 40}}]
    }})
}

pub(crate) async fn post(client: &reqwest::Client, base: &str, job: &Value, query: &str) -> Value {
    let res = client.post(format!("{base}/v1/jobs{query}")).json(job).send().await.unwrap();
    assert!(res.status().is_success(), "{}", res.status());
    res.json().await.unwrap()
}

pub(crate) async fn get(client: &reqwest::Client, base: &str, id: &str) -> Value {
    client.get(format!("{base}/v1/jobs/{id}")).send().await.unwrap().json().await.unwrap()
}

pub(crate) async fn result(client: &reqwest::Client, base: &str, id: &str) -> Value {
    client.get(format!("{base}/v1/jobs/{id}/result")).send().await.unwrap().json().await.unwrap()
}

/// Poll until the job is finished; the job.
pub(crate) async fn finished(client: &reqwest::Client, base: &str, id: &str, timeout: Duration) -> Value {
    let deadline = Instant::now() + timeout;
    loop {
        let job = get(client, base, id).await;
        if matches!(job["status"].as_str(), Some("succeeded" | "failed" | "canceled")) {
            return job;
        }
        assert!(Instant::now() < deadline, "job {id} not finished in {timeout:?}: {job}");
        tokio::time::sleep(Duration::from_millis(50)).await;
    }
}

/// A sweep result without what only a fan-out adds (`instance`, `reused`) and without `meta`.
pub(crate) fn comparable(mut r: Value) -> Value {
    r.as_object_mut().unwrap().remove("meta");
    for row in r["cases"].as_array_mut().unwrap() {
        let row = row.as_object_mut().unwrap();
        row.remove("instance");
        row.remove("reused");
    }
    let cols: Vec<Value> = r["columns"].as_array().unwrap().iter().filter(|c| *c != "instance" && *c != "reused").cloned().collect();
    r["columns"] = Value::Array(cols);
    r
}

/// The result of `job` from one in-process instance on a SQLite file.
pub(crate) async fn single_instance_result(client: &reqwest::Client, job: &Value) -> Value {
    let dir = tempfile::tempdir().unwrap();
    let db = dir.path().join("ref.db");
    let one = Instance::serve(db.to_str().unwrap(), &["--workers", "2"]);
    let id = post(client, &one.base, job, "").await["id"].as_str().unwrap().to_string();
    let done = finished(client, &one.base, &id, Duration::from_secs(60)).await;
    assert_eq!(done["status"], "succeeded", "{done}");
    assert!(done.get("children").is_none(), "SQLite: in-process, no children: {done}");
    result(client, &one.base, &id).await
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_sweep_fans_out_over_three_instances_and_equals_the_single_instance_result() {
    if !postgres_available("a_sweep_fans_out_over_three_instances_and_equals_the_single_instance_result") {
        return;
    }
    let url = fresh_postgres_database().await;
    let a = Instance::serve(&url, OPTS);
    let b = Instance::serve(&url, OPTS);
    let _c = Instance::worker(&url, OPTS);
    let client = reqwest::Client::new();

    let job = sleep_sweep(40, 0.2, 1);
    let id = post(&client, &a.base, &job, "").await["id"].as_str().unwrap().to_string();
    // While it runs, GET (on the other instance) shows its cases.
    let deadline = Instant::now() + Duration::from_secs(10);
    let running = loop {
        let j = get(&client, &b.base, &id).await;
        if j["children"]["total"] == 40 && j["status"] == "running" {
            break j;
        }
        assert!(Instant::now() < deadline, "no children seen: {j}");
        tokio::time::sleep(Duration::from_millis(20)).await;
    };
    assert!(running["children"]["succeeded"].as_i64().unwrap() < 40, "{running}");
    // The event stream carries the counts too.
    let mut events = client.get(format!("{}/v1/jobs/{id}/events", b.base)).send().await.unwrap();
    let mut seen = String::new();
    while !seen.contains("\"children\":{\"total\":40") {
        let chunk = tokio::time::timeout(Duration::from_secs(5), events.chunk()).await.expect("an event").unwrap().expect("open stream");
        seen.push_str(&String::from_utf8_lossy(&chunk));
    }
    drop(events);
    // Fairness: a tiny job submitted now waits for at most one case per worker, not the sweep.
    let asked = Instant::now();
    let tiny = post(&client, &b.base, &hertz_job(777.0), "").await["id"].as_str().unwrap().to_string();
    let tiny_done = finished(&client, &b.base, &tiny, Duration::from_secs(20)).await;
    let tiny_latency = asked.elapsed();
    let sweep_state = get(&client, &a.base, &id).await;
    eprintln!("tiny job latency during the fan-out: {tiny_latency:?} (sweep then: {})", sweep_state["children"]);
    assert_eq!(tiny_done["status"], "succeeded");
    assert!(tiny_latency < Duration::from_secs(2), "tiny job waited {tiny_latency:?}");

    let done = finished(&client, &a.base, &id, Duration::from_secs(60)).await;
    assert_eq!(done["status"], "succeeded", "{done}");
    assert_eq!(done["children"]["succeeded"], 40, "{done}");
    assert_eq!(done["started_at"], running["started_at"], "assembled elsewhere, started when first claimed");
    assert_eq!(done["attempts"], 1, "{done}");
    let fanned = result(&client, &b.base, &id).await;
    let rows = fanned["cases"].as_array().unwrap();
    assert_eq!(rows.len(), 40);
    let instances: BTreeSet<&str> = rows.iter().map(|r| r["instance"].as_str().expect("instance")).collect();
    assert!(rows.iter().all(|r| r["reused"] == false), "nothing to reuse in a fresh database");
    assert_eq!(instances.len(), 3, "every instance solved cases: {instances:?}");
    assert_eq!(fanned["meta"]["fan_out"]["cases"], 40);

    // The same table as one instance gives, and a physics sweep bit for bit.
    let reference = single_instance_result(&client, &job).await;
    assert_eq!(comparable(fanned), comparable(reference));
    let physics = hertz_sweep();
    let hid = post(&client, &a.base, &physics, "").await["id"].as_str().unwrap().to_string();
    let hdone = finished(&client, &a.base, &hid, Duration::from_secs(30)).await;
    assert_eq!(hdone["status"], "succeeded");
    // Line contacts are microseconds: below the crossover they stay in-process.
    assert!(hdone.get("children").is_none(), "{hdone}");
    assert_eq!(result(&client, &a.base, &hid).await["meta"].get("fan_out"), None);
    drop((a, b));
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_fanned_out_physics_sweep_is_bit_identical_to_the_in_process_one() {
    if !postgres_available("a_fanned_out_physics_sweep_is_bit_identical_to_the_in_process_one") {
        return;
    }
    let url = fresh_postgres_database().await;
    // Every sweep fans out.
    let opts = ["--workers", "1", "--lease-seconds", "2", "--fan-out-min-case-seconds", "0"];
    let a = Instance::serve(&url, &opts);
    let _w = Instance::worker(&url, &opts);
    let client = reqwest::Client::new();
    let job = hertz_sweep();
    let id = post(&client, &a.base, &job, "").await["id"].as_str().unwrap().to_string();
    let done = finished(&client, &a.base, &id, Duration::from_secs(30)).await;
    assert_eq!(done["status"], "succeeded", "{done}");
    assert_eq!(done["children"]["total"], 40, "{done}");
    let fanned = result(&client, &a.base, &id).await;
    let reference = single_instance_result(&client, &job).await;
    assert_eq!(comparable(fanned), comparable(reference));
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn kill_9_of_an_instance_mid_sweep_reruns_only_its_cases() {
    if !postgres_available("kill_9_of_an_instance_mid_sweep_reruns_only_its_cases") {
        return;
    }
    let url = fresh_postgres_database().await;
    let a = Instance::serve(&url, OPTS);
    let mut b = Instance::serve(&url, OPTS);
    let _c = Instance::worker(&url, OPTS);
    let client = reqwest::Client::new();
    let id = post(&client, &a.base, &sleep_sweep(40, 0.3, 100), "").await["id"].as_str().unwrap().to_string();

    // Kill B (SIGKILL) while it solves a case of the sweep.
    let mut db = sqlx::PgConnection::connect(&url).await.unwrap();
    let owner = format!("%/{}/%", b.child.id());
    let deadline = Instant::now() + Duration::from_secs(20);
    loop {
        let held: i64 = sqlx::query(
            "SELECT count(*) FROM jobs j JOIN job_children c ON c.job_id = j.id \
             WHERE c.parent_id = $1 AND j.status = 'running' AND j.lease_owner LIKE $2",
        )
        .bind(&id)
        .bind(&owner)
        .fetch_one(&mut db)
        .await
        .unwrap()
        .get(0);
        let succeeded = get(&client, &a.base, &id).await["children"]["succeeded"].as_i64().unwrap_or(0);
        if held > 0 && succeeded >= 3 {
            break;
        }
        assert!(Instant::now() < deadline, "B never solved a case");
        tokio::time::sleep(Duration::from_millis(10)).await;
    }
    b.child.kill().unwrap();
    b.child.wait().unwrap();

    let done = finished(&client, &a.base, &id, Duration::from_secs(60)).await;
    assert_eq!(done["status"], "succeeded", "{done}");
    let r = result(&client, &a.base, &id).await;
    assert_eq!(r["succeeded"], 40, "no case lost");
    // Only B's claimed case ran twice (1 worker: at most one case held at the kill).
    let rerun: i64 = sqlx::query(
        "SELECT count(*) FROM jobs j JOIN job_children c ON c.job_id = j.id WHERE c.parent_id = $1 AND j.attempts > 1",
    )
    .bind(&id)
    .fetch_one(&mut db)
    .await
    .unwrap()
    .get(0);
    assert_eq!(rerun, 1, "only the killed instance's case ran again");
    assert_eq!(comparable(r), comparable(single_instance_result(&client, &sleep_sweep(40, 0.3, 100)).await));
    let _ = db.close().await;
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_cancel_of_a_fanned_out_sweep_stops_its_cases_on_every_instance() {
    if !postgres_available("a_cancel_of_a_fanned_out_sweep_stops_its_cases_on_every_instance") {
        return;
    }
    let url = fresh_postgres_database().await;
    let a = Instance::serve(&url, OPTS);
    let _w = Instance::worker(&url, OPTS);
    let client = reqwest::Client::new();
    let id = post(&client, &a.base, &sleep_sweep(40, 1.0, 200), "").await["id"].as_str().unwrap().to_string();
    let deadline = Instant::now() + Duration::from_secs(10);
    loop {
        let j = get(&client, &a.base, &id).await;
        if j["children"]["running"].as_i64().unwrap_or(0) == 2 {
            break;
        }
        assert!(Instant::now() < deadline, "cases never ran on both instances: {j}");
        tokio::time::sleep(Duration::from_millis(20)).await;
    }
    let asked = Instant::now();
    let res = client.delete(format!("{}/v1/jobs/{id}", a.base)).send().await.unwrap();
    assert!(res.status().is_success(), "{}", res.status());
    let mut db = sqlx::PgConnection::connect(&url).await.unwrap();
    loop {
        let open: i64 = sqlx::query(
            "SELECT count(*) FROM jobs j JOIN job_children c ON c.job_id = j.id \
             WHERE c.parent_id = $1 AND j.status IN ('queued', 'running')",
        )
        .bind(&id)
        .fetch_one(&mut db)
        .await
        .unwrap()
        .get(0);
        if open == 0 {
            break;
        }
        assert!(asked.elapsed() < Duration::from_secs(3), "{open} cases still open");
        tokio::time::sleep(Duration::from_millis(10)).await;
    }
    let took = asked.elapsed();
    eprintln!("cancel of the sweep reached its cases in {took:?}");
    assert!(took < Duration::from_millis(1500), "cancel took {took:?}");
    let job = get(&client, &a.base, &id).await;
    assert_eq!(job["status"], "canceled", "{job}");
    assert_eq!(job["children"]["failed"], 40, "{job}");
    let _ = db.close().await;
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_sweep_rerun_with_one_more_value_solves_one_case() {
    if !postgres_available("a_sweep_rerun_with_one_more_value_solves_one_case") {
        return;
    }
    let url = fresh_postgres_database().await;
    let a = Instance::serve(&url, OPTS);
    let client = reqwest::Client::new();
    let first = post(&client, &a.base, &sleep_sweep(10, 0.1, 300), "").await["id"].as_str().unwrap().to_string();
    assert_eq!(finished(&client, &a.base, &first, Duration::from_secs(30)).await["status"], "succeeded");

    let second = post(&client, &a.base, &sleep_sweep(11, 0.1, 300), "").await["id"].as_str().unwrap().to_string();
    let done = finished(&client, &a.base, &second, Duration::from_secs(30)).await;
    assert_eq!(done["status"], "succeeded", "{done}");
    assert_eq!(done["children"]["reused"], 10, "{done}");
    let r = result(&client, &a.base, &second).await;
    let reused: Vec<bool> = r["cases"].as_array().unwrap().iter().map(|c| c["reused"].as_bool().unwrap()).collect();
    assert_eq!(reused, [vec![true; 10], vec![false]].concat());
    assert!(r["cases"].as_array().unwrap().iter().all(|c| c["instance"].is_string()), "a reused case names who solved it");
    let mut db = sqlx::PgConnection::connect(&url).await.unwrap();
    let solved: i64 = sqlx::query("SELECT count(*) FROM jobs WHERE kind = 'test_sleep'").fetch_one(&mut db).await.unwrap().get(0);
    assert_eq!(solved, 11, "eleven cases solved for 21 rows");

    // `?fresh=true` reuses nothing.
    let third = post(&client, &a.base, &sleep_sweep(3, 0.1, 300), "?fresh=true").await["id"].as_str().unwrap().to_string();
    assert_eq!(finished(&client, &a.base, &third, Duration::from_secs(30)).await["status"], "succeeded");
    let r = result(&client, &a.base, &third).await;
    assert!(r["cases"].as_array().unwrap().iter().all(|c| c["reused"] == false), "{r}");
    let solved: i64 = sqlx::query("SELECT count(*) FROM jobs WHERE kind = 'test_sleep'").fetch_one(&mut db).await.unwrap().get(0);
    assert_eq!(solved, 14);
    let _ = db.close().await;
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_failed_case_is_a_failed_row_with_its_error() {
    if !postgres_available("a_failed_case_is_a_failed_row_with_its_error") {
        return;
    }
    let url = fresh_postgres_database().await;
    let a = Instance::serve(&url, OPTS);
    let client = reqwest::Client::new();
    let job = json!({"kind": "sweep", "spec": {
        "kind": "test_sleep", "base": {"seconds": 0.1, "nonce": 400},
        "parameters": [{"path": "/panic", "values": [false, true, false]}, {"path": "/nonce", "values": [400]}],
        "quantities": ["/table/step/3"]
    }});
    let id = post(&client, &a.base, &job, "").await["id"].as_str().unwrap().to_string();
    let done = finished(&client, &a.base, &id, Duration::from_secs(30)).await;
    assert_eq!(done["status"], "succeeded", "a failed case does not fail the sweep: {done}");
    assert_eq!(done["children"]["failed"], 1, "{done}");
    let r = result(&client, &a.base, &id).await;
    assert_eq!((r["succeeded"].as_i64(), r["failed"].as_i64()), (Some(2), Some(1)), "{r}");
    let row = &r["cases"][1];
    assert_eq!(row["status"], "failed");
    assert_eq!(row["error_code"], "internal_error");
    assert!(row["error"].as_str().unwrap().contains("panicked"), "{row}");
    assert!(r["columns"].as_array().unwrap().contains(&json!("error")));
    // Cases 1 and 3 are the same spec: solved once.
    assert_eq!(r["cases"][0]["table.step.3"], r["cases"][2]["table.step.3"]);
}

/// The ids of `GET /v1/jobs{query}` (one page of 500).
pub(crate) async fn listed(client: &reqwest::Client, base: &str, query: &str) -> BTreeSet<String> {
    let sep = if query.is_empty() { "?" } else { "&" };
    let res = client.get(format!("{base}/v1/jobs{query}{sep}limit=500")).send().await.unwrap();
    assert!(res.status().is_success(), "{query}: {}", res.status());
    let page: Value = res.json().await.unwrap();
    page["jobs"].as_array().unwrap().iter().map(|j| j["id"].as_str().unwrap().to_string()).collect()
}

/// Poll until `id` has `n` children recorded.
pub(crate) async fn fanned_out(client: &reqwest::Client, base: &str, id: &str, n: i64) {
    let deadline = Instant::now() + Duration::from_secs(10);
    loop {
        let j = get(client, base, id).await;
        if j["children"]["total"] == n {
            return;
        }
        assert!(Instant::now() < deadline, "{id} not fanned out: {j}");
        tokio::time::sleep(Duration::from_millis(20)).await;
    }
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn case_jobs_are_hidden_from_the_list_and_not_counted_against_max_queue() {
    if !postgres_available("case_jobs_are_hidden_from_the_list_and_not_counted_against_max_queue") {
        return;
    }
    let url = fresh_postgres_database().await;
    let a = Instance::serve(&url, &["--workers", "1", "--lease-seconds", "2", "--fan-out-min-case-seconds", "0.05", "--max-queue", "3"]);
    let client = reqwest::Client::new();
    let sweep = post(&client, &a.base, &sleep_sweep(8, 1.0, 600), "").await["id"].as_str().unwrap().to_string();
    fanned_out(&client, &a.base, &sweep, 8).await;
    // Past a recount of the shared queue (every 100 ms): ≥ 6 cases are queued, none counts.
    tokio::time::sleep(Duration::from_millis(250)).await;
    let mut small = BTreeSet::new();
    for nonce in 0..3 {
        let job = json!({"kind": "test_sleep", "spec": {"seconds": 0.05, "nonce": 700 + nonce}});
        small.insert(post(&client, &a.base, &job, "").await["id"].as_str().unwrap().to_string());
    }
    let job = json!({"kind": "test_sleep", "spec": {"seconds": 0.05, "nonce": 710}});
    let res = client.post(format!("{}/v1/jobs", a.base)).json(&job).send().await.unwrap();
    assert_eq!(res.status(), 503, "the fourth job over --max-queue 3 (the sweep's cases not counted)");

    let default = listed(&client, &a.base, "").await;
    let expected: BTreeSet<String> = small.iter().cloned().chain([sweep.clone()]).collect();
    assert_eq!(default, expected, "the default list hides the cases");
    let cases = listed(&client, &a.base, &format!("?parent={sweep}")).await;
    assert_eq!(cases.len(), 8);
    assert!(cases.is_disjoint(&expected));
    let all = listed(&client, &a.base, "?cases=true").await;
    assert_eq!(all, expected.union(&cases).cloned().collect::<BTreeSet<_>>());
    let kind = listed(&client, &a.base, "?kind=test_sleep").await;
    assert_eq!(kind, small, "filters combine: the cases stay hidden");
    // An unknown parent: an empty list.
    assert!(listed(&client, &a.base, &format!("?parent={}", small.first().unwrap())).await.is_empty());
    let res = client.delete(format!("{}/v1/jobs/{sweep}", a.base)).send().await.unwrap();
    assert!(res.status().is_success());
}

/// Below the crossover (default 0.5 s per case) a sweep stays in-process: no case jobs, on SQLite
/// as on PostgreSQL (SQLite's fan-out: `fan_out_sqlite.rs`).
#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn sqlite_lists_every_job_and_no_job_has_cases() {
    let dir = tempfile::tempdir().unwrap();
    let db = dir.path().join("list.db");
    let one = Instance::serve(db.to_str().unwrap(), &["--workers", "1"]);
    let client = reqwest::Client::new();
    let id = post(&client, &one.base, &sleep_sweep(2, 0.01, 800), "").await["id"].as_str().unwrap().to_string();
    assert_eq!(listed(&client, &one.base, "").await, BTreeSet::from([id.clone()]));
    assert_eq!(listed(&client, &one.base, "?cases=true").await, BTreeSet::from([id.clone()]));
    assert!(listed(&client, &one.base, &format!("?parent={id}")).await.is_empty());
    let res = client.get(format!("{}/v1/jobs?cases=maybe", one.base)).send().await.unwrap();
    assert_eq!(res.status(), 400);
}

/// The status and cancel flag of each case job of `parent`.
async fn case_states(db: &mut sqlx::PgConnection, parent: &str) -> Vec<(String, bool)> {
    sqlx::query("SELECT j.status, j.cancel_requested FROM jobs j JOIN job_children c ON c.job_id = j.id WHERE c.parent_id = $1 ORDER BY c.idx")
        .bind(parent)
        .fetch_all(db)
        .await
        .unwrap()
        .iter()
        .map(|r| (r.get(0), r.get(1)))
        .collect()
}

/// The status and cancel flag of each case job linked to both `a` and `b`.
async fn shared_states(db: &mut sqlx::PgConnection, a: &str, b: &str) -> Vec<(String, bool)> {
    sqlx::query(
        "SELECT j.status, j.cancel_requested FROM jobs j JOIN job_children x ON x.job_id = j.id \
         JOIN job_children y ON y.job_id = j.id WHERE x.parent_id = $1 AND y.parent_id = $2 ORDER BY x.idx",
    )
    .bind(a)
    .bind(b)
    .fetch_all(db)
    .await
    .unwrap()
    .iter()
    .map(|r| (r.get(0), r.get(1)))
    .collect()
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_case_shared_by_two_sweeps_is_canceled_only_when_both_are() {
    if !postgres_available("a_case_shared_by_two_sweeps_is_canceled_only_when_both_are") {
        return;
    }
    let url = fresh_postgres_database().await;
    let opts = ["--lease-seconds", "2", "--fan-out-min-case-seconds", "0.05"];
    let a = Instance::serve(&url, &[&["--workers", "0"][..], &opts].concat());
    let client = reqwest::Client::new();
    // The same eight cases and two more (not the same sweep: that would be the first one,
    // joined), queued on an instance without workers, then claimed together by a worker of two
    // threads, so that both fan out before the cases run (one after the other, the second would
    // wait behind the first's cases: they keep its earlier place in the fair order). Whichever
    // creates a case, the other joins it.
    let first = post(&client, &a.base, &sleep_sweep(8, 2.0, 900), "").await["id"].as_str().unwrap().to_string();
    let second = post(&client, &a.base, &sleep_sweep(10, 2.0, 900), "").await["id"].as_str().unwrap().to_string();
    assert_ne!(first, second);
    let _w = Instance::worker(&url, &[&["--workers", "2"][..], &opts].concat());
    fanned_out(&client, &a.base, &first, 8).await;
    fanned_out(&client, &a.base, &second, 10).await;
    let mut db = sqlx::PgConnection::connect(&url).await.unwrap();
    // Cancel first the sweep that created more of the shared cases (the other joined them).
    let owned = |p: &str| {
        sqlx::query("SELECT count(*) FROM job_children a JOIN job_children b ON a.job_id = b.job_id WHERE a.parent_id = $1 AND a.owned AND b.parent_id <> $1")
            .bind(p.to_string())
    };
    let first_owns: i64 = owned(&first).fetch_one(&mut db).await.unwrap().get(0);
    let second_owns: i64 = owned(&second).fetch_one(&mut db).await.unwrap().get(0);
    assert_eq!(first_owns + second_owns, 8, "eight shared cases, each created once");
    let (first, second) = if first_owns >= second_owns { (first, second) } else { (second, first) };
    let open = |s: &[(String, bool)]| s.iter().filter(|(st, _)| st == "queued" || st == "running").count();
    assert!(open(&shared_states(&mut db, &first, &second).await) >= 4);

    let res = client.delete(format!("{}/v1/jobs/{first}", a.base)).send().await.unwrap();
    assert!(res.status().is_success());
    assert_eq!(finished(&client, &a.base, &first, Duration::from_secs(3)).await["status"], "canceled");
    let after = shared_states(&mut db, &first, &second).await;
    assert!(after.iter().all(|(st, flag)| st != "canceled" && !flag), "the second sweep still needs them: {after:?}");
    assert!(open(&after) >= 3, "{after:?}");

    // The last parent's cancel reaches the shared cases (it created none of them).
    let asked = Instant::now();
    let res = client.delete(format!("{}/v1/jobs/{second}", a.base)).send().await.unwrap();
    assert!(res.status().is_success());
    loop {
        let now = shared_states(&mut db, &first, &second).await;
        if open(&now) == 0 && open(&case_states(&mut db, &second).await) == 0 {
            break;
        }
        assert!(asked.elapsed() < Duration::from_secs(3), "cases still open: {now:?}");
        tokio::time::sleep(Duration::from_millis(20)).await;
    }
    assert_eq!(finished(&client, &a.base, &second, Duration::from_secs(3)).await["status"], "canceled");
    let _ = db.close().await;
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_sweep_whose_assembler_died_is_reassembled_elsewhere_with_the_same_result() {
    if !postgres_available("a_sweep_whose_assembler_died_is_reassembled_elsewhere_with_the_same_result") {
        return;
    }
    let url = fresh_postgres_database().await;
    let client = reqwest::Client::new();
    let a = Instance::serve(&url, OPTS);
    let id = post(&client, &a.base, &sleep_sweep(4, 0.1, 1000), "").await["id"].as_str().unwrap().to_string();
    let done = finished(&client, &a.base, &id, Duration::from_secs(10)).await;
    assert_eq!(done["status"], "succeeded", "{done}");
    let mut before = result(&client, &a.base, &id).await;
    before.as_object_mut().unwrap().remove("meta");
    drop(a);
    let mut db = sqlx::PgConnection::connect(&url).await.unwrap();
    let attempts: i64 = sqlx::query("SELECT attempts FROM jobs WHERE id = $1").bind(&id).fetch_one(&mut db).await.unwrap().get(0);
    assert_eq!(attempts, 1, "fanning out is not counted as an attempt, assembling is");
    // The row as an instance leaves it when it is killed (-9) while assembling: its cases all
    // finished, the parent claimed again (running, leased by the dead instance), no result. The
    // exact instant of a real kill inside an assembly of milliseconds cannot be hit from outside.
    sqlx::query(
        "UPDATE jobs SET status = 'running', finished_at = NULL, solved_by = NULL, lease_owner = 'killed-9', \
         lease_until = 1, attempts = attempts + 1 WHERE id = $1",
    )
    .bind(&id)
    .execute(&mut db)
    .await
    .unwrap();
    sqlx::query("DELETE FROM job_results WHERE job_id = $1").bind(&id).execute(&mut db).await.unwrap();
    let b = Instance::serve(&url, OPTS);
    let again = finished(&client, &b.base, &id, Duration::from_secs(10)).await;
    assert_eq!(again["status"], "succeeded", "{again}");
    let mut after = result(&client, &b.base, &id).await;
    after.as_object_mut().unwrap().remove("meta");
    assert_eq!(after, before, "reassembled: the same table, the same instance per case");
    let solved: i64 = sqlx::query("SELECT count(*) FROM jobs WHERE kind = 'test_sleep'").fetch_one(&mut db).await.unwrap().get(0);
    assert_eq!(solved, 4, "no case solved again");
    let _ = db.close().await;
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_cancel_reaches_the_cases_a_dead_fan_out_made_before_its_retry() {
    if !postgres_available("a_cancel_reaches_the_cases_a_dead_fan_out_made_before_its_retry") {
        return;
    }
    let url = fresh_postgres_database().await;
    let client = reqwest::Client::new();
    let a = Instance::serve(&url, OPTS);
    let id = post(&client, &a.base, &sleep_sweep(6, 1.0, 1100), "").await["id"].as_str().unwrap().to_string();
    fanned_out(&client, &a.base, &id, 6).await;
    // As an instance leaves it when killed after inserting the cases, before recording them (one
    // statement, at the end): the cases queued or running, no children, the parent leased by the
    // dead instance. The retry joins the cases; they are still the sweep's own.
    let mut db = sqlx::PgConnection::connect(&url).await.unwrap();
    sqlx::query("DELETE FROM job_children WHERE parent_id = $1").bind(&id).execute(&mut db).await.unwrap();
    sqlx::query("UPDATE jobs SET lease_owner = 'killed-9', lease_until = 1, stage = NULL WHERE id = $1")
        .bind(&id)
        .execute(&mut db)
        .await
        .unwrap();
    fanned_out(&client, &a.base, &id, 6).await;
    let made: i64 = sqlx::query("SELECT count(*) FROM jobs WHERE kind = 'test_sleep'").fetch_one(&mut db).await.unwrap().get(0);
    assert_eq!(made, 6, "the retry made no case twice");
    let res = client.delete(format!("{}/v1/jobs/{id}", a.base)).send().await.unwrap();
    assert!(res.status().is_success());
    let asked = Instant::now();
    loop {
        let states = case_states(&mut db, &id).await;
        if states.iter().all(|(st, _)| st != "queued" && st != "running") {
            break;
        }
        assert!(asked.elapsed() < Duration::from_secs(3), "cases still open: {states:?}");
        tokio::time::sleep(Duration::from_millis(20)).await;
    }
    assert_eq!(finished(&client, &a.base, &id, Duration::from_secs(3)).await["status"], "canceled");
    let _ = db.close().await;
}
