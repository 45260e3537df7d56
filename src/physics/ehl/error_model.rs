//! Estimated error of the closed-form line-contact films — Moes' central film and Pan–Hamrock's
//! minimum film ([`super::formulas`]) — for a contact state, from maps *measured* with the
//! numerical solver. The `auto` fidelity runs the closed form where
//! [`estimate_closed_form_error`] is within the requested tolerance and the numerical solver
//! elsewhere.
//!
//! # The model
//! The relative error of a closed-form film against the numerical (isothermal, Roelands,
//! Dowson–Higginson, squeeze) solution is split into
//! * a **steady** part `e_s(M, L)`: the signed error of the formula against the grid-converged
//!   steady solution, tabulated over Moes' `M` and `L` ([`STEADY_M`], [`STEADY_L`],
//!   [`STEADY_CENTRAL`], [`STEADY_MINIMUM`]) and interpolated bilinearly in `(ln M, ln L)`;
//! * a **transient** part `e_t(ξ)`: the largest measured departure of the squeeze (transient)
//!   solution from the steady solution at the same instant, as a function of the squeeze number
//!   `ξ` ([`squeeze_number`]) ([`SQUEEZE_XI`], [`SQUEEZE_CENTRAL`], [`SQUEEZE_MINIMUM`]).
//!
//! The estimate is the worst case of the two, `|e_s| + e_t (1 + |e_s|)`. Outside the measured
//! maps — `M` or `L` beyond the tables, `α p_h` beyond [`MAX_ALPHA_PH`], `ξ` beyond the last
//! squeeze bin, zero entrainment — the estimate is `f64::INFINITY`: nothing was measured there, so
//! the caller must run the numerical solver. Proximity to zero entrainment shows up twice: `M`
//! grows like `|u_m|^(−1/2)` and `ξ` like `1/|u_m|`.
//!
//! The slide-to-roll ratio is part of [`ContactState`] but does not enter the estimate: the
//! numerical model is isothermal and its Reynolds equation Newtonian, so sliding changes the
//! traction and not the film (checked by a test). With shear heating (not modelled, see
//! [`super`]) the film would thin with sliding and this estimate would be optimistic there.
//!
//! # How the tables were generated
//! `cargo bench --bench ehl -- error-map` (release) prints both tables as Rust source:
//! * steady: [`measure_steady`] at every `(M, L)` cell with `α p_h ≤ MAX_ALPHA_PH`, by Richardson
//!   extrapolation of 511 and 256 nodes (tolerance 1e-9), for the reference contact of
//!   [`reference_contact`] (steel, `R` = 10 mm, `η0` = 0.04 Pa·s, `α` = 2e-8 1/Pa, Roelands and
//!   Dowson–Higginson at the reference temperature);
//! * transient: [`measure_squeeze`] over the benchmark cam-like cycle ([`cycle_input`]) at cycle
//!   periods of 4, 2, 1, ½ and ¼ times 63.2 ms (950 rpm), Richardson 97 + 193 nodes; each angle gives
//!   `(ξ, e_t)`; the table holds the largest `|e_t|` per `ξ` bin, made non-decreasing in `ξ`.
//!
//! A validation test regenerates a few cells at smaller grids and checks them against the tables.

use super::formulas::{moes_central_film, pan_hamrock_minimum_film, Groups};
use super::{EhlInput, EhlOptions, Extrapolation, Rheology, TransientSolver};
use crate::physics::lubricant::Lubricant;
use crate::physics::{Observer, SolveError};

/// A contact state as the `auto` fidelity sees it (dimensionless; compute `M`, `L` with
/// [`Groups`] and `ξ` with [`squeeze_number`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ContactState {
    /// Moes load parameter `M` (sum-velocity convention, [`Groups::moes_m`]).
    pub moes_m: f64,
    /// Moes material parameter `L` ([`Groups::moes_l`]).
    pub moes_l: f64,
    /// Slide-to-roll ratio `u_s/u_m` (does not enter the estimate: see the module docs).
    pub slide_roll_ratio: f64,
    /// Squeeze number `ξ` ([`squeeze_number`]); 0 in steady running.
    pub squeeze_number: f64,
}

