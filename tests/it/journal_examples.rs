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
