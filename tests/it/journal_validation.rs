//! Validation of the journal bearing solver against closed forms, the classical design tables
//! and seed 002, plus a Richardson grid-convergence study. Tolerances are stated per check.

use std::f64::consts::PI;
use tribod::physics::journal::*;
use tribod::physics::Silent;

fn grid(nt: usize, nz: usize) -> Settings {
    Settings { circumferential: nt, axial: nz, ..Settings::default() }
}

fn at_eps(ld: f64, eps: f64, s: &Settings) -> Analysis {
    analyse(&Bearing::plain(ld), &Operating::Eccentricity(eps), s, None, None, false, &Silent).unwrap()
}

/// Raimondi & Boyd (1958), full journal bearing, L/D = 1, Reynolds boundary conditions, as
/// tabulated in Shigley's Mechanical Engineering Design: ε, S, φ (deg), (r/c) f, Q/(rcNl),
/// Qs/Q, P/p_max.
const RAIMONDI_BOYD_LD1: [[f64; 7]; 5] = [
    [0.2, 0.631, 74.02, 12.8, 3.59, 0.280, 0.529],
    [0.4, 0.264, 63.10, 5.79, 3.99, 0.497, 0.484],
    [0.6, 0.121, 50.58, 3.22, 4.33, 0.680, 0.415],
    [0.8, 0.0446, 36.24, 1.70, 4.62, 0.842, 0.313],
    [0.9, 0.0188, 26.45, 1.05, 4.74, 0.919, 0.247],
];

#[test]
fn raimondi_boyd_l_over_d_1() {
    // The table gives 3 significant figures from a 1958 relaxation solution; tolerances:
    // S 2 %, φ 1°, (r/c)f 1.5 %, flow 1 %, side-flow ratio 0.005, P/p_max 3 %.
    let s = grid(121, 61);
    for row in RAIMONDI_BOYD_LD1 {
        let [eps, ss, phi, f, q, qsq, pr] = row;
        let a = at_eps(1.0, eps, &s);
        let s_num = a.sommerfeld.unwrap();
        let p_ratio = a.load / 2.0 / a.max_pressure; // P_avg/p_max = W̄/(2 P_max) in seed 002 scaling
        eprintln!(
            "eps {eps}: S {s_num:.4} ({ss}) phi {:.2} ({phi}) f {:.3} ({f}) Q {:.3} ({q}) Qs/Q {:.3} ({qsq}) P/pmax {:.3} ({pr})",
            a.attitude.to_degrees(),
            a.friction_variable.unwrap(),
            a.flow_variable,
            a.side_flow_ratio.unwrap(),
            p_ratio
        );
        assert!((s_num / ss - 1.0).abs() < 0.02, "S at eps {eps}: {s_num} vs {ss}");
        assert!((a.attitude.to_degrees() - phi).abs() < 1.0, "attitude at eps {eps}");
        assert!((a.friction_variable.unwrap() / f - 1.0).abs() < 0.015, "friction at eps {eps}");
        assert!((a.flow_variable / q - 1.0).abs() < 0.01, "flow at eps {eps}");
        assert!((a.side_flow_ratio.unwrap() - qsq).abs() < 0.005, "side flow at eps {eps}");
        assert!((p_ratio / pr - 1.0).abs() < 0.03, "P/pmax at eps {eps}");
    }
}

/// Ocvirk's short bearing in seed 002 scaling: `W̄ = (L/D)² ε √(16ε² + π²(1−ε²)) / (6 (1−ε²)²)`,
/// `tan φ = π √(1−ε²) / (4ε)`.
fn ocvirk(ld: f64, e: f64) -> (f64, f64) {
    let w = ld * ld * e * (16.0 * e * e + PI * PI * (1.0 - e * e)).sqrt() / (6.0 * (1.0 - e * e).powi(2));
    let phi = (PI * (1.0 - e * e).sqrt() / (4.0 * e)).atan();
    (w, phi)
}

