//! Every example spec in `examples/` runs through `tribod run` and yields a result without
//! `null`s; the CSV form works for kinds with tables.

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
    assert!(text.starts_with("depth,sigma_x,"), "{text}");
    assert_eq!(text.lines().count(), 62);
}
