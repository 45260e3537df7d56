//! A total deadline for request bodies (issue 40).
//!
//! A request's body must have arrived completely within `--body-timeout` of the moment its
//! headers were read (when the request enters the router), however it trickles in: a total
//! deadline, not a per-read one. (`tower_http`'s `RequestBodyTimeoutLayer` times each frame, so a
//! client sending one byte every 20 s kept a request open for ever under a 30 s timeout.) A total
//! deadline rather than a minimum rate: one number to state and test, and any JSON body this
//! server accepts (`--body-limit`, 1 MiB by default) arrives in well under a second at ordinary
//! speeds.
//!
//! Past the deadline the body yields a [`BodyTimedOut`] error instead of more data; the JSON
//! extractor answers it `408 request_timeout` with `Connection: close`, and hyper, seeing the
//! body abandoned half-read, closes the connection after that answer.

use axum::body::{Body, Bytes};
use axum::extract::Request;
use hyper::body::{Body as HttpBody, Frame, SizeHint};
use std::future::Future;
use std::pin::Pin;
use std::task::{Context, Poll};
use std::time::Duration;

/// Give `req`'s body a deadline `timeout` from now (a request without a body is left alone).
pub fn limit(req: Request, timeout: Duration) -> Request {
    if req.body().is_end_stream() {
        return req;
    }
    req.map(|body| {
        Body::new(DeadlineBody { inner: body, timeout, deadline: Box::pin(tokio::time::sleep(timeout)) })
    })
}

/// The body did not arrive within the deadline.
#[derive(Debug, thiserror::Error)]
#[error("the request body did not arrive within {} s of its headers", .0.as_secs_f64())]
pub struct BodyTimedOut(pub Duration);

impl BodyTimedOut {
    /// Whether `error` or any error it was caused by is a [`BodyTimedOut`].
    pub fn caused<'a>(error: &'a (dyn std::error::Error + 'static)) -> Option<&'a BodyTimedOut> {
        let mut e = Some(error);
        while let Some(err) = e {
            if let Some(t) = err.downcast_ref::<BodyTimedOut>() {
                return Some(t);
            }
            e = err.source();
        }
        None
    }
}

/// A body that fails with [`BodyTimedOut`] once its deadline passes.
struct DeadlineBody {
    inner: Body,
    timeout: Duration,
    deadline: Pin<Box<tokio::time::Sleep>>,
}

impl HttpBody for DeadlineBody {
    type Data = Bytes;
    type Error = axum::BoxError;

    fn poll_frame(mut self: Pin<&mut Self>, cx: &mut Context<'_>) -> Poll<Option<Result<Frame<Bytes>, Self::Error>>> {
        // The deadline first: data arriving after it does not extend it.
        if self.deadline.as_mut().poll(cx).is_ready() {
            return Poll::Ready(Some(Err(Box::new(BodyTimedOut(self.timeout)))));
        }
        Pin::new(&mut self.inner).poll_frame(cx).map_err(Into::into)
    }

    fn is_end_stream(&self) -> bool {
        self.inner.is_end_stream()
    }

    fn size_hint(&self) -> SizeHint {
        self.inner.size_hint()
    }
}
