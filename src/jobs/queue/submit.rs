//! Admission: validate (on blocking threads, bounded), answer repeats (idempotency keys,
//! identical jobs reused or joined), reserve a backlog place, persist and signal; the fair
//! scheduling estimate that sets a new job's virtual deadline.

use super::*;

impl Queue {
    /// Validate, dedup, persist and signal. Problems carry field paths under `/spec`.
    ///
    /// With an `idempotency_key`, a repeated request (same kind, spec and label) answers the job
    /// that answered the first one, whether it was created, reused or joined
    /// ([`Submitted::Replayed`]); another request under the same key is refused with
    /// `idempotency_key_reused` (see [`crate::jobs::idempotency`]).
    pub async fn submit(
        &self,
        kind: &str,
        spec: &Value,
        label: Option<String>,
        fresh: bool,
        strict: bool,
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
        let (prepared, estimate, warnings) = self.validate(k, spec).await?;
        if strict && !warnings.is_empty() {
            let n = warnings.len();
            return Err(Problem::new(ErrorCode::InvalidSpec, format!("{n} field(s) look implausible (strict: warnings refuse the spec)"))
                .with_errors(warnings)
                .under("/spec"));
        }
        let spec_text = serde_json::to_string(&prepared).unwrap_or_default();
        let hash = spec_hash(k.name(), &spec_text);
        let keyed = idempotency_key.clone().map(|key| Keyed { key, spec_hash: hash.clone(), label: label.clone() });
        if let Some(answer) = self.earlier(&keyed).await? {
            return Ok(answer);
        }
        if let Some(row) = self.same(&hash, k.solver_version(), !fresh).await? {
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
            // A job without a label gets one that tells it apart (`jobs::label`).
            label: label.clone().or_else(|| Some(crate::jobs::label::auto_label(k, &prepared, &hash))),
            spec: spec_text,
            spec_hash: hash.clone(),
            solver_version: k.solver_version().to_string(),
            created_at,
            idempotency_key: idempotency_key.clone(),
            key_label: label.clone(),
            due_at: created_at + (AGING * self.estimate(k.name(), estimate.cpu_seconds) * 1e3).min(MAX_DUE_MS) as i64,
            estimate_cpu_seconds: estimate.cpu_seconds,
            estimate_memory_bytes: estimate.memory_bytes,
        };
        // A fanned-out job passes `fresh` on to its cases (`jobs::queue::fanout`): recorded
        // before the insert, so that no instance claims the job before it is there.
        if fresh && job.kind == "sweep" {
            if let Err(e) = self.inner.store.set_fresh(job.id).await {
                self.inner.backlog.fetch_sub(1, Ordering::Relaxed);
                return Err(storage_problem(e));
            }
        }
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
                    match self.same(&hash, k.solver_version(), false).await? {
                        Some(row) => {
                            if let Some(answer) = self.existing(row, &keyed).await? {
                                return Ok(answer);
                            }
                        }
                        // The identical job was being canceled and has stopped: submit anew.
                        None => return Box::pin(self.submit(kind, spec, label, fresh, strict, idempotency_key)).await,
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

    /// The identical job this submission reuses (succeeded, when `reusable`) or joins (queued or
    /// running). Never one whose cancel was requested (issue 44: a sweep joining a sweep being
    /// canceled would be canceled with it): that one is waited for until it stops, and the look
    /// repeated.
    async fn same(&self, hash: &str, version: &str, reusable: bool) -> Result<Option<JobRow>, Problem> {
        let store = &self.inner.store;
        for _ in 0..3 {
            let row = store.find_same(hash, version, reusable).await.map_err(storage_problem)?;
            match row {
                Some(r) if r.cancel_requested && !r.status.is_finished() => self.stopped(r.id).await.map_err(storage_problem)?,
                other => return Ok(other),
            }
        }
        Err(Problem::new(ErrorCode::StorageUnavailable, "identical jobs kept being canceled; try again"))
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
    async fn validate(&self, k: &'static dyn crate::jobs::kind::DynKind, spec: &Value) -> Result<(Value, Estimate, Vec<crate::problem::FieldError>), Problem> {
        let _permit = self
            .inner
            .validating
            .acquire()
            .await
            .map_err(|_| Problem::new(ErrorCode::ShuttingDown, "the service is shutting down"))?;
        let spec = spec.clone();
        let limits = self.inner.config.limits;
        tokio::task::spawn_blocking(move || k.prepare(&spec, &limits).map(|p| (p.canonical, p.cost.estimate, p.warnings)))
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
}
