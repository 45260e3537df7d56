//! Issue 10: hostile sizes, slow clients, shutdown, prefetching, idempotency, fair scheduling and
//! the smaller defects — each against the real server on loopback.

use crate::common::*;
use serde_json::{json, Value};
use std::time::{Duration, Instant};
use tokio::io::{AsyncReadExt, AsyncWriteExt};

on_both_backends!(
    idempotency_key_makes_a_retried_post_safe,
    an_idempotency_key_is_kept_when_the_first_answer_is_an_existing_job,
    idempotency_keys_stored_before_the_keys_table_still_answer,
);

fn kind_example(name: &str) -> Value {
    tribod::jobs::registry::find(name).expect("kind").example()
}

#[tokio::test]
async fn hostile_sizes_are_refused_before_anything_is_allocated() {
    let s = start().await;
    // 1e12 linspace values: refused by counting, not by building them (it used to abort).
    let sweep = json!({"kind": "sweep", "spec": {"kind": "hertz", "base": {},
        "parameters": [{"path": "/load", "linspace": {"start": 1, "stop": 2, "num": 1_000_000_000_000u64}}]}});
    let p = expect_problem(s.post_job(&sweep).await, 422, "invalid_spec").await;
    assert!(p.to_string().contains("/spec/parameters/0/linspace/num"), "{p}");
    // A grid of 8 × 1000 values: 1e24 cases, counted with saturation.
    let params: Vec<Value> = (0..8)
        .map(|i| json!({"path": format!("/p{i}"), "linspace": {"start": 1, "stop": 2, "num": 1000}}))
        .collect();
    let grid = json!({"kind": "sweep", "spec": {"kind": "hertz", "base": {}, "parameters": params}});
    expect_problem(s.post_job(&grid).await, 422, "limit_exceeded").await;

    // 65,536 EHL nodes of the numerical film: the dense matrices would need ~80 GiB; refused by
    // the memory model (the closed forms of `fidelity: fast` would not use them).
    let mut cam = kind_example("cam_cycle");
    cam["fidelity"] = json!("accurate");
    cam["ehl"] = json!({"nodes": 65536});
    let p = expect_problem(s.post_job(&json!({"kind": "cam_cycle", "spec": cam})).await, 422, "limit_exceeded").await;
    let text = p.to_string();
    assert!(text.contains("/spec/ehl/nodes") && text.contains("MiB"), "{p}");

    // A rough contact of 512² points at 64 films: ≈ 160 s of solver time by the work model of
    // benches/rough.rs, above the default 60 s; refused before a surface is generated.
    let mut rough = kind_example("rough_contact");
    rough["surface"]["points"] = json!(512);
    rough["films"] = json!((1..=64).map(|k| 1e-8 * k as f64).collect::<Vec<f64>>());
    let p = expect_problem(s.post_job(&json!({"kind": "rough_contact", "spec": rough})).await, 422, "limit_exceeded").await;
    assert!(p.to_string().contains("/spec/films") && p.to_string().contains("solver time"), "{p}");

    // A grid whose node count overflows usize (found by schemathesis: a panic in validation, 500).
    let mut bearing = kind_example("bearing");
    bearing["grid"] = json!({"circumferential": 11784423u64, "axial": 478913318372841856u64});
    let p = expect_problem(s.post_job(&json!({"kind": "bearing", "spec": bearing})).await, 422, "invalid_spec").await;
    assert!(p.to_string().contains("/spec/grid"), "{p}");

    // A bearing optimisation of ~960 analyses on 2001×361 nodes (≈ 70 s of solver time by the
    // work model; 360 analyses on 3001×181 take 27 s): refused by the work model, naming the grid.
    let mut opt = kind_example("bearing_optimisation");
    opt["base"]["grid"] = json!({"circumferential": 2001, "axial": 361});
    opt["continuous"]["enabled"] = json!(true);
    opt["continuous"]["evaluations_per_order"] = json!(300);
    let p = expect_problem(s.post_job(&json!({"kind": "bearing_optimisation", "spec": opt})).await, 422, "limit_exceeded").await;
    assert!(p.to_string().contains("/spec/base/grid") && p.to_string().contains("of solver time"), "{p}");

    // A load of 1e308 N is a field error, not an internal error.
    let mut hertz = hertz_job(1e308);
    let p = expect_problem(s.post_job(&hertz).await, 422, "invalid_spec").await;
    assert!(p.to_string().contains("/spec/load"), "{p}");
    hertz["spec"]["load"] = json!(1000.0);
    assert_eq!(s.post_job(&hertz).await.status(), 202);
    s.stop().await;
}

