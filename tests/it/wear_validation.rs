//! Validation of the `wear` kind (issue 6 item 6): exact linear wear under constant pressure and
//! sliding, worn volume = k ∫ F ds, convergence in the update interval, seed 004 Tables 1–3 and
//! the Table 5 layout, typed stops with partial history; fidelity accurate/auto (issue 6 item 2
//! with issue 5's numerical film): full film, mixed lubrication against fast, grid convergence.
//! Run: `cargo test --test wear_validation`.

use serde_json::{json, Value};
use tribod::jobs::{registry, Limits};
use tribod::physics::cam::seed004;
use tribod::physics::wear::irgashev;

use crate::common::wear_spec;
use crate::in_process::{example, run, Failure};

fn col(v: &Value) -> Vec<f64> {
    v.as_array().unwrap_or_else(|| panic!("not an array: {v}")).iter().map(|x| x.as_f64().unwrap()).collect()
}

fn with(spec: &Value, f: impl Fn(&mut Value)) -> Value {
    let mut s = spec.clone();
    f(&mut s);
    s
}

/// A base-circle cam (lift table of zeros) under a flat follower, dry, constant spring force.
fn base_circle(hours: f64, update: f64) -> Value {
    let angles: Vec<f64> = (0..36).map(|i| 10.0 * i as f64).collect();
    wear_spec(json!({
        "cam": {"profile": {"type": "table", "base_radius": 0.02, "angle_deg": angles, "lift": vec![0.0; 36]}, "width": 0.01},
        "follower": {"type": "flat_faced"},
        "operation": {"speed_rpm": 1500.0},
        "load": {"type": "valve_train", "spring_preload": 500.0, "spring_stiffness": 0.0, "moving_mass": 0.0},
        "load_share": "full",
        "wear_coefficient": {"dimensional": 2e-18},
        "hours": hours,
        "update_interval_hours": update,
        "angles": 360
    }))
}

/// Constant pressure and sliding: every cam point loses `k (v_s/u_c) ∫p dx = k F/L` per
/// revolution (v_s = u_c on a circle under a flat face), so the depth is linear in time, the same
/// everywhere and independent of the update interval — exactly.
#[test]
fn constant_pressure_and_sliding_wear_linearly() {
    let (k, f, l, rpm) = (2e-18, 500.0, 0.01, 1500.0);
    for update in [500.0, 37.0] {
        let out = run("wear", &base_circle(500.0, update)).unwrap();
        assert_eq!(out["termination"]["reason"], "completed");
        let per_rev = k * f / l;
        let expect = per_rev * 500.0 * 60.0 * rpm;
        for d in col(&out["series"]["wear_depth"]) {
            assert!((d / expect - 1.0).abs() < 1e-11, "update {update}: {d} vs {expect}");
        }
        for h in out["history"].as_array().unwrap() {
            let t = h["hours"].as_f64().unwrap();
            let d = h["max_wear_depth"].as_f64().unwrap();
            assert!((d - per_rev * t * 60.0 * rpm).abs() <= 1e-11 * expect, "at {t} h: {d}");
        }
        // Volume: k F × sliding distance (2π r_b per revolution on the circle, radius shrinking by
        // the wear): k F Σ 2π (r_b − w) × revolutions — to first order k F 2π r_b N.
        let vol = out["summary"]["worn_volume"].as_f64().unwrap();
        let n = 500.0 * 60.0 * rpm;
        assert!((vol / (k * f * std::f64::consts::TAU * 0.02 * n) - 1.0).abs() < 1e-3, "{vol}");
        // The worn support function: the lift drops by the wear.
        let lift = col(&out["series"]["final_lift"]);
        assert!(lift.iter().all(|s| (s + expect).abs() < 1e-9 * expect.max(1e-12) + 1e-15));
    }
}

