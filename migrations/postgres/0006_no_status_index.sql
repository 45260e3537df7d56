-- Issue 46: the planner joined every by-id update of a running job (finish, progress, lease
-- renewal) and the fan-out's parent lookup with a bitmap scan of `jobs_by_status` for
-- status = 'running', which reads every index entry of a running version, dead ones included
-- (bitmap scans never mark entries dead; only VACUUM removes them): 1 400 entries per tiny job
-- under `cargo bench --bench scale` (counted with pg_stat_user_indexes). Without the index those
-- statements look their rows up by `id` alone, and inserts, claims and finishes each write one
-- index entry fewer. Queued jobs are found through `jobs_queue`, in-flight ones through
-- `jobs_in_flight`; counts by status, the expiry scan (every 2 s) and listing a rare status read
-- the table.
DROP INDEX IF EXISTS jobs_by_status;
