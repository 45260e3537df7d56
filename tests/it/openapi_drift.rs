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
    // The request body is a oneOf of one request per kind, tagged by `kind`.
    let request = &doc["components"]["schemas"]["JobRequest"];
    assert_eq!(request["oneOf"].as_array().unwrap().len(), tribod::jobs::registry::KINDS.len());
    assert_eq!(request["discriminator"]["propertyName"], "kind");
    for k in tribod::jobs::registry::KINDS {
        let target = request["discriminator"]["mapping"][k.name()].as_str().expect("kind in the mapping");
        let variant = &doc["components"]["schemas"][target.rsplit('/').next().unwrap()];
        assert_eq!(variant["properties"]["kind"]["enum"][0], k.name());
        let spec = variant["properties"]["spec"]["$ref"].as_str().unwrap();
        assert!(spec.ends_with(&format!("/{}", k.schema_names().0)), "{} → {spec}", k.name());
    }
    // Query parameters are query parameters; reads document 406, /v1 routes 401.
    for (path, item) in doc["paths"].as_object().unwrap() {
        for (method, op) in item.as_object().unwrap() {
            for p in op["parameters"].as_array().into_iter().flatten() {
                let name = p["name"].as_str().unwrap();
                let expected = if path.contains(&format!("{{{name}}}")) { "path" } else if p["in"] == "header" { "header" } else { "query" };
                assert_eq!(p["in"], expected, "{method} {path}: parameter {name}");
            }
            let codes = op["responses"].as_object().unwrap();
            assert!(codes.contains_key("405"), "{method} {path}");
            if method == "get" {
                assert!(codes.contains_key("406"), "{method} {path}");
            }
            if path.starts_with("/v1") {
                assert!(codes.contains_key("401"), "{method} {path}");
            }
        }
    }
}

/// Does `value` fit `schema` as far as object keys go (every key of an object is a property of
/// the schema, recursively; `$ref`, `oneOf`/`anyOf`/`allOf` and `items` followed)? Catches two
/// Rust types with one schema name, where the document silently keeps only one of them.
fn keys_fit(doc: &serde_json::Value, schema: &serde_json::Value, value: &serde_json::Value) -> bool {
    use serde_json::Value;
    if let Some(r) = schema["$ref"].as_str() {
        let name = r.rsplit('/').next().unwrap();
        return keys_fit(doc, &doc["components"]["schemas"][name], value);
    }
    for key in ["oneOf", "anyOf"] {
        if let Some(alts) = schema[key].as_array() {
            return alts.iter().any(|s| keys_fit(doc, s, value));
        }
    }
    if let Some(all) = schema["allOf"].as_array() {
        // Properties may be spread over the parts: merge them.
        let mut merged = serde_json::Map::new();
        for s in all {
            let s = match s["$ref"].as_str() {
                Some(r) => &doc["components"]["schemas"][r.rsplit('/').next().unwrap()],
                None => s,
            };
            if let Some(p) = s["properties"].as_object() {
                merged.extend(p.clone());
            }
        }
        if merged.is_empty() {
            return all.iter().all(|s| keys_fit(doc, s, value));
        }
        return keys_fit(doc, &serde_json::json!({"type": "object", "properties": merged}), value);
    }
    match value {
        Value::Object(map) => match schema["properties"].as_object() {
            Some(props) => map.iter().all(|(k, v)| props.get(k).is_some_and(|s| keys_fit(doc, s, v))),
            None => true,
        },
        Value::Array(items) => items.iter().all(|v| keys_fit(doc, &schema["items"], v)),
        _ => true,
    }
}

#[test]
fn every_example_fits_its_kinds_schema() {
    let doc = serde_json::to_value(tribod::api::openapi()).unwrap();
    let mapping = doc["components"]["schemas"]["JobRequest"]["discriminator"]["mapping"].clone();
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("examples");
    let mut checked = 0;
    for entry in std::fs::read_dir(dir).unwrap() {
        let path = entry.unwrap().path();
        let v: serde_json::Value = serde_json::from_str(&std::fs::read_to_string(&path).unwrap()).unwrap();
        // The example as a whole request, against its own kind's request schema.
        let target = mapping[v["kind"].as_str().unwrap()].as_str().expect("the example's kind is in the mapping");
        let fits = keys_fit(&doc, &serde_json::json!({"$ref": target}), &v);
        assert!(fits, "{}: its spec has a key the OpenAPI document does not describe", path.display());
        checked += 1;
    }
    assert!(checked > 10);
}
