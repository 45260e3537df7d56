//! Finishing a batch of jobs on PostgreSQL, and claiming the next ones for the slots they free, in
//! one statement and one commit (issue 46 item 5: a tiny job's finish and the claim of the next
//! job were two round trips and two commits; the dispatcher's claim now runs only for slots no
//! finish refilled — start-up, submissions to an idle instance, lost notifications).

use super::*;

/// Rows of claimed jobs (`id, kind, spec, attempts, due_at, seq, short` from column `first` on)
/// in virtual-deadline order.
pub(super) fn claimed_from_rows<'a>(rows: impl IntoIterator<Item = &'a PgRow>, first: usize) -> StoreResult<Vec<ClaimedJob>> {
    let mut jobs = rows
        .into_iter()
        .map(|r| {
            Ok((
                (r.try_get::<i64, _>(first + 4)?, r.try_get::<i64, _>(first + 5)?),
                ClaimedJob {
                    id: parse_uuid(&r.try_get::<String, _>(first)?)?,
                    kind: r.try_get(first + 1)?,
                    spec: r.try_get(first + 2)?,
                    attempts: r.try_get(first + 3)?,
                    short: r.try_get(first + 6)?,
                },
            ))
        })
        .collect::<StoreResult<Vec<_>>>()?;
    jobs.sort_by_key(|(order, _)| *order);
    Ok(jobs.into_iter().map(|(_, j)| j).collect())
}

/// The claim of [`ClaimNext`] as the `WHERE` of an update of `jobs`: the first `$n` queued jobs
/// in virtual-deadline order and the first `$short` short ones after them, each locked (`FOR
/// UPDATE SKIP LOCKED`: another instance's claim takes others). Short ones are read through
/// `jobs_short_queue`, whose predicate is the same text.
pub(super) fn claim_where(n: &str, short: &str) -> String {
    format!(
        "seq = ANY(ARRAY(WITH g AS MATERIALIZED (SELECT seq FROM jobs WHERE status = 'queued' ORDER BY due_at, seq LIMIT {n} \
                                               FOR UPDATE SKIP LOCKED) \
                        SELECT seq FROM g \
                        UNION ALL \
                        SELECT seq FROM (SELECT seq FROM jobs WHERE status = 'queued' AND {SHORT_JOB_SQL} \
                                         AND NOT EXISTS (SELECT 1 FROM g WHERE g.seq = jobs.seq) \
                                         ORDER BY due_at, seq LIMIT {short} FOR UPDATE SKIP LOCKED) s))"
    )
}

/// The batch statement. `done`: the terminal updates, only by the lease holder (after a lost lease
/// the job runs elsewhere); `stored`: the results of the succeeded ones; `claimed`: the queued
/// jobs of [`claim_where`] (`$10` of any size, `$12` short), leased to `$8` until `$11` (as
/// [`PgStore::claim`]; the rows `done` updates are running, the rows `claimed` locks are queued:
/// never the same row). One row per finished job (`claimed` false; it sends `finished:<id>`, and
/// tells whether any finished job is a fanned-out job's case), then one per claimed job.
static FINISH_AND_CLAIM: std::sync::LazyLock<String> = std::sync::LazyLock::new(|| {
    format!(
        "WITH u AS (SELECT * FROM UNNEST($1::text[], $2::text[], $3::text[], $4::text[], $5::bigint[], $6::bytea[]) \
                AS u(id, status, error, encoding, size, body)), \
     done AS (UPDATE jobs SET status = u.status, finished_at = $7, solved_by = jobs.lease_owner, lease_owner = NULL, error = u.error, \
              progress = CASE WHEN u.status = 'succeeded' THEN 1 ELSE jobs.progress END, \
              stage = CASE WHEN u.status = 'succeeded' THEN NULL ELSE jobs.stage END \
              FROM u WHERE jobs.id = ANY($1) AND jobs.id = u.id AND (jobs.status || '') = 'running' AND jobs.lease_owner = $8 \
              RETURNING jobs.id, jobs.status), \
     stored AS (INSERT INTO job_results (job_id, encoding, size, body) \
                SELECT u.id, u.encoding, u.size, u.body FROM u JOIN done ON done.id = u.id \
                WHERE done.status = 'succeeded' \
                ON CONFLICT (job_id) DO UPDATE SET encoding = EXCLUDED.encoding, size = EXCLUDED.size, \
                body = EXCLUDED.body RETURNING job_id), \
     claimed AS (UPDATE jobs SET status = 'running', started_at = COALESCE(started_at, $7), attempts = attempts + 1, \
                 progress = CASE WHEN started_at IS NULL THEN 0 ELSE progress END, \
                 stage = CASE WHEN started_at IS NULL THEN NULL ELSE stage END, lease_owner = $8, lease_until = $11 \
                 WHERE {} \
                 RETURNING id, kind, spec, attempts, due_at, seq, COALESCE({SHORT_JOB_SQL}, FALSE) AS short) \
     SELECT FALSE AS claimed, (SELECT count(*) FROM stored) >= 0 AND EXISTS (SELECT 1 FROM job_children c WHERE c.job_id = ANY($1)) AS cases, \
            pg_notify($9, 'finished:' || done.id)::text AS note, done.id, NULL::text AS kind, NULL::text AS spec, \
            0::bigint AS attempts, 0::bigint AS due_at, 0::bigint AS seq, FALSE AS short FROM done \
     UNION ALL \
     SELECT TRUE, FALSE, NULL, id, kind, spec, attempts, due_at, seq, short FROM claimed",
        claim_where("$10", "$12")
    )
});

