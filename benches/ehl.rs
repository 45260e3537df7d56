//! Run time against error of the numerical line-contact EHL solver (`physics::ehl`).
//!
//! `cargo bench --bench ehl` prints two markdown tables:
//! 1. one contact point (seed 001 nose) at 64…4096 nodes, errors of the central and minimum film
//!    against the Richardson extrapolation of the two finest grids;
//! 2. a 720-step transient cam-like cycle (sinusoidal load, entrainment reversing twice, squeeze)
//!    at several grids, errors against the same cycle on 1024 nodes.
//! Times are the best of several repetitions (single thread for the solver's own work).

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

/// Cam-like cycle: 720 steps over one revolution at 950 rpm; load 2.25–12.5 kN over 21 mm,
/// radius 10.5–15.2 mm, entrainment `u_m = 4 cos θ + 1.5` m/s (reverses twice per cycle).
fn cycle(nodes: usize, tol: f64) -> (Vec<f64>, Vec<f64>, u32) {
    let steps = 720;
    let dt = 60.0 / 950.0 / steps as f64;
    let mut state: Option<EhlState> = None;
    let (mut hc, mut hm) = (Vec::with_capacity(steps), Vec::with_capacity(steps));
    let mut iters = 0;
    for k in 0..steps {
        let th = 2.0 * std::f64::consts::PI * k as f64 / steps as f64;
        let f = 2250.0 + (12500.0 - 2250.0) * (0.5 - 0.5 * th.cos()).powi(2);
        let r = 0.0152 - 0.0047 * (0.5 - 0.5 * th.cos());
        let u = 4.0 * th.cos() + 1.5;
        let mut inp = point(f / 0.021, r, u);
        if let Some(s) = &state {
            inp.transient = Some(Transient { previous: s, time_step: dt });
        }
        let opts = EhlOptions { nodes, tolerance: tol, ..EhlOptions::default() };
        let s = solve(&inp, &opts, &Silent).unwrap_or_else(|e| panic!("step {k}: {e}"));
        iters += s.convergence.iterations;
        hc.push(s.central_film);
        hm.push(s.min_film);
        state = Some(s.state);
    }
    (hc, hm, iters)
}

/// The same cycle through `TransientSolver` (kept grid, factors and workspace; optionally
/// Richardson extrapolation of two grids on two threads).
fn cycle_ts(nodes: usize, tol: f64, ex: Extrapolation) -> (Vec<f64>, Vec<f64>, String) {
    let steps = 720;
    let dt = 60.0 / 950.0 / steps as f64;
    let opts = EhlOptions { nodes, tolerance: tol, ..EhlOptions::default() };
    let mut ts = TransientSolver::new(opts, ex);
    let (mut hc, mut hm) = (Vec::with_capacity(steps), Vec::with_capacity(steps));
    for k in 0..steps {
        let th = 2.0 * std::f64::consts::PI * k as f64 / steps as f64;
        let f = 2250.0 + (12500.0 - 2250.0) * (0.5 - 0.5 * th.cos()).powi(2);
        let r = 0.0152 - 0.0047 * (0.5 - 0.5 * th.cos());
        let u = 4.0 * th.cos() + 1.5;
        let inp = point(f / 0.021, r, u);
        let s = ts.step(&inp, Some(dt), &Silent).unwrap_or_else(|e| panic!("step {k}: {e}"));
        hc.push(s.central_film);
        hm.push(s.min_film);
    }
    let (st, lc) = ts.stats();
    let info = format!(
        "{:.2} Newton/step, {} LU, {:.1} GMRES it/Newton, {lc} layouts",
        st.newton_steps as f64 / steps as f64,
        st.factorisations,
        st.gmres_iterations as f64 / st.newton_steps.max(1) as f64
    );
    (hc, hm, info)
}

fn main() {
    faer::set_global_parallelism(faer::Par::Seq);
    // `cargo bench --bench ehl -- point` or `-- cycle` runs one table only.
    let args: Vec<String> = std::env::args().skip(1).filter(|a| !a.starts_with('-')).collect();
    let want = |name: &str| args.is_empty() || args.iter().any(|a| a == name);
    if want("point") {
        point_table();
    }
    if want("cycle") {
        cycle_table();
    }
    if let Some(n) = args.iter().find_map(|a| a.strip_prefix("once=")) {
        let n: usize = n.parse().unwrap();
        let t = Instant::now();
        let (_, _, it) = cycle(n, 1e-6);
        println!("cycle {n}: {:.3} s, {it} Newton steps", t.elapsed().as_secs_f64());
    }
    for (key, ex) in [("ts=", Extrapolation::None), ("rich=", Extrapolation::Richardson)] {
        if let Some(n) = args.iter().find_map(|a| a.strip_prefix(key)) {
            let n: usize = n.parse().unwrap();
            let t = Instant::now();
            let (hc, hm, info) = cycle_ts(n, 1e-6, ex);
            println!("{key}{n}: {:.3} s, {info}", t.elapsed().as_secs_f64());
            let mut out = String::new();
            for k in 0..hc.len() {
                out += &format!("{k} {:.9e} {:.9e}\n", hc[k], hm[k]);
            }
            std::fs::write(format!("/tmp/ehl2_{}{n}.txt", key.trim_end_matches('=')), out).unwrap();
        }
    }
    if let Some(n) = args.iter().find_map(|a| a.strip_prefix("dump=")) {
        let n: usize = n.parse().unwrap();
        let (hc, hm, _) = cycle(n, 1e-8);
        let mut out = String::new();
        for k in 0..hc.len() {
            out += &format!("{k} {:.9e} {:.9e}\n", hc[k], hm[k]);
        }
        std::fs::write(format!("/tmp/ehl2_cycle_{n}.txt"), out).unwrap();
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

}

fn cycle_table() {
    println!("\n### Transient cycle: 720 steps (950 rpm, load 2.25–12.5 kN, u_m = 4 cos θ + 1.5 m/s, squeeze)\n");
    let (_, (hc_ref, hm_ref, _)) = best_of(1, || cycle(1024, 1e-8));
    println!("reference: the same cycle on 1024 nodes, tolerance 1e-8\n");
    println!("| nodes | tolerance | time (s) | ms/step | Newton steps/step | max error h_c | max error h_min |");
    println!("| ---: | ---: | ---: | ---: | ---: | ---: | ---: |");
    for (n, tol) in [(64, 1e-6), (96, 1e-6), (128, 1e-6), (192, 1e-6), (256, 1e-6), (512, 1e-8)] {
        let (t, (hc, hm, iters)) = best_of(3, || cycle(n, tol));
        let err = |a: &[f64], b: &[f64]| a.iter().zip(b).map(|(x, y)| (x / y - 1.0).abs()).fold(0.0, f64::max);
        println!(
            "| {n} | {tol:.0e} | {t:.3} | {:.2} | {:.1} | {:.2} % | {:.2} % |",
            t * 1e3 / 720.0,
            iters as f64 / 720.0,
            100.0 * err(&hc, &hc_ref),
            100.0 * err(&hm, &hm_ref)
        );
    }
}
