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
//!
//! Two kinds of waiting connection are spared, because there the server is the slow one or the
//! client has had no chance yet:
//! * a connection whose socket holds bytes the server has not read yet (a stalled runtime, a burst
//!   of accepts): its client has sent. It is never evicted; when every waiting connection is in
//!   that state the newcomer is answered 503, as when every connection is busy;
//! * a connection accepted less than [`FRESH_MS`] ago whose client has not sent a byte yet (a
//!   client under load writes its request a moment after its connect completes). It is evicted
//!   only when no other waiting connection can be. Tricklers send their first bytes at once, so a
//!   burst of reconnecting tricklers evicts each other, not a normal client's new connection.

use axum::body::{Body, Bytes};
use axum::http::{Request, Response};
use hyper::body::{Body as HttpBody, Frame, SizeHint};
use std::collections::HashMap;
use std::os::fd::RawFd;
use std::pin::Pin;
use std::sync::atomic::{AtomicBool, AtomicI32, AtomicU64, AtomicU8, Ordering};
use std::sync::{Arc, Mutex};
use std::task::{Context, Poll};
use std::time::Instant;
use tokio::io::{AsyncRead, AsyncWrite, ReadBuf};
use tokio::sync::Notify;

/// How long a new connection whose client has not sent a byte yet is spared from eviction, ms.
pub const FRESH_MS: u64 = 250;

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
    /// The connection's socket, for [`Slot::has_unread_bytes`]; −1 until [`Slot::watch`].
    fd: AtomicI32,
    /// Accepted at, ms after `epoch`.
    born_ms: u64,
    /// Whether the client has sent any byte on this connection (set by [`Heard`]).
    heard: AtomicBool,
    evicted: Notify,
}

impl Slot {
    fn new(epoch: Instant) -> Slot {
        let born_ms = epoch.elapsed().as_millis() as u64;
        let (fd, heard) = (AtomicI32::new(-1), AtomicBool::new(false));
        let slot = Slot { epoch, phase: AtomicU8::new(Phase::Headers as u8), since_ms: AtomicU64::new(0), fd, born_ms, heard, evicted: Notify::new() };
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

    /// The connection's socket, whose unread bytes tell a client that has sent its request from
    /// one that has not.
    pub fn watch(&self, fd: RawFd) {
        self.fd.store(fd, Ordering::Relaxed);
    }

    /// Whether the client has sent bytes the server has not read yet (`FIONREAD` on the socket).
    fn has_unread_bytes(&self) -> bool {
        let fd = self.fd.load(Ordering::Relaxed);
        if fd < 0 {
            return false;
        }
        let mut pending: libc::c_int = 0;
        // SAFETY: FIONREAD writes one c_int into `pending`; on a descriptor that is not a socket
        // (closed and reused meanwhile) it fails or reports a count, and either only decides
        // which waiting connection is closed.
        let ok = unsafe { libc::ioctl(fd, libc::FIONREAD, &mut pending as *mut libc::c_int) } == 0;
        ok && pending > 0
    }

    /// Accepted less than [`FRESH_MS`] before `now_ms` and nothing received yet.
    fn fresh_and_silent(&self, now_ms: u64) -> bool {
        now_ms.saturating_sub(self.born_ms) < FRESH_MS && !self.heard.load(Ordering::Relaxed)
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
    /// longest on its client (which is told to close). `None`: every connection is busy or has
    /// unread bytes from its client.
    pub fn admit(self: &Arc<Self>) -> Option<(Place, Admission)> {
        let mut open = self.open.lock().unwrap_or_else(|e| e.into_inner());
        let mut admission = Admission::Free;
        if open.len() >= self.cap {
            // Oldest waiter first, fresh silent connections last; ties (the same millisecond) go
            // to the older connection (ids grow with each accept). A waiter with unread bytes is
            // not waiting on its client.
            let now = self.epoch.elapsed().as_millis() as u64;
            let mut waiting: Vec<(bool, u64, u64)> = open
                .iter()
                .filter_map(|(&id, slot)| slot.waiting_since().map(|since| (slot.fresh_and_silent(now), since, id)))
                .collect();
            waiting.sort_unstable();
            let (_, since, victim) = waiting.into_iter().find(|(_, _, id)| !open[id].has_unread_bytes())?;
            if let Some(slot) = open.remove(&victim) {
                slot.evicted.notify_one();
            }
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

/// A connection's byte stream that marks its slot once the client has sent anything, and marks it
/// busy the moment a request's headers are complete (before hyper parses them: a worker thread
/// descheduled between the read and the dispatch must not leave a complete request looking like a
/// client still sending its headers).
pub struct Heard<S> {
    inner: S,
    slot: Arc<Slot>,
    /// The last three bytes read, for an end of headers split across reads.
    tail: [u8; 3],
}

impl<S> Heard<S> {
    pub fn new(inner: S, slot: Arc<Slot>) -> Heard<S> {
        Heard { inner, slot, tail: [0; 3] }
    }
}

/// Note the bytes just read on `slot`'s connection: the client was heard; `\r\n\r\n` among them
/// (with `tail`, the last three bytes of the previous read) ends a request's headers.
fn note_read(slot: &Slot, tail: &mut [u8; 3], read: &[u8]) {
    slot.heard.store(true, Ordering::Relaxed);
    let ends = |b: &[u8]| b.windows(4).any(|w| w == b"\r\n\r\n");
    let mut seam = [0u8; 6];
    let joined = read.len().min(3);
    seam[..3].copy_from_slice(tail);
    seam[3..3 + joined].copy_from_slice(&read[..joined]);
    if ends(&seam[..3 + joined]) || ends(read) {
        slot.advance(Phase::Headers, Phase::Busy);
    }
    for &b in &read[read.len().saturating_sub(3)..] {
        *tail = [tail[1], tail[2], b];
    }
}

impl<S: AsyncRead + Unpin> AsyncRead for Heard<S> {
    fn poll_read(self: Pin<&mut Self>, cx: &mut Context<'_>, buf: &mut ReadBuf<'_>) -> Poll<std::io::Result<()>> {
        let this = self.get_mut();
        let before = buf.filled().len();
        let polled = Pin::new(&mut this.inner).poll_read(cx, buf);
        if buf.filled().len() > before {
            note_read(&this.slot, &mut this.tail, &buf.filled()[before..]);
        }
        polled
    }
}

impl<S: AsyncWrite + Unpin> AsyncWrite for Heard<S> {
    fn poll_write(mut self: Pin<&mut Self>, cx: &mut Context<'_>, data: &[u8]) -> Poll<std::io::Result<usize>> {
        Pin::new(&mut self.inner).poll_write(cx, data)
    }

    fn poll_flush(mut self: Pin<&mut Self>, cx: &mut Context<'_>) -> Poll<std::io::Result<()>> {
        Pin::new(&mut self.inner).poll_flush(cx)
    }

    fn poll_shutdown(mut self: Pin<&mut Self>, cx: &mut Context<'_>) -> Poll<std::io::Result<()>> {
        Pin::new(&mut self.inner).poll_shutdown(cx)
    }

    fn poll_write_vectored(mut self: Pin<&mut Self>, cx: &mut Context<'_>, bufs: &[std::io::IoSlice<'_>]) -> Poll<std::io::Result<usize>> {
        Pin::new(&mut self.inner).poll_write_vectored(cx, bufs)
    }

    fn is_write_vectored(&self) -> bool {
        self.inner.is_write_vectored()
    }
}