impl ContactState {
    /// The state of a contact with groups `g`, slide-to-roll ratio and squeeze number.
    pub fn new(g: &Groups, slide_roll_ratio: f64, squeeze_number: f64) -> Self {
        ContactState { moes_m: g.moes_m, moes_l: g.moes_l, slide_roll_ratio, squeeze_number }
    }
}

/// Squeeze number `ξ = (b/|u_m|) |d ln h/dt|`: the time the lubricant takes to cross the
/// Hertzian half-width `b` (m) at the entrainment speed `u_m` (m/s), over the time scale on which
/// the (closed-form, quasi-steady) film `h` changes; `film_rate = d ln h/dt` (1/s), e.g. by
/// differencing the closed-form film over neighbouring cam angles. `ξ ≪ 1`: quasi-steady; `ξ`
/// of order 0.1 and more: the film lags behind (squeeze, entrainment reversal). Infinite at
/// zero entrainment.
pub fn squeeze_number(half_width: f64, entrainment_velocity: f64, film_rate: f64) -> f64 {
    let u = entrainment_velocity.abs();
    if u == 0.0 {
        return f64::INFINITY;
    }
    half_width / u * film_rate.abs()
}

/// Estimated relative errors (magnitudes) of the closed-form films.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ClosedFormError {
    /// Moes' central film.
    pub central: f64,
    /// Pan–Hamrock's minimum film.
    pub minimum: f64,
}

/// Estimated relative errors of Moes' central and Pan–Hamrock's minimum film for `state`
/// (`f64::INFINITY` outside the measured maps).
pub fn closed_form_errors(state: &ContactState) -> ClosedFormError {
    let steady = steady_errors(state.moes_m, state.moes_l);
    let squeeze = squeeze_errors(state.squeeze_number);
    let combine = |s: Option<f64>, t: Option<f64>| match (s, t) {
        (Some(s), Some(t)) => s.abs() + t * (1.0 + s.abs()),
        _ => f64::INFINITY,
    };
    ClosedFormError {
        central: combine(steady.map(|s| s.0), squeeze.map(|t| t.0)),
        minimum: combine(steady.map(|s| s.1), squeeze.map(|t| t.1)),
    }
}

/// The larger of the estimated relative errors of the closed-form central and minimum films
/// for `state` (`f64::INFINITY` where nothing was measured): compare with the tolerance of the
/// `auto` fidelity.
pub fn estimate_closed_form_error(state: &ContactState) -> f64 {
    let e = closed_form_errors(state);
    e.central.max(e.minimum)
}

/// Largest `α p_h = L sqrt(M/2π)` of the steady map (`p_h` ≈ 3.5 GPa at `α` = 2e-8 1/Pa).
pub const MAX_ALPHA_PH: f64 = 70.0;

/// `M` of the steady map's rows.
pub const STEADY_M: [f64; NM] = [0.3, 0.5, 1.0, 2.0, 3.0, 5.0, 10.0, 20.0, 30.0, 50.0, 100.0, 200.0, 300.0, 500.0, 1000.0];
/// `L` of the steady map's columns.
pub const STEADY_L: [f64; NL] = [2.5, 5.0, 7.5, 10.0, 12.5, 15.0, 20.0];
/// Rows and columns of the steady map.
pub const NM: usize = 15;
pub const NL: usize = 7;

