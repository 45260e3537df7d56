//! Seed 003 Table 3 and eq. 17–18 through the 2-D finite-line solver (issue 42 item 1).

use super::*;
use crate::Silent;
use crate::geometry::{Crown, CrownProfile};
use crate::lubricant::Lubricant;

fn conditions() -> Vec<Seed003Condition> {
    seed003_table3().into_iter().map(|(_, c)| c).collect()
}

/// The fit recovers a law it is given to 1e-9 (eq. 17 over Table 3's runs).
#[test]
fn seed003_fit_recovers_eq17_from_its_own_values() {
    let runs = conditions();
    assert_eq!(runs.len(), 20);
    let films: Vec<f64> = runs.iter().map(|c| Seed003Fit::EQ17.film(c)).collect();
    let f = seed003_fit(&runs, &films).unwrap();
    let e = Seed003Fit::EQ17;
    for (a, b) in [(f.coefficient, e.coefficient), (f.load, e.load), (f.speed, e.speed), (f.materials, e.materials), (f.squeeze, e.squeeze)] {
        assert!((a / b - 1.0).abs() < 1e-9, "{f:?}");
    }
    assert!(seed003_max_difference(&f, &runs, &films) < 1e-7);
    assert!(matches!(seed003_fit(&runs[..4], &films[..4]), Err(SolveError::InvalidInput { .. })));
    let flat: Vec<Seed003Condition> = runs.iter().map(|c| Seed003Condition { squeeze: 0.0, ..*c }).collect();
    assert!(matches!(seed003_fit(&flat, &films), Err(SolveError::InvalidInput { .. })));
}

/// The mapping: the groups of the solver's input are the condition's; bad conditions are refused
/// naming the field.
#[test]
fn seed003_input_has_the_conditions_groups() {
    let setup = Seed003Setup::default();
    let c = seed003_table3()[0].1;
    let i = seed003_input(&c, &setup).unwrap();
    let (r, ep, l) = (setup.reduced_radius, setup.effective_modulus, setup.length);
    assert!((i.load / (ep * r * l) / c.load - 1.0).abs() < 1e-12);
    assert!((i.entrainment_velocity * setup.viscosity / (ep * r) / c.speed - 1.0).abs() < 1e-12);
    assert!((i.lubricant.pressure_viscosity * ep / c.materials - 1.0).abs() < 1e-12);
    let bad = Seed003Condition { load: -1.0, ..c };
    assert!(matches!(seed003_input(&bad, &setup), Err(SolveError::InvalidInput { field, .. }) if field == "Seed003Condition.load"));
    let bad = Seed003Condition { squeeze: f64::NAN, ..c };
    assert!(matches!(seed003_input(&bad, &setup), Err(SolveError::InvalidInput { field, .. }) if field == "Seed003Condition.squeeze"));
}

/// The default setup on 49 × 65 nodes (cells ≈ 1 a along, 1.9 a across at the base run).
fn coarse() -> Seed003Setup {
    let d = Seed003Setup::default();
    Seed003Setup { options: Ehl2dOptions { nx: 49, ny: 65, ..d.options }, ..d }
}

