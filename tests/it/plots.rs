//! Plots (issue 13): every plot a kind defines renders from its example's result as an SVG with
//! the axis labels and one line per series; and over HTTP, `/plots` lists and serves them.

use crate::common::*;
use crate::in_process::run;
use serde_json::Value;
use tribod::plots::{Chart, Plot};
use std::time::Duration;

/// The examples whose results the plots are drawn from, one or more per kind, with the plots
/// each must give.
const EXAMPLES: &[(&str, &[&str])] = &[
    ("hertz_roller_on_cam", &["subsurface_stress"]),
    ("seed000_roller_steady", &["lift", "velocity", "acceleration", "contact_load", "hertz_pressure", "film", "lambda", "friction", "slide_roll_ratio"]),
    ("seed003_flat_archard", &["wear_depth", "lift", "hertz_pressure"]),
    ("seed003_synthesised", &["lift", "lift_law", "lift_law_velocity", "lift_law_acceleration", "lift_law_jerk", "cam_contour"]),
    ("ehl_point_seed001_nose", &["pressure", "film"]),
    ("seed001_nose_point", &["slide_roll_ratio", "traction"]),
    ("seed002_taguchi_l9", &["main_effects", "run_scores"]),
    ("seed003_cam_optimisation", &["pareto", "best_score"]),
    ("sweep_hertz_load", &["max_pressure", "half_width", "max_shear.value", "max_shear.depth"]),
];

fn example(name: &str) -> (String, Value) {
    let text = std::fs::read_to_string(format!("examples/{name}.json")).unwrap();
    let job: Value = serde_json::from_str(&text).unwrap();
    (job["kind"].as_str().unwrap().to_string(), job["spec"].clone())
}

/// The text content of every `<text>` element of an SVG.
fn texts(svg: &str) -> Vec<String> {
    svg.split("<text").skip(1).filter_map(|t| Some(t.split_once('>')?.1.split_once("</text>")?.0.trim().to_string())).collect()
}

/// Checks an SVG of `plot`: a document, the title, both axis labels, and what its chart draws —
/// one polyline and legend entry per curve, one filled rectangle per bar or field cell, one
/// panel title per factor.
pub(crate) fn check_svg(what: &str, plot: &Plot, svg: &str) {
    assert!(svg.trim_start().starts_with("<svg") && svg.trim_end().ends_with("</svg>"), "{what}: not an SVG document");
    let labels = texts(svg);
    // Panels carry their own x labels (checked below).
    let axes = if matches!(plot.chart, Chart::Panels { .. }) { vec![&plot.y_label] } else { vec![&plot.x_label, &plot.y_label] };
    for want in axes {
        let head = want.split(',').next().unwrap();
        assert!(labels.iter().any(|t| t.contains(head)), "{what}: no axis label '{want}' in {labels:?}");
    }
    assert!(labels.iter().any(|t| t.contains(&plot.title)), "{what}: no title");
    let rects = svg.matches("<rect").count();
    match &plot.chart {
        Chart::Lines { series, marks, .. } => {
            let lines = svg.matches("<polyline").count();
            assert!(lines >= series.len(), "{what}: {lines} lines for {} series", series.len());
            if series.len() > 1 {
                for s in series {
                    assert!(labels.iter().any(|t| *t == s.label), "{what}: no legend entry '{}' in {labels:?}", s.label);
                }
            }
            for m in marks {
                assert!(labels.iter().any(|t| *t == m.label), "{what}: mark '{}' not labelled", m.label);
            }
        }
        Chart::HeatMap { x, y, z_label, .. } => {
            assert!(rects >= x.len() * y.len(), "{what}: {rects} rectangles for a {}×{} field", x.len(), y.len());
            assert!(labels.iter().any(|t| t.contains(z_label.split(',').next().unwrap())), "{what}: no colour-bar label");
        }
        Chart::Panels { panels } => {
            for p in panels {
                assert!(labels.iter().any(|t| *t == p.title), "{what}: no panel '{}' in {labels:?}", p.title);
                assert!(labels.iter().any(|t| t.contains(p.x_label.split(',').next().unwrap())), "{what}: no axis '{}'", p.x_label);
            }
            assert!(svg.matches("<polyline").count() >= panels.len());
        }
        Chart::Bars { labels: bars, values, highlight } => {
            assert!(rects > values.len(), "{what}: {rects} rectangles for {} bars", values.len());
            for b in bars {
                assert!(labels.iter().any(|t| t == b), "{what}: bar '{b}' not labelled");
            }
            assert!(highlight.is_some(), "{what}: the best run is not marked");
        }
    }
}

