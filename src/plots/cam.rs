//! Plots of the cam kinds: the cycle, wear and the single contact point.

use super::{col, column, line_plots, number, Chart, Column, LineDef, Plot, Series};
use serde_json::Value;

const ANGLE: Column = col("angle_deg", "cam angle, °", 1.0);

static CAM_CYCLE: &[LineDef] = &[
    LineDef { name: "lift", title: "Follower lift", table: "series", x: ANGLE, y_label: "lift, mm", series: &[col("lift", "lift", 1e3)] },
    LineDef { name: "velocity", title: "Follower velocity", table: "series", x: ANGLE, y_label: "velocity, m/s", series: &[col("velocity", "velocity", 1.0)] },
    LineDef { name: "acceleration", title: "Follower acceleration", table: "series", x: ANGLE, y_label: "acceleration, m/s²", series: &[col("acceleration", "acceleration", 1.0)] },
    LineDef { name: "contact_load", title: "Contact load", table: "series", x: ANGLE, y_label: "load, N", series: &[col("contact_load", "contact load", 1.0)] },
    LineDef { name: "hertz_pressure", title: "Maximum Hertz pressure", table: "series", x: ANGLE, y_label: "pressure, GPa", series: &[col("hertz_max_pressure", "p_h", 1e-9)] },
    LineDef { name: "film", title: "Film thickness", table: "series", x: ANGLE, y_label: "film, µm", series: &[col("film_central", "central", 1e6), col("film_min", "minimum", 1e6)] },
    LineDef { name: "lambda", title: "Film parameter λ", table: "series", x: ANGLE, y_label: "λ, –", series: &[col("lambda", "λ", 1.0)] },
    LineDef { name: "friction", title: "Friction coefficient", table: "series", x: ANGLE, y_label: "μ, –", series: &[col("friction_coefficient", "μ", 1.0)] },
    LineDef { name: "slide_roll_ratio", title: "Slide-to-roll ratio", table: "series", x: ANGLE, y_label: "SRR, –", series: &[col("slide_roll_ratio", "SRR", 1.0)] },
    LineDef { name: "temperature", title: "Flash temperature rise", table: "series", x: ANGLE, y_label: "ΔT, K", series: &[col("flash_temperature", "flash temperature", 1.0)] },
];

/// Cam cycle: kinematics, load and pressure, films and λ, friction and SRR, flash temperature;
/// with the 2-D `fields` table, the pressure and film maps at each of its angles.
pub(super) fn cam_cycle(result: &Value) -> Vec<Plot> {
    let mut plots = line_plots(result, CAM_CYCLE);
    plots.extend(synthesis_plots(result));
    if let Some(t) = result.get("fields") {
        plots.extend(field_maps(t));
    }
    plots
}

/// Heat maps of the `fields` table (rows over `x` fastest, then `y`, then the angle): pressure
/// (GPa) and film (µm) over the contact at each angle, `x` along the rolling direction and `y`
/// along the roller axis, both in mm.
fn field_maps(table: &Value) -> Vec<Plot> {
    let cols = ["angle_deg", "x", "y", "pressure", "film"].map(|c| column(table, c, 1.0));
    let [Some(angle), Some(x), Some(y), Some(p), Some(h)] = cols else { return Vec::new() };
    let mut plots = Vec::new();
    let mut start = 0;
    while start < angle.len() {
        let a = angle[start];
        let end = (start..angle.len()).find(|&k| angle[k] != a).unwrap_or(angle.len());
        // x repeats with period nx inside the block.
        let nx = (start + 1..end).find(|&k| y[k] != y[start]).map_or(end - start, |k| k - start);
        if nx == 0 || (end - start) % nx != 0 {
            break;
        }
        let xs: Vec<f64> = x[start..start + nx].iter().map(|v| v * 1e3).collect();
        let ys: Vec<f64> = (start..end).step_by(nx).map(|k| y[k] * 1e3).collect();
        let grid = |v: &[f64], scale: f64| -> Vec<Vec<f64>> { v[start..end].chunks(nx).map(|r| r.iter().map(|z| z * scale).collect()).collect() };
        for (name, title, z, label) in [("pressure_field", "Pressure", grid(&p, 1e-9), "pressure, GPa"), ("film_field", "Film thickness", grid(&h, 1e6), "film, µm")] {
            plots.push(Plot {
                name: format!("{name}_{}", short(a)),
                title: format!("{title} over the contact at {}°", short(a)),
                x_label: "x along the rolling direction, mm".into(),
                y_label: "y along the roller axis, mm".into(),
                chart: Chart::HeatMap { x: xs.clone(), y: ys.clone(), z, z_label: label.into() },
            });
        }
        start = end;
    }
    plots
}

