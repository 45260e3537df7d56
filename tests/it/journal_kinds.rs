//! The `bearing` and `bearing_optimisation` job kinds: validation with JSON paths, load forms,
//! dimensional outputs, fields, arrays.
use serde_json::{json, Value};
use tribod::jobs::registry;
use tribod::jobs::Limits;
use tribod::physics::Silent;

fn prepare(kind: &str, spec: Value) -> Result<Value, tribod::problem::Problem> {
    let k = registry::find(kind).unwrap();
    let p = k.prepare(&spec, &Limits::default())?;
    Ok(p.run(&Silent).unwrap())
}

fn errors(kind: &str, spec: Value, limits: Limits) -> (String, Vec<String>) {
    let k = registry::find(kind).unwrap();
    let p = k.prepare(&spec, &limits).unwrap_err();
    (p.code.clone(), p.errors.iter().map(|e| e.path.clone()).collect())
}

fn base() -> Value {
    json!({"geometry": {"length_to_diameter": 1.0}, "load": {"eccentricity_ratio": 0.6}, "grid": {"circumferential": 61, "axial": 31}})
}

#[test]
fn bad_specs_name_their_fields() {
    let mut s = base();
    s["load"] = json!({"eccentricity_ratio": 0.6, "force": 100.0});
    let (code, paths) = errors("bearing", s, Limits::default());
    assert_eq!(code, "invalid_spec");
    assert!(paths.contains(&"/load".to_string()), "{paths:?}");
    assert!(paths.contains(&"/load/force".to_string()), "force without dimensions: {paths:?}");

    let mut s = base();
    s["profile"] = json!({"order": 4, "height": 0.4, "length_fraction": 0.7});
    let (_, paths) = errors("bearing", s, Limits::default());
    assert!(paths.contains(&"/profile/order".to_string()) && paths.contains(&"/profile/length_fraction".to_string()), "{paths:?}");

    let mut s = base();
    s["geometry"]["colour"] = json!("red");
    let (code, paths) = errors("bearing", s, Limits::default());
    assert_eq!(code, "invalid_spec");
    assert_eq!(paths, vec!["/geometry/colour".to_string()], "unknown field");

    let mut s = base();
    s["grid"] = json!({"circumferential": 2001, "axial": 1001});
    let (code, paths) = errors("bearing", s, Limits::default());
    assert_eq!(code, "limit_exceeded");
    assert_eq!(paths, vec!["/grid".to_string()]);

    let spec = json!({"base": {"geometry": {"length_to_diameter": 1.25}, "load": {"sommerfeld_number": 0.1},
        "profile": {"order": 1, "height": 0.1, "length_fraction": 0.1}},
        "factors": {"order": [1, 2], "height": [0.1, 0.4, 1.0], "length_fraction": [0.01, 0.2, 0.6]}});
    let (_, paths) = errors("bearing_optimisation", spec, Limits::default());
    for p in ["/base/profile", "/factors/order", "/factors/length_fraction/2"] {
        assert!(paths.contains(&p.to_string()), "{p} in {paths:?}");
    }
    let spec = json!({"base": {"geometry": {"length_to_diameter": 1.25}, "load": {"sommerfeld_number": 0.1}},
        "factors": {"order": [1, 2, 3], "height": [0.1, 0.4, 1.0], "length_fraction": [0.01, 0.2, 0.4]}});
    let (code, paths) = errors("bearing_optimisation", spec, Limits { max_evaluations: 20, ..Limits::default() });
    assert_eq!(code, "limit_exceeded");
    assert_eq!(paths, vec!["/continuous/evaluations_per_order".to_string()]);
}

#[test]
fn load_forms_agree() {
    // the seed 002 dimensional bearing at ε = 0.6, then the same load as a force and as S
    let dims = json!({"length_to_diameter": 1.25, "radius": 0.032, "length": 0.08, "radial_clearance": 0.0001175});
    let g = json!({"circumferential": 91, "axial": 46});
    let op = json!({"speed_rpm": 3000, "viscosity": 0.0293});
    let a = prepare("bearing", json!({"geometry": dims, "operating": op, "load": {"eccentricity_ratio": 0.6}, "grid": g})).unwrap();
    let force = a["load"]["force"].as_f64().unwrap();
    let s = a["sommerfeld_number"].as_f64().unwrap();
    // p_max in Pa = P0 · 6ηω(R/c)² (seed 002 scaling); h_min = H0 c
    let scale = 6.0 * 0.0293 * (3000.0 * std::f64::consts::TAU / 60.0) * (0.032f64 / 0.0001175).powi(2);
    assert!((a["max_pressure"].as_f64().unwrap() / (a["max_pressure_dimensionless"].as_f64().unwrap() * scale) - 1.0).abs() < 1e-12);
    assert!((a["min_film"].as_f64().unwrap() - 0.4 * 0.0001175).abs() < 1e-15);
    let b = prepare("bearing", json!({"geometry": dims, "operating": op, "load": {"force": force}, "grid": g})).unwrap();
    let c = prepare("bearing", json!({"geometry": dims, "operating": op, "load": {"sommerfeld_number": s}, "grid": g})).unwrap();
    let d = prepare("bearing", json!({"geometry": dims, "operating": op, "load": {"aligned_eccentricity_ratio": 0.6}, "grid": g})).unwrap();
    for r in [&b, &c, &d] {
        assert!((r["eccentricity_ratio"].as_f64().unwrap() - 0.6).abs() < 1e-5, "{r}");
        assert!((r["attitude_angle_deg"].as_f64().unwrap() - a["attitude_angle_deg"].as_f64().unwrap()).abs() < 1e-3);
    }
    // a fully fixed position reports the force in both directions
    let e = prepare("bearing", json!({"geometry": {"length_to_diameter": 1.25}, "load": {"eccentricity_ratio": 0.6, "attitude_angle_deg": 0.0}, "grid": g})).unwrap();
    assert!(e["load"]["across_load_dimensionless"].as_f64().unwrap().abs() > 0.1);
    assert!(e.get("max_pressure").is_none(), "no dimensions, no SI outputs");
}

