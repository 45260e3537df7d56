//! `/v1/jobs`: submit, list, inspect, fetch results, cancel or delete.

use super::error::{ApiError, ApiResult};
use super::extract::{ApiJson, ApiQuery, JobIdPath};
use super::AppState;
use crate::jobs::idempotency::Replay;
use crate::jobs::queue::{Cancellation, Submitted};
use crate::jobs::{registry, table, Estimate};
use crate::problem::{ErrorCode, Problem};
use crate::store::{JobRow, JobStatus, ListFilter};
use axum::extract::State;
use axum::http::{header, HeaderMap, HeaderValue, StatusCode};
use axum::response::{IntoResponse, Response};
use axum::Json;
use serde::{Deserialize, Serialize};
use serde_json::Value;
use std::time::Duration;
use utoipa::{IntoParams, ToSchema};
use uuid::Uuid;

/// Body of `POST /v1/jobs`.
#[derive(Debug, Deserialize, Serialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct JobRequest {
    /// The job kind (see `GET /v1/kinds`).
    #[schema(example = "hertz")]
    pub kind: String,
    /// The kind's spec: one of the `*Spec` schemas, chosen by `kind`.
    #[schema(value_type = Object)]
    pub spec: Value,
    /// Free text to find the job again (at most 200 characters).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub label: Option<String>,
}

/// Progress of a running job.
#[derive(Debug, Serialize, ToSchema)]
pub struct Progress {
    /// Fraction done, 0–1.
    pub fraction: f64,
    /// What the solver is doing.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub stage: Option<String>,
}

/// Links of a job.
#[derive(Debug, Serialize, ToSchema)]
pub struct JobLinks {
    #[serde(rename = "self")]
    pub self_: String,
    pub result: String,
}

/// A job: its state, not its result (see `/v1/jobs/{id}/result`).
#[derive(Debug, Serialize, ToSchema)]
pub struct JobView {
    pub id: Uuid,
    pub kind: String,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub label: Option<String>,
    pub status: JobStatus,
    /// RFC 3339.
    pub created_at: String,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub started_at: Option<String>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub finished_at: Option<String>,
    /// Times a worker started this job (more than 1 after a restart interrupted it).
    pub attempts: i64,
    pub progress: Progress,
    /// A cancel was requested while the job was running.
    pub cancel_requested: bool,
    /// `true` when this answer is an earlier identical job returned instead of a new one.
    pub reused: bool,
    pub solver_version: String,
    /// sha256 of the kind and canonical spec: the dedup key.
    pub spec_hash: String,
    /// The canonical spec (defaults filled in); only on `GET /v1/jobs/{id}`.
    #[serde(skip_serializing_if = "Option::is_none")]
    #[schema(value_type = Option<Object>)]
    pub spec: Option<Value>,
    /// Why the job failed.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub error: Option<Problem>,
    /// Legal but implausible values of the spec (most often a unit slip: a radius of 25.5 m
    /// meant as mm), each at its JSON pointer. Shown with the spec (on `POST /v1/jobs` and
    /// `GET /v1/jobs/{id}`); `POST /v1/jobs?strict=true` refuses them instead.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub warnings: Vec<crate::problem::FieldError>,
    /// What the job was expected to cost when it was accepted (the work and memory models; a
    /// dashboard can say "about 40 s"). Absent for jobs stored before the models existed.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub estimate: Option<Estimate>,
    /// A job whose cases run as jobs of their own (a sweep above `--fan-out-min-case-seconds` per
    /// case; on every instance sharing the store): its cases counted by status. `progress.fraction` is the share finished.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub children: Option<crate::store::ChildCounts>,
    pub links: JobLinks,
}

/// The warnings of a stored spec, at pointers into the request body (`/spec/...`).
fn spec_warnings(kind: &str, spec: &Value) -> Vec<crate::problem::FieldError> {
    let Some(k) = registry::find(kind) else { return Vec::new() };
    k.warnings(spec).into_iter().map(|w| crate::problem::FieldError::new(format!("/spec{}", w.path), w.message)).collect()
}

