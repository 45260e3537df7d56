//! The SQLite backend of the store.
//!
//! One file in WAL mode, two pools: a single writer connection (SQLite admits one writer at a time;
//! funnelling writes through one connection avoids busy-waiting) and several readers.
//!
//! After any failed write the writer connection is closed, never returned to the pool: on
//! `SQLITE_FULL` or `SQLITE_IOERR` SQLite may roll a transaction back by itself or leave it open
//! holding the write lock, behind the back of the driver's own bookkeeping. A fresh connection is
//! the only state known to be clean (issue 10: jobs acknowledged after a disk-full error were lost
//! because later "commits" ran inside the failed transaction).

use super::*;

use sqlx::pool::PoolConnection;
use sqlx::sqlite::{
    SqliteConnectOptions, SqliteConnection, SqliteJournalMode, SqlitePool, SqlitePoolOptions, SqliteRow,
    SqliteSynchronous,
};
use sqlx::{AssertSqlSafe, Connection, Row, Sqlite};
use std::str::FromStr;
use std::time::Duration;
use uuid::Uuid;

mod children;

/// Handle to the database (cheap to clone).
#[derive(Clone, Debug)]
pub struct SqliteStore {
    writer: SqlitePool,
    /// Unix ms of the last failed write (0: none) — `/readyz` reports a recent failure.
    last_write_failure: std::sync::Arc<std::sync::atomic::AtomicI64>,
    /// Whether the file may hold children of a fanned-out job (any row of `job_children` at open
    /// or added since; one process owns the file): until then no finished job is a case, and the
    /// writer does not look for parents to move on after each finish.
    children_seen: std::sync::Arc<std::sync::atomic::AtomicBool>,
    reader: SqlitePool,
    /// Accepted jobs on their way to the group-commit task ([`insert_batches`]).
    inserts: tokio::sync::mpsc::Sender<PendingInsert>,
}

/// A job waiting for its insert to be committed, and who waits for the answer (its `seq`).
type PendingInsert = (NewJob, tokio::sync::oneshot::Sender<StoreResult<i64>>);

/// Most inserts committed in one transaction.
const INSERT_BATCH: usize = 256;

/// Group commit of accepted jobs: every insert waiting when the writer becomes free goes into one
/// transaction, so concurrent submissions share one commit (one WAL append and sync point) instead
/// of queueing for one each; each caller is answered only after the commit. A failed batch is
/// retried one insert at a time so that one bad row fails only its own submission.
async fn insert_batches(
    writer: SqlitePool,
    mut rx: tokio::sync::mpsc::Receiver<PendingInsert>,
    last_failure: std::sync::Arc<std::sync::atomic::AtomicI64>,
) {
    let mut batch: Vec<PendingInsert> = Vec::with_capacity(INSERT_BATCH);
    while rx.recv_many(&mut batch, INSERT_BATCH).await > 0 {
        let jobs: Vec<&NewJob> = batch.iter().map(|(j, _)| j).collect();
        match insert_all(&writer, &jobs).await {
            Ok(seqs) => {
                for ((_, reply), seq) in batch.drain(..).zip(seqs) {
                    let _ = reply.send(Ok(seq));
                }
            }
            Err(_) => {
                last_failure.store(unix_ms(), std::sync::atomic::Ordering::Relaxed);
                for (job, reply) in batch.drain(..) {
                    let _ = reply.send(insert_all(&writer, &[&job]).await.map(|s| s[0]));
                }
            }
        }
    }
}

/// Insert `jobs` (status `queued`) in one transaction; their `seq`s in order.
async fn insert_all(writer: &SqlitePool, jobs: &[&NewJob]) -> StoreResult<Vec<i64>> {
    let mut conn = writer.acquire().await?;
    let result = insert_on(&mut conn, jobs).await;
    settle(conn, result).await
}

/// Return the writer connection to the pool after a success; close it after any error (see the
/// module docs), so the pool opens a fresh one for the next write.
async fn settle<T>(conn: PoolConnection<Sqlite>, result: StoreResult<T>) -> StoreResult<T> {
    if result.is_err() {
        let _ = conn.close().await;
    }
    result
}


/// Which unique index an insert hit: the client's key, or an identical job in flight.
fn unique_violation(e: sqlx::Error) -> StoreError {
    match &e {
        sqlx::Error::Database(d) if d.is_unique_violation() => {
            if d.message().contains("idempotency_key") {
                StoreError::DuplicateKey
            } else {
                StoreError::InFlight
            }
        }
        _ => StoreError::Sqlx(e),
    }
}

