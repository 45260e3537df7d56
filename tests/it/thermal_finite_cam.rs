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
