//! The dry contact solver of the 2-D EHL grid (`physics::ehl::twod::solve_dry`, Polonsky–Keer
//! conjugate gradient, issue 16 deliverable 3): circular and elliptic point contacts against Hertz
//! (Johnson ch. 4), the seed 000 crowned roller against the slice model, and the EHL roller's dry
//! limit against it.

use crate::ehl_2d::{oil, opts, point, rel, rows, seed000_nose, E_PRIME};
use tribod::physics::contact::hertz_point;
use tribod::physics::ehl::twod::{solve, solve_dry, DryOptions, DrySolution, Ehl2dInput, Ehl2dOptions, Fields2d, Geometry2d};
use tribod::physics::roller::{Crown, CrownProfile};
use tribod::physics::Silent;

/// The point contacts' grid: a square of ±1.5 semi-axes around the centre (x: in units of the
/// semi-axis along x; across: `side` semi-axes along x).
fn point_grid(n: usize, side: f64) -> Ehl2dOptions {
    Ehl2dOptions { inlet: Some(1.5), outlet: Some(1.5), side: Some(side), ..opts(n, n) }
}

/// Where the pressure along a line of nodes from the centre outwards, `(distance, p)`, reaches
/// zero: `p²` extrapolated linearly from the last two loaded nodes (Hertz: `p² ∝ 1 − r²/a²`).
fn edge_of(line: &[(f64, f64)]) -> f64 {
    let last = line.iter().rposition(|(_, p)| *p > 0.0).expect("a loaded node");
    let (r1, p1) = line[last];
    let (r0, p0) = line[last - 1];
    r1 + (r1 - r0) * p1 * p1 / (p0 * p0 - p1 * p1)
}

/// The semi-axes of the dry footprint along x and y through the centre node (m).
fn semi_axes(f: &Fields2d) -> (f64, f64) {
    let nx = f.x.len();
    let i0 = f.x.iter().position(|x| x.abs() < 1e-12).expect("a node at x = 0");
    let j0 = f.y.iter().position(|y| y.abs() < 1e-12).expect("a node at y = 0");
    let along_x: Vec<(f64, f64)> = (i0..nx).map(|i| (f.x[i].abs(), f.pressure[j0 * nx + i])).collect();
    let along_y: Vec<(f64, f64)> = (j0..f.y.len()).map(|j| (f.y[j], f.pressure[j * nx + i0])).collect();
    (edge_of(&along_x), edge_of(&along_y))
}

/// `(p_max/p0 − 1, a_x/a_x,H − 1, a_y/a_y,H − 1, δ/δ_H − 1)` of the dry point contact on `n`².
fn dry_point_errors(rx: f64, ry: f64, n: usize) -> [f64; 4] {
    let hz = hertz_point(100.0, rx, ry, 0.5 * E_PRIME).unwrap();
    let (ax, ay) = if rx >= ry { (hz.semi_major, hz.semi_minor) } else { (hz.semi_minor, hz.semi_major) };
    let input = point(100.0, rx, ry, 1.0, oil(0.04, 2e-8));
    let t = std::time::Instant::now();
    let s = solve_dry(&input, &point_grid(n, 1.5 * ay / ax), &DryOptions::default(), &Silent).unwrap();
    let (sx, sy) = semi_axes(&s.fields);
    let e = [s.max_pressure.value / hz.max_pressure - 1.0, sx / ax - 1.0, sy / ay - 1.0, s.approach / hz.approach - 1.0];
    println!("R_x/R_y {:.2} on {n}²: {} iterations in {:.1?}; p_max/p0 − 1 {:+.4}, a_x {:+.4}, a_y {:+.4}, δ {:+.4}; load {}", rx / ry, s.convergence.iterations, t.elapsed(), e[0], e[1], e[2], e[3], s.load);
    assert!(rel(s.load, 100.0) < 1e-9, "{}", s.load);
    e
}

#[test]
fn ehl2d_dry_point_contacts_are_hertz() {
    for (rx, ry) in [(0.01, 0.01), (0.01, 0.04)] {
        for n in [65, 129] {
            dry_point_errors(rx, ry, n);
        }
    }
}

/// Load per length along the roller `w(y) = ∫ p dx` (N/m) of a field.
fn load_per_length(f: &Fields2d) -> Vec<f64> {
    let nx = f.x.len();
    let dx = (f.x[1] - f.x[0]).abs();
    (0..f.y.len()).map(|j| f.pressure[j * nx..(j + 1) * nx].iter().sum::<f64>() * dx).collect()
}

