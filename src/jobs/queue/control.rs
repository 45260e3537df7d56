//! Waiting for a job, cancelling it, and shutting the queue down.

use super::*;

impl Queue {
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
                    // A fanned-out job: its cases on every instance, and the job itself if it
                    // waits for them (no worker holds it).
                    store.cancel_children(id, now_ms()).await.map_err(storage_problem)?;
                    let row = store.get(id).await.map_err(storage_problem)?;
                    if row.as_ref().is_some_and(|r| r.status.is_finished()) {
                        self.inner.running.lock().unwrap_or_else(|e| e.into_inner()).remove(&id);
                        self.notify_waiters(id);
                    }
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

    pub(super) fn notify_waiters(&self, id: Uuid) {
        let senders = self.inner.waiters.lock().unwrap_or_else(|e| e.into_inner()).remove(&id);
        for s in senders.into_iter().flatten() {
            let _ = s.send(());
        }
    }
}