#[test]
fn short_bearing_limit_is_ocvirk() {
    let eps = 0.5;
    let mut errs = Vec::new();
    for ld in [0.2, 0.1, 0.05] {
        let a = at_eps(ld, eps, &grid(181, 17));
        let (w, phi) = ocvirk(ld, eps);
        let err = (a.load / w - 1.0).abs();
        eprintln!("L/D {ld}: W {} Ocvirk {w} rel {err:.4}; phi {:.2} Ocvirk {:.2}", a.load, a.attitude.to_degrees(), phi.to_degrees());
        errs.push((err, (a.attitude - phi).abs().to_degrees()));
    }
    // the finite-length load approaches the short-bearing load from below as L/D → 0
    assert!(errs[0].0 > errs[1].0 && errs[1].0 > errs[2].0, "{errs:?}");
    assert!(errs[2].0 < 0.01, "{errs:?}");
    assert!(errs[2].1 < 0.5, "{errs:?}");
}

/// Infinitely long bearing with the Reynolds condition (groove at the largest film): with `θ`
/// from the largest film, `H³ P' = H − H_c`, `P(0) = 0`, `P(θ_c) = P'(θ_c) = 0`. Returns
/// (W̄ per unit Z, attitude angle, P_max) by bisection on θ_c and Simpson quadrature.
fn long_bearing(e: f64) -> (f64, f64, f64) {
    let h = |t: f64| 1.0 + e * t.cos();
    let n = 20_000;
    let integrate = |tc: f64, f: &dyn Fn(f64) -> f64| {
        let d = tc / n as f64;
        let mut s = f(0.0) + f(tc);
        for k in 1..n {
            s += if k % 2 == 1 { 4.0 } else { 2.0 } * f(k as f64 * d);
        }
        s * d / 3.0
    };
    let g = |tc: f64| {
        let hc = h(tc);
        integrate(tc, &|t| (h(t) - hc) / h(t).powi(3))
    };
    let (mut a, mut b) = (PI + 1e-9, 2.0 * PI - 1e-9);
    let ga = g(a);
    for _ in 0..80 {
        let m = 0.5 * (a + b);
        if (g(m) > 0.0) == (ga > 0.0) { a = m } else { b = m }
    }
    let tc = 0.5 * (a + b);
    let hc = h(tc);
    // pressure by cumulative trapezoid on a fine grid, then the force integrals
    let m = 200_000;
    let d = tc / m as f64;
    let (mut p, mut fc, mut fs, mut pmax) = (0.0f64, 0.0, 0.0, 0.0f64);
    let dp = |t: f64| (h(t) - hc) / h(t).powi(3);
    for k in 0..m {
        let t0 = k as f64 * d;
        let p1 = p + 0.5 * d * (dp(t0) + dp(t0 + d));
        fc += 0.5 * d * (p * t0.cos() + p1 * (t0 + d).cos());
        fs += 0.5 * d * (p * t0.sin() + p1 * (t0 + d).sin());
        p = p1;
        pmax = pmax.max(p);
    }
    let w = fc.hypot(fs);
    let att = PI - fs.atan2(fc);
    (w, att, pmax)
}

#[test]
fn long_bearing_limit_is_the_reynolds_condition_solution() {
    let eps = 0.6;
    let (w1, att1, p1) = long_bearing(eps);
    let mut errs = Vec::new();
    for ld in [2.0, 4.0, 8.0] {
        let a = at_eps(ld, eps, &grid(181, 65));
        let ew = (a.load / w1 - 1.0).abs();
        let ep = (a.max_pressure / p1 - 1.0).abs();
        let ea = (a.attitude - att1).abs().to_degrees();
        eprintln!("L/D {ld}: W {} long {w1} ({ew:.4}); Pmax {} long {p1} ({ep:.5}); att {:.2} long {:.2}", a.load, a.max_pressure, a.attitude.to_degrees(), att1.to_degrees());
        errs.push((ew, ep, ea));
    }
    // The load approaches the long-bearing load with edge losses proportional to D/L (the error
    // halves as L/D doubles), so a first-order extrapolation in D/L from L/D = 4 and 8 lands on
    // the long-bearing load; the mid-plane peak pressure converges much faster.
    let ratio = errs[1].0 / errs[2].0;
    assert!((1.7..2.3).contains(&ratio), "{errs:?}");
    let w4 = w1 * (1.0 - errs[1].0);
    let w8 = w1 * (1.0 - errs[2].0);
    let extrapolated = 2.0 * w8 - w4;
    eprintln!("extrapolated in D/L: {extrapolated} vs {w1}");
    assert!((extrapolated / w1 - 1.0).abs() < 0.005);
    assert!(errs[2].1 < 5e-4, "{errs:?}");
    assert!(errs[2].2 < 0.5, "{errs:?}");
}

