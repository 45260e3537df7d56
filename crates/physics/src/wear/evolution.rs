//! Worn-profile evolution: run the cycle, wear the cam for one update interval at that
//! revolution's rate, rebuild the profile, and repeat until the running time or the wear limit.
//!
//! * Time stepping: explicit (forward Euler) in running time. Within an interval the wear per
//!   revolution is held at the value of the profile at the interval's start; the error is first
//!   order in the interval (the benchmark measures it).
//! * Profile update: the cam point of cam angle `θ` is worn by `w(θ)` along its normal. For a flat
//!   face the support function `r_b + s(θ)` drops by exactly `w(θ)`; for a curved follower (roller,
//!   spherical tappet) the pitch curve moves inward by `w` along the contact normal, so the
//!   follower's centre drops by `w/cos φ` along its axis (φ the pressure angle). The accumulated
//!   lift drop is interpolated by a periodic cubic spline and subtracted from the original,
//!   exact profile ([`CamProfile::Worn`]); the kinematics, loads, contact and film are recomputed
//!   from it. (The follower face's own wear is reported but not fed back into the kinematics.)
//! * Stability: an explicit update is stable only while it wears less than about `0.2 ρ Δθ²`
//!   (see [`STABLE_FRACTION`]); intervals are shortened automatically to half of that.
//! * Termination: the requested time, or the wear limit (the interval that crosses it is cut at
//!   the crossing, which is exact for the Euler step), or a worn profile the pair cannot run on:
//!   the cycle's typed errors (`cam_undercut`, `follower_separation`, `contact_off_face`, …) end
//!   the run and the history up to the last valid profile is returned with the reason.

use crate::cam::summary::{check_contact_on_face, FlatFace};
use super::archard::{face_bins, revolution_wear, ArchardParams, RevolutionWear};
use super::deposit::Bins;
use crate::cam::cycle::{run_cycle, CycleOutput, CycleSpec, Needs};
use crate::cam::{CamProfile, PeriodicSpline};
use crate::film::{FilmModel, FilmModelId};
use crate::{ensure_finite, Convergence, Observer, SolveError};
use std::f64::consts::TAU;

/// Everything an Archard evolution needs.
#[derive(Debug, Clone)]
pub struct WearRun {
    /// The pair on its new profile (steady running).
    pub cycle: CycleSpec,
    /// What the cycle computes (loads and contact at least; film for the asperity share; slip
    /// for a roller).
    pub needs: Needs,
    pub archard: ArchardParams,
    /// Running time, h.
    pub hours: f64,
    /// Update interval, h.
    pub update_hours: f64,
    /// Wear depth (cam, along the normal) that ends the run, m.
    pub wear_limit: Option<f64>,
    /// Number of wear-depth snapshots to keep, evenly spaced in time (the final state is always
    /// reported separately).
    pub snapshots: usize,
    /// A flat face of finite radius: the contact must stay on it.
    pub face: Option<FlatFace>,
    /// Bins over a flat follower's face.
    pub face_bins: usize,
    /// Most profile updates, those added by the stability cut included (the update interval is
    /// shortened automatically where a step would be unstable; see [`STABLE_FRACTION`]). A run
    /// that would need more ends with `update_limit`.
    pub max_updates: usize,
}

/// Largest wear per update, as a fraction of `ρ Δθ²` (ρ the cam's radius of curvature at the
/// point, Δθ the angle step). Why: the wear per pass grows where the cam is more sharply curved
/// (the contact dwells longer there: `v_s/u_c = (r_b + s)/ρ` for a flat face), so wear smooths a
/// bump — a diffusion in the cam angle — and an explicit update of a mode of wavenumber `m` is
/// stable only while `Δw m²/ρ < 2`; with `m` up to `π/Δθ` that is `Δw < 0.2 ρ Δθ²`. Half of that
/// bound is used: each update interval is cut to respect it.
pub const STABLE_FRACTION: f64 = 0.1;

/// Why the evolution stopped.
#[derive(Debug, Clone, PartialEq)]
pub enum Stop {
    /// The requested running time was reached.
    Completed,
    /// The cam wear reached the limit.
    WearLimit,
    /// The next worn profile cannot run: the cycle's typed error.
    Failed { code: crate::PhysicalFailure, message: String, at_hours: f64 },
}

