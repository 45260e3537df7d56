//! Service throughput: tiny `hertz` jobs through HTTP + SQLite with concurrent clients.
//!
//! `cargo bench --bench http [-- JOBS CLIENTS]` starts the release `tribod serve` on a loopback
//! port with a fresh SQLite file, then measures: end-to-end jobs/s (POST → solved → stored) with
//! CLIENTS concurrent submitters, p50/p99 latency of `GET /v1/jobs/{id}` under that load, and the
//! server's resident memory idle and loaded. Client and server share the machine's cores.

use serde_json::{json, Value};
use std::io::{BufRead, BufReader};
use std::process::{Command, Stdio};
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant};

fn rss_kib(pid: u32) -> u64 {
    std::fs::read_to_string(format!("/proc/{pid}/status"))
        .ok()
        .and_then(|s| s.lines().find(|l| l.starts_with("VmRSS:")).and_then(|l| l.split_whitespace().nth(1)?.parse().ok()))
        .unwrap_or(0)
}

fn percentile(sorted: &[f64], p: f64) -> f64 {
    if sorted.is_empty() {
        return f64::NAN;
    }
    sorted[((sorted.len() - 1) as f64 * p).round() as usize]
}

#[tokio::main(flavor = "multi_thread", worker_threads = 2)]
async fn main() {
    let args: Vec<String> = std::env::args().skip(1).filter(|a| !a.starts_with("--")).collect();
    let jobs: usize = args.first().and_then(|s| s.parse().ok()).unwrap_or(20_000);
    let clients: usize = args.get(1).and_then(|s| s.parse().ok()).unwrap_or(32);

    let dir = tempfile::tempdir().unwrap();
    let db = dir.path().join("bench.db").display().to_string();
    let mut child = Command::new(env!("CARGO_BIN_EXE_tribod"))
        .args(["serve", "--addr", "127.0.0.1:0", "--database-url", &db, "--max-queue", "1000000"])
        .env("RUST_LOG", "warn")
        .stdout(Stdio::piped())
        .stderr(Stdio::null())
        .spawn()
        .expect("start tribod serve");
    let pid = child.id();
    let mut line = String::new();
    BufReader::new(child.stdout.take().unwrap()).read_line(&mut line).unwrap();
    let base = line.trim().trim_start_matches("tribod listening on ").to_string();
    let client = reqwest::Client::builder().pool_max_idle_per_host(clients * 2).build().unwrap();
    tokio::time::sleep(Duration::from_millis(300)).await;
    let idle_rss = rss_kib(pid);

    let ids = Arc::new(Mutex::new(Vec::<String>::with_capacity(jobs)));
    let running = Arc::new(AtomicBool::new(true));
    let peak_rss = Arc::new(Mutex::new(idle_rss));

    // Memory sampler.
    let sampler = {
        let (running, peak) = (running.clone(), peak_rss.clone());
        tokio::spawn(async move {
            while running.load(Ordering::Relaxed) {
                let r = rss_kib(pid);
                {
                    let mut p = peak.lock().unwrap();
                    *p = (*p).max(r);
                }
                tokio::time::sleep(Duration::from_millis(50)).await;
            }
        })
    };
    // Readers: GET /v1/jobs/{id} of known jobs while the load runs.
    let mut readers = Vec::new();
    let latencies = Arc::new(Mutex::new(Vec::<f64>::new()));
    for r in 0..4 {
        let (client, base, ids, running, latencies) = (client.clone(), base.clone(), ids.clone(), running.clone(), latencies.clone());
        readers.push(tokio::spawn(async move {
            let mut i = r;
            while running.load(Ordering::Relaxed) {
                let id = {
                    let ids = ids.lock().unwrap();
                    if ids.is_empty() { None } else { Some(ids[(i * 7919) % ids.len()].clone()) }
                };
                i += 1;
                let Some(id) = id else {
                    tokio::time::sleep(Duration::from_millis(5)).await;
                    continue;
                };
                let t = Instant::now();
                let res = client.get(format!("{base}/v1/jobs/{id}")).send().await.unwrap();
                assert_eq!(res.status().as_u16(), 200);
                let _ = res.bytes().await.unwrap();
                latencies.lock().unwrap().push(t.elapsed().as_secs_f64() * 1e3);
            }
        }));
    }

    let start = Instant::now();
    let mut writers = Vec::new();
    for c in 0..clients {
        let (client, base, ids) = (client.clone(), base.clone(), ids.clone());
        writers.push(tokio::spawn(async move {
            let mut k = c;
            while k < jobs {
                // Distinct loads: no dedup, every job is solved.
                let body = json!({"kind": "hertz", "spec": {"contact": "line", "load": 1000.0 + k as f64,
                    "length": 0.01, "body_1": {"shape": "cylinder", "radius": 0.02}, "body_2": {"shape": "flat"}}});
                let res = client.post(format!("{base}/v1/jobs")).json(&body).send().await.unwrap();
                assert_eq!(res.status().as_u16(), 202);
                let v: Value = res.json().await.unwrap();
                ids.lock().unwrap().push(v["id"].as_str().unwrap().to_string());
                k += clients;
            }
        }));
    }
    for w in writers {
        w.await.unwrap();
    }
    let submitted = start.elapsed().as_secs_f64();
    // Wait until every job is solved and stored.
    loop {
        let text = client.get(format!("{base}/metrics")).send().await.unwrap().text().await.unwrap();
        let done = text
            .lines()
            .find(|l| l.starts_with("tribod_jobs{status=\"succeeded\"}"))
            .and_then(|l| l.split_whitespace().nth(1)?.parse::<f64>().ok())
            .unwrap_or(0.0);
        if done as usize >= jobs {
            break;
        }
        tokio::time::sleep(Duration::from_millis(20)).await;
    }
    let finished = start.elapsed().as_secs_f64();
    running.store(false, Ordering::Relaxed);
    for r in readers {
        r.await.unwrap();
    }
    sampler.await.unwrap();
    let loaded_rss = *peak_rss.lock().unwrap();
    let mut lat = latencies.lock().unwrap().clone();
    lat.sort_by(|a, b| a.partial_cmp(b).unwrap());
    let _ = child.kill();
    let _ = child.wait();

    println!("| jobs | clients | submit jobs/s | end-to-end jobs/s | GET p50 ms | GET p99 ms | GETs | idle RSS MiB | peak RSS MiB |");
    println!("|---|---|---|---|---|---|---|---|---|");
    println!(
        "| {jobs} | {clients} | {:.0} | {:.0} | {:.2} | {:.2} | {} | {:.1} | {:.1} |",
        jobs as f64 / submitted,
        jobs as f64 / finished,
        percentile(&lat, 0.5),
        percentile(&lat, 0.99),
        lat.len(),
        idle_rss as f64 / 1024.0,
        loaded_rss as f64 / 1024.0
    );
}