/// Signed relative error `h_Moes/h_c − 1` of Moes' central film against the numerical steady
/// solution, by `[M][L]`; `None` where `α p_h > MAX_ALPHA_PH`. Generated by
/// `cargo bench --bench ehl -- error-map` (see the module docs).
#[rustfmt::skip]
pub const STEADY_CENTRAL: [[Option<f64>; NL]; NM] = [
    //    L = 2.5,       5,            7.5,          10,           12.5,         15,           20
    [Some(0.2058), Some(0.1847), Some(0.1726), Some(0.1668), Some(0.1656), Some(0.1676), Some(0.1773)], // M = 0.3
    [Some(0.1853), Some(0.1718), Some(0.1738), Some(0.1828), Some(0.1942), Some(0.2056), Some(0.2249)], // M = 0.5
    [Some(0.1246), Some(0.1416), Some(0.1589), Some(0.1697), Some(0.1747), Some(0.1760), Some(0.1776)], // M = 1
    [Some(-0.0131), Some(-0.0061), Some(-0.0007), Some(0.0170), Some(0.0391), Some(0.0573), Some(0.0857)], // M = 2
    [Some(-0.0473), Some(-0.0148), Some(0.0198), Some(0.0447), Some(0.0645), Some(0.0812), Some(0.1079)], // M = 3
    [Some(-0.0083), Some(0.0302), Some(0.0592), Some(0.0820), Some(0.1007), Some(0.1162), Some(0.1408)], // M = 5
    [Some(0.0288), Some(0.0712), Some(0.1018), Some(0.1249), Some(0.1429), Some(0.1574), Some(0.1793)], // M = 10
    [Some(0.0609), Some(0.1097), Some(0.1421), Some(0.1650), Some(0.1820), Some(0.1951), Some(0.2141)], // M = 20
    [Some(0.0805), Some(0.1331), Some(0.1660), Some(0.1883), Some(0.2045), Some(0.2166), Some(0.2338)], // M = 30
    [Some(0.1064), Some(0.1625), Some(0.1954), Some(0.2167), Some(0.2317), Some(0.2426), Some(0.2575)], // M = 50
    [Some(0.1431), Some(0.2017), Some(0.2329), Some(0.2521), Some(0.2651), Some(0.2744), None], // M = 100
    [Some(0.1804), Some(0.2383), Some(0.2667), Some(0.2835), None, None, None], // M = 200
    [Some(0.2018), Some(0.2580), Some(0.2846), Some(0.2999), None, None, None], // M = 300
    [Some(0.2277), Some(0.2810), Some(0.3050), None, None, None, None], // M = 500
    [Some(0.2595), Some(0.3075), None, None, None, None, None], // M = 1000
];
/// Signed relative error `h_PH/h_min − 1` of Pan–Hamrock's minimum film, as [`STEADY_CENTRAL`].
#[rustfmt::skip]
pub const STEADY_MINIMUM: [[Option<f64>; NL]; NM] = [
    //    L = 2.5,       5,            7.5,          10,           12.5,         15,           20
    [Some(-0.6544), Some(-0.5215), Some(-0.4290), Some(-0.3585), Some(-0.3025), Some(-0.2571), Some(-0.1884)], // M = 0.3
    [Some(-0.5018), Some(-0.3327), Some(-0.2281), Some(-0.1575), Some(-0.1085), Some(-0.0740), Some(-0.0334)], // M = 0.5
    [Some(-0.2879), Some(-0.1164), Some(-0.0426), Some(-0.0120), Some(-0.0031), Some(-0.0049), Some(-0.0179)], // M = 1
    [Some(-0.1774), Some(-0.0601), Some(-0.0290), Some(-0.0215), Some(-0.0233), Some(-0.0292), Some(-0.0447)], // M = 2
    [Some(-0.1538), Some(-0.0507), Some(-0.0263), Some(-0.0245), Some(-0.0303), Some(-0.0389), Some(-0.0578)], // M = 3
    [Some(-0.1256), Some(-0.0390), Some(-0.0253), Some(-0.0298), Some(-0.0399), Some(-0.0510), Some(-0.0732)], // M = 5
    [Some(-0.0974), Some(-0.0293), Some(-0.0262), Some(-0.0378), Some(-0.0526), Some(-0.0675), Some(-0.0907)], // M = 10
    [Some(-0.0747), Some(-0.0214), Some(-0.0268), Some(-0.0433), Some(-0.0614), Some(-0.0787), Some(-0.1097)], // M = 20
    [Some(-0.0628), Some(-0.0168), Some(-0.0264), Some(-0.0453), Some(-0.0650), Some(-0.0834), Some(-0.1157)], // M = 30
    [Some(-0.0483), Some(-0.0111), Some(-0.0252), Some(-0.0466), Some(-0.0680), Some(-0.0876), Some(-0.1218)], // M = 50
    [Some(-0.0292), Some(-0.0027), Some(-0.0223), Some(-0.0471), Some(-0.0703), Some(-0.0911), None], // M = 100
    [Some(-0.0103), Some(0.0064), Some(-0.0180), Some(-0.0450), None, None, None], // M = 200
    [Some(0.0009), Some(0.0120), Some(-0.0148), Some(-0.0437), None, None, None], // M = 300
    [Some(0.0149), Some(0.0195), Some(-0.0105), None, None, None, None], // M = 500
    [Some(0.0333), Some(0.0293), None, None, None, None, None], // M = 1000
];

