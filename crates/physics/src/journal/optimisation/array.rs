//! The orthogonal array on the rayon pool, every analysis on a reset workspace
//! (`Workspace::reset`), so its result is the same bit for bit whichever worker runs it after
//! whichever analysis, for any pool size. The order (BENCHMARKS.md, journal speed, fourteenth
//! round):
//! 1. the runs, each worker taking the next from a shared counter;
//! 2. the unprofiled baseline, which nothing else needs, by the first worker without a run;
//! 3. the confirmation of the best-level combination (when it is not a run), by the worker
//!    that completes the array. It then overlaps the baseline instead of following the array
//!    on one thread.
//!
//! A worker left with nothing while runs are still in flight (more workers than these tasks)
//! guesses the best levels ([`predicted_best_levels`]) and starts that confirmation
//! speculatively; a wrong guess is abandoned as soon as the last run is in and costs only that
//! idle worker's time.

use super::*;
use rayon::prelude::*;
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};
use std::sync::Mutex;

/// What the array leaves: the designs (the baseline first, then the runs), the confirmation
/// done on the way (if any), and the workers' workspaces.
pub(super) struct Outcome {
    pub(super) done: Vec<Option<Design>>,
    pub(super) confirmation: Option<([usize; 3], Design)>,
    pub(super) workspaces: Vec<Workspace>,
}

/// The state the workers share.
struct Scheduler<'a> {
    ev: &'a Evaluator<'a>,
    rows: &'a [[usize; 3]],
    levels: usize,
    /// The baseline (`None`) and the runs' profiles.
    cases: &'a [Option<Profile>],
    observer: &'a dyn Observer,
    runs_total: usize,
    next: AtomicUsize,
    failed: AtomicBool,
    baseline_taken: AtomicBool,
    done: Mutex<Vec<Option<Design>>>,
    /// 0: the array is not complete; else 1 + the index of its best-level combination
    known_best: AtomicUsize,
    /// 0: no speculation started; else 1 + the index of the combination speculated on
    speculated: AtomicUsize,
    confirmation_taken: AtomicBool,
    confirmation: Mutex<Option<([usize; 3], Design)>>,
    spare: Mutex<Vec<Workspace>>,
}

/// Run the array's `cases` (the baseline, then the runs of `rows`) on `workers` workers, with
/// the workspaces `spares` (one each).
pub(super) fn run(
    ev: &Evaluator,
    rows: &[[usize; 3]],
    levels: usize,
    cases: &[Option<Profile>],
    spares: Vec<Workspace>,
    workers: usize,
    observer: &dyn Observer,
) -> Result<Outcome, SolveError> {
    let s = Scheduler {
        ev,
        rows,
        levels,
        cases,
        observer,
        runs_total: cases.len() - 1,
        next: AtomicUsize::new(0),
        failed: AtomicBool::new(false),
        baseline_taken: AtomicBool::new(false),
        done: Mutex::new(vec![None; cases.len()]),
        known_best: AtomicUsize::new(0),
        speculated: AtomicUsize::new(0),
        confirmation_taken: AtomicBool::new(false),
        confirmation: Mutex::new(None),
        spare: Mutex::new(spares),
    };
    let workspaces: Vec<Workspace> = (0..workers).into_par_iter().map(|_| s.worker()).collect::<Result<_, _>>()?;
    Ok(Outcome {
        done: s.done.into_inner().unwrap_or_else(|e| e.into_inner()),
        confirmation: s.confirmation.into_inner().unwrap_or_else(|e| e.into_inner()),
        workspaces,
    })
}

