//! Plots (issue 13): how long drawing one SVG from a stored result takes, and how large it is,
//! for every plot of the examples (one per kind; the bearing with its fields requested).
//!
//! `cargo bench --bench plots`. Times are the best of 5 renders (wall, one thread); "parse" is
//! reading the stored result JSON, which the server does once per request.
use serde_json::Value;
use std::time::Instant;
use tribod::jobs::{registry, Limits};
use tribod::physics::Silent;

fn result(example: &str, tweak: impl Fn(&mut Value)) -> (String, String) {
    let text = std::fs::read_to_string(format!("examples/{example}.json")).unwrap();
    let mut job: Value = serde_json::from_str(&text).unwrap();
    tweak(&mut job["spec"]);
    let kind = job["kind"].as_str().unwrap().to_string();
    let k = registry::find(&kind).unwrap();
    let prepared = k.prepare(&job["spec"], &Limits::default()).unwrap();
    let out = prepared.run(&Silent).unwrap();
    (kind, serde_json::to_string(&out).unwrap())
}

fn best<T>(n: usize, mut f: impl FnMut() -> T) -> (f64, T) {
    let mut t = f64::INFINITY;
    let mut out = None;
    for _ in 0..n {
        let s = Instant::now();
        out = Some(f());
        t = t.min(s.elapsed().as_secs_f64());
    }
    (t, out.unwrap())
}

fn main() {
    let cases: Vec<(&str, Box<dyn Fn(&mut Value)>)> = vec![
        ("seed000_roller_steady", Box::new(|_| {})),
        ("seed003_flat_archard", Box::new(|_| {})),
        ("seed001_nose_point", Box::new(|_| {})),
        ("hertz_roller_on_cam", Box::new(|_| {})),
        ("ehl_point_seed001_nose", Box::new(|_| {})),
        ("seed002_misaligned", Box::new(|s| s["outputs"] = serde_json::json!(["pressure_field", "film_field"]))),
        ("seed002_taguchi_l9", Box::new(|_| {})),
        ("sweep_hertz_load", Box::new(|_| {})),
    ];
    println!("| example | kind | result JSON | parse ms | plot | points or cells | render ms | SVG KB |");
    println!("| --- | --- | ---: | ---: | --- | ---: | ---: | ---: |");
    for (example, tweak) in cases {
        let (kind, text) = result(example, tweak);
        let (parse, value) = best(5, || serde_json::from_str::<Value>(&text).unwrap());
        for plot in tribod::plots::available(&kind, &value) {
            let size = match &plot.chart {
                tribod::plots::Chart::Lines { series, .. } => series.iter().map(|s| s.points.len()).sum(),
                tribod::plots::Chart::HeatMap { x, y, .. } => x.len() * y.len(),
                tribod::plots::Chart::Panels { panels } => panels.iter().map(|p| p.points.len()).sum(),
                tribod::plots::Chart::Bars { values, .. } => values.len(),
            };
            let (ms, svg) = best(5, || tribod::plots::render_plot(&plot, example).unwrap());
            println!(
                "| {example} | {kind} | {:.0} KB | {:.2} | {} | {size} | {:.2} | {:.0} |",
                text.len() as f64 / 1024.0,
                parse * 1e3,
                plot.name,
                ms * 1e3,
                svg.len() as f64 / 1024.0
            );
        }
    }
}