#[test]
fn dense_ehl_memory_model_admits_the_documented_grids() {
    let limits = tribod::jobs::kind::Limits::default();
    // 4096 nodes (ehl_point's largest) fit the default 2 GiB budget; 16,384 do not.
    assert!(tribod::physics::ehl::dense_memory_bytes(4096) < limits.max_job_memory as f64);
    assert!(tribod::physics::ehl::dense_memory_bytes(16384) > limits.max_job_memory as f64);
}

#[tokio::test]
async fn smaller_defects_of_the_http_layer() {
    let s = start_with(|c| c.api.tokens = vec!["s3cret-token".into()]).await;
    // Unknown /v1 routes and methods ask for the token first.
    for (method, path) in [("GET", "/v1/nope"), ("PUT", "/v1/jobs"), ("GET", "/v1")] {
        let res = s.client.request(method.parse().unwrap(), s.url(path)).send().await.unwrap();
        expect_problem(res, 401, "unauthorized").await;
    }
    let auth = |r: reqwest::RequestBuilder| r.bearer_auth("s3cret-token");
    // An id that is not UTF-8 after decoding: a problem document, not text/plain.
    let res = auth(s.client.get(s.url("/v1/jobs/%FF%FE"))).send().await.unwrap();
    expect_problem(res, 404, "job_not_found").await;
    // Accept that excludes JSON: 406.
    let res = auth(s.client.get(s.url("/v1/kinds"))).header("accept", "image/png").send().await.unwrap();
    expect_problem(res, 406, "not_acceptable").await;
    let res = auth(s.client.get(s.url("/v1/kinds"))).header("accept", "application/*").send().await.unwrap();
    assert_eq!(res.status(), 200);
    s.stop().await;
}

#[test]
fn a_blank_api_token_is_refused_at_start() {
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_tribod"))
        .args(["serve", "--addr", "127.0.0.1:0", "--database-url", "sqlite::memory:", "--api-token", " "])
        .output()
        .expect("run tribod");
    assert_eq!(out.status.code(), Some(2), "{}", String::from_utf8_lossy(&out.stderr));
    assert!(String::from_utf8_lossy(&out.stderr).contains("blank token"));
}

#[tokio::test(flavor = "multi_thread", worker_threads = 4)]
async fn the_backlog_limit_holds_under_concurrent_submissions() {
    let s = start_with(|c| {
        c.queue.workers = 1;
        c.queue.max_backlog = 10;
    })
    .await;
    let mut tasks = Vec::new();
    for i in 0..60u64 {
        let client = s.client.clone();
        let url = s.url("/v1/jobs");
        tasks.push(tokio::spawn(async move {
            client.post(url).json(&sleep_job(2.0, 1000 + i)).send().await.unwrap().status().as_u16()
        }));
    }
    let mut accepted = 0;
    for t in tasks {
        match t.await.unwrap() {
            202 => accepted += 1,
            503 => {}
            other => panic!("unexpected {other}"),
        }
    }
    let (_, page) = s.get_json("/v1/jobs?status=queued&limit=500").await;
    let queued = page["jobs"].as_array().unwrap().len();
    assert!(queued <= 10, "{queued} queued with --max-queue 10");
    assert!(accepted <= 11, "{accepted} accepted: 10 queued + at most 1 started meanwhile");
    s.stop().await;
}

