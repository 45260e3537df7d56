//! The PostgreSQL backend of the store: one database shared by any number of instances.
//!
//! * Claims take the next queued rows with `FOR UPDATE SKIP LOCKED`, so concurrent claimers never
//!   wait for nor take the same job, and record a lease (owner instance, expiry).
//! * Every state change other instances must hear about is announced with `pg_notify` on the
//!   channel [`CHANNEL`] inside its transaction (delivered at commit): `queued` wakes dispatchers,
//!   `finished:<id>` answers `Prefer: wait` requests held by any instance. A listener task turns
//!   notifications into [`StoreEvent`]s; callers also poll slowly, so a lost notification costs
//!   latency, never a job.
//! * Identical in-flight submissions are decided by the unique partial index `jobs_in_flight`
//!   (not an advisory lock: the index holds across every code path and survives crashes, and the
//!   loser of the race simply reads the winner's row).
//! * Statements on given running jobs (finish, progress, lease renewal) test the status as
//!   `(status || '') = 'running'`: an expression no partial index's predicate matches, so the
//!   planner looks the rows up by `id` instead of AND-ing that with a bitmap scan of every entry
//!   of `jobs_in_flight` — dead ones included, which bitmap scans never mark (issue 46: ≈ 1 000
//!   index entries read per tiny job under `cargo bench --bench scale`).

use super::*;
use sqlx::postgres::{PgListener, PgPool, PgPoolOptions, PgRow};
use sqlx::{AssertSqlSafe, Row};
use std::sync::atomic::{AtomicI64, Ordering};
use std::sync::Arc;
use std::time::Duration;
use tokio::sync::{broadcast, mpsc, oneshot};
use tracing::warn;

mod finish;
use finish::claimed_from_rows;

/// The `LISTEN/NOTIFY` channel of tribod's events.
pub const CHANNEL: &str = "tribod_events";

#[derive(Clone, Debug)]
pub struct PgStore {
    /// Durable writes (submissions, finishes, cancels) and reads.
    pub(super) pool: PgPool,
    /// Writes that may be lost in a database crash without losing a job (claims, lease renewals,
    /// progress): committed with `synchronous_commit = off`, so they do not wait for a WAL flush.
    /// A lost claim or renewal leaves the job queued or its lease expiring: it runs again.
    relaxed: PgPool,
    /// The writer's finishes with the next claims ([`finish`]): durable commits; one statement,
    /// prepared and planned once per connection (`plan_cache_mode = force_generic_plan`: planning
    /// it took ≈ 0.45 ms a call) with `enable_seqscan = off`, so that its plan, made while the
    /// table may be empty, reads every table through an index (by id, the queue's partial index in
    /// deadline order) and never scans the grown table (a generic plan cached while the table was
    /// small did: found with auto_explain under `cargo bench --bench scale`).
    finishes: PgPool,
    /// Submissions for the batch writer (one multi-row insert, one commit, per batch).
    inserts: mpsc::Sender<(NewJob, oneshot::Sender<StoreResult<i64>>)>,
    events: broadcast::Sender<StoreEvent>,
    last_write_failure: Arc<AtomicI64>,
}

/// Most submissions in one insert batch.
const INSERT_BATCH: usize = 256;

/// Which unique index an insert hit.
fn unique_violation(e: sqlx::Error) -> StoreError {
    match &e {
        sqlx::Error::Database(d) if d.is_unique_violation() => match d.constraint() {
            Some("idempotency_keys_pkey") => StoreError::DuplicateKey,
            _ => StoreError::InFlight,
        },
        _ => StoreError::Sqlx(e),
    }
}

/// How long a request waits for a database connection before it is answered
/// `503 storage_unavailable` (the database unreachable: `storage_faults::an_unreachable_database…`).
const ACQUIRE_TIMEOUT: Duration = Duration::from_secs(5);

