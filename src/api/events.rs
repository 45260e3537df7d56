//! `GET /v1/jobs/{id}/events`: a job followed live as Server-Sent Events, so a dashboard needs no
//! polling of its own.
//!
//! The stream samples the stored job at most four times a second and sends an event only when
//! something changed: `status` (the first event, and each status change), `progress` (fraction or
//! stage), and last `done` with the finished job, after which the stream ends. Each event's data
//! is the job as `GET /v1/jobs/{id}` shows it. The stream is pulled by the client's reads: a slow
//! client gets the newest state when it reads again (nothing queues up), and no worker waits for it.

use super::error::ApiResult;
use super::extract::JobIdPath;
use super::jobs::{not_found, store_error, JobView};
use super::AppState;
use crate::jobs::queue::Queue;
use crate::problem::Problem;
use crate::store::JobStatus;
use axum::extract::State;
use axum::response::sse::{Event, KeepAlive, Sse};
use axum::response::{IntoResponse, Response};
use std::convert::Infallible;
use std::time::Duration;
use uuid::Uuid;

/// How often a stream looks at the job.
const SAMPLE_EVERY: Duration = Duration::from_millis(250);

/// Follow a job live (Server-Sent Events).
///
/// Events: `status` first and at every status change, `progress` when the fraction or stage
/// changes (sampled at most 4 times a second), and a last `done` carrying the finished job, after
/// which the stream ends (`deleted` if the job is deleted meanwhile; `shutdown` if the server
/// stops). Each event's `data` is the job as `GET /v1/jobs/{id}` returns it, without its spec.
#[utoipa::path(get, path = "/v1/jobs/{id}/events", tag = "jobs",
    params(("id" = Uuid, Path, description = "Job id")),
    responses(
        (status = 200, description = "Server-Sent Events until the job ends", body = String, content_type = "text/event-stream"),
        (status = 404, description = "No such job", body = Problem, content_type = "application/problem+json"),
    ))]
pub async fn job_events(State(state): State<AppState>, JobIdPath(id): JobIdPath) -> ApiResult<Response> {
    state.queue.store().get(id).await.map_err(store_error)?.ok_or_else(|| not_found(id))?;
    let follow = Follow { queue: state.queue.clone(), id, last: None, ended: false };
    let stream = futures_util::stream::unfold(follow, |mut f| async move {
        let event = f.next().await?;
        Some((Ok::<_, Infallible>(event), f))
    });
    Ok(Sse::new(stream).keep_alive(KeepAlive::default()).into_response())
}

/// The state of one stream: what it last sent.
struct Follow {
    queue: Queue,
    id: Uuid,
    last: Option<(JobStatus, f64, Option<String>)>,
    ended: bool,
}

impl Follow {
    /// The next event, waiting until something changed; `None` after the last one.
    async fn next(&mut self) -> Option<Event> {
        if self.ended {
            return None;
        }
        loop {
            if !self.queue.is_accepting() {
                self.ended = true;
                return Some(Event::default().event("shutdown").data("the server is shutting down; reconnect later"));
            }
            match self.queue.store().get(self.id).await {
                Ok(None) => {
                    self.ended = true;
                    return Some(Event::default().event("deleted").data(self.id.to_string()));
                }
                Ok(Some(row)) => {
                    let now = (row.status, row.progress, row.stage.clone());
                    if self.last.as_ref() != Some(&now) {
                        let name = if row.status.is_finished() {
                            self.ended = true;
                            "done"
                        } else if self.last.as_ref().map(|l| l.0) != Some(row.status) {
                            "status"
                        } else {
                            "progress"
                        };
                        self.last = Some(now);
                        let mut view = JobView::from_row(row, false);
                        view.children = super::jobs::children_of(&self.queue, &view).await.unwrap_or_default();
                        let data = serde_json::to_string(&view).unwrap_or_default();
                        return Some(Event::default().event(name).data(data));
                    }
                }
                // A store hiccup: keep the stream and look again.
                Err(e) => tracing::debug!(error = %e, "job events: reading the job failed"),
            }
            tokio::time::sleep(SAMPLE_EVERY).await;
        }
    }
}
