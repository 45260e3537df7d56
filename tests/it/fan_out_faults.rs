//! Fan-out under faults (issue 44), with real `tribod` processes: the instance that creates a
//! sweep's cases, or the one that assembles it, killed with SIGKILL at that very point (test
//! builds pause there when an environment variable asks, so the kill lands where it must); and
//! the races of a join with a cancel — a sweep identical to one being canceled, and a sweep that
//! joined cases just before their other sweep's cancel reached them.
//!
//! The kill tests need `TRIBOD_TEST_POSTGRES_URL` (several instances); the races run on SQLite,
//! and on PostgreSQL too when it is there.

use crate::common::*;
use crate::fan_out::*;
use crate::multi_instance::Instance;
use sqlx::{Connection, Row};
use std::time::{Duration, Instant};

/// Pause points of test builds (see `jobs::queue::fanout::test_pause`).
const PAUSE_BEFORE_RECORDING: &str = "TRIBOD_TEST_PAUSE_BEFORE_RECORDING_CASES_MS";
const PAUSE_IN_ASSEMBLY: &str = "TRIBOD_TEST_PAUSE_IN_ASSEMBLY_MS";

/// `(status, lease_owner, attempts)` of a job.
async fn lease_of(db: &mut sqlx::PgConnection, id: &str) -> (String, Option<String>, i64) {
    let r = sqlx::query("SELECT status, lease_owner, attempts FROM jobs WHERE id = $1").bind(id).fetch_one(db).await.unwrap();
    (r.get(0), r.get(1), r.get(2))
}

/// `(case jobs, case jobs started more than once)` of kind `test_sleep`.
async fn case_jobs(db: &mut sqlx::PgConnection) -> (i64, i64) {
    let r = sqlx::query("SELECT count(*), count(*) FILTER (WHERE attempts > 1) FROM jobs WHERE kind = 'test_sleep'")
        .fetch_one(db)
        .await
        .unwrap();
    (r.get(0), r.get(1))
}

