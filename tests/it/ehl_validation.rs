//! Validation of the numerical line-contact EHL solver (`physics::ehl`) against its limits and
//! closed forms: dry Hertz, rigid–isoviscous (Martin), Moes (Barus, incompressible) and
//! Pan–Hamrock (Roelands, Dowson–Higginson) films, grid convergence, squeeze and reversal.

use tribod::physics::ehl::formulas::*;
use tribod::physics::ehl::*;
use tribod::physics::lubricant::{DensityModel, Lubricant, ViscosityModel};
use tribod::physics::Silent;

/// Steel on steel: E' = 2/(2(1 − 0.3²)/210e9) = 230.8 GPa.
const E_PRIME: f64 = 210e9 / 0.91;

fn oil(eta0: f64, alpha: f64) -> Lubricant {
    Lubricant { viscosity: eta0, pressure_viscosity: alpha, ..Lubricant::SEED000 }
}

fn input(w: f64, r: f64, u: f64, lub: Lubricant) -> EhlInput<'static> {
    EhlInput {
        load_per_length: w,
        reduced_radius: r,
        effective_modulus: E_PRIME,
        entrainment_velocity: u,
        sliding_velocity: 0.0,
        lubricant: lub,
        temperature: lub.reference_temperature,
        rheology: Rheology::default(),
        transient: None,
        warm_start: None,
        asperity: None,
    }
}

fn opts(nodes: usize) -> EhlOptions {
    EhlOptions { nodes, ..Default::default() }
}

/// Load `w'` and mean speed `u_m` giving Moes `M`, `L` (sum-velocity convention) for radius `r`,
/// viscosity `η0`, `α`.
fn load_speed_for(m: f64, l: f64, r: f64, eta0: f64, alpha: f64) -> (f64, f64) {
    let g = alpha * E_PRIME;
    let u_sum = (l / g).powi(4);
    let w_dimless = m * u_sum.sqrt();
    (w_dimless * E_PRIME * r, 0.5 * u_sum * E_PRIME * r / eta0)
}

fn rel(a: f64, b: f64) -> f64 {
    (a - b).abs() / b.abs()
}

#[test]
fn dry_limit_heavy_load_low_speed_gives_hertz_pressure() {
    // p_h = 2.0 GPa, u_m = 0.01 m/s: M ≈ 1130.
    let lub = oil(0.02, 2e-8);
    let r = 0.01;
    let w = (2.0e9f64).powi(2) * 2.0 * std::f64::consts::PI * r / E_PRIME;
    let s = solve(&input(w, r, 0.01, lub), &opts(512), &Silent).unwrap();
    println!("M {} pmax/ph {} spike {:?}", s.moes_m, s.max_pressure / s.hertz_pressure, s.pressure_spike);
    assert!(s.moes_m > 1000.0, "M = {}", s.moes_m);
    assert!(rel(s.max_pressure, s.hertz_pressure) < 0.02, "{} vs {}", s.max_pressure, s.hertz_pressure);
    let st = &s.state;
    let b = s.hertz_half_width;
    let mut worst: f64 = 0.0;
    for (x, p) in st.x.iter().zip(&st.pressure) {
        let xx = x / b;
        if xx.abs() < 0.9 {
            let hertz = (1.0 - xx * xx).sqrt();
            worst = worst.max((p / s.hertz_pressure - hertz).abs());
        }
    }
    assert!(worst < 0.02, "largest deviation from Hertz in |x| < 0.9 b: {worst}");
    // The film is thin and flat in the Hertzian zone.
    assert!(s.central_film < 0.02 * b * b / r * 10.0);
}