async fn insert_on(conn: &mut SqliteConnection, jobs: &[&NewJob]) -> StoreResult<Vec<i64>> {
    let mut tx = conn.begin().await?;
    // One statement for the whole batch (each statement is a round trip to the connection's
    // thread); RETURNING gives the rows in no promised order, so each `seq` is matched by id.
    let mut sql = String::from(
        "INSERT INTO jobs (id, kind, label, status, spec, spec_hash, solver_version, created_at, due_at, \
         estimate_cpu_seconds, estimate_memory_bytes) VALUES ",
    );
    for k in 0..jobs.len() {
        sql.push_str(if k == 0 { "(?, ?, ?, 'queued', ?, ?, ?, ?, ?, ?, ?)" } else { ", (?, ?, ?, 'queued', ?, ?, ?, ?, ?, ?, ?)" });
    }
    sql.push_str(" RETURNING id, seq");
    let mut q = sqlx::query(AssertSqlSafe(sql));
    for job in jobs {
        q = q
            .bind(job.id.to_string())
            .bind(&job.kind)
            .bind(&job.label)
            .bind(&job.spec)
            .bind(&job.spec_hash)
            .bind(&job.solver_version)
            .bind(job.created_at)
            .bind(job.due_at)
            .bind(job.estimate_cpu_seconds)
            .bind(job.estimate_memory_bytes);
    }
    let rows = q.fetch_all(&mut *tx).await.map_err(unique_violation)?;
    let mut seq_of = std::collections::HashMap::with_capacity(rows.len());
    for row in &rows {
        seq_of.insert(row.try_get::<String, _>(0)?, row.try_get::<i64, _>(1)?);
    }
    let seqs = jobs
        .iter()
        .map(|job| seq_of.get(&job.id.to_string()).copied().ok_or_else(|| StoreError::Corrupt(format!("job {} was not inserted", job.id))))
        .collect::<StoreResult<Vec<_>>>()?;
    for job in jobs {
        if let Some(key) = &job.idempotency_key {
            sqlx::query(
                "INSERT INTO idempotency_keys (key, job_id, spec_hash, label, reused, created_at) \
                 VALUES (?, ?, ?, ?, 0, ?)",
            )
            .bind(key)
            .bind(job.id.to_string())
            .bind(&job.spec_hash)
            .bind(&job.key_label)
            .bind(job.created_at)
            .execute(&mut *tx)
            .await
            .map_err(unique_violation)?;
        }
    }
    tx.commit().await?;
    Ok(seqs)
}


impl SqliteStore {
    /// Open (creating if missing) the database at `url` (`sqlite://path`, a plain path, or
    /// `sqlite::memory:`), switch to WAL and apply the migrations.
    ///
    /// Durability: WAL with `synchronous = NORMAL` — a commit is in the WAL file when it returns,
    /// so an accepted job survives a crash or kill of the process (`tests/it/restart_recovery.rs`
    /// kills it with SIGKILL); after a power loss or OS crash the commits since the last WAL sync
    /// may be lost. `FULL` would sync every commit (group commit of submissions shares that cost).
    pub async fn open(url: &str) -> StoreResult<SqliteStore> {
        let url = if url.starts_with("sqlite:") { url.to_string() } else { format!("sqlite://{url}") };
        let options = SqliteConnectOptions::from_str(&url)?
            .create_if_missing(true)
            .journal_mode(SqliteJournalMode::Wal)
            .synchronous(SqliteSynchronous::Normal)
            .foreign_keys(true)
            .busy_timeout(Duration::from_secs(10));
        let writer = SqlitePoolOptions::new()
            .max_connections(1)
            .min_connections(1)
            .acquire_timeout(Duration::from_secs(30))
            .connect_with(options.clone())
            .await?;
        super::migrations::migrator(super::migrations::SQLITE).run(&writer).await?;
        let reader = SqlitePoolOptions::new()
            .max_connections(4)
            .acquire_timeout(Duration::from_secs(30))
            .connect_with(options.read_only(true))
            .await?;
        let (inserts, rx) = tokio::sync::mpsc::channel(4 * INSERT_BATCH);
        let last_write_failure = std::sync::Arc::new(std::sync::atomic::AtomicI64::new(0));
        tokio::spawn(insert_batches(writer.clone(), rx, last_write_failure.clone()));
        let seen: bool = sqlx::query_scalar("SELECT EXISTS (SELECT 1 FROM job_children)").fetch_one(&reader).await?;
        let children_seen = std::sync::Arc::new(std::sync::atomic::AtomicBool::new(seen));
        Ok(SqliteStore { writer, reader, inserts, last_write_failure, children_seen })
    }