async fn idempotency_key_makes_a_retried_post_safe() {
    let s = start().await;
    let post = |body: &Value, key: &str| s.client.post(s.url("/v1/jobs")).header("idempotency-key", key).json(body).send();
    let first = post(&sleep_job(0.2, 77), "order-4711").await.unwrap();
    assert_eq!(first.status(), 202);
    let first: Value = first.json().await.unwrap();
    let again = post(&sleep_job(0.2, 77), "order-4711").await.unwrap();
    assert!(matches!(again.status().as_u16(), 200 | 202));
    assert_eq!(again.headers()["idempotent-replayed"], "true");
    let again: Value = again.json().await.unwrap();
    assert_eq!(again["id"], first["id"], "the same key and body answer the same job");
    let other = post(&sleep_job(0.2, 78), "order-4711").await.unwrap();
    expect_problem(other, 422, "idempotency_key_reused").await;
    let bad = post(&sleep_job(0.2, 79), "").await.unwrap();
    expect_problem(bad, 422, "invalid_request").await;
    // Concurrent first attempts with one key make one job.
    let mut tasks = Vec::new();
    for _ in 0..8 {
        let req = s.client.post(s.url("/v1/jobs")).header("idempotency-key", "burst-1").json(&sleep_job(0.1, 80));
        tasks.push(tokio::spawn(async move { req.send().await.unwrap().json::<Value>().await.unwrap()["id"].clone() }));
    }
    let mut ids = Vec::new();
    for t in tasks {
        ids.push(t.await.unwrap());
    }
    ids.dedup();
    assert_eq!(ids.len(), 1, "one job for one key: {ids:?}");
    s.stop().await;
}

#[tokio::test]
async fn only_started_jobs_are_running_and_a_queued_job_cancels_at_once() {
    let s = start_with(|c| c.queue.workers = 1).await;
    let mut ids = Vec::new();
    for i in 0..5 {
        let res: Value = s.post_job(&sleep_job(0.3, 500 + i)).await.json().await.unwrap();
        ids.push(res["id"].as_str().unwrap().to_string());
    }
    tokio::time::sleep(Duration::from_millis(100)).await;
    let (_, running) = s.get_json("/v1/jobs?status=running").await;
    assert_eq!(running["jobs"].as_array().unwrap().len(), 1, "one worker, one running job: {running}");
    let res = s.client.delete(s.url(&format!("/v1/jobs/{}", ids[3]))).send().await.unwrap();
    let job: Value = res.json().await.unwrap();
    assert_eq!(job["status"], "canceled", "a queued job is canceled by DELETE at once: {job}");
    for id in &ids {
        let job = s.wait_finished(id, Duration::from_secs(20)).await;
        assert_eq!(job["attempts"].as_i64().unwrap() <= 1, true, "{job}");
    }
    s.stop().await;
}

#[tokio::test]
async fn a_tiny_job_does_not_wait_behind_the_heavy_backlog() {
    let s = start_with(|c| c.queue.workers = 1).await;
    // Calibrate both kinds' estimates with one job each.
    let h: Value = s.post_job(&hertz_job(999.0)).await.json().await.unwrap();
    s.wait_finished(h["id"].as_str().unwrap(), Duration::from_secs(10)).await;
    let w: Value = s.post_job(&sleep_job(0.3, 900)).await.json().await.unwrap();
    s.wait_finished(w["id"].as_str().unwrap(), Duration::from_secs(10)).await;
    // A heavy backlog, then a tiny job.
    let mut heavy = Vec::new();
    for i in 0..8 {
        let res: Value = s.post_job(&sleep_job(0.3, 901 + i)).await.json().await.unwrap();
        heavy.push(res["id"].as_str().unwrap().to_string());
    }
    let tiny: Value = s.post_job(&hertz_job(1234.0)).await.json().await.unwrap();
    let tiny = s.wait_finished(tiny["id"].as_str().unwrap(), Duration::from_secs(20)).await;
    assert_eq!(tiny["status"], "succeeded");
    let mut waiting_heavy = 0;
    for id in &heavy {
        let (_, job) = s.get_json(&format!("/v1/jobs/{id}")).await;
        if job["status"] == "queued" {
            waiting_heavy += 1;
        }
    }
    assert!(waiting_heavy >= 5, "the tiny job ran after only {} of 8 heavy jobs started", 8 - waiting_heavy);
    s.stop().await;
}

