use super::*;

impl Queue {
    /// Recover interrupted jobs, then start the dispatcher and the writer on the current tokio
    /// runtime.
    pub async fn start(store: Store, config: QueueConfig, metrics: Arc<Metrics>) -> Result<Queue, StoreError> {
        // The solvers' process-wide tables (Greenwood–Tripp integrals, ≈ 0.12 s), built now so
        // that the first job does not pay for them (the work models leave them out).
        tokio::task::spawn_blocking(super::super::warm_up);
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
    /// `idempotency_key_reused` (see [`super::super::idempotency`]).
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
    pub(super) async fn earlier(&self, keyed: &Option<Keyed>) -> Result<Option<Submitted>, Problem> {
        let Some(request) = keyed else { return Ok(None) };
        Ok(idempotency::look_up(&self.inner.store, request).await.map_err(storage_problem)?.into_replay()?.map(Submitted::Replayed))
    }

    /// The answer for an identical existing job (reused if it succeeded, else joined), once the
    /// request's key is recorded for it; or the key's earlier answer; `None`: the job was deleted.
    pub(super) async fn existing(&self, row: JobRow, keyed: &Option<Keyed>) -> Result<Option<Submitted>, Problem> {
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
    pub(super) async fn validate(&self, k: &'static dyn super::super::kind::DynKind, spec: &Value) -> Result<(Value, Estimate), Problem> {
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
    pub(super) fn estimate(&self, kind: &str, modelled: f64) -> f64 {
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

}
