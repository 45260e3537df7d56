//! Fan-out (issue 44): a big sweep's cases become jobs of their own that every instance sharing
//! the store claims, leases and (after a kill -9) re-runs like any other job; the sweep waits for
//! them without a worker thread and is assembled, by whichever instance claims it once its last
//! case finished, into the result an in-process run gives (plus, per case, the instance that
//! solved it and whether it was reused). The children's table and its queries: `store::children`.
//!
//! * **Which kinds.** `sweep` (any case kind, so also a sweep of `bearing_optimisation` runs or of
//!   wear studies). An optimisation's array runs stay in-process: they start from their
//!   neighbours' solutions and share workspaces, so as separate cases their numbers would change.
//! * **When.** On both stores (PostgreSQL: every instance sharing it claims the cases; SQLite:
//!   the one instance's workers do, and gain the cache, the rows' `instance`/`reused`, progress
//!   by case and a restart that re-runs only unfinished cases), when the work model's mean case
//!   cost is at least [`QueueConfig::fan_out_min_case_seconds`]; below it the per-case cost of
//!   the fan-out (an insert, a claim, a finish, a result read: 4–9 ms wall, ≈ 2 ms CPU) is not
//!   worth the rows it writes.
//! * **The case cache.** A case whose canonical spec and solver version match a succeeded job (of
//!   any sweep, or a job submitted alone) reuses it; one queued or running is joined. A sweep
//!   submitted with `?fresh=true` reuses nothing (it still joins cases being solved right now).
//! * **Joins and cancels.** A case (or a sweep) whose cancel was requested is never joined: the
//!   newcomer waits for it to stop and solves it anew. A case joined just before its other
//!   parent's cancel reached it (the join is recorded after the cancel looked for live parents)
//!   is found canceled when this parent is assembled, and solved again for it.
//! * **Memory.** The assembly reads the cases' results [`RESULTS_AT_ONCE`] at a time and keeps of
//!   each only the values the table shows: its memory is one page of results plus the table.
//! * **Fairness.** The cases inherit the sweep's virtual deadline: they keep the sweep's place in
//!   the fair order, so a tiny job submitted meanwhile is claimed before the remaining cases.

use super::*;
use crate::jobs::kinds::sweep::{self, SweepSpec};
use crate::store::{Child, ChildOutcome, ClaimedJob};
use serde_json::json;

/// What becomes of a claimed sweep.
enum Plan {
    /// Small cases (or a store of one instance): solve in-process, as before.
    InProcess,
    /// Its children are recorded and it waits for them.
    Waiting,
    /// Its children have all finished: assemble.
    Assemble(Assembly),
}

/// What the assembly of a fanned-out sweep needs, read from the store a page at a time: each
/// case's record and the values of the quantities its result holds (or its problem).
pub(super) struct Assembly {
    children: Vec<ChildOutcome>,
    quantities: Vec<String>,
    names: Vec<String>,
    values: Vec<Result<Vec<Option<Value>>, Problem>>,
}

/// One case to become a job.
struct Case {
    index: i64,
    kind: &'static dyn crate::jobs::kind::DynKind,
    spec: String,
    hash: String,
    estimate: Estimate,
}

/// Cases inserted (or looked up) at once.
const CREATE_AT_ONCE: usize = 64;

/// Case results an assembly holds in memory at once.
pub const RESULTS_AT_ONCE: i64 = 16;

/// Longest wait for a case (or sweep) being canceled to stop before it is solved anew.
pub(super) const CANCEL_WAIT: Duration = Duration::from_secs(60);

/// Test builds only (feature `test-kinds`): a pause, ms from environment variable `var`, at a
/// point where a test kills an instance (kill -9) or cancels a job. Zero otherwise.
pub(super) fn test_pause(var: &str) -> Duration {
    #[cfg(feature = "test-kinds")]
    if let Some(ms) = std::env::var(var).ok().and_then(|v| v.parse::<u64>().ok()) {
        return Duration::from_millis(ms);
    }
    let _ = var;
    Duration::ZERO
}

impl Queue {
    /// Whether a claimed job may fan out (the work model decides later, in [`Queue::fan_out`]).
    pub(super) fn fans_out(&self, job: &ClaimedJob) -> bool {
        job.kind == <crate::jobs::kinds::sweep::Sweep as crate::jobs::kind::Kind>::NAME
            && self.inner.config.fan_out_min_case_seconds.is_some()
    }

