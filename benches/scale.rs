//! Scale-out: tribod instances sharing one PostgreSQL database, against one instance on SQLite.
//!
//! `cargo bench --bench scale [-- TINY_JOBS HEAVY_JOBS]` (defaults 5000 and 8) needs a PostgreSQL
//! server named by `TRIBOD_TEST_POSTGRES_URL` (e.g. `postgres://root@127.0.0.1:5432/test`); each
//! scenario runs on a fresh database it creates and drops. It measures, with the release binary:
//!
//! * tiny `hertz` jobs end to end (POST → solved → stored) through 1 SQLite instance and 1, 2 and 4
//!   PostgreSQL instances (`serve`, default workers), 32 clients spread round-robin over the
//!   instances: jobs/s, POST latency p50/p99, `GET /v1/jobs/{id}` latency p50/p99 of 4 readers
//!   (each pausing 5 ms between requests), and CPU per job of tribod, PostgreSQL and the machine;
//! * heavy jobs (the seed 002 Taguchi L9, distinct viscosities so none is reused) through an API
//!   instance (`serve --workers 0`) and 1 or 2 `tribod worker --workers 1` instances: jobs/s and
//!   the speed-up of the second worker.
//!
//! `TRIBOD_BENCH_SERVE_ARGS` adds options to every `serve` (e.g. `--workers 4`).
//! `TRIBOD_BENCH_LOG_STATEMENTS=1` logs every statement of the PostgreSQL rows in the server's log
//! (with its duration), to count round trips by kind.
//!
//! A third argument runs only the rows whose name contains it: `sqlite`, `pg1`, `pg2`, `pg4`,
//! `heavy`. Client, servers and PostgreSQL share the machine's cores: on 2 cores the numbers are a floor.

use serde_json::{json, Value};
use sqlx::{Connection, Executor};
use std::io::{BufRead, BufReader};
use std::process::{Child, Command, Stdio};
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant};

struct Instance {
    child: Child,
    base: String,
}

impl Drop for Instance {
    fn drop(&mut self) {
        // SIGTERM first so a serve instance releases its connections; then make sure.
        unsafe {
            libc::kill(self.child.id() as i32, libc::SIGTERM);
        }
        let deadline = Instant::now() + Duration::from_secs(10);
        while Instant::now() < deadline {
            if let Ok(Some(_)) = self.child.try_wait() {
                return;
            }
            std::thread::sleep(Duration::from_millis(20));
        }
        let _ = self.child.kill();
        let _ = self.child.wait();
    }
}

/// The tribod binary: this build's, or `TRIBOD_BENCH_BIN` (an older build, for an A/B in one run).
fn binary() -> String {
    std::env::var("TRIBOD_BENCH_BIN").unwrap_or_else(|_| env!("CARGO_BIN_EXE_tribod").to_string())
}

fn serve(url: &str, extra: &[&str]) -> Instance {
    // `TRIBOD_BENCH_SERVE_ARGS`: more options for every `serve` (e.g. `--workers 4`), to try them.
    let more = std::env::var("TRIBOD_BENCH_SERVE_ARGS").unwrap_or_default();
    let mut child = Command::new(binary())
        .args(["serve", "--addr", "127.0.0.1:0", "--database-url", url, "--max-queue", "1000000"])
        .args(extra)
        .args(more.split_whitespace())
        .env("RUST_LOG", "warn")
        .stdout(Stdio::piped())
        .stderr(Stdio::null())
        .spawn()
        .expect("start tribod serve");
    let mut line = String::new();
    BufReader::new(child.stdout.take().unwrap()).read_line(&mut line).unwrap();
    let base = line.trim().trim_start_matches("tribod listening on ").to_string();
    Instance { child, base }
}