#[test]
fn rigid_isoviscous_limit_matches_martin() {
    // α = 0, incompressible, very light load: M = 0.05, so the deflection is negligible.
    let lub = Lubricant {
        pressure_viscosity: 0.0,
        viscosity_model: ViscosityModel::Barus,
        density_model: DensityModel::Incompressible,
        ..oil(0.05, 0.0)
    };
    let r = 0.02;
    // Choose U = 1e-10, then W = M sqrt(U).
    let u_dimless: f64 = 1e-10;
    let w = 0.05 * u_dimless.sqrt() * E_PRIME * r;
    let u = u_dimless * E_PRIME * r / 0.05;
    let mut inp = input(w, r, u, lub);
    inp.lubricant.pressure_viscosity = 0.0;
    let s = solve(&inp, &EhlOptions { nodes: 1024, ..Default::default() }, &Silent).unwrap();
    let g = Groups::new(w, r, E_PRIME, u, 0.05, 0.0);
    let martin = martin_minimum_film(&g, r);
    println!("martin {martin:.5e} solver {:.5e} ({:+.2} %)", s.min_film, 100.0 * (s.min_film / martin - 1.0));
    assert!(rel(s.min_film, martin) < 0.015, "h_min {} vs Martin {}", s.min_film, martin);
}

#[test]
fn central_film_matches_moes_for_barus_incompressible() {
    // Moes' formula fits Barus, incompressible solutions; valid within a few per cent.
    let (r, eta0, alpha) = (0.01, 0.04, 2e-8);
    for (m, l) in [(5.0, 5.0), (20.0, 10.0), (50.0, 10.0), (100.0, 5.0)] {
        let (w, u) = load_speed_for(m, l, r, eta0, alpha);
        let lub = Lubricant {
            viscosity_model: ViscosityModel::Barus,
            density_model: DensityModel::Incompressible,
            ..oil(eta0, alpha)
        };
        let s = solve(&input(w, r, u, lub), &opts(512), &Silent).unwrap();
        let g = Groups::new(w, r, E_PRIME, u, eta0, alpha);
        let moes = moes_central_film(&g, r);
        println!("M {m} L {l}: h_c {:.4e} Moes {:.4e} ({:+.2} %)", s.central_film, moes, 100.0 * (s.central_film / moes - 1.0));
        // Measured (512 nodes, grid-converged to 0.2 %): +5.6, +5.4, +4.3, +2.1 %. Moes' fit of
        // Venner's solutions is itself good to a few per cent; 6 % bounds it here.
        assert!(rel(s.central_film, moes) < 0.06, "M {m} L {l}: {} vs {}", s.central_film, moes);
    }
}

#[test]
fn films_are_near_pan_hamrock() {
    // Roelands + Dowson–Higginson, the physics Pan & Hamrock regressed.
    let r = 0.01;
    for (w, u, eta0) in [(2e5, 1.0, 0.04), (5e5, 1.0, 0.04), (5e5, 5.0, 0.04), (1e6, 2.0, 0.04), (3e5, 3.0, 0.08)] {
        let lub = oil(eta0, 2e-8);
        let s = solve(&input(w, r, u, lub), &opts(512), &Silent).unwrap();
        let g = Groups::of(w, r, E_PRIME, u, &lub, lub.reference_temperature);
        let (hc, hm) = (pan_hamrock_central_film(&g, r), pan_hamrock_minimum_film(&g, r));
        println!(
            "W {:.2e} U {:.2e} M {:.1} L {:.1}: h_c {:+.2} %, h_min {:+.2} %",
            g.load, g.speed, g.moes_m, g.moes_l,
            100.0 * (s.central_film / hc - 1.0),
            100.0 * (s.min_film / hm - 1.0)
        );
        // Measured: h_c +7.6 … +13.7 %, h_min +4.7 … +9.0 % (the solver's films are thicker, more
        // so at large L). Pan & Hamrock's Roelands parameters are not those of `Lubricant`
        // (Z from α here), so the regression is a sanity bound, not a 5 % reference: the 5 %
        // validation is the Moes test above, with the physics Moes fitted.
        assert!(rel(s.central_film, hc) < 0.15, "central {} vs {}", s.central_film, hc);
        assert!(rel(s.min_film, hm) < 0.10, "minimum {} vs {}", s.min_film, hm);
    }
}

