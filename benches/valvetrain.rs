//! Valve-train dynamics benchmarks (issue 17): one revolution of seed 003's train at 3600 output
//! angles against the integration tolerance (run time, steps, contact-load error against a
//! tight run from the same periodic state), the periodic steady state from rest, and a run-up of
//! 20 revolutions (from rest at constant speed, and over a speed ramp 1000 → 3600 rpm with
//! `run_up`). `cargo bench --bench valvetrain` (release). Plain `Instant` timing, best of N.

use std::f64::consts::TAU;
use std::time::Instant;
use tribod::physics::cam::{LiftLaw, LiftProgram};
use tribod::physics::valvetrain::{
    damping_from_ratio, line_contact_stiffness, periodic_response, run_up, transient, Drive, DynamicsOptions, HelicalSpring, Lever, Link,
    Pushrod, Seat, SpringChain, ValveTrain,
};
use tribod::physics::Silent;

/// Seed 003's train as in `examples/seed003_dynamic.json` (Table 1 masses, 38 N/mm spring from
/// its coils, eq. 6 contact stiffness, seat).
fn seed003() -> ValveTrain {
    let coil = HelicalSpring { wire_diameter: 4e-3, mean_diameter: 25e-3, active_coils: 4.27, shear_modulus: 79.3e9, density: 7850.0 };
    let es = 1.0 / (2.0 * (1.0 - 0.3f64 * 0.3) / 210e9);
    let kc = line_contact_stiffness(300.0, 0.012, 0.018, es);
    let m = 0.045 + 0.157;
    ValveTrain {
        lash: None,
        follower_mass: 0.045,
        valve_mass: 0.157,
        train: None,
        spring: SpringChain { rate: coil.rate(), mass: coil.active_mass(), elements: 8, damping_ratio: 0.02, groups: Vec::new() },
        inner_spring: None,
        preload: 300.0,
        contact: Link { stiffness: kc, damping: damping_from_ratio(0.1, kc, m) },
        seat: Some(Seat { link: Link { stiffness: 2e8, damping: damping_from_ratio(0.1, 2e8, m) }, gap: 1e-6 }),
        lever: None,
    }
}

