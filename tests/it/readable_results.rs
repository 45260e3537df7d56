//! Results an engineer can read (issue 39): a unit for every numeric result field, CSV headers
//! with units, plausibility warnings (and `?strict=true`), labels that tell jobs apart, sweep
//! columns named by what they are, tick labels that differ.

use crate::common::*;
use serde_json::{json, Value};
use std::time::Duration;
use tribod::jobs::registry;
use tribod::jobs::units::{unit_at, unit_of};

#[test]
fn every_numeric_result_field_of_every_kind_has_a_unit() {
    let mut missing = Vec::new();
    for k in registry::KINDS.iter() {
        let fields = k.documented_units(false);
        assert!(k.name() == "sweep" || fields.len() >= 3, "{}: {} numeric fields found", k.name(), fields.len());
        for (pointer, unit) in fields {
            if unit.is_none() {
                missing.push(format!("{} {pointer}", k.name()));
            }
        }
    }
    assert!(missing.is_empty(), "numeric result fields whose doc names no unit (add ', <unit>.' or a pure-number cue):\n{}", missing.join("\n"));
}

#[test]
fn units_are_read_from_the_field_docs_and_names() {
    assert_eq!(unit_of("film_min", "Minimum film, m."), Some("m"));
    assert_eq!(unit_of("max_pressure", "Maximum pressure at pure rolling, Pa (the Hertz p0 for closed forms)."), Some("Pa"));
    assert_eq!(unit_of("hertz_max_pressure", "Pa."), Some("Pa"));
    assert_eq!(unit_of("pressure_spike_position", "Its position, m from the contact centre."), Some("m"));
    assert_eq!(unit_of("sliding_velocity", "u_c − u_r, m/s."), Some("m/s"));
    assert_eq!(unit_of("angle_deg", "Cam angle."), Some("°"));
    assert_eq!(unit_of("lambda", "h_min/σ at pure rolling (rough surfaces)."), Some("1"));
    assert_eq!(unit_of("power_loss", "Friction power, W."), Some("W"));
    assert_eq!(unit_of("flow", "Q, m³/s (with dimensions)."), Some("m³/s"));
    assert_eq!(unit_of("mystery", "Something."), None);
    // Kinds' tables as the service lists them.
    let cam = registry::find("cam_cycle").unwrap();
    let units = cam.result_units();
    assert_eq!(units.get("/series/film_min").map(String::as_str), Some("m"));
    assert_eq!(units.get("/series/angle_deg").map(String::as_str), Some("°"));
    assert_eq!(units.get("/series/cam_curvature").map(String::as_str), Some("1/m"));
    assert_eq!(unit_at(units, "/series/film_min/200"), Some("m"));
    let bearing = registry::find("bearing").unwrap().result_units();
    assert_eq!(bearing.get("/eccentricity_ratio").map(String::as_str), Some("1"));
}

#[test]
fn tick_labels_differ_and_are_scaled() {
    use tribod::plots::draw::ticker;
    for (lo, hi) in [(1e-7, 3e-7), (0.5, 0.5001), (0.0, 1.0), (-1e9, 2e9), (0.1, 0.9), (300.0, 300.02), (-2e-5, 4e-5)] {
        let t = ticker(lo, hi);
        let labels: Vec<String> = (0..=10).map(|i| t(&(lo + (hi - lo) * i as f64 / 10.0))).collect();
        let mut unique = labels.clone();
        unique.dedup();
        assert_eq!(unique.len(), labels.len(), "{lo}..{hi}: {labels:?}");
    }
    let (f, label) = tribod::plots::scale::axis("min_film", "m", [1e-7, 3e-7].into_iter());
    assert_eq!(label, "min_film, µm");
    assert!((3e-7 * f - 0.3).abs() < 1e-9);
    let (_, label) = tribod::plots::scale::axis("max_pressure", "Pa", [1.2e9].into_iter());
    assert_eq!(label, "max_pressure, GPa");
    let (_, label) = tribod::plots::scale::axis("slide_roll_ratio", "1", [0.3].into_iter());
    assert_eq!(label, "slide_roll_ratio");
}

const LONG: Duration = Duration::from_secs(30);