/// The state after one update.
#[derive(Debug, Clone, PartialEq)]
pub struct HistoryPoint {
    pub hours: f64,
    pub cycles: f64,
    /// Largest cam wear depth, m, and its cam angle (rad).
    pub max_depth: f64,
    pub max_depth_angle: f64,
    /// Largest cam wear rate at this profile, m/s.
    pub max_rate: f64,
    /// Cam volume worn so far, m³.
    pub cam_volume: f64,
    /// Follower volume worn so far, m³.
    pub follower_volume: f64,
    /// Drop of the peak follower lift, m.
    pub peak_lift_loss: f64,
    /// Smallest minimum film over the revolution, m (when a film is computed).
    pub min_film: Option<f64>,
    /// Largest Hertz pressure over the revolution, Pa.
    pub max_pressure: f64,
    /// Largest pressure of the numerical EHL film over the revolution (exit spike included), Pa,
    /// when that model ran at some angle.
    pub max_film_pressure: Option<f64>,
}

/// Result of [`evolve`].
#[derive(Debug, Clone)]
pub struct WearEvolution {
    /// Cam angles, rad.
    pub angle: Vec<f64>,
    /// Cam wear depth along the normal per cam angle, m.
    pub depth: Vec<f64>,
    /// Follower lift drop per cam angle, m.
    pub lift_drop: Vec<f64>,
    /// Cam wear rate per cam angle on the final profile, m/s.
    pub rate: Vec<f64>,
    /// Arc length along the cam surface of each cam angle's point, m (from θ = 0's point).
    pub surface_position: Vec<f64>,
    /// Lift of the original and of the final profile, m.
    pub initial_lift: Vec<f64>,
    pub final_lift: Vec<f64>,
    /// Share of the load that wears on the final profile.
    pub worn_share: Vec<f64>,
    /// Flat follower face: bin centres (m from the follower axis) and wear depth (m).
    pub face: Option<(Vec<f64>, Vec<f64>)>,
    /// One entry at the start and one after each update.
    pub history: Vec<HistoryPoint>,
    /// `(hours, depth per cam angle)`.
    pub snapshots: Vec<(f64, Vec<f64>)>,
    pub stop: Stop,
    /// Running time reached, h.
    pub hours: f64,
    /// Time at which the wear limit was reached, h.
    pub hours_to_limit: Option<f64>,
    /// Revolution period, s.
    pub period: f64,
    /// Profile updates performed.
    pub updates: usize,
    /// The cycle on the first and on the final profile (without their film profiles).
    pub initial_cycle: CycleOutput,
    pub final_cycle: CycleOutput,
    /// Angles at which each film model ran, summed over every cycle of the run (the unworn
    /// profile and each update), in order of first appearance. Empty without a film.
    pub film_models: Vec<(FilmModelId, usize)>,
}

struct Evaluated {
    out: CycleOutput,
    wear: RevolutionWear,
    /// Largest numerical-film pressure (before the profiles are dropped).
    max_film_pressure: Option<f64>,
}

fn evaluate(
    run: &WearRun,
    cycle: &CycleSpec,
    model: &dyn FilmModel,
    bins: Option<Bins>,
    observer: &dyn Observer,
) -> Result<Evaluated, SolveError> {
    let out = run_cycle(cycle, run.needs, model, &QuietObserver(observer))?;
    wear_of(run, cycle, out, bins)
}

fn wear_of(run: &WearRun, cycle: &CycleSpec, out: CycleOutput, bins: Option<Bins>) -> Result<Evaluated, SolveError> {
    if let Some(face) = run.face {
        check_contact_on_face(&out.series, face)?;
    }
    let wear = revolution_wear(cycle, &out, &run.archard, bins)?;
    let max_film_pressure =
        (!out.profiles.is_empty()).then(|| out.profiles.iter().flat_map(|(_, p)| p.pressure.iter().copied()).fold(0.0, f64::max));
    // The film profiles have served: keep memory flat over long runs.
    let mut out = out;
    out.profiles = Vec::new();
    Ok(Evaluated { out, wear, max_film_pressure })
}

fn count_models(counts: &mut Vec<(FilmModelId, usize)>, out: &CycleOutput) {
    for m in out.series.film_model.iter().flatten() {
        match counts.iter_mut().find(|(id, _)| id == m) {
            Some((_, c)) => *c += 1,
            None => counts.push((*m, 1)),
        }
    }
}

fn update_limit(max_updates: usize, at_hours: f64) -> Stop {
    Stop::Failed {
        code: crate::PhysicalFailure::UpdateLimit,
        message: format!(
            "the wear per update must stay below {STABLE_FRACTION}·ρ·Δθ² for a stable profile update; \
             this run would need more than {max_updates} updates (fewer angles, a smaller wear coefficient or a \
             shorter running time help)"
        ),
        at_hours,
    }
}