#[test]
fn grid_convergence_is_second_order() {
    // Seed 001 base circle: F = 2250 N over 21 mm, R = 15.2 mm, u = 4.62 m/s, η0 = 0.013 Pa·s.
    let lub = oil(0.013, 1.84e-8);
    let inp = input(2250.0 / 0.021, 0.0152, 4.62, lub);
    let hc: Vec<f64> = [128, 256, 512, 1024]
        .iter()
        .map(|&n| solve(&inp, &opts(n), &Silent).unwrap().central_film)
        .collect();
    let d1 = hc[1] - hc[0];
    let d2 = hc[2] - hc[1];
    let d3 = hc[3] - hc[2];
    println!("h_c {hc:?}; ratios {} {}", d1 / d2, d2 / d3);
    // Successive differences shrink by about four (second order) and the finest is converged.
    assert!(d1.abs() / d2.abs() > 2.5 && d2.abs() / d3.abs() > 2.5);
    let extrapolated = hc[3] + d3 / 3.0;
    assert!(rel(hc[2], extrapolated) < 0.005, "512 nodes {} vs extrapolated {}", hc[2], extrapolated);
}

#[test]
fn squeeze_carries_load_without_entrainment() {
    let lub = oil(0.04, 2e-8);
    let (w, r) = (3e5, 0.01);
    let steady = solve(&input(w, r, 1.0, lub), &opts(256), &Silent).unwrap();
    // Entrainment stops: the film is squeezed out, more slowly the thinner it gets.
    let mut state = steady.state.clone();
    let mut films = vec![steady.central_film];
    for _ in 0..5 {
        let mut inp = input(w, r, 0.0, lub);
        inp.transient = Some(Transient { previous: &state, time_step: 1e-4 });
        let s = solve(&inp, &opts(256), &Silent).unwrap();
        assert!(s.convergence.iterations < 30);
        films.push(s.central_film);
        state = s.state;
    }
    println!("central film under pure squeeze: {films:?}");
    for k in 1..films.len() {
        assert!(films[k] < films[k - 1], "{films:?}");
        assert!(films[k] > 0.0);
    }
    assert!(films[1] - films[2] > films[4] - films[5]);
}

#[test]
fn entrainment_reversal_mirrors_the_solution() {
    let lub = oil(0.04, 2e-8);
    let (w, r) = (3e5, 0.01);
    let fwd = solve(&input(w, r, 1.5, lub), &opts(256), &Silent).unwrap();
    let back = solve(&input(w, r, -1.5, lub), &opts(256), &Silent).unwrap();
    assert!(rel(fwd.central_film, back.central_film) < 1e-9);
    assert!(rel(fwd.min_film, back.min_film) < 1e-9);
    assert!((fwd.min_film_position + back.min_film_position).abs() < 1e-9 * fwd.hertz_half_width);
    // Transient steps through the reversal converge from the previous state; after a while
    // the exit constriction has moved to the new downstream side.
    let mut state = fwd.state.clone();
    let mut last = None;
    for k in 0..12 {
        let u = 1.5 - 0.25 * k as f64;
        let mut inp = input(w, r, u, lub);
        inp.transient = Some(Transient { previous: &state, time_step: 2e-4 });
        let s = solve(&inp, &opts(256), &Silent).unwrap();
        state = s.state.clone();
        last = Some(s);
    }
    let s = last.unwrap();
    println!("after reversal: h_c {} h_min {} at {}", s.central_film, s.min_film, s.min_film_position);
    assert!(s.min_film_position < 0.0, "the exit moves upstream: {}", s.min_film_position);
}

/// The benchmark cycle's load, radius and entrainment at angle index `k` of `steps`.
fn cycle_input(k: usize, steps: usize) -> EhlInput<'static> {
    let th = 2.0 * std::f64::consts::PI * k as f64 / steps as f64;
    let f = 2250.0 + (12500.0 - 2250.0) * (0.5 - 0.5 * th.cos()).powi(2);
    let r = 0.0152 - 0.0047 * (0.5 - 0.5 * th.cos());
    let u = 4.0 * th.cos() + 1.5;
    let lub = oil(0.013, 1.84e-8);
    input(f / 0.021, r, u, lub)
}

