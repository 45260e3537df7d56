//! What a job will cost before it runs: the work and memory models of its solvers.
//!
//! Every kind answers [`super::kind::Kind::cost`] from its validated spec: CPU seconds of one
//! core of the reference machine (a 2-core VM of BENCHMARKS.md, release build) and the peak
//! memory its solvers allocate. The server refuses a spec whose estimate exceeds
//! `--max-job-seconds` or `--max-job-memory-mb` (`limit_exceeded`, naming the field that drives
//! the cost), stores the estimate with the job (`GET /v1/jobs/{id}` → `estimate`), schedules by
//! it (fair scheduling's virtual deadline) and adds it to the result's `meta`.
//!
//! The unit costs below are calibrated against measured release runs (`cargo bench --bench cost`
//! runs the examples and a spread of grids and angle counts through `tribod run` and prints model
//! against measured CPU time and peak resident memory; BENCHMARKS.md, "Work and memory models").
//! The models aim at a factor 2 in time and an upper bound within 1.5× in memory; the job
//! timeout (`--job-timeout`) still bounds what a model misses.

use serde::{Deserialize, Serialize};
use utoipa::ToSchema;

/// Bytes of one MiB.
pub const MIB: f64 = 1_048_576.0;

/// A job's estimated cost (CPU time of one core and peak memory of its solvers).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize, ToSchema)]
pub struct Estimate {
    /// CPU time by the work model, s (one core of the reference machine, release build). A job
    /// that runs cases in parallel finishes sooner on more cores.
    pub cpu_seconds: f64,
    /// Peak memory of the solvers by the memory model, bytes (above the idle process).
    pub memory_bytes: f64,
}

/// A job's cost and the spec fields that drive it (named by a refusal).
#[derive(Debug, Clone, PartialEq)]
pub struct Cost {
    pub estimate: Estimate,
    /// JSON pointer (relative to the spec) of the field that drives the time.
    pub work_path: String,
    /// What takes the time, in an engineer's words ("360 angles of the 2-D EHL solver on 65×129").
    pub work_what: String,
    /// JSON pointer of the field that drives the memory.
    pub memory_path: String,
    /// What takes the memory.
    pub memory_what: String,
}

impl Cost {
    /// A cost of `cpu_seconds` and `memory_bytes`, driven by the spec as a whole.
    pub fn new(cpu_seconds: f64, memory_bytes: f64) -> Self {
        Cost {
            estimate: Estimate { cpu_seconds: sane(cpu_seconds), memory_bytes: sane(memory_bytes) },
            work_path: String::new(),
            work_what: "the job".into(),
            memory_path: String::new(),
            memory_what: "the job".into(),
        }
    }

    /// The field (JSON pointer) and description of what takes the time.
    pub fn work_at(mut self, path: impl Into<String>, what: impl Into<String>) -> Self {
        self.work_path = path.into();
        self.work_what = what.into();
        self
    }

    /// The field and description of what takes the memory.
    pub fn memory_at(mut self, path: impl Into<String>, what: impl Into<String>) -> Self {
        self.memory_path = path.into();
        self.memory_what = what.into();
        self
    }

    /// Both paths under `prefix` (a nested spec, e.g. a wear job's `/cycle`).
    pub fn under(mut self, prefix: &str) -> Self {
        self.work_path = format!("{prefix}{}", self.work_path);
        self.memory_path = format!("{prefix}{}", self.memory_path);
        self
    }

    /// This cost `times` over (the same work repeated), memory unchanged.
    pub fn repeated(mut self, times: f64) -> Self {
        self.estimate.cpu_seconds = sane(self.estimate.cpu_seconds * times);
        self
    }

    /// Add `seconds` of other work.
    pub fn plus_seconds(mut self, seconds: f64) -> Self {
        self.estimate.cpu_seconds = sane(self.estimate.cpu_seconds + seconds);
        self
    }

    pub fn cpu_seconds(&self) -> f64 {
        self.estimate.cpu_seconds
    }

    pub fn memory_bytes(&self) -> f64 {
        self.estimate.memory_bytes
    }
}

