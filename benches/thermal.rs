//! Run time against error of the thermal line-contact EHL model (`physics::ehl::thermal`).
//!
//! `cargo bench --bench thermal` prints a markdown table: one contact (seed 000 base-circle-like:
//! w' = 5e4 N/m, R = 14 mm, u_m = 3 m/s, slide-to-roll ratio 0.3) at x nodes × film levels from
//! 96 × 5 to 512 × 9, errors of the central film, the largest temperature rise and the friction
//! coefficient against 512 × 11, the coupling iterations and the best of three run times.
//!
//! `cargo bench --bench thermal -- cycle` (only that part; without an argument both run): the
//! seed 000 thermal cycle (`examples/seed000_thermal_steady.json`) at 720 angles, the full
//! thermal solve at every angle against key points (`ehl.thermal.carry_tolerance`) and `auto`:
//! run time (the whole job, one run each: the full cycle takes minutes), key points, and the worst
//! film and SRR differences against the full cycle.

use serde_json::Value;
use std::time::Instant;
use tribod::jobs::{registry, Limits};
use tribod::physics::ehl::thermal::{self, ThermalBodies, ThermalInput, ThermalOptions};
use tribod::physics::ehl::{EhlInput, EhlOptions, Rheology};
use tribod::physics::lubricant::Lubricant;
use tribod::physics::Silent;

/// The whole `cam_cycle` job: result and run time, s.
fn cycle_job(spec: &Value) -> (Value, f64) {
    let k = registry::find("cam_cycle").unwrap();
    let prepared = k.prepare(spec, &Limits { max_job_seconds: 3600.0, ..Limits::default() }).unwrap();
    let t = Instant::now();
    let out = prepared.run(&Silent).unwrap();
    (out, t.elapsed().as_secs_f64())
}

fn series(out: &Value, name: &str) -> Vec<f64> {
    out["series"][name].as_array().unwrap_or_else(|| panic!("{name}")).iter().map(|v| v.as_f64().unwrap()).collect()
}