/// Worn volume = k ∫ F_worn |v_s| dt: the depth field integrated over the cam surface (cell
/// widths ρ_c Δθ from an independent `cam_cycle` run of the same pair) equals k times the
/// asperity-borne load times the sliding distance from that run's series.
#[test]
fn worn_volume_is_k_times_load_times_sliding_distance() {
    let spec = with(&example("seed003_flat_archard"), |s| {
        s["hours"] = json!(1.0);
        s["update_interval_hours"] = json!(1.0);
        s["wear_limit"] = Value::Null;
        s.as_object_mut().unwrap().remove("wear_limit");
    });
    let out = run("wear", &spec).unwrap();
    // The cycle a wear run wears is its spec's `cycle`, run as a cam_cycle job.
    let mut cycle = spec["cycle"].clone();
    cycle["outputs"] = json!(["kinematics", "loads", "contact", "film"]);
    let cyc = run("cam_cycle", &cycle).unwrap();
    let s = &cyc["series"];
    let (kappa, load, vs, share) = (col(&s["cam_curvature"]), col(&s["contact_load"]), col(&s["sliding_velocity"]), col(&s["asperity_load_fraction"]));
    let n = kappa.len();
    let omega = 3000.0 * std::f64::consts::PI / 30.0;
    let (dtheta, dt) = (std::f64::consts::TAU / n as f64, std::f64::consts::TAU / n as f64 / omega);
    let revs = 3600.0 * 3000.0 / 60.0;
    let k = 1e-7 / 7e9;
    let archard: f64 = (0..n).map(|i| k * share[i] * load[i] * vs[i].abs() * dt).sum::<f64>() * revs;
    let depth = col(&out["series"]["wear_depth"]);
    let integrated: f64 = (0..n).map(|i| depth[i] * dtheta / kappa[i]).sum::<f64>() * 0.012;
    assert!(archard > 0.0);
    assert!((integrated / archard - 1.0).abs() < 1e-9, "{integrated} vs {archard}");
    let reported = out["summary"]["worn_volume"].as_f64().unwrap();
    assert!((reported / archard - 1.0).abs() < 1e-9);
    // The flat face loses the same volume (same k): its depth field integrated over the face.
    let face = &out["follower_face"];
    let (pos, fd) = (col(&face["position"]), col(&face["wear_depth"]));
    let h = pos[1] - pos[0];
    let face_vol: f64 = fd.iter().sum::<f64>() * h * 0.012;
    assert!((face_vol / archard - 1.0).abs() < 1e-6, "{face_vol} vs {archard}");
}

/// Forward Euler in running time: the final wear converges at first order as the update
/// interval shrinks (reference: 1600 updates; the stability cut of the interval, about 59
/// updates here, does not bind below).
#[test]
fn wear_converges_as_the_update_interval_shrinks() {
    let spec = with(&example("seed003_flat_archard"), |s| {
        s["cycle"]["load"]["spring_preload"] = json!(500.0);
        s["load_share"] = json!("full");
        s["wear_coefficient"] = json!({"dimensionless": 3e-9, "hardness": 7e9});
        s["hours"] = json!(1000.0);
        s["cycle"]["angles"] = json!(360);
        s["snapshots"] = json!(0);
        s.as_object_mut().unwrap().remove("wear_limit");
    });
    let depth_at = |updates: f64| {
        let out = run("wear", &with(&spec, |s| s["update_interval_hours"] = json!(1000.0 / updates))).unwrap();
        assert_eq!(out["termination"]["reason"], "completed", "{}", out["termination"]);
        assert_eq!(out["updates"].as_u64().unwrap() as f64, updates);
        col(&out["series"]["wear_depth"])
    };
    let reference = depth_at(1600.0);
    let scale = reference.iter().copied().fold(0.0, f64::max);
    let err = |d: &[f64]| d.iter().zip(&reference).map(|(a, b)| (a - b).abs()).fold(0.0, f64::max) / scale;
    let errors: Vec<f64> = [100.0, 200.0, 400.0].iter().map(|&u| err(&depth_at(u))).collect();
    eprintln!("relative max-norm errors for 100, 200, 400 updates: {errors:?}");
    assert!(errors[0] > 1e-5 && errors[0] < 1e-3, "{errors:?}");
    // First order against a reference at 1/1600: the ideal ratios are (1/200 − 1/1600)/(1/100 −
    // 1/1600) = 0.47 and 0.43.
    for w in errors.windows(2) {
        let r = w[1] / w[0];
        assert!(r > 0.3 && r < 0.6, "not first order: {errors:?}");
    }
}

// ------------------------------------------------------------------ seed 004

fn rows(out: &Value) -> Vec<Value> {
    out["rows"].as_array().unwrap().clone()
}

fn f(v: &Value, key: &str) -> f64 {
    v[key].as_f64().unwrap_or_else(|| panic!("no {key} in {v}"))
}

