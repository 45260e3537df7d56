//! Run time against error of the 2-D (point / finite line) EHL solver (`physics::ehl::twod`).
//!
//! `cargo bench --bench ehl2d` prints a markdown table: one circular point contact (F = 100 N,
//! R = 10 mm, u_m = 1 m/s, η0 = 0.04 Pa·s, α = 2e-8 1/Pa, Roelands + Dowson–Higginson; M ≈ 60,
//! L ≈ 11) on square grids 33² … 257² (`-- 513` adds 513²), errors of the central and minimum film
//! against the Richardson extrapolation (second order) of the two finest grids. Then the seed 000
//! crowned roller at the cam nose (`-- roller`). Times are the best of a few repetitions, one
//! thread for the solver's own work (faer's sparse LU may use the rayon pool).
//!
//! `-- cycle [angles=360] [nx=65] [ny=129] [stride=30] [reference] [cycle-only] [steady] [auto]
//! [dump=FILE] [ref=FILE]`:
//! the seed 000 roller cycle (`examples/seed000_roller_accurate.json`) with `ehl.geometry: finite`
//! through the `cam_cycle` kind (with the squeeze term; `steady`: `ehl.squeeze: false`; `auto`:
//! `fidelity: auto`) — wall time, Newton steps per angle, warm/cold solves; then the film model
//! alone along the cycle's contact points (smooth surfaces): the warm-started chain against cold
//! solves at every `stride`-th angle (Newton steps and time saved by the warm start); with
//! `reference` the films at the largest-load, nose and base-circle angles against the Richardson
//! extrapolation of this grid and the one with twice the intervals (cold solves).
//! `grids=65x129,129x129:in=8:out=2,…`: cold steady solves at those three angles' contact points
//! on each grid (`in`/`out`: inlet/outlet distance in units of `a`), with the domain used;
//! `pts=F:u:R/F:u:R/F:u:R` (load N, entrainment m/s, R_x mm of the three points, as the cycle
//! prints them) runs the `grids=` solves without the cycle (BENCHMARKS.md issue 16, `ehl2d-16`).

use std::time::Instant;
use tribod::physics::ehl::twod::{solve, Ehl2dInput, Ehl2dOptions, Geometry2d};
use tribod::physics::lubricant::Lubricant;
use tribod::physics::roller::Crown;
use tribod::physics::Silent;

const E_PRIME: f64 = 210e9 / 0.91;

fn best_of<T>(reps: usize, mut f: impl FnMut() -> T) -> (f64, T) {
    let mut best = f64::INFINITY;
    let mut out = None;
    for _ in 0..reps {
        let t = Instant::now();
        let v = f();
        best = best.min(t.elapsed().as_secs_f64());
        out = Some(v);
    }
    (best, out.expect("at least one repetition"))
}