fn cycle_table() {
    let text = std::fs::read_to_string("examples/seed000_thermal_steady.json").unwrap();
    let base = serde_json::from_str::<Value>(&text).unwrap()["spec"].clone();
    let angles = std::env::var("THERMAL_BENCH_ANGLES").ok().and_then(|a| a.parse::<u64>().ok()).unwrap_or(720);
    let spec = |f: &dyn Fn(&mut Value)| {
        let mut s = base.clone();
        s["angles"] = angles.into();
        f(&mut s);
        s
    };
    // THERMAL_BENCH_NO_FULL: leave out the every-angle thermal cycles (full and plain `auto`:
    // minutes each); errors then against the carried cycle at carry_tolerance 0.01.
    let skip_full = std::env::var("THERMAL_BENCH_NO_FULL").is_ok();
    let (full, t_full) = if skip_full { cycle_job(&spec(&|s| s["ehl"]["thermal"]["carry_tolerance"] = 0.01.into())) } else { cycle_job(&spec(&|s| s["ehl"]["thermal"]["carry_tolerance"] = 0.0.into())) };
    let srr_full = series(&full, "slide_roll_ratio");
    let srr_scale = srr_full.iter().fold(0.0f64, |m, s| m.max(s.abs()));
    println!("\n## Seed 000 thermal cycle, {angles} angles (whole job, release, rayon pool of the machine)\n");
    println!("| case | time, s | thermal solves (angles) | worst film_central | worst film_min | worst SRR (of max \\|SRR\\| {srr_scale:.3}) | convergence |");
    println!("|---|---|---|---|---|---|---|");
    // THERMAL_BENCH_DUMP=<dir>: each case's result JSON is written there (for per-angle study).
    let dump = std::env::var("THERMAL_BENCH_DUMP").ok();
    let angle = series(&full, "angle_deg");
    let row = |name: &str, out: &Value, t: f64| {
        // Worst difference and the angle where it sits.
        let worst_at = |d: Vec<f64>| d.iter().enumerate().fold((0.0, 0.0), |(w, a), (i, &v)| if v > w { (v, angle[i]) } else { (w, a) });
        let worst = |n: &str| {
            let (a, b) = (series(&full, n), series(out, n));
            worst_at((0..a.len()).map(|i| (b[i] - a[i]).abs() / a[i].abs()).collect())
        };
        let srr = series(out, "slide_roll_ratio");
        let ws = worst_at((0..srr.len()).map(|i| (srr[i] - srr_full[i]).abs() / srr_scale).collect());
        let (hc, hm) = (worst("film_central"), worst("film_min"));
        println!(
            "| {name} | {t:.2} | {} | {:.3} % ({:.1}°) | {:.3} % ({:.1}°) | {:.3} % ({:.1}°) | {} |",
            out["summary"]["fidelity_used"],
            100.0 * hc.0,
            hc.1,
            100.0 * hm.0,
            hm.1,
            100.0 * ws.0,
            ws.1,
            out["convergence"]
        );
        if let Some(dir) = &dump {
            let file = format!("{dir}/{}.json", name.replace([' ', ','], "_"));
            std::fs::write(&file, out.to_string()).unwrap_or_else(|e| panic!("{file}: {e}"));
        }
    };
    row(if skip_full { "reference: accurate, carry_tolerance 0.01" } else { "accurate, full thermal solve at every angle" }, &full, t_full);
    for tol in [0.02, 0.05, 0.1] {
        let (out, t) = cycle_job(&spec(&|s| s["ehl"]["thermal"]["carry_tolerance"] = tol.into()));
        row(&format!("accurate, carry_tolerance {tol}"), &out, t);
    }
    if !skip_full {
        let (out, t) = cycle_job(&spec(&|s| {
            s["fidelity"] = "auto".into();
            s["ehl"]["thermal"]["carry_tolerance"] = 0.0.into();
        }));
        row("auto", &out, t);
    }
    let (out, t) = cycle_job(&spec(&|s| {
        s["fidelity"] = "auto".into();
        s["ehl"]["thermal"]["carry_tolerance"] = 0.05.into();
    }));
    row("auto, carry_tolerance 0.05", &out, t);
}

/// Seed 000 Figs. 9 and 13 with the thermal model (`-- trends`): the SRR at the paper's angles
/// (0°, 100°, 155°, 176°) and at the model's closing-flank extreme, against the oil viscosity η0
/// and the modified load w1, for the thermal steady example with key points
/// (`THERMAL_BENCH_CARRY`, default 0.02) at `THERMAL_BENCH_ANGLES` (default 360), and for the
/// isothermal `fast` model of `seed000_roller_steady` beside it.
fn trends() {
    let angles = std::env::var("THERMAL_BENCH_ANGLES").ok().and_then(|a| a.parse::<u64>().ok()).unwrap_or(360);
    let carry = std::env::var("THERMAL_BENCH_CARRY").ok().and_then(|a| a.parse::<f64>().ok()).unwrap_or(0.02);
    let load = |name: &str| serde_json::from_str::<Value>(&std::fs::read_to_string(format!("examples/{name}.json")).unwrap()).unwrap()["spec"].clone();
    let at = |a: &[f64], v: &[f64], deg: f64| v[(0..a.len()).min_by(|&i, &j| (a[i] - deg).abs().total_cmp(&(a[j] - deg).abs())).unwrap()];
    for (model, base) in [("thermal (accurate, key points)", load("seed000_thermal_steady")), ("isothermal fast", load("seed000_roller_steady"))] {
        println!("\n## Seed 000 trends, {model}, {angles} angles (carry_tolerance {carry})\n");
        println!("| case | SRR 0° | 100° | 155° | 176° | closing-flank minimum (130–200°) | time, s |");
        println!("|---|---:|---:|---:|---:|---|---:|");
        let cases: Vec<(String, Box<dyn Fn(&mut Value)>)> = [0.08, 0.112, 0.152, 0.2]
            .into_iter()
            .map(|eta| (format!("η0 = {eta} Pa·s"), Box::new(move |s: &mut Value| s["lubricant"]["viscosity"] = eta.into()) as Box<dyn Fn(&mut Value)>))
            .chain([0.0, 200.0, 400.0, 800.0].into_iter().map(|w1| (format!("w1 = {w1} N"), Box::new(move |s: &mut Value| s["load"]["offset"] = w1.into()) as Box<dyn Fn(&mut Value)>)))
            .collect();
        for (name, f) in &cases {
            let mut s = base.clone();
            s["angles"] = angles.into();
            if s["ehl"]["thermal"].is_object() {
                s["ehl"]["thermal"]["carry_tolerance"] = carry.into();
            }
            f(&mut s);
            let (out, t) = cycle_job(&s);
            let (a, v) = (series(&out, "angle_deg"), series(&out, "slide_roll_ratio"));
            let k = (0..a.len()).filter(|&i| a[i] >= 130.0 && a[i] <= 200.0).min_by(|&i, &j| v[i].total_cmp(&v[j])).unwrap();
            println!("| {name} | {:.5} | {:.5} | {:.5} | {:.5} | {:.5} at {:.1}° | {t:.1} |", at(&a, &v, 0.0), at(&a, &v, 100.0), at(&a, &v, 155.0), at(&a, &v, 176.0), v[k], a[k]);
        }
    }
}

