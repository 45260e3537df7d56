//! Journal bearing solver (seed 002): run time against error, the load-balanced misaligned
//! profiled case at the paper's 361×181 grid, and the Taguchi L9 on two cores.
//!
//! `cargo bench --bench journal` (add `-- --quick` for fewer repetitions). Times are the best of
//! N runs; "CPU" is the thread's CPU time (POSIX CLOCK_THREAD_CPUTIME_ID), which on a machine
//! shared with other jobs measures the work better than wall time; wall time is given too.
use std::time::Instant;
use tribod::jobs::kinds::bearing_optimisation::{BearingOptimisation, OptimisationSpec};
use tribod::jobs::Kind;
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
/// CPU time of the calling thread, s (POSIX `CLOCK_THREAD_CPUTIME_ID` = 3 on Linux).
fn thread_cpu() -> f64 {
    let mut ts = Timespec { tv_sec: 0, tv_nsec: 0 };
    // SAFETY: plain libc call writing into a local struct of the C layout.
    unsafe { clock_gettime(3, &mut ts) };
    ts.tv_sec as f64 + ts.tv_nsec as f64 * 1e-9
}

/// CPU time of the whole process (all threads), s (`CLOCK_PROCESS_CPUTIME_ID` = 2).
fn process_cpu() -> f64 {
    let mut ts = Timespec { tv_sec: 0, tv_nsec: 0 };
    // SAFETY: as above.
    unsafe { clock_gettime(2, &mut ts) };
    ts.tv_sec as f64 + ts.tv_nsec as f64 * 1e-9
}

/// Best of `n` runs: (thread CPU s, wall s, last result).
fn best_of<T>(n: usize, mut f: impl FnMut() -> T) -> (f64, f64, T) {
    let (mut cpu, mut wall) = (f64::INFINITY, f64::INFINITY);
    let mut out = None;
    for _ in 0..n {
        let (c, t) = (thread_cpu(), Instant::now());
        let r = f();
        cpu = cpu.min(thread_cpu() - c);
        wall = wall.min(t.elapsed().as_secs_f64());
        out = Some(r);
    }
    (cpu, wall, out.unwrap())
}

fn settings(nt: usize, nz: usize) -> Settings {
    Settings { circumferential: nt, axial: nz, ..Settings::default() }
}

/// Seed 002's optimised design under its misalignment, at the aligned load of ε = 0.6.
fn seed_case() -> Bearing {
    Bearing {
        misalignment: Misalignment { vertical: 0.56, horizontal: 0.56 },
        profile: Some(Profile { order: 2, height: 0.4, length_fraction: 0.2 }),
        ..Bearing::plain(1.25)
    }
}

fn richardson(f2: f64, f3: f64, p: f64) -> f64 {
    f3 + (f3 - f2) / (2f64.powf(p) - 1.0)
}

/// Dynamic coefficients (issue 18): run time of the equilibrium and of the coefficients on the
/// same workspace, and the coefficients' error against the finest grid, at L/D 0.5 and 1,
/// load of aligned ε = 0.5 (max-film groove); then seed 002's misaligned profiled case.
/// `cargo bench --bench journal -- coefficients`.
fn coefficients_section(reps: usize) {
    use tribod::physics::journal::dynamics::coefficients;
    println!("\n## Dynamic coefficients: run time against error (one thread)\n");
    println!("| L/D | grid | equilibrium CPU ms | coefficients CPU ms | ratio | K̄ err | C̄ err |");
    println!("| ---: | --- | ---: | ---: | ---: | ---: | ---: |");
    let grids: &[(usize, usize)] = &[(41, 21), (61, 21), (121, 41), (181, 61), (241, 81), (361, 121), (721, 241)];
    for ld in [0.5, 1.0] {
        let b = Bearing::plain(ld);
        let (fnt, fnz) = grids[grids.len() - 1];
        let w = analyse(&b, &Operating::Eccentricity(0.5), &settings(fnt, fnz), None, None, false, &Silent).unwrap().load;
        let mut rows = Vec::new();
        for &(nt, nz) in grids {
            let s = settings(nt, nz);
            let r = if nt * nz > 50_000 { 1 } else { reps };
            let (ce, _, (a, mut ws)) = best_of(r, || {
                let mut ws = Workspace::new(&b, &s);
                let a = analyse(&b, &Operating::Load(w), &s, Some(&mut ws), None, false, &Silent).unwrap();
                (a, ws)
            });
            let (cc, _, c) = best_of(r, || coefficients(&b, &a, &s, &mut ws, &Silent).unwrap());
            let (k, d) = c.dimensionless(a.load).unwrap();
            rows.push((nt, nz, ce, cc, k, d));
        }
        let (_, _, _, _, kf, df) = rows[rows.len() - 1];
        let err = |m: &[[f64; 2]; 2], r: &[[f64; 2]; 2]| {
            let scale = r.iter().flatten().fold(0.0f64, |a, v| a.max(v.abs()));
            m.iter().flatten().zip(r.iter().flatten()).fold(0.0f64, |a, (x, y)| a.max((x - y).abs())) / scale
        };
        for (nt, nz, ce, cc, k, d) in &rows {
            println!("| {ld} | {nt}×{nz} | {:.2} | {:.2} | {:.2} | {:.1e} | {:.1e} |", ce * 1e3, cc * 1e3, cc / ce, err(k, &kf), err(d, &df));
        }
        println!("\nL/D {ld} reference ({fnt}×{fnz}): K̄ = {kf:?}, C̄ = {df:?}\n");
    }
    let s = settings(361, 181);
    let w = analyse(&Bearing::plain(1.25), &Operating::Eccentricity(0.6), &s, None, None, false, &Silent).unwrap().load;
    let b = seed_case();
    let mut ws = Workspace::new(&b, &s);
    let (ce, _, a) = best_of(reps, || analyse(&b, &Operating::Load(w), &s, Some(&mut ws), None, false, &Silent).unwrap());
    let (cc, _, c) = best_of(reps, || coefficients(&b, &a, &s, &mut ws, &Silent).unwrap());
    println!(
        "Seed 002 misaligned profiled, 361×181: equilibrium {:.1} ms, coefficients {:.1} ms (ratio {:.2}); K̄ = {:?}, C̄ = {:?}",
        ce * 1e3,
        cc * 1e3,
        cc / ce,
        c.dimensionless(a.load).unwrap().0,
        c.dimensionless(a.load).unwrap().1
    );
}

