//! Leases of running jobs (renewal, cancels and lost leases through other instances, expired
//! leases re-queued) and other instances' events.

use super::*;

/// Entries of the queue's set of uncounted jobs (fan-out cases) above which it is re-read from
/// the store (it keeps the ids of cases canceled while queued until then).
const UNCOUNTED_BOUND: usize = 50_000;

impl Queue {
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
                // Fan-out's safety net: parents whose last case finished on an instance that died
                // (or failed at the attempt cap here) before it moved them on.
                match inner.store.release_parents(None, None).await {
                    Ok(0) => {}
                    Ok(_) => inner.wake.notify_one(),
                    Err(e) => warn!(error = %e, "scanning for parents whose cases finished failed"),
                }
                // Cases canceled while queued never finish here: past a bound, re-read the set.
                if inner.uncounted.lock().unwrap_or_else(|e| e.into_inner()).len() > UNCOUNTED_BOUND {
                    match inner.store.uncounted_jobs().await {
                        Ok(ids) => *inner.uncounted.lock().unwrap_or_else(|e| e.into_inner()) = ids.into_iter().collect(),
                        Err(e) => warn!(error = %e, "re-reading the fan-out's cases failed"),
                    }
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
}
