//! Issue 40: every job's cost known before it runs (work and memory models, refused over the
//! limits, stored with the job), physical bounds on every input, cancel inside the 2-D solver,
//! and no accepted spec ending in `internal_error`.

use crate::common::*;
use serde_json::{json, Value};
use std::time::{Duration, Instant};
use tribod::jobs::{registry, Limits};

fn kind_example(name: &str) -> Value {
    registry::find(name).expect("kind").example()
}

fn example_file(name: &str) -> Value {
    let path = format!("{}/examples/{name}.json", env!("CARGO_MANIFEST_DIR"));
    serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap()
}

/// A circular point contact on an `n × n` grid (the 2-D solver's cost grows as n^2.8).
fn point_contact(n: usize) -> Value {
    json!({"kind": "ehl_point", "spec": {"load": 100.0, "length": 0.01, "reduced_radius": 0.01,
        "entrainment_velocity": 1.0, "lubricant": {"viscosity": 0.04, "pressure_viscosity": 2e-8},
        "geometry": {"type": "point", "rx": 0.01, "ry": 0.01, "nx": n, "ny": n}}})
}

#[tokio::test]
async fn a_job_over_the_work_limit_is_refused_with_its_estimate_and_an_accepted_one_carries_it() {
    let s = start().await;
    // The outside check: a finite-line cycle of 36,000 angles on 513×513 nodes.
    let mut cycle = example_file("seed000_finite_cycle");
    cycle["spec"]["angles"] = json!(36_000);
    cycle["spec"]["ehl"]["nx"] = json!(513);
    cycle["spec"]["ehl"]["ny"] = json!(513);
    let p = expect_problem(s.post_job(&cycle).await, 422, "limit_exceeded").await;
    let text = p.to_string();
    assert!(text.contains("/spec/angles") && text.contains("of solver time") && text.contains("--max-job-seconds"), "{p}");
    assert!(text.contains("days"), "the estimate is stated: {p}");
    // Memory: the cycle keeps a 2-D film per angle.
    assert!(text.contains("MiB"), "{p}");

    // A sweep's total is the sum of its cases: each of 1000 rough contacts (~10 s) is accepted
    // alone, their sweep is not.
    let mut rough = kind_example("rough_contact");
    rough["surface"]["points"] = json!(256);
    let one = json!({"kind": "rough_contact", "spec": rough.clone()});
    let prepared = registry::find("rough_contact").unwrap().prepare(&one["spec"], &Limits::default()).expect("one case is accepted");
    assert!(prepared.cost.cpu_seconds() < 60.0);
    let seeds: Vec<u64> = (1..=1000).collect();
    let sweep = json!({"kind": "sweep", "spec": {"kind": "rough_contact", "base": rough,
        "parameters": [{"path": "/surface/seed", "values": seeds}]}});
    let p = expect_problem(s.post_job(&sweep).await, 422, "limit_exceeded").await;
    assert!(p.to_string().contains("/spec/parameters") && p.to_string().contains("1000 cases"), "{p}");

    // An accepted job carries its estimate (GET and the result's meta).
    let res = s.post_job(&hertz_job(1000.0)).await;
    assert_eq!(res.status(), 202);
    let job: Value = res.json().await.unwrap();
    let id = job["id"].as_str().unwrap().to_string();
    let seconds = job["estimate"]["cpu_seconds"].as_f64().expect("estimate on the answer");
    assert!(seconds > 0.0 && seconds < 0.01, "{job}");
    let done = s.wait_finished(&id, Duration::from_secs(30)).await;
    assert_eq!(done["estimate"]["cpu_seconds"].as_f64(), Some(seconds), "{done}");
    assert!(done["estimate"]["memory_bytes"].as_f64().is_some(), "{done}");
    let (_, result) = s.get_json(&format!("/v1/jobs/{id}/result")).await;
    assert_eq!(result["meta"]["estimate"]["cpu_seconds"].as_f64(), Some(seconds), "{result}");
    s.stop().await;
}

