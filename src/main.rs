//! The `tribod` command line: `serve`, `worker`, `run`, `openapi`.

use clap::{Parser, Subcommand, ValueEnum};
use std::io::Read;
use std::process::ExitCode;
use std::time::Duration;
use tribod::api::ApiConfig;
use tribod::jobs::queue::QueueConfig;
use tribod::jobs::{registry, runner, table, Limits};
use tribod::physics::Silent;
use tribod::problem::{ErrorCode, Problem};
use tribod::server::{self, ServeConfig};

#[derive(Parser)]
#[command(name = "tribod", version, about = "Valve-train and bearing tribology calculation service")]
struct Cli {
    /// Log format.
    #[arg(long, global = true, env = "TRIBOD_LOG_FORMAT", value_enum, default_value_t = LogFormat::Pretty)]
    log_format: LogFormat,
    #[command(subcommand)]
    command: Command,
}

#[derive(Clone, Copy, ValueEnum)]
enum LogFormat {
    Pretty,
    Json,
}

#[derive(Subcommand)]
enum Command {
    /// Serve the HTTP API with a worker pool (`--workers 0`: API only).
    Serve(ServeArgs),
    /// Run workers only, no HTTP: compute nodes sharing a PostgreSQL store with `serve` instances.
    Worker(WorkerArgs),
    /// Validate and solve one job spec offline; print the result JSON (or a CSV table).
    Run(RunArgs),
    /// Print the OpenAPI document.
    Openapi,
}

#[derive(clap::Args)]
struct QueueArgs {
    /// Job store: a SQLite file path or sqlite:// URL (created on first start), or a
    /// postgres:// URL shared by several instances.
    #[arg(long, env = "TRIBOD_DATABASE_URL", default_value = "tribod.db")]
    database_url: String,
    /// Worker threads (jobs solved at once); default: number of cores. 0 with `serve`: API only.
    #[arg(long, env = "TRIBOD_WORKERS")]
    workers: Option<usize>,
    /// Short-job slots besides the workers: threads that take only jobs the work model
    /// estimates at 10 ms of CPU or less, so tiny jobs neither wait behind heavy ones nor are
    /// held to the workers' count. 0: none.
    #[arg(long, env = "TRIBOD_SHORT_SLOTS", default_value_t = tribod::jobs::queue::DEFAULT_SHORT_SLOTS)]
    short_slots: usize,
    /// Queued jobs accepted before POST answers 503.
    #[arg(long, env = "TRIBOD_MAX_QUEUE", default_value_t = 10_000)]
    max_queue: usize,
    /// Per-job time limit in seconds (0 = none).
    #[arg(long, env = "TRIBOD_JOB_TIMEOUT", default_value_t = 600.0)]
    job_timeout: f64,
    /// Start attempts before a job interrupted by restarts or lost workers fails.
    #[arg(long, env = "TRIBOD_MAX_ATTEMPTS", default_value_t = 3)]
    max_attempts: i64,
    /// Seconds running jobs get to finish at shutdown before being re-queued.
    #[arg(long, env = "TRIBOD_SHUTDOWN_GRACE", default_value_t = 30.0)]
    shutdown_grace: f64,
    /// Seconds a claimed job stays with an instance that stopped renewing its lease (it renews
    /// twice a second); after that any instance re-queues the job.
    #[arg(long, env = "TRIBOD_LEASE_SECONDS", default_value_t = 30.0)]
    lease_seconds: f64,
    /// A sweep whose cases the work model estimates at this many CPU seconds or more (on
    /// average) spreads its cases, as jobs of their own, over every instance sharing the store
    /// (SQLite: this instance's workers); cheaper sweeps run in-process. `inf`: never.
    #[arg(long, env = "TRIBOD_FAN_OUT_MIN_CASE_SECONDS", default_value_t = tribod::jobs::queue::DEFAULT_FAN_OUT_MIN_CASE_SECONDS)]
    fan_out_min_case_seconds: f64,
    #[command(flatten)]
    limits: LimitArgs,
}

impl QueueArgs {
    fn queue(&self, default_workers: usize) -> QueueConfig {
        QueueConfig {
            workers: self.workers.unwrap_or(default_workers),
            short_slots: self.short_slots,
            max_backlog: self.max_queue,
            job_timeout: (self.job_timeout > 0.0).then(|| Duration::from_secs_f64(self.job_timeout)),
            max_attempts: self.max_attempts.max(1),
            limits: self.limits.limits(),
            lease: Duration::from_secs_f64(self.lease_seconds.max(1.0)),
            fan_out_min_case_seconds: self.fan_out_min_case_seconds.is_finite().then_some(self.fan_out_min_case_seconds.max(0.0)),
            ..QueueConfig::default()
        }
    }
}