impl Scheduler<'_> {
    fn combo_index(&self, c: &[usize; 3]) -> usize {
        let levels = self.levels;
        1 + (c[0] * levels + c[1]) * levels + c[2]
    }

    fn combo_of(&self, index: usize) -> [usize; 3] {
        let levels = self.levels;
        let i = index - 1;
        [i / (levels * levels), (i / levels) % levels, i % levels]
    }

    fn fail(&self, e: SolveError) -> SolveError {
        self.failed.store(true, Ordering::SeqCst);
        e
    }

    fn confirm(&self, ws: &mut Workspace, combo: [usize; 3], observer: &dyn Observer) -> Result<(), SolveError> {
        ws.reset();
        let pr = self.ev.problem;
        let (d, _) = self.ev.design(&pr.settings, Some(pr.profile(&combo)), Some(ws), observer)?;
        *self.confirmation.lock().unwrap_or_else(|e| e.into_inner()) = Some((combo, d));
        Ok(())
    }

    /// One worker: runs while there are runs, then the baseline, then the confirmation (or a
    /// speculation on it). Returns its workspace.
    fn worker(&self) -> Result<Workspace, SolveError> {
        let pr = self.ev.problem;
        let mut ws = self.spare.lock().ok().and_then(|mut s| s.pop()).unwrap_or_else(|| Workspace::new(&pr.bearing, &pr.settings));
        loop {
            if self.failed.load(Ordering::SeqCst) {
                break;
            }
            let run = self.next.fetch_add(1, Ordering::SeqCst);
            let case = if run < self.runs_total {
                Some(run + 1)
            } else if !self.baseline_taken.swap(true, Ordering::SeqCst) {
                Some(0)
            } else {
                None
            };
            if let Some(i) = case {
                self.run_case(&mut ws, i)?;
                continue;
            }
            let known = self.known_best.load(Ordering::SeqCst);
            if known != 0 {
                // the array is complete: its confirmation, unless it is a run or a
                // speculation on the right combination is under way
                let best = self.combo_of(known);
                if !self.rows.contains(&best) && self.speculated.load(Ordering::SeqCst) != known && !self.confirmation_taken.swap(true, Ordering::SeqCst) {
                    self.confirm(&mut ws, best, self.observer).map_err(|e| self.fail(e))?;
                }
                break;
            }
            if self.speculated.load(Ordering::SeqCst) != 0 {
                break;
            }
            if !self.speculate(&mut ws) {
                break;
            }
        }
        Ok(ws)
    }

    /// Case `i` (0: the baseline) on a reset workspace; the best levels once the array is complete.
    fn run_case(&self, ws: &mut Workspace, i: usize) -> Result<(), SolveError> {
        ws.reset();
        let settings = &self.ev.problem.settings;
        let (d, _) = self
            .observer
            .check()
            .map_err(SolveError::from)
            .and_then(|_| self.ev.design(settings, self.cases[i], Some(&mut *ws), self.observer))
            .map_err(|e| self.fail(e))?;
        let mut all = self.done.lock().unwrap_or_else(|e| e.into_inner());
        all[i] = Some(d);
        if i > 0 && all[1..].iter().all(Option::is_some) {
            let designs: Vec<Design> = all[1..].iter().flatten().copied().collect();
            drop(all);
            let best = best_levels(self.rows, self.levels, &sn_ratios(&designs, &self.ev.problem.weights));
            self.known_best.store(self.combo_index(&best), Ordering::SeqCst);
        }
        Ok(())
    }

    /// A speculative confirmation of the guessed best levels by an idle worker. `true`: look
    /// for work again; `false`: this worker is done.
    fn speculate(&self, ws: &mut Workspace) -> bool {
        let weights = &self.ev.problem.weights;
        let runs_so_far: Vec<Option<Design>> = self.done.lock().unwrap_or_else(|e| e.into_inner())[1..].to_vec();
        let Some(combo) = predicted_best_levels(self.rows, self.levels, &runs_so_far, weights) else { return false };
        let mine = self.combo_index(&combo);
        if self.speculated.compare_exchange(0, mine, Ordering::SeqCst, Ordering::SeqCst).is_err() {
            return false;
        }
        let known = self.known_best.load(Ordering::SeqCst);
        if known != 0 && known != mine {
            // the array completed meanwhile with another best: the loop takes its
            // confirmation
            return true;
        }
        if self.confirmation_taken.swap(true, Ordering::SeqCst) {
            // the worker that completed the array took it before seeing this guess
            return false;
        }
        let abandon = Abandon { inner: self.observer, known_best: &self.known_best, failed: &self.failed, mine };
        // an error here (a wrong guess abandoned, a cancel, a failure) is not kept:
        // the confirmation runs again (below or after the array) and reports it
        if self.confirm(ws, combo, &abandon).is_err() && self.known_best.load(Ordering::SeqCst) != mine {
            // abandoned for another combination: take the true confirmation
            self.confirmation_taken.store(false, Ordering::SeqCst);
            self.speculated.store(usize::MAX, Ordering::SeqCst);
            return true;
        }
        false
    }
}

/// A guess of the array's best-level combination while some runs are still running, for
/// starting the confirmation run early: the S/N ratios of the runs done (on their own
/// normalisation), the missing runs' S/N set to one value `s` scanned from below the lowest to
/// above the highest known ratio, and of the combinations that come out and are not runs of
/// the array (only those need a confirmation run) the one that does for the widest range of
/// `s`. `None` when every outcome is a run or too few runs are done. Only a guess: a wrong
/// one costs the idle worker's time, never a result.
fn predicted_best_levels(rows: &[[usize; 3]], levels: usize, runs: &[Option<Design>], weights: &Weights) -> Option<[usize; 3]> {
    let done: Vec<Design> = runs.iter().flatten().copied().collect();
    if done.len() < 2 {
        return None;
    }
    let known = sn_ratios(&done, weights);
    let (lo, hi) = known.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), x| (a.min(*x), b.max(*x)));
    if !(lo.is_finite() && hi.is_finite()) {
        return None;
    }
    let margin = 0.5 * (hi - lo) + 1e-3;
    let mut tally: Vec<([usize; 3], usize)> = Vec::new();
    const SAMPLES: usize = 64;
    for k in 0..=SAMPLES {
        let s = lo - margin + (hi - lo + 2.0 * margin) * k as f64 / SAMPLES as f64;
        let mut it = known.iter();
        let sn: Vec<f64> = runs.iter().map(|r| if r.is_some() { *it.next().unwrap_or(&s) } else { s }).collect();
        let combo = best_levels(rows, levels, &sn);
        if rows.contains(&combo) {
            continue;
        }
        match tally.iter_mut().find(|t| t.0 == combo) {
            Some(t) => t.1 += 1,
            None => tally.push((combo, 1)),
        }
    }
    tally.iter().max_by_key(|t| t.1).map(|t| t.0)
}

/// The observer of a speculative confirmation run: stops it once the array is complete and its
/// best-level combination is another one (`known_best`: 0 while unknown, else 1 + its index),
/// or a case of the array failed.
struct Abandon<'a> {
    inner: &'a dyn Observer,
    known_best: &'a AtomicUsize,
    failed: &'a AtomicBool,
    mine: usize,
}

impl Observer for Abandon<'_> {
    fn progress(&self, fraction: f64, stage: &str) {
        self.inner.progress(fraction, stage);
    }
    fn check(&self) -> Result<(), crate::Interrupt> {
        let known = self.known_best.load(Ordering::Relaxed);
        if (known != 0 && known != self.mine) || self.failed.load(Ordering::Relaxed) {
            return Err(crate::Interrupt::Canceled);
        }
        self.inner.check()
    }
}