fn march(nodes: usize, ex: Extrapolation, range: std::ops::Range<usize>, tol: f64) -> Vec<(f64, f64)> {
    let mut ts = TransientSolver::new(EhlOptions { nodes, tolerance: tol, ..Default::default() }, ex);
    let dt = 60.0 / 950.0 / 720.0;
    range
        .map(|k| {
            let s = ts.step(&cycle_input(k, 720), Some(dt), &Silent).unwrap();
            assert!(s.min_film > 0.0 && s.min_film <= s.central_film && s.min_film <= s.exit_film);
            (s.central_film, s.min_film)
        })
        .collect()
}

#[test]
fn richardson_transient_matches_a_fine_grid_through_reversal() {
    // 40 angles of the benchmark cycle across the entrainment reversal at θ ≈ 248° (k ≈ 496),
    // where the film is thinnest and squeeze carries the load.
    let range = 470..510;
    let reference = march(513, Extrapolation::Richardson, range.clone(), 1e-8);
    let rich = march(193, Extrapolation::Richardson, range.clone(), 1e-6);
    let single = march(193, Extrapolation::None, range.clone(), 1e-6);
    let worst = |a: &[(f64, f64)]| {
        a.iter().zip(&reference).fold((0.0f64, 0.0f64), |(c, m), (x, r)| {
            (c.max((x.0 / r.0 - 1.0).abs()), m.max((x.1 / r.1 - 1.0).abs()))
        })
    };
    let (rc, rm) = worst(&rich);
    let (sc, sm) = worst(&single);
    println!("worst error against 257 + 513 nodes: Richardson 97 + 193: h_c {rc:.4} h_min {rm:.4}; 193 alone: {sc:.4} {sm:.4}");
    // Measured: Richardson 0.08 % (h_c), 0.25 % (h_min); 193 nodes alone 1.7 %, 2.1 %.
    assert!(rc < 0.005 && rm < 0.006, "Richardson {rc} {rm}");
    assert!(sc > 2.0 * rc && sm > 2.0 * rm, "the extrapolation must beat the fine grid alone");
}

/// The same march with the state carried by the caller ([`ReusableSolver`], as the `accurate`
/// film model of a cam cycle does): fine and coarse states passed back step by step.
fn march_reusable(nodes: usize, richardson: bool, range: std::ops::Range<usize>) -> Vec<(f64, f64)> {
    let options = EhlOptions { nodes, tolerance: 1e-6, ..Default::default() };
    let mut solver = ReusableSolver::new();
    let dt = 60.0 / 950.0 / 720.0;
    let (mut fine, mut coarse): (Option<EhlState>, Option<EhlState>) = (None, None);
    range
        .map(|k| {
            let mut inp = cycle_input(k, 720);
            inp.transient = fine.as_ref().map(|previous| Transient { previous, time_step: dt });
            let s = if richardson {
                let r = solver.solve_richardson(&inp, coarse.as_ref(), &options, &Silent).unwrap();
                coarse = r.coarse_state;
                r.solution
            } else {
                solver.solve(&inp, &options, &Silent).unwrap()
            };
            assert!(s.min_film > 0.0 && s.min_film <= s.central_film && s.min_film <= s.exit_film);
            fine = Some(s.state.clone());
            (s.central_film, s.min_film)
        })
        .collect()
}

