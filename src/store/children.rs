//! Children of a fanned-out job (issue 44): the cases of a big sweep as ordinary jobs of their
//! case kind, tied to the parent by table `job_children` (both backends: on PostgreSQL every
//! instance sharing the database claims the cases; a SQLite file has one instance, whose workers
//! claim them — the case cache, the rows' `instance` and `reused`, the progress by case and a
//! restart that re-runs only unfinished cases are the same). The PostgreSQL statements are here,
//! SQLite's in `sqlite/children.rs`.
//!
//! Life of a parent: claimed like any job; the instance that claimed it creates (or reuses, or
//! joins) one job per case, records them here and lets go of the parent — status stays
//! `running`, the lease becomes [`WAITING_UNTIL`] with no owner, so no worker thread waits and no
//! expiry scan re-queues it. Every finish of a child moves the parent's progress; the finish of
//! the last one puts the parent back in the queue (first in line: `due_at` 0), and whichever
//! instance claims it assembles the result from the children's results.

use super::*;
use sqlx::{AssertSqlSafe, Row};

/// The lease of a parent waiting for its children: far in the future, no owner.
pub const WAITING_UNTIL: i64 = 4_000_000_000_000_000;

/// The stage a waiting parent shows.
pub const WAITING_STAGE: &str = "cases";

/// One case of a parent as recorded.
#[derive(Debug, Clone, PartialEq)]
pub struct Child {
    pub index: i64,
    pub job_id: Uuid,
    /// An identical case had already succeeded (the case cache).
    pub reused: bool,
    /// Created for this parent (not an identical job joined or reused).
    pub owned: bool,
}

/// A case as it stands: its job's status, who solved it and its error (results are read a page
/// at a time: [`Store::child_results`]).
#[derive(Debug, Clone)]
pub struct ChildOutcome {
    pub index: i64,
    pub job_id: Uuid,
    pub reused: bool,
    /// Created for this parent (not joined or reused).
    pub owned: bool,
    /// `None`: the case's job was deleted.
    pub status: Option<JobStatus>,
    pub solved_by: Option<String>,
    /// problem+json of a failed case.
    pub error: Option<String>,
}

/// The children of a job counted by status.
#[derive(Debug, Clone, Copy, Default, PartialEq, Serialize, ToSchema)]
pub struct ChildCounts {
    pub total: i64,
    pub queued: i64,
    pub running: i64,
    pub succeeded: i64,
    /// Failed, canceled, or deleted.
    pub failed: i64,
    /// Of the succeeded: reused from an identical case solved before (the case cache).
    pub reused: i64,
}

impl Store {
    /// Record the children of `parent` (a repeat of an index keeps the first record).
    pub async fn add_children(&self, parent: Uuid, children: &[Child]) -> StoreResult<()> {
        let s = match self {
            Store::Sqlite(s) => return s.add_children(parent, children).await,
            Store::Postgres(s) => s,
        };
        let idx: Vec<i64> = children.iter().map(|c| c.index).collect();
        let ids: Vec<String> = children.iter().map(|c| c.job_id.to_string()).collect();
        let reused: Vec<bool> = children.iter().map(|c| c.reused).collect();
        let owned: Vec<bool> = children.iter().map(|c| c.owned).collect();
        sqlx::query(
            "INSERT INTO job_children (parent_id, idx, job_id, reused, owned) \
             SELECT $1, * FROM UNNEST($2::bigint[], $3::text[], $4::bool[], $5::bool[]) \
             ON CONFLICT (parent_id, idx) DO NOTHING",
        )
        .bind(parent.to_string())
        .bind(idx)
        .bind(ids)
        .bind(reused)
        .bind(owned)
        .execute(&s.pool)
        .await?;
        Ok(())
    }

    /// The parent's `due_at` (its children inherit it: a big job's cases keep the big job's place
    /// in the fair order).
    pub async fn due_at(&self, id: Uuid) -> StoreResult<Option<i64>> {
        let s = match self {
            Store::Sqlite(s) => return s.due_at(id).await,
            Store::Postgres(s) => s,
        };
        Ok(sqlx::query_scalar::<_, i64>("SELECT due_at FROM jobs WHERE id = $1").bind(id.to_string()).fetch_optional(&s.pool).await?)
    }