fn main() {
    let h = 8e-3;
    let p = LiftProgram {
        lift: h,
        rise_start: 90f64.to_radians(),
        rise: 90f64.to_radians(),
        top_dwell: 0.0,
        fall: 90f64.to_radians(),
        rise_law: LiftLaw::Cycloidal,
        return_law: LiftLaw::Cycloidal,
    };
    let cam = move |th: f64| {
        let j = p.lift(th);
        (j.v, j.d1)
    };
    let train = seed003();
    let reps = 20;
    // Optional filter: `cargo bench --bench valvetrain -- 3600` (one speed's rows only) or
    // `-- rocker` (the rocker example's revolution only).
    let filter: Option<String> = std::env::args().skip(1).find(|a| !a.starts_with("--"));
    if filter.as_deref() == Some("rocker") {
        rocker(reps);
        return;
    }
    let speeds: Vec<f64> = match filter.as_deref().and_then(|f| f.parse::<f64>().ok()) {
        Some(rpm) => vec![rpm],
        None => vec![3000.0, 3600.0],
    };
    for rpm in speeds {
        let omega = rpm * TAU / 60.0;
        let drive = Drive { lift: &cam, omega, max_lift: h };
        let period = TAU / omega;
        let n = 3600;
        let times: Vec<f64> = (1..=n).map(|k| period * k as f64 / n as f64).collect();
        // The periodic state (tight), then one revolution from it per tolerance.
        let t = Instant::now();
        let per = match periodic_response(&train, drive, n, &DynamicsOptions { tolerance: 1e-8, ..Default::default() }, &Silent) {
            Ok(p) => p,
            Err(e) => {
                println!("{rpm} rpm: no periodic state: {e}");
                continue;
            }
        };
        let steady_ms = t.elapsed().as_secs_f64() * 1e3;
        println!(
            "{rpm} rpm: periodic state from rest (tolerance 1e-8, 3600 angles): {:.1} ms, {} revolutions, separation {:?}",
            steady_ms, per.convergence.iterations, per.separation
        );
        let start = per.start.clone();
        let tight = DynamicsOptions { tolerance: 1e-11, ..Default::default() };
        let (_, reference, _) = transient(&train, drive, Some(&start), period, &times, &tight).unwrap();
        let fmax = reference.iter().map(|p| p.contact.abs()).fold(0.0, f64::max);
        println!("| rpm | tolerance | ms / revolution | max contact-load error / max load |");
        println!("|---|---|---|---|");
        for tol in [1e-3, 1e-4, 1e-5, 1e-6, 1e-7, 1e-8, 1e-9] {
            let options = DynamicsOptions { tolerance: tol, ..Default::default() };
            let mut best = f64::INFINITY;
            let mut probes = Vec::new();
            for _ in 0..reps {
                let t = Instant::now();
                let (_, pr, _) = transient(&train, drive, Some(&start), period, &times, &options).unwrap();
                best = best.min(t.elapsed().as_secs_f64() * 1e3);
                probes = pr;
            }
            let err = probes.iter().zip(&reference).map(|(a, b)| (a.contact - b.contact).abs()).fold(0.0, f64::max) / fmax;
            println!("| {rpm} | {tol:.0e} | {best:.2} | {err:.2e} |");
        }
        // Run-up: 20 revolutions from rest, 3600 samples per revolution.
        let options = DynamicsOptions { tolerance: 1e-6, ..Default::default() };
        let times20: Vec<f64> = (1..=20 * n).map(|k| period * k as f64 / n as f64).collect();
        let mut best = f64::INFINITY;
        for _ in 0..3 {
            let t = Instant::now();
            let r = transient(&train, drive, None, 20.0 * period, &times20, &options).unwrap();
            best = best.min(t.elapsed().as_secs_f64() * 1e3);
            std::hint::black_box(r);
        }
        println!("{rpm} rpm: run-up of 20 revolutions from rest (tolerance 1e-6, 3600 samples each): {best:.1} ms\n");
    }
    if filter.is_some() {
        return;
    }
    rocker(reps);
    // Run-up over a speed ramp (load.run_up): 20 revolutions from 1000 to 3600 rpm, 360 samples
    // per revolution; the speed at the first loss of contact against a tight run.
    let to = 3600.0 * TAU / 60.0;
    let from = Drive { lift: &cam, omega: 1000.0 * TAU / 60.0, max_lift: h };
    let tight = run_up(&train, from, to, 20, 360, &DynamicsOptions { tolerance: 1e-11, ..Default::default() }, &Silent).unwrap();
    let rpm = |w: Option<f64>| w.map(|w| w * 60.0 / TAU);
    println!("| run-up 1000→3600 rpm, 20 rev | tolerance | ms | steps | first separation, rpm | max contact-load error / max load |");
    println!("|---|---|---|---|---|---|");
    let fmax = tight.contact_force.iter().copied().fold(0.0, f64::max);
    for tol in [1e-6, 1e-7, 1e-8, 1e-9] {
        let options = DynamicsOptions { tolerance: tol, ..Default::default() };
        let mut best = f64::INFINITY;
        let mut last = None;
        for _ in 0..3 {
            let t = Instant::now();
            let r = run_up(&train, from, to, 20, 360, &options, &Silent).unwrap();
            best = best.min(t.elapsed().as_secs_f64() * 1e3);
            last = Some(r);
        }
        let r = last.unwrap();
        let err = r.contact_force.iter().zip(&tight.contact_force).map(|(a, b)| (a - b).abs()).fold(0.0, f64::max) / fmax;
        println!(
            "| | {tol:.0e} | {best:.1} | {} | {:.1} (tight {:.1}) | {err:.2e} |",
            r.stats.accepted,
            rpm(r.first_separation_speed).unwrap_or(f64::NAN),
            rpm(tight.first_separation_speed).unwrap_or(f64::NAN)
        );
    }
}

