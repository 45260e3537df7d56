//! Plots of stored results, rendered on request as SVG (plotters' SVG backend: no fonts, no
//! browser). Each kind's module lists the plots an engineer of its field looks at first, built
//! from the result JSON — so a plot always follows the stored result, never the solver — and
//! `draw` turns them into SVG. Nothing is drawn for a job nobody looks at.

mod bearing;
mod cam;
mod contact;
pub mod draw;
mod optimisation;
pub mod scale;
mod sweep;

use serde_json::Value;

/// One plot of a result, with its data in the units shown.
#[derive(Debug, Clone, PartialEq)]
pub struct Plot {
    /// URL name (`/v1/jobs/{id}/plots/{name}`).
    pub name: String,
    pub title: String,
    /// Quantity and unit on each axis (for a heat map, `z_label` names the colour).
    pub x_label: String,
    pub y_label: String,
    pub chart: Chart,
}

/// What is drawn.
#[derive(Debug, Clone, PartialEq)]
pub enum Chart {
    /// Curves (with point markers where `markers`), and marked points such as a pressure spike.
    Lines { series: Vec<Series>, marks: Vec<Mark>, markers: bool },
    /// A scalar field on a grid: `z[j][i]` at (`x[i]`, `y[j]`).
    HeatMap { x: Vec<f64>, y: Vec<f64>, z: Vec<Vec<f64>>, z_label: String },
    /// Side-by-side panels sharing the y axis (main effects: one panel per factor).
    Panels { panels: Vec<Panel> },
    /// One bar per category; `highlight` draws one bar in the accent colour.
    Bars { labels: Vec<String>, values: Vec<f64>, highlight: Option<usize> },
}

/// One curve.
#[derive(Debug, Clone, PartialEq)]
pub struct Series {
    pub label: String,
    pub points: Vec<(f64, f64)>,
}

/// A marked point with its label.
#[derive(Debug, Clone, PartialEq)]
pub struct Mark {
    pub label: String,
    pub at: (f64, f64),
}

/// One panel of a `Panels` chart.
#[derive(Debug, Clone, PartialEq)]
pub struct Panel {
    pub title: String,
    pub x_label: String,
    pub points: Vec<(f64, f64)>,
}

impl Plot {
    /// The legend entries (curve labels) a reader should find.
    pub fn series_labels(&self) -> Vec<&str> {
        match &self.chart {
            Chart::Lines { series, .. } => series.iter().map(|s| s.label.as_str()).collect(),
            Chart::Panels { panels } => panels.iter().map(|p| p.title.as_str()).collect(),
            Chart::HeatMap { .. } | Chart::Bars { .. } => Vec::new(),
        }
    }
}

/// The plots a `kind` result gives (those whose data the result holds).
pub fn available(kind: &str, result: &Value) -> Vec<Plot> {
    match kind {
        "cam_cycle" => cam::cam_cycle(result),
        "wear" => cam::wear(result),
        "cam_point" => cam::cam_point(result),
        "hertz" => contact::hertz(result),
        "ehl_point" => contact::ehl_point(result),
        "bearing" => bearing::bearing(result),
        "bearing_optimisation" => bearing::optimisation(result),
        "cam_optimisation" => optimisation::cam_optimisation(result),
        "sweep" => sweep::sweep(result),
        _ => Vec::new(),
    }
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
    let plot = available(kind, result).into_iter().find(|p| p.name == name).ok_or_else(|| PlotError::Unknown(name.into()))?;
    draw::svg(&plot, subtitle)
}

/// Render one plot (from `available`) as an SVG document.
pub fn render_plot(plot: &Plot, subtitle: &str) -> Result<String, PlotError> {
    draw::svg(plot, subtitle)
}

// --- Reading the result JSON ---------------------------------------------------------------

/// A column of a result table, scaled by `scale`: `table` is either an object of equal-length
/// arrays (`{"x": [..], "y": [..]}`) or an array of row objects (`[{"x": .., "y": ..}, ..]`).
/// Missing or non-numeric cells become NaN (skipped when drawn); `None` when the column is absent.
fn column(table: &Value, field: &str, scale: f64) -> Option<Vec<f64>> {
    let number = |v: Option<&Value>| v.and_then(Value::as_f64).map_or(f64::NAN, |x| x * scale);
    match table {
        Value::Object(map) => Some(map.get(field)?.as_array()?.iter().map(|v| number(Some(v))).collect()),
        Value::Array(rows) => {
            if !rows.iter().any(|r| r.get(field).is_some_and(Value::is_number)) {
                return None;
            }
            Some(rows.iter().map(|r| number(r.get(field))).collect())
        }
        _ => None,
    }
}

/// A number at a JSON pointer, scaled.
fn number(result: &Value, pointer: &str, scale: f64) -> Option<f64> {
    result.pointer(pointer)?.as_f64().map(|v| v * scale).filter(|v| v.is_finite())
}

/// A column on an axis: the field, its legend label and the factor from the stored SI value to
/// the unit shown.
#[derive(Debug, Clone, Copy)]
struct Column {
    field: &'static str,
    label: &'static str,
    scale: f64,
}

const fn col(field: &'static str, label: &'static str, scale: f64) -> Column {
    Column { field, label, scale }
}

/// A line plot of some columns of one table against another, as data.
struct LineDef {
    name: &'static str,
    title: &'static str,
    table: &'static str,
    x: Column,
    y_label: &'static str,
    series: &'static [Column],
}

/// The line plots of `defs` that `result` has every column for.
fn line_plots(result: &Value, defs: &[LineDef]) -> Vec<Plot> {
    defs.iter().filter_map(|d| line_plot(result, d)).collect()
}

fn line_plot(result: &Value, d: &LineDef) -> Option<Plot> {
    let table = result.get(d.table)?;
    let x = column(table, d.x.field, d.x.scale)?;
    let series = d
        .series
        .iter()
        .map(|c| {
            let y = column(table, c.field, c.scale)?;
            (y.len() == x.len()).then(|| Series { label: c.label.into(), points: x.iter().copied().zip(y).collect() })
        })
        .collect::<Option<Vec<_>>>()?;
    (!x.is_empty() && series.iter().any(|s| s.points.iter().any(|(a, b)| a.is_finite() && b.is_finite()))).then(|| Plot {
        name: d.name.into(),
        title: d.title.into(),
        x_label: d.x.label.into(),
        y_label: d.y_label.into(),
        chart: Chart::Lines { series, marks: Vec::new(), markers: x.len() <= 30 },
    })
}
