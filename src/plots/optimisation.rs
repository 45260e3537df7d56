//! Plots of a `cam_optimisation`: the Pareto front of its first two objectives (the baseline and
//! the best design marked), and the best feasible score against the designs evaluated.

use super::{Chart, Mark, Plot, Series};
use serde_json::Value;

pub(super) fn cam_optimisation(result: &Value) -> Vec<Plot> {
    let mut plots = Vec::new();
    let designs: Vec<&Value> = result.get("designs").and_then(Value::as_array).map(|d| d.iter().collect()).unwrap_or_default();
    let unit = |c: &str| result.get("units").and_then(|u| u.get(c)).and_then(Value::as_str).unwrap_or("1").to_string();
    if let Some(p) = result.get("pareto") {
        let names: Vec<&str> = p.get("objectives").and_then(Value::as_array).map(|o| o.iter().filter_map(Value::as_str).collect()).unwrap_or_default();
        let column = |k: &str| p.get(k).and_then(Value::as_array).map(|v| v.iter().filter_map(Value::as_f64).collect::<Vec<f64>>()).unwrap_or_default();
        let (first, second) = (column("first"), column("second"));
        if let ([a, b], false) = (names.as_slice(), first.is_empty()) {
            // Axes cover the feasible designs too, so the front sits among them.
            let feasible: Vec<(f64, f64)> = designs
                .iter()
                .filter(|d| d["feasible"] == true)
                .filter_map(|d| Some((d.get(*a)?.as_f64()?, d.get(*b)?.as_f64()?)))
                .collect();
            let (xs, xl) = super::scale::axis(a, &unit(a), feasible.iter().map(|p| p.0).chain(first.iter().copied()));
            let (ys, yl) = super::scale::axis(b, &unit(b), feasible.iter().map(|p| p.1).chain(second.iter().copied()));
            let front = first.iter().zip(&second).map(|(x, y)| (x * xs, y * ys)).collect();
            let mut marks = Vec::new();
            for (label, at) in [("baseline", "/baseline/objectives"), ("best", "/best/objectives")] {
                let o = result.pointer(at);
                if let (Some(x), Some(y)) = (o.and_then(|o| o.get(*a)).and_then(Value::as_f64), o.and_then(|o| o.get(*b)).and_then(Value::as_f64)) {
                    marks.push(Mark { label: label.into(), at: (x * xs, y * ys) });
                }
            }
            plots.push(Plot {
                name: "pareto".into(),
                title: format!("cam_optimisation: Pareto front of {a} and {b}"),
                x_label: xl,
                y_label: yl,
                chart: Chart::Lines { series: vec![Series { label: "Pareto front".into(), points: front }], marks, markers: true },
            });
        }
    }
    let mut best = f64::INFINITY;
    let mut points = Vec::new();
    for d in &designs {
        let (Some(n), Some(s)) = (d["design"].as_f64(), d.get("score").and_then(Value::as_f64)) else { continue };
        if d["feasible"] == true && s < best {
            best = s;
        }
        if best.is_finite() {
            points.push((n, best));
        }
    }
    if points.len() > 1 {
        plots.push(Plot {
            name: "best_score".into(),
            title: "cam_optimisation: best feasible score against designs evaluated".into(),
            x_label: "design".into(),
            y_label: "best feasible score".into(),
            chart: Chart::Lines { series: vec![Series { label: "best feasible score".into(), points }], marks: Vec::new(), markers: false },
        });
    }
    plots
}