/// Forwards cancellation but not the cycle's own progress (the evolution reports its own).
struct QuietObserver<'a>(&'a dyn Observer);
impl Observer for QuietObserver<'_> {
    fn check(&self) -> Result<(), crate::Interrupt> {
        self.0.check()
    }
}

fn argmax(v: &[f64]) -> (usize, f64) {
    v.iter().copied().enumerate().fold((0, f64::NEG_INFINITY), |b, (i, x)| if x > b.1 { (i, x) } else { b })
}

fn max_of(v: &[f64]) -> f64 {
    v.iter().copied().fold(f64::NEG_INFINITY, f64::max)
}

fn point(hours: f64, period: f64, depth: &[f64], angle: &[f64], e: &Evaluated, vol: (f64, f64), lift0_max: f64) -> HistoryPoint {
    let (i, d) = argmax(depth);
    let s = &e.out.series;
    HistoryPoint {
        hours,
        cycles: hours * 3600.0 / period,
        max_depth: d,
        max_depth_angle: angle[i],
        max_rate: max_of(&e.wear.cam_depth) / period,
        cam_volume: vol.0,
        follower_volume: vol.1,
        peak_lift_loss: lift0_max - max_of(&s.lift),
        min_film: s.film_min.as_ref().map(|v| v.iter().copied().fold(f64::INFINITY, f64::min)),
        max_pressure: s.hertz_max_pressure.as_ref().map_or(0.0, |v| max_of(v)),
        max_film_pressure: e.max_film_pressure,
    }
}