#[test]
fn reusable_solver_with_caller_held_states_matches_the_transient_solver() {
    let range = 470..510;
    let reference = march(513, Extrapolation::Richardson, range.clone(), 1e-8);
    let worst = |a: &[(f64, f64)]| {
        a.iter().zip(&reference).fold(0.0f64, |w, (x, r)| w.max((x.0 / r.0 - 1.0).abs()).max((x.1 / r.1 - 1.0).abs()))
    };
    let rich = worst(&march_reusable(193, true, range.clone()));
    let single = worst(&march_reusable(193, false, range.clone()));
    println!("worst film error against 257 + 513 nodes: ReusableSolver Richardson 97 + 193 {rich:.4}, 193 alone {single:.4}");
    // The TransientSolver's figures on the same steps: 0.25 % and 2.1 %.
    assert!(rich < 0.006, "Richardson {rich}");
    assert!(single > 2.0 * rich && single < 0.03, "single grid {single}");
}

/// Scan of the point solve's settings against a grid-converged reference over M = 5–200,
/// L = 5–15, Barus and Roelands (issue 16 item 6). Run with
/// `cargo test --test it -- --ignored ehl_point_settings_scan --nocapture`.
#[test]
#[ignore]
fn ehl_point_settings_scan() {
    use std::time::Instant;
    let r = 0.01;
    let eta0 = 0.05;
    let alpha = 2e-8;
    let spike_of = |s: &EhlSolution| s.pressure_spike.map(|p| p.position / s.hertz_half_width);
    for model in [ViscosityModel::Barus, ViscosityModel::Roelands] {
        for &l in &[5.0, 10.0, 15.0] {
            for &m in &[5.0, 10.0, 20.0, 50.0, 100.0, 200.0] {
                let (w, u) = load_speed_for(m, l, r, eta0, alpha);
                let lub = Lubricant { viscosity_model: model, ..oil(eta0, alpha) };
                let inp = input(w, r, u, lub);
                let o = |n| EhlOptions { nodes: n, tolerance: 1e-10, ..Default::default() };
                let reference = ReusableSolver::new().solve_richardson(&inp, None, &o(2049), &Silent).unwrap().solution;
                let fine = solve(&inp, &o(2049), &Silent).unwrap();
                let mut line = format!("{model:?} M {m:>5} L {l:>4}: ref hc {:.4e} hm {:.4e} spike {:?} |", reference.central_film, reference.min_film, spike_of(&fine));
                for (label, nodes, rich) in [("256", 256, false), ("512", 512, false), ("R385", 385, true), ("R513", 513, true), ("R257", 257, true)] {
                    let t = Instant::now();
                    let s = if rich {
                        ReusableSolver::new().solve_richardson(&inp, None, &opts(nodes), &Silent).unwrap().solution
                    } else {
                        solve(&inp, &opts(nodes), &Silent).unwrap()
                    };
                    let ms = t.elapsed().as_secs_f64() * 1e3;
                    line += &format!(" {label}: {:+.2}/{:+.2}% sp {:?} {ms:.0}ms |",
                        100.0 * (s.central_film / reference.central_film - 1.0), 100.0 * (s.min_film / reference.min_film - 1.0),
                        spike_of(&s).map(|p| (p * 1000.0).round() / 1000.0));
                }
                println!("{line}");
            }
        }
    }
}

/// Spike presence near M = 20, L = 5 over oils and radii (issue 16 item 6). Run with
/// `cargo test --test it -- --ignored ehl_point_spike_scan --nocapture`.
#[test]
#[ignore]
fn ehl_point_spike_scan() {
    let spike_of = |s: &EhlSolution| s.pressure_spike.map(|p| ((p.position / s.hertz_half_width) * 1000.0).round() / 1000.0);
    for model in [ViscosityModel::Barus, ViscosityModel::Roelands] {
        for &(eta0, alpha, r) in &[(0.01, 1e-8, 0.005), (0.152, 2.2e-8, 0.014), (0.013, 1.84e-8, 0.0105), (0.5, 3e-8, 0.05), (0.004, 1.5e-8, 0.02)] {
            for &m in &[12.0, 15.0, 18.0, 20.0, 22.0, 25.0, 30.0] {
                let l = 5.0;
                let (w, u) = load_speed_for(m, l, r, eta0, alpha);
                let lub = Lubricant { viscosity_model: model, ..oil(eta0, alpha) };
                let inp = input(w, r, u, lub);
                let reference = solve(&inp, &EhlOptions { nodes: 2049, tolerance: 1e-10, ..Default::default() }, &Silent).unwrap();
                let s256 = solve(&inp, &opts(256), &Silent).unwrap();
                let r385 = ReusableSolver::new().solve_richardson(&inp, None, &opts(385), &Silent).unwrap().solution;
                println!("{model:?} eta0 {eta0} alpha {alpha} R {r} M {m}: ph {:.3e} ref {:?} 256 {:?} R385 {:?}",
                    reference.hertz_pressure, spike_of(&reference), spike_of(&s256), spike_of(&r385));
            }
        }
    }
}