#[tokio::test(flavor = "multi_thread", worker_threads = 4)]
async fn shutdown_answers_waiters_and_hands_running_jobs_back() {
    let dir = tempfile::tempdir().unwrap();
    let mut cfg = config(&dir);
    cfg.queue.workers = 1;
    cfg.shutdown_grace = Duration::from_millis(500);
    let s = start_in(dir, cfg.clone()).await;
    let long: Value = s.post_job(&sleep_job(30.0, 1)).await.json().await.unwrap();
    let long_id = long["id"].as_str().unwrap().to_string();
    s.wait_status(&long_id, "running", Duration::from_secs(5)).await;
    // A client waiting for a queued job, and a client that sent half a request.
    let waiter = {
        let req = s.client.post(s.url("/v1/jobs")).header("prefer", "wait=300").json(&sleep_job(1.0, 2));
        tokio::spawn(async move { req.send().await.unwrap() })
    };
    let mut half = tokio::net::TcpStream::connect(s.base.trim_start_matches("http://")).await.unwrap();
    half.write_all(b"POST /v1/jobs HTTP/1.1\r\nhost: x\r\ncontent-length: 100\r\n\r\n{\"kind\":").await.unwrap();
    tokio::time::sleep(Duration::from_millis(200)).await;

    let started = Instant::now();
    let dir = s.stop().await;
    let took = started.elapsed();
    let answer = tokio::time::timeout(Duration::from_secs(5), waiter).await.expect("waiter answered").unwrap();
    assert_eq!(answer.status(), 202, "the waiting request gets the job as it is");
    assert!(took < Duration::from_secs(5), "shutdown took {took:?} with open waits and a half-sent request");

    // The interrupted job is queued again, its attempt not charged.
    let s = start_in(dir, cfg).await;
    let (_, job) = s.get_json(&format!("/v1/jobs/{long_id}")).await;
    assert!(matches!(job["status"].as_str(), Some("queued" | "running")), "{job}");
    assert!(job["attempts"].as_i64().unwrap() <= 1, "{job}");
    s.stop().await;
}

#[tokio::test(flavor = "multi_thread", worker_threads = 4)]
async fn slow_clients_cannot_lock_others_out() {
    let s = start_with(|c| {
        c.connections.max_connections = 50;
        c.connections.header_timeout = Duration::from_millis(500);
    })
    .await;
    let addr = s.base.trim_start_matches("http://").to_string();
    // 200 clients that never finish their headers: over the cap, each new one takes the place of
    // the one that has waited longest (issue 40; they used to be refused with 503 until the slow
    // ones timed out, so 4,096 tricklers locked everyone out).
    let mut slow = Vec::new();
    for _ in 0..200 {
        let mut c = tokio::net::TcpStream::connect(&addr).await.unwrap();
        let _ = c.write_all(b"GET /healthz HTTP/1.1\r\nhost: x\r\n").await;
        slow.push(c);
    }
    let mut closed_at_once = 0;
    for c in slow.iter_mut().take(140) {
        let mut buf = [0u8; 256];
        match tokio::time::timeout(Duration::from_millis(100), c.read(&mut buf)).await {
            Ok(Ok(n)) => closed_at_once += (!String::from_utf8_lossy(&buf[..n]).contains(" 200 ")) as usize,
            Ok(Err(_)) => closed_at_once += 1,
            Err(_) => {}
        }
    }
    assert!(closed_at_once >= 130, "{closed_at_once} of the 140 oldest slow connections were closed for newer ones");
    // A normal client is served at once, before any header timeout.
    let started = Instant::now();
    let res = s.client.get(s.url("/healthz")).send().await.unwrap();
    assert_eq!(res.status(), 200);
    assert!(started.elapsed() < Duration::from_millis(400), "{:?}", started.elapsed());
    // After the header timeout the slow ones still open are gone too.
    tokio::time::sleep(Duration::from_millis(800)).await;
    let mut closed = 0;
    for c in slow.iter_mut().skip(150) {
        let mut buf = [0u8; 256];
        if let Ok(Ok(_) | Err(_)) = tokio::time::timeout(Duration::from_millis(100), c.read(&mut buf)).await {
            closed += 1;
        }
    }
    assert!(closed >= 45, "only {closed} of the 50 newest slow connections were closed by the header timeout");
    s.stop().await;
}

