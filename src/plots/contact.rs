//! Plots of the single-contact kinds: Hertz stresses, the EHL pressure and film.

use super::{col, line_plot, line_plots, number, Chart, LineDef, Mark, Plot};
use serde_json::Value;

static HERTZ: &[LineDef] = &[LineDef {
    name: "subsurface_stress",
    title: "Stresses below the contact centre",
    table: "stress_profile",
    x: col("depth", "depth, mm", 1e3),
    y_label: "stress, MPa",
    series: &[
        col("sigma_x", "σx", 1e-6),
        col("sigma_y", "σy", 1e-6),
        col("sigma_z", "σz", 1e-6),
        col("principal_shear", "τ1 (Tresca)", 1e-6),
        col("von_mises", "von Mises", 1e-6),
    ],
}];

/// Hertz: the stresses along the depth below the centre.
pub(super) fn hertz(result: &Value) -> Vec<Plot> {
    line_plots(result, HERTZ)
}

const PRESSURE: LineDef = LineDef { name: "pressure", title: "EHL pressure", table: "profile", x: col("x", "x, mm", 1e3), y_label: "pressure, GPa", series: &[col("pressure", "p", 1e-9)] };
const FILM: LineDef = LineDef { name: "film", title: "EHL film", table: "profile", x: col("x", "x, mm", 1e3), y_label: "film, µm", series: &[col("film", "h", 1e6)] };

/// EHL point: the pressure profile with the exit spike marked, and the film.
pub(super) fn ehl_point(result: &Value) -> Vec<Plot> {
    let mut plots = Vec::new();
    if let Some(mut pressure) = line_plot(result, &PRESSURE) {
        if let (Some(x), Some(p), Chart::Lines { marks, .. }) =
            (number(result, "/pressure_spike/position", 1e3), number(result, "/pressure_spike/pressure", 1e-9), &mut pressure.chart)
        {
            marks.push(Mark { label: format!("spike {p:.3} GPa"), at: (x, p) });
        }
        plots.push(pressure);
    }
    plots.extend(line_plot(result, &FILM));
    plots
}
