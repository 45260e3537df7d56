//! Storage faults through a real filesystem that fills (issue 10, defect 1): after `SQLITE_FULL`
//! the service must answer 503 while it cannot commit, say so on `/readyz`, and recover when space
//! returns — and every job it acknowledged with a 2xx must be in the database and finish.
//!
//! The database lives on a small tmpfs mounted for the test (needs root, as in CI); without the
//! permission to mount, the test says SKIPPED and passes.

use crate::common::*;
use serde_json::Value;
use std::path::{Path, PathBuf};
use std::process::Command;
use std::time::{Duration, Instant};

/// A tmpfs mounted for one test, unmounted when dropped.
struct SmallFs {
    dir: PathBuf,
}

impl SmallFs {
    fn mount(dir: &Path, kib: u64) -> Option<SmallFs> {
        std::fs::create_dir_all(dir).ok()?;
        let ok = Command::new("mount")
            .args(["-t", "tmpfs", "-o", &format!("size={kib}k"), "tmpfs"])
            .arg(dir)
            .stderr(std::process::Stdio::null())
            .status()
            .is_ok_and(|s| s.success());
        ok.then(|| SmallFs { dir: dir.to_path_buf() })
    }

    /// Bytes free on the filesystem.
    fn free(&self) -> u64 {
        let out = Command::new("df").args(["-B1", "--output=avail"]).arg(&self.dir).output().expect("df");
        String::from_utf8_lossy(&out.stdout).lines().nth(1).and_then(|l| l.trim().parse().ok()).unwrap_or(0)
    }
}

impl Drop for SmallFs {
    fn drop(&mut self) {
        let _ = Command::new("umount").arg("-l").arg(&self.dir).status();
    }
}

#[tokio::test(flavor = "multi_thread", worker_threads = 4)]
async fn every_acknowledged_job_survives_a_full_disk() {
    let base = tempfile::tempdir().expect("temp dir");
    let Some(fs) = SmallFs::mount(&base.path().join("small"), 4096) else {
        eprintln!("SKIPPED every_acknowledged_job_survives_a_full_disk: cannot mount a tmpfs (run as root, as .ci/run does)");
        return;
    };
    let db = fs.dir.join("tribod.db");
    let server = start_with(|c| c.database_url = db.display().to_string()).await;
    assert_eq!(server.client.get(server.url("/readyz")).send().await.unwrap().status(), 200);

    // Fill the filesystem but for a few pages: the WAL soon cannot grow.
    let filler = fs.dir.join("filler");
    let slack = 256 * 1024;
    std::fs::write(&filler, vec![0u8; (fs.free().saturating_sub(slack)) as usize]).expect("filler");

    let mut acknowledged: Vec<String> = Vec::new();
    let mut refused = 0;
    let mut readyz_while_full = None;
    let mut nonce = 0u64;
    let start = Instant::now();
    while refused < 5 && start.elapsed() < Duration::from_secs(60) {
        nonce += 1;
        let res = server.post_job(&sleep_job(0.0, nonce)).await;
        let status = res.status().as_u16();
        let body: Value = res.json().await.unwrap_or(Value::Null);
        match status {
            200 | 202 => acknowledged.push(body["id"].as_str().expect("job id").to_string()),
            503 => {
                assert_eq!(body["code"], "storage_unavailable", "{body}");
                refused += 1;
                if readyz_while_full.is_none() {
                    readyz_while_full = Some(server.client.get(server.url("/readyz")).send().await.unwrap().status().as_u16());
                }
            }
            other => panic!("unexpected {other}: {body}"),
        }
    }
    assert!(refused >= 5, "the filesystem never filled ({} jobs accepted)", acknowledged.len());
    assert_eq!(readyz_while_full, Some(503), "/readyz must report a database that cannot commit");

    // Space returns: the service recovers on its own.
    std::fs::remove_file(&filler).expect("remove filler");
    let ready_again = Instant::now();
    while server.client.get(server.url("/readyz")).send().await.unwrap().status() != 200 {
        assert!(ready_again.elapsed() < Duration::from_secs(15), "/readyz did not recover after space returned");
        tokio::time::sleep(Duration::from_millis(50)).await;
    }
    for _ in 0..40 {
        nonce += 1;
        let res = server.post_job(&sleep_job(0.0, nonce)).await;
        assert_eq!(res.status().as_u16(), 202, "after space returned");
        let body: Value = res.json().await.unwrap();
        acknowledged.push(body["id"].as_str().unwrap().to_string());
    }

    // Every acknowledged job finishes …
    for id in &acknowledged {
        let job = server.wait_finished(id, Duration::from_secs(30)).await;
        assert_eq!(job["status"], "succeeded", "acknowledged job {id}: {job}");
    }
    // … and another process can write the file (no transaction left open holding the lock).
    let other = sqlx::sqlite::SqlitePoolOptions::new()
        .max_connections(1)
        .connect_with(
            sqlx::sqlite::SqliteConnectOptions::new().filename(&db).busy_timeout(Duration::from_secs(5)),
        )
        .await
        .expect("open the database from outside");
    {
        let mut conn = other.acquire().await.expect("connection");
        sqlx::query("BEGIN IMMEDIATE").execute(&mut *conn).await.expect("an outside writer gets the write lock");
        sqlx::query("ROLLBACK").execute(&mut *conn).await.expect("rollback");
    }
    other.close().await;

    // After a restart, the database holds exactly the acknowledged jobs, all succeeded.
    let dir = server.stop().await;
    let restarted = start_in(dir, {
        let mut c = config(&base);
        c.database_url = db.display().to_string();
        c
    })
    .await;
    let (_, page) = restarted.get_json("/v1/jobs?limit=500").await;
    let stored: Vec<&str> = page["jobs"].as_array().unwrap().iter().map(|j| j["id"].as_str().unwrap()).collect();
    for id in &acknowledged {
        assert!(stored.contains(&id.as_str()), "acknowledged job {id} is not in the database");
    }
    assert!(page["jobs"].as_array().unwrap().iter().all(|j| j["status"] == "succeeded"));
    eprintln!(
        "full disk: {} jobs acknowledged ({} before the first refusal), {refused} refused with 503, 0 lost",
        acknowledged.len(),
        acknowledged.len() - 40
    );
    restarted.stop().await;
    drop(fs);
}