fn worker(url: &str, extra: &[&str]) -> Instance {
    let child = Command::new(binary())
        .args(["worker", "--database-url", url, "--max-queue", "1000000"])
        .args(extra)
        .env("RUST_LOG", "warn")
        .stdout(Stdio::null())
        .stderr(Stdio::null())
        .spawn()
        .expect("start tribod worker");
    Instance { child, base: String::new() }
}

/// CPU seconds (user + system) a process has used.
fn cpu_seconds(pid: u32) -> f64 {
    let ticks = unsafe { libc::sysconf(libc::_SC_CLK_TCK) } as f64;
    std::fs::read_to_string(format!("/proc/{pid}/stat"))
        .ok()
        .and_then(|s| {
            let rest = s.rsplit_once(") ")?.1.split_whitespace().map(str::to_string).collect::<Vec<_>>();
            Some((rest.get(11)?.parse::<f64>().ok()? + rest.get(12)?.parse::<f64>().ok()?) / ticks)
        })
        .unwrap_or(0.0)
}

/// CPU seconds used by all `postgres` processes now alive (the server and its backends).
fn postgres_cpu_seconds() -> f64 {
    let mut total = 0.0;
    for entry in std::fs::read_dir("/proc").into_iter().flatten().flatten() {
        let Some(pid) = entry.file_name().to_str().and_then(|n| n.parse::<u32>().ok()) else { continue };
        if std::fs::read_to_string(format!("/proc/{pid}/comm")).is_ok_and(|c| c.trim() == "postgres") {
            total += cpu_seconds(pid);
        }
    }
    total
}

/// CPU seconds the whole machine spent busy (all cores).
fn machine_busy_seconds() -> f64 {
    let ticks = unsafe { libc::sysconf(libc::_SC_CLK_TCK) } as f64;
    let stat = std::fs::read_to_string("/proc/stat").unwrap_or_default();
    let fields: Vec<f64> = stat.lines().next().unwrap_or("").split_whitespace().skip(1).filter_map(|v| v.parse().ok()).collect();
    // user nice system idle iowait irq softirq steal
    let busy: f64 = fields.iter().enumerate().filter(|(i, _)| *i != 3 && *i != 4).map(|(_, v)| v).sum();
    busy / ticks
}

fn percentile(sorted: &[f64], p: f64) -> f64 {
    if sorted.is_empty() {
        return f64::NAN;
    }
    sorted[((sorted.len() - 1) as f64 * p).round() as usize]
}

async fn create_database(admin: &str) -> (String, String) {
    let mut conn = sqlx::PgConnection::connect(admin).await.expect("connect to PostgreSQL");
    let name = format!("tribod_bench_{}", uuid::Uuid::now_v7().simple());
    conn.execute(sqlx::AssertSqlSafe(format!("CREATE DATABASE \"{name}\""))).await.unwrap();
    let _ = conn.close().await;
    let (head, _) = admin.rsplit_once('/').expect("a URL with a database path");
    (format!("{head}/{name}"), name)
}

async fn drop_database(admin: &str, name: &str) {
    if let Ok(mut conn) = sqlx::PgConnection::connect(admin).await {
        let _ = conn.execute(sqlx::AssertSqlSafe(format!("DROP DATABASE IF EXISTS \"{name}\" WITH (FORCE)"))).await;
        let _ = conn.close().await;
    }
}

/// The number of succeeded jobs as `base`'s /metrics reports it (the database's count).
async fn succeeded(client: &reqwest::Client, base: &str) -> usize {
    let text = client.get(format!("{base}/metrics")).send().await.unwrap().text().await.unwrap();
    text.lines()
        .find(|l| l.starts_with("tribod_jobs{status=\"succeeded\"}"))
        .and_then(|l| l.split_whitespace().nth(1)?.parse::<f64>().ok())
        .unwrap_or(0.0) as usize
}

struct Run {
    jobs_per_s: f64,
    post: Vec<f64>,
    get: Vec<f64>,
}

