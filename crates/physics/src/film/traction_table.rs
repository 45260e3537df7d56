//! The thermal film's traction table (`physics::film::thermal`): the follower's surface stress
//! integral (seed 000 eq. 9) from the energy equation (eq. 7–8) solved on one point's pressure
//! and film at a fixed set of slide-to-roll ratios, interpolated between them by a monotone cubic
//! (Steffen 1990: no overshoot, C¹), linear beyond the ends.
//!
//! **Entries are solved when first needed**: the value at a sliding velocity needs the two
//! entries of the interval that holds it and one neighbour on each side (they set the
//! interval's slopes). The four around the point's own sliding velocity, and those between them
//! and rolling (their starts, below), are solved with the point (a failure there fails the
//! point); the others when the roller balance evaluates the traction where they are needed, and
//! one that fails is left out (the interpolant bridges it). A cam cycle's slip stays near its
//! own point's, while the far entries (±0.5, ±2) cost most: their energy sweeps converge slowly
//! under strong shear heating (BENCHMARKS.md, "Where the thermal cycle's time goes"; the lazy
//! table's effect: "Thermal cycle: lazy table, layouts, lag window, calibrated carry").
//!
//! **The interpolant does not depend on the order of evaluation.** The rolling entry starts its
//! sweeps from the point's coupled temperature field, every other entry from its inner
//! neighbour's converged field (solved first when needed) — so an entry's value is the same
//! whichever query asked for it first; and the value at a sliding velocity uses only the four
//! entries around it, all solved — the value the whole table would give. (Every entry from the
//! coupled field instead cost 70 % more sweeps: near rolling the coupled field's shear heating
//! is far from the entry's.)

use crate::ehl::thermal::{energy, EnergyInput, TemperatureField, ThermalBodies, ThermalOptions};
use crate::ehl::Rheology;
use crate::lubricant::Lubricant;
use crate::SolveError;
use std::sync::{Arc, Mutex};

/// Slide-to-roll ratios `u_s/u_m` of the traction table (both signs and zero). Entries whose
/// energy solve fails (beyond the point's own four) are left out; beyond the last entry the
/// interpolant extends linearly.
pub const SLIDE_TO_ROLL_TABLE: [f64; 13] = [-2.0, -0.5, -0.15, -0.05, -0.015, -0.004, 0.0, 0.004, 0.015, 0.05, 0.15, 0.5, 2.0];

/// Index of the rolling entry (`u_s = 0`).
const ROLLING: usize = 6;

/// Factors on an entry's sliding velocity tried in turn until its energy solve succeeds. A
/// failing ±0.15 entry is retried closer to rolling (±0.105, ±0.0735) so that the table still
/// reaches past ±0.05 (seed 000 with w1 = 800 N: the −0.15 entry runs away at w' = 193 kN/m;
/// BENCHMARKS.md, "Figs. 9 and 13").
pub fn shrinks(srr: f64) -> &'static [f64] {
    if srr.abs() <= 0.05 || srr.abs() > 0.15 { &[1.0] } else { &[1.0, 0.7, 0.49] }
}

/// Every sliding velocity an entry may take at entrainment scale `scale` (m/s): per entry, its
/// nominal one and its retries ([`shrinks`]).
pub fn candidate_sliding(scale: f64) -> Vec<Vec<f64>> {
    SLIDE_TO_ROLL_TABLE.iter().map(|&srr| shrinks(srr).iter().map(|s| s * srr * scale).collect()).collect()
}

/// The problem every entry solves: the energy equation on the point's pressure and film over the
/// pressurised zone, the surfaces moving at `u_m ± u_s/2`.
#[derive(Debug)]
pub struct TableProblem {
    pub x: Vec<f64>,
    pub pressure: Vec<f64>,
    pub film: Vec<f64>,
    /// Entrainment velocity `u_m`, m/s.
    pub entrainment: f64,
    /// Sliding velocity per unit slide-to-roll ratio, m/s (`|u_m|`, at least 1e-6).
    pub scale: f64,
    pub lubricant: Lubricant,
    pub inlet_temperature: f64,
    pub bodies: ThermalBodies,
    pub half_width: f64,
    pub load_per_length: f64,
    pub rheology: Rheology,
    pub options: ThermalOptions,
}

