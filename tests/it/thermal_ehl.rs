//! Validation of the thermal line-contact EHL model (`physics::ehl::thermal`, seed 000 eq. 2,
//! 4–5, 7–9): the isothermal limit, the energy balance, the thermal film reduction against the
//! Gupta et al. (1992) correction, the thermal traction maximum, and grid convergence.

use tribod::physics::ehl::thermal::{self, EnergyIteration, ThermalBodies, ThermalInput, ThermalOptions, ThermalSolution};
use tribod::physics::ehl::*;
use tribod::physics::lubricant::Lubricant;
use tribod::physics::Silent;

/// Steel on steel: E' = 2/(2(1 − 0.3²)/210e9).
const E_PRIME: f64 = 210e9 / 0.91;

fn input(w: f64, r: f64, um: f64, srr: f64, lub: Lubricant) -> EhlInput<'static> {
    EhlInput {
        load_per_length: w,
        reduced_radius: r,
        effective_modulus: E_PRIME,
        entrainment_velocity: um,
        sliding_velocity: srr * um,
        lubricant: lub,
        temperature: lub.reference_temperature,
        rheology: Rheology::default(),
        transient: None,
        warm_start: None,
        asperity: None,
    }
}

fn solve_thermal(ehl: EhlInput, nodes: usize, opts: ThermalOptions) -> ThermalSolution {
    let tin = ThermalInput { ehl, bodies: ThermalBodies::SEED000, previous_temperature: None };
    thermal::solve(&tin, &EhlOptions { nodes, ..Default::default() }, &opts, &Silent).expect("thermal solve")
}

fn rel(a: f64, b: f64) -> f64 {
    (a - b).abs() / b.abs()
}

#[test]
fn zero_sliding_low_speed_is_the_isothermal_solution() {
    let lub = Lubricant::SEED000;
    let ehl = input(2e5, 0.015, 0.05, 0.0, lub);
    let iso = solve(&ehl, &EhlOptions { nodes: 256, ..Default::default() }, &Silent).unwrap();
    let th = solve_thermal(ehl, 256, ThermalOptions::default());
    println!(
        "iso hc {:.4e} hmin {:.4e}; thermal hc {:.4e} hmin {:.4e}; Tmax − T0 {:.3e} K; iterations {}",
        iso.central_film, iso.min_film, th.ehl.central_film, th.ehl.min_film,
        th.summary.film_temperature_max - lub.reference_temperature, th.convergence.iterations
    );
    assert!(rel(th.ehl.central_film, iso.central_film) < 2e-3);
    assert!(rel(th.ehl.min_film, iso.min_film) < 2e-3);
    assert!(th.summary.film_temperature_max - lub.reference_temperature < 0.05);
}

/// Gupta, Cheng, Zhu & Wedeven (1992) thermal reduction of the central film, in the form
/// `φ_T = (1 − 13.2 (p_h/E') L^0.42) / (1 + 0.213 (1 + 2.23 S^0.83) L^0.64)`, with the thermal
/// loading `L = β η0 u_m²/k_f` and the slide-to-roll ratio `S = u_s/u_m`. (Quoted from memory of
/// the TEHL literature; the original was not available offline — see BENCHMARKS.md.)
fn gupta(ph: f64, l: f64, s: f64) -> f64 {
    (1.0 - 13.2 * (ph / E_PRIME) * l.powf(0.42)) / (1.0 + 0.213 * (1.0 + 2.23 * s.powf(0.83)) * l.powf(0.64))
}

#[test]
fn energy_balance_closes_to_one_percent() {
    let lub = Lubricant::SEED000;
    for &(w, um, srr) in &[(5e4, 3.0, 0.05), (2e5, 5.0, 0.3)] {
        let th = solve_thermal(input(w, 0.014, um, srr, lub), 256, ThermalOptions::default());
        let s = th.summary;
        println!(
            "w {w:.0e} um {um} srr {srr}: generated {:.1} W/m = body 1 {:.1} + body 2 {:.1} + film {:.1}; error {:.2e}",
            s.heat_generated, s.heat_to_body_1, s.heat_to_body_2, s.heat_convected, s.energy_balance_error
        );
        assert!(s.energy_balance_error < 0.01, "{}", s.energy_balance_error);
        assert!(s.heat_generated > 0.0);
    }
}

/// The model against the Gupta et al. (1992) correction. In rolling (S = 0) the two agree to
/// 0.06 over L = 0.05–0.4 and the model's reduction grows with L as the formula's does; with
/// sliding the model thins the film by less than the formula says (S = 0.3: φ = 0.92 against
/// 0.81) — asserted as measured; BENCHMARKS.md ("Thermal EHL") discusses why.
#[test]
fn thermal_film_reduction_against_gupta() {
    let lub = Lubricant::SEED000;
    let (k_f, beta, eta0) = (0.14, lub.temperature_viscosity, lub.viscosity);
    let mut phi = Vec::new();
    for &(w, um, srr) in &[(5e4, 1.0, 0.0), (5e4, 2.0, 0.0), (5e4, 3.0, 0.0), (5e4, 3.0, 0.3), (1e5, 3.0, 0.1)] {
        let ehl = input(w, 0.014, um, srr, lub);
        let iso = solve(&ehl, &EhlOptions { nodes: 256, ..Default::default() }, &Silent).unwrap();
        let th = solve_thermal(ehl, 256, ThermalOptions::default());
        let l = beta * eta0 * um * um / k_f;
        let model = th.ehl.central_film / iso.central_film;
        let reference = gupta(iso.hertz_pressure, l, srr);
        println!("w {w:.0e} um {um} S {srr}: L {l:.3} φ model {model:.4} Gupta {reference:.4} diff {:+.4}", model - reference);
        phi.push((model, reference));
    }
    // Rolling: within 0.06 of the formula, decreasing with L like it.
    for &(m, r) in &phi[..3] {
        assert!((m - r).abs() < 0.06, "{m} vs {r}");
    }
    assert!(phi[0].0 > phi[1].0 && phi[1].0 > phi[2].0, "{phi:?}");
    // Sliding at L = 0.41: thinner than rolling, but by less than the formula.
    assert!(phi[3].0 < phi[2].0, "{phi:?}");
    for &(m, r) in &phi[3..] {
        assert!(m > r + 0.05 && m < r + 0.13, "measured: model above Gupta by 0.08–0.12 with sliding: {m} vs {r}");
    }
}