/// ROSS's plain-bearing case (issue 18): the geometry, speed and load of ROSS's cylindrical
/// bearing example (`PlainJournal` docstring / `cylindrical_bearing_example`: L = 0.263144 m,
/// D = 0.4 m, c = 1.95e-4 m, 900 rpm, W = 112814.91 N), isothermal with ROSS's reference
/// viscosity 0.02 Pa·s, one supply line at the largest film. Returns (L/D, W̄).
fn ross_case() -> (f64, f64) {
    let (l, r, c, eta, w) = (0.263144, 0.2, 1.95e-4, 0.02, 112814.91);
    let omega = 900.0 * std::f64::consts::TAU / 60.0;
    // seed 002 scaling: W̄ = w (c/R)² / (6 η ω R L)
    (l / (2.0 * r), w * (c / r).powi(2) / (6.0 * eta * omega * r * l))
}

/// The speed deliverable of issue 18: ROSS's case at 121×41 (and 41×121), equilibrium and
/// coefficients; the misaligned profiled case at 361×181; the L9 on two cores.
/// `cargo bench --bench journal -- speed`.
fn speed_section(reps: usize) {
    use tribod::physics::journal::dynamics::{coefficients, tilt_coefficients};
    let (ld, w) = ross_case();
    let b = Bearing::plain(ld);
    let fine = settings(721, 241);
    let r = analyse(&b, &Operating::Load(w), &fine, None, None, false, &Silent).unwrap();
    println!("\n## ROSS plain-bearing case: L/D = {ld:.5}, W̄ = {w:.6} (S = {:.4}); 721×241: ε = {:.6}, β = {:.4}°\n", 1.0 / (6.0 * std::f64::consts::PI * w), r.eccentricity, r.attitude.to_degrees());
    println!("| grid | cold equilibrium CPU ms (wall) | warm workspace CPU ms | coefficients CPU ms | ratio | force + moment (4×4) CPU ms | ratio | ε err | β err | steps per grid | V-cycles per level |");
    println!("| --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | --- | --- |");
    for (nt, nz) in [(121, 41), (41, 121), (241, 81)] {
        let s = settings(nt, nz);
        let (ce, we, a) = best_of(reps * 4, || analyse(&b, &Operating::Load(w), &s, None, None, false, &Silent).unwrap());
        let mut ws = Workspace::new(&b, &s);
        analyse(&b, &Operating::Load(w), &s, Some(&mut ws), None, false, &Silent).unwrap();
        let c0 = ws.cycles();
        let (cw, _, _) = best_of(reps * 4, || analyse(&b, &Operating::Load(w), &s, Some(&mut ws), None, false, &Silent).unwrap());
        let mut ws2 = Workspace::new(&b, &s);
        analyse(&b, &Operating::Load(w), &s, Some(&mut ws2), None, false, &Silent).unwrap();
        let (cc, _, _) = best_of(reps * 4, || coefficients(&b, &a, &s, &mut ws2, &Silent).unwrap());
        let (ct, _, _) = best_of(reps * 4, || tilt_coefficients(&b, &a, &s, &mut ws2, &Silent).unwrap());
        println!(
            "| {nt}×{nz} | {:.3} ({:.3}) | {:.3} | {:.3} | {:.2} | {:.3} | {:.2} | {:.1e} | {:.1e} | {:?} | {:?} |",
            ce * 1e3, we * 1e3, cw * 1e3, cc * 1e3, cc / ce, ct * 1e3, ct / ce,
            (a.eccentricity / r.eccentricity - 1.0).abs(), (a.attitude / r.attitude - 1.0).abs(),
            a.steps_per_grid, c0
        );
    }
    let s = settings(361, 181);
    let wa = analyse(&Bearing::plain(1.25), &Operating::Eccentricity(0.6), &s, None, None, false, &Silent).unwrap().load;
    let (c, wl, m) = best_of(reps * 2, || analyse(&seed_case(), &Operating::Load(wa), &s, None, None, false, &Silent).unwrap());
    let mut ws = Workspace::new(&seed_case(), &s);
    analyse(&seed_case(), &Operating::Load(wa), &s, Some(&mut ws), None, false, &Silent).unwrap();
    println!("\nmisaligned profiled 361×181, cold: {:.2} ms CPU ({:.2} wall); P0 {:.6}, H0 {:.6}; steps per grid {:?}; V-cycles {:?}; active-set steps {:?}",
        c * 1e3, wl * 1e3, m.max_pressure, m.min_film, m.steps_per_grid, ws.cycles(), ws.steps());
    let (cc, _, _) = best_of(reps * 2, || coefficients(&seed_case(), &m, &s, &mut ws, &Silent).unwrap());
    let (ct, _, _) = best_of(reps * 2, || tilt_coefficients(&seed_case(), &m, &s, &mut ws, &Silent).unwrap());
    println!("misaligned profiled 361×181: coefficients {:.2} ms CPU ({:.2}× the equilibrium), force and moment coefficients (4×4) {:.2} ms CPU ({:.2}×)", cc * 1e3, cc / c, ct * 1e3, ct / c);
    let spec_json = serde_json::json!({
        "base": {
            "geometry": {"length_to_diameter": 1.25},
            "load": {"aligned_eccentricity_ratio": 0.6},
            "misalignment": {"vertical": 0.56, "horizontal": 0.56},
            "grid": {"circumferential": 361, "axial": 181}
        },
        "method": "taguchi_l9",
        "factors": {"order": [1, 2, 3], "height": [0.1, 0.4, 1.0], "length_fraction": [0.01, 0.2, 0.4]},
        "continuous": {"enabled": false}
    });
    let spec: OptimisationSpec = serde_json::from_value(spec_json).unwrap();
    let pool = rayon::ThreadPoolBuilder::new().num_threads(2).build().unwrap();
    let (mut wall, mut cpu) = (f64::INFINITY, f64::INFINITY);
    let mut ev = 0;
    for _ in 0..reps {
        let (c, t) = (process_cpu(), Instant::now());
        ev = pool.install(|| BearingOptimisation::solve(&spec, &Silent).unwrap()).evaluations;
        wall = wall.min(t.elapsed().as_secs_f64());
        cpu = cpu.min(process_cpu() - c);
    }
    println!("L9 ({ev} analyses, 2 threads): {:.1} ms wall, {:.1} ms CPU over both threads (best of {reps})", wall * 1e3, cpu * 1e3);
}