#[derive(Debug, Clone)]
enum Entry {
    Unsolved,
    /// `candidate`: which of [`shrinks`] succeeded; `sliding` in m/s, `force` the follower's
    /// fluid traction per unit length, N/m.
    Solved { candidate: usize, sliding: f64, force: f64, field: TemperatureField },
    Failed,
}

/// A traction table whose entries are solved when first needed (module docs).
#[derive(Debug)]
pub struct TractionTable {
    problem: TableProblem,
    /// The point's coupled temperature field: the rolling entry's start.
    start: TemperatureField,
    entries: Mutex<Vec<Entry>>,
}

impl TableProblem {
    /// The entry at slide-to-roll ratio `srr` from the field `warm`: the index of the first of
    /// its candidates whose energy solve succeeds, its sliding velocity (m/s) and traction (N/m),
    /// or the last error.
    fn solve(&self, srr: f64, warm: &TemperatureField) -> Result<(usize, f64, f64, TemperatureField), SolveError> {
        let mut last = None;
        for (candidate, &shrink) in shrinks(srr).iter().enumerate() {
            let us = shrink * srr * self.scale;
            let input = EnergyInput {
                limited_gradient: false,
                velocity_1: self.entrainment + 0.5 * us,
                velocity_2: self.entrainment - 0.5 * us,
                lubricant: &self.lubricant,
                inlet_temperature: self.inlet_temperature,
                bodies: &self.bodies,
                half_width: self.half_width,
                load_per_length: self.load_per_length,
                rheology: &self.rheology,
                previous: None,
                warm: Some(warm),
            };
            match energy(&self.x, &self.pressure, &self.film, &input, &self.options) {
                Ok(en) => return Ok((candidate, us, en.traction.force_body_2, en.field)),
                Err(e) => last = Some(e),
            }
        }
        Err(last.expect("every entry has a candidate"))
    }
}

impl TractionTable {
    /// The table of `problem` with the four entries around the point's own sliding velocity
    /// `sliding` (m/s) solved (and the entries between them and rolling that they start from),
    /// the rolling entry from the point's coupled temperature field `start`; one of them failing
    /// fails the table.
    pub fn new(problem: TableProblem, start: TemperatureField, sliding: f64) -> Result<Self, SolveError> {
        let table = TractionTable { problem, start, entries: Mutex::new(vec![Entry::Unsolved; SLIDE_TO_ROLL_TABLE.len()]) };
        {
            let mut entries = table.entries.lock().unwrap_or_else(|e| e.into_inner());
            let nominal: Vec<f64> = SLIDE_TO_ROLL_TABLE.iter().map(|s| s * table.problem.scale).collect();
            let j = interval(&nominal, sliding);
            let (lo, hi) = (j.saturating_sub(1).min(ROLLING), (j + 2).min(nominal.len() - 1).max(ROLLING));
            // From rolling outwards, so that each entry's start is solved before it.
            for k in (ROLLING..=hi).chain((lo..ROLLING).rev()) {
                table.solve_entry(&mut entries, k);
                if !matches!(entries[k], Entry::Solved { .. }) {
                    let warm = table.warm(&entries, k).clone();
                    let (_, _, force, _) = table.problem.solve(SLIDE_TO_ROLL_TABLE[k], &warm)?;
                    crate::ensure_finite("thermal traction table", [&force])?;
                }
            }
        }
        Ok(table)
    }

    /// The field entry `k` starts from: its inner neighbour's (the nearest solved entry towards
    /// rolling), the coupled field for the rolling entry.
    fn warm<'a>(&'a self, entries: &'a [Entry], k: usize) -> &'a TemperatureField {
        let inner = |j: usize| if j > ROLLING { j - 1 } else { j + 1 };
        let mut j = k;
        while j != ROLLING {
            j = inner(j);
            if let Entry::Solved { field, .. } = &entries[j] {
                return field;
            }
        }
        &self.start
    }

    /// Entry `k`'s candidate and force (N/m), solved now if needed; `None` if it failed.
    fn entry(&self, k: usize) -> Option<(usize, f64)> {
        let mut entries = self.entries.lock().unwrap_or_else(|e| e.into_inner());
        if matches!(entries[k], Entry::Unsolved) {
            self.solve_entry(&mut entries, k);
        }
        match entries[k] {
            Entry::Solved { candidate, force, .. } => Some((candidate, force)),
            _ => None,
        }
    }

