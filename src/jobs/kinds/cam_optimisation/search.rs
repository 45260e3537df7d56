//! The search: the baseline, a seeded Latin hypercube over the variables (in parallel on the
//! worker pool), then Nelder–Mead on the continuous variables from the best designs of the
//! distinct categorical choices (in parallel), a penalty keeping it feasible.

use super::evaluate::{self as ev, Judged, Limit, Measured, Outcome, Point};
use super::spec::CamOptimisationSpec;
use crate::physics::numerics::nelder_mead::nelder_mead;
use crate::physics::{Observer, SolveError};
use rayon::prelude::*;
use std::sync::atomic::{AtomicUsize, Ordering};

/// Where a design comes from.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Phase {
    Baseline,
    Sample,
    Search,
}

impl Phase {
    pub fn name(self) -> &'static str {
        match self {
            Phase::Baseline => "baseline",
            Phase::Sample => "sample",
            Phase::Search => "search",
        }
    }
}

/// One evaluated design.
#[derive(Debug, Clone, PartialEq)]
pub struct Record {
    pub phase: Phase,
    pub point: Option<Point>,
    pub outcome: Outcome,
}

/// Every design of the search, the baseline first, and the constraints' absolute limits.
pub struct Searched {
    pub records: Vec<Record>,
    pub limits: Vec<Limit>,
}

/// SplitMix64: a small seeded generator (same seed, same hypercube on every machine).
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }
    /// Uniform in [0, 1).
    fn unit(&mut self) -> f64 {
        (self.next() >> 11) as f64 / (1u64 << 53) as f64
    }
    fn shuffle(&mut self, v: &mut [usize]) {
        for i in (1..v.len()).rev() {
            let j = (self.next() % (i as u64 + 1)) as usize;
            v.swap(i, j);
        }
    }
}

/// `n` points of a Latin hypercube: every variable's range cut in `n` strata, one point in each
/// (categorical choices by stratum, so each appears about equally often).
pub fn hypercube(spec: &CamOptimisationSpec, n: usize, seed: u64) -> Vec<Point> {
    let mut rng = Rng(seed);
    let mut points: Vec<Point> = (0..n).map(|_| Point { u: Vec::new(), choice: Vec::new() }).collect();
    for v in &spec.variables {
        let mut strata: Vec<usize> = (0..n).collect();
        rng.shuffle(&mut strata);
        for (p, s) in points.iter_mut().zip(&strata) {
            let t = (*s as f64 + rng.unit()) / n as f64;
            match &v.values {
                Some(vals) => p.choice.push(((*s * vals.len()) / n.max(1)).min(vals.len().saturating_sub(1))),
                None => p.u.push(t),
            }
        }
    }
    points
}

/// Designs the search will evaluate at most: the baseline, the sample, every start's budget.
pub fn planned(spec: &CamOptimisationSpec) -> usize {
    let continuous = spec.variables.iter().any(|v| v.is_continuous());
    let search = if continuous { spec.search.starts.saturating_mul(spec.search.iterations) } else { 0 };
    1usize.saturating_add(spec.search.samples).saturating_add(search)
}

/// The records' order of merit: feasible before infeasible, then by score (feasible) or
/// violation (infeasible); failed designs last. Ties keep evaluation order.
pub fn rank(judged: &[Option<Judged>]) -> Vec<usize> {
    let key = |j: &Option<Judged>| match j {
        Some(j) if j.feasible => (0, j.score),
        Some(j) => (1, j.violation),
        None => (2, 0.0),
    };
    let mut order: Vec<usize> = (0..judged.len()).collect();
    order.sort_by(|&a, &b| {
        let (ka, kb) = (key(&judged[a]), key(&judged[b]));
        ka.0.cmp(&kb.0).then(ka.1.total_cmp(&kb.1))
    });
    order
}

/// Judge every record against the baseline.
pub fn judge_all(spec: &CamOptimisationSpec, records: &[Record], baseline: &Measured, limits: &[Limit]) -> Vec<Option<Judged>> {
    records
        .iter()
        .map(|r| match &r.outcome {
            Outcome::Measured(m) => Some(ev::judge(spec, m, baseline, limits)),
            Outcome::Failed { .. } => None,
        })
        .collect()
}

