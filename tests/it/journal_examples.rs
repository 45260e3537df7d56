//! Every `examples/seed002_*.json` parses, validates and solves through the job registry (what
//! `tribod run` does), and the result carries the contract's fields.
use serde_json::Value;
use tribod::jobs::registry;
use tribod::jobs::Limits;
use tribod::physics::Silent;

fn run(path: &str) -> Value {
    let text = std::fs::read_to_string(path).unwrap();
    let doc: Value = serde_json::from_str(&text).unwrap();
    let kind = registry::find(doc["kind"].as_str().unwrap()).expect("registered kind");
    let prepared = kind.prepare(&doc["spec"], &Limits::default()).unwrap_or_else(|p| panic!("{path}: {p}"));
    prepared.run(&Silent).unwrap_or_else(|e| panic!("{path}: {e}"))
}

#[test]
fn bearing_examples_run() {
    for name in ["seed002_aligned", "seed002_misaligned", "seed002_optimised"] {
        let r = run(&format!("examples/{name}.json"));
        for key in [
            "eccentricity_ratio", "attitude_angle_deg", "sommerfeld_number", "max_pressure_dimensionless",
            "min_film_dimensionless", "friction_variable", "flow_variable", "side_flow_ratio", "convergence",
            "max_pressure", "min_film", "power_loss",
        ] {
            assert!(r.get(key).is_some(), "{name}: missing {key} in {r}");
        }
        eprintln!("{name}: {}", serde_json::to_string(&r).unwrap());
    }
}

#[test]
fn taguchi_example_runs() {
    let r = run("examples/seed002_taguchi_l9.json");
    let runs = r["runs"].as_array().unwrap();
    assert_eq!(runs.len(), 9);
    for key in ["order", "height", "length_fraction", "max_pressure_dimensionless", "min_film_dimensionless", "friction_variable", "score"] {
        assert!(runs[0].get(key).is_some(), "missing {key}");
    }
    assert!(r["best_run"].as_u64().unwrap() >= 1);
    assert!(r.get("best_levels").is_some());
    let c = &r["continuous"];
    assert!(c["improves_on_taguchi"].as_bool().unwrap(), "{c}");
    eprintln!("{}", serde_json::to_string_pretty(&r).unwrap());
    // The array's best run (5: n = 2, ξ = 0.4, ψ = 0.4) scores 0.984, above the paper's best-level
    // combination (n = 2, ξ = 0.4, ψ = 0.2, its confirmation run) at 0.809; the continuous search
    // starts from the best of them and reaches 1.011 (order 1). The result recommends it and says
    // that it beat the best run.
    let score = |v: &Value| v["score"].as_f64().unwrap();
    assert_eq!(r["best_run"], 5);
    let (run5, levels, cont) = (score(&runs[4]), score(&r["best_levels"]["design"]), score(&c["design"]));
    assert!((run5 - 0.984).abs() < 1e-3 && (levels - 0.809).abs() < 1e-3, "{run5} {levels}");
    assert!((cont - 1.011).abs() < 1e-3, "{cont}");
    assert_eq!(c["beats_best_run"], true);
    let rec = &r["recommended"];
    assert_eq!(rec["source"], "continuous");
    assert_eq!(rec["design"], c["design"]);
    assert!(rec.get("run").is_none());
}