/// A model's number as a finite non-negative value (an overflowing product is "too much", never
/// NaN: `+∞` is clamped to `f64::MAX` so that it still compares above every limit and serialises).
fn sane(x: f64) -> f64 {
    if x.is_nan() {
        f64::MAX
    } else {
        x.clamp(0.0, f64::MAX)
    }
}

/// Human-readable seconds: "0.3 s", "40 s", "12 min", "3.2 h", "41 days".
pub fn describe_seconds(s: f64) -> String {
    if s < 10.0 {
        format!("{s:.2} s")
    } else if s < 120.0 {
        format!("{s:.0} s")
    } else if s < 7200.0 {
        format!("{:.0} min", s / 60.0)
    } else if s < 172_800.0 {
        format!("{:.1} h", s / 3600.0)
    } else {
        format!("{:.0} days", s / 86_400.0)
    }
}

// ---- Unit costs of the solvers (release, one core of the reference machine) ----------------
// Each is calibrated against `cargo bench --bench cost` (BENCHMARKS.md, "Work and memory
// models"); the comment of each says what it was fitted to.

/// A kind's fixed cost: parsing, result assembly and serialisation, s.
pub const JOB_OVERHEAD_S: f64 = 2e-4;

/// The process-wide tables of the asperity contact (Greenwood–Tripp integrals), built once per
/// process (a server builds them at start, `Queue::start`), s: not part of any job's estimate;
/// `benches/cost.rs` takes them off a `tribod run` of a cam kind.
pub const PROCESS_TABLES_S: f64 = 0.12;

/// A cam cycle's fixed cost (profile tables, closed-form setup, result assembly), s.
pub const CYCLE_BASE_S: f64 = 0.02;

/// One cam angle by the closed forms (kinematics, Hertz, film, friction, temperature, the
/// roller's slip), s, in a `cam_cycle` job (its series serialised).
pub const FAST_ANGLE_S: f64 = 2.0e-5;

/// One cam angle by the closed forms inside a wear run's cycles (no series kept), s: the seed 003
/// flat-faced wear run of 101 cycles × 720 angles takes 1.8 s, the seed 000 roller's 1.0 s.
pub const WEAR_ANGLE_S: f64 = 2.0e-5;

/// One numerical line-contact solve (`physics::ehl`, dense Newton) on `nodes` nodes from a cold
/// start, s (with `richardson`, plus the half grid): 23 ms at 385 nodes growing as nodes^1.96
/// (fitted to `ehl_point` at 129–2049 nodes), plus 5 ms of set-up.
pub fn ehl_line_seconds(nodes: usize, richardson: bool) -> f64 {
    let n = nodes as f64;
    let one = 0.0232 * (n / 385.0).powf(1.96);
    5e-3 + if richardson { one } else { one / 1.25 }
}

/// A line-contact film along a cycle against a cold solve: the warm start from the previous
/// angle, and films reused by the roller's later passes (the seed 000 roller at 360 angles and
/// the seed 003 wear run fit 0.1–0.15).
pub const WARM_LINE_FRACTION: f64 = 0.12;

/// The thermal line-contact model (`physics::ehl::thermal`) on `nodes` nodes with `film_points`
/// levels across the film and `solid_points` in each solid: its fixed cost per run (the first
/// coupled solve and the traction table's energy solves), s.
pub fn ehl_thermal_seconds(nodes: usize, film_points: usize, solid_points: usize) -> f64 {
    1.2 * (nodes as f64 / 96.0).powf(1.5) * thermal_layers(film_points, solid_points)
}

/// The thermal model's cost per cam angle solved in full, s: 14 ms at 96 nodes and the default
/// layers (the seed 000 thermal cycle: 1.8 s at 36 angles, 2.5 s at 72, 6.2 s at 360).
pub fn ehl_thermal_angle_seconds(nodes: usize, film_points: usize, solid_points: usize) -> f64 {
    0.014 * (nodes as f64 / 96.0).powf(2.0) * thermal_layers(film_points, solid_points)
}

