//! The browser side of the service: the dashboard at `/` (plain HTML, CSS and JavaScript
//! embedded in the binary — no CDN, no build step) and the API docs at `/docs` (Swagger UI,
//! vendored by `utoipa-swagger-ui`, reading `/openapi.json`). Both only talk to the public API.
//! The dashboard's charts use uPlot, vendored under `assets/vendor/` (see its README.md); the
//! new-job page's example picker reads `examples/*.json`, embedded here and served as one list
//! at `/assets/examples.json` (an asset of the page, not an API route).

mod docs;

use axum::http::{header, HeaderValue};
use axum::response::{IntoResponse, Response};
use axum::routing::get;
use axum::Router;
use serde_json::{json, Value};
use std::sync::LazyLock;

const INDEX: &str = include_str!("assets/index.html");
const APP_JS: &str = include_str!("assets/app.js");
const STYLE_CSS: &str = include_str!("assets/style.css");
const UPLOT_JS: &str = include_str!("assets/vendor/uPlot.iife.min.js");
const UPLOT_CSS: &str = include_str!("assets/vendor/uPlot.min.css");

/// Embeds `examples/<name>.json` for each name, as `(file name, text)`.
macro_rules! examples {
    ($($name:literal),* $(,)?) => {
        &[$((concat!($name, ".json"), include_str!(concat!("../../examples/", $name, ".json")))),*]
    };
}

/// Every file of `examples/` (a test checks this list against the folder).
const EXAMPLES: &[(&str, &str)] = examples![
    "bearing_coefficients",
    "bearing_moment_coefficients",
    "bearing_thermal",
    "ehl_point_seed001_base_circle",
    "ehl_point_seed001_nose",
    "hertz_roller_on_cam",
    "rocker_dynamic",
    "rough_contact_seed001",
    "seed000_finite_cycle",
    "seed000_finite_nose",
    "seed000_finite_nose_printed",
    "seed000_roller_accurate",
    "seed000_roller_archard",
    "seed000_roller_startup",
    "seed000_roller_steady",
    "seed000_thermal_finite_cycle",
    "seed000_thermal_finite_nose",
    "seed000_thermal_startup",
    "seed000_thermal_steady",
    "seed000_viscosity_sweep",
    "seed001_base_circle_point",
    "seed001_micro_slip_map",
    "seed001_micro_slip_nose",
    "seed001_mixed_nose",
    "seed001_nose_point",
    "seed002_aligned",
    "seed002_misaligned",
    "seed002_optimised",
    "seed002_taguchi_l9",
    "seed003_cam_optimisation",
    "seed003_cam_optimisation_dynamic",
    "seed003_cam_optimisation_synthesised",
    "seed003_cycloidal_auto",
    "seed003_cycloidal_flat",
    "seed003_dynamic",
    "seed003_dynamic_hla",
    "seed003_dynamic_lash",
    "seed003_dynamic_springs",
    "seed003_flat_archard",
    "seed003_flat_archard_accurate",
    "seed003_synthesised",
    "seed004_irgashev",
    "seed004_multiarc",
    "sweep_hertz_load",
];

/// `[{file, kind, label, spec}]` of [`EXAMPLES`], in file order; a file that is not an example
/// (`{"kind", "label"?, "spec"}`) is left out.
static EXAMPLES_JSON: LazyLock<String> = LazyLock::new(|| {
    let list: Vec<Value> = EXAMPLES
        .iter()
        .filter_map(|(file, text)| {
            let v: Value = serde_json::from_str(text).ok()?;
            let kind = v.get("kind")?.as_str()?.to_string();
            let spec = v.get("spec")?.clone();
            Some(json!({"file": file, "kind": kind, "label": v.get("label").cloned().unwrap_or(Value::Null), "spec": spec}))
        })
        .collect();
    serde_json::to_string(&list).unwrap_or_else(|_| "[]".into())
});

/// The dashboard reads from this server only (its scripts, uPlot included, and styles are files
/// of this server; uPlot styles its elements through the DOM, which `style-src` does not limit);
/// plots arrive as `blob:` images (fetched with the token when one is set), charts are canvases.
const CSP: &str = "default-src 'self'; img-src 'self' blob: data:; style-src 'self'; script-src 'self'; connect-src 'self'; frame-ancestors 'none'";

fn asset(body: &'static str, content_type: &'static str) -> Response {
    (
        [
            (header::CONTENT_TYPE, HeaderValue::from_static(content_type)),
            (header::CONTENT_SECURITY_POLICY, HeaderValue::from_static(CSP)),
            (header::CACHE_CONTROL, HeaderValue::from_static("no-cache")),
            (header::X_CONTENT_TYPE_OPTIONS, HeaderValue::from_static("nosniff")),
        ],
        body,
    )
        .into_response()
}

/// `/`, `/assets/*` and `/docs`.
pub fn routes<S: Clone + Send + Sync + 'static>() -> Router<S> {
    Router::new()
        .route("/", get(|| async { asset(INDEX, "text/html; charset=utf-8") }))
        .route("/assets/app.js", get(|| async { asset(APP_JS, "text/javascript; charset=utf-8") }))
        .route("/assets/style.css", get(|| async { asset(STYLE_CSS, "text/css; charset=utf-8") }))
        .route("/assets/vendor/uPlot.iife.min.js", get(|| async { asset(UPLOT_JS, "text/javascript; charset=utf-8") }))
        .route("/assets/vendor/uPlot.min.css", get(|| async { asset(UPLOT_CSS, "text/css; charset=utf-8") }))
        .route("/assets/examples.json", get(|| async { asset(EXAMPLES_JSON.as_str(), "application/json") }))
        .route("/docs", get(docs::index))
        .route("/docs/", get(docs::index))
        .route("/docs/{*file}", get(docs::file))
}
