//! Dynamic coefficients of the journal bearing (issue 18): the linearised Reynolds solution
//! against the short-bearing closed forms, against central differences of whole complementarity
//! solves, damping symmetry, grid convergence and the rigid-rotor stability threshold.

use std::f64::consts::PI;
use tribod::physics::journal::dynamics::{coefficients, stability, tilt_coefficients, Coefficients};
use tribod::physics::journal::*;
use tribod::physics::Silent;

fn solve(b: &Bearing, op: Operating, s: &Settings) -> (Analysis, Coefficients) {
    let mut ws = Workspace::new(b, s);
    let a = analyse(b, &op, s, Some(&mut ws), None, false, &Silent).unwrap();
    let c = coefficients(b, &a, s, &mut ws, &Silent).unwrap();
    (a, c)
}

/// Short bearing (Ocvirk, π-film) dimensionless coefficients `K̄ = K c/W`, `C̄ = C c ω/W`: the
/// closed forms of Childs (Turbomachinery Rotordynamics, Wiley 1993, ch. 3), in the form ROSS's
/// `fluid_flow_coefficients` codes them — there the load is vertical (−y) and x horizontal.
/// Returned here in our frame (X along the load, Y 90° ahead in rotation): `X = −y_ref`,
/// `Y = x_ref`, so `K_XX = k_yy`, `K_XY = −k_yx`, `K_YX = −k_xy`, `K_YY = k_xx` (same for C).
pub fn short_bearing(e: f64) -> ([[f64; 2]; 2], [[f64; 2]; 2]) {
    let e2 = e * e;
    let p2 = PI * PI;
    let h0 = 1.0 / (p2 * (1.0 - e2) + 16.0 * e2).powf(1.5);
    let sq = (1.0 - e2).sqrt();
    let kxx = 4.0 * h0 * (p2 * (2.0 - e2) + 16.0 * e2);
    let kxy = h0 * PI * (p2 * (1.0 - e2).powi(2) - 16.0 * e2 * e2) / (e * sq);
    let kyx = -h0 * PI * (p2 * (1.0 - e2) * (1.0 + 2.0 * e2) + 32.0 * e2 * (1.0 + e2)) / (e * sq);
    let kyy = 4.0 * h0 * (p2 * (1.0 + 2.0 * e2) + 32.0 * e2 * (1.0 + e2) / (1.0 - e2));
    let cxx = 2.0 * PI * h0 * sq * (p2 * (1.0 + 2.0 * e2) - 16.0 * e2) / e;
    let cxy = -8.0 * h0 * (p2 * (1.0 + 2.0 * e2) - 16.0 * e2);
    let cyy = 2.0 * PI * h0 * (p2 * (1.0 - e2).powi(2) + 48.0 * e2) / (e * sq);
    ([[kyy, -kyx], [-kxy, kxx]], [[cyy, -cxy], [-cxy, cxx]])
}

fn max_abs(m: &[[f64; 2]; 2]) -> f64 {
    m.iter().flatten().fold(0.0f64, |a, v| a.max(v.abs()))
}

fn max_err(a: &[[f64; 2]; 2], b: &[[f64; 2]; 2]) -> f64 {
    let mut e = 0.0f64;
    for i in 0..2 {
        for j in 0..2 {
            e = e.max((a[i][j] - b[i][j]).abs());
        }
    }
    e / max_abs(b)
}

/// L/D = 0.1 against the short-bearing closed forms: every coefficient within 2.5 % of the
/// largest coefficient of its matrix (measured: ≤ 2.0 % for K, ≤ 1.9 % for C over ε = 0.2–0.8;
/// the finite-length effect at L/D = 0.2 is up to 6.5 %, printed). The critical mass from the
/// two sets agrees within 5 %.
#[test]
fn short_bearing_limit() {
    let s = Settings { circumferential: 361, axial: 31, pressure_tolerance: 1e-10, load_tolerance: 1e-9, ..Settings::default() };
    for ld in [0.2, 0.1] {
        for e in [0.2, 0.4, 0.6, 0.8] {
            let b = Bearing::plain(ld);
            let (a, c) = solve(&b, Operating::Eccentricity(e), &s);
            let (k, d) = c.dimensionless(a.load).unwrap();
            let (kr, dr) = short_bearing(e);
            let (ek, ed) = (max_err(&k, &kr), max_err(&d, &dr));
            let (st, sr) = (stability(k, d), stability(kr, dr));
            eprintln!(
                "L/D {ld} eps {e}: K {k:?} ref {kr:?} err {ek:.4}; C {d:?} ref {dr:?} err {ed:.4}; whirl {:.4} ({:.4}) Mc {:?} ({:?}); cycles {}",
                st.whirl_ratio, sr.whirl_ratio, st.critical_mass, sr.critical_mass, c.convergence.iterations
            );
            if ld == 0.1 {
                assert!(ek < 0.025 && ed < 0.025, "L/D {ld} eps {e}: K err {ek}, C err {ed}");
                match (st.critical_mass, sr.critical_mass) {
                    (Some(m), Some(r)) => assert!((m / r - 1.0).abs() < 0.05, "critical mass {m} vs {r}"),
                    (None, None) => {}
                    (m, r) => assert!(e > 0.7, "stability differs at eps {e}: {m:?} vs {r:?}"),
                }
            }
        }
    }
}

