//! Crash recovery with the real binary: start `tribod serve`, submit, kill -9, start again on the
//! same SQLite file. The interrupted job runs again and finishes; nothing accepted is lost.

use serde_json::{json, Value};
use std::io::{BufRead, BufReader};
use std::process::{Child, Command, Stdio};
use std::time::{Duration, Instant};

struct Proc {
    child: Child,
    base: String,
}

impl Drop for Proc {
    fn drop(&mut self) {
        let _ = self.child.kill();
        let _ = self.child.wait();
    }
}

fn spawn(db: &str, extra: &[&str]) -> Proc {
    let mut child = Command::new(env!("CARGO_BIN_EXE_tribod"))
        .args(["serve", "--addr", "127.0.0.1:0", "--database-url", db, "--workers", "1"])
        .args(extra)
        .env("RUST_LOG", "warn")
        .stdout(Stdio::piped())
        .stderr(Stdio::null())
        .spawn()
        .expect("spawn tribod serve");
    let mut line = String::new();
    BufReader::new(child.stdout.take().unwrap()).read_line(&mut line).expect("listening line");
    let base = line.trim().strip_prefix("tribod listening on ").expect("listening line format").to_string();
    Proc { child, base }
}

async fn job(client: &reqwest::Client, base: &str, id: &str) -> Value {
    client.get(format!("{base}/v1/jobs/{id}")).send().await.unwrap().json().await.unwrap()
}

async fn wait_for(client: &reqwest::Client, base: &str, id: &str, statuses: &[&str]) -> Value {
    let start = Instant::now();
    loop {
        let j = job(client, base, id).await;
        if statuses.iter().any(|s| j["status"] == *s) || start.elapsed() > Duration::from_secs(30) {
            return j;
        }
        tokio::time::sleep(Duration::from_millis(20)).await;
    }
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn killed_server_resumes_interrupted_jobs_and_loses_nothing() {
    let dir = tempfile::tempdir().unwrap();
    let db = dir.path().join("jobs.db").display().to_string();
    let client = reqwest::Client::new();

    let a = spawn(&db, &[]);
    let done: Value = client
        .post(format!("{}/v1/jobs", a.base))
        .header("prefer", "wait=10")
        .json(&json!({"kind": "hertz", "spec": {"contact": "point", "load": 10.0,
            "body_1": {"shape": "sphere", "radius": 0.01}, "body_2": {"shape": "flat"}}}))
        .send()
        .await
        .unwrap()
        .json()
        .await
        .unwrap();
    assert_eq!(done["status"], "succeeded");
    let slow: Value = client
        .post(format!("{}/v1/jobs", a.base))
        .json(&json!({"kind": "test_sleep", "spec": {"seconds": 1.0}}))
        .send()
        .await
        .unwrap()
        .json()
        .await
        .unwrap();
    let waiting: Value = client
        .post(format!("{}/v1/jobs", a.base))
        .json(&json!({"kind": "test_sleep", "spec": {"seconds": 0.1, "nonce": 2}}))
        .send()
        .await
        .unwrap()
        .json()
        .await
        .unwrap();
    let slow_id = slow["id"].as_str().unwrap();
    let waiting_id = waiting["id"].as_str().unwrap();
    assert_eq!(wait_for(&client, &a.base, slow_id, &["running"]).await["status"], "running");
    drop(a); // SIGKILL: no graceful shutdown.

    let b = spawn(&db, &[]);
    let slow_done = wait_for(&client, &b.base, slow_id, &["succeeded", "failed", "canceled"]).await;
    assert_eq!(slow_done["status"], "succeeded", "{slow_done}");
    assert_eq!(slow_done["attempts"], 2, "the interrupted attempt counts");
    let waiting_done = wait_for(&client, &b.base, waiting_id, &["succeeded", "failed", "canceled"]).await;
    assert_eq!(waiting_done["status"], "succeeded");
    assert_eq!(waiting_done["attempts"], 1);
    let earlier = job(&client, &b.base, done["id"].as_str().unwrap()).await;
    assert_eq!(earlier["status"], "succeeded");
    let result: Value =
        client.get(format!("{}/v1/jobs/{}/result", b.base, done["id"].as_str().unwrap())).send().await.unwrap().json().await.unwrap();
    assert!(result["max_pressure"].as_f64().unwrap() > 0.0);
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_job_interrupted_too_often_fails_with_a_reason() {
    let dir = tempfile::tempdir().unwrap();
    let db = dir.path().join("jobs.db").display().to_string();
    let client = reqwest::Client::new();
    let a = spawn(&db, &["--max-attempts", "1"]);
    let slow: Value = client
        .post(format!("{}/v1/jobs", a.base))
        .json(&json!({"kind": "test_sleep", "spec": {"seconds": 30.0}}))
        .send()
        .await
        .unwrap()
        .json()
        .await
        .unwrap();
    let id = slow["id"].as_str().unwrap();
    wait_for(&client, &a.base, id, &["running"]).await;
    drop(a);
    let b = spawn(&db, &["--max-attempts", "1"]);
    let j = job(&client, &b.base, id).await;
    assert_eq!(j["status"], "failed", "{j}");
    assert_eq!(j["error"]["code"], "interrupted");
}
