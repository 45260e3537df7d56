-- Issue 40: the work and memory models' estimate of each job (as migrations/sqlite/0005).
ALTER TABLE jobs ADD COLUMN estimate_cpu_seconds DOUBLE PRECISION;
ALTER TABLE jobs ADD COLUMN estimate_memory_bytes DOUBLE PRECISION;
