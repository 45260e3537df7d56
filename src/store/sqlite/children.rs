//! Children of a fanned-out job on SQLite (issue 44): the statements of `store::children` for
//! one file. Lists of ids travel as JSON arrays (`json_each`); writes go through the one writer
//! connection, so a cancel and a join never interleave.

use super::*;
use crate::store::children::WAITING_UNTIL;

/// Ids as a JSON array (for `json_each`).
fn id_array(ids: &[Uuid]) -> String {
    serde_json::to_string(&ids.iter().map(Uuid::to_string).collect::<Vec<_>>()).unwrap_or_else(|_| "[]".into())
}

impl SqliteStore {
    /// The first column of every row of `sql` (a constant statement).
    pub(crate) async fn read_strings(&self, sql: &'static str) -> StoreResult<Vec<String>> {
        Ok(sqlx::query_scalar(sql).fetch_all(&self.reader).await?)
    }

    pub(crate) async fn add_children(&self, parent: Uuid, children: &[Child]) -> StoreResult<()> {
        // Before the rows exist: a finish committed after them sees the flag.
        self.children_seen.store(true, std::sync::atomic::Ordering::SeqCst);
        let mut conn = self.writer.acquire().await?;
        let result = async {
            let mut tx = conn.begin().await?;
            for c in children {
                sqlx::query("INSERT INTO job_children (parent_id, idx, job_id, reused, owned) VALUES (?, ?, ?, ?, ?) ON CONFLICT (parent_id, idx) DO NOTHING")
                    .bind(parent.to_string())
                    .bind(c.index)
                    .bind(c.job_id.to_string())
                    .bind(c.reused as i64)
                    .bind(c.owned as i64)
                    .execute(&mut *tx)
                    .await?;
            }
            tx.commit().await?;
            Ok(())
        }
        .await;
        self.settle(conn, result).await
    }

    /// Point case `index` of `parent` at another job (a case canceled for another parent, solved
    /// again for this one).
    pub(crate) async fn replace_child(&self, parent: Uuid, child: &Child) -> StoreResult<()> {
        let mut conn = self.writer.acquire().await?;
        let r = sqlx::query("UPDATE job_children SET job_id = ?, reused = ?, owned = ? WHERE parent_id = ? AND idx = ?")
            .bind(child.job_id.to_string())
            .bind(child.reused as i64)
            .bind(child.owned as i64)
            .bind(parent.to_string())
            .bind(child.index)
            .execute(&mut *conn)
            .await
            .map(|_| ())
            .map_err(StoreError::from);
        self.settle(conn, r).await
    }

    pub(crate) async fn due_at(&self, id: Uuid) -> StoreResult<Option<i64>> {
        Ok(sqlx::query_scalar::<_, i64>("SELECT due_at FROM jobs WHERE id = ?").bind(id.to_string()).fetch_optional(&self.reader).await?)
    }

    pub(crate) async fn wait_for_children(&self, parent: Uuid, owner: &str) -> StoreResult<bool> {
        let mut conn = self.writer.acquire().await?;
        let r = sqlx::query(
            "UPDATE jobs SET lease_owner = NULL, lease_until = ?, stage = ?, attempts = MAX(attempts - 1, 0) \
             WHERE id = ? AND status = 'running' AND lease_owner = ?",
        )
        .bind(WAITING_UNTIL)
        .bind(crate::store::children::WAITING_STAGE)
        .bind(parent.to_string())
        .bind(owner)
        .execute(&mut *conn)
        .await
        .map_err(StoreError::from);
        let r = self.settle(conn, r).await?;
        self.release_parents(Some(&[parent]), None).await?;
        Ok(r.rows_affected() == 1)
    }