#[test]
fn every_kind_plots_render_from_an_example_result() {
    let mut drawn = 0;
    for (name, want) in EXAMPLES {
        let (kind, spec) = example(name);
        let result = run(&kind, &spec).unwrap_or_else(|e| panic!("{name}: {e:?}"));
        let plots = tribod::plots::available(&kind, &result);
        let names: Vec<&str> = plots.iter().map(|p| p.name.as_str()).collect();
        for w in *want {
            assert!(names.contains(w), "{name}: no plot '{w}' in {names:?}");
        }
        for plot in &plots {
            let svg = tribod::plots::render(&kind, &result, &plot.name, "test").unwrap();
            check_svg(&format!("{name}/{}", plot.name), plot, &svg);
            drawn += 1;
        }
    }
    assert!(drawn >= 25, "{drawn} plots drawn");
    // An unknown plot is an error, not an empty picture.
    let (kind, spec) = example("hertz_roller_on_cam");
    let result = run(&kind, &spec).unwrap();
    assert!(tribod::plots::render(&kind, &result, "nope", "").is_err());
}

/// The bearing draws its pressure and film fields as heat maps (with the mid-plane profiles)
/// when the fields are requested, and nothing it has no data for otherwise.
#[test]
fn bearing_fields_are_drawn_as_heat_maps() {
    let (kind, mut spec) = example("seed002_misaligned");
    let plain = run(&kind, &spec).unwrap();
    assert!(tribod::plots::available(&kind, &plain).is_empty(), "plots without fields");
    spec["outputs"] = serde_json::json!(["pressure_field", "film_field"]);
    spec["field_stride"] = serde_json::json!({"circumferential": 4, "axial": 2});
    let result = run(&kind, &spec).unwrap();
    let plots = tribod::plots::available(&kind, &result);
    let names: Vec<&str> = plots.iter().map(|p| p.name.as_str()).collect();
    assert_eq!(names, ["pressure_field", "film_field", "pressure_midplane", "film_midplane"]);
    for plot in &plots {
        check_svg(&plot.name, plot, &tribod::plots::render_plot(plot, "").unwrap());
    }
    // The pressure map's cells span the stored grid, and its largest value is the result's P_max
    // at a node (the result refines P_max between nodes, so the node value is at most it).
    let Chart::HeatMap { z, .. } = &plots[0].chart else { panic!("not a heat map") };
    let max = z.iter().flatten().copied().fold(f64::MIN, f64::max);
    let p_max = result["max_pressure_dimensionless"].as_f64().unwrap();
    assert!(max <= p_max * (1.0 + 1e-9) && max > 0.9 * p_max, "{max} vs {p_max}");
}

/// The wear kind draws the depth at each requested running time.
#[test]
fn wear_history_has_one_curve_per_snapshot() {
    let (kind, mut spec) = example("seed003_flat_archard");
    spec["snapshots"] = serde_json::json!(4);
    let result = run(&kind, &spec).unwrap();
    let snapshots = result["snapshots"].as_array().map_or(0, Vec::len);
    assert!(snapshots >= 2, "{snapshots} snapshots");
    let plots = tribod::plots::available(&kind, &result);
    let history = plots.iter().find(|p| p.name == "wear_history").expect("no wear_history plot");
    let Chart::Lines { series, .. } = &history.chart else { panic!() };
    assert_eq!(series.len(), snapshots);
    check_svg("wear_history", history, &tribod::plots::render_plot(history, "").unwrap());
}

