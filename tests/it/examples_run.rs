//! Every example spec in `examples/` runs through `tribod run` and yields a result without
//! `null`s, equal to its golden digest (`tests/golden/<example>.json`); the CSV form works for
//! kinds with tables.
//!
//! Golden digests guard refactors (issue 11): every result must stay identical within
//! floating-point noise. A digest keeps every scalar and string, and of every numeric array its
//! length, min, max, mean, rms and nine evenly spaced samples (full results are 3.7 MB). Numbers
//! compare with a relative tolerance of 1e-9 (of the array's largest magnitude for array
//! statistics; 1 % for solver residuals, which amplify last-bit differences). After an intended change of results, bump the kind's solver version and
//! regenerate: `TRIBOD_BLESS=1 cargo test --test it -- examples_run`.

use serde_json::Value;
use std::process::Command;

#[test]
fn every_example_runs_with_tribod_run() {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("examples");
    let mut files: Vec<_> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "json"))
        .collect();
    files.sort();
    assert!(!files.is_empty());
    for file in files {
        let out = Command::new(env!("CARGO_BIN_EXE_tribod")).arg("run").arg(&file).arg("--compact").output().unwrap();
        assert!(
            out.status.success(),
            "{}: exit {:?}\n{}",
            file.display(),
            out.status.code(),
            String::from_utf8_lossy(&out.stderr)
        );
        let result: Value = serde_json::from_slice(&out.stdout).unwrap();
        assert!(result["meta"]["solver_version"].is_string(), "{}", file.display());
        if let Some(path) = null_field(&result, String::new()) {
            panic!("{}: field {path} is null (absent quantities are left out)", file.display());
        }
        check_golden(&file, &result);
    }
}

const GOLDEN_RTOL: f64 = 1e-9;

/// Compare the digest of `result` with the golden file of `example` (or write it when
/// `TRIBOD_BLESS` is set).
fn check_golden(example: &std::path::Path, result: &Value) {
    let name = example.file_name().unwrap();
    let golden_path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/golden").join(name);
    let mut result = result.clone();
    // Run time is not a result, nor is the work model's estimate (recalibrated without a
    // change of results); that every example carries one is checked here.
    if let Some(meta) = result.get_mut("meta").and_then(Value::as_object_mut) {
        meta.remove("wall_time_seconds");
        let estimate = meta.remove("estimate");
        let seconds = estimate.as_ref().and_then(|e| e["cpu_seconds"].as_f64());
        assert!(seconds.is_some_and(|s| s.is_finite() && s > 0.0), "{}: meta.estimate.cpu_seconds {estimate:?}", example.display());
    }
    let got = digest(&result);
    if std::env::var_os("TRIBOD_BLESS").is_some() {
        std::fs::create_dir_all(golden_path.parent().unwrap()).unwrap();
        std::fs::write(&golden_path, serde_json::to_string_pretty(&got).unwrap() + "\n").unwrap();
        return;
    }
    let text = std::fs::read_to_string(&golden_path).unwrap_or_else(|_| {
        panic!("{}: no golden digest; create it with TRIBOD_BLESS=1 cargo test --test it -- examples_run", golden_path.display())
    });
    let want: Value = serde_json::from_str(&text).unwrap();
    let mut diffs = Vec::new();
    compare(&want, &got, String::new(), 0.0, &mut diffs);
    assert!(
        diffs.is_empty(),
        "{}: the result moved from its golden digest ({} differences; first: {:?}). If intended, bump the solver version and re-bless.",
        example.display(),
        diffs.len(),
        &diffs[..diffs.len().min(5)]
    );
}

/// Scalars and strings as they are; numeric arrays as statistics and samples.
fn digest(v: &Value) -> Value {
    match v {
        Value::Object(map) => Value::Object(map.iter().map(|(k, x)| (k.clone(), digest(x))).collect()),
        Value::Array(items) if !items.is_empty() && items.iter().all(|x| x.is_number() || x.is_null()) => {
            let xs: Vec<f64> = items.iter().filter_map(Value::as_f64).collect();
            let n = xs.len().max(1) as f64;
            let samples: Vec<Value> = (0..9)
                .map(|i| items[(i * (items.len() - 1)) / 8].clone())
                .collect();
            serde_json::json!({
                "len": items.len(),
                "min": xs.iter().cloned().fold(f64::INFINITY, f64::min),
                "max": xs.iter().cloned().fold(f64::NEG_INFINITY, f64::max),
                "mean": xs.iter().sum::<f64>() / n,
                "rms": (xs.iter().map(|x| x * x).sum::<f64>() / n).sqrt(),
                "samples": samples,
            })
        }
        Value::Array(items) => Value::Array(items.iter().map(digest).collect()),
        other => other.clone(),
    }
}

