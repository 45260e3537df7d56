//! Run time against error of the thermal line-contact EHL model (`physics::ehl::thermal`).
//!
//! `cargo bench --bench thermal` prints a markdown table: one contact (seed 000 base-circle-like:
//! w' = 5e4 N/m, R = 14 mm, u_m = 3 m/s, slide-to-roll ratio 0.3) at x nodes × film levels from
//! 96 × 5 to 512 × 9, errors of the central film, the largest temperature rise and the friction
//! coefficient against 512 × 11, the coupling iterations and the best of three run times.

use std::time::Instant;
use tribod::physics::ehl::thermal::{self, ThermalBodies, ThermalInput, ThermalOptions};
use tribod::physics::ehl::{EhlInput, EhlOptions, Rheology};
use tribod::physics::lubricant::Lubricant;
use tribod::physics::Silent;

fn main() {
    faer::set_global_parallelism(faer::Par::Seq);
    let lub = Lubricant::SEED000;
    let ehl = EhlInput {
        load_per_length: 5e4,
        reduced_radius: 0.014,
        effective_modulus: 210e9 / 0.91,
        entrainment_velocity: 3.0,
        sliding_velocity: 0.9,
        lubricant: lub,
        temperature: lub.reference_temperature,
        rheology: Rheology::default(),
        transient: None,
        warm_start: None,
        asperity: None,
    };
    let run = |nodes: usize, nz: usize| {
        let input = ThermalInput { ehl, bodies: ThermalBodies::SEED000, previous_temperature: None };
        let options = EhlOptions { nodes, ..Default::default() };
        let topts = ThermalOptions { film_points: nz, ..Default::default() };
        let mut best = f64::INFINITY;
        let mut out = None;
        for _ in 0..3 {
            let t = Instant::now();
            let s = thermal::solve(&input, &options, &topts, &Silent).expect("thermal solve");
            best = best.min(t.elapsed().as_secs_f64());
            out = Some(s);
        }
        (out.unwrap(), best)
    };
    let (reference, _) = run(512, 11);
    let t0 = lub.reference_temperature;
    let rel = |a: f64, b: f64| (a - b).abs() / b.abs();
    println!("| x nodes × film levels | central film error | ΔT_max error | μ error | coupling iterations | time, ms |");
    println!("|---|---|---|---|---|---|");
    for &(n, nz) in &[(96, 5), (128, 5), (128, 7), (192, 7), (256, 7), (384, 7), (512, 7), (512, 9)] {
        let (s, time) = run(n, nz);
        println!(
            "| {n} × {nz} | {:.2} % | {:.2} % | {:.2} % | {} | {:.0} |",
            100.0 * rel(s.ehl.central_film, reference.ehl.central_film),
            100.0 * rel(s.summary.film_temperature_max - t0, reference.summary.film_temperature_max - t0),
            100.0 * rel(s.ehl.traction.friction_coefficient, reference.ehl.traction.friction_coefficient),
            s.convergence.iterations,
            1e3 * time
        );
    }
    println!(
        "\nreference 512 × 11: central film {:.4e} m, ΔT_max {:.2} K, μ {:.5}",
        reference.ehl.central_film,
        reference.summary.film_temperature_max - t0,
        reference.ehl.traction.friction_coefficient
    );
}
