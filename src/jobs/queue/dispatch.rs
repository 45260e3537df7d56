//! The dispatcher: claim queued jobs for free worker slots and run each on the rayon pool with
//! an observer that carries progress, cancel, shutdown and the deadline.

use super::*;
use crate::store::ClaimNext;

impl Queue {
    pub(super) async fn dispatcher(self) {
        let inner = &self.inner;
        loop {
            let notified = inner.wake.notified();
            inner.claim_loop_at.store(now_ms(), Ordering::Relaxed);
            if !inner.claiming.load(Ordering::Relaxed) {
                return;
            }
            let now = now_ms();
            let free = self.free_slots(now);
            let mut claimed_all = false;
            if !free.is_empty() {
                match inner.store.claim(free, now, &inner.instance).await {
                    Ok(jobs) => {
                        claimed_all = jobs.len() == free.n + free.short;
                        self.take_claimed(jobs, free.short);
                    }
                    Err(e) => warn!(error = %e, "claiming jobs failed; retrying"),
                }
            }
            if claimed_all && !self.free_slots(now).is_empty() {
                continue;
            }
            // Woken by a submission or a finished job; the timeout is a safety net only.
            let _ = tokio::time::timeout(Duration::from_secs(2), notified).await;
        }
    }

    /// The slots free now: ordinary ones (`n`) and short-job ones (`short`), as a claim.
    fn free_slots(&self, now: i64) -> ClaimNext {
        let inner = &self.inner;
        let (active, short) = (inner.active.load(Ordering::Relaxed), inner.active_short.load(Ordering::Relaxed));
        ClaimNext {
            n: inner.config.workers.max(1).saturating_sub(active.saturating_sub(short)),
            short: inner.config.short_slots.saturating_sub(short),
            lease_until: now + inner.config.lease.as_millis() as i64,
        }
    }

    /// Count claimed jobs out of the backlog and start them, each in a slot: a short job in one
    /// of the `short` short-job slots claimed for (while they last), any other in an ordinary
    /// one (the claim took at most as many of those as it had ordinary slots).
    pub(super) fn take_claimed(&self, jobs: Vec<crate::store::ClaimedJob>, short: usize) {
        let inner = &self.inner;
        // Cases of a fan-out (and parents back to be assembled) were admitted with their sweep:
        // not counted in the backlog.
        let n = {
            let set = inner.uncounted.lock().unwrap_or_else(|e| e.into_inner());
            jobs.iter().filter(|j| !set.contains(&j.id)).count() as i64
        };
        if n > 0 {
            let depth = inner.backlog.fetch_sub(n, Ordering::Relaxed) - n;
            if depth < 0 {
                // Claimed case jobs of a fan-out, which the backlog does not count (their sweep
                // was counted): not a credit for more jobs.
                inner.backlog.fetch_max(0, Ordering::Relaxed);
            }
            inner.metrics.queue_depth.set(depth.max(0));
        }
        let mut short_left = short;
        for mut job in jobs {
            job.short = job.short && short_left > 0;
            short_left -= usize::from(job.short);
            self.spawn(job);
        }
    }

    fn spawn(&self, job: crate::store::ClaimedJob) {
        let inner = &self.inner;
        if job.short {
            inner.active_short.fetch_add(1, Ordering::Relaxed);
        }
        inner.active.fetch_add(1, Ordering::Relaxed);
        inner.metrics.running.set(inner.active.load(Ordering::Relaxed) as i64);
        let flag = inner
            .running
            .lock()
            .unwrap_or_else(|e| e.into_inner())
            .entry(job.id)
            .or_insert_with(|| Arc::new(AtomicU8::new(FLAG_NONE)))
            .clone();
        if self.fans_out(&job) {
            tokio::spawn(self.clone().fan_out(job, flag));
            return;
        }
        self.run(job, flag, Work::Solve);
    }

    /// Run `job` on the pool: solve it, or assemble it from its children's outcomes.
    pub(super) fn run(&self, job: crate::store::ClaimedJob, flag: Arc<AtomicU8>, work: Work) {
        let inner = &self.inner;
        let events = inner.events.clone();
        let limits = inner.config.limits;
        let timeout = inner.config.job_timeout;
        let interval = inner.config.progress_interval;
        let short = job.short;
        let pool = if short { inner.short_pool.as_ref().unwrap_or(&inner.pool) } else { &inner.pool };
        pool.spawn(move || {
            let deadline = timeout.map(|t| Instant::now() + t);
            let span = info_span!("job", id = %job.id, kind = %job.kind, attempt = job.attempts);
            let _entered = span.enter();
            let observer = JobObserver {
                id: job.id,
                flag,
                deadline,
                events: events.clone(),
                interval,
                last: Mutex::new((None, 0.0)),
            };
            // Canceled (or shut down) while it waited in the pool's queue: do not start it.
            let mut modelled = 0.0;
            let (outcome, wall) = match (observer.check(), prepare(&job.kind, &job.spec, &limits)) {
                (Err(interrupt), _) => (Outcome::Interrupted(interrupt), 0.0),
                (Ok(()), Ok(prepared)) => match work {
                    Work::Solve => {
                        modelled = prepared.cost.cpu_seconds();
                        runner::run(prepared, &observer)
                    }
                    Work::Assemble(assembly) => super::fanout::assemble(prepared, &assembly),
                },
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
            let _ = events.send(Event::Finished { id: job.id, kind: job.kind.clone(), finish, status, wall, modelled, short });
        });
    }
}

fn prepare(kind: &str, spec: &str, limits: &Limits) -> Result<crate::jobs::kind::Prepared, Problem> {
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
    /// When progress was last sent, and the largest fraction sent: a job's progress never goes
    /// back (nested stages of a solver may report a smaller fraction than an outer one did).
    last: Mutex<(Option<Instant>, f64)>,
}

impl Observer for JobObserver {
    fn progress(&self, fraction: f64, stage: &str) {
        let now = Instant::now();
        let mut last = self.last.lock().unwrap_or_else(|e| e.into_inner());
        if last.0.is_some_and(|t| now.duration_since(t) < self.interval) {
            return;
        }
        let fraction = if fraction.is_finite() { fraction.clamp(0.0, 1.0) } else { 0.0 };
        let fraction = fraction.max(last.1);
        *last = (Some(now), fraction);
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