    /// Solve entry `k` from its inner neighbour's field ([`Self::warm`]; solving that first
    /// when needed); one whose energy solve fails or is not finite is marked failed.
    fn solve_entry(&self, entries: &mut [Entry], k: usize) {
        if k != ROLLING {
            let inner = if k > ROLLING { k - 1 } else { k + 1 };
            if matches!(entries[inner], Entry::Unsolved) {
                self.solve_entry(entries, inner);
            }
        }
        let warm = self.warm(entries, k);
        entries[k] = match self.problem.solve(SLIDE_TO_ROLL_TABLE[k], warm) {
            Ok((candidate, sliding, force, field)) if force.is_finite() => Entry::Solved { candidate, sliding, force, field },
            _ => Entry::Failed,
        };
    }

    /// Value and slope of the table seen through `view` at sliding velocity `at` (m/s). The
    /// interval is located on the live entries' positions (an unsolved entry at its nominal
    /// ratio: a retry keeps it between its neighbours); once its four entries are solved, the
    /// positions that matter are exact.
    fn evaluate(&self, view: &TableView, at: f64) -> (f64, f64) {
        let mut entries = self.entries.lock().unwrap_or_else(|e| e.into_inner());
        let position = |e: &Entry, k: usize| match e {
            Entry::Solved { sliding, .. } => sliding * view.speed,
            _ => SLIDE_TO_ROLL_TABLE[k] * self.problem.scale * view.speed,
        };
        loop {
            let live: Vec<usize> = (0..entries.len()).filter(|&k| !matches!(entries[k], Entry::Failed)).collect();
            let n = live.len();
            let positions: Vec<f64> = live.iter().map(|&k| position(&entries[k], k)).collect();
            let j = interval(&positions, at);
            let stencil = &live[j.saturating_sub(1)..=(j + 2).min(n - 1)];
            if let Some(&k) = stencil.iter().find(|&&k| matches!(entries[k], Entry::Unsolved)) {
                self.solve_entry(&mut entries, k);
                continue;
            }
            // Only the stencil's entries are read: the others stay NaN.
            let mut x = vec![f64::NAN; n];
            let mut y = vec![f64::NAN; n];
            for (i, &k) in live.iter().enumerate().skip(j.saturating_sub(1)).take(4) {
                if let Entry::Solved { candidate, sliding, force, .. } = &entries[k] {
                    x[i] = sliding * view.speed;
                    y[i] = force * view.factor(k, *candidate, *force);
                }
            }
            let mut m = vec![f64::NAN; n];
            m[j] = steffen_slope(&x, &y, j);
            m[j + 1] = steffen_slope(&x, &y, j + 1);
            return hermite(&x, &y, &m, j, at);
        }
    }
}

/// One point's view of a traction table (its own, or a key point's carried to it): sliding
/// velocities times `speed`, and forces times `ratio[entry][candidate]` (`None`: 1) — raised to
/// the calibrated exponent where a `calibration` is given.
#[derive(Debug, Clone)]
pub struct TableView {
    pub table: Arc<TractionTable>,
    pub speed: f64,
    pub ratio: Option<Vec<Vec<f64>>>,
    pub calibration: Option<Calibration>,
}

/// The sensitivity of a carried table's forces to the change of conditions, measured between two
/// tables: `ratio` is the closed form's prediction of a force's change from one point to another;
/// the thermal forces of this table and of `table` (another point's) change by `ratio^γ`, with
/// `γ = ln(f / f_other) / ln(closed_form_ratio)` per entry (the closed form's change between the two
/// points), clamped to [0, 2]; 1 where the closed form barely changes (|ln| < 1e-3) or the
/// entries' signs or candidates differ.
#[derive(Debug, Clone)]
pub struct Calibration {
    pub table: Arc<TractionTable>,
    /// The closed form's force at this table's point over that at `table`'s, per entry and
    /// candidate.
    pub closed_form_ratio: Vec<Vec<f64>>,
}

impl PartialEq for TableView {
    fn eq(&self, other: &Self) -> bool {
        let calibration = match (&self.calibration, &other.calibration) {
            (None, None) => true,
            (Some(a), Some(b)) => Arc::ptr_eq(&a.table, &b.table) && a.closed_form_ratio == b.closed_form_ratio,
            _ => false,
        };
        Arc::ptr_eq(&self.table, &other.table) && self.speed == other.speed && self.ratio == other.ratio && calibration
    }
}