fn main() {
    let args: Vec<String> = std::env::args().collect();
    // `seq`: faer's kernels (the sparse LU) on the calling thread only.
    if args.iter().any(|a| a == "seq") {
        faer::set_global_parallelism(faer::Par::Seq);
    }
    if args.iter().any(|a| a == "cycle") {
        cycle(&args);
        return;
    }
    let with_513 = args.iter().any(|a| a == "513");
    let roller_only = args.iter().any(|a| a == "roller");
    if args.iter().any(|a| a == "probe") {
        // Truncation error of coarser grids against the solution on `fine=N` (default 257).
        let fine = args.iter().find_map(|a| a.strip_prefix("fine=")).and_then(|v| v.parse().ok()).unwrap_or(257);
        let lub = Lubricant { viscosity: 0.04, pressure_viscosity: 2e-8, ..Lubricant::SEED000 };
        let input = Ehl2dInput { load: 100.0, geometry: Geometry2d::Point { rx: 0.01, ry: 0.01 }, effective_modulus: E_PRIME, entrainment_velocity: 1.0, lubricant: lub, temperature: 313.0 };
        let o = Ehl2dOptions { nx: fine, ny: fine, inlet: Some(3.5), outlet: Some(1.5), side: Some(2.0), ..Default::default() };
        let strides: Vec<usize> = [2, 4, 8].into_iter().filter(|s| (fine - 1) / s >= 16).collect();
        match tribod::physics::ehl::twod::solver::truncation_probe(&input, &o, &strides) {
            Ok(report) => print!("{report}"),
            Err(e) => println!("probe failed: {e}"),
        }
        return;
    }
    if !roller_only {
        let lub = Lubricant { viscosity: 0.04, pressure_viscosity: 2e-8, ..Lubricant::SEED000 };
        let input = Ehl2dInput { load: 100.0, geometry: Geometry2d::Point { rx: 0.01, ry: 0.01 }, effective_modulus: E_PRIME, entrainment_velocity: 1.0, lubricant: lub, temperature: 313.0 };
        let mut sizes = vec![33, 65, 129, 257];
        if with_513 {
            sizes.push(513);
        }
        let mut rows = Vec::new();
        for &n in &sizes {
            let o = Ehl2dOptions { nx: n, ny: n, inlet: Some(3.5), outlet: Some(1.5), side: Some(2.0), ..Default::default() };
            let reps = if n <= 65 { 3 } else { 1 };
            let (t, s) = best_of(reps, || solve(&input, &o, &Silent));
            match s {
                Ok(s) => {
                    eprintln!("{n}: {t:.3} s, hc {:.6e}, hmin {:.6e}, newton {}", s.central_film, s.min_film.value, s.convergence.iterations);
                    rows.push((n, t, s.central_film, s.min_film.value, s.convergence.iterations));
                }
                Err(e) => println!("{n}×{n}: not converged after {t:.3} s: {e}"),
            }
        }
        let k = rows.len();
        if k < 2 {
            println!("fewer than two converged grids: no Richardson reference");
            return;
        }
        let rich = |a: f64, b: f64| b + (b - a) / 3.0;
        let (rc, rm) = (rich(rows[k - 2].2, rows[k - 1].2), rich(rows[k - 2].3, rows[k - 1].3));
        println!("| grid | time (s) | Newton steps | h_c (nm) | error h_c | h_min (nm) | error h_min |");
        println!("| --- | --- | --- | --- | --- | --- | --- |");
        for (n, t, hc, hm, it) in &rows {
            println!("| {n}×{n} | {t:.3} | {it} | {:.2} | {:.2} % | {:.2} | {:.2} % |", hc * 1e9, 100.0 * (hc / rc - 1.0), hm * 1e9, 100.0 * (hm / rm - 1.0));
        }
        println!("Richardson reference: h_c = {:.3} nm, h_min = {:.3} nm", rc * 1e9, rm * 1e9);
    }
    // Seed 000 roller at the nose (tests/it/ehl_2d.rs: seed000_nose).
    let crown = Crown::SEED000;
    let input = Ehl2dInput { load: 954.0, geometry: Geometry2d::Finite { rx: 0.01037, crown }, effective_modulus: 2.1e11, entrainment_velocity: 2.77, lubricant: Lubricant::SEED000, temperature: 313.0 };
    println!();
    println!("| roller grid | time (s) | h_c (µm) | h_min (µm) at y (mm) | p_max (GPa) | edge peak (GPa at y mm) |");
    println!("| --- | --- | --- | --- | --- | --- |");
    for (nx, ny) in [(33, 65), (65, 129), (129, 257)] {
        let o = Ehl2dOptions { nx, ny, ..Default::default() };
        let (t, s) = best_of(1, || solve(&input, &o, &Silent));
        let Ok(s) = s else {
            println!("| {nx}×{ny} | {t:.3} | not converged | | | |");
            continue;
        };
        let edge = s.edge_pressure_peak.map_or("none".to_string(), |e| format!("{:.3} at {:.2}", e.value * 1e-9, e.y * 1e3));
        println!("| {nx}×{ny} | {t:.3} | {:.4} | {:.4} at {:.2} | {:.3} | {edge} |", s.central_film * 1e6, s.min_film.value * 1e6, s.min_film.y * 1e3, s.max_pressure.value * 1e-9);
    }
}

fn arg<T: std::str::FromStr>(args: &[String], name: &str, default: T) -> T {
    args.iter().find_map(|a| a.strip_prefix(&format!("{name}="))).and_then(|v| v.parse().ok()).unwrap_or(default)
}