/// The grid and tight tolerances of the tests against differences of whole solves.
fn derivative_settings() -> Settings {
    Settings { circumferential: 121, axial: 41, pressure_tolerance: 1e-12, load_tolerance: 1e-10, ..Settings::default() }
}

/// Their bearings and eccentricity ratios: L/D 1 aligned, and L/D 1.25 misaligned and profiled
/// (seed 002's optimised design under a smaller misalignment).
fn derivative_cases() -> [(Bearing, f64); 2] {
    [
        (Bearing::plain(1.0), 0.6),
        (
            Bearing {
                length_to_diameter: 1.25,
                misalignment: Misalignment { vertical: 0.2, horizontal: 0.2 },
                profile: Some(Profile { order: 2, height: 0.4, length_fraction: 0.2 }),
                supply: Supply::MaxFilm,
            },
            0.5,
        ),
    ]
}

/// The linearisation is the derivative of the discrete problem: stiffness against central
/// differences (δ = 1e-4 c) of whole complementarity solves at fixed positions, with the supply
/// groove held where the equilibrium has it. L/D 1 aligned and L/D 1.25 misaligned + profiled
/// (seed 002's case). Within 0.2 % of the largest coefficient (measured in the output).
#[test]
fn stiffness_is_the_derivative_of_whole_solves() {
    let s = derivative_settings();
    for (b0, e) in derivative_cases() {
        let eq = analyse(&b0, &Operating::Eccentricity(e), &s, None, None, false, &Silent).unwrap();
        // the groove fixed at the equilibrium's largest-film angle
        let b = Bearing { supply: Supply::Angle(eq.attitude), ..b0 };
        let (x0, y0) = (eq.eccentricity * eq.attitude.cos(), eq.eccentricity * eq.attitude.sin());
        let at = |x: f64, y: f64| {
            let a = analyse(&b, &Operating::Position { eccentricity: x.hypot(y), attitude: y.atan2(x) }, &s, None, None, false, &Silent).unwrap();
            [a.force_along_load, a.force_across_load]
        };
        let (a, c) = solve(&b, Operating::Position { eccentricity: eq.eccentricity, attitude: eq.attitude }, &s);
        let d = 1e-4;
        let mut fd = [[0.0; 2]; 2];
        for j in 0..2 {
            let (dx, dy) = if j == 0 { (d, 0.0) } else { (0.0, d) };
            let (p, m) = (at(x0 + dx, y0 + dy), at(x0 - dx, y0 - dy));
            for i in 0..2 {
                fd[i][j] = -(p[i] - m[i]) / (2.0 * d);
            }
        }
        let err = max_err(&c.stiffness, &fd);
        eprintln!("L/D {} eps {e}: linearised {:?} fd {:?} err {err:.2e} load {}", b.length_to_diameter, c.stiffness, fd, a.load);
        assert!(err < 2e-3, "{err}");
    }
}

/// Damping from the squeeze term is symmetric (the perturbed problem is self-adjoint up to the
/// quadrature of the load) and dissipative; grid convergence of the coefficients at L/D 0.5
/// (Richardson-style: the change from the medium to the fine grid is below 1 %).
#[test]
fn damping_symmetric_dissipative_and_grid_converged() {
    let b = Bearing::plain(0.5);
    let mut prev: Option<([[f64; 2]; 2], [[f64; 2]; 2])> = None;
    for (nt, nz) in [(61, 21), (121, 41), (241, 81)] {
        let s = Settings { circumferential: nt, axial: nz, pressure_tolerance: 1e-10, load_tolerance: 1e-9, ..Settings::default() };
        let (a, c) = solve(&b, Operating::Eccentricity(0.5), &s);
        let (k, d) = c.dimensionless(a.load).unwrap();
        assert!((d[0][1] - d[1][0]).abs() < 2e-3 * max_abs(&d), "{d:?}");
        assert!(d[0][0] > 0.0 && d[1][1] > 0.0 && d[0][0] * d[1][1] - 0.25 * (d[0][1] + d[1][0]).powi(2) > 0.0);
        let st = stability(k, d);
        eprintln!("{nt}x{nz}: K {k:?} C {d:?} whirl {:.4} Mc {:?} S {:?}", st.whirl_ratio, st.critical_mass, a.sommerfeld);
        if let Some((kp, dp)) = prev {
            if nt == 241 {
                assert!(max_err(&k, &kp) < 0.01 && max_err(&d, &dp) < 0.01, "grid change K {} C {}", max_err(&k, &kp), max_err(&d, &dp));
            }
        }
        prev = Some((k, d));
    }
}

/// The generalised forces `(F̄x, F̄y, M̄x, M̄y)` of a pressure field: the force quadrature of
/// `dynamics` over the interior rows, the moments with the lever `Z − ½`.
fn generalised_forces(f: &Fields) -> [f64; 4] {
    let (nt, nz) = (f.theta.len(), f.z.len());
    let ds = (f.theta[1] - f.theta[0]) * (f.z[1] - f.z[0]);
    let mut q = [0.0; 4];
    for j in 1..nz - 1 {
        for i in 0..nt {
            let p = f.pressure[j * nt + i] * ds;
            let (c, s) = (f.theta[i].cos(), f.theta[i].sin());
            let lever = f.z[j] - 0.5;
            q[0] += p * c;
            q[1] += p * s;
            q[2] += p * c * lever;
            q[3] += p * s * lever;
        }
    }
    q
}