/// Table 3's directions on a coarse grid (49 × 65; the six runs 1.2 s dev). From the base run,
/// measured (model; eq. 17 over the same step): U* ×2.62 → h0* ×2.19 (×1.67), G* ×1.38 → ×1.049
/// (×1.14), approaching squeeze w_s* 0 → −0.005 → ×1.72 (×1.62) — the paper's directions; W*
/// ×5.37 → ×0.59 and W* ×0.33 → ×1.96 (eq. 17: ×1.10, ×0.94) — the paper's "barely changes with
/// W*" does not hold: Table 3's films are thick (Moes M 0.1–1.1, peak pressures 10–60 MPa), below
/// the elastic–piezoviscous regime where the film forgets the load, and the model's film falls
/// with it (the same weak piezoviscosity makes G* matter less than eq. 17 says). Asserted: the
/// measured ratios within ±0.1 (±0.02 for G*).
#[test]
fn seed003_table3_directions_on_a_coarse_grid() {
    let t = std::time::Instant::now();
    let runs = seed003_table3();
    let base = runs[0].1;
    let h = |c: Seed003Condition| seed003_run(&c, &coarse(), &Silent).unwrap().central;
    let h0 = h(base);
    let ratio = |c: Seed003Condition| (h(c) / h0, Seed003Fit::EQ17.film(&c) / Seed003Fit::EQ17.film(&base));
    let (u, g) = (ratio(Seed003Condition { speed: 3.3e-11, ..base }), ratio(Seed003Condition { materials: 9650.0, ..base }));
    let (w_hi, w_lo) = (ratio(Seed003Condition { load: 5.6e-6, ..base }), ratio(Seed003Condition { load: 0.34e-6, ..base }));
    let s = ratio(Seed003Condition { squeeze: -0.005, ..base });
    println!("h0* {h0:.4e}; ratios (model, eq. 17): U* {u:?}, G* {g:?}, W* max {w_hi:?}, W* min {w_lo:?}, w_s* {s:?}; {:?}", t.elapsed());
    let near = |v: f64, want: f64, tol: f64| (v - want).abs() < tol;
    assert!(near(u.0, 2.19, 0.1) && near(g.0, 1.049, 0.02) && near(s.0, 1.72, 0.1), "{u:?} {g:?} {s:?}");
    assert!(near(w_hi.0, 0.59, 0.1) && near(w_lo.0, 1.96, 0.1), "{w_hi:?} {w_lo:?}");
}