/// `ehl_point` at its default settings (385 nodes, Richardson extrapolation with 193) against a
/// grid-converged reference (Richardson of 1025 and 513 nodes, tolerance 1e-10) at the corners
/// of M = 5–200, L = 5–15 where the one-grid defaults were worst (issue 16 item 6): central and
/// minimum film within 1 % (measured ≤ 0.1 % and ≤ 0.6 %, see BENCHMARKS.md "One contact point:
/// the defaults"), the exit spike found and placed within 0.05 half-widths of the reference's.
#[test]
fn ehl_point_defaults_are_within_one_percent_and_find_the_spike() {
    use serde_json::json;
    use tribod::jobs::{registry, Limits};
    let kind = registry::find("ehl_point").unwrap();
    let (r, eta0, alpha) = (0.01, 0.05, 2e-8);
    for (model, m, l) in [(ViscosityModel::Barus, 200.0, 15.0), (ViscosityModel::Roelands, 5.0, 15.0), (ViscosityModel::Roelands, 20.0, 5.0), (ViscosityModel::Barus, 100.0, 10.0)] {
        let (w, u) = load_speed_for(m, l, r, eta0, alpha);
        let lub = Lubricant { viscosity_model: model, ..oil(eta0, alpha) };
        let reference = ReusableSolver::new()
            .solve_richardson(&input(w, r, u, lub), None, &EhlOptions { nodes: 1025, tolerance: 1e-10, ..Default::default() }, &Silent)
            .unwrap()
            .solution;
        let model_name = if model == ViscosityModel::Barus { "barus" } else { "roelands" };
        let spec = json!({
            "load": w, "length": 1.0, "reduced_radius": r, "entrainment_velocity": u,
            "body_1": {"youngs_modulus": 210e9, "poisson_ratio": 0.3}, "body_2": {"youngs_modulus": 210e9, "poisson_ratio": 0.3},
            "lubricant": {"viscosity": eta0, "pressure_viscosity": alpha, "temperature_viscosity": 0.042, "reference_temperature": 313.0,
                "density": 870.0, "viscosity_model": model_name, "density_model": "dowson_higginson"}
        });
        let out = kind.prepare(&spec, &Limits::default()).unwrap().run(&Silent).unwrap();
        assert_eq!(out["nodes"], json!(385));
        assert_eq!(out["extrapolated"], json!(true));
        let (hc, hm) = (out["central_film"].as_f64().unwrap(), out["min_film"].as_f64().unwrap());
        let b = out["hertz_half_width"].as_f64().unwrap();
        let spike = out["pressure_spike"]["position"].as_f64().map(|x| x / b);
        let reference_spike = reference.pressure_spike.map(|p| p.position / reference.hertz_half_width);
        println!("{model_name} M {m} L {l}: h_c {:+.3} %, h_min {:+.3} %, spike {spike:?} (reference {reference_spike:?})",
            100.0 * (hc / reference.central_film - 1.0), 100.0 * (hm / reference.min_film - 1.0));
        assert!(rel(hc, reference.central_film) < 0.01 && rel(hm, reference.min_film) < 0.01, "M {m} L {l}");
        let (s, rs) = (spike.expect("default finds the spike"), reference_spike.expect("reference spike"));
        assert!((s - rs).abs() < 0.05, "M {m} L {l}: spike at {s} vs {rs}");
    }
}
