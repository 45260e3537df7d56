//! The finishing pass over the generated OpenAPI document: what the route annotations cannot say
//! once for every route. A client generator must be able to build a typed request and handle
//! every answer from this document alone (issue 10, defect 8).
//!
//! * `JobRequest` becomes a `oneOf` of one request schema per kind (`HertzJobRequest`, …) with
//!   `kind` as the discriminator, each tying its `kind` constant to its spec schema.
//! * Answers every route can give are added where they apply: `401` under `/v1` (bearer token),
//!   `405` (other methods), `406` on reads (`Accept`), `503` where the job store is read or
//!   written, `415` and `408` on bodies.
//! * Numeric fields carry the bounds the kinds' validation checks (`minimum`, `exclusiveMinimum`,
//!   `maximum`), taken from the rules `validate` checks on each kind's example spec, so the
//!   validator is the one source of truth; where one schema serves several fields or kinds the
//!   loosest bound is kept (the schema is then necessary, the validator decides).
//! * Arrays carry the item counts the kinds' validation checks (`minItems`, `maxItems`), from
//!   the same rules (`Validation::items`) on the example and the kinds' bound examples.
//! * What a schema can say and the types cannot: a sweep's `kind` is one of the case kinds;
//!   `?table=` of a result is one of the kinds' table names; the events of
//!   `GET /v1/jobs/{id}/events` are objects whose `data` is the job as JSON (`JobEvent`).
//! * Object schemas are closed (`additionalProperties: false`), as the specs reject unknown fields.
//! * A newtype variant of an internally tagged enum (`Dynamic(DynamicLoadSpec)` under
//!   `#[serde(tag = "type")]`), which utoipa writes as `allOf: [$ref, {type tag}]`, is inlined as
//!   one object (the referenced properties plus the tag), the form struct variants take: client
//!   generators (openapi-python-client) cannot build a union member from that `allOf`.

use crate::jobs::registry;
use serde_json::{json, Map, Value};

/// Apply the finishing pass to the document utoipa generated.
pub fn finish(mut doc: Value) -> Value {
    numeric_bounds(&mut doc);
    inline_tagged_newtypes(&mut doc);
    closed_objects(&mut doc);
    sweep_rules(&mut doc);
    kind_tagged_requests(&mut doc);
    result_tables(&mut doc);
    job_events(&mut doc);
    common_responses(&mut doc);
    doc
}

/// A sweep runs one of the case kinds. (A parameter's "exactly one of `values` and `linspace`"
/// stays in its description: the `oneOf` of two `required` lists that would state it defeats
/// openapi-python-client, and the validator answers it with 422 naming the parameter.)
fn sweep_rules(doc: &mut Value) {
    let kinds: Vec<&str> = crate::jobs::kinds::CASE_KINDS.iter().map(|k| k.name()).collect();
    if let Some(kind) = doc.pointer_mut("/components/schemas/SweepSpec/properties/kind").and_then(Value::as_object_mut) {
        kind.insert("enum".into(), json!(kinds));
    }
}

/// `?table=` of `GET /v1/jobs/{id}/result`: one of the kinds' table names (which of them a job
/// has depends on its kind and outputs: a name its result lacks answers 404 `table_not_found`).
fn result_tables(doc: &mut Value) {
    let mut names: Vec<&str> = registry::KINDS.iter().flat_map(|k| k.tables().iter().copied()).collect();
    names.sort_unstable();
    names.dedup();
    let Some(params) = doc.pointer_mut("/paths/~1v1~1jobs~1{id}~1result/get/parameters").and_then(Value::as_array_mut) else { return };
    for p in params.iter_mut().filter(|p| p["name"] == "table") {
        p["schema"]["enum"] = json!(names);
    }
}