/// Of each 2×2 block of two 4×4 matrices (forces/moments × translations/tilts): the largest
/// difference over the block's largest reference entry (or 1e-3 of the whole matrix's, for a
/// block that vanishes).
fn block_errors(a: &[[f64; 4]; 4], r: &[[f64; 4]; 4]) -> [f64; 4] {
    let whole = r.iter().flatten().fold(0.0f64, |m, v| m.max(v.abs()));
    let mut out = [0.0; 4];
    for (b, o) in out.iter_mut().enumerate() {
        let (i0, j0) = (2 * (b / 2), 2 * (b % 2));
        let (mut diff, mut size) = (0.0f64, 0.0f64);
        for i in i0..i0 + 2 {
            for j in j0..j0 + 2 {
                diff = diff.max((a[i][j] - r[i][j]).abs());
                size = size.max(r[i][j].abs());
            }
        }
        *o = diff / size.max(1e-3 * whole);
    }
    out
}

/// The force and moment coefficients of translations and tilts are the derivative of the
/// discrete problem: the 4×4 stiffness against central differences (δ = 1e-4) of whole
/// complementarity solves at fixed positions — the translations move the mid-plane centre, the
/// tilts the misalignment (`Γx = 2 Δv0`, `Γy = −2 Δh0`) — with the forces and moments summed
/// from the pressure fields; the supply groove held where the equilibrium has it. L/D 1 aligned
/// (the translation–tilt blocks vanish by symmetry: ≤ 1e-9 of the largest entry) and L/D 1.25
/// misaligned + profiled. Every 2×2 block within 2e-3 of its largest entry. Damping: symmetric
/// (the squeeze source of each coordinate is its force quadrature times a constant) and positive
/// definite; the translations' blocks equal `coefficients` bit for bit.
#[test]
fn moment_coefficients_are_the_derivative_of_whole_solves() {
    let s = derivative_settings();
    for (b0, e) in derivative_cases() {
        let eq = analyse(&b0, &Operating::Eccentricity(e), &s, None, None, false, &Silent).unwrap();
        let b = Bearing { supply: Supply::Angle(eq.attitude), ..b0 };
        let (x0, y0) = (eq.eccentricity * eq.attitude.cos(), eq.eccentricity * eq.attitude.sin());
        let m0 = b.misalignment;
        // q = (X, Y, Γx, Γy) moved by `dq`
        let at = |dq: [f64; 4]| {
            let (x, y) = (x0 + dq[0], y0 + dq[1]);
            let bm = Bearing { misalignment: Misalignment { vertical: m0.vertical + 0.5 * dq[2], horizontal: m0.horizontal - 0.5 * dq[3] }, ..b };
            let a = analyse(&bm, &Operating::Position { eccentricity: x.hypot(y), attitude: y.atan2(x) }, &s, None, None, true, &Silent).unwrap();
            generalised_forces(a.fields.as_ref().unwrap())
        };
        // the 4×4 and the 2×2 set, each after the same analysis on a new workspace
        let pos = Operating::Position { eccentricity: eq.eccentricity, attitude: eq.attitude };
        let mut ws = Workspace::new(&b, &s);
        let a = analyse(&b, &pos, &s, Some(&mut ws), None, false, &Silent).unwrap();
        let t = tilt_coefficients(&b, &a, &s, &mut ws, &Silent).unwrap();
        let mut ws2 = Workspace::new(&b, &s);
        let a2 = analyse(&b, &pos, &s, Some(&mut ws2), None, false, &Silent).unwrap();
        let c2 = coefficients(&b, &a2, &s, &mut ws2, &Silent).unwrap();
        assert_eq!(t.translation().stiffness, c2.stiffness);
        assert_eq!(t.translation().damping, c2.damping);
        let d = 1e-4;
        let mut fd = [[0.0; 4]; 4];
        for j in 0..4 {
            let mut dq = [0.0; 4];
            dq[j] = d;
            let p = at(dq);
            dq[j] = -d;
            let m = at(dq);
            for i in 0..4 {
                fd[i][j] = -(p[i] - m[i]) / (2.0 * d);
            }
        }
        let err = block_errors(&t.stiffness, &fd);
        eprintln!("L/D {} eps {e}: linearised {:?}\n fd {:?}\n block errors (FX, FΓ, MX, MΓ) {err:?}; damping {:?}", b.length_to_diameter, t.stiffness, fd, t.damping);
        for e in err {
            assert!(e < 2e-3, "{err:?}");
        }
        let (k, c) = (t.stiffness, t.damping);
        let largest = k.iter().flatten().fold(0.0f64, |m, v| m.max(v.abs()));
        let largest_c = c.iter().flatten().fold(0.0f64, |m, v| m.max(v.abs()));
        if b0.misalignment.is_zero() {
            for (i, j) in [(0, 2), (0, 3), (1, 2), (1, 3), (2, 0), (2, 1), (3, 0), (3, 1)] {
                assert!(k[i][j].abs() < 1e-9 * largest && c[i][j].abs() < 1e-9 * largest_c, "aligned: K[{i}][{j}] = {}, C = {}", k[i][j], c[i][j]);
            }
        }
        for i in 0..4 {
            assert!(c[i][i] > 0.0);
            for j in 0..4 {
                assert!((c[i][j] - c[j][i]).abs() < 1e-8 * largest_c, "C[{i}][{j}] {} vs {}", c[i][j], c[j][i]);
            }
        }
        // positive definite: Cholesky of the symmetric damping
        let mut l = [[0.0f64; 4]; 4];
        for i in 0..4 {
            for j in 0..=i {
                let sum: f64 = (0..j).map(|m| l[i][m] * l[j][m]).sum();
                if i == j {
                    let v = c[i][i] - sum;
                    assert!(v > 0.0, "damping not positive definite: {c:?}");
                    l[i][j] = v.sqrt();
                } else {
                    l[i][j] = (c[i][j] - sum) / l[j][j];
                }
            }
        }
    }
}