fn dry_roller_against_slices(input: &Ehl2dInput, ny: usize) -> DrySolution {
    let Geometry2d::Finite { rx, crown } = input.geometry else { unreachable!() };
    let slices = crown.distribute(input.load, rx, 0.5 * input.effective_modulus);
    let t = std::time::Instant::now();
    let s = solve_dry(input, &opts(65, ny), &DryOptions::default(), &Silent).unwrap();
    let f = &s.fields;
    let w = load_per_length(f);
    let dy = f.y[1] - f.y[0];
    let loaded = w.iter().filter(|v| **v > 0.0).count() as f64 * dy;
    let w_max = w.iter().cloned().fold(0.0, f64::max);
    let slice_w = |y: f64| slices.peak_load_per_length * (1.0 - crown.gap(y) / slices.approach).max(0.0);
    let dist: f64 = f.y.iter().zip(&w).map(|(y, v)| (v - slice_w(*y)).abs() * dy).sum::<f64>() / input.load;
    println!(
        "{:?} 65×{ny}: {} it in {:.1?}; loaded length {:.3} mm (slices {:.3}), peak w {:.4e} (slices {:.4e}), ∫|w − w_slice|/F {dist:.4}, approach {:.3e} (slices {:.3e}), p_max {:?}, edge {:?}",
        crown.profile,
        s.convergence.iterations,
        t.elapsed(),
        loaded * 1e3,
        slices.effective_length * 1e3,
        w_max,
        slices.peak_load_per_length,
        s.approach,
        slices.approach,
        s.max_pressure,
        s.edge_pressure_peak
    );
    s
}

#[test]
fn ehl2d_dry_seed000_roller_against_the_slice_model() {
    for ny in [129, 257] {
        dry_roller_against_slices(&seed000_nose(), ny);
        let mut printed = seed000_nose();
        if let Geometry2d::Finite { crown, .. } = &mut printed.geometry {
            crown.profile = CrownProfile::Seed000Eq3;
        }
        dry_roller_against_slices(&printed, ny);
    }
}

/// `∫∫|p − q| dA / F` on common nodes.
fn distance(a: &Fields2d, b: &Fields2d, load: f64) -> f64 {
    let cell = (a.x[1] - a.x[0]).abs() * (a.y[1] - a.y[0]);
    a.pressure.iter().zip(&b.pressure).map(|(p, q)| (p - q).abs()).sum::<f64>() * cell / load
}

fn ehl_roller_dry_limit(input0: Ehl2dInput, speeds: &[f64]) {
    for &u in speeds {
        let input = Ehl2dInput { entrainment_velocity: u, ..input0 };
        let o = Ehl2dOptions { fields: true, grid_tolerance: 1.0, ..opts(65, 129) };
        let dry = solve_dry(&input, &o, &DryOptions::default(), &Silent).unwrap();
        let t = std::time::Instant::now();
        match solve(&input, &o, &Silent) {
            Ok(s) => {
                let f = s.fields.as_ref().unwrap();
                assert_eq!(f.x, dry.fields.x);
                let d = distance(f, &dry.fields, input.load);
                let (re, rd) = (rows(f), rows(&dry.fields));
                let prof: f64 = re.iter().zip(&rd).map(|(a, b)| (a.1 - b.1).abs()).fold(0.0, f64::max);
                println!(
                    "u_m {u}: M {:.0} L {:.2} ∫|p − p_dry|/F {d:.4}; max_y |max_x p − dry| {:.4e}; p_max {:.4e} (dry {:.4e}); edge {:?} (dry {:?}); hc {:.3e} hmin {:.3e}; {} steps in {:.1?}",
                    s.moes_m, s.moes_l, prof, s.max_pressure.value, dry.max_pressure.value, s.edge_pressure_peak, dry.edge_pressure_peak, s.central_film, s.min_film.value, s.convergence.iterations, t.elapsed()
                );
            }
            Err(e) => println!("u_m {u}: EHL failed after {:.1?}: {e}", t.elapsed()),
        }
    }
}

#[test]
fn ehl2d_roller_dry_limit_probe() {
    ehl_roller_dry_limit(seed000_nose(), &[2.77, 0.3, 0.03]);
    let mut printed = seed000_nose();
    if let Geometry2d::Finite { crown, .. } = &mut printed.geometry {
        crown.profile = CrownProfile::Seed000Eq3;
    }
    ehl_roller_dry_limit(printed, &[2.77, 0.3, 0.03]);
    let _ = Crown::SEED000;
}