#[test]
fn traction_rises_to_a_thermal_maximum_and_declines() {
    let lub = Lubricant::SEED000;
    let mut mu = Vec::new();
    let mut opts = ThermalOptions::default();
    opts.max_iterations = 60;
    for &srr in &[0.005, 0.02, 0.05, 0.1, 0.2, 0.4, 0.8] {
        let th = solve_thermal(input(1e5, 0.014, 2.0, srr, lub), 192, opts);
        println!("S {srr}: μ {:.4} Tmax {:.1} K", th.ehl.traction.friction_coefficient, th.summary.film_temperature_max);
        mu.push(th.ehl.traction.friction_coefficient);
    }
    let imax = (0..mu.len()).fold(0, |j, i| if mu[i] > mu[j] { i } else { j });
    assert!(imax > 0 && imax < mu.len() - 1, "maximum inside the range: {mu:?}");
    assert!(mu[mu.len() - 1] < 0.9 * mu[imax], "declines beyond the maximum: {mu:?}");
}

#[test]
fn grid_convergence_in_x_and_z() {
    let lub = Lubricant::SEED000;
    let ehl = input(5e4, 0.014, 3.0, 0.3, lub);
    let run = |nodes: usize, nz: usize| {
        let th = solve_thermal(ehl, nodes, ThermalOptions { film_points: nz, ..Default::default() });
        (th.ehl.central_film, th.summary.film_temperature_max - 313.0, th.ehl.traction.friction_coefficient)
    };
    let fine = run(512, 11);
    for &(nodes, nz) in &[(128, 7), (256, 7), (512, 7), (512, 5), (512, 9)] {
        let c = run(nodes, nz);
        println!(
            "{nodes} × {nz}: hc {:+.2e} ΔTmax {:+.2e} μ {:+.2e} (relative to 512 × 11)",
            rel(c.0, fine.0), rel(c.1, fine.1), rel(c.2, fine.2)
        );
    }
    // Measured (BENCHMARKS.md, "Thermal EHL"): the central film converges fastest in x, the
    // temperature maximum needs 512 nodes for 1 %, the traction mostly z resolution.
    let (c128, c256, c512) = (run(128, 7), run(256, 7), run(512, 7));
    assert!(rel(c256.0, fine.0) < 0.01, "central film at 256 × 7: {c256:?} vs {fine:?}");
    assert!(rel(c512.1, fine.1) < 0.01, "temperature rise at 512 × 7: {c512:?} vs {fine:?}");
    assert!(rel(c128.1, fine.1) > rel(c256.1, fine.1) && rel(c256.1, fine.1) > rel(c512.1, fine.1), "x convergence of the temperature");
    let c9 = run(512, 9);
    assert!(rel(c9.2, fine.2) < 0.01 && rel(c512.2, fine.2) < 0.02, "traction: 512 × 9 {c9:?}, 512 × 7 {c512:?} vs {fine:?}");
}

/// The two energy iterations (`EnergyIteration::Sweeps`, the default, and `Anderson`) on one
/// traction curve around the thermal maximum (seed 000 oil, w' = 1e5 N/m, u_m = 2 m/s, 96 nodes)
/// and on the heavily sheared contact of the energy balance (w' = 2e5, u_m = 5, S = 0.3, 122 K):
/// the same films, traction and heat to 1e-4 where both converge.
#[test]
fn energy_iterations_agree() {
    let lub = Lubricant::SEED000;
    let run = |iteration: EnergyIteration, w: f64, um: f64, srr: f64, nodes: usize| {
        let opts = ThermalOptions { iteration, max_iterations: 60, ..Default::default() };
        solve_thermal(input(w, 0.014, um, srr, lub), nodes, opts)
    };
    for k in 0..5 {
        let srr = 0.16 + 0.02 * k as f64;
        let (a, b) = (run(EnergyIteration::Sweeps, 1e5, 2.0, srr, 96), run(EnergyIteration::Anderson, 1e5, 2.0, srr, 96));
        let (ma, mb) = (a.ehl.traction.friction_coefficient, b.ehl.traction.friction_coefficient);
        println!("S {srr:.2}: μ {ma:.6} / {mb:.6}, hc {:.5e} / {:.5e}", a.ehl.central_film, b.ehl.central_film);
        assert!(rel(mb, ma) < 1e-4 && rel(b.ehl.central_film, a.ehl.central_film) < 1e-4, "S {srr}");
    }
    let (a, b) = (run(EnergyIteration::Sweeps, 2e5, 5.0, 0.3, 256), run(EnergyIteration::Anderson, 2e5, 5.0, 0.3, 256));
    println!(
        "w' 2e5, u_m 5, S 0.3: heat {:.1} / {:.1} W/m, balance {:.2e} / {:.2e}, μ {:.6} / {:.6}",
        a.summary.heat_generated, b.summary.heat_generated, a.summary.energy_balance_error, b.summary.energy_balance_error,
        a.ehl.traction.friction_coefficient, b.ehl.traction.friction_coefficient
    );
    assert!(rel(b.summary.heat_generated, a.summary.heat_generated) < 1e-3);
    assert!(b.summary.energy_balance_error < 0.01);
}

