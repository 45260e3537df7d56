//! Extractors whose rejections are problems with field paths, not axum's plain-text bodies.

use super::deadline::BodyTimedOut;
use super::error::ApiError;
use crate::jobs::kind::parse_value;
use crate::problem::{ErrorCode, FieldError};
use axum::body::Bytes;
use axum::extract::{FromRequest, FromRequestParts, Request};
use axum::http::{header, request::Parts, StatusCode};
use serde::de::DeserializeOwned;

/// A JSON body: malformed → 400 `malformed_json` (with line and column), wrong shape → 422
/// `invalid_request` naming the field, too large → 413, a non-JSON content type → 415, not
/// arrived by its deadline ([`super::deadline`]) → 408 `request_timeout`.
/// A missing content type, `text/plain` and curl's default form type are accepted as JSON.
pub struct ApiJson<T>(pub T);

impl<S, T> FromRequest<S> for ApiJson<T>
where
    S: Send + Sync,
    T: DeserializeOwned,
{
    type Rejection = ApiError;

    async fn from_request(req: Request, state: &S) -> Result<Self, ApiError> {
        if let Some(ct) = req.headers().get(header::CONTENT_TYPE) {
            let ct = ct.to_str().unwrap_or("").to_ascii_lowercase();
            let essence = ct.split(';').next().unwrap_or("").trim();
            let ok = essence == "application/json"
                || essence.ends_with("+json")
                || essence == "text/plain"
                || essence == "application/x-www-form-urlencoded";
            if !ok {
                return Err(ApiError::new(
                    ErrorCode::UnsupportedMediaType,
                    format!("content type '{essence}' is not JSON; send application/json"),
                ));
            }
        }
        let bytes = Bytes::from_request(req, state).await.map_err(|rejection| {
            if let Some(timed_out) = BodyTimedOut::caused(&rejection) {
                ApiError::new(ErrorCode::RequestTimeout, timed_out.to_string())
            } else if rejection.status() == StatusCode::PAYLOAD_TOO_LARGE {
                ApiError::new(ErrorCode::PayloadTooLarge, "the request body is larger than this server accepts")
            } else {
                ApiError::new(ErrorCode::MalformedJson, rejection.body_text())
            }
        })?;
        let value: serde_json::Value = serde_json::from_slice(&bytes).map_err(|e| {
            ApiError::new(ErrorCode::MalformedJson, format!("{e}"))
        })?;
        parse_value::<T>(&value).map(ApiJson).map_err(|e| {
            let detail = format!("{}: {}", if e.path.is_empty() { "/" } else { &e.path }, e.message);
            let mut err = ApiError::new(ErrorCode::InvalidRequest, detail);
            err.problem.errors = vec![e];
            err
        })
    }
}

/// Query parameters: a bad parameter → 400 `invalid_query` naming it.
pub struct ApiQuery<T>(pub T);

impl<S, T> FromRequestParts<S> for ApiQuery<T>
where
    S: Send + Sync,
    T: DeserializeOwned,
{
    type Rejection = ApiError;

    async fn from_request_parts(parts: &mut Parts, _state: &S) -> Result<Self, ApiError> {
        let query = parts.uri.query().unwrap_or("");
        let de = serde_urlencoded::Deserializer::new(form_urlencoded::parse(query.as_bytes()));
        serde_path_to_error::deserialize(de).map(ApiQuery).map_err(|e| {
            let path = e.path().to_string();
            let mut err = ApiError::new(ErrorCode::InvalidQuery, format!("query parameter '{path}': {}", e.inner()));
            err.problem.errors = vec![FieldError::new(format!("?{path}"), e.inner().to_string())];
            err
        })
    }
}

/// The `{id}` of a job route: a UUID. Anything else — including a segment that is not UTF-8 after
/// percent-decoding, which axum's own `Path` rejects in plain text — is a `404 job_not_found`
/// problem: no job has that id.
pub struct JobIdPath(pub uuid::Uuid);

impl<S: Send + Sync> FromRequestParts<S> for JobIdPath {
    type Rejection = ApiError;

    async fn from_request_parts(parts: &mut Parts, state: &S) -> Result<Self, ApiError> {
        let axum::extract::Path(raw) = axum::extract::Path::<String>::from_request_parts(parts, state)
            .await
            .map_err(|_| ApiError::new(ErrorCode::JobNotFound, "the job id is not UTF-8 text, so no job has it"))?;
        uuid::Uuid::parse_str(&raw)
            .map(JobIdPath)
            .map_err(|_| ApiError::new(ErrorCode::JobNotFound, format!("'{raw}' is not a job id (a UUID)")))
    }
}