/// A stored instant (unix ms) as RFC 3339 in UTC with always three fraction digits, so that the
/// times of one server sort as text too (the well-known format drops trailing zeros: "10.53Z"
/// would sort after "10.532Z").
pub fn rfc3339(ms: i64) -> String {
    const FORMAT: &[time::format_description::BorrowedFormatItem<'_>] =
        time::macros::format_description!("[year]-[month]-[day]T[hour]:[minute]:[second].[subsecond digits:3]Z");
    time::OffsetDateTime::from_unix_timestamp_nanos(ms as i128 * 1_000_000).ok().and_then(|t| t.format(FORMAT).ok()).unwrap_or_default()
}

impl JobView {
    pub fn from_row(row: JobRow, reused: bool) -> Self {
        let id = row.id;
        let spec: Option<Value> = row.spec.as_deref().and_then(|s| serde_json::from_str(s).ok());
        JobView {
            id,
            warnings: spec.as_ref().map(|s| spec_warnings(&row.kind, s)).unwrap_or_default(),
            kind: row.kind,
            label: row.label,
            status: row.status,
            created_at: rfc3339(row.created_at),
            started_at: row.started_at.map(rfc3339),
            finished_at: row.finished_at.map(rfc3339),
            attempts: row.attempts,
            progress: Progress { fraction: row.progress, stage: row.stage },
            cancel_requested: row.cancel_requested,
            reused,
            solver_version: row.solver_version,
            spec_hash: row.spec_hash,
            spec,
            error: row.error.and_then(|e| serde_json::from_str(&e).ok()),
            estimate: match (row.estimate_cpu_seconds, row.estimate_memory_bytes) {
                (Some(cpu_seconds), Some(memory_bytes)) => Some(Estimate { cpu_seconds, memory_bytes }),
                _ => None,
            },
            children: None,
            links: JobLinks { self_: format!("/v1/jobs/{id}"), result: format!("/v1/jobs/{id}/result") },
        }
    }
}

/// Query of `POST /v1/jobs`.
#[derive(Debug, Deserialize, IntoParams)]
#[into_params(parameter_in = Query)]
#[serde(deny_unknown_fields)]
pub struct SubmitQuery {
    /// Solve again even when an identical succeeded job exists.
    #[serde(default)]
    pub fresh: bool,
    /// Refuse a spec with warnings (legal but implausible values, see `JobView.warnings`) with
    /// `422 invalid_spec` instead of accepting it.
    #[serde(default)]
    pub strict: bool,
}

/// Seconds of `Prefer: wait=N` (RFC 7240), if present.
fn prefer_wait(headers: &HeaderMap) -> Option<f64> {
    headers.get_all("prefer").iter().filter_map(|v| v.to_str().ok()).flat_map(|v| v.split([',', ';'])).find_map(|p| {
        let (k, v) = p.trim().split_once('=')?;
        (k.trim().eq_ignore_ascii_case("wait")).then(|| v.trim().trim_matches('"').parse::<f64>().ok()).flatten()
    })
}

fn job_response(status: StatusCode, view: JobView, extra: Vec<(&'static str, String)>) -> Response {
    let location = view.links.self_.clone();
    let mut res = (status, Json(view)).into_response();
    if let Ok(v) = HeaderValue::from_str(&location) {
        res.headers_mut().insert(header::LOCATION, v);
    }
    for (name, value) in extra {
        if let Ok(v) = HeaderValue::from_str(&value) {
            res.headers_mut().insert(name, v);
        }
    }
    res
}

/// Submit a job.
///
/// Validates the spec against its kind, stores the job and queues it. Answers `202 Accepted` with
/// the job and its `Location`. With `Prefer: wait=N` the server waits up to N seconds (capped by
/// the server) and answers `200` with the finished job if it finishes in time. An identical spec
/// that already succeeded with the same solver version is answered at once with that job
/// (`200`, `reused: true`) unless `?fresh=true`; one that is queued or running (on any instance
/// sharing the database) is joined: the answer is that job (`202`, `reused: true`), one solve
/// serves both. Invalid specs get a `problem+json` naming each
/// offending field by JSON pointer; a full queue answers `503` with `Retry-After`.
///
/// A client that may retry (a lost answer, a timeout) sends an `Idempotency-Key`: the same key
/// with the same kind, spec and label answers the job that answered the first request — the job
/// it created, reused or joined — (`Idempotent-Replayed: true`), never a second job; the same key
/// with another request is refused (`422 idempotency_key_reused`). A key lives as long as its job:
/// once that (finished) job is deleted, the key is free again.
#[utoipa::path(post, path = "/v1/jobs", tag = "jobs",
    params(SubmitQuery,
        ("Prefer" = Option<String>, Header, description = "`wait=N`: wait up to N seconds for the job to finish (RFC 7240)"),
        ("Idempotency-Key" = Option<String>, Header, description = "Client-chosen key (1–255 visible ASCII characters) making retries of this POST safe", pattern = "^[!-~]{1,255}$")),
    request_body(content = JobRequest, description = "The job kind and its spec"),
    responses(
        (status = 202, description = "Accepted and queued", body = JobView, headers(("Location" = String, description = "URL of the job"))),
        (status = 200, description = "Finished within the wait, or reused", body = JobView),
        (status = 400, description = "Malformed JSON", body = Problem, content_type = "application/problem+json"),
        (status = 413, description = "Body too large", body = Problem, content_type = "application/problem+json"),
        (status = 422, description = "Unknown kind, invalid spec or over a server limit", body = Problem, content_type = "application/problem+json"),
        (status = 503, description = "Queue full or shutting down", body = Problem, content_type = "application/problem+json"),
    ))]