/// Run time against error of the force and moment coefficients (`cargo bench --bench journal --
/// moments`): seed 002's misaligned, profiled design at the load of the aligned ε = 0.6, the
/// load solved on each grid, then the 2×2 and the 4×4 coefficients; the error of each 2×2 block
/// of the dimensionless 4×4 (`K̄ = K/W̄`) over that block's largest entry, against 721×361.
fn moments() {
    use tribod::physics::journal::dynamics::{coefficients, tilt_coefficients};
    let b = seed_case();
    let solve = |nt: usize, nz: usize| {
        let s = settings(nt, nz);
        let w = analyse(&Bearing::plain(1.25), &Operating::Eccentricity(0.6), &s, None, None, false, &Silent).unwrap().load;
        let (te, _, a) = best_of(3, || analyse(&b, &Operating::Load(w), &s, None, None, false, &Silent).unwrap());
        let mut ws = Workspace::new(&b, &s);
        analyse(&b, &Operating::Load(w), &s, Some(&mut ws), None, false, &Silent).unwrap();
        let (tc, _, _) = best_of(3, || coefficients(&b, &a, &s, &mut ws, &Silent).unwrap());
        let (tt, _, t) = best_of(3, || tilt_coefficients(&b, &a, &s, &mut ws, &Silent).unwrap());
        let (k, c) = t.dimensionless(a.load).unwrap();
        (te, tc, tt, k, c)
    };
    let (_, _, _, kr, cr) = solve(721, 361);
    let blocks = |m: &[[f64; 4]; 4], r: &[[f64; 4]; 4]| -> Vec<f64> {
        (0..4)
            .map(|bk| {
                let (i0, j0) = (2 * (bk / 2), 2 * (bk % 2));
                let (mut d, mut size) = (0.0f64, 0.0f64);
                for i in i0..i0 + 2 {
                    for j in j0..j0 + 2 {
                        d = d.max((m[i][j] - r[i][j]).abs());
                        size = size.max(r[i][j].abs());
                    }
                }
                d / size
            })
            .collect()
    };
    println!("reference 721×361: K̄ {kr:?}\n C̄ {cr:?}\n");
    println!("| grid | equilibrium CPU ms | 2×2 CPU ms | 4×4 CPU ms | 4×4 / equilibrium | K̄ error FX / FΓ / MX / MΓ | C̄ error FX / FΓ / MX / MΓ |");
    println!("| --- | ---: | ---: | ---: | ---: | --- | --- |");
    for (nt, nz) in [(61, 31), (121, 61), (181, 91), (241, 121), (361, 181)] {
        let (te, tc, tt, k, c) = solve(nt, nz);
        let f = |v: Vec<f64>| v.iter().map(|x| format!("{x:.1e}")).collect::<Vec<_>>().join(" / ");
        println!("| {nt}×{nz} | {:.2} | {:.2} | {:.2} | {:.2} | {} | {} |", te * 1e3, tc * 1e3, tt * 1e3, tt / te, f(blocks(&k, &kr)), f(blocks(&c, &cr)));
    }
}

