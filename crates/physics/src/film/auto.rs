//! The `auto` fidelity: per contact point, the closed form where its estimated error is within a
//! tolerance, the numerical EHL solver elsewhere. The whole decision is [`closed_form_error`];
//! [`Auto`] only compares its estimate with the tolerance.
//!
//! # The error estimate
//! The estimate is the largest of three measured contributions, each a relative error of the
//! closed-form film against the numerical solution (`physics::ehl`, 384 graded nodes, Roelands
//! viscosity with the pressure–viscosity index from `α`, Dowson–Higginson density):
//!
//! 1. **Steady regime** ([`steady_error`]): the closed form against the steady numerical film,
//!    tabulated over Moes' `M` (load) and `L` (lubricant) — the larger of the central- and
//!    minimum-film errors. Pan–Hamrock regressed elastic–piezoviscous solutions; measured here it
//!    is within 5 % only for `M ≈ 2–20` at small `L` and drifts to −12 … −26 % (too thin) at large
//!    `L` and `M`, while at light loads (`M ≤ 1`) its minimum film is 15–38 % too thin. Outside
//!    the measured load range (`M < 0.5`: the rigid regimes; `M > 1000`: near-dry heavy loads and
//!    vanishing entrainment) and at zero entrainment the estimate is infinite. Outside
//!    `L = 4–20` the nearest table value is used (clamped). Other formulas are estimated through Pan–Hamrock's table:
//!    `e_f = (h_f/h_PH)(1 + e_PH) − 1`.
//! 2. **Squeeze** ([`squeeze_number`]): a closed form is quasi-steady. The ratio of the squeeze
//!    term to the wedge term of Reynolds' equation, `S = b |ḣ| / (|u_m| h)` with `ḣ` the rate of
//!    change of the closed form's steady film between consecutive points, measures how far the
//!    film lags its steady value: measured on the seed 003 cycle, the film error is at most
//!    [`SQUEEZE_ERROR_PER_S`]` · S` (largest just after a reversal), added to the steady error. Near entrainment reversal
//!    `S → ∞`.
//! 3. **Traction** ([`traction_error`]): the closed form spreads the load as Hertz pressure over a
//!    uniform central film. In the Newtonian (linear) range of the shear law the traction depends
//!    on `∫ η(p)/h`, which is dominated by the pressure peak, so it is sensitive to the real
//!    pressure distribution; in the Eyring plateau (large `η u_s/(h τ0)`) only logarithmically.
//!    Measured against the numerical model's nodes over the same `M`–`L` grid (Newtonian: the
//!    closed form is 2–20 % high at `M ≥ 5`, L = 4, 12–36 % at L = 10–20, and off by −35 … +460 %
//!    at `M ≤ 2`, where the real pressure is lower and wider than Hertz's; with an Eyring law the
//!    error shrinks like `1/ln(2x)`): see [`traction_error`]. This term is what makes `auto` pick
//!    the numerical model on the seed 000 roller, whose slip is set by the traction.
//!
//! Point contacts have no numerical model ([`super::Numerical`] keeps the closed form): their
//! estimate is 0 with the rule [`ErrorRule::PointContact`].
//!
//! The estimate is a function of the contact point alone and is written so that a sharper error
//! model (e.g. one measured by the EHL solver for the exact lubricant) can replace any term.

use super::closed_form::ClosedForm;
use super::formulas::{pan_hamrock, LineGroups};
use super::numerical::Numerical;
use super::{ContactInput, ContactShape, FilmModel, FilmSolution};
use crate::friction::Rheology;
use crate::SolveError;
use serde::Serialize;

/// Which rule set the estimate.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum ErrorRule {
    /// The steady film table (load/lubricant regime).
    Regime,
    /// Below the tabulated load range (rigid regimes) or no entrainment: infinite.
    OutsideRange,
    /// The squeeze number.
    Squeeze,
    /// The traction of the closed form.
    Traction,
    /// Point contacts have only the closed form.
    PointContact,
}

/// Estimated relative error of the closed-form film at one contact point.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ClosedFormError {
    /// Relative error (∞ where the closed form does not apply).
    pub estimate: f64,
    /// The contribution that set it.
    pub rule: ErrorRule,
}