/// Short-bearing limit of the tilt coefficients (aligned film, `H0` independent of `Z`; derived
/// here from Ocvirk's short-bearing equation `∂/∂Z(H³ ∂P/∂Z) ∝ ∂H/∂θ + 2 ∂H/∂τ` linearised in
/// `H1 = (Z − ½) Γ cos/sin θ`): the perturbation pressure of a tilt has the axial shape
/// `(Z − ½)³/6 − (Z − ½)/24` where a translation has `Z(Z − 1)/2`, and its Poiseuille term
/// `∂/∂Z(3H0² H1 ∂P0/∂Z)` is twice the translation's. With `∫ shape·(Z − ½) = −1/720` against
/// `∫ Z(Z − 1)/2 = −1/12`, the tilt block (moments against tilts) is
/// `C_MΓ = C_FX/60` and `K_MΓ = (2 K_FX − Ω)/60`, where `Ω` is the wedge part of `K_FX`:
/// `Ω_iX = −C_iY/2`, `Ω_iY = C_iX/2` (the wedge source of a displacement along X is −½ the
/// squeeze source of a velocity along Y, exactly, also in the discretisation). With the
/// short-bearing `K_FX`, `C_FX` of Childs (`short_bearing`) this gives closed forms. On 361×31
/// the tilt block converges to them as L/D falls (0.2, 0.1, 0.05, 0.025: the largest error of
/// each block over its largest entry falls at every step, to < 1 % at 0.025; measured in the
/// output), and the translation–tilt blocks vanish (< 1e-8).
#[test]
fn tilt_coefficients_in_the_short_bearing_limit() {
    let s = Settings { circumferential: 361, axial: 31, pressure_tolerance: 1e-10, load_tolerance: 1e-9, ..Settings::default() };
    let tilt_of = |k: [[f64; 2]; 2], c: [[f64; 2]; 2]| {
        let omega = [[-c[0][1] / 2.0, c[0][0] / 2.0], [-c[1][1] / 2.0, c[1][0] / 2.0]];
        let mut kt = [[0.0; 2]; 2];
        let mut ct = [[0.0; 2]; 2];
        for i in 0..2 {
            for j in 0..2 {
                kt[i][j] = (2.0 * k[i][j] - omega[i][j]) / 60.0;
                ct[i][j] = c[i][j] / 60.0;
            }
        }
        (kt, ct)
    };
    let block = |m: &[[f64; 4]; 4], i0: usize, j0: usize| [[m[i0][j0], m[i0][j0 + 1]], [m[i0 + 1][j0], m[i0 + 1][j0 + 1]]];
    let mut previous = [None; 4];
    for ld in [0.2, 0.1, 0.05, 0.025] {
        for (ei, e) in [0.2, 0.4, 0.6, 0.8].into_iter().enumerate() {
            let b = Bearing::plain(ld);
            let mut ws = Workspace::new(&b, &s);
            let a = analyse(&b, &Operating::Eccentricity(e), &s, Some(&mut ws), None, false, &Silent).unwrap();
            let t = tilt_coefficients(&b, &a, &s, &mut ws, &Silent).unwrap();
            let (k, c) = t.dimensionless(a.load).unwrap();
            let (kt, ct) = (block(&k, 2, 2), block(&c, 2, 2));
            // against the closed forms, and against the relations applied to this solution's own
            // translation block (the finite-length effect on the relations alone)
            let (kr, cr) = short_bearing(e);
            let (ktr, ctr) = tilt_of(kr, cr);
            let (kts, cts) = tilt_of(block(&k, 0, 0), block(&c, 0, 0));
            let (ek, ec) = (max_err(&kt, &ktr), max_err(&ct, &ctr));
            let (eks, ecs) = (max_err(&kt, &kts), max_err(&ct, &cts));
            eprintln!("L/D {ld} eps {e}: K_MΓ {kt:?} closed {ktr:?} err {ek:.4} (own {eks:.4}); C_MΓ {ct:?} closed {ctr:?} err {ec:.4} (own {ecs:.4})");
            let largest = k.iter().flatten().fold(0.0f64, |m, v| m.max(v.abs()));
            for (i, j) in [(0, 2), (0, 3), (1, 2), (1, 3), (2, 0), (2, 1), (3, 0), (3, 1)] {
                assert!(k[i][j].abs() < 1e-8 * largest, "K[{i}][{j}] = {}", k[i][j]);
            }
            // the finite-length effect shrinks with every halving of L/D (at ε 0.8, C: 16.5 %,
            // 6.8 %, 3.5 %, 0.85 %), and is below 1 % of each block's largest entry at L/D 0.025
            let worst = ek.max(ec);
            if let Some(p) = previous[ei] {
                assert!(worst < p, "L/D {ld} eps {e}: {worst} not below {p} at twice the L/D");
            }
            previous[ei] = Some(worst);
            if ld == 0.025 {
                assert!(worst < 0.01, "L/D {ld} eps {e}: K err {ek}, C err {ec}");
            }
        }
    }
}