    /// Can the database be read *and written* (for `/readyz`)? Fails while any write failed in the
    /// last [`FAILURE_MEMORY_MS`], and otherwise commits one heartbeat row through the writer, so a
    /// full disk, a read-only file or a stuck writer shows as not ready.
    pub async fn ping(&self, now: i64) -> StoreResult<()> {
        sqlx::query("SELECT 1").execute(&self.reader).await?;
        let failed_at = self.last_write_failure.load(std::sync::atomic::Ordering::Relaxed);
        if failed_at > 0 && now - failed_at < FAILURE_MEMORY_MS {
            return Err(StoreError::RecentWriteFailure { ms_ago: now - failed_at });
        }
        let mut conn = self.writer.acquire().await?;
        let result = sqlx::query("UPDATE heartbeat SET beat = ? WHERE id = 1")
            .bind(now)
            .execute(&mut *conn)
            .await
            .map(|_| ())
            .map_err(StoreError::from);
        self.settle(conn, result).await
    }

    /// Close both pools (checkpoints the WAL).
    pub async fn close(&self) {
        self.reader.close().await;
        self.writer.close().await;
    }

    /// Insert an accepted job (status `queued`); committed when this returns.
    pub async fn insert(&self, job: &NewJob) -> StoreResult<JobRow> {
        let (reply, answer) = tokio::sync::oneshot::channel();
        let closed = || StoreError::Sqlx(sqlx::Error::PoolClosed);
        self.inserts.send((job.clone(), reply)).await.map_err(|_| closed())?;
        let seq = answer.await.map_err(|_| closed())??;
        Ok(job.queued_row(seq))
    }

    /// The newest succeeded job with this spec hash and solver version.
    pub async fn find_reusable(&self, spec_hash: &str, solver_version: &str) -> StoreResult<Option<JobRow>> {
        let sql = format!(
            "SELECT {ROW_COLUMNS} FROM jobs WHERE spec_hash = ? AND solver_version = ? \
             AND status = 'succeeded' ORDER BY seq DESC LIMIT 1"
        );
        let row = sqlx::query(AssertSqlSafe(sql))
            .bind(spec_hash)
            .bind(solver_version)
            .fetch_optional(&self.reader)
            .await?;
        row.map(|r| job_from_row(&r, false)).transpose()
    }

    /// The newest succeeded job with this spec (when `reusable`), else the in-flight one, in one
    /// statement (one trip to the reader's thread per submission instead of two).
    pub async fn find_same(&self, spec_hash: &str, solver_version: &str, reusable: bool) -> StoreResult<Option<JobRow>> {
        let sql = format!(
            "SELECT * FROM (SELECT {ROW_COLUMNS}, NULL AS spec, 0 AS rank FROM jobs WHERE spec_hash = ?1 \
               AND solver_version = ?2 AND status = 'succeeded' AND ?3 ORDER BY seq DESC LIMIT 1) \
             UNION ALL \
             SELECT * FROM (SELECT {ROW_COLUMNS}, spec, 1 AS rank FROM jobs WHERE spec_hash = ?1 \
               AND solver_version = ?2 AND status IN ('queued', 'running') LIMIT 1) \
             ORDER BY rank LIMIT 1"
        );
        let row = sqlx::query(AssertSqlSafe(sql))
            .bind(spec_hash)
            .bind(solver_version)
            .bind(reusable)
            .fetch_optional(&self.reader)
            .await?;
        match row {
            None => Ok(None),
            Some(r) => {
                let in_flight = r.try_get::<i64, _>("rank")? == 1;
                job_from_row(&r, in_flight).map(Some)
            }
        }
    }

    /// The record of a client's `Idempotency-Key`.
    pub async fn find_idempotency_key(&self, key: &str) -> StoreResult<Option<IdempotencyKey>> {
        let sql = format!("SELECT {KEY_COLUMNS} FROM idempotency_keys WHERE key = ?");
        let row = sqlx::query(AssertSqlSafe(sql)).bind(key).fetch_optional(&self.reader).await?;
        row.map(|r| key_from_row(&r)).transpose()
    }