pub async fn submit_job(
    State(state): State<AppState>,
    ApiQuery(query): ApiQuery<SubmitQuery>,
    headers: HeaderMap,
    ApiJson(req): ApiJson<JobRequest>,
) -> ApiResult<Response> {
    if let Some(label) = &req.label {
        if label.chars().count() > 200 {
            let mut e = ApiError::new(ErrorCode::InvalidRequest, "label is longer than 200 characters");
            e.problem.errors = vec![crate::problem::FieldError::new("/label", "at most 200 characters")];
            return Err(e);
        }
    }
    let wait = prefer_wait(&headers);
    let key = idempotency_key(&headers)?;
    // `reused`: the job is another request's; `replayed`: the answer this key gave before.
    let (row, reused, replayed) = match state.queue.submit(&req.kind, &req.spec, req.label.clone(), query.fresh, query.strict, key).await? {
        Submitted::Reused(row) => return Ok(job_response(StatusCode::OK, JobView::from_row(row, true), Vec::new())),
        Submitted::Replayed(Replay { row, reused }) => (row, reused, true),
        Submitted::Joined(row) => (row, true, false),
        Submitted::Accepted(row) => (row, false, false),
    };
    let mut extra: Vec<_> = replayed.then(|| ("idempotent-replayed", "true".to_string())).into_iter().collect();
    let mut row = row;
    if let Some(secs) = wait.filter(|s| *s > 0.0 && !row.status.is_finished()) {
        let secs = secs.min(state.max_wait.as_secs_f64());
        let id = row.id;
        if let Some(waited) = state.queue.wait(id, Duration::from_secs_f64(secs)).await? {
            row = waited;
            extra.push(("preference-applied", format!("wait={}", secs.round() as u64)));
        }
    }
    let code = if row.status.is_finished() { StatusCode::OK } else { StatusCode::ACCEPTED };
    Ok(job_response(code, JobView::from_row(row, reused), extra))
}