impl PgStore {
    /// Connect, apply `migrations/postgres` and start listening for other instances' events.
    pub async fn open(url: &str) -> StoreResult<PgStore> {
        let pool = PgPoolOptions::new()
            .max_connections(16)
            .acquire_timeout(ACQUIRE_TIMEOUT)
            .connect(url)
            .await?;
        super::migrations::migrator(super::migrations::POSTGRES).run(&pool).await?;
        let relaxed = PgPoolOptions::new()
            .max_connections(4)
            .acquire_timeout(ACQUIRE_TIMEOUT)
            .after_connect(|conn, _| {
                Box::pin(async move {
                    sqlx::query("SET synchronous_commit = off").execute(&mut *conn).await?;
                    sqlx::query("SET plan_cache_mode = force_custom_plan").execute(conn).await?;
                    Ok(())
                })
            })
            .connect(url)
            .await?;
        let finishes = PgPoolOptions::new()
            .max_connections(2)
            .acquire_timeout(ACQUIRE_TIMEOUT)
            .after_connect(|conn, _| {
                Box::pin(async move {
                    sqlx::query("SET plan_cache_mode = force_generic_plan").execute(&mut *conn).await?;
                    sqlx::query("SET enable_seqscan = off").execute(conn).await?;
                    Ok(())
                })
            })
            .connect(url)
            .await?;
        let (events, _) = broadcast::channel(1024);
        let mut listener = PgListener::connect_with(&pool).await?;
        listener.listen(CHANNEL).await?;
        tokio::spawn(listen(listener, events.clone(), pool.clone()));
        let last_write_failure = Arc::new(AtomicI64::new(0));
        let (inserts, queue) = mpsc::channel(4 * INSERT_BATCH);
        tokio::spawn(insert_batches(pool.clone(), queue, last_write_failure.clone()));
        Ok(PgStore { pool, relaxed, finishes, inserts, events, last_write_failure })
    }

    pub fn events(&self) -> broadcast::Receiver<StoreEvent> {
        self.events.subscribe()
    }

    fn note<T>(&self, r: Result<T, sqlx::Error>) -> StoreResult<T> {
        r.map_err(|e| {
            self.last_write_failure.store(unix_ms(), Ordering::Relaxed);
            StoreError::from(e)
        })
    }

    pub async fn ping(&self, now: i64) -> StoreResult<()> {
        let failed_at = self.last_write_failure.load(Ordering::Relaxed);
        if failed_at > 0 && now - failed_at < FAILURE_MEMORY_MS {
            return Err(StoreError::RecentWriteFailure { ms_ago: now - failed_at });
        }
        let r = sqlx::query("UPDATE heartbeat SET beat = $1 WHERE id = 1").bind(now).execute(&self.pool).await;
        self.note(r).map(|_| ())
    }

    pub async fn close(&self) {
        self.relaxed.close().await;
        self.finishes.close().await;
        self.pool.close().await;
    }

    /// Insert a queued job: batched with concurrent submissions into one statement and one commit;
    /// a job the batch could not insert (a unique index said no) is retried alone for its error.
    /// A job with an `Idempotency-Key` is inserted alone, in one transaction with its key.
    pub async fn insert(&self, job: &NewJob) -> StoreResult<JobRow> {
        if job.idempotency_key.is_some() {
            return self.insert_one(job).await;
        }
        let (reply, answer) = oneshot::channel();
        let closed = || StoreError::Sqlx(sqlx::Error::PoolClosed);
        self.inserts.send((job.clone(), reply)).await.map_err(|_| closed())?;
        match answer.await.map_err(|_| closed())? {
            Ok(seq) => Ok(job.queued_row(seq)),
            Err(StoreError::InFlight) => self.insert_one(job).await,
            Err(e) => Err(e),
        }
    }

    /// Insert one job (and its `Idempotency-Key`) in one transaction; a unique index violation is
    /// named (in flight, or idempotency key recorded).
    async fn insert_one(&self, job: &NewJob) -> StoreResult<JobRow> {
        match self.insert_one_tx(job).await {
            Ok(seq) => Ok(job.queued_row(seq)),
            Err(e) => {
                let e = unique_violation(e);
                if matches!(e, StoreError::Sqlx(_)) {
                    self.last_write_failure.store(unix_ms(), Ordering::Relaxed);
                }
                Err(e)
            }
        }
    }