/// The coefficients at the default tolerances against the same equilibrium position solved
/// and linearised at a tight one (pressure 1e-12): the linear solves' tolerance moves every
/// coefficient by far less than the grid does (~1e-3 of the largest at 121×41, BENCHMARKS.md).
/// Plain L/D 0.5 at ε 0.5 and seed 002's misaligned profiled design, both load-balanced.
#[test]
fn coefficients_at_the_default_tolerance_match_a_tight_solve() {
    let cases = [
        (Bearing::plain(0.5), 0.5),
        (
            Bearing {
                misalignment: Misalignment { vertical: 0.56, horizontal: 0.56 },
                profile: Some(Profile { order: 2, height: 0.4, length_fraction: 0.2 }),
                ..Bearing::plain(1.25)
            },
            0.6,
        ),
    ];
    for (b, e) in cases {
        let s = Settings { circumferential: 121, axial: 41, ..Settings::default() };
        let w = analyse(&Bearing::plain(b.length_to_diameter), &Operating::Eccentricity(e), &s, None, None, false, &Silent).unwrap().load;
        let (a, c) = solve(&b, Operating::Load(w), &s);
        let tight = Settings { pressure_tolerance: 1e-12, load_tolerance: 1e-10, ..s };
        let pos = Operating::Position { eccentricity: a.eccentricity, attitude: a.attitude };
        let (_, ct) = solve(&b, pos, &tight);
        let (ek, ec) = (max_err(&c.stiffness, &ct.stiffness), max_err(&c.damping, &ct.damping));
        eprintln!("L/D {}: K {:?} tight {:?}; error K {ek:.2e}, C {ec:.2e}; {:?}", b.length_to_diameter, c.stiffness, ct.stiffness, c.convergence);
        assert!(ek < 1e-5 && ec < 1e-5, "K {ek:e}, C {ec:e}");
        assert!(c.convergence.residual <= c.convergence.tolerance);
    }
}

/// The `bearing` kind's contract: `outputs: ["dynamic_coefficients"]` gives SI stiffness and
/// damping consistent with the dimensionless ones (K = K̄ W/c, C = C̄ W/(cω)).
#[test]
fn kind_reports_coefficients_in_si() {
    let spec = crate::in_process::example("bearing_coefficients");
    let r = crate::in_process::run("bearing", &spec).unwrap();
    let dc = &r["dynamic_coefficients"];
    let w = r["load"]["force"].as_f64().unwrap();
    let c = 75e-6;
    let omega = 3000.0 * 2.0 * PI / 60.0;
    for (name, nd) in [("kxx", "kxx"), ("kxy", "kxy"), ("kyx", "kyx"), ("kyy", "kyy")] {
        let si = dc["stiffness"][name].as_f64().unwrap();
        let kb = dc["stiffness_dimensionless"][nd].as_f64().unwrap();
        assert!((si - kb * w / c).abs() <= 1e-9 * si.abs().max(1.0), "{name}");
    }
    for name in ["cxx", "cxy", "cyx", "cyy"] {
        let si = dc["damping"][name].as_f64().unwrap();
        let cb = dc["damping_dimensionless"][name].as_f64().unwrap();
        assert!((si - cb * w / (c * omega)).abs() <= 1e-9 * si.abs().max(1.0), "{name}");
    }
    assert!((w - 5000.0).abs() < 5000.0 * 1e-5);
    assert!(dc["stiffness"]["kxx"].as_f64().unwrap() > 0.0);
}