    pub(crate) async fn release_parents(&self, parents: Option<&[Uuid]>, children: Option<&[Uuid]>) -> StoreResult<u64> {
        // Most finished jobs are nobody's case: a look on a reader spares the one writer.
        if let Some(ids) = children {
            let linked = sqlx::query_scalar::<_, i64>("SELECT EXISTS (SELECT 1 FROM job_children WHERE job_id IN (SELECT value FROM json_each(?)))")
                .bind(id_array(ids))
                .fetch_one(&self.reader)
                .await?;
            if linked == 0 {
                return Ok(0);
            }
        }
        let mut conn = self.writer.acquire().await?;
        let rows = sqlx::query(
            "WITH p AS (SELECT id FROM jobs WHERE status = 'running' AND lease_owner IS NULL AND lease_until = ?1 \
                        AND (?2 IS NULL OR id IN (SELECT value FROM json_each(?2))) \
                        AND (?3 IS NULL OR id IN (SELECT parent_id FROM job_children WHERE job_id IN (SELECT value FROM json_each(?3))))), \
             n AS (SELECT c.parent_id AS pid, COUNT(*) AS total, \
                          SUM(CASE WHEN j.status IS NULL OR j.status IN ('succeeded', 'failed', 'canceled') THEN 1 ELSE 0 END) AS done \
                   FROM job_children c LEFT JOIN jobs j ON j.id = c.job_id \
                   WHERE c.parent_id IN (SELECT id FROM p) GROUP BY c.parent_id) \
             UPDATE jobs SET progress = CAST(n.done AS REAL) / n.total, \
                 status = CASE WHEN n.done = n.total THEN 'queued' ELSE 'running' END, \
                 lease_until = CASE WHEN n.done = n.total THEN NULL ELSE jobs.lease_until END, \
                 due_at = CASE WHEN n.done = n.total THEN 0 ELSE jobs.due_at END, \
                 attempts = CASE WHEN n.done = n.total THEN MAX(jobs.attempts - 1, 0) ELSE jobs.attempts END \
             FROM n WHERE jobs.id = n.pid AND jobs.status = 'running' AND jobs.lease_owner IS NULL AND jobs.lease_until = ?1 \
               AND (n.done = n.total OR jobs.progress <> CAST(n.done AS REAL) / n.total) \
             RETURNING status",
        )
        .bind(WAITING_UNTIL)
        .bind(parents.map(id_array))
        .bind(children.map(id_array))
        .fetch_all(&mut *conn)
        .await
        .map_err(StoreError::from);
        let rows = self.settle(conn, rows).await?;
        let mut requeued = 0;
        for r in &rows {
            if r.try_get::<String, _>(0)? == "queued" {
                requeued += 1;
            }
        }
        Ok(requeued)
    }

    pub(crate) async fn child_outcomes(&self, parent: Uuid) -> StoreResult<Vec<ChildOutcome>> {
        let rows = sqlx::query(
            "SELECT c.idx, c.job_id, c.reused, j.status, j.solved_by, j.error, c.owned \
             FROM job_children c LEFT JOIN jobs j ON j.id = c.job_id WHERE c.parent_id = ? ORDER BY c.idx",
        )
        .bind(parent.to_string())
        .fetch_all(&self.reader)
        .await?;
        rows.iter()
            .map(|r| {
                let status: Option<String> = r.try_get(3)?;
                Ok(ChildOutcome {
                    index: r.try_get(0)?,
                    job_id: parse_uuid(&r.try_get::<String, _>(1)?)?,
                    reused: r.try_get::<i64, _>(2)? != 0,
                    owned: r.try_get::<i64, _>(6)? != 0,
                    status: status.as_deref().and_then(JobStatus::parse),
                    solved_by: r.try_get(4)?,
                    error: r.try_get(5)?,
                })
            })
            .collect()
    }

    pub(crate) async fn child_results(&self, parent: Uuid, from: i64, limit: i64) -> StoreResult<Vec<(i64, String)>> {
        let rows = sqlx::query(
            "SELECT c.idx, r.encoding, r.body FROM job_children c JOIN job_results r ON r.job_id = c.job_id \
             WHERE c.parent_id = ? AND c.idx >= ? ORDER BY c.idx LIMIT ?",
        )
        .bind(parent.to_string())
        .bind(from)
        .bind(limit)
        .fetch_all(&self.reader)
        .await?;
        rows.iter()
            .map(|r| {
                let (e, b): (String, Vec<u8>) = (r.try_get(1)?, r.try_get(2)?);
                Ok((r.try_get(0)?, decode_result(&e, &b).map_err(StoreError::Corrupt)?))
            })
            .collect()
    }

