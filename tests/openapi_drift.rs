//! `openapi/openapi.json` is what the code generates. Regenerate with
//! `cargo run -- openapi > openapi/openapi.json`.

#[test]
fn committed_openapi_matches_the_code() {
    let generated = serde_json::to_string_pretty(&tribod::api::openapi()).unwrap() + "\n";
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("openapi/openapi.json");
    let committed = std::fs::read_to_string(&path).unwrap_or_default();
    if committed != generated {
        let line = committed.lines().zip(generated.lines()).position(|(a, b)| a != b).unwrap_or(0) + 1;
        panic!(
            "openapi/openapi.json is stale (first difference at line {line}); regenerate it with\n    \
             cargo run -- openapi > openapi/openapi.json"
        );
    }
}

#[test]
fn every_operation_is_documented() {
    let doc = serde_json::to_value(tribod::api::openapi()).unwrap();
    for (path, item) in doc["paths"].as_object().unwrap() {
        for (method, op) in item.as_object().unwrap() {
            assert!(op["summary"].as_str().is_some_and(|s| !s.is_empty()), "{method} {path} lacks a summary");
            assert!(op["description"].as_str().is_some_and(|s| !s.is_empty()), "{method} {path} lacks a description");
        }
    }
    // Every kind's spec is in the oneOf of the request body.
    let one_of = doc["components"]["schemas"]["JobRequest"]["properties"]["spec"]["oneOf"].as_array().unwrap().len();
    assert_eq!(one_of, tribod::jobs::registry::KINDS.len());
}