/// `-- finite-cycle [angles=N] [nx=N] [ny=N] [dump=FILE] [ref=FILE] [set=json-pointer=value,...]`:
/// the thermal finite-line cycle (`examples/seed000_thermal_finite_cycle.json`) as a whole job:
/// run time, the work counters per angle, and (with `ref=`, a result dumped by an earlier run)
/// the worst film, film temperature and SRR differences against it.
fn finite_cycle(args: &[String]) {
    let arg = |name: &str| args.iter().find_map(|a| a.strip_prefix(&format!("{name}=")).map(str::to_string));
    let text = std::fs::read_to_string("examples/seed000_thermal_finite_cycle.json").unwrap();
    let mut spec = serde_json::from_str::<Value>(&text).unwrap()["spec"].clone();
    let angles: u64 = arg("angles").and_then(|a| a.parse().ok()).unwrap_or(360);
    spec["angles"] = angles.into();
    if let Some(nx) = arg("nx").and_then(|a| a.parse::<u64>().ok()) {
        spec["ehl"]["nx"] = nx.into();
    }
    if let Some(ny) = arg("ny").and_then(|a| a.parse::<u64>().ok()) {
        spec["ehl"]["ny"] = ny.into();
    }
    for set in arg("set").iter().flat_map(|s| s.split(',').map(str::to_string).collect::<Vec<_>>()) {
        let (ptr, value) = set.split_once('=').expect("set=pointer=value");
        let value: Value = serde_json::from_str(value).unwrap_or(Value::String(value.into()));
        let parts: Vec<&str> = ptr.trim_start_matches('/').split('/').collect();
        let mut at = &mut spec;
        for p in &parts[..parts.len() - 1] {
            at = &mut at[*p];
        }
        at[parts[parts.len() - 1]] = value;
    }
    tribod::physics::film::work::reset();
    let (out, t) = cycle_job(&spec);
    let counters = tribod::physics::film::work::snapshot();
    println!("thermal finite cycle, {angles} angles, ehl {}: {t:.2} s, convergence {}", spec["ehl"], out["convergence"]);
    println!("  work counters: {}", counters.iter().filter(|(_, v)| *v > 0).map(|(k, v)| format!("{} {v}", k.to_lowercase())).collect::<Vec<_>>().join(", "));
    if let Some(file) = arg("dump") {
        std::fs::write(&file, out.to_string()).unwrap();
    }
    if let Some(file) = arg("ref") {
        let reference: Value = serde_json::from_str(&std::fs::read_to_string(&file).unwrap()).unwrap();
        let angle = series(&reference, "angle_deg");
        for name in ["film_central", "film_min", "film_temperature_max", "slide_roll_ratio"] {
            let (a, b) = (series(&reference, name), series(&out, name));
            let scale = if name == "slide_roll_ratio" { a.iter().fold(0.0f64, |m, v| m.max(v.abs())) } else if name == "film_temperature_max" { f64::NAN } else { 0.0 };
            let (mut worst, mut at, mut sum) = (0.0f64, 0.0, 0.0);
            for i in 0..a.len() {
                let d = if scale.is_nan() { (b[i] - a[i]).abs() } else if scale > 0.0 { (b[i] - a[i]).abs() / scale } else { (b[i] - a[i]).abs() / a[i].abs() };
                sum += d;
                if d > worst {
                    (worst, at) = (d, angle[i]);
                }
            }
            let unit = if scale.is_nan() { "K" } else { "(relative)" };
            println!("  {name}: worst {worst:.4} {unit} at {at:.1}°, mean {:.4}", sum / a.len() as f64);
        }
    }
}