/// `ln M` nodes of [`STEADY_TABLE`].
const TABLE_M: [f64; 10] = [0.5, 1.0, 2.0, 5.0, 10.0, 20.0, 50.0, 100.0, 300.0, 1000.0];
/// `L` nodes of [`STEADY_TABLE`].
const TABLE_L: [f64; 5] = [4.0, 7.0, 10.0, 14.0, 20.0];
/// Pan–Hamrock against the numerical solver: `(h_c,PH/h_c − 1, h_min,PH/h_min − 1)` in percent,
/// rows `L`, columns `M` (`cargo bench --bench cam -- auto-tables` regenerates it; a unit test
/// checks one entry).
const STEADY_TABLE: [[(f64, f64); 10]; 5] = [
    [(-15.4, -38.4), (6.6, -16.1), (-1.7, -8.3), (-4.0, -5.3), (-3.6, -3.8), (-3.0, -2.6), (-2.0, -1.0), (-1.1, 0.2), (0.2, 2.4), (0.8, 4.7)],
    [(-0.2, -23.9), (16.3, -4.6), (-0.5, -2.7), (-2.7, -2.0), (-3.9, -2.3), (-4.4, -2.2), (-4.7, -1.9), (-4.9, -1.4), (-5.4, -0.3), (-6.5, 1.2)],
    [(8.2, -15.0), (18.1, -0.6), (-1.1, -1.6), (-4.0, -2.4), (-6.0, -3.6), (-7.2, -4.2), (-8.4, -4.4), (-9.3, -4.3), (-10.8, -3.7), (-12.6, -2.6)],
    [(14.1, -7.9), (16.2, 0.2), (-2.1, -2.1), (-6.4, -3.9), (-9.0, -6.0), (-10.9, -7.0), (-13.0, -7.6), (-14.4, -7.8), (-16.6, -7.5), (-19.0, -6.8)],
    [(17.2, -2.6), (11.6, -1.3), (-4.5, -3.8), (-9.8, -6.4), (-12.5, -7.7), (-15.7, -10.8), (-18.5, -11.7), (-20.4, -12.1), (-23.1, -12.2), (-25.8, -11.7)],
];

/// Film error per unit squeeze number, measured on the seed 003 cycle (720 angles, Pan–Hamrock
/// against the numerical film on 256 nodes). Approaching a reversal the error per unit `S` is
/// ≈ 1–1.6 (central film: 0.08 at S = 0.05, 0.20 at 0.19, 0.39 at 0.66); just after it, while the
/// new inlet builds the film up, the minimum film is off by up to 2.5·S (0.43 at S = 0.17, 0.53 at
/// 0.26, 0.15 at 0.084). 2.5 bounds both.
pub const SQUEEZE_ERROR_PER_S: f64 = 2.5;

/// `M` nodes of [`TRACTION_TABLE`].
const TRACTION_M: [f64; 8] = [0.5, 1.0, 2.0, 5.0, 10.0, 30.0, 100.0, 300.0];
/// `L` nodes of [`TRACTION_TABLE`].
const TRACTION_L: [f64; 3] = [4.0, 10.0, 20.0];
/// Newtonian traction (and traction slope) of the closed form against the numerical model's
/// nodes, `T_closed/T_num − 1` in percent, rows `L`, columns `M` (256 nodes; independent of the
/// sliding velocity in the Newtonian law; `cargo bench --bench cam -- auto-tables`). The closed form puts the Hertz pressure where the
/// light-load solution (`M ≤ 2`) spreads a lower, wider pressure, and misses the spike.
const TRACTION_TABLE: [[f64; 8]; 3] = [
    [-22.0, 2.0, 20.0, 17.0, 13.0, 7.0, 2.0, 0.0],
    [53.0, 111.0, 32.0, 19.0, 21.0, 16.0, 12.0, 12.0],
    [461.0, 201.0, -35.0, 3.0, 36.0, 33.0, 29.0, 45.0],
];

