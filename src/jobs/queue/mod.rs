//! The persistent queue and its worker pool.
//!
//! Save, then signal: a job row is committed before the request is acknowledged, and the
//! dispatcher is woken after the commit. The dispatcher claims queued rows for free worker slots
//! only — a claimed job starts at once, so `running` means running, an attempt is charged only to
//! a job that started, and a cancel reaches it within one solver step — and runs each on a rayon
//! pool, never on tokio's threads. Workers send their outcome (and throttled progress) to one
//! writer task, which commits them in batches and then wakes `Prefer: wait` waiters and the
//! dispatcher. Cancellation, time limits and shutdown reach a running solver through a flag its
//! [`Observer`] polls.
//!
//! **Fair scheduling**: queued jobs are claimed by earliest *virtual deadline*
//! `due_at = created_at + AGING × estimated solve time` (then by age). The estimate is the job's
//! own work model (`jobs::cost`, stored with the job) scaled by the kind's measured-to-modelled
//! ratio in this process (1 until one of its jobs finished here, so a restart starts from the
//! model). A tiny job submitted behind hours of heavy work is due long before the
//! heavy jobs and starts at the next free slot; a heavy job waits at most `AGING ×` its own
//! estimate beyond its fair turn, so nothing starves.
//!
//! **Validation** runs on tokio's blocking threads, at most [`QueueConfig::validators`] at once, so a
//! large spec never stalls the async threads that answer health checks and other requests.
//!
//! Files: `submit.rs` (admission and the fair-scheduling estimate), `dispatch.rs` (claim and run
//! on the pool; the worker's observer), `writer.rs` (batched commits of progress and outcomes),
//! `leases.rs` (lease renewal and other instances' events), `control.rs` (wait, cancel,
//! shutdown); this file holds the shared state and the start.

mod control;
mod dispatch;
mod fanout;
mod leases;
mod submit;
mod writer;

use super::cost::Estimate;
use super::idempotency::{self, Keyed, Replay, Verdict};
use super::kind::Limits;
use super::registry;
use super::runner::{self, spec_hash, Outcome};
use crate::metrics::{KindLabel, KindStatusLabel, Metrics};
use crate::physics::{Interrupt, Observer};
use crate::problem::{ErrorCode, Problem};
use crate::store::{encode_result, Finish, JobRow, JobStatus, NewJob, Store, StoreError};
use serde_json::Value;
use std::collections::HashMap;
use std::sync::atomic::{AtomicBool, AtomicI64, AtomicU8, AtomicUsize, Ordering};
use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant};
use tokio::sync::{mpsc, oneshot, Notify};
use tracing::{info, info_span, warn};
use uuid::Uuid;

/// Tuning of the queue.
#[derive(Debug, Clone)]
pub struct QueueConfig {
    /// Worker threads (rayon pool size) = jobs of any size solved at once.
    pub workers: usize,
    /// Short-job slots besides the workers: threads of their own that take only short jobs (the
    /// stored estimate at most [`crate::store::SHORT_JOB_SECONDS`] of CPU), so that tiny jobs do
    /// not wait behind heavy ones and their throughput is not bound by the workers' count (a
    /// tiny job waits ≈ 1.5 ms on its commits for 30 µs of solving). None without workers.
    pub short_slots: usize,
    /// Queued jobs accepted before `POST` answers 503.
    pub max_backlog: usize,
    /// Per-job wall-time limit.
    pub job_timeout: Option<Duration>,
    /// Start attempts before an interrupted job fails.
    pub max_attempts: i64,
    /// Least time between two progress writes of one job.
    pub progress_interval: Duration,
    /// Problem-size limits applied to every spec.
    pub limits: Limits,
    /// Specs validated at once (each on a blocking thread).
    pub validators: usize,
    /// How long a claimed job stays with this instance without a renewal. The holder renews
    /// every [`RENEW_EVERY`]; when an instance dies, others re-queue its jobs this long after
    /// its last renewal.
    pub lease: Duration,
    /// Fan-out (issue 44): a sweep whose cases the work model estimates at this many CPU seconds
    /// or more (on average) runs its cases as child jobs that every instance sharing the store
    /// claims (on SQLite: this instance's workers); cheaper sweeps run in-process. `None`: never
    /// fan out.
    pub fan_out_min_case_seconds: Option<f64>,
}

impl Default for QueueConfig {
    fn default() -> Self {
        QueueConfig {
            workers: std::thread::available_parallelism().map(|n| n.get()).unwrap_or(2),
            short_slots: DEFAULT_SHORT_SLOTS,
            max_backlog: 10_000,
            job_timeout: Some(Duration::from_secs(600)),
            max_attempts: 3,
            progress_interval: Duration::from_millis(250),
            limits: Limits::default(),
            validators: 2,
            lease: Duration::from_secs(30),
            fan_out_min_case_seconds: Some(DEFAULT_FAN_OUT_MIN_CASE_SECONDS),
        }
    }
}

