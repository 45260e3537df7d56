//! `cam_optimisation` end to end over HTTP (issue 45 item 4): a small search on seed 003's cam
//! that never ends worse than its baseline and keeps its constraints, a Pareto front that is
//! non-dominated, validation errors naming the field, cancellation.

use crate::common::*;
use serde_json::{json, Value};

on_both_backends!(
    a_small_optimisation_beats_its_baseline_within_its_constraints,
    bad_variables_and_quantities_are_named,
    canceling_an_optimisation_stops_it,
);

/// Seed 003's cam (examples/seed003_cycloidal_flat.json) on a coarse fast cycle.
fn seed003_base(angles: usize) -> Value {
    let text = std::fs::read_to_string("examples/seed003_cycloidal_flat.json").unwrap();
    let mut base = serde_json::from_str::<Value>(&text).unwrap()["spec"].clone();
    base["angles"] = json!(angles);
    base["fidelity"] = json!("fast");
    base
}

fn small_spec() -> Value {
    json!({
        "base": seed003_base(180),
        "variables": [
            {"path": "/load/spring_preload", "min": 250.0, "max": 600.0},
            {"path": "/cam/profile/law", "values": ["cycloidal", "polynomial_345"]}
        ],
        "objectives": [{"quantity": "friction_power"}, {"quantity": "max_hertz_pressure", "weight": 0.5}],
        "constraints": [
            {"quantity": "no_separation", "at_rpm": 4000.0},
            {"quantity": "max_hertz_pressure", "max": 1.0, "relative": true}
        ],
        "search": {"samples": 6, "iterations": 8, "starts": 2, "seed": 7}
    })
}

async fn run(s: &TestServer, kind: &str, spec: &Value) -> Value {
    run_id(s, kind, spec).await.1
}

async fn run_id(s: &TestServer, kind: &str, spec: &Value) -> (String, Value) {
    let job = json!({"kind": kind, "spec": spec});
    let res = s.client.post(s.url("/v1/jobs")).header("prefer", "wait=60").json(&job).send().await.unwrap();
    let mut done: Value = res.json().await.unwrap();
    if done["status"] != "succeeded" && done["id"].is_string() {
        let id = done["id"].as_str().unwrap().to_string();
        done = s.wait_finished(&id, std::time::Duration::from_secs(120)).await;
    }
    assert_eq!(done["status"], "succeeded", "{done}");
    let id = done["id"].as_str().unwrap().to_string();
    let result = s.get_json(&format!("/v1/jobs/{id}/result")).await.1;
    (id, result)
}