    pub(crate) async fn child_counts(&self, id: Uuid) -> StoreResult<Option<ChildCounts>> {
        let r = sqlx::query(
            "SELECT COUNT(*), COUNT(*) FILTER (WHERE j.status = 'queued'), COUNT(*) FILTER (WHERE j.status = 'running'), \
                    COUNT(*) FILTER (WHERE j.status = 'succeeded'), \
                    COUNT(*) FILTER (WHERE j.status IS NULL OR j.status IN ('failed', 'canceled')), \
                    COUNT(*) FILTER (WHERE j.status = 'succeeded' AND c.reused) \
             FROM job_children c LEFT JOIN jobs j ON j.id = c.job_id WHERE c.parent_id = ?",
        )
        .bind(id.to_string())
        .fetch_one(&self.reader)
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

    /// See `Store::cancel_children` (the same rules; one writer, so no race with a join).
    pub(crate) async fn cancel_children(&self, parent: Uuid, now: i64) -> StoreResult<u64> {
        // ?1 = now, ?2 = parent, ?3 = the waiting lease.
        const UNNEEDED: &str = "EXISTS (SELECT 1 FROM job_children o WHERE o.job_id = jobs.id AND o.owned) \
             AND NOT EXISTS (SELECT 1 FROM job_children o JOIN jobs pj ON pj.id = o.parent_id \
                             WHERE o.job_id = jobs.id AND o.parent_id <> ?2 \
                               AND pj.status IN ('queued', 'running') AND NOT pj.cancel_requested)";
        let mut conn = self.writer.acquire().await?;
        let result = async {
            let mut tx = conn.begin().await?;
            let queued = sqlx::query(AssertSqlSafe(format!(
                "UPDATE jobs SET status = 'canceled', finished_at = ?1, cancel_requested = 1 \
                 WHERE status = 'queued' AND id IN (SELECT job_id FROM job_children WHERE parent_id = ?2) AND {UNNEEDED}"
            )))
            .bind(now)
            .bind(parent.to_string())
            .execute(&mut *tx)
            .await?
            .rows_affected();
            let running = sqlx::query(AssertSqlSafe(format!(
                "UPDATE jobs SET cancel_requested = 1 \
                 WHERE status = 'running' AND id IN (SELECT job_id FROM job_children WHERE parent_id = ?2) AND {UNNEEDED} AND ?1 IS NOT NULL"
            )))
            .bind(now)
            .bind(parent.to_string())
            .execute(&mut *tx)
            .await?
            .rows_affected();
            sqlx::query(
                "UPDATE jobs SET status = 'canceled', finished_at = ?1, lease_until = NULL \
                 WHERE id = ?2 AND status = 'running' AND lease_owner IS NULL AND lease_until = ?3",
            )
            .bind(now)
            .bind(parent.to_string())
            .bind(WAITING_UNTIL)
            .execute(&mut *tx)
            .await?;
            tx.commit().await?;
            Ok(queued + running)
        }
        .await;
        self.settle(conn, result).await
    }

    pub(crate) async fn set_fresh(&self, id: Uuid) -> StoreResult<()> {
        let mut conn = self.writer.acquire().await?;
        let r = sqlx::query("INSERT INTO job_options (job_id, fresh) VALUES (?, 1) ON CONFLICT (job_id) DO UPDATE SET fresh = 1")
            .bind(id.to_string())
            .execute(&mut *conn)
            .await
            .map(|_| ())
            .map_err(StoreError::from);
        self.settle(conn, r).await
    }

    pub(crate) async fn is_fresh(&self, id: Uuid) -> StoreResult<bool> {
        Ok(sqlx::query_scalar::<_, i64>("SELECT fresh FROM job_options WHERE job_id = ?")
            .bind(id.to_string())
            .fetch_optional(&self.reader)
            .await?
            .is_some_and(|f| f != 0))
    }
}