/// Only when every connection is being served (none waits on its client) is a new connection
/// refused: `503 too_many_connections` with `Retry-After`, and closed.
#[tokio::test(flavor = "multi_thread", worker_threads = 4)]
async fn a_table_full_of_busy_connections_answers_503() {
    let s = start_with(|c| {
        c.connections.max_connections = 4;
        c.queue.workers = 1;
    })
    .await;
    // Four requests held open by the server (`Prefer: wait` on a 2 s job), each on its own connection.
    let mut waits = Vec::new();
    for _ in 0..4 {
        let client = reqwest::Client::builder().pool_max_idle_per_host(0).build().unwrap();
        let req = client.post(s.url("/v1/jobs")).header("prefer", "wait=10").json(&sleep_job(2.0, 4100));
        waits.push(tokio::spawn(async move { req.send().await.map(|r| r.status().as_u16()) }));
    }
    tokio::time::sleep(Duration::from_millis(500)).await;
    let mut c = tokio::net::TcpStream::connect(s.base.trim_start_matches("http://")).await.unwrap();
    let mut buf = [0u8; 512];
    let n = tokio::time::timeout(Duration::from_secs(1), c.read(&mut buf)).await.expect("answered at once").unwrap();
    let answer = String::from_utf8_lossy(&buf[..n]).to_string();
    assert!(answer.starts_with("HTTP/1.1 503 ") && answer.contains("too_many_connections") && answer.contains("retry-after: 1"), "{answer}");
    for w in waits {
        assert_eq!(w.await.unwrap().ok(), Some(200), "the busy requests are not disturbed");
    }
    s.stop().await;
}

/// Issue 40: a key whose first answer was an existing job (a finished job reused, an in-flight job
/// joined) is recorded like a key that created its job: the same request again replays that job,
/// another request under the key is refused. A key lives as long as its job: deleting the
/// (finished) job forgets the key, which then starts afresh.
async fn an_idempotency_key_is_kept_when_the_first_answer_is_an_existing_job() {
    let s = start().await;
    let post = |body: &Value, key: &str| s.client.post(s.url("/v1/jobs")).header("idempotency-key", key).json(body).send();
    let id_and_reused = |v: &Value| (v["id"].clone(), v["reused"].clone());

    // A finished job; the same spec under a new key is reused, and the key records it.
    let res = s.client.post(s.url("/v1/jobs")).header("prefer", "wait=10").json(&hertz_job(4321.0)).send().await.unwrap();
    let done: Value = res.json().await.unwrap();
    assert_eq!(done["status"], "succeeded", "{done}");
    let first = post(&hertz_job(4321.0), "reuse-1").await.unwrap();
    assert_eq!(first.status(), 200);
    assert!(first.headers().get("idempotent-replayed").is_none());
    let first: Value = first.json().await.unwrap();
    assert_eq!(id_and_reused(&first), (done["id"].clone(), json!(true)), "{first}");
    let again = post(&hertz_job(4321.0), "reuse-1").await.unwrap();
    assert_eq!(again.status(), 200);
    assert_eq!(again.headers()["idempotent-replayed"], "true");
    let again: Value = again.json().await.unwrap();
    assert_eq!(id_and_reused(&again), (done["id"].clone(), json!(true)), "the repeat replays the reuse: {again}");
    let other = post(&hertz_job(4322.0), "reuse-1").await.unwrap();
    expect_problem(other, 422, "idempotency_key_reused").await;
    let mut labelled = hertz_job(4321.0);
    labelled["label"] = json!("another label");
    expect_problem(post(&labelled, "reuse-1").await.unwrap(), 422, "idempotency_key_reused").await;

    // A job in flight, joined under a new key (also by a burst of concurrent first attempts).
    let running: Value = s.post_job(&sleep_job(1.0, 4001)).await.json().await.unwrap();
    let joined = post(&sleep_job(1.0, 4001), "join-1").await.unwrap();
    assert_eq!(joined.status(), 202);
    let joined: Value = joined.json().await.unwrap();
    assert_eq!(id_and_reused(&joined), (running["id"].clone(), json!(true)), "{joined}");
    expect_problem(post(&sleep_job(1.0, 4002), "join-1").await.unwrap(), 422, "idempotency_key_reused").await;
    let mut tasks = Vec::new();
    for _ in 0..8 {
        let req = s.client.post(s.url("/v1/jobs")).header("idempotency-key", "join-burst").json(&sleep_job(1.0, 4001));
        tasks.push(tokio::spawn(async move { req.send().await.unwrap().json::<Value>().await.unwrap()["id"].clone() }));
    }
    for t in tasks {
        assert_eq!(t.await.unwrap(), running["id"], "every concurrent first attempt joins the one job");
    }
    expect_problem(post(&sleep_job(1.0, 4003), "join-burst").await.unwrap(), 422, "idempotency_key_reused").await;
    let id = running["id"].as_str().unwrap();
    assert_eq!(s.wait_finished(id, Duration::from_secs(20)).await["status"], "succeeded");
    // Finished since: the key still answers that job.
    let again = post(&sleep_job(1.0, 4001), "join-1").await.unwrap();
    assert_eq!(again.status(), 200);
    assert_eq!(again.headers()["idempotent-replayed"], "true");
    let again: Value = again.json().await.unwrap();
    assert_eq!(id_and_reused(&again), (running["id"].clone(), json!(true)), "{again}");
    expect_problem(post(&sleep_job(1.0, 4002), "join-1").await.unwrap(), 422, "idempotency_key_reused").await;

    // Deleting the job forgets its keys: the key then answers whatever request comes first.
    assert_eq!(s.client.delete(s.url(&format!("/v1/jobs/{id}"))).send().await.unwrap().status(), 204);
    let fresh = post(&sleep_job(0.1, 4002), "join-1").await.unwrap();
    assert_eq!(fresh.status(), 202);
    assert!(fresh.headers().get("idempotent-replayed").is_none());
    let fresh: Value = fresh.json().await.unwrap();
    assert_ne!(fresh["id"], running["id"]);
    assert_eq!(fresh["reused"], false);
    expect_problem(post(&sleep_job(1.0, 4001), "join-1").await.unwrap(), 422, "idempotency_key_reused").await;
    s.stop().await;
}