/// The seed 001 nose (1.41 GPa, w' = 595 kN/m on R = 10.5 mm, u_m = 3.98 m/s, η0 = 0.013 Pa·s,
/// α = 1.84e-8 1/Pa) with seed 001's Eyring film (τ_E = 5 MPa) from rolling to S = 1, and the same
/// contact loaded to p_h = 1.7 GPa: the thermal solve converges with bounded temperatures and a
/// closed energy balance. Before the Eyring stress was solved per column every sliding case here
/// ran away in the first energy sweep (typed error). At S = 2 (the roller at rest): converged or
/// a typed runaway, never a NaN. Measured figures in
/// BENCHMARKS.md (issue 14, "Eyring at seed 001 loads").
#[test]
fn seed001_nose_with_eyring_converges_under_sliding() {
    let lub = Lubricant { viscosity: 0.013, pressure_viscosity: 1.84e-8, ..Lubricant::SEED000 };
    let eyring = Rheology { eyring_stress: Some(5e6), ..Rheology::default() };
    let e_prime = 200e9 / 0.91;
    let case = |w: f64, srr: f64| EhlInput { effective_modulus: e_prime, rheology: eyring, ..input(w, 0.0105, 3.98, srr, lub) };
    let iso = solve(&case(595_238.0, 0.0), &EhlOptions { nodes: 256, ..Default::default() }, &Silent).unwrap();
    let mut rows = Vec::new();
    for (w, srr) in [(595_238.0, 0.0), (595_238.0, 0.01), (595_238.0, 0.1), (595_238.0, 0.25), (595_238.0, 0.5), (595_238.0, 1.0), (867_700.0, 0.25)] {
        let th = solve_thermal(case(w, srr), 256, ThermalOptions::default());
        let rise = th.summary.film_temperature_max - 313.0;
        println!(
            "w' {w:.0} p_h {:.3} GPa S {srr}: hc {:.4e} (iso {:.4e}) hmin {:.4e} μ {:.4} Tmax {:.1} K surfaces {:.1}/{:.1} K balance {:.2e} coupling {} ({:?})",
            th.ehl.hertz_pressure * 1e-9, th.ehl.central_film, iso.central_film, th.ehl.min_film, th.ehl.traction.friction_coefficient,
            th.summary.film_temperature_max, th.summary.surface_temperature_max_1, th.summary.surface_temperature_max_2,
            th.summary.energy_balance_error, th.convergence.iterations, th.convergence.termination
        );
        assert!(th.ehl.central_film.is_finite() && th.ehl.min_film > 0.0 && th.ehl.traction.friction_coefficient.is_finite());
        // Measured ≤ 0.19 %.
        assert!(th.summary.energy_balance_error < 0.01, "energy balance {}", th.summary.energy_balance_error);
        assert!(rise > -0.5 && rise < thermal::MAX_TEMPERATURE_RISE, "rise {rise}");
        // The thermal film stays within 12 % of the isothermal one at this load (measured
        // −2.6 % in rolling — the compressive heating — to −9.4 % at S = 1).
        if w < 6e5 {
            assert!(rel(th.ehl.central_film, iso.central_film) < 0.12, "{} vs {}", th.ehl.central_film, iso.central_film);
        }
        rows.push((srr, th.ehl.traction.friction_coefficient, th.summary.film_temperature_max));
    }
    // Rolling: no heating beyond the compression's; the rise grows with sliding.
    assert!(rows[0].2 - 313.0 < 5.0, "{rows:?}");
    for k in 1..6 {
        assert!(rows[k].2 > rows[k - 1].2, "Tmax grows with S: {rows:?}");
    }
    // Traction: the thermal maximum (measured μ 0.029, 0.034, 0.032, 0.027, 0.022 at S = 0.01,
    // 0.1, 0.25, 0.5, 1) — the Eyring film's stress grows only logarithmically with the shear
    // rate while the heating thins it.
    assert!(rows[2].1 > rows[1].1 && rows[1].1 > 0.02, "{rows:?}");
    for k in 3..6 {
        assert!(rows[k].1 < rows[k - 1].1, "declines beyond the maximum: {rows:?}");
    }
    // The roller at rest (S = 2): converged or a typed runaway, never a NaN.
    let tin = ThermalInput { ehl: case(595_238.0, 2.0), bodies: ThermalBodies::SEED000, previous_temperature: None };
    match thermal::solve(&tin, &EhlOptions { nodes: 256, ..Default::default() }, &ThermalOptions::default(), &Silent) {
        Ok(th) => {
            println!("S 2: converged, Tmax {:.1} K μ {:.4}", th.summary.film_temperature_max, th.ehl.traction.friction_coefficient);
            assert!(th.summary.film_temperature_max < 313.0 + thermal::MAX_TEMPERATURE_RISE && th.ehl.central_film.is_finite());
        }
        Err(e) => {
            println!("S 2: {e}");
            assert!(matches!(e, tribod::physics::SolveError::NotConverged { .. }), "{e:?}");
        }
    }
}

