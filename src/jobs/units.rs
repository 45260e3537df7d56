//! The unit of every numeric result field (issue 39), read from the one source that documents it:
//! the result schemas' field descriptions, which feed the OpenAPI document ("Minimum film, m.",
//! "Peak pressure, Pa (…)") and the field names (`*_deg` in degrees). A field that is a pure
//! number says so by a cue (a ratio, a coefficient, a fraction, a count, a dimensionless group)
//! and gets unit `1`. `GET /v1/kinds` lists the table as `result_units` (JSON pointer → unit;
//! `*` stands for any index of a row table); CSV headers carry the units (`film_min [m]`).
//! A test holds every numeric field of every kind to a unit.

use utoipa::openapi::{RefOr, Schema};
use serde_json::Value;
use std::collections::{BTreeMap, HashMap};
use std::sync::OnceLock;

/// Units as the descriptions write them, longer first (so `m/s` is not read as `m`).
const UNITS: &[&str] = &[
    "W/(m·K)", "J/(kg·K)", "W/(m²·K)", "W/m²", "W/m", "N·m·s/rad", "N·m/rad", "N·s/m", "N·m·s", "kg·m²", "kg/m³", "m³/s", "mm²/s", "m²/s", "Pa·s", "rad/s²",
    "rad/s", "m/rad³", "m/rad²", "m/rad", "m/s³", "m/s²", "mm/h", "m/s", "N/m", "N·m", "MPa", "GPa", "1/s", "1/m", "1/Pa", "Pa", "rpm", "rev/s", "kg", "m²", "m³", "Hz", "°C", "J", "W", "N",
    "K", "s", "h", "m", "°", "%",
];

/// Words that say a field is a pure number.
const DIMENSIONLESS_CUES: &[&str] = &[
    "ratio", "coefficient", "fraction", "dimensionless", "number of", "count", "iterations", "steps", "λ", "lambda", "h_min/σ", "/c", "share",
    "index", "score", "factor", "1 when", "exponent", "variable", "relative", "normalised", "margin", "per cent", "%", "cycles", "updates",
    "angles", "ε", "order", "rank",
];

/// Field-name endings that say the unit (they win over the description).
const NAME_UNITS: &[(&str, &str)] = &[("_deg", "°"), ("_rpm", "rpm"), ("_mm_per_h", "mm/h"), ("_hours", "h"), ("_per_s", "1/s")];

/// Field names of pure numbers.
const DIMENSIONLESS_NAMES: &[&str] = &[
    "_ratio", "_fraction", "_coefficient", "_dimensionless", "_variable", "_number", "_count", "iterations", "lambda", "sticking", "_factor",
    "_share", "pass", "angles", "updates", "cycles", "succeeded", "failed", "case", "step", "part", "_order", "newton_steps", "margin",
    "ratio", "tolerance", "residual", "_level", "evaluations", "nodes", "score", "normalised", "bounces", "moes_", "_error", "axial", "circumferential",
];

/// The unit of a field whose unit varies by row and is given by the row's `unit` field (a
/// constraint of an optimisation: N for one, Pa for the next).
pub const ROW_UNIT: &str = "the row's `unit`";

/// The unit of a numeric field from its name and description; `None` when neither tells.
pub fn unit_of(name: &str, description: &str) -> Option<&'static str> {
    if name == "hours" {
        return Some("h");
    }
    if description.contains(ROW_UNIT) {
        return Some(ROW_UNIT);
    }
    if let Some((_, u)) = NAME_UNITS.iter().find(|(end, _)| name.ends_with(end)) {
        return Some(u);
    }
    if let Some(u) = unit_in(description) {
        return Some(u);
    }
    is_pure_number(name, description).then_some("1")
}

/// The first unit written as the descriptions write units: after ", " (or "in ") and before
/// the end, a full stop, a comma, a semicolon, a space or a bracket; or a description that is
/// only a unit ("Pa.").
fn unit_in(description: &str) -> Option<&'static str> {
    let d = description.replace('\n', " ");
    let trimmed = d.trim().trim_end_matches('.');
    if let Some(u) = UNITS.iter().find(|u| **u == trimmed) {
        return Some(u);
    }
    // A description that opens with its unit ("Pa (plane strain …)").
    for u in UNITS {
        if let Some(rest) = d.trim_start().strip_prefix(u) {
            if matches!(rest.chars().next(), None | Some('.' | ',' | ';' | ' ' | '(')) {
                return Some(u);
            }
        }
    }
    let mut best: Option<(usize, &'static str)> = None;
    for u in UNITS {
        for lead in [", ", " in ", " (", "; "] {
            let pat = format!("{lead}{u}");
            let mut from = 0;
            while let Some(i) = d[from..].find(&pat) {
                let at = from + i;
                let end = at + pat.len();
                let next = d[end..].chars().next();
                if matches!(next, None | Some('.' | ',' | ';' | ' ' | ')' | ':')) {
                    if best.is_none_or(|(b, _)| at < b) {
                        best = Some((at, u));
                    }
                    break;
                }
                from = end;
            }
        }
    }
    best.map(|(_, u)| u)
}

