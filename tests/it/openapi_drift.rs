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
    for k in tribod::jobs::registry::KINDS.iter() {
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

/// The numeric bounds in the document come from the validation rules (issue 10, defect 8): for
/// every rule a kind checks on its example's fields, the document's schema for that field carries
/// a bound no stricter than the rule, and the validator refuses a value beyond it, naming the field.
/// Item counts likewise (issue 40): `minItems`/`maxItems` no stricter than the rule, and an array
/// one item short or over is refused, naming the array.
#[test]
fn numeric_bounds_in_the_document_agree_with_the_validator() {
    let doc = tribod::api::openapi();
    let (mut checked, mut arrays) = (0, 0);
    for k in tribod::jobs::registry::KINDS.iter() {
        for b in k.bounds() {
            if b.items {
                let schema = tribod::api::spec_array_schema(&doc, k.name(), &b.path)
                    .unwrap_or_else(|| panic!("{} {}: no single array schema in the document", k.name(), b.path));
                let count = |key: &str| schema.get(key).and_then(serde_json::Value::as_u64);
                if let Some(min) = b.min.filter(|m| *m > 0.0) {
                    assert!(count("minItems").is_some_and(|m| m as f64 <= min), "{} {}: {schema} vs {b:?}", k.name(), b.path);
                    refused_items(*k, &b.path, min as usize - 1);
                }
                if let Some(max) = b.max {
                    assert!(count("maxItems").is_some_and(|m| m as f64 >= max), "{} {}: {schema} vs {b:?}", k.name(), b.path);
                    refused_items(*k, &b.path, max as usize + 1);
                }
                arrays += 1;
                continue;
            }
            // A field of a union variant shared by several variants gets no bound (ambiguous).
            let Some(schema) = tribod::api::spec_field_schema(&doc, k.name(), &b.path) else {
                eprintln!("{} {}: no single numeric schema; no bound in the document", k.name(), b.path);
                continue;
            };
            if let Some(min) = b.min {
                let (doc_min, exclusive) = match (schema.get("minimum"), schema.get("exclusiveMinimum")) {
                    (Some(m), _) => (m.as_f64().unwrap(), false),
                    (None, Some(m)) => (m.as_f64().unwrap(), true),
                    (None, None) => panic!("{} {}: no lower bound in {schema}", k.name(), b.path),
                };
                assert!(doc_min <= min && (!exclusive || b.min_exclusive || doc_min < min), "{} {}: {schema} vs {b:?}", k.name(), b.path);
                let below = if b.integer { min - 1.0 } else if b.min_exclusive { min } else { min - (min.abs() * 0.5).max(1e-300) };
                refused(*k, &b.path, below);
            }
            if let Some(max) = b.max {
                let doc_max = schema.get("maximum").and_then(|m| m.as_f64()).unwrap_or_else(|| panic!("{} {}: no upper bound in {schema}", k.name(), b.path));
                assert!(doc_max >= max, "{} {}: {schema} vs {b:?}", k.name(), b.path);
                let above = if b.integer { max + 1.0 } else { max + (max.abs() * 0.5).max(1.0) };
                refused(*k, &b.path, above);
            }
            checked += 1;
        }
    }
    assert!(checked >= 60, "only {checked} bounds checked");
    assert!(arrays >= 15, "only {arrays} item counts checked");
}

/// The first of the kind's bound examples (defaults filled in: the field may be a default) that
/// has a field at `path`.
fn example_with_field(k: &'static dyn tribod::jobs::kind::DynKind, path: &str) -> serde_json::Value {
    let limits = tribod::jobs::kind::Limits::default();
    k.bound_examples()
        .iter()
        .map(|e| k.prepare(e, &limits).expect("the bound examples validate").canonical)
        .find(|spec| spec.pointer(path).is_some())
        .unwrap_or_else(|| panic!("{}: no bound example has {path}", k.name()))
}

/// The kind's example with the field at `path` set to `value` is refused, naming that field.
fn refused(k: &'static dyn tribod::jobs::kind::DynKind, path: &str, value: f64) {
    let limits = tribod::jobs::kind::Limits::default();
    let mut spec = example_with_field(k, path);
    *spec.pointer_mut(path).unwrap() = serde_json::json!(value);
    match k.prepare(&spec, &limits) {
        Ok(_) => panic!("{} {path} = {value} was accepted", k.name()),
        Err(p) => assert!(p.errors.iter().any(|e| e.path == path), "{} {path} = {value}: {p:?}", k.name()),
    }
}

/// The example with the array at `path` made `len` items long (copies of its first item) is
/// refused by the item-count rule, naming the array.
fn refused_items(k: &'static dyn tribod::jobs::kind::DynKind, path: &str, len: usize) {
    let limits = tribod::jobs::kind::Limits::default();
    let mut spec = example_with_field(k, path);
    let array = spec.pointer_mut(path).unwrap();
    let item = array[0].clone();
    *array = serde_json::Value::Array(vec![item; len]);
    match k.prepare(&spec, &limits) {
        Ok(_) => panic!("{} {path} with {len} items was accepted", k.name()),
        Err(p) => assert!(p.errors.iter().any(|e| e.path == path && e.message.contains("item")), "{} {path} with {len} items: {p:?}", k.name()),
    }
}

/// Each kind's bound examples (the example and the specs that document the fields it leaves
/// out) are valid specs, so the rules read from them are the rules of accepted requests.
#[test]
fn every_bound_example_validates() {
    let limits = tribod::jobs::kind::Limits::default();
    for k in tribod::jobs::registry::KINDS.iter() {
        for (i, spec) in k.bound_examples().iter().enumerate() {
            if let Err(p) = k.prepare(spec, &limits) {
                panic!("{} bound example {i}: {p:?}", k.name());
            }
        }
    }
}

/// utoipa names a schema by its Rust type name and the document keeps the first schema of a
/// name: two different types of the same name in two kinds (say each kind's own `LubricantSpec`)
/// would silently document one kind with the other's fields. Every name must mean one schema.
#[test]
fn no_two_different_schemas_share_a_name() {
    let mut all = Vec::new();
    for k in tribod::jobs::registry::KINDS.iter() {
        k.schemas(&mut all);
    }
    let mut seen = std::collections::HashMap::new();
    for (name, schema) in all {
        let s = serde_json::to_string(&schema).unwrap();
        match seen.get(&name) {
            Some(prev) => assert_eq!(prev, &s, "two different types are named `{name}` in the OpenAPI document: rename one"),
            None => {
                seen.insert(name, s);
            }
        }
    }
    assert!(seen.len() > 20, "{} schemas", seen.len());
}

/// A sweep's `values` accept any JSON value (numbers, strings, objects), and so does the
/// document: a generated client can send `values: [0.1, 0.2]` and `["cycloidal", "polynomial_345"]`
/// (an array of objects, as it once said, refuses both).
#[test]
fn sweep_values_are_any_json_in_the_document() {
    let doc = serde_json::to_value(tribod::api::openapi()).unwrap();
    for name in ["Parameter", "Variable"] {
        let values = &doc["components"]["schemas"][name]["properties"]["values"];
        assert_eq!(values["items"], serde_json::json!({}), "{name}.values: {values}");
    }
}