#[tokio::test]
async fn absurd_magnitudes_are_field_errors_with_units() {
    let s = start().await;
    // The outside check: an ehl_point load of 1e308 N.
    let mut ehl = json!({"kind": "ehl_point", "spec": kind_example("ehl_point")});
    ehl["spec"]["load"] = json!(1e308);
    let p = expect_problem(s.post_job(&ehl).await, 422, "invalid_spec").await;
    let text = p.to_string();
    assert!(text.contains("/spec/load") && text.contains(" N"), "{p}");
    // cam_point: a load of 1e300 N, a radius or length of 1e-300 m (these used to end in a 500).
    for (path, x) in [("/load", 1e300), ("/reduced_radius", 1e-300), ("/contact_length", 1e-300)] {
        let mut cam = json!({"kind": "cam_point", "spec": kind_example("cam_point")});
        *cam["spec"].pointer_mut(path).unwrap() = json!(x);
        let p = expect_problem(s.post_job(&cam).await, 422, "invalid_spec").await;
        assert!(p.to_string().contains(&format!("/spec{path}")), "{path}: {p}");
    }
    // Grid sizes whose product overflows (schemathesis found a rough_contact table of
    // 9948166445796346 × 222217139 points ending in a 500 "multiply with overflow").
    let table = json!({"kind": "rough_contact", "spec": {"surface": {"type": "table", "nx": 9948166445796346u64, "ny": 222217139u64, "spacing": 1e-6, "heights": vec![0.0; 256]}}});
    let p = expect_problem(s.post_job(&table).await, 422, "invalid_spec").await;
    assert!(p.to_string().contains("/spec/surface/nx"), "{p}");
    let mut point = json!({"kind": "ehl_point", "spec": kind_example("ehl_point")});
    point["spec"]["geometry"] = json!({"type": "finite", "nx": 9948166445796346u64, "ny": 222217139u64});
    let status = s.post_job(&point).await.status().as_u16();
    assert!(status == 422 || status == 400, "ehl_point with an overflowing grid: {status}");
    s.stop().await;
}

/// Every numeric field of every kind's example set to hostile magnitudes: refused as a field
/// error, or (when the work model says it is quick) solved or failed with a typed physical
/// problem — never `internal_error`.
#[test]
fn no_accepted_spec_ends_in_internal_error() {
    fn numeric_pointers(v: &Value, at: String, out: &mut Vec<String>) {
        match v {
            Value::Number(_) => out.push(at),
            Value::Object(m) => m.iter().for_each(|(k, x)| numeric_pointers(x, format!("{at}/{k}"), out)),
            Value::Array(a) => a.iter().take(3).enumerate().for_each(|(i, x)| numeric_pointers(x, format!("{at}/{i}"), out)),
            _ => {}
        }
    }
    let (mut refused, mut solved, mut failed) = (0, 0, 0);
    let mut internal = Vec::new();
    for kind in registry::KINDS.iter().filter(|k| !["sweep", "bearing_optimisation", "cam_optimisation", "test_sleep"].contains(&k.name())) {
        let example = kind.example();
        let mut pointers = Vec::new();
        numeric_pointers(&example, String::new(), &mut pointers);
        for pointer in &pointers {
            for x in [1e300, -1e300, 1e-300, 0.0, -1.0, 1e12] {
                let mut spec = example.clone();
                *spec.pointer_mut(pointer).unwrap() = json!(x);
                let prepared = match kind.prepare(&spec, &Limits::default()) {
                    Ok(p) => p,
                    Err(p) => {
                        if p.code == "internal_error" {
                            internal.push(format!("{} {pointer} = {x:e} refused as {p:?}", kind.name()));
                        }
                        refused += 1;
                        continue;
                    }
                };
                // Quick ones only (the debug build is ~5× slower than the model's release).
                if prepared.cost.cpu_seconds() > 0.05 {
                    continue;
                }
                match tribod::jobs::runner::run(prepared, &tribod::physics::Silent).0 {
                    tribod::jobs::runner::Outcome::Succeeded(_) => solved += 1,
                    tribod::jobs::runner::Outcome::Failed(p) => {
                        if p.code == "internal_error" {
                            internal.push(format!("{} {pointer} = {x:e} was accepted and ended in {}", kind.name(), p.detail));
                        }
                        failed += 1;
                    }
                    tribod::jobs::runner::Outcome::Interrupted(i) => panic!("{i:?}"),
                }
            }
        }
    }
    eprintln!("hostile magnitudes: {refused} refused, {solved} solved, {failed} failed with a typed problem");
    assert!(internal.is_empty(), "{} internal errors:\n{}", internal.len(), internal.join("\n"));
    assert!(refused > 100 && solved > 10, "{refused} refused, {solved} solved");
}