/// Differences between two digests; `scale` is the magnitude numbers are compared against (an
/// array's largest magnitude inside its statistics, else the number itself).
fn compare(want: &Value, got: &Value, path: String, scale: f64, diffs: &mut Vec<String>) {
    match (want, got) {
        (Value::Number(a), Value::Number(b)) => {
            let (a, b) = (a.as_f64().unwrap(), b.as_f64().unwrap());
            // A solver's final residual amplifies last-bit differences (it is what the iteration
            // drives below its tolerance): 1 % there, the golden tolerance everywhere else.
            let rtol = if path.rsplit('/').next().is_some_and(|k| k.contains("residual")) { 1e-2 } else { GOLDEN_RTOL };
            let tol = rtol * scale.max(a.abs()).max(b.abs());
            if (a - b).abs() > tol {
                diffs.push(format!("{path}: {a} → {b}"));
            }
        }
        (Value::Object(a), Value::Object(b)) => {
            let scale = if a.contains_key("rms") && a.contains_key("samples") {
                ["min", "max"].iter().filter_map(|k| a.get(*k).and_then(Value::as_f64)).fold(0.0, |m, x| f64::max(m, x.abs()))
            } else {
                scale
            };
            for k in a.keys().chain(b.keys().filter(|k| !a.contains_key(*k))) {
                match (a.get(k), b.get(k)) {
                    (Some(x), Some(y)) => compare(x, y, format!("{path}/{k}"), scale, diffs),
                    (x, y) => diffs.push(format!("{path}/{k}: {x:?} → {y:?}")),
                }
            }
        }
        (Value::Array(a), Value::Array(b)) if a.len() == b.len() => {
            for (i, (x, y)) in a.iter().zip(b).enumerate() {
                compare(x, y, format!("{path}/{i}"), scale, diffs);
            }
        }
        (a, b) if a == b => {}
        (a, b) => diffs.push(format!("{path}: {a} → {b}")),
    }
}

/// The path of a `null` object field, if any. `null` elements of numeric columns are allowed
/// (not computed at that index).
fn null_field(v: &Value, path: String) -> Option<String> {
    match v {
        Value::Null => Some(path),
        Value::Object(map) => map.iter().find_map(|(k, x)| null_field(x, format!("{path}/{k}"))),
        Value::Array(items) if items.iter().any(Value::is_number) => None,
        Value::Array(items) => items.iter().enumerate().find_map(|(i, x)| null_field(x, format!("{path}/{i}"))),
        _ => None,
    }
}

#[test]
fn run_reports_invalid_specs_on_stderr_with_exit_2() {
    let mut child = Command::new(env!("CARGO_BIN_EXE_tribod"))
        .args(["run", "-"])
        .stdin(std::process::Stdio::piped())
        .stdout(std::process::Stdio::piped())
        .stderr(std::process::Stdio::piped())
        .spawn()
        .unwrap();
    use std::io::Write;
    child
        .stdin
        .take()
        .unwrap()
        .write_all(br#"{"kind": "hertz", "spec": {"contact": "line", "load": 0, "length": 1, "body_1": {"shape": "flat"}, "body_2": {"shape": "flat"}}}"#)
        .unwrap();
    let out = child.wait_with_output().unwrap();
    assert_eq!(out.status.code(), Some(2));
    assert!(out.stdout.is_empty());
    let problem: Value = serde_json::from_slice(&out.stderr).unwrap();
    assert_eq!(problem["code"], "invalid_spec");
    assert_eq!(problem["errors"][0]["path"], "/spec/load");
}

#[test]
fn run_prints_csv_tables() {
    let file = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/hertz_roller_on_cam.json");
    let out = Command::new(env!("CARGO_BIN_EXE_tribod")).arg("run").arg(&file).args(["--format", "csv"]).output().unwrap();
    assert!(out.status.success());
    let text = String::from_utf8(out.stdout).unwrap();
    assert!(text.starts_with("depth [m],sigma_x [Pa],"), "{text}");
    assert_eq!(text.lines().count(), 62);
}
