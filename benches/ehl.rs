//! Run time against error of the numerical line-contact EHL solver (`physics::ehl`).
//!
//! `cargo bench --bench ehl` prints two markdown tables (or one: `-- point`, `-- cycle`):
//! 1. one contact point (seed 001 nose) at 64…4096 nodes, errors of the central and minimum film
//!    against the Richardson extrapolation of the two finest grids;
//! 2. a 720-step transient cam-like cycle (load and radius varying, entrainment reversing twice,
//!    squeeze) by `solve()` per angle and by `TransientSolver` with and without Richardson
//!    extrapolation, errors against the same cycle extrapolated from 512 and 1023 nodes.
//!
//! Also: `-- run=rich:193`
//! (modes `solve`, `ts`, `rich`; optional `@TOL`) times one cycle.
//! Times are the best of several repetitions; the solver's own linear algebra is single-threaded
//! (`faer::Par::Seq`), Richardson runs its two grids on two rayon threads.

use std::time::Instant;
use tribod::physics::ehl::{solve, EhlInput, EhlOptions, EhlState, Extrapolation, Rheology, Transient, TransientSolver};
use tribod::physics::lubricant::Lubricant;
use tribod::physics::Silent;

const E_PRIME: f64 = 2.0 / (2.0 * 0.91 / 200e9);

fn lub() -> Lubricant {
    Lubricant { viscosity: 0.013, pressure_viscosity: 1.84e-8, ..Lubricant::SEED000 }
}

fn point(w: f64, r: f64, u: f64) -> EhlInput<'static> {
    EhlInput {
        load_per_length: w,
        reduced_radius: r,
        effective_modulus: E_PRIME,
        entrainment_velocity: u,
        sliding_velocity: 0.01 * u,
        lubricant: lub(),
        temperature: lub().reference_temperature,
        rheology: Rheology { eyring_stress: Some(5e6), ..Rheology::default() },
        transient: None,
        warm_start: None,
        asperity: None,
    }
}

fn best_of<T>(reps: usize, mut f: impl FnMut() -> T) -> (f64, T) {
    let mut best = f64::INFINITY;
    let mut out = None;
    for _ in 0..reps {
        let t = Instant::now();
        let v = f();
        best = best.min(t.elapsed().as_secs_f64());
        out = Some(v);
    }
    (best, out.unwrap())
}

/// The benchmark cam-like cycle at angle index `k` of `steps` (one revolution at 950 rpm):
/// load 2.25–12.5 kN over 21 mm, radius 15.2–10.5 mm, entrainment `u_m = 4 cos θ + 1.5` m/s
/// (reverses twice per cycle), slide 1 %, oil η0 = 0.013 Pa·s, α = 1.84e-8 1/Pa (Roelands,
/// Dowson–Higginson), steel.
fn cycle_input(k: usize, steps: usize) -> EhlInput<'static> {
    let th = 2.0 * std::f64::consts::PI * k as f64 / steps as f64;
    let f = 2250.0 + (12500.0 - 2250.0) * (0.5 - 0.5 * th.cos()).powi(2);
    let r = 0.0152 - 0.0047 * (0.5 - 0.5 * th.cos());
    let u = 4.0 * th.cos() + 1.5;
    point(f / 0.021, r, u)
}

const STEPS: usize = 720;

fn time_step() -> f64 {
    60.0 / 950.0 / STEPS as f64
}

/// Central and minimum film at every angle, and a note on the work done.
struct CycleRun {
    hc: Vec<f64>,
    hm: Vec<f64>,
    newton_per_step: f64,
    factorisations: u64,
    gmres_per_newton: f64,
    layouts: u64,
}

/// The cycle with `solve()` at every angle (the phase-1 path: grid, influence matrix and
/// factorisation built afresh at each angle), warm-started from the previous state.
fn cycle_solve(nodes: usize, tol: f64) -> CycleRun {
    let mut state: Option<EhlState> = None;
    let (mut hc, mut hm) = (Vec::with_capacity(STEPS), Vec::with_capacity(STEPS));
    let mut iters = 0;
    let opts = EhlOptions { nodes, tolerance: tol, ..EhlOptions::default() };
    for k in 0..STEPS {
        let mut inp = cycle_input(k, STEPS);
        if let Some(s) = &state {
            inp.transient = Some(Transient { previous: s, time_step: time_step() });
        }
        let s = solve(&inp, &opts, &Silent).unwrap_or_else(|e| panic!("step {k}: {e}"));
        iters += s.convergence.iterations;
        hc.push(s.central_film);
        hm.push(s.min_film);
        state = Some(s.state);
    }
    CycleRun { hc, hm, newton_per_step: iters as f64 / STEPS as f64, factorisations: 0, gmres_per_newton: 0.0, layouts: STEPS as u64 }
}

