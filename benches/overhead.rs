//! The service's own cost per job (issue 46 item 4), stage by stage, in one warm process.
//!
//! `cargo bench --bench overhead [-- REPS]`: for a tiny `hertz` job, the ROSS plain-bearing case
//! (41×121) and seed 001's `ehl_point`, the median CPU-free wall time of each stage a job passes
//! through from the request body to the stored bytes — body → JSON, request shape, validation
//! (typed parse, rules, cost, canonical form), canonical text + hash, auto label, the worker's
//! preparation of the stored spec, the solve (physics alone beside it where the bench can call
//! it), the result text and its encoding for the store — then each job end to end through a
//! release `tribod serve` on SQLite (`Prefer: wait`, one client: POST → solved → stored →
//! answered), whose difference from the in-process stages is the store, HTTP and hand-off.
//! `TRIBOD_BENCH_BIN` names another build of the server (an A/B in one run).

use serde_json::{json, Value};
use std::io::{BufRead, BufReader};
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};
use tribod::jobs::kind::{parse_value, Limits};
use tribod::jobs::kinds::bearing::BearingSpec;
use tribod::jobs::{label, registry, runner};
use tribod::physics::{journal, Silent};

/// Median wall time of `f` over `reps` calls, µs.
fn median_us<T>(reps: usize, mut f: impl FnMut() -> T) -> f64 {
    let mut t: Vec<f64> = (0..reps)
        .map(|_| {
            let s = Instant::now();
            std::hint::black_box(f());
            s.elapsed().as_secs_f64() * 1e6
        })
        .collect();
    t.sort_by(f64::total_cmp);
    t[t.len() / 2]
}

/// The ROSS plain-bearing case (issue 18; `benches/journal.rs`) as a `bearing` job at 41×121.
fn ross() -> Value {
    json!({"kind": "bearing", "spec": {
        "geometry": {"radius": 0.2, "length": 0.263144, "radial_clearance": 1.95e-4},
        "operating": {"speed_rpm": 900, "viscosity": 0.02},
        "load": {"force": 112814.91},
        "grid": {"circumferential": 41, "axial": 121}}})
}

fn tiny() -> Value {
    json!({"kind": "hertz", "spec": {"contact": "line", "load": 1000.0, "length": 0.01,
        "body_1": {"shape": "cylinder", "radius": 0.02}, "body_2": {"shape": "flat"}}})
}

fn example(name: &str) -> Value {
    let path = format!("{}/examples/{name}.json", env!("CARGO_MANIFEST_DIR"));
    serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap()
}

/// One row: the in-process stages of `job`, µs.
fn stages(name: &str, job: &Value, reps: usize) -> Vec<(String, f64)> {
    let body = serde_json::to_string(job).unwrap();
    let limits = Limits::default();
    let kind = registry::find(job["kind"].as_str().unwrap()).unwrap();
    let mut out = Vec::new();
    out.push(("body → JSON".into(), median_us(reps, || serde_json::from_str::<Value>(&body).unwrap())));
    let value: Value = serde_json::from_str(&body).unwrap();
    out.push((
        "request shape".into(),
        median_us(reps, || parse_value::<tribod::api::jobs::JobRequest>(&value).unwrap()),
    ));
    let spec = &job["spec"];
    out.push(("validate (parse, rules, cost, canonical)".into(), median_us(reps, || kind.prepare(spec, &limits).unwrap())));
    let canonical = kind.prepare(spec, &limits).unwrap().canonical;
    out.push((
        "canonical text + hash".into(),
        median_us(reps, || runner::spec_hash(kind.name(), &serde_json::to_string(&canonical).unwrap())),
    ));
    let text = serde_json::to_string(&canonical).unwrap();
    let hash = runner::spec_hash(kind.name(), &text);
    out.push(("auto label".into(), median_us(reps, || label::auto_label(kind, &canonical, &hash))));
    out.push((
        "worker: stored spec → prepared".into(),
        median_us(reps, || kind.prepare(&serde_json::from_str::<Value>(&text).unwrap(), &limits).unwrap()),
    ));
    let solve_reps = reps.min(200);
    out.push((
        "solve + result document (meta.wall_time_seconds)".into(),
        median_us(solve_reps, || runner::run(kind.prepare(spec, &limits).unwrap(), &Silent)),
    ));
    if name == "ross" {
        let b: BearingSpec = serde_json::from_value(canonical.clone()).unwrap();
        let case = b.case().unwrap();
        out.push(("  of it physics (journal::case::solve)".into(), median_us(solve_reps, || journal::case::solve(&case, &Silent).unwrap())));
    }
    let (outcome, _) = runner::run(kind.prepare(spec, &limits).unwrap(), &Silent);
    let runner::Outcome::Succeeded(result) = outcome else { panic!("{name} failed") };
    out.push(("result text".into(), median_us(reps, || serde_json::to_string(&result).unwrap())));
    let result_text = serde_json::to_string(&result).unwrap();
    out.push((
        format!("encode for the store ({} bytes)", result_text.len()),
        median_us(reps, || tribod::store::encode_result(&result_text)),
    ));
    out
}