/// Tables 1–3 through the kind: reduced radii (Table 1, 0.03 mm: the paper prints 14.20 for
/// 14.22), profile lengths by eq. 1 as printed (Table 2, 1e-3 mm; 53.440 printed for 53.442),
/// contact width and area (Table 3, within 1 %).
#[test]
fn seed004_tables_1_to_3_through_the_kind() {
    let out = run("wear", &example("seed004_irgashev")).unwrap();
    let r = rows(&out);
    assert_eq!(r.len(), 22);
    let table3 = [
        (264.0, 0.508, 0.262),
        (308.0, 0.709, 0.508),
        (352.0, 0.741, 0.554),
        (396.0, 0.771, 0.600),
        (440.0, 0.799, 0.643),
        (484.0, 0.825, 0.685),
        (528.0, 0.849, 0.727),
        (572.0, 0.872, 0.766),
        (616.0, 0.894, 0.805),
        (660.0, 0.915, 0.842),
        (704.0, 0.764, 0.587),
    ];
    // Rows 0..=10 are the rising half; the falling half mirrors it.
    for (i, (force, width, area)) in table3.iter().enumerate() {
        for row in [&r[i], &r[21 - i]] {
            assert!((f(row, "spring_force") - force).abs() < 1e-9);
            let w = f(row, "contact_width") * 1e3;
            let a = f(row, "contact_area") * 1e6;
            assert!((w / width - 1.0).abs() < 0.01, "F = {force}: width {w} vs {width}");
            assert!((a / area - 1.0).abs() < 0.01, "F = {force}: area {a} vs {area}");
        }
    }
    let table1 = [(1, 14.20), (2, 32.97), (3, 18.00), (4, 18.00), (5, 32.97), (6, 14.20)];
    let table2 = [(1, 13.856), (2, 53.442), (3, 0.219), (4, 0.219), (5, 53.442), (6, 13.856)];
    for ((part, rho), (_, len)) in table1.iter().zip(table2) {
        let row = r.iter().find(|x| x["part"] == *part).unwrap();
        assert!((f(row, "reduced_radius") * 1e3 - rho).abs() < 0.03, "part {part}");
        assert!((f(row, "profile_length_as_printed") * 1e3 - len).abs() < 1e-3, "part {part}");
        // The true length is π times eq. 1's.
        assert!((f(row, "profile_length") / f(row, "profile_length_as_printed") - std::f64::consts::PI).abs() < 1e-12);
    }
    // Table 2's total: 135.028 mm (their rounded parts; 135.032 unrounded).
    let total: f64 = [1, 2, 3, 4, 5, 6]
        .iter()
        .map(|p| f(r.iter().find(|x| x["part"] == *p).unwrap(), "profile_length_as_printed") * 1e3)
        .sum();
    assert!((total - 135.028).abs() < 0.006, "{total}");
    // Exhaust cam (Table 2): 113.45° × 21.5 mm → 13.550 (13.551); 65° × 117 mm → 42.25, not the
    // printed 42.752; the printed nose 0.272 mm follows from 31.5 mm, not the listed 56.18 mm.
    assert!((seed004::arc_length_as_printed(113.45, 21.5) - 13.551).abs() < 1e-3);
    assert!((seed004::arc_length_as_printed(65.0, 117.0) - 42.25).abs() < 1e-3);
    assert!((seed004::arc_length_as_printed(1.55, 31.5) - 0.272).abs() < 1e-3);
    // Exhaust part 2 width (Table 3, 0.694 mm at 308 N) from ρ = 117·42/159.
    let w = seed004::contact_width_mm(308.0, seed004::reduced_radius(117.0, 42.0), 2.1e5, 0.3);
    assert!((w / 0.694 - 1.0).abs() < 0.01, "{w}");
}

/// Table 5's withheld column: eq. 15 per row, with the inputs listed after it, recomputed here
/// from the printed formula; the layout of Table 5 (current angles, forces) is the paper's.
#[test]
fn seed004_table5_wear_rates() {
    let out = run("wear", &example("seed004_irgashev")).unwrap();
    let r = rows(&out);
    for row in &r {
        let (p, b, d) = (f(row, "spring_force"), f(row, "contact_width") * 1e3, f(row, "slip"));
        let eq15 = 6.376 * p * p * 4.23e-6 * (1.0 + d) * 20.0 / (b.powi(3) * 1300.0 * 3.0 * 24.0);
        assert!((f(row, "wear_rate_mm_per_h") / eq15 - 1.0).abs() < 1e-12, "{row}");
        // The eq. 6–14 chain: 6.3766 P²θ δ l n/(B² c σ_t F n_p), l = eq. 1's length.
        let (area, l) = (f(row, "contact_area") * 1e6, f(row, "profile_length_as_printed") * 1e3);
        let chain = 0.65 * 0.0389 / 14.275 * 3600.0 * p * p * 4.23e-6 * d * l * 20.0 / (b * b * 3.0 * 1300.0 * area * 24.0);
        assert!((f(row, "chain_wear_rate_mm_per_h") / chain - 1.0).abs() < 1e-12);
        assert!(f(row, "archard_wear_rate_mm_per_h") > 0.0);
    }
    // Table 5's current angles: 6.97° steps over part 2, back down over part 5.
    let angles: Vec<f64> = r.iter().map(|x| f(x, "angle_deg")).collect();
    assert!((angles[1] - 6.97).abs() < 0.01 && (angles[9] - 62.75).abs() < 0.03);
    assert!((angles[12] - 62.75).abs() < 0.03 && (angles[20] - 6.97).abs() < 0.01);
    // The nose rows wear fastest (largest force, largest slip); the series and the summary agree.
    let (imax, _) = r.iter().enumerate().fold((0, 0.0), |b, (i, x)| if f(x, "wear_rate_mm_per_h") > b.1 { (i, f(x, "wear_rate_mm_per_h")) } else { b });
    assert!(r[imax]["role"] == "nose");
    let sm = &out["summary"];
    assert!((f(sm, "max_wear_rate") * 3600.0 * 1e3 / f(&r[imax], "wear_rate_mm_per_h") - 1.0).abs() < 1e-12);
    // The limit (0.5 mm) is reached at 0.5/γ_max hours and the run stops there.
    assert_eq!(out["termination"]["reason"], "wear_limit");
    let t = f(sm, "hours_to_limit");
    assert!((t * f(&r[imax], "wear_rate_mm_per_h") - 0.5).abs() < 1e-12);
}

