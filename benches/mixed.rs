//! Run time against error of mixed lubrication (issue 15): the numerical EHL solver with the
//! asperities sharing the load (`EhlInput::asperity`) and the fast load-sharing closed form.
//!
//! `cargo bench --bench mixed` prints:
//! 1. one point (seed 001 nose load and radius, u_e = 0.4 m/s, σ = 0.3 µm: λ ≈ 0.17, asperity
//!    share ≈ 3.6 %) at 64…2048 nodes: time, asperity share and films against the Richardson
//!    extrapolation of the two finest grids; the smooth solve for comparison; the closed form;
//! 2. a 720-step cycle modelled on seed 001 (the `benches/ehl.rs` cycle: 2.25–12.5 kN over
//!    21 mm, R 15.2–10.5 mm, u_m = 4 cos θ + 1.5 m/s reversing twice, squeeze) with σ = 0.3 µm,
//!    through `TransientSolver` with Richardson extrapolation, smooth and mixed, with the
//!    asperity-share error against the same cycle at twice the resolution.
//! Single-threaded linear algebra; Richardson uses two rayon threads.

use std::time::Instant;
use tribod::physics::ehl::{solve, AsperityPressure, EhlInput, EhlOptions, Extrapolation, Rheology, TransientSolver};
use tribod::physics::film::mixed::LoadSharingLaw;
use tribod::physics::film::{ClosedForm, ContactInput, ContactShape, FilmFormula, FilmModel};
use tribod::physics::friction::{AsperityFriction, AsperityModel, Rheology as Shear, Roughness, TractionLaw};
use tribod::physics::lubricant::Lubricant;
use tribod::physics::Silent;

const E_STAR: f64 = 200e9 / (2.0 * 0.91);
const STEPS: usize = 720;

fn lub() -> Lubricant {
    Lubricant { viscosity: 0.013, pressure_viscosity: 1.84e-8, density: 870.0, ..Lubricant::SEED000 }
}

fn rough(sigma: f64) -> Roughness {
    Roughness { sigma, eta_beta_sigma: 0.04, sigma_over_beta: 0.001, plastic_limit: 6e9, curve: None }
}

fn input<'a>(w: f64, r: f64, u: f64, asperity: Option<&'a dyn AsperityPressure>) -> EhlInput<'a> {
    EhlInput {
        load_per_length: w,
        reduced_radius: r,
        effective_modulus: 2.0 * E_STAR,
        entrainment_velocity: u,
        sliding_velocity: 0.0,
        lubricant: lub(),
        temperature: lub().reference_temperature,
        rheology: Rheology::default(),
        transient: None,
        warm_start: None,
        asperity,
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

fn point_table() {
    let law = LoadSharingLaw { roughness: rough(0.3e-6), contact_modulus: E_STAR };
    let w = 12_500.0 / 0.021;
    let grids = [64, 128, 256, 512, 1024, 2048];
    let mut rows = Vec::new();
    for &n in &grids {
        let reps = if n <= 512 { 5 } else { 2 };
        let opts = EhlOptions { nodes: n, ..EhlOptions::default() };
        let (t, s) = best_of(reps, || solve(&input(w, 0.0105, 0.4, Some(&law)), &opts, &Silent).unwrap());
        let (ts, _) = best_of(reps, || solve(&input(w, 0.0105, 0.4, None), &opts, &Silent).unwrap());
        rows.push((n, t, ts, s));
    }
    let k = rows.len();
    let rich = |f: &dyn Fn(&tribod::physics::ehl::EhlSolution) -> f64| {
        let (a, b) = (f(&rows[k - 2].3), f(&rows[k - 1].3));
        b + (b - a) / 3.0
    };
    let fa_ref = rich(&|s| s.asperity_load_per_length / w);
    let hc_ref = rich(&|s| s.central_film);
    let hm_ref = rich(&|s| s.min_film);
    println!("### One mixed point: seed 001 nose load, u_e = 0.4 m/s, σ = 0.3 µm\n");
    println!("reference (Richardson of 1024/2048 nodes): asperity share {:.5}, h_c = {:.5} µm, h_min = {:.5} µm\n", fa_ref, hc_ref * 1e6, hm_ref * 1e6);
    println!("| nodes | mixed (ms) | smooth (ms) | Newton steps | share | error share | error h_c | error h_min |");
    println!("| ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: |");
    for (n, t, ts, s) in &rows {
        let fa = s.asperity_load_per_length / w;
        println!(
            "| {n} | {:.2} | {:.2} | {} | {:.5} | {:+.2} % | {:+.2} % | {:+.2} % |",
            t * 1e3,
            ts * 1e3,
            s.convergence.iterations,
            fa,
            100.0 * (fa / fa_ref - 1.0),
            100.0 * (s.central_film / hc_ref - 1.0),
            100.0 * (s.min_film / hm_ref - 1.0)
        );
    }
    // The fast closed form at the same point.
    let (l, r) = (lub(), rough(0.3e-6));
    let law_t = TractionLaw { rheology: Shear::Eyring { tau0: 5e6 }, limiting_shear_coefficient: None };
    let asp = AsperityFriction { coefficient: 0.12, model: AsperityModel::Coulomb, map: None };
    let c = ContactInput {
        load: 12_500.0,
        shape: ContactShape::Line { reduced_radius: 0.0105, length: 0.021 },
        entrainment_velocity: 0.4,
        sliding_velocity: 0.0,
        time: 0.0,
        time_step: 0.0,
        contact_modulus: E_STAR,
        temperature: l.reference_temperature,
        lubricant: &l,
        roughness: &r,
        traction_law: &law_t,
        asperity_friction: &asp,
        interrupts: tribod::physics::Interrupts::NONE,
    };
    let cf = ClosedForm { formula: FilmFormula::PanHamrock, squeeze: false };
    let (t, f) = best_of(2000, || cf.solve(&c, None).unwrap());
    println!(
        "\nclosed form (Johnson–Greenwood–Poon, Pan–Hamrock): {:.2} µs, share {:.5} ({:+.1} % against the reference), h_c {:.5} µm\n",
        t * 1e6,
        f.asperity.load / 12_500.0,
        100.0 * (f.asperity.load / 12_500.0 / fa_ref - 1.0),
        f.central_film * 1e6
    );
}

/// The benchmark cycle of `benches/ehl.rs` at step `k`.
fn cycle_input(k: usize, asperity: Option<&dyn AsperityPressure>) -> EhlInput<'_> {
    let th = 2.0 * std::f64::consts::PI * k as f64 / STEPS as f64;
    let f = 2250.0 + (12500.0 - 2250.0) * (0.5 - 0.5 * th.cos()).powi(2);
    let r = 0.0152 - 0.0047 * (0.5 - 0.5 * th.cos());
    let u = 4.0 * th.cos() + 1.5;
    input(f / 0.021, r, u, asperity)
}