/// What a submission led to.
#[derive(Debug)]
pub enum Submitted {
    /// A new job, queued.
    Accepted(JobRow),
    /// An identical succeeded job, returned instead of recomputing.
    Reused(JobRow),
    /// The answer to the same request sent earlier under the same `Idempotency-Key`.
    Replayed(Replay),
    /// An identical job already queued or running (on any instance): one solve serves both.
    Joined(JobRow),
}

/// What `DELETE /v1/jobs/{id}` did.
#[derive(Debug)]
pub enum Cancellation {
    /// It was queued and is now canceled.
    Canceled(JobRow),
    /// It is running; the solver was asked to stop and will within one iteration step.
    Requested(JobRow),
    /// It was finished and is deleted (or did not exist: deleting is idempotent).
    Deleted,
}

/// The default crossover of fan-out, estimated CPU seconds per case (BENCHMARKS.md: the
/// fan-out's own cost per case is 4–9 ms of wall time; at 0.5 s it is 1–2 % of a case).
pub const DEFAULT_FAN_OUT_MIN_CASE_SECONDS: f64 = 0.5;

/// The default number of short-job slots ([`QueueConfig::short_slots`]; BENCHMARKS.md, scale-out).
pub const DEFAULT_SHORT_SLOTS: usize = 6;

/// Virtual-deadline weight of the estimated solve time (fair scheduling, see the module docs).
pub const AGING: f64 = 100.0;
/// The smallest solve time fair scheduling counts (a closed form's microseconds still cost a
/// claim and a commit).
pub const MIN_ESTIMATE: Duration = Duration::from_millis(1);
/// The furthest a virtual deadline lies ahead (ms; ≈ 30 years): a job's estimate may be
/// astronomically large only on a server without a work limit.
const MAX_DUE_MS: f64 = 1e12;
/// How often a worker renews the leases of its running jobs, and so how soon it sees a cancel
/// made through another instance.
pub const RENEW_EVERY: Duration = Duration::from_millis(500);
/// This instance's name in leases (`lease_owner`): `host/pid/random`, so an operator can tell
/// which process holds a running job; the random part keeps restarts with a reused pid apart.
fn instance_name() -> String {
    let mut buf = [0u8; 256];
    // SAFETY: gethostname writes at most buf.len() bytes into buf.
    let host = if unsafe { libc::gethostname(buf.as_mut_ptr().cast(), buf.len()) } == 0 {
        let end = buf.iter().position(|&b| b == 0).unwrap_or(buf.len());
        String::from_utf8_lossy(&buf[..end]).into_owned()
    } else {
        "host".to_string()
    };
    let random = Uuid::new_v4().simple().to_string();
    format!("{host}/{}/{}", std::process::id(), &random[..8])
}

/// How often a shared store's queue length is re-read for the backlog limit, ms.
const BACKLOG_RECOUNT_MS: i64 = 100;

/// How often an instance looks for jobs whose lease expired (their worker is gone).
pub const EXPIRY_SCAN_EVERY: Duration = Duration::from_secs(2);

/// Longest `Idempotency-Key` accepted (bytes).
pub const MAX_IDEMPOTENCY_KEY: usize = 255;

const FLAG_NONE: u8 = 0;
const FLAG_CANCEL: u8 = 1;
const FLAG_SHUTDOWN: u8 = 2;

/// What a worker does with a claimed job.
enum Work {
    Solve,
    /// A fanned-out job whose children have all finished: its result from theirs.
    Assemble(fanout::Assembly),
}

enum Event {
    /// `modelled`: the work model's CPU seconds of the job (0 when it did not run).
    /// `short`: it held a short-job slot.
    Finished { id: Uuid, kind: String, finish: Finish, status: JobStatus, wall: f64, modelled: f64, short: bool },
    Progress { id: Uuid, fraction: f64, stage: String },
}

struct Inner {
    store: Store,
    /// This process's name in leases (a fresh UUID per start).
    instance: String,
    /// Unix ms of the dispatcher's last pass (for `/readyz`).
    claim_loop_at: AtomicI64,
    config: QueueConfig,
    metrics: Arc<Metrics>,
    pool: rayon::ThreadPool,
    /// The short-job slots' threads (none without short slots).
    short_pool: Option<rayon::ThreadPool>,
    wake: Notify,
    idle: Notify,
    claiming: AtomicBool,
    /// Jobs this instance holds (claimed, not yet finished), in either kind of slot.
    active: AtomicUsize,
    /// Of `active`, those in short-job slots.
    active_short: AtomicUsize,
    /// Moving mean of measured solve wall time per kind, seconds (fair scheduling).
    estimates: Mutex<HashMap<String, f64>>,
    /// Specs being validated (bounded by `config.validators`).
    validating: tokio::sync::Semaphore,
    backlog: AtomicI64,
    /// When `backlog` was last re-read from a shared store (unix ms).
    backlog_counted_at: AtomicI64,
    running: Mutex<HashMap<Uuid, Arc<AtomicU8>>>,
    /// Jobs the backlog does not count (cases of a fan-out, parents waiting for theirs): their
    /// claims take no place back. Removed when they finish.
    uncounted: Mutex<std::collections::HashSet<Uuid>>,
    waiters: Mutex<HashMap<Uuid, Vec<oneshot::Sender<()>>>>,
    events: mpsc::UnboundedSender<Event>,
}

