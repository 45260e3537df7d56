-- Issue 12: leases (the claiming instance and until when it holds the job) and one in-flight job
-- per spec: an identical submission while the first is queued or running joins it.
ALTER TABLE jobs ADD COLUMN lease_owner TEXT;
ALTER TABLE jobs ADD COLUMN lease_until INTEGER;          -- unix milliseconds

-- Identical jobs already waiting (possible before this migration): keep the oldest.
UPDATE jobs SET status = 'canceled', finished_at = CAST(strftime('%s', 'now') AS INTEGER) * 1000,
    error = '{"type":"urn:tribod:problem:interrupted","title":"Job interrupted","status":503,"code":"interrupted","detail":"an identical job was already queued; this one was merged into it by an upgrade"}'
WHERE status IN ('queued', 'running')
  AND seq NOT IN (SELECT MIN(seq) FROM jobs WHERE status IN ('queued', 'running') GROUP BY spec_hash, solver_version);

CREATE UNIQUE INDEX jobs_in_flight ON jobs (spec_hash, solver_version) WHERE status IN ('queued', 'running');