fn main() {
    let args: Vec<String> = std::env::args().skip(1).filter(|a| !a.starts_with('-')).collect();
    if args.iter().any(|a| a == "finite-cycle") {
        finite_cycle(&args);
        return;
    }
    if args.iter().any(|a| a == "cycle") {
        cycle_table();
        return;
    }
    if args.iter().any(|a| a == "trends") {
        trends();
        return;
    }
    faer::set_global_parallelism(faer::Par::Seq);
    let lub = Lubricant::SEED000;
    let ehl = EhlInput {
        load_per_length: 5e4,
        reduced_radius: 0.014,
        effective_modulus: 210e9 / 0.91,
        entrainment_velocity: 3.0,
        sliding_velocity: 0.9,
        lubricant: lub,
        temperature: lub.reference_temperature,
        rheology: Rheology::default(),
        transient: None,
        warm_start: None,
        asperity: None,
    };
    let run = |nodes: usize, nz: usize| {
        let input = ThermalInput { ehl, bodies: ThermalBodies::SEED000, previous_temperature: None };
        let options = EhlOptions { nodes, ..Default::default() };
        let topts = ThermalOptions { film_points: nz, ..Default::default() };
        let mut best = f64::INFINITY;
        let mut out = None;
        for _ in 0..3 {
            let t = Instant::now();
            let s = thermal::solve(&input, &options, &topts, &Silent).expect("thermal solve");
            best = best.min(t.elapsed().as_secs_f64());
            out = Some(s);
        }
        (out.unwrap(), best)
    };
    let (reference, _) = run(512, 11);
    let t0 = lub.reference_temperature;
    let rel = |a: f64, b: f64| (a - b).abs() / b.abs();
    println!("| x nodes × film levels | central film error | ΔT_max error | μ error | coupling iterations | time, ms |");
    println!("|---|---|---|---|---|---|");
    for &(n, nz) in &[(96, 5), (128, 5), (128, 7), (192, 7), (256, 7), (384, 7), (512, 7), (512, 9)] {
        let (s, time) = run(n, nz);
        println!(
            "| {n} × {nz} | {:.2} % | {:.2} % | {:.2} % | {} | {:.0} |",
            100.0 * rel(s.ehl.central_film, reference.ehl.central_film),
            100.0 * rel(s.summary.film_temperature_max - t0, reference.summary.film_temperature_max - t0),
            100.0 * rel(s.ehl.traction.friction_coefficient, reference.ehl.traction.friction_coefficient),
            s.convergence.iterations,
            1e3 * time
        );
    }
    println!(
        "\nreference 512 × 11: central film {:.4e} m, ΔT_max {:.2} K, μ {:.5}",
        reference.ehl.central_film,
        reference.summary.film_temperature_max - t0,
        reference.ehl.traction.friction_coefficient
    );
    cycle_table();
}