    /// Fan a claimed sweep out, assemble it, or run it in-process.
    pub(super) async fn fan_out(self, job: ClaimedJob, flag: Arc<AtomicU8>) {
        match self.plan(&job).await {
            Ok(Plan::InProcess) => self.run(job, flag, Work::Solve),
            Ok(Plan::Assemble(assembly)) => self.run(job, flag, Work::Assemble(assembly)),
            Ok(Plan::Waiting) => {
                info!(id = %job.id, "sweep fanned out: waiting for its cases");
                self.let_go(&job);
            }
            Err(e) => {
                // The children recorded so far finish on their own; this attempt solves the
                // sweep in-process, and a later one (after a lost lease) assembles or waits.
                warn!(id = %job.id, error = %e, "fanning out failed: solving in-process");
                self.run(job, flag, Work::Solve);
            }
        }
    }

    async fn plan(&self, job: &ClaimedJob) -> Result<Plan, StoreError> {
        let store = &self.inner.store;
        let existing = store.child_outcomes(job.id).await?;
        if !existing.is_empty() {
            if existing.iter().all(|c| c.status.is_none_or(JobStatus::is_finished)) {
                if self.resolve_again(job, &existing).await? {
                    return Ok(Plan::Waiting);
                }
                return Ok(Plan::Assemble(self.assembly(job, existing).await?));
            }
            store.wait_for_children(job.id, &self.inner.instance).await?;
            return Ok(Plan::Waiting);
        }
        let threshold = self.inner.config.fan_out_min_case_seconds.unwrap_or(f64::INFINITY);
        let text = job.spec.clone();
        let cases = tokio::task::spawn_blocking(move || cases(&text, threshold)).await.ok().flatten();
        let Some(cases) = cases else { return Ok(Plan::InProcess) };
        let fresh = store.is_fresh(job.id).await?;
        let due_at = store.due_at(job.id).await?.unwrap_or_else(now_ms);
        let mut children = Vec::with_capacity(cases.len());
        for chunk in cases.chunks(CREATE_AT_ONCE) {
            let made = futures_util::future::join_all(chunk.iter().map(|c| self.child(job.id, c, fresh, due_at))).await;
            for child in made {
                children.push(child?);
            }
        }
        tokio::time::sleep(test_pause("TRIBOD_TEST_PAUSE_BEFORE_RECORDING_CASES_MS")).await;
        store.add_children(job.id, &children).await?;
        store.wait_for_children(job.id, &self.inner.instance).await?;
        self.inner.wake.notify_one();
        Ok(Plan::Waiting)
    }

    /// Cases this parent joined that were canceled for another parent (whose cancel looked for
    /// live parents before this one's join was recorded), while this parent is not being
    /// canceled: solved again for this parent. Whether any was (the parent then waits again).
    async fn resolve_again(&self, job: &ClaimedJob, children: &[ChildOutcome]) -> Result<bool, StoreError> {
        let store = &self.inner.store;
        let stale: Vec<i64> =
            children.iter().filter(|c| c.status == Some(JobStatus::Canceled) && !c.owned).map(|c| c.index).collect();
        if stale.is_empty() || store.get(job.id).await?.is_none_or(|r| r.cancel_requested) {
            return Ok(false);
        }
        let text = job.spec.clone();
        let Some(cases) = tokio::task::spawn_blocking(move || cases(&text, f64::NEG_INFINITY)).await.ok().flatten() else {
            return Ok(false);
        };
        let fresh = store.is_fresh(job.id).await?;
        let due_at = store.due_at(job.id).await?.unwrap_or_else(now_ms);
        for index in stale {
            let Some(case) = cases.get(index as usize) else { continue };
            let child = self.child(job.id, case, fresh, due_at).await?;
            store.replace_child(job.id, &child).await?;
        }
        info!(id = %job.id, "cases canceled for another sweep are solved again for this one");
        store.wait_for_children(job.id, &self.inner.instance).await?;
        self.inner.wake.notify_one();
        Ok(true)
    }