/// Table 5's printed inputs (force, width; slip of Table 4; the inputs after eq. 15) through
/// eq. 15 — the paper's rows — against the kind's `irgashev` rows, to 0.1 %: with the paper's
/// width reading (eq. 2 at 215 GPa, rounded to 0.001 mm, what the example asks for) every row
/// agrees to 1e-12; the material reading at 210 GPa leaves the widths 0.80 % wide and the rates
/// 2.3–2.5 % low — the ~2 % of issue 17 (regression test named after it).
#[test]
fn seed004_table5_rows_from_printed_inputs_to_0_1_percent() {
    // (force N, printed width mm, part) in Table 5's order.
    let table5 = [
        (264.0, 0.508, 1),
        (308.0, 0.709, 2),
        (352.0, 0.741, 2),
        (396.0, 0.771, 2),
        (440.0, 0.799, 2),
        (484.0, 0.825, 2),
        (528.0, 0.849, 2),
        (572.0, 0.872, 2),
        (616.0, 0.894, 2),
        (660.0, 0.915, 2),
        (704.0, 0.764, 3),
        (704.0, 0.764, 4),
        (660.0, 0.915, 5),
        (616.0, 0.894, 5),
        (572.0, 0.872, 5),
        (528.0, 0.849, 5),
        (484.0, 0.825, 5),
        (440.0, 0.799, 5),
        (396.0, 0.771, 5),
        (352.0, 0.741, 5),
        (308.0, 0.709, 5),
        (264.0, 0.508, 6),
    ];
    let slip = [0.0111, 0.1211, 0.2360, 0.2360, 0.1285, 0.113];
    let paper = |p: f64, b: f64, d: f64| 6.376 * p * p * 4.23e-6 * (1.0 + d) * 20.0 / (b.powi(3) * 1300.0 * 3.0 * 24.0);
    let spec = example("seed004_irgashev");
    assert_eq!(spec["irgashev"]["width_reading"], "paper");
    let r = rows(&run("wear", &spec).unwrap());
    let material = rows(&run("wear", &with(&spec, |s| s["irgashev"]["width_reading"] = json!("material"))).unwrap());
    let mut worst = 0.0f64;
    for (k, (p, b, part)) in table5.iter().enumerate() {
        let expect = paper(*p, *b, slip[part - 1]);
        assert_eq!(r[k]["part"], *part);
        assert!((f(&r[k], "spring_force") - p).abs() < 1e-9);
        assert!((f(&r[k], "contact_width") * 1e3 - b).abs() < 1e-9, "row {k}: width {}", f(&r[k], "contact_width"));
        let got = f(&r[k], "wear_rate_mm_per_h");
        assert!((got / expect - 1.0).abs() < 1e-3, "row {k}: {got} vs {expect}");
        assert!((got / expect - 1.0).abs() < 1e-12, "row {k}: {got} vs {expect}");
        let off = f(&material[k], "wear_rate_mm_per_h") / expect - 1.0;
        assert!((-0.026..-0.021).contains(&off), "row {k}: material reading {off}");
        worst = worst.max(off.abs());
    }
    eprintln!("material reading (210 GPa, unrounded): worst {:.2} % off Table 5's printed inputs", 100.0 * worst);
    // Unrounded at 215 GPa the rates stay within 0.17 % (the widths' rounding, cubed).
    let i = irgashev::paper_intake();
    for (p, b, part) in table5 {
        let rho = seed004::reduced_radius([21.5, 153.3, 31.5, 31.5, 153.3, 21.5][part - 1], 42.0);
        let w = seed004::contact_width_mm(p, rho, irgashev::PAPER_WIDTH_MODULUS_MPA, 0.3);
        assert!((w - b).abs() <= 5e-4 + 1e-12, "{p} N: {w} vs {b}");
        let un = irgashev::eq15(p, w, slip[part - 1], &i) / paper(p, b, slip[part - 1]) - 1.0;
        assert!(un.abs() < 1.8e-3, "{p} N: {un}");
    }
}

// ------------------------------------------------------------------ stops and errors