/// Run the Archard wear evolution. Errors of the first cycle (the unworn pair) are returned as
/// errors; errors after a profile update end the run (see [`Stop::Failed`]).
pub fn evolve(run: &WearRun, model: &dyn FilmModel, observer: &dyn Observer) -> Result<WearEvolution, SolveError> {
    if !(run.hours > 0.0 && run.update_hours > 0.0) {
        return Err(SolveError::invalid("WearRun.hours", "running time and update interval must be > 0"));
    }
    let n = run.cycle.angles;
    observer.progress(0.0, "unworn cycle");
    let first = run_cycle(&run.cycle, run.needs, model, &QuietObserver(observer))?;
    let bins = face_bins(&run.cycle, &first, run.face_bins);
    let mut film_models = Vec::new();
    count_models(&mut film_models, &first);
    let mut current = wear_of(run, &run.cycle, first, bins)?;
    let period = current.wear.period;
    let angle = current.out.series.angle.clone();
    let initial_lift = current.out.series.lift.clone();
    let lift0_max = max_of(&initial_lift);
    let initial_cycle = current.out.clone();
    let original = run.cycle.profile.clone();
    let mut depth = vec![0.0; n];
    let mut drop = vec![0.0; n];
    let mut face = bins.map(|b| vec![0.0; b.n]);
    let mut vol = (0.0, 0.0);
    let mut t = 0.0;
    let mut history = vec![point(0.0, period, &depth, &angle, &current, vol, lift0_max)];
    let mut snapshots = Vec::new();
    let snap_dt = run.hours / run.snapshots.max(1) as f64;
    let mut next_snap = snap_dt;
    let mut stop = Stop::Completed;
    let mut hours_to_limit = None;
    let mut updates = 0;
    let eps = 1e-12 * run.hours;
    while t < run.hours - eps {
        observer.check()?;
        observer.progress(t / run.hours, "wear");
        let mut dt_h = run.update_hours.min(run.hours - t);
        if updates >= run.max_updates {
            stop = update_limit(run.max_updates, t + dt_h);
            break;
        }
        let inc = &current.wear.cam_depth;
        // Stability of the explicit step: at most `STABLE_FRACTION ρ Δθ²` of wear per update.
        let curvature = &current.out.series.cam_curvature;
        let dtheta = TAU / n as f64;
        let max_revs = inc
            .iter()
            .zip(curvature)
            .filter(|(r, k)| **r > 0.0 && **k > 0.0)
            .map(|(r, k)| STABLE_FRACTION * dtheta * dtheta / (k * r))
            .fold(f64::INFINITY, f64::min);
        if max_revs * period / 3600.0 < dt_h {
            dt_h = max_revs * period / 3600.0;
        }
        let mut revs = dt_h * 3600.0 / period;
        // Cut the interval where the wear limit is crossed.
        let mut limit_hit = false;
        if let Some(limit) = run.wear_limit {
            let tau = depth
                .iter()
                .zip(inc)
                .filter(|(_, r)| **r > 0.0)
                .map(|(d, r)| (limit - d) / (r * revs))
                .fold(f64::INFINITY, f64::min);
            if tau <= 1.0 {
                let tau = tau.max(0.0);
                dt_h *= tau;
                revs *= tau;
                limit_hit = true;
            }
        }
        let pressure_angle = &current.out.series.pressure_angle;
        let new_depth: Vec<f64> = depth.iter().zip(inc).map(|(d, r)| d + r * revs).collect();
        let new_drop: Vec<f64> =
            drop.iter().zip(inc).zip(pressure_angle).map(|((d, r), phi)| d + r * revs / phi.cos()).collect();
        ensure_finite("worn profile", new_depth.iter().chain(&new_drop))?;
        let t_new = t + dt_h;
        // Rebuild the profile and rerun the pair on it.
        let worn = PeriodicSpline::new(&angle, &new_drop)?;
        let mut cycle = run.cycle.clone();
        cycle.profile = CamProfile::Worn { original: Box::new(original.clone()), wear: worn };
        let next = match evaluate(run, &cycle, model, bins, observer) {
            Ok(e) => e,
            Err(SolveError::Physical { code, message }) => {
                stop = Stop::Failed { code, message, at_hours: t_new };
                break;
            }
            Err(e) => return Err(e),
        };
        // Commit.
        updates += 1;
        count_models(&mut film_models, &next.out);
        if let (Some(f), Some(fr)) = (face.as_mut(), current.wear.face_depth.as_ref()) {
            for (a, r) in f.iter_mut().zip(fr) {
                *a += r * revs;
            }
        }
        vol.0 += current.wear.cam_volume * revs;
        vol.1 += current.wear.follower_volume * revs;
        depth = new_depth;
        drop = new_drop;
        t = t_new;
        current = next;
        history.push(point(t, period, &depth, &angle, &current, vol, lift0_max));
        while run.snapshots > 0 && t >= next_snap - eps && snapshots.len() < run.snapshots {
            snapshots.push((t, depth.clone()));
            next_snap += snap_dt;
        }
        if limit_hit {
            stop = Stop::WearLimit;
            hours_to_limit = Some(t);
            break;
        }
    }
    observer.progress(1.0, "done");
    let rate: Vec<f64> = current.wear.cam_depth.iter().map(|d| d / period).collect();
    let mut surface_position = Vec::with_capacity(n);
    for j in 0..n {
        surface_position.push(0.5 * (current.wear.cells.edges[j] + current.wear.cells.edges[j + 1]) - 0.5 * current.wear.cells.width(0));
    }
    let face = match (bins, face) {
        (Some(b), Some(f)) => Some(((0..b.n).map(|j| b.centre(j)).collect(), f)),
        _ => None,
    };
    let out = WearEvolution {
        angle,
        depth,
        lift_drop: drop,
        rate,
        surface_position,
        initial_lift,
        final_lift: current.out.series.lift.clone(),
        worn_share: current.wear.worn_share.clone(),
        face,
        history,
        snapshots,
        stop,
        hours: t,
        hours_to_limit,
        period,
        updates,
        initial_cycle,
        final_cycle: current.out,
        film_models,
    };
    ensure_finite("wear evolution", out.depth.iter().chain(&out.lift_drop).chain(&out.rate))?;
    Ok(out)
}

/// Revolutions in `hours` of steady running at angular speed `omega` (rad/s).
pub fn cycles_in(hours: f64, omega: f64) -> f64 {
    hours * 3600.0 * omega / TAU
}

/// Convergence summary of an evolution: the updates as iterations (no tolerance: a fixed-step
/// march), or the closed form.
pub fn convergence(updates: usize) -> Convergence {
    Convergence { iterations: updates as u32, ..Convergence::closed_form() }
}

/// Time for the wear `depth` (m) growing at `rate` (m/s) at each point to reach `limit` (m)
/// somewhere, s (linear extrapolation of the current rates); `None` where nothing grows.
pub fn time_to_limit(depth: &[f64], rate: &[f64], limit: f64) -> Option<f64> {
    let t = depth
        .iter()
        .zip(rate)
        .filter(|(_, r)| **r > 0.0)
        .map(|(d, r)| (limit - d).max(0.0) / r)
        .fold(f64::INFINITY, f64::min);
    t.is_finite().then_some(t)
}