/// The `Idempotency-Key` header: 1–255 visible ASCII characters.
fn idempotency_key(headers: &HeaderMap) -> ApiResult<Option<String>> {
    let Some(value) = headers.get("idempotency-key") else { return Ok(None) };
    let max = crate::jobs::queue::MAX_IDEMPOTENCY_KEY;
    match value.to_str() {
        Ok(k) if !k.is_empty() && k.len() <= max && k.bytes().all(|b| b.is_ascii_graphic()) => Ok(Some(k.to_string())),
        _ => {
            let mut e = ApiError::new(ErrorCode::InvalidRequest, "Idempotency-Key must be 1–255 visible ASCII characters");
            e.problem.errors = vec![crate::problem::FieldError::new("Idempotency-Key", format!("1–{max} visible ASCII characters"))];
            Err(e)
        }
    }
}

/// Query of `GET /v1/jobs`.
#[derive(Debug, Deserialize, IntoParams)]
#[into_params(parameter_in = Query)]
#[serde(deny_unknown_fields)]
pub struct ListQuery {
    /// Only jobs in these statuses (comma-separated, no spaces).
    #[param(example = "queued,running", pattern = "^(queued|running|succeeded|failed|canceled)(,(queued|running|succeeded|failed|canceled))*$")]
    pub status: Option<String>,
    /// Only jobs of this kind.
    pub kind: Option<String>,
    /// Only jobs created after this instant (RFC 3339).
    #[param(format = DateTime)]
    pub created_after: Option<String>,
    /// Only jobs created before this instant (RFC 3339).
    #[param(format = DateTime)]
    pub created_before: Option<String>,
    /// Page size, 1–500 (default 50).
    #[param(minimum = 1, maximum = 500)]
    pub limit: Option<u32>,
    /// Also list the case jobs of fanned-out sweeps (default `false`: hidden, so a 500-case sweep
    /// does not flood the list; its progress is the sweep's `children` counts). Jobs a sweep
    /// joined or reused but that were submitted on their own are always listed.
    pub cases: Option<bool>,
    /// Only the case jobs of this fanned-out job (the ones it created, joined or reused; implies
    /// `cases=true`). Empty for a job that did not fan out.
    pub parent: Option<Uuid>,
    /// Cursor: the `next` of the previous page (jobs older than this id). If that job was deleted
    /// meanwhile, the page resumes where it stood: at the creation instant its id (a UUIDv7)
    /// carries, jobs of that millisecond included (a job may appear on two pages, none is
    /// skipped). An id this server did not issue (not a UUIDv7) names no place: an empty last page.
    pub after: Option<Uuid>,
}

/// A page of jobs, newest first.
#[derive(Debug, Serialize, ToSchema)]
pub struct JobPage {
    pub jobs: Vec<JobView>,
    /// Pass as `after` for the next page; absent on the last page.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub next: Option<Uuid>,
}

fn parse_time(name: &str, s: &str) -> ApiResult<i64> {
    time::OffsetDateTime::parse(s, &time::format_description::well_known::Rfc3339)
        .map(|t| (t.unix_timestamp_nanos() / 1_000_000) as i64)
        .map_err(|e| {
            let mut err = ApiError::new(ErrorCode::InvalidQuery, format!("{name}: not an RFC 3339 instant ({e})"));
            err.problem.errors = vec![crate::problem::FieldError::new(format!("?{name}"), "must be RFC 3339, e.g. 2026-11-22T10:00:00Z")];
            err
        })
}

/// List jobs.
///
/// Newest first, filtered by status, kind and creation time, paged by a keyset cursor: pass the
/// `next` of one page as `after` to get the next.
#[utoipa::path(get, path = "/v1/jobs", tag = "jobs", params(ListQuery),
    responses(
        (status = 200, description = "A page of jobs", body = JobPage),
        (status = 400, description = "Invalid query", body = Problem, content_type = "application/problem+json"),
    ))]