/// A worn profile the follower cannot run on ends the run with the typed reason and everything
/// up to the last valid profile (seed 003's cam at its spring preload is close to separating at
/// 156°; the nose wear changes the follower's deceleration).
#[test]
fn a_failing_profile_returns_the_partial_history() {
    let spec = with(&example("seed003_flat_archard"), |s| {
        s["load_share"] = json!("full");
        s["wear_coefficient"] = json!({"dimensionless": 3e-8, "hardness": 7e9});
        s["hours"] = json!(1000.0);
        s["update_interval_hours"] = json!(10.0);
        s.as_object_mut().unwrap().remove("wear_limit");
    });
    let out = run("wear", &spec).unwrap();
    let term = &out["termination"];
    assert_eq!(term["reason"], "follower_separation", "{term}");
    assert_eq!(term["code"], "follower_separation");
    let hours = out["hours"].as_f64().unwrap();
    let at = term["at_hours"].as_f64().unwrap();
    assert!(hours > 0.0 && hours < 1000.0 && at > hours && at <= hours + 10.0 + 1e-9, "{hours} {at}");
    let history = out["history"].as_array().unwrap();
    assert_eq!(history.len(), out["updates"].as_u64().unwrap() as usize + 1);
    assert!((history.last().unwrap()["hours"].as_f64().unwrap() - hours).abs() < 1e-9);
    let depth = col(&out["series"]["wear_depth"]);
    assert!(depth.iter().all(|d| d.is_finite() && *d >= 0.0));
    assert!((depth.iter().copied().fold(0.0, f64::max) - out["summary"]["max_wear_depth"].as_f64().unwrap()).abs() < 1e-18);
}

#[test]
fn invalid_specs_name_their_fields() {
    let paths = |spec: &Value| match run("wear", spec) {
        Err(Failure::Spec(p)) => p.errors.iter().map(|e| e.path.clone()).collect::<Vec<_>>(),
        other => panic!("expected a spec error, got {other:?}"),
    };
    let base = example("seed003_flat_archard");
    assert!(paths(&with(&base, |s| { s.as_object_mut().unwrap().remove("wear_coefficient"); })).contains(&"/wear_coefficient".to_string()));
    assert!(paths(&with(&base, |s| s["cycle"]["operation"]["startup"] = json!({}))).contains(&"/cycle/operation/startup".to_string()));
    // The nested cycle is validated as a cam_cycle spec, at its paths under /cycle; what its
    // cycles compute is the wear model's choice.
    assert!(paths(&with(&base, |s| s["cycle"]["operation"]["speed_rpm"] = json!(-1.0))).contains(&"/cycle/operation/speed_rpm".to_string()));
    assert!(paths(&with(&base, |s| s["cycle"]["outputs"] = json!(["kinematics"]))).contains(&"/cycle/outputs".to_string()));
    assert!(paths(&with(&base, |s| s["cycle"]["profile_angles_deg"] = json!([90.0]))).contains(&"/cycle/profile_angles_deg".to_string()));
    assert!(paths(&with(&base, |s| s["cycles"] = json!(1e6))).contains(&"/hours".to_string()));
    assert!(paths(&with(&base, |s| s["wear_coefficient"] = json!({"dimensionless": 1e-7}))).contains(&"/wear_coefficient".to_string()));
    assert!(paths(&with(&base, |s| { s["cycle"]["cam"]["roughness_rq"] = json!(0.0); s["cycle"]["follower"]["roughness_rq"] = json!(0.0); })).contains(&"/load_share".to_string()));
    assert!(paths(&with(&base, |s| { s["cycle"].as_object_mut().unwrap().remove("lubricant"); })).contains(&"/load_share".to_string()));
    // Too many updates for the server's evaluation limit: limit_exceeded at the interval.
    match run("wear", &with(&base, |s| s["update_interval_hours"] = json!(0.01))) {
        Err(Failure::Spec(p)) => {
            assert_eq!(p.code, "limit_exceeded");
            assert_eq!(p.errors[0].path, "/update_interval_hours");
        }
        other => panic!("{other:?}"),
    }
    let ir = example("seed004_irgashev");
    assert!(paths(&with(&ir, |s| s["irgashev"]["slip"] = json!([0.1, 0.1]))).contains(&"/irgashev/slip".to_string()));
    assert!(paths(&with(&ir, |s| s["cycle"]["follower"] = json!({"type": "flat_faced"}))).contains(&"/cycle/follower".to_string()));
}

/// Smooth surfaces under a thick film do not wear in the asperity model; dry contact wears the
/// whole load.
#[test]
fn roller_wears_only_where_it_slides() {
    let out = run("wear", &with(&example("seed000_roller_archard"), |s| {
        s["hours"] = json!(100.0);
        s["update_interval_hours"] = json!(50.0);
        s["cycle"]["angles"] = json!(360);
    }))
    .unwrap();
    let depth = col(&out["series"]["wear_depth"]);
    let vs = col(&out["series"]["sliding_velocity"]);
    // Base circle (0–50°): the roller sticks (no slip), no wear there.
    for i in 0..50 {
        assert!(vs[i].abs() < 1e-9 && depth[i] == 0.0, "{i}: {} {}", vs[i], depth[i]);
    }
    assert!(depth.iter().copied().fold(0.0, f64::max) > 0.0);
    assert!(out["summary"]["roller_wear_depth"].as_f64().unwrap() > 0.0);
}

