//! The job store: the only module that speaks SQL. Two backends behind one type, [`Store`]:
//!
//! * [`sqlite`] — one embedded file (the default): one process, one writer connection.
//! * [`postgres`] — one PostgreSQL database shared by any number of instances (`tribod serve`,
//!   `tribod worker`): claims with `FOR UPDATE SKIP LOCKED`, leases renewed by the worker that
//!   holds a job, `LISTEN/NOTIFY` wake-ups.
//!
//! Both keep the same schema (each with its own migrations directory) and the same semantics,
//! and the same behaviour tests run against both. Leases exist in both: a claim records the
//! claiming instance and an expiry; a worker renews its jobs' leases (and learns of cancels made
//! through other instances); finishing is conditional on still holding the lease, so a job whose
//! lease expired and was re-run elsewhere is never finished twice.

pub mod children;
pub mod codec;
pub mod migrations;
pub mod postgres;
pub mod sqlite;

pub use children::{Child, ChildCounts, ChildOutcome};
pub use codec::{decode_result, encode_result, Encoded};

use serde::{Deserialize, Serialize};
use utoipa::ToSchema;
use uuid::Uuid;

/// Life cycle of a job: `queued → running → succeeded | failed | canceled`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize, ToSchema)]
#[serde(rename_all = "snake_case")]
pub enum JobStatus {
    Queued,
    Running,
    Succeeded,
    Failed,
    Canceled,
}

impl JobStatus {
    pub const ALL: [JobStatus; 5] =
        [Self::Queued, Self::Running, Self::Succeeded, Self::Failed, Self::Canceled];

    pub fn as_str(self) -> &'static str {
        match self {
            Self::Queued => "queued",
            Self::Running => "running",
            Self::Succeeded => "succeeded",
            Self::Failed => "failed",
            Self::Canceled => "canceled",
        }
    }

    pub fn parse(s: &str) -> Option<Self> {
        Self::ALL.into_iter().find(|x| x.as_str() == s)
    }

    pub fn is_finished(self) -> bool {
        matches!(self, Self::Succeeded | Self::Failed | Self::Canceled)
    }
}

/// A job row as stored (timestamps in unix milliseconds).
#[derive(Debug, Clone, PartialEq)]
pub struct JobRow {
    pub seq: i64,
    pub id: Uuid,
    pub kind: String,
    pub label: Option<String>,
    pub status: JobStatus,
    /// Canonical spec JSON; loaded only by [`Store::get`].
    pub spec: Option<String>,
    pub spec_hash: String,
    pub solver_version: String,
    pub created_at: i64,
    pub started_at: Option<i64>,
    pub finished_at: Option<i64>,
    pub attempts: i64,
    pub progress: f64,
    pub stage: Option<String>,
    pub cancel_requested: bool,
    /// problem+json of a failed job.
    pub error: Option<String>,
    /// The work model's CPU seconds and the memory model's bytes at submission (absent for jobs
    /// stored before the models existed).
    pub estimate_cpu_seconds: Option<f64>,
    pub estimate_memory_bytes: Option<f64>,
}

/// What the API writes when it accepts a job.
#[derive(Debug, Clone)]
pub struct NewJob {
    pub id: Uuid,
    pub kind: String,
    pub label: Option<String>,
    pub spec: String,
    pub spec_hash: String,
    pub solver_version: String,
    pub created_at: i64,
    /// The client's `Idempotency-Key`, recorded (table `idempotency_keys`) in the transaction
    /// that inserts the job; a key already recorded fails the insert with
    /// [`StoreError::DuplicateKey`].
    pub idempotency_key: Option<String>,
    /// The label the client sent (`label` may be the one the service gave): what a repeat under
    /// the same key is compared with.
    pub key_label: Option<String>,
    /// Virtual deadline for fair scheduling (unix ms); queued jobs are claimed by `due_at`, `seq`.
    pub due_at: i64,
    /// The work model's CPU seconds and the memory model's bytes.
    pub estimate_cpu_seconds: f64,
    pub estimate_memory_bytes: f64,
}

impl NewJob {
    /// The row of this job as inserted (status `queued`) with its `seq`.
    pub fn queued_row(&self, seq: i64) -> JobRow {
        JobRow {
            seq,
            id: self.id,
            kind: self.kind.clone(),
            label: self.label.clone(),
            status: JobStatus::Queued,
            spec: Some(self.spec.clone()),
            spec_hash: self.spec_hash.clone(),
            solver_version: self.solver_version.clone(),
            created_at: self.created_at,
            started_at: None,
            finished_at: None,
            attempts: 0,
            progress: 0.0,
            stage: None,
            cancel_requested: false,
            error: None,
            estimate_cpu_seconds: Some(self.estimate_cpu_seconds),
            estimate_memory_bytes: Some(self.estimate_memory_bytes),
        }
    }
}