/// Seed 003 Table 3 redone (issue 42 item 1): the 20 runs of [`seed003_table3`] on the default
/// setup (129 × 257), the log-linear fits of h0* and h_sc*, beside eq. 17 and eq. 18, and the
/// largest difference per group (Table 3's last columns) of eq. 17/18 and of the refit against
/// the runs. Grid error: the base run against 193 × 385. Measured (dev, 115 s for the 20 runs):
/// refit h0* = 67.4 W*^−0.434 U*^0.823 G*^0.091 e^(−106.6 w_s*) (eq. 17: 1.67, 0.059, 0.541,
/// 0.421, −96.775), h_sc* = 9.18 W*^−0.627 U*^0.871 G*^0.142 e^(−117.6 w_s*) (eq. 18: 1150,
/// −0.037, 0.857, 0.406, −138.059); eq. 17 against the runs: up to 69.6 % (the W* sweep; the
/// model's films are 1.2–3.3 × eq. 17's), the refit 18.4 % (paper's column: 2.5–7.6 %); eq. 18
/// 72.1 %, its refit 4.4 %; grid: +0.054 % (h0*), +0.075 % (h_sc*) against 193 × 385. Asserted:
/// the squeeze exponents within 15 % (h0*) and 20 % (h_sc*) of the paper's, h_sc*'s speed
/// exponent within 5 %; the other exponents and the differences as measured. Run:
/// `cargo test -p tribod-physics --release seed003_table3_regression -- --ignored --nocapture`.
#[test]
#[ignore = "the 20 runs of seed 003 Table 3 (issue 42), 2 min: run in release"]
fn seed003_table3_regression() {
    let t = std::time::Instant::now();
    let setup = Seed003Setup::default();
    let runs = seed003_table3();
    let solved: Vec<Seed003Film> = runs.iter().map(|(_, c)| seed003_run(c, &setup, &Silent).unwrap()).collect();
    let elapsed = t.elapsed();
    let cs = conditions();
    let h0: Vec<f64> = solved.iter().map(|f| f.central).collect();
    let hsc: Vec<f64> = solved.iter().map(|f| f.side).collect();
    println!("group     W*         U*         G*      w_s*      h0*        eq.17      h_sc*      eq.18      M      p_max MPa  fixed point");
    for ((g, c), f) in runs.iter().zip(&solved) {
        println!("{:<9} {:.3e}  {:.3e}  {:6.0}  {:+.5}  {:.4e}  {:.4e}  {:.4e}  {:.4e}  {:.3}  {:7.2}  {}", format!("{g:?}"), c.load, c.speed, c.materials, c.squeeze, f.central, Seed003Fit::EQ17.film(c), f.side, Seed003Fit::EQ18.film(c), f.solution.moes_m, 1e-6 * f.solution.max_pressure.value, f.fixed_point.iterations);
    }
    let fit0 = seed003_fit(&cs, &h0).unwrap();
    let fit1 = seed003_fit(&cs, &hsc).unwrap();
    println!("h0*:  fit {fit0:?}\n      eq. 17 {:?}", Seed003Fit::EQ17);
    println!("h_sc*: fit {fit1:?}\n      eq. 18 {:?}", Seed003Fit::EQ18);
    let groups = [(Seed003Group::Materials, 7.9, 7.6), (Seed003Group::Squeeze, 32.6, 5.8), (Seed003Group::Load, 13.1, 4.7), (Seed003Group::Speed, 12.5, 2.5)];
    let mut worst = [0.0f64; 4];
    for (group, paper_sc, paper_0) in groups {
        let pick = |v: &[f64]| -> (Vec<Seed003Condition>, Vec<f64>) { runs.iter().zip(v).filter(|((g, _), _)| *g == group || *g == Seed003Group::Base).map(|((_, c), h)| (*c, *h)).unzip() };
        let ((c0, v0), (_, v1)) = (pick(&h0), pick(&hsc));
        let d = [seed003_max_difference(&Seed003Fit::EQ17, &c0, &v0), seed003_max_difference(&fit0, &c0, &v0), seed003_max_difference(&Seed003Fit::EQ18, &c0, &v1), seed003_max_difference(&fit1, &c0, &v1)];
        println!("{group:?}: max difference h0*: eq. 17 {:.1} %, refit {:.1} % (paper {paper_0} %); h_sc*: eq. 18 {:.1} %, refit {:.1} % (paper {paper_sc} %)", d[0], d[1], d[2], d[3]);
        for k in 0..4 {
            worst[k] = worst[k].max(d[k]);
        }
    }
    let base = runs[0].1;
    let fine = Seed003Setup { options: Ehl2dOptions { nx: 193, ny: 385, ..setup.options }, ..setup };
    let (f, c) = (seed003_run(&base, &fine, &Silent).unwrap(), &solved[0]);
    println!("grid: base run 129 × 257 h0* {:.5e}, h_sc* {:.5e}; 193 × 385 {:.5e}, {:.5e} ({:+.3} %, {:+.3} %); the 20 runs in {elapsed:?}", c.central, c.side, f.central, f.side, 100.0 * (c.central / f.central - 1.0), 100.0 * (c.side / f.side - 1.0));
    println!("worst: {worst:?}");
    let near = |v: f64, want: f64, tol: f64| (v - want).abs() <= tol;
    // The paper's statements that hold: the squeeze exponents and h_sc*'s speed exponent.
    assert!(near(fit0.squeeze, Seed003Fit::EQ17.squeeze, 0.15 * 96.775), "{fit0:?}");
    assert!(near(fit1.squeeze, Seed003Fit::EQ18.squeeze, 0.2 * 138.059), "{fit1:?}");
    assert!(near(fit1.speed, Seed003Fit::EQ18.speed, 0.05 * 0.857), "{fit1:?}");
    // The rest as measured (docs/seeds.md, seed 003 Table 3: thick films, M 0.07–1.1).
    for (v, want, tol) in [(fit0.load, -0.434, 0.03), (fit0.speed, 0.823, 0.03), (fit0.materials, 0.091, 0.02), (fit1.load, -0.627, 0.03), (fit1.materials, 0.142, 0.02)] {
        assert!(near(v, want, tol), "{v} vs {want}: {fit0:?} {fit1:?}");
    }
    for (v, want, tol) in [(worst[0], 69.6, 3.0), (worst[1], 18.4, 2.0), (worst[2], 72.1, 3.0), (worst[3], 4.4, 1.0)] {
        assert!(near(v, want, tol), "{worst:?}");
    }
    assert!((c.central / f.central - 1.0).abs() < 2e-3 && (c.side / f.side - 1.0).abs() < 2e-3);
}

