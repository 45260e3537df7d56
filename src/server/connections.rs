//! The HTTP/1.1 accept loop: hyper connections with bounded time and a bounded count.
//!
//! `axum::serve` has no header or idle timeout and no connection cap: slow or idle clients could
//! hold every file descriptor, and one half-sent request kept graceful shutdown waiting forever
//! (issue 10). Here each connection gets hyper's header-read timeout — a total deadline for a
//! request's headers, counted from the connection's start or the end of its previous answer, so
//! it also closes a keep-alive connection idle for that long — and the number of open connections
//! is capped by the connection table ([`super::slots`]): when it is full, a new connection takes
//! the place of the connection that has waited longest on its client (headers or body still
//! arriving, or idle), which is closed; only when every connection is busy being served (or has a
//! request the server has not read yet) is the new one answered `503` with `Retry-After` and
//! closed at once (issue 40: 4,096 tricklers no longer lock everyone out). The request body's own deadline is a request layer in `api`. Shutdown asks
//! every connection to finish its request in flight, then drops whatever is still open when the
//! drain deadline passes.

use super::slots::{self, Admission, Slots};
use axum::http::Request;
use axum::response::Response;
use axum::Router;
use hyper::body::Incoming;
use hyper_util::rt::{TokioIo, TokioTimer};
use hyper_util::service::TowerToHyperService;
use std::time::Duration;
use tokio::net::TcpListener;
use tokio::sync::watch;
use tokio::task::JoinSet;
use tracing::{debug, info, warn};

/// Limits of the HTTP layer on connections (the body-read timeout is a request layer in `api`).
#[derive(Debug, Clone, Copy)]
pub struct ConnectionLimits {
    /// Open connections at once; at the cap a new connection takes the place of the one waiting
    /// longest on its client, or is answered 503 and closed when all are busy.
    pub max_connections: usize,
    /// Time allowed for a request's headers to arrive (in total, however they trickle), counted
    /// from the connection's start or the end of its previous response (so it also closes idle
    /// keep-alive connections).
    pub header_timeout: Duration,
}

impl Default for ConnectionLimits {
    fn default() -> Self {
        ConnectionLimits { max_connections: 4096, header_timeout: Duration::from_secs(10) }
    }
}

/// What a connection over the cap gets before it is closed.
fn busy_response() -> Vec<u8> {
    let body = r#"{"type":"urn:tribod:problem:too_many_connections","title":"Too many connections","status":503,"code":"too_many_connections","detail":"the server is at its connection limit; retry in a second"}"#;
    format!(
        "HTTP/1.1 503 Service Unavailable\r\ncontent-type: application/problem+json\r\nretry-after: 1\r\n\
         connection: close\r\ncontent-length: {}\r\n\r\n{body}",
        body.len()
    )
    .into_bytes()
}

/// Raise the soft limit of open files to the hard limit (connections are file descriptors);
/// returns the soft limit in force.
pub fn raise_open_files_limit() -> u64 {
    // SAFETY: getrlimit/setrlimit only read and write the struct passed to them.
    unsafe {
        let mut lim = libc::rlimit { rlim_cur: 0, rlim_max: 0 };
        if libc::getrlimit(libc::RLIMIT_NOFILE, &mut lim) != 0 {
            return 1024;
        }
        if lim.rlim_cur < lim.rlim_max {
            let raised = libc::rlimit { rlim_cur: lim.rlim_max, rlim_max: lim.rlim_max };
            if libc::setrlimit(libc::RLIMIT_NOFILE, &raised) == 0 {
                lim.rlim_cur = lim.rlim_max;
            }
        }
        lim.rlim_cur as u64
    }
}

/// Serve `app` on `listener` until `stop` turns true; then let requests in flight finish until
/// `drain` has passed and close what is left.
pub async fn serve(
    listener: TcpListener,
    app: Router,
    limits: ConnectionLimits,
    mut stop: watch::Receiver<bool>,
    drain: Duration,
) {
    // Keep descriptors in reserve for the database, the listener and the log.
    let fd_limit = raise_open_files_limit() as usize;
    let cap = limits.max_connections.min(fd_limit.saturating_sub(64)).max(1);
    if cap < limits.max_connections {
        warn!(cap, fd_limit, "connection cap lowered to fit the open-files limit");
    }
    let slots = Slots::new(cap);
    let mut connections = JoinSet::new();
    let mut http = hyper::server::conn::http1::Builder::new();
    http.timer(TokioTimer::new()).header_read_timeout(limits.header_timeout);
    loop {
        let accepted = tokio::select! {
            _ = stop.wait_for(|s| *s) => break,
            accepted = listener.accept() => accepted,
            Some(_) = connections.join_next(), if !connections.is_empty() => continue,
        };
        let (stream, peer) = match accepted {
            Ok(a) => a,
            Err(e) => {
                // EMFILE and friends: back off instead of spinning.
                warn!(error = %e, "accept failed");
                tokio::time::sleep(Duration::from_millis(50)).await;
                continue;
            }
        };
        let Some((place, admission)) = slots.admit() else {
            let _ = stream.try_write(&busy_response());
            debug!(%peer, "connection refused: at the connection cap, every connection busy or with a request unread");
            continue;
        };
        if let Admission::Evicted { waited_ms } = admission {
            debug!(%peer, waited_ms, "at the connection cap: closed the connection waiting longest on its client");
        }
        let _ = stream.set_nodelay(true);
        place.slot.watch(std::os::fd::AsRawFd::as_raw_fd(&stream));
        let (on_request, on_response) = (place.slot.clone(), place.slot.clone());
        let service = tower::ServiceBuilder::new()
            .map_request(move |req: Request<Incoming>| slots::track_request(req, &on_request))
            .map_response(move |res: Response| slots::track_response(res, &on_response))
            .service(app.clone());
        let stream = slots::Heard::new(stream, place.slot.clone());
        let conn = http.serve_connection(TokioIo::new(stream), TowerToHyperService::new(service)).with_upgrades();
        let mut stop = stop.clone();
        // The task owns the connection's place in the table, freed when the task ends.
        connections.spawn(async move {
            let mut conn = std::pin::pin!(conn);
            tokio::select! {
                r = conn.as_mut() => return log_end(r),
                // Its place was given to a new connection: close at once.
                _ = place.slot.evicted() => return,
                _ = stop.wait_for(|s| *s) => conn.as_mut().graceful_shutdown(),
            }
            log_end(conn.await);
        });
    }
    drop(listener);
    let open = connections.len();
    if open > 0 {
        info!(open, drain_seconds = drain.as_secs_f64(), "finishing requests in flight");
    }
    let drained = tokio::time::timeout(drain, async { while connections.join_next().await.is_some() {} }).await;
    if drained.is_err() {
        warn!(open = connections.len(), "drain time over: closing the remaining connections");
        connections.shutdown().await;
    }
}

fn log_end(r: Result<(), hyper::Error>) {
    if let Err(e) = r {
        debug!(error = %e, "connection ended with an error");
    }
}
