//! `/docs`: Swagger UI (vendored in the binary by `utoipa-swagger-ui`) rendering `/openapi.json`.

use axum::extract::Path;
use axum::http::{header, HeaderValue, StatusCode};
use axum::response::{IntoResponse, Response};
use std::sync::{Arc, LazyLock};
use utoipa_swagger_ui::Config;

static CONFIG: LazyLock<Arc<Config<'static>>> =
    LazyLock::new(|| Arc::new(Config::new(["/openapi.json"]).persist_authorization(true).try_it_out_enabled(true)));

fn serve(file: &str) -> Response {
    match utoipa_swagger_ui::serve(file, CONFIG.clone()) {
        Ok(Some(f)) => {
            let mut bytes = f.bytes.into_owned();
            if file == "index.html" {
                // Served at `/docs` as well as `/docs/`: its relative links resolve under /docs/.
                let html = String::from_utf8_lossy(&bytes).replacen("<head>", "<head>\n    <base href=\"/docs/\">", 1);
                bytes = html.into_bytes();
            }
            let mut res = (StatusCode::OK, bytes).into_response();
            let headers = res.headers_mut();
            if let Ok(v) = HeaderValue::from_str(&f.content_type) {
                headers.insert(header::CONTENT_TYPE, v);
            }
            if f.gzpipped {
                headers.insert(header::CONTENT_ENCODING, HeaderValue::from_static("gzip"));
            }
            res
        }
        Ok(None) => not_found("no such file of the API docs"),
        Err(e) => (StatusCode::INTERNAL_SERVER_ERROR, e.to_string()).into_response(),
    }
}

/// A `404 route_not_found` problem (as the API answers an unknown route).
fn not_found(detail: &str) -> Response {
    let problem = crate::problem::Problem::new(crate::problem::ErrorCode::RouteNotFound, detail);
    let mut res = (StatusCode::NOT_FOUND, serde_json::to_vec(&problem).unwrap_or_default()).into_response();
    res.headers_mut().insert(header::CONTENT_TYPE, HeaderValue::from_static("application/problem+json"));
    res
}

/// The docs page.
pub async fn index() -> Response {
    serve("index.html")
}

/// The page's scripts and styles.
pub async fn file(Path(file): Path<String>) -> Response {
    serve(if file.is_empty() { "index.html" } else { &file })
}