impl PgStore {
    /// Finish a batch and claim up to `next.n` jobs, in one commit; see [`Store::finish_batch`].
    pub async fn finish_batch(&self, items: &[Finish], now: i64, owner: &str, next: ClaimNext) -> StoreResult<Finished> {
        let rows = self.finish_tx(items, now, owner, next).await;
        let rows = self.note(rows)?;
        let mut cases = false;
        for row in &rows {
            cases |= row.try_get::<bool, _>(1)?;
        }
        let claimed = claimed_from_rows(rows.iter().filter(|r| r.try_get::<bool, _>(0).unwrap_or(false)), 3)?;
        Ok(Finished { cases, claimed })
    }

    /// One statement ([`FINISH_AND_CLAIM`]) without a transaction around it; re-queues (rare:
    /// shutdown, which claims nothing) follow it in one transaction.
    async fn finish_tx(&self, items: &[Finish], now: i64, owner: &str, next: ClaimNext) -> Result<Vec<PgRow>, sqlx::Error> {
        let mut ids = Vec::new();
        let mut statuses = Vec::new();
        let mut errors: Vec<Option<String>> = Vec::new();
        let mut encodings: Vec<Option<String>> = Vec::new();
        let mut sizes: Vec<Option<i64>> = Vec::new();
        let mut bodies: Vec<Option<Vec<u8>>> = Vec::new();
        let mut requeue = Vec::new();
        for item in items {
            let (id, status, error, result) = match item {
                Finish::Succeeded { id, result } => (id, "succeeded", None, Some(result)),
                Finish::Failed { id, error } => (id, "failed", Some(error.clone()), None),
                Finish::Canceled { id } => (id, "canceled", None, None),
                Finish::Requeue { id } => {
                    requeue.push(id.to_string());
                    continue;
                }
            };
            ids.push(id.to_string());
            statuses.push(status);
            errors.push(error);
            encodings.push(result.map(|r| r.encoding.to_string()));
            sizes.push(result.map(|r| r.size as i64));
            bodies.push(result.map(|r| r.body.clone()));
        }
        let (claim, short) = if requeue.is_empty() { (next.n, next.short) } else { (0, 0) };
        // On `finishes`: prepared and planned once per connection, every table read by an index.
        let q = sqlx::query(AssertSqlSafe(FINISH_AND_CLAIM.as_str()))
            .bind(&ids)
            .bind(&statuses)
            .bind(&errors)
            .bind(&encodings)
            .bind(&sizes)
            .bind(&bodies)
            .bind(now)
            .bind(owner)
            .bind(CHANNEL)
            .bind(claim as i64)
            .bind(next.lease_until)
            .bind(short as i64);
        if requeue.is_empty() {
            return q.fetch_all(&self.finishes).await;
        }
        let mut tx = self.finishes.begin().await?;
        let rows = if ids.is_empty() { Vec::new() } else { q.fetch_all(&mut *tx).await? };
        let n = sqlx::query(
            "UPDATE jobs SET status = 'queued', started_at = NULL, progress = 0, stage = NULL, \
             attempts = GREATEST(attempts - 1, 0), lease_owner = NULL, lease_until = NULL \
             WHERE id = ANY($1) AND (status || '') = 'running' AND lease_owner = $2",
        )
        .bind(&requeue)
        .bind(owner)
        .execute(&mut *tx)
        .await?
        .rows_affected();
        if n > 0 {
            sqlx::query("SELECT pg_notify($1, 'queued')").bind(CHANNEL).execute(&mut *tx).await?;
        }
        tx.commit().await?;
        Ok(rows)
    }
}
