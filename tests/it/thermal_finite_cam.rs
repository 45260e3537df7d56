//! The thermal finite-line model inside the cam kinds (issue 43 b: `ehl.thermal` with
//! `ehl.geometry: finite`): the seed 000 cycle (`examples/seed000_thermal_finite_cycle.json`)
//! runs hot and its film at the nose agrees with `ehl_point`'s thermal finite-line solution at
//! the same conditions; `cam_point` likewise at pure rolling.

use crate::in_process::{example, run};
use serde_json::{json, Value};

fn rel(a: f64, b: f64) -> f64 {
    (a / b - 1.0).abs()
}

fn col(out: &Value, name: &str) -> Vec<f64> {
    out["series"][name].as_array().unwrap_or_else(|| panic!("series {name}")).iter().map(|v| v.as_f64().unwrap()).collect()
}

/// `ehl_point` with seed 000's crowned roller (convex crown, L = 14 mm, L1 = 12 mm,
/// h_td = 4.5 µm, R_d = 12.5 mm) and oil, thermal, on the cycle's 33×65 grid.
fn ehl_point(load: f64, radius: f64, um: f64, us: f64) -> Value {
    let steel = json!({"youngs_modulus": 1.911e11, "poisson_ratio": 0.3});
    let spec = json!({
        "load": load, "length": 0.014, "reduced_radius": radius, "entrainment_velocity": um, "sliding_velocity": us,
        "body_1": steel, "body_2": steel, "tolerance": 1e-6,
        "geometry": {"type": "finite", "middle_length": 0.012, "crown_height": 4.5e-6, "end_radius": 0.0125, "nx": 33, "ny": 65},
        "thermal": {}
    });
    run("ehl_point", &spec).unwrap()
}

/// The 12-angle seed 000 cycle, thermal finite-line at every angle: film temperatures above the
/// 313 K inlet and finite (the seed 000 roller heats the film by 5–25 K on this grid), the
/// slide-to-roll ratio finite and within ±1; at the nose (120°, index 4) against `ehl_point`'s
/// thermal finite-line solution at the cycle's converged load, radius, entrainment and sliding:
/// central and minimum films within 0.5 % (measured 0.03 %), the largest film temperature
/// within 1.5 K (measured 326.3 against 325.8 K) and the follower's traction (the cycle's
/// `friction_force`, the calibrated nodal traction) within 4 % of the whole-contact thermal
/// force on body 2 (measured 26.36 against 26.86 N, −1.9 %: the film is solved at the roller
/// balance's guessed slip, re-solved when the converged entrainment moves by more than 1e-3,
/// and the calibration holds that slip's viscosity reduction; `--nocapture`).
#[test]
fn thermal_finite_cycle_runs_hot_and_matches_ehl_point_at_the_nose() {
    let t = std::time::Instant::now();
    let out = run("cam_cycle", &example("seed000_thermal_finite_cycle")).unwrap();
    println!("cycle {:?}", t.elapsed());
    assert_eq!(out["summary"]["fidelity_used"], json!({"thermal_finite": 12}));
    let (tmax, srr) = (col(&out, "film_temperature_max"), col(&out, "slide_roll_ratio"));
    assert_eq!(tmax.len(), 12);
    for i in 0..12 {
        assert!(tmax[i].is_finite() && tmax[i] > 313.0 + 1.0 && tmax[i] < 313.0 + 100.0, "{i}: {}", tmax[i]);
        assert!(srr[i].is_finite() && srr[i].abs() < 1.0, "{i}: {}", srr[i]);
    }
    let i = 4;
    let (w, r, um, us) = (col(&out, "contact_load")[i], col(&out, "reduced_radius")[i], col(&out, "entrainment_velocity")[i], col(&out, "sliding_velocity")[i]);
    let point = ehl_point(w, r, um, us);
    let (hc, hm) = (col(&out, "film_central")[i], col(&out, "film_min")[i]);
    let (pc, pm) = (point["central_film"].as_f64().unwrap(), point["min_film"].as_f64().unwrap());
    let pt = point["film_temperature_max"].as_f64().unwrap();
    println!("nose: W {w} N, u_m {um} m/s, u_s {us} m/s; h_c {hc:e} / {pc:e}, h_min {hm:e} / {pm:e}, T_max {} / {pt} K", tmax[i]);
    assert!(rel(hc, pc) < 0.005, "central film {hc} vs ehl_point {pc}");
    assert!(rel(hm, pm) < 0.005, "minimum film {hm} vs ehl_point {pm}");
    assert!((tmax[i] - pt).abs() < 1.5, "film temperature {} vs ehl_point {pt}", tmax[i]);
    let (f, pf) = (col(&out, "friction_force")[i], point["thermal_finite"]["traction_force_body_2"].as_f64().unwrap());
    println!("nose traction {f} N, ehl_point body 2 {pf} N");
    assert!(rel(f, pf) < 0.04, "traction {f} vs ehl_point {pf}");
}