pub async fn list_jobs(State(state): State<AppState>, ApiQuery(q): ApiQuery<ListQuery>) -> ApiResult<Json<JobPage>> {
    let mut filter = ListFilter { limit: q.limit.unwrap_or(50), ..Default::default() };
    if !(1..=500).contains(&filter.limit) {
        let mut err = ApiError::new(ErrorCode::InvalidQuery, "limit must be in [1, 500]");
        err.problem.errors = vec![crate::problem::FieldError::new("?limit", "must be in [1, 500]")];
        return Err(err);
    }
    if let Some(s) = &q.status {
        // Exactly the document's pattern: names separated by commas, nothing else.
        for name in s.split(',') {
            let st = JobStatus::parse(name).ok_or_else(|| {
                let mut err = ApiError::new(ErrorCode::InvalidQuery, format!("unknown status '{name}'"));
                err.problem.errors = vec![crate::problem::FieldError::new(
                    "?status",
                    "must be queued, running, succeeded, failed or canceled",
                )];
                err
            })?;
            filter.statuses.push(st);
        }
    }
    filter.kind = q.kind.clone();
    filter.cases = q.cases.unwrap_or(false);
    filter.parent = q.parent;
    filter.created_after = q.created_after.as_deref().map(|s| parse_time("created_after", s)).transpose()?;
    filter.created_before = q.created_before.as_deref().map(|s| parse_time("created_before", s)).transpose()?;
    if let Some(after) = q.after {
        match state.queue.store().seq_of(after).await.map_err(store_error)? {
            Some(seq) => filter.before_seq = Some(seq),
            // Deleted between pages: resume at its creation instant (`created_at` is taken just
            // before the id, so jobs created up to the id's millisecond are older or the same).
            None => match after.get_timestamp().filter(|_| after.get_version_num() == 7) {
                Some(t) => {
                    let (secs, nanos) = t.to_unix();
                    let until = (secs as i64).saturating_mul(1000).saturating_add(i64::from(nanos / 1_000_000)).saturating_add(1);
                    filter.created_before = Some(filter.created_before.map_or(until, |b| b.min(until)));
                }
                None => return Ok(Json(JobPage { jobs: Vec::new(), next: None })),
            },
        }
    }
    let limit = filter.limit as usize;
    filter.limit += 1;
    let mut rows = state.queue.store().list(&filter).await.map_err(store_error)?;
    let more = rows.len() > limit;
    rows.truncate(limit);
    let next = if more { rows.last().map(|r| r.id) } else { None };
    Ok(Json(JobPage { jobs: rows.into_iter().map(|r| JobView::from_row(r, false)).collect(), next }))
}

pub fn store_error(e: crate::store::StoreError) -> ApiError {
    tracing::warn!(error = %e, "storage error");
    ApiError::new(ErrorCode::StorageUnavailable, "the job store could not be reached; try again")
}

pub(super) fn not_found(id: Uuid) -> ApiError {
    ApiError::new(ErrorCode::JobNotFound, format!("no job with id {id}"))
}

/// Get a job.
///
/// Status, progress, timing, the canonical spec and, for a failed job, its problem.
#[utoipa::path(get, path = "/v1/jobs/{id}", tag = "jobs",
    params(("id" = Uuid, Path, description = "Job id")),
    responses(
        (status = 200, description = "The job", body = JobView),
        (status = 404, description = "No such job", body = Problem, content_type = "application/problem+json"),
    ))]
pub async fn get_job(State(state): State<AppState>, JobIdPath(id): JobIdPath) -> ApiResult<Json<JobView>> {
    let row = state.queue.store().get(id).await.map_err(store_error)?.ok_or_else(|| not_found(id))?;
    let mut view = JobView::from_row(row, false);
    view.children = children_of(&state.queue, &view).await?;
    Ok(Json(view))
}

