//! Shared helpers of the HTTP tests: a real server on a loopback port with a temporary SQLite file
//! or a fresh PostgreSQL database, and a real HTTP client.
//!
//! The behaviour suites run on both store backends through [`on_both_backends!`]: each test body
//! runs once with SQLite and once with PostgreSQL (a new database per server on the server named by
//! `TRIBOD_TEST_POSTGRES_URL`; without it the PostgreSQL runs are skipped and say so on stderr).
#![allow(dead_code)]

use serde_json::{json, Value};
use std::time::{Duration, Instant};
use tribod::api::ApiConfig;
use tribod::jobs::queue::QueueConfig;
use tribod::server::{ServeConfig, Server};

pub struct TestServer {
    pub base: String,
    pub client: reqwest::Client,
    pub server: Option<Server>,
    pub dir: tempfile::TempDir,
    pub db: String,
}

/// A config for tests: loopback, port 0, a file in `dir`, 2 workers, short grace.
pub fn config(dir: &tempfile::TempDir) -> ServeConfig {
    ServeConfig {
        addr: "127.0.0.1:0".into(),
        database_url: dir.path().join("tribod.db").display().to_string(),
        queue: QueueConfig { workers: 2, ..QueueConfig::default() },
        api: ApiConfig::default(),
        shutdown_grace: Duration::from_secs(5),
        connections: Default::default(),
    }
}

pub async fn start() -> TestServer {
    start_with(|_| {}).await
}

pub async fn start_with(tweak: impl FnOnce(&mut ServeConfig)) -> TestServer {
    let dir = tempfile::tempdir().expect("temp dir");
    let mut cfg = test_config(&dir).await;
    tweak(&mut cfg);
    start_in(dir, cfg).await
}

pub async fn start_in(dir: tempfile::TempDir, cfg: ServeConfig) -> TestServer {
    let db = cfg.database_url.clone();
    let server = Server::start(cfg).await.expect("server starts");
    TestServer {
        base: format!("http://{}", server.addr),
        // A server that never answers fails the test by name instead of hanging the suite (one
        // run hung in `reliability::postgres::idempotency_key_makes_a_retried_post_safe`).
        client: reqwest::Client::builder().read_timeout(Duration::from_secs(120)).build().expect("HTTP client"),
        server: Some(server),
        dir,
        db,
    }
}

impl TestServer {
    pub fn url(&self, path: &str) -> String {
        format!("{}{}", self.base, path)
    }

    pub async fn post_job(&self, body: &Value) -> reqwest::Response {
        self.client.post(self.url("/v1/jobs")).json(body).send().await.expect("POST /v1/jobs")
    }

    pub async fn get_json(&self, path: &str) -> (u16, Value) {
        let res = self.client.get(self.url(path)).send().await.expect("GET");
        let status = res.status().as_u16();
        (status, res.json().await.unwrap_or(Value::Null))
    }

    /// Poll a job until it is finished (or `timeout`); the final job JSON.
    pub async fn wait_finished(&self, id: &str, timeout: Duration) -> Value {
        let start = Instant::now();
        loop {
            let (_, job) = self.get_json(&format!("/v1/jobs/{id}")).await;
            let status = job["status"].as_str().unwrap_or("");
            if matches!(status, "succeeded" | "failed" | "canceled") || start.elapsed() > timeout {
                return job;
            }
            tokio::time::sleep(Duration::from_millis(20)).await;
        }
    }

    /// Poll until the job has `status`.
    pub async fn wait_status(&self, id: &str, status: &str, timeout: Duration) -> Value {
        let start = Instant::now();
        loop {
            let (_, job) = self.get_json(&format!("/v1/jobs/{id}")).await;
            if job["status"] == status || start.elapsed() > timeout {
                return job;
            }
            tokio::time::sleep(Duration::from_millis(10)).await;
        }
    }

    pub async fn stop(mut self) -> tempfile::TempDir {
        if let Some(s) = self.server.take() {
            s.shutdown().await.expect("clean shutdown");
        }
        self.dir
    }
}

/// A line-contact `hertz` job with load `load` N.
pub fn hertz_job(load: f64) -> Value {
    json!({
        "kind": "hertz",
        "spec": {
            "contact": "line",
            "load": load,
            "length": 0.01,
            "body_1": {"shape": "cylinder", "radius": 0.02},
            "body_2": {"shape": "flat"}
        }
    })
}

/// A `test_sleep` job (test builds only).
pub fn sleep_job(seconds: f64, nonce: u64) -> Value {
    json!({"kind": "test_sleep", "spec": {"seconds": seconds, "nonce": nonce}})
}

/// Assert a response is a problem+json with `status` and `code`; return the problem.
pub async fn expect_problem(res: reqwest::Response, status: u16, code: &str) -> Value {
    assert_eq!(res.status().as_u16(), status, "status");
    let ct = res.headers().get("content-type").and_then(|v| v.to_str().ok()).unwrap_or("").to_string();
    assert_eq!(ct, "application/problem+json", "content type");
    let body: Value = res.json().await.expect("problem body");
    assert_eq!(body["code"], code, "problem code in {body}");
    assert_eq!(body["status"], status);
    assert!(body["type"].as_str().unwrap().starts_with("urn:tribod:problem:"));
    assert!(body["title"].is_string() && body["detail"].is_string());
    body
}

/// The store backend a test body runs against.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Backend {
    Sqlite,
    Postgres,
}