/// `cam_point` thermal + finite at seed 000's nose (954 N, R = 10.37 mm, cam surface 2.77 m/s,
/// crowned roller, 33×65): the pure-rolling film within 0.5 % of `ehl_point`'s thermal
/// finite-line solution at the same entrainment and no sliding (the same solver, both cold),
/// the rows' slide-to-roll ratios finite.
#[test]
fn thermal_finite_cam_point_matches_ehl_point_at_rolling() {
    let spec = json!({
        "load": 954.0, "reduced_radius": 0.01037, "cam_surface_velocity": 2.77, "contact_length": 0.014,
        "roller": {"radius": 0.0255, "pin_radius": 0.016, "crown": {"middle_length": 0.012, "crown_height": 4.5e-6, "end_radius": 0.0125}},
        "pin_friction": [0.002, 0.004],
        "cam": {"material": {"youngs_modulus": 1.911e11, "poisson_ratio": 0.3}},
        "follower": {"material": {"youngs_modulus": 1.911e11, "poisson_ratio": 0.3}},
        "lubricant": {"viscosity": 0.152, "pressure_viscosity": 2.2e-8, "temperature_viscosity": 0.042, "reference_temperature": 313.0, "density": 870.0},
        "traction": {"model": "newtonian"},
        "fidelity": "accurate",
        "ehl": {"geometry": "finite", "nx": 33, "ny": 65, "tolerance": 1e-6, "grid_tolerance": 0.08, "thermal": {}}
    });
    let out = run("cam_point", &spec).unwrap();
    assert_eq!(out["film_model"], json!("thermal_finite"));
    let hc = out["summary"]["film_central"].as_f64().unwrap();
    let point = ehl_point(954.0, 0.01037, 2.77, 0.0);
    let pc = point["central_film"].as_f64().unwrap();
    println!("cam_point h_c {hc:e}, ehl_point {pc:e}; rows {}", out["rows"]);
    assert!(rel(hc, pc) < 0.005, "{hc} vs {pc}");
    for row in out["rows"].as_array().unwrap() {
        let srr = row["slide_roll_ratio"].as_f64().unwrap();
        assert!(srr.is_finite() && srr.abs() < 2.0, "{row}");
    }
}

/// Seed 000's cycle (`examples/seed000_thermal_finite_cycle.json`) at `angles` with viscosity
/// `eta` (Pa·s) and modified load `w1` (N), on the thermal finite-line model (`finite`) or the
/// 1-D thermal model (the same spec with `ehl: {thermal: {}}`).
fn seed000_thermal_cycle(eta: f64, w1: f64, finite: bool, angles: usize) -> Value {
    let mut spec = example("seed000_thermal_finite_cycle");
    spec["angles"] = json!(angles);
    spec["lubricant"]["viscosity"] = json!(eta);
    spec["load"]["offset"] = json!(w1);
    if !finite {
        spec["ehl"] = json!({"thermal": {}});
    }
    run("cam_cycle", &spec).unwrap()
}

/// Value of series `name` at cam angle `deg` (an angle of the grid).
fn at(out: &Value, name: &str, deg: f64) -> f64 {
    let angles = col(out, "angle_deg");
    let i = angles.iter().position(|a| (a - deg).abs() < 1e-9).unwrap_or_else(|| panic!("{deg}° is not on the grid"));
    col(out, name)[i]
}

fn summary(out: &Value, key: &str) -> f64 {
    out["summary"][key].as_f64().unwrap_or_else(|| panic!("summary {key}"))
}

fn max_of(out: &Value, name: &str) -> f64 {
    col(out, name).into_iter().fold(f64::MIN, f64::max)
}

/// The statements of seed 000 Figs. 10, 12 and 14 that the fast model cannot reproduce
/// (docs/seeds.md: its slip grows faster with η0 than the film's shear falls), with the thermal
/// models: the cam–roller friction at 100° and its magnitude at 155° (the roller overruns there:
/// the friction is negative) *rise as η0 falls*; the minimum film and the film's largest
/// temperature rise with η0; the minimum film *falls* with the modified load w1 while the mean
/// friction coefficient falls. `assert_fig_10_to_14_trends` holds them for one model.
fn assert_fig_10_to_14_trends(by_eta: &[Value], by_w1: &[Value]) {
    for w in by_eta.windows(2) {
        let (lo, hi) = (&w[0], &w[1]);
        assert!(at(lo, "friction_coefficient", 100.0) > at(hi, "friction_coefficient", 100.0), "μ_cr(100°) rises as η0 falls");
        assert!(at(lo, "friction_coefficient", 155.0).abs() > at(hi, "friction_coefficient", 155.0).abs(), "|μ_cr(155°)| rises as η0 falls");
        assert!(summary(hi, "min_film") > summary(lo, "min_film"), "the minimum film rises with η0");
        assert!(max_of(hi, "film_temperature_max") > max_of(lo, "film_temperature_max"), "the film temperature rises with η0");
    }
    for w in by_w1.windows(2) {
        let (lo, hi) = (&w[0], &w[1]);
        assert!(summary(hi, "min_film") < summary(lo, "min_film"), "the minimum film falls with w1");
        assert!(summary(hi, "mean_friction_coefficient") < summary(lo, "mean_friction_coefficient"), "the friction falls with w1");
        assert!(summary(hi, "max_hertz_pressure") > summary(lo, "max_hertz_pressure"), "the pressure rises with w1");
    }
}