/// The cycle through `TransientSolver` (kept grid, factors and workspace; optionally Richardson
/// extrapolation of two grids on two threads).
fn cycle_ts(nodes: usize, tol: f64, ex: Extrapolation) -> CycleRun {
    let opts = EhlOptions { nodes, tolerance: tol, ..EhlOptions::default() };
    let mut ts = TransientSolver::new(opts, ex);
    let (mut hc, mut hm) = (Vec::with_capacity(STEPS), Vec::with_capacity(STEPS));
    for k in 0..STEPS {
        let s = ts.step(&cycle_input(k, STEPS), Some(time_step()), &Silent).unwrap_or_else(|e| panic!("step {k}: {e}"));
        hc.push(s.central_film);
        hm.push(s.min_film);
    }
    let st = ts.stats();
    let layouts = st.layouts;
    CycleRun {
        hc,
        hm,
        newton_per_step: st.newton_steps as f64 / STEPS as f64,
        factorisations: st.factorisations,
        gmres_per_newton: st.gmres_iterations as f64 / st.newton_steps.max(1) as f64,
        layouts,
    }
}

/// Worst relative error over the angles (and its angle index), and the error of the cycle's
/// smallest value.
fn errors(x: &[f64], reference: &[f64]) -> (f64, usize, f64) {
    let (mut worst, mut at) = (0.0, 0);
    for (k, (a, b)) in x.iter().zip(reference).enumerate() {
        let e = (a / b - 1.0).abs();
        if e > worst {
            (worst, at) = (e, k);
        }
    }
    let min = |v: &[f64]| v.iter().cloned().fold(f64::INFINITY, f64::min);
    (worst, at, min(x) / min(reference) - 1.0)
}

fn main() {
    faer::set_global_parallelism(faer::Par::Seq);
    // `cargo bench --bench ehl -- point` or `-- cycle` runs one table only; `-- run=rich:193`
    // (or `ts:192`, `solve:128`, optionally `@1e-8`) times one cycle.
    let args: Vec<String> = std::env::args().skip(1).filter(|a| !a.starts_with('-')).collect();
    let want = |name: &str| args.is_empty() || args.iter().any(|a| a == name);
    if want("point") {
        point_table();
    }
    if want("cycle") {
        cycle_table();
    }
    for a in args.iter().filter_map(|a| a.strip_prefix("run=")) {
        let (spec, tol) = a.split_once('@').unwrap_or((a, "1e-6"));
        let (mode, n) = spec.split_once(':').expect("run=MODE:NODES");
        let (n, tol): (usize, f64) = (n.parse().unwrap(), tol.parse().unwrap());
        let t = Instant::now();
        let r = match mode {
            "solve" => cycle_solve(n, tol),
            "ts" => cycle_ts(n, tol, Extrapolation::None),
            "rich" => cycle_ts(n, tol, Extrapolation::Richardson),
            _ => panic!("mode solve | ts | rich"),
        };
        println!(
            "{a}: {:.3} s, {:.2} Newton/step, {} LU, {:.1} GMRES/Newton, {} layouts",
            t.elapsed().as_secs_f64(),
            r.newton_per_step,
            r.factorisations,
            r.gmres_per_newton,
            r.layouts
        );
    }
}