/// `chattr` the files of a SQLite database (immutable on or off); false when not permitted.
fn set_immutable(db: &Path, on: bool) -> bool {
    let flag = if on { "+i" } else { "-i" };
    let files = [db.to_path_buf(), PathBuf::from(format!("{}-wal", db.display()))];
    Command::new("chattr")
        .arg(flag)
        .args(&files)
        .stderr(std::process::Stdio::null())
        .status()
        .is_ok_and(|s| s.success())
}

/// The database file and its WAL made immutable under a running server (issue 10, defect 1, the
/// second way): every write fails with an I/O error until the flag is removed.
#[tokio::test(flavor = "multi_thread", worker_threads = 4)]
async fn every_acknowledged_job_survives_an_immutable_database() {
    let base = tempfile::tempdir_in(std::env::temp_dir()).expect("temp dir");
    let db = base.path().join("tribod.db");
    let server = start_with(|c| c.database_url = db.display().to_string()).await;
    let mut acknowledged: Vec<String> = Vec::new();
    let mut nonce = 0u64;
    for _ in 0..5 {
        nonce += 1;
        let body: Value = server.post_job(&sleep_job(0.0, nonce)).await.json().await.unwrap();
        acknowledged.push(body["id"].as_str().unwrap().to_string());
    }
    if !set_immutable(&db, true) {
        eprintln!("SKIPPED every_acknowledged_job_survives_an_immutable_database: chattr +i not permitted here (run as root on ext4, as .ci/run does)");
        server.stop().await;
        return;
    }
    struct Unlock<'a>(&'a Path);
    impl Drop for Unlock<'_> {
        fn drop(&mut self) {
            set_immutable(self.0, false);
        }
    }
    let unlock = Unlock(&db);

    let mut refused = 0;
    let mut readyz_while_locked = None;
    let start = Instant::now();
    while refused < 5 && start.elapsed() < Duration::from_secs(30) {
        nonce += 1;
        let res = server.post_job(&sleep_job(0.0, nonce)).await;
        let status = res.status().as_u16();
        let body: Value = res.json().await.unwrap_or(Value::Null);
        match status {
            200 | 202 => acknowledged.push(body["id"].as_str().expect("job id").to_string()),
            503 => {
                assert_eq!(body["code"], "storage_unavailable", "{body}");
                refused += 1;
                if readyz_while_locked.is_none() {
                    readyz_while_locked = Some(server.client.get(server.url("/readyz")).send().await.unwrap().status().as_u16());
                }
            }
            other => panic!("unexpected {other}: {body}"),
        }
    }
    assert!(refused >= 5, "writes never failed ({} jobs accepted)", acknowledged.len());
    assert_eq!(readyz_while_locked, Some(503), "/readyz must report a database that cannot commit");

    drop(unlock);
    let ready_again = Instant::now();
    while server.client.get(server.url("/readyz")).send().await.unwrap().status() != 200 {
        assert!(ready_again.elapsed() < Duration::from_secs(15), "/readyz did not recover");
        tokio::time::sleep(Duration::from_millis(50)).await;
    }
    for _ in 0..20 {
        nonce += 1;
        let res = server.post_job(&sleep_job(0.0, nonce)).await;
        assert_eq!(res.status().as_u16(), 202, "after the flag was removed");
        let body: Value = res.json().await.unwrap();
        acknowledged.push(body["id"].as_str().unwrap().to_string());
    }
    for id in &acknowledged {
        let job = server.wait_finished(id, Duration::from_secs(30)).await;
        assert_eq!(job["status"], "succeeded", "acknowledged job {id}: {job}");
    }
    let dir = server.stop().await;
    let restarted = start_in(dir, {
        let mut c = config(&base);
        c.database_url = db.display().to_string();
        c
    })
    .await;
    for id in &acknowledged {
        let (status, job) = restarted.get_json(&format!("/v1/jobs/{id}")).await;
        assert_eq!((status, job["status"].as_str()), (200, Some("succeeded")), "acknowledged job {id} after restart");
    }
    eprintln!("immutable database: {} jobs acknowledged, {refused} refused with 503, 0 lost", acknowledged.len());
    restarted.stop().await;
}

