//! Drawing a `Plot` as an SVG document with plotters' SVG backend.

use super::{Chart, Mark, Panel, Plot, PlotError, Series};
use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::coord::ranged1d::ValueFormatter;
use plotters::coord::types::RangedCoordf64;
use plotters::style::colors::colormaps::ViridisRGB;

const SIZE: (u32, u32) = (900, 520);
type Area<'a> = DrawingArea<SVGBackend<'a>, Shift>;

fn fail(e: impl std::fmt::Display) -> PlotError {
    PlotError::Drawing(e.to_string())
}

/// The SVG document of `plot`; the title carries `subtitle` (what was run).
pub fn svg(plot: &Plot, subtitle: &str) -> Result<String, PlotError> {
    let mut svg = String::new();
    {
        let area = SVGBackend::with_string(&mut svg, SIZE).into_drawing_area();
        area.fill(&WHITE).map_err(fail)?;
        let title = if subtitle.is_empty() { plot.title.clone() } else { format!("{} — {subtitle}", plot.title) };
        let area = area.titled(&title, ("sans-serif", 20)).map_err(fail)?;
        match &plot.chart {
            Chart::Lines { series, marks, markers } => lines(&area, plot, series, marks, *markers)?,
            Chart::HeatMap { x, y, z, z_label } => heat_map(&area, plot, x, y, z, z_label)?,
            Chart::Panels { panels } => panels_chart(&area, plot, panels)?,
            Chart::Bars { labels, values, highlight } => bars(&area, plot, labels, values, *highlight)?,
        }
        area.present().map_err(fail)?;
    }
    Ok(svg)
}

/// `(lo, hi)` of the finite values, padded by 5 % (and widened when they are all equal).
fn range(values: impl Iterator<Item = f64>) -> (f64, f64) {
    let (lo, hi) = values.filter(|v| v.is_finite()).fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), v| (l.min(v), h.max(v)));
    if !lo.is_finite() {
        (0.0, 1.0)
    } else if hi - lo <= f64::EPSILON * lo.abs().max(1e-300) {
        let pad = if lo == 0.0 { 1.0 } else { lo.abs() * 0.05 };
        (lo - pad, hi + pad)
    } else {
        let pad = (hi - lo) * 0.05;
        (lo - pad, hi + pad)
    }
}

/// An axis tick as plotters prints it, without the sign of a tick that rounds to zero (a key point
/// at −1e-17 printed "-0.0" on the heat maps' x axis).
pub fn tick(v: &f64) -> String {
    let s = <RangedCoordf64 as ValueFormatter<f64>>::format(v);
    match s.strip_prefix('-') {
        Some(rest) if rest.chars().all(|c| c == '0' || c == '.') => rest.to_string(),
        _ => s,
    }
}

/// Tick labels for an axis from `lo` to `hi`: as many decimals as the tick spacing needs (about a
/// tenth of the span), trailing zeros dropped, scientific where the values are tiny or huge — so
/// no two ticks print alike (a film of 1e-7 m used to print every tick as "0.0").
pub fn ticker(lo: f64, hi: f64) -> impl Fn(&f64) -> String {
    let big = lo.abs().max(hi.abs());
    let step = ((hi - lo).abs() / 10.0).max(big * 1e-12).max(f64::MIN_POSITIVE);
    move |v: &f64| {
        let v = if v.abs() < step * 1e-6 { 0.0 } else { *v };
        if v != 0.0 && (big >= 1e6 || big < 1e-3) {
            let digits = ((big / step).log10().ceil().max(0.0) as usize).min(12);
            let s = format!("{v:.digits$e}");
            let (m, e) = s.split_once('e').unwrap_or((&s, "0"));
            let m = if m.contains('.') { m.trim_end_matches('0').trim_end_matches('.') } else { m };
            return format!("{m}e{e}");
        }
        let decimals = ((-step.log10()).ceil().max(0.0) as usize + 1).min(15);
        let s = format!("{v:.decimals$}");
        let s = if s.contains('.') { s.trim_end_matches('0').trim_end_matches('.').to_string() } else { s };
        if s == "-0" { "0".into() } else { s }
    }
}

fn finite(points: &[(f64, f64)]) -> Vec<(f64, f64)> {
    points.iter().copied().filter(|(a, b)| a.is_finite() && b.is_finite()).collect()
}