/// The largest `|table|` value at the corners of the table cell holding `(m, l)` (clamped to the
/// table): conservative where neighbouring measurements differ.
fn cell_max<const NM: usize, const NL: usize>(ms: &[f64; NM], ls: &[f64; NL], m: f64, l: f64, value: impl Fn(usize, usize) -> f64) -> f64 {
    let bracket = |nodes: &[f64], v: f64| -> (usize, usize) {
        let n = nodes.len();
        if v <= nodes[0] {
            return (0, 0);
        }
        if v >= nodes[n - 1] {
            return (n - 1, n - 1);
        }
        let i = nodes.partition_point(|&x| x <= v);
        (i - 1, i)
    };
    let (m0, m1) = bracket(ms, m);
    let (l0, l1) = bracket(ls, l);
    [(l0, m0), (l0, m1), (l1, m0), (l1, m1)].iter().map(|&(a, b)| value(a, b).abs()).fold(0.0, f64::max)
}

/// Pan–Hamrock's tabulated relative errors `(central, minimum)` at Moes `M`, `L`
/// (bilinear in `ln M` and `L`, `L` clamped to the table), or `None` outside the measured load
/// range `M = 0.5–1000` (rigid regimes; near-dry heavy loads or vanishing entrainment).
pub fn pan_hamrock_table(m: f64, l: f64) -> Option<(f64, f64)> {
    if !(m >= TABLE_M[0] && m <= TABLE_M[TABLE_M.len() - 1]) || !l.is_finite() {
        return None;
    }
    let locate = |nodes: &[f64], v: f64, f: &dyn Fn(f64) -> f64| -> (usize, f64) {
        let v = f(v.clamp(nodes[0], nodes[nodes.len() - 1]));
        let i = nodes.partition_point(|&x| f(x) <= v).clamp(1, nodes.len() - 1);
        let (a, b) = (f(nodes[i - 1]), f(nodes[i]));
        (i, ((v - a) / (b - a)).clamp(0.0, 1.0))
    };
    let (im, tm) = locate(&TABLE_M, m, &|x: f64| x.ln());
    let (il, tl) = locate(&TABLE_L, l, &|x: f64| x);
    let at = |li: usize, mi: usize| STEADY_TABLE[li][mi];
    let lerp = |a: (f64, f64), b: (f64, f64), t: f64| (a.0 + (b.0 - a.0) * t, a.1 + (b.1 - a.1) * t);
    let lo = lerp(at(il - 1, im - 1), at(il - 1, im), tm);
    let hi = lerp(at(il, im - 1), at(il, im), tm);
    let (c, mn) = lerp(lo, hi, tl);
    Some((c / 100.0, mn / 100.0))
}

/// Steady-regime error of a closed-form line-contact film (`film_central`, `film_min`, m) for the groups `g` (`None`: outside the
/// closed form's range).
pub fn steady_error(g: &LineGroups, film_central: f64, film_min: f64, radius: f64) -> Option<f64> {
    let u_sum = 2.0 * g.speed;
    if !(u_sum > 0.0) {
        return None;
    }
    let m = g.load / u_sum.sqrt();
    let l = g.material * u_sum.powf(0.25);
    let (ec, em) = pan_hamrock_table(m, l)?;
    let (pc, pm) = pan_hamrock(g);
    let (pc, pm) = (pc * radius, pm * radius);
    // The numerical films implied by the table, then this formula's error against them.
    let (nc, nm) = (pc / (1.0 + ec), pm / (1.0 + em));
    Some(((film_central / nc - 1.0).abs()).max((film_min / nm - 1.0).abs()))
}

/// Squeeze number `S = b |ḣ| / (|u_m| h)` between `previous` and the closed-form solution `now`
/// at `input` (0 without a previous point or time step; ∞ at zero entrainment).
pub fn squeeze_number(input: &ContactInput, previous: Option<&FilmSolution>, now: &FilmSolution) -> f64 {
    let u = input.entrainment_velocity.abs();
    match previous {
        Some(prev) if input.time_step > 0.0 => {
            let h = now.steady_central_film;
            if !(u > 0.0 && h > 0.0) {
                return f64::INFINITY;
            }
            let hdot = (h - prev.steady_central_film) / input.time_step;
            now.half_width * hdot.abs() / (u * h)
        }
        _ => 0.0,
    }
}