mod stability {
    //! Stability of the thermal model over seed 000/001 conditions: converged, or a typed error;
    //! never a NaN; temperatures above the inlet temperature less the exit's expansion cooling
    //! (25 K margin) and bounded.
    use super::*;
    use proptest::prelude::*;
    use tribod::physics::SolveError;

    proptest! {
        #![proptest_config(ProptestConfig { cases: 12, failure_persistence: None, ..ProptestConfig::default() })]
        #[test]
        fn converges_or_fails_cleanly(p0 in 0.2e9f64..1.2e9, um in 0.5f64..8.0, srr in 0.0f64..1.0, r in 0.008f64..0.02) {
            // Load per length for Hertz pressure p0: w' = π p0² R / E'.
            let w = std::f64::consts::PI * p0 * p0 * r / E_PRIME;
            let ehl = input(w, r, um, srr, Lubricant::SEED000);
            let tin = ThermalInput { ehl, bodies: ThermalBodies::SEED000, previous_temperature: None };
            match thermal::solve(&tin, &EhlOptions { nodes: 128, ..Default::default() }, &ThermalOptions::default(), &Silent) {
                Ok(s) => {
                    let t0 = 313.0;
                    let f = &s.temperature;
                    // Below the inlet temperature only by the expansion cooling at the exit (eq. 7's
                    // compressive term): measured down to T0 − 7 K at p0 = 1.14 GPa, u_m = 4.4 m/s.
                    for v in f.film.iter().chain(&f.body_1).chain(&f.body_2) {
                        prop_assert!(v.is_finite() && *v > t0 - 25.0 && *v < t0 + 1500.0, "temperature {v}");
                    }
                    prop_assert!(s.ehl.central_film.is_finite() && s.ehl.central_film > 0.0);
                    prop_assert!(s.ehl.traction.friction_coefficient.is_finite());
                    prop_assert!(s.summary.energy_balance_error < 0.05, "balance {}", s.summary.energy_balance_error);
                }
                Err(SolveError::NotConverged { residual, .. }) => prop_assert!(!residual.is_nan()),
                Err(e) => prop_assert!(matches!(e, SolveError::Physical { .. }), "unexpected error {e:?}"),
            }
        }
    }
}

mod seed000_cycle {
    //! Seed 000 §4.1–4.2 with the thermal model: `examples/seed000_thermal_steady.json` and
    //! `…_startup.json` (thermal EHL, finite thermal pin; 36 angles and 96 nodes to keep the run
    //! at ≈ 30 s). What the paper states is asserted where the model reproduces it; where it does
    //! not, the test asserts what the model gives (BENCHMARKS.md, "Thermal EHL", seed 000 table).
    use crate::in_process::{example, run};
    use serde_json::Value;

    fn series(out: &Value, name: &str) -> Vec<f64> {
        out["series"][name].as_array().unwrap_or_else(|| panic!("{name}")).iter().map(|v| v.as_f64().unwrap()).collect()
    }

    /// SRR at angle `deg` (the nearest tabulated angle).
    fn at(angles: &[f64], v: &[f64], deg: f64) -> f64 {
        let i = (0..angles.len()).fold(0, |j, i| if (angles[i] - deg).abs() < (angles[j] - deg).abs() { i } else { j });
        v[i]
    }

    /// The seed 000 example with the full thermal solve at every angle (`carry_tolerance` 0; the
    /// examples run with the default key points, 0.05).
    fn every_angle(name: &str) -> Value {
        let mut s = example(name);
        s["ehl"]["thermal"]["carry_tolerance"] = 0.0.into();
        s
    }