    async fn insert_one_tx(&self, job: &NewJob) -> Result<i64, sqlx::Error> {
        let mut tx = self.pool.begin().await?;
        let row = sqlx::query(
            "WITH ins AS (INSERT INTO jobs (id, kind, label, status, spec, spec_hash, solver_version, created_at, \
             due_at, estimate_cpu_seconds, estimate_memory_bytes) VALUES ($1, $2, $3, 'queued', $4, $5, $6, $7, $8, $10, $11) RETURNING seq) \
             SELECT seq, pg_notify($9, 'queued')::text FROM ins",
        )
        .bind(job.id.to_string())
        .bind(&job.kind)
        .bind(&job.label)
        .bind(&job.spec)
        .bind(&job.spec_hash)
        .bind(&job.solver_version)
        .bind(job.created_at)
        .bind(job.due_at)
        .bind(CHANNEL)
        .bind(job.estimate_cpu_seconds)
        .bind(job.estimate_memory_bytes)
        .fetch_one(&mut *tx)
        .await?;
        if let Some(key) = &job.idempotency_key {
            sqlx::query(
                "INSERT INTO idempotency_keys (key, job_id, spec_hash, label, reused, created_at) \
                 VALUES ($1, $2, $3, $4, FALSE, $5)",
            )
            .bind(key)
            .bind(job.id.to_string())
            .bind(&job.spec_hash)
            .bind(&job.key_label)
            .bind(job.created_at)
            .execute(&mut *tx)
            .await?;
        }
        tx.commit().await?;
        row.try_get(0)
    }

    async fn one(&self, sql: String, binds: &[&str]) -> StoreResult<Option<JobRow>> {
        let mut q = sqlx::query(AssertSqlSafe(sql));
        for b in binds {
            q = q.bind(*b);
        }
        let row = q.fetch_optional(&self.pool).await?;
        row.map(|r| job_from_row(&r)).transpose()
    }

    pub async fn find_reusable(&self, spec_hash: &str, solver_version: &str) -> StoreResult<Option<JobRow>> {
        let sql = format!(
            "SELECT {ROW_COLUMNS}, NULL::text AS spec FROM jobs WHERE spec_hash = $1 AND solver_version = $2 \
             AND status = 'succeeded' ORDER BY seq DESC LIMIT 1"
        );
        self.one(sql, &[spec_hash, solver_version]).await
    }

    pub async fn find_in_flight(&self, spec_hash: &str, solver_version: &str) -> StoreResult<Option<JobRow>> {
        let sql = format!(
            "SELECT {ROW_COLUMNS}, spec FROM jobs WHERE spec_hash = $1 AND solver_version = $2 \
             AND status IN ('queued', 'running') LIMIT 1"
        );
        self.one(sql, &[spec_hash, solver_version]).await
    }

    /// The newest succeeded job with this spec (when `reusable`), else the in-flight one, in one
    /// round trip (each branch on its own partial index).
    pub async fn find_same(&self, spec_hash: &str, solver_version: &str, reusable: bool) -> StoreResult<Option<JobRow>> {
        let sql = format!(
            "(SELECT {ROW_COLUMNS}, NULL::text AS spec, 0 AS rank FROM jobs WHERE spec_hash = $1 AND solver_version = $2 \
              AND status = 'succeeded' AND $3 ORDER BY seq DESC LIMIT 1) \
             UNION ALL \
             (SELECT {ROW_COLUMNS}, spec, 1 AS rank FROM jobs WHERE spec_hash = $1 AND solver_version = $2 \
              AND status IN ('queued', 'running') LIMIT 1) \
             ORDER BY rank LIMIT 1"
        );
        let row = sqlx::query(AssertSqlSafe(sql))
            .bind(spec_hash)
            .bind(solver_version)
            .bind(reusable)
            .fetch_optional(&self.pool)
            .await?;
        row.map(|r| job_from_row(&r)).transpose()
    }

    pub async fn find_idempotency_key(&self, key: &str) -> StoreResult<Option<IdempotencyKey>> {
        let sql = format!("SELECT {KEY_COLUMNS} FROM idempotency_keys WHERE key = $1");
        let row = sqlx::query(AssertSqlSafe(sql)).bind(key).fetch_optional(&self.pool).await?;
        row.map(|r| key_from_row(&r)).transpose()
    }

    /// Record a key for an existing job unless the key is taken, then read the record under the
    /// key in a second statement (its snapshot sees a concurrent request's committed record, which
    /// the insert's snapshot may not). The job deleted meanwhile: nothing recorded, `None`.
    pub async fn record_idempotency_key(&self, record: &IdempotencyKey) -> StoreResult<Option<IdempotencyKey>> {
        let r = sqlx::query(
            "INSERT INTO idempotency_keys (key, job_id, spec_hash, label, reused, created_at) \
             SELECT $1, $2, $3, $4, $5, $6 WHERE EXISTS (SELECT 1 FROM jobs WHERE id = $2) \
             ON CONFLICT (key) DO NOTHING",
        )
        .bind(&record.key)
        .bind(record.job_id.to_string())
        .bind(&record.spec_hash)
        .bind(&record.label)
        .bind(record.reused)
        .bind(record.created_at)
        .execute(&self.pool)
        .await;
        match r {
            // Deleted between the check and the commit.
            Err(sqlx::Error::Database(d)) if d.is_foreign_key_violation() => return Ok(None),
            r => {
                self.note(r)?;
            }
        }
        self.find_idempotency_key(&record.key).await
    }