/// The cases of a fanned-out job counted by status (only sweeps have any).
pub async fn children_of(queue: &crate::jobs::queue::Queue, view: &JobView) -> ApiResult<Option<crate::store::ChildCounts>> {
    if view.kind != "sweep" {
        return Ok(None);
    }
    queue.store().child_counts(view.id).await.map_err(store_error)
}

/// A job's stored result (JSON text) with its row; 404 for no job, 409 while it runs or when it
/// has none.
pub(super) async fn stored_result(state: &AppState, id: Uuid) -> ApiResult<(JobRow, String)> {
    let store = state.queue.store();
    let row = store.get(id).await.map_err(store_error)?.ok_or_else(|| not_found(id))?;
    match row.status {
        JobStatus::Queued | JobStatus::Running => {
            return Err(ApiError::new(
                ErrorCode::ResultNotReady,
                format!("the job is {} ({:.0} % done); poll /v1/jobs/{id} or submit with Prefer: wait=N", row.status.as_str(), row.progress * 100.0),
            ));
        }
        JobStatus::Failed => {
            let why = row.error.and_then(|e| serde_json::from_str::<Problem>(&e).ok()).map(|p| p.to_string()).unwrap_or_default();
            return Err(ApiError::new(ErrorCode::ResultUnavailable, format!("the job failed: {why}")));
        }
        JobStatus::Canceled => {
            return Err(ApiError::new(ErrorCode::ResultUnavailable, "the job was canceled"));
        }
        JobStatus::Succeeded => {}
    }
    let Some(text) = store.result(id).await.map_err(store_error)? else {
        // Deleted between the two reads (a concurrent DELETE): no such job any more.
        if store.get(id).await.map_err(store_error)?.is_none() {
            return Err(not_found(id));
        }
        return Err(ApiError::new(ErrorCode::InternalError, "the job succeeded but its result is missing"));
    };
    Ok((row, text))
}

/// Query of `GET /v1/jobs/{id}/result`.
#[derive(Debug, Deserialize, IntoParams)]
#[into_params(parameter_in = Query)]
#[serde(deny_unknown_fields)]
pub struct ResultQuery {
    /// `json` (default) or `csv`; same as `Accept: text/csv`.
    #[param(pattern = "^(json|csv)$")]
    pub format: Option<String>,
    /// For CSV: which table of the result (see the kind's `tables` in `/v1/kinds`); default the
    /// first. One of the kinds' table names; a name this job's result lacks (another kind's, or
    /// an output its spec did not request) answers `404 table_not_found`.
    pub table: Option<String>,
}

/// Get a job's result.
///
/// JSON by default: the kind's result object plus `meta` (kind, solver version, wall time).
/// With `Accept: text/csv` (or `?format=csv`) a tabular part of the result as CSV (`?table=`
/// picks which; `404 table_not_found` when this job's result has no such table).
/// `409 result_not_ready` while the job is queued or running; `409 result_unavailable` when it
/// failed or was canceled.
#[utoipa::path(get, path = "/v1/jobs/{id}/result", tag = "jobs",
    params(("id" = Uuid, Path, description = "Job id"), ResultQuery),
    responses(
        (status = 200, description = "The result", content(
            (Object = "application/json"),
            (String = "text/csv"),
        )),
        (status = 404, description = "No such job (`job_not_found`), or its result has no such table (`table_not_found`)", body = Problem, content_type = "application/problem+json"),
        (status = 406, description = "The Accept header asks for CSV and the result has no table", body = Problem, content_type = "application/problem+json"),
        (status = 409, description = "Not ready, or the job has no result", body = Problem, content_type = "application/problem+json"),
    ))]