/// The `bearing` kind's force and moment coefficients (`outputs: ["moment_coefficients"]`, the
/// example on seed 002's misaligned, profiled bearing): SI consistent with the dimensionless
/// (`K_ij = K̄_ij W/c · l_i l_j`, `C_ij = C̄_ij W/(cω) · l_i l_j`, `l = (1, 1, L, L)`), the
/// translations' block equal to `dynamic_coefficients`, the damping symmetric; refused in an
/// optimisation's base.
#[test]
fn kind_reports_moment_coefficients_in_si() {
    let spec = crate::in_process::example("bearing_moment_coefficients");
    let r = crate::in_process::run("bearing", &spec).unwrap();
    let m = &r["moment_coefficients"];
    let w = r["load"]["force"].as_f64().unwrap();
    let (c, length) = (1.175e-4, 0.08);
    let omega = 3000.0 * 2.0 * PI / 60.0;
    let l = [1.0, 1.0, length, length];
    let at = |block: &str, i: usize, j: usize| m[block][i][j].as_f64().unwrap();
    assert_eq!(m["coordinates"], serde_json::json!(["x", "y", "tilt_x", "tilt_y"]));
    for i in 0..4 {
        for j in 0..4 {
            let (k, kb) = (at("stiffness", i, j), at("stiffness_dimensionless", i, j));
            assert!((k - kb * w / c * l[i] * l[j]).abs() <= 1e-9 * k.abs(), "K[{i}][{j}]");
            let (d, db) = (at("damping", i, j), at("damping_dimensionless", i, j));
            assert!((d - db * w / (c * omega) * l[i] * l[j]).abs() <= 1e-9 * d.abs(), "C[{i}][{j}]");
            assert!((d - at("damping", j, i)).abs() <= 1e-6 * at("damping", 0, 0), "C[{i}][{j}] symmetric");
        }
    }
    let dc = &r["dynamic_coefficients"];
    for (n, (i, j)) in [("kxx", (0, 0)), ("kxy", (0, 1)), ("kyx", (1, 0)), ("kyy", (1, 1))] {
        assert_eq!(dc["stiffness"][n].as_f64().unwrap(), at("stiffness", i, j), "{n}");
    }
    // the tilts of a misaligned bearing couple to the force (seed 002's case: |K_FΓ| up to 16 %
    // of K̄xx in dimensionless terms)
    assert!(at("stiffness_dimensionless", 0, 2).abs() > 0.01 * at("stiffness_dimensionless", 0, 0));
    let mut opt = crate::in_process::example("seed002_taguchi_l9");
    opt["base"]["outputs"] = serde_json::json!(["moment_coefficients"]);
    let e = crate::in_process::run("bearing_optimisation", &opt).unwrap_err();
    assert!(format!("{e:?}").contains("moment_coefficients"), "{e:?}");
}

/// The heat balance closes: with κ = 0 and no housing the friction power equals
/// `ρ c_p (Q − Q_s/2)(T_2 − T_s)` (Raimondi & Boyd), the effective temperature is the mean of
/// inlet and outlet, the viscosity is the ISO VG 46 Walther law at it, and the checks compare
/// the result's own values.
#[test]
fn kind_heat_balance_closes() {
    let spec = crate::in_process::example("bearing_thermal");
    let r = crate::in_process::run("bearing", &spec).unwrap();
    let t = &r["thermal"];
    let g = |k: &str| t[k].as_f64().unwrap();
    let (rho, cp) = (870.0, 2000.0);
    let carried = rho * cp * (g("film_inflow") - 0.5 * g("side_flow")) * (g("outlet_temperature") - g("supply_temperature"));
    eprintln!("{t}");
    assert!((carried / g("power_loss") - 1.0).abs() < 1e-9);
    assert!((g("effective_temperature") - 0.5 * (g("inlet_temperature") + g("outlet_temperature"))).abs() <= 0.01);
    assert!(t["convergence"]["residual"].as_f64().unwrap() <= 0.01);
    // Walther through (40 °C, 46 mm²/s) and (100 °C, 6.8 mm²/s)
    let y = |nu: f64| ((nu + 0.7f64).log10()).log10();
    let b = (y(46.0) - y(6.8)) / (373.15f64.log10() - 313.15f64.log10());
    let a = y(46.0) + b * 313.15f64.log10();
    let nu = 10f64.powf(10f64.powf(a - b * g("effective_temperature").log10())) - 0.7;
    assert!((g("kinematic_viscosity") / nu - 1.0).abs() < 1e-9);
    assert!((r["power_loss"].as_f64().unwrap() / g("power_loss") - 1.0).abs() < 1e-9);
    let ch = &r["checks"];
    assert!((ch["min_film"]["value"].as_f64().unwrap() - r["min_film"].as_f64().unwrap()).abs() < 1e-15);
    assert!((ch["min_film"]["limit"].as_f64().unwrap() - 5e-6).abs() < 1e-15);
    assert!((ch["specific_load"]["value"].as_f64().unwrap() / (8000.0 / (0.1 * 0.04)) - 1.0).abs() < 1e-5);
    assert_eq!(ch["max_temperature"]["value"].as_f64().unwrap(), g("max_temperature"));
}

#[test]
fn thermal_spec_rules() {
    let mut spec = crate::in_process::example("bearing_thermal");
    spec["operating"]["viscosity"] = serde_json::json!(0.02);
    assert!(crate::in_process::run("bearing", &spec).is_err());
    let mut spec = crate::in_process::example("bearing_thermal");
    spec["load"] = serde_json::json!({"sommerfeld_number": 0.1});
    assert!(crate::in_process::run("bearing", &spec).is_err());
    let mut spec = crate::in_process::example("bearing_thermal");
    spec["thermal"]["lubricant"] = serde_json::json!({"iso_vg": 47});
    assert!(crate::in_process::run("bearing", &spec).is_err());
}

mod properties {
    use super::*;
    use proptest::prelude::*;
    use tribod::physics::SolveError;