/// The events of `GET /v1/jobs/{id}/events`: before Open API 3.2's `itemSchema`, a
/// `text/event-stream` schema describes one event (its `event` and `data` fields).
fn job_events(doc: &mut Value) {
    let Some(schemas) = doc.pointer_mut("/components/schemas").and_then(Value::as_object_mut) else { return };
    let data = |description: &str| json!({"type": "string", "description": description});
    schemas.insert(
        "JobEvent".into(),
        json!({
            "description": "One Server-Sent Event of a followed job: its name (`event`) and `data`.",
            "oneOf": [
                {
                    "type": "object",
                    "required": ["event", "data"],
                    "properties": {
                        "event": {"type": "string", "enum": ["status", "progress", "done"],
                            "description": "`status`: first, and at each status change; `progress`: the fraction or stage changed; `done`: the job finished (last event)."},
                        "data": {"type": "string", "contentMediaType": "application/json", "contentSchema": schema_ref("JobView"),
                            "description": "The job as `GET /v1/jobs/{id}` returns it, as JSON."}
                    }
                },
                {
                    "type": "object",
                    "required": ["event", "data"],
                    "properties": {
                        "event": {"type": "string", "const": "deleted", "description": "The job was deleted meanwhile (last event)."},
                        "data": {"type": "string", "format": "uuid", "description": "The job's id."}
                    }
                },
                {
                    "type": "object",
                    "required": ["event", "data"],
                    "properties": {
                        "event": {"type": "string", "const": "shutdown", "description": "The server is shutting down (last event); reconnect later."},
                        "data": data("Why the stream ends, as text.")
                    }
                }
            ]
        }),
    );
    let at = "/paths/~1v1~1jobs~1{id}~1events/get/responses/200/content/text~1event-stream/schema";
    if let Some(schema) = doc.pointer_mut(at) {
        *schema = schema_ref("JobEvent");
    }
}

fn schema_ref(name: &str) -> Value {
    json!({ "$ref": format!("#/components/schemas/{name}") })
}

fn kind_tagged_requests(doc: &mut Value) {
    let Some(schemas) = doc.pointer_mut("/components/schemas").and_then(Value::as_object_mut) else { return };
    let mut variants = Vec::new();
    let mut mapping = Map::new();
    for k in registry::KINDS.iter() {
        let (spec, _) = k.schema_names();
        let camel: String = k.name().split('_').map(|w| w[..1].to_uppercase() + &w[1..]).collect();
        let name = format!("{camel}JobRequest");
        schemas.insert(
            name.clone(),
            json!({
                "type": "object",
                "description": format!("A `{}` job: {}", k.name(), k.description()),
                "required": ["kind", "spec"],
                "additionalProperties": false,
                "properties": {
                    "kind": { "type": "string", "enum": [k.name()], "description": "The job kind." },
                    "spec": schema_ref(&spec),
                    "label": { "type": "string", "maxLength": 200, "description": "Free text to find the job again." }
                }
            }),
        );
        mapping.insert(k.name().to_string(), json!(format!("#/components/schemas/{name}")));
        variants.push(schema_ref(&name));
    }
    schemas.insert(
        "JobRequest".into(),
        json!({
            "description": "Body of `POST /v1/jobs`: a job kind and the spec of that kind.",
            "oneOf": variants,
            "discriminator": { "propertyName": "kind", "mapping": mapping }
        }),
    );
}

/// Specs reject unknown fields (`deny_unknown_fields`): say so on every object schema a spec
/// uses, so that generators and fuzzers do not invent fields. (Results stay open: a result's
/// `meta` gains the job id when stored.)
fn inline_tagged_newtypes(doc: &mut Value) {
    let Some(schemas) = doc.pointer_mut("/components/schemas").and_then(Value::as_object_mut) else { return };
    let lookup = schemas.clone();
    fn walk(v: &mut Value, lookup: &Map<String, Value>) {
        match v {
            Value::Object(map) => {
                let merged = match map.get("allOf").and_then(Value::as_array).map(Vec::as_slice) {
                    Some([target, tag]) if tag.get("properties").is_some() => target
                        .get("$ref")
                        .and_then(Value::as_str)
                        .and_then(|r| lookup.get(r.rsplit('/').next().unwrap_or("")))
                        .filter(|t| t.get("properties").is_some())
                        .map(|t| {
                            let mut out = t.clone();
                            let o = out.as_object_mut().expect("an object schema");
                            let mut props = tag["properties"].as_object().cloned().unwrap_or_default();
                            props.extend(o["properties"].as_object().cloned().unwrap_or_default());
                            o.insert("properties".into(), Value::Object(props));
                            let mut required: Vec<Value> = tag.get("required").and_then(Value::as_array).cloned().unwrap_or_default();
                            required.extend(o.get("required").and_then(Value::as_array).cloned().unwrap_or_default());
                            o.insert("required".into(), Value::Array(required));
                            if let Some(d) = map.get("description") {
                                o.insert("description".into(), d.clone());
                            }
                            out
                        }),
                    _ => None,
                };
                match merged {
                    Some(m) => *v = m,
                    None => map.values_mut().for_each(|x| walk(x, lookup)),
                }
            }
            Value::Array(items) => items.iter_mut().for_each(|x| walk(x, lookup)),
            _ => {}
        }
    }
    schemas.values_mut().for_each(|s| walk(s, &lookup));
}