    /// Record a key for an existing job unless the key is taken; the record under the key
    /// afterwards (`None`: the job is gone, nothing recorded). On the writer connection, so the
    /// read-back sees the write.
    pub async fn record_idempotency_key(&self, record: &IdempotencyKey) -> StoreResult<Option<IdempotencyKey>> {
        let mut conn = self.writer.acquire().await?;
        let result = record_key_on(&mut conn, record).await;
        self.settle(conn, result).await
    }

    /// One job with its spec.
    pub async fn get(&self, id: Uuid) -> StoreResult<Option<JobRow>> {
        let sql = format!("SELECT {ROW_COLUMNS}, spec FROM jobs WHERE id = ?");
        let row = sqlx::query(AssertSqlSafe(sql)).bind(id.to_string()).fetch_optional(&self.reader).await?;
        row.map(|r| job_from_row(&r, true)).transpose()
    }

    /// The `seq` of a job (to turn an id cursor into a keyset position).
    pub async fn seq_of(&self, id: Uuid) -> StoreResult<Option<i64>> {
        Ok(sqlx::query_scalar::<_, i64>("SELECT seq FROM jobs WHERE id = ?")
            .bind(id.to_string())
            .fetch_optional(&self.reader)
            .await?)
    }

    /// Jobs newest first, filtered, at most `limit` (keyset pagination on `seq`).
    pub async fn list(&self, f: &ListFilter) -> StoreResult<Vec<JobRow>> {
        let mut sql = format!("SELECT {ROW_COLUMNS} FROM jobs WHERE 1 = 1");
        if !f.statuses.is_empty() {
            // Status names come from a closed enum, never from the request text.
            let names: Vec<String> = f.statuses.iter().map(|s| format!("'{}'", s.as_str())).collect();
            sql.push_str(&format!(" AND status IN ({})", names.join(", ")));
        }
        if f.kind.is_some() {
            sql.push_str(" AND kind = ?");
        }
        if f.parent.is_some() {
            sql.push_str(" AND id IN (SELECT job_id FROM job_children WHERE parent_id = ?)");
        } else if !f.cases {
            sql.push_str(" AND NOT EXISTS (SELECT 1 FROM job_children c WHERE c.job_id = jobs.id AND c.owned)");
        }
        if f.created_after.is_some() {
            sql.push_str(" AND created_at > ?");
        }
        if f.created_before.is_some() {
            sql.push_str(" AND created_at < ?");
        }
        if f.before_seq.is_some() {
            sql.push_str(" AND seq < ?");
        }
        sql.push_str(" ORDER BY seq DESC LIMIT ?");
        let mut q = sqlx::query(AssertSqlSafe(sql));
        if let Some(k) = &f.kind {
            q = q.bind(k.clone());
        }
        if let Some(p) = f.parent {
            q = q.bind(p.to_string());
        }
        if let Some(t) = f.created_after {
            q = q.bind(t);
        }
        if let Some(t) = f.created_before {
            q = q.bind(t);
        }
        if let Some(s) = f.before_seq {
            q = q.bind(s);
        }
        let rows = q.bind(f.limit as i64).fetch_all(&self.reader).await?;
        rows.iter().map(|r| job_from_row(r, false)).collect()
    }

    /// Claim up to `n` queued jobs, earliest virtual deadline (`due_at`) first, then oldest:
    /// `running`, attempts + 1.
    pub async fn claim(&self, next: ClaimNext, now: i64, owner: &str) -> StoreResult<Vec<ClaimedJob>> {
        if next.is_empty() {
            return Ok(Vec::new());
        }
        let mut conn = self.writer.acquire().await?;
        let result = claim_on(&mut conn, next, now, owner).await;
        self.settle(conn, result).await
    }

    /// Write several workers' final words and claim up to `next.n` jobs in one transaction.
    /// `cases`: whether the file may hold any fanned-out job's case (read after the commit; a case
    /// linked just before the commit is linked after setting the flag); the caller then looks for
    /// the parents to move on (on a reader).
    pub async fn finish_batch(&self, items: &[Finish], now: i64, owner: &str, next: ClaimNext) -> StoreResult<Finished> {
        let mut conn = self.writer.acquire().await?;
        let result = finish_on(&mut conn, items, now, owner, next).await;
        let claimed = self.settle(conn, result).await?;
        Ok(Finished { cases: self.children_seen.load(std::sync::atomic::Ordering::SeqCst), claimed })
    }

