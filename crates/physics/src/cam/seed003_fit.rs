//! Seed 003 §6 as published: the cam and operating point the paper gives only in part, found by
//! an inverse fit of the cycle model, with the residual of every statement.
//!
//! The paper gives a cycloidal cam under a flat follower, nose at 180° (Fig. 9–10), the spring
//! rate (38 N/mm, §2.3) and the masses (Table 1); it does not give the base radius, lift,
//! rise/return angle, nose dwell ("broadened flat nose"), face width, speed or spring preload.
//! It states the figures listed in [`STATEMENTS`] (§6, Fig. 10–12). [`figures`] runs the cycle
//! ([`super::cycle::run_cycle`], the model the `cam_cycle` kind runs) on a template with the
//! unknowns substituted; [`fit`] minimises the weighted sum of squared scaled residuals by
//! Nelder–Mead in a box from given starts (a coarse grid's best points, say).
//!
//! What pins what, for a flat follower (`u_e = ω (r_b + s + 2s'')/2`, see [`super::kinematics`]):
//! the reversal angles depend only on `r_b/h`, the rise angle and the dwell (not on speed or
//! load); the shape of the Hertz pressure over the cycle on the load law (preload, `k s`,
//! `m ω² s''`) and the radius `r_b + s + s''`; its level on the width (`p ∝ L^-1/2`); the films
//! mostly on the speed (`h ∝ u^0.541`, seed 003 eq. 17).

use super::cycle::{run_cycle, CycleOutput, CycleSpec, FollowerKind, Needs};
use super::lift::{LiftLaw, LiftProgram};
use super::loads::LoadModel;
use super::profile::CamProfile;
use super::kinematics::SpeedSchedule;
use crate::film::FilmModel;
use crate::numerics::nelder_mead::nelder_mead;
use crate::{Convergence, Silent, SolveError, Termination};
use std::f64::consts::{PI, TAU};

/// The unknowns of seed 003's cam and operating point.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CamUnknowns {
    /// Base-circle radius, m.
    pub base_radius: f64,
    /// Lift, m.
    pub lift: f64,
    /// Rise angle (= return angle: the paper's cycle is symmetric about the nose), rad.
    pub rise: f64,
    /// Dwell at full lift, centred on the nose, rad.
    pub top_dwell: f64,
    /// Face width (contact length), m.
    pub width: f64,
    /// Camshaft speed, rad/s.
    pub omega: f64,
    /// Spring preload at zero lift, N.
    pub preload: f64,
}

impl CamUnknowns {
    fn to_vec(self) -> [f64; 7] {
        [self.base_radius, self.lift, self.rise, self.top_dwell, self.width, self.omega, self.preload]
    }

    fn from_slice(x: &[f64]) -> Self {
        CamUnknowns { base_radius: x[0], lift: x[1], rise: x[2], top_dwell: x[3], width: x[4], omega: x[5], preload: x[6] }
    }

    /// Cam angle where the rise starts (the nose at 180°), rad.
    pub fn rise_start(&self) -> f64 {
        PI - 0.5 * self.top_dwell - self.rise
    }

    /// The cycloidal rise – nose dwell – cycloidal return program, nose at 180°.
    pub fn profile(&self) -> CamProfile {
        CamProfile::Program {
            base_radius: self.base_radius,
            program: LiftProgram {
                lift: self.lift,
                rise_start: self.rise_start(),
                rise: self.rise,
                top_dwell: self.top_dwell,
                fall: self.rise,
                rise_law: LiftLaw::Cycloidal,
                return_law: LiftLaw::Cycloidal,
            },
        }
    }

