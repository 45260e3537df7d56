-- Issue 46: the frequent updates of a running job — lease renewals (every few seconds per job) and
-- progress (several a second) — become HOT updates: they touch no indexed column and find room
-- on the row's page, so PostgreSQL writes neither a new index entry nor, mostly, a new page.
-- Claims and finishes change `status`, which the queue's indexes key on, and stay ordinary.
--
-- `jobs_leases` indexed `lease_until` only to find expired leases; the few running jobs are found
-- as well through `jobs_by_status` (status = 'running'), and without the index a renewal is HOT.
DROP INDEX IF EXISTS jobs_leases;
-- Room on each page for the updated versions of its rows (new pages; existing ones as rewritten),
-- and autovacuum that keeps up with a queue table's churn instead of waiting for 20 % dead rows.
ALTER TABLE jobs SET (
    fillfactor = 70,
    autovacuum_vacuum_scale_factor = 0.02,
    autovacuum_analyze_scale_factor = 0.02,
    autovacuum_vacuum_cost_delay = 0
);