/// Submit `jobs` bodies from `clients` concurrent clients round-robin over `bases`, read jobs back
/// with 4 readers meanwhile, and wait until all are solved.
async fn drive(bases: &[String], jobs: usize, clients: usize, body: impl Fn(usize) -> Value + Send + Sync + 'static) -> Run {
    let client = reqwest::Client::builder().pool_max_idle_per_host(clients * 2).build().unwrap();
    let body = Arc::new(body);
    let ids = Arc::new(Mutex::new(Vec::<String>::with_capacity(jobs)));
    let running = Arc::new(AtomicBool::new(true));
    let gets = Arc::new(Mutex::new(Vec::<f64>::new()));
    let posts = Arc::new(Mutex::new(Vec::<f64>::new()));
    let mut readers = Vec::new();
    for r in 0..4 {
        let (client, bases, ids, running, gets) = (client.clone(), bases.to_vec(), ids.clone(), running.clone(), gets.clone());
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
                let base = &bases[i % bases.len()];
                let t = Instant::now();
                let res = client.get(format!("{base}/v1/jobs/{id}")).send().await.unwrap();
                assert_eq!(res.status().as_u16(), 200);
                let _ = res.bytes().await.unwrap();
                gets.lock().unwrap().push(t.elapsed().as_secs_f64() * 1e3);
                tokio::time::sleep(Duration::from_millis(5)).await;
            }
        }));
    }
    let start = Instant::now();
    let mut writers = Vec::new();
    for c in 0..clients {
        let (client, bases, ids, posts, body) = (client.clone(), bases.to_vec(), ids.clone(), posts.clone(), body.clone());
        writers.push(tokio::spawn(async move {
            let mut k = c;
            while k < jobs {
                let base = &bases[k % bases.len()];
                let t = Instant::now();
                let res = client.post(format!("{base}/v1/jobs")).json(&body(k)).send().await.unwrap();
                assert_eq!(res.status().as_u16(), 202, "{}", res.text().await.unwrap_or_default());
                let v: Value = res.json().await.unwrap();
                posts.lock().unwrap().push(t.elapsed().as_secs_f64() * 1e3);
                ids.lock().unwrap().push(v["id"].as_str().unwrap().to_string());
                k += clients;
            }
        }));
    }
    for w in writers {
        w.await.unwrap();
    }
    let posted = start.elapsed().as_secs_f64();
    // Poll for completion every 100 ms (each poll counts the whole table by status).
    while succeeded(&client, &bases[0]).await < jobs {
        tokio::time::sleep(Duration::from_millis(100)).await;
    }
    let elapsed = start.elapsed().as_secs_f64();
    eprintln!("all {jobs} POSTs answered after {posted:.2} s, all solved after {elapsed:.2} s");
    running.store(false, Ordering::Relaxed);
    for r in readers {
        r.await.unwrap();
    }
    let sorted = |v: &Arc<Mutex<Vec<f64>>>| {
        let mut v = v.lock().unwrap().clone();
        v.sort_by(|a, b| a.partial_cmp(b).unwrap());
        v
    };
    Run { jobs_per_s: jobs as f64 / elapsed, post: sorted(&posts), get: sorted(&gets) }
}

fn tiny(k: usize) -> Value {
    json!({"kind": "hertz", "spec": {"contact": "line", "load": 1000.0 + k as f64, "length": 0.01,
        "body_1": {"shape": "cylinder", "radius": 0.02}, "body_2": {"shape": "flat"}}})
}

fn l9(k: usize) -> Value {
    let mut job: Value = serde_json::from_str(include_str!("../examples/seed002_taguchi_l9.json")).unwrap();
    job["spec"]["base"]["operating"]["viscosity"] = json!(0.0293 * (1.0 + 1e-6 * k as f64));
    job
}