fn cycle(nodes: usize, asperity: Option<&dyn AsperityPressure>) -> (f64, Vec<f64>, Vec<f64>) {
    let opts = EhlOptions { nodes, tolerance: 1e-6, ..EhlOptions::default() };
    let mut ts = TransientSolver::new(opts, Extrapolation::Richardson);
    let dt = 60.0 / 950.0 / STEPS as f64;
    let t = Instant::now();
    let (mut share, mut hc) = (Vec::with_capacity(STEPS), Vec::with_capacity(STEPS));
    for k in 0..STEPS {
        let inp = cycle_input(k, asperity);
        let s = ts.step(&inp, Some(dt), &Silent).unwrap_or_else(|e| panic!("step {k}: {e}"));
        share.push(s.asperity_load_per_length / inp.load_per_length);
        hc.push(s.central_film);
    }
    (t.elapsed().as_secs_f64(), share, hc)
}

fn cycle_table() {
    let law = LoadSharingLaw { roughness: rough(0.3e-6), contact_modulus: E_STAR };
    println!("### Mixed cycle: 720 steps modelled on seed 001, σ = 0.3 µm, Richardson\n");
    println!("| nodes | smooth (s) | mixed (s) | largest share | worst share error | worst h_c error |");
    println!("| ---: | ---: | ---: | ---: | ---: | ---: |");
    let (_, share_ref, hc_ref) = cycle(385, Some(&law));
    for n in [97, 193] {
        let (ts, _, _) = cycle(n, None);
        let (tm, share, hc) = cycle(n, Some(&law));
        let worst = |a: &[f64], b: &[f64], floor: f64| a.iter().zip(b).map(|(x, y)| (x - y).abs() / y.abs().max(floor)).fold(0.0, f64::max);
        let top = share.iter().cloned().fold(0.0, f64::max);
        println!(
            "| {n} | {ts:.3} | {tm:.3} | {top:.4} | {:.2} % | {:.2} % |",
            100.0 * worst(&share, &share_ref, 0.01 * top),
            100.0 * worst(&hc, &hc_ref, 0.0)
        );
    }
    println!("\nreference: the same cycle at 385 nodes (Richardson with 193); share errors relative, floored at 1 % of the largest share\n");
}

fn main() {
    faer::set_global_parallelism(faer::Par::Seq);
    let args: Vec<String> = std::env::args().skip(1).filter(|a| !a.starts_with('-')).collect();
    let want = |name: &str| args.is_empty() || args.iter().any(|a| a == name);
    if want("point") {
        point_table();
    }
    if want("cycle") {
        cycle_table();
    }
}