/// Keys stored with their jobs before the keys table existed (the `jobs.idempotency_key` column
/// up to SQLite migration 0003 / PostgreSQL 0001) keep answering after the upgrade.
async fn idempotency_keys_stored_before_the_keys_table_still_answer() {
    use sqlx::migrate::Migrator;
    let dir = tempfile::tempdir().unwrap();
    let cfg = test_config(&dir).await;
    // The job a client submitted with key `legacy-1` under the old schema.
    let job = hertz_job(2468.0);
    let kind = tribod::jobs::registry::find("hertz").unwrap();
    let canonical = kind.prepare(&job["spec"], &tribod::jobs::Limits::default()).unwrap().canonical;
    let hash = tribod::jobs::runner::spec_hash("hertz", &serde_json::to_string(&canonical).unwrap());
    let id = uuid::Uuid::now_v7().to_string();
    let now = std::time::SystemTime::now().duration_since(std::time::UNIX_EPOCH).unwrap().as_millis() as i64;
    let (migrations, old_version) = match backend() {
        Backend::Sqlite => ("sqlite", 3),
        Backend::Postgres => ("postgres", 1),
    };
    let dir_of = std::path::PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("migrations").join(migrations);
    let migrator = Migrator::new(dir_of.as_path()).await.unwrap();
    let insert = "INSERT INTO jobs (id, kind, status, spec, spec_hash, solver_version, created_at, idempotency_key, due_at) \
                  VALUES ($1, 'hertz', 'queued', $2, $3, $4, $5, 'legacy-1', 0)";
    match backend() {
        Backend::Sqlite => {
            let options = sqlx::sqlite::SqliteConnectOptions::new().filename(&cfg.database_url).create_if_missing(true);
            let pool = sqlx::sqlite::SqlitePoolOptions::new().max_connections(1).connect_with(options).await.unwrap();
            migrator.run_to(old_version, &pool).await.unwrap();
            let q = sqlx::query(insert).bind(&id).bind(canonical.to_string()).bind(&hash).bind(kind.solver_version()).bind(now);
            q.execute(&pool).await.unwrap();
            pool.close().await;
        }
        Backend::Postgres => {
            let pool = sqlx::postgres::PgPoolOptions::new().max_connections(1).connect(&cfg.database_url).await.unwrap();
            migrator.run_to(old_version, &pool).await.unwrap();
            let q = sqlx::query(insert).bind(&id).bind(canonical.to_string()).bind(&hash).bind(kind.solver_version()).bind(now);
            q.execute(&pool).await.unwrap();
            pool.close().await;
        }
    }
    let s = start_in(dir, cfg).await;
    let post = |body: &Value, key: &str| s.client.post(s.url("/v1/jobs")).header("idempotency-key", key).json(body).send();
    let again = post(&job, "legacy-1").await.unwrap();
    assert!(matches!(again.status().as_u16(), 200 | 202), "{}", again.status());
    assert_eq!(again.headers()["idempotent-replayed"], "true");
    let again: Value = again.json().await.unwrap();
    assert_eq!((again["id"].as_str(), again["reused"].as_bool()), (Some(id.as_str()), Some(false)), "{again}");
    expect_problem(post(&hertz_job(2469.0), "legacy-1").await.unwrap(), 422, "idempotency_key_reused").await;
    assert_eq!(s.wait_finished(&id, Duration::from_secs(20)).await["status"], "succeeded");
    s.stop().await;
}