    /// Record progress of running jobs (one transaction).
    pub async fn progress_batch(&self, items: &[(Uuid, f64, String)]) -> StoreResult<()> {
        let mut conn = self.writer.acquire().await?;
        let result = progress_on(&mut conn, items).await;
        self.settle(conn, result).await
    }

    /// Cancel a queued job; `true` when it was queued.
    pub async fn cancel_queued(&self, id: Uuid, now: i64) -> StoreResult<bool> {
        let mut conn = self.writer.acquire().await?;
        let r = sqlx::query(
            "UPDATE jobs SET status = 'canceled', finished_at = ?, cancel_requested = 1 \
             WHERE id = ? AND status = 'queued'",
        )
        .bind(now)
        .bind(id.to_string())
        .execute(&mut *conn)
        .await;
        let r = self.settle(conn, r.map_err(StoreError::from)).await?;
        Ok(r.rows_affected() == 1)
    }

    /// Mark a running job as asked to cancel; `true` when it was running.
    pub async fn request_cancel(&self, id: Uuid) -> StoreResult<bool> {
        let mut conn = self.writer.acquire().await?;
        let r = sqlx::query("UPDATE jobs SET cancel_requested = 1 WHERE id = ? AND status = 'running'")
            .bind(id.to_string())
            .execute(&mut *conn)
            .await;
        let r = self.settle(conn, r.map_err(StoreError::from)).await?;
        Ok(r.rows_affected() == 1)
    }

    /// Delete a finished job and its result; `true` when one was deleted.
    pub async fn delete_finished(&self, id: Uuid) -> StoreResult<bool> {
        let mut conn = self.writer.acquire().await?;
        let r = sqlx::query(
            "DELETE FROM jobs WHERE id = ? AND status IN ('succeeded', 'failed', 'canceled')",
        )
        .bind(id.to_string())
        .execute(&mut *conn)
        .await;
        let r = self.settle(conn, r.map_err(StoreError::from)).await?;
        Ok(r.rows_affected() == 1)
    }

    /// At start-up: jobs left `running` by a previous process were interrupted. Below
    /// `max_attempts` they are queued again; at the cap they fail with `error`.
    /// Returns `(requeued, failed)`.
    pub async fn recover_interrupted(&self, max_attempts: i64, error: &str, now: i64) -> StoreResult<(u64, u64)> {
        let mut conn = self.writer.acquire().await?;
        // Not a fanned-out job waiting for its cases (no worker holds it; its cases are re-queued).
        let result = recover_on(&mut conn, max_attempts, error, now, crate::store::children::WAITING_UNTIL).await;
        self.settle(conn, result).await
    }

    /// Running jobs whose lease expired go back to the queue (or fail at the attempt cap).
    pub async fn requeue_expired(&self, max_attempts: i64, error: &str, now: i64) -> StoreResult<(u64, u64)> {
        let mut conn = self.writer.acquire().await?;
        let result = recover_on(&mut conn, max_attempts, error, now, now).await;
        self.settle(conn, result).await
    }

    /// Extend `owner`'s leases on `ids`; the jobs still held and their cancel flags.
    pub async fn renew_leases(&self, owner: &str, ids: &[Uuid], until: i64) -> StoreResult<Vec<Renewed>> {
        if ids.is_empty() {
            return Ok(Vec::new());
        }
        let list: Vec<String> = ids.iter().map(|id| format!("'{id}'")).collect();
        // Ids are formatted UUIDs, never request text.
        let sql = format!(
            "UPDATE jobs SET lease_until = ? WHERE lease_owner = ? AND status = 'running' AND id IN ({}) \
             RETURNING id, cancel_requested",
            list.join(", ")
        );
        let mut conn = self.writer.acquire().await?;
        let rows = sqlx::query(AssertSqlSafe(sql)).bind(until).bind(owner).fetch_all(&mut *conn).await;
        let rows = self.settle(conn, rows.map_err(StoreError::from)).await?;
        rows.iter()
            .map(|r| {
                Ok(Renewed {
                    id: parse_uuid(&r.try_get::<String, _>(0)?)?,
                    cancel_requested: r.try_get::<i64, _>(1)? != 0,
                })
            })
            .collect()
    }

    /// The queued or running job with this spec hash and solver version.
    pub async fn find_in_flight(&self, spec_hash: &str, solver_version: &str) -> StoreResult<Option<JobRow>> {
        let sql = format!(
            "SELECT {ROW_COLUMNS}, spec FROM jobs WHERE spec_hash = ? AND solver_version = ? \
             AND status IN ('queued', 'running') LIMIT 1"
        );
        let row = sqlx::query(AssertSqlSafe(sql)).bind(spec_hash).bind(solver_version).fetch_optional(&self.reader).await?;
        row.map(|r| job_from_row(&r, true)).transpose()
    }