    #[test]
    fn slide_to_roll_features_steady_and_startup() {
        let steady = run("cam_cycle", &every_angle("seed000_thermal_steady")).unwrap();
        assert_eq!(steady["summary"]["fidelity_used"]["thermal"].as_u64(), Some(36), "{}", steady["summary"]["fidelity_used"]);
        let a = series(&steady, "angle_deg");
        let srr = series(&steady, "slide_roll_ratio");
        let tmax = series(&steady, "film_temperature_max");
        let pin = series(&steady, "pin_temperature");
        println!("steady SRR: {:?}", a.iter().zip(&srr).map(|(a, s)| format!("{a:.0}:{s:.3}")).collect::<Vec<_>>());
        assert!(tmax.iter().all(|t| *t > 313.0 && *t < 400.0), "{tmax:?}");
        assert!(pin.iter().all(|t| *t > 313.0 && *t < 450.0), "{pin:?}");
        // The examples use seed 000's Newtonian film (eq. 7, 9: no limiting or Eyring stress;
        // `traction.model: newtonian`). With the default Eyring stress (τ_E = 5 MPa, seed 001)
        // the base circle sat at 0.113–0.115 and the nose kept sliding (0.190 at 120°, 0.093 at
        // 130°); BENCHMARKS.md, "Seed 000 as published: the Newtonian film".
        // (1) Large and nearly constant on the base circle before the lift (0–50°): 0.0472.
        let base: Vec<f64> = (0..a.len()).filter(|&i| a[i] <= 50.0).map(|i| srr[i]).collect();
        let (lo, hi) = base.iter().fold((f64::MAX, f64::MIN), |(l, h), &s| (l.min(s), h.max(s)));
        assert!(lo > 0.03 && (hi - lo) / hi < 0.03, "base circle {base:?}");
        // (2) A sharp drop at the opening ramp (60°: 0.005).
        assert!(at(&a, &srr, 60.0) < 0.2 * lo, "opening ramp");
        // (3) Paper: the rise near 100° does not exceed the base-circle level. Model: it does
        // (0.121 against 0.047): the roller's inertia torque there (the moment of inertia is not
        // in seed 000's Table 1; a solid steel ring here) is twice the pin's torque —
        // BENCHMARKS.md shows the rise falling with the inertia.
        assert!(at(&a, &srr, 100.0) > 2.0 * hi, "measured: the rise near 100° exceeds the base circle");
        // (4) Almost zero at the nose (127°): 0.003 at 120°, 0.002 at 130°.
        for deg in [120.0, 130.0] {
            let s = at(&a, &srr, deg);
            assert!(s.abs() < 0.1 * lo, "nose {deg}°: {s}");
        }
        // (5) Negative on the closing ramp with a local negative extreme: model 160–190°, the
        // extreme −0.023 at 180° (paper: near 155°, |SRR| < 0.003).
        let closing: Vec<(f64, f64)> = (0..a.len()).filter(|&i| a[i] >= 140.0 && a[i] <= 200.0).map(|i| (a[i], srr[i])).collect();
        let (amin, smin) = closing.iter().fold((0.0, f64::MAX), |(am, sm), &(an, s)| if s < sm { (an, s) } else { (am, sm) });
        assert!(smin < 0.0 && smin > -0.05, "negative on the closing ramp: {closing:?}");
        assert!((160.0..=190.0).contains(&amin), "extreme at {amin}°");

        // Fig. 5: skidding against pure rolling (the same example with `slip.mode: pure_rolling`).
        // Paper: the film barely moves, the temperature rise and the friction do. Model: minimum
        // film within 4.1 % at every angle, the largest film temperature rise 32.0 K against
        // 11.0 K, the mean |μ_cr| ×3.6. (The pin is not solved under pure rolling here: its
        // comparison is the fast model's, `cam_validation::seed000_skidding_against_pure_rolling`.)
        let mut rolling_spec = example("seed000_thermal_steady");
        rolling_spec["slip"] = serde_json::json!({"mode": "pure_rolling"});
        let rolling = run("cam_cycle", &rolling_spec).unwrap();
        let worst = |name: &str, offset: f64| {
            let (x, y) = (series(&steady, name), series(&rolling, name));
            x.iter().zip(&y).map(|(a, b)| ((a - offset) - (b - offset)).abs() / (b - offset).abs()).fold(0.0, f64::max)
        };
        let rise = |o: &Value| series(o, "film_temperature_max").iter().map(|t| t - 313.0).fold(0.0, f64::max);
        let mean_mu = |o: &Value| series(o, "friction_coefficient").iter().map(|m| m.abs()).sum::<f64>() / a.len() as f64;
        let film_w = worst("film_min", 0.0);
        println!(
            "Fig. 5: film_min worst {film_w:.3e}; film temperature rise skid {:.3} K / rolling {:.3} K; mean |μ_cr| {:.4e} / {:.4e}",
            rise(&steady), rise(&rolling), mean_mu(&steady), mean_mu(&rolling)
        );
        assert!(film_w < 0.05, "film {film_w}");
        assert!(rise(&steady) > 2.5 * rise(&rolling) && rise(&rolling) > 0.0, "temperature rise");
        assert!(mean_mu(&steady) > 3.0 * mean_mu(&rolling), "friction");

        // Startup: the roller starts from rest — far more slip at 0–18° than in steady running.
        let startup = run("cam_cycle", &every_angle("seed000_thermal_startup")).unwrap();
        let sa = series(&startup, "angle_deg");
        let ss = series(&startup, "slide_roll_ratio");
        println!("startup SRR: {:?}", sa.iter().zip(&ss).map(|(a, s)| format!("{a:.0}:{s:.3}")).collect::<Vec<_>>());
        for deg in [0.0, 10.0] {
            let (s_start, s_steady) = (at(&sa, &ss, deg), at(&a, &srr, deg));
            println!("{deg}°: startup {s_start:.3} steady {s_steady:.3}");
        }
        assert!(at(&sa, &ss, 0.0) > 1.5 * at(&a, &srr, 0.0), "0°: more than 50 % above steady");
        // Paper: more than 50 % above steady over 0–18°. Model: above steady but by less — at 10°
        // 0.060 against the steady 0.047 (+28 %); with the Eyring film it had caught up (−9 %).
        // Why (BENCHMARKS.md, "The startup statement, at 720 angles"): the Newtonian traction
        // spins the roller up within the first 0.5° step; what remains follows the slow cam.
        let (s10, st10) = (at(&sa, &ss, 10.0), at(&a, &srr, 10.0));
        assert!(s10 > 1.1 * st10 && s10 < 1.5 * st10, "10°: startup {s10} steady {st10}");
        // Paper (Fig. 16): over 34–54° the startup SRR is slightly below steady (< 5 %). Model:
        // above it, ×1.35 at 40° and ×1.43 at 50° (×1.27 at 30°), the gap still growing towards
        // the opening ramp — the startup SRR never dips below steady before 60°. Traced in
        // `startup_below_steady_is_the_slow_cam_plus_the_roller_inertia`: the slower cam alone
        // puts it below steady (×0.81 at 40°), the steel ring's inertia torque lifts it above.
        for deg in [30.0, 40.0, 50.0] {
            let (s_start, s_steady) = (at(&sa, &ss, deg), at(&a, &srr, deg));
            println!("{deg}°: startup/steady {:.4}", s_start / s_steady);
        }
        for (deg, measured) in [(40.0, 1.350), (50.0, 1.431)] {
            let r = at(&sa, &ss, deg) / at(&a, &srr, deg);
            assert!((r - measured).abs() < 0.02, "{deg}°: startup/steady {r}");
        }
    }