/// Traction error of the closed form (relative) at Moes `m`, `l`: the Newtonian table value
/// (largest at the corners of its cell), divided by `max(1, ln 2x)` with the Eyring parameter at
/// the Hertzian peak `x = η(p0) |u_s| / (h_c τ0)` — in the Eyring plateau the stress depends on
/// the viscosity and film only through `ln x`. Measured with τ0 = 5 MPa: at M = 10, L = 10 the
/// closed form is 21 % high at x = 0.26, 13 % at x = 2.6 and 6 % at x = 26 (the rule: 21, 12.7,
/// 5.3 %).
pub fn traction_error(input: &ContactInput, now: &FilmSolution, m: f64, l: f64) -> f64 {
    let newtonian = cell_max(&TRACTION_M, &TRACTION_L, m, l, |li, mi| TRACTION_TABLE[li][mi]) / 100.0;
    let x = match input.traction_law.rheology {
        Rheology::Eyring { tau0 } if tau0 > 0.0 && now.central_film > 0.0 => {
            let eta = input.lubricant.viscosity_at(now.max_pressure, input.temperature);
            eta * input.sliding_velocity.abs() / (now.central_film * tau0)
        }
        _ => 0.0,
    };
    newtonian / (2.0 * x).ln().max(1.0)
}

/// The estimated relative error of a closed form at `input` (the whole `auto` decision; see the
/// module docs). `now` is the closed form's solution at `input`, `previous` the run's solution at
/// the previous point.
pub fn closed_form_error(
    input: &ContactInput,
    previous: Option<&FilmSolution>,
    now: &FilmSolution,
) -> ClosedFormError {
    let (r, length) = match input.shape {
        ContactShape::Point { .. } => return ClosedFormError { estimate: 0.0, rule: ErrorRule::PointContact },
        ContactShape::Line { reduced_radius, length } => (reduced_radius, length),
    };
    let outside = ClosedFormError { estimate: f64::INFINITY, rule: ErrorRule::OutsideRange };
    let t = input.temperature;
    let eta0 = input.lubricant.viscosity_at(0.0, t);
    let g = LineGroups::new(input.load / length, r, input.entrainment_velocity, eta0, input.lubricant.pressure_viscosity, 2.0 * input.contact_modulus);
    let Some(steady) = steady_error(&g, now.steady_central_film, now.min_film.min(now.steady_central_film), r) else {
        return outside;
    };
    // Film: the steady error plus the lag behind the steady film.
    let squeeze = SQUEEZE_ERROR_PER_S * squeeze_number(input, previous, now);
    let film = steady + squeeze;
    let rule = if squeeze > steady { ErrorRule::Squeeze } else { ErrorRule::Regime };
    let u_sum = 2.0 * g.speed;
    let (m, l) = (g.load / u_sum.sqrt(), g.material * u_sum.powf(0.25));
    let traction = traction_error(input, now, m, l);
    if traction > film {
        ClosedFormError { estimate: traction, rule: ErrorRule::Traction }
    } else {
        ClosedFormError { estimate: film, rule }
    }
}