/// The L9's nine profiled cases one by one on one thread (`cargo bench --bench journal --
/// l9-cases`), with the unprofiled baseline before them and the confirmation after: each a cold analysis at 361×181 under seed 002's misalignment and the load of the
/// aligned ε = 0.6, started at the aligned position (as the L9 runs are), with its work counters:
/// balance steps per grid, V-cycles and active-set steps per level (finest first).
fn l9_cases() {
    let s = settings(361, 181);
    // the reference as the kind solves it (the mirrored half)
    let mut wr = Workspace::new(&Bearing::plain(1.25), &s);
    let a = analyse_symmetric(&Bearing::plain(1.25), &Operating::Eccentricity(0.6), &s, Some(&mut wr), None, false, &Silent).unwrap();
    println!("reference (half): W̄ {:.12}, β {:.12}; steps per grid {:?}", a.load, a.attitude, a.steps_per_grid);
    let guess = Guess { eccentricity: a.eccentricity, attitude: a.attitude };
    let runs = [(1, 0.1, 0.01), (1, 0.4, 0.2), (1, 1.0, 0.4), (2, 0.1, 0.2), (2, 0.4, 0.4), (2, 1.0, 0.01), (3, 0.1, 0.4), (3, 0.4, 0.01), (3, 1.0, 0.2)];
    let mut finest_cycles = 0;
    // the unprofiled baseline first and the confirmation (2, 0.4, 0.2) last, outside the sum
    let cases = std::iter::once(None).chain(runs.iter().map(|&(order, height, length_fraction)| Some(Profile { order, height, length_fraction }))).chain(std::iter::once(Some(Profile { order: 2, height: 0.4, length_fraction: 0.2 })));
    for (n, profile) in cases.enumerate() {
        let b = Bearing { profile, ..seed_case() };
        let (order, height, length_fraction) = profile.map_or((0, 0.0, 0.0), |p| (p.order, p.height, p.length_fraction));
        let mut ws = Workspace::new(&b, &s);
        let (c, _, m) = best_of(1, || analyse(&b, &Operating::Load(a.load), &s, Some(&mut ws), Some(guess), false, &Silent).unwrap());
        if (1..=9).contains(&n) {
            finest_cycles += ws.cycles()[0];
        }
        println!(
            "({order}, {height}, {length_fraction}): {:.1} ms CPU; ε {:.7}, β {:.7}; steps per grid {:?}; V-cycles {:?}; active-set steps {:?}",
            c * 1e3, m.eccentricity, m.attitude, m.steps_per_grid, ws.cycles(), ws.steps()
        );
    }
    println!("finest-grid V-cycles over the nine cases: {finest_cycles}");
}

