//! Several tribod instances on one PostgreSQL database (issue 12): one job list, one claim per
//! job, leases that move the jobs of a killed instance to the others, cancellation across
//! instances, and identical submissions racing on different instances solved once.
//!
//! Every test here needs `TRIBOD_TEST_POSTGRES_URL` (set by `.ci/run`); without it each says
//! SKIPPED on stderr and passes. Each test creates its own database.

use crate::common::*;
use serde_json::{json, Value};
use sqlx::{Connection, Executor, Row};
use std::collections::{HashMap, HashSet};
use std::io::{BufRead, BufReader};
use std::process::{Child, Command, Stdio};
use std::sync::Arc;
use std::time::{Duration, Instant};

/// A `tribod` child process, killed (SIGKILL) when dropped.
pub(crate) struct Instance {
    pub(crate) child: Child,
    /// `http://addr` of a `serve` instance; empty for a `worker`.
    pub(crate) base: String,
}

impl Drop for Instance {
    fn drop(&mut self) {
        let _ = self.child.kill();
        let _ = self.child.wait();
    }
}

impl Instance {
    /// `tribod serve` on `url`; returns once it listens (its migrations have run).
    pub(crate) fn serve(url: &str, extra: &[&str]) -> Instance {
        Self::serve_with_env(url, extra, &[])
    }

    /// `tribod serve` with extra environment variables (the test builds' pause points).
    pub(crate) fn serve_with_env(url: &str, extra: &[&str], env: &[(&str, &str)]) -> Instance {
        let mut child = Command::new(env!("CARGO_BIN_EXE_tribod"))
            .args(["serve", "--addr", "127.0.0.1:0", "--database-url", url])
            .args(extra)
            .envs(env.iter().copied())
            .env("RUST_LOG", "warn")
            .stdout(Stdio::piped())
            .stderr(Stdio::null())
            .spawn()
            .expect("spawn tribod serve");
        let mut line = String::new();
        BufReader::new(child.stdout.take().unwrap()).read_line(&mut line).expect("listening line");
        let base = line.trim().strip_prefix("tribod listening on ").expect("listening line format").to_string();
        Instance { child, base }
    }

    /// `tribod worker` on `url`; returns once its queue runs.
    pub(crate) fn worker(url: &str, extra: &[&str]) -> Instance {
        let mut child = Command::new(env!("CARGO_BIN_EXE_tribod"))
            .args(["worker", "--database-url", url, "--log-format", "json"])
            .args(extra)
            .env("RUST_LOG", "info")
            .stdout(Stdio::null())
            .stderr(Stdio::piped())
            .spawn()
            .expect("spawn tribod worker");
        let mut lines = BufReader::new(child.stderr.take().unwrap()).lines();
        loop {
            let line = lines.next().expect("worker log line").expect("worker log line");
            if line.contains("tribod worker running") {
                break;
            }
        }
        // Keep draining its log so the worker never blocks on a full pipe.
        std::thread::spawn(move || for _ in lines {});
        Instance { child, base: String::new() }
    }
}

/// Record every terminal status change and every result write, so a test can prove that each job
/// finished exactly once.
async fn install_finish_log(url: &str) {
    let mut conn = sqlx::PgConnection::connect(url).await.expect("connect");
    conn.execute(
        "CREATE TABLE finish_log (job_id TEXT NOT NULL, what TEXT NOT NULL);
         CREATE FUNCTION log_finish() RETURNS trigger AS $$
         BEGIN
             IF TG_TABLE_NAME = 'jobs' THEN
                 INSERT INTO finish_log VALUES (NEW.id, NEW.status);
             ELSE
                 INSERT INTO finish_log VALUES (NEW.job_id, 'result');
             END IF;
             RETURN NEW;
         END $$ LANGUAGE plpgsql;
         CREATE TRIGGER jobs_finish AFTER UPDATE OF status ON jobs FOR EACH ROW
             WHEN (OLD.status IS DISTINCT FROM NEW.status AND NEW.status IN ('succeeded', 'failed', 'canceled'))
             EXECUTE FUNCTION log_finish();
         CREATE TRIGGER results_write AFTER INSERT OR UPDATE ON job_results FOR EACH ROW
             EXECUTE FUNCTION log_finish();",
    )
    .await
    .expect("install the finish log");
    let _ = conn.close().await;
}