    /// Let go of a parent `owner` holds: it waits for its children without a lease or a thread.
    /// Then, if its children are all finished already (every case reused), back to the queue.
    pub async fn wait_for_children(&self, parent: Uuid, owner: &str) -> StoreResult<bool> {
        let s = match self {
            Store::Sqlite(s) => return s.wait_for_children(parent, owner).await,
            Store::Postgres(s) => s,
        };
        let r = sqlx::query(
            // Fanning out was not an interrupted attempt: the claim that assembles is counted
            // alone against --max-attempts (an assembler's death is one interruption, not two).
            "UPDATE jobs SET lease_owner = NULL, lease_until = $1, stage = $2, attempts = GREATEST(attempts - 1, 0) \
             WHERE id = $3 AND status = 'running' AND lease_owner = $4",
        )
        .bind(WAITING_UNTIL)
        .bind(WAITING_STAGE)
        .bind(parent.to_string())
        .bind(owner)
        .execute(&s.pool)
        .await?;
        self.release_parents(Some(&[parent]), None).await?;
        Ok(r.rows_affected() == 1)
    }

    /// Progress of the waiting parents of `children` (or of `parents`; or, both `None`, of every
    /// waiting parent: the safety net for a finish whose instance died before this ran); parents
    /// whose children have all finished go back to the queue to be assembled. The number
    /// re-queued.
    pub async fn release_parents(&self, parents: Option<&[Uuid]>, children: Option<&[Uuid]>) -> StoreResult<u64> {
        let s = match self {
            Store::Sqlite(s) => return s.release_parents(parents, children).await,
            Store::Postgres(s) => s,
        };
        let parents: Option<Vec<String>> = parents.map(|p| p.iter().map(Uuid::to_string).collect());
        let children: Option<Vec<String>> = children.map(|p| p.iter().map(Uuid::to_string).collect());
        // Which parents to look at: the parents of finished cases (through `job_children_by_job`),
        // given parents by id, else every waiting parent (the periodic safety net) — only the
        // conditions that apply, so that each plan looks rows up by what it is given (one plan
        // for all three read every running row; issue 46, with migration 0006).
        // Given ids: the status as an expression, so that the rows are looked up by id (see
        // `store::postgres`).
        let status = if parents.is_some() || children.is_some() { "(status || '')" } else { "status" };
        let mut p = format!("SELECT id FROM jobs WHERE {status} = 'running' AND lease_owner IS NULL AND lease_until = $1");
        if parents.is_some() {
            p.push_str(" AND id = ANY($2)");
        }
        if children.is_some() {
            p.push_str(" AND id IN (SELECT parent_id FROM job_children WHERE job_id = ANY($3))");
        }
        let rows = sqlx::query(AssertSqlSafe(format!(
            "WITH p AS ({p}), \
             n AS (SELECT c.parent_id, count(*) AS total, \
                          count(*) FILTER (WHERE j.status IS NULL OR j.status IN ('succeeded', 'failed', 'canceled')) AS done \
                   FROM job_children c LEFT JOIN jobs j ON j.id = c.job_id \
                   WHERE c.parent_id IN (SELECT id FROM p) GROUP BY c.parent_id), \
             up AS (UPDATE jobs SET progress = n.done::float8 / n.total, \
                        status = CASE WHEN n.done = n.total THEN 'queued' ELSE 'running' END, \
                        lease_until = CASE WHEN n.done = n.total THEN NULL ELSE jobs.lease_until END, \
                        due_at = CASE WHEN n.done = n.total THEN 0 ELSE jobs.due_at END, \
                        attempts = CASE WHEN n.done = n.total THEN GREATEST(jobs.attempts - 1, 0) ELSE jobs.attempts END \
                    FROM n WHERE jobs.id = n.parent_id AND (jobs.status || '') = 'running' AND jobs.lease_owner IS NULL \
                    AND jobs.lease_until = $1 \
                    AND (n.done = n.total OR jobs.progress <> n.done::float8 / n.total) RETURNING jobs.status) \
             SELECT count(*) FILTER (WHERE status = 'queued') FROM up"
        )))
        .bind(WAITING_UNTIL)
        .bind(parents)
        .bind(children)
        .fetch_one(&s.pool)
        .await?;
        let requeued: i64 = rows.try_get(0)?;
        if requeued > 0 {
            sqlx::query("SELECT pg_notify($1, 'queued')").bind(postgres::CHANNEL).execute(&s.pool).await?;
        }
        Ok(requeued as u64)
    }