    /// Number of jobs in each status.
    pub async fn count_by_status(&self) -> StoreResult<Vec<(JobStatus, i64)>> {
        let rows = sqlx::query("SELECT status, COUNT(*) FROM jobs GROUP BY status").fetch_all(&self.reader).await?;
        rows.iter()
            .map(|r| {
                let s: String = r.try_get(0)?;
                let status = JobStatus::parse(&s).ok_or_else(|| StoreError::Corrupt(format!("status {s}")))?;
                Ok((status, r.try_get(1)?))
            })
            .collect()
    }

    /// Number of queued jobs.
    pub async fn queued_count(&self) -> StoreResult<i64> {
        // A fanned-out job's cases are its work, admitted with it: not counted again.
        Ok(sqlx::query_scalar::<_, i64>(
            "SELECT COUNT(*) FROM jobs WHERE status = 'queued' \
             AND NOT EXISTS (SELECT 1 FROM job_children c WHERE c.job_id = jobs.id AND c.owned)",
        )
            .fetch_one(&self.reader)
            .await?)
    }

    /// The stored result of a job, decoded to JSON text.
    pub async fn result(&self, id: Uuid) -> StoreResult<Option<String>> {
        let row = sqlx::query("SELECT encoding, body FROM job_results WHERE job_id = ?")
            .bind(id.to_string())
            .fetch_optional(&self.reader)
            .await?;
        match row {
            None => Ok(None),
            Some(r) => {
                let encoding: String = r.try_get(0)?;
                let body: Vec<u8> = r.try_get(1)?;
                decode_result(&encoding, &body).map(Some).map_err(StoreError::Corrupt)
            }
        }
    }

    /// [`settle`], remembering a failure for `/readyz`.
    async fn settle<T>(&self, conn: PoolConnection<Sqlite>, result: StoreResult<T>) -> StoreResult<T> {
        if result.is_err() {
            self.last_write_failure.store(unix_ms(), std::sync::atomic::Ordering::Relaxed);
        }
        settle(conn, result).await
    }
}

/// Claim the queued jobs `next` says, in virtual-deadline order (on the writer, in or out of a
/// transaction): the first `next.n` of all, and the first `next.short` short ones after those.
async fn claim_on(conn: &mut SqliteConnection, next: ClaimNext, now: i64, owner: &str) -> StoreResult<Vec<ClaimedJob>> {
    static CLAIM: std::sync::LazyLock<String> = std::sync::LazyLock::new(|| {
        format!(
            "UPDATE jobs SET status = 'running', started_at = ?1, attempts = attempts + 1, \
             progress = 0, stage = NULL, lease_owner = ?2, lease_until = ?3 \
             WHERE seq IN (SELECT seq FROM (SELECT seq FROM jobs WHERE status = 'queued' ORDER BY due_at, seq LIMIT ?4) \
                           UNION ALL \
                           SELECT seq FROM (SELECT seq FROM jobs WHERE status = 'queued' AND {SHORT_JOB_SQL} \
                             AND seq NOT IN (SELECT seq FROM jobs WHERE status = 'queued' ORDER BY due_at, seq LIMIT ?4) \
                             ORDER BY due_at, seq LIMIT ?5)) \
             RETURNING id, kind, spec, attempts, due_at, seq, COALESCE({SHORT_JOB_SQL}, 0)"
        )
    });
    let rows = sqlx::query(AssertSqlSafe(CLAIM.as_str()))
        .bind(now)
        .bind(owner)
        .bind(next.lease_until)
        .bind(next.n as i64)
        .bind(next.short as i64)
        .fetch_all(&mut *conn)
        .await?;
    let mut jobs = rows
        .iter()
        .map(|r| {
            Ok((
                (r.try_get::<i64, _>(4)?, r.try_get::<i64, _>(5)?),
                ClaimedJob {
                    id: parse_uuid(&r.try_get::<String, _>(0)?)?,
                    kind: r.try_get(1)?,
                    spec: r.try_get(2)?,
                    attempts: r.try_get(3)?,
                    short: r.try_get::<bool, _>(6)?,
                },
            ))
        })
        .collect::<StoreResult<Vec<_>>>()?;
    jobs.sort_by_key(|(order, _)| *order);
    Ok(jobs.into_iter().map(|(_, j)| j).collect())
}