/// Read from `conn` until the server closes it (EOF or reset) or `within` passes; what arrived
/// and whether it was closed.
async fn read_until_closed(conn: &mut tokio::net::tcp::OwnedReadHalf, within: Duration) -> (String, bool) {
    let deadline = tokio::time::Instant::now() + within;
    let mut got = Vec::new();
    loop {
        let mut buf = [0u8; 4096];
        match tokio::time::timeout_at(deadline, conn.read(&mut buf)).await {
            Ok(Ok(0)) | Ok(Err(_)) => return (String::from_utf8_lossy(&got).into_owned(), true),
            Ok(Ok(n)) => got.extend_from_slice(&buf[..n]),
            Err(_) => return (String::from_utf8_lossy(&got).into_owned(), false),
        }
    }
}

/// Issue 40, defect A: a body has a total deadline counted from its headers, however it trickles
/// (a per-read timeout never fires on one byte every 0.4 s); past it the answer is `408
/// request_timeout` and the connection is closed.
#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_trickling_body_is_answered_408_and_closed_at_its_total_deadline() {
    let s = start_with(|c| c.api.body_timeout = Duration::from_secs(2)).await;
    let stream = tokio::net::TcpStream::connect(s.base.trim_start_matches("http://")).await.unwrap();
    let (mut read, mut write) = stream.into_split();
    let started = Instant::now();
    write.write_all(b"POST /v1/jobs HTTP/1.1\r\nhost: x\r\ncontent-type: application/json\r\ncontent-length: 100\r\n\r\n{").await.unwrap();
    let trickle = tokio::spawn(async move {
        for _ in 0..100 {
            tokio::time::sleep(Duration::from_millis(400)).await;
            if write.write_all(b" ").await.is_err() {
                return;
            }
        }
    });
    let (answer, closed) = read_until_closed(&mut read, Duration::from_secs(6)).await;
    let took = started.elapsed();
    trickle.abort();
    assert!(answer.starts_with("HTTP/1.1 408 "), "{answer}");
    let lower = answer.to_ascii_lowercase();
    assert!(lower.contains("content-type: application/problem+json") && lower.contains("connection: close"), "{answer}");
    assert!(answer.contains(r#""code":"request_timeout""#), "{answer}");
    assert!(closed, "the connection stays open after the 408");
    assert!(took >= Duration::from_millis(1900) && took < Duration::from_millis(3500), "closed after {took:?} with a 2 s body deadline");
    // The server is fine meanwhile and after.
    assert_eq!(s.client.get(s.url("/healthz")).send().await.unwrap().status(), 200);
    s.stop().await;
}

/// The header timeout is a total deadline too (hyper's `header_read_timeout` is set once per
/// request, not per read): headers trickling one byte every 0.2 s are cut off at the deadline.
#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn trickling_headers_are_closed_at_their_total_deadline() {
    let s = start_with(|c| c.connections.header_timeout = Duration::from_secs(1)).await;
    let stream = tokio::net::TcpStream::connect(s.base.trim_start_matches("http://")).await.unwrap();
    let (mut read, mut write) = stream.into_split();
    let started = Instant::now();
    write.write_all(b"GET /healthz HTTP/1.1\r\nhost: x\r\nx-slow: ").await.unwrap();
    let trickle = tokio::spawn(async move {
        for _ in 0..100 {
            tokio::time::sleep(Duration::from_millis(200)).await;
            if write.write_all(b"a").await.is_err() {
                return;
            }
        }
    });
    let (answer, closed) = read_until_closed(&mut read, Duration::from_secs(5)).await;
    let took = started.elapsed();
    trickle.abort();
    assert!(closed, "still open after {took:?}");
    assert!(!answer.contains(" 200 "), "{answer}");
    assert!(took >= Duration::from_millis(900) && took < Duration::from_millis(2500), "closed after {took:?} with a 1 s header deadline");
    s.stop().await;
}