    pub async fn get(&self, id: Uuid) -> StoreResult<Option<JobRow>> {
        self.one(format!("SELECT {ROW_COLUMNS}, spec FROM jobs WHERE id = $1"), &[&id.to_string()]).await
    }

    pub async fn seq_of(&self, id: Uuid) -> StoreResult<Option<i64>> {
        Ok(sqlx::query_scalar::<_, i64>("SELECT seq FROM jobs WHERE id = $1")
            .bind(id.to_string())
            .fetch_optional(&self.pool)
            .await?)
    }

    pub async fn list(&self, f: &ListFilter) -> StoreResult<Vec<JobRow>> {
        let mut sql = format!("SELECT {ROW_COLUMNS}, NULL::text AS spec FROM jobs WHERE TRUE");
        let mut n = 0;
        let mut next = || {
            n += 1;
            format!("${n}")
        };
        if !f.statuses.is_empty() {
            // Status names come from a closed enum, never from the request text.
            let names: Vec<String> = f.statuses.iter().map(|s| format!("'{}'", s.as_str())).collect();
            sql.push_str(&format!(" AND status IN ({})", names.join(", ")));
        }
        if f.kind.is_some() {
            sql.push_str(&format!(" AND kind = {}", next()));
        }
        if f.parent.is_some() {
            sql.push_str(&format!(" AND id IN (SELECT job_id FROM job_children WHERE parent_id = {})", next()));
        } else if !f.cases {
            sql.push_str(" AND NOT EXISTS (SELECT 1 FROM job_children c WHERE c.job_id = jobs.id AND c.owned)");
        }
        if f.created_after.is_some() {
            sql.push_str(&format!(" AND created_at > {}", next()));
        }
        if f.created_before.is_some() {
            sql.push_str(&format!(" AND created_at < {}", next()));
        }
        if f.before_seq.is_some() {
            sql.push_str(&format!(" AND seq < {}", next()));
        }
        sql.push_str(&format!(" ORDER BY seq DESC LIMIT {}", next()));
        let mut q = sqlx::query(AssertSqlSafe(sql));
        if let Some(k) = &f.kind {
            q = q.bind(k.clone());
        }
        if let Some(p) = f.parent {
            q = q.bind(p.to_string());
        }
        for t in [f.created_after, f.created_before, f.before_seq].into_iter().flatten() {
            q = q.bind(t);
        }
        let rows = q.bind(f.limit as i64).fetch_all(&self.pool).await?;
        rows.iter().map(job_from_row).collect()
    }

    /// Claim up to `n` queued jobs in virtual-deadline order. The locked `seq`s come back as an
    /// array (`= ANY(ARRAY(…))`), so the update is a primary-key lookup: written as `IN (…)` the
    /// generic plan hash-joins against a scan of the whole table on every claim.
    pub async fn claim(&self, next: ClaimNext, now: i64, owner: &str) -> StoreResult<Vec<ClaimedJob>> {
        if next.is_empty() {
            return Ok(Vec::new());
        }
        static CLAIM: std::sync::LazyLock<String> = std::sync::LazyLock::new(|| {
            // A fanned-out job claimed to be assembled keeps its start and progress (a queued
            // job has neither: never started, or reset when it was handed back).
            format!(
                "UPDATE jobs SET status = 'running', started_at = COALESCE(started_at, $1), attempts = attempts + 1, \
                 progress = CASE WHEN started_at IS NULL THEN 0 ELSE progress END, \
                 stage = CASE WHEN started_at IS NULL THEN NULL ELSE stage END, lease_owner = $2, lease_until = $3 \
                 WHERE {} \
                 RETURNING id, kind, spec, attempts, due_at, seq, COALESCE({SHORT_JOB_SQL}, FALSE)",
                finish::claim_where("$4", "$5")
            )
        });
        let rows = sqlx::query(AssertSqlSafe(CLAIM.as_str()))
            // Prepared once, planned at each call (the relaxed pool's `plan_cache_mode =
            // force_custom_plan`: a generic plan cached while the table was small scans it
            // sequentially for ever after — found with auto_explain under `cargo bench --bench scale`).
            .bind(now)
            .bind(owner)
            .bind(next.lease_until)
            .bind(next.n as i64)
            .bind(next.short as i64)
            .fetch_all(&self.relaxed)
            .await;
        Ok(claimed_from_rows(&self.note(rows)?, 0)?)
    }