/// The kind's own example runs to completion, and every table of the kind renders as CSV.
#[test]
fn example_runs_and_tables_render_as_csv() {
    let k = registry::find("wear").unwrap();
    let out = run("wear", &k.example()).unwrap();
    assert_eq!(out["termination"]["reason"], "completed", "{}", out["termination"]);
    for table in ["series", "history", "follower_face"] {
        let csv = tribod::jobs::table::to_csv(&out[table], &|_| None).unwrap_or_else(|e| panic!("{table}: {e}"));
        assert!(csv.lines().count() > 2, "{table}");
    }
    let ir = run("wear", &example("seed004_irgashev")).unwrap();
    let csv = tribod::jobs::table::to_csv(&ir["rows"], &|_| None).unwrap();
    assert_eq!(csv.lines().count(), 23);
    assert!(csv.starts_with("part,step,role,"));
    assert_eq!(k.tables(), &["series", "rows", "history", "follower_face"]);
}

// ---------------------------------------------------------------- fidelity accurate / auto

fn num(v: &Value) -> f64 {
    v.as_f64().unwrap_or_else(|| panic!("not a number: {v}"))
}

fn max(v: &[f64]) -> f64 {
    v.iter().copied().fold(f64::NEG_INFINITY, f64::max)
}

/// A gentle cam (no entrainment reversal under the flat face: r_b + s + 2s'' > 0) with a thick
/// film: λ = h_min/σ ≈ 3.2 at both fidelities.
fn gentle(fidelity: &str, share: &str) -> Value {
    wear_spec(json!({
        "cam": {"profile": {"type": "rise_return", "base_radius": 0.02, "lift": 0.002, "rise_start_deg": 60.0,
                            "rise_deg": 120.0, "return_deg": 120.0, "law": "cycloidal"},
                "width": 0.012, "roughness_rq": 2e-7},
        "follower": {"type": "flat_faced", "roughness_rq": 2e-7},
        "operation": {"speed_rpm": 3000.0},
        "load": {"type": "valve_train", "spring_preload": 300.0, "spring_stiffness": 20000.0, "moving_mass": 0.1},
        "lubricant": {"viscosity": 0.05, "pressure_viscosity": 2.2e-8},
        "load_share": share,
        "wear_coefficient": {"dimensionless": 1e-7, "hardness": 7e9},
        "hours": 10.0,
        "update_interval_hours": 10.0,
        "angles": 180,
        "snapshots": 0,
        "fidelity": fidelity,
        "ehl": {"nodes": 128}
    }))
}

/// Full film (λ ≈ 3.2): the asperity share, and with it the wear, is negligible at every fidelity
/// (below 1e-3 of the wear of the whole load). With the whole load wearing (`full`), the worn
/// volume `k ∫ F |v_s| dt` does not depend on the pressure distribution: the EHL band of
/// `accurate` wears exactly the volume of the Hertz band of `fast`, only spread differently (the
/// peak depth moves by < 1 %).
#[test]
fn full_film_wears_nothing_at_any_fidelity_and_full_share_volume_is_model_independent() {
    let full_fast = run("wear", &gentle("fast", "full")).unwrap();
    let full_depth = num(&full_fast["summary"]["max_wear_depth"]);
    let full_volume = num(&full_fast["summary"]["worn_volume"]);
    assert!(full_depth > 0.0);
    for fid in ["fast", "accurate", "auto"] {
        let out = run("wear", &gentle(fid, "asperity")).unwrap();
        let share = max(&col(&out["series"]["worn_load_share"]));
        let lambda = col(&out["series"]["initial_film_min"]).iter().copied().fold(f64::INFINITY, f64::min) / (2.0f64.sqrt() * 2e-7);
        let depth = num(&out["summary"]["max_wear_depth"]);
        eprintln!("{fid}: λ_min {lambda:.2}, largest asperity share {share:.2e}, wear {:.2e} of the full-share wear", depth / full_depth);
        assert!(lambda > 3.0, "{fid}: λ = {lambda}");
        assert!(share < 1e-3, "{fid}: share {share}");
        assert!(depth < 1e-3 * full_depth, "{fid}: {depth} vs {full_depth}");
        if fid != "fast" {
            assert_eq!(out["summary"]["fidelity_used"]["numerical_mixed"], json!(2 * 180), "{fid}: {}", out["summary"]["fidelity_used"]);
            let full = run("wear", &gentle(fid, "full")).unwrap();
            let v = num(&full["summary"]["worn_volume"]);
            assert!((v / full_volume - 1.0).abs() < 1e-9, "{fid}: {v} vs {full_volume}");
            let d = num(&full["summary"]["max_wear_depth"]);
            eprintln!("{fid}, full share: volume {:.3e} (fast {:.3e}), peak depth {:+.3} % against fast", v, full_volume, 100.0 * (d / full_depth - 1.0));
            assert!((d / full_depth - 1.0).abs() < 0.01, "{fid}: {d} vs {full_depth}");
        }
    }
}