    /// Read the finished cases' results a page at a time ([`RESULTS_AT_ONCE`]), keeping of each
    /// only the values of the sweep's quantities.
    async fn assembly(&self, job: &ClaimedJob, children: Vec<ChildOutcome>) -> Result<Assembly, StoreError> {
        let store = &self.inner.store;
        let spec: Option<SweepSpec> = serde_json::from_str(&job.spec).ok();
        let Some(spec) = spec else {
            return Ok(Assembly { children, quantities: Vec::new(), names: Vec::new(), values: Vec::new() });
        };
        // The first case whose result reads (the quantities' names may come from it).
        let mut first = None;
        let mut from = 0;
        while first.is_none() {
            let Some((idx, text)) = store.child_results(job.id, from, 1).await?.pop() else { break };
            first = serde_json::from_str::<Value>(&text).ok();
            from = idx + 1;
        }
        let (quantities, names) = sweep::quantities(&spec, first.as_ref());
        drop(first);
        let mut found: HashMap<i64, Vec<Option<Value>>> = HashMap::with_capacity(children.len());
        let mut from = 0;
        loop {
            let page = store.child_results(job.id, from, RESULTS_AT_ONCE).await?;
            let Some(last) = page.last().map(|p| p.0) else { break };
            let q = quantities.clone();
            let extracted = tokio::task::spawn_blocking(move || {
                page.into_iter()
                    .filter_map(|(idx, text)| serde_json::from_str::<Value>(&text).ok().map(|v| (idx, sweep::extract(&v, &q))))
                    .collect::<Vec<_>>()
            })
            .await
            .map_err(|e| StoreError::Corrupt(format!("reading case results: {e}")))?;
            found.extend(extracted);
            from = last + 1;
        }
        let values = children
            .iter()
            .map(|c| match c.status {
                Some(JobStatus::Succeeded) => found.remove(&c.index).ok_or_else(|| case_problem(c, ErrorCode::ResultUnavailable, "its result is missing")),
                _ => Err(case_outcome(c)),
            })
            .collect();
        Ok(Assembly { children, quantities, names, values })
    }

    /// The job of one case: an identical succeeded one (reused, unless `fresh`), an identical
    /// queued or running one (joined), or a new one.
    async fn child(&self, parent: Uuid, case: &Case, fresh: bool, due_at: i64) -> Result<Child, StoreError> {
        let store = &self.inner.store;
        let version = case.kind.solver_version();
        let label = format!("case {} of {parent}", case.index + 1);
        for _ in 0..3 {
            if let Some(row) = store.find_same(&case.hash, version, !fresh).await? {
                if row.cancel_requested && !row.status.is_finished() {
                    // Being canceled (for another parent): not joined; solved anew once it stopped.
                    self.stopped(row.id).await?;
                    continue;
                }
                let reused = row.status == JobStatus::Succeeded;
                // A case job an earlier attempt at this parent created (its instance died before
                // recording the children) is this parent's own: a cancel reaches it.
                let owned = !reused && row.label.as_deref() == Some(label.as_str());
                return Ok(Child { index: case.index, job_id: row.id, reused, owned });
            }
            let new = NewJob {
                id: Uuid::now_v7(),
                kind: case.kind.name().to_string(),
                label: Some(label.clone()),
                spec: case.spec.clone(),
                spec_hash: case.hash.clone(),
                solver_version: version.to_string(),
                created_at: now_ms(),
                idempotency_key: None,
                key_label: None,
                due_at,
                estimate_cpu_seconds: case.estimate.cpu_seconds,
                estimate_memory_bytes: case.estimate.memory_bytes,
            };
            match store.insert(&new).await {
                Ok(row) => {
                    self.inner.uncounted.lock().unwrap_or_else(|e| e.into_inner()).insert(row.id);
                    return Ok(Child { index: case.index, job_id: row.id, reused: false, owned: true });
                }
                // Queued meanwhile (another sweep's identical case, or a duplicate value): join it.
                Err(StoreError::InFlight) => continue,
                Err(e) => return Err(e),
            }
        }
        Err(StoreError::Corrupt(format!("case {} of {parent}: its identical job kept changing state", case.index + 1)))
    }

    /// Wait until job `id` is finished (or gone), at most [`CANCEL_WAIT`].
    pub(super) async fn stopped(&self, id: Uuid) -> Result<(), StoreError> {
        let deadline = Instant::now() + CANCEL_WAIT;
        while self.inner.store.get(id).await?.is_some_and(|r| !r.status.is_finished()) {
            if Instant::now() > deadline {
                return Err(StoreError::Corrupt(format!("job {id} was asked to cancel {CANCEL_WAIT:?} ago and still runs")));
            }
            tokio::time::sleep(Duration::from_millis(50)).await;
        }
        Ok(())
    }

    /// A parent that waits for its children gives its worker slot back.
    fn let_go(&self, job: &ClaimedJob) {
        let (inner, id) = (&self.inner, job.id);
        if job.short {
            inner.active_short.fetch_sub(1, Ordering::Relaxed);
        }
        inner.running.lock().unwrap_or_else(|e| e.into_inner()).remove(&id);
        inner.uncounted.lock().unwrap_or_else(|e| e.into_inner()).insert(id);
        let active = inner.active.fetch_sub(1, Ordering::Relaxed) - 1;
        inner.metrics.running.set(active as i64);
        inner.wake.notify_one();
        inner.idle.notify_waiters();
    }
}