fn print_cycle(label: &str, out: &Value) {
    println!(
        "{label}: min film {:.4} µm, h_min(100°) {:.4} µm, h_min(125°) {:.4} µm, T_max {:.1} K, μ(100°) {:.4}, μ(155°) {:.4}, mean μ {:.4}, SRR(0°) {:.4}, max |SRR| {:.3}",
        summary(out, "min_film") * 1e6,
        at(out, "film_min", 100.0) * 1e6,
        at(out, "film_min", 125.0) * 1e6,
        max_of(out, "film_temperature_max"),
        at(out, "friction_coefficient", 100.0),
        at(out, "friction_coefficient", 155.0),
        summary(out, "mean_friction_coefficient"),
        at(out, "slide_roll_ratio", 0.0),
        summary(out, "max_abs_slide_roll_ratio"),
    );
}

/// Seed 000 Figs. 10–14 with the 1-D thermal model (72 angles, η0 0.08 and 0.2 Pa·s; w1 0 and
/// 800 N): the trends of [`assert_fig_10_to_14_trends`]. Measured (release, `--nocapture`):
/// μ(100°) 0.0365 → 0.0261, μ(155°) −0.0053 → −0.0029, minimum film 0.847 → 1.540 µm, T_max
/// 332.0 → 370.7 K over η0; minimum film 1.286 → 1.234 µm and mean μ 0.0110 → 0.0058 over w1.
#[test]
fn seed000_figs_10_to_14_with_the_thermal_line_model() {
    let by_eta: Vec<Value> = [0.08, 0.2].iter().map(|&eta| seed000_thermal_cycle(eta, 0.0, false, 72)).collect();
    let by_w1: Vec<Value> = [0.0, 800.0].iter().map(|&w1| seed000_thermal_cycle(0.152, w1, false, 72)).collect();
    for (label, out) in ["η0 0.08", "η0 0.2"].iter().zip(&by_eta).chain(["w1 0", "w1 800"].iter().zip(&by_w1)) {
        print_cycle(label, out);
    }
    assert_fig_10_to_14_trends(&by_eta, &by_w1);
}

/// Issue 43 item 3: seed 000 Figs. 10–14 with the thermal finite-line model beside the 1-D
/// thermal model (72 angles; η0 0.08, 0.152, 0.2 Pa·s at w1 = 0; w1 0, 400, 800 N at η0 =
/// 0.152): both models hold the trends of [`assert_fig_10_to_14_trends`]; the finite length
/// changes each by (measured, finite/line): minimum film +6.6 %, +5.5 %, −7.5 % over η0 and
/// +5.5 %, +5.8 %, +5.9 % over w1; largest film temperature +9.4, +10.2, +19.7 K over η0; mean
/// friction coefficient −4 % to −8 % over η0, within 1.5 % over w1; the roller's slip two to four times the 1-D model's
/// (SRR(0°) 0.165 against 0.047 at η0 0.152 — docs/seeds.md, seed 000, "roller slip: finite
/// against line": the line model runs the crown's equivalent line, all the load at the peak load
/// per length, with 1.8× the crowned contact's sliding traction and half its rolling resistance;
/// pinned by *lib* `film::thermal_finite::tests::base_circle_traction_finite_against_the_equivalent_line`).
/// Asserted: the trends, the films within 10 % of each other, the finite model's slip at 0°
/// above the 1-D model's. Release, about 100 s on two cores: `cargo test --release --test it --
/// seed000_figs_10_to_14_finite_against_line --include-ignored --nocapture`.
#[test]
#[ignore = "release: ten thermal cycles, five of them finite-line (about 100 s); run with --include-ignored"]
fn seed000_figs_10_to_14_finite_against_line() {
    let cases = [(0.08, 0.0), (0.152, 0.0), (0.2, 0.0), (0.152, 400.0), (0.152, 800.0)];
    let mut runs = Vec::new();
    for finite in [false, true] {
        let outs: Vec<Value> = cases.iter().map(|&(eta, w1)| seed000_thermal_cycle(eta, w1, finite, 72)).collect();
        for ((eta, w1), out) in cases.iter().zip(&outs) {
            print_cycle(&format!("{} η0 {eta} w1 {w1}", if finite { "finite" } else { "line" }), out);
        }
        assert_fig_10_to_14_trends(&outs[..3], &[outs[1].clone(), outs[3].clone(), outs[4].clone()]);
        runs.push(outs);
    }
    for (line, finite) in runs[0].iter().zip(&runs[1]) {
        let (hl, hf) = (summary(line, "min_film"), summary(finite, "min_film"));
        println!("finite/line: min film {:+.1} %, T_max {:+.1} K, mean μ {:+.1} %", 100.0 * (hf / hl - 1.0), max_of(finite, "film_temperature_max") - max_of(line, "film_temperature_max"), 100.0 * (summary(finite, "mean_friction_coefficient") / summary(line, "mean_friction_coefficient") - 1.0));
        assert!(rel(hf, hl) < 0.10, "minimum films {hf} (finite) and {hl} (line)");
        assert!(at(finite, "slide_roll_ratio", 0.0) > at(line, "slide_roll_ratio", 0.0), "the finite model's base-circle slip is the larger");
    }
}