#[derive(clap::Args)]
struct WorkerArgs {
    #[command(flatten)]
    queue: QueueArgs,
    /// Serve /healthz, /readyz (database and claim loop) and /metrics on this address, for
    /// probes and scrapes; no API. Default: no port.
    #[arg(long, env = "TRIBOD_HEALTH_ADDR")]
    health_addr: Option<String>,
}

#[derive(clap::Args)]
struct ServeArgs {
    /// Address to listen on.
    #[arg(long, env = "TRIBOD_ADDR", default_value = "127.0.0.1:8080")]
    addr: String,
    #[command(flatten)]
    queue: QueueArgs,
    /// Bearer token(s) required on /v1 routes (comma-separated). Never logged.
    #[arg(long, env = "TRIBOD_API_TOKEN", value_delimiter = ',', hide_env_values = true)]
    api_token: Vec<String>,
    /// File with one bearer token per line (`#` comments).
    #[arg(long, env = "TRIBOD_API_TOKENS_FILE")]
    api_tokens_file: Option<std::path::PathBuf>,
    /// Allowed CORS origins (comma-separated, `*` for any). Default: no CORS.
    #[arg(long, env = "TRIBOD_CORS_ORIGINS", value_delimiter = ',')]
    cors_origin: Vec<String>,
    /// Largest request body, bytes.
    #[arg(long, env = "TRIBOD_BODY_LIMIT", default_value_t = 1 << 20)]
    body_limit: usize,
    /// Longest `Prefer: wait=N` honoured, seconds.
    #[arg(long, env = "TRIBOD_MAX_WAIT", default_value_t = 300.0)]
    max_wait: f64,
    /// Open connections at once; at the cap a new one takes the place of the connection waiting
    /// longest on its client (503 only when all are busy); lowered to fit the open-files limit.
    #[arg(long, env = "TRIBOD_MAX_CONNECTIONS", default_value_t = 4096)]
    max_connections: usize,
    /// Seconds a client has to send a request's headers, in total (also closes idle keep-alive
    /// connections).
    #[arg(long, env = "TRIBOD_HEADER_TIMEOUT", default_value_t = 10.0)]
    header_timeout: f64,
    /// Seconds a client has to send a request's body, in total, counted from its headers (408).
    #[arg(long, env = "TRIBOD_BODY_TIMEOUT", default_value_t = 30.0)]
    body_timeout: f64,
}

#[derive(clap::Args)]
struct LimitArgs {
    /// Most nodes in one solver grid.
    #[arg(long, env = "TRIBOD_MAX_GRID_NODES", default_value_t = Limits::default().max_grid_nodes)]
    max_grid_nodes: usize,
    /// Most cam angles in one cycle.
    #[arg(long, env = "TRIBOD_MAX_ANGLES", default_value_t = Limits::default().max_angles)]
    max_angles: usize,
    /// Most cases in one sweep.
    #[arg(long, env = "TRIBOD_MAX_SWEEP_CASES", default_value_t = Limits::default().max_sweep_cases)]
    max_sweep_cases: usize,
    /// Most solver evaluations in one optimisation.
    #[arg(long, env = "TRIBOD_MAX_EVALUATIONS", default_value_t = Limits::default().max_evaluations)]
    max_evaluations: usize,
    /// Most memory one job may need by the solvers' memory models, MiB.
    #[arg(long, env = "TRIBOD_MAX_JOB_MEMORY_MB", default_value_t = Limits::default().max_job_memory >> 20)]
    max_job_memory_mb: u64,
    /// Most solver time one job may need by the solvers' work models, seconds of one core.
    #[arg(long, env = "TRIBOD_MAX_JOB_SECONDS", default_value_t = Limits::default().max_job_seconds)]
    max_job_seconds: f64,
}

impl LimitArgs {
    fn limits(&self) -> Limits {
        Limits {
            max_grid_nodes: self.max_grid_nodes,
            max_angles: self.max_angles,
            max_sweep_cases: self.max_sweep_cases,
            max_evaluations: self.max_evaluations,
            max_job_memory: self.max_job_memory_mb.saturating_mul(1 << 20),
            max_job_seconds: if self.max_job_seconds > 0.0 { self.max_job_seconds } else { f64::INFINITY },
        }
    }
}

#[derive(clap::Args)]
struct RunArgs {
    /// Job file `{"kind": ..., "spec": ...}`, or `-` for standard input.
    spec: String,
    /// Output format.
    #[arg(long, value_enum, default_value_t = RunFormat::Json)]
    format: RunFormat,
    /// With `--format csv`: which table of the result (default: the kind's first).
    #[arg(long)]
    table: Option<String>,
    /// One-line JSON instead of pretty-printed.
    #[arg(long)]
    compact: bool,
    /// Also write the kind's plots of the result into this directory, as `<name>.svg`.
    #[arg(long)]
    plots: Option<std::path::PathBuf>,
    #[command(flatten)]
    limits: LimitArgs,
}