pub async fn get_result(
    State(state): State<AppState>,
    JobIdPath(id): JobIdPath,
    headers: HeaderMap,
    ApiQuery(q): ApiQuery<ResultQuery>,
) -> ApiResult<Response> {
    let (row, text) = stored_result(&state, id).await?;
    let tables = registry::find(&row.kind).map(|k| k.tables()).unwrap_or(&[]);
    if let Some(t) = q.table.as_deref().filter(|t| !tables.contains(t) && !registry::KINDS.iter().any(|k| k.tables().contains(t))) {
        let mut err = ApiError::new(ErrorCode::InvalidQuery, format!("no kind has a table '{t}'; this job's: {}", tables.join(", ")));
        err.problem.errors = vec![crate::problem::FieldError::new("?table", "must be one of the kinds' table names (GET /v1/kinds)")];
        return Err(err);
    }
    let accept = headers.get(header::ACCEPT).and_then(|v| v.to_str().ok()).unwrap_or("");
    let wants_csv = match q.format.as_deref() {
        Some("csv") => true,
        Some("json") | None => q.format.is_none() && accept.contains("text/csv") && !accept.contains("application/json"),
        Some(other) => {
            let mut err = ApiError::new(ErrorCode::InvalidQuery, format!("unknown format '{other}'"));
            err.problem.errors = vec![crate::problem::FieldError::new("?format", "must be json or csv")];
            return Err(err);
        }
    };
    if !wants_csv {
        return Ok(([(header::CONTENT_TYPE, "application/json")], text).into_response());
    }
    // No table for the CSV asked for: by the query (`format`, `table`: a URL naming no part of
    // this result), 404; by the Accept header alone (content negotiation), 406.
    let by_query = q.format.is_some() || q.table.is_some();
    let missing = |detail: String| ApiError::new(if by_query { ErrorCode::TableNotFound } else { ErrorCode::NotAcceptable }, detail);
    let name = match &q.table {
        Some(t) if tables.contains(&t.as_str()) => t.as_str(),
        // Another kind's table (names no kind has were refused above): the query is well
        // formed, this job has none of it.
        Some(t) => {
            return Err(ApiError::new(
                ErrorCode::TableNotFound,
                format!("kind '{}' has no table '{t}'; its tables: {}", row.kind, tables.join(", ")),
            ))
        }
        None => *tables.first().ok_or_else(|| missing(format!("kind '{}' has no tabular result; ask for JSON", row.kind)))?,
    };
    let value: Value = serde_json::from_str(&text).map_err(|e| ApiError::new(ErrorCode::InternalError, e.to_string()))?;
    let Some(part) = value.get(name) else {
        return Err(missing(format!("this result has no '{name}' (not requested in the spec's outputs?)")));
    };
    let unit = table::units_of(registry::find(&row.kind), &value, name);
    let csv = table::to_csv(part, &*unit).map_err(|e| ApiError::new(ErrorCode::InternalError, e))?;
    Ok(([(header::CONTENT_TYPE, "text/csv; charset=utf-8")], csv).into_response())
}

/// Cancel or delete a job.
///
/// A queued job is canceled at once (`200`, the canceled job). A running job is asked to stop
/// (`202`, the job with `cancel_requested`); its solver stops within one iteration step. A
/// finished job is deleted with its result (`204`). Deleting is idempotent: an unknown id also
/// answers `204`.
#[utoipa::path(delete, path = "/v1/jobs/{id}", tag = "jobs",
    params(("id" = Uuid, Path, description = "Job id")),
    responses(
        (status = 200, description = "Canceled (was queued)", body = JobView),
        (status = 202, description = "Cancel requested (running)", body = JobView),
        (status = 204, description = "Deleted, or never existed"),
    ))]
pub async fn delete_job(State(state): State<AppState>, JobIdPath(id): JobIdPath) -> ApiResult<Response> {
    Ok(match state.queue.cancel(id).await? {
        Cancellation::Canceled(row) => (StatusCode::OK, Json(JobView::from_row(row, false))).into_response(),
        Cancellation::Requested(row) => (StatusCode::ACCEPTED, Json(JobView::from_row(row, false))).into_response(),
        Cancellation::Deleted => StatusCode::NO_CONTENT.into_response(),
    })
}