/// Seed 000 Fig. 5 over the cycle with the thermal finite-line model (issue 43 item 3): skidding
/// (the roller's torque balance) against pure rolling (`slip.mode: pure_rolling`), the example's
/// spec at 36 angles on 33×65. Paper: the film barely moves, the temperature rise and the
/// friction do. The 1-D thermal model (`thermal_ehl::seed000_cycle`, 36 angles): minimum film
/// within 4.1 % at every angle, largest rise 32.0 against 11.0 K, mean |µ| ×3.6. Measured here
/// (`--nocapture`): the rise 48.8 against 10.3 K and the mean |µ| ×2.8 as the paper; the
/// minimum film within 1 % wherever |SRR| < 0.03 but thinner with the slip elsewhere — 6 % on
/// the base circle (SRR 0.16), 11.4 % at 100° (SRR 0.24): the crowned contact skids three times
/// as much as the 1-D model's equivalent line (docs/seeds.md, "Roller slip: finite against
/// line"), and its shear heating thins the film by about half the slide-to-roll ratio. Asserted
/// as measured: within 12 %, below `0.5 |SRR| + 1 %` at every angle, 1 % where |SRR| < 0.03.
#[test]
fn seed000_fig5_skidding_over_the_cycle_with_the_thermal_finite_model() {
    let mut skid = example("seed000_thermal_finite_cycle");
    skid["angles"] = json!(36);
    let mut rolling = skid.clone();
    rolling["slip"] = json!({"mode": "pure_rolling"});
    let (skid, rolling) = (run("cam_cycle", &skid).unwrap(), run("cam_cycle", &rolling).unwrap());
    let (hs, hr) = (col(&skid, "film_min"), col(&rolling, "film_min"));
    let (angles, srr) = (col(&skid, "angle_deg"), col(&skid, "slide_roll_ratio"));
    let mut film_w: f64 = 0.0;
    for i in 0..angles.len() {
        let d = rel(hs[i], hr[i]);
        println!("{:5.1}° SRR {:+.4} film_min {:.4} / {:.4} µm ({:+.2} %)", angles[i], srr[i], hs[i] * 1e6, hr[i] * 1e6, 100.0 * (hs[i] / hr[i] - 1.0));
        assert!(d < 0.5 * srr[i].abs() + 0.01, "{}°: film {d} at SRR {}", angles[i], srr[i]);
        if srr[i].abs() < 0.03 {
            assert!(d < 0.01, "{}°: film {d} at SRR {}", angles[i], srr[i]);
        }
        film_w = film_w.max(d);
    }
    let rise = |o: &Value| col(o, "film_temperature_max").iter().map(|t| t - 313.0).fold(0.0, f64::max);
    let mean_mu = |o: &Value| {
        let mu = col(o, "friction_coefficient");
        mu.iter().map(|m| m.abs()).sum::<f64>() / mu.len() as f64
    };
    println!("Fig. 5 (thermal finite): film_min worst {film_w:.4}; rise {:.2} / {:.2} K; mean |µ| {:.4e} / {:.4e}", rise(&skid), rise(&rolling), mean_mu(&skid), mean_mu(&rolling));
    assert!(film_w < 0.12, "film {film_w}");
    assert!(rise(&skid) > 4.0 * rise(&rolling) && rise(&rolling) > 0.0, "temperature rise");
    assert!(mean_mu(&skid) > 2.5 * mean_mu(&rolling), "friction");
}
