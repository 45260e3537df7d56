//! The persistent queue and its worker pool.
//!
//! Save, then signal: a job row is committed before the request is acknowledged, and the
//! dispatcher is woken after the commit. The dispatcher claims queued rows (oldest first) for free
//! worker slots and runs each on a rayon pool — never on tokio's threads. Workers send their
//! outcome (and throttled progress) to one writer task, which commits them in batches and then
//! wakes `Prefer: wait` waiters and the dispatcher. Cancellation, time limits and shutdown reach a
//! running solver through a flag its [`Observer`] polls.
//!
//! Short jobs are claimed ahead: while the recent mean solve time is below [`PREFETCH_BELOW`], the
//! dispatcher keeps up to [`PREFETCH_PER_WORKER`] claimed jobs per worker in the pool's queue, so
//! tiny jobs do not each wait for a database round trip. A prefetched job shows `running` with
//! progress 0 until a worker takes it; its time limit starts when the worker does.

use super::kind::Limits;
use super::registry;
use super::runner::{self, spec_hash, Outcome};
use crate::metrics::{KindLabel, KindStatusLabel, Metrics};
use crate::physics::{Interrupt, Observer};
use crate::problem::{ErrorCode, Problem};
use crate::store::{encode_result, Finish, JobRow, JobStatus, NewJob, Store, StoreError};
use serde_json::Value;
use std::collections::HashMap;
use std::sync::atomic::{AtomicBool, AtomicI64, AtomicU64, AtomicU8, AtomicUsize, Ordering};
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

/// Claim ahead only while jobs take less than this on average.
pub const PREFETCH_BELOW: Duration = Duration::from_millis(20);
/// Claimed-but-waiting jobs per worker when prefetching.
pub const PREFETCH_PER_WORKER: usize = 16;

const FLAG_NONE: u8 = 0;
const FLAG_CANCEL: u8 = 1;
const FLAG_SHUTDOWN: u8 = 2;

enum Event {
    Finished { id: Uuid, kind: String, finish: Finish, status: JobStatus, wall: f64 },
    Progress { id: Uuid, fraction: f64, stage: String },
}