#[test]
fn fields_only_when_asked_and_downsampled() {
    let r = prepare("bearing", base()).unwrap();
    assert!(r.get("field").is_none());
    let mut s = base();
    s["outputs"] = json!(["pressure_field"]);
    s["field_stride"] = json!({"circumferential": 4, "axial": 5});
    let r = prepare("bearing", s).unwrap();
    let f = &r["field"];
    assert!(f.get("film_dimensionless").is_none());
    let n = f["angle_deg"].as_array().unwrap().len();
    // 61 columns (0..=60 with the repeated 360° column) every 4th: 16; 31 rows every 5th: 7
    assert_eq!(n, 16 * 7);
    assert_eq!(f["pressure_dimensionless"].as_array().unwrap().len(), n);
    let pmax = f["pressure_dimensionless"].as_array().unwrap().iter().map(|v| v.as_f64().unwrap()).fold(0.0, f64::max);
    assert!(pmax <= r["max_pressure_dimensionless"].as_f64().unwrap() + 1e-12);
}

#[test]
fn l4_and_l27_arrays_run() {
    for (method, levels) in [("taguchi_l4", 2usize), ("taguchi_l27", 3)] {
        let f = if levels == 2 {
            json!({"order": [1, 2], "height": [0.2, 0.6], "length_fraction": [0.1, 0.3]})
        } else {
            json!({"order": [1, 2, 3], "height": [0.1, 0.4, 1.0], "length_fraction": [0.01, 0.2, 0.4]})
        };
        let spec = json!({"base": {"geometry": {"length_to_diameter": 1.25}, "load": {"aligned_eccentricity_ratio": 0.6},
            "misalignment": {"vertical": 0.3, "horizontal": 0.3}, "grid": {"circumferential": 61, "axial": 31}},
            "method": method, "factors": f, "continuous": {"enabled": false}});
        let r = prepare("bearing_optimisation", spec).unwrap();
        let runs = r["runs"].as_array().unwrap();
        assert_eq!(runs.len(), if levels == 2 { 4 } else { 27 });
        let best = r["best_run"].as_u64().unwrap() as usize;
        let top = runs.iter().map(|x| x["score"].as_f64().unwrap()).fold(0.0, f64::max);
        assert_eq!(runs[best - 1]["score"].as_f64().unwrap(), top);
        assert_eq!(r["main_effects"].as_array().unwrap().len(), 3 * levels);
        assert!(r.get("continuous").is_none());
    }
}

/// `supply: two_grooves` (issue 18): the kind solves Someya's two-axial-groove bearing (Table 1a,
/// L/D = 0.5, S = 0.580: ε = 0.477, φ = 51.01°; the physics-level comparison of every row and
/// its tolerances are in `journal_dynamics::someya_two_axial_groove_l_over_d_half`), and an even
/// circumferential node count, which would put the second groove between nodes, is refused.
#[test]
fn two_groove_supply_is_a_spec_choice() {
    let spec = json!({"geometry": {"length_to_diameter": 0.5}, "load": {"sommerfeld_number": 0.580},
        "supply": {"type": "two_grooves", "angle_deg": 90.0}, "grid": {"circumferential": 121, "axial": 41}});
    let r = prepare("bearing", spec.clone()).unwrap();
    let e = r["eccentricity_ratio"].as_f64().unwrap();
    let phi = r["attitude_angle_deg"].as_f64().unwrap();
    assert!((e - 0.477).abs() < 0.006, "ε = {e}");
    assert!((phi - 51.01).abs() < 4.0, "φ = {phi}");
    let mut s = spec;
    s["grid"]["circumferential"] = json!(120);
    let (code, paths) = errors("bearing", s, Limits::default());
    assert_eq!(code, "invalid_spec");
    assert_eq!(paths, vec!["/grid/circumferential".to_string()]);
}