#[tokio::test]
async fn a_running_2d_ehl_point_is_cancelled_within_two_seconds() {
    let s = start_with(|c| {
        c.queue.limits.max_job_seconds = f64::INFINITY;
        c.queue.limits.max_job_memory = u64::MAX;
    })
    .await;
    // 257² (a minute or more in a test build): cancel once it is running and past its first
    // grid level; then it must end within 2 s.
    let res = s.post_job(&point_contact(257)).await;
    assert_eq!(res.status(), 202);
    let id = res.json::<Value>().await.unwrap()["id"].as_str().unwrap().to_string();
    let started = Instant::now();
    let mut fractions = Vec::new();
    loop {
        let (_, job) = s.get_json(&format!("/v1/jobs/{id}")).await;
        let f = job["progress"]["fraction"].as_f64().unwrap_or(0.0);
        if fractions.last() != Some(&f) {
            fractions.push(f);
        }
        if job["status"] == "running" && f > 0.05 {
            break;
        }
        assert!(started.elapsed() < Duration::from_secs(120), "never got going: {job}");
        tokio::time::sleep(Duration::from_millis(100)).await;
    }
    let t = Instant::now();
    let res = s.client.delete(s.url(&format!("/v1/jobs/{id}"))).send().await.unwrap();
    assert!(res.status().is_success(), "{}", res.status());
    let job = s.wait_status(&id, "canceled", Duration::from_secs(10)).await;
    let took = t.elapsed();
    assert!(took < Duration::from_secs(2), "cancel took {took:?}: {job}");
    assert!(fractions.len() >= 3, "progress moved inside the 2-D solve: {fractions:?}");
    s.stop().await;
}

/// The memory model bounds what a job really allocates: a 2-D solve run by `tribod run` with the
/// memory limit just above its estimate stays under that limit (its peak resident memory, VmHWM
/// read from `/proc/<pid>/status` while it runs, above an idle process's).
#[test]
fn an_accepted_job_stays_under_its_memory_limit() {
    fn peak_bytes(request: &Value, limit_mb: u64) -> (bool, f64) {
        let dir = tempfile::tempdir().unwrap();
        let file = dir.path().join("case.json");
        std::fs::write(&file, serde_json::to_vec(request).unwrap()).unwrap();
        let mut child = std::process::Command::new(env!("CARGO_BIN_EXE_tribod"))
            .args(["run", "--compact", "--max-job-seconds", "0", "--max-job-memory-mb", &limit_mb.to_string()])
            .arg(&file)
            .stdout(std::process::Stdio::null())
            .stderr(std::process::Stdio::null())
            .spawn()
            .unwrap();
        let status_file = format!("/proc/{}/status", child.id());
        let mut hwm_kb = 0.0_f64;
        let status = loop {
            if let Ok(text) = std::fs::read_to_string(&status_file) {
                if let Some(kb) = text.lines().find_map(|l| l.strip_prefix("VmHWM:")).and_then(|v| v.trim().trim_end_matches("kB").trim().parse::<f64>().ok()) {
                    hwm_kb = hwm_kb.max(kb);
                }
            }
            if let Some(status) = child.try_wait().unwrap() {
                break status;
            }
            std::thread::sleep(Duration::from_millis(5));
        };
        (status.success(), hwm_kb * 1024.0)
    }
    let (_, idle) = peak_bytes(&hertz_job(1000.0), 1 << 20);
    let request = point_contact(129);
    let cost = registry::find("ehl_point").unwrap().prepare(&request["spec"], &Limits::UNLIMITED).unwrap().cost;
    let limit_mb = (cost.memory_bytes() / 1048576.0).ceil() as u64 + 1;
    let (ok, peak) = peak_bytes(&request, limit_mb);
    assert!(ok, "accepted at {limit_mb} MiB");
    let used = peak - idle;
    eprintln!("129² point contact: model {:.0} MiB, measured {:.0} MiB above idle ({:.0} MiB)", cost.memory_bytes() / 1048576.0, used / 1048576.0, idle / 1048576.0);
    assert!(used <= limit_mb as f64 * 1048576.0, "peak {used} bytes over the {limit_mb} MiB limit");
    assert!(used >= cost.memory_bytes() / 1.5, "the model is not a loose bound: {used} bytes against {}", cost.memory_bytes());
    // Below the estimate it is refused before anything is allocated.
    let (refused_ok, _) = peak_bytes(&request, limit_mb / 2);
    assert!(!refused_ok);
}