/// The long straight roller of the 2-D solver's tests (`tests/it/ehl_2d.rs`,
/// `long_straight_roller`): w' = 2e5 N/m on R = 10 mm, u_m = 1 m/s, Roelands + Dowson–Higginson
/// (η0 = 0.04 Pa·s, α = 2e-8 1/Pa), 20 half-widths long with the ends relieved over `relief`
/// half-widths (0: sharp ends).
fn long_roller(relief: f64) -> Ehl2dInput {
    let e_prime = 210e9 / 0.91;
    let lubricant = Lubricant { viscosity: 0.04, pressure_viscosity: 2e-8, ..Lubricant::SEED000 };
    let (rx, w) = (0.01, 2.0e5);
    let b = crate::contact::hertz_line(w, rx, 0.5 * e_prime).half_width;
    let length = 20.0 * b;
    let crown = Crown { length, middle_length: length - 2.0 * relief * b, crown_height: 0.0, end_radius: rx, profile: CrownProfile::Convex };
    Ehl2dInput { load: w * length, geometry: Geometry2d::Finite { rx, crown }, effective_modulus: e_prime, entrainment_velocity: 1.0, lubricant, temperature: lubricant.reference_temperature }
}

/// Seed 003 Figs. 4–6 (issue 42 item 2): at the same load, a larger approach (squeeze) velocity
/// gives a thicker film through the contact centre (section 3-3) and a larger side-constriction
/// pressure spike. The long straight roller (ends relieved over 2 half-widths: with sharp ends the
/// film pinches at the edge on this grid, refused by the resolution check), 49 × 65 nodes, inlet
/// 5 a, outlet 2 a; v = 0, 1, 3 mm/s imposed by [`solve_prescribed_squeeze`] (3 solves each).
/// Measured (dev, 6 s; 15 s with the cores taken by other builds): h_c 259.2 → 403.5 → 663.0 nm (×1.56, ×2.56),
/// edge peak 1.210 → 1.230 → 1.597 GPa (+1.7 %, +32 %); on 129² (the ignored probe in
/// `tests/it/ehl_2d_transient.rs`) 277.5 → 421.8 → 680.5 nm (×1.52, ×2.45) and 1.226 → 1.247 →
/// 2.41 GPa — the film ratios are grid-converged to 4 %, the spike at 3 mm/s is not (1.60, 1.75,
/// 2.41 GPa on 49 × 65, 65², 129²: it sharpens with the grid). Asserted: both grow at each step,
/// the film ratios within 0.08, the spike's +1.7 % within 1 point and +32 % within 8.
#[test]
fn seed003_figs_4_6_squeeze_thickens_the_film_and_raises_the_edge_spike() {
    let t = std::time::Instant::now();
    let input = long_roller(2.0);
    let o = Ehl2dOptions { nx: 49, ny: 65, inlet: Some(5.0), outlet: Some(2.0), grid_tolerance: 1.0, grid_check: false, ..Ehl2dOptions::default() };
    let (s0, w0) = solve_from(&input, &o, None, &Silent).unwrap();
    let edge = |s: &Ehl2dSolution| s.edge_pressure_peak.as_ref().expect("an edge peak").value;
    let mut rows = vec![(0.0, s0.central_film, s0.min_film.value, edge(&s0))];
    for v in [1e-3, 3e-3] {
        let (s, _, fp) = solve_prescribed_squeeze(&input, &o, (&s0, &w0), v, 1e3, 1e-4, 8, &Silent).unwrap();
        assert_eq!(fp.termination, Termination::Converged);
        rows.push((v, s.central_film, s.min_film.value, edge(&s)));
    }
    println!("(v m/s, h_c m, h_min m, edge peak Pa): {rows:?}; {:?}", t.elapsed());
    for w in rows.windows(2) {
        assert!(w[1].1 > w[0].1 && w[1].2 > w[0].2 && w[1].3 > w[0].3, "{rows:?}");
    }
    let (h, p) = (|k: usize| rows[k].1 / rows[0].1, |k: usize| 100.0 * (rows[k].3 / rows[0].3 - 1.0));
    assert!((h(1) - 1.56).abs() < 0.08 && (h(2) - 2.56).abs() < 0.08, "{rows:?}");
    assert!((p(1) - 1.7).abs() < 1.0 && (p(2) - 32.0).abs() < 8.0, "{rows:?}");
}

