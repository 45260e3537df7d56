//! A label for a job submitted without one (issue 39): the kind and the inputs that differ from
//! the kind's example, then a short tag of the spec hash — so two different specs of one kind
//! never share a label, and the dashboard's list, page titles, plot titles and download names
//! tell jobs apart. `hertz · load=9000 · body_1.radius=0.03 · #3fa2c1`.

use super::kind::{DynKind, Limits};
use serde_json::Value;

/// At most this many differing inputs are named; the rest are counted.
const NAMED: usize = 3;

/// The label of a spec (canonical, defaults filled) of kind `k` with hash `hash` (hex).
pub fn auto_label(k: &'static dyn DynKind, canonical: &Value, hash: &str) -> String {
    let example = canonical_example(k);
    let mut diffs = Vec::new();
    differences("", canonical, example, &mut diffs);
    let tag = &hash[..hash.len().min(6)];
    let mut parts = vec![k.name().to_string()];
    if diffs.is_empty() {
        parts.push("example".into());
    } else {
        let more = diffs.len().saturating_sub(NAMED);
        parts.extend(diffs.into_iter().take(NAMED));
        if more > 0 {
            parts.push(format!("+{more} more"));
        }
    }
    parts.push(format!("#{tag}"));
    parts.join(" · ")
}

/// The kind's example, canonical (defaults filled): validated once per kind and kept, not on
/// every submission.
fn canonical_example(k: &'static dyn DynKind) -> &'static Value {
    static CACHE: std::sync::OnceLock<std::sync::Mutex<std::collections::HashMap<&'static str, &'static Value>>> = std::sync::OnceLock::new();
    let mut map = CACHE.get_or_init(Default::default).lock().unwrap_or_else(|e| e.into_inner());
    map.entry(k.name()).or_insert_with(|| {
        let example = k.prepare(&k.example(), &Limits::UNLIMITED).map(|p| p.canonical).unwrap_or(Value::Null);
        Box::leak(Box::new(example))
    })
}

/// `path=value` for every input of `spec` that differs from `example` (a whole object or list
/// counts once where the example has none, or a different variant).
fn differences(path: &str, spec: &Value, example: &Value, out: &mut Vec<String>) {
    match (spec, example) {
        (Value::Object(a), Value::Object(b)) if same_variant(a, b) => {
            for (key, v) in a {
                let p = if path.is_empty() { key.clone() } else { format!("{path}.{key}") };
                differences(&p, v, b.get(key).unwrap_or(&Value::Null), out);
            }
        }
        (a, b) if a == b => {}
        (a, _) => out.push(format!("{}={}", if path.is_empty() { "spec" } else { path }, brief(a))),
    }
}

/// Two objects are the same variant unless a tag (`type`, `shape`, `model`) differs.
fn same_variant(a: &serde_json::Map<String, Value>, b: &serde_json::Map<String, Value>) -> bool {
    ["type", "shape", "model"].iter().all(|t| a.get(*t) == b.get(*t))
}

/// A value in a few characters: numbers to 4 significant figures, lists by their length,
/// objects by their tag.
fn brief(v: &Value) -> String {
    match v {
        Value::Number(n) => n.as_f64().map(significant).unwrap_or_else(|| n.to_string()),
        Value::String(s) => s.chars().take(24).collect(),
        Value::Array(items) if items.len() <= 3 && items.iter().all(|x| !x.is_object() && !x.is_array()) => {
            format!("[{}]", items.iter().map(brief).collect::<Vec<_>>().join(","))
        }
        Value::Array(items) => format!("[{} items]", items.len()),
        Value::Object(m) => ["type", "shape", "model"].iter().find_map(|t| m.get(*t).and_then(Value::as_str)).unwrap_or("{…}").to_string(),
        other => other.to_string(),
    }
}

/// `x` to 4 significant figures, without trailing zeros (`0.0255`, `1.25e+04` → `12500`).
fn significant(x: f64) -> String {
    if x == 0.0 || !x.is_finite() {
        return format!("{x}");
    }
    let a = x.abs();
    if (1e-3..1e6).contains(&a) {
        let decimals = (3 - a.log10().floor() as i32).max(0) as usize;
        let s = format!("{x:.decimals$}");
        if s.contains('.') { s.trim_end_matches('0').trim_end_matches('.').to_string() } else { s }
    } else {
        format!("{x:.3e}")
    }
}