    /// `template` with these unknowns substituted (profile, width, speed, preload).
    pub fn apply(&self, template: &CycleSpec) -> Result<CycleSpec, SolveError> {
        let mut spec = template.clone();
        spec.profile = self.profile();
        spec.follower = FollowerKind::Flat { contact_length: self.width };
        spec.schedule = SpeedSchedule::Steady { omega: self.omega };
        match &mut spec.load {
            LoadModel::ValveTrain { preload, .. } => *preload = self.preload,
            _ => return Err(SolveError::invalid("CycleSpec.load", "the seed 003 fit needs a valve-train load")),
        }
        Ok(spec)
    }
}

/// How a statement is compared.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Sense {
    Equal,
    /// The paper states a lower bound ("in excess of").
    AtLeast,
    /// The paper states an upper bound ("never in excess of").
    AtMost,
}

/// One figure the paper states.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Statement {
    pub name: &'static str,
    /// The paper's value, SI (angles in degrees from the nose).
    pub paper: f64,
    /// Residual unit: relative (`model/paper − 1`) when true, else the difference.
    pub relative: bool,
    /// What one unit of scaled residual is (a relative fraction or degrees).
    pub scale: f64,
    pub sense: Sense,
}

/// Number of [`STATEMENTS`].
pub const STATEMENT_COUNT: usize = 10;

const fn st(name: &'static str, paper: f64, relative: bool, scale: f64, sense: Sense) -> Statement {
    Statement { name, paper, relative, scale, sense }
}

/// Seed 003 §6 and Fig. 10–12, in the order of [`Figures::values`]. "Just below 1 µm" is read as
/// 0.95 µm; the 0.03 µm minimum film is not a statement of the fit (the entraining-only formula
/// the paper uses for Fig. 10 gives no film where the entrainment vanishes: its 0.03 µm is where
/// its sampling of the cycle fell, see [`Figures::min_film`]).
pub const STATEMENTS: [Statement; STATEMENT_COUNT] = [
    st("reversal_inner_deg", 15.0, false, 1.0, Sense::Equal),
    st("reversal_outer_deg", 51.0, false, 1.0, Sense::Equal),
    st("hertz_at_62_deg", 325e6, true, 0.02, Sense::Equal),
    st("hertz_at_nose", 180e6, true, 0.02, Sense::Equal),
    st("hertz_max", 325e6, true, 0.02, Sense::Equal),
    st("hertz_max_from_nose_deg", 62.0, false, 1.0, Sense::Equal),
    st("film_at_nose", 0.95e-6, true, 0.05, Sense::Equal),
    st("entrainment_at_nose", 4.0, true, 0.02, Sense::AtLeast),
    st("film_max", 1.3e-6, true, 0.02, Sense::AtMost),
    st("shear_max", 96e6, true, 0.02, Sense::Equal),
];

/// The model's figures for the statements.
#[derive(Debug, Clone, PartialEq)]
pub struct Figures {
    /// The model's value of each of [`STATEMENTS`], SI (angles in degrees from the nose).
    pub values: [f64; STATEMENT_COUNT],
    /// Distances of the entrainment reversals from the nose, degrees, ascending.
    pub reversals_deg: Vec<f64>,
    /// Smallest central film over the sampled cycle, m.
    pub min_film: f64,
    /// Contact load at the nose and at the Hertz maximum, N.
    pub load_at_nose: f64,
    pub load_at_hertz_max: f64,
}

/// Scaled residual of statement `s` for the model value `value` (0 when a bound holds).
pub fn residual(s: &Statement, value: f64) -> f64 {
    let d = if s.relative { value / s.paper - 1.0 } else { value - s.paper };
    let d = match s.sense {
        Sense::Equal => d,
        Sense::AtLeast => d.min(0.0),
        Sense::AtMost => d.max(0.0),
    };
    d / s.scale
}

/// Linear interpolation of a periodic column sampled at `2πk/n` at angle `theta` (rad).
fn sample(values: &[f64], theta: f64) -> f64 {
    let n = values.len();
    let x = theta.rem_euclid(TAU) / TAU * n as f64;
    let i = x.floor() as usize % n;
    let f = x - x.floor();
    values[i] * (1.0 - f) + values[(i + 1) % n] * f
}