async fn a_small_optimisation_beats_its_baseline_within_its_constraints() {
    let s = start().await;
    let (id, r) = run_id(&s, "cam_optimisation", &small_spec()).await;
    let (base, best) = (&r["baseline"], &r["best"]);
    let power = |x: &Value| x["friction_power"].as_f64().unwrap();
    eprintln!("friction power {} W → {} W, best {}", power(base), power(best), best["variables"]);
    // The baseline is design 1, the base spec as it is: seed 003's cam cycle at 180 angles.
    assert_eq!(base["design"], 1);
    assert_eq!(r["designs"][0]["phase"], "baseline");
    let cycle = run(&s, "cam_cycle", &seed003_base(180)).await;
    assert!((power(base) / cycle["summary"]["mean_power_loss"].as_f64().unwrap() - 1.0).abs() < 1e-12);
    // Never worse than the (feasible) baseline, every constraint kept with a margin ≥ 0.
    assert_eq!(base["feasible"], true, "{base}");
    assert!(best["score"].as_f64().unwrap() <= base["score"].as_f64().unwrap());
    assert!(power(best) < power(base), "a lighter spring lowers the friction power");
    for c in best["constraints"].as_array().unwrap() {
        assert_eq!(c["satisfied"], true, "{c}");
        assert!(c["margin"].as_f64().unwrap() >= 0.0, "{c}");
    }
    assert_eq!(best["constraints"][0]["unit"], "N");
    assert_eq!(best["constraints"][1]["unit"], "Pa");
    // The separation margin is the design's minimum contact load at 4000 rpm: the cycle of its
    // spec at that speed, loads only, gives the same number.
    let mut at4000 = best["spec"].clone();
    at4000["operation"]["speed_rpm"] = json!(4000.0);
    at4000["outputs"] = json!(["loads"]);
    let check = run(&s, "cam_cycle", &at4000).await;
    let (m, v) = (best["constraints"][0]["value"].as_f64().unwrap(), check["summary"]["min_axial_load"].as_f64().unwrap());
    assert!((m - v).abs() <= 1e-9 * v.abs().max(1.0), "{m} vs {v}");
    // The best design's own spec reproduces its friction power.
    let again = run(&s, "cam_cycle", &best["spec"]).await;
    assert!((again["summary"]["mean_power_loss"].as_f64().unwrap() / power(best) - 1.0).abs() < 1e-12);
    // Every design is a row; the Pareto front is non-dominated among the feasible rows.
    let designs = r["designs"].as_array().unwrap();
    assert_eq!(designs.len() as u64, r["evaluations"].as_u64().unwrap());
    assert!(designs.len() <= 1 + 6 + 2 * 8);
    let feasible: Vec<(f64, f64)> = designs
        .iter()
        .filter(|d| d["feasible"] == true)
        .map(|d| (d["friction_power"].as_f64().unwrap(), d["max_hertz_pressure"].as_f64().unwrap()))
        .collect();
    assert_eq!(feasible.len() as u64, r["feasible_count"].as_u64().unwrap());
    let front = r["pareto"]["designs"].as_array().unwrap();
    assert!(!front.is_empty());
    for d in front {
        let row = &designs[d.as_u64().unwrap() as usize - 1];
        let (a, b) = (row["friction_power"].as_f64().unwrap(), row["max_hertz_pressure"].as_f64().unwrap());
        assert_eq!(row["feasible"], true);
        assert!(!feasible.iter().any(|&(x, y)| x <= a && y <= b && (x < a || y < b)), "design {d} is dominated");
    }
    // The table as CSV, with units in the header.
    let csv = s.client.get(s.url(&format!("/v1/jobs/{id}/result"))).header("accept", "text/csv").send().await.unwrap().text().await.unwrap();
    let header = csv.lines().next().unwrap();
    assert!(header.contains("load.spring_preload [N]") && header.contains("friction_power [W]"), "{header}");
    s.stop().await;
}

async fn bad_variables_and_quantities_are_named() {
    let s = start_with(|c| {
        c.queue.limits.max_evaluations = 100;
        c.queue.limits.max_job_seconds = 3.0;
    })
    .await;
    let cases: Vec<(Value, &str, &str)> = vec![
        (json!({"variables": [{"path": "load/spring_preload", "min": 250.0, "max": 600.0}]}), "/spec/variables/0/path", "JSON pointer"),
        (json!({"variables": [{"path": "/load/spring_preload", "min": 600.0, "max": 250.0}]}), "/spec/variables/0/max", "min < max"),
        (json!({"variables": [{"path": "/cam/width", "min": -0.01, "max": 0.03}]}), "/spec/variables/0", "/cam/width = -0.01"),
        (json!({"variables": [{"path": "/load/spring_preload"}]}), "/spec/variables/0", "exactly one of"),
        (json!({"objectives": [{"quantity": "/summary/no_such_number"}]}), "/spec/objectives/0/quantity", "unknown quantity"),
        (json!({"objectives": [{"quantity": "no_separation"}]}), "/spec/objectives/0/quantity", "constraint"),
        (json!({"constraints": [{"quantity": "no_separation"}]}), "/spec/constraints/0/at_rpm", "rpm"),
        (json!({"constraints": [{"quantity": "min_film"}]}), "/spec/constraints/0", "`min` or `max`"),
        (json!({"base": {"angles": 2}}), "/spec/base/angles", ""),
    ];
    for (patch, path, words) in cases {
        let mut spec = small_spec();
        tribod::jobs::kind::merge_patch(&mut spec, patch.clone());
        let p = expect_problem(s.post_job(&json!({"kind": "cam_optimisation", "spec": spec})).await, 422, "invalid_spec").await;
        let e = p["errors"].as_array().unwrap().iter().find(|e| e["path"] == path).unwrap_or_else(|| panic!("{patch}: no error at {path}: {p}"));
        assert!(e["message"].as_str().unwrap().contains(words), "{patch}: {e}");
    }
    let mut spec = small_spec();
    spec["search"] = json!({"samples": 90, "iterations": 10, "starts": 2});
    let p = expect_problem(s.post_job(&json!({"kind": "cam_optimisation", "spec": spec})).await, 422, "limit_exceeded").await;
    assert_eq!(p["errors"][0]["path"], "/spec/search", "{p}");
    // Within the design count but over the work limit: designs × 2 cycles × the cycle's estimate.
    let mut spec = small_spec();
    spec["base"]["angles"] = json!(720);
    spec["search"] = json!({"samples": 90, "iterations": 0});
    let p = expect_problem(s.post_job(&json!({"kind": "cam_optimisation", "spec": spec})).await, 422, "limit_exceeded").await;
    assert_eq!(p["errors"][0]["path"], "/spec/search", "{p}");
    assert!(p["errors"][0]["message"].as_str().unwrap().contains("91 designs, 182 cam cycles"), "{p}");
    s.stop().await;
}