/// Upper ends of the squeeze-number bins (the first bin starts at 0).
pub const SQUEEZE_XI: [f64; 8] = [0.001, 0.003, 0.01, 0.03, 0.1, 0.3, 1.0, 3.0];
/// Largest measured `|h_transient/h_steady − 1|` of the central film per bin of
/// [`SQUEEZE_XI`], non-decreasing; `None`: no sample in or beyond the bin.
pub const SQUEEZE_CENTRAL: [Option<f64>; 8] = [Some(0.0031), Some(0.0055), Some(0.0163), Some(0.0467), Some(0.1432), Some(0.4105), Some(0.8473), Some(1.4410)];
/// The same for the minimum film.
pub const SQUEEZE_MINIMUM: [Option<f64>; 8] = [Some(0.0035), Some(0.0071), Some(0.0201), Some(0.0612), Some(0.2362), Some(0.3918), Some(0.4486), Some(0.6367)];

/// Bilinear interpolation of the steady map in `(ln M, ln L)`; `None` outside it or inside a
/// cell with an unmeasured corner.
fn steady_errors(m: f64, l: f64) -> Option<(f64, f64)> {
    if !(m.is_finite() && l.is_finite() && m > 0.0 && l > 0.0) || l * (m / (2.0 * std::f64::consts::PI)).sqrt() > MAX_ALPHA_PH {
        return None;
    }
    let bracket = |v: f64, axis: &[f64]| -> Option<(usize, f64)> {
        if v < axis[0] || v > axis[axis.len() - 1] {
            return None;
        }
        let i = axis.partition_point(|&a| a <= v).clamp(1, axis.len() - 1);
        let t = (v.ln() - axis[i - 1].ln()) / (axis[i].ln() - axis[i - 1].ln());
        Some((i, t))
    };
    let (i, s) = bracket(m, &STEADY_M)?;
    let (j, t) = bracket(l, &STEADY_L)?;
    // Corners of zero weight (on a grid line) may be unmeasured.
    let lerp = |table: &[[Option<f64>; NL]; NM]| -> Option<f64> {
        let mut sum = 0.0;
        for (ii, wi) in [(i - 1, 1.0 - s), (i, s)] {
            for (jj, wj) in [(j - 1, 1.0 - t), (j, t)] {
                if wi * wj > 0.0 {
                    sum += wi * wj * table[ii][jj]?;
                }
            }
        }
        Some(sum)
    };
    Some((lerp(&STEADY_CENTRAL)?, lerp(&STEADY_MINIMUM)?))
}

