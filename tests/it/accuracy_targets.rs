//! `ehl.accuracy` (issue 46 item 3): the spec's target chooses the grid and the thermal key
//! points from the measured ladders, the result reports the choice, and the chosen grid meets the
//! target against a grid-converged cycle.

use crate::in_process::{example, run, Failure};
use serde_json::{json, Value};

fn with(mut spec: Value, f: impl FnOnce(&mut Value)) -> Value {
    f(&mut spec);
    spec
}

fn spec_of(name: &str) -> Value {
    example(name)
}

fn settings(kind: &str, spec: &Value) -> Value {
    run(kind, spec).unwrap_or_else(|e| panic!("{e:?}"))["ehl_settings"].clone()
}

fn flat(angles: usize) -> Value {
    with(spec_of("seed003_cycloidal_flat"), |s| {
        s["fidelity"] = "accurate".into();
        s["angles"] = angles.into();
    })
}

fn roller(angles: usize) -> Value {
    with(spec_of("seed000_roller_accurate"), |s| {
        s["ehl"] = json!({});
        s["angles"] = angles.into();
    })
}

#[test]
fn the_default_accuracy_picks_the_cheapest_measured_grid_per_follower() {
    let flat_default = settings("cam_cycle", &flat(8));
    assert_eq!(flat_default["accuracy"], 0.01);
    assert_eq!(flat_default["nodes"], 208);
    assert_eq!(flat_default["nodes_from_accuracy"], true);
    assert_eq!(flat_default["measured_error"], 0.0083);
    assert_eq!(settings("cam_cycle", &roller(8))["nodes"], 288);
    // A looser target: a coarser grid; a tighter one: finer.
    let loose = settings("cam_cycle", &with(flat(8), |s| s["ehl"] = json!({"accuracy": 0.02})));
    assert_eq!(loose["nodes"], 160);
    let tight = settings("cam_cycle", &with(roller(8), |s| s["ehl"] = json!({"accuracy": 0.005})));
    assert_eq!(tight["nodes"], 384);
    // The spec's own grid wins, and has no measured error unless it is a rung.
    let own = settings("cam_cycle", &with(flat(8), |s| s["ehl"] = json!({"nodes": 100, "accuracy": 0.002})));
    assert_eq!((own["nodes"].as_u64(), own["nodes_from_accuracy"].as_bool()), (Some(100), Some(false)));
    assert!(own.get("measured_error").is_none(), "{own}");
    // A single point keeps 192 nodes unless the spec asks (the ladders were measured on cycles).
    let nose = with(example("seed001_nose_point"), |s| s["fidelity"] = "accurate".into());
    assert_eq!(settings("cam_point", &nose)["nodes"], 192);
    assert_eq!(settings("cam_point", &with(nose, |s| s["ehl"] = json!({"accuracy": 0.01})))["nodes"], 288);
    // `fast` runs no numerical film: nothing to report.
    let fast = run("cam_cycle", &with(flat(8), |s| s["fidelity"] = "fast".into())).unwrap();
    assert!(fast.get("ehl_settings").is_none());
}

#[test]
fn the_thermal_key_points_follow_the_accuracy() {
    let thermal = |accuracy: Option<f64>| {
        with(spec_of("seed000_thermal_steady"), |s| {
            s["angles"] = 8.into();
            if let Some(a) = accuracy {
                s["ehl"]["accuracy"] = a.into();
            }
        })
    };
    // Seed 000's thermal cycle at 8 angles: 1 % keeps 0.05 (0.94 % measured), 0.5 % needs 0.01.
    assert_eq!(settings("cam_cycle", &thermal(None))["carry_tolerance"], 0.05);
    assert_eq!(settings("cam_cycle", &thermal(Some(0.005)))["carry_tolerance"], 0.01);
    let every_angle = settings("cam_cycle", &thermal(Some(0.002)));
    assert!(every_angle.get("carry_tolerance").is_none(), "below the ladder: every angle in full: {every_angle}");
}

#[test]
fn an_accuracy_out_of_range_is_refused_naming_the_field() {
    match run("cam_cycle", &with(flat(8), |s| s["ehl"] = json!({"accuracy": 0.5}))) {
        Err(Failure::Spec(p)) => assert!(format!("{p:?}").contains("/ehl/accuracy"), "{p:?}"),
        other => panic!("expected a refused spec, got {:?}", other.map(|_| ())),
    }
}

/// The largest relative difference of a series between two results.
fn worst(a: &Value, b: &Value, column: &str) -> f64 {
    let col = |v: &Value| -> Vec<f64> { v["series"][column].as_array().unwrap().iter().map(|x| x.as_f64().unwrap()).collect() };
    col(a).iter().zip(col(b)).map(|(x, y)| ((x - y) / y).abs()).fold(0.0, f64::max)
}

#[test]
fn the_chosen_grid_meets_the_default_accuracy_against_the_converged_cycle() {
    // 24 angles of each reference cycle (the ladder was measured at 720): the default-accuracy
    // grid against Richardson of 767 + 384 nodes at a Newton tolerance of 1e-8.
    for (name, spec) in [("seed 003 flat", flat(24)), ("seed 000 roller", roller(24))] {
        let chosen = run("cam_cycle", &spec).unwrap();
        let reference = run("cam_cycle", &with(spec.clone(), |s| s["ehl"] = json!({"nodes": 767, "tolerance": 1e-8}))).unwrap();
        for column in ["film_central", "film_min"] {
            let e = worst(&chosen, &reference, column);
            println!("{name}: {column} worst {:.3} % on {} nodes", 100.0 * e, chosen["ehl_settings"]["nodes"]);
            assert!(e <= 0.01, "{name}: {column} off the converged cycle by {:.2} %", 100.0 * e);
        }
    }
}