async fn canceling_an_optimisation_stops_it() {
    let s = start().await;
    let mut spec = small_spec();
    spec["base"]["angles"] = json!(720);
    spec["search"] = json!({"samples": 600, "iterations": 0});
    let created: Value = s.post_job(&json!({"kind": "cam_optimisation", "spec": spec})).await.json().await.unwrap();
    let id = created["id"].as_str().unwrap_or_else(|| panic!("{created}")).to_string();
    s.wait_status(&id, "running", std::time::Duration::from_secs(10)).await;
    tokio::time::sleep(std::time::Duration::from_millis(500)).await;
    let t0 = std::time::Instant::now();
    let res = s.client.delete(s.url(&format!("/v1/jobs/{id}"))).send().await.unwrap();
    assert_eq!(res.status().as_u16(), 202);
    let done = s.wait_finished(&id, std::time::Duration::from_secs(30)).await;
    assert_eq!(done["status"], "canceled", "{done}");
    assert!(t0.elapsed().as_secs_f64() < 3.0, "took {:?}", t0.elapsed());
    s.stop().await;
}

/// A dynamic train (seed 003's, `seed003_dynamic.json`): `no_separation` at 3300 rpm reads the
/// integrated train's contact, so feasibility is monotone in the spring preload — every design
/// below some preload separates, every one above keeps contact — and the cheapest feasible
/// design (least friction) is the lightest spring that keeps contact.
#[test]
fn no_separation_of_a_dynamic_train_is_monotone_in_the_preload() {
    let mut base = crate::in_process::example("seed003_dynamic");
    base["angles"] = json!(180);
    base["fidelity"] = json!("fast");
    let spec = json!({
        "base": base,
        "variables": [{"path": "/load/spring_preload", "min": 100.0, "max": 400.0}],
        "objectives": [{"quantity": "friction_power"}],
        "constraints": [{"quantity": "no_separation", "at_rpm": 3300.0}],
        "search": {"samples": 8, "iterations": 0}
    });
    let r = crate::in_process::run("cam_optimisation", &spec).unwrap();
    let mut rows: Vec<(f64, bool, f64)> = r["designs"]
        .as_array()
        .unwrap()
        .iter()
        .map(|d| (d["load.spring_preload"].as_f64().unwrap(), d["feasible"] == true, d["friction_power"].as_f64().unwrap_or(f64::NAN)))
        .collect();
    rows.sort_by(|a, b| a.0.total_cmp(&b.0));
    eprintln!("(preload N, feasible, friction W): {rows:?}");
    let first = rows.iter().position(|r| r.1).expect("a feasible design");
    assert!(first > 0, "the lightest springs separate at 3300 rpm: {rows:?}");
    assert!(rows[first..].iter().all(|r| r.1), "{rows:?}");
    // Friction grows with the preload, so the best is the lightest feasible spring. The lightest
    // springs lose contact even at the base speed: their cycles fail (`follower_separation`),
    // rows without a friction power.
    let ran: Vec<f64> = rows.iter().map(|r| r.2).filter(|f| f.is_finite()).collect();
    assert!(ran.len() >= rows.len() - first && ran.windows(2).all(|w| w[1] > w[0]), "{rows:?}");
    assert_eq!(r["best"]["variables"]["/load/spring_preload"].as_f64().unwrap(), rows[first].0);
    assert!(r["best"]["friction_power"].as_f64().unwrap() <= r["baseline"]["friction_power"].as_f64().unwrap());
}