    /// Key points (`ehl.thermal.carry_tolerance` 0.01) against the full thermal solve at every
    /// angle, the seed 000 steady example (36 angles; 72 angles at the example's slip tolerance
    /// did not settle in the full cycle within the time available). Films relative at every angle,
    /// SRR relative to the cycle's largest |SRR| (the closing-ramp SRR crosses zero). Measured
    /// (BENCHMARKS.md, "Eyring at seed 001 loads"): films within 0.93 % (central) and 1.10 %
    /// (minimum), SRR within 0.2 % of its largest value — the 1 % for the SRR; the minimum
    /// film 0.1 % above it. (Before the Eyring stress was solved per column the SRR was 11 % off:
    /// the lagged iteration's noise on the traction table.)
    #[test]
    fn carried_thermal_factors_against_the_full_cycle() {
        let base = every_angle("seed000_thermal_steady");
        let full = run("cam_cycle", &base).unwrap();
        let mut spec = base.clone();
        spec["ehl"]["thermal"]["carry_tolerance"] = 0.01.into();
        let fast = run("cam_cycle", &spec).unwrap();
        let keys = fast["summary"]["fidelity_used"]["thermal"].as_u64().unwrap_or(0);
        println!("fidelity_used: {}", fast["summary"]["fidelity_used"]);
        let a = series(&full, "angle_deg");
        let worst = |name: &str, scale: Option<f64>, range: (f64, f64)| {
            let (x, y) = (series(&full, name), series(&fast, name));
            (0..x.len()).filter(|&i| a[i] >= range.0 && a[i] <= range.1).map(|i| (y[i] - x[i]).abs() / scale.unwrap_or(x[i].abs())).fold(0.0, f64::max)
        };
        let srr = series(&full, "slide_roll_ratio");
        let scale = srr.iter().fold(0.0f64, |m, s| m.max(s.abs()));
        for (label, range) in [("base circle 0–50°", (0.0, 50.0)), ("whole cycle", (0.0, 360.0))] {
            let (hc, hm, sr) = (worst("film_central", None, range), worst("film_min", None, range), worst("slide_roll_ratio", Some(scale), range));
            println!("{label}: worst film_central {hc:.3e}, film_min {hm:.3e}, SRR {sr:.3e} (of {scale:.3})");
        }
        let cycle = (0.0, 360.0);
        assert!(worst("film_central", None, cycle) < FILM_CYCLE, "films over the cycle");
        assert!(worst("film_min", None, cycle) < FILM_CYCLE, "films over the cycle");
        assert!(worst("slide_roll_ratio", Some(scale), cycle) < SRR_CYCLE, "SRR over the cycle");
        assert!(keys < 36, "{keys}");
    }
    /// Measured worst differences over the whole cycle (see the test above), Newtonian film: films
    /// 0.28 % / 0.31 % (central / minimum), SRR 0.15 % of its largest value with the lazy table,
    /// layouts and calibrated traction carry (session 32; 0.66 / 0.69 %, SRR 0.52 % before; Eyring
    /// film before that: 0.67 %, SRR 0.2 %; 1.10 % when the closed form carried the change of
    /// conditions).
    const FILM_CYCLE: f64 = 0.01;
    const SRR_CYCLE: f64 = 0.01;

    /// The carried mode through seed 000's load spike (600 → 2241 N at 54.5–58°), 360 angles,
    /// `carry_tolerance` 0.02 and 0.05, against the full thermal solve at every angle. The films' lag behind
    /// the jump (the temperatures' `∂T/∂t`) is not in a steady key: before the transient window the
    /// carried films were 1.2–2.2 % thinner over 54.5–57.5° at 720 angles (BENCHMARKS.md, "Thermal
    /// cycle: lazy table, layouts, lag window"). Measured (dev), carry 0.02 / 0.05: whole cycle
    /// films within 0.58 / 0.85 % (central) and 0.68 / 0.91 % (minimum), SRR 0.34 / 0.73 % of its
    /// largest value; at the spike films within 0.04 / 0.38 %. The 1 % is asserted, and at
    /// the spike the window's own exit criterion (a tenth of the tolerance). (At 144 angles the
    /// minimum film is 1.4 % off at four carried points beside the nose — not traced; see
    /// BENCHMARKS.md.)
    #[test]
    fn carried_cycle_follows_the_load_spike() {
        let mut base = every_angle("seed000_thermal_steady");
        base["angles"] = 360.into();
        let carry = |tolerance: f64| {
            let mut spec = base.clone();
            spec["ehl"]["thermal"]["carry_tolerance"] = tolerance.into();
            spec
        };
        let (full, carried) = std::thread::scope(|sc| {
            let f = sc.spawn(|| run("cam_cycle", &base).unwrap());
            let c: Vec<Value> = [0.02, 0.05].iter().map(|&t| run("cam_cycle", &carry(t)).unwrap()).collect();
            (f.join().unwrap(), c)
        });
        let a = series(&full, "angle_deg");
        let srr = series(&full, "slide_roll_ratio");
        let scale = srr.iter().fold(0.0f64, |m, s| m.max(s.abs()));
        for (tolerance, carried) in [0.02, 0.05].iter().zip(&carried) {
            println!("carry {tolerance}: fidelity_used {}", carried["summary"]["fidelity_used"]);
            let worst = |name: &str, scale: Option<f64>, range: (f64, f64)| {
                let (x, y) = (series(&full, name), series(carried, name));
                (0..x.len()).filter(|&i| a[i] >= range.0 && a[i] <= range.1).map(|i| (y[i] - x[i]).abs() / scale.unwrap_or(x[i].abs())).fold(0.0, f64::max)
            };
            for (label, range) in [("spike 54–62°", (54.0, 62.0)), ("whole cycle", (0.0, 360.0))] {
                let (hc, hm, sr) = (worst("film_central", None, range), worst("film_min", None, range), worst("slide_roll_ratio", Some(scale), range));
                println!("  {label}: worst film_central {hc:.3e}, film_min {hm:.3e}, SRR {sr:.3e} (of {scale:.3})");
            }
            let spike = (54.0, 62.0);
            // The window closes once its film agrees with the carried one to a tenth of the
            // tolerance.
            let window = 0.1 * tolerance;
            assert!(worst("film_central", None, spike) < window && worst("film_min", None, spike) < window, "{tolerance}: films at the spike");
            let cycle = (0.0, 360.0);
            assert!(worst("film_central", None, cycle) < FILM_CYCLE && worst("film_min", None, cycle) < FILM_CYCLE, "{tolerance}: films over the cycle");
            assert!(worst("slide_roll_ratio", Some(scale), cycle) < SRR_CYCLE, "{tolerance}: SRR over the cycle");
        }
    }

