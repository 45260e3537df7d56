//! Wear benchmarks: run time of 1000 h of Archard wear with profile updates, and run time
//! against update interval against error. `cargo bench --bench wear` (release). Plain `Instant`
//! timing, best of N repetitions; "job" is the whole job as the service runs it (solve, result
//! serialisation to JSON, finite-number check; spec preparation excluded).
//! `cargo bench --bench wear -- fidelity` runs only the fidelity table (accurate/auto against
//! fast).

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
    let only_fidelity = std::env::args().any(|a| a == "fidelity");
    if only_fidelity {
        fidelity(&flat, &roller);
        return;
    }

    println!("### 1000 h, an update every 10 h, fidelity fast\n");
    println!("| case | angles | updates | job (ms) | max wear (µm) | aim |");
    println!("| --- | ---: | ---: | ---: | ---: | --- |");
    for (name, spec, reps) in [("seed 003 flat, asperity share", &flat, 5), ("seed 000 roller, slip, asperity share", &roller, 3)] {
        for angles in [360, 720] {
            let s = with(spec, |s| {
                s["hours"] = json!(1000.0);
                s["update_interval_hours"] = json!(10.0);
                s["cycle"]["angles"] = json!(angles);
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
            s["cycle"]["load"]["spring_preload"] = json!(500.0);
        })),
        ("seed 003 flat, asperity share, K = 1e-7", flat.clone()),
        ("seed 000 roller, asperity share, K = 1e-6", roller.clone()),
    ];
    for (name, base) in cases {
        let base = with(&base, |s| {
            s["hours"] = json!(1000.0);
            s["cycle"]["angles"] = json!(360);
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

fn summary(out: &Value, key: &str) -> f64 {
    out["summary"][key].as_f64().unwrap_or(f64::NAN)
}

/// Fidelity accurate and auto against fast on a short run (100 h, an update every 25 h, 360
/// angles): job time, wear and its difference from fast, and the grid error of accurate against
/// accurate on 384 nodes.
fn fidelity(flat: &Value, roller: &Value) {
    println!("### Fidelity: accurate and auto against fast (100 h, an update every 25 h, 360 angles)\n");
    println!("Depth difference: largest difference of the final wear-depth profile from the reference,");
    println!("relative to the reference's maximum. Reference for \"vs fast\": fast; for \"grid error\":");
    println!("accurate on 384 nodes.\n");
    println!("| case | fidelity | nodes | numerical angles | job (s) | worn volume (mm³) | max wear (µm) at (°) | volume / fast | depth vs fast | grid error |");
    println!("| --- | --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: |");
    for (name, base, reps) in [("seed 003 flat, asperity share", flat, 3), ("seed 000 roller, slip, asperity share", roller, 1)] {
        let base = with(base, |s| {
            s["hours"] = json!(100.0);
            s["update_interval_hours"] = json!(25.0);
            s["cycle"]["angles"] = json!(360);
            s["snapshots"] = json!(0);
        });
        let at = |fid: &str, nodes: usize| {
            with(&base, |s| {
                s["cycle"]["fidelity"] = json!(fid);
                s["cycle"]["ehl"] = json!({"nodes": nodes});
            })
        };
        let (ms_fast, fast) = job(&base, 5);
        let (_, reference) = job(&at("accurate", 384), 1);
        let (d_fast, d_ref) = (depth(&fast), depth(&reference));
        let v_fast = summary(&fast, "worn_volume");
        let row = |fid: &str, nodes: &str, ms: f64, out: &Value| {
            let numerical = out["summary"]["fidelity_used"]["numerical"].as_u64().map_or("0".to_string(), |n| n.to_string());
            let d = depth(out);
            let grid = if fid == "fast" { "–".to_string() } else { format!("{:.2e}", rel_err(&d, &d_ref)) };
            let time = if ms.is_finite() { format!("{:.2}", ms / 1e3) } else { "–".to_string() };
            println!(
                "| {name} | {fid} | {nodes} | {numerical} | {time} | {:.4e} | {:.4} at {:.1} | {:.3} | {:.2e} | {grid} |",
                summary(out, "worn_volume") * 1e9,
                summary(out, "max_wear_depth") * 1e6,
                summary(out, "max_wear_angle_deg"),
                summary(out, "worn_volume") / v_fast,
                rel_err(&d, &d_fast),
            );
        };
        row("fast", "–", ms_fast, &fast);
        for nodes in [128, 192, 256] {
            let (ms, out) = job(&at("accurate", nodes), reps);
            row("accurate", &nodes.to_string(), ms, &out);
        }
        let (ms, out) = job(&at("auto", 192), reps);
        row("auto", "192", ms, &out);
        let (ms, out) = job(&with(&at("auto", 192), |s| s["cycle"]["ehl"]["auto_tolerance"] = json!(0.25)), reps);
        row("auto, tol 0.25", "192", ms, &out);
        row("accurate (reference)", "384", f64::NAN, &reference);
    }
}