/// The environment variable naming the PostgreSQL server for tests (`.ci/run` sets it).
pub const POSTGRES_ENV: &str = "TRIBOD_TEST_POSTGRES_URL";

tokio::task_local! {
    static BACKEND: Backend;
}

/// The backend of the running test body (SQLite outside [`on_backend`]).
pub fn backend() -> Backend {
    BACKEND.try_with(|b| *b).unwrap_or(Backend::Sqlite)
}

/// The PostgreSQL server for tests, if `TRIBOD_TEST_POSTGRES_URL` is set.
pub fn postgres_url() -> Option<String> {
    std::env::var(POSTGRES_ENV).ok().filter(|u| !u.trim().is_empty())
}

/// Whether a PostgreSQL test may run; if not, say so loudly (the test then passes as skipped).
pub fn postgres_available(test: &str) -> bool {
    if postgres_url().is_some() {
        return true;
    }
    eprintln!("SKIPPED {test} on PostgreSQL: set {POSTGRES_ENV} (e.g. postgres://root@127.0.0.1:5432/test) to run it");
    false
}

/// Run `body` with every server it starts on `backend`.
pub async fn on_backend(backend: Backend, test: &str, body: impl std::future::Future<Output = ()>) {
    if backend == Backend::Postgres && !postgres_available(test) {
        return;
    }
    BACKEND.scope(backend, body).await
}

/// A config like [`config`] on the backend of the running test body.
pub async fn test_config(dir: &tempfile::TempDir) -> ServeConfig {
    let mut cfg = config(dir);
    if backend() == Backend::Postgres {
        cfg.database_url = fresh_postgres_database().await;
    }
    cfg
}

/// Create an empty database `tribod_t_<unix seconds>_<random>` on the test server and return its
/// URL. Databases of earlier runs older than an hour are dropped on the way (tests leave theirs
/// behind because a restarted server must find its data).
pub async fn fresh_postgres_database() -> String {
    use sqlx::{Connection, Executor, Row};
    let admin = postgres_url().expect("TRIBOD_TEST_POSTGRES_URL");
    let mut conn = sqlx::PgConnection::connect(&admin).await.expect("connect to the test PostgreSQL");
    let now = std::time::SystemTime::now().duration_since(std::time::UNIX_EPOCH).unwrap().as_secs();
    let old: Vec<String> = sqlx::query("SELECT datname FROM pg_database WHERE datname LIKE 'tribod\\_t\\_%'")
        .fetch_all(&mut conn)
        .await
        .expect("list test databases")
        .iter()
        .map(|r| r.get::<String, _>(0))
        .filter(|name| {
            let secs = name.trim_start_matches("tribod_t_").split('_').next().and_then(|s| s.parse::<u64>().ok());
            secs.is_some_and(|s| s + 3600 < now)
        })
        .collect();
    for name in old {
        let _ = conn.execute(sqlx::AssertSqlSafe(format!("DROP DATABASE IF EXISTS \"{name}\" WITH (FORCE)"))).await;
    }
    let name = format!("tribod_t_{now}_{}", uuid::Uuid::now_v7().simple());
    conn.execute(sqlx::AssertSqlSafe(format!("CREATE DATABASE \"{name}\""))).await.expect("create a test database");
    let _ = conn.close().await;
    with_database(&admin, &name)
}

/// `url` with its database path replaced by `name`.
pub fn with_database(url: &str, name: &str) -> String {
    let (base, query) = match url.split_once('?') {
        Some((b, q)) => (b, Some(q)),
        None => (url, None),
    };
    let scheme_end = base.find("://").map(|i| i + 3).unwrap_or(0);
    let host_end = base[scheme_end..].find('/').map(|i| scheme_end + i).unwrap_or(base.len());
    let mut out = format!("{}/{name}", &base[..host_end]);
    if let Some(q) = query {
        out.push('?');
        out.push_str(q);
    }
    out
}

/// Generate, for each named `async fn` test body in the calling module, one test on SQLite
/// (`sqlite::<name>`) and one on PostgreSQL (`postgres::<name>`, skipped loudly without
/// `TRIBOD_TEST_POSTGRES_URL`).
macro_rules! on_both_backends {
    ($($name:ident),* $(,)?) => {
        mod sqlite {
            $(
                #[tokio::test(flavor = "multi_thread", worker_threads = 2)]
                async fn $name() {
                    crate::common::on_backend(crate::common::Backend::Sqlite, stringify!($name), super::$name()).await
                }
            )*
        }
        mod postgres {
            $(
                #[tokio::test(flavor = "multi_thread", worker_threads = 2)]
                async fn $name() {
                    crate::common::on_backend(crate::common::Backend::Postgres, stringify!($name), super::$name()).await
                }
            )*
        }
    };
}

/// A `wear` spec from a flat description: the pair's fields (those of a `cam_cycle` spec) go into
/// `cycle`, the wear fields stay at the top.
pub fn wear_spec(flat: Value) -> Value {
    const PAIR: [&str; 12] =
        ["cam", "follower", "operation", "load", "lubricant", "asperities", "traction", "film", "slip", "fidelity", "ehl", "angles"];
    let mut cycle = serde_json::Map::new();
    let mut spec = serde_json::Map::new();
    for (k, v) in flat.as_object().expect("an object").clone() {
        if PAIR.contains(&k.as_str()) {
            cycle.insert(k, v);
        } else {
            spec.insert(k, v);
        }
    }
    spec.insert("cycle".into(), Value::Object(cycle));
    Value::Object(spec)
}
