//! The HTTP API: `fn app(state) -> Router`, so tests and the server build the same thing.

pub mod error;
mod deadline;
mod document;
mod events;
mod plots;
mod extract;
pub mod jobs;
pub mod meta;

use crate::jobs::queue::Queue;
use crate::jobs::registry;
use crate::problem::{ErrorCode, Problem};
use axum::extract::{DefaultBodyLimit, Request, State};
use axum::http::{header, HeaderValue, Method};
use axum::middleware::{self, Next};
use axum::response::{IntoResponse, Response};
use error::ApiError;
use std::sync::Arc;
use std::time::Duration;
use tower_http::cors::{AllowOrigin, Any, CorsLayer};
use tower_http::trace::{DefaultOnResponse, TraceLayer};
use utoipa::OpenApi;
use utoipa_axum::router::OpenApiRouter;
use utoipa_axum::routes;

/// Settings of the HTTP layer.
#[derive(Debug, Clone)]
pub struct ApiConfig {
    /// Bearer tokens; empty = no authentication.
    pub tokens: Vec<String>,
    /// Allowed CORS origins; `["*"]` = any; empty = no CORS headers.
    pub cors_origins: Vec<String>,
    /// Largest request body, bytes.
    pub body_limit: usize,
    /// Cap on `Prefer: wait=N`.
    pub max_wait: Duration,
    /// Longest time a request body may take to arrive, counted from its headers (a total
    /// deadline: slow senders are answered `408 request_timeout` and disconnected).
    pub body_timeout: Duration,
}

impl Default for ApiConfig {
    fn default() -> Self {
        ApiConfig {
            tokens: Vec::new(),
            cors_origins: Vec::new(),
            body_limit: 1 << 20,
            max_wait: Duration::from_secs(300),
            body_timeout: Duration::from_secs(30),
        }
    }
}

/// What every handler sees.
#[derive(Clone)]
pub struct AppState {
    pub queue: Queue,
    pub tokens: Arc<Vec<String>>,
    pub max_wait: Duration,
    pub openapi: Arc<String>,
}

#[derive(OpenApi)]
#[openapi(
    info(
        title = "tribod",
        description = "Calculation service for valve-train and bearing tribology. Submit a job \
            (`POST /v1/jobs` with a kind and its spec), follow it (`GET /v1/jobs/{id}`, or \
            `Prefer: wait=N`) and fetch its result as JSON or CSV. SI units throughout unless a \
            field's name says otherwise (`speed_rpm`, `angle_deg`). Errors are RFC 9457 \
            `application/problem+json` with a stable `code` and the JSON pointer of each \
            offending field.",
        license(name = "MIT OR Apache-2.0"),
    ),
    tags(
        (name = "jobs", description = "Submit, follow, fetch and cancel calculations"),
        (name = "kinds", description = "What the service can compute"),
        (name = "operations", description = "Health, readiness, metrics and this document"),
    ),
    components(schemas(crate::problem::Problem, crate::problem::FieldError, crate::jobs::schemas::ConvergenceDoc, crate::jobs::schemas::TerminationDoc)),
    modifiers(&BearerScheme),
)]
struct ApiDoc;

struct BearerScheme;

impl utoipa::Modify for BearerScheme {
    fn modify(&self, openapi: &mut utoipa::openapi::OpenApi) {
        use utoipa::openapi::security::{HttpAuthScheme, HttpBuilder, SecurityScheme};
        if let Some(components) = openapi.components.as_mut() {
            components.add_security_scheme(
                "bearer",
                SecurityScheme::Http(
                    HttpBuilder::new()
                        .scheme(HttpAuthScheme::Bearer)
                        .description(Some("Needed on /v1 routes when the server runs with --api-token"))
                        .build(),
                ),
            );
        }
    }
}

fn routers() -> (OpenApiRouter<AppState>, OpenApiRouter<AppState>) {
    let v1 = OpenApiRouter::new()
        .routes(routes!(jobs::submit_job, jobs::list_jobs))
        .routes(routes!(jobs::get_job, jobs::delete_job))
        .routes(routes!(jobs::get_result))
        .routes(routes!(events::job_events))
        .routes(routes!(plots::list_plots))
        .routes(routes!(plots::get_plot))
        .routes(routes!(meta::list_kinds));
    let open = OpenApiRouter::new()
        .routes(routes!(meta::healthz))
        .routes(routes!(meta::readyz))
        .routes(routes!(meta::metrics))
        .routes(routes!(meta::openapi_json));
    (v1, open)
}