    /// Seed 000 Figs. 9 and 13 with the thermal model (the steady example with key points,
    /// `carry_tolerance` 0.05, 36 angles; the five cycles run side by side). Paper, Fig. 9: the SRR
    /// grows with η0 at 0° and 100°, and at the closing flank's negative extreme (155° in the
    /// paper) the skidding slightly decreases with η0. Fig. 13: the SRR falls as the modified load
    /// w1 grows at 0°, 100° and 176°, most at 0° (the model: most at 100°, see below). The model's closing-flank extreme sits at 180°
    /// (test above), so its counterpart of the paper's 155° is that extreme; at 176° the model's
    /// SRR is negative (the paper's is a positive peak), and there the skid's magnitude falls
    /// with w1. Release figures at 360 angles: BENCHMARKS.md, "Thermal EHL", Figs. 9 and 13.
    #[test]
    fn viscosity_and_modified_load_trends() {
        let base = {
            let mut s = example("seed000_thermal_steady");
            s["ehl"]["thermal"]["carry_tolerance"] = 0.05.into();
            s
        };
        let variant = |path: &[&str], v: f64| {
            let mut s = base.clone();
            let mut node = &mut s;
            for p in path {
                node = &mut node[*p];
            }
            *node = v.into();
            s
        };
        let specs = [base.clone(), variant(&["lubricant", "viscosity"], 0.112), variant(&["lubricant", "viscosity"], 0.2), variant(&["load", "offset"], 400.0), variant(&["load", "offset"], 800.0)];
        let outs: Vec<Value> = std::thread::scope(|sc| {
            let handles: Vec<_> = specs.iter().map(|s| sc.spawn(move || run("cam_cycle", s).unwrap())).collect();
            handles.into_iter().map(|h| h.join().unwrap()).collect()
        });
        let a = series(&outs[0], "angle_deg");
        let srr: Vec<Vec<f64>> = outs.iter().map(|o| series(o, "slide_roll_ratio")).collect();
        // The closing flank's negative extreme (130–200°): (angle, SRR).
        let extreme = |v: &[f64]| (0..a.len()).filter(|&i| a[i] >= 130.0 && a[i] <= 200.0).map(|i| (a[i], v[i])).fold((0.0, f64::MAX), |m, p| if p.1 < m.1 { p } else { m });
        let [base, thin, thick, loaded, heavier] = [&srr[0], &srr[1], &srr[2], &srr[3], &srr[4]];
        for (name, v) in [("η0 0.152", base), ("η0 0.112", thin), ("η0 0.2", thick), ("w1 400", loaded), ("w1 800", heavier)] {
            println!("{name}: 0° {:.4}, 100° {:.4}, 180° {:.4}, extreme {:?}", at(&a, v, 0.0), at(&a, v, 100.0), at(&a, v, 180.0), extreme(v));
        }
        // Fig. 9: 0° and 100° grow with the viscosity.
        for deg in [0.0, 100.0] {
            assert!(at(&a, thin, deg) < at(&a, base, deg) && at(&a, base, deg) < at(&a, thick, deg), "{deg}°");
        }
        // Fig. 9: at the negative extreme the skid's magnitude falls as the viscosity grows.
        let (e_thin, e_base, e_thick) = (extreme(thin), extreme(base), extreme(thick));
        assert!(e_thin.1 < e_base.1 && e_base.1 < e_thick.1 && e_thick.1 < 0.0, "{e_thin:?} {e_base:?} {e_thick:?}");
        assert!([e_thin.0, e_base.0, e_thick.0].iter().all(|d| (160.0..=190.0).contains(d)));
        // Fig. 13: the SRR falls with the modified load at 0° and 100°. Paper: relatively most at
        // 0°. Model (Newtonian film): most at 100° (×0.07 against ×0.21 at 0°) — its 100° slip is
        // the roller's inertia demand, which a larger load's traction meets with far less slip
        // (BENCHMARKS.md, "Seed 000 as published: the Newtonian film"; with the Eyring film it was
        // most at 0°).
        let ratio = |deg: f64| at(&a, loaded, deg) / at(&a, base, deg);
        assert!(ratio(100.0) < ratio(0.0) && ratio(0.0) < 1.0, "0° {} 100° {}", ratio(0.0), ratio(100.0));
        // At 176° (nearest angle 180°) the model's SRR is negative; its magnitude falls with w1.
        assert!(at(&a, base, 176.0) < 0.0 && at(&a, loaded, 176.0) < 0.0 && at(&a, loaded, 176.0) > at(&a, base, 176.0));
        // w1 = 800 N (the peak load 3 kN): its traction table's −0.15 point runs away and is
        // retried closer to rolling; the cycle converges and continues the trend at 0° and 100°.
        assert_eq!(outs[4]["convergence"]["termination"], "converged");
        assert!(at(&a, heavier, 0.0) < at(&a, loaded, 0.0) && at(&a, heavier, 100.0) < at(&a, loaded, 100.0), "w1 800: {} {}", at(&a, heavier, 0.0), at(&a, heavier, 100.0));
    }

