-- Issue 44 on SQLite: the same fan-out as on PostgreSQL (migrations/postgres/0005_children.sql).
-- The cases of a fanned-out job (a sweep) are ordinary jobs of their case kind; `job_children`
-- ties each case (parent, index) to the job that solves it: a new one, an identical one already
-- queued or running (joined), or an identical succeeded one (reused: the case cache).
CREATE TABLE job_children (
    parent_id TEXT    NOT NULL REFERENCES jobs (id) ON DELETE CASCADE,
    idx       INTEGER NOT NULL,                 -- the case's index in the parent (0-based)
    job_id    TEXT    NOT NULL,                 -- the job solving the case (may be deleted later)
    reused    INTEGER NOT NULL,                 -- an identical case had already succeeded
    owned     INTEGER NOT NULL,                 -- created for this parent (a cancel of the parent cancels it)
    PRIMARY KEY (parent_id, idx)
);
CREATE INDEX job_children_by_job ON job_children (job_id);

-- The instance that solved a job (its lease owner when it finished): a sweep's rows name it.
ALTER TABLE jobs ADD COLUMN solved_by TEXT;

-- Submission options a fanned-out job passes on to its cases (`?fresh=true`: no case reused),
-- written before the job itself: no foreign key.
CREATE TABLE job_options (
    job_id TEXT    PRIMARY KEY,
    fresh  INTEGER NOT NULL
);
