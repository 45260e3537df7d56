//! Plots of stored results, rendered on request as SVG (plotters' SVG backend: no fonts, no
//! browser). Each kind lists the plots an engineer of its field looks at first, as data: which
//! table of the result, which column on x and which on y, with the units they are shown in.
//! Plots are made from the result JSON, so they follow the stored result, never the solver.

use plotters::prelude::*;
use serde_json::Value;

/// One column of a result table on an axis: the JSON field, its name, and the factor from the
/// stored SI value to the unit shown.
#[derive(Debug, Clone, Copy)]
pub struct Column {
    pub field: &'static str,
    pub label: &'static str,
    pub scale: f64,
}

const fn col(field: &'static str, label: &'static str, scale: f64) -> Column {
    Column { field, label, scale }
}

/// A plot of some columns of one table against another.
#[derive(Debug, Clone, Copy)]
pub struct PlotDef {
    /// URL name (`/v1/jobs/{id}/plots/{name}`).
    pub name: &'static str,
    pub title: &'static str,
    /// The result field holding the table (an object of equal-length arrays).
    pub table: &'static str,
    pub x: Column,
    /// The y-axis label (quantity and unit).
    pub y_label: &'static str,
    pub series: &'static [Column],
}

const ANGLE: Column = col("angle_deg", "cam angle, °", 1.0);

static CAM_CYCLE: &[PlotDef] = &[
    PlotDef { name: "lift", title: "Follower lift", table: "series", x: ANGLE, y_label: "lift, mm", series: &[col("lift", "lift", 1e3)] },
    PlotDef { name: "velocity", title: "Follower velocity", table: "series", x: ANGLE, y_label: "velocity, m/s", series: &[col("velocity", "velocity", 1.0)] },
    PlotDef { name: "acceleration", title: "Follower acceleration", table: "series", x: ANGLE, y_label: "acceleration, m/s²", series: &[col("acceleration", "acceleration", 1.0)] },
    PlotDef { name: "contact_load", title: "Contact load", table: "series", x: ANGLE, y_label: "load, N", series: &[col("contact_load", "contact load", 1.0)] },
    PlotDef { name: "hertz_pressure", title: "Maximum Hertz pressure", table: "series", x: ANGLE, y_label: "pressure, GPa", series: &[col("hertz_max_pressure", "p_h", 1e-9)] },
    PlotDef { name: "film", title: "Film thickness", table: "series", x: ANGLE, y_label: "film, µm", series: &[col("film_central", "central", 1e6), col("film_min", "minimum", 1e6)] },
    PlotDef { name: "lambda", title: "Film parameter λ", table: "series", x: ANGLE, y_label: "λ, –", series: &[col("lambda", "λ", 1.0)] },
    PlotDef { name: "friction", title: "Friction coefficient", table: "series", x: ANGLE, y_label: "μ, –", series: &[col("friction_coefficient", "μ", 1.0)] },
    PlotDef { name: "slide_roll_ratio", title: "Slide-to-roll ratio", table: "series", x: ANGLE, y_label: "SRR, –", series: &[col("slide_roll_ratio", "SRR", 1.0)] },
    PlotDef { name: "temperature", title: "Flash temperature rise", table: "series", x: ANGLE, y_label: "ΔT, K", series: &[col("flash_temperature", "flash temperature", 1.0)] },
];

static WEAR: &[PlotDef] = &[
    PlotDef { name: "wear_depth", title: "Cam wear depth", table: "series", x: ANGLE, y_label: "wear depth, µm", series: &[col("wear_depth", "wear depth", 1e6)] },
    PlotDef { name: "lift", title: "Lift before and after wear", table: "series", x: ANGLE, y_label: "lift, mm", series: &[col("initial_lift", "initial", 1e3), col("final_lift", "worn", 1e3)] },
    PlotDef { name: "hertz_pressure", title: "Hertz pressure before and after wear", table: "series", x: ANGLE, y_label: "pressure, GPa", series: &[col("initial_hertz_pressure", "initial", 1e-9), col("final_hertz_pressure", "worn", 1e-9)] },
];

static HERTZ: &[PlotDef] = &[PlotDef {
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

static EHL_POINT: &[PlotDef] = &[
    PlotDef { name: "pressure", title: "EHL pressure", table: "profile", x: col("x", "x, mm", 1e3), y_label: "pressure, GPa", series: &[col("pressure", "p", 1e-9)] },
    PlotDef { name: "film", title: "EHL film", table: "profile", x: col("x", "x, mm", 1e3), y_label: "film, µm", series: &[col("film", "h", 1e6)] },
];

/// The plots defined for `kind`.
pub fn definitions(kind: &str) -> &'static [PlotDef] {
    match kind {
        "cam_cycle" => CAM_CYCLE,
        "wear" => WEAR,
        "hertz" => HERTZ,
        "ehl_point" => EHL_POINT,
        _ => &[],
    }
}

/// The plots a result can give (every column they need is present).
pub fn available(kind: &str, result: &Value) -> Vec<&'static PlotDef> {
    definitions(kind).iter().filter(|d| data(d, result).is_some()).collect()
}

