-- Issue 10: a write-path probe for /readyz, idempotent submissions and fair scheduling.

-- One row that /readyz rewrites through the writer connection: ready means "a commit works".
CREATE TABLE heartbeat (
    id   INTEGER PRIMARY KEY CHECK (id = 1),
    beat INTEGER NOT NULL                       -- unix milliseconds of the last probe
);
INSERT INTO heartbeat (id, beat) VALUES (1, 0);

-- The client's Idempotency-Key of POST /v1/jobs: one job per key.
ALTER TABLE jobs ADD COLUMN idempotency_key TEXT;
CREATE UNIQUE INDEX jobs_by_idempotency_key ON jobs (idempotency_key) WHERE idempotency_key IS NOT NULL;

-- Fair scheduling: queued jobs are claimed by earliest virtual deadline
-- (created_at + aging factor × estimated solve time), then by seq.
ALTER TABLE jobs ADD COLUMN due_at INTEGER NOT NULL DEFAULT 0;
CREATE INDEX jobs_queue ON jobs (status, due_at, seq);
