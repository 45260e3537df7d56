//! Discovery and operations: `/v1/kinds`, `/healthz`, `/readyz`, `/metrics`, `/openapi.json`.

use super::error::ApiResult;
use super::jobs::store_error;
use super::AppState;
use crate::jobs::registry;
use crate::metrics::StatusLabel;
use crate::problem::Problem;
use crate::store::JobStatus;
use axum::extract::State;
use axum::http::{header, StatusCode};
use axum::response::{IntoResponse, Response};
use axum::Json;
use serde::Serialize;
use serde_json::Value;
use utoipa::ToSchema;

/// An optional output of a kind.
#[derive(Debug, Serialize, ToSchema)]
pub struct OutputView {
    pub name: String,
    pub description: String,
}

/// A job kind: what it computes, an example spec, its optional outputs and tables.
#[derive(Debug, Serialize, ToSchema)]
pub struct KindView {
    pub name: String,
    pub description: String,
    pub solver_version: String,
    /// A valid spec to start from.
    #[schema(value_type = Object)]
    pub example: Value,
    /// Optional outputs, selected with the spec's `outputs` list.
    pub outputs: Vec<OutputView>,
    /// Result fields available as CSV (`Accept: text/csv`, `?table=`).
    pub tables: Vec<String>,
    /// OpenAPI schema of the spec.
    pub spec_schema: String,
    /// OpenAPI schema of the result.
    pub result_schema: String,
    /// The unit of every numeric result field: JSON pointer → unit (`1`: a pure number; `*`
    /// stands for any index of a row table; a column's unit is its values' unit). SI throughout,
    /// but angles in degrees (`°`), speeds in `rpm` and running times in hours (`h`) where the
    /// field name says so.
    pub result_units: std::collections::BTreeMap<String, String>,
    /// The figures an engineer checks first (JSON pointers into the result, most important
    /// first; a pointer may be absent from a result that did not compute it).
    pub key_figures: Vec<String>,
}

/// The kinds this server runs.
#[derive(Debug, Serialize, ToSchema)]
pub struct KindList {
    pub kinds: Vec<KindView>,
}

/// List job kinds.
///
/// Every kind with a description, an example spec (ready to POST), its optional outputs, its
/// CSV tables and the names of its spec and result schemas in this OpenAPI document.
#[utoipa::path(get, path = "/v1/kinds", tag = "kinds",
    responses((status = 200, description = "The job kinds", body = KindList)))]
pub async fn list_kinds() -> Json<KindList> {
    let kinds = registry::KINDS
        .iter()
        .map(|k| {
            let (spec, result) = k.schema_names();
            KindView {
                name: k.name().into(),
                description: k.description().into(),
                solver_version: k.solver_version().into(),
                example: k.example(),
                outputs: k.outputs().iter().map(|o| OutputView { name: o.name.into(), description: o.description.into() }).collect(),
                tables: k.tables().iter().map(|t| t.to_string()).collect(),
                spec_schema: format!("#/components/schemas/{spec}"),
                result_schema: format!("#/components/schemas/{result}"),
                result_units: k.result_units().clone(),
                key_figures: k.key_figures().iter().map(|p| p.to_string()).collect(),
            }
        })
        .collect();
    Json(KindList { kinds })
}

/// Liveness.
///
/// `200 ok` while the process serves HTTP.
#[utoipa::path(get, path = "/healthz", tag = "operations",
    responses((status = 200, description = "Alive", body = String, content_type = "text/plain")))]
pub async fn healthz() -> &'static str {
    "ok"
}

/// Readiness.
///
/// `200 ready` when the database can be read and a commit succeeds (one heartbeat row is rewritten
/// through the writer connection) and, with workers, the claim loop ran in the last 10 s; `503`
/// problem otherwise or when the service shuts down.
#[utoipa::path(get, path = "/readyz", tag = "operations",
    responses(
        (status = 200, description = "Ready", body = String, content_type = "text/plain"),
        (status = 503, description = "The database cannot be read or written (a commit of a heartbeat row failed), or the service is shutting down", body = Problem, content_type = "application/problem+json"),
    ))]
pub async fn readyz(State(state): State<AppState>) -> ApiResult<&'static str> {
    if !state.queue.is_accepting() {
        return Err(super::error::ApiError::new(crate::problem::ErrorCode::ShuttingDown, "the service is shutting down"));
    }
    state.queue.store().ping(crate::jobs::queue::now_ms()).await.map_err(store_error)?;
    if !state.queue.claim_loop_alive() {
        return Err(super::error::ApiError::new(
            crate::problem::ErrorCode::StorageUnavailable,
            "this instance's workers have not looked for jobs for over 10 s",
        ));
    }
    Ok("ready")
}

/// Prometheus metrics.
///
/// Text exposition format: jobs by status, queue depth, running jobs, solve-time histogram by
/// kind, submissions, reuses and HTTP requests.
#[utoipa::path(get, path = "/metrics", tag = "operations",
    responses((status = 200, description = "Metrics (OpenMetrics 1.0 text)", body = String, content_type = "application/openmetrics-text; version=1.0.0; charset=utf-8")))]
pub async fn metrics(State(state): State<AppState>) -> Response {
    let metrics = state.queue.metrics();
    if let Ok(counts) = state.queue.store().count_by_status().await {
        for status in JobStatus::ALL {
            let n = counts.iter().find(|(s, _)| *s == status).map(|(_, n)| *n).unwrap_or(0);
            metrics.jobs.get_or_create(&StatusLabel { status: status.as_str().into() }).set(n);
            if status == JobStatus::Queued {
                // The store's count: with a shared database, every instance's queue.
                metrics.queue_depth.set(n);
            }
        }
    }
    (
        StatusCode::OK,
        [(header::CONTENT_TYPE, "application/openmetrics-text; version=1.0.0; charset=utf-8")],
        metrics.encode(),
    )
        .into_response()
}

/// This OpenAPI document.
///
/// OpenAPI 3.1, generated from the code (the same as `tribod openapi`): every route, every kind's
/// spec and result schema with units.
#[utoipa::path(get, path = "/openapi.json", tag = "operations",
    responses((status = 200, description = "OpenAPI 3.1 document", body = Object)))]
pub async fn openapi_json(State(state): State<AppState>) -> Response {
    ([(header::CONTENT_TYPE, "application/json")], state.openapi.as_ref().clone()).into_response()
}