#[derive(Clone, Copy, ValueEnum, PartialEq)]
enum RunFormat {
    Json,
    Csv,
}

fn main() -> ExitCode {
    let cli = Cli::parse();
    // One job per worker thread: faer's kernels (sparse and dense LU) run on the job's own thread.
    // Nested parallelism inside a job competes with the other workers and spins: measured on the
    // seed 000 finite cycle, 36 angles, release, 22.9 → 17.9 s and kernel time 9.8 → 4.1 s
    // (BENCHMARKS.md, issue 16). The benches run so too.
    faer::set_global_parallelism(faer::Par::Seq);
    match cli.command {
        Command::Serve(args) => {
            init_tracing(cli.log_format);
            serve(args)
        }
        Command::Worker(args) => {
            init_tracing(cli.log_format);
            worker(args)
        }
        Command::Run(args) => {
            init_tracing(cli.log_format);
            run(args)
        }
        Command::Openapi => {
            println!("{}", serde_json::to_string_pretty(&tribod::api::openapi()).unwrap_or_default());
            ExitCode::SUCCESS
        }
    }
}

fn init_tracing(format: LogFormat) {
    let filter = tracing_subscriber::EnvFilter::try_from_default_env()
        .unwrap_or_else(|_| tracing_subscriber::EnvFilter::new("info,sqlx=warn,tower_http=info"));
    use std::io::IsTerminal;
    let builder = tracing_subscriber::fmt()
        .with_env_filter(filter)
        .with_writer(std::io::stderr)
        .with_ansi(std::io::stderr().is_terminal());
    match format {
        LogFormat::Pretty => builder.init(),
        LogFormat::Json => builder.json().flatten_event(true).init(),
    }
}

fn worker(args: WorkerArgs) -> ExitCode {
    let default_workers = QueueConfig::default().workers;
    let config = server::WorkerConfig {
        database_url: args.queue.database_url.clone(),
        queue: args.queue.queue(default_workers),
        shutdown_grace: Duration::from_secs_f64(args.queue.shutdown_grace.max(0.0)),
        health_addr: args.health_addr.clone(),
    };
    if config.queue.workers == 0 {
        eprintln!("tribod: a worker needs --workers of at least 1");
        return ExitCode::from(2);
    }
    let runtime = match tokio::runtime::Builder::new_multi_thread().enable_all().build() {
        Ok(r) => r,
        Err(e) => {
            eprintln!("tribod: cannot start the async runtime: {e}");
            return ExitCode::FAILURE;
        }
    };
    match runtime.block_on(server::work(config)) {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("tribod: {e}");
            ExitCode::FAILURE
        }
    }
}

fn serve(args: ServeArgs) -> ExitCode {
    // A blank token would silently switch authentication off: refuse it.
    if args.api_token.iter().any(|t| t.trim().is_empty()) {
        eprintln!("tribod: --api-token (TRIBOD_API_TOKEN) holds an empty or blank token; give real tokens or none");
        return ExitCode::from(2);
    }
    let mut tokens: Vec<String> = args.api_token.iter().map(|t| t.trim().to_string()).collect();
    if let Some(path) = &args.api_tokens_file {
        match std::fs::read_to_string(path) {
            Ok(text) => tokens.extend(
                text.lines().map(str::trim).filter(|l| !l.is_empty() && !l.starts_with('#')).map(String::from),
            ),
            Err(e) => {
                eprintln!("tribod: cannot read tokens file {}: {e}", path.display());
                return ExitCode::from(2);
            }
        }
    }
    let config = ServeConfig {
        addr: args.addr,
        database_url: args.queue.database_url.clone(),
        queue: args.queue.queue(QueueConfig::default().workers),
        api: ApiConfig {
            tokens,
            cors_origins: args.cors_origin,
            body_limit: args.body_limit,
            max_wait: Duration::from_secs_f64(args.max_wait.max(0.0)),
            body_timeout: Duration::from_secs_f64(args.body_timeout.max(0.1)),
        },
        shutdown_grace: Duration::from_secs_f64(args.queue.shutdown_grace.max(0.0)),
        connections: server::ConnectionLimits {
            max_connections: args.max_connections.max(1),
            header_timeout: Duration::from_secs_f64(args.header_timeout.max(0.1)),
        },
    };
    if !config.api.tokens.is_empty() {
        tracing::info!(tokens = config.api.tokens.len(), "bearer authentication on /v1");
    }
    let runtime = match tokio::runtime::Builder::new_multi_thread().enable_all().build() {
        Ok(r) => r,
        Err(e) => {
            eprintln!("tribod: cannot start the async runtime: {e}");
            return ExitCode::FAILURE;
        }
    };
    // One machine-readable line on stdout: scripts and tests started with `--addr …:0` read it.
    let on_bound = |addr| println!("tribod listening on http://{addr}");
    match runtime.block_on(server::serve(config, on_bound)) {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("tribod: {e}");
            ExitCode::FAILURE
        }
    }
}

