//! Prometheus metrics (`/metrics`, text exposition format).

use prometheus_client::encoding::EncodeLabelSet;
use prometheus_client::metrics::counter::Counter;
use prometheus_client::metrics::family::Family;
use prometheus_client::metrics::gauge::Gauge;
use prometheus_client::metrics::histogram::{exponential_buckets, Histogram};
use prometheus_client::registry::Registry;

#[derive(Clone, Debug, Hash, PartialEq, Eq, EncodeLabelSet)]
pub struct KindLabel {
    pub kind: String,
}

#[derive(Clone, Debug, Hash, PartialEq, Eq, EncodeLabelSet)]
pub struct KindStatusLabel {
    pub kind: String,
    pub status: String,
}

#[derive(Clone, Debug, Hash, PartialEq, Eq, EncodeLabelSet)]
pub struct StatusLabel {
    pub status: String,
}

#[derive(Clone, Debug, Hash, PartialEq, Eq, EncodeLabelSet)]
pub struct HttpLabel {
    pub method: String,
    pub status: u16,
}

/// Every metric the service exports.
pub struct Metrics {
    registry: Registry,
    pub submitted: Family<KindLabel, Counter>,
    pub reused: Family<KindLabel, Counter>,
    pub finished: Family<KindStatusLabel, Counter>,
    pub solve_seconds: Family<KindLabel, Histogram>,
    pub queue_depth: Gauge,
    pub running: Gauge,
    /// Jobs in the database by status, refreshed at each scrape.
    pub jobs: Family<StatusLabel, Gauge>,
    pub http_requests: Family<HttpLabel, Counter>,
}

impl Default for Metrics {
    fn default() -> Self {
        Self::new()
    }
}

impl Metrics {
    pub fn new() -> Self {
        let mut registry = Registry::with_prefix("tribod");
        let submitted = Family::<KindLabel, Counter>::default();
        let reused = Family::<KindLabel, Counter>::default();
        let finished = Family::<KindStatusLabel, Counter>::default();
        let solve_seconds = Family::<KindLabel, Histogram>::new_with_constructor(|| {
            // 100 µs … ~1 h
            Histogram::new(exponential_buckets(1e-4, 3.0, 16))
        });
        let queue_depth = Gauge::default();
        let running = Gauge::default();
        let jobs = Family::<StatusLabel, Gauge>::default();
        let http_requests = Family::<HttpLabel, Counter>::default();
        registry.register("jobs_submitted", "Jobs accepted, by kind", submitted.clone());
        registry.register("jobs_reused", "Submissions answered by an identical finished job", reused.clone());
        registry.register("jobs_finished", "Jobs finished, by kind and final status", finished.clone());
        registry.register("job_solve_seconds", "Solver wall time per job, by kind", solve_seconds.clone());
        registry.register("queue_depth", "Jobs waiting in the queue", queue_depth.clone());
        registry.register("running_jobs", "Jobs running in this process", running.clone());
        registry.register("jobs", "Jobs in the database, by status", jobs.clone());
        registry.register("http_requests", "HTTP requests answered, by method and status", http_requests.clone());
        Metrics { registry, submitted, reused, finished, solve_seconds, queue_depth, running, jobs, http_requests }
    }

    /// Text exposition.
    pub fn encode(&self) -> String {
        let mut out = String::new();
        // Encoding into a String cannot fail.
        prometheus_client::encoding::text::encode(&mut out, &self.registry).expect("encode metrics");
        out
    }
}