/// Estimated relative error of the isothermal numerical model against the thermal one at a
/// point (`ehl.thermal` with `auto`): the larger of
/// * the **thermal film reduction** `0.11 L^0.64 (1 + 0.6 S^0.8)`, `L = β η0 u_m²/k_f`, `S` the
///   slide-to-roll ratio — fitted to this project's thermal model (`tests/it/thermal_ehl.rs`:
///   1 − φ = 0.0145, 0.033, 0.064 at L = 0.046, 0.18, 0.41 in rolling, 0.077 at S = 0.3;
///   the fit is within 0.004 of each);
/// * the **traction**: the isothermal film's viscosity drop `1 − exp(−β_p ΔT)` over the shear
///   heating's temperature rise, `ΔT = q h/(8 k_f)` in the film plus the surfaces' Blok flash
///   temperature, with the heat flux `q = τ u_s` of the isothermal nodes at the peak pressure and
///   `β_p = −∂ ln η/∂T` there.
pub fn thermal_error(input: &ContactInput, iso: &FilmSolution, film_heat: &crate::ehl::thermal::FilmHeat, bodies: (&crate::thermal::ThermalSolid, &crate::thermal::ThermalSolid)) -> f64 {
    let lub = input.lubricant;
    let t = input.temperature;
    let um = input.entrainment_velocity.abs();
    let us = input.sliding_velocity.abs();
    let eta0 = lub.viscosity_at(0.0, t);
    let beta0 = -lub.ln_viscosity_temperature_slope(0.0, t);
    let l = beta0 * eta0 * um * um / film_heat.conductivity;
    let srr = if um > 0.0 { us / um } else { 2.0 };
    let film = 0.11 * l.powf(0.64) * (1.0 + 0.6 * srr.powf(0.8));
    // Traction: the node carrying the peak pressure.
    let Some(node) = iso.nodes.iter().max_by(|a, b| a.pressure.total_cmp(&b.pressure)) else {
        return film;
    };
    let tau = match input.traction_law.rheology {
        crate::friction::Rheology::Eyring { tau0 } => tau0 * (node.viscosity * us / (node.film * tau0)).asinh(),
        crate::friction::Rheology::Newtonian => node.viscosity * us / node.film,
    };
    let q = tau * us;
    let film_rise = q * node.film / (8.0 * film_heat.conductivity);
    let (v1, v2) = (input.entrainment_velocity + 0.5 * input.sliding_velocity, input.entrainment_velocity - 0.5 * input.sliding_velocity);
    let power = q * iso.contact_area;
    let flash = crate::thermal::flash_temperature(power, iso.half_width, iso.contact_area, v1, v2, bodies.0, bodies.1);
    let beta_p = -lub.ln_viscosity_temperature_slope(node.pressure, t);
    let traction = 1.0 - (-beta_p * (film_rise + flash)).exp();
    film.max(traction)
}

/// The `auto` film model.
#[derive(Debug)]
pub struct Auto {
    pub fast: ClosedForm,
    pub numerical: Numerical,
    /// Largest estimated relative error of the closed form accepted.
    pub tolerance: f64,
    /// With `ehl.thermal`: the thermal model, run where [`thermal_error`] of the isothermal
    /// numerical solution exceeds the tolerance.
    pub thermal: Option<super::thermal::ThermalNumerical>,
}

impl FilmModel for Auto {
    /// 1e-4: the film moves by < 1e-4 relative, against a discretisation error of ≈ 1e-2.
    fn entrainment_tolerance(&self) -> f64 {
        1e-4
    }

    fn solve(&self, input: &ContactInput, previous: Option<&FilmSolution>) -> Result<FilmSolution, SolveError> {
        let closed = self.fast.solve(input, previous)?;
        let err = closed_form_error(input, previous, &closed);
        if err.estimate <= self.tolerance {
            return Ok(closed);
        }
        let iso = self.numerical.solve(input, previous)?;
        match &self.thermal {
            Some(th) if iso.thermal.is_none() && matches!(input.shape, ContactShape::Line { .. }) => {
                let b = &th.settings.bodies;
                if thermal_error(input, &iso, &b.film, (&b.body_1, &b.body_2)) <= self.tolerance {
                    Ok(iso)
                } else {
                    th.solve(input, previous)
                }
            }
            _ => Ok(iso),
        }
    }