/// The recommendation is the best of the best run, the best-level confirmation and the continuous
/// design (and the baseline): without the search it is the array's run 5 (the paper's best-level
/// combination scores lower in this model); with the shortest search (5 evaluations per order,
/// no polish) the continuous design still never scores below where it started. Coarse grid
/// (61 × 31) to keep it quick; the scores are on that grid's normalisation.
#[test]
fn recommended_design_is_the_best_of_array_confirmation_and_search() {
    let text = std::fs::read_to_string("examples/seed002_taguchi_l9.json").unwrap();
    let mut doc: Value = serde_json::from_str(&text).unwrap();
    doc["spec"]["base"]["grid"] = serde_json::json!({"circumferential": 61, "axial": 31});
    let kind = registry::find("bearing_optimisation").unwrap();
    let solve = |cont: Value| {
        let mut spec = doc["spec"].clone();
        spec["continuous"] = cont;
        kind.prepare(&spec, &Limits::default()).unwrap().run(&Silent).unwrap()
    };
    let score = |v: &Value| v["score"].as_f64().unwrap();
    let off = solve(serde_json::json!({"enabled": false}));
    let best_run = off["best_run"].as_u64().unwrap() as usize;
    let run_score = score(&off["runs"][best_run - 1]);
    let levels = score(&off["best_levels"]["design"]);
    println!("best run {best_run} {run_score:.4}, best levels {levels:.4}, baseline {:.4}", score(&off["baseline"]));
    assert!(run_score > levels);
    assert_eq!(off["recommended"]["source"], "array_run");
    assert_eq!(off["recommended"]["run"].as_u64(), Some(best_run as u64));
    assert_eq!(score(&off["recommended"]["design"]), run_score);
    let short = solve(serde_json::json!({"evaluations_per_order": 5, "coarse_search": false}));
    let c = &short["continuous"];
    let cont = score(&c["design"]);
    println!("short search: {cont:.4} (order {}), beats the best run: {}", c["design"]["order"], c["beats_best_run"]);
    assert!(cont >= run_score.max(levels), "{cont} below the start {run_score}");
    assert_eq!(c["beats_best_run"].as_bool().unwrap(), cont > run_score);
    for d in c["per_order"].as_array().unwrap() {
        // each order starts from its best run, so no order ends below its best run
        let n = d["order"].as_u64().unwrap();
        let best_of_order = short["runs"].as_array().unwrap().iter().filter(|r| r["order"].as_u64() == Some(n)).map(score).fold(0.0, f64::max);
        assert!(score(d) >= best_of_order, "order {n}: {} < {best_of_order}", score(d));
    }
    let rec = score(&short["recommended"]["design"]);
    assert_eq!(rec, cont.max(run_score).max(levels).max(score(&short["baseline"])));
}

/// Seed 002 Table 6, aligned column (80 mm wide, 64 mm bore, c = 0.1175 mm, ε = 0.6, 3000 rpm,
/// 0.0293 Pa·s): h_min 47.000 µm, p_max 2.63966 MPa. Model (361 × 181): 47.0 µm, 2.6405 MPa.
#[test]
fn seed002_table6_aligned_in_si_units() {
    let r = run("examples/seed002_aligned.json");
    let (h, p) = (r["min_film"].as_f64().unwrap(), r["max_pressure"].as_f64().unwrap());
    println!("Table 6 aligned: h_min {:.4} µm (paper 47.000), p_max {:.5} MPa (paper 2.63966)", h * 1e6, p * 1e-6);
    assert!((h / 47.0e-6 - 1.0).abs() < 1e-3, "{h}");
    assert!((p / 2.63966e6 - 1.0).abs() < 1e-3, "{p}");
}

/// Seed 002 Table 5 (n = 2, ξ = 0.4, ψ = 0.2 against the misaligned bearing Δh0 = Δv0 = 0.56,
/// same load): the profile lowers P0 and f and raises H0, the film "almost doubled". Model: P0
/// 1.396 → 0.863, f 2.717 → 2.525, H0 0.0403 → 0.177, ×4.4, because its misaligned film is half the
/// paper's 0.0820 (the Table 2 misaligned difference, docs/seeds.md); against the paper's 0.0820
/// the profiled film is ×2.15, the paper's "almost doubled". Table 6's misaligned column (9.635 µm,
/// 3.578 MPa) differs for the same reason (model 4.73 µm, 5.72 MPa).
#[test]
fn seed002_table5_profile_direction() {
    let mis = run("examples/seed002_misaligned.json");
    let opt = run("examples/seed002_optimised.json");
    let g = |r: &Value, k: &str| r[k].as_f64().unwrap();
    for k in ["max_pressure_dimensionless", "min_film_dimensionless", "friction_variable", "friction_variable_seed002", "min_film", "max_pressure"] {
        println!("{k}: misaligned {:.5e}, profiled {:.5e}", g(&mis, k), g(&opt, k));
    }
    assert!(g(&opt, "max_pressure_dimensionless") < g(&mis, "max_pressure_dimensionless"));
    assert!(g(&opt, "friction_variable") < g(&mis, "friction_variable"));
    assert!(g(&opt, "friction_variable_seed002") < g(&mis, "friction_variable_seed002"));
    let ratio = g(&opt, "min_film_dimensionless") / g(&mis, "min_film_dimensionless");
    assert!((ratio - 4.39).abs() < 0.05, "{ratio}");
    let against_paper = g(&opt, "min_film_dimensionless") / 0.0820;
    assert!((1.8..2.5).contains(&against_paper), "{against_paper}");
}

