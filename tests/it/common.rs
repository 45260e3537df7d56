//! Shared helpers of the HTTP tests: a real server on a loopback port with a temporary SQLite file,
//! and a real HTTP client.
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
    let mut cfg = config(&dir);
    tweak(&mut cfg);
    start_in(dir, cfg).await
}

pub async fn start_in(dir: tempfile::TempDir, cfg: ServeConfig) -> TestServer {
    let db = cfg.database_url.clone();
    let server = Server::start(cfg).await.expect("server starts");
    TestServer {
        base: format!("http://{}", server.addr),
        client: reqwest::Client::new(),
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