/// Progress over the planned evaluations.
struct Progress<'a> {
    observer: &'a dyn Observer,
    done: AtomicUsize,
    total: usize,
}

impl Progress<'_> {
    fn tick(&self, stage: &str) {
        let n = self.done.fetch_add(1, Ordering::Relaxed) + 1;
        self.observer.progress((n as f64 / self.total.max(1) as f64).min(1.0), stage);
    }
}

/// Why one Nelder–Mead run stopped early.
enum Stop {
    Budget,
    Solve(SolveError),
}

/// The search.
pub fn search(spec: &CamOptimisationSpec, observer: &dyn Observer) -> Result<Searched, SolveError> {
    let progress = Progress { observer, done: AtomicUsize::new(0), total: planned(spec) };
    let baseline = ev::evaluate_baseline(spec, observer)?;
    progress.tick("baseline");
    let base = match &baseline {
        Outcome::Measured(m) => (**m).clone(),
        Outcome::Failed { code, detail, .. } => {
            return Err(SolveError::invalid("/base", format!("the baseline design (the base spec) fails: {code}: {detail}")));
        }
    };
    let limits = ev::limits(spec, &base)?;
    let mut records = vec![Record { phase: Phase::Baseline, point: ev::baseline_point(spec), outcome: baseline }];
    let sample: Vec<Result<Record, SolveError>> = hypercube(spec, spec.search.samples, spec.search.seed)
        .into_par_iter()
        .map(|p| {
            let outcome = ev::evaluate(spec, &p, observer)?;
            progress.tick("sample");
            Ok(Record { phase: Phase::Sample, point: Some(p), outcome })
        })
        .collect();
    observer.check()?;
    for r in sample {
        records.push(r?);
    }
    let n_continuous = spec.variables.iter().filter(|v| v.is_continuous()).count();
    if n_continuous > 0 && spec.search.iterations > 0 {
        let starts = starts(spec, &records, &base, &limits);
        let runs: Vec<Result<Vec<Record>, SolveError>> =
            starts.into_par_iter().map(|p| descend(spec, p, &base, &limits, &progress)).collect();
        observer.check()?;
        for r in runs {
            records.extend(r?);
        }
    }
    Ok(Searched { records, limits })
}

/// The starts of the descent: the best design of each distinct categorical choice, best first.
fn starts(spec: &CamOptimisationSpec, records: &[Record], base: &Measured, limits: &[Limit]) -> Vec<Point> {
    let judged = judge_all(spec, records, base, limits);
    let mut out: Vec<Point> = Vec::new();
    for i in rank(&judged) {
        let (Some(p), Some(_)) = (&records[i].point, &judged[i]) else { continue };
        if out.len() < spec.search.starts && !out.iter().any(|q| q.choice == p.choice) {
            out.push(p.clone());
        }
    }
    out
}

/// Nelder–Mead over the continuous variables (normalised to [0, 1]) from `start`, the
/// categorical choices held; every design it evaluates is kept.
fn descend(spec: &CamOptimisationSpec, start: Point, base: &Measured, limits: &[Limit], progress: &Progress) -> Result<Vec<Record>, SolveError> {
    let n = start.u.len();
    let budget = spec.search.iterations;
    let mut records: Vec<Record> = Vec::new();
    let f = |u: &[f64]| -> Result<f64, Stop> {
        if records.len() >= budget {
            return Err(Stop::Budget);
        }
        let p = Point { u: u.to_vec(), choice: start.choice.clone() };
        let outcome = ev::evaluate(spec, &p, progress.observer).map_err(Stop::Solve)?;
        progress.tick("search");
        let value = match &outcome {
            Outcome::Measured(m) => ev::judge(spec, m, base, limits).penalised(),
            Outcome::Failed { .. } => 1e6,
        };
        records.push(Record { phase: Phase::Search, point: Some(p), outcome });
        Ok(value)
    };
    let step = vec![0.15; n];
    let (lo, hi) = (vec![0.0; n], vec![1.0; n]);
    match nelder_mead(f, &start.u, &step, &lo, &hi, budget, 1e-6) {
        Ok(_) | Err(Stop::Budget) => Ok(records),
        Err(Stop::Solve(e)) => Err(e),
    }
}