#[test]
fn every_example_validates() {
    for entry in std::fs::read_dir("examples").unwrap() {
        let path = entry.unwrap().path();
        if path.extension().and_then(|e| e.to_str()) != Some("json") {
            continue;
        }
        let doc: Value = serde_json::from_str(&std::fs::read_to_string(&path).unwrap()).unwrap();
        let kind = registry::find(doc["kind"].as_str().unwrap()).expect("registered kind");
        kind.prepare(&doc["spec"], &Limits::default()).unwrap_or_else(|p| panic!("{}: {p}", path.display()));
    }
}

/// Seed 002 Figs. 8–10: the score over (n, ξ), (ξ, ψ) and (n, ψ), the third factor at its best
/// level (`outputs: ["score_grid"]`; every cell a bearing analysis, not the paper's interpolation
/// of nine runs). Coarse grid (61 × 31), 3 even values per axis besides the levels. The paper
/// reads its optimum n = 2, ξ = 0.4, ψ = 0.2 off these maps; the model's maps put the best-level
/// cell at the confirmation run's score and their maxima elsewhere (printed; the best of the
/// (ξ, ψ) map at n = 2 lies at ψ = 0.4, where run 5 sits).
#[test]
fn seed002_score_maps_over_two_factors() {
    let text = std::fs::read_to_string("examples/seed002_taguchi_l9.json").unwrap();
    let mut doc: Value = serde_json::from_str(&text).unwrap();
    let spec = &mut doc["spec"];
    spec["base"]["grid"] = serde_json::json!({"circumferential": 61, "axial": 31});
    spec["continuous"] = serde_json::json!({"enabled": false});
    spec["outputs"] = serde_json::json!(["score_grid"]);
    spec["score_grid_points"] = serde_json::json!(3);
    let kind = registry::find("bearing_optimisation").unwrap();
    let r = kind.prepare(spec, &Limits::default()).unwrap().run(&Silent).unwrap();
    let grids = r["score_grids"].as_array().unwrap();
    assert_eq!(grids.len(), 3);
    let confirmation = r["best_levels"]["design"]["score"].as_f64().unwrap();
    let best = [("order", 2.0), ("height", 0.4), ("length_fraction", 0.2)];
    let value = |f: &str| best.iter().find(|b| b.0 == f).unwrap().1;
    let mut map_max: Vec<(f64, f64, f64)> = Vec::new();
    for g in grids {
        let (xf, yf) = (g["x_factor"].as_str().unwrap(), g["y_factor"].as_str().unwrap());
        let nums = |v: &Value| v.as_array().unwrap().iter().map(|x| x.as_f64().unwrap()).collect::<Vec<f64>>();
        let (x, y) = (nums(&g["x"]), nums(&g["y"]));
        let z: Vec<Vec<f64>> = g["score"].as_array().unwrap().iter().map(nums).collect();
        assert_eq!(z.len(), y.len());
        assert!(z.iter().all(|row| row.len() == x.len() && row.iter().all(|s| s.is_finite() && *s > 0.0)));
        assert_eq!(g["held_value"].as_f64().unwrap(), value(g["held_factor"].as_str().unwrap()));
        let i = x.iter().position(|v| (v - value(xf)).abs() < 1e-12).expect("the best level is a cell");
        let j = y.iter().position(|v| (v - value(yf)).abs() < 1e-12).expect("the best level is a cell");
        println!("{xf} × {yf}: x {x:?}, y {y:?}");
        for (yj, row) in y.iter().zip(&z) {
            println!("  {yf} {yj:.3}: {}", row.iter().map(|s| format!("{s:.4}")).collect::<Vec<_>>().join(" "));
        }
        assert!((z[j][i] - confirmation).abs() < 1e-6 * confirmation, "{} vs {confirmation}", z[j][i]);
        let (mut bi, mut bj) = (0, 0);
        for jj in 0..y.len() {
            for ii in 0..x.len() {
                if z[jj][ii] > z[bj][bi] {
                    (bi, bj) = (ii, jj);
                }
            }
        }
        println!("  maximum {:.4} at {xf} {}, {yf} {}", z[bj][bi], x[bi], y[bj]);
        map_max.push((x[bi], y[bj], z[bj][bi]));
    }
    // drawn as heat maps, one per pair
    let names: Vec<String> = tribod::plots::available("bearing_optimisation", &r).into_iter().map(|p| p.name).collect();
    for k in 1..=3 {
        assert!(names.contains(&format!("score_map_{k}")), "{names:?}");
    }
    // (ξ, ψ) at n = 2: the model's best cell is at ψ = 0.4 and scores above the confirmation
    let (_, psi, top) = map_max[1];
    assert_eq!(psi, 0.4);
    assert!(top > confirmation);
}