/// A wear objective (`wear_depth`, seed 003's Archard example over 100 h): every design also runs
/// the `wear` job on its cycle; the best design's wear depth is the wear job of its own spec, and
/// a wear quantity without the wear fields is refused naming `/wear`.
#[test]
fn a_wear_objective_runs_the_wear_job_of_each_design() {
    let mut wear = crate::in_process::example("seed003_flat_archard");
    let mut base = wear.as_object_mut().unwrap().remove("cycle").unwrap();
    base["angles"] = json!(180);
    wear["hours"] = json!(100.0);
    wear["update_interval_hours"] = json!(50.0);
    let spec = json!({
        "base": base, "wear": wear,
        "variables": [{"path": "/load/spring_preload", "min": 300.0, "max": 400.0}, {"path": "/cam/width", "min": 0.01, "max": 0.02}],
        "objectives": [{"quantity": "wear_depth"}],
        "constraints": [{"quantity": "wear:hours_to_limit_extrapolated", "min": 1000.0}],
        "search": {"samples": 4, "iterations": 4, "starts": 1}
    });
    let r = crate::in_process::run("cam_optimisation", &spec).unwrap();
    let depth = |x: &Value| x["objectives"]["wear_depth"].as_f64().unwrap();
    assert!(depth(&r["best"]) <= depth(&r["baseline"]), "{} {}", r["best"], r["baseline"]);
    assert_eq!(r["units"]["wear_depth"], "m");
    assert_eq!(r["best"]["constraints"][0]["unit"], "h");
    let mut again = wear.clone();
    again["cycle"] = r["best"]["spec"].clone();
    let w = crate::in_process::run("wear", &again).unwrap();
    assert!((w["summary"]["max_wear_depth"].as_f64().unwrap() / depth(&r["best"]) - 1.0).abs() < 1e-12);
    let mut bad = spec.clone();
    bad.as_object_mut().unwrap().remove("wear");
    let Err(crate::in_process::Failure::Spec(p)) = crate::in_process::run("cam_optimisation", &bad) else { panic!("accepted without `wear`") };
    assert_eq!(p.errors[0].path, "/wear", "{p:?}");
}

/// Issue 45: the synthesised cam optimised (examples/seed003_cam_optimisation_synthesised.json,
/// a smaller search): seed 003's lift and event duration, the law, ramp, base radius and spring
/// as variables. The best design is feasible and no worse than the baseline (the example's
/// full search: friction power 107.6 W → 62.3 W, −42 %, docs/kinds/cam_optimisation.md).
#[test]
fn the_synthesised_cam_optimises_within_its_constraints() {
    let mut spec = crate::in_process::example("seed003_cam_optimisation_synthesised");
    spec["search"] = json!({"samples": 8, "iterations": 6, "starts": 1, "seed": 1});
    let r = crate::in_process::run("cam_optimisation", &spec).unwrap();
    let (base, best) = (&r["baseline"], &r["best"]);
    let power = |x: &Value| x["friction_power"].as_f64().unwrap();
    eprintln!("synthesised: {} W → {} W, {}", power(base), power(best), best["variables"]);
    assert_eq!(base["feasible"], true, "{base}");
    assert_eq!(best["feasible"], true, "{best}");
    assert!(best["score"].as_f64().unwrap() <= base["score"].as_f64().unwrap());
    assert!(power(best) <= power(base));
    for c in best["constraints"].as_array().unwrap() {
        assert!(c["margin"].as_f64().unwrap() >= 0.0, "{c}");
    }
    // Same lift and event duration as seed 003's cam in every design.
    assert_eq!(best["spec"]["cam"]["profile"]["lift"], json!(0.013998));
    assert_eq!(best["spec"]["cam"]["profile"]["duration_deg"], json!(268.55));
}

