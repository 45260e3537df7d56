//! Plots (issue 13): every plot a kind defines renders from its example's result as an SVG with
//! the axis labels and one line per series; and over HTTP, `/plots` lists and serves them.

use crate::common::*;
use crate::in_process::run;
use serde_json::Value;
use std::time::Duration;

/// The examples whose results the plots are drawn from, one per kind with plots.
const EXAMPLES: &[&str] = &["hertz_roller_on_cam", "seed000_roller_steady", "seed003_flat_archard", "ehl_point_seed001_nose"];

fn example(name: &str) -> (String, Value) {
    let text = std::fs::read_to_string(format!("examples/{name}.json")).unwrap();
    let job: Value = serde_json::from_str(&text).unwrap();
    (job["kind"].as_str().unwrap().to_string(), job["spec"].clone())
}

/// The text content of every `<text>` element of an SVG.
fn texts(svg: &str) -> Vec<String> {
    svg.split("<text").skip(1).filter_map(|t| Some(t.split_once('>')?.1.split_once("</text>")?.0.trim().to_string())).collect()
}

#[test]
fn every_plot_renders_from_an_example_result() {
    let mut drawn = 0;
    for name in EXAMPLES {
        let (kind, spec) = example(name);
        let result = run(&kind, &spec).unwrap_or_else(|e| panic!("{name}: {e:?}"));
        let plots = tribod::plots::available(&kind, &result);
        assert!(!plots.is_empty(), "{name}: no plots");
        for def in plots {
            let svg = tribod::plots::render(&kind, &result, def.name, "test").unwrap();
            assert!(svg.trim_start().starts_with("<svg") && svg.trim_end().ends_with("</svg>"), "{name}/{}: not an SVG document", def.name);
            let labels = texts(&svg);
            for want in [def.x.label, def.y_label] {
                assert!(labels.iter().any(|t| t.contains(want.split(',').next().unwrap())), "{name}/{}: no axis label '{want}' in {labels:?}", def.name);
            }
            assert!(labels.iter().any(|t| t.contains(def.title)), "{name}/{}: no title", def.name);
            let lines = svg.matches("<polyline").count();
            assert!(lines >= def.series.len(), "{name}/{}: {lines} lines for {} series", def.name, def.series.len());
            if def.series.len() > 1 {
                for s in def.series {
                    assert!(labels.iter().any(|t| t == s.label), "{name}/{}: no legend entry '{}' in {labels:?}", def.name, s.label);
                }
            }
            drawn += 1;
        }
    }
    assert!(drawn >= 14, "{drawn} plots drawn");
    // An unknown plot is an error, not an empty picture.
    let (kind, spec) = example("hertz_roller_on_cam");
    let result = run(&kind, &spec).unwrap();
    assert!(tribod::plots::render(&kind, &result, "nope", "").is_err());
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