fn point_table() {
    let grids = [64, 128, 256, 512, 1024, 2048, 4096];
    let inp = point(12500.0 / 0.021, 0.0105, 3.98);
    let mut rows = Vec::new();
    for &n in &grids {
        let reps = if n <= 512 { 5 } else if n <= 1024 { 3 } else { 1 };
        let opts = EhlOptions { nodes: n, ..EhlOptions::default() };
        let (t, s) = best_of(reps, || solve(&inp, &opts, &Silent).unwrap());
        rows.push((n, t, s));
    }
    let k = rows.len();
    let rich = |f: &dyn Fn(&tribod::physics::ehl::EhlSolution) -> f64| {
        let (a, b) = (f(&rows[k - 2].2), f(&rows[k - 1].2));
        b + (b - a) / 3.0
    };
    let hc_ref = rich(&|s| s.central_film);
    let hm_ref = rich(&|s| s.min_film);
    println!("### One contact point: seed 001 nose (M = {:.1}, L = {:.1}, p_h = {:.2} GPa)\n", rows[0].2.moes_m, rows[0].2.moes_l, rows[0].2.hertz_pressure / 1e9);
    println!("reference: Richardson extrapolation of 2048/4096 nodes, h_c = {:.5} µm, h_min = {:.5} µm\n", hc_ref * 1e6, hm_ref * 1e6);
    println!("| nodes | time (ms) | Newton steps | h_c (µm) | error h_c | h_min (µm) | error h_min | p_max/p_h | residual |");
    println!("| ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: |");
    for (n, t, s) in &rows {
        println!(
            "| {n} | {:.2} | {} | {:.5} | {:+.2} % | {:.5} | {:+.2} % | {:.3} | {:.1e} |",
            t * 1e3,
            s.convergence.iterations,
            s.central_film * 1e6,
            100.0 * (s.central_film / hc_ref - 1.0),
            s.min_film * 1e6,
            100.0 * (s.min_film / hm_ref - 1.0),
            s.max_pressure / s.hertz_pressure,
            s.convergence.residual
        );
    }
    // `ehl_point`'s defaults (issue 16 item 6): Richardson of 385 and 193 nodes on one layout,
    // two threads, against one 512-node grid.
    for fine in [257, 385, 513] {
        let opts = EhlOptions { nodes: fine, ..EhlOptions::default() };
        let (t, r) = best_of(5, || tribod::physics::ehl::ReusableSolver::new().solve_richardson(&inp, None, &opts, &Silent).unwrap());
        let s = r.solution;
        println!(
            "| Richardson {fine}/{} | {:.2} | {} | {:.5} | {:+.2} % | {:.5} | {:+.2} % | {:.3} | {:.1e} |",
            (fine - 1) / 2 + 1,
            t * 1e3,
            s.convergence.iterations,
            s.central_film * 1e6,
            100.0 * (s.central_film / hc_ref - 1.0),
            s.min_film * 1e6,
            100.0 * (s.min_film / hm_ref - 1.0),
            s.max_pressure / s.hertz_pressure,
            s.convergence.residual
        );
    }
}

fn cycle_table() {
    println!("\n### Transient cycle: 720 steps (950 rpm, load 2.25–12.5 kN, u_m = 4 cos θ + 1.5 m/s, squeeze)\n");
    let t = Instant::now();
    let reference = cycle_ts(1023, 1e-8, Extrapolation::Richardson);
    println!(
        "reference: the same cycle (same time steps) by TransientSolver, Richardson extrapolation of 512 and 1023 nodes, tolerance 1e-8 ({:.0} s)\n",
        t.elapsed().as_secs_f64()
    );
    println!("| method | nodes | time (s) | ms/step | Newton steps/step | LU | GMRES it/Newton | max error h_c (angle) | max error h_min (angle) | error of the cycle's min h_min |");
    println!("| --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: |");
    let rows: [(&str, usize, Extrapolation, bool); 9] = [
        ("solve() per angle", 192, Extrapolation::None, true),
        ("TransientSolver", 128, Extrapolation::None, false),
        ("TransientSolver", 192, Extrapolation::None, false),
        ("TransientSolver", 256, Extrapolation::None, false),
        ("TransientSolver", 384, Extrapolation::None, false),
        ("TransientSolver + Richardson", 129, Extrapolation::Richardson, false),
        ("TransientSolver + Richardson", 161, Extrapolation::Richardson, false),
        ("TransientSolver + Richardson", 193, Extrapolation::Richardson, false),
        ("TransientSolver + Richardson", 257, Extrapolation::Richardson, false),
    ];
    for (name, n, ex, per_angle) in rows {
        let (t, r) = best_of(5, || if per_angle { cycle_solve(n, 1e-6) } else { cycle_ts(n, 1e-6, ex) });
        let (ec, kc, _) = errors(&r.hc, &reference.hc);
        let (em, km, emin) = errors(&r.hm, &reference.hm);
        let nodes = if ex == Extrapolation::Richardson { format!("{} + {n}", (n - 1) / 2 + 1) } else { n.to_string() };
        let lu = if per_angle { "every step".to_string() } else { r.factorisations.to_string() };
        let gm = if per_angle { "–".to_string() } else { format!("{:.1}", r.gmres_per_newton) };
        println!(
            "| {name} | {nodes} | {t:.3} | {:.2} | {:.2} | {lu} | {gm} | {:.2} % ({kc}) | {:.2} % ({km}) | {:+.2} % |",
            t * 1e3 / STEPS as f64,
            r.newton_per_step,
            100.0 * ec,
            100.0 * em,
            100.0 * emin
        );
    }
}