/// The seed 003 pair for one update at fidelity `fidelity`, 180 angles, `nodes` EHL nodes.
fn flat_mixed(fidelity: &str, nodes: usize) -> Value {
    with(&example("seed003_flat_archard"), |s| {
        s.as_object_mut().unwrap().remove("wear_limit");
        s["hours"] = json!(10.0);
        s["update_interval_hours"] = json!(10.0);
        s["cycle"]["angles"] = json!(180);
        s["snapshots"] = json!(0);
        s["cycle"]["fidelity"] = json!(fidelity);
        s["cycle"]["ehl"] = json!({"nodes": nodes});
    })
}

/// Mixed lubrication (seed 003 flat follower, λ ≈ 0.6–1.5): accurate wears ≈ 1.7× the volume of
/// fast (2.2× before issue 15, when both evaluated Greenwood–Tripp after a smooth solution; now
/// both share the load inside their solutions with the mean-gap law of
/// `Roughness::load_sharing_pressure`). Measured on the base circle (where a third of the cycle's
/// wear happens at fast), the asperity share is 5.7× fast's, for two reasons that multiply:
/// 1. the film: seed 003's closed form is 23 % thicker than the numerical central film there
///    (488 vs 396 nm), and the Greenwood–Tripp pressure falls steeply with the film (F_5/2 at
///    λ ≈ 1.8): the load-sharing law at the numerical central film over the Hertz area already
///    gives 3.7× fast's share;
/// 2. the pressure/film distribution: the numerical film is thinnest at the exit constriction
///    (337 nm, 15 % below its centre), where the asperity pressure peaks; the node-by-node share
///    is another 1.56× the uniform one.
/// On the base circle (uniform cells) the wear depth is exactly `k (v_s/u_c) f_a w` per pass
/// whatever the band's shape, so the depth ratio equals the share ratio there (to 1e-5: the
/// numerical film varies by ~1e-7 between base-circle angles, a transient settling). Near the
/// entrainment reversals (≈ 170°, 190°) the closed form collapses to a few nm and its share jumps,
/// while the numerical squeeze film does not collapse: there fast's peak depth is the larger one.
#[test]
fn mixed_lubrication_accurate_against_fast_is_explained() {
    let fast = run("wear", &flat_mixed("fast", 192)).unwrap();
    let acc = run("wear", &flat_mixed("accurate", 192)).unwrap();
    let ratio = num(&acc["summary"]["worn_volume"]) / num(&fast["summary"]["worn_volume"]);
    let (sf, sa) = (col(&fast["series"]["worn_load_share"])[0], col(&acc["series"]["worn_load_share"])[0]);
    let (df, da) = (col(&fast["series"]["wear_depth"])[0], col(&acc["series"]["wear_depth"])[0]);
    eprintln!(
        "volume accurate/fast {ratio:.3}; base circle share {sa:.3e}/{sf:.3e} = {:.3}, depth ratio {:.3}; peak depth {:.3e} (fast {:.3e})",
        sa / sf,
        da / df,
        num(&acc["summary"]["max_wear_depth"]),
        num(&fast["summary"]["max_wear_depth"])
    );
    assert!((1.5..2.0).contains(&ratio), "{ratio}");
    assert!(((da / df) / (sa / sf) - 1.0).abs() < 1e-5, "{} vs {}", da / df, sa / sf);
    assert!(num(&fast["summary"]["max_wear_depth"]) > num(&acc["summary"]["max_wear_depth"]));
    // The decomposition, from cam_cycle at the same settings (angle 0: base circle).
    let cycle = |fid: &str| {
        let mut s = flat_mixed(fid, 192)["cycle"].clone();
        s["outputs"] = json!(["kinematics", "loads", "contact", "film"]);
        run("cam_cycle", &s).unwrap()
    };
    let (cf, ca) = (cycle("fast"), cycle("accurate"));
    let sigma = (2e-7f64.powi(2) + 1e-7f64.powi(2)).sqrt();
    let rough = tribod::jobs::kinds::common::AsperitySpec::default().roughness(sigma);
    let es = num(&ca["contact_modulus"]);
    let at0 = |o: &Value, key: &str| col(&o["series"][key])[0];
    let uniform = |o: &Value| rough.load_sharing_pressure(at0(o, "film_central"), es).0 * 2.0 * at0(o, "hertz_half_width") * 0.012 / at0(o, "contact_load");
    let (hc_f, hc_a, hmin_a) = (at0(&cf, "film_central"), at0(&ca, "film_central"), at0(&ca, "film_min"));
    eprintln!(
        "base circle: h_c closed form {hc_f:.3e}, numerical {hc_a:.3e} (min {hmin_a:.3e}); share fast {sf:.3e}, GT at numerical h_c {:.3e}, node by node {sa:.3e}",
        uniform(&ca)
    );
    // Fast's share is Greenwood–Tripp at its central film over the Hertz area (to 1e-5: the
    // wear result's share is that of the worn profile after 10 h, the cycle's of the unworn one).
    assert!((uniform(&cf) / sf - 1.0).abs() < 1e-5, "{} vs {sf}", uniform(&cf));
    // 1. the closed-form film is thicker; 2. the local film (exit constriction) raises the share.
    assert!(hc_f / hc_a > 1.15 && hmin_a < 0.9 * hc_a, "{hc_f} {hc_a} {hmin_a}");
    assert!(uniform(&ca) > 2.5 * sf && sa > 1.2 * uniform(&ca), "{sf} {} {sa}", uniform(&ca));
}