/// The train of `examples/rocker_dynamic.json` (pushrod rocker, r = 1.5; damping as the job
/// derives it from the example's default ratios) at 2500 rpm: one revolution at 3600 angles from
/// its periodic state against the tolerance.
fn rocker(reps: usize) {
    let coil = HelicalSpring { wire_diameter: 4.3e-3, mean_diameter: 24e-3, active_coils: 5.5, shear_modulus: 79.3e9, density: 7850.0 };
    let es = 1.0 / (2.0 * (1.0 - 0.3f64 * 0.3) / 210e9);
    let r: f64 = 1.5;
    let kc = line_contact_stiffness(r * 350.0, 0.012, 0.019, es);
    let (mf, mp, mv, inertia, lc) = (0.055, 0.045, 0.095, 3e-5, 0.03);
    let (tappet, lever) = (mf + 0.5 * mp, inertia / (lc * lc) + 0.5 * mp);
    let reduced = |a: f64, b: f64| a * b / (a + b);
    let train = ValveTrain {
        lash: None,
        follower_mass: mf,
        valve_mass: mv,
        train: Some(Link { stiffness: 3e7, damping: damping_from_ratio(0.05, 3e7, reduced(lever / (r * r), mv)) }),
        spring: SpringChain { rate: coil.rate(), mass: coil.active_mass(), elements: 8, damping_ratio: 0.02, groups: Vec::new() },
        inner_spring: None,
        preload: 350.0,
        contact: Link { stiffness: kc, damping: damping_from_ratio(0.1, kc, tappet) },
        seat: Some(Seat { link: Link { stiffness: 2e8, damping: damping_from_ratio(0.1, 2e8, mv) }, gap: 1e-6 }),
        lever: Some(Lever { cam_arm: lc, valve_arm: r * lc, inertia, pushrod: Some(Pushrod { mass: mp, link: Link { stiffness: 1.8e7, damping: damping_from_ratio(0.05, 1.8e7, reduced(tappet, lever)) } }) }),
    };
    let h = 6.5e-3;
    let p = LiftProgram {
        lift: h,
        rise_start: 90f64.to_radians(),
        rise: 90f64.to_radians(),
        top_dwell: 0.0,
        fall: 90f64.to_radians(),
        rise_law: LiftLaw::Cycloidal,
        return_law: LiftLaw::Cycloidal,
    };
    let cam = move |th: f64| {
        let j = p.lift(th);
        (j.v, j.d1)
    };
    let omega = 2500.0 * TAU / 60.0;
    let drive = Drive { lift: &cam, omega, max_lift: h };
    let period = TAU / omega;
    let n = 3600;
    let times: Vec<f64> = (1..=n).map(|k| period * k as f64 / n as f64).collect();
    let t = Instant::now();
    let per = periodic_response(&train, drive, n, &DynamicsOptions::default(), &Silent).unwrap();
    println!("rocker example, 2500 rpm: periodic state from rest (1e-8, 3600 angles) {:.1} ms, {} revolutions", t.elapsed().as_secs_f64() * 1e3, per.convergence.iterations);
    let start = per.start.clone();
    let (_, reference, _) = transient(&train, drive, Some(&start), period, &times, &DynamicsOptions { tolerance: 1e-11, ..Default::default() }).unwrap();
    let fmax = reference.iter().map(|p| p.contact.abs()).fold(0.0, f64::max);
    println!("| rocker | tolerance | ms / revolution | max contact-load error / max load |");
    println!("|---|---|---|---|");
    for tol in [1e-6, 1e-7, 1e-8, 1e-9] {
        let options = DynamicsOptions { tolerance: tol, ..Default::default() };
        let mut best = f64::INFINITY;
        let mut probes = Vec::new();
        for _ in 0..reps {
            let t = Instant::now();
            let (_, pr, _) = transient(&train, drive, Some(&start), period, &times, &options).unwrap();
            best = best.min(t.elapsed().as_secs_f64() * 1e3);
            probes = pr;
        }
        let err = probes.iter().zip(&reference).map(|(a, b)| (a.contact - b.contact).abs()).fold(0.0, f64::max) / fmax;
        println!("| 2500 | {tol:.0e} | {best:.2} | {err:.2e} |");
    }
}