#[tokio::main(flavor = "multi_thread", worker_threads = 2)]
async fn main() {
    let args: Vec<String> = std::env::args().skip(1).filter(|a| !a.starts_with("--")).collect();
    let tiny_jobs: usize = args.first().and_then(|s| s.parse().ok()).unwrap_or(5000);
    let heavy_jobs: usize = args.get(1).and_then(|s| s.parse().ok()).unwrap_or(8);
    // Optional: run only the rows whose name contains this (`sqlite`, `pg1`, `pg2`, `pg4`, `heavy`).
    let only = args.get(2).cloned().unwrap_or_default();
    let want = |name: &str| only.is_empty() || name.contains(only.as_str());
    let Some(admin) = std::env::var("TRIBOD_TEST_POSTGRES_URL").ok().filter(|u| !u.is_empty()) else {
        eprintln!("scale bench: set TRIBOD_TEST_POSTGRES_URL (e.g. postgres://root@127.0.0.1:5432/test)");
        std::process::exit(2);
    };
    let clients = 32;

    println!("Tiny hertz jobs, {tiny_jobs} per row, {clients} clients round-robin over the instances:\n");
    println!("| store | instances | end-to-end jobs/s | POST p50 ms | POST p99 ms | GET p50 ms | GET p99 ms | tribod CPU ms/job | PostgreSQL CPU ms/job | machine CPU ms/job |");
    println!("|---|---|---|---|---|---|---|---|---|---|");
    let row = |store: &str, n: usize, r: &Run, tribod_cpu: f64, pg_cpu: f64, machine_cpu: f64| {
        println!(
            "| {store} | {n} | {:.0} | {:.2} | {:.2} | {:.2} | {:.2} | {:.2} | {:.2} | {:.2} |",
            r.jobs_per_s,
            percentile(&r.post, 0.5),
            percentile(&r.post, 0.99),
            percentile(&r.get, 0.5),
            percentile(&r.get, 0.99),
            tribod_cpu * 1e3 / tiny_jobs as f64,
            pg_cpu * 1e3 / tiny_jobs as f64,
            machine_cpu * 1e3 / tiny_jobs as f64,
        )
    };
    if want("sqlite") {
        let dir = tempfile::tempdir().unwrap();
        let db = dir.path().join("bench.db").display().to_string();
        let one = serve(&db, &[]);
        let (cpu0, busy0) = (cpu_seconds(one.child.id()), machine_busy_seconds());
        let r = drive(&[one.base.clone()], tiny_jobs, clients, tiny).await;
        row("SQLite", 1, &r, cpu_seconds(one.child.id()) - cpu0, 0.0, machine_busy_seconds() - busy0);
    }
    for n in [1, 2, 4] {
        if !want(&format!("pg{n}")) {
            continue;
        }
        let (url, name) = create_database(&admin).await;
        if std::env::var_os("TRIBOD_BENCH_EXPLAIN").is_some() {
            // Diagnosis: the server log gets the plan of every statement slower than 1 ms.
            let mut conn = sqlx::PgConnection::connect(&admin).await.unwrap();
            for sql in [
                format!("ALTER DATABASE \"{name}\" SET session_preload_libraries = 'auto_explain'"),
                format!("ALTER DATABASE \"{name}\" SET auto_explain.log_min_duration = '1ms'"),
            ] {
                conn.execute(sqlx::AssertSqlSafe(sql)).await.unwrap();
            }
            let _ = conn.close().await;
        }
        if std::env::var_os("TRIBOD_BENCH_LOG_STATEMENTS").is_some() {
            // Diagnosis: the server log gets every statement of this database (count them by kind).
            let mut conn = sqlx::PgConnection::connect(&admin).await.unwrap();
            let sql = format!("ALTER DATABASE \"{name}\" SET log_min_duration_statement = 0");
            conn.execute(sqlx::AssertSqlSafe(sql)).await.unwrap();
            let _ = conn.close().await;
        }
        let instances: Vec<Instance> = (0..n).map(|_| serve(&url, &[])).collect();
        let bases: Vec<String> = instances.iter().map(|i| i.base.clone()).collect();
        let cpu = || instances.iter().map(|i| cpu_seconds(i.child.id())).sum::<f64>();
        let (cpu0, pg0, busy0) = (cpu(), postgres_cpu_seconds(), machine_busy_seconds());
        let r = drive(&bases, tiny_jobs, clients, tiny).await;
        row("PostgreSQL", n, &r, cpu() - cpu0, postgres_cpu_seconds() - pg0, machine_busy_seconds() - busy0);
        if std::env::var_os("TRIBOD_BENCH_DB_STATS").is_some() {
            let mut conn = sqlx::PgConnection::connect(&url).await.unwrap();
            let stats: (i64, i64, i64, i64, i64) = sqlx::query_as(
                "SELECT xact_commit, tup_returned, tup_fetched, blks_hit, tup_updated FROM pg_stat_database WHERE datname = current_database()",
            )
            .fetch_one(&mut conn)
            .await
            .unwrap();
            let per = |v: i64| v as f64 / tiny_jobs as f64;
            eprintln!(
                "per job: commits {:.1}, rows returned {:.0}, rows fetched {:.1}, buffer hits {:.0}, rows updated {:.1}",
                per(stats.0), per(stats.1), per(stats.2), per(stats.3), per(stats.4)
            );
            let t: (i64, i64, i64, i64) = sqlx::query_as(
                "SELECT seq_scan, seq_tup_read, idx_scan, idx_tup_fetch FROM pg_stat_user_tables WHERE relname = 'jobs'",
            )
            .fetch_one(&mut conn)
            .await
            .unwrap();
            eprintln!("jobs table: {} seq scans reading {} rows; {} index scans fetching {} rows", t.0, t.1, t.2, t.3);
            let u: (i64, i64, i64) = sqlx::query_as(
                "SELECT n_tup_upd, n_tup_hot_upd, n_dead_tup FROM pg_stat_user_tables WHERE relname = 'jobs'",
            )
            .fetch_one(&mut conn)
            .await
            .unwrap();
            eprintln!("jobs updates per job: {:.2}, of them HOT {:.2}; dead rows {:.2} per job", per(u.0), per(u.1), per(u.2));
            let rows: Vec<(String, i64, i64, i64, i64)> = sqlx::query_as(
                "SELECT indexrelname::text, idx_scan, idx_tup_read, idx_tup_fetch, pg_relation_size(indexrelid) \
                 FROM pg_stat_user_indexes ORDER BY idx_tup_read DESC",
            )
            .fetch_all(&mut conn)
            .await
            .unwrap();
            for (name, scans, read, fetched, bytes) in rows {
                eprintln!("  index {name}: scans {:.2}, entries read {:.1}, rows fetched {:.1} per job; {} kB", per(scans), per(read), per(fetched), bytes / 1024);
            }
            let _ = conn.close().await;
        }
        drop(instances);
        drop_database(&admin, &name).await;
    }

    println!("\nHeavy jobs (seed 002 Taguchi L9), {heavy_jobs} per row, through `serve --workers 0` + worker instances of 1 thread:\n");
    println!("| worker instances | jobs/s | s per job | speed-up |");
    println!("|---|---|---|---|");
    let mut first = None;
    for n in [1, 2] {
        if !want("heavy") {
            continue;
        }
        let (url, name) = create_database(&admin).await;
        let api = serve(&url, &["--workers", "0"]);
        let workers: Vec<Instance> = (0..n).map(|_| worker(&url, &["--workers", "1"])).collect();
        let r = drive(&[api.base.clone()], heavy_jobs, 4, l9).await;
        let base = *first.get_or_insert(r.jobs_per_s);
        println!("| {n} | {:.3} | {:.2} | {:.2}× |", r.jobs_per_s, 1.0 / r.jobs_per_s, r.jobs_per_s / base);
        drop(workers);
        drop(api);
        drop_database(&admin, &name).await;
    }
}