    /// A thermal point's traction comes from its table (the thermal model), any other from its
    /// nodes.
    fn traction_local(&self, film: &FilmSolution, input: &ContactInput, sliding: f64) -> (super::Traction, (f64, f64)) {
        match (&self.thermal, film.thermal.is_some()) {
            (Some(th), true) => th.traction_local(film, input, sliding),
            _ => self.numerical.traction_local(film, input, sliding),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn tables_return_their_nodes_and_refuse_outside_the_load_range() {
        let (c, m) = pan_hamrock_table(10.0, 10.0).unwrap();
        assert!((c + 0.060).abs() < 1e-12 && (m + 0.036).abs() < 1e-12);
        // L clamped, M bracketed.
        assert_eq!(pan_hamrock_table(10.0, 40.0), pan_hamrock_table(10.0, 20.0));
        assert!(pan_hamrock_table(0.3, 10.0).is_none() && pan_hamrock_table(2000.0, 10.0).is_none());
        // Cell maximum: between M = 1 and 2 at L = 10–20 the largest corner is 201 %.
        let v = cell_max(&TRACTION_M, &TRACTION_L, 1.5, 15.0, |l, m| TRACTION_TABLE[l][m]);
        assert_eq!(v, 201.0);
        assert_eq!(cell_max(&TRACTION_M, &TRACTION_L, 1000.0, 30.0, |l, m| TRACTION_TABLE[l][m]), 45.0);
    }

    /// The thermal estimate: small in near-rolling at the seed 001 nose (low-viscosity oil with
    /// an Eyring law), large when the seed 000 oil slides.
    #[test]
    fn thermal_error_grows_with_sliding_and_viscosity() {
        use crate::ehl::thermal::ThermalBodies;
        use crate::film::closed_form::test_inputs::{oil, seed001_nose};
        use crate::film::FilmFormula;
        use crate::friction::{AsperityFriction, AsperityModel, Roughness, TractionLaw};
        use crate::lubricant::Lubricant;
        let b = ThermalBodies::SEED000;
        let est = |lub: &Lubricant, slide: f64, eyring: Option<f64>| {
            let rough = Roughness { sigma: 0.0, eta_beta_sigma: 0.04, sigma_over_beta: 0.001, plastic_limit: f64::INFINITY, curve: None };
            let rheology = match eyring {
                Some(tau0) => Rheology::Eyring { tau0 },
                None => Rheology::Newtonian,
            };
            let law = TractionLaw { rheology, limiting_shear_coefficient: None };
            let asp = AsperityFriction { coefficient: 0.1, model: AsperityModel::Coulomb, map: None };
            let mut input = seed001_nose(lub, &rough, &law, &asp);
            input.sliding_velocity = slide;
            let cf = ClosedForm { formula: FilmFormula::PanHamrock, squeeze: false };
            let iso = cf.solve(&input, None).unwrap();
            thermal_error(&input, &iso, &b.film, (&b.body_1, &b.body_2))
        };
        let light = Lubricant { temperature_viscosity: 0.03, ..oil() };
        let rolling = est(&light, 0.004, Some(5e6));
        let sliding = est(&Lubricant::SEED000, 0.8, None);
        println!("rolling {rolling:.4}, sliding {sliding:.4}");
        assert!(rolling < 0.05, "{rolling}");
        assert!(sliding > 0.5, "{sliding}");
    }

    /// One entry of the steady table re-measured (M = 10, L = 10 at 384 nodes: −6.0 % / −3.6 %).
    #[test]
    fn steady_table_entry_is_reproduced() {
        use crate::ehl::formulas::{pan_hamrock_central_film, pan_hamrock_minimum_film, Groups};
        use crate::ehl::{solve, EhlInput, EhlOptions, Rheology};
        use crate::lubricant::Lubricant;
        use crate::Silent;
        let es = 210e9 / 0.91 / 2.0;
        let (r, alpha, eta0) = (0.015, 2.2e-8, 0.05);
        let lub = Lubricant { viscosity: eta0, pressure_viscosity: alpha, ..Lubricant::SEED000 };
        let u_sum = (10.0 / (alpha * 2.0 * es)).powi(4);
        let (w, u) = (10.0 * u_sum.sqrt() * 2.0 * es * r, 0.5 * u_sum * 2.0 * es * r / eta0);
        let inp = EhlInput {
            load_per_length: w, reduced_radius: r, effective_modulus: 2.0 * es, entrainment_velocity: u,
            sliding_velocity: 0.0, lubricant: lub, temperature: lub.reference_temperature,
            rheology: Rheology::default(), transient: None, warm_start: None, asperity: None,
        };
        let s = solve(&inp, &EhlOptions { nodes: 384, ..Default::default() }, &Silent).unwrap();
        let g = Groups::of(w, r, 2.0 * es, u, &lub, lub.reference_temperature);
        let ec = pan_hamrock_central_film(&g, r) / s.central_film - 1.0;
        let em = pan_hamrock_minimum_film(&g, r) / s.min_film - 1.0;
        let (tc, tm) = pan_hamrock_table(10.0, 10.0).unwrap();
        assert!((ec - tc).abs() < 0.002 && (em - tm).abs() < 0.002, "{ec} {em}");
    }
}