    pub async fn progress_batch(&self, items: &[(Uuid, f64, String)]) -> StoreResult<()> {
        let ids: Vec<String> = items.iter().map(|(id, _, _)| id.to_string()).collect();
        let fractions: Vec<f64> = items.iter().map(|(_, f, _)| *f).collect();
        let stages: Vec<String> = items.iter().map(|(_, _, s)| s.clone()).collect();
        let r = sqlx::query(
            "UPDATE jobs SET progress = u.fraction, stage = u.stage \
             FROM UNNEST($1::text[], $2::float8[], $3::text[]) AS u(id, fraction, stage) \
             WHERE jobs.id = ANY($1) AND jobs.id = u.id AND (jobs.status || '') = 'running'",
        )
        .bind(ids)
        .bind(fractions)
        .bind(stages)
        .execute(&self.relaxed)
        .await;
        self.note(r).map(|_| ())
    }

    pub async fn cancel_queued(&self, id: Uuid, now: i64) -> StoreResult<bool> {
        let r = sqlx::query(
            "WITH up AS (UPDATE jobs SET status = 'canceled', finished_at = $1, cancel_requested = TRUE \
             WHERE id = $2 AND status = 'queued' RETURNING id) \
             SELECT pg_notify($3, 'finished:' || id)::text FROM up",
        )
        .bind(now)
        .bind(id.to_string())
        .bind(CHANNEL)
        .fetch_all(&self.pool)
        .await;
        Ok(self.note(r)?.len() == 1)
    }

    pub async fn request_cancel(&self, id: Uuid) -> StoreResult<bool> {
        let r = sqlx::query("UPDATE jobs SET cancel_requested = TRUE WHERE id = $1 AND status = 'running'")
            .bind(id.to_string())
            .execute(&self.pool)
            .await;
        Ok(self.note(r)?.rows_affected() == 1)
    }

    pub async fn delete_finished(&self, id: Uuid) -> StoreResult<bool> {
        let r = sqlx::query("DELETE FROM jobs WHERE id = $1 AND status IN ('succeeded', 'failed', 'canceled')")
            .bind(id.to_string())
            .execute(&self.pool)
            .await;
        Ok(self.note(r)?.rows_affected() == 1)
    }

    /// Other instances may hold running jobs: only expired leases are recovered.
    pub async fn recover_interrupted(&self, max_attempts: i64, error: &str, now: i64) -> StoreResult<(u64, u64)> {
        self.requeue_expired(max_attempts, error, now).await
    }

    pub async fn requeue_expired(&self, max_attempts: i64, error: &str, now: i64) -> StoreResult<(u64, u64)> {
        let r = self.requeue_tx(max_attempts, error, now).await;
        self.note(r)
    }

    async fn requeue_tx(&self, max_attempts: i64, error: &str, now: i64) -> Result<(u64, u64), sqlx::Error> {
        let mut tx = self.pool.begin().await?;
        let failed = sqlx::query(
            "UPDATE jobs SET status = 'failed', finished_at = $1, error = $2, lease_owner = NULL \
             WHERE status = 'running' AND attempts >= $3 AND COALESCE(lease_until, 0) < $1",
        )
        .bind(now)
        .bind(error)
        .bind(max_attempts)
        .execute(&mut *tx)
        .await?
        .rows_affected();
        let requeued = sqlx::query(
            "UPDATE jobs SET status = 'queued', started_at = NULL, progress = 0, stage = NULL, \
             lease_owner = NULL, lease_until = NULL \
             WHERE status = 'running' AND COALESCE(lease_until, 0) < $1",
        )
        .bind(now)
        .execute(&mut *tx)
        .await?
        .rows_affected();
        // A cancel requested while the worker was gone is honoured now.
        sqlx::query("UPDATE jobs SET status = 'canceled', finished_at = $1 WHERE status = 'queued' AND cancel_requested")
            .bind(now)
            .execute(&mut *tx)
            .await?;
        if requeued > 0 {
            sqlx::query("SELECT pg_notify($1, 'queued')").bind(CHANNEL).execute(&mut *tx).await?;
        }
        tx.commit().await?;
        Ok((requeued, failed))
    }

