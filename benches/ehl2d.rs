//! Run time against error of the 2-D (point / finite line) EHL solver (`physics::ehl::twod`).
//!
//! `cargo bench --bench ehl2d` prints a markdown table: one circular point contact (F = 100 N,
//! R = 10 mm, u_m = 1 m/s, η0 = 0.04 Pa·s, α = 2e-8 1/Pa, Roelands + Dowson–Higginson; M ≈ 60,
//! L ≈ 11) on square grids 33² … 257² (`-- 513` adds 513²), errors of the central and minimum film
//! against the Richardson extrapolation (second order) of the two finest grids. Then the seed 000
//! crowned roller at the cam nose (`-- roller`). Times are the best of a few repetitions, one
//! thread for the solver's own work (faer's sparse LU may use the rayon pool).

use std::time::Instant;
use tribod::physics::ehl::twod::{solve, Ehl2dInput, Ehl2dOptions, Geometry2d};
use tribod::physics::lubricant::Lubricant;
use tribod::physics::roller::Crown;
use tribod::physics::Silent;

const E_PRIME: f64 = 210e9 / 0.91;

fn best_of<T>(reps: usize, mut f: impl FnMut() -> T) -> (f64, T) {
    let mut best = f64::INFINITY;
    let mut out = None;
    for _ in 0..reps {
        let t = Instant::now();
        let v = f();
        best = best.min(t.elapsed().as_secs_f64());
        out = Some(v);
    }
    (best, out.expect("at least one repetition"))
}

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let with_513 = args.iter().any(|a| a == "513");
    let roller_only = args.iter().any(|a| a == "roller");
    if args.iter().any(|a| a == "probe") {
        // Truncation error of coarser grids against the solution on `fine=N` (default 257).
        let fine = args.iter().find_map(|a| a.strip_prefix("fine=")).and_then(|v| v.parse().ok()).unwrap_or(257);
        let lub = Lubricant { viscosity: 0.04, pressure_viscosity: 2e-8, ..Lubricant::SEED000 };
        let input = Ehl2dInput { load: 100.0, geometry: Geometry2d::Point { rx: 0.01, ry: 0.01 }, effective_modulus: E_PRIME, entrainment_velocity: 1.0, lubricant: lub, temperature: 313.0 };
        let o = Ehl2dOptions { nx: fine, ny: fine, inlet: Some(3.5), outlet: Some(1.5), side: Some(2.0), ..Default::default() };
        let strides: Vec<usize> = [2, 4, 8].into_iter().filter(|s| (fine - 1) / s >= 16).collect();
        if let Err(e) = tribod::physics::ehl::twod::solver::truncation_probe(&input, &o, &strides) {
            println!("probe failed: {e}");
        }
        return;
    }
    if !roller_only {
        let lub = Lubricant { viscosity: 0.04, pressure_viscosity: 2e-8, ..Lubricant::SEED000 };
        let input = Ehl2dInput { load: 100.0, geometry: Geometry2d::Point { rx: 0.01, ry: 0.01 }, effective_modulus: E_PRIME, entrainment_velocity: 1.0, lubricant: lub, temperature: 313.0 };
        let mut sizes = vec![33, 65, 129, 257];
        if with_513 {
            sizes.push(513);
        }
        let mut rows = Vec::new();
        for &n in &sizes {
            let o = Ehl2dOptions { nx: n, ny: n, inlet: Some(3.5), outlet: Some(1.5), side: Some(2.0), ..Default::default() };
            let reps = if n <= 65 { 3 } else { 1 };
            let (t, s) = best_of(reps, || solve(&input, &o, &Silent));
            match s {
                Ok(s) => {
                    eprintln!("{n}: {t:.3} s, hc {:.6e}, hmin {:.6e}, newton {}", s.central_film, s.min_film.value, s.convergence.iterations);
                    rows.push((n, t, s.central_film, s.min_film.value, s.convergence.iterations));
                }
                Err(e) => println!("{n}×{n}: not converged after {t:.3} s: {e}"),
            }
        }
        let k = rows.len();
        if k < 2 {
            println!("fewer than two converged grids: no Richardson reference");
            return;
        }
        let rich = |a: f64, b: f64| b + (b - a) / 3.0;
        let (rc, rm) = (rich(rows[k - 2].2, rows[k - 1].2), rich(rows[k - 2].3, rows[k - 1].3));
        println!("| grid | time (s) | Newton steps | h_c (nm) | error h_c | h_min (nm) | error h_min |");
        println!("| --- | --- | --- | --- | --- | --- | --- |");
        for (n, t, hc, hm, it) in &rows {
            println!("| {n}×{n} | {t:.3} | {it} | {:.2} | {:.2} % | {:.2} | {:.2} % |", hc * 1e9, 100.0 * (hc / rc - 1.0), hm * 1e9, 100.0 * (hm / rm - 1.0));
        }
        println!("Richardson reference: h_c = {:.3} nm, h_min = {:.3} nm", rc * 1e9, rm * 1e9);
    }
    // Seed 000 roller at the nose (tests/it/ehl_2d.rs: seed000_nose).
    let crown = Crown { length: 0.014, middle_length: 0.012, crown_height: 4.5e-6, end_radius: 0.0125 };
    let input = Ehl2dInput { load: 954.0, geometry: Geometry2d::Finite { rx: 0.01037, crown }, effective_modulus: 2.1e11, entrainment_velocity: 2.77, lubricant: Lubricant::SEED000, temperature: 313.0 };
    println!();
    println!("| roller grid | time (s) | h_c (µm) | h_min (µm) at y (mm) | p_max (GPa) | edge peak (GPa at y mm) |");
    println!("| --- | --- | --- | --- | --- | --- |");
    for (nx, ny) in [(33, 65), (65, 129), (129, 257)] {
        let o = Ehl2dOptions { nx, ny, ..Default::default() };
        let (t, s) = best_of(1, || solve(&input, &o, &Silent));
        let Ok(s) = s else {
            println!("| {nx}×{ny} | {t:.3} | not converged | | | |");
            continue;
        };
        let edge = s.edge_pressure_peak.map_or("none".to_string(), |e| format!("{:.3} at {:.2}", e.value * 1e-9, e.y * 1e3));
        println!("| {nx}×{ny} | {t:.3} | {:.4} | {:.4} at {:.2} | {:.3} | {edge} |", s.central_film * 1e6, s.min_film.value * 1e6, s.min_film.y * 1e3, s.max_pressure.value * 1e-9);
    }
}