fn closed_objects(doc: &mut Value) {
    fn refs(v: &Value, out: &mut Vec<String>) {
        match v {
            Value::Object(map) => {
                if let Some(r) = map.get("$ref").and_then(Value::as_str) {
                    out.push(r.rsplit('/').next().unwrap_or("").to_string());
                }
                map.values().for_each(|v| refs(v, out));
            }
            Value::Array(items) => items.iter().for_each(|v| refs(v, out)),
            _ => {}
        }
    }
    fn close(v: &mut Value) {
        match v {
            Value::Object(map) => {
                if map.get("properties").is_some_and(Value::is_object) && !map.contains_key("additionalProperties") {
                    map.insert("additionalProperties".into(), Value::Bool(false));
                }
                map.values_mut().for_each(close);
            }
            Value::Array(items) => items.iter_mut().for_each(close),
            _ => {}
        }
    }
    let Some(schemas) = doc.pointer_mut("/components/schemas").and_then(Value::as_object_mut) else { return };
    let mut todo: Vec<String> = registry::KINDS.iter().map(|k| k.schema_names().0).collect();
    let mut seen = std::collections::HashSet::new();
    while let Some(name) = todo.pop() {
        if !seen.insert(name.clone()) {
            continue;
        }
        if let Some(schema) = schemas.get(&name) {
            refs(schema, &mut todo);
        }
    }
    for name in seen {
        if let Some(schema) = schemas.get_mut(&name) {
            close(schema);
        }
    }
}

fn problem(description: &str) -> Value {
    json!({
        "description": description,
        "content": { "application/problem+json": { "schema": schema_ref("Problem") } }
    })
}

fn common_responses(doc: &mut Value) {
    let Some(paths) = doc.get_mut("paths").and_then(Value::as_object_mut) else { return };
    for (path, item) in paths.iter_mut() {
        let Some(item) = item.as_object_mut() else { continue };
        for (method, op) in item.iter_mut() {
            let Some(responses) = op.get_mut("responses").and_then(Value::as_object_mut) else { continue };
            let mut add = |code: &str, description: &str| {
                responses.entry(code.to_string()).or_insert_with(|| problem(description));
            };
            let v1 = path.starts_with("/v1");
            if v1 {
                add("401", "Missing or wrong bearer token (when the server runs with --api-token)");
            }
            if method == "get" {
                add("406", "The Accept header excludes every representation of this resource");
            }
            if method == "post" {
                add("415", "The body is not JSON");
                add("408", "The body did not arrive within the server's body timeout (counted from the headers); the connection is closed");
            }
            if path.starts_with("/v1/jobs") {
                add("503", "The job store cannot be reached, or the service is shutting down");
            }
            if path.contains("{id}") {
                add("404", "No job has this id (also for an id that is not a UUID)");
            }
            if path.ends_with("/result") {
                add("400", "Invalid query (unknown format or table)");
            }
            add("405", "This route does not answer that method");
            // Stable order of codes for the drift test and for readers.
            let mut sorted: Vec<(String, Value)> = std::mem::take(responses).into_iter().collect();
            sorted.sort_by(|a, b| a.0.cmp(&b.0));
            responses.extend(sorted);
        }
    }
}

/// A numeric range, merged loosely across every rule that lands on one schema.
#[derive(Debug, Clone, Copy)]
struct Range {
    min: Option<f64>,
    min_exclusive: bool,
    max: Option<f64>,
}

impl Range {
    fn loosest(self, other: Range) -> Range {
        let (min, min_exclusive) = match (self.min, other.min) {
            (Some(a), Some(b)) if a < b => (Some(a), self.min_exclusive),
            (Some(a), Some(b)) if b < a => (Some(b), other.min_exclusive),
            (Some(a), Some(_)) => (Some(a), self.min_exclusive && other.min_exclusive),
            _ => (None, false),
        };
        let max = match (self.max, other.max) {
            (Some(a), Some(b)) => Some(a.max(b)),
            _ => None,
        };
        Range { min, min_exclusive, max }
    }
}