/// Angle (rad) of the largest value, refined by the parabola through it and its neighbours.
fn peak_angle(values: &[f64]) -> f64 {
    let n = values.len();
    let i = values.iter().enumerate().fold(0, |b, (k, v)| if *v > values[b] { k } else { b });
    let (a, b, c) = (values[(i + n - 1) % n], values[i], values[(i + 1) % n]);
    let den = a - 2.0 * b + c;
    let off = if den < 0.0 { (0.5 * (a - c) / den).clamp(-0.5, 0.5) } else { 0.0 };
    TAU * (i as f64 + off) / n as f64
}

fn column<'a>(v: &'a Option<Vec<f64>>, name: &str) -> Result<&'a [f64], SolveError> {
    v.as_deref().ok_or_else(|| SolveError::invalid("seed003_fit", format!("the cycle computed no {name}")))
}

/// The statements' figures of a cycle output (a flat follower, nose at 180°).
pub fn figures_of(out: &CycleOutput) -> Result<Figures, SolveError> {
    let s = &out.series;
    let mut rev: Vec<f64> = out.events.zero_entrainment.iter().map(|a| (a - PI).abs().to_degrees()).collect();
    rev.sort_by(f64::total_cmp);
    if rev.len() != 4 {
        return Err(SolveError::invalid("seed003_fit", format!("{} entrainment reversals, not four", rev.len())));
    }
    let p = column(&s.hertz_max_pressure, "Hertz pressure")?;
    let h = column(&s.film_central, "central film")?;
    let tau = column(&s.max_shear_stress, "sub-surface shear")?;
    let w = column(&s.contact_load, "contact load")?;
    let at62 = 62f64.to_radians();
    let theta_max = peak_angle(p);
    let max = |v: &[f64]| v.iter().copied().fold(f64::NEG_INFINITY, f64::max);
    let values = [
        0.5 * (rev[0] + rev[1]),
        0.5 * (rev[2] + rev[3]),
        0.5 * (sample(p, PI - at62) + sample(p, PI + at62)),
        sample(p, PI),
        max(p),
        (theta_max - PI).abs().to_degrees(),
        sample(h, PI),
        sample(&s.entrainment_velocity, PI),
        max(h),
        max(tau),
    ];
    Ok(Figures {
        values,
        reversals_deg: rev,
        min_film: h.iter().copied().fold(f64::INFINITY, f64::min),
        load_at_nose: sample(w, PI),
        load_at_hertz_max: sample(w, theta_max),
    })
}

/// What the fit runs: the template cycle (lubricant, materials, load law, angles), its film
/// model, and the flat face's radius (contact must stay on the face).
pub struct FitSetup<'a> {
    pub template: &'a CycleSpec,
    pub model: &'a dyn FilmModel,
    /// Radius of the flat face, m (`None`: unbounded).
    pub face_radius: Option<f64>,
}

/// The cycle of `x` and its figures (contact, film; no friction).
pub fn figures(setup: &FitSetup, x: &CamUnknowns) -> Result<Figures, SolveError> {
    let spec = x.apply(setup.template)?;
    let needs = Needs { loads: true, contact: true, film: true, ..Needs::default() };
    let out = run_cycle(&spec, needs, setup.model, &Silent)?;
    if let Some(r) = setup.face_radius {
        let reach = out.series.contact_offset.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        if reach > r {
            return Err(SolveError::invalid("seed003_fit", format!("contact leaves the face ({:.2} mm > {:.2} mm)", reach * 1e3, r * 1e3)));
        }
    }
    figures_of(&out)
}