/// The transient part for squeeze number `xi`; `None` beyond the measured bins.
fn squeeze_errors(xi: f64) -> Option<(f64, f64)> {
    if !(xi >= 0.0) {
        return None;
    }
    let k = SQUEEZE_XI.iter().position(|&top| xi <= top)?;
    Some((SQUEEZE_CENTRAL[k]?, SQUEEZE_MINIMUM[k]?))
}

/// The steel contact the steady map is measured on, at Moes `M`, `L`: `E'` = 2.2e11 Pa,
/// `R` = 10 mm, `η0` = 0.04 Pa·s, `α` = 2e-8 1/Pa, Roelands and Dowson–Higginson at 303 K.
/// `w' = M (L/G)² E' R`, `u_m = (L/G)⁴ E' R/(2 η0)` with `G = α E'`.
pub fn reference_contact(m: f64, l: f64) -> EhlInput<'static> {
    let (e_prime, r, eta0, alpha) = (2.2e11, 0.01, 0.04, 2e-8);
    let lubricant = Lubricant { viscosity: eta0, pressure_viscosity: alpha, ..Lubricant::SEED000 };
    let g = alpha * e_prime;
    let u_sum = (l / g).powi(4);
    EhlInput {
        load_per_length: m * u_sum.sqrt() * e_prime * r,
        reduced_radius: r,
        effective_modulus: e_prime,
        entrainment_velocity: 0.5 * u_sum * e_prime * r / eta0,
        sliding_velocity: 0.0,
        lubricant,
        temperature: lubricant.reference_temperature,
        rheology: Rheology::default(),
        transient: None,
        warm_start: None,
    }
}

/// Measure one steady cell: the signed errors `(h_Moes/h_c − 1, h_PH/h_min − 1)` of the
/// closed forms against Richardson extrapolation of `nodes` and `(nodes − 1)/2 + 1` nodes.
pub fn measure_steady(m: f64, l: f64, nodes: usize, observer: &dyn Observer) -> Result<(f64, f64), SolveError> {
    let input = reference_contact(m, l);
    let options = EhlOptions { nodes, tolerance: 1e-9, max_iterations: 80, ..EhlOptions::default() };
    let mut solver = TransientSolver::new(options, Extrapolation::Richardson);
    let s = solver.step(&input, None, observer)?;
    let r = input.reduced_radius;
    let g = Groups::of(input.load_per_length, r, input.effective_modulus, input.entrainment_velocity, &input.lubricant, input.temperature);
    Ok((moes_central_film(&g, r) / s.central_film - 1.0, pan_hamrock_minimum_film(&g, r) / s.min_film - 1.0))
}

/// The benchmark cam-like cycle at angle index `k` of `steps`: load 2.25–12.5 kN over 21 mm,
/// radius 15.2–10.5 mm, entrainment `u_m = 4 cos θ + 1.5` m/s (reverses twice), slide 1 %,
/// oil η0 = 0.013 Pa·s, α = 1.84e-8 1/Pa (Roelands, Dowson–Higginson), steel (`E'` = 219.8 GPa).
/// The velocities do not depend on the cycle period: a shorter period is a faster load change
/// at the same entrainment, a larger squeeze number.
pub fn cycle_input(k: usize, steps: usize) -> EhlInput<'static> {
    let th = 2.0 * std::f64::consts::PI * k as f64 / steps as f64;
    let f = 2250.0 + (12500.0 - 2250.0) * (0.5 - 0.5 * th.cos()).powi(2);
    let r = 0.0152 - 0.0047 * (0.5 - 0.5 * th.cos());
    let u = 4.0 * th.cos() + 1.5;
    let lubricant = Lubricant { viscosity: 0.013, pressure_viscosity: 1.84e-8, ..Lubricant::SEED000 };
    EhlInput {
        load_per_length: f / 0.021,
        reduced_radius: r,
        effective_modulus: 2.0 / (2.0 * 0.91 / 200e9),
        entrainment_velocity: u,
        sliding_velocity: 0.01 * u,
        lubricant,
        temperature: lubricant.reference_temperature,
        rheology: Rheology { eyring_stress: Some(5e6), ..Rheology::default() },
        transient: None,
        warm_start: None,
    }
}