/// The L9's schedule on two idle cores, modelled from measured costs (`cargo bench --bench
/// journal -- l9-schedule`): the thread CPU of each analysis (best of 3; the reference, the
/// baseline, the nine runs and the confirmation, each on a reset workspace as the kind runs
/// them) and of a workspace allocation, then the makespan of round 8's schedule (reference;
/// cases `w, w + 2, …` per worker, the second worker allocating its workspace first;
/// confirmation after both) and of round 9's (allocation during the reference; cases from a
/// shared counter; the idle worker starts the confirmation while the last case runs, kept when
/// the predicted best levels hold). Wall times on this shared VM are too noisy to show it.
fn l9_schedule() {
    let s = settings(361, 181);
    let plain = Bearing::plain(1.25);
    let (alloc, _, _) = best_of(3, || Workspace::new(&seed_case(), &s));
    let mut ws = Workspace::new(&plain, &s);
    // the reference on the full grid and on the mirrored half (what the kind runs), alternately
    let (mut reference_full, mut reference) = (f64::INFINITY, f64::INFINITY);
    let mut a = None;
    for _ in 0..3 {
        reference_full = reference_full.min(best_of(1, || {
            ws.reset();
            analyse(&plain, &Operating::Eccentricity(0.6), &s, Some(&mut ws), None, false, &Silent).unwrap()
        }).0);
        // as the kind runs it: `symmetric_load` on grids of its own
        let (c, _, h) = best_of(1, || symmetric_load(&plain, &Operating::Eccentricity(0.6), &s, None, None, &Silent).unwrap());
        reference = reference.min(c);
        a = Some(h);
    }
    let (load, guess) = a.unwrap();
    println!("reference on the full grid {:.2} ms, on the mirrored half {:.2} ms (the model below uses the half; the kind allocates both workers' workspaces during it)", reference_full * 1e3, reference * 1e3);
    let runs = [(1, 0.1, 0.01), (1, 0.4, 0.2), (1, 1.0, 0.4), (2, 0.1, 0.2), (2, 0.4, 0.4), (2, 1.0, 0.01), (3, 0.1, 0.4), (3, 0.4, 0.01), (3, 1.0, 0.2)];
    let profiles: Vec<Option<Profile>> = std::iter::once(None)
        .chain(runs.iter().map(|&(order, height, length_fraction)| Some(Profile { order, height, length_fraction })))
        .chain(std::iter::once(Some(Profile { order: 2, height: 0.4, length_fraction: 0.2 })))
        .collect();
    let costs: Vec<f64> = profiles
        .iter()
        .map(|p| {
            let b = Bearing { profile: *p, ..seed_case() };
            best_of(3, || {
                ws.reset();
                analyse(&b, &Operating::Load(load), &s, Some(&mut ws), Some(guess), false, &Silent).unwrap()
            })
            .0
        })
        .collect();
    let (cases, confirm) = (&costs[..10], costs[10]);
    let ms = |x: f64| x * 1e3;
    println!("workspace {:.2} ms, reference {:.2} ms, confirmation {:.2} ms; baseline and runs 1–9 (ms): {:?}", ms(alloc), ms(reference), ms(confirm), cases.iter().map(|c| (ms(*c) * 100.0).round() / 100.0).collect::<Vec<_>>());
    let total: f64 = cases.iter().sum();
    let (a0, a1): (f64, f64) = (cases.iter().step_by(2).sum(), cases.iter().skip(1).step_by(2).sum());
    let old = reference + a0.max(alloc + a1) + confirm;
    // shared counter in index order, the first worker to be free takes the next case; `start`:
    // when both workers start (the reference and the allocations during it)
    let schedule = |start: f64| {
        let mut free = [start, start];
        let mut last_of = [0usize; 2];
        for (i, c) in cases.iter().enumerate() {
            let w = if free[0] <= free[1] { 0 } else { 1 };
            free[w] += c;
            last_of[w] = i;
        }
        let idle = if free[0] <= free[1] { 0 } else { 1 };
        let busy = free[1 - idle];
        (busy.max(free[idle] + confirm), busy + confirm, last_of[1 - idle])
    };
    // before this round: the full-grid reference, the other worker's workspace allocated during it
    let (hit_full, miss_full, _) = schedule(reference_full.max(alloc));
    let (hit, miss, last) = schedule(reference.max(2.0 * alloc));
    println!(
        "full-grid reference (round 9–12 schedule): {:.1} ms when the prediction holds, {:.1} ms when not; mirrored half: {:.1} ms ({:+.1} %), {:.1} ms ({:+.1} %)",
        ms(hit_full), ms(miss_full), ms(hit), (hit / hit_full - 1.0) * 100.0, ms(miss), (miss / miss_full - 1.0) * 100.0
    );
    // round 14: the runs from the shared counter, the baseline by the first worker without a
    // run, the confirmation by the worker that completes the array (no prediction needed)
    let round14 = {
        let start = reference.max(2.0 * alloc);
        let mut free = [start, start];
        let mut runs_end = start;
        for c in cases[1..].iter().chain(std::iter::once(&cases[0])) {
            let w = if free[0] <= free[1] { 0 } else { 1 };
            free[w] += c;
            if !std::ptr::eq(c, &cases[0]) {
                runs_end = runs_end.max(free[w]);
            }
        }
        let w = if free[0] <= free[1] { 0 } else { 1 };
        free[1 - w].max(free[w].max(runs_end) + confirm)
    };
    println!("round 14 (runs, then the baseline; the confirmation by the worker that completes the array): {:.1} ms ({:+.1} % against round 9–13 when the prediction holds, {:+.1} % when not)", ms(round14), (round14 / hit - 1.0) * 100.0, (round14 / miss - 1.0) * 100.0);
    println!(
        "modelled makespan on two idle cores: round 8 {:.1} ms; round 9 {:.1} ms when the prediction holds ({:+.1} %), {:.1} ms when not ({:+.1} %); the idle worker waits on case {} (0 = baseline); lower bound (reference + half the rest) {:.1} ms; one thread {:.1} ms",
        ms(old), ms(hit), (hit / old - 1.0) * 100.0, ms(miss), (miss / old - 1.0) * 100.0, last, ms(reference + 0.5 * (total + confirm)), ms(reference + total + confirm)
    );
}

/// Records every `check()` of a solve: (rayon worker, wall s since start, the thread's CPU s), and
/// the progress stages. `cargo bench --bench journal -- l9-timeline`: when each worker of the L9
/// pool worked, and how much CPU it got while it did.
struct Timeline {
    t0: Instant,
    events: std::sync::Mutex<Vec<(Option<usize>, f64, f64, String)>>,
}