/// Median POST → answered latency of `job` through a release server on SQLite, with
/// `Prefer: wait` (each job a new spec: `fresh=true`), µs.
async fn end_to_end(base: &str, job: &Value, reps: usize) -> f64 {
    let client = reqwest::Client::new();
    let url = format!("{base}/v1/jobs?fresh=true");
    let body = serde_json::to_string(job).unwrap();
    let mut t = Vec::with_capacity(reps);
    for i in 0..reps + 20 {
        let s = Instant::now();
        let r = client.post(&url).header("content-type", "application/json").header("prefer", "wait=10").body(body.clone()).send().await.unwrap();
        assert_eq!(r.status().as_u16(), 200);
        r.bytes().await.unwrap();
        if i >= 20 {
            t.push(s.elapsed().as_secs_f64() * 1e6);
        }
    }
    t.sort_by(f64::total_cmp);
    t[t.len() / 2]
}

fn main() {
    let args: Vec<String> = std::env::args().skip(1).filter(|a| !a.starts_with("--")).collect();
    let reps: usize = args.first().and_then(|s| s.parse().ok()).unwrap_or(2000);
    tribod::jobs::warm_up();
    let jobs = [("hertz", tiny()), ("ross", ross()), ("ehl_point", example("seed001_nose_point"))];

    let dir = tempfile::tempdir().unwrap();
    let db = dir.path().join("overhead.db").display().to_string();
    let binary = std::env::var("TRIBOD_BENCH_BIN").unwrap_or_else(|_| env!("CARGO_BIN_EXE_tribod").to_string());
    let mut child = Command::new(binary)
        .args(["serve", "--addr", "127.0.0.1:0", "--database-url", &db, "--workers", "1"])
        .env("RUST_LOG", "warn")
        .stdout(Stdio::piped())
        .stderr(Stdio::null())
        .spawn()
        .expect("start tribod serve");
    let mut line = String::new();
    BufReader::new(child.stdout.take().unwrap()).read_line(&mut line).unwrap();
    let base = line.trim().trim_start_matches("tribod listening on ").to_string();
    std::thread::sleep(Duration::from_millis(300));
    let rt = tokio::runtime::Builder::new_current_thread().enable_all().build().unwrap();

    println!("## Per-job overhead, µs (median of {reps}; solves of at most 200)\n");
    for (name, job) in &jobs {
        let rows = stages(name, job, reps);
        let e2e = rt.block_on(end_to_end(&base, job, (reps / 10).max(20)));
        println!("### {name}\n\n| stage | µs |\n| --- | ---: |");
        let mut sum = 0.0;
        for (stage, us) in &rows {
            println!("| {stage} | {us:.1} |");
            if !stage.starts_with("  ") {
                sum += us;
            }
        }
        println!("| in-process stages together | {sum:.1} |");
        println!("| POST → solved → stored → answered (server, SQLite, `Prefer: wait`) | {e2e:.1} |");
        println!("| of it store, HTTP and hand-off | {:.1} |\n", e2e - sum);
    }
    let _ = child.kill();
    let _ = child.wait();
}