/// The i-th job of the mixed load: short sleeps, Hertz contacts and small cam cycles, all distinct.
fn mixed_job(i: usize) -> Value {
    match i % 3 {
        0 => sleep_job(0.02 + 0.02 * (i % 5) as f64, i as u64),
        1 => hertz_job(100.0 + i as f64),
        _ => {
            let mut job: Value =
                serde_json::from_str(include_str!("../../examples/seed000_roller_steady.json")).unwrap();
            job["spec"]["operation"]["speed_rpm"] = json!(500.0 + i as f64);
            job["spec"]["angles"] = json!(90);
            job
        }
    }
}

/// POST `job` to `base`; the job id if it was acknowledged (202/200), else None.
async fn submit(client: &reqwest::Client, base: &str, job: &Value) -> Option<String> {
    let res = client.post(format!("{base}/v1/jobs")).json(job).send().await.ok()?;
    if !res.status().is_success() {
        return None;
    }
    let body: Value = res.json().await.ok()?;
    body["id"].as_str().map(str::to_string)
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn three_instances_share_one_queue_and_a_killed_one_loses_nothing() {
    if !postgres_available("three_instances_share_one_queue_and_a_killed_one_loses_nothing") {
        return;
    }
    let url = fresh_postgres_database().await;
    let lease = ["--workers", "1", "--lease-seconds", "2", "--max-attempts", "5"];
    let a = Instance::serve(&url, &lease);
    install_finish_log(&url).await;
    let mut b = Instance::serve(&url, &lease);
    let _c = Instance::worker(&url, &lease);
    let client = reqwest::Client::new();

    // 300 jobs, submitted alternately to A and B, 6 at a time; B is killed (SIGKILL) after the
    // 120th submission while it runs a job, and started again. A submission that B never answered is sent to A.
    let mut acknowledged: Vec<String> = Vec::new();
    let mut killed_at = None;
    let mut marker_count = 0;
    let mut i = 0;
    while i < 300 {
        if i >= 120 && killed_at.is_none() {
            // Kill B while it runs one of our 2 s marker jobs (its lease owner is
            // `host/pid/random`): a marker is submitted every second until B has claimed one, so
            // the kill cannot fall between two jobs.
            let owner = format!("%/{}/%", b.child.id());
            let mut db = sqlx::PgConnection::connect(&url).await.unwrap();
            let mut markers: Vec<String> = Vec::new();
            let deadline = Instant::now() + Duration::from_secs(60);
            let mut last_marker = Instant::now() - Duration::from_secs(10);
            loop {
                if last_marker.elapsed() >= Duration::from_secs(1) {
                    let nonce = 10_000 + markers.len() as u64;
                    markers.push(submit(&client, &a.base, &sleep_job(2.0, nonce)).await.unwrap());
                    last_marker = Instant::now();
                }
                let held: i64 = sqlx::query(
                    "SELECT count(*) FROM jobs WHERE status = 'running' AND lease_owner LIKE $1 AND id = ANY($2)",
                )
                .bind(&owner)
                .bind(&markers)
                .fetch_one(&mut db)
                .await
                .unwrap()
                .get(0);
                if held > 0 {
                    break;
                }
                assert!(Instant::now() < deadline, "B never ran a marker job");
                tokio::time::sleep(Duration::from_millis(5)).await;
            }
            marker_count = markers.len();
            acknowledged.extend(markers);
            let _ = db.close().await;
            b.child.kill().unwrap();
            b.child.wait().unwrap();
            killed_at = Some(Instant::now());
            b = Instance::serve(&url, &lease);
        }
        let batch: Vec<(usize, String)> =
            (i..(i + 6).min(300)).map(|k| (k, if k % 2 == 0 { a.base.clone() } else { b.base.clone() })).collect();
        let handles: Vec<_> = batch
            .into_iter()
            .map(|(k, base)| {
                let client = client.clone();
                let fallback = a.base.clone();
                tokio::spawn(async move {
                    let job = mixed_job(k);
                    match submit(&client, &base, &job).await {
                        Some(id) => Some(id),
                        None => submit(&client, &fallback, &job).await,
                    }
                })
            })
            .collect();
        for h in handles {
            acknowledged.push(h.await.unwrap().expect("every job is acknowledged by A or B"));
        }
        i += 6;
    }
    assert!(killed_at.is_some());
    let total = 300 + marker_count;
    assert_eq!(acknowledged.len(), total);
    assert_eq!(acknowledged.iter().collect::<HashSet<_>>().len(), total, "{total} distinct jobs");

    // Everything finishes: the killed instance's running job is re-queued when its 2 s lease ends.
    let mut db = sqlx::PgConnection::connect(&url).await.unwrap();
    let deadline = Instant::now() + Duration::from_secs(180);
    loop {
        let open: i64 = sqlx::query("SELECT count(*) FROM jobs WHERE status IN ('queued', 'running')")
            .fetch_one(&mut db)
            .await
            .unwrap()
            .get(0);
        if open == 0 {
            break;
        }
        assert!(Instant::now() < deadline, "{open} jobs still open after 180 s");
        tokio::time::sleep(Duration::from_millis(200)).await;
    }

    let rows = sqlx::query("SELECT id, status, attempts FROM jobs").fetch_all(&mut db).await.unwrap();
    let status: HashMap<String, (String, i64)> =
        rows.iter().map(|r| (r.get::<String, _>(0), (r.get::<String, _>(1), r.get::<i64, _>(2)))).collect();
    for id in &acknowledged {
        let (s, _) = status.get(id).unwrap_or_else(|| panic!("acknowledged job {id} is not stored"));
        assert_eq!(s, "succeeded", "job {id}");
    }
    let max_attempts = status.values().map(|(_, a)| *a).max().unwrap();
    assert!(max_attempts >= 2, "the job B was running when killed ran again (max attempts {max_attempts})");

    // Exactly once: one terminal status change and one result write per job.
    let log = sqlx::query("SELECT job_id, what, count(*) FROM finish_log GROUP BY job_id, what")
        .fetch_all(&mut db)
        .await
        .unwrap();
    let mut finishes: HashMap<(String, String), i64> = HashMap::new();
    for r in &log {
        finishes.insert((r.get(0), r.get(1)), r.get(2));
    }
    for id in &acknowledged {
        assert_eq!(finishes.get(&(id.clone(), "succeeded".into())), Some(&1), "job {id} finished once");
        assert_eq!(finishes.get(&(id.clone(), "result".into())), Some(&1), "job {id} result written once");
    }
    assert!(finishes.keys().all(|(_, what)| what == "succeeded" || what == "result"), "{finishes:?}");

    // One job list: a job submitted to A is served, with its result, by the restarted B.
    let sample = &acknowledged[0];
    let job: Value = client.get(format!("{}/v1/jobs/{sample}", b.base)).send().await.unwrap().json().await.unwrap();
    assert_eq!(job["status"], "succeeded");
    let res = client.get(format!("{}/v1/jobs/{sample}/result", b.base)).send().await.unwrap();
    assert_eq!(res.status(), 200);
    let _ = db.close().await;
}

/// In-process servers on one PostgreSQL database.
async fn servers_on(url: &str, workers: &[usize]) -> Vec<TestServer> {
    let mut out = Vec::new();
    for &w in workers {
        let dir = tempfile::tempdir().unwrap();
        let mut cfg = config(&dir);
        cfg.database_url = url.to_string();
        cfg.queue.workers = w;
        cfg.shutdown_grace = Duration::from_millis(500);
        out.push(start_in(dir, cfg).await);
    }
    out
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_cancel_on_one_instance_stops_the_job_running_on_another() {
    if !postgres_available("a_cancel_on_one_instance_stops_the_job_running_on_another") {
        return;
    }
    let url = fresh_postgres_database().await;
    // A answers the API only; B solves.
    let servers = servers_on(&url, &[0, 1]).await;
    let (a, b) = (&servers[0], &servers[1]);
    let job: Value = a.post_job(&sleep_job(60.0, 7)).await.json().await.unwrap();
    let id = job["id"].as_str().unwrap().to_string();
    let running = a.wait_status(&id, "running", Duration::from_secs(10)).await;
    assert_eq!(running["status"], "running", "B claimed the job A accepted");

    let asked = Instant::now();
    let res = a.client.delete(a.url(&format!("/v1/jobs/{id}"))).send().await.unwrap();
    assert!(res.status().is_success(), "{}", res.status());
    let done = b.wait_status(&id, "canceled", Duration::from_secs(10)).await;
    let took = asked.elapsed();
    assert_eq!(done["status"], "canceled", "{done}");
    assert!(took < Duration::from_secs(2), "cancel crossed instances in {took:?} (lease renewal every 0.5 s)");
    for s in servers {
        s.stop().await;
    }
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn identical_submissions_racing_on_three_instances_are_solved_once() {
    if !postgres_available("identical_submissions_racing_on_three_instances_are_solved_once") {
        return;
    }
    let url = fresh_postgres_database().await;
    let servers = Arc::new(servers_on(&url, &[1, 1, 1]).await);
    install_finish_log(&url).await;
    let job = sleep_job(0.3, 4242);
    let handles: Vec<_> = (0..30)
        .map(|k| {
            let servers = servers.clone();
            let job = job.clone();
            tokio::spawn(async move {
                let s = &servers[k % 3];
                let res = s.post_job(&job).await;
                assert!(res.status().is_success(), "{}", res.status());
                let body: Value = res.json().await.unwrap();
                body["id"].as_str().unwrap().to_string()
            })
        })
        .collect();
    let mut ids = HashSet::new();
    for h in handles {
        ids.insert(h.await.unwrap());
    }
    assert_eq!(ids.len(), 1, "30 identical submissions on 3 instances name one job: {ids:?}");
    let id = ids.into_iter().next().unwrap();
    let done = servers[2].wait_finished(&id, Duration::from_secs(20)).await;
    assert_eq!(done["status"], "succeeded");

    let mut db = sqlx::PgConnection::connect(&url).await.unwrap();
    let jobs: i64 = sqlx::query("SELECT count(*) FROM jobs").fetch_one(&mut db).await.unwrap().get(0);
    let solves: i64 = sqlx::query("SELECT count(*) FROM finish_log WHERE what = 'result'")
        .fetch_one(&mut db)
        .await
        .unwrap()
        .get(0);
    assert_eq!((jobs, solves), (1, 1), "one job row, one solve");
    let _ = db.close().await;
    for s in Arc::into_inner(servers).unwrap() {
        s.stop().await;
    }
}

/// Issue 46: a running job's lease renewals and progress updates are HOT updates on PostgreSQL —
/// no index entry written, the row's new version on its own page — so the queue's cost per running
/// second is a page write, not a page and an index write per index. While three 2-s jobs ran
/// (renewals every 0.5 s, progress batched), the only updates of `jobs` that were not HOT are the
/// claims and the finishes, which change `status`.
#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn lease_renewals_and_progress_are_hot_updates() {
    if !postgres_available("lease_renewals_and_progress_are_hot_updates") {
        return;
    }
    let url = fresh_postgres_database().await;
    let servers = servers_on(&url, &[3]).await;
    let s = &servers[0];
    let mut ids = Vec::new();
    for i in 0..3 {
        let job: Value = s.post_job(&sleep_job(2.0, 4600 + i)).await.json().await.unwrap();
        ids.push(job["id"].as_str().unwrap().to_string());
    }
    for id in &ids {
        let done = s.wait_status(id, "succeeded", Duration::from_secs(20)).await;
        assert_eq!(done["status"], "succeeded", "{done}");
    }
    // The server's database sessions end with it and hand their statistics over as they exit.
    for s in servers {
        s.stop().await;
    }
    let mut conn = sqlx::PgConnection::connect(&url).await.unwrap();
    let deadline = Instant::now() + Duration::from_secs(10);
    let (updates, hot) = loop {
        let row = conn.fetch_one("SELECT n_tup_upd, n_tup_hot_upd FROM pg_stat_user_tables WHERE relname = 'jobs'").await.unwrap();
        let (updates, hot): (i64, i64) = (row.get(0), row.get(1));
        if updates >= 12 || Instant::now() > deadline {
            break (updates, hot);
        }
        tokio::time::sleep(Duration::from_millis(200)).await;
    };
    eprintln!("jobs: {updates} row updates, {hot} HOT");
    let claims_and_finishes = 2 * ids.len() as i64;
    assert!(updates >= claims_and_finishes + 6, "renewals and progress updates were made: {updates} updates in all");
    assert_eq!(updates - hot, claims_and_finishes, "{updates} updates, {hot} HOT: only the claims and finishes may touch an index");
}

/// Issue 46 item 5: a finish claims the next jobs for the slots it frees in the same commit, and
/// short jobs (estimated ≤ 10 ms) also take short-job slots. Two instances of 2 workers and 2
/// short-job slots drain 120 jobs (long: sleeping 20 ms; short: sleeping 5 ms, or Hertz) while
/// a trigger records, at every claim, how many jobs the claiming instance then holds: never
/// more than its 4 slots, never more long jobs than its 2 workers (a claim is a start), the
/// short slots used, and every job finished exactly once.
#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn finishes_that_claim_the_next_jobs_never_hold_more_than_the_workers() {
    if !postgres_available("finishes_that_claim_the_next_jobs_never_hold_more_than_the_workers") {
        return;
    }
    let url = fresh_postgres_database().await;
    let mut servers = Vec::new();
    for _ in 0..2 {
        let dir = tempfile::tempdir().unwrap();
        let mut cfg = config(&dir);
        cfg.database_url = url.to_string();
        cfg.queue.workers = 2;
        cfg.queue.short_slots = 2;
        cfg.shutdown_grace = Duration::from_millis(500);
        servers.push(start_in(dir, cfg).await);
    }
    install_finish_log(&url).await;
    let mut conn = sqlx::PgConnection::connect(&url).await.unwrap();
    conn.execute(
        "CREATE TABLE claim_log (owner TEXT NOT NULL, held BIGINT NOT NULL, held_long BIGINT NOT NULL);
         CREATE FUNCTION log_claim() RETURNS trigger AS $$
         BEGIN
             INSERT INTO claim_log SELECT NEW.lease_owner, count(*), count(*) FILTER (WHERE NOT COALESCE(estimate_cpu_seconds <= 0.01, FALSE))
                 FROM jobs WHERE status = 'running' AND lease_owner = NEW.lease_owner;
             RETURN NEW;
         END $$ LANGUAGE plpgsql;
         CREATE TRIGGER jobs_claim AFTER UPDATE OF status ON jobs FOR EACH ROW
             WHEN (OLD.status = 'queued' AND NEW.status = 'running') EXECUTE FUNCTION log_claim();",
    )
    .await
    .unwrap();
    let n = 120;
    let mut ids = Vec::new();
    for i in 0..n {
        let job = match i % 3 {
            0 => sleep_job(0.02, 9000 + i as u64),
            1 => sleep_job(0.005, 9000 + i as u64),
            _ => hertz_job(300.0 + i as f64),
        };
        let s = &servers[i % 2];
        let body: Value = s.post_job(&job).await.json().await.unwrap();
        ids.push(body["id"].as_str().unwrap().to_string());
    }
    for id in &ids {
        let done = servers[0].wait_finished(id, Duration::from_secs(60)).await;
        assert_eq!(done["status"], "succeeded", "{done}");
    }
    let rows = sqlx::query("SELECT owner, max(held), max(held_long), count(*) FROM claim_log GROUP BY owner").fetch_all(&mut conn).await.unwrap();
    let claims: i64 = rows.iter().map(|r| r.get::<i64, _>(3)).sum();
    assert_eq!(claims, n as i64, "one claim per job: {claims}");
    let mut most = 0;
    for r in &rows {
        let (owner, held, held_long): (String, i64, i64) = (r.get(0), r.get(1), r.get(2));
        eprintln!("{owner}: at most {held} jobs ({held_long} long) held at a claim");
        assert!(held <= 4, "{owner} held {held} jobs at once with 2 workers and 2 short-job slots");
        assert!(held_long <= 2, "{owner} held {held_long} long jobs at once with 2 workers");
        most = most.max(held);
    }
    assert!(most > 2, "the short-job slots were never used (at most {most} jobs held)");
    let finishes: Vec<(String, i64)> = sqlx::query("SELECT job_id, count(*) FROM finish_log WHERE what = 'succeeded' GROUP BY job_id")
        .fetch_all(&mut conn)
        .await
        .unwrap()
        .iter()
        .map(|r| (r.get(0), r.get(1)))
        .collect();
    assert_eq!(finishes.len(), n, "every job finished");
    assert!(finishes.iter().all(|(_, k)| *k == 1), "each exactly once");
    let _ = conn.close().await;
    for s in servers {
        s.stop().await;
    }
}
