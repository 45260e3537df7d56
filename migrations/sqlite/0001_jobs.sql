-- Jobs: one row per accepted request. `seq` orders the queue (FIFO) and pages listings (keyset).
CREATE TABLE jobs (
    seq              INTEGER PRIMARY KEY AUTOINCREMENT,
    id               TEXT    NOT NULL UNIQUE,
    kind             TEXT    NOT NULL,
    label            TEXT,
    status           TEXT    NOT NULL
        CHECK (status IN ('queued', 'running', 'succeeded', 'failed', 'canceled')),
    spec             TEXT    NOT NULL,          -- canonical JSON (keys sorted, defaults filled)
    spec_hash        TEXT    NOT NULL,          -- sha256 of kind + canonical spec, hex
    solver_version   TEXT    NOT NULL,
    created_at       INTEGER NOT NULL,          -- unix milliseconds
    started_at       INTEGER,
    finished_at      INTEGER,
    attempts         INTEGER NOT NULL DEFAULT 0,
    progress         REAL    NOT NULL DEFAULT 0,
    stage            TEXT,
    cancel_requested INTEGER NOT NULL DEFAULT 0,
    error            TEXT                       -- problem+json of a failed job
);

CREATE INDEX jobs_by_status ON jobs (status, seq);
CREATE INDEX jobs_by_kind ON jobs (kind, seq);
CREATE INDEX jobs_by_created ON jobs (created_at);
CREATE INDEX jobs_dedup ON jobs (spec_hash, solver_version) WHERE status = 'succeeded';

-- Results live apart from job rows so that listing jobs never reads them.
CREATE TABLE job_results (
    job_id   TEXT    PRIMARY KEY REFERENCES jobs (id) ON DELETE CASCADE,
    encoding TEXT    NOT NULL CHECK (encoding IN ('json', 'json+deflate')),
    size     INTEGER NOT NULL,                  -- uncompressed bytes
    body     BLOB    NOT NULL
);