    /// The children of `parent` with their outcomes, by index (empty: not a fanned-out job).
    pub async fn child_outcomes(&self, parent: Uuid) -> StoreResult<Vec<ChildOutcome>> {
        let s = match self {
            Store::Sqlite(s) => return s.child_outcomes(parent).await,
            Store::Postgres(s) => s,
        };
        let rows = sqlx::query(
            "SELECT c.idx, c.job_id, c.reused, j.status, j.solved_by, j.error, c.owned \
             FROM job_children c LEFT JOIN jobs j ON j.id = c.job_id WHERE c.parent_id = $1 ORDER BY c.idx",
        )
        .bind(parent.to_string())
        .fetch_all(&s.pool)
        .await?;
        rows.iter()
            .map(|r| {
                let status: Option<String> = r.try_get(3)?;
                Ok(ChildOutcome {
                    index: r.try_get(0)?,
                    job_id: parse_uuid(&r.try_get::<String, _>(1)?)?,
                    reused: r.try_get(2)?,
                    owned: r.try_get(6)?,
                    status: status.as_deref().and_then(JobStatus::parse),
                    solved_by: r.try_get(4)?,
                    error: r.try_get(5)?,
                })
            })
            .collect()
    }

    /// The stored results of the children of `parent` from index `from` on, at most `limit`, by
    /// index (children without a result are skipped): the assembly reads them a page at a time.
    pub async fn child_results(&self, parent: Uuid, from: i64, limit: i64) -> StoreResult<Vec<(i64, String)>> {
        let s = match self {
            Store::Sqlite(s) => return s.child_results(parent, from, limit).await,
            Store::Postgres(s) => s,
        };
        let rows = sqlx::query(
            "SELECT c.idx, r.encoding, r.body FROM job_children c JOIN job_results r ON r.job_id = c.job_id \
             WHERE c.parent_id = $1 AND c.idx >= $2 ORDER BY c.idx LIMIT $3",
        )
        .bind(parent.to_string())
        .bind(from)
        .bind(limit)
        .fetch_all(&s.pool)
        .await?;
        rows.iter()
            .map(|r| {
                let (e, b): (String, Vec<u8>) = (r.try_get(1)?, r.try_get(2)?);
                Ok((r.try_get(0)?, decode_result(&e, &b).map_err(StoreError::Corrupt)?))
            })
            .collect()
    }

    /// Point case `child.index` of `parent` at another job: a case canceled for another parent
    /// (a race of a join with that parent's cancel), solved again for this one.
    pub async fn replace_child(&self, parent: Uuid, child: &Child) -> StoreResult<()> {
        let s = match self {
            Store::Sqlite(s) => return s.replace_child(parent, child).await,
            Store::Postgres(s) => s,
        };
        sqlx::query("UPDATE job_children SET job_id = $1, reused = $2, owned = $3 WHERE parent_id = $4 AND idx = $5")
            .bind(child.job_id.to_string())
            .bind(child.reused)
            .bind(child.owned)
            .bind(parent.to_string())
            .bind(child.index)
            .execute(&s.pool)
            .await?;
        Ok(())
    }

    /// The children of `id` counted by status (`None`: it has none).
    pub async fn child_counts(&self, id: Uuid) -> StoreResult<Option<ChildCounts>> {
        let s = match self {
            Store::Sqlite(s) => return s.child_counts(id).await,
            Store::Postgres(s) => s,
        };
        let r = sqlx::query(
            "SELECT count(*), count(*) FILTER (WHERE j.status = 'queued'), count(*) FILTER (WHERE j.status = 'running'), \
                    count(*) FILTER (WHERE j.status = 'succeeded'), \
                    count(*) FILTER (WHERE j.status IS NULL OR j.status IN ('failed', 'canceled')), \
                    count(*) FILTER (WHERE j.status = 'succeeded' AND c.reused) \
             FROM job_children c LEFT JOIN jobs j ON j.id = c.job_id WHERE c.parent_id = $1",
        )
        .bind(id.to_string())
        .fetch_one(&s.pool)
        .await?;
        let total: i64 = r.try_get(0)?;
        if total == 0 {
            return Ok(None);
        }
        Ok(Some(ChildCounts {
            total,
            queued: r.try_get(1)?,
            running: r.try_get(2)?,
            succeeded: r.try_get(3)?,
            failed: r.try_get(4)?,
            reused: r.try_get(5)?,
        }))
    }