/// Fair scheduling after a restart: the queued jobs' stored estimates order the queue from the
/// first claim (it used to start every kind at 1 s, so a tiny job waited behind the backlog).
#[tokio::test]
async fn a_tiny_job_does_not_wait_behind_a_backlog_after_a_restart() {
    let dir = tempfile::tempdir().unwrap();
    let mut cfg = test_config(&dir).await;
    // The backlog is queued by an instance that serves the API only; the restarted one solves.
    cfg.queue.workers = 0;
    let s = start_in(dir, cfg.clone()).await;
    let mut heavy = Vec::new();
    for i in 0..6 {
        let res: Value = s.post_job(&sleep_job(2.0, 700 + i)).await.json().await.unwrap();
        heavy.push(res["id"].as_str().unwrap().to_string());
    }
    let dir = s.stop().await;
    // A new process on the same database: nothing measured yet, only the stored estimates. Its
    // first claim may take a heavy job before the tiny one arrives.
    cfg.queue.workers = 1;
    let s = start_in(dir, cfg).await;
    let tiny: Value = s.post_job(&hertz_job(4321.0)).await.json().await.unwrap();
    let tiny = s.wait_finished(tiny["id"].as_str().unwrap(), Duration::from_secs(20)).await;
    assert_eq!(tiny["status"], "succeeded");
    // Once the tiny job is queued it is the next one claimed: no heavy job starts between its
    // acceptance and its start. How many heavy jobs started before it arrived depends on how fast
    // this machine answered the POST after the restart, not on the scheduler, so only the ones
    // that started after it arrived count. The times are parsed: RFC 3339 drops trailing zeros of
    // the fraction, so as text "10.532Z" sorts before "10.53Z" (this test once failed on that).
    let at = |job: &Value, field: &str| job[field].as_str().map(|t| time::OffsetDateTime::parse(t, &time::format_description::well_known::Rfc3339).unwrap());
    let (tiny_created, tiny_started) = (at(&tiny, "created_at").unwrap(), at(&tiny, "started_at").unwrap());
    // The server writes three fraction digits always, so its times also sort as text.
    for field in ["created_at", "started_at", "finished_at"] {
        let text = tiny[field].as_str().unwrap();
        assert!(text.len() == 24 && text.as_bytes()[19] == b'.' && text.ends_with('Z'), "{field}: {text}");
    }
    let mut jumped = Vec::new();
    for id in &heavy {
        let (_, job) = s.get_json(&format!("/v1/jobs/{id}")).await;
        if let Some(t) = at(&job, "started_at") {
            if t > tiny_created && t < tiny_started {
                jumped.push(t);
            }
        }
    }
    assert!(jumped.is_empty(), "heavy jobs started at {jumped:?}, after the tiny one was queued at {tiny_created} and before it started at {tiny_started}");
    s.stop().await;
}

/// Short-job slots (issue 46 item 5): with the only worker busy on a long job and another long one
/// queued, a tiny job (estimated ≤ 10 ms) runs at once on a short-job slot instead of waiting
/// seconds; a long job never takes a short-job slot.
#[tokio::test]
async fn a_tiny_job_runs_beside_long_jobs_that_fill_every_worker() {
    let s = start_with(|c| {
        c.queue.workers = 1;
        c.queue.short_slots = 2;
    })
    .await;
    let mut long = Vec::new();
    for i in 0..2 {
        let res: Value = s.post_job(&sleep_job(3.0, 800 + i)).await.json().await.unwrap();
        long.push(res["id"].as_str().unwrap().to_string());
    }
    s.wait_status(&long[0], "running", Duration::from_secs(10)).await;
    let t = Instant::now();
    let tiny: Value = s.post_job(&hertz_job(4322.0)).await.json().await.unwrap();
    let tiny = s.wait_finished(tiny["id"].as_str().unwrap(), Duration::from_secs(20)).await;
    let took = t.elapsed();
    assert_eq!(tiny["status"], "succeeded");
    assert!(took < Duration::from_millis(1500), "the tiny job took {took:?} beside a 3 s job on the only worker");
    let (_, first) = s.get_json(&format!("/v1/jobs/{}", long[0])).await;
    let (_, second) = s.get_json(&format!("/v1/jobs/{}", long[1])).await;
    assert_eq!(first["status"], "running", "{first}");
    assert_eq!(second["status"], "queued", "a long job took a short-job slot: {second}");
    s.stop().await;
}
