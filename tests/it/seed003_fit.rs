//! Seed 003 §6 as published (issue 42 item 1): the inverse fit of the cycloidal cam and flat
//! follower over the paper's unknowns, the bound that shows which statements conflict, and the
//! example's figures against the paper's statements.
//! Run: `cargo test --release --test it -- seed003_fit --include-ignored --nocapture` (prints the
//! residual tables). The three searches (a 3⁷ grid and Nelder–Mead restarts, ≈ 18,000 cycle
//! evaluations, 3.5 min in a debug build) are `#[ignore]`d in CI; the example's figures against
//! the paper run in CI.

use serde_json::{json, Value};
use std::f64::consts::PI;
use tribod::jobs::kinds::cam_cycle::CamCycleSpec;
use tribod::jobs::kinds::contact::LubricatedContact;
use tribod::physics::cam::seed003_fit::{fit, grid_starts, CamFit, CamUnknowns, FitOptions, FitSetup, STATEMENTS, STATEMENT_COUNT};

use crate::in_process::example;

/// The example's spec as the fit's template: the paper's entraining-only film (no squeeze).
fn template_spec() -> CamCycleSpec {
    let mut s: Value = example("seed003_cycloidal_flat");
    s["film"] = json!({"formula": "seed003", "squeeze": false});
    serde_json::from_value(s).unwrap()
}

fn rpm(x: f64) -> f64 {
    x * PI / 30.0
}

/// The search box: automotive flat-follower valve trains (base radius 10–30 mm, lift 4–14 mm,
/// rise 40–170°, nose dwell 0–60°, face width 6–30 mm, 1000–6000 camshaft rpm, preload
/// 50–1000 N).
fn options(weights: [f64; STATEMENT_COUNT], span: bool) -> FitOptions {
    FitOptions {
        weights,
        lower: CamUnknowns { base_radius: 0.010, lift: 0.004, rise: 40f64.to_radians(), top_dwell: 0.0, width: 0.006, omega: rpm(1000.0), preload: 50.0 },
        upper: CamUnknowns { base_radius: 0.030, lift: 0.014, rise: 170f64.to_radians(), top_dwell: 60f64.to_radians(), width: 0.030, omega: rpm(6000.0), preload: 1000.0 },
        span_90_270: span,
        evaluations_per_start: 500,
        tolerance: 1e-6,
    }
}

fn print_fit(label: &str, f: &CamFit) {
    let x = &f.unknowns;
    println!(
        "{label}: cost {:.3} ({} evaluations); r_b {:.3} mm, lift {:.3} mm, rise {:.2}°, dwell {:.2}° (rise starts {:.2}°), width {:.2} mm, {:.0} rpm, preload {:.1} N",
        f.cost,
        f.convergence.iterations,
        x.base_radius * 1e3,
        x.lift * 1e3,
        x.rise.to_degrees(),
        x.top_dwell.to_degrees(),
        x.rise_start().to_degrees(),
        x.width * 1e3,
        x.omega * 30.0 / PI,
        x.preload
    );
    for (i, s) in STATEMENTS.iter().enumerate() {
        println!("  {:<26} paper {:>10.4e} model {:>10.4e} residual {:>8.2}", s.name, s.paper, f.figures.values[i], f.residuals[i]);
    }
    println!("  reversals from the nose {:?}°, min central film {:.3e} m", f.figures.reversals_deg, f.figures.min_film);
}

fn run_fit(weights: [f64; STATEMENT_COUNT], span: bool, label: &str) -> CamFit {
    let spec = template_spec();
    let template = spec.cycle_spec().unwrap();
    let model = spec.film_model(spec.ehl.to_physics(spec.line_family()));
    let setup = FitSetup { template: &template, model: model.as_ref(), face_radius: Some(0.017) };
    let opts = options(weights, span);
    let starts = grid_starts(&setup, &opts, 3, 4);
    assert!(!starts.is_empty(), "{label}: no grid point has four reversals");
    let f = fit(&setup, &opts, &starts).unwrap();
    print_fit(label, &f);
    f
}

/// All statements at once (unit weights; the scales are 1°, 2 % and, for the nose film, 5 %):
/// the best compromise, which the example carries.
#[test]
#[ignore = "the inverse fit's search: 3.5 min in debug; run with --include-ignored in release"]
fn seed003_fit_all_statements() {
    let f = run_fit([1.0; STATEMENT_COUNT], false, "all statements");
    assert!(f.cost.is_finite());
}

/// The bound: the reversals at ±15°/±51° and the Hertz maximum at ±62° cannot hold together.
/// With only these three statements weighted, the best cycle in the box still misses them (a
/// geometry with the reversals there has its smallest radius, hence its Hertz maximum, between
/// them, ≈ ±33°, unless inertia nearly unloads the contact there, which moves the maximum past
/// ±85°).
#[test]
#[ignore = "the inverse fit's search: 3.5 min in debug; run with --include-ignored in release"]
fn seed003_fit_reversals_against_hertz_peak_angle() {
    let mut w = [0.0; STATEMENT_COUNT];
    w[0] = 1.0;
    w[1] = 1.0;
    w[5] = 1.0;
    let f = run_fit(w, false, "reversals + Hertz peak angle");
    assert!(f.cost > 25.0, "the conflict is at least 5° combined: {}", f.cost);
}