/// The accurate wear converges at second order in the EHL grid: worn volume and base-circle share
/// on 96, 192 and 384 nodes; the Richardson estimate of the error at 384 nodes is ≈ 1 %.
#[test]
fn accurate_wear_converges_with_the_ehl_grid() {
    let runs: Vec<(f64, f64)> = [96, 192, 384]
        .iter()
        .map(|&n| {
            let out = run("wear", &flat_mixed("accurate", n)).unwrap();
            (num(&out["summary"]["worn_volume"]), col(&out["series"]["worn_load_share"])[0])
        })
        .collect();
    for (name, pick) in [("worn volume", 0), ("base-circle share", 1)] {
        let v: Vec<f64> = runs.iter().map(|r| if pick == 0 { r.0 } else { r.1 }).collect();
        let (d1, d2) = (v[0] - v[1], v[1] - v[2]);
        let rate = d1 / d2;
        let limit = v[2] - d2 / (rate - 1.0);
        let err = (v[2] / limit - 1.0).abs();
        eprintln!("{name}: {:.5e} {:.5e} {:.5e}; ratio of differences {rate:.2} (order {:.2}); error at 384 nodes {:.2} %", v[0], v[1], v[2], rate.log2(), 100.0 * err);
        assert!((3.0..6.0).contains(&rate), "{name}: {rate}");
        assert!(err < 0.02, "{name}: {err}");
    }
}

/// Accurate/auto specs: a lubricant is needed, seed 004's method has no film, and the numerical
/// work is bounded by the server's evaluation limit (limit_exceeded at `/ehl/nodes`).
#[test]
fn accurate_specs_are_checked_and_bounded() {
    let paths = |spec: &Value| match run("wear", spec) {
        Err(Failure::Spec(p)) => p.errors.iter().map(|e| e.path.clone()).collect::<Vec<_>>(),
        other => panic!("expected a spec error, got {other:?}"),
    };
    let base = flat_mixed("accurate", 128);
    assert!(paths(&with(&base, |s| {
        s["cycle"].as_object_mut().unwrap().remove("lubricant");
        s["load_share"] = json!("full");
    }))
    .contains(&"/cycle/fidelity".to_string()));
    assert!(paths(&with(&example("seed004_irgashev"), |s| s["cycle"]["fidelity"] = json!("auto"))).contains(&"/cycle/fidelity".to_string()));
    assert!(paths(&with(&base, |s| s["cycle"]["ehl"]["nodes"] = json!(8))).contains(&"/cycle/ehl/nodes".to_string()));
    // 720 angles × (2 × 100 + 1) cycles × 192 nodes = 201 standard cycles: within the default
    // evaluation budget (the work model, ≈ 95 s for the 101 planned cycles, is a separate limit),
    // refused by a server allowing 200 evaluations.
    let big = with(&base, |s| {
        s["hours"] = json!(1000.0);
        s["cycle"]["angles"] = json!(720);
        s["cycle"]["ehl"]["nodes"] = json!(192);
    });
    let k = registry::find("wear").unwrap();
    let unlimited_time = Limits { max_job_seconds: f64::INFINITY, ..Limits::default() };
    assert!(k.prepare(&big, &unlimited_time).is_ok());
    let p = k.prepare(&big, &Limits::default()).unwrap_err();
    assert_eq!(p.code, "limit_exceeded");
    assert!(p.errors[0].message.contains("of solver time"), "{p:?}");
    let p = k.prepare(&big, &Limits { max_evaluations: 200, ..unlimited_time }).unwrap_err();
    assert_eq!(p.code, "limit_exceeded");
    assert_eq!(p.errors[0].path, "/cycle/ehl/nodes", "{p:?}");
    assert!(p.errors[0].message.contains("is 201"), "{}", p.errors[0].message);
}