/// Finish `items` and claim up to `next.n` jobs (none when a job goes back to the queue: shutdown)
/// in one transaction; the jobs claimed.
async fn finish_on(conn: &mut SqliteConnection, items: &[Finish], now: i64, owner: &str, next: ClaimNext) -> StoreResult<Vec<ClaimedJob>> {
    let mut tx = conn.begin().await?;
    finish_succeeded_on(&mut tx, items, now, owner).await?;
    for item in items {
        // Only the lease holder finishes a job: after a lost lease the job runs elsewhere.
        // ?1 = now, ?2 = id, ?3 = owner, ?4 = error.
        let (sql, id) = match item {
            Finish::Succeeded { .. } => continue,
            Finish::Failed { id, .. } => (
                "UPDATE jobs SET status = 'failed', finished_at = ?1, error = ?4, solved_by = lease_owner, lease_owner = NULL \
                 WHERE id = ?2 AND status = 'running' AND lease_owner = ?3",
                id,
            ),
            Finish::Canceled { id } => (
                "UPDATE jobs SET status = 'canceled', finished_at = ?1, lease_owner = NULL \
                 WHERE id = ?2 AND status = 'running' AND lease_owner = ?3",
                id,
            ),
            Finish::Requeue { id } => (
                "UPDATE jobs SET status = 'queued', started_at = NULL, progress = 0, stage = NULL, \
                 attempts = MAX(attempts - 1, 0), lease_owner = NULL, lease_until = NULL \
                 WHERE id = ?2 AND status = 'running' AND lease_owner = ?3 AND ?1 IS NOT NULL",
                id,
            ),
        };
        let mut q = sqlx::query(sql).bind(now).bind(id.to_string()).bind(owner);
        if let Finish::Failed { error, .. } = item {
            q = q.bind(error);
        }
        q.execute(&mut *tx).await?;
    }
    let requeue = items.iter().any(|i| matches!(i, Finish::Requeue { .. }));
    let claimed = if !next.is_empty() && !requeue { claim_on(&mut tx, next, now, owner).await? } else { Vec::new() };
    tx.commit().await?;
    Ok(claimed)
}

/// The succeeded jobs of a finish batch in two statements whatever their number (each statement is
/// a round trip to the connection's thread): their rows, only those the lease holder still holds,
/// and the results of those.
async fn finish_succeeded_on(conn: &mut SqliteConnection, items: &[Finish], now: i64, owner: &str) -> StoreResult<()> {
    let succeeded: Vec<(&Uuid, &Encoded)> = items
        .iter()
        .filter_map(|i| match i {
            Finish::Succeeded { id, result } => Some((id, result)),
            _ => None,
        })
        .collect();
    if succeeded.is_empty() {
        return Ok(());
    }
    let marks = vec!["?"; succeeded.len()].join(", ");
    let sql = format!(
        "UPDATE jobs SET status = 'succeeded', finished_at = ?, progress = 1, stage = NULL, solved_by = lease_owner, lease_owner = NULL \
         WHERE id IN ({marks}) AND status = 'running' AND lease_owner = ? RETURNING id"
    );
    let mut q = sqlx::query(AssertSqlSafe(sql)).bind(now);
    for (id, _) in &succeeded {
        q = q.bind(id.to_string());
    }
    let held: std::collections::HashSet<String> =
        q.bind(owner).fetch_all(&mut *conn).await?.iter().map(|r| r.try_get::<String, _>(0)).collect::<Result<_, _>>()?;
    let stored: Vec<_> = succeeded.iter().filter(|(id, _)| held.contains(&id.to_string())).collect();
    if stored.is_empty() {
        return Ok(());
    }
    let rows = vec!["(?, ?, ?, ?)"; stored.len()].join(", ");
    let mut q = sqlx::query(AssertSqlSafe(format!("INSERT OR REPLACE INTO job_results (job_id, encoding, size, body) VALUES {rows}")));
    for (id, result) in stored {
        q = q.bind(id.to_string()).bind(result.encoding).bind(result.size as i64).bind(&result.body);
    }
    q.execute(&mut *conn).await?;
    Ok(())
}

async fn progress_on(conn: &mut SqliteConnection, items: &[(Uuid, f64, String)]) -> StoreResult<()> {
    let mut tx = conn.begin().await?;
    for (id, fraction, stage) in items {
        sqlx::query("UPDATE jobs SET progress = ?, stage = ? WHERE id = ? AND status = 'running'")
            .bind(fraction)
            .bind(stage)
            .bind(id.to_string())
            .execute(&mut *tx)
            .await?;
    }
    tx.commit().await?;
    Ok(())
}