pub use document::{spec_array_schema, spec_field_schema};

/// The OpenAPI document the server serves (and `tribod openapi` prints).
pub fn openapi() -> serde_json::Value {
    let (v1, open) = routers();
    let mut doc = OpenApiRouter::<AppState>::with_openapi(ApiDoc::openapi()).merge(v1).merge(open).into_openapi();
    // The kinds' spec and result schemas, and `JobRequest.spec` as one of the specs.
    let mut schemas = Vec::new();
    for k in registry::KINDS.iter() {
        k.schemas(&mut schemas);
    }
    let components = doc.components.get_or_insert_with(Default::default);
    for (name, schema) in schemas {
        components.schemas.entry(name).or_insert(schema);
    }
    for path in doc.paths.paths.values_mut() {
        for op in [&mut path.get, &mut path.post, &mut path.delete].into_iter().flatten() {
            if op.tags.as_ref().is_some_and(|t| t.iter().any(|t| t == "jobs" || t == "kinds")) {
                let req = utoipa::openapi::security::SecurityRequirement::new::<_, _, &str>("bearer", []);
                op.security = Some(vec![req, Default::default()]);
            }
        }
    }
    document::finish(serde_json::to_value(&doc).unwrap_or_default())
}

/// The whole application.
pub fn app(queue: Queue, config: &ApiConfig) -> axum::Router {
    let openapi = serde_json::to_string_pretty(&openapi()).unwrap_or_default();
    let state = AppState {
        queue,
        tokens: Arc::new(config.tokens.clone()),
        max_wait: config.max_wait,
        openapi: Arc::new(openapi),
    };
    let body_timeout = config.body_timeout;
    let (v1, open) = routers();
    let (router, _) = OpenApiRouter::new().merge(v1).merge(open).split_for_parts();
    let mut router = router
        .merge(crate::web::routes())
        .fallback(|| async { ApiError::new(ErrorCode::RouteNotFound, "no such route; see /openapi.json") })
        .method_not_allowed_fallback(|| async {
            ApiError::new(ErrorCode::MethodNotAllowed, "this route does not answer that method; see /openapi.json")
        })
        .layer(DefaultBodyLimit::max(config.body_limit))
        .layer(tower::util::MapRequestLayer::new(move |req| deadline::limit(req, body_timeout)))
        .layer(middleware::from_fn(refuse_unacceptable))
        // Outside the routing: an unknown /v1 route or method is also refused without a token.
        .layer(middleware::from_fn_with_state(state.clone(), require_token))
        .layer(middleware::from_fn_with_state(state.clone(), count_requests))
        .layer(
            // One span per request (method and path only: headers, and so tokens, are never logged).
            TraceLayer::new_for_http()
                .make_span_with(|req: &Request| {
                    tracing::info_span!("request", method = %req.method(), path = %req.uri().path())
                })
                .on_response(DefaultOnResponse::new().level(tracing::Level::INFO)),
        )
        .with_state(state);
    if let Some(cors) = cors_layer(&config.cors_origins) {
        router = router.layer(cors);
    }
    router
}

/// The operations routes alone (`/healthz`, `/readyz`, `/metrics`), for a `tribod worker`'s
/// health port: probes and scrapes of a compute node that serves no API.
pub fn operations_app(queue: Queue) -> axum::Router {
    let state = AppState {
        queue,
        tokens: Arc::new(Vec::new()),
        max_wait: std::time::Duration::ZERO,
        openapi: Arc::new(String::new()),
    };
    axum::Router::new()
        .route("/healthz", axum::routing::get(meta::healthz))
        .route("/readyz", axum::routing::get(meta::readyz))
        .route("/metrics", axum::routing::get(meta::metrics))
        .fallback(|| async { ApiError::new(ErrorCode::RouteNotFound, "a worker serves /healthz, /readyz and /metrics only") })
        .with_state(state)
}