    fn check(ld: f64, e: f64, mis: (f64, f64), nt: usize, nz: usize) -> Result<(), TestCaseError> {
        let b = Bearing { misalignment: Misalignment { vertical: mis.0, horizontal: mis.1 }, ..Bearing::plain(ld) };
        let s = Settings { circumferential: nt, axial: nz, ..Settings::default() };
        let mut ws = Workspace::new(&b, &s);
        let a = match analyse(&b, &Operating::Eccentricity(e), &s, Some(&mut ws), None, false, &Silent) {
            Ok(a) => a,
            Err(SolveError::Physical { .. }) => return Ok(()),
            Err(e) => return Err(TestCaseError::fail(format!("{e:?}"))),
        };
        match coefficients(&b, &a, &s, &mut ws, &Silent) {
            Ok(c) => {
                prop_assert!(c.stiffness.iter().chain(c.damping.iter()).flatten().all(|v| v.is_finite()));
                prop_assert!(c.convergence.residual <= c.convergence.tolerance * 10.0, "{:?}", c.convergence);
                let d = c.damping;
                // the squeeze film dissipates: the symmetric part of C is positive semi-definite
                prop_assert!(d[0][0] >= 0.0 && d[1][1] >= 0.0, "{d:?}");
                prop_assert!(d[0][0] * d[1][1] - 0.25 * (d[0][1] + d[1][0]).powi(2) >= -1e-9 * (d[0][0] * d[1][1]).abs(), "{d:?}");
                if let Some((k, cc)) = c.dimensionless(a.load) {
                    let st = stability(k, cc);
                    prop_assert!(st.whirl_ratio.is_finite() && st.equivalent_stiffness.is_finite());
                }
                // the translations and tilts: finite, the translations' block the same numbers,
                // the damping symmetric with a positive diagonal
                let t = tilt_coefficients(&b, &a, &s, &mut ws, &Silent).map_err(|e| TestCaseError::fail(format!("{e:?}")))?;
                prop_assert!(t.stiffness.iter().chain(t.damping.iter()).flatten().all(|v| v.is_finite()));
                let kmax = c.stiffness.iter().flatten().fold(0.0f64, |m, v| m.max(v.abs()));
                for i in 0..2 {
                    for j in 0..2 {
                        prop_assert!((t.stiffness[i][j] - c.stiffness[i][j]).abs() <= 1e-5 * kmax, "{:?} vs {:?}", t.stiffness, c.stiffness);
                    }
                }
                let largest = t.damping.iter().flatten().fold(0.0f64, |m, v| m.max(v.abs()));
                for i in 0..4 {
                    prop_assert!(t.damping[i][i] >= 0.0, "{:?}", t.damping);
                    for j in 0..4 {
                        prop_assert!((t.damping[i][j] - t.damping[j][i]).abs() <= 1e-5 * largest, "{:?}", t.damping);
                    }
                }
                Ok(())
            }
            Err(SolveError::NotConverged { .. }) => Err(TestCaseError::fail("coefficients did not converge")),
            Err(e) => Err(TestCaseError::fail(format!("{e:?}"))),
        }
    }

    proptest! {
        #![proptest_config(ProptestConfig { cases: 32, ..ProptestConfig::default() })]
        #[test]
        fn coefficients_finite_and_dissipative(ld in 0.1f64..3.0, e in 0.0f64..0.95, mis in prop::option::weighted(0.4, (-0.5f64..0.5, -0.5f64..0.5)), nt in 17usize..122, nz in 5usize..42) {
            check(ld, e, mis.unwrap_or((0.0, 0.0)), nt, nz)?;
        }
    }
}

/// Cost of the coefficients against the equilibrium (thread CPU is not available here: wall
/// time, best of 5). Not a pass/fail test: `cargo test --test it -- --ignored coefficients_cost
/// --nocapture` prints the table quoted in BENCHMARKS.md (test profile).
#[test]
#[ignore]
fn coefficients_cost() {
    use std::time::Instant;
    let best = |f: &mut dyn FnMut()| {
        let mut t = f64::INFINITY;
        for _ in 0..5 {
            let s = Instant::now();
            f();
            t = t.min(s.elapsed().as_secs_f64());
        }
        t
    };
    for (ld, nt, nz) in [(0.5, 41, 21), (0.5, 121, 41), (0.5, 241, 81), (1.0, 121, 41), (1.0, 361, 121)] {
        let b = Bearing::plain(ld);
        let s = Settings { circumferential: nt, axial: nz, ..Settings::default() };
        let w = analyse(&b, &Operating::Eccentricity(0.5), &s, None, None, false, &Silent).unwrap().load;
        let mut ws = Workspace::new(&b, &s);
        let mut a = None;
        let te = best(&mut || {
            ws = Workspace::new(&b, &s);
            a = Some(analyse(&b, &Operating::Load(w), &s, Some(&mut ws), None, false, &Silent).unwrap());
        });
        let a = a.unwrap();
        let tc = best(&mut || {
            coefficients(&b, &a, &s, &mut ws, &Silent).unwrap();
        });
        eprintln!("| {ld} | {nt}×{nz} | {:.2} | {:.2} | {:.2} |", te * 1e3, tc * 1e3, tc / te);
    }
}