/// One trickling client: a request whose headers (`body: false`) or body (`body: true`) arrive one
/// byte every `every`; when the server closes it, it waits `pause` and starts over. Counts its
/// connections.
async fn trickler(addr: String, body: bool, every: Duration, pause: Duration, connections: std::sync::Arc<std::sync::atomic::AtomicUsize>) {
    let head: &[u8] = if body {
        b"POST /v1/jobs HTTP/1.1\r\nhost: x\r\ncontent-type: application/json\r\ncontent-length: 10000\r\n\r\n{"
    } else {
        b"GET /healthz HTTP/1.1\r\nhost: x\r\n"
    };
    loop {
        if let Ok(mut c) = tokio::net::TcpStream::connect(&addr).await {
            connections.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
            let mut ok = c.write_all(head).await.is_ok();
            while ok {
                let mut buf = [0u8; 1024];
                // Anything from the server (an answer, EOF, a reset) ends this connection.
                ok = tokio::time::timeout(every, c.read(&mut buf)).await.is_err() && c.write_all(if body { b" " } else { b"x" }).await.is_ok();
            }
        }
        tokio::time::sleep(pause).await;
    }
}

/// Issue 40, defect B: trickling clients that fill the connection table cannot lock normal clients
/// out. 200 tricklers (half sending headers, half bodies, one byte a second, reconnecting when
/// closed) against a table of 64 places: `GET /healthz` and `POST /v1/jobs` of a tiny job on a
/// fresh connection are each served within 1 s throughout.
#[tokio::test(flavor = "multi_thread", worker_threads = 4)]
async fn trickling_clients_cannot_starve_normal_ones() {
    let s = start_with(|c| {
        c.connections.max_connections = 64;
        c.connections.header_timeout = Duration::from_secs(3);
        c.api.body_timeout = Duration::from_secs(3);
    })
    .await;
    let addr = s.base.trim_start_matches("http://").to_string();
    let connections = std::sync::Arc::new(std::sync::atomic::AtomicUsize::new(0));
    let tricklers: Vec<_> = (0..200)
        .map(|i| tokio::spawn(trickler(addr.clone(), i % 2 == 1, Duration::from_secs(1), Duration::from_millis(200), connections.clone())))
        .collect();
    tokio::time::sleep(Duration::from_millis(1500)).await;
    // A fresh connection for every request: each needs a place in the full table.
    let client = reqwest::Client::builder().pool_max_idle_per_host(0).timeout(Duration::from_secs(5)).build().unwrap();
    let mut latencies = Vec::new();
    let until = Instant::now() + Duration::from_secs(10);
    let mut n = 0u32;
    while Instant::now() < until {
        n += 1;
        let t = Instant::now();
        let res = client.get(s.url("/healthz")).send().await;
        let health = res.map(|r| r.status().as_u16());
        latencies.push(t.elapsed());
        assert_eq!(health.as_ref().ok(), Some(&200), "GET /healthz #{n}: {health:?} after {:?}", t.elapsed());
        let t = Instant::now();
        let res = client.post(s.url("/v1/jobs")).json(&hertz_job(1000.0 + f64::from(n))).send().await;
        let post = res.map(|r| r.status().as_u16());
        latencies.push(t.elapsed());
        assert!(matches!(post, Ok(200 | 202)), "POST /v1/jobs #{n}: {post:?} after {:?}", t.elapsed());
        tokio::time::sleep(Duration::from_millis(100)).await;
    }
    for t in &tricklers {
        t.abort();
    }
    latencies.sort();
    let (p50, max) = (latencies[latencies.len() / 2], latencies[latencies.len() - 1]);
    let opened = connections.load(std::sync::atomic::Ordering::Relaxed);
    eprintln!("{} normal requests beside 200 tricklers ({opened} trickling connections) on 64 places: p50 {p50:?}, max {max:?}", latencies.len());
    assert!(max < Duration::from_secs(1), "a normal request took {max:?}");
    assert!(opened > 200, "the tricklers were never cut off ({opened} connections)");
    s.stop().await;
}