fn thermal_layers(film_points: usize, solid_points: usize) -> f64 {
    ((film_points as f64 + 2.0 * solid_points as f64) / 39.0).max(0.2)
}

/// One cold 2-D EHL solve (`physics::ehl::twod`, nested iteration, resolution check) on
/// `nx × ny` nodes, s: ≈ nodes^1.4 (the seed 000 roller at 65×129: 0.75–0.85 s; the circular
/// point contact at 129²: 1.65 s; BENCHMARKS.md, "One point solve, run time against error").
pub fn ehl_2d_seconds(nx: usize, ny: usize) -> f64 {
    let n = nx as f64 * ny as f64;
    0.3 * (n / 4225.0).powf(1.4)
}

/// The thermal finite-line / point model on `nx × ny` nodes on top of its isothermal start, s:
/// about four coupling passes, each the row energies (≈ 5 ms a row of 65 columns at the default
/// layers, debug build; seed 000's nose on 65×129: 0.5–0.9 s a pass on 2 threads) and a warm 2-D
/// solve (a fifth of a cold one).
pub fn ehl_thermal_2d_seconds(nx: usize, ny: usize, film_points: usize, solid_points: usize) -> f64 {
    let rows = ny as f64 * (nx as f64 / 65.0) * 0.005 * thermal_layers(film_points, solid_points);
    4.0 * (rows + 0.2 * ehl_2d_seconds(nx, ny))
}

/// One 2-D film along a cam cycle against a cold solve, by the angle step (degrees): a step of
/// 45° is as costly as a cold solve; the warm start (and the squeeze step's short pseudo-time)
/// makes fine steps cheap (the seed 000 finite cycle at 33×65: 0.13 s an angle at 8 angles,
/// 37 ms at 36, 18 ms at 90).
pub fn ehl_2d_step_fraction(step_deg: f64) -> f64 {
    (0.05 + 0.02 * step_deg).min(1.0)
}

/// Peak memory of one 2-D EHL solve on `nx × ny` nodes, bytes: node arrays, the padded FFT
/// buffers of the elastic kernel, the near-field sparse LU (single precision since issue 46) and
/// flexible GMRES' basis (two vectors per iteration): an upper bound of ≈ 8 kB per node (peak
/// resident memory of `tribod run` above idle: 104 MiB at 129², 464 MiB at 257²; with the double
/// LU before, 140 / 610 / 2585 MiB at 129² / 257² / 513²: 513² not measured again, ≈ 7.8 kB per
/// node by the ratio at the two smaller grids).
pub fn ehl_2d_bytes(nx: usize, ny: usize) -> f64 {
    let n = nx as f64 * ny as f64;
    8.0 * n * 1000.0 + 8.0 * MIB
}

/// Memory a cam cycle keeps per angle of a 2-D film (the converged pressure and mass fields as
/// the next pass's warm start), bytes per grid node.
pub const EHL_2D_KEPT_BYTES_PER_NODE: f64 = 32.0;

/// Peak memory of one dense line-contact solve on `nodes` nodes (with its Richardson half grid),
/// bytes: the influence and Newton matrices (`physics::ehl::dense_memory_bytes`) and 35 % of
/// scratch, plus 3 MiB of threads and tables (measured 6 MiB at 385 nodes, 32 at 1025, 118 at
/// 2049).
pub fn ehl_line_bytes(nodes: usize) -> f64 {
    1.35 * crate::physics::ehl::dense_memory_bytes(nodes) + 3.0 * MIB
}

/// A cam-kind job's resident baseline above an idle process (the rayon pool's threads, the
/// profile tables), bytes.
pub const CAM_BASE_BYTES: f64 = 4.0 * MIB;

/// One load-balanced bearing analysis on `nodes` grid nodes, s: 2 ms and 0.4 µs per node
/// (the seed 002 bearing at 91×45, 181×91, 361×181 and 721×361).
pub fn bearing_analysis_seconds(nodes: usize) -> f64 {
    2e-3 + 0.4e-6 * nodes as f64
}