struct Inner {
    store: Store,
    config: QueueConfig,
    metrics: Arc<Metrics>,
    pool: rayon::ThreadPool,
    wake: Notify,
    idle: Notify,
    claiming: AtomicBool,
    active: AtomicUsize,
    /// Moving average of solve wall time, µs (starts pessimistic: no prefetch until measured).
    mean_solve_us: AtomicU64,
    backlog: AtomicI64,
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
        let inner = Arc::new(Inner {
            store,
            config,
            metrics,
            pool,
            wake: Notify::new(),
            idle: Notify::new(),
            claiming: AtomicBool::new(true),
            active: AtomicUsize::new(0),
            mean_solve_us: AtomicU64::new(1_000_000),
            backlog: AtomicI64::new(backlog),
            running: Mutex::new(HashMap::new()),
            waiters: Mutex::new(HashMap::new()),
            events: tx,
        });
        inner.metrics.queue_depth.set(backlog);
        let queue = Queue { inner };
        tokio::spawn(queue.clone().writer(rx));
        tokio::spawn(queue.clone().dispatcher());
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
    pub async fn submit(&self, kind: &str, spec: &Value, label: Option<String>, fresh: bool) -> Result<Submitted, Problem> {
        let Some(k) = registry::find(kind) else {
            return Err(Problem::new(
                ErrorCode::UnknownKind,
                format!("no job kind named '{kind}'; known kinds: {}", registry::names().join(", ")),
            )
            .with_errors(vec![crate::problem::FieldError::new("/kind", "unknown kind")]));
        };
        let prepared = k.prepare(spec, &self.inner.config.limits).map_err(|p| p.under("/spec"))?;
        let spec_text = serde_json::to_string(&prepared.canonical).unwrap_or_default();
        let hash = spec_hash(k.name(), &spec_text);
        if !fresh {
            if let Some(row) = self.inner.store.find_reusable(&hash, k.solver_version()).await.map_err(storage_problem)? {
                self.inner.metrics.reused.get_or_create(&KindLabel { kind: k.name().into() }).inc();
                return Ok(Submitted::Reused(row));
            }
        }
        if self.backlog() >= self.inner.config.max_backlog as i64 {
            return Err(Problem::new(
                ErrorCode::QueueFull,
                format!("{} jobs are waiting; retry later", self.backlog()),
            ));
        }
        if !self.inner.claiming.load(Ordering::Relaxed) {
            return Err(Problem::new(ErrorCode::ShuttingDown, "the service is shutting down"));
        }
        let job = NewJob {
            id: Uuid::now_v7(),
            kind: k.name().to_string(),
            label,
            spec: spec_text,
            spec_hash: hash,
            solver_version: k.solver_version().to_string(),
            created_at: now_ms(),
        };
        let row = self.inner.store.insert(&job).await.map_err(storage_problem)?;
        let depth = self.inner.backlog.fetch_add(1, Ordering::Relaxed) + 1;
        self.inner.metrics.queue_depth.set(depth);
        self.inner.metrics.submitted.get_or_create(&KindLabel { kind: job.kind.clone() }).inc();
        self.inner.wake.notify_one();
        Ok(Submitted::Accepted(row))
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
            Some(r) if !r.status.is_finished() => {
                let _ = tokio::time::timeout(timeout, rx).await;
                self.inner.store.get(id).await.map_err(storage_problem)
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
                    // The flag may not exist yet (claimed, not yet spawned): create it set, and
                    // `spawn` adopts it.
                    self.inner
                        .running
                        .lock()
                        .unwrap_or_else(|e| e.into_inner())
                        .entry(id)
                        .or_insert_with(|| Arc::new(AtomicU8::new(FLAG_NONE)))
                        .store(FLAG_CANCEL, Ordering::Relaxed);
                    store.request_cancel(id).await.map_err(storage_problem)?;
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
        self.inner.claiming.store(false, Ordering::Relaxed);
        self.inner.wake.notify_one();
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
            if !inner.claiming.load(Ordering::Relaxed) {
                return;
            }
            let fast = inner.mean_solve_us.load(Ordering::Relaxed) < PREFETCH_BELOW.as_micros() as u64;
            let target = inner.config.workers * if fast { 1 + PREFETCH_PER_WORKER } else { 1 };
            let free = target.saturating_sub(inner.active.load(Ordering::Relaxed));
            let mut claimed_all = false;
            if free > 0 {
                match inner.store.claim(free, now_ms()).await {
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
            let (outcome, wall) = match (observer.check(), prepare(&job.kind, &job.spec, &limits)) {
                (Err(interrupt), _) => (Outcome::Interrupted(interrupt), 0.0),
                (Ok(()), Ok(prepared)) => runner::run(prepared, &observer),
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
            let _ = events.send(Event::Finished { id: job.id, kind: job.kind.clone(), finish, status, wall });
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
                    Event::Finished { id, kind, finish, status, wall } => {
                        progress.remove(&id);
                        finishes.push(finish);
                        done.push((id, kind, status, wall));
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
            while let Err(e) = inner.store.finish_batch(&finishes, now_ms()).await {
                warn!(error = %e, "writing finished jobs failed; retrying");
                tokio::time::sleep(delay).await;
                delay = (delay * 2).min(Duration::from_secs(5));
            }
            for (id, kind, status, wall) in done {
                inner.running.lock().unwrap_or_else(|e| e.into_inner()).remove(&id);
                if status == JobStatus::Queued {
                    let depth = inner.backlog.fetch_add(1, Ordering::Relaxed) + 1;
                    inner.metrics.queue_depth.set(depth);
                } else {
                    inner.metrics.finished.get_or_create(&KindStatusLabel { kind: kind.clone(), status: status.as_str().into() }).inc();
                    if status == JobStatus::Succeeded {
                        inner.metrics.solve_seconds.get_or_create(&KindLabel { kind }).observe(wall);
                    }
                    let us = (wall * 1e6) as u64;
                    let mean = inner.mean_solve_us.load(Ordering::Relaxed);
                    inner.mean_solve_us.store((mean * 4 + us) / 5, Ordering::Relaxed);
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
