//! `Idempotency-Key`s of `POST /v1/jobs` (issue 40).
//!
//! A key is recorded with the job that answered the first request carrying it, whatever that
//! answer was — a new job, an identical finished job reused, or an identical queued or running job
//! joined — together with that request's spec hash and label (the store's `idempotency_keys`).
//! A repeat of the same request under the key is answered that job again ([`Verdict::Replay`]);
//! another request under it is refused `422 idempotency_key_reused`. The key of a new job is
//! written in the transaction that inserts the job; the key of a reused or joined job by a
//! conditional insert, which loses to a concurrent request that recorded the key first (whose
//! record then answers both).
//!
//! A key lives as long as its job: `DELETE` of the (finished) job deletes the key with it, and the
//! key may then be used afresh. A record outliving its job would replay an answer nobody can fetch.

use crate::problem::{ErrorCode, FieldError, Problem};
use crate::store::{IdempotencyKey, JobRow, Store, StoreResult};

/// A request that carries an `Idempotency-Key`: the key and what identifies the request.
#[derive(Debug, Clone)]
pub struct Keyed {
    pub key: String,
    pub spec_hash: String,
    pub label: Option<String>,
}

/// An earlier answer given again: the job, and whether it was another request's (reused or
/// joined) rather than created by the key's first request.
#[derive(Debug)]
pub struct Replay {
    pub row: JobRow,
    pub reused: bool,
}

/// What a key says about a request.
#[derive(Debug)]
pub enum Verdict {
    /// Nothing is recorded under the key (or its job was deleted meanwhile).
    Unused,
    /// The key now answers the job it was to be recorded for.
    Recorded,
    /// An earlier identical request holds the key: its answer.
    Replay(Replay),
    /// An earlier different request holds the key.
    Refused(Problem),
}

impl Verdict {
    /// The earlier answer to give again, a refusal, or nothing (the request goes on).
    pub fn into_replay(self) -> Result<Option<Replay>, Problem> {
        match self {
            Verdict::Replay(replay) => Ok(Some(replay)),
            Verdict::Refused(problem) => Err(problem),
            Verdict::Unused | Verdict::Recorded => Ok(None),
        }
    }
}

/// The verdict on `request` from the key's record, if any.
pub async fn look_up(store: &Store, request: &Keyed) -> StoreResult<Verdict> {
    match store.find_idempotency_key(&request.key).await? {
        Some(record) => judge(store, request, record).await,
        None => Ok(Verdict::Unused),
    }
}

/// Record `request`'s key for `job`, an identical job it reused or joined: [`Verdict::Recorded`]
/// when the key now answers `job`, else the verdict of the record a concurrent request stored
/// first ([`Verdict::Unused`]: `job` was deleted meanwhile and nothing was recorded).
pub async fn attach(store: &Store, request: &Keyed, job: &JobRow, now: i64) -> StoreResult<Verdict> {
    let record = IdempotencyKey {
        key: request.key.clone(),
        job_id: job.id,
        spec_hash: request.spec_hash.clone(),
        label: request.label.clone(),
        reused: true,
        created_at: now,
    };
    match store.record_idempotency_key(&record).await? {
        Some(stored) if stored.job_id == job.id && same_request(request, &stored) => Ok(Verdict::Recorded),
        Some(stored) => judge(store, request, stored).await,
        None => Ok(Verdict::Unused),
    }
}

fn same_request(request: &Keyed, record: &IdempotencyKey) -> bool {
    record.spec_hash == request.spec_hash && record.label == request.label
}

async fn judge(store: &Store, request: &Keyed, record: IdempotencyKey) -> StoreResult<Verdict> {
    if !same_request(request, &record) {
        return Ok(Verdict::Refused(
            Problem::new(
                ErrorCode::IdempotencyKeyReused,
                format!("this Idempotency-Key was used for job {} with another kind, spec or label", record.job_id),
            )
            .with_errors(vec![FieldError::new("/", "differs from the request first sent with this Idempotency-Key")]),
        ));
    }
    Ok(match store.get(record.job_id).await? {
        Some(row) => Verdict::Replay(Replay { row, reused: record.reused }),
        // Deleted since the record was read: the key went with it.
        None => Verdict::Unused,
    })
}
