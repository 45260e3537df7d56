//! The house rules (issue 11), checked on the source: who may import whom, and the typed
//! boundary between the solvers and the job layer.

use std::path::{Path, PathBuf};
use tribod::physics::SolveError;

fn files(dir: &str) -> Vec<PathBuf> {
    let mut out = Vec::new();
    let mut stack = vec![Path::new(env!("CARGO_MANIFEST_DIR")).join(dir)];
    while let Some(d) = stack.pop() {
        for entry in std::fs::read_dir(&d).unwrap() {
            let p = entry.unwrap().path();
            if p.is_dir() {
                stack.push(p);
            } else if p.extension().is_some_and(|e| e == "rs") {
                out.push(p);
            }
        }
    }
    assert!(!out.is_empty(), "no sources under {dir}");
    out
}

/// `room` imports none of `forbidden` (as `crate::<name>` paths).
fn imports_none(room: &str, forbidden: &[&str]) {
    for file in files(room) {
        let text = std::fs::read_to_string(&file).unwrap();
        // Code only: comments may name other rooms.
        let code: Vec<&str> = text.lines().filter(|l| !l.trim_start().starts_with("//")).collect();
        for name in forbidden {
            let used = code.iter().any(|l| l.contains(&format!("crate::{name}::")) || l.contains(&format!("crate::{name};")) || l.contains(&format!("crate::{name}{{")));
            assert!(!used, "{} imports crate::{name}", file.display());
        }
    }
}

/// The physics crate's `[dependencies]` are exactly within `allowed`.
fn physics_depends_only_on(allowed: &[&str]) {
    let manifest = std::fs::read_to_string(Path::new(env!("CARGO_MANIFEST_DIR")).join("crates/physics/Cargo.toml")).unwrap();
    let deps = manifest.split("[dependencies]").nth(1).expect("crates/physics/Cargo.toml has [dependencies]");
    let deps = deps.split("\n[").next().unwrap();
    let names: Vec<&str> = deps.lines().filter_map(|l| l.split('=').next()).map(str::trim).filter(|n| !n.is_empty() && !n.starts_with('#')).collect();
    assert!(!names.is_empty());
    for name in names {
        assert!(allowed.contains(&name), "the physics crate depends on {name}; physics stays free of service crates");
    }
    for file in files("crates/physics/src") {
        let text = std::fs::read_to_string(&file).unwrap();
        assert!(!text.contains("utoipa"), "{} names utoipa", file.display());
    }
}

#[test]
fn rooms_import_only_what_they_may() {
    // Physics is pure: a crate of its own, so the compiler keeps service code out of it; its
    // dependencies are numerics and serde only (no transport, database, async or schema crates).
    physics_depends_only_on(&["serde", "thiserror", "faer", "rayon", "rustfft"]);
    // The API reaches solvers only through jobs.
    imports_none("src/api", &["physics"]);
    // Plots read result JSON; the store keeps rows; the web pages talk to the public API.
    imports_none("src/plots", &["physics", "jobs", "api", "store", "server"]);
    imports_none("src/store", &["physics", "jobs", "api", "server", "plots", "web"]);
    imports_none("src/web", &["physics", "jobs", "store", "server", "plots"]);
}

/// A solver names its own input's field; the kind turns it into the spec's path; an error
/// nobody mapped still says which solver input it was about.
#[test]
fn solver_input_errors_name_solver_fields_and_kinds_map_them() {
    let e = tribod::physics::cam::MultiArc::new(&[(0.02, 1.0), (-1.0, 5.28)]).unwrap_err();
    assert_eq!(e, SolveError::invalid("MultiArc.arcs[1]", "radius and angle must be finite and > 0"));
    let mapped = e.clone().in_spec(tribod::jobs::kinds::common::cam_spec_path);
    assert_eq!(mapped, SolveError::invalid("/cam/profile/arcs/1", "radius and angle must be finite and > 0"));
    let p = tribod::problem::Problem::from_solve_error(&mapped);
    assert_eq!(p.errors[0].path, "/cam/profile/arcs/1");
    // Unmapped: no field error with a made-up path, the solver field in the detail.
    let p = tribod::problem::Problem::from_solve_error(&SolveError::invalid("EhlInput.reduced_radius", "must be a finite number > 0"));
    assert!(p.errors.is_empty());
    assert!(p.detail.contains("EhlInput.reduced_radius"), "{}", p.detail);
    // Already a spec path: kept.
    let kept = SolveError::invalid("/load", "x").in_spec(|_| Some("/elsewhere".into()));
    assert_eq!(kept, SolveError::invalid("/load", "x"));
}

/// Every migration file of both backends is embedded in the binary, in version order, and
/// nothing else is (the lists in `store::migrations` are written by hand).
#[test]
fn every_migration_file_is_embedded() {
    for (folder, list) in [("migrations/sqlite", tribod::store::migrations::SQLITE), ("migrations/postgres", tribod::store::migrations::POSTGRES)] {
        let mut on_disk: Vec<(String, String)> = std::fs::read_dir(Path::new(env!("CARGO_MANIFEST_DIR")).join(folder))
            .unwrap()
            .map(|e| e.unwrap().path())
            .filter(|p| p.extension().is_some_and(|x| x == "sql"))
            .map(|p| (p.file_name().unwrap().to_string_lossy().to_string(), std::fs::read_to_string(&p).unwrap()))
            .collect();
        on_disk.sort();
        let embedded: Vec<(String, String)> = list.iter().map(|(n, s)| (n.to_string(), s.to_string())).collect();
        assert_eq!(embedded, on_disk, "{folder}: store::migrations lists every file, in version order");
        let versions: Vec<i64> = tribod::store::migrations::migrator(list).iter().map(|m| m.version).collect();
        assert!(versions.windows(2).all(|w| w[0] < w[1]), "{versions:?}");
    }
}

/// The service crate has no test harness of its own (`[lib] test = false`): a unit test written
/// in `src/` would never run, so there are none; its tests are modules of this binary
/// (`service_units` for the parts).
#[test]
fn no_unit_tests_hide_in_the_service_crate() {
    for file in files("src") {
        let text = std::fs::read_to_string(&file).unwrap();
        assert!(!text.contains("#[test]") && !text.contains("#[cfg(test)]"), "{} holds a unit test that cargo test would not run; move it to tests/it/", file.display());
    }
}

/// Physics does no I/O: outside its test modules (a `tests.rs` file, or what follows a file's
/// `#[cfg(test)]`) no solver reads the environment, a file or the clock's wall date, or prints.
/// Development traces go through the `Observer`, or stay on a branch.
#[test]
fn physics_does_no_io() {
    let forbidden = ["std::env::", "std::fs::", "println!", "eprintln!", "print!(", "eprint!(", "dbg!(", "SystemTime"];
    for file in files("crates/physics/src") {
        if file.file_name().is_some_and(|n| n == "tests.rs") || file.components().any(|c| c.as_os_str() == "tests") {
            continue;
        }
        let text = std::fs::read_to_string(&file).unwrap();
        let code = text.split("#[cfg(test)]").next().unwrap();
        for (i, line) in code.lines().enumerate() {
            let line = line.split("//").next().unwrap();
            for f in forbidden {
                assert!(!line.contains(f), "{}:{}: physics does no I/O, found `{f}`", file.display(), i + 1);
            }
        }
    }
}
