//! `tribod serve`: open the store, start the queue, serve HTTP, shut down gracefully.
//!
//! Shutdown (SIGTERM, SIGINT or [`Server::shutdown`]): the queue stops claiming and accepting at
//! once and answers every `Prefer: wait` request with its job as it is; connections finish the
//! request in flight; running jobs get `shutdown_grace` to finish and are then interrupted and
//! queued again; connections still open after the grace period are closed.

mod connections;
mod slots;

pub use connections::{raise_open_files_limit, ConnectionLimits};

use crate::api::{self, ApiConfig};
use crate::jobs::queue::{Queue, QueueConfig};
use crate::metrics::Metrics;
use crate::store::{Store, StoreError};
use std::future::Future;
use std::net::SocketAddr;
use std::sync::Arc;
use std::time::Duration;
use tokio::net::TcpListener;
use tokio::sync::{oneshot, watch};
use tracing::info;

/// Everything `serve` needs.
#[derive(Debug, Clone)]
pub struct ServeConfig {
    pub addr: String,
    pub database_url: String,
    pub queue: QueueConfig,
    pub api: ApiConfig,
    /// How long running jobs may take to finish at shutdown before they are interrupted and
    /// queued again (also the longest wait for requests in flight).
    pub shutdown_grace: Duration,
    /// Connection cap and header timeout.
    pub connections: ConnectionLimits,
}

impl Default for ServeConfig {
    fn default() -> Self {
        ServeConfig {
            addr: "127.0.0.1:8080".into(),
            database_url: "tribod.db".into(),
            queue: QueueConfig::default(),
            api: ApiConfig::default(),
            shutdown_grace: Duration::from_secs(30),
            connections: ConnectionLimits::default(),
        }
    }
}

/// A running server (for tests and embedding): its address and a way to stop it.
pub struct Server {
    pub addr: SocketAddr,
    stop: Option<oneshot::Sender<()>>,
    task: tokio::task::JoinHandle<std::io::Result<()>>,
}

impl Server {
    /// Open the store, recover interrupted jobs, bind and start serving in the background.
    pub async fn start(config: ServeConfig) -> Result<Server, StartError> {
        let (stop, stopped) = oneshot::channel::<()>();
        let (addr, fut) = prepare(config, async move {
            let _ = stopped.await;
        })
        .await?;
        let task = tokio::spawn(fut);
        Ok(Server { addr, stop: Some(stop), task })
    }

    /// Graceful shutdown; returns when the queue is idle and the store closed.
    pub async fn shutdown(mut self) -> std::io::Result<()> {
        if let Some(s) = self.stop.take() {
            let _ = s.send(());
        }
        self.task.await.unwrap_or_else(|e| Err(std::io::Error::other(e)))
    }
}

/// Serve until SIGINT/SIGTERM; `on_bound` learns the bound address first.
pub async fn serve(config: ServeConfig, on_bound: impl FnOnce(SocketAddr)) -> Result<(), StartError> {
    let (addr, fut) = prepare(config, shutdown_signal()).await?;
    on_bound(addr);
    fut.await?;
    Ok(())
}

/// Bind and wire everything; the returned future serves until `stop` resolves, then drains.
async fn prepare(
    config: ServeConfig,
    stop: impl Future<Output = ()> + Send + 'static,
) -> Result<(SocketAddr, impl Future<Output = std::io::Result<()>>), StartError> {
    let url = config.database_url.clone();
    let store = Store::open(&url).await.map_err(|source| StartError::Store { url: url.clone(), source })?;
    let metrics = Arc::new(Metrics::new());
    let queue = Queue::start(store.clone(), config.queue.clone(), metrics)
        .await
        .map_err(|source| StartError::Store { url, source })?;
    let app = api::app(queue.clone(), &config.api);
    let listener = TcpListener::bind(&config.addr)
        .await
        .map_err(|source| StartError::Bind { addr: config.addr.clone(), source })?;
    let addr = listener.local_addr()?;
    info!(%addr, workers = config.queue.workers, database = %config.database_url, "tribod listening");
    let grace = config.shutdown_grace;
    let (stopping, stop_rx) = watch::channel(false);
    let http = tokio::spawn(connections::serve(listener, app, config.connections, stop_rx, grace));
    let fut = async move {
        stop.await;
        info!("shutting down: no new jobs; waiting requests answered; running jobs get the grace period");
        queue.begin_shutdown();
        let _ = stopping.send(true);
        let (_, http) = tokio::join!(queue.shutdown(grace), http);
        if let Err(e) = http {
            tracing::warn!(error = %e, "HTTP task ended abnormally");
        }
        store.close().await;
        info!("shutdown complete");
        Ok(())
    };
    Ok((addr, fut))
}

