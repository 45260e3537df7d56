//! `GET /v1/jobs/{id}/plots` and `GET /v1/jobs/{id}/plots/{name}`: the plots of a finished job,
//! drawn from its stored result when asked for (nothing is drawn for a job nobody looks at).

use super::error::{ApiError, ApiResult};
use super::jobs::stored_result;
use super::AppState;
use crate::problem::{ErrorCode, Problem};
use axum::extract::{Path, State};
use axum::http::header;
use axum::response::{IntoResponse, Response};
use axum::Json;
use serde::Serialize;
use utoipa::ToSchema;
use uuid::Uuid;

/// One plot of a job.
#[derive(Debug, Serialize, ToSchema)]
pub struct PlotLink {
    /// Name in `/v1/jobs/{id}/plots/{name}`.
    pub name: String,
    pub title: String,
    /// Where the SVG is.
    pub href: String,
}

/// The plots of a job.
#[derive(Debug, Serialize, ToSchema)]
pub struct PlotList {
    pub plots: Vec<PlotLink>,
}

fn job_id(raw: &str) -> ApiResult<Uuid> {
    Uuid::parse_str(raw).map_err(|_| ApiError::new(ErrorCode::JobNotFound, format!("'{raw}' is not a job id (a UUID)")))
}

/// List a job's plots.
///
/// The plots its kind draws that its result has data for (none for kinds without plots yet).
/// 409 while the job runs or when it has no result.
#[utoipa::path(get, path = "/v1/jobs/{id}/plots", tag = "jobs",
    params(("id" = Uuid, Path, description = "Job id")),
    responses(
        (status = 200, description = "The plots", body = PlotList),
        (status = 404, description = "No such job", body = Problem, content_type = "application/problem+json"),
        (status = 409, description = "Not ready, or the job has no result", body = Problem, content_type = "application/problem+json"),
    ))]
pub async fn list_plots(State(state): State<AppState>, Path(id): Path<String>) -> ApiResult<Json<PlotList>> {
    let id = job_id(&id)?;
    let (row, text) = stored_result(&state, id).await?;
    // Parsing a large result (a bearing with its fields: 4 MB, ~12 ms) is CPU work: off the
    // async threads, as drawing is.
    let plots = tokio::task::spawn_blocking(move || {
        let result: serde_json::Value = serde_json::from_str(&text)
            .map_err(|e| ApiError::new(ErrorCode::InternalError, format!("the stored result is not JSON: {e}")))?;
        Ok::<_, ApiError>(crate::plots::available(&row.kind, &result))
    })
    .await
    .map_err(|e| ApiError::new(ErrorCode::InternalError, format!("listing stopped: {e}")))??;
    let plots = plots
        .into_iter()
        .map(|p| PlotLink { href: format!("/v1/jobs/{id}/plots/{}", p.name), name: p.name, title: p.title })
        .collect();
    Ok(Json(PlotList { plots }))
}

/// Get one plot of a job (SVG).
///
/// Drawn from the stored result: axes with units, a title saying what was run.
#[utoipa::path(get, path = "/v1/jobs/{id}/plots/{name}", tag = "jobs",
    params(("id" = Uuid, Path, description = "Job id"), ("name" = String, Path, description = "Plot name from the list")),
    responses(
        (status = 200, description = "The plot", body = String, content_type = "image/svg+xml"),
        (status = 404, description = "No such job or plot", body = Problem, content_type = "application/problem+json"),
        (status = 409, description = "Not ready, or the job has no result", body = Problem, content_type = "application/problem+json"),
    ))]
pub async fn get_plot(State(state): State<AppState>, Path((id, name)): Path<(String, String)>) -> ApiResult<Response> {
    let id = job_id(&id)?;
    let (row, text) = stored_result(&state, id).await?;
    let kind = row.kind.clone();
    let subtitle = row.label.clone().unwrap_or_else(|| format!("{kind} job {}", &id.to_string()[..8]));
    // Drawing is CPU work: off the async threads.
    let svg = tokio::task::spawn_blocking(move || {
        let result: serde_json::Value = serde_json::from_str(&text).unwrap_or_default();
        crate::plots::render(&kind, &result, &name, &subtitle)
    })
    .await
    .map_err(|e| ApiError::new(ErrorCode::InternalError, format!("drawing stopped: {e}")))?
    .map_err(|e| match e {
        crate::plots::PlotError::Unknown(_) => ApiError::new(ErrorCode::PlotNotFound, e.to_string()),
        crate::plots::PlotError::Drawing(_) => ApiError::new(ErrorCode::InternalError, e.to_string()),
    })?;
    Ok(([(header::CONTENT_TYPE, "image/svg+xml")], svg).into_response())
}
