use super::*;

impl Queue {
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
    pub(super) async fn leases(self, expired_error: String) {
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
    pub(super) async fn forward(self, mut events: tokio::sync::broadcast::Receiver<crate::store::StoreEvent>) {
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

    pub(super) async fn wait_idle(&self, timeout: Duration) -> bool {
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

    pub(super) fn notify_waiters(&self, id: Uuid) {
        let senders = self.inner.waiters.lock().unwrap_or_else(|e| e.into_inner()).remove(&id);
        for s in senders.into_iter().flatten() {
            let _ = s.send(());
        }
    }

    pub(super) async fn dispatcher(self) {
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

    pub(super) fn spawn(&self, job: crate::store::ClaimedJob) {
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

    pub(super) async fn writer(self, mut rx: mpsc::UnboundedReceiver<Event>) {
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

pub(super) fn prepare(kind: &str, spec: &str, limits: &Limits) -> Result<super::super::kind::Prepared, Problem> {
    let k = registry::find(kind).ok_or_else(|| {
        Problem::new(ErrorCode::UnknownKind, format!("this server no longer knows the kind '{kind}'"))
    })?;
    let value: Value = serde_json::from_str(spec)
        .map_err(|e| Problem::new(ErrorCode::InternalError, format!("stored spec is not JSON: {e}")))?;
    k.prepare(&value, limits).map_err(|p| p.under("/spec"))
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