/// Running jobs whose lease ends before `expired_before` (all of them with `i64::MAX`) go back to
/// the queue, or fail at the attempt cap.
async fn recover_on(
    conn: &mut SqliteConnection,
    max_attempts: i64,
    error: &str,
    now: i64,
    expired_before: i64,
) -> StoreResult<(u64, u64)> {
    let mut tx = conn.begin().await?;
    let failed = sqlx::query(
        "UPDATE jobs SET status = 'failed', finished_at = ?, error = ?, lease_owner = NULL \
         WHERE status = 'running' AND attempts >= ? AND COALESCE(lease_until, 0) < ?",
    )
    .bind(now)
    .bind(error)
    .bind(max_attempts)
    .bind(expired_before)
    .execute(&mut *tx)
    .await?
    .rows_affected();
    let requeued = sqlx::query(
        "UPDATE jobs SET status = 'queued', started_at = NULL, progress = 0, stage = NULL, \
         lease_owner = NULL, lease_until = NULL \
         WHERE status = 'running' AND COALESCE(lease_until, 0) < ?",
    )
    .bind(expired_before)
    .execute(&mut *tx)
    .await?
    .rows_affected();
    // A cancel requested while the process died is honoured now.
    sqlx::query(
        "UPDATE jobs SET status = 'canceled', finished_at = ? WHERE status = 'queued' AND cancel_requested = 1",
    )
    .bind(now)
    .execute(&mut *tx)
    .await?;
    tx.commit().await?;
    Ok((requeued, failed))
}


async fn record_key_on(conn: &mut SqliteConnection, record: &IdempotencyKey) -> StoreResult<Option<IdempotencyKey>> {
    sqlx::query(
        "INSERT INTO idempotency_keys (key, job_id, spec_hash, label, reused, created_at) \
         SELECT ?1, ?2, ?3, ?4, ?5, ?6 WHERE EXISTS (SELECT 1 FROM jobs WHERE id = ?2) \
         ON CONFLICT (key) DO NOTHING",
    )
    .bind(&record.key)
    .bind(record.job_id.to_string())
    .bind(&record.spec_hash)
    .bind(&record.label)
    .bind(record.reused as i64)
    .bind(record.created_at)
    .execute(&mut *conn)
    .await?;
    let sql = format!("SELECT {KEY_COLUMNS} FROM idempotency_keys WHERE key = ?");
    let row = sqlx::query(AssertSqlSafe(sql)).bind(&record.key).fetch_optional(&mut *conn).await?;
    row.map(|r| key_from_row(&r)).transpose()
}

fn key_from_row(r: &SqliteRow) -> StoreResult<IdempotencyKey> {
    Ok(IdempotencyKey {
        key: r.try_get("key")?,
        job_id: parse_uuid(&r.try_get::<String, _>("job_id")?)?,
        spec_hash: r.try_get("spec_hash")?,
        label: r.try_get("label")?,
        reused: r.try_get::<i64, _>("reused")? != 0,
        created_at: r.try_get("created_at")?,
    })
}

fn job_from_row(r: &SqliteRow, with_spec: bool) -> StoreResult<JobRow> {
    let status: String = r.try_get("status")?;
    Ok(JobRow {
        seq: r.try_get("seq")?,
        id: parse_uuid(&r.try_get::<String, _>("id")?)?,
        kind: r.try_get("kind")?,
        label: r.try_get("label")?,
        status: JobStatus::parse(&status).ok_or_else(|| StoreError::Corrupt(format!("status {status}")))?,
        spec: if with_spec { Some(r.try_get("spec")?) } else { None },
        spec_hash: r.try_get("spec_hash")?,
        solver_version: r.try_get("solver_version")?,
        created_at: r.try_get("created_at")?,
        started_at: r.try_get("started_at")?,
        finished_at: r.try_get("finished_at")?,
        attempts: r.try_get("attempts")?,
        progress: r.try_get("progress")?,
        stage: r.try_get("stage")?,
        cancel_requested: r.try_get::<i64, _>("cancel_requested")? != 0,
        error: r.try_get("error")?,
        estimate_cpu_seconds: r.try_get("estimate_cpu_seconds")?,
        estimate_memory_bytes: r.try_get("estimate_memory_bytes")?,
    })
}
