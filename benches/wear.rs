//! Wear benchmarks: run time of 1000 h of Archard wear with profile updates, and run time
//! against update interval against error. `cargo bench --bench wear` (release). Plain `Instant`
//! timing, best of N repetitions; "job" is the whole job as the service runs it (solve, result
//! serialisation to JSON, finite-number check; spec preparation excluded).

use serde_json::{json, Value};
use std::time::Instant;
use tribod::jobs::{registry, Limits};
use tribod::physics::Silent;

fn load(path: &str) -> Value {
    let text = std::fs::read_to_string(path).unwrap_or_else(|e| panic!("{path}: {e}"));
    serde_json::from_str::<Value>(&text).unwrap()["spec"].clone()
}

fn with(spec: &Value, f: impl Fn(&mut Value)) -> Value {
    let mut s = spec.clone();
    f(&mut s);
    s
}

/// Best-of-`reps` job time (ms) and the result.
fn job(spec: &Value, reps: usize) -> (f64, Value) {
    let k = registry::find("wear").unwrap();
    let limits = Limits { max_evaluations: 100_000, ..Limits::default() };
    let mut best = f64::INFINITY;
    let mut out = Value::Null;
    for _ in 0..reps {
        let prepared = k.prepare(spec, &limits).unwrap();
        let t = Instant::now();
        out = prepared.run(&Silent).unwrap();
        best = best.min(t.elapsed().as_secs_f64() * 1e3);
    }
    (best, out)
}

fn depth(out: &Value) -> Vec<f64> {
    out["series"]["wear_depth"].as_array().unwrap().iter().map(|x| x.as_f64().unwrap()).collect()
}

fn rel_err(a: &[f64], reference: &[f64]) -> f64 {
    let scale = reference.iter().copied().fold(0.0, f64::max);
    a.iter().zip(reference).map(|(x, y)| (x - y).abs()).fold(0.0, f64::max) / scale
}

fn main() {
    let flat = with(&load("examples/seed003_flat_archard.json"), |s| {
        s.as_object_mut().unwrap().remove("wear_limit");
    });
    let roller = with(&load("examples/seed000_roller_archard.json"), |s| {
        s.as_object_mut().unwrap().remove("wear_limit");
    });
    let irgashev = load("examples/seed004_irgashev.json");

    println!("### 1000 h, an update every 10 h, fidelity fast\n");
    println!("| case | angles | updates | job (ms) | max wear (µm) | aim |");
    println!("| --- | ---: | ---: | ---: | ---: | --- |");
    for (name, spec, reps) in [("seed 003 flat, asperity share", &flat, 5), ("seed 000 roller, slip, asperity share", &roller, 3)] {
        for angles in [360, 720] {
            let s = with(spec, |s| {
                s["hours"] = json!(1000.0);
                s["update_interval_hours"] = json!(10.0);
                s["angles"] = json!(angles);
            });
            let (ms, out) = job(&s, reps);
            let max = out["summary"]["max_wear_depth"].as_f64().unwrap() * 1e6;
            let aim = if ms <= 1000.0 { "≤ 1 s ✔" } else { "≤ 1 s ✘" };
            println!("| {name} | {angles} | {} | {ms:.1} | {max:.3} | {aim} |", out["updates"]);
        }
    }
    let (ms, _) = job(&irgashev, 20);
    println!("| seed 004 method (eq. 15, 22 rows) | 1440 | 0 | {ms:.2} | | |");

    println!("\n### Update interval against error (1000 h, 360 angles)\n");
    println!("Error: largest difference of the final wear-depth profile from the reference run (1/3200 of the");
    println!("running time per update), relative to its maximum.\n");
    println!("| case | interval (h) | updates run | job (ms) | max wear (µm) | error |");
    println!("| --- | ---: | ---: | ---: | ---: | ---: |");
    let cases = [
        ("seed 003 flat, full load share, K = 3e-9, preload 500 N", with(&flat, |s| {
            s["load_share"] = json!("full");
            s["wear_coefficient"] = json!({"dimensionless": 3e-9, "hardness": 7e9});
            s["load"]["spring_preload"] = json!(500.0);
        })),
        ("seed 003 flat, asperity share, K = 1e-7", flat.clone()),
        ("seed 000 roller, asperity share, K = 1e-6", roller.clone()),
    ];
    for (name, base) in cases {
        let base = with(&base, |s| {
            s["hours"] = json!(1000.0);
            s["angles"] = json!(360);
            s["snapshots"] = json!(0);
        });
        let (_, reference) = job(&with(&base, |s| s["update_interval_hours"] = json!(1000.0 / 3200.0)), 1);
        let reference = depth(&reference);
        for interval in [100.0, 50.0, 25.0, 10.0, 5.0, 2.5, 1.25] {
            let (ms, out) = job(&with(&base, |s| s["update_interval_hours"] = json!(interval)), 3);
            let err = rel_err(&depth(&out), &reference);
            let max = out["summary"]["max_wear_depth"].as_f64().unwrap() * 1e6;
            println!("| {name} | {interval} | {} | {ms:.1} | {max:.4} | {err:.2e} |", out["updates"]);
        }
    }
}