/// Search settings of [`fit`].
#[derive(Debug, Clone, PartialEq)]
pub struct FitOptions {
    /// Weight of each statement's squared scaled residual (0 leaves it out).
    pub weights: [f64; STATEMENT_COUNT],
    /// The box of the search.
    pub lower: CamUnknowns,
    pub upper: CamUnknowns,
    /// Tie the rise to the dwell so that the cam acts from 90° to 270° (`rise + dwell/2 = 90°`,
    /// seed 003 §6); the rise of the box is then ignored.
    pub span_90_270: bool,
    /// Evaluations per start (Nelder–Mead), and the spread of the simplex's costs that ends it.
    pub evaluations_per_start: usize,
    pub tolerance: f64,
}

/// Result of [`fit`].
#[derive(Debug, Clone, PartialEq)]
pub struct CamFit {
    pub unknowns: CamUnknowns,
    pub figures: Figures,
    /// Scaled residual of each statement (see [`residual`]).
    pub residuals: [f64; STATEMENT_COUNT],
    /// Weighted sum of squared scaled residuals.
    pub cost: f64,
    /// Evaluations (all starts), final simplex spread, tolerance; `Stalled` when the budget ended
    /// the best start's search first.
    pub convergence: Convergence,
}

/// Weighted cost of `x` (`+∞` where the cycle cannot be run or has not four reversals).
pub fn cost(setup: &FitSetup, weights: &[f64; STATEMENT_COUNT], x: &CamUnknowns) -> f64 {
    match figures(setup, x) {
        Ok(f) => STATEMENTS.iter().zip(&f.values).zip(weights).map(|((s, v), w)| w * residual(s, *v).powi(2)).sum(),
        Err(_) => f64::INFINITY,
    }
}

fn tie(x: &mut CamUnknowns, span: bool) {
    if span {
        x.rise = 0.5 * PI - 0.5 * x.top_dwell;
    }
}

/// Minimise [`cost`] over the box from each of `starts` (scaled to the box, Nelder–Mead with a
/// first simplex edge of 15 % of the box), then once more from the best point (a restart with a
/// fresh simplex); returns the best.
pub fn fit(setup: &FitSetup, opts: &FitOptions, starts: &[CamUnknowns]) -> Result<CamFit, SolveError> {
    if starts.is_empty() || opts.evaluations_per_start < 8 || !(opts.tolerance > 0.0) {
        return Err(SolveError::invalid("FitOptions", "needs a start, at least 8 evaluations and a positive tolerance"));
    }
    let (lo, hi) = (opts.lower.to_vec(), opts.upper.to_vec());
    if lo.iter().zip(&hi).any(|(a, b)| !(a < b) || !a.is_finite() || !b.is_finite()) {
        return Err(SolveError::invalid("FitOptions.lower", "each lower bound must be finite and below its upper bound"));
    }
    let unscale = |u: &[f64]| {
        let v: Vec<f64> = (0..7).map(|i| lo[i] + (hi[i] - lo[i]) * u[i]).collect();
        let mut x = CamUnknowns::from_slice(&v);
        tie(&mut x, opts.span_90_270);
        x
    };
    let scale = |x: &CamUnknowns| -> Vec<f64> { x.to_vec().iter().enumerate().map(|(i, v)| ((v - lo[i]) / (hi[i] - lo[i])).clamp(0.0, 1.0)).collect() };
    let objective = |u: &[f64]| -> Result<f64, SolveError> {
        let x = unscale(u);
        if x.rise <= 0.0 || x.rise_start() < 0.0 {
            return Ok(f64::INFINITY);
        }
        Ok(cost(setup, &opts.weights, &x))
    };
    let (zeros, ones, step) = (vec![0.0; 7], vec![1.0; 7], vec![0.15; 7]);
    let mut evaluations = 0;
    let mut best: Option<crate::numerics::nelder_mead::Minimum> = None;
    for s in starts {
        let m = nelder_mead(objective, &scale(s), &step, &zeros, &ones, opts.evaluations_per_start, opts.tolerance)?;
        evaluations += m.evaluations;
        if best.as_ref().map_or(true, |b| m.value < b.value) {
            best = Some(m);
        }
    }
    let first = best.expect("at least one start");
    let again = nelder_mead(objective, &first.x, &[0.05; 7], &zeros, &ones, opts.evaluations_per_start, opts.tolerance)?;
    evaluations += again.evaluations;
    let m = if again.value <= first.value { again } else { first };
    if !m.value.is_finite() {
        return Err(SolveError::invalid("seed003_fit", "no start gave a cycle with four entrainment reversals inside the box"));
    }
    let unknowns = unscale(&m.x);
    let figures = figures(setup, &unknowns)?;
    let mut residuals = [0.0; STATEMENT_COUNT];
    for (i, s) in STATEMENTS.iter().enumerate() {
        residuals[i] = residual(s, figures.values[i]);
    }
    let termination = if m.spread.abs() <= opts.tolerance { Termination::Converged } else { Termination::Stalled };
    let convergence = Convergence { iterations: evaluations as u32, residual: m.spread.abs(), tolerance: opts.tolerance, termination };
    Ok(CamFit { unknowns, figures, residuals, cost: m.value, convergence })
}