/// Issue 45: a design whose cam undercuts is infeasible with a named `no_undercut` margin (the
/// signed undercut margin, `r_b + s + s''` for the flat face: negative), not a lost evaluation;
/// the plain cycle of the same design still refuses with `cam_undercut`, saying why.
#[test]
fn undercut_designs_are_infeasible_with_a_margin() {
    let mut spec = crate::in_process::example("seed003_cam_optimisation_synthesised");
    spec["variables"] = json!([{"path": "/cam/profile/base_radius", "min": 0.002, "max": 0.005}]);
    spec["search"] = json!({"samples": 3, "iterations": 0, "seed": 1});
    let r = crate::in_process::run("cam_optimisation", &spec).unwrap();
    let rows: Vec<&Value> = r["designs"].as_array().unwrap().iter().filter(|d| d["phase"] != "baseline").collect();
    assert_eq!(rows.len(), 3);
    for d in &rows {
        let (value, margin) = (d["no_undercut"].as_f64().unwrap(), d["no_undercut.margin"].as_f64().unwrap());
        assert_eq!(d["feasible"], false, "{d}");
        assert!(value < 0.0 && (margin - (value - 0.002)).abs() < 1e-15, "{d}");
        assert!(d.get("friction_power").is_none_or(Value::is_null), "{d}");
    }
    // The cycle of the smallest cam: refused, naming the rule and the radius.
    let mut cycle = spec["base"].clone();
    cycle["cam"]["profile"]["base_radius"] = json!(0.002);
    match crate::in_process::run("cam_cycle", &cycle) {
        Err(crate::in_process::Failure::Solve(e)) => {
            let text = format!("{e:?}");
            assert!(text.contains("CamUndercut") && text.contains("r_b + s + s''") && text.contains("base radius"), "{text}");
            // The field and the cycle's margin, the same number as the optimisation's row.
            let m = rows.iter().map(|d| d["no_undercut"].as_f64().unwrap()).fold(f64::INFINITY, f64::min);
            assert!(text.contains("field /cam/profile/base_radius") && text.contains("must be > 0 mm"), "{text}");
            eprintln!("{text} (smallest margin in the rows {:.4} mm)", m * 1e3);
        }
        other => panic!("{other:?}"),
    }
}

/// Issue 45: the spring checks are constraints when the base's `dynamic` load has a
/// `spring.design` (`seed003_dynamic_springs.json` on the synthesised cam of seed 003's lift and
/// duration): `min_spring_fatigue_safety_factor` and `min_coil_clash_margin` are read from each
/// design's cycle, with their units and margins.
#[test]
fn spring_checks_are_constraints_of_a_dynamic_base() {
    let mut base = crate::in_process::example("seed003_dynamic_springs");
    base["cam"]["profile"] = crate::in_process::example("seed003_synthesised")["cam"]["profile"].clone();
    base["operation"]["speed_rpm"] = json!(2672.0);
    base["angles"] = json!(180);
    base["fidelity"] = json!("fast");
    let spec = json!({
        "base": base,
        "variables": [{"path": "/load/spring/design/installed_length", "min": 0.034, "max": 0.038}],
        "objectives": [{"quantity": "friction_power"}],
        "constraints": [
            {"quantity": "min_spring_fatigue_safety_factor", "min": 1.1},
            {"quantity": "min_coil_clash_margin", "min": 0.0}
        ],
        "search": {"samples": 3, "iterations": 0, "seed": 1}
    });
    let r = crate::in_process::run("cam_optimisation", &spec).unwrap();
    let best = &r["best"];
    eprintln!("spring checks: {}", best["constraints"]);
    assert_eq!(best["constraints"][0]["unit"], "1");
    assert_eq!(best["constraints"][1]["unit"], "m");
    for d in r["designs"].as_array().unwrap() {
        let (sf, clash) = (d["min_spring_fatigue_safety_factor"].as_f64().unwrap(), d["min_coil_clash_margin"].as_f64().unwrap());
        assert!((d["min_spring_fatigue_safety_factor.margin"].as_f64().unwrap() - (sf - 1.1)).abs() < 1e-12, "{d}");
        assert!((d["min_coil_clash_margin.margin"].as_f64().unwrap() - clash).abs() < 1e-15, "{d}");
        assert_eq!(d["feasible"], sf >= 1.1 && clash >= 0.0, "{d}");
    }
}