impl tribod::physics::Observer for Timeline {
    fn progress(&self, _fraction: f64, stage: &str) {
        let e = (rayon::current_thread_index(), self.t0.elapsed().as_secs_f64(), thread_cpu(), stage.to_string());
        self.events.lock().unwrap().push(e);
    }
    fn check(&self) -> Result<(), tribod::physics::Interrupt> {
        let e = (rayon::current_thread_index(), self.t0.elapsed().as_secs_f64(), thread_cpu(), String::new());
        self.events.lock().unwrap().push(e);
        Ok(())
    }
}

fn l9_timeline() {
    let spec_json = serde_json::json!({
        "base": {
            "geometry": {"length_to_diameter": 1.25},
            "load": {"aligned_eccentricity_ratio": 0.6},
            "misalignment": {"vertical": 0.56, "horizontal": 0.56},
            "grid": {"circumferential": 361, "axial": 181}
        },
        "method": "taguchi_l9",
        "factors": {"order": [1, 2, 3], "height": [0.1, 0.4, 1.0], "length_fraction": [0.01, 0.2, 0.4]},
        "continuous": {"enabled": false}
    });
    let spec: OptimisationSpec = serde_json::from_value(spec_json).unwrap();
    let threads: usize = std::env::var("L9_THREADS").ok().and_then(|v| v.parse().ok()).unwrap_or(2);
    let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build().unwrap();
    for rep in 0..3 {
        let obs = Timeline { t0: Instant::now(), events: std::sync::Mutex::new(Vec::new()) };
        let c0 = process_cpu();
        let r = pool.install(|| BearingOptimisation::solve(&spec, &obs).unwrap());
        let wall = obs.t0.elapsed().as_secs_f64();
        let cpu = process_cpu() - c0;
        let ev = obs.events.into_inner().unwrap();
        println!("\nrun {rep}: {} analyses, {:.1} ms wall, {:.1} ms CPU (all threads)", r.evaluations, wall * 1e3, cpu * 1e3);
        // the results, to the last bit (equal for every pool size and run)
        let bits: Vec<u64> = r.runs.iter().flat_map(|x| [x.sn_ratio_db, x.eccentricity_ratio]).chain([r.best_levels.design.score, r.best_levels.design.eccentricity_ratio, r.baseline.eccentricity_ratio]).map(f64::to_bits).collect();
        let fold = bits.iter().fold(0u64, |h, b| h.rotate_left(5) ^ b);
        println!("  results: hash {fold:016x}; best levels {}/{}/{}, confirmation ε {:.15}", r.best_levels.order_level, r.best_levels.height_level, r.best_levels.length_fraction_level, r.best_levels.design.eccentricity_ratio);
        for e in ev.iter().filter(|e| !e.3.is_empty()) {
            println!("  stage '{}' at {:.1} ms on {:?}", e.3, e.1 * 1e3, e.0);
        }
        let mut ids: Vec<Option<usize>> = ev.iter().map(|e| e.0).collect();
        ids.sort();
        ids.dedup();
        for id in ids {
            let mine: Vec<&(Option<usize>, f64, f64, String)> = ev.iter().filter(|e| e.0 == id).collect();
            let (a, b) = (mine[0], mine[mine.len() - 1]);
            // gaps of more than 2 ms between successive checks of one thread
            let mut gaps = Vec::new();
            for w in mine.windows(2) {
                if w[1].1 - w[0].1 > 2e-3 {
                    gaps.push(format!("{:.0}-{:.0} ({:.0} cpu)", w[0].1 * 1e3, w[1].1 * 1e3, (w[1].2 - w[0].2) * 1e3));
                }
            }
            println!(
                "  thread {id:?}: {} checks, {:.1}–{:.1} ms wall, CPU over that span {:.1} ms; spans > 2 ms: {}",
                mine.len(), a.1 * 1e3, b.1 * 1e3, (b.2 - a.2) * 1e3, gaps.join(", ")
            );
        }
    }
}