/// Print a problem as JSON on stderr and return `code`.
fn fail(problem: &Problem, code: u8) -> ExitCode {
    eprintln!("{}", serde_json::to_string_pretty(problem).unwrap_or_default());
    ExitCode::from(code)
}

/// Every plot of a result as `<dir>/<name>.svg`; the files written are listed on stderr.
fn write_plots(dir: &std::path::Path, kind: &str, result: &serde_json::Value, label: &str) -> Result<(), String> {
    std::fs::create_dir_all(dir).map_err(|e| e.to_string())?;
    for def in tribod::plots::available(kind, result) {
        let svg = tribod::plots::render_plot(&def, label).map_err(|e| e.to_string())?;
        let path = dir.join(format!("{}.svg", def.name));
        std::fs::write(&path, svg).map_err(|e| format!("{}: {e}", path.display()))?;
        eprintln!("{}", path.display());
    }
    Ok(())
}

fn run(args: RunArgs) -> ExitCode {
    let text = if args.spec == "-" {
        let mut s = String::new();
        if let Err(e) = std::io::stdin().read_to_string(&mut s) {
            return fail(&Problem::new(ErrorCode::MalformedJson, format!("reading stdin: {e}")), 2);
        }
        s
    } else {
        match std::fs::read_to_string(&args.spec) {
            Ok(s) => s,
            Err(e) => {
                // Not the JSON's fault: the file could not be read (missing, a directory, no access).
                return fail(&Problem::new(ErrorCode::InvalidRequest, format!("cannot read the spec file {}: {e}", args.spec)), 2);
            }
        }
    };
    let request: serde_json::Value = match serde_json::from_str(&text) {
        Ok(v) => v,
        Err(e) => return fail(&Problem::new(ErrorCode::MalformedJson, e.to_string()), 2),
    };
    let request: tribod::api::jobs::JobRequest = match tribod::jobs::kind::parse_value(&request) {
        Ok(r) => r,
        Err(e) => {
            return fail(
                &Problem::new(ErrorCode::InvalidRequest, format!("{}: {}", e.path, e.message)).with_errors(vec![e]),
                2,
            )
        }
    };
    let Some(kind) = registry::find(&request.kind) else {
        let p = Problem::new(
            ErrorCode::UnknownKind,
            format!("no job kind named '{}'; known kinds: {}", request.kind, registry::names().join(", ")),
        );
        return fail(&p, 2);
    };
    let prepared = match kind.prepare(&request.spec, &args.limits.limits()) {
        Ok(p) => p,
        Err(p) => return fail(&p.under("/spec"), 2),
    };
    for w in &prepared.warnings {
        eprintln!("warning: /spec{}: {}", w.path, w.message);
    }
    tribod::jobs::warm_up();
    let (outcome, _) = runner::run(prepared, &Silent);
    let value = match outcome {
        runner::Outcome::Succeeded(v) => v,
        runner::Outcome::Failed(p) => return fail(&p, 1),
        runner::Outcome::Interrupted(i) => {
            return fail(&Problem::new(ErrorCode::Interrupted, format!("{i:?}")), 1);
        }
    };
    if let Some(dir) = &args.plots {
        let label = request.label.clone().unwrap_or_else(|| args.spec.clone());
        if let Err(e) = write_plots(dir, kind.name(), &value, &label) {
            return fail(&Problem::new(ErrorCode::InternalError, format!("writing plots to {}: {e}", dir.display())), 1);
        }
    }
    if args.format == RunFormat::Csv {
        let tables = kind.tables();
        let name = args.table.as_deref().or(tables.first().copied());
        let Some(part) = name.filter(|n| tables.contains(n)).and_then(|n| value.get(n)) else {
            let p = Problem::new(
                ErrorCode::NotAcceptable,
                format!("no such table in this result; kind '{}' has: {}", kind.name(), tables.join(", ")),
            );
            return fail(&p, 2);
        };
        return match table::to_csv(part, &*table::units_of(Some(kind), &value, name.unwrap_or_default())) {
            Ok(csv) => {
                print!("{csv}");
                ExitCode::SUCCESS
            }
            Err(e) => fail(&Problem::new(ErrorCode::InternalError, e), 1),
        };
    }
    let out = if args.compact { serde_json::to_string(&value) } else { serde_json::to_string_pretty(&value) };
    println!("{}", out.unwrap_or_default());
    ExitCode::SUCCESS
}