fn lines(area: &Area, plot: &Plot, series: &[Series], marks: &[Mark], markers: bool) -> Result<(), PlotError> {
    let all = || series.iter().flat_map(|s| s.points.iter().copied()).chain(marks.iter().map(|m| m.at));
    let (x0, x1) = range(all().map(|p| p.0));
    let (y0, y1) = range(all().map(|p| p.1));
    let mut chart = ChartBuilder::on(area)
        .margin(16)
        .x_label_area_size(44)
        .y_label_area_size(70)
        .build_cartesian_2d(x0..x1, y0..y1)
        .map_err(fail)?;
    let (xt, yt) = (ticker(x0, x1), ticker(y0, y1));
    chart.configure_mesh().x_desc(&plot.x_label).y_desc(&plot.y_label).x_label_formatter(&xt).y_label_formatter(&yt).label_style(("sans-serif", 14)).draw().map_err(fail)?;
    for (i, s) in series.iter().enumerate() {
        let color = Palette99::pick(i).to_rgba();
        let points = finite(&s.points);
        chart
            .draw_series(LineSeries::new(points.clone(), color.stroke_width(2)))
            .map_err(fail)?
            .label(s.label.as_str())
            .legend(move |(px, py)| PathElement::new(vec![(px, py), (px + 18, py)], color.stroke_width(2)));
        if markers {
            chart.draw_series(points.iter().map(|p| Circle::new(*p, 3, color.filled()))).map_err(fail)?;
        }
    }
    for m in marks {
        chart.draw_series(std::iter::once(Cross::new(m.at, 7, RED.stroke_width(2)))).map_err(fail)?;
        chart
            .draw_series(std::iter::once(
                EmptyElement::at(m.at) + Text::new(m.label.clone(), (10, -20), ("sans-serif", 14).into_font().color(&RED)),
            ))
            .map_err(fail)?;
    }
    if series.len() > 1 {
        chart
            .configure_series_labels()
            .background_style(WHITE.mix(0.8))
            .border_style(BLACK)
            .label_font(("sans-serif", 14))
            .draw()
            .map_err(fail)?;
    }
    Ok(())
}

/// Cell edges around grid points: midpoints between neighbours, half a step beyond the ends.
fn edges(points: &[f64]) -> Vec<f64> {
    let n = points.len();
    let mut e = Vec::with_capacity(n + 1);
    e.push(points[0] - (points[1] - points[0]) / 2.0);
    e.extend(points.windows(2).map(|w| (w[0] + w[1]) / 2.0));
    e.push(points[n - 1] + (points[n - 1] - points[n - 2]) / 2.0);
    e
}

fn heat_map(area: &Area, plot: &Plot, x: &[f64], y: &[f64], z: &[Vec<f64>], z_label: &str) -> Result<(), PlotError> {
    let (xe, ye) = (edges(x), edges(y));
    let (lo, hi) = z.iter().flatten().copied().filter(|v| v.is_finite()).fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), v| (l.min(v), h.max(v)));
    let (lo, hi) = if lo.is_finite() && hi > lo { (lo, hi) } else { (lo.min(0.0), lo.max(0.0) + 1.0) };
    let (main, bar) = area.split_horizontally(SIZE.0 - 130);
    let mut chart = ChartBuilder::on(&main)
        .margin(16)
        .x_label_area_size(44)
        .y_label_area_size(70)
        .build_cartesian_2d(xe[0]..xe[xe.len() - 1], ye[0]..ye[ye.len() - 1])
        .map_err(fail)?;
    let (xt, yt) = (ticker(xe[0], xe[xe.len() - 1]), ticker(ye[0], ye[ye.len() - 1]));
    chart.configure_mesh().disable_mesh().x_desc(&plot.x_label).y_desc(&plot.y_label).x_label_formatter(&xt).y_label_formatter(&yt).label_style(("sans-serif", 14)).draw().map_err(fail)?;
    let cells = z.iter().enumerate().flat_map(|(j, row)| {
        let (xe, ye) = (&xe, &ye);
        row.iter().enumerate().filter(|(_, v)| v.is_finite()).map(move |(i, v)| {
            let c = ViridisRGB::get_color_normalized(*v, lo, hi);
            Rectangle::new([(xe[i], ye[j]), (xe[i + 1], ye[j + 1])], c.filled())
        })
    });
    chart.draw_series(cells).map_err(fail)?;
    // The colour bar, with the field's name and unit.
    let mut scale = ChartBuilder::on(&bar)
        .margin_top(16)
        .margin_bottom(60)
        .margin_right(8)
        .y_label_area_size(70)
        .build_cartesian_2d(0.0..1.0, lo..hi)
        .map_err(fail)?;
    scale
        .configure_mesh()
        .disable_mesh()
        .disable_x_axis()
        .y_desc(z_label)
        .y_label_formatter(&ticker(lo, hi))
        .label_style(("sans-serif", 12))
        .draw()
        .map_err(fail)?;
    let steps = 64;
    let band = (hi - lo) / steps as f64;
    scale
        .draw_series((0..steps).map(|k| {
            let v = lo + band * k as f64;
            Rectangle::new([(0.0, v), (1.0, v + band)], ViridisRGB::get_color_normalized(v + band / 2.0, lo, hi).filled())
        }))
        .map_err(fail)?;
    Ok(())
}

