//! The connection table: every open connection, whether it waits on its client or is being served,
//! and which one gives its place up when the table is full (issue 40).
//!
//! A connection is in one of three phases:
//! * **headers** — waiting for a request's headers: just accepted, or idle on keep-alive after an
//!   answer;
//! * **body** — its request is routed and its body is still arriving;
//! * **busy** — its request is being handled or its answer written (including a `Prefer: wait`
//!   request or an event stream: the server is the slow one, not the client).
//!
//! Headers and body are the phases in which the *client* holds the place. When the table is full,
//! a new connection takes the place of the one that has been waiting on its client the longest
//! (the earliest start of its current headers or body phase), which is closed at once; only when
//! every connection is busy is the new one answered `503 too_many_connections`. So clients that
//! trickle their requests (or sit idle) can never lock out clients that send theirs at once: the
//! tricklers are the oldest waiters, and a normal request leaves the waiting phases within one
//! round trip. The per-connection deadlines still bound each phase (`--header-timeout` in hyper,
//! `--body-timeout` in the API): eviction is only what happens *before* them when places run out.

use axum::body::{Body, Bytes};
use axum::http::{Request, Response};
use hyper::body::{Body as HttpBody, Frame, SizeHint};
use std::collections::HashMap;
use std::pin::Pin;
use std::sync::atomic::{AtomicU64, AtomicU8, Ordering};
use std::sync::{Arc, Mutex};
use std::task::{Context, Poll};
use std::time::Instant;
use tokio::sync::Notify;

/// What an open connection is doing.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[repr(u8)]
pub enum Phase {
    /// Waiting for a request's headers (new, or idle on keep-alive).
    Headers = 0,
    /// Waiting for the rest of a request's body.
    Body = 1,
    /// Handling a request or writing its answer.
    Busy = 2,
}

/// One connection's entry: its phase, since when, and the signal that it was evicted.
#[derive(Debug)]
pub struct Slot {
    epoch: Instant,
    phase: AtomicU8,
    /// Start of the current phase, ms after `epoch`.
    since_ms: AtomicU64,
    evicted: Notify,
}

impl Slot {
    fn new(epoch: Instant) -> Slot {
        let slot = Slot { epoch, phase: AtomicU8::new(Phase::Headers as u8), since_ms: AtomicU64::new(0), evicted: Notify::new() };
        slot.enter(Phase::Headers);
        slot
    }

    /// Enter `phase` now.
    pub fn enter(&self, phase: Phase) {
        self.since_ms.store(self.epoch.elapsed().as_millis() as u64, Ordering::Relaxed);
        self.phase.store(phase as u8, Ordering::Relaxed);
    }

    /// Enter `to` now if the connection is in `from`.
    fn advance(&self, from: Phase, to: Phase) {
        if self.phase.load(Ordering::Relaxed) == from as u8 {
            self.enter(to);
        }
    }

    /// Since when (ms after the table's epoch) the connection has waited on its client, if it does.
    fn waiting_since(&self) -> Option<u64> {
        let phase = self.phase.load(Ordering::Relaxed);
        (phase != Phase::Busy as u8).then(|| self.since_ms.load(Ordering::Relaxed))
    }

    /// Resolves when the connection was chosen to give its place up.
    pub async fn evicted(&self) {
        self.evicted.notified().await
    }
}

/// The table of open connections, at most `cap` of them.
#[derive(Debug)]
pub struct Slots {
    cap: usize,
    epoch: Instant,
    next_id: AtomicU64,
    open: Mutex<HashMap<u64, Arc<Slot>>>,
}

/// A connection's place in the table: freed when dropped (the connection's task ended).
#[derive(Debug)]
pub struct Place {
    slots: Arc<Slots>,
    id: u64,
    pub slot: Arc<Slot>,
}

impl Drop for Place {
    fn drop(&mut self) {
        self.slots.open.lock().unwrap_or_else(|e| e.into_inner()).remove(&self.id);
    }
}

/// How a new connection was admitted.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Admission {
    /// There was a free place.
    Free,
    /// It took the place of the connection waiting longest on its client, now closed.
    Evicted { waited_ms: u64 },
}