fn hertz(radius: f64, load: f64) -> Value {
    json!({"kind": "hertz", "spec": {"contact": "line", "load": load, "length": 0.014,
        "body_1": {"shape": "cylinder", "radius": radius}, "body_2": {"shape": "cylinder", "radius": 0.02}, "outputs": ["stress_profile"]}})
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn kinds_list_units_and_csv_headers_carry_them() {
    let s = start().await;
    let (status, kinds) = s.get_json("/v1/kinds").await;
    assert_eq!(status, 200);
    for k in kinds["kinds"].as_array().unwrap() {
        let units = k["result_units"].as_object().unwrap_or_else(|| panic!("{}: no result_units", k["name"]));
        assert!(k["name"] == "sweep" || !units.is_empty(), "{}", k["name"]);
    }
    let hertz_units = &kinds["kinds"].as_array().unwrap().iter().find(|k| k["name"] == "hertz").unwrap()["result_units"];
    assert_eq!(hertz_units["/max_pressure"], "Pa");
    assert_eq!(hertz_units["/half_width"], "m");

    let job: Value = s.post_job(&hertz(0.0255, 5000.0)).await.json().await.unwrap();
    let id = job["id"].as_str().unwrap();
    assert_eq!(s.wait_finished(id, LONG).await["status"], "succeeded");
    let csv = s.client.get(s.url(&format!("/v1/jobs/{id}/result?format=csv&table=stress_profile"))).send().await.unwrap().text().await.unwrap();
    let header = csv.lines().next().unwrap();
    assert!(header.contains("depth [m]"), "{header}");
    assert!(header.split(',').any(|c| c.ends_with("[Pa]")), "{header}");
    s.stop().await;
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn implausible_values_warn_and_strict_refuses_them() {
    let s = start().await;
    let res = s.post_job(&hertz(25.5, 5000.0)).await;
    assert_eq!(res.status().as_u16(), 202);
    let job: Value = res.json().await.unwrap();
    let w = job["warnings"].as_array().unwrap_or_else(|| panic!("no warnings: {job}"));
    assert_eq!(w.len(), 1, "{w:?}");
    assert_eq!(w[0]["path"], "/spec/body_1/radius");
    assert!(w[0]["message"].as_str().unwrap().contains("millimetres"), "{w:?}");
    let id = job["id"].as_str().unwrap();
    let (_, again) = s.get_json(&format!("/v1/jobs/{id}")).await;
    assert_eq!(again["warnings"][0]["path"], "/spec/body_1/radius");
    // A plausible spec has none.
    let ok: Value = s.post_job(&hertz(0.0255, 5000.0)).await.json().await.unwrap();
    assert!(ok.get("warnings").is_none(), "{ok}");
    // Strict: the warning refuses the spec.
    let res = s.client.post(s.url("/v1/jobs?strict=true")).json(&hertz(25.5, 5001.0)).send().await.unwrap();
    let p = expect_problem(res, 422, "invalid_spec").await;
    assert_eq!(p["errors"][0]["path"], "/spec/body_1/radius");
    s.stop().await;
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn jobs_without_a_label_get_one_that_tells_them_apart() {
    let s = start().await;
    let a: Value = s.post_job(&hertz(0.0255, 5000.0)).await.json().await.unwrap();
    let b: Value = s.post_job(&hertz(0.0255, 7000.0)).await.json().await.unwrap();
    let (la, lb) = (a["label"].as_str().unwrap(), b["label"].as_str().unwrap());
    assert!(la.starts_with("hertz"), "{la}");
    assert_ne!(la, lb);
    assert!(lb.contains("load=7000"), "{lb}");
    // The kind's example itself.
    let (_, kinds) = s.get_json("/v1/kinds").await;
    let example = kinds["kinds"].as_array().unwrap().iter().find(|k| k["name"] == "hertz").unwrap()["example"].clone();
    let e: Value = s.post_job(&json!({"kind": "hertz", "spec": example})).await.json().await.unwrap();
    assert!(e["label"].as_str().unwrap().starts_with("hertz · example"), "{e}");
    // A label given is kept.
    let mut named = hertz(0.0255, 9000.0);
    named["label"] = json!("my roller");
    let n: Value = s.post_job(&named).await.json().await.unwrap();
    assert_eq!(n["label"], "my roller");
    s.stop().await;
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn sweep_columns_are_named_by_angle_and_carry_units() {
    let s = start().await;
    let (_, kinds) = s.get_json("/v1/kinds").await;
    let mut base = kinds["kinds"].as_array().unwrap().iter().find(|k| k["name"] == "cam_cycle").unwrap()["example"].clone();
    base["angles"] = json!(360);
    base["fidelity"] = json!("fast");
    base.as_object_mut().unwrap().remove("profile_angles_deg");
    base["outputs"] = json!(["kinematics", "loads", "contact", "film"]);
    let sweep = json!({"kind": "sweep", "spec": {"kind": "cam_cycle", "base": base,
        "parameters": [{"path": "/lubricant/viscosity", "values": [0.02, 0.04, 0.08]}],
        "quantities": ["/series/film_min/200", "/summary/min_film"]}});
    let res = s.post_job(&sweep).await;
    let job: Value = expect_status(res, 202).await;
    let id = job["id"].as_str().unwrap();
    let done = s.wait_finished(id, LONG).await;
    assert_eq!(done["status"], "succeeded", "{done}");
    let (_, r) = s.get_json(&format!("/v1/jobs/{id}/result")).await;
    let columns: Vec<&str> = r["columns"].as_array().unwrap().iter().map(|c| c.as_str().unwrap()).collect();
    assert!(columns.contains(&"film_min@200deg"), "{columns:?}");
    assert_eq!(r["units"]["film_min@200deg"], "m");
    assert_eq!(r["units"]["lubricant.viscosity"], "Pa·s");
    let csv = s.client.get(s.url(&format!("/v1/jobs/{id}/result?format=csv"))).send().await.unwrap().text().await.unwrap();
    let header = csv.lines().next().unwrap();
    assert!(header.contains("film_min@200deg [m]") && header.contains("lubricant.viscosity [Pa·s]"), "{header}");
    // The plots: axes in engineering units, no two tick labels alike.
    let (_, plots) = s.get_json(&format!("/v1/jobs/{id}/plots")).await;
    for p in plots["plots"].as_array().unwrap() {
        let svg = s.client.get(s.url(p["href"].as_str().unwrap())).send().await.unwrap().text().await.unwrap();
        assert!(!svg.contains("(SI)"), "{}", p["name"]);
        let ticks = y_ticks(&svg);
        assert!(ticks.len() >= 3, "{}: y ticks {ticks:?}", p["name"]);
        let mut unique = ticks.clone();
        unique.sort();
        unique.dedup();
        assert_eq!(unique.len(), ticks.len(), "{}: {ticks:?}", p["name"]);
    }
    s.stop().await;
}

async fn expect_status(res: reqwest::Response, status: u16) -> Value {
    let got = res.status().as_u16();
    let body: Value = res.json().await.unwrap();
    assert_eq!(got, status, "{body}");
    body
}

/// The y-axis tick labels of an SVG plot: texts anchored at the end (right-aligned, left of
/// the plot area).
fn y_ticks(svg: &str) -> Vec<String> {
    svg.split("<text").skip(1).filter(|t| t.contains("text-anchor=\"end\"")).filter_map(|t| {
        let body = t.split_once('>')?.1;
        Some(body.split_once("</text>")?.0.trim().to_string())
    }).filter(|s| !s.is_empty()).collect()
}

/// The shipped examples are plausible: none draws a warning (a warning there would teach users
/// to ignore them).
#[test]
fn no_example_draws_a_warning() {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("examples");
    let mut warned = Vec::new();
    for entry in std::fs::read_dir(dir).unwrap() {
        let path = entry.unwrap().path();
        if path.extension().is_none_or(|e| e != "json") {
            continue;
        }
        let request: Value = serde_json::from_str(&std::fs::read_to_string(&path).unwrap()).unwrap();
        let k = registry::find(request["kind"].as_str().unwrap()).unwrap();
        for w in k.warnings(&request["spec"]) {
            warned.push(format!("{}: {} {}", path.display(), w.path, w.message));
        }
    }
    assert!(warned.is_empty(), "{}", warned.join("\n"));
}

/// Errors in an engineer's words: "a number", not "f64"; ranges with the field's unit.
#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn error_messages_say_number_and_units() {
    let s = start().await;
    let mut bad = hertz(0.0255, 5000.0);
    bad["spec"]["load"] = json!("five thousand");
    let p = expect_problem(s.post_job(&bad).await, 422, "invalid_spec").await;
    let m = p["errors"][0]["message"].as_str().unwrap();
    assert!(m.contains("a number") && !m.contains("f64"), "{m}");
    let (_, kinds) = s.get_json("/v1/kinds").await;
    let mut cam = kinds["kinds"].as_array().unwrap().iter().find(|k| k["name"] == "cam_cycle").unwrap()["example"].clone();
    cam["cam"]["profile"]["base_radius"] = json!(25.5);
    let p = expect_problem(s.post_job(&json!({"kind": "cam_cycle", "spec": cam})).await, 422, "invalid_spec").await;
    let e = p["errors"].as_array().unwrap().iter().find(|e| e["path"] == "/spec/cam/profile/base_radius").unwrap_or_else(|| panic!("{p}"));
    assert_eq!(e["message"], "must be between 0.0001 m and 10 m", "{p}");
    s.stop().await;
}

/// `tribod run` of a file that is not there says so (not "malformed JSON").
#[test]
fn run_of_a_missing_file_says_it_cannot_read_it() {
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_tribod")).args(["run", "no-such-spec.json"]).output().unwrap();
    assert_eq!(out.status.code(), Some(2));
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains("cannot read the spec file no-such-spec.json") && !err.contains("malformed_json"), "{err}");
}

/// Every kind's key figures point at numeric (or pass/fail) fields its result documents.
#[test]
fn key_figures_point_at_documented_fields() {
    for k in registry::KINDS.iter() {
        let units = k.result_units();
        for p in k.key_figures() {
            assert!(units.contains_key(*p) || p.ends_with("/pass"), "{}: key figure {p} is not a documented numeric field", k.name());
        }
        assert!(k.name() == "sweep" || k.key_figures().len() >= 3, "{}: no key figures", k.name());
    }
}

/// The progress fractions an example's job streams while it runs (SSE), and its final status.
async fn streamed_fractions(s: &TestServer, example: &str, every_angle: bool) -> (Vec<f64>, Value) {
    let mut example: Value = serde_json::from_str(&std::fs::read_to_string(example).unwrap()).unwrap();
    if every_angle {
        example["spec"]["ehl"]["thermal"]["carry_tolerance"] = 0.0.into();
    }
    let res = s.client.post(s.url("/v1/jobs?fresh=true")).json(&example).send().await.unwrap();
    let job = expect_status(res, 202).await;
    let id = job["id"].as_str().unwrap().to_string();
    let mut res = s.client.get(s.url(&format!("/v1/jobs/{id}/events"))).header("accept", "text/event-stream").send().await.unwrap();
    let mut body = String::new();
    let read = tokio::time::timeout(Duration::from_secs(120), async {
        while let Some(chunk) = res.chunk().await.unwrap() {
            body.push_str(&String::from_utf8_lossy(&chunk));
        }
    })
    .await;
    assert!(read.is_ok(), "the stream did not end: {body}");
    let jobs: Vec<Value> = crate::http_api::sse_events(&body).iter().map(|(_, d)| serde_json::from_str(d).unwrap()).collect();
    let fractions = jobs.iter().filter(|j| j["status"] == "running").filter_map(|j| j["progress"]["fraction"].as_f64()).collect();
    (fractions, jobs.last().cloned().unwrap_or(Value::Null))
}

/// Progress that moves: the seed 000 thermal cycle (36 angles, the full thermal film at each —
/// with the default key points it ends within a second or two) streams at least three distinct
/// progress fractions before it is done, never going back; the printed crown's 2-D point solve
/// (it sent none) streams more than one.
#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn the_thermal_example_streams_moving_progress() {
    let s = start_with(|c| c.queue.workers = 1).await;
    for (example, least, every_angle) in [("examples/seed000_thermal_steady.json", 3, true), ("examples/seed000_finite_nose_printed.json", 2, false)] {
        let (fractions, last) = streamed_fractions(&s, example, every_angle).await;
        assert_eq!(last["status"], "succeeded", "{example}: {last}");
        let mut distinct = fractions.clone();
        distinct.dedup();
        assert!(distinct.len() >= least, "{example}: progress fractions while running: {fractions:?}");
        assert!(fractions.windows(2).all(|w| w[0] <= w[1]), "{example}: progress went back: {fractions:?}");
    }
    s.stop().await;
}