/// The cases of a stored sweep spec as jobs, if it fans out: every case valid and the mean case
/// estimated at `threshold` CPU seconds or more.
fn cases(text: &str, threshold: f64) -> Option<Vec<Case>> {
    let spec: SweepSpec = serde_json::from_str(text).ok()?;
    let kind = crate::jobs::kinds::case_kind(&spec.kind)?;
    let specs = sweep::case_specs(&spec).ok()?;
    if specs.len() < 2 {
        return None;
    }
    let mut out = Vec::with_capacity(specs.len());
    let mut seconds = 0.0;
    for (i, s) in specs.iter().enumerate() {
        // The server's limits were enforced on every case at submission.
        let prepared = kind.prepare(s, &Limits::UNLIMITED).ok()?;
        let text = serde_json::to_string(&prepared.canonical).ok()?;
        seconds += prepared.cost.cpu_seconds();
        out.push(Case { index: i as i64, kind, hash: spec_hash(kind.name(), &text), spec: text, estimate: prepared.cost.estimate });
    }
    (seconds / out.len() as f64 >= threshold).then_some(out)
}

/// A fanned-out sweep's result from its children: the table an in-process run gives, with each
/// row's `instance` (the instance that solved the case) and `reused`.
pub(super) fn assemble(prepared: crate::jobs::kind::Prepared, assembly: &Assembly) -> (Outcome, f64) {
    std::thread::sleep(test_pause("TRIBOD_TEST_PAUSE_IN_ASSEMBLY_MS"));
    let start = Instant::now();
    let children = &assembly.children;
    let failed = |detail: String| (Outcome::Failed(Problem::new(ErrorCode::InternalError, detail)), 0.0);
    let spec: SweepSpec = match serde_json::from_value(prepared.canonical.clone()) {
        Ok(s) => s,
        Err(e) => return failed(format!("stored sweep spec: {e}")),
    };
    let Some(kind) = crate::jobs::kinds::case_kind(&spec.kind) else {
        return failed(format!("this server no longer knows the kind '{}'", spec.kind));
    };
    let all = sweep::cases(&spec);
    if all.len() != children.len() || all.len() != assembly.values.len() {
        return failed(format!("{} cases but {} case jobs", all.len(), children.len()));
    }
    let mut result = sweep::table(&spec, kind, &all, &assembly.quantities, &assembly.names, &assembly.values);
    for (row, child) in result.cases.iter_mut().zip(children) {
        row.insert("instance".into(), json!(child.solved_by));
        row.insert("reused".into(), json!(child.reused));
    }
    result.columns.extend(["instance".to_string(), "reused".to_string()]);
    let mut value = match serde_json::to_value(&result) {
        Ok(v) => v,
        Err(e) => return failed(format!("sweep result: {e}")),
    };
    let wall = start.elapsed().as_secs_f64();
    let instances: std::collections::BTreeSet<&str> = children.iter().filter(|c| !c.reused).filter_map(|c| c.solved_by.as_deref()).collect();
    if let Value::Object(map) = &mut value {
        map.insert(
            "meta".into(),
            json!({
                "kind": prepared.kind.name(),
                "solver_version": prepared.kind.solver_version(),
                "wall_time_seconds": wall,
                "estimate": prepared.cost.estimate,
                "fan_out": {
                    "cases": children.len(),
                    "reused": children.iter().filter(|c| c.reused).count(),
                    "instances": instances.len(),
                },
            }),
        );
    }
    (Outcome::Succeeded(value), wall)
}

fn case_problem(child: &ChildOutcome, code: ErrorCode, detail: &str) -> Problem {
    Problem::new(code, format!("case job {}: {detail}", child.job_id))
}

/// The problem of a case that did not succeed, as the in-process sweep has it.
fn case_outcome(child: &ChildOutcome) -> Problem {
    let problem = |code: ErrorCode, detail: &str| case_problem(child, code, detail);
    match child.status {
        Some(JobStatus::Failed) => child
            .error
            .as_deref()
            .and_then(|t| serde_json::from_str::<Problem>(t).ok())
            .unwrap_or_else(|| problem(ErrorCode::InternalError, "failed without a problem")),
        Some(JobStatus::Canceled) => problem(ErrorCode::Interrupted, "it was canceled"),
        None => problem(ErrorCode::ResultUnavailable, "it was deleted"),
        Some(s) => problem(ErrorCode::InternalError, &format!("it is still {}", s.as_str())),
    }
}
