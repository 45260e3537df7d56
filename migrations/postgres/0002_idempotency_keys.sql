-- Issue 40: an Idempotency-Key is recorded whatever the first answer to its request was — a new
-- job, an identical finished job reused, or an identical queued or running job joined — with the
-- request's spec hash and label, so that a repeat replays that answer and another request under
-- the key is refused (as migrations/sqlite/0004). Until now only a new job kept its key.
CREATE TABLE idempotency_keys (
    key        TEXT    PRIMARY KEY,             -- the client's Idempotency-Key
    -- The job that answered; a key lives as long as its job (DELETE of the job forgets the key).
    job_id     TEXT    NOT NULL REFERENCES jobs (id) ON DELETE CASCADE,
    spec_hash  TEXT    NOT NULL,                -- of the request first sent with the key
    label      TEXT,                            -- of that request
    reused     BOOLEAN NOT NULL DEFAULT FALSE,  -- the job was another request's (reused or joined)
    created_at BIGINT  NOT NULL                 -- unix milliseconds
);
CREATE INDEX idempotency_keys_by_job ON idempotency_keys (job_id);

-- Keys stored with the jobs they created keep working.
INSERT INTO idempotency_keys (key, job_id, spec_hash, label, reused, created_at)
SELECT idempotency_key, id, spec_hash, label, FALSE, created_at FROM jobs WHERE idempotency_key IS NOT NULL;

ALTER TABLE jobs DROP COLUMN idempotency_key;   -- drops jobs_by_idempotency_key with it