/// The EHL pressure plot marks the exit spike at the position the result gives.
#[test]
fn ehl_pressure_plot_marks_the_spike() {
    let (kind, spec) = example("ehl_point_seed001_nose");
    let result = run(&kind, &spec).unwrap();
    let spike = &result["pressure_spike"];
    assert!(spike.is_object(), "the example has no spike: {}", result);
    let plot = tribod::plots::available(&kind, &result).into_iter().find(|p| p.name == "pressure").unwrap();
    let Chart::Lines { marks, .. } = &plot.chart else { panic!() };
    assert_eq!(marks.len(), 1);
    assert!((marks[0].at.0 - spike["position"].as_f64().unwrap() * 1e3).abs() < 1e-12);
    assert!((marks[0].at.1 - spike["pressure"].as_f64().unwrap() * 1e-9).abs() < 1e-12);
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn plots_are_listed_and_served_as_svg() {
    let s = start().await;
    let text = std::fs::read_to_string("examples/hertz_roller_on_cam.json").unwrap();
    let job: Value = s.post_job(&serde_json::from_str(&text).unwrap()).await.json().await.unwrap();
    let id = job["id"].as_str().unwrap().to_string();
    let done = s.wait_finished(&id, Duration::from_secs(20)).await;
    assert_eq!(done["status"], "succeeded");
    let (status, list) = s.get_json(&format!("/v1/jobs/{id}/plots")).await;
    assert_eq!(status, 200, "{list}");
    let plots = list["plots"].as_array().unwrap();
    assert_eq!(plots[0]["name"], "subsurface_stress");
    let res = s.client.get(s.url(plots[0]["href"].as_str().unwrap())).send().await.unwrap();
    assert_eq!(res.status(), 200);
    assert_eq!(res.headers()["content-type"], "image/svg+xml");
    let svg = res.text().await.unwrap();
    assert!(texts(&svg).iter().any(|t| t.contains("depth, mm")));
    let res = s.client.get(s.url(&format!("/v1/jobs/{id}/plots/nope"))).send().await.unwrap();
    expect_problem(res, 404, "plot_not_found").await;
    // A running job has no plots yet.
    let slow: Value = s.post_job(&sleep_job(2.0, 5)).await.json().await.unwrap();
    let res = s.client.get(s.url(&format!("/v1/jobs/{}/plots", slow["id"].as_str().unwrap()))).send().await.unwrap();
    expect_problem(res, 409, "result_not_ready").await;
    s.stop().await;
}

#[test]
fn tribod_run_writes_the_plots_of_a_result() {
    let dir = tempfile::tempdir().unwrap();
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_tribod"))
        .args(["run", "examples/ehl_point_seed001_nose.json", "--compact", "--plots"])
        .arg(dir.path())
        .output()
        .unwrap();
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    for name in ["pressure", "film"] {
        let svg = std::fs::read_to_string(dir.path().join(format!("{name}.svg"))).unwrap();
        assert!(svg.starts_with("<svg") && texts(&svg).iter().any(|t| t.contains("x, mm")), "{name}.svg");
    }
}

/// Axis and dashboard multiples: films and pressures read in a multiple from a tenth of it
/// (0.3 µm, 0.5 GPa), forces, powers and the rest from one (129.7 W, not 0.1297 kW).
#[test]
fn films_and_pressures_from_a_tenth_the_rest_from_one() {
    use tribod::plots::scale::multiple;
    assert_eq!(multiple("m", 3e-7).1, "µm");
    assert_eq!(multiple("Pa", 5e8).1, "GPa");
    assert_eq!(multiple("W", 129.7).1, "W");
    assert_eq!(multiple("W", 1297.0).1, "kW");
    assert_eq!(multiple("N", 600.0).1, "N");
    assert_eq!(multiple("1", 0.5).1, "");
}