/// A client's `Idempotency-Key` of `POST /v1/jobs` and the request first sent with it (table
/// `idempotency_keys`). It lives as long as its job: deleting the job deletes the key.
#[derive(Debug, Clone, PartialEq)]
pub struct IdempotencyKey {
    pub key: String,
    /// The job that answered the first request: created by it, or an identical job it reused or
    /// joined.
    pub job_id: Uuid,
    /// Spec hash and label of the first request (a repeat must match both).
    pub spec_hash: String,
    pub label: Option<String>,
    /// The job was another request's (reused or joined), not created by this key's request.
    pub reused: bool,
    pub created_at: i64,
}

/// A job a worker has claimed.
#[derive(Debug, Clone)]
pub struct ClaimedJob {
    pub id: Uuid,
    pub kind: String,
    pub spec: String,
    pub attempts: i64,
    /// Its stored estimate is at most [`SHORT_JOB_SECONDS`]: it may take a short-job slot (the
    /// queue clears it when the job takes an ordinary slot instead).
    pub short: bool,
}

/// The CPU seconds (the work model's stored estimate) up to which a job is *short*: besides the
/// ordinary worker slots, an instance has short-job slots that take only such jobs (issue 46
/// item 5: a tiny job's claim → solve → commit cycle is ≈ 1.5 ms of waiting on the database for
/// 30 µs of solving, so a few slots bound the throughput; and a tiny job need not wait behind
/// heavy ones). The partial indexes `jobs_short_queue` (migrations) carry the same predicate,
/// [`SHORT_JOB_SQL`], literally, so that the planners use them.
pub const SHORT_JOB_SECONDS: f64 = 0.01;
/// [`SHORT_JOB_SECONDS`] as the SQL predicate of the short-job claims and indexes.
pub const SHORT_JOB_SQL: &str = "estimate_cpu_seconds <= 0.01";

/// A worker's final word on a job, written by [`Store::finish_batch`].
#[derive(Debug, Clone)]
pub enum Finish {
    Succeeded { id: Uuid, result: Encoded },
    Failed { id: Uuid, error: String },
    Canceled { id: Uuid },
    /// Interrupted by shutdown: back to the queue, the attempt not counted.
    Requeue { id: Uuid },
}

/// The jobs to claim (alone, or in the commit that finishes a batch): up to `n` queued jobs of any
/// size in virtual-deadline order (the free ordinary slots), and up to `short` more among the
/// short ones (the free short-job slots, [`SHORT_JOB_SECONDS`]), leased until `lease_until` (unix
/// ms). A job claimed is marked [`ClaimedJob::short`] when short; at most `n` of those claimed are
/// not short.
#[derive(Debug, Clone, Copy, Default)]
pub struct ClaimNext {
    pub n: usize,
    pub short: usize,
    pub lease_until: i64,
}

impl ClaimNext {
    pub fn is_empty(&self) -> bool {
        self.n + self.short == 0
    }
}

/// What [`Store::finish_batch`] did besides finishing.
#[derive(Debug, Default)]
pub struct Finished {
    /// Some finished job is a fanned-out job's case (its parent may move on).
    pub cases: bool,
    /// The jobs claimed for the freed slots, in virtual-deadline order.
    pub claimed: Vec<ClaimedJob>,
}

/// Filters of `GET /v1/jobs`.
#[derive(Debug, Clone, Default)]
pub struct ListFilter {
    pub statuses: Vec<JobStatus>,
    pub kind: Option<String>,
    pub created_after: Option<i64>,
    pub created_before: Option<i64>,
    /// Keyset cursor: only jobs older (smaller `seq`) than this one.
    pub before_seq: Option<i64>,
    /// Also the case jobs of fanned-out jobs (hidden by default: a big sweep's cases would flood
    /// the list). Jobs joined or reused by a sweep but created on their own are always listed.
    pub cases: bool,
    /// Only the case jobs of this fanned-out job (created, joined or reused by it).
    pub parent: Option<Uuid>,
    pub limit: u32,
}