    pub async fn renew_leases(&self, owner: &str, ids: &[Uuid], until: i64) -> StoreResult<Vec<Renewed>> {
        if ids.is_empty() {
            return Ok(Vec::new());
        }
        let ids: Vec<String> = ids.iter().map(Uuid::to_string).collect();
        let rows = sqlx::query(
            "UPDATE jobs SET lease_until = $1 WHERE lease_owner = $2 AND (status || '') = 'running' AND id = ANY($3) \
             RETURNING id, cancel_requested",
        )
        .bind(until)
        .bind(owner)
        .bind(ids)
        .fetch_all(&self.relaxed)
        .await;
        self.note(rows)?
            .iter()
            .map(|r| Ok(Renewed { id: parse_uuid(&r.try_get::<String, _>(0)?)?, cancel_requested: r.try_get(1)? }))
            .collect()
    }

    pub async fn count_by_status(&self) -> StoreResult<Vec<(JobStatus, i64)>> {
        let rows = sqlx::query("SELECT status, COUNT(*) FROM jobs GROUP BY status").fetch_all(&self.pool).await?;
        rows.iter()
            .map(|r| {
                let s: String = r.try_get(0)?;
                let status = JobStatus::parse(&s).ok_or_else(|| StoreError::Corrupt(format!("status {s}")))?;
                Ok((status, r.try_get(1)?))
            })
            .collect()
    }

    pub async fn queued_count(&self) -> StoreResult<i64> {
        // A fanned-out job's cases are its work, admitted with it: not counted again.
        Ok(sqlx::query_scalar::<_, i64>(
            "SELECT COUNT(*) FROM jobs WHERE status = 'queued' \
             AND NOT EXISTS (SELECT 1 FROM job_children c WHERE c.job_id = jobs.id AND c.owned)",
        )
        .fetch_one(&self.pool)
        .await?)
    }