    /// Cancel the children of `parent` that are case jobs (created for a fan-out: by this parent
    /// or by another one it joined) and that no other live parent needs (reference-counted
    /// joins: a case shared with a sweep neither finished nor asked to stop keeps running; the
    /// last parent's cancel stops it). Jobs submitted on their own and joined are never
    /// canceled. Queued ones at once, running ones through their cancel flag (their workers see
    /// it at the next lease renewal, ≤ 0.5 s); a parent waiting for them is canceled at once.
    /// The children canceled or asked to stop.
    pub async fn cancel_children(&self, parent: Uuid, now: i64) -> StoreResult<u64> {
        let s = match self {
            Store::Sqlite(s) => return s.cancel_children(parent, now).await,
            Store::Postgres(s) => s,
        };
        // A case job (some parent created it) that no parent other than `parent` still needs:
        // every other parent linking it is finished or asked to stop. A constant: no request text.
        const UNNEEDED: &str = "EXISTS (SELECT 1 FROM job_children o WHERE o.job_id = jobs.id AND o.owned) \
             AND NOT EXISTS (SELECT 1 FROM job_children o JOIN jobs pj ON pj.id = o.parent_id \
                             WHERE o.job_id = jobs.id AND o.parent_id <> $P \
                               AND pj.status IN ('queued', 'running') AND NOT pj.cancel_requested)";
        let (unneeded_1, unneeded_2) = (UNNEEDED.replace("$P", "$1"), UNNEEDED.replace("$P", "$2"));
        let mut tx = s.pool.begin().await?;
        let p = parent.to_string();
        let queued = sqlx::query(AssertSqlSafe(format!(
            "WITH up AS (UPDATE jobs SET status = 'canceled', finished_at = $1, cancel_requested = TRUE \
                         WHERE status = 'queued' AND id IN (SELECT job_id FROM job_children WHERE parent_id = $2) AND {unneeded_2} \
                         RETURNING id) \
             SELECT pg_notify($3, 'finished:' || id)::text FROM up"
        )))
        .bind(now)
        .bind(&p)
        .bind(postgres::CHANNEL)
        .fetch_all(&mut *tx)
        .await?
        .len() as u64;
        let running = sqlx::query(AssertSqlSafe(format!(
            "UPDATE jobs SET cancel_requested = TRUE \
             WHERE status = 'running' AND id IN (SELECT job_id FROM job_children WHERE parent_id = $1) AND {unneeded_1}"
        )))
        .bind(&p)
        .execute(&mut *tx)
        .await?
        .rows_affected();
        sqlx::query(
            "WITH up AS (UPDATE jobs SET status = 'canceled', finished_at = $1, lease_until = NULL \
                         WHERE id = $2 AND status = 'running' AND lease_owner IS NULL AND lease_until = $3 RETURNING id) \
             SELECT pg_notify($4, 'finished:' || id)::text FROM up",
        )
        .bind(now)
        .bind(&p)
        .bind(WAITING_UNTIL)
        .bind(postgres::CHANNEL)
        .fetch_all(&mut *tx)
        .await?;
        tx.commit().await?;
        Ok(queued + running)
    }

    /// The jobs the queue's backlog does not count (at start-up): cases of a fan-out that are
    /// queued or running, and parents waiting for their cases.
    pub async fn uncounted_jobs(&self) -> StoreResult<Vec<Uuid>> {
        const SQL: &str = "SELECT id FROM jobs WHERE (status IN ('queued', 'running') \
             AND EXISTS (SELECT 1 FROM job_children c WHERE c.job_id = jobs.id AND c.owned)) \
             OR (status = 'running' AND EXISTS (SELECT 1 FROM job_children c WHERE c.parent_id = jobs.id))";
        let ids: Vec<String> = match self {
            Store::Sqlite(s) => s.read_strings(SQL).await?,
            Store::Postgres(s) => sqlx::query_scalar(SQL).fetch_all(&s.pool).await?,
        };
        ids.iter().map(|id| parse_uuid(id)).collect()
    }

    /// Remember that `id` is submitted with `?fresh=true` (its cases reuse nothing); written
    /// before the job itself.
    pub async fn set_fresh(&self, id: Uuid) -> StoreResult<()> {
        let s = match self {
            Store::Sqlite(s) => return s.set_fresh(id).await,
            Store::Postgres(s) => s,
        };
        sqlx::query("INSERT INTO job_options (job_id, fresh) VALUES ($1, TRUE) ON CONFLICT (job_id) DO UPDATE SET fresh = TRUE")
            .bind(id.to_string())
            .execute(&s.pool)
            .await?;
        Ok(())
    }

    pub async fn is_fresh(&self, id: Uuid) -> StoreResult<bool> {
        let s = match self {
            Store::Sqlite(s) => return s.is_fresh(id).await,
            Store::Postgres(s) => s,
        };
        Ok(sqlx::query_scalar::<_, bool>("SELECT fresh FROM job_options WHERE job_id = $1")
            .bind(id.to_string())
            .fetch_optional(&s.pool)
            .await?
            .unwrap_or(false))
    }
}