    /// The solid steel ring's moment of inertia, the roller's default (R1 25.5 mm, R2 16 mm,
    /// L 14 mm, 7850 kg/m³): 6.17e-5 kg·m².
    fn steel_ring() -> f64 {
        7850.0 * std::f64::consts::PI * (0.0255f64.powi(2) - 0.016f64.powi(2)) * 0.014 * (0.0255f64.powi(2) + 0.016f64.powi(2)) / 2.0
    }

    /// The thermal startup example's SRR with the roller's moment of inertia `inertia` (kg·m²).
    fn startup_srr(inertia: f64) -> Vec<f64> {
        let mut s = every_angle("seed000_thermal_startup");
        s["follower"]["inertia"] = inertia.into();
        series(&run("cam_cycle", &s).unwrap(), "slide_roll_ratio")
    }

    /// Seed 000 Fig. 16, 34–54° "slightly (< 5 %) below steady", traced (issue 42 item 3). The
    /// startup SRR on the base circle is the sum of two parts. (1) The slower cam: with the
    /// roller's inertia ≈ 0 the startup is quasi-steady at the cam's instantaneous speed (at 40°,
    /// 950·sqrt(40/180) = 447.8 rpm: 0.03816 against the steady run at that speed, 0.03812) and
    /// lies *below* the rated steady SRR — ×0.742, ×0.809, ×0.860 at 30, 40, 50° (the base
    /// circle's SRR falls with the speed). (2) The roller's inertia torque under the cam's constant
    /// acceleration adds slip in proportion to the inertia (release CLI, 36 angles, at 40°:
    /// ×0.809, 1.076, 1.350, 1.923 for 0, ½, 1, 2 × the solid steel ring's 6.17e-5 kg·m²; Table 1
    /// gives none): the default ring makes the sum ×1.35 (asserted in
    /// [`slide_to_roll_features_steady_and_startup`]). Asserted here: (1) to 0.5 % at 40° and the
    /// ratios within 0.02 (three thermal cycles, 11 s dev).
    #[test]
    fn startup_below_steady_is_the_slow_cam_plus_the_roller_inertia() {
        let steady = run("cam_cycle", &every_angle("seed000_thermal_steady")).unwrap();
        let (a, srr) = (series(&steady, "angle_deg"), series(&steady, "slide_roll_ratio"));
        let mut slow = every_angle("seed000_thermal_steady");
        slow["operation"]["speed_rpm"] = (950.0 * (40.0f64 / 180.0).sqrt()).into();
        let slow = series(&run("cam_cycle", &slow).unwrap(), "slide_roll_ratio");
        let light = startup_srr(1e-6 * steel_ring());
        let ratio = |v: &[f64], deg: f64| at(&a, v, deg) / at(&a, &srr, deg);
        println!("at 40°: inertia-free startup {:.5} vs steady at 447.8 rpm {:.5}", at(&a, &light, 40.0), at(&a, &slow, 40.0));
        assert!((at(&a, &light, 40.0) / at(&a, &slow, 40.0) - 1.0).abs() < 5e-3);
        for (deg, zero) in [(30.0, 0.742), (40.0, 0.809), (50.0, 0.860)] {
            println!("{deg}°: startup/steady with inertia ≈ 0: {:.4}", ratio(&light, deg));
            assert!((ratio(&light, deg) - zero).abs() < 0.02, "{deg}°");
        }
    }

    /// Fig. 16's "slightly below steady" with a lighter roller: 0.3 × the steel ring gives
    /// ×0.895, 0.967, 1.028 at 30, 40, 50° — the paper's statement near 40° — and no single inertia
    /// keeps all of 34–54° within 5 % below, because the slow-cam part climbs by 0.12 across it
    /// (0.2 × the ring: 0.871 at 34°, 0.989 at 54°; 0.4: 0.974, 1.105; 180 angles). Asserted: the
    /// 36-angle ratios within 0.02. Run:
    /// `cargo test --release --test it -- lighter_roller_startup --include-ignored --nocapture`.
    #[test]
    #[ignore = "two thermal cycles beyond the startup trace (8 s dev): the inertia that meets Fig. 16 near 40°"]
    fn lighter_roller_startup_is_slightly_below_steady_near_40_degrees() {
        let steady = run("cam_cycle", &every_angle("seed000_thermal_steady")).unwrap();
        let (a, srr) = (series(&steady, "angle_deg"), series(&steady, "slide_roll_ratio"));
        let third = startup_srr(0.3 * steel_ring());
        for (deg, want) in [(30.0, 0.895), (40.0, 0.967), (50.0, 1.028)] {
            let r = at(&a, &third, deg) / at(&a, &srr, deg);
            println!("{deg}°: startup/steady with 0.3 × the ring {r:.4}");
            assert!((r - want).abs() < 0.02, "{deg}°");
        }
    }
}