/// The seed 000 cycle with the finite-length model (see the module docs).
fn cycle(args: &[String]) {
    use serde_json::{json, Value};
    use tribod::jobs::{registry, Limits};
    use tribod::physics::film::{ClosedForm, ContactShape, Finite, FilmFormula, FilmModel, SmoothContact};
    let angles: usize = arg(args, "angles", 360);
    let nx: usize = arg(args, "nx", 65);
    let ny: usize = arg(args, "ny", 129);
    let stride: usize = arg(args, "stride", 30);
    let text = std::fs::read_to_string("examples/seed000_roller_accurate.json").expect("example");
    let mut spec: Value = serde_json::from_str::<Value>(&text).unwrap()["spec"].clone();
    spec["angles"] = json!(angles);
    spec["ehl"] = json!({"geometry": "finite", "nx": nx, "ny": ny, "tolerance": 1e-6});
    // `steady`: the quasi-steady cycle (no squeeze term; the default is the transient one).
    if args.iter().any(|a| a == "steady") {
        spec["ehl"]["squeeze"] = json!(false);
    }
    // `auto`: the 2-D model only where the contact's ends matter, the 1-D `auto` elsewhere.
    if args.iter().any(|a| a == "auto") {
        spec["fidelity"] = json!("auto");
    }
    // `pts=F:u:R/F:u:R/F:u:R` (load N, entrainment m/s, R_x mm at the max load, nose and base
    // circle angles, as the cycle prints them): the `grids=` solves only, without the cycle.
    if let Some(pts) = args.iter().find_map(|a| a.strip_prefix("pts=")) {
        let v: Vec<Vec<f64>> = pts.split('/').map(|p| p.split(':').map(|x| x.parse().expect("number")).collect()).collect();
        let load: Vec<f64> = v.iter().map(|p| p[0]).collect();
        let ue: Vec<f64> = v.iter().map(|p| p[1]).collect();
        let rx: Vec<f64> = v.iter().map(|p| p[2] * 1e-3).collect();
        grids(args, &load, &ue, &rx, 0, 1, 2);
        return;
    }
    let kind = registry::find("cam_cycle").unwrap();
    let prepared = kind.prepare(&spec, &Limits::default()).expect("valid spec");
    tribod::physics::film::work::reset();
    let t = Instant::now();
    let out = prepared.run(&Silent);
    let wall = t.elapsed().as_secs_f64();
    let counters = tribod::physics::film::work::snapshot();
    let out = match out {
        Ok(v) => v,
        Err(e) => {
            println!("cycle failed after {wall:.1} s: {e}");
            return;
        }
    };
    let series = &out["series"];
    let col = |name: &str| -> Vec<f64> { series[name].as_array().map(|a| a.iter().map(|v| v.as_f64().unwrap_or(f64::NAN)).collect()).unwrap_or_default() };
    let steps = col("newton_steps");
    let (hc, hm, load, rx, ue) = (col("film_central"), col("film_min"), col("contact_load"), col("reduced_radius"), col("entrainment_velocity"));
    let edge = col("edge_pressure_peak");
    let ymin = col("min_film_axial_position");
    let total_steps: f64 = steps.iter().sum();
    println!("seed 000 cycle, ehl.geometry finite {nx}×{ny}, {angles} angles: {wall:.2} s ({:.3} s per angle), Newton steps {total_steps} in the stored solutions (mean {:.2}), fidelity_used {}", wall / angles as f64, total_steps / angles as f64, out["summary"]["fidelity_used"]);
    println!("  work counters (per angle): {}", counters.iter().map(|(k, v)| format!("{} {v} ({:.2})", k.to_lowercase(), *v as f64 / angles as f64)).collect::<Vec<_>>().join(", "));
    let imax = (0..load.len()).max_by(|&a, &b| load[a].total_cmp(&load[b])).unwrap_or(0);
    let inose = angles * 127 / 360;
    let ibase = angles * 300 / 360;
    for (what, i) in [("max load", imax), ("nose 127°", inose), ("base circle 300°", ibase)] {
        // A null edge peak (none found at that angle) reads as NaN in `col`.
        let peak = if edge[i].is_finite() { format!("{:.3} GPa", edge[i] * 1e-9) } else { "none".to_string() };
        println!("  {what} (angle {i}): load {:.1} N, u_e {:.3} m/s, R_x {:.3} mm, h_c {:.4} µm, h_min {:.4} µm at y = {:.2} mm, edge peak {peak}", load[i], ue[i], rx[i] * 1e3, hc[i] * 1e6, hm[i] * 1e6, ymin[i] * 1e3);
    }
    dump_and_compare(args, &out);
    grids(args, &load, &ue, &rx, imax, inose, ibase);
    // `cycle-only`: stop here (the counters and the cycle's time only).
    if args.iter().any(|a| a == "cycle-only") {
        return;
    }
    // The film model alone along the cycle's contact points: warm chain against cold solves.
    let crown = Crown::SEED000;
    let smooth = SmoothContact::seed000();
    let input = |i: usize| smooth.input(load[i], ContactShape::Line { reduced_radius: rx[i], length: 0.014 }, ue[i]);
    let fallback = ClosedForm { formula: FilmFormula::PanHamrock, squeeze: false };
    let options = Ehl2dOptions { nx, ny, tolerance: 1e-6, max_iterations: 60, ..Default::default() };
    let warm_model = Finite::new(options, Some(crown), fallback).check_first_only();
    let cold_model = Finite::new(options, Some(crown), fallback);
    let (mut warm_steps, mut warm_time, mut cold_steps, mut cold_time, mut n_cold, mut warm_at_cold, mut warm_time_at_cold) = (0u32, 0.0, 0u32, 0.0, 0, 0u32, 0.0);
    let mut prev = None;
    let mut fails = 0;
    let mut worst: f64 = 0.0;
    // The cycle's films against Newton solves at its converged load and entrainment (the films
    // of the converged cycle on this grid; no entrainment rescale in this chain).
    let (mut dev_c, mut dev_m, mut at_c, mut at_m) = (0.0f64, 0.0f64, 0, 0);
    let warm_model = warm_model.with_rescale_range(0.0);
    for i in 0..angles {
        let t = Instant::now();
        let w = warm_model.solve(&input(i), prev.as_ref());
        let tw = t.elapsed().as_secs_f64();
        let Ok(w) = w else {
            fails += 1;
            prev = None;
            continue;
        };
        let (dc, dm) = ((hc[i] / w.central_film - 1.0).abs(), (hm[i] / w.min_film - 1.0).abs());
        if dc > dev_c {
            (dev_c, at_c) = (dc, i);
        }
        if dm > dev_m {
            (dev_m, at_m) = (dm, i);
        }
        let sw = w.iterations.unwrap_or(0);
        warm_steps += sw;
        warm_time += tw;
        if i % stride == 0 {
            let t = Instant::now();
            if let Ok(c) = cold_model.solve(&input(i), None) {
                cold_time += t.elapsed().as_secs_f64();
                cold_steps += c.iterations.unwrap_or(0);
                n_cold += 1;
                warm_at_cold += sw;
                warm_time_at_cold += tw;
                worst = worst.max((w.central_film / c.central_film - 1.0).abs()).max((w.min_film / c.min_film - 1.0).abs());
            }
        }
        prev = Some(w);
    }
    println!("film model alone, {angles} angles (smooth, no torque balance): warm chain {warm_time:.2} s ({:.3} s/angle), {warm_steps} Newton steps ({:.2}/angle); {fails} failed", warm_time / angles as f64, warm_steps as f64 / angles as f64);
    println!("  cycle films against Newton solves at the cycle's converged load and entrainment (same grid): central film within {:.2e} (largest at angle {at_c}), minimum film within {:.2e} (angle {at_m})", dev_c, dev_m);
    if n_cold > 0 {
        println!(
            "  at {n_cold} angles (every {stride}th): cold {:.3} s and {:.1} Newton steps per angle (nested grids + check) against warm {:.3} s and {:.1}; films warm vs cold within {:.2e}",
            cold_time / n_cold as f64,
            cold_steps as f64 / n_cold as f64,
            warm_time_at_cold / n_cold as f64,
            warm_at_cold as f64 / n_cold as f64,
            worst
        );
    }
    if args.iter().any(|a| a == "reference") {
        let fine = Ehl2dOptions { nx: 2 * nx - 1, ny: 2 * ny - 1, ..options };
        let fine_model = Finite::new(fine, Some(crown), fallback);
        for (what, i) in [("max load", imax), ("nose 127°", inose), ("base circle 300°", ibase)] {
            let t = Instant::now();
            let (c, f) = (cold_model.solve(&input(i), None), fine_model.solve(&input(i), None));
            match (c, f) {
                (Ok(c), Ok(f)) => {
                    let rich = |a: f64, b: f64| b + (b - a) / 3.0;
                    let (rc, rm) = (rich(c.central_film, f.central_film), rich(c.min_film, f.min_film));
                    println!(
                        "  {what}: {nx}×{ny} h_c {:.4} µm ({:+.2} %), h_min {:.4} µm ({:+.2} %); {}×{} h_c {:.4} ({:+.2} %), h_min {:.4} ({:+.2} %); Richardson {:.4} / {:.4} µm ({:.1} s)",
                        c.central_film * 1e6,
                        100.0 * (c.central_film / rc - 1.0),
                        c.min_film * 1e6,
                        100.0 * (c.min_film / rm - 1.0),
                        fine.nx,
                        fine.ny,
                        f.central_film * 1e6,
                        100.0 * (f.central_film / rc - 1.0),
                        f.min_film * 1e6,
                        100.0 * (f.min_film / rm - 1.0),
                        rc * 1e6,
                        rm * 1e6,
                        t.elapsed().as_secs_f64()
                    );
                }
                (c, f) => println!("  {what}: reference failed: {:?} / {:?}", c.err(), f.err()),
            }
        }
    }
}

