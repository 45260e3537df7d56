//! Cam-cycle benchmarks: run time against angle resolution against error.
//! `cargo bench --bench cam` (release). Plain `Instant` timing, best of N repetitions.
//!
//! "physics" times `physics::cam::cycle::run_cycle` alone; "job" times the whole job as the
//! service runs it (spec preparation excluded; solve, result serialisation to JSON and the
//! finite-number check included). `CAM_BENCH_PROFILE=1` runs only the steady roller cycle (for
//! `perf record` on the bench binary).

use serde_json::Value;
use std::time::Instant;
use tribod::jobs::kinds::cam_cycle::CamCycleSpec;
use tribod::jobs::{registry, Limits};
use tribod::physics::cam::cycle::run_cycle;
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

/// Best-of-`reps` physics time (ms).
fn physics_ms(spec: &Value, reps: usize) -> f64 {
    let typed: CamCycleSpec = serde_json::from_value(spec.clone()).unwrap();
    let cycle = typed.cycle_spec().unwrap();
    let needs = typed.needs();
    let model = typed.film.to_physics();
    let mut best = f64::INFINITY;
    for _ in 0..reps {
        let t = Instant::now();
        let out = run_cycle(&cycle, needs, &model, &Silent).unwrap();
        best = best.min(t.elapsed().as_secs_f64() * 1e3);
        std::hint::black_box(out);
    }
    best
}

/// Best-of-`reps` job time (ms) and the result.
fn job(spec: &Value, reps: usize) -> (f64, Value) {
    let k = registry::find("cam_cycle").unwrap();
    let mut best = f64::INFINITY;
    let mut out = Value::Null;
    for _ in 0..reps {
        let prepared = k.prepare(spec, &Limits::default()).unwrap();
        let t = Instant::now();
        out = prepared.run(&Silent).unwrap();
        best = best.min(t.elapsed().as_secs_f64() * 1e3);
    }
    (best, out)
}

fn outputs(list: &[&str]) -> Value {
    list.iter().map(|o| Value::from(*o)).collect()
}