/// The paper's "flank and nose actions from 90° to 270°" (rise + dwell/2 = 90°) with the
/// reversals at ±15°/±51°: only a negative base radius (r_b = −0.10 h) puts them there.
#[test]
#[ignore = "the inverse fit's search: 3.5 min in debug; run with --include-ignored in release"]
fn seed003_fit_reversals_within_90_to_270() {
    let mut w = [0.0; STATEMENT_COUNT];
    w[0] = 1.0;
    w[1] = 1.0;
    let f = run_fit(w, true, "reversals, cam acting 90°–270°");
    assert!(f.cost > 4.0, "{}", f.cost);
    let free = run_fit(w, false, "reversals, free span");
    assert!(free.cost < 0.01, "{}", free.cost);
}

fn col(out: &Value, name: &str) -> Vec<f64> {
    out["series"][name].as_array().unwrap_or_else(|| panic!("no column {name}")).iter().map(|v| v.as_f64().unwrap()).collect()
}

fn at_deg(out: &Value, name: &str, angle: f64) -> f64 {
    let a = col(out, "angle_deg");
    let i = a.iter().enumerate().min_by(|x, y| (x.1 - angle).abs().total_cmp(&(y.1 - angle).abs())).unwrap().0;
    col(out, name)[i]
}

fn pearson(x: &[f64], y: &[f64]) -> f64 {
    let n = x.len() as f64;
    let (mx, my) = (x.iter().sum::<f64>() / n, y.iter().sum::<f64>() / n);
    let cov: f64 = x.iter().zip(y).map(|(a, b)| (a - mx) * (b - my)).sum();
    let vx: f64 = x.iter().map(|a| (a - mx).powi(2)).sum();
    let vy: f64 = y.iter().map(|b| (b - my).powi(2)).sum();
    cov / (vx * vy).sqrt()
}

/// The example (the all-statements fit) against seed 003 §6 / Fig. 10–12. Where the model
/// differs the assertion is what the model gives (docs/seeds.md says why; the bound is the two
/// tests above): reversals at ±28.8°/±61.7° (paper ±15°/±51°), Hertz 257 MPa at ±62° and 213 MPa
/// at the nose (325/180), its maximum 329 MPa at ±45.7° (±62°), nose film 0.71 µm at 3.93 m/s
/// (just below 1 µm, > 4 m/s), film ≤ 1.12 µm (≤ 1.3), shear 98.7 MPa (96). Tolerances: 0.1°
/// on angles, 0.5 % on pressures, films and velocities (the fit's own figures, rounded in the
/// example). Fig. 11: deflection and contact width rise with the load.
#[test]
fn seed003_example_against_the_paper() {
    let out = crate::in_process::run("cam_cycle", &example("seed003_cycloidal_flat")).unwrap();
    let z: Vec<f64> = out["events"]["zero_entrainment_angles_deg"].as_array().unwrap().iter().map(|v| v.as_f64().unwrap()).collect();
    assert_eq!(z.len(), 4, "{z:?}");
    let from_nose: Vec<f64> = z.iter().map(|a| (a - 180.0).abs()).collect();
    for (got, want) in from_nose.iter().zip([61.75, 28.78, 28.78, 61.75]) {
        assert!((got - want).abs() < 0.1, "{from_nose:?}");
    }
    let close = |a: f64, b: f64| (a / b - 1.0).abs() < 5e-3;
    let (p62a, p62b, pn) = (at_deg(&out, "hertz_max_pressure", 118.0), at_deg(&out, "hertz_max_pressure", 242.0), at_deg(&out, "hertz_max_pressure", 180.0));
    assert!(close(p62a, 256.9e6) && close(p62b, 256.9e6) && close(pn, 213.3e6), "{p62a} {p62b} {pn}");
    let sm = &out["summary"];
    let pmax = sm["max_hertz_pressure"].as_f64().unwrap();
    assert!(close(pmax, 328.7e6), "{pmax}");
    assert!(((sm["max_hertz_pressure_angle_deg"].as_f64().unwrap() - 180.0).abs() - 45.5).abs() < 0.6);
    let (hn, un) = (at_deg(&out, "film_central", 180.0), at_deg(&out, "entrainment_velocity", 180.0));
    assert!(close(hn, 0.7116e-6) && close(un, 3.934), "{hn} {un}");
    let h = col(&out, "film_central");
    let hmax = h.iter().copied().fold(0.0, f64::max);
    assert!(close(hmax, 1.1195e-6) && hmax < 1.3e-6, "{hmax}");
    // Minimum film: the entraining-only formula vanishes with the entrainment; the sampled
    // minimum (0.5° grid) is 0.048 µm, the paper's 0.03 µm a sampling of the same collapse.
    let hmin = h.iter().copied().fold(f64::INFINITY, f64::min);
    assert!(hmin < 0.06e-6, "{hmin}");
    let tau = col(&out, "max_shear_stress").into_iter().fold(0.0, f64::max);
    assert!(close(tau, 98.71e6), "{tau}");
    // Fig. 11: deflection (eq. 6) and contact width over the cycle rise with the load.
    let (w, d, b) = (col(&out, "contact_load"), col(&out, "contact_deflection"), col(&out, "hertz_half_width"));
    let (rd, rb) = (pearson(&w, &d), pearson(&w, &b));
    println!("seed 003 Fig. 11: deflection {:.3e}–{:.3e} m; correlation with load: deflection {rd:.4}, half-width {rb:.4}", d.iter().copied().fold(f64::INFINITY, f64::min), d.iter().copied().fold(0.0, f64::max));
    assert!(rd > 0.99 && rb > 0.9, "{rd} {rb}");
}
