//! RFC 9457 problem details: the one error object of the service. HTTP answers, failed jobs and
//! `tribod run` all report failures as a [`Problem`]; its `code` comes from one table
//! ([`ErrorCode`]), or from a solver's physical-failure code (see [`Problem::from_solve_error`]).

use serde::{Deserialize, Serialize};
use utoipa::ToSchema;

/// One offending field: a JSON pointer into the request body and the rule it broke.
#[derive(Debug, Clone, PartialEq, Eq, Serialize, Deserialize, ToSchema)]
pub struct FieldError {
    /// JSON pointer (RFC 6901) into the request body, e.g. `/spec/grid/circumferential`.
    #[schema(example = "/spec/load/eccentricity_ratio")]
    pub path: String,
    /// The rule the value broke.
    #[schema(example = "must be in [0, 0.999]")]
    pub message: String,
}

impl FieldError {
    pub fn new(path: impl Into<String>, message: impl Into<String>) -> Self {
        Self { path: path.into(), message: message.into() }
    }
}

/// The table of error codes: each has one HTTP status and one title.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, ToSchema)]
#[serde(rename_all = "snake_case")]
pub enum ErrorCode {
    MalformedJson,
    UnsupportedMediaType,
    PayloadTooLarge,
    RequestTimeout,
    InvalidQuery,
    InvalidRequest,
    UnknownKind,
    InvalidSpec,
    LimitExceeded,
    IdempotencyKeyReused,
    Unauthorized,
    JobNotFound,
    RouteNotFound,
    PlotNotFound,
    TableNotFound,
    MethodNotAllowed,
    NotAcceptable,
    ResultNotReady,
    ResultUnavailable,
    QueueFull,
    ShuttingDown,
    StorageUnavailable,
    NotConverged,
    NonPhysical,
    Timeout,
    Interrupted,
    InternalError,
}

impl ErrorCode {
    /// `(status, title)` of each code.
    pub fn describe(self) -> (u16, &'static str) {
        use ErrorCode::*;
        match self {
            MalformedJson => (400, "Request body is not valid JSON"),
            UnsupportedMediaType => (415, "Request body must be application/json"),
            PayloadTooLarge => (413, "Request body too large"),
            RequestTimeout => (408, "Request body did not arrive in time"),
            InvalidQuery => (400, "Invalid query parameters"),
            InvalidRequest => (422, "Request body does not match the schema"),
            UnknownKind => (422, "Unknown job kind"),
            InvalidSpec => (422, "Invalid job spec"),
            LimitExceeded => (422, "Problem size above the server's limits"),
            IdempotencyKeyReused => (422, "Idempotency key already used for another request"),
            Unauthorized => (401, "Missing or invalid bearer token"),
            JobNotFound => (404, "Job not found"),
            RouteNotFound => (404, "No such route"),
            PlotNotFound => (404, "Plot not found"),
            TableNotFound => (404, "Table not found"),
            MethodNotAllowed => (405, "Method not allowed"),
            NotAcceptable => (406, "Requested representation not available"),
            ResultNotReady => (409, "Result not ready"),
            ResultUnavailable => (409, "Job has no result"),
            QueueFull => (503, "Job queue is full"),
            ShuttingDown => (503, "Service is shutting down"),
            StorageUnavailable => (503, "Storage unavailable"),
            NotConverged => (422, "Solver did not converge"),
            NonPhysical => (422, "No physical solution for this input"),
            Timeout => (422, "Job exceeded its time limit"),
            Interrupted => (503, "Job interrupted"),
            InternalError => (500, "Internal error"),
        }
    }

    pub fn as_str(self) -> &'static str {
        use ErrorCode::*;
        match self {
            MalformedJson => "malformed_json",
            UnsupportedMediaType => "unsupported_media_type",
            PayloadTooLarge => "payload_too_large",
            RequestTimeout => "request_timeout",
            InvalidQuery => "invalid_query",
            InvalidRequest => "invalid_request",
            UnknownKind => "unknown_kind",
            InvalidSpec => "invalid_spec",
            LimitExceeded => "limit_exceeded",
            IdempotencyKeyReused => "idempotency_key_reused",
            Unauthorized => "unauthorized",
            JobNotFound => "job_not_found",
            RouteNotFound => "route_not_found",
            PlotNotFound => "plot_not_found",
            TableNotFound => "table_not_found",
            MethodNotAllowed => "method_not_allowed",
            NotAcceptable => "not_acceptable",
            ResultNotReady => "result_not_ready",
            ResultUnavailable => "result_unavailable",
            QueueFull => "queue_full",
            ShuttingDown => "shutting_down",
            StorageUnavailable => "storage_unavailable",
            NotConverged => "not_converged",
            NonPhysical => "non_physical",
            Timeout => "timeout",
            Interrupted => "interrupted",
            InternalError => "internal_error",
        }
    }
}

/// `application/problem+json` body (RFC 9457) with this service's extensions `code` and `errors`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, ToSchema)]
pub struct Problem {
    /// URI naming the problem type: `urn:tribod:problem:<code>`.
    #[serde(rename = "type")]
    #[schema(example = "urn:tribod:problem:invalid_spec")]
    pub type_uri: String,
    /// Short summary of the problem type.
    pub title: String,
    /// HTTP status of this problem type.
    pub status: u16,
    /// What happened in this occurrence.
    pub detail: String,
    /// Stable machine-readable code (snake_case). Physical failures of solvers carry the solver's
    /// own code (e.g. `film_closed`, `follower_separation`) with status 422.
    #[schema(example = "invalid_spec")]
    pub code: String,
    /// The offending fields, when the problem is about the request's content.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub errors: Vec<FieldError>,
}

impl Problem {
    pub fn new(code: ErrorCode, detail: impl Into<String>) -> Self {
        let (status, title) = code.describe();
        Self::with_code(code.as_str(), status, title, detail)
    }

    /// A problem with a code of its own (a solver's physical failure), not one of [`ErrorCode`].
    pub fn with_code(code: &str, status: u16, title: &str, detail: impl Into<String>) -> Self {
        Problem {
            type_uri: format!("urn:tribod:problem:{code}"),
            title: title.to_string(),
            status,
            detail: detail.into(),
            code: code.to_string(),
            errors: Vec::new(),
        }
    }

    pub fn with_errors(mut self, errors: Vec<FieldError>) -> Self {
        self.errors = errors;
        self
    }

    /// Prefix every field path with `prefix` (e.g. `/spec` when a kind validated its own spec).
    pub fn under(mut self, prefix: &str) -> Self {
        for e in &mut self.errors {
            e.path = format!("{prefix}{}", e.path);
        }
        self
    }
}

impl std::fmt::Display for Problem {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "{} ({}): {}", self.title, self.code, self.detail)?;
        for e in &self.errors {
            write!(f, "; {}: {}", e.path, e.message)?;
        }
        Ok(())
    }
}