/// `(x, [(label, y)])` of a plot, scaled to its units; `None` when a column is missing.
fn data(def: &PlotDef, result: &Value) -> Option<(Vec<f64>, Vec<(&'static str, Vec<f64>)>)> {
    let table = result.get(def.table)?;
    let column = |c: &Column| -> Option<Vec<f64>> {
        let values = table.get(c.field)?.as_array()?;
        Some(values.iter().map(|v| v.as_f64().map_or(f64::NAN, |x| x * c.scale)).collect())
    };
    let x = column(&def.x)?;
    let series = def.series.iter().map(|c| Some((c.label, column(c)?))).collect::<Option<Vec<_>>>()?;
    (!x.is_empty() && series.iter().all(|(_, y)| y.len() == x.len())).then_some((x, series))
}

/// Why a plot could not be drawn.
#[derive(Debug, thiserror::Error)]
pub enum PlotError {
    #[error("this job's result has no plot named '{0}'")]
    Unknown(String),
    #[error("drawing failed: {0}")]
    Drawing(String),
}

/// Render the plot `name` of a `kind` result as an SVG document; `subtitle` says what was run.
pub fn render(kind: &str, result: &Value, name: &str, subtitle: &str) -> Result<String, PlotError> {
    let def = definitions(kind).iter().find(|d| d.name == name).ok_or_else(|| PlotError::Unknown(name.into()))?;
    let (x, series) = data(def, result).ok_or_else(|| PlotError::Unknown(name.into()))?;
    let finite = |v: &f64| v.is_finite();
    let range = |values: &mut dyn Iterator<Item = f64>| {
        let (lo, hi) = values.filter(finite).fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), v| (l.min(v), h.max(v)));
        if !lo.is_finite() {
            (0.0, 1.0)
        } else if hi - lo <= f64::EPSILON * lo.abs().max(1e-300) {
            let pad = if lo == 0.0 { 1.0 } else { lo.abs() * 0.05 };
            (lo - pad, hi + pad)
        } else {
            let pad = (hi - lo) * 0.05;
            (lo - pad, hi + pad)
        }
    };
    let (x0, x1) = range(&mut x.iter().copied());
    let (y0, y1) = range(&mut series.iter().flat_map(|(_, y)| y.iter().copied()));
    let mut svg = String::new();
    {
        let area = SVGBackend::with_string(&mut svg, (900, 520)).into_drawing_area();
        let err = |e: &dyn std::fmt::Display| PlotError::Drawing(e.to_string());
        area.fill(&WHITE).map_err(|e| err(&e))?;
        let title = if subtitle.is_empty() { def.title.to_string() } else { format!("{} — {subtitle}", def.title) };
        let mut chart = ChartBuilder::on(&area)
            .caption(title, ("sans-serif", 20))
            .margin(16)
            .x_label_area_size(44)
            .y_label_area_size(70)
            .build_cartesian_2d(x0..x1, y0..y1)
            .map_err(|e| err(&e))?;
        chart
            .configure_mesh()
            .x_desc(def.x.label)
            .y_desc(def.y_label)
            .label_style(("sans-serif", 14))
            .draw()
            .map_err(|e| err(&e))?;
        for (i, (label, y)) in series.iter().enumerate() {
            let color = Palette99::pick(i).to_rgba();
            let points: Vec<(f64, f64)> =
                x.iter().zip(y).filter(|(a, b)| a.is_finite() && b.is_finite()).map(|(a, b)| (*a, *b)).collect();
            chart
                .draw_series(LineSeries::new(points, color.stroke_width(2)))
                .map_err(|e| err(&e))?
                .label(*label)
                .legend(move |(px, py)| PathElement::new(vec![(px, py), (px + 18, py)], color.stroke_width(2)));
        }
        if series.len() > 1 {
            chart
                .configure_series_labels()
                .background_style(WHITE.mix(0.8))
                .border_style(BLACK)
                .label_font(("sans-serif", 14))
                .draw()
                .map_err(|e| err(&e))?;
        }
        area.present().map_err(|e| err(&e))?;
    }
    Ok(svg)
}