/// The points of a coarse grid over the box (`levels` per unknown, at the centres of equal
/// cells), sorted by cost; the `keep` cheapest with finite cost. `levels^7` evaluations.
pub fn grid_starts(setup: &FitSetup, opts: &FitOptions, levels: usize, keep: usize) -> Vec<CamUnknowns> {
    let (lo, hi) = (opts.lower.to_vec(), opts.upper.to_vec());
    let levels = levels.max(1);
    let total = levels.saturating_pow(7);
    let mut scored: Vec<(f64, CamUnknowns)> = Vec::new();
    for k in 0..total {
        let mut v = [0.0; 7];
        let mut r = k;
        for i in 0..7 {
            let l = r % levels;
            r /= levels;
            v[i] = lo[i] + (hi[i] - lo[i]) * (l as f64 + 0.5) / levels as f64;
        }
        let mut x = CamUnknowns::from_slice(&v);
        tie(&mut x, opts.span_90_270);
        if x.rise_start() < 0.0 {
            continue;
        }
        let c = cost(setup, &opts.weights, &x);
        if c.is_finite() {
            scored.push((c, x));
        }
    }
    scored.sort_by(|a, b| a.0.total_cmp(&b.0));
    scored.into_iter().take(keep).map(|s| s.1).collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn residuals_of_bounds_vanish_inside_them() {
        let at_least = &STATEMENTS[7];
        assert_eq!(residual(at_least, 5.0), 0.0);
        assert!((residual(at_least, 3.92) - (-0.02 / 0.02)).abs() < 1e-12);
        let at_most = &STATEMENTS[8];
        assert_eq!(residual(at_most, 1.0e-6), 0.0);
        assert!((residual(&STATEMENTS[0], 16.5) - 1.5).abs() < 1e-12);
    }

    #[test]
    fn sampling_and_peak_interpolate_a_periodic_column() {
        let n = 360;
        let v: Vec<f64> = (0..n).map(|k| -(TAU * k as f64 / n as f64 - 2.0).powi(2)).collect();
        assert!((sample(&v, 2.0) - v[(2.0 / TAU * n as f64) as usize]).abs() < 2e-3);
        assert!((peak_angle(&v) - 2.0).abs() < 1e-9);
    }

    #[test]
    fn the_nose_is_at_180_degrees() {
        let x = CamUnknowns { base_radius: 0.015, lift: 0.01, rise: 1.9, top_dwell: 0.2, width: 0.02, omega: 300.0, preload: 200.0 };
        let nose = x.profile().nose_angle(crate::cam::FollowerShape::Flat);
        assert!((nose - PI).abs() < 0.11, "{nose}");
        let j = x.profile().lift(PI, crate::cam::FollowerShape::Flat);
        assert!((j.v - 0.01).abs() < 1e-15 && j.d2 == 0.0);
    }
}