/// `dump=FILE`: the cycle job's output as JSON; `ref=FILE` (an earlier dump): the largest relative
/// differences of the films, the load and the entrainment at every angle against it.
fn dump_and_compare(args: &[String], out: &serde_json::Value) {
    let col = |v: &serde_json::Value, name: &str| -> Vec<f64> { v["series"][name].as_array().map(|a| a.iter().map(|x| x.as_f64().unwrap_or(f64::NAN)).collect()).unwrap_or_default() };
    if let Some(file) = args.iter().find_map(|a| a.strip_prefix("dump=")) {
        std::fs::write(file, out.to_string()).expect("dump");
    }
    let Some(file) = args.iter().find_map(|a| a.strip_prefix("ref=")) else { return };
    let reference: serde_json::Value = serde_json::from_str(&std::fs::read_to_string(file).expect("ref file")).expect("ref JSON");
    for name in ["film_central", "film_min", "contact_load", "entrainment_velocity"] {
        let (a, b) = (col(&reference, name), col(out, name));
        let (mut worst, mut at, mut sum) = (0.0f64, 0, 0.0);
        for i in 0..a.len().min(b.len()) {
            let d = (b[i] / a[i] - 1.0).abs();
            sum += d;
            if d > worst {
                (worst, at) = (d, i);
            }
        }
        println!("  against {file}: {name} worst {:.3e} at angle {at}, mean {:.3e}", worst, sum / a.len().max(1) as f64);
    }
}

