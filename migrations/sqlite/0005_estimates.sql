-- Issue 40: the work and memory models' estimate of each job, stored at submission (shown by
-- GET /v1/jobs/{id}, and the fair scheduler's solve time after a restart). NULL for jobs
-- accepted before the models existed.
ALTER TABLE jobs ADD COLUMN estimate_cpu_seconds REAL;
ALTER TABLE jobs ADD COLUMN estimate_memory_bytes REAL;
