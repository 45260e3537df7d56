-- Issue 40: an Idempotency-Key is recorded whatever the first answer to its request was — a new
-- job, an identical finished job reused, or an identical queued or running job joined — with the
-- request's spec hash and label, so that a repeat replays that answer and another request under
-- the key is refused. Until now only a new job kept its key (in jobs.idempotency_key).
CREATE TABLE idempotency_keys (
    key        TEXT    PRIMARY KEY,             -- the client's Idempotency-Key
    -- The job that answered; a key lives as long as its job (DELETE of the job forgets the key).
    job_id     TEXT    NOT NULL REFERENCES jobs (id) ON DELETE CASCADE,
    spec_hash  TEXT    NOT NULL,                -- of the request first sent with the key
    label      TEXT,                            -- of that request
    reused     INTEGER NOT NULL DEFAULT 0,      -- 1: the job was another request's (reused or joined)
    created_at INTEGER NOT NULL                 -- unix milliseconds
);
CREATE INDEX idempotency_keys_by_job ON idempotency_keys (job_id);

-- Keys stored with the jobs they created keep working.
INSERT INTO idempotency_keys (key, job_id, spec_hash, label, reused, created_at)
SELECT idempotency_key, id, spec_hash, label, 0, created_at FROM jobs WHERE idempotency_key IS NOT NULL;

DROP INDEX jobs_by_idempotency_key;
ALTER TABLE jobs DROP COLUMN idempotency_key;