impl TableView {
    /// The factor on entry `k`'s force `force` (solved at `candidate`): `ratio`, or `ratio^γ`
    /// with the calibration's exponent ([`Calibration`]).
    fn factor(&self, k: usize, candidate: usize, force: f64) -> f64 {
        let Some(ratio) = self.ratio.as_ref().map(|r| r[k][candidate]) else {
            return 1.0;
        };
        let Some(cal) = &self.calibration else {
            return ratio;
        };
        let predicted = cal.closed_form_ratio[k][candidate];
        match cal.table.entry(k) {
            Some((c, other)) if c == candidate && ratio > 0.0 && predicted > 0.0 && predicted.ln().abs() > 1e-3 && force / other > 0.0 => {
                let gamma = ((force / other).ln() / predicted.ln()).clamp(0.0, 2.0);
                ratio.powf(gamma)
            }
            _ => ratio,
        }
    }

    /// The follower's fluid traction per unit length (N/m) and its slope in the sliding
    /// velocity at `sliding` (m/s).
    pub fn force(&self, sliding: f64) -> (f64, f64) {
        self.table.evaluate(self, sliding)
    }

    /// The table's problem (entrainment and sliding scale).
    pub fn problem(&self) -> &TableProblem {
        &self.table.problem
    }
}

/// Steffen's (1990) slope at node `i` of the data `(x, y)` (reads nodes `i − 1 … i + 1`):
/// monotone where the data are, no overshoot; one-sided at the ends.
fn steffen_slope(x: &[f64], y: &[f64], i: usize) -> f64 {
    let n = x.len();
    let d = |k: usize| (y[k + 1] - y[k]) / (x[k + 1] - x[k]);
    if i == 0 {
        return d(0);
    }
    if i == n - 1 {
        return d(n - 2);
    }
    let (d0, d1) = (d(i - 1), d(i));
    let (h0, h1) = (x[i] - x[i - 1], x[i + 1] - x[i]);
    let p = (d0 * h1 + d1 * h0) / (h0 + h1);
    if d0 * d1 <= 0.0 {
        return 0.0;
    }
    let m = d0.signum() * d0.abs().min(d1.abs()).min(0.5 * p.abs()) * 2.0;
    if m.abs() > p.abs() { p } else { m }
}

/// Index `i` of the interval `[x_i, x_{i+1}]` of the increasing nodes `x` that holds `at`
/// (the first or last interval beyond the ends).
fn interval(x: &[f64], at: f64) -> usize {
    x.partition_point(|&v| v <= at).clamp(1, x.len() - 1) - 1
}