fn main() {
    let flat = load("examples/seed003_cycloidal_flat.json");
    let roller = load("examples/seed000_roller_steady.json");
    let startup = load("examples/seed000_roller_startup.json");
    // Warm the one-time F5/2 table.
    let _ = physics_ms(&with(&flat, |s| s["angles"] = 64.into()), 1);

    if std::env::var("CAM_BENCH_PROFILE").is_ok() {
        // For `perf record`: the steady roller cycle only.
        let s = with(&roller, |s| s["angles"] = 3600.into());
        println!("profile: {:.3} ms", physics_ms(&s, 30));
        println!("convergence: {}", job(&s, 1).1["convergence"]);

        return;
    }
    // `cargo bench --bench cam -- fidelity` runs only the fidelity table.
    let args: Vec<String> = std::env::args().skip(1).filter(|a| !a.starts_with('-')).collect();
    if args.iter().any(|a| a == "fidelity") {
        fidelity_table(&flat, &roller);
        return;
    }
    if args.iter().any(|a| a == "auto-tables") {
        auto_tables();
        return;
    }
    // `cargo bench --bench cam -- pin` runs only the roller–pin table.
    if args.iter().any(|a| a == "pin") {
        pin_table(&roller);
        return;
    }
    let all = ["kinematics", "loads", "contact", "film", "friction", "slip", "temperature"];
    let roller_finite = with(&roller, |s| s["follower"]["pin"] = serde_json::json!({"model": "finite"}));
    println!("## Cam cycle: run time at 3600 angles (release, best of 20)\n");
    println!("| case | outputs | physics (ms) | job incl. JSON (ms) |");
    println!("| --- | --- | ---: | ---: |");
    for (name, spec, outs) in [
        ("seed 003 flat, cycloidal", &flat, &["kinematics"][..]),
        ("seed 003 flat, cycloidal", &flat, &all[..]),
        ("seed 000 roller (table profile), steady", &roller, &["kinematics"][..]),
        ("seed 000 roller, steady", &roller, &["kinematics", "loads", "contact", "film"][..]),
        ("seed 000 roller, steady", &roller, &all[..]),
        ("seed 000 roller, startup", &startup, &all[..]),
        ("seed 000 roller, steady, finite thermal pin", &roller_finite, &all[..]),
    ] {
        let s = with(spec, |s| {
            s["angles"] = 3600.into();
            s["outputs"] = outputs(outs);
        });
        let p = physics_ms(&s, 20);
        let (j, _) = job(&s, 20);
        let label = if outs.len() == all.len() { "all".to_string() } else { outs.join(", ") };
        println!("| {name} | {label} | {p:.3} | {j:.3} |");
    }

    println!("\n## Cam cycle: angle resolution against error (reference: 28 800 angles)\n");
    println!("Relative errors against the same case at 28 800 angles; `x@θ` is series x at cam angle θ.\n");
    println!("| case | angles | physics (ms) | errors |");
    println!("| --- | ---: | ---: | --- |");
    type Metric = (&'static str, Option<f64>);
    let cases: [(&str, &Value, &[Metric]); 3] = [
        ("seed 003 flat", &flat, &[("mean_power_loss", None), ("mean_friction_torque", None), ("max_flash_temperature", None)]),
        ("seed 000 roller steady", &roller, &[("min_film", None), ("max_abs_slide_roll_ratio", None), ("mean_power_loss", None), ("slide_roll_ratio", Some(100.0))]),
        ("seed 000 roller startup", &startup, &[("slide_roll_ratio", Some(10.0)), ("slide_roll_ratio", Some(100.0)), ("slide_roll_ratio", Some(300.0)), ("mean_power_loss", None)]),
    ];
    let value = |out: &Value, m: &Metric| -> Option<f64> {
        match m.1 {
            None => out["summary"][m.0].as_f64(),
            Some(deg) => {
                let a = out["series"]["angle_deg"].as_array()?;
                let i = a.iter().position(|x| (x.as_f64().unwrap() - deg).abs() < 1e-9)?;
                out["series"][m.0][i].as_f64()
            }
        }
    };
    for (name, spec, metrics) in cases {
        let (_, reference) = job(&with(spec, |s| s["angles"] = 28_800.into()), 1);
        for n in [180usize, 360, 720, 1440, 3600, 7200] {
            let s = with(spec, |s| s["angles"] = n.into());
            let ms = physics_ms(&s, 10);
            let (_, out) = job(&s, 1);
            let errs: Vec<String> = metrics
                .iter()
                .map(|m| {
                    let label = match m.1 {
                        None => m.0.to_string(),
                        Some(d) => format!("{}@{d}°", m.0),
                    };
                    match (value(&out, m), value(&reference, m)) {
                        (Some(a), Some(b)) if b != 0.0 => format!("{label} {:.1e}", ((a - b) / b).abs()),
                        _ => format!("{label} –"),
                    }
                })
                .collect();
            println!("| {name} | {n} | {ms:.3} | {} |", errs.join("; "));
        }
    }
}

/// Time and error of the fidelities on the seed 000 and seed 003 scenarios at 720 angles, against
/// the numerical model on a fine grid (384 nodes, tolerance 1e-8) at every angle.
fn fidelity_table(flat: &Value, roller: &Value) {
    faer::set_global_parallelism(faer::Par::Seq);
    let col = |out: &Value, name: &str| -> Vec<f64> {
        out["series"][name].as_array().map(|a| a.iter().map(|v| v.as_f64().unwrap()).collect()).unwrap_or_default()
    };
    let max_rel = |a: &[f64], b: &[f64]| a.iter().zip(b).map(|(x, y)| ((x - y) / y).abs()).fold(0.0, f64::max);
    let mean_rel = |a: &[f64], b: &[f64]| a.iter().zip(b).map(|(x, y)| ((x - y) / y).abs()).sum::<f64>() / a.len() as f64;
    let summary = |out: &Value, key: &str| out["summary"][key].as_f64();
    println!("\n## Film models: time and error at 720 angles (release; Richardson runs its two grids on two threads)\n");
    println!("Errors against `accurate` with Richardson extrapolation of 384 + 767 nodes, tolerance 1e-8. Film errors: largest (mean) relative deviation over the angles.\n");
    println!("| case | fidelity | nodes | numerical angles | time (s) | h_c error | h_min error | other |");
    println!("| --- | --- | ---: | ---: | ---: | --- | --- | --- |");
    let flat_ph = with(flat, |s| s["film"] = serde_json::json!({"formula": "pan_hamrock"}));
    let cases: [(&str, &Value, &[&str]); 3] = [
        ("seed 000 roller, steady", roller, &["mean_slide_roll_ratio", "max_abs_slide_roll_ratio", "mean_friction_coefficient"]),
        ("seed 003 flat, cycloidal", flat, &["min_film", "mean_friction_coefficient", "max_flash_temperature"]),
        ("seed 003 flat, Pan–Hamrock as closed form", &flat_ph, &["min_film", "mean_friction_coefficient", "max_flash_temperature"]),
    ];
    for (name, spec, metrics) in cases {
        let base = with(spec, |s| s["angles"] = 720.into());
        let reference_spec = with(&base, |s| {
            s["fidelity"] = "accurate".into();
            s["ehl"] = serde_json::json!({"nodes": 767, "tolerance": 1e-8, "extrapolation": "richardson"});
        });
        let (t_ref, reference) = job(&reference_spec, 1);
        let closed_only = name.contains("Pan–Hamrock");
        // (fidelity, nodes, auto tolerance, Richardson extrapolation, repetitions)
        // `fidelity nodes=a,b,…`: only those Richardson grids (the accuracy ladder's rungs).
        let ladder: Option<Vec<usize>> = std::env::args().find_map(|a| a.strip_prefix("nodes=").map(|l| l.split(',').filter_map(|n| n.parse().ok()).collect()));
        let runs: Vec<(&str, usize, f64, bool, usize)> = if let Some(l) = &ladder {
            if closed_only {
                continue;
            }
            l.iter().map(|&n| ("accurate", n, 0.0, true, 1)).collect()
        } else if closed_only {
            vec![("fast", 0, 0.0, true, 5), ("auto", 192, 0.05, true, 2), ("auto", 192, 0.25, true, 2), ("auto", 192, 1.0, true, 2)]
        } else {
            vec![
                ("fast", 0, 0.0, true, 5),
                ("auto", 192, 0.05, true, 2),
                ("auto", 192, 0.25, true, 2),
                ("accurate", 96, 0.0, true, 2),
                ("accurate", 128, 0.0, true, 2),
                ("accurate", 192, 0.0, true, 2),
                ("accurate", 192, 0.0, false, 2),
                ("accurate", 256, 0.0, true, 2),
                ("accurate", 384, 0.0, true, 1),
            ]
        };
        for (fidelity, nodes, tol, richardson, reps) in runs {
            let s = with(&base, |s| {
                s["fidelity"] = fidelity.into();
                if nodes > 0 {
                    let extrapolation = if richardson { "richardson" } else { "none" };
                    s["ehl"] = serde_json::json!({"nodes": nodes, "tolerance": 1e-6, "auto_tolerance": tol, "extrapolation": extrapolation});
                }
            });
            let (ms, out) = job(&s, reps);
            let numerical = out["summary"]["fidelity_used"]["numerical"].as_u64().unwrap_or(0);
            let fc = (col(&out, "film_central"), col(&reference, "film_central"));
            let fm = (col(&out, "film_min"), col(&reference, "film_min"));
            let others: Vec<String> = metrics
                .iter()
                .map(|m| match (summary(&out, m), summary(&reference, m)) {
                    (Some(a), Some(b)) => format!("{m} {a:.4e} ({:+.1} %)", 100.0 * (a / b - 1.0)),
                    _ => format!("{m} –"),
                })
                .collect();
            let label = match (fidelity, richardson) {
                ("auto", _) => format!("auto (tol {tol})"),
                (_, false) if nodes > 0 => format!("{fidelity}, one grid"),
                _ => fidelity.to_string(),
            };
            println!(
                "| {name} | {label} | {} | {numerical} | {:.2} | {:.2} % ({:.2} %) | {:.2} % ({:.2} %) | {} |",
                if nodes > 0 { nodes.to_string() } else { "–".into() },
                ms / 1e3,
                100.0 * max_rel(&fc.0, &fc.1),
                100.0 * mean_rel(&fc.0, &fc.1),
                100.0 * max_rel(&fm.0, &fm.1),
                100.0 * mean_rel(&fm.0, &fm.1),
                others.join("; ")
            );
        }
        println!("| {name} | reference (accurate) | 767 | 720 | {:.2} | 0 | 0 | |", t_ref / 1e3);
    }
}

/// The measurements behind `physics::film::auto`'s tables: Pan–Hamrock's films and the closed
/// form's traction against the numerical model over Moes M and L (`cargo bench --bench cam --
/// auto-tables`). Steady, R = 15 mm, α = 2.2e-8 1/Pa, η0 = 0.05 Pa·s, Roelands + Dowson–Higginson.
fn auto_tables() {
    use tribod::physics::ehl::formulas::{pan_hamrock_central_film, pan_hamrock_minimum_film, Groups};
    use tribod::physics::ehl::{solve, EhlInput, EhlOptions, Rheology as EhlRheology};
    use tribod::physics::film::{ClosedForm, ContactInput, ContactShape, FilmFormula, FilmModel, Numerical};
    use tribod::physics::friction::{AsperityFriction, AsperityModel, Rheology, Roughness, TractionLaw};
    use tribod::physics::lubricant::Lubricant;
    faer::set_global_parallelism(faer::Par::Seq);
    let es = 210e9 / 0.91 / 2.0;
    let (r, alpha, eta0, len) = (0.015, 2.2e-8, 0.05, 0.012);
    let lub = Lubricant { viscosity: eta0, pressure_viscosity: alpha, ..Lubricant::SEED000 };
    let case = |m: f64, l: f64| {
        let g = alpha * 2.0 * es;
        let u_sum = (l / g).powi(4);
        (m * u_sum.sqrt() * 2.0 * es * r, 0.5 * u_sum * 2.0 * es * r / eta0)
    };
    println!("## Pan–Hamrock against the numerical film (384 nodes): h_PH/h_num − 1, central / minimum (%)\n");
    let ms = [0.5, 1.0, 2.0, 5.0, 10.0, 20.0, 50.0, 100.0, 300.0, 1000.0];
    println!("| L \\ M | {} |", ms.map(|m| m.to_string()).join(" | "));
    println!("|---|{}", "---:|".repeat(ms.len()));
    for l in [4.0, 7.0, 10.0, 14.0, 20.0] {
        let mut row = format!("| {l} |");
        for m in ms {
            let (w, u) = case(m, l);
            let inp = EhlInput {
                load_per_length: w, reduced_radius: r, effective_modulus: 2.0 * es, entrainment_velocity: u,
                sliding_velocity: 0.0, lubricant: lub, temperature: lub.reference_temperature,
                rheology: EhlRheology::default(), transient: None, warm_start: None, asperity: None,
            };
            match solve(&inp, &EhlOptions { nodes: 384, ..Default::default() }, &Silent) {
                Ok(s) => {
                    let g = Groups::of(w, r, 2.0 * es, u, &lub, lub.reference_temperature);
                    row += &format!(
                        " {:+.1} / {:+.1} |",
                        100.0 * (pan_hamrock_central_film(&g, r) / s.central_film - 1.0),
                        100.0 * (pan_hamrock_minimum_film(&g, r) / s.min_film - 1.0)
                    );
                }
                Err(e) => row += &format!(" {e} |"),
            }
        }
        println!("{row}");
    }
    println!("\n## Closed-form traction against the numerical model's nodes (256 nodes): T_closed/T_num − 1 (%)\n");
    let ms = [0.5, 1.0, 2.0, 5.0, 10.0, 30.0, 100.0, 300.0];
    let rough = Roughness { sigma: 0.0, eta_beta_sigma: 0.04, sigma_over_beta: 0.001, plastic_limit: f64::INFINITY, curve: None };
    let asp = AsperityFriction { coefficient: 0.1, model: AsperityModel::Coulomb, map: None };
    let fast = ClosedForm { formula: FilmFormula::PanHamrock, squeeze: false };
    let num = Numerical::new(EhlOptions { nodes: 256, tolerance: 1e-8, ..Default::default() }, fast);
    for (label, law) in [
        ("Newtonian", TractionLaw { rheology: Rheology::Newtonian, limiting_shear_coefficient: None }),
        ("Eyring τ0 = 5 MPa, SRR 0.01", TractionLaw { rheology: Rheology::Eyring { tau0: 5e6 }, limiting_shear_coefficient: None }),
    ] {
        println!("{label}\n\n| L \\ M | {} |", ms.map(|m| m.to_string()).join(" | "));
        println!("|---|{}", "---:|".repeat(ms.len()));
        for l in [4.0, 10.0, 20.0] {
            let mut row = format!("| {l} |");
            for m in ms {
                let (w, u) = case(m, l);
                let input = ContactInput {
                    load: w * len, shape: ContactShape::Line { reduced_radius: r, length: len }, entrainment_velocity: u,
                    sliding_velocity: 0.0, time: 0.0, time_step: 0.0, contact_modulus: es, temperature: lub.reference_temperature,
                    lubricant: &lub, roughness: &rough, traction_law: &law, asperity_friction: &asp, interrupts: tribod::physics::Interrupts::NONE,
                };
                let (Ok(a), Ok(b)) = (fast.solve(&input, None), num.solve(&input, None)) else {
                    row += " – |";
                    continue;
                };
                let us = 0.01 * u;
                row += &format!(" {:+.0} |", 100.0 * (fast.traction(&a, &input, us).viscous / num.traction(&b, &input, us).viscous - 1.0));
            }
            println!("{row}");
        }
        println!();
    }
}

/// The finite roller–pin bearing (issue 14 item 2): table build, one torque call, and the seed
/// 000 steady cycle with the three hydrodynamic pins.
fn pin_table(roller: &Value) {
    use std::cell::Cell;
    use std::sync::Arc;
    use tribod::physics::lubricant::Lubricant;
    use tribod::physics::roller::pin_finite::roller_cooled_area;
    use tribod::physics::roller::{pin_torque_warm, FinitePin, PinFriction, PinTable, PinThermal};
    let ld = 14.0 / 32.0;
    let mut build = f64::INFINITY;
    let mut table = None;
    for _ in 0..5 {
        let t = Instant::now();
        table = Some(PinTable::build(ld, &Silent).unwrap());
        build = build.min(t.elapsed().as_secs_f64() * 1e3);
    }
    let table = Arc::new(table.unwrap());
    println!("## Roller–pin bearing (release)\n");
    println!("Table at L/D = 14/32: {} journal analyses (361 × 41 nodes) in {build:.1} ms (best of 5).\n", table.len());
    let finite = |thermal: bool| {
        PinFriction::FiniteBearing(FinitePin {
            pin_radius: 0.016,
            clearance: 10e-6,
            length: 0.014,
            lubricant: Lubricant::SEED000,
            ambient_temperature: 313.0,
            thermal: thermal.then(|| PinThermal {
                oil_specific_heat: 1700.0,
                oil_density: 870.0,
                convection_coefficient: 80.0,
                cooled_area: roller_cooled_area(0.0255, 0.016, 0.014),
            }),
            table: table.clone(),
        })
    };
    let short = PinFriction::ShortBearing { pin_radius: 0.016, clearance: 10e-6, length: 0.014, viscosity: 0.152 };
    println!("| pin | ns per call, warm (Ω varying by 1e-3) | ns per call, cold (Ω 1–1000 rad/s) |");
    println!("| --- | ---: | ---: |");
    for (name, pin) in [("short bearing (Ocvirk)", short), ("finite, isothermal", finite(false)), ("finite, thermal", finite(true))] {
        let n = 1_000_000;
        let mut acc = 0.0;
        let warm = Cell::new(f64::NAN);
        let t = Instant::now();
        for k in 0..n {
            let omega = 125.0 * (1.0 + 1e-3 * ((k % 1000) as f64 * 1e-3).sin());
            acc += pin_torque_warm(&pin, omega, 600.0 + (k % 7) as f64, 0, &warm).0;
        }
        let warm_ns = t.elapsed().as_secs_f64() / n as f64 * 1e9;
        let t = Instant::now();
        for k in 0..n {
            acc += pin_torque_warm(&pin, 1.0 + (k % 1000) as f64, 600.0, 0, &Cell::new(f64::NAN)).0;
        }
        let cold_ns = t.elapsed().as_secs_f64() / n as f64 * 1e9;
        std::hint::black_box(acc);
        println!("| {name} | {warm_ns:.0} | {cold_ns:.0} |");
    }
    println!("\nSeed 000 steady cycle, all outputs, 3600 angles (best of 10; the job time includes the table build):\n");
    println!("| pin | physics (ms) | job incl. JSON (ms) | mean pin torque (N·m) | SRR at 0° |");
    println!("| --- | ---: | ---: | ---: | ---: |");
    for (name, pin) in [
        ("hydrodynamic (short)", serde_json::json!({"model": "hydrodynamic"})),
        ("finite, isothermal", serde_json::json!({"model": "finite", "thermal": false})),
        ("finite, thermal", serde_json::json!({"model": "finite"})),
    ] {
        let s = with(roller, |s| {
            s["angles"] = 3600.into();
            s["follower"]["pin"] = pin.clone();
        });
        let p = physics_ms(&s, 10);
        let (j, out) = job(&s, 10);
        let tp: Vec<f64> = out["series"]["pin_torque"].as_array().unwrap().iter().map(|v| v.as_f64().unwrap()).collect();
        let mean = tp.iter().map(|x| x.abs()).sum::<f64>() / tp.len() as f64;
        let srr0 = out["series"]["slide_roll_ratio"][0].as_f64().unwrap();
        println!("| {name} | {p:.3} | {j:.3} | {mean:.4} | {srr0:.4} |");
    }
}
