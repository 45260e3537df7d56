//! Journal bearing solver: run time against error. `cargo bench --bench journal`.
use std::time::Instant;
use tribod::physics::journal::*;
use tribod::physics::Silent;

#[repr(C)]
struct Timespec {
    tv_sec: i64,
    tv_nsec: i64,
}
unsafe extern "C" {
    fn clock_gettime(clock: i32, ts: *mut Timespec) -> i32;
}
/// CPU time of the calling thread, s (POSIX `CLOCK_THREAD_CPUTIME_ID`). On a machine shared
/// with other jobs wall time includes waiting for a core; thread CPU time measures the work.
fn thread_cpu() -> f64 {
    let mut ts = Timespec { tv_sec: 0, tv_nsec: 0 };
    // SAFETY: plain libc call writing into a local struct of the C layout.
    unsafe { clock_gettime(3, &mut ts) };
    ts.tv_sec as f64 + ts.tv_nsec as f64 * 1e-9
}

/// Best of `n` runs: (thread CPU seconds, wall seconds, result).
fn best_of<T>(n: usize, mut f: impl FnMut() -> T) -> (f64, T) {
    let mut best = f64::INFINITY;
    let mut out = None;
    for _ in 0..n {
        let c = thread_cpu();
        let r = f();
        best = best.min(thread_cpu() - c);
        out = Some(r);
    }
    (best, out.unwrap())
}

fn main() {
    let quick = std::env::args().any(|a| a == "--quick");
    cycle_cost();
    let reps = if quick { 2 } else { 5 };
    let grid = |nt, nz| Settings { circumferential: nt, axial: nz, ..Settings::default() };
    let b = Bearing::plain(1.25);
    let s = grid(361, 181);
    let (t, a) = best_of(reps, || analyse(&b, &Operating::Eccentricity(0.6), &s, None, None, false, &Silent).unwrap());
    println!("aligned eps=0.6 361x181: {:.1} ms  P0 {:.5} W {:.5} steps {:?} {:?}", t * 1e3, a.max_pressure, a.load, a.steps_per_grid, a.pressure_solve);
    let w = a.load;
    let mut bm = b;
    bm.misalignment = Misalignment { vertical: 0.56, horizontal: 0.56 };
    bm.profile = Some(Profile { order: 2, height: 0.4, length_fraction: 0.2 });
    let (t, m) = best_of(reps, || analyse(&bm, &Operating::Load(w), &s, None, None, false, &Silent).unwrap());
    let mut ws = Workspace::new(&bm, &s);
    let t0 = Instant::now();
    analyse(&bm, &Operating::Load(w), &s, Some(&mut ws), None, false, &Silent).unwrap();
    println!("ws run {:.1} ms cycles {:?} steps {:?}", t0.elapsed().as_secs_f64()*1e3, ws.cycles(), ws.steps());
    println!("misaligned profiled load balance 361x181: {:.1} ms  P0 {:.5} H0 {:.5} steps {:?} {:?}", t * 1e3, m.max_pressure, m.min_film, m.steps_per_grid, m.pressure_solve);
}
#[allow(dead_code)]
fn cycle_cost() {
    use tribod::physics::journal::multigrid::Hierarchy;
    let mut h = Hierarchy::new(360, 181, 0.16, true);
    h.set_film(&Film::aligned(0.6, 0.0), 0.0);
    let (t, rep) = best_of(10, || {
        h.levels[0].u.fill(0.0);
        h.nested_solve(0, 1e-10, 60, 1000)
    });
    println!("nested solve 361x181 tol 1e-10: {:.2} ms, level-0 {rep:?}", t * 1e3);
    let (t, _) = best_of(20, || h.set_film(&Film::aligned(0.6, 0.0), 0.0));
    println!("set_film all levels: {:.3} ms", t * 1e3);
}