/// A TCP proxy in front of the test PostgreSQL server that the test can cut (every connection
/// closed, new ones refused) and restore on the same port: the database becomes unreachable.
struct CuttableProxy {
    port: u16,
    task: Option<tokio::task::JoinHandle<()>>,
}

impl CuttableProxy {
    async fn start(port: u16, upstream: String) -> CuttableProxy {
        let listener = tokio::net::TcpListener::bind(("127.0.0.1", port)).await.expect("bind the proxy");
        let port = listener.local_addr().unwrap().port();
        let task = tokio::spawn(async move {
            let mut links = tokio::task::JoinSet::new();
            loop {
                let Ok((mut client, _)) = listener.accept().await else { continue };
                let upstream = upstream.clone();
                links.spawn(async move {
                    if let Ok(mut server) = tokio::net::TcpStream::connect(upstream).await {
                        let _ = tokio::io::copy_bidirectional(&mut client, &mut server).await;
                    }
                });
            }
        });
        CuttableProxy { port, task: Some(task) }
    }

    /// Close every link and stop listening (the links die with the accept task's `JoinSet`).
    async fn cut(&mut self) {
        if let Some(t) = self.task.take() {
            t.abort();
            let _ = t.await;
        }
    }
}

/// PostgreSQL unreachable under a running server: submissions answer `503 storage_unavailable`
/// within seconds and `/readyz` says not ready; once the database is back the server recovers
/// without a restart and the job accepted before the cut finishes.
#[tokio::test(flavor = "multi_thread", worker_threads = 4)]
async fn an_unreachable_database_answers_503_and_the_server_recovers() {
    if !postgres_available("an_unreachable_database_answers_503_and_the_server_recovers") {
        return;
    }
    let direct = fresh_postgres_database().await;
    let upstream = {
        let after = direct.split_once('@').map_or(direct.as_str(), |(_, a)| a);
        after.split('/').next().unwrap().to_string()
    };
    let mut proxy = CuttableProxy::start(0, upstream.clone()).await;
    let proxied = direct.replacen(&upstream, &format!("127.0.0.1:{}", proxy.port), 1);
    let dir = tempfile::tempdir().unwrap();
    let mut cfg = config(&dir);
    cfg.database_url = proxied;
    cfg.queue.workers = 1;
    let s = start_in(dir, cfg).await;
    let res = s.post_job(&sleep_job(1.0, 4242)).await;
    assert_eq!(res.status(), 202);
    let before: Value = res.json().await.unwrap();
    let id = before["id"].as_str().unwrap().to_string();

    proxy.cut().await;
    let t = Instant::now();
    let res = s.post_job(&hertz_job(2468.0)).await;
    let took = t.elapsed();
    expect_problem(res, 503, "storage_unavailable").await;
    assert!(took < Duration::from_secs(10), "the 503 took {took:?}");
    let (status, _) = s.get_json("/readyz").await;
    assert_eq!(status, 503, "not ready while the database is unreachable");

    let port = proxy.port;
    let _proxy = CuttableProxy::start(port, upstream).await;
    let deadline = Instant::now() + Duration::from_secs(60);
    loop {
        let res = s.post_job(&hertz_job(2469.0)).await;
        if res.status() == 202 {
            break;
        }
        assert!(Instant::now() < deadline, "no recovery: {}", res.status());
        tokio::time::sleep(Duration::from_millis(250)).await;
    }
    let job = s.wait_finished(&id, Duration::from_secs(90)).await;
    assert_eq!(job["status"], "succeeded", "{job}");
    s.stop().await;
}