/// Someya's *Journal-Bearing Databook* (Springer 1989), Table 1a: two-axial-groove bearing,
/// L/D = 0.5 — the rows as reproduced in the DTU course script "Tribology of Machine Elements
/// (41524): Journal bearing dynamics & stability analysis" (I. F. Santos, 2023; a MATLAB file in
/// the stored public code corpus). Columns: S = ηNLD/W (R/c)², ε, φ (deg), K̄xx, K̄xy, K̄yx,
/// K̄yy, C̄xx, C̄xy, C̄yx, C̄yy with x along the load (vertical) and y horizontal, K̄ = K c/W,
/// C̄ = C c ω/W — the frame and scaling of `dynamics` (y 90° ahead in rotation: the signs of
/// the cross terms agree with the short-bearing closed forms in this frame).
#[allow(clippy::approx_constant)] // C̄yy = 6.28 in the first row is the table's value, not 2π.
const SOMEYA_1A: [[f64; 11]; 7] = [
    [2.634, 0.165, 72.36, 1.61, 6.74, -3.01, 1.91, 13.36, 2.00, 2.00, 6.28],
    [1.656, 0.244, 65.85, 1.69, 5.06, -2.20, 1.95, 9.93, 2.15, 2.15, 4.80],
    [0.917, 0.372, 57.45, 2.12, 4.01, -1.30, 1.85, 7.70, 2.06, 2.06, 3.23],
    [0.580, 0.477, 51.01, 2.67, 3.70, -0.78, 1.75, 6.96, 1.94, 1.94, 2.40],
    [0.378, 0.570, 45.43, 3.33, 3.64, -0.43, 1.68, 6.76, 1.87, 1.87, 1.89],
    [0.244, 0.655, 40.25, 4.21, 3.74, -0.13, 1.64, 6.87, 1.82, 1.82, 1.54],
    [0.151, 0.734, 35.20, 5.48, 3.98, 0.15, 1.61, 7.26, 1.79, 1.79, 1.27],
];

/// The finite-bearing coefficients against Someya's table (L/D = 0.5, two axial grooves on the
/// horizontal plane, modelled as two ambient-pressure lines at θ = 90° and 270° without width;
/// the Databook's grooves have a finite arc, so the pressurised land is slightly shorter there).
/// The same rows with a single supply line at the largest film (the Raimondi–Boyd convention
/// of the rest of this file) are printed to show the effect of the film-start convention.
#[test]
fn someya_two_axial_groove_l_over_d_half() {
    let s = Settings { circumferential: 241, axial: 61, pressure_tolerance: 1e-9, load_tolerance: 1e-8, ..Settings::default() };
    let two = Bearing { supply: Supply::TwoGrooves(PI / 2.0), ..Bearing::plain(0.5) };
    let one = Bearing::plain(0.5);
    let (mut worst_e, mut worst_phi, mut worst_k, mut worst_c, mut worst_m) = (0.0f64, 0.0f64, 0.0f64, 0.0f64, 0.0f64);
    for row in SOMEYA_1A {
        let w = 1.0 / (6.0 * PI * row[0]);
        let kr = [[row[3], row[4]], [row[5], row[6]]];
        let cr = [[row[7], row[8]], [row[9], row[10]]];
        let (a, c) = solve(&two, Operating::Load(w), &s);
        let (k, d) = c.dimensionless(a.load).unwrap();
        let (a1, c1) = solve(&one, Operating::Load(w), &s);
        let (k1, d1) = c1.dimensionless(a1.load).unwrap();
        let (ek, ec) = (max_err(&k, &kr), max_err(&d, &cr));
        let m_ref = stability(kr, cr).critical_mass;
        let m = stability(k, d).critical_mass;
        let em = match (m, m_ref) {
            (Some(x), Some(y)) => (x / y - 1.0).abs(),
            _ => 0.0,
        };
        eprintln!(
            "S {:.3}: eps {:.4} ({}) phi {:.2} ({}) | K {:?} err {ek:.3} | C {:?} err {ec:.3} | Mc {m:?} ({m_ref:?}) | one groove: eps {:.4} phi {:.2} Kerr {:.3} Cerr {:.3}",
            row[0], a.eccentricity, row[1], a.attitude.to_degrees(), row[2], k, d,
            a1.eccentricity, a1.attitude.to_degrees(), max_err(&k1, &kr), max_err(&d1, &cr)
        );
        // measured (241×61): |Δε| ≤ 0.0051, φ 1.3–3.6° larger, K̄/C̄ within 2–8.4 % of the largest
        // coefficient from ε = 0.37 on and 13–20 % at ε = 0.17–0.24 (where the finite groove
        // arc of the Databook shortens the land most), critical mass within 13 %
        assert!((a.eccentricity - row[1]).abs() < 0.006, "eccentricity {} against {}", a.eccentricity, row[1]);
        assert!((a.attitude.to_degrees() - row[2]).abs() < 4.0, "attitude {} against {}", a.attitude.to_degrees(), row[2]);
        let lim = if row[1] >= 0.37 { 0.09 } else { 0.21 };
        assert!(ek < lim && ec < lim, "K err {ek}, C err {ec} (limit {lim})");
        assert!(em < 0.15, "critical mass {m:?} against {m_ref:?}");
        // the film-start convention: one supply line at the largest film is further off
        assert!(max_err(&k1, &kr) > ek && max_err(&d1, &cr) > ec);
        worst_e = worst_e.max((a.eccentricity - row[1]).abs());
        worst_phi = worst_phi.max((a.attitude.to_degrees() - row[2]).abs());
        worst_k = worst_k.max(ek);
        worst_c = worst_c.max(ec);
        worst_m = worst_m.max(em);
    }
    eprintln!("worst: eps {worst_e:.4}, phi {worst_phi:.2} deg, K {worst_k:.3}, C {worst_c:.3}, Mc {worst_m:.3}");
}