/// Poll `check` (true: done) every 20 ms for up to `secs` seconds.
async fn poll<F: std::future::Future<Output = bool>>(what: &str, secs: u64, mut check: impl FnMut() -> F) {
    let deadline = Instant::now() + Duration::from_secs(secs);
    while !check().await {
        assert!(Instant::now() < deadline, "{what}");
        tokio::time::sleep(Duration::from_millis(20)).await;
    }
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn kill_9_of_the_instance_creating_the_cases_loses_none_and_makes_none_twice() {
    if !postgres_available("kill_9_of_the_instance_creating_the_cases_loses_none_and_makes_none_twice") {
        return;
    }
    let url = fresh_postgres_database().await;
    let client = reqwest::Client::new();
    // A alone claims the sweep; it inserts the 40 cases, then (test pause) holds them unrecorded.
    let mut a = Instance::serve_with_env(&url, OPTS, &[(PAUSE_BEFORE_RECORDING, "60000")]);
    let job = sleep_sweep(40, 0.2, 1);
    let id = post(&client, &a.base, &job, "").await["id"].as_str().unwrap().to_string();
    let mut db = sqlx::PgConnection::connect(&url).await.unwrap();
    let pid = format!("/{}/", a.child.id());
    let mut made = 0;
    let deadline = Instant::now() + Duration::from_secs(30);
    while made < 40 {
        made = case_jobs(&mut db).await.0;
        assert!(Instant::now() < deadline, "A made {made} cases");
        tokio::time::sleep(Duration::from_millis(20)).await;
    }
    let (status, owner, _) = lease_of(&mut db, &id).await;
    assert_eq!(status, "running");
    assert!(owner.is_some_and(|o| o.contains(&pid)), "A holds the sweep while it creates its cases");
    // The others solve the cases meanwhile; A dies before recording them.
    let b = Instance::serve(&url, OPTS);
    let _c = Instance::worker(&url, OPTS);
    tokio::time::sleep(Duration::from_millis(300)).await;
    a.child.kill().unwrap();
    a.child.wait().unwrap();

    let done = finished(&client, &b.base, &id, Duration::from_secs(90)).await;
    assert_eq!(done["status"], "succeeded", "{done}");
    assert_eq!(done["children"]["total"], 40, "{done}");
    let r = result(&client, &b.base, &id).await;
    assert_eq!(r["succeeded"], 40, "no case lost: {r}");
    assert_eq!(case_jobs(&mut db).await, (40, 0), "the retry joined or reused A's cases; A held none of them");
    assert_eq!(comparable(r), comparable(single_instance_result(&client, &job).await));
    let _ = db.close().await;
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn kill_9_of_the_instance_assembling_the_sweep_solves_no_case_again() {
    if !postgres_available("kill_9_of_the_instance_assembling_the_sweep_solves_no_case_again") {
        return;
    }
    let url = fresh_postgres_database().await;
    let client = reqwest::Client::new();
    // A alone fans out and solves the six cases, then (test pause) assembles slowly.
    let mut a = Instance::serve_with_env(&url, OPTS, &[(PAUSE_IN_ASSEMBLY, "60000")]);
    let job = sleep_sweep(6, 0.1, 500);
    let id = post(&client, &a.base, &job, "").await["id"].as_str().unwrap().to_string();
    let mut db = sqlx::PgConnection::connect(&url).await.unwrap();
    let pid = format!("/{}/", a.child.id());
    let deadline = Instant::now() + Duration::from_secs(30);
    loop {
        let children = get(&client, &a.base, &id).await["children"].clone();
        let (status, owner, _) = lease_of(&mut db, &id).await;
        if children["succeeded"] == 6 && status == "running" && owner.as_deref().is_some_and(|o| o.contains(&pid)) {
            break;
        }
        assert!(Instant::now() < deadline, "A never assembled: {children} {status} {owner:?}");
        tokio::time::sleep(Duration::from_millis(20)).await;
    }
    let b = Instance::serve(&url, OPTS);
    a.child.kill().unwrap();
    a.child.wait().unwrap();

    let done = finished(&client, &b.base, &id, Duration::from_secs(60)).await;
    assert_eq!(done["status"], "succeeded", "{done}");
    let r = result(&client, &b.base, &id).await;
    assert_eq!(r["succeeded"], 6, "{r}");
    assert!(r["cases"].as_array().unwrap().iter().all(|c| c["instance"].as_str().unwrap().contains(&pid)), "A solved every case: {r}");
    assert_eq!(case_jobs(&mut db).await, (6, 0), "no case solved again");
    assert_eq!(comparable(r), comparable(single_instance_result(&client, &job).await));
    let _ = db.close().await;
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_cancel_mid_sweep_stops_its_cases_on_three_instances_within_a_second() {
    if !postgres_available("a_cancel_mid_sweep_stops_its_cases_on_three_instances_within_a_second") {
        return;
    }
    let url = fresh_postgres_database().await;
    let a = Instance::serve(&url, OPTS);
    let b = Instance::serve(&url, OPTS);
    let _c = Instance::worker(&url, OPTS);
    let client = reqwest::Client::new();
    let id = post(&client, &a.base, &sleep_sweep(40, 1.0, 1200), "").await["id"].as_str().unwrap().to_string();
    let mut db = sqlx::PgConnection::connect(&url).await.unwrap();
    let mut owners = 0;
    let deadline = Instant::now() + Duration::from_secs(20);
    while owners < 3 {
        owners = sqlx::query("SELECT count(DISTINCT lease_owner) FROM jobs WHERE kind = 'test_sleep' AND status = 'running'")
            .fetch_one(&mut db)
            .await
            .unwrap()
            .get::<i64, _>(0);
        assert!(Instant::now() < deadline, "cases never ran on all three instances ({owners})");
        tokio::time::sleep(Duration::from_millis(20)).await;
    }
    let asked = Instant::now();
    let res = client.delete(format!("{}/v1/jobs/{id}", b.base)).send().await.unwrap();
    assert!(res.status().is_success(), "{}", res.status());
    let (c, base, idr) = (&client, &a.base, &id);
    poll("cases still open", 10, || async move {
        get(c, base, idr).await["children"].as_object().is_some_and(|c| c["queued"] == 0 && c["running"] == 0)
    })
    .await;
    let took = asked.elapsed();
    eprintln!("cancel of the sweep reached its cases on three instances in {took:?}");
    assert!(took < Duration::from_millis(1500), "cancel took {took:?}");
    let job = get(&client, &a.base, &id).await;
    assert_eq!(job["status"], "canceled", "{job}");
    assert_eq!(job["children"]["failed"], 40, "{job}");
    let _ = db.close().await;
}

/// A database URL of `backend` (a temp file for SQLite) and the directory that holds it.
async fn store(postgres: bool, dir: &tempfile::TempDir) -> String {
    if postgres {
        fresh_postgres_database().await
    } else {
        dir.path().join("race.db").to_str().unwrap().to_string()
    }
}

/// A sweep identical to one being canceled is not joined to it: it waits for it to stop and runs.
async fn identical_sweep_during_cancel(postgres: bool) {
    let dir = tempfile::tempdir().unwrap();
    let url = store(postgres, &dir).await;
    // Cases below the crossover: the sweep runs in-process and stops at its next case.
    let a = Instance::serve(&url, &["--workers", "1", "--lease-seconds", "2", "--fan-out-min-case-seconds", "10"]);
    let client = reqwest::Client::new();
    let job = sleep_sweep(6, 0.5, 1300);
    let first = post(&client, &a.base, &job, "").await["id"].as_str().unwrap().to_string();
    let (c, base, idr) = (&client, &a.base, &first);
    poll("the sweep never ran", 30, || async move { get(c, base, idr).await["status"] == "running" }).await;
    let res = client.delete(format!("{}/v1/jobs/{first}", a.base)).send().await.unwrap();
    assert!(res.status().is_success());
    let second = post(&client, &a.base, &job, "").await;
    let second = second["id"].as_str().unwrap().to_string();
    assert_ne!(second, first, "not joined to a sweep being canceled");
    assert_eq!(finished(&client, &a.base, &first, Duration::from_secs(10)).await["status"], "canceled");
    let done = finished(&client, &a.base, &second, Duration::from_secs(60)).await;
    assert_eq!(done["status"], "succeeded", "{done}");
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_sweep_identical_to_one_being_canceled_runs_on_its_own() {
    identical_sweep_during_cancel(false).await;
    if postgres_available("a_sweep_identical_to_one_being_canceled_runs_on_its_own") {
        identical_sweep_during_cancel(true).await;
    }
}

/// Sweep Y joins the two running cases of sweep X and (test pause) records them only after X's
/// cancel, which found no other live parent of them and canceled them: Y solves them again and
/// succeeds. Three workers: X's fan-out pauses too (one slot) while its two cases run (two slots);
/// then Y takes the free slot.
async fn join_before_the_cancel_of_the_other_sweep(postgres: bool) {
    let dir = tempfile::tempdir().unwrap();
    let url = store(postgres, &dir).await;
    let opts = ["--workers", "3", "--lease-seconds", "2", "--fan-out-min-case-seconds", "0.05"];
    let a = Instance::serve_with_env(&url, &opts, &[(PAUSE_BEFORE_RECORDING, "2000")]);
    let client = reqwest::Client::new();
    let x = post(&client, &a.base, &sleep_sweep(2, 4.0, 1400), "").await["id"].as_str().unwrap().to_string();
    fanned_out(&client, &a.base, &x, 2).await;
    let y = post(&client, &a.base, &sleep_sweep(4, 4.0, 1400), "").await["id"].as_str().unwrap().to_string();
    // Y has made its two own cases (and looked up X's two): it pauses before recording them.
    let (c, base) = (&client, &a.base);
    poll("Y never made its cases", 30, || async move { listed(c, base, "?kind=test_sleep&cases=true").await.len() >= 4 }).await;
    let res = client.delete(format!("{}/v1/jobs/{x}", a.base)).send().await.unwrap();
    assert!(res.status().is_success());
    assert_eq!(finished(&client, &a.base, &x, Duration::from_secs(10)).await["status"], "canceled");
    let done = finished(&client, &a.base, &y, Duration::from_secs(120)).await;
    assert_eq!(done["status"], "succeeded", "{done}");
    let r = result(&client, &a.base, &y).await;
    assert_eq!((r["succeeded"].as_i64(), r["failed"].as_i64()), (Some(4), Some(0)), "no row of Y canceled by X's cancel: {r}");
    let made = listed(&client, &a.base, "?kind=test_sleep&cases=true").await.len();
    eprintln!("join vs cancel ({}): {made} case jobs for 4 distinct cases (6: X's two solved again for Y)", if postgres { "PostgreSQL" } else { "SQLite" });
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_case_joined_just_before_its_other_sweeps_cancel_is_solved_again() {
    join_before_the_cancel_of_the_other_sweep(false).await;
    if postgres_available("a_case_joined_just_before_its_other_sweeps_cancel_is_solved_again") {
        join_before_the_cancel_of_the_other_sweep(true).await;
    }
}