/// Table 3 with the inlet boundary 7 Hertz half-widths upstream (as in the fixed, few-half-width
/// domains of 1980s finite-line solutions; 49 × 65, L = 4 mm): a starved inlet whose length grows
/// with the load. Measured (4 s dev): refit h0* = 5.17 W*^0.044 U*^0.528 G*^0.216 e^(−133.0 w_s*)
/// (the fully flooded setup: −0.434, 0.823, 0.091, −106.6; eq. 17: 0.059, 0.541, 0.421,
/// −96.775), base run 3.42e-5 (eq. 17: 3.95e-5); the refit's largest difference per group
/// 1.7 % (G*), 6.1 % (w_s*), 5.3 % (W*), 1.2 % (U*) — Table 3's column: 7.6, 5.8, 4.7, 2.5 % —
/// and eq. 17's against these runs 23.4 % at most. Asserted: the W* exponent within 0.03 of
/// eq. 17's, the U* exponent within 5 %, the refit's differences below 8 % (the paper's largest
/// 7.6 %); G*, w_s* and eq. 17's difference as measured. Inlet 4, 5, 6, 8 b on
/// 65 × 129: W* exponent +0.229, +0.160, +0.096, −0.005 and U* 0.441, 0.472, 0.501, 0.553 — eq.
/// 17's load and speed exponents are those of an inlet ≈ 7 b. Its G* exponent is not (0.2 at
/// every inlet: Table 3's pressures are too low for piezoviscosity to matter more). The 6 b
/// inlet's fit moves by < 0.003 in every exponent from 49 × 65 to 129 × 257.
#[test]
fn seed003_table3_with_a_short_inlet_has_eq17s_load_and_speed_exponents() {
    let t = std::time::Instant::now();
    let d = Seed003Setup::default();
    let setup = Seed003Setup { options: Ehl2dOptions { nx: 49, ny: 65, inlet: Some(7.0), outlet: None, ..d.options }, ..d };
    let table = seed003_table3();
    let runs = conditions();
    let h: Vec<f64> = runs.iter().map(|c| seed003_run(c, &setup, &Silent).unwrap().central).collect();
    let f = seed003_fit(&runs, &h).unwrap();
    println!("7 b inlet: base h0* {:.4e} (eq. 17 {:.4e}); fit {f:?}; {:?}", h[0], Seed003Fit::EQ17.film(&runs[0]), t.elapsed());
    for group in [Seed003Group::Materials, Seed003Group::Squeeze, Seed003Group::Load, Seed003Group::Speed] {
        let (c, v): (Vec<Seed003Condition>, Vec<f64>) = table.iter().zip(&h).filter(|((g, _), _)| *g == group || *g == Seed003Group::Base).map(|((_, c), h)| (*c, *h)).unzip();
        let (eq17, refit) = (seed003_max_difference(&Seed003Fit::EQ17, &c, &v), seed003_max_difference(&f, &c, &v));
        println!("{group:?}: max difference eq. 17 {eq17:.1} %, refit {refit:.1} %");
        assert!(refit < 8.0 && eq17 < 25.5, "{group:?}: {eq17} {refit}");
    }
    let e = Seed003Fit::EQ17;
    assert!((f.load - e.load).abs() < 0.03 && (f.speed / e.speed - 1.0).abs() < 0.05, "{f:?}");
    assert!((f.materials - 0.216).abs() < 0.02 && (f.squeeze + 133.0).abs() < 5.0, "{f:?}");
    assert!(seed003_max_difference(&e, &runs, &h) > 21.0, "eq. 17 as measured: 23.4 %");
}