impl Slots {
    pub fn new(cap: usize) -> Arc<Slots> {
        Arc::new(Slots { cap: cap.max(1), epoch: Instant::now(), next_id: AtomicU64::new(0), open: Mutex::new(HashMap::new()) })
    }

    /// A place for a new connection: a free one, or the place of the connection that has waited
    /// longest on its client (which is told to close). `None`: every connection is busy.
    pub fn admit(self: &Arc<Self>) -> Option<(Place, Admission)> {
        let mut open = self.open.lock().unwrap_or_else(|e| e.into_inner());
        let mut admission = Admission::Free;
        if open.len() >= self.cap {
            // Ties (the same millisecond) go to the older connection (ids grow with each accept).
            let (since, victim) = open
                .iter()
                .filter_map(|(&id, slot)| slot.waiting_since().map(|since| (since, id)))
                .min()?;
            if let Some(slot) = open.remove(&victim) {
                slot.evicted.notify_one();
            }
            let now = self.epoch.elapsed().as_millis() as u64;
            admission = Admission::Evicted { waited_ms: now.saturating_sub(since) };
        }
        let id = self.next_id.fetch_add(1, Ordering::Relaxed);
        let slot = Arc::new(Slot::new(self.epoch));
        open.insert(id, slot.clone());
        Some((Place { slots: self.clone(), id, slot }, admission))
    }
}

/// A request as it enters the service: its connection is now waiting for the body, or busy when
/// there is none; the body marks the connection busy once read or dropped.
pub fn track_request<B>(req: Request<B>, slot: &Arc<Slot>) -> Request<Body>
where
    B: HttpBody<Data = Bytes> + Send + Unpin + 'static,
    B::Error: Into<axum::BoxError>,
{
    if req.body().is_end_stream() {
        slot.enter(Phase::Busy);
        return req.map(Body::new);
    }
    slot.enter(Phase::Body);
    req.map(|inner| Body::new(RequestBody { inner, slot: slot.clone() }))
}

/// An answer as it leaves the service: once hyper has written its body (and drops it), the
/// connection waits for the next request's headers.
pub fn track_response(res: Response<Body>, slot: &Arc<Slot>) -> Response<Body> {
    res.map(|inner| Body::new(ResponseBody { inner, slot: slot.clone() }))
}

struct RequestBody<B> {
    inner: B,
    slot: Arc<Slot>,
}

impl<B> HttpBody for RequestBody<B>
where
    B: HttpBody<Data = Bytes> + Unpin,
{
    type Data = Bytes;
    type Error = B::Error;

    fn poll_frame(mut self: Pin<&mut Self>, cx: &mut Context<'_>) -> Poll<Option<Result<Frame<Bytes>, B::Error>>> {
        let polled = Pin::new(&mut self.inner).poll_frame(cx);
        if matches!(polled, Poll::Ready(None)) || self.inner.is_end_stream() {
            self.slot.advance(Phase::Body, Phase::Busy);
        }
        polled
    }

    fn is_end_stream(&self) -> bool {
        self.inner.is_end_stream()
    }

    fn size_hint(&self) -> SizeHint {
        self.inner.size_hint()
    }
}

impl<B> Drop for RequestBody<B> {
    fn drop(&mut self) {
        self.slot.advance(Phase::Body, Phase::Busy);
    }
}

struct ResponseBody {
    inner: Body,
    slot: Arc<Slot>,
}

impl HttpBody for ResponseBody {
    type Data = Bytes;
    type Error = axum::Error;

    fn poll_frame(mut self: Pin<&mut Self>, cx: &mut Context<'_>) -> Poll<Option<Result<Frame<Bytes>, axum::Error>>> {
        Pin::new(&mut self.inner).poll_frame(cx)
    }

    fn is_end_stream(&self) -> bool {
        self.inner.is_end_stream()
    }

    fn size_hint(&self) -> SizeHint {
        self.inner.size_hint()
    }
}

impl Drop for ResponseBody {
    fn drop(&mut self) {
        self.slot.advance(Phase::Busy, Phase::Headers);
    }
}