/// A synthesised profile (`contour` table): the law per cam angle — lift, velocity,
/// acceleration and jerk, the last two with their limits (`synthesis.*_limit`) drawn at ± the
/// limit; with a dynamic correction the lift beside the designed valve law — and the cam contour
/// (surface and, for a roller, the pitch curve) in the cam frame.
fn synthesis_plots(result: &Value) -> Vec<Plot> {
    let Some(table) = result.get("contour") else { return Vec::new() };
    let Some(angle) = column(table, "angle_deg", 1.0) else { return Vec::new() };
    let (Some(&first), Some(&last)) = (angle.first(), angle.last()) else { return Vec::new() };
    let laws = [
        ("lift_law", "Synthesised lift", "lift, mm", "lift", None),
        ("lift_law_velocity", "Synthesised velocity per cam angle", "ds/dθ, mm/rad", "lift_velocity", None),
        ("lift_law_acceleration", "Synthesised acceleration per cam angle", "d²s/dθ², mm/rad²", "lift_acceleration", Some("/synthesis/acceleration_limit")),
        ("lift_law_jerk", "Synthesised jerk per cam angle", "d³s/dθ³, mm/rad³", "lift_jerk", Some("/synthesis/jerk_limit")),
    ];
    let mut plots = Vec::new();
    for (name, title, y_label, field, limit) in laws {
        let Some(y) = column(table, field, 1e3) else { continue };
        let mut series = vec![Series { label: field.replace('_', " "), points: angle.iter().copied().zip(y).collect() }];
        // With the polydyne's dynamic correction: the designed valve law beside the cam's lift.
        if field == "lift" {
            if let Some(v) = column(table, "valve_lift", 1e3) {
                series[0].label = "cam lift".into();
                series.push(Series { label: "designed valve lift".into(), points: angle.iter().copied().zip(v).collect() });
            }
        }
        if let Some(l) = limit.and_then(|p| number(result, p, 1e3)) {
            series.push(Series { label: "limit".into(), points: vec![(first, l), (last, l)] });
            series.push(Series { label: "−limit".into(), points: vec![(first, -l), (last, -l)] });
        }
        plots.push(Plot {
            name: name.into(),
            title: title.into(),
            x_label: ANGLE.label.into(),
            y_label: y_label.into(),
            chart: Chart::Lines { series, marks: Vec::new(), markers: false },
        });
    }
    let closed = |x: Vec<f64>, y: Vec<f64>| -> Vec<(f64, f64)> {
        let mut p: Vec<(f64, f64)> = x.into_iter().zip(y).collect();
        if let Some(&q) = p.first() {
            p.push(q);
        }
        p
    };
    let mut series = Vec::new();
    if let (Some(x), Some(y)) = (column(table, "x", 1e3), column(table, "y", 1e3)) {
        series.push(Series { label: "cam surface".into(), points: closed(x, y) });
    }
    if let (Some(x), Some(y)) = (column(table, "pitch_x", 1e3), column(table, "pitch_y", 1e3)) {
        series.push(Series { label: "pitch curve".into(), points: closed(x, y) });
    }
    if !series.is_empty() {
        plots.push(Plot {
            name: "cam_contour".into(),
            title: "Cam contour".into(),
            x_label: "x, mm".into(),
            y_label: "y, mm".into(),
            chart: Chart::Lines { series, marks: Vec::new(), markers: false },
        });
    }
    plots
}

static WEAR: &[LineDef] = &[
    LineDef { name: "wear_depth", title: "Cam wear depth", table: "series", x: ANGLE, y_label: "wear depth, µm", series: &[col("wear_depth", "wear depth", 1e6)] },
    LineDef { name: "lift", title: "Lift before and after wear", table: "series", x: ANGLE, y_label: "lift, mm", series: &[col("initial_lift", "initial", 1e3), col("final_lift", "worn", 1e3)] },
    LineDef { name: "hertz_pressure", title: "Hertz pressure before and after wear", table: "series", x: ANGLE, y_label: "pressure, GPa", series: &[col("initial_hertz_pressure", "initial", 1e-9), col("final_hertz_pressure", "worn", 1e-9)] },
    LineDef { name: "follower_wear", title: "Follower face wear", table: "follower_face", x: col("position", "position on the face, mm", 1e3), y_label: "wear depth, µm", series: &[col("wear_depth", "wear depth", 1e6)] },
];

/// Wear: final depth, the depth at the requested times, the worn lift and pressure, the face.
pub(super) fn wear(result: &Value) -> Vec<Plot> {
    let mut plots = line_plots(result, WEAR);
    // The wear depth over the cam angle at several running times (`snapshots` in the spec).
    let angles = result.get("series").and_then(|t| column(t, "angle_deg", 1.0));
    if let (Some(angles), Some(snapshots)) = (angles, result.get("snapshots").and_then(Value::as_array)) {
        let series: Vec<Series> = snapshots
            .iter()
            .filter_map(|s| {
                let hours = s.get("hours")?.as_f64()?;
                let depth = column(s, "wear_depth", 1e6)?;
                (depth.len() == angles.len())
                    .then(|| Series { label: format!("{} h", short(hours)), points: angles.iter().copied().zip(depth).collect() })
            })
            .collect();
        if !series.is_empty() {
            plots.insert(1, Plot {
                name: "wear_history".into(),
                title: "Cam wear depth over running time".into(),
                x_label: ANGLE.label.into(),
                y_label: "wear depth, µm".into(),
                chart: Chart::Lines { series, marks: Vec::new(), markers: false },
            });
        }
    }
    plots
}

static CAM_POINT: &[LineDef] = &[
    LineDef { name: "slide_roll_ratio", title: "Slide-to-roll ratio against pin friction", table: "rows", x: col("pin_friction", "pin friction coefficient, –", 1.0), y_label: "SRR, –", series: &[col("slide_roll_ratio", "SRR", 1.0)] },
    LineDef {
        name: "traction",
        title: "Cam–roller traction against pin friction",
        table: "rows",
        x: col("pin_friction", "pin friction coefficient, –", 1.0),
        y_label: "traction coefficient, –",
        series: &[col("cam_roller_friction", "total", 1.0), col("viscous_traction", "viscous", 1.0), col("asperity_traction", "asperity", 1.0)],
    },
];

/// Cam point: the roller's slip and the traction as the pin friction grows.
pub(super) fn cam_point(result: &Value) -> Vec<Plot> {
    line_plots(result, CAM_POINT)
}

/// A number printed short (3 significant digits, no trailing zeros).
fn short(v: f64) -> String {
    let s = format!("{v:.3}");
    let s = s.trim_end_matches('0').trim_end_matches('.');
    if v.abs() >= 1000.0 { format!("{v:.0}") } else { s.to_string() }
}
