//! Plots of the bearing kinds: the pressure and film fields, the optimisation's main effects and
//! run scores.

use super::{column, Chart, Panel, Plot, Series};
use serde_json::Value;

/// A field of the `field` table on its grid (circumferential index fastest, as stored).
struct Grid {
    angle: Vec<f64>,
    z: Vec<f64>,
    /// `values[j][i]` at (`angle[i]`, `z[j]`).
    values: Vec<Vec<f64>>,
}

fn grid(result: &Value, field: &str) -> Option<Grid> {
    let table = result.get("field")?;
    let angles = column(table, "angle_deg", 1.0)?;
    let zs = column(table, "z", 1.0)?;
    let values = column(table, field, 1.0)?;
    let nx = zs.iter().take_while(|z| **z == zs[0]).count();
    if nx < 2 || values.len() != angles.len() || zs.len() != angles.len() || angles.len() % nx != 0 {
        return None;
    }
    let ny = angles.len() / nx;
    if ny < 2 {
        return None;
    }
    // The stored angles start at the supply line and wrap through 360°: unwrap them.
    let mut angle = angles[..nx].to_vec();
    for i in 1..nx {
        while angle[i] <= angle[i - 1] {
            angle[i] += 360.0;
        }
    }
    // At most MAX_CELLS per direction are drawn (every k-th node, the last always kept), so the
    // SVG stays small (a 361×181 field would be 5 MB).
    let keep = |n: usize, most: usize| -> Vec<usize> {
        let step = n.div_ceil(most).max(1);
        let mut v: Vec<usize> = (0..n).step_by(step).collect();
        if v.last() != Some(&(n - 1)) {
            v.push(n - 1);
        }
        v
    };
    let (cols, rows) = (keep(nx, MAX_CELLS.0), keep(ny, MAX_CELLS.1));
    Some(Grid {
        angle: cols.iter().map(|&i| angle[i]).collect(),
        z: rows.iter().map(|&j| zs[j * nx]).collect(),
        values: rows.iter().map(|&j| cols.iter().map(|&i| values[j * nx + i]).collect()).collect(),
    })
}

/// Most cells drawn along the circumference and the width.
const MAX_CELLS: (usize, usize) = (180, 60);

/// Bearing: pressure and film over the unrolled bearing (when the fields were requested), and
/// both along the mid-plane.
pub(super) fn bearing(result: &Value) -> Vec<Plot> {
    let mut plots = Vec::new();
    let mut mid = Vec::new();
    for (field, name, title, label) in [
        ("pressure_dimensionless", "pressure_field", "Film pressure over the bearing", "P = p(c/R)²/(6ηω), –"),
        ("film_dimensionless", "film_field", "Film thickness over the bearing", "H = h/c, –"),
    ] {
        let Some(g) = grid(result, field) else { continue };
        // The mid-plane: the axial row nearest the middle of the width.
        let middle = (g.z[0] + g.z[g.z.len() - 1]) / 2.0;
        let j = (0..g.z.len()).min_by(|a, b| (g.z[*a] - middle).abs().total_cmp(&(g.z[*b] - middle).abs())).unwrap_or(0);
        mid.push((label, Series { label: label.split(' ').next().unwrap_or(label).into(), points: g.angle.iter().copied().zip(g.values[j].iter().copied()).collect() }));
        plots.push(Plot {
            name: name.into(),
            title: title.into(),
            x_label: "angle from the unloaded side, °".into(),
            y_label: "Z = z/L, –".into(),
            chart: Chart::HeatMap { x: g.angle, y: g.z, z: g.values, z_label: label.into() },
        });
    }
    for (label, series) in mid {
        let (name, title) = if label.starts_with('P') { ("pressure_midplane", "Film pressure along the mid-plane") } else { ("film_midplane", "Film thickness along the mid-plane") };
        plots.push(Plot {
            name: name.into(),
            title: title.into(),
            x_label: "angle from the unloaded side, °".into(),
            y_label: label.into(),
            chart: Chart::Lines { series: vec![series], marks: Vec::new(), markers: false },
        });
    }
    plots
}

/// Bearing optimisation: the main effects (mean S/N ratio per level of each factor) and the
/// score of every run of the array, the best one highlighted.
pub(super) fn optimisation(result: &Value) -> Vec<Plot> {
    let mut plots = Vec::new();
    if let Some(effects) = result.get("main_effects").and_then(Value::as_array) {
        let mut panels: Vec<Panel> = Vec::new();
        for e in effects {
            let (Some(factor), Some(value), Some(sn)) =
                (e.get("factor").and_then(Value::as_str), e.get("value").and_then(Value::as_f64), e.get("mean_sn_ratio_db").and_then(Value::as_f64))
            else {
                continue;
            };
            let (title, x_label, scale) = match factor {
                "order" => ("profile order", "order n, –", 1.0),
                "height" => ("profile height", "ξ = m_r/c, –", 1.0),
                "length_fraction" => ("profiled length", "fraction of L, –", 1.0),
                other => (other, other, 1.0),
            };
            match panels.iter_mut().find(|p| p.title == title) {
                Some(p) => p.points.push((value * scale, sn)),
                None => panels.push(Panel { title: title.into(), x_label: x_label.into(), points: vec![(value * scale, sn)] }),
            }
        }
        if !panels.is_empty() {
            plots.push(Plot {
                name: "main_effects".into(),
                title: "Main effects (mean S/N ratio per level)".into(),
                x_label: "factor level".into(),
                y_label: "mean S/N ratio, dB".into(),
                chart: Chart::Panels { panels },
            });
        }
    }
    for (k, g) in result.get("score_grids").and_then(Value::as_array).into_iter().flatten().enumerate() {
        let label = |f: &str| match f {
            "order" => "order n, –".to_string(),
            "height" => "ξ = m_r/c, –".to_string(),
            "length_fraction" => "ψ = m_l/L, –".to_string(),
            other => other.to_string(),
        };
        let nums = |v: &Value| v.as_array().map(|a| a.iter().filter_map(Value::as_f64).collect::<Vec<f64>>());
        let (Some(x), Some(y), Some(z)) = (nums(&g["x"]), nums(&g["y"]), g["score"].as_array().map(|r| r.iter().filter_map(nums).collect::<Vec<_>>())) else { continue };
        let (xf, yf, held) = (g["x_factor"].as_str().unwrap_or(""), g["y_factor"].as_str().unwrap_or(""), g["held_factor"].as_str().unwrap_or(""));
        plots.push(Plot {
            name: format!("score_map_{}", k + 1),
            title: format!("Score over {xf} and {yf}, {held} = {} (seed 002 Fig. {})", g["held_value"], 8 + k),
            x_label: label(xf),
            y_label: label(yf),
            chart: Chart::HeatMap { x, y, z, z_label: "score, –".into() },
        });
    }
    if let Some(runs) = result.get("runs").and_then(Value::as_array) {
        let numbers = column(&Value::Array(runs.clone()), "run", 1.0).unwrap_or_default();
        if let Some(scores) = column(&Value::Array(runs.clone()), "score", 1.0) {
            let best = result.get("best_run").and_then(Value::as_f64);
            plots.push(Plot {
                name: "run_scores".into(),
                title: "Score of each run (seed 002 eq. 19)".into(),
                x_label: "run".into(),
                y_label: "score, –".into(),
                chart: Chart::Bars {
                    labels: numbers.iter().map(|n| format!("{n:.0}")).collect(),
                    highlight: best.and_then(|b| numbers.iter().position(|n| *n == b)),
                    values: scores,
                },
            });
        }
    }
    plots
}