fn main() {
    let quick = std::env::args().any(|a| a == "--quick");
    let reps = if quick { 2 } else { 5 };
    if std::env::args().any(|a| a == "prof-ref") {
        // the L9's reference (aligned, unprofiled, ε 0.6 at 361×181), `PROF_N` times on one
        // workspace reset before each (as the kind runs it): `HALF=0` on the full grid, else on
        // the mirrored half (`analyse_symmetric`, what the kind uses)
        let s = settings(361, 181);
        let b = Bearing::plain(1.25);
        let half = std::env::var("HALF").map_or(true, |v| v != "0");
        let n = std::env::var("PROF_N").ok().and_then(|v| v.parse().ok()).unwrap_or(100);
        let mut ws = Workspace::new(&b, &s);
        let (c, _, a) = best_of(1, || {
            let mut last = None;
            for _ in 0..n {
                ws.reset();
                let f = if half { analyse_symmetric } else { analyse };
                last = Some(f(&b, &Operating::Eccentricity(0.6), &s, Some(&mut ws), None, false, &Silent).unwrap());
            }
            last.unwrap()
        });
        println!(
            "prof-ref ({}): {:.3} ms CPU per analysis; W̄ {:.12}, β {:.12}, P0 {:.10}, friction {:.10}, flow {:.10}, side flow {:.10}, steps per grid {:?}",
            if half { "half" } else { "full" }, c * 1e3 / n as f64, a.load, a.attitude, a.max_pressure, a.friction_force, a.flow_variable, a.side_flow_variable, a.steps_per_grid
        );
        return;
    }
    if let Some(which) = std::env::args().find(|a| a.starts_with("prof-")) {
        // a loop for a sampling profiler (`perf record`): prof-ross or prof-mis
        let (b, w, mut s) = if which == "prof-ross" {
            let (ld, w) = ross_case();
            (Bearing::plain(ld), w, settings(121, 41))
        } else {
            (seed_case(), 0.557045, settings(361, 181))
        };
        // tolerance study (issue 18 candidate 2): `P_TOL` / `LOAD_TOL` override the defaults
        if let Some(t) = std::env::var("P_TOL").ok().and_then(|v| v.parse().ok()) {
            s.pressure_tolerance = t;
        }
        if let Some(t) = std::env::var("LOAD_TOL").ok().and_then(|v| v.parse().ok()) {
            s.load_tolerance = t;
        }
        let n = std::env::var("PROF_N").ok().and_then(|v| v.parse().ok()).unwrap_or(if which == "prof-ross" { 2000 } else { 100 });
        let (c, _, a) = best_of(1, || {
            let sweeps: usize = std::env::var("SWEEPS").ok().and_then(|v| v.parse().ok()).unwrap_or(2);
            let mut last = None;
            for _ in 0..n {
                let mut ws = Workspace::new(&b, &s);
                ws.set_smoothing_sweeps(sweeps);
                last = Some(analyse(&b, &Operating::Load(w), &s, Some(&mut ws), None, false, &Silent).unwrap());
            }
            last
        });
        println!("{which}: {:.3} ms CPU per analysis", c * 1e3 / n as f64);
        if let Some(a) = a {
            println!(
                "tolerances p {:.0e} load {:.0e}: ε {:.10}, β {:.10}, P0 {:.10}, H0 {:.10}, friction {:.10}, steps per grid {:?}",
                s.pressure_tolerance, s.load_tolerance, a.eccentricity, a.attitude, a.max_pressure, a.min_film, a.friction_force, a.steps_per_grid
            );
        }
        return;
    }
    if std::env::args().any(|a| a == "moments") {
        moments();
        return;
    }
    if std::env::args().any(|a| a == "l9-cases") {
        l9_cases();
        return;
    }
    if std::env::args().any(|a| a == "l9-schedule") {
        l9_schedule();
        return;
    }
    if std::env::args().any(|a| a == "l9-timeline") {
        l9_timeline();
        return;
    }
    if std::env::args().any(|a| a == "speed") {
        speed_section(reps);
        return;
    }
    if std::env::args().any(|a| a == "coefficients") {
        coefficients_section(reps);
        return;
    }
    let plain = Bearing::plain(1.25);
    // the load every case carries: aligned ε = 0.6 on the finest grid of the study
    let grids: &[(usize, usize)] = &[(31, 16), (61, 31), (91, 46), (121, 61), (181, 91), (241, 121), (361, 181), (721, 361), (1441, 721)];
    let (fnt, fnz) = grids[grids.len() - 1];
    let reference = analyse(&plain, &Operating::Eccentricity(0.6), &settings(fnt, fnz), None, None, false, &Silent).unwrap();
    let w = reference.load;
    // the target case: one thread, 361×181
    println!("\n## Load-balanced misaligned profiled case at 361×181 (one thread)\n");
    let s = settings(361, 181);
    let (c, wl, m) = best_of(if quick { 3 } else { 10 }, || analyse(&seed_case(), &Operating::Load(w), &s, None, None, false, &Silent).unwrap());
    let mut ws = Workspace::new(&seed_case(), &s);
    analyse(&seed_case(), &Operating::Load(w), &s, Some(&mut ws), None, false, &Silent).unwrap();
    println!("best of {}: {:.1} ms CPU ({:.1} ms wall); load residual {:.1e} after {} steps on 361×181; grids (nt, nz, steps) {:?}; V-cycles per level (finest first) {:?}",
        if quick { 3 } else { 10 }, c * 1e3, wl * 1e3, m.convergence.residual, m.convergence.iterations, m.steps_per_grid, ws.cycles());
    // with a warm workspace and start (a nearby design, as in the optimisation)
    let mut near = seed_case();
    near.profile = Some(Profile { order: 2, height: 0.42, length_fraction: 0.21 });
    let g = Guess { eccentricity: m.eccentricity, attitude: m.attitude };
    let (c2, w2, _) = best_of(if quick { 3 } else { 10 }, || analyse(&near, &Operating::Load(w), &s, Some(&mut ws), Some(g), false, &Silent).unwrap());
    println!("nearby design, warm workspace and start: {:.1} ms CPU ({:.1} ms wall)", c2 * 1e3, w2 * 1e3);

    // the full L9 on two cores through the job kind (array only, and with the continuous search)
    println!("\n## Taguchi L9 at 361×181 on 2 cores (job kind `bearing_optimisation`)\n");
    let spec_json = serde_json::json!({
        "base": {
            "geometry": {"length_to_diameter": 1.25},
            "load": {"aligned_eccentricity_ratio": 0.6},
            "misalignment": {"vertical": 0.56, "horizontal": 0.56},
            "grid": {"circumferential": 361, "axial": 181}
        },
        "method": "taguchi_l9",
        "factors": {"order": [1, 2, 3], "height": [0.1, 0.4, 1.0], "length_fraction": [0.01, 0.2, 0.4]},
        "continuous": {"enabled": false}
    });
    let spec: OptimisationSpec = serde_json::from_value(spec_json.clone()).unwrap();
    let pool = rayon::ThreadPoolBuilder::new().num_threads(2).build().unwrap();
    let n = if quick { 2 } else { 5 };
    let (mut wall, mut cpu) = (f64::INFINITY, f64::INFINITY);
    let mut r = None;
    for _ in 0..n {
        let (c, t) = (process_cpu(), Instant::now());
        r = Some(pool.install(|| BearingOptimisation::solve(&spec, &Silent).unwrap()));
        wall = wall.min(t.elapsed().as_secs_f64());
        cpu = cpu.min(process_cpu() - c);
    }
    let r = r.unwrap();
    println!("L9 array (reference load + baseline + 9 runs, {} analyses): {:.0} ms wall, {:.0} ms CPU over both threads (best of {n}); best run {}, best levels n/ξ/ψ = {}/{}/{}",
        r.evaluations, wall * 1e3, cpu * 1e3, r.best_run, r.best_levels.order_level, r.best_levels.height_level, r.best_levels.length_fraction_level);
    let mut full = spec_json;
    full["continuous"] = serde_json::json!({"enabled": true});
    let spec: OptimisationSpec = serde_json::from_value(full).unwrap();
    let (_, wall, r) = best_of(1, || pool.install(|| BearingOptimisation::solve(&spec, &Silent).unwrap()));
    let c = r.continuous.as_ref().unwrap();
    println!("L9 + continuous search ({} analyses): {:.2} s wall; continuous optimum n = {}, ξ = {:.4}, ψ = {:.4}, score {:.4} (best Taguchi run {:.4})",
        r.evaluations, wall, c.design.order, c.design.height, c.design.length_fraction, c.design.score, r.runs[r.best_run - 1].score);
    println!("## Run time against error (L/D = 1.25)\n");
    println!("Aligned bearing at ε = 0.6 (fixed eccentricity, attitude from the force balance) and seed 002's");
    println!("optimised design (n = 2, ξ = 0.4, ψ = 0.2) under Δv0 = Δh0 = 0.56, load-balanced to the aligned load");
    println!("W̄ = {w:.6} (ε = 0.6 on {fnt}×{fnz}). Errors against Richardson extrapolation (order 2) of the two finest grids.\n");
    let mut rows = Vec::new();
    for &(nt, nz) in grids {
        let s = settings(nt, nz);
        let r = if nt * nz > 300_000 { 1 } else { reps };
        let (ca, wa, a) = best_of(r, || analyse(&plain, &Operating::Eccentricity(0.6), &s, None, None, false, &Silent).unwrap());
        let (cm, wm, m) = best_of(r, || analyse(&seed_case(), &Operating::Load(w), &s, None, None, false, &Silent).unwrap());
        rows.push((nt, nz, ca, wa, a, cm, wm, m));
    }
    let n = rows.len();
    let ext = |f: &dyn Fn(usize) -> f64| richardson(f(n - 2), f(n - 1), 2.0);
    let w_ref = ext(&|i| rows[i].4.load);
    let p_ref = ext(&|i| rows[i].4.max_pressure);
    let pm_ref = ext(&|i| rows[i].7.max_pressure);
    let hm_ref = ext(&|i| rows[i].7.min_film);
    let fm_ref = ext(&|i| rows[i].7.friction_variable.unwrap());
    println!("| grid | nodes | aligned: CPU ms (wall) | load err | P0 err | balanced misaligned profiled: CPU ms (wall) | P0 err | H0 err | (R/c)f err |");
    println!("| --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: |");
    for (nt, nz, ca, wa, a, cm, wm, m) in &rows {
        println!(
            "| {nt}×{nz} | {} | {:.2} ({:.2}) | {:.1e} | {:.1e} | {:.2} ({:.2}) | {:.1e} | {:.1e} | {:.1e} |",
            nt * nz,
            ca * 1e3,
            wa * 1e3,
            (a.load / w_ref - 1.0).abs(),
            (a.max_pressure / p_ref - 1.0).abs(),
            cm * 1e3,
            wm * 1e3,
            (m.max_pressure / pm_ref - 1.0).abs(),
            (m.min_film / hm_ref - 1.0).abs(),
            (m.friction_variable.unwrap() / fm_ref - 1.0).abs(),
        );
    }
    println!("\nExtrapolated: aligned W̄ = {w_ref:.6}, P0 = {p_ref:.6}; misaligned profiled P0 = {pm_ref:.6}, H0 = {hm_ref:.6}, (R/c)f = {fm_ref:.6}.");

}