/// Everything `worker` needs: a queue without HTTP, sharing a PostgreSQL store with servers.
#[derive(Debug, Clone)]
pub struct WorkerConfig {
    pub database_url: String,
    pub queue: QueueConfig,
    /// How long running jobs may take to finish at shutdown before they are queued again.
    pub shutdown_grace: Duration,
    /// Where to serve `/healthz`, `/readyz` and `/metrics` (none: no port at all).
    pub health_addr: Option<String>,
}

/// `tribod worker`: claim and run jobs from a shared store until SIGINT/SIGTERM.
pub async fn work(config: WorkerConfig) -> Result<(), StartError> {
    let url = config.database_url.clone();
    let store = Store::open(&url).await.map_err(|source| StartError::Store { url: url.clone(), source })?;
    if !store.is_shared() {
        store.close().await;
        return Err(StartError::NotShared { url });
    }
    let metrics = Arc::new(Metrics::new());
    let queue = Queue::start(store.clone(), config.queue.clone(), metrics)
        .await
        .map_err(|source| StartError::Store { url, source })?;
    let (stopping, stop_rx) = watch::channel(false);
    let health = match &config.health_addr {
        Some(addr) => {
            let listener = TcpListener::bind(addr)
                .await
                .map_err(|source| StartError::Bind { addr: addr.clone(), source })?;
            info!(addr = %listener.local_addr()?, "health port: /healthz /readyz /metrics");
            let app = api::operations_app(queue.clone());
            let limits = ConnectionLimits { max_connections: 64, ..ConnectionLimits::default() };
            Some(tokio::spawn(connections::serve(listener, app, limits, stop_rx, Duration::from_secs(1))))
        }
        None => None,
    };
    info!(workers = config.queue.workers, database = %config.database_url, "tribod worker running");
    shutdown_signal().await;
    queue.begin_shutdown();
    let _ = stopping.send(true);
    queue.shutdown(config.shutdown_grace).await;
    if let Some(h) = health {
        let _ = h.await;
    }
    store.close().await;
    info!("worker stopped");
    Ok(())
}

async fn shutdown_signal() {
    let ctrl_c = async {
        let _ = tokio::signal::ctrl_c().await;
    };
    #[cfg(unix)]
    let term = async {
        match tokio::signal::unix::signal(tokio::signal::unix::SignalKind::terminate()) {
            Ok(mut s) => {
                s.recv().await;
            }
            Err(_) => std::future::pending::<()>().await,
        }
    };
    #[cfg(not(unix))]
    let term = std::future::pending::<()>();
    tokio::select! {
        _ = ctrl_c => info!("SIGINT: shutting down"),
        _ = term => info!("SIGTERM: shutting down"),
    }
}

/// Why the server could not start (or stopped with an I/O error).
#[derive(Debug, thiserror::Error)]
pub enum StartError {
    #[error("opening the database {url}: {source}")]
    Store { url: String, source: StoreError },
    #[error("{url} is an embedded SQLite file, which one `tribod serve` owns; separate workers need a shared PostgreSQL database (postgres://…)")]
    NotShared { url: String },
    #[error("binding {addr}: {source}")]
    Bind { addr: String, source: std::io::Error },
    #[error(transparent)]
    Io(#[from] std::io::Error),
}
