-- The PostgreSQL schema: the same tables and semantics as migrations/sqlite (0001–0003), for a
-- database shared by many tribod instances.
CREATE TABLE jobs (
    seq              BIGSERIAL PRIMARY KEY,
    id               TEXT    NOT NULL UNIQUE,
    kind             TEXT    NOT NULL,
    label            TEXT,
    status           TEXT    NOT NULL
        CHECK (status IN ('queued', 'running', 'succeeded', 'failed', 'canceled')),
    spec             TEXT    NOT NULL,          -- canonical JSON (keys sorted, defaults filled)
    spec_hash        TEXT    NOT NULL,          -- sha256 of kind + canonical spec, hex
    solver_version   TEXT    NOT NULL,
    created_at       BIGINT  NOT NULL,          -- unix milliseconds
    started_at       BIGINT,
    finished_at      BIGINT,
    attempts         BIGINT  NOT NULL DEFAULT 0,
    progress         DOUBLE PRECISION NOT NULL DEFAULT 0,
    stage            TEXT,
    cancel_requested BOOLEAN NOT NULL DEFAULT FALSE,
    error            TEXT,                      -- problem+json of a failed job
    idempotency_key  TEXT,                      -- the client's Idempotency-Key
    due_at           BIGINT  NOT NULL DEFAULT 0, -- fair scheduling: virtual deadline, unix ms
    lease_owner      TEXT,                      -- instance holding a running job
    lease_until      BIGINT                     -- its lease ends (unix ms) unless renewed
);

CREATE INDEX jobs_by_status ON jobs (status, seq);
CREATE INDEX jobs_by_kind ON jobs (kind, seq);
CREATE INDEX jobs_by_created ON jobs (created_at);
CREATE INDEX jobs_dedup ON jobs (spec_hash, solver_version) WHERE status = 'succeeded';
CREATE INDEX jobs_queue ON jobs (due_at, seq) WHERE status = 'queued';
CREATE INDEX jobs_leases ON jobs (lease_until) WHERE status = 'running';
CREATE UNIQUE INDEX jobs_by_idempotency_key ON jobs (idempotency_key) WHERE idempotency_key IS NOT NULL;
-- One in-flight job per spec: identical submissions on any instance join it (the index decides
-- the race between instances; the loser reads the winner's row).
CREATE UNIQUE INDEX jobs_in_flight ON jobs (spec_hash, solver_version) WHERE status IN ('queued', 'running');

CREATE TABLE job_results (
    job_id   TEXT    PRIMARY KEY REFERENCES jobs (id) ON DELETE CASCADE,
    encoding TEXT    NOT NULL CHECK (encoding IN ('json', 'json+deflate')),
    size     BIGINT  NOT NULL,                  -- uncompressed bytes
    body     BYTEA   NOT NULL
);

CREATE TABLE heartbeat (
    id   INTEGER PRIMARY KEY CHECK (id = 1),
    beat BIGINT  NOT NULL
);
INSERT INTO heartbeat (id, beat) VALUES (1, 0);