/// The schemas of a kind (its spec's and result's and everything they reference) and the
/// names of the two roots, as `DynKind::documents` gives them.
pub struct Documents {
    pub schemas: Vec<(String, RefOr<Schema>)>,
    pub spec: String,
    pub result: String,
}

/// Every numeric field of a kind's result (or, `spec`, of its spec): JSON pointer → unit
/// (`None`: undocumented).
pub fn walk(docs: Documents, spec: bool) -> BTreeMap<String, Option<&'static str>> {
    let by_name: HashMap<String, Value> = docs.schemas.into_iter().map(|(n, s)| (n, serde_json::to_value(s).unwrap_or(Value::Null))).collect();
    let mut out = BTreeMap::new();
    if let Some(root) = by_name.get(if spec { &docs.spec } else { &docs.result }) {
        fields(root, "", &by_name, &mut out, 0);
    }
    out
}

/// The numeric fields below `schema` at `path`.
fn fields(schema: &Value, path: &str, by_name: &HashMap<String, Value>, out: &mut BTreeMap<String, Option<&'static str>>, depth: usize) {
    if depth > 12 {
        return;
    }
    fields_in(schema, path, None, by_name, out, depth)
}

/// The numeric fields below `schema`; `inherited` is the unit its parent field's doc gives
/// (the value and limit of a `checks.min_film` are in the unit "Minimum film, m, …" names).
fn fields_in(
    schema: &Value,
    path: &str,
    inherited: Option<&'static str>,
    by_name: &HashMap<String, Value>,
    out: &mut BTreeMap<String, Option<&'static str>>,
    depth: usize,
) {
    if depth > 12 {
        return;
    }
    let Some(props) = resolve(schema, by_name).get("properties").and_then(Value::as_object) else { return };
    for (name, p) in props {
        let here = format!("{path}/{name}");
        let description = describe(p, by_name);
        let s = resolve(p, by_name);
        match kind_of(s, by_name) {
            Shape::Number | Shape::Numbers => {
                let own = unit_of(name, &description);
                // A field of a parent that states the unit takes it unless its own doc says
                // otherwise (a relative margin stays a pure number).
                let unit = match (own, inherited) {
                    (Some(u), _) if u != "1" || inherited.is_none() => Some(u),
                    (Some("1"), Some(_)) if is_pure_number(name, &description) => Some("1"),
                    (_, Some(u)) => Some(u),
                    (own, None) => own,
                };
                out.insert(here, unit);
            }
            Shape::Object(o) => fields_in(o, &here, parent_unit(name, &description), by_name, out, depth + 1),
            Shape::Rows(o) => fields_in(o, &format!("{here}/*"), parent_unit(name, &description), by_name, out, depth + 1),
            Shape::Other => {}
        }
    }
}

/// The unit a parent field's doc gives its members: its stated unit, `1` for a dimensionless
/// group or a convergence record (iterations, residual and tolerance are pure numbers).
fn parent_unit(name: &str, description: &str) -> Option<&'static str> {
    if name.contains("dimensionless") || name.contains("convergence") {
        return Some("1");
    }
    unit_in(description)
}

/// A field that says it is a pure number by its own doc or name.
fn is_pure_number(name: &str, description: &str) -> bool {
    let d = description.to_lowercase();
    DIMENSIONLESS_CUES.iter().any(|c| d.contains(c)) || DIMENSIONLESS_NAMES.iter().any(|n| name.contains(n.trim_start_matches('_')))
}