/// One sample of the transient map: squeeze number and the departures
/// `h_transient/h_steady − 1` of the central and minimum film.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SqueezeSample {
    pub angle_index: usize,
    pub xi: f64,
    pub central: f64,
    pub minimum: f64,
}

/// Measure the transient map over the second of two revolutions of [`cycle_input`] (the first
/// sets up the squeeze history) with `steps` angles per revolution of `period` s: at each angle
/// the squeeze solution against the steady solution at the same instant (both Richardson of
/// `nodes` and `(nodes − 1)/2 + 1`), and `ξ` from Moes' central film differenced over the
/// neighbouring angles. Angles where the steady problem has no solution (zero entrainment)
/// are skipped.
pub fn measure_squeeze(period: f64, steps: usize, nodes: usize, tolerance: f64, observer: &dyn Observer) -> Result<Vec<SqueezeSample>, SolveError> {
    let options = EhlOptions { nodes, tolerance, ..EhlOptions::default() };
    let mut transient = TransientSolver::new(options, Extrapolation::Richardson);
    let mut steady = TransientSolver::new(options, Extrapolation::Richardson);
    let dt = period / steps as f64;
    let moes = |k: usize| {
        let i = cycle_input(k % steps, steps);
        let g = Groups::of(i.load_per_length, i.reduced_radius, i.effective_modulus, i.entrainment_velocity, &i.lubricant, i.temperature);
        moes_central_film(&g, i.reduced_radius)
    };
    let mut out = Vec::new();
    for k in 0..2 * steps {
        let input = cycle_input(k % steps, steps);
        let t = transient.step(&input, Some(dt), observer)?;
        if k < steps {
            continue;
        }
        let s = match steady.step(&input, None, observer) {
            Ok(s) => s,
            Err(SolveError::Physical { .. }) | Err(SolveError::NotConverged { .. }) => {
                steady.reset();
                continue;
            }
            Err(e) => return Err(e),
        };
        let (a, b) = (moes(k + steps - 1), moes(k + 1));
        let rate = if a > 0.0 && b > 0.0 { (b.ln() - a.ln()) / (2.0 * dt) } else { f64::INFINITY };
        out.push(SqueezeSample {
            angle_index: k - steps,
            xi: squeeze_number(t.hertz_half_width, input.entrainment_velocity, rate),
            central: t.central_film / s.central_film - 1.0,
            minimum: t.min_film / s.min_film - 1.0,
        });
    }
    Ok(out)
}

/// The squeeze table from samples: the largest `|e_t|` per bin of [`SQUEEZE_XI`], made
/// non-decreasing; bins beyond the last sample stay `None`.
pub fn squeeze_table(samples: &[SqueezeSample]) -> ([Option<f64>; 8], [Option<f64>; 8]) {
    let mut c = [None::<f64>; 8];
    let mut m = [None::<f64>; 8];
    for s in samples {
        if let Some(k) = SQUEEZE_XI.iter().position(|&top| s.xi <= top) {
            c[k] = Some(c[k].unwrap_or(0.0).max(s.central.abs()));
            m[k] = Some(m[k].unwrap_or(0.0).max(s.minimum.abs()));
        }
    }
    let last = c.iter().rposition(|v| v.is_some());
    let (mut rc, mut rm) = (0.0f64, 0.0f64);
    for k in 0..8 {
        if last.is_some_and(|l| k <= l) {
            rc = rc.max(c[k].unwrap_or(0.0));
            rm = rm.max(m[k].unwrap_or(0.0));
            c[k] = Some(rc);
            m[k] = Some(rm);
        }
    }
    (c, m)
}