/// Cold steady solves at the cycle's max load, nose and base-circle contact points on the grids of
/// `grids=` (see `cycle`).
fn grids(args: &[String], load: &[f64], ue: &[f64], rx: &[f64], imax: usize, inose: usize, ibase: usize) {
    use tribod::physics::film::{ClosedForm, ContactShape, Finite, FilmFormula, FilmModel, SmoothContact};
    // `grids=65x129,129x129:in=6:out=2,...`: each grid (and domain: `in`/`out` the inlet/outlet
    // distance in units of `a`), with the domain the solver used and the Newton steps.
    let Some(list) = args.iter().find_map(|a| a.strip_prefix("grids=")) else { return };
    let smooth = SmoothContact::seed000();
    let fallback = ClosedForm { formula: FilmFormula::PanHamrock, squeeze: false };
    for item in list.split(',') {
        let mut parts = item.split(':');
        let Some((gx, gy)) = parts.next().and_then(|g| g.split_once('x')) else { continue };
        let (gx, gy): (usize, usize) = (gx.parse().expect("nx"), gy.parse().expect("ny"));
        let mut o = Ehl2dOptions { nx: gx, ny: gy, tolerance: 1e-6, max_iterations: 60, ..Default::default() };
        for p in parts {
            if let Some(v) = p.strip_prefix("in=") {
                o.inlet = Some(v.parse().expect("inlet"));
            }
            if let Some(v) = p.strip_prefix("out=") {
                o.outlet = Some(v.parse().expect("outlet"));
            }
        }
        let model = Finite::new(o, Some(Crown::SEED000), fallback);
        for (what, i) in [("max load", imax), ("nose 127°", inose), ("base circle 300°", ibase)] {
            let input = smooth.input(load[i], ContactShape::Line { reduced_radius: rx[i], length: 0.014 }, ue[i]);
            let t = Instant::now();
            match model.solve(&input, None) {
                Ok(f) => {
                    let ff = f.finite.as_deref().expect("2-D film");
                    let w = &ff.warm;
                    let (x0, x1) = (w.x[0], w.x[w.x.len() - 1]);
                    println!(
                        "  grid {item} {what}: h_c {:.4} µm, h_min {:.4} µm at y {:.2} mm, {} Newton steps, {:.2} s; a {:.1} µm, H_est {:.3}, x in [{x0:.2}, {x1:.2}] a, dx {:.3} a, dy {:.3} a",
                        f.central_film * 1e6,
                        f.min_film * 1e6,
                        ff.min_film_position.1 * 1e3,
                        f.iterations.unwrap_or(0),
                        t.elapsed().as_secs_f64(),
                        w.a * 1e6,
                        w.h_est,
                        w.x[1] - w.x[0],
                        w.y[1] - w.y[0]
                    );
                }
                Err(e) => println!("  grid {item} {what}: failed: {e}"),
            }
        }
    }
}