    pub async fn result(&self, id: Uuid) -> StoreResult<Option<String>> {
        let row = sqlx::query("SELECT encoding, body FROM job_results WHERE job_id = $1")
            .bind(id.to_string())
            .fetch_optional(&self.pool)
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
}

/// The batch writer: take every waiting submission (up to [`INSERT_BATCH`]), insert them with one
/// multi-row statement that also notifies `queued` once, and answer each with its `seq`. Rows a
/// unique index refused (`ON CONFLICT DO NOTHING`) are answered [`StoreError::InFlight`], and
/// [`PgStore::insert`] retries them alone to learn which index; a failed statement fails the
/// whole batch (nothing of it was committed).
async fn insert_batches(
    pool: PgPool,
    mut queue: mpsc::Receiver<(NewJob, oneshot::Sender<StoreResult<i64>>)>,
    last_write_failure: Arc<AtomicI64>,
) {
    let mut batch = Vec::with_capacity(INSERT_BATCH);
    while queue.recv_many(&mut batch, INSERT_BATCH).await > 0 {
        let r = sqlx::query(
            "WITH ins AS (INSERT INTO jobs (id, kind, label, status, spec, spec_hash, solver_version, created_at, \
             due_at, estimate_cpu_seconds, estimate_memory_bytes) \
             SELECT u.id, u.kind, u.label, 'queued', u.spec, u.spec_hash, u.solver_version, u.created_at, u.due_at, u.cpu, u.mem \
             FROM UNNEST($1::text[], $2::text[], $3::text[], $4::text[], $5::text[], $6::text[], $7::bigint[], \
                         $8::bigint[], $10::float8[], $11::float8[]) \
                  AS u(id, kind, label, spec, spec_hash, solver_version, created_at, due_at, cpu, mem) \
             ON CONFLICT DO NOTHING RETURNING id, seq) \
             SELECT id, seq, (SELECT pg_notify($9, 'queued'))::text FROM ins",
        )
        .bind(batch.iter().map(|(j, _)| j.id.to_string()).collect::<Vec<_>>())
        .bind(batch.iter().map(|(j, _)| j.kind.clone()).collect::<Vec<_>>())
        .bind(batch.iter().map(|(j, _)| j.label.clone()).collect::<Vec<_>>())
        .bind(batch.iter().map(|(j, _)| j.spec.clone()).collect::<Vec<_>>())
        .bind(batch.iter().map(|(j, _)| j.spec_hash.clone()).collect::<Vec<_>>())
        .bind(batch.iter().map(|(j, _)| j.solver_version.clone()).collect::<Vec<_>>())
        .bind(batch.iter().map(|(j, _)| j.created_at).collect::<Vec<_>>())
        .bind(batch.iter().map(|(j, _)| j.due_at).collect::<Vec<_>>())
        .bind(CHANNEL)
        .bind(batch.iter().map(|(j, _)| j.estimate_cpu_seconds).collect::<Vec<_>>())
        .bind(batch.iter().map(|(j, _)| j.estimate_memory_bytes).collect::<Vec<_>>())
        .fetch_all(&pool)
        .await;
        match r {
            Ok(rows) => {
                let mut seqs = std::collections::HashMap::with_capacity(rows.len());
                for row in &rows {
                    if let (Ok(id), Ok(seq)) = (row.try_get::<String, _>(0), row.try_get::<i64, _>(1)) {
                        seqs.insert(id, seq);
                    }
                }
                for (job, reply) in batch.drain(..) {
                    let answer = seqs.get(&job.id.to_string()).copied().ok_or(StoreError::InFlight);
                    let _ = reply.send(answer);
                }
            }
            Err(e) => {
                last_write_failure.store(unix_ms(), Ordering::Relaxed);
                let message = e.to_string();
                for (_, reply) in batch.drain(..) {
                    let _ = reply.send(Err(StoreError::Sqlx(sqlx::Error::Protocol(message.clone()))));
                }
            }
        }
    }
}

/// Forward `LISTEN` notifications as events until the store is dropped. `recv` reconnects by
/// itself after a lost connection; notifications sent meanwhile are lost, which the callers'
/// slow polls cover.
async fn listen(mut listener: PgListener, events: broadcast::Sender<StoreEvent>, pool: PgPool) {
    while !pool.is_closed() {
        match listener.recv().await {
            Ok(n) => {
                let event = match n.payload().strip_prefix("finished:") {
                    Some(id) => match Uuid::parse_str(id) {
                        Ok(id) => StoreEvent::Finished(id),
                        Err(_) => continue,
                    },
                    None => StoreEvent::Queued,
                };
                // No receiver yet (or any more): the event is dropped, the connection kept.
                let _ = events.send(event);
            }
            Err(e) => {
                warn!(error = %e, "LISTEN connection failed; retrying");
                tokio::time::sleep(Duration::from_secs(1)).await;
            }
        }
    }
}

fn key_from_row(r: &PgRow) -> StoreResult<IdempotencyKey> {
    Ok(IdempotencyKey {
        key: r.try_get("key")?,
        job_id: parse_uuid(&r.try_get::<String, _>("job_id")?)?,
        spec_hash: r.try_get("spec_hash")?,
        label: r.try_get("label")?,
        reused: r.try_get("reused")?,
        created_at: r.try_get("created_at")?,
    })
}

fn job_from_row(r: &PgRow) -> StoreResult<JobRow> {
    let status: String = r.try_get("status")?;
    Ok(JobRow {
        seq: r.try_get("seq")?,
        id: parse_uuid(&r.try_get::<String, _>("id")?)?,
        kind: r.try_get("kind")?,
        label: r.try_get("label")?,
        status: JobStatus::parse(&status).ok_or_else(|| StoreError::Corrupt(format!("status {status}")))?,
        spec: r.try_get("spec")?,
        spec_hash: r.try_get("spec_hash")?,
        solver_version: r.try_get("solver_version")?,
        created_at: r.try_get("created_at")?,
        started_at: r.try_get("started_at")?,
        finished_at: r.try_get("finished_at")?,
        attempts: r.try_get("attempts")?,
        progress: r.try_get("progress")?,
        stage: r.try_get("stage")?,
        cancel_requested: r.try_get("cancel_requested")?,
        error: r.try_get("error")?,
        estimate_cpu_seconds: r.try_get("estimate_cpu_seconds")?,
        estimate_memory_bytes: r.try_get("estimate_memory_bytes")?,
    })
}