#[test]
fn petroff_as_eccentricity_vanishes() {
    // (R/c) f → 2π² S as ε → 0 (Petroff); here with the exact 1/√(1−ε²) and the small
    // pressure term ε sin φ / 2 the ratio is 1 within 0.1 %.
    for eps in [0.01, 0.001] {
        let a = at_eps(1.0, eps, &grid(121, 61));
        let petroff = 2.0 * PI * PI * a.sommerfeld.unwrap();
        let ratio = a.friction_variable.unwrap() / petroff;
        eprintln!("eps {eps}: (R/c)f {} Petroff {petroff} ratio {ratio}", a.friction_variable.unwrap());
        assert!((ratio - 1.0).abs() < 1e-3, "{ratio}");
    }
}

#[test]
fn seed_002_table_2_aligned() {
    // ε = 0.6, L/D = 1.25, the paper's 361 × 181 grid: P0 = 0.6444, H0 = 0.4.
    let a = at_eps(1.25, 0.6, &grid(361, 181));
    eprintln!("aligned: P0 {} H0 {} (R/c)f {:?} seed002 {:?} S {:?} att {}", a.max_pressure, a.min_film, a.friction_variable, a.friction_variable_seed002, a.sommerfeld, a.attitude.to_degrees());
    assert!((a.max_pressure / 0.6444 - 1.0).abs() < 0.002, "P0 {}", a.max_pressure);
    assert!((a.min_film - 0.4).abs() < 1e-12);
    // f = 2.2178 with the striated-cavity reading of eq. (9)
    let f = a.friction_variable_seed002.unwrap();
    assert!((f / 2.2178 - 1.0).abs() < 0.006, "f {f}");
}

/// Richardson extrapolation of three values on grids refined by 2: (order, extrapolated value).
fn richardson(f1: f64, f2: f64, f3: f64) -> (f64, f64) {
    let p = ((f1 - f2) / (f2 - f3)).abs().log2();
    let ext = f3 + (f3 - f2) / (2f64.powf(p) - 1.0);
    (p, ext)
}

#[test]
fn grid_convergence_is_second_order() {
    // aligned ε = 0.6, L/D = 1.25: load and P0; misaligned + profiled load balance: H0
    let grids = [(61, 31), (121, 61), (241, 121)];
    let mut load = Vec::new();
    let mut p0 = Vec::new();
    for &(nt, nz) in &grids {
        let a = at_eps(1.25, 0.6, &grid(nt, nz));
        load.push(a.load);
        p0.push(a.max_pressure);
    }
    let w = load[2];
    let b = Bearing {
        misalignment: Misalignment { vertical: 0.56, horizontal: 0.56 },
        profile: Some(Profile { order: 2, height: 0.4, length_fraction: 0.2 }),
        ..Bearing::plain(1.25)
    };
    let mut h0 = Vec::new();
    for &(nt, nz) in &grids {
        let a = analyse(&b, &Operating::Load(w), &grid(nt, nz), None, None, false, &Silent).unwrap();
        h0.push(a.min_film);
    }
    // H0 of the balanced misaligned bearing is not yet monotone on these grids (its differences
    // change sign): require the changes to contract by at least 3 per refinement instead.
    eprintln!("H0 (misaligned, profiled): {h0:?}");
    assert!((h0[2] - h0[1]).abs() < (h0[1] - h0[0]).abs() / 3.0, "{h0:?}");
    for (name, v) in [("load", &load), ("P0", &p0)] {
        assert!((v[0] - v[1]) * (v[1] - v[2]) > 0.0, "{name}: not monotone {v:?}");
        let (p, ext) = richardson(v[0], v[1], v[2]);
        eprintln!("{name}: {v:?} order {p:.2} extrapolated {ext:.6} error of finest {:.2e}", (v[2] / ext - 1.0).abs());
        // second order discretisation; the parabola-refined peak converges a little faster
        assert!((1.5..3.5).contains(&p), "{name}: observed order {p}");
        assert!((v[2] / ext - 1.0).abs() < 2e-3, "{name}");
    }
}
