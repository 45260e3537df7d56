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
    /// Worker threads (rayon pool size) = jobs solved at once.
    pub workers: usize,
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
}

impl Default for QueueConfig {
    fn default() -> Self {
        QueueConfig {
            workers: std::thread::available_parallelism().map(|n| n.get()).unwrap_or(2),
            max_backlog: 10_000,
            job_timeout: Some(Duration::from_secs(600)),
            max_attempts: 3,
            progress_interval: Duration::from_millis(250),
            limits: Limits::default(),
            validators: 2,
            lease: Duration::from_secs(30),
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

enum Event {
    /// `modelled`: the work model's CPU seconds of the job (0 when it did not run).
    Finished { id: Uuid, kind: String, finish: Finish, status: JobStatus, wall: f64, modelled: f64 },
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
    wake: Notify,
    idle: Notify,
    claiming: AtomicBool,
    active: AtomicUsize,
    /// Moving mean of measured solve wall time per kind, seconds (fair scheduling).
    estimates: Mutex<HashMap<String, f64>>,
    /// Specs being validated (bounded by `config.validators`).
    validating: tokio::sync::Semaphore,
    backlog: AtomicI64,
    /// When `backlog` was last re-read from a shared store (unix ms).
    backlog_counted_at: AtomicI64,
    running: Mutex<HashMap<Uuid, Arc<AtomicU8>>>,
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
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(config.workers.max(1))
            .thread_name(|i| format!("tribod-worker-{i}"))
            .build()
            .map_err(|e| StoreError::Corrupt(format!("worker pool: {e}")))?;
        let (tx, rx) = mpsc::unbounded_channel();
        let validators = config.validators.max(1);
        let inner = Arc::new(Inner {
            instance: instance_name(),
            claim_loop_at: AtomicI64::new(now_ms()),
            store,
            config,
            metrics,
            pool,
            wake: Notify::new(),
            idle: Notify::new(),
            claiming: AtomicBool::new(true),
            active: AtomicUsize::new(0),
            estimates: Mutex::new(HashMap::new()),
            validating: tokio::sync::Semaphore::new(validators),
            backlog: AtomicI64::new(backlog),
            backlog_counted_at: AtomicI64::new(now_ms()),
            running: Mutex::new(HashMap::new()),
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

    /// Validate, dedup, persist and signal. Problems carry field paths under `/spec`.
    ///
    /// With an `idempotency_key`, a repeated request (same kind, spec and label) answers the job
    /// that answered the first one, whether it was created, reused or joined
    /// ([`Submitted::Replayed`]); another request under the same key is refused with
    /// `idempotency_key_reused` (see [`super::idempotency`]).
    pub async fn submit(
        &self,
        kind: &str,
        spec: &Value,
        label: Option<String>,
        fresh: bool,
        idempotency_key: Option<String>,
    ) -> Result<Submitted, Problem> {
        let Some(k) = registry::find(kind) else {
            return Err(Problem::new(
                ErrorCode::UnknownKind,
                format!("no job kind named '{kind}'; known kinds: {}", registry::names().join(", ")),
            )
            .with_errors(vec![crate::problem::FieldError::new("/kind", "unknown kind")]));
        };
        if !self.inner.claiming.load(Ordering::Relaxed) {
            return Err(Problem::new(ErrorCode::ShuttingDown, "the service is shutting down"));
        }
        let (prepared, estimate) = self.validate(k, spec).await?;
        let spec_text = serde_json::to_string(&prepared).unwrap_or_default();
        let hash = spec_hash(k.name(), &spec_text);
        let keyed = idempotency_key.clone().map(|key| Keyed { key, spec_hash: hash.clone(), label: label.clone() });
        if let Some(answer) = self.earlier(&keyed).await? {
            return Ok(answer);
        }
        if let Some(row) = self.inner.store.find_same(&hash, k.solver_version(), !fresh).await.map_err(storage_problem)? {
            // None: deleted meanwhile (before its key could be recorded): a new job after all.
            if let Some(answer) = self.existing(row, &keyed).await? {
                return Ok(answer);
            }
        }
        // Reserve a backlog place before the insert, so concurrent submissions cannot overshoot.
        // A shared database counts every instance's queue: re-read at most every
        // BACKLOG_RECOUNT, counted locally in between (other instances' submissions within
        // that window can overshoot the limit by what they accept in it).
        if self.inner.store.is_shared() {
            let now = now_ms();
            let counted = self.inner.backlog_counted_at.load(Ordering::Relaxed);
            if now - counted >= BACKLOG_RECOUNT_MS
                && self.inner.backlog_counted_at.compare_exchange(counted, now, Ordering::Relaxed, Ordering::Relaxed).is_ok()
            {
                let queued = self.inner.store.queued_count().await.map_err(storage_problem)?;
                self.inner.backlog.store(queued, Ordering::Relaxed);
            }
        }
        let depth = self.inner.backlog.fetch_add(1, Ordering::Relaxed);
        if depth >= self.inner.config.max_backlog as i64 {
            self.inner.backlog.fetch_sub(1, Ordering::Relaxed);
            return Err(Problem::new(ErrorCode::QueueFull, format!("{depth} jobs are waiting; retry later")));
        }
        let created_at = now_ms();
        let job = NewJob {
            id: Uuid::now_v7(),
            kind: k.name().to_string(),
            label: label.clone(),
            spec: spec_text,
            spec_hash: hash.clone(),
            solver_version: k.solver_version().to_string(),
            created_at,
            idempotency_key: idempotency_key.clone(),
            due_at: created_at + (AGING * self.estimate(k.name(), estimate.cpu_seconds) * 1e3).min(MAX_DUE_MS) as i64,
            estimate_cpu_seconds: estimate.cpu_seconds,
            estimate_memory_bytes: estimate.memory_bytes,
        };
        let row = match self.inner.store.insert(&job).await {
            Ok(row) => row,
            Err(e) => {
                self.inner.backlog.fetch_sub(1, Ordering::Relaxed);
                // A concurrent request with the same key won the insert: answer as its record says.
                if let (StoreError::DuplicateKey, Some(answer)) = (&e, self.earlier(&keyed).await?) {
                    return Ok(answer);
                }
                // An identical job was queued meanwhile (here or on another instance): join it.
                if let StoreError::InFlight = e {
                    if let Some(row) = self.inner.store.find_in_flight(&hash, k.solver_version()).await.map_err(storage_problem)? {
                        if let Some(answer) = self.existing(row, &keyed).await? {
                            return Ok(answer);
                        }
                    }
                }
                return Err(storage_problem(e));
            }
        };
        self.inner.metrics.queue_depth.set(depth + 1);
        self.inner.metrics.submitted.get_or_create(&KindLabel { kind: job.kind.clone() }).inc();
        self.inner.wake.notify_one();
        Ok(Submitted::Accepted(row))
    }

    /// The replay (or refusal) an earlier request under the same `Idempotency-Key` gives, if any.
    async fn earlier(&self, keyed: &Option<Keyed>) -> Result<Option<Submitted>, Problem> {
        let Some(request) = keyed else { return Ok(None) };
        Ok(idempotency::look_up(&self.inner.store, request).await.map_err(storage_problem)?.into_replay()?.map(Submitted::Replayed))
    }

    /// The answer for an identical existing job (reused if it succeeded, else joined), once the
    /// request's key is recorded for it; or the key's earlier answer; `None`: the job was deleted.
    async fn existing(&self, row: JobRow, keyed: &Option<Keyed>) -> Result<Option<Submitted>, Problem> {
        if let Some(request) = keyed {
            match idempotency::attach(&self.inner.store, request, &row, now_ms()).await.map_err(storage_problem)? {
                Verdict::Recorded => {}
                other => return Ok(other.into_replay()?.map(Submitted::Replayed)),
            }
        }
        if row.status == JobStatus::Succeeded {
            self.inner.metrics.reused.get_or_create(&KindLabel { kind: row.kind.clone() }).inc();
            return Ok(Some(Submitted::Reused(row)));
        }
        Ok(Some(Submitted::Joined(row)))
    }

    /// Parse and validate a spec on a blocking thread (at most `validators` at once); the
    /// canonical spec (defaults filled) and the estimated cost.
    async fn validate(&self, k: &'static dyn super::kind::DynKind, spec: &Value) -> Result<(Value, Estimate), Problem> {
        let _permit = self
            .inner
            .validating
            .acquire()
            .await
            .map_err(|_| Problem::new(ErrorCode::ShuttingDown, "the service is shutting down"))?;
        let spec = spec.clone();
        let limits = self.inner.config.limits;
        tokio::task::spawn_blocking(move || k.prepare(&spec, &limits).map(|p| (p.canonical, p.cost.estimate)))
            .await
            .map_err(|e| Problem::new(ErrorCode::InternalError, format!("validation task failed: {e}")))?
            .map_err(|p| p.under("/spec"))
    }

    /// Estimated solve time of a job, seconds (fair scheduling): the work model's `modelled`
    /// CPU seconds, scaled by the kind's measured-to-modelled ratio in this process (1 until a
    /// job of the kind has finished here, so a restart starts from the model, not from nothing).
    fn estimate(&self, kind: &str, modelled: f64) -> f64 {
        let ratios = self.inner.estimates.lock().unwrap_or_else(|e| e.into_inner());
        modelled.max(MIN_ESTIMATE.as_secs_f64()) * ratios.get(kind).copied().unwrap_or(1.0)
    }

    /// Wait until job `id` is finished or `timeout` passes; the job as it then is.
    pub async fn wait(&self, id: Uuid, timeout: Duration) -> Result<Option<JobRow>, Problem> {
        let (tx, rx) = oneshot::channel();
        {
            let mut waiters = self.inner.waiters.lock().unwrap_or_else(|e| e.into_inner());
            let list = waiters.entry(id).or_default();
            list.retain(|s| !s.is_closed());
            list.push(tx);
        }
        // Registered before looking, so a finish between the look and the wait is not missed.
        let row = self.inner.store.get(id).await.map_err(storage_problem)?;
        match row {
            // Shutting down: answer with the job as it is (`begin_shutdown` wakes earlier waiters).
            Some(r) if !r.status.is_finished() && self.inner.claiming.load(Ordering::Relaxed) => {
                // Woken by this instance's writer, another instance's notification, or shutdown;
                // a slow poll covers a lost notification.
                let deadline = tokio::time::Instant::now() + timeout;
                let mut rx = rx;
                loop {
                    let step = tokio::time::Instant::now() + Duration::from_secs(1);
                    let woken = tokio::time::timeout_at(step.min(deadline), &mut rx).await.is_ok();
                    let row = self.inner.store.get(id).await.map_err(storage_problem)?;
                    let done = row.as_ref().is_none_or(|r| r.status.is_finished());
                    if woken || done || tokio::time::Instant::now() >= deadline || !self.is_accepting() {
                        return Ok(row);
                    }
                }
            }
            other => Ok(other),
        }
    }

    /// Cancel a queued or running job, or delete a finished one.
    pub async fn cancel(&self, id: Uuid) -> Result<Cancellation, Problem> {
        let store = &self.inner.store;
        for _ in 0..3 {
            let Some(row) = store.get(id).await.map_err(storage_problem)? else {
                return Ok(Cancellation::Deleted);
            };
            match row.status {
                JobStatus::Queued => {
                    if store.cancel_queued(id, now_ms()).await.map_err(storage_problem)? {
                        let depth = self.inner.backlog.fetch_sub(1, Ordering::Relaxed) - 1;
                        self.inner.metrics.queue_depth.set(depth);
                        self.notify_waiters(id);
                        let row = store.get(id).await.map_err(storage_problem)?;
                        return Ok(row.map(Cancellation::Canceled).unwrap_or(Cancellation::Deleted));
                    }
                    // Claimed meanwhile: look again.
                }
                JobStatus::Running => {
                    // The stored flag first (other instances and the response see it), then this
                    // instance's flag: the other order lets a local job finish as canceled before
                    // the stored flag is written, and the answer says no cancel was requested.
                    store.request_cancel(id).await.map_err(storage_problem)?;
                    // The flag may not exist yet (claimed, not yet spawned): create it set, and
                    // `spawn` adopts it.
                    self.inner
                        .running
                        .lock()
                        .unwrap_or_else(|e| e.into_inner())
                        .entry(id)
                        .or_insert_with(|| Arc::new(AtomicU8::new(FLAG_NONE)))
                        .store(FLAG_CANCEL, Ordering::Relaxed);
                    let row = store.get(id).await.map_err(storage_problem)?;
                    return Ok(row.map(Cancellation::Requested).unwrap_or(Cancellation::Deleted));
                }
                _ => {
                    store.delete_finished(id).await.map_err(storage_problem)?;
                    return Ok(Cancellation::Deleted);
                }
            }
        }
        Err(Problem::new(ErrorCode::StorageUnavailable, "the job changed state repeatedly; try again"))
    }

    /// Stop claiming; let running jobs finish within `grace`; interrupt the rest, which go back to
    /// the queue. Returns when no job runs in this process (or after `grace` + 10 s at most).
    pub async fn shutdown(&self, grace: Duration) {
        self.begin_shutdown();
        let running = self.inner.active.load(Ordering::Relaxed);
        if running > 0 {
            info!(running, grace_seconds = grace.as_secs_f64(), "waiting for running jobs");
        }
        if !self.wait_idle(grace).await {
            let flags: Vec<_> = self.inner.running.lock().unwrap_or_else(|e| e.into_inner()).values().cloned().collect();
            warn!(jobs = flags.len(), "grace period over: interrupting running jobs; they will be queued again");
            for f in flags {
                f.store(FLAG_SHUTDOWN, Ordering::Relaxed);
            }
            self.wait_idle(Duration::from_secs(10)).await;
        }
    }

    /// Stop claiming and accepting at once, and answer every `Prefer: wait` request now with its
    /// job as it is. Idempotent; [`Queue::shutdown`] calls it too.
    pub fn begin_shutdown(&self) {
        self.inner.claiming.store(false, Ordering::Relaxed);
        self.inner.wake.notify_one();
        let waiters: Vec<_> = self.inner.waiters.lock().unwrap_or_else(|e| e.into_inner()).drain().collect();
        for s in waiters.into_iter().flat_map(|(_, list)| list) {
            let _ = s.send(());
        }
    }

    /// Whether this instance's claim loop ran recently (always true without workers).
    pub fn claim_loop_alive(&self) -> bool {
        self.inner.config.workers == 0 || now_ms() - self.inner.claim_loop_at.load(Ordering::Relaxed) < 10_000
    }

    /// Renew the leases of this instance's running jobs, pass on cancels made through other
    /// instances, stop jobs whose lease was lost, and re-queue jobs whose worker is gone.
    async fn leases(self, expired_error: String) {
        let inner = &self.inner;
        let mut renew = tokio::time::interval(RENEW_EVERY);
        let mut last_scan = Instant::now();
        let mut last_renewed = Instant::now();
        loop {
            renew.tick().await;
            if !inner.claiming.load(Ordering::Relaxed) && inner.active.load(Ordering::Relaxed) == 0 {
                return;
            }
            let flags: Vec<(Uuid, Arc<AtomicU8>)> =
                inner.running.lock().unwrap_or_else(|e| e.into_inner()).iter().map(|(id, f)| (*id, f.clone())).collect();
            if !flags.is_empty() {
                let ids: Vec<Uuid> = flags.iter().map(|(id, _)| *id).collect();
                let until = now_ms() + inner.config.lease.as_millis() as i64;
                match inner.store.renew_leases(&inner.instance, &ids, until).await {
                    Ok(held) => {
                        last_renewed = Instant::now();
                        for (id, flag) in &flags {
                            match held.iter().find(|r| r.id == *id) {
                                Some(r) if r.cancel_requested => flag.store(FLAG_CANCEL, Ordering::Relaxed),
                                Some(_) => {}
                                // Lost (expired and taken over): stop; the finish will be dropped.
                                None => flag.store(FLAG_SHUTDOWN, Ordering::Relaxed),
                            }
                        }
                    }
                    Err(e) => {
                        warn!(error = %e, "renewing leases failed");
                        // Past our lease another instance may take the jobs over: stop them
                        // rather than race it (their finishes would be refused anyway).
                        if last_renewed.elapsed() >= inner.config.lease {
                            warn!(jobs = flags.len(), "leases could not be renewed in time: stopping this instance's jobs");
                            for (_, flag) in &flags {
                                flag.store(FLAG_SHUTDOWN, Ordering::Relaxed);
                            }
                        }
                    }
                }
            } else {
                last_renewed = Instant::now();
            }
            if last_scan.elapsed() >= EXPIRY_SCAN_EVERY {
                last_scan = Instant::now();
                match inner.store.requeue_expired(inner.config.max_attempts, &expired_error, now_ms()).await {
                    Ok((0, 0)) => {}
                    Ok((requeued, failed)) => {
                        info!(requeued, failed, "jobs whose worker stopped renewing its lease");
                        inner.wake.notify_one();
                    }
                    Err(e) => warn!(error = %e, "scanning for expired leases failed"),
                }
            }
        }
    }

    /// Other instances' events: claim when they queue, answer waiters when they finish.
    async fn forward(self, mut events: tokio::sync::broadcast::Receiver<crate::store::StoreEvent>) {
        use tokio::sync::broadcast::error::RecvError;
        loop {
            match events.recv().await {
                Ok(crate::store::StoreEvent::Queued) => self.inner.wake.notify_one(),
                Ok(crate::store::StoreEvent::Finished(id)) => self.notify_waiters(id),
                Err(RecvError::Lagged(_)) => self.inner.wake.notify_one(),
                Err(RecvError::Closed) => return,
            }
        }
    }

    /// Whether the queue still claims and accepts jobs.
    pub fn is_accepting(&self) -> bool {
        self.inner.claiming.load(Ordering::Relaxed)
    }

    async fn wait_idle(&self, timeout: Duration) -> bool {
        let deadline = tokio::time::Instant::now() + timeout;
        loop {
            let notified = self.inner.idle.notified();
            if self.inner.active.load(Ordering::Relaxed) == 0 {
                return true;
            }
            if tokio::time::timeout_at(deadline, notified).await.is_err() {
                return self.inner.active.load(Ordering::Relaxed) == 0;
            }
        }
    }

    fn notify_waiters(&self, id: Uuid) {
        let senders = self.inner.waiters.lock().unwrap_or_else(|e| e.into_inner()).remove(&id);
        for s in senders.into_iter().flatten() {
            let _ = s.send(());
        }
    }

    async fn dispatcher(self) {
        let inner = &self.inner;
        loop {
            let notified = inner.wake.notified();
            inner.claim_loop_at.store(now_ms(), Ordering::Relaxed);
            if !inner.claiming.load(Ordering::Relaxed) {
                return;
            }
            let target = inner.config.workers.max(1);
            let free = target.saturating_sub(inner.active.load(Ordering::Relaxed));
            let mut claimed_all = false;
            if free > 0 {
                let now = now_ms();
                let lease_until = now + inner.config.lease.as_millis() as i64;
                match inner.store.claim(free, now, &inner.instance, lease_until).await {
                    Ok(jobs) => {
                        claimed_all = jobs.len() == free;
                        let n = jobs.len() as i64;
                        if n > 0 {
                            let depth = inner.backlog.fetch_sub(n, Ordering::Relaxed) - n;
                            inner.metrics.queue_depth.set(depth.max(0));
                        }
                        for job in jobs {
                            self.spawn(job);
                        }
                    }
                    Err(e) => warn!(error = %e, "claiming jobs failed; retrying"),
                }
            }
            if claimed_all && inner.active.load(Ordering::Relaxed) < target {
                continue;
            }
            // Woken by a submission or a finished job; the timeout is a safety net only.
            let _ = tokio::time::timeout(Duration::from_secs(2), notified).await;
        }
    }

    fn spawn(&self, job: crate::store::ClaimedJob) {
        let inner = &self.inner;
        inner.active.fetch_add(1, Ordering::Relaxed);
        inner.metrics.running.set(inner.active.load(Ordering::Relaxed) as i64);
        let flag = inner
            .running
            .lock()
            .unwrap_or_else(|e| e.into_inner())
            .entry(job.id)
            .or_insert_with(|| Arc::new(AtomicU8::new(FLAG_NONE)))
            .clone();
        let events = inner.events.clone();
        let limits = inner.config.limits;
        let timeout = inner.config.job_timeout;
        let interval = inner.config.progress_interval;
        inner.pool.spawn(move || {
            let deadline = timeout.map(|t| Instant::now() + t);
            let span = info_span!("job", id = %job.id, kind = %job.kind, attempt = job.attempts);
            let _entered = span.enter();
            let observer = JobObserver {
                id: job.id,
                flag,
                deadline,
                events: events.clone(),
                interval,
                last: Mutex::new(None),
            };
            // Canceled (or shut down) while it waited in the pool's queue: do not start it.
            let mut modelled = 0.0;
            let (outcome, wall) = match (observer.check(), prepare(&job.kind, &job.spec, &limits)) {
                (Err(interrupt), _) => (Outcome::Interrupted(interrupt), 0.0),
                (Ok(()), Ok(prepared)) => {
                    modelled = prepared.cost.cpu_seconds();
                    runner::run(prepared, &observer)
                }
                (Ok(()), Err(problem)) => (Outcome::Failed(problem), 0.0),
            };
            let (finish, status) = match outcome {
                Outcome::Succeeded(mut value) => {
                    if let Some(meta) = value.get_mut("meta").and_then(Value::as_object_mut) {
                        meta.insert("job_id".into(), Value::String(job.id.to_string()));
                    }
                    let text = serde_json::to_string(&value).unwrap_or_default();
                    (Finish::Succeeded { id: job.id, result: encode_result(&text) }, JobStatus::Succeeded)
                }
                Outcome::Failed(problem) => {
                    info!(code = %problem.code, detail = %problem.detail, "job failed");
                    let error = serde_json::to_string(&problem).unwrap_or_default();
                    (Finish::Failed { id: job.id, error }, JobStatus::Failed)
                }
                Outcome::Interrupted(Interrupt::Shutdown) => (Finish::Requeue { id: job.id }, JobStatus::Queued),
                Outcome::Interrupted(_) => (Finish::Canceled { id: job.id }, JobStatus::Canceled),
            };
            info!(status = status.as_str(), wall_seconds = wall, "job done");
            let _ = events.send(Event::Finished { id: job.id, kind: job.kind.clone(), finish, status, wall, modelled });
        });
    }

    async fn writer(self, mut rx: mpsc::UnboundedReceiver<Event>) {
        let inner = &self.inner;
        let mut batch = Vec::new();
        while rx.recv_many(&mut batch, 512).await > 0 {
            let mut progress: HashMap<Uuid, (f64, String)> = HashMap::new();
            let mut finishes = Vec::new();
            let mut done = Vec::new();
            for event in batch.drain(..) {
                match event {
                    Event::Progress { id, fraction, stage } => {
                        progress.insert(id, (fraction, stage));
                    }
                    Event::Finished { id, kind, finish, status, wall, modelled } => {
                        progress.remove(&id);
                        finishes.push(finish);
                        done.push((id, kind, status, wall, modelled));
                    }
                }
            }
            if !progress.is_empty() {
                let items: Vec<_> = progress.into_iter().map(|(id, (f, s))| (id, f, s)).collect();
                if let Err(e) = inner.store.progress_batch(&items).await {
                    warn!(error = %e, "writing progress failed");
                }
            }
            if finishes.is_empty() {
                continue;
            }
            // A finished job must not be lost: retry until the database takes it.
            let mut delay = Duration::from_millis(50);
            while let Err(e) = inner.store.finish_batch(&finishes, now_ms(), &inner.instance).await {
                warn!(error = %e, "writing finished jobs failed; retrying");
                tokio::time::sleep(delay).await;
                delay = (delay * 2).min(Duration::from_secs(5));
            }
            for (id, kind, status, wall, modelled) in done {
                inner.running.lock().unwrap_or_else(|e| e.into_inner()).remove(&id);
                if status == JobStatus::Queued {
                    let depth = inner.backlog.fetch_add(1, Ordering::Relaxed) + 1;
                    inner.metrics.queue_depth.set(depth);
                } else {
                    inner.metrics.finished.get_or_create(&KindStatusLabel { kind: kind.clone(), status: status.as_str().into() }).inc();
                    if status == JobStatus::Succeeded {
                        // The kind's measured-to-modelled time ratio (a moving mean of logs, so
                        // that one outlier does not swing it), within [0.1, 10].
                        if modelled > 0.0 && wall > 0.0 {
                            let mut ratios = inner.estimates.lock().unwrap_or_else(|e| e.into_inner());
                            let r = (wall / modelled.max(MIN_ESTIMATE.as_secs_f64())).clamp(0.1, 10.0);
                            let mean = ratios.entry(kind.clone()).or_insert(r);
                            *mean = (0.8 * mean.ln() + 0.2 * r.ln()).exp();
                        }
                        inner.metrics.solve_seconds.get_or_create(&KindLabel { kind }).observe(wall);
                    }
                }
                let active = inner.active.fetch_sub(1, Ordering::Relaxed) - 1;
                inner.metrics.running.set(active as i64);
                self.notify_waiters(id);
            }
            inner.wake.notify_one();
            inner.idle.notify_waiters();
        }
    }
}

fn prepare(kind: &str, spec: &str, limits: &Limits) -> Result<super::kind::Prepared, Problem> {
    let k = registry::find(kind).ok_or_else(|| {
        Problem::new(ErrorCode::UnknownKind, format!("this server no longer knows the kind '{kind}'"))
    })?;
    let value: Value = serde_json::from_str(spec)
        .map_err(|e| Problem::new(ErrorCode::InternalError, format!("stored spec is not JSON: {e}")))?;
    k.prepare(&value, limits).map_err(|p| p.under("/spec"))
}

/// The observer a worker hands to its solver: throttled progress into the writer's channel,
/// and the cancel / shutdown flag and the deadline behind `check`.
struct JobObserver {
    id: Uuid,
    flag: Arc<AtomicU8>,
    deadline: Option<Instant>,
    events: mpsc::UnboundedSender<Event>,
    interval: Duration,
    last: Mutex<Option<Instant>>,
}

impl Observer for JobObserver {
    fn progress(&self, fraction: f64, stage: &str) {
        let now = Instant::now();
        let mut last = self.last.lock().unwrap_or_else(|e| e.into_inner());
        if last.is_some_and(|t| now.duration_since(t) < self.interval) {
            return;
        }
        *last = Some(now);
        let fraction = if fraction.is_finite() { fraction.clamp(0.0, 1.0) } else { 0.0 };
        let _ = self.events.send(Event::Progress { id: self.id, fraction, stage: stage.to_string() });
    }

    fn check(&self) -> Result<(), Interrupt> {
        match self.flag.load(Ordering::Relaxed) {
            FLAG_CANCEL => return Err(Interrupt::Canceled),
            FLAG_SHUTDOWN => return Err(Interrupt::Shutdown),
            _ => {}
        }
        if self.deadline.is_some_and(|d| Instant::now() > d) {
            return Err(Interrupt::TimedOut);
        }
        Ok(())
    }
}