#[derive(Debug, thiserror::Error)]
pub enum StoreError {
    #[error("database error: {0}")]
    Sqlx(#[from] sqlx::Error),
    #[error("migration error: {0}")]
    Migrate(#[from] sqlx::migrate::MigrateError),
    #[error("corrupt row: {0}")]
    Corrupt(String),
    /// An insert collided with a recorded `Idempotency-Key`.
    #[error("this idempotency key is recorded")]
    DuplicateKey,
    /// An insert collided with an identical job (same spec hash and solver version) that is
    /// queued or running: one solve serves both.
    #[error("an identical job is queued or running")]
    InFlight,
    #[error("a write to the database failed {ms_ago} ms ago")]
    RecentWriteFailure { ms_ago: i64 },
}

pub type StoreResult<T> = Result<T, StoreError>;


/// What other instances did, as far as this one needs to know (PostgreSQL `LISTEN/NOTIFY`).
#[derive(Debug, Clone, PartialEq)]
pub enum StoreEvent {
    /// A job was queued (or handed back): claim.
    Queued,
    /// A job finished: answer its `Prefer: wait` requests.
    Finished(Uuid),
}

/// A job that renewed its lease: whether a cancel was requested meanwhile (possibly through
/// another instance).
#[derive(Debug, Clone, PartialEq)]
pub struct Renewed {
    pub id: Uuid,
    pub cancel_requested: bool,
}

/// Handle to the job store (cheap to clone): SQLite or PostgreSQL, chosen by the URL.
#[derive(Clone, Debug)]
pub enum Store {
    Sqlite(sqlite::SqliteStore),
    Postgres(postgres::PgStore),
}

/// Forward a method to the backend.
macro_rules! each {
    ($self:ident, $s:ident => $e:expr) => {
        match $self {
            Store::Sqlite($s) => $e,
            Store::Postgres($s) => $e,
        }
    };
}

impl Store {
    /// Open the store at `url`: `postgres://…` (or `postgresql://…`) selects PostgreSQL; a
    /// `sqlite:` URL or a plain path selects SQLite. Applies the backend's migrations.
    pub async fn open(url: &str) -> StoreResult<Store> {
        if url.starts_with("postgres://") || url.starts_with("postgresql://") {
            Ok(Store::Postgres(postgres::PgStore::open(url).await?))
        } else {
            Ok(Store::Sqlite(sqlite::SqliteStore::open(url).await?))
        }
    }

    /// Whether other processes may share this store (PostgreSQL): the queue then counts the
    /// backlog in the database and listens for other instances' events.
    pub fn is_shared(&self) -> bool {
        matches!(self, Store::Postgres(_))
    }

    /// Other instances' events (PostgreSQL only).
    pub fn events(&self) -> Option<tokio::sync::broadcast::Receiver<StoreEvent>> {
        match self {
            Store::Sqlite(_) => None,
            Store::Postgres(s) => Some(s.events()),
        }
    }

    pub async fn ping(&self, now: i64) -> StoreResult<()> {
        each!(self, s => s.ping(now).await)
    }
    pub async fn close(&self) {
        each!(self, s => s.close().await)
    }
    pub async fn insert(&self, job: &NewJob) -> StoreResult<JobRow> {
        each!(self, s => s.insert(job).await)
    }
    pub async fn find_reusable(&self, spec_hash: &str, solver_version: &str) -> StoreResult<Option<JobRow>> {
        each!(self, s => s.find_reusable(spec_hash, solver_version).await)
    }
    /// The queued or running job with this spec hash and solver version.
    pub async fn find_in_flight(&self, spec_hash: &str, solver_version: &str) -> StoreResult<Option<JobRow>> {
        each!(self, s => s.find_in_flight(spec_hash, solver_version).await)
    }
    /// The newest succeeded job with this spec (when `reusable`), else the queued or running one:
    /// the job a submission of this spec reuses (status succeeded) or joins (queued, running).
    pub async fn find_same(&self, spec_hash: &str, solver_version: &str, reusable: bool) -> StoreResult<Option<JobRow>> {
        each!(self, s => s.find_same(spec_hash, solver_version, reusable).await)
    }
    /// The record of a client's `Idempotency-Key`.
    pub async fn find_idempotency_key(&self, key: &str) -> StoreResult<Option<IdempotencyKey>> {
        each!(self, s => s.find_idempotency_key(key).await)
    }
    /// Record `record` for its (existing) job unless its key is recorded already; the record
    /// stored under the key afterwards (this one, or the earlier one that kept the key), or `None`
    /// when the job no longer exists (deleted meanwhile), so nothing was recorded.
    pub async fn record_idempotency_key(&self, record: &IdempotencyKey) -> StoreResult<Option<IdempotencyKey>> {
        each!(self, s => s.record_idempotency_key(record).await)
    }
    pub async fn get(&self, id: Uuid) -> StoreResult<Option<JobRow>> {
        each!(self, s => s.get(id).await)
    }
    pub async fn seq_of(&self, id: Uuid) -> StoreResult<Option<i64>> {
        each!(self, s => s.seq_of(id).await)
    }
    pub async fn list(&self, f: &ListFilter) -> StoreResult<Vec<JobRow>> {
        each!(self, s => s.list(f).await)
    }
    /// Claim queued jobs for `owner` as `next` says.
    pub async fn claim(&self, next: ClaimNext, now: i64, owner: &str) -> StoreResult<Vec<ClaimedJob>> {
        each!(self, s => s.claim(next, now, owner).await)
    }
    /// Commit workers' final words on jobs `owner` still holds (others' are dropped: their lease
    /// expired and the job was handed to another worker), and in the same commit claim the
    /// queued jobs `next` says for `owner` (none when the batch re-queues a job: shutdown); whether
    /// any finished job is a fanned-out job's case, and the jobs claimed.
    pub async fn finish_batch(&self, items: &[Finish], now: i64, owner: &str, next: ClaimNext) -> StoreResult<Finished> {
        each!(self, s => s.finish_batch(items, now, owner, next).await)
    }
    pub async fn progress_batch(&self, items: &[(Uuid, f64, String)]) -> StoreResult<()> {
        each!(self, s => s.progress_batch(items).await)
    }
    pub async fn cancel_queued(&self, id: Uuid, now: i64) -> StoreResult<bool> {
        each!(self, s => s.cancel_queued(id, now).await)
    }
    pub async fn request_cancel(&self, id: Uuid) -> StoreResult<bool> {
        each!(self, s => s.request_cancel(id).await)
    }
    pub async fn delete_finished(&self, id: Uuid) -> StoreResult<bool> {
        each!(self, s => s.delete_finished(id).await)
    }
    /// At start-up: jobs whose worker is gone go back to the queue (or fail at the attempt cap).
    /// SQLite: every `running` job (one process owns the file). PostgreSQL: jobs whose lease
    /// expired (other instances may be running theirs).
    pub async fn recover_interrupted(&self, max_attempts: i64, error: &str, now: i64) -> StoreResult<(u64, u64)> {
        each!(self, s => s.recover_interrupted(max_attempts, error, now).await)
    }
    /// Jobs whose lease expired go back to the queue (or fail at the attempt cap).
    pub async fn requeue_expired(&self, max_attempts: i64, error: &str, now: i64) -> StoreResult<(u64, u64)> {
        each!(self, s => s.requeue_expired(max_attempts, error, now).await)
    }
    /// Extend the leases `owner` holds on `ids` to `until`; the jobs still held, with their
    /// cancel flags.
    pub async fn renew_leases(&self, owner: &str, ids: &[Uuid], until: i64) -> StoreResult<Vec<Renewed>> {
        each!(self, s => s.renew_leases(owner, ids, until).await)
    }
    pub async fn count_by_status(&self) -> StoreResult<Vec<(JobStatus, i64)>> {
        each!(self, s => s.count_by_status().await)
    }
    pub async fn queued_count(&self) -> StoreResult<i64> {
        each!(self, s => s.queued_count().await)
    }
    pub async fn result(&self, id: Uuid) -> StoreResult<Option<String>> {
        each!(self, s => s.result(id).await)
    }
}

/// Columns of a [`JobRow`] (both backends).
pub(crate) const ROW_COLUMNS: &str = "seq, id, kind, label, status, spec_hash, solver_version, created_at, \
    started_at, finished_at, attempts, progress, stage, cancel_requested, error, estimate_cpu_seconds, \
    estimate_memory_bytes";

/// Columns of an [`IdempotencyKey`] (both backends).
pub(crate) const KEY_COLUMNS: &str = "key, job_id, spec_hash, label, reused, created_at";

pub(crate) fn parse_uuid(s: &str) -> StoreResult<Uuid> {
    Uuid::parse_str(s).map_err(|e| StoreError::Corrupt(format!("job id {s}: {e}")))
}

/// How long `/readyz` reports a failed write.
pub const FAILURE_MEMORY_MS: i64 = 5_000;

/// Unix time in milliseconds.
pub(crate) fn unix_ms() -> i64 {
    std::time::SystemTime::now().duration_since(std::time::UNIX_EPOCH).map(|d| d.as_millis() as i64).unwrap_or(0)
}
