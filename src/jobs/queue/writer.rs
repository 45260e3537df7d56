//! The writer: commit workers' progress and outcomes in batches, keep the counters and the
//! fair-scheduling ratios, then wake waiters and the dispatcher.

use super::*;
use crate::store::ClaimNext;

impl Queue {
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
                    Event::Finished { id, kind, finish, status, wall, modelled, short } => {
                        progress.remove(&id);
                        finishes.push(finish);
                        done.push((id, kind, status, wall, modelled, short));
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
            // The slots this batch frees are refilled in its commit (the dispatcher never sees
            // them free: `active` still counts the finished jobs until the claimed ones started).
            // Not on a retry: a failed attempt may have committed its claim, which then comes
            // back to the queue when its lease expires (as any lost claim).
            let freed = |short: bool| done.iter().filter(|d| d.2 != JobStatus::Queued && d.5 == short).count();
            let refill = if inner.claiming.load(Ordering::Relaxed) { (freed(false), freed(true)) } else { (0, 0) };
            // A finished job must not be lost: retry until the database takes it.
            let mut delay = Duration::from_millis(50);
            let mut retried = false;
            let finished = loop {
                let now = now_ms();
                let (n, short) = if retried { (0, 0) } else { refill };
                let next = ClaimNext { n, short, lease_until: now + inner.config.lease.as_millis() as i64 };
                match inner.store.finish_batch(&finishes, now, &inner.instance, next).await {
                    Ok(finished) => break finished,
                    Err(e) => warn!(error = %e, "writing finished jobs failed; retrying"),
                }
                retried = true;
                tokio::time::sleep(delay).await;
                delay = (delay * 2).min(Duration::from_secs(5));
            };
            let cases = finished.cases;
            self.take_claimed(finished.claimed, if retried { 0 } else { refill.1 });
            // Fan-out: the parents of finished cases move on (the last case re-queues its parent).
            // Beside the next claim, not before it. Skipped when no finished job is a case
            // (PostgreSQL: told by the finish; SQLite: none while the file holds no case at all; a
            // retried batch may have been committed by the failed attempt: not skipped then).
            if cases || retried {
                let finished: Vec<Uuid> = done.iter().filter(|d| d.2 != JobStatus::Queued).map(|d| d.0).collect();
                let queue = self.clone();
                tokio::spawn(async move {
                    match queue.inner.store.release_parents(None, Some(&finished)).await {
                        // SQLite has no notification: wake this instance's dispatcher.
                        Ok(n) if n > 0 => queue.inner.wake.notify_one(),
                        Ok(_) => {}
                        Err(e) => warn!(error = %e, "moving the parents of finished cases failed (the expiry scan retries)"),
                    }
                });
            }
            for (id, kind, status, wall, modelled, short) in done {
                inner.running.lock().unwrap_or_else(|e| e.into_inner()).remove(&id);
                let uncounted = {
                    let mut set = inner.uncounted.lock().unwrap_or_else(|e| e.into_inner());
                    if status == JobStatus::Queued { set.contains(&id) } else { set.remove(&id) }
                };
                if status == JobStatus::Queued && uncounted {
                    // A case (or a parent) back in the queue: not a new admission.
                } else if status == JobStatus::Queued {
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
                if short {
                    inner.active_short.fetch_sub(1, Ordering::Relaxed);
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