fn numeric_bounds(doc: &mut Value) {
    // Where each bound lands: a JSON pointer into the document, and whether it counts items.
    let mut ranges: Vec<(String, bool, Range)> = Vec::new();
    for k in registry::KINDS.iter() {
        let (spec, _) = k.schema_names();
        for b in k.bounds() {
            let leaf = if b.items { Leaf::Array } else { Leaf::Number };
            let Some(target) = schema_pointer(doc, &format!("/components/schemas/{spec}"), &b.path, leaf) else { continue };
            let range = Range { min: b.min, min_exclusive: b.min_exclusive, max: b.max };
            match ranges.iter_mut().find(|(t, items, _)| *t == target && *items == b.items) {
                Some((_, _, r)) => *r = r.loosest(range),
                None => ranges.push((target, b.items, range)),
            }
        }
    }
    for (target, items, range) in ranges {
        let Some(schema) = doc.pointer_mut(&target).and_then(Value::as_object_mut) else { continue };
        let (lower, upper) = if items { ("minItems", "maxItems") } else { ("minimum", "maximum") };
        match range.min {
            // Every array has at least none.
            Some(min) if items && min > 0.0 => {
                schema.insert(lower.into(), json!(min as u64));
            }
            Some(_) if items => {}
            Some(min) if range.min_exclusive => {
                schema.insert("exclusiveMinimum".into(), json!(min));
            }
            Some(min) => {
                schema.insert(lower.into(), json!(min));
            }
            None => {}
        }
        match range.max {
            Some(max) if items => {
                schema.insert(upper.into(), json!(max as u64));
            }
            Some(max) => {
                schema.insert(upper.into(), json!(max));
            }
            None => {}
        }
    }
}

/// What a spec field's schema describes: a number (bounds) or an array (item counts).
#[derive(Debug, Clone, Copy, PartialEq)]
enum Leaf {
    Number,
    Array,
}

/// The schema of a numeric spec field of `kind` (`path` relative to the spec), as the document
/// describes it (for tests that the bounds and the validator agree).
pub fn spec_field_schema(doc: &Value, kind: &str, path: &str) -> Option<Value> {
    let k = registry::find(kind)?;
    let (spec, _) = k.schema_names();
    let at = schema_pointer(doc, &format!("/components/schemas/{spec}"), path, Leaf::Number)?;
    doc.pointer(&at).cloned()
}

/// The schema of an array spec field of `kind` (`path` relative to the spec), as the document
/// describes it (for tests that the item counts and the validator agree).
pub fn spec_array_schema(doc: &Value, kind: &str, path: &str) -> Option<Value> {
    let k = registry::find(kind)?;
    let (spec, _) = k.schema_names();
    let at = schema_pointer(doc, &format!("/components/schemas/{spec}"), path, Leaf::Array)?;
    doc.pointer(&at).cloned()
}

/// The pointer of the numeric (or array: `leaf`) schema a spec field (`path`, a JSON pointer into
/// the spec) is described by, starting at the schema at `at`: through `$ref`s, `properties`, array
/// `items` and the one non-null member of an optional's `oneOf`.
fn schema_pointer(doc: &Value, at: &str, path: &str, leaf: Leaf) -> Option<String> {
    let mut here = resolve(doc, at.to_string())?;
    for segment in path.split('/').skip(1) {
        let schema = doc.pointer(&here)?;
        let has = |s: &Value| s.pointer(&format!("/properties/{segment}")).is_some();
        let next = if segment.parse::<usize>().is_ok() && schema.get("items").is_some() {
            format!("{here}/items")
        } else if has(schema) {
            format!("{here}/properties/{segment}")
        } else {
            // A tagged union: the one variant that has this field (ambiguous → no bound).
            let members = schema.get("oneOf").and_then(Value::as_array)?;
            let with: Vec<String> = (0..members.len())
                .filter_map(|i| resolve(doc, format!("{here}/oneOf/{i}")))
                .filter(|m| doc.pointer(m).is_some_and(has))
                .collect();
            match with.as_slice() {
                [only] => format!("{only}/properties/{segment}"),
                _ => return None,
            }
        };
        here = resolve(doc, next)?;
    }
    let found = doc.pointer(&here)?;
    let fits = |t: &Value| match leaf {
        Leaf::Number => t == "number" || t == "integer",
        Leaf::Array => t == "array",
    };
    let fitting = match found.get("type") {
        Some(Value::Array(types)) => types.iter().any(fits),
        Some(t) => fits(t),
        None => false,
    };
    fitting.then_some(here)
}

/// Follow `$ref`s and an optional's `oneOf: [null, X]` to the schema that describes a value.
fn resolve(doc: &Value, mut at: String) -> Option<String> {
    for _ in 0..16 {
        let schema = doc.pointer(&at)?;
        if let Some(r) = schema.get("$ref").and_then(Value::as_str) {
            at = r.strip_prefix('#')?.to_string();
            continue;
        }
        if let Some(members) = schema.get("oneOf").and_then(Value::as_array) {
            let real: Vec<usize> = (0..members.len()).filter(|&i| members[i].get("type") != Some(&json!("null"))).collect();
            if real.len() == 1 && members.len() == 2 {
                at = format!("{at}/oneOf/{}", real[0]);
                continue;
            }
        }
        return Some(at);
    }
    None
}