fn panels_chart(area: &Area, plot: &Plot, panels: &[Panel]) -> Result<(), PlotError> {
    let (y0, y1) = range(panels.iter().flat_map(|p| p.points.iter().map(|q| q.1)));
    for (k, (panel, cell)) in panels.iter().zip(area.split_evenly((1, panels.len().max(1)))).enumerate() {
        let (x0, x1) = range(panel.points.iter().map(|q| q.0));
        let mut chart = ChartBuilder::on(&cell)
            .caption(&panel.title, ("sans-serif", 16))
            .margin(12)
            .x_label_area_size(44)
            .y_label_area_size(if k == 0 { 70 } else { 50 })
            .build_cartesian_2d(x0..x1, y0..y1)
            .map_err(fail)?;
        let (xt, yt) = (ticker(x0, x1), ticker(y0, y1));
        let mut mesh = chart.configure_mesh();
        mesh.x_desc(&panel.x_label).x_labels(5).x_label_formatter(&xt).y_label_formatter(&yt).label_style(("sans-serif", 13));
        if k == 0 {
            mesh.y_desc(&plot.y_label);
        }
        mesh.draw().map_err(fail)?;
        let points = finite(&panel.points);
        let color = Palette99::pick(0).to_rgba();
        chart.draw_series(LineSeries::new(points.clone(), color.stroke_width(2))).map_err(fail)?;
        chart.draw_series(points.iter().map(|p| Circle::new(*p, 4, color.filled()))).map_err(fail)?;
    }
    Ok(())
}

fn bars(area: &Area, plot: &Plot, labels: &[String], values: &[f64], highlight: Option<usize>) -> Result<(), PlotError> {
    let (_, y1) = range(values.iter().copied().chain(std::iter::once(0.0)));
    let n = values.len().max(1);
    let mut chart = ChartBuilder::on(area)
        .margin(16)
        .x_label_area_size(44)
        .y_label_area_size(70)
        .build_cartesian_2d(-0.5..(n as f64 - 0.5), 0.0..y1)
        .map_err(fail)?;
    let label_of = |v: &f64| {
        let i = v.round();
        if (v - i).abs() < 1e-6 && i >= 0.0 { labels.get(i as usize).cloned().unwrap_or_default() } else { String::new() }
    };
    chart
        .configure_mesh()
        .disable_x_mesh()
        .x_labels(n + 1)
        .x_label_formatter(&label_of)
        .x_desc(&plot.x_label)
        .y_desc(&plot.y_label)
        .y_label_formatter(&ticker(0.0, y1))
        .label_style(("sans-serif", 14))
        .draw()
        .map_err(fail)?;
    let base = RGBColor(31, 95, 191).to_rgba();
    chart
        .draw_series(values.iter().enumerate().filter(|(_, v)| v.is_finite()).map(|(i, v)| {
            let color = if Some(i) == highlight { RED.to_rgba() } else { base };
            Rectangle::new([(i as f64 - 0.35, 0.0), (i as f64 + 0.35, *v)], color.filled())
        }))
        .map_err(fail)?;
    Ok(())
}
