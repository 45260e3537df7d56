//! Plots of a sweep: each result quantity against the first swept parameter, one curve per
//! combination of the other parameters.

use super::{Chart, Plot, Series};
use serde_json::{Map, Value};

/// At most this many curves per plot (more combinations are left to the CSV).
const MAX_CURVES: usize = 12;

pub(super) fn sweep(result: &Value) -> Vec<Plot> {
    let (Some(columns), Some(cases)) = (result.get("columns").and_then(Value::as_array), result.get("cases").and_then(Value::as_array)) else {
        return Vec::new();
    };
    let columns: Vec<&str> = columns.iter().filter_map(Value::as_str).collect();
    let rows: Vec<&Map<String, Value>> = cases.iter().filter_map(Value::as_object).collect();
    // Columns: case, the parameters, status, error_code, then the quantities.
    let Some(status_at) = columns.iter().position(|c| *c == "status") else { return Vec::new() };
    let parameters = &columns[1.min(status_at)..status_at];
    let quantities: Vec<&str> = columns[status_at..].iter().copied().filter(|c| *c != "status" && *c != "error_code").collect();
    let Some((x_name, others)) = parameters.split_first() else { return Vec::new() };
    if !rows.iter().any(|r| r.get(*x_name).is_some_and(Value::is_number)) {
        return Vec::new();
    }
    let kind = result.get("kind").and_then(Value::as_str).unwrap_or("sweep");
    let unit = |c: &str| result.get("units").and_then(|u| u.get(c)).and_then(Value::as_str).unwrap_or("1").to_string();
    let (x_scale, x_label) = super::scale::axis(x_name, &unit(x_name), rows.iter().filter_map(|r| r.get(*x_name).and_then(Value::as_f64)));
    let mut plots = Vec::new();
    for q in quantities {
        let (y_scale, y_label) = super::scale::axis(q, &unit(q), rows.iter().filter_map(|r| r.get(q).and_then(Value::as_f64)));
        let mut series: Vec<Series> = Vec::new();
        for r in &rows {
            let (Some(x), Some(y)) = (r.get(*x_name).and_then(Value::as_f64), r.get(q).and_then(Value::as_f64)) else { continue };
            let label = if others.is_empty() {
                q.to_string()
            } else {
                others.iter().map(|o| format!("{o} = {}", r.get(*o).map_or("–".into(), |v| v.to_string()))).collect::<Vec<_>>().join(", ")
            };
            match series.iter().position(|s| s.label == label) {
                Some(k) => series[k].points.push((x * x_scale, y * y_scale)),
                None if series.len() < MAX_CURVES => series.push(Series { label, points: vec![(x * x_scale, y * y_scale)] }),
                None => {}
            }
        }
        if series.is_empty() {
            continue;
        }
        for s in &mut series {
            s.points.sort_by(|a, b| a.0.total_cmp(&b.0));
        }
        let markers = series.iter().all(|s| s.points.len() <= 30);
        plots.push(Plot {
            name: q.to_string(),
            title: format!("{kind}: {q} against {x_name}"),
            x_label: x_label.clone(),
            y_label,
            chart: Chart::Lines { series, marks: Vec::new(), markers },
        });
    }
    plots
}