/// Handle to the queue (cheap to clone).
#[derive(Clone)]
pub struct Queue {
    inner: Arc<Inner>,
}

/// Unix time in milliseconds.
pub fn now_ms() -> i64 {
    std::time::SystemTime::now()
        .duration_since(std::time::UNIX_EPOCH)
        .map(|d| d.as_millis() as i64)
        .unwrap_or(0)
}

fn storage_problem(e: StoreError) -> Problem {
    warn!(error = %e, "storage error");
    Problem::new(ErrorCode::StorageUnavailable, "the job store could not be reached; try again")
}

impl Queue {
    /// Recover interrupted jobs, then start the dispatcher and the writer on the current tokio
    /// runtime.
    pub async fn start(store: Store, config: QueueConfig, metrics: Arc<Metrics>) -> Result<Queue, StoreError> {
        // The solvers' process-wide tables (Greenwood–Tripp integrals, ≈ 0.12 s), built now so
        // that the first job does not pay for them (the work models leave them out).
        tokio::task::spawn_blocking(super::warm_up);
        let interrupted = Problem::new(
            ErrorCode::Interrupted,
            format!("the job was interrupted {} times (service restarts) and was given up", config.max_attempts),
        );
        let error_json = serde_json::to_string(&interrupted).unwrap_or_default();
        let (requeued, failed) = store.recover_interrupted(config.max_attempts, &error_json, now_ms()).await?;
        if requeued + failed > 0 {
            info!(requeued, failed, "recovered jobs interrupted by a previous process");
        }
        let backlog = store.queued_count().await?;
        let uncounted = store.uncounted_jobs().await?;
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(config.workers.max(1))
            .thread_name(|i| format!("tribod-worker-{i}"))
            .build()
            .map_err(|e| StoreError::Corrupt(format!("worker pool: {e}")))?;
        let short_slots = if config.workers > 0 { config.short_slots } else { 0 };
        let short_pool = if short_slots > 0 {
            Some(
                rayon::ThreadPoolBuilder::new()
                    .num_threads(short_slots)
                    .thread_name(|i| format!("tribod-short-{i}"))
                    .build()
                    .map_err(|e| StoreError::Corrupt(format!("short-job pool: {e}")))?,
            )
        } else {
            None
        };
        let config = QueueConfig { short_slots, ..config };
        let (tx, rx) = mpsc::unbounded_channel();
        let validators = config.validators.max(1);
        let inner = Arc::new(Inner {
            instance: instance_name(),
            claim_loop_at: AtomicI64::new(now_ms()),
            store,
            config,
            metrics,
            pool,
            short_pool,
            wake: Notify::new(),
            idle: Notify::new(),
            claiming: AtomicBool::new(true),
            active: AtomicUsize::new(0),
            active_short: AtomicUsize::new(0),
            estimates: Mutex::new(HashMap::new()),
            validating: tokio::sync::Semaphore::new(validators),
            backlog: AtomicI64::new(backlog),
            backlog_counted_at: AtomicI64::new(now_ms()),
            running: Mutex::new(HashMap::new()),
            uncounted: Mutex::new(uncounted.into_iter().collect()),
            waiters: Mutex::new(HashMap::new()),
            events: tx,
        });
        inner.metrics.queue_depth.set(backlog);
        let queue = Queue { inner };
        tokio::spawn(queue.clone().writer(rx));
        if queue.inner.config.workers > 0 {
            tokio::spawn(queue.clone().dispatcher());
            tokio::spawn(queue.clone().leases(error_json));
        }
        if let Some(events) = queue.inner.store.events() {
            tokio::spawn(queue.clone().forward(events));
        }
        Ok(queue)
    }

    pub fn store(&self) -> &Store {
        &self.inner.store
    }

    pub fn limits(&self) -> &Limits {
        &self.inner.config.limits
    }

    pub fn metrics(&self) -> &Arc<Metrics> {
        &self.inner.metrics
    }

    /// Queued jobs (this process's count, initialised from the database).
    pub fn backlog(&self) -> i64 {
        self.inner.backlog.load(Ordering::Relaxed)
    }

    /// Whether the queue still claims and accepts jobs.
    pub fn is_accepting(&self) -> bool {
        self.inner.claiming.load(Ordering::Relaxed)
    }

    /// Whether this instance's claim loop ran recently (always true without workers).
    pub fn claim_loop_alive(&self) -> bool {
        self.inner.config.workers == 0 || now_ms() - self.inner.claim_loop_at.load(Ordering::Relaxed) < 10_000
    }
}