/// Value and slope at `at` of the monotone cubic through `(x, y)` with slopes `m` on interval
/// `i` ([`interval`]); linear beyond the ends. Reads only the nodes `i`, `i + 1`.
fn hermite(x: &[f64], y: &[f64], m: &[f64], i: usize, at: f64) -> (f64, f64) {
    let n = x.len();
    if i == 0 && at <= x[0] {
        return (y[0] + m[0] * (at - x[0]), m[0]);
    }
    if i + 2 == n && at >= x[n - 1] {
        return (y[n - 1] + m[n - 1] * (at - x[n - 1]), m[n - 1]);
    }
    let h = x[i + 1] - x[i];
    let t = (at - x[i]) / h;
    let (t2, t3) = (t * t, t * t * t);
    let v = (2.0 * t3 - 3.0 * t2 + 1.0) * y[i] + (t3 - 2.0 * t2 + t) * h * m[i] + (-2.0 * t3 + 3.0 * t2) * y[i + 1] + (t3 - t2) * h * m[i + 1];
    let dv = ((6.0 * t2 - 6.0 * t) * y[i] + (3.0 * t2 - 4.0 * t + 1.0) * h * m[i] + (-6.0 * t2 + 6.0 * t) * y[i + 1] + (3.0 * t2 - 2.0 * t) * h * m[i + 1]) / h;
    (v, dv)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A light table problem: a smooth pressure bump (`p0 (1 − x²/b²)^1.5`, p0 = 0.3 GPa,
    /// b = 0.1 mm: finite slopes, unlike Hertz's, whose Poiseuille flow on a uniform film runs
    /// away at the edges) on a uniform 2 µm film, u_m = 3 m/s, Newtonian, the seed 000 oil.
    fn problem() -> TableProblem {
        let b = 1e-4;
        let x: Vec<f64> = (0..=120).map(|i| -1.5 * b + 3.0 * b * i as f64 / 120.0).collect();
        let pressure = x.iter().map(|x| 0.3e9 * (1.0 - (x / b).powi(2)).max(0.0).powf(1.5)).collect();
        TableProblem {
            film: vec![2e-6; x.len()],
            x,
            pressure,
            entrainment: 3.0,
            scale: 3.0,
            lubricant: Lubricant::SEED000,
            inlet_temperature: 313.0,
            bodies: ThermalBodies::SEED000,
            half_width: b,
            load_per_length: 0.375 * std::f64::consts::PI * b * 0.3e9,
            rheology: Rheology::default(),
            options: ThermalOptions::default(),
        }
    }

    /// A calibrated carry from table B back to the conditions of its calibration table A
    /// (the closed form's ratio B → A the inverse of A → B) gives A's forces: `ratio^γ` with
    /// `γ = ln(f_B/f_A)/ln(closed-form ratio)` undoes B's change exactly, whatever the closed
    /// form's sensitivity (here 0.8 of the thermal one's in log).
    #[test]
    fn calibrated_carry_back_to_the_calibration_table_gives_its_forces() {
        let a = TractionTable::new(problem(), start(&problem()), 0.047 * 3.0).unwrap();
        let heavier = || TableProblem { pressure: problem().pressure.iter().map(|p| 1.1 * p).collect(), load_per_length: 1.1 * problem().load_per_length, ..problem() };
        let b = TractionTable::new(heavier(), start(&heavier()), 0.047 * 3.0).unwrap();
        let (a, b) = (Arc::new(a), Arc::new(b));
        let n = SLIDE_TO_ROLL_TABLE.len();
        let mut closed_form_ratio = vec![vec![1.0; 3]; n];
        for k in 0..n {
            if let (Some((_, fa)), Some((_, fb))) = (a.entry(k), b.entry(k)) {
                closed_form_ratio[k] = vec![(fb / fa).powf(0.8); 3];
            }
        }
        let ratio = closed_form_ratio.iter().map(|r| r.iter().map(|x| 1.0 / x).collect()).collect();
        let view = TableView { table: b.clone(), speed: 1.0, ratio: Some(ratio), calibration: Some(Calibration { table: a.clone(), closed_form_ratio }) };
        for k in [2, 4, 8, 9, 10, 11] {
            let (_, fa) = a.entry(k).unwrap();
            let (_, fb) = b.entry(k).unwrap();
            let at = SLIDE_TO_ROLL_TABLE[k] * 3.0;
            let (carried, _) = view.force(at);
            println!("SRR {}: f_A {fa:.6e}, f_B {fb:.6e}, carried back {carried:.6e}", SLIDE_TO_ROLL_TABLE[k]);
            assert!((carried - fa).abs() <= 1e-9 * fa.abs(), "{k}");
        }
    }

    fn start(p: &TableProblem) -> TemperatureField {
        let n = p.x.len();
        let o = p.options;
        TemperatureField { x: p.x.clone(), film: vec![p.inlet_temperature; n * o.film_points], body_1: vec![p.inlet_temperature; n * o.solid_points], body_2: vec![p.inlet_temperature; n * o.solid_points], film_points: o.film_points, solid_points: o.solid_points }
    }

    fn solved(table: &TractionTable) -> Vec<usize> {
        let entries = table.entries.lock().unwrap();
        (0..entries.len()).filter(|&k| matches!(entries[k], Entry::Solved { .. })).collect()
    }

    /// A table solves only the entries the queries need, and its values do not depend on the
    /// order of the queries: the same as every entry solved up front and interpolated whole.
    #[test]
    fn lazy_table_solves_what_it_needs_and_matches_the_whole_table() {
        let p = problem();
        let field = start(&p);
        let lazy = TractionTable::new(problem(), field.clone(), 0.047 * 3.0).unwrap();
        // The point's own interval [0.015, 0.05], its neighbours 0.004 and 0.15, and rolling
        // (0.004's start).
        assert_eq!(solved(&lazy), vec![6, 7, 8, 9, 10]);
        let view = TableView { table: Arc::new(lazy), speed: 1.0, ratio: None, calibration: None };
        let queries = [0.12, -0.1 * 3.0, 0.01, 5.0];
        let values: Vec<(f64, f64)> = queries.iter().map(|&q| view.force(q)).collect();
        assert_eq!(solved(&view.table), (0..13).filter(|&k| k != 0).collect::<Vec<_>>(), "−2 is not needed by any query");
        // The whole table, eagerly: rolling from the start, then outwards each from its inner
        // neighbour.
        let n = SLIDE_TO_ROLL_TABLE.len();
        let (mut x, mut y, mut fields) = (vec![0.0; n], vec![0.0; n], vec![None; n]);
        for k in (ROLLING..n).chain((0..ROLLING).rev()) {
            let warm = if k == ROLLING { &field } else { fields[if k > ROLLING { k - 1 } else { k + 1 }].as_ref().unwrap() };
            let (_, us, f, next) = p.solve(SLIDE_TO_ROLL_TABLE[k], warm).unwrap();
            (x[k], y[k], fields[k]) = (us, f, Some(next));
        }
        let m: Vec<f64> = (0..x.len()).map(|i| steffen_slope(&x, &y, i)).collect();
        for (&q, &(v, dv)) in queries.iter().zip(&values) {
            let (w, dw) = hermite(&x, &y, &m, interval(&x, q), q);
            println!("u_s {q}: lazy {v:.6e} / {dv:.6e}, whole {w:.6e} / {dw:.6e}");
            assert_eq!((v, dv), (w, dw), "{q}");
        }
        // Queried again in the reverse order: the same values.
        let view2 = TableView { table: Arc::new(TractionTable::new(problem(), field, 0.047 * 3.0).unwrap()), speed: 1.0, ratio: None, calibration: None };
        for (&q, &v) in queries.iter().zip(&values).rev() {
            assert_eq!(view2.force(q), v);
        }
    }

    fn slopes(x: &[f64], y: &[f64]) -> Vec<f64> {
        (0..x.len()).map(|i| steffen_slope(x, y, i)).collect()
    }

    #[test]
    fn steffen_interpolant_passes_through_the_data_without_overshoot() {
        let x = [-2.0, -0.5, 0.0, 0.5, 2.0];
        let y = [-1.0, -0.9, 0.0, 0.9, 1.0];
        let m = slopes(&x, &y);
        let at = |v: f64| hermite(&x, &y, &m, interval(&x, v), v);
        for (i, &xi) in x.iter().enumerate() {
            assert!((at(xi).0 - y[i]).abs() < 1e-12);
        }
        for k in 0..=400 {
            let u = -2.0 + 4.0 * k as f64 / 400.0;
            let (v, _) = at(u);
            assert!((-1.0 - 1e-12..=1.0 + 1e-12).contains(&v), "{u}: {v}");
        }
        // Slope against a finite difference.
        let (a, da) = at(0.3);
        let (b, _) = at(0.3 + 1e-7);
        assert!(((b - a) / 1e-7 - da).abs() < 1e-5);
    }

    #[test]
    fn the_interpolant_reads_only_its_stencil() {
        // NaN outside the four nodes around the interval changes nothing.
        let x: Vec<f64> = (0..7).map(|i| i as f64 * 0.7 - 2.0).collect();
        let y: Vec<f64> = x.iter().map(|v: &f64| v.tanh()).collect();
        let m = slopes(&x, &y);
        for at in [-3.0, -1.9, -0.3, 2.1, 3.5] {
            let j = interval(&x, at);
            let (mut xs, mut ys) = (vec![f64::NAN; 7], vec![f64::NAN; 7]);
            for i in j.saturating_sub(1)..=(j + 2).min(6) {
                xs[i] = x[i];
                ys[i] = y[i];
            }
            let mut ms = vec![f64::NAN; 7];
            ms[j] = steffen_slope(&xs, &ys, j);
            ms[j + 1] = steffen_slope(&xs, &ys, j + 1);
            assert_eq!(hermite(&xs, &ys, &ms, j, at), hermite(&x, &y, &m, j, at), "{at}");
        }
    }
}
