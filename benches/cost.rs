//! The work and memory models (`jobs::cost`) against measured release runs (issue 40).
//!
//! Every example in `examples/` and a spread of grids and angle counts runs through the release
//! binary (`target/release/tribod run`, one process per case); the child's CPU time (user +
//! system) and peak resident memory come from `wait4`'s resource usage, the model's estimate from
//! the same spec prepared in-process. Time and memory are compared above the idle process (a
//! `hertz` job, which also builds the process-wide tables that every `tribod run` and server
//! builds before its first job). Prints a markdown table and the worst ratios.
//!
//! `cargo build --release && cargo bench --bench cost` (`-- <filter>` runs the cases whose name
//! contains it; `-- --large` adds the grids near the default limits, minutes each).
use serde_json::{json, Value};
use std::io::Read;
use std::process::{Command, Stdio};
use tribod::jobs::{registry, Limits};

struct Measured {
    cpu: f64,
    wall: f64,
    max_rss: f64,
    ok: bool,
    error: String,
}

/// Run `tribod run` on `request` (a `{"kind", "spec"}` object); CPU s and peak RSS bytes.
fn measure(binary: &std::path::Path, request: &Value) -> Measured {
    let dir = std::env::temp_dir().join(format!("tribod-cost-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let file = dir.join("case.json");
    std::fs::write(&file, serde_json::to_vec(request).unwrap()).unwrap();
    let start = std::time::Instant::now();
    let mut child = Command::new(binary)
        .args(["run", "--compact", "--max-job-seconds", "0", "--max-job-memory-mb", "1000000"])
        .arg(&file)
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("start tribod");
    let mut out = Vec::new();
    let mut err = String::new();
    child.stdout.take().unwrap().read_to_end(&mut out).unwrap();
    child.stderr.take().unwrap().read_to_string(&mut err).unwrap();
    let mut status = 0;
    // SAFETY: rusage is plain data written by the kernel; the pid is our own child.
    let mut usage: libc::rusage = unsafe { std::mem::zeroed() };
    unsafe { libc::wait4(child.id() as i32, &mut status, 0, &mut usage) };
    let wall = start.elapsed().as_secs_f64();
    let tv = |t: libc::timeval| t.tv_sec as f64 + t.tv_usec as f64 * 1e-6;
    Measured {
        cpu: tv(usage.ru_utime) + tv(usage.ru_stime),
        wall,
        max_rss: usage.ru_maxrss as f64 * 1024.0,
        ok: status == 0,
        error: err.lines().take(3).collect::<Vec<_>>().join(" "),
    }
}

fn example(name: &str) -> Value {
    let path = format!("{}/examples/{name}.json", env!("CARGO_MANIFEST_DIR"));
    serde_json::from_str(&std::fs::read_to_string(&path).unwrap()).unwrap()
}

fn with(mut v: Value, pointer: &str, x: Value) -> Value {
    let (parent, key) = pointer.rsplit_once('/').unwrap();
    let target = if parent.is_empty() { &mut v } else { v.pointer_mut(parent).unwrap() };
    target[key] = x;
    v
}

/// The spread: grids and angle counts around the examples.
fn variants(large: bool) -> Vec<(String, Value)> {
    let mut out = Vec::new();
    let point = |n: usize| json!({"kind": "ehl_point", "spec": {"load": 100.0, "length": 0.01, "reduced_radius": 0.01,
        "entrainment_velocity": 1.0, "lubricant": {"viscosity": 0.04, "pressure_viscosity": 2e-8},
        "geometry": {"type": "point", "rx": 0.01, "ry": 0.01, "nx": n, "ny": n}}});
    let mut grids = vec![129];
    if large {
        grids.extend([257, 513]);
    }
    for n in grids {
        out.push((format!("ehl_point point {n}x{n}"), point(n)));
    }
    let nose = example("ehl_point_seed001_nose");
    for n in [129, 385, 1025, 2049] {
        out.push((format!("ehl_point line {n} nodes"), with(nose.clone(), "/spec/nodes", json!(n))));
    }
    let finite = example("seed000_finite_cycle");
    for a in [36, 90, 360] {
        out.push((format!("finite cycle 33x65 {a} angles"), with(finite.clone(), "/spec/angles", json!(a))));
    }
    let fine = with(with(finite.clone(), "/spec/ehl/nx", json!(65)), "/spec/ehl/ny", json!(129));
    for a in [36, 360] {
        out.push((format!("finite cycle 65x129 {a} angles"), with(fine.clone(), "/spec/angles", json!(a))));
    }
    let flat = with(example("seed003_cycloidal_flat"), "/spec/fidelity", json!("accurate"));
    for a in [180, 720] {
        out.push((format!("seed003 accurate {a} angles"), with(flat.clone(), "/spec/angles", json!(a))));
    }
    let carried = with(example("seed000_thermal_steady"), "/spec/ehl/thermal/carry_tolerance", json!(0.05));
    out.push(("thermal cycle 360 angles carried".into(), with(carried, "/spec/angles", json!(360))));
    let thermal = with(example("seed000_thermal_steady"), "/spec/ehl/thermal/carry_tolerance", json!(0.0));
    for a in [72, 360] {
        out.push((format!("thermal cycle {a} angles"), with(thermal.clone(), "/spec/angles", json!(a))));
    }
    let bearing = example("seed002_aligned");
    for (c, a) in [(91, 45), (181, 91), (721, 361)] {
        let b = with(with(bearing.clone(), "/spec/grid/circumferential", json!(c)), "/spec/grid/axial", json!(a));
        out.push((format!("bearing {c}x{a}"), b));
    }
    let rough = example("rough_contact_seed001");
    for n in [64, 256] {
        out.push((format!("rough {n}²"), with(rough.clone(), "/spec/surface/points", json!(n))));
    }
    out
}

fn main() {
    let args: Vec<String> = std::env::args().skip(1).filter(|a| a != "--bench").collect();
    let large = args.iter().any(|a| a == "--large");
    let filter = args.iter().find(|a| !a.starts_with("--")).cloned().unwrap_or_default();
    let binary = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("target/release/tribod");
    assert!(binary.exists(), "build the release binary first: cargo build --release");
    // The least of five: a loaded machine only adds time.
    let hertz = json!({"kind": "hertz", "spec": registry::find("hertz").unwrap().example()});
    let idle = (0..5).map(|_| measure(&binary, &hertz)).min_by(|a, b| a.cpu.total_cmp(&b.cpu)).unwrap();
    println!("idle process (a hertz job): {:.3} s CPU, {:.1} MiB peak resident\n", idle.cpu, idle.max_rss / 1048576.0);
    let mut cases: Vec<(String, Value)> = Vec::new();
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("examples");
    let mut files: Vec<_> = std::fs::read_dir(&dir).unwrap().map(|e| e.unwrap().path()).collect();
    files.sort();
    for f in files {
        let name = f.file_stem().unwrap().to_string_lossy().to_string();
        cases.push((name.clone(), example(&name)));
    }
    cases.extend(variants(large));
    println!("| case | model CPU (s) | measured CPU above idle (s) | wall (s) | CPU ratio | model MiB | measured MiB | memory ratio |");
    println!("| --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: |");
    let (mut worst_lo, mut worst_hi, mut worst_mem) = (f64::INFINITY, 0.0_f64, 0.0_f64);
    for (name, request) in cases.into_iter().filter(|(n, _)| n.contains(&filter)) {
        let kind = registry::find(request["kind"].as_str().unwrap()).unwrap();
        let cost = match kind.prepare(&request["spec"], &Limits::UNLIMITED) {
            Ok(p) => p.cost,
            Err(p) => {
                println!("| {name} | refused: {} | | | | | | |", p.detail);
                continue;
            }
        };
        // Short cases: the least of three runs (the idle process's time is of their order).
        let mut m = measure(&binary, &request);
        if m.cpu < idle.cpu + 1.0 {
            for _ in 0..2 {
                let again = measure(&binary, &request);
                if again.cpu < m.cpu {
                    m = again;
                }
            }
        }
        let model = cost.estimate;
        let cpu = (m.cpu - idle.cpu).max(1e-4);
        let ratio = cpu / model.cpu_seconds;
        let used = (m.max_rss - idle.max_rss).max(0.0);
        let mem_ratio = used / model.memory_bytes.max(1.0);
        let mib = |b: f64| b / 1048576.0;
        let note = if m.ok { String::new() } else { format!(" (failed: {})", m.error) };
        println!(
            "| {name}{note} | {:.4} | {:.4} | {:.3} | {ratio:.2} | {:.1} | {:.1} | {mem_ratio:.2} |",
            model.cpu_seconds, cpu, m.wall, mib(model.memory_bytes), mib(used)
        );
        if cpu > 0.2 {
            worst_lo = worst_lo.min(ratio);
            worst_hi = worst_hi.max(ratio);
        }
        if used > 20.0 * 1048576.0 {
            worst_mem = worst_mem.max(mem_ratio);
        }
    }
    println!("\nmeasured/model CPU over cases above 0.2 s: {worst_lo:.2} … {worst_hi:.2}; measured/model memory above 20 MiB: at most {worst_mem:.2}");
}