enum Shape<'a> {
    Number,
    /// An array of numbers (a column), or of arrays of numbers (pairs, matrices).
    Numbers,
    Object(&'a Value),
    /// An array of objects.
    Rows(&'a Value),
    Other,
}

fn kind_of<'a>(s: &'a Value, by_name: &'a HashMap<String, Value>) -> Shape<'a> {
    let types: Vec<&str> = match s.get("type") {
        Some(Value::String(t)) => vec![t.as_str()],
        Some(Value::Array(ts)) => ts.iter().filter_map(Value::as_str).collect(),
        _ => Vec::new(),
    };
    if types.iter().any(|t| *t == "number" || *t == "integer") {
        return Shape::Number;
    }
    if types.contains(&"array") {
        let item = resolve(s.get("items").unwrap_or(&Value::Null), by_name);
        return match kind_of(item, by_name) {
            Shape::Number | Shape::Numbers => Shape::Numbers,
            Shape::Object(o) => Shape::Rows(o),
            _ => Shape::Other,
        };
    }
    if s.get("properties").is_some() {
        return Shape::Object(s);
    }
    Shape::Other
}

/// A `$ref` (or a `oneOf`/`anyOf`/`allOf` of one schema and `null`) resolved to its schema.
fn resolve<'a>(s: &'a Value, by_name: &'a HashMap<String, Value>) -> &'a Value {
    if let Some(r) = s.get("$ref").and_then(Value::as_str) {
        let name = r.rsplit('/').next().unwrap_or(r);
        return by_name.get(name).map(|t| resolve(t, by_name)).unwrap_or(s);
    }
    for key in ["oneOf", "anyOf", "allOf"] {
        if let Some(alts) = s.get(key).and_then(Value::as_array) {
            if let Some(one) = alts.iter().find(|a| a.get("type").and_then(Value::as_str) != Some("null")) {
                return resolve(one, by_name);
            }
        }
    }
    s
}

/// The field's description (its own, or its schema's).
fn describe(p: &Value, by_name: &HashMap<String, Value>) -> String {
    let own = p.get("description").and_then(Value::as_str).map(str::to_string);
    let inner = ["oneOf", "anyOf", "allOf"].iter().find_map(|k| {
        p.get(*k).and_then(Value::as_array).and_then(|alts| alts.iter().find_map(|a| a.get("description").and_then(Value::as_str).map(str::to_string)))
    });
    own.or(inner).or_else(|| resolve(p, by_name).get("description").and_then(Value::as_str).map(str::to_string)).unwrap_or_default()
}

/// The documented units of kind `kind`'s result (or, `spec`, of its spec), computed once per
/// kind from `docs` (`DynKind::result_units`, `DynKind::spec_units`).
pub fn cached(kind: &str, spec: bool, docs: impl FnOnce() -> Documents) -> &'static BTreeMap<String, String> {
    type Cache = std::sync::Mutex<HashMap<(String, bool), &'static BTreeMap<String, String>>>;
    static CACHE: OnceLock<Cache> = OnceLock::new();
    let mut map = CACHE.get_or_init(Default::default).lock().unwrap_or_else(|e| e.into_inner());
    map.entry((kind.to_string(), spec))
        .or_insert_with(|| Box::leak(Box::new(walk(docs(), spec).into_iter().filter_map(|(p, u)| u.map(|u| (p, u.to_string()))).collect())))
}

/// The unit at a JSON pointer into a result or spec: the field's own, or, for an element of a
/// column (`/series/film_min/200`) or a row table (`/rows/3/film_min`), its column's.
pub fn unit_at<'a>(units: &'a BTreeMap<String, String>, pointer: &str) -> Option<&'a str> {
    if let Some(u) = units.get(pointer) {
        return Some(u);
    }
    let segments: Vec<&str> = pointer.split('/').collect();
    // An index at the end: the column's unit.
    if let Some((last, parent)) = segments.split_last() {
        if last.parse::<usize>().is_ok() {
            if let Some(u) = units.get(&parent.join("/")) {
                return Some(u);
            }
        }
    }
    // Indices inside: `*`.
    let starred: Vec<&str> = segments.iter().map(|s| if s.parse::<usize>().is_ok() { "*" } else { s }).collect();
    units.get(&starred.join("/")).map(String::as_str)
}

/// A number in a few characters for a name or a label (`100`, `0.0255`, `1.5e-05`).
pub fn short_number(x: f64) -> String {
    if x == x.round() && x.abs() < 1e9 {
        return format!("{}", x as i64);
    }
    let s = format!("{x:.4}");
    if x.abs() >= 1e-3 && x.abs() < 1e6 {
        s.trim_end_matches('0').trim_end_matches('.').to_string()
    } else {
        format!("{x:.3e}")
    }
}

/// The unit of the column `column` of table `table` (columnar `/table/column` or rows
/// `/table/*/column`), when it has a dimension (`1` is left out of CSV headers).
pub fn column_unit<'a>(units: &'a BTreeMap<String, String>, table: &str, column: &str) -> Option<&'a str> {
    let unit = units.get(&format!("/{table}/{column}")).or_else(|| units.get(&format!("/{table}/*/{column}")))?;
    (unit != "1").then_some(unit.as_str())
}
