//! The 2-D pressure and film fields of `ehl.geometry: finite` at chosen cam angles (issue 16,
//! deliverable 2: "on request the 2-D pressure and film fields at chosen angles, as a table that
//! the CSV and plot outputs can carry"): output `profiles` with `profile_angles_deg` gives the
//! `fields` table, its heat maps, and `?table=fields` as CSV.

use crate::common::*;
use crate::in_process::{example, run};
use serde_json::{json, Value};
use std::time::Duration;
use tribod::plots::Chart;

/// The seed 000 finite cycle example (33×65) in pure rolling (one warm 2-D solve per angle) with
/// the fields asked for at two angles.
fn spec() -> Value {
    let mut s = example("seed000_finite_cycle");
    s["slip"] = json!({"mode": "pure_rolling"});
    s["outputs"] = json!(["film", "profiles"]);
    s["profile_angles_deg"] = json!([0.0, 135.0]);
    s
}

fn col(v: &Value, name: &str) -> Vec<f64> {
    v[name].as_array().unwrap_or_else(|| panic!("{name}")).iter().map(|x| x.as_f64().unwrap()).collect()
}

/// The table holds every node at each requested angle; its film is the film the cycle reports
/// at that angle (the smallest node value is the series' minimum film, its largest pressure is
/// positive and the pressure is zero on the boundary), and each angle gives a pressure and a film
/// heat map drawn over the whole grid.
#[test]
fn finite_cycle_returns_the_fields_at_the_requested_angles() {
    let out = run("cam_cycle", &spec()).unwrap();
    let t = &out["fields"];
    let (angle, x, y, p, h) = (col(t, "angle_deg"), col(t, "x"), col(t, "y"), col(t, "pressure"), col(t, "film"));
    let (nx, ny) = (33, 65);
    assert_eq!(angle.len(), 2 * nx * ny);
    assert!([x.len(), y.len(), p.len(), h.len()].iter().all(|&n| n == angle.len()));
    let series_angle = col(&out["series"], "angle_deg");
    let film_min = col(&out["series"], "film_min");
    let film_central = col(&out["series"], "film_central");
    for (k, want) in [0.0, 135.0].into_iter().enumerate() {
        let rows = k * nx * ny..(k + 1) * nx * ny;
        // 135° is taken at the nearest computed angle (8 angles: 135°).
        assert!(rows.clone().all(|r| (angle[r] - want).abs() < 1e-9), "angle {want}");
        let i = series_angle.iter().position(|a| (a - want).abs() < 1e-9).unwrap();
        let hmin = rows.clone().map(|r| h[r]).fold(f64::INFINITY, f64::min);
        assert!((hmin / film_min[i] - 1.0).abs() < 1e-6, "{want}°: field minimum {hmin} vs series {}", film_min[i]);
        // The node nearest the centre carries about the central film (the solver reads it
        // bilinearly at x = y = 0; neighbouring nodes differ by a grid cell's change).
        let c = rows.clone().min_by(|&a, &b| (x[a].hypot(y[a])).total_cmp(&x[b].hypot(y[b]))).unwrap();
        assert!((h[c] / film_central[i] - 1.0).abs() < 0.05, "{want}°: centre node {} vs central film {}", h[c], film_central[i]);
        let pmax = rows.clone().map(|r| p[r]).fold(0.0, f64::max);
        assert!(pmax > 1e8, "{want}°: peak {pmax}");
        // Boundary rows (first and last y, first and last x) carry no pressure.
        for r in rows.clone() {
            let (i, j) = ((r - rows.start) % nx, (r - rows.start) / nx);
            if i == 0 || i == nx - 1 || j == 0 || j == ny - 1 {
                assert_eq!(p[r], 0.0, "{want}°: boundary node ({i}, {j})");
            }
        }
    }
    let plots = tribod::plots::available("cam_cycle", &out);
    for name in ["pressure_field_0", "film_field_0", "pressure_field_135", "film_field_135"] {
        let plot = plots.iter().find(|p| p.name == name).unwrap_or_else(|| panic!("no plot {name}"));
        let Chart::HeatMap { x, y, z, .. } = &plot.chart else { panic!("{name}: not a heat map") };
        assert_eq!((x.len(), y.len(), z.len()), (nx, ny, ny), "{name}");
        crate::plots::check_svg(name, plot, &tribod::plots::render_plot(plot, "").unwrap());
    }
}

/// A request whose fields would be too large is refused naming `profile_angles_deg`; the line
/// model keeps its 1-D profiles and has no fields table.
#[test]
fn fields_are_bounded_and_only_for_the_finite_model() {
    let mut big = spec();
    big["ehl"]["nx"] = json!(257);
    big["ehl"]["ny"] = json!(257);
    let err = run("cam_cycle", &big).unwrap_err();
    let text = format!("{err:?}");
    assert!(text.contains("/profile_angles_deg") && text.contains("rows"), "{text}");
}

/// Over HTTP: the CSV of `?table=fields` has the table's columns and one line per node and
/// angle; the plot list links the heat maps.
#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn fields_table_is_served_as_csv_and_plots() {
    let s = start().await;
    let job: Value = s.post_job(&json!({"kind": "cam_cycle", "spec": spec()})).await.json().await.unwrap();
    let id = job["id"].as_str().unwrap_or_else(|| panic!("{job}")).to_string();
    let done = s.wait_finished(&id, Duration::from_secs(120)).await;
    assert_eq!(done["status"], "succeeded", "{done}");
    let res = s.client.get(s.url(&format!("/v1/jobs/{id}/result?format=csv&table=fields"))).send().await.unwrap();
    assert_eq!(res.status(), 200);
    let csv = res.text().await.unwrap();
    let mut lines = csv.lines();
    let header = lines.next().unwrap();
    // Each column with its unit (issue 39).
    for c in ["angle_deg [°]", "x [m]", "y [m]", "pressure [Pa]", "film [m]"] {
        assert!(header.split(',').any(|h| h == c), "{header}");
    }
    assert_eq!(lines.count(), 2 * 33 * 65);
    let (status, list) = s.get_json(&format!("/v1/jobs/{id}/plots")).await;
    assert_eq!(status, 200, "{list}");
    let names: Vec<&str> = list["plots"].as_array().unwrap().iter().filter_map(|p| p["name"].as_str()).collect();
    assert!(names.contains(&"pressure_field_135") && names.contains(&"film_field_0"), "{names:?}");
    s.stop().await;
}
