-- Issue 46 item 5: short-job slots. Besides its ordinary worker slots an instance has slots that
-- take only short jobs (the work model's stored estimate at most 10 ms of CPU); their claim
-- reads the queue's short jobs in virtual-deadline order through this index, whatever the number
-- of long jobs due before them. The predicate is the text of `store::SHORT_JOB_SQL` (a generic
-- plan uses a partial index only when the query states its predicate literally).
CREATE INDEX jobs_short_queue ON jobs (due_at, seq) WHERE status = 'queued' AND estimate_cpu_seconds <= 0.01;