fn cors_layer(origins: &[String]) -> Option<CorsLayer> {
    if origins.is_empty() {
        return None;
    }
    let layer = CorsLayer::new()
        .allow_methods([Method::GET, Method::POST, Method::DELETE, Method::OPTIONS])
        .allow_headers([header::CONTENT_TYPE, header::AUTHORIZATION, header::ACCEPT, "prefer".parse().expect("header name"), "idempotency-key".parse().expect("header name")])
        .expose_headers([header::LOCATION, header::RETRY_AFTER, "preference-applied".parse().expect("header name"), "idempotent-replayed".parse().expect("header name")]);
    Some(if origins.iter().any(|o| o == "*") {
        layer.allow_origin(Any)
    } else {
        let list: Vec<HeaderValue> = origins.iter().filter_map(|o| HeaderValue::from_str(o).ok()).collect();
        layer.allow_origin(AllowOrigin::list(list))
    })
}

/// Constant-time comparison, so response timing does not reveal a token's prefix.
fn token_matches(given: &[u8], expected: &[u8]) -> bool {
    let mut diff = given.len() ^ expected.len();
    for (i, b) in expected.iter().enumerate() {
        diff |= (given.get(i).copied().unwrap_or(0) ^ b) as usize;
    }
    diff == 0
}

/// Content negotiation for reads: a `GET` whose `Accept` header excludes the media type of the
/// answer gets `406 not_acceptable` instead (reads have no effects, so the answer can be
/// dropped). Routes with several representations (the result's JSON or CSV) choose among them
/// before this check.
async fn refuse_unacceptable(req: Request, next: Next) -> Response {
    let accept = req.headers().get(header::ACCEPT).and_then(|v| v.to_str().ok()).map(str::to_owned);
    let read = req.method() == Method::GET || req.method() == Method::HEAD;
    let res = next.run(req).await;
    let (Some(accept), true, true) = (accept, read, res.status().is_success()) else { return res };
    let produced = res
        .headers()
        .get(header::CONTENT_TYPE)
        .and_then(|v| v.to_str().ok())
        .and_then(|v| v.split(';').next())
        .map(|v| v.trim().to_ascii_lowercase())
        .unwrap_or_default();
    if produced.is_empty() || accepts(&accept, &produced) {
        return res;
    }
    ApiError::new(
        ErrorCode::NotAcceptable,
        format!("this resource is available as {produced}; the request accepts only '{accept}'"),
    )
    .into_response()
}

/// Does an `Accept` header admit `media` (`type/subtype`)? Ranges with `q=0` exclude.
fn accepts(accept: &str, media: &str) -> bool {
    let (ty, _) = media.split_once('/').unwrap_or((media, ""));
    accept.split(',').any(|range| {
        let mut parts = range.split(';').map(str::trim);
        let r = parts.next().unwrap_or("").to_ascii_lowercase();
        let refused = parts.any(|p| p.replace(' ', "").eq_ignore_ascii_case("q=0") || p.replace(' ', "") == "q=0.0");
        !refused && (r == "*/*" || r == media || r.strip_suffix("/*") == Some(ty))
    })
}

/// Bearer check of every path under `/v1` (routes or not); other paths are open.
async fn require_token(State(state): State<AppState>, req: Request, next: Next) -> Response {
    let path = req.uri().path();
    let protected = path == "/v1" || path.starts_with("/v1/");
    if !protected || state.tokens.is_empty() || req.method() == Method::OPTIONS {
        return next.run(req).await;
    }
    let given = req
        .headers()
        .get(header::AUTHORIZATION)
        .and_then(|v| v.to_str().ok())
        .and_then(|v| v.strip_prefix("Bearer ").or_else(|| v.strip_prefix("bearer ")))
        .map(str::trim);
    let ok = given.is_some_and(|g| state.tokens.iter().fold(false, |acc, t| acc | token_matches(g.as_bytes(), t.as_bytes())));
    if ok {
        next.run(req).await
    } else {
        ApiError::from(Problem::new(
            ErrorCode::Unauthorized,
            "this server needs `Authorization: Bearer <token>` on /v1 routes",
        ))
        .into_response()
    }
}

async fn count_requests(State(state): State<AppState>, req: Request, next: Next) -> Response {
    let method = req.method().to_string();
    let res = next.run(req).await;
    state
        .queue
        .metrics()
        .http_requests
        .get_or_create(&crate::metrics::HttpLabel { method, status: res.status().as_u16() })
        .inc();
    res
}
