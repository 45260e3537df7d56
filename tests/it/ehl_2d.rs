//! Validation of the 2-D (point and finite line contact) EHL solver `physics::ehl::twod`: the dry
//! Hertz limit, circular and elliptic films against Hamrock–Dowson and Nijenbanning–Venner–Moes,
//! a long straight roller against the 1-D line solution, grid convergence, and the crowned roller
//! of seed 000 at the cam nose.

use tribod::physics::contact::hertz_point;
use tribod::physics::ehl::formulas::nijenbanning_central_film;
use tribod::physics::ehl::twod::elastic::Deflection;
use tribod::physics::ehl::twod::{solve, Ehl2dInput, Ehl2dOptions, Geometry2d};
use tribod::physics::film::formulas::{ellipticity, hamrock_dowson_point};
use tribod::physics::lubricant::{DensityModel, Lubricant, ViscosityModel};
use tribod::physics::roller::Crown;
use tribod::physics::Silent;

/// Steel on steel: E' = 210e9/0.91 = 230.8 GPa.
pub const E_PRIME: f64 = 210e9 / 0.91;

pub fn oil(eta0: f64, alpha: f64) -> Lubricant {
    Lubricant { viscosity: eta0, pressure_viscosity: alpha, ..Lubricant::SEED000 }
}

fn barus_incompressible(eta0: f64, alpha: f64) -> Lubricant {
    Lubricant { viscosity_model: ViscosityModel::Barus, density_model: DensityModel::Incompressible, ..oil(eta0, alpha) }
}

pub fn point(load: f64, rx: f64, ry: f64, u: f64, lub: Lubricant) -> Ehl2dInput {
    Ehl2dInput { load, geometry: Geometry2d::Point { rx, ry }, effective_modulus: E_PRIME, entrainment_velocity: u, lubricant: lub, temperature: lub.reference_temperature }
}

pub fn opts(nx: usize, ny: usize) -> Ehl2dOptions {
    Ehl2dOptions { nx, ny, ..Default::default() }
}

pub fn rel(a: f64, b: f64) -> f64 {
    (a - b).abs() / b.abs()
}

/// The dry limit (issue 16): at a fixed load (F = 100 N on R = 10 mm: p0 = 1.37 GPa, a = 0.187 mm;
/// Roelands + Dowson–Higginson, η0 = 0.04 Pa·s, α = 2e-8 1/Pa) the entrainment speed falls
/// 1 → 0.3 → 0.1 m/s, so M = 303 → 748 → 1706 (L = 11.2 → 8.3 → 6.3), and the pressure tends to
/// Hertz's `p0 sqrt(1 − r²/a²)` (Johnson eq. 3.41): the distance `∫∫|p − p_Hertz| dA / F` falls
/// with M (measured on 97², ehl2d-9: 0.0298 at M = 748, 0.0198 at M = 1706, i.e. ∝ M^−0.5;
/// 0.0162 on 129² and 0.0127 at M = 2869 on 129²), the peak stays within 1 % of p0 (the pressure
/// spike shrinks with the film), the contact radius across the entrainment is a within 1.5 cells
/// and the load integral is F. The films are not asserted here: they are thinner than 97² resolves
/// at the larger M (their change from 49² is 9–36 %, hence `grid_tolerance` 1), the pressure is
/// what the limit is about (M = 748: ∫|p − p_Hertz|/F 0.0369 on 65², 0.0298 on 97²).
#[test]
fn ehl2d_dry_limit_is_hertz_for_a_circular_contact() {
    let hz = hertz_point(100.0, 0.01, 0.01, 0.5 * E_PRIME).unwrap();
    let (p0, a) = (hz.max_pressure, hz.semi_major);
    let mut last = (0.0, f64::INFINITY);
    let mut first = None;
    for u in [1.0, 0.3, 0.1] {
        let input = point(100.0, 0.01, 0.01, u, oil(0.04, 2e-8));
        let o = Ehl2dOptions { fields: true, grid_tolerance: 1.0, ..opts(97, 97) };
        let t = std::time::Instant::now();
        let s = solve(&input, &o, &Silent).unwrap();
        let f = s.fields.as_ref().unwrap();
        let nx = f.x.len();
        let (dx, dy) = (f.x[1] - f.x[0], f.y[1] - f.y[0]);
        let mut dist = 0.0;
        for (j, y) in f.y.iter().enumerate() {
            for (i, x) in f.x.iter().enumerate() {
                let hertz = p0 * (1.0 - (x * x + y * y) / (a * a)).max(0.0).sqrt();
                dist += (f.pressure[j * nx + i] - hertz).abs() * dx * dy;
            }
        }
        let dist = dist / 100.0;
        // Contact radius across the entrainment (no inlet/outlet distortion): the last node on the
        // line x = 0 with a pressure above 1 % of p0.
        let i0 = f.x.iter().position(|&x| x >= 0.0).unwrap();
        let edge = f.y.iter().enumerate().filter(|(j, _)| f.pressure[j * nx + i0] > 0.01 * p0).map(|(_, y)| *y).fold(0.0, f64::max);
        println!("u_m {u}: M {:.0} L {:.2} ∫|p − p_Hertz|/F {dist:.4} p_max/p0 {:.4} edge/a {:.4} (cell {:.4} a) h_c {:.3e} h_min {:.3e} grid error {:?} {} steps in {:.1?}", s.moes_m, s.moes_l, s.max_pressure.value / p0, edge / a, dy / a, s.central_film, s.min_film.value, s.grid_error, s.convergence.iterations, t.elapsed());
        assert!(rel(s.load, 100.0) < 1e-5, "load {}", s.load);
        assert!(rel(s.max_pressure.value, p0) < 0.01, "M {}: p_max {} vs p0 {p0}", s.moes_m, s.max_pressure.value);
        assert!((edge - a).abs() < 1.5 * dy, "M {}: contact radius {edge} vs {a}", s.moes_m);
        assert!(s.moes_m > 1.5 * last.0 && dist < 0.85 * last.1, "M {} distance {dist} after M {} distance {}", s.moes_m, last.0, last.1);
        first.get_or_insert((s.moes_m, dist));
        last = (s.moes_m, dist);
    }
    // The distance falls at least like M^−0.4 (measured −0.5) and is below 2.5 % of F at M ≈ 1700.
    let (m0, d0) = first.unwrap();
    let slope = (last.1 / d0).ln() / (last.0 / m0).ln();
    println!("∫|p − p_Hertz|/F ∝ M^{slope:.2}");
    assert!(slope < -0.4, "{slope}");
    assert!(last.1 < 0.025, "{}", last.1);
}

/// The near-dry case at a low L (≈ 0.45: η0 = 0.01 Pa·s, u_m = 2 mm/s, M ≈ 3000) with a short
/// inlet (2 a): p_max and the contact radius against Hertz.
#[test]
#[ignore = "issue 16: low-L near dry: at M ≈ 3000 (L ≈ 0.45) on 97² NotConverged, 3.2e-4 after 422 steps (ehl2d-8; 0.49 after 367 steps, 63 s, with the contact rows, session 34); this family (η0 = 0.01 Pa·s, inlet 2 a) does not converge even at M ≈ 95, L ≈ 1.4 (65², inlet 2 a: 8.4e-3 after 341 steps; 97², default domain: 7.0e-2 after 324 steps, 184 s; M ≈ 270: 4.9e-2; ehl2d-9): the failure is the low L, not the high M. The dry limit is shown at L ≈ 6–11 by ehl2d_dry_limit_is_hertz_for_a_circular_contact; at M ≈ 2870, L ≈ 5.3 the solver converges on 129² (23 steps, 60 s dev)"]
fn ehl2d_near_dry_isoviscous_circular_contact_converges() {
    // F = 100 N on R = 10 mm: p0 = 1.37 GPa, a = 0.187 mm; u_m = 2 mm/s: M ≈ 3000 (near dry).
    let lub = oil(0.01, 2e-8);
    let input = point(100.0, 0.01, 0.01, 0.002, lub);
    let o = Ehl2dOptions { fields: true, inlet: Some(2.0), outlet: Some(1.5), side: Some(1.5), ..opts(97, 97) };
    let t = std::time::Instant::now();
    let s = solve(&input, &o, &Silent).unwrap();
    let hz = hertz_point(100.0, 0.01, 0.01, 0.5 * E_PRIME).unwrap();
    println!("M {} pmax {} p0 {} a {} hc {} hmin {:?} {:?} in {:?}", s.moes_m, s.max_pressure.value, hz.max_pressure, hz.semi_major, s.central_film, s.min_film, s.convergence, t.elapsed());
    assert!(rel(s.max_pressure.value, hz.max_pressure) < 0.03, "{} vs {}", s.max_pressure.value, hz.max_pressure);
    // Contact radius across the entrainment (no inlet/outlet distortion): the last node on the
    // line x = 0 with a pressure above 1 % of p0, within one cell of the Hertz radius.
    let f = s.fields.as_ref().unwrap();
    let nx = f.x.len();
    let i0 = f.x.iter().position(|&x| x >= 0.0).unwrap();
    let dy = f.y[1] - f.y[0];
    let edge = f.y.iter().enumerate().filter(|(j, _)| f.pressure[j * nx + i0] > 0.01 * hz.max_pressure).map(|(_, y)| *y).fold(0.0, f64::max);
    println!("edge {edge} a {} dy {dy}", hz.semi_major);
    assert!((edge - hz.semi_major).abs() < 1.5 * dy, "contact radius {edge} vs {}", hz.semi_major);
}

/// The circular Barus case on `n`² (F = 100 N, R = 10 mm, u_m = 1 m/s, η0 = 0.04 Pa·s,
/// α = 2e-8 1/Pa, incompressible: the conditions of both formulas) against
/// Nijenbanning–Venner–Moes (central film) and Hamrock–Dowson (central, minimum), each within its
/// tolerance.
fn circular_barus_against_formulas(n: usize, nvm_tolerance: f64, hd_central_tolerance: f64, hd_min_tolerance: f64) {
    let lub = barus_incompressible(0.04, 2e-8);
    let input = point(100.0, 0.01, 0.01, 1.0, lub);
    let t = std::time::Instant::now();
    let s = solve(&input, &opts(n, n), &Silent).unwrap();
    let w = 100.0 / (E_PRIME * 1e-4);
    let u = 0.04 * 1.0 / (E_PRIME * 0.01);
    let (hd_c, hd_m) = hamrock_dowson_point(w, u, 2e-8 * E_PRIME, ellipticity(0.01, 0.01));
    let nvm = nijenbanning_central_film(100.0, 0.01, 0.01, E_PRIME, 1.0, 0.04, 2e-8);
    println!("{n}²: M {} L {} hc {} (HD {} NVM {}) hmin {:?} (HD {}) grid error {:?} {:?} in {:?}", s.moes_m, s.moes_l, s.central_film, hd_c * 0.01, nvm, s.min_film, hd_m * 0.01, s.grid_error, s.convergence, t.elapsed());
    assert!(rel(s.central_film, nvm) < nvm_tolerance, "central {} vs NVM {nvm}", s.central_film);
    assert!(rel(s.central_film, hd_c * 0.01) < hd_central_tolerance, "central {} vs HD {}", s.central_film, hd_c * 0.01);
    assert!(rel(s.min_film.value, hd_m * 0.01) < hd_min_tolerance, "min {} vs HD {}", s.min_film.value, hd_m * 0.01);
}

/// The circular Barus case on 65², where the solver accepts it without a half-grid check (its 33²
/// check solve does not converge). The 65² solution is the nested level of the checked 129² solve
/// below, which it matches to 2.3 % (ehl2d-9): central film 281.9 nm on 65², 270.9 on 97², 275.5
/// on 129²; 351 on 49² — the 49² level's x spacing (0.115 a) is under-resolved, which is why 97²
/// is refused (28.9 % from 49²), not the 97² solution (97×49 gives the same film as 97², the error
/// is along x). Measured on 65²: h_c +3.4 % against Nijenbanning–Venner–Moes (which states a few
/// percent against its own solutions), +19.1 % against Hamrock–Dowson; h_min −15.0 % against
/// Hamrock–Dowson (their formulas fit coarse-grid solutions; the gap is the one measured on every
/// grid from 65² to 129²: +14…+19 % central, −15…−19 % minimum). 10.5 s wall in the dev profile.
#[test]
fn ehl2d_circular_film_against_nijenbanning_on_65() {
    circular_barus_against_formulas(65, 0.05, 0.22, 0.2);
}

/// Measured (129², M ≈ 303, L ≈ 11.2, geometric face means; ehl2d-9): central 275.5 nm, +1.0 %
/// against the Nijenbanning transcription (272.7 nm) and +16.3 % against Hamrock–Dowson
/// (236.8 nm); minimum 111.5 nm, −17.9 % against Hamrock–Dowson's 135.7 nm. 97² (before the
/// resolution check): 270.9 nm, −0.7 % / +14.4 %, minimum 112.3 nm.
#[test]
#[ignore = "issue 16: passes on 129² but takes 45 s wall in the dev profile under load (177 Newton steps since ehl2d-12; 264 steps and 164 s before, mostly the θ continuation on each level; ehl2d-9): h_c 275.5 nm, +1.0 % against NVM, +16.3 % against HD, h_min −17.9 % against HD, 2.3 % from the 65² level. 97² is refused by the resolution check (28.9 % from 49², whose x spacing does not resolve the inlet); ehl2d_circular_film_against_nijenbanning_on_65 runs the 65² level"]
fn ehl2d_circular_film_against_hamrock_dowson_and_nijenbanning() {
    circular_barus_against_formulas(129, 0.03, 0.17, 0.2);
}

/// The elliptic contact on 65² (accepted without the half-grid check, as the circular 65² case:
/// its 33² level is 53 % off, `grid_tolerance` 1). Measured (session 33, dev, 107 Newton steps,
/// 14.6 s; since ehl2d-12's near field with the Poiseuille film terms 18 steps, 5.0 s, the films
/// equal to 3e-7): central 302.57 nm, −0.9 % against the Nijenbanning transcription (305.2 nm) and +5.9 %
/// against Hamrock–Dowson (285.7 nm); minimum 201.1 nm, −3.6 % against Hamrock–Dowson (208.7 nm) —
/// 2.5 % / 1.8 % below the 129² solution (310.2 / 204.8 nm, session 29), and the
/// circular case's pattern. This case converges on the kept-preconditioner policy 25 / 15; with
/// 15 / 8 it stalled at a residual of 4.9e-6 (ascent direction at one row of tiny diagonal,
/// BENCHMARKS.md issue 16, session 33), so the test also guards that path.
#[test]
fn ehl2d_elliptic_film_against_nijenbanning_on_65() {
    elliptic_against_formulas(65, 1.0);
}

#[test]
#[ignore = "issue 16: 271 s wall in the dev profile on 129² under load (225 Newton steps since ehl2d-12; 379–396 before, 441 s; 97² is refused by the resolution check, 7.4 % from 49²); ehl2d_elliptic_film_against_nijenbanning_on_65 runs the 65² case"]
fn ehl2d_elliptic_film_against_hamrock_dowson_and_nijenbanning() {
    elliptic_against_formulas(129, 0.05);
}

fn elliptic_against_formulas(n: usize, grid_tolerance: f64) {
    // R_x = 10 mm, R_y = 40 mm (the ellipse's major axis across the entrainment, k ≈ 2.4).
    let lub = barus_incompressible(0.04, 2e-8);
    let (rx, ry) = (0.01, 0.04);
    let input = point(200.0, rx, ry, 1.0, lub);
    let t = std::time::Instant::now();
    let s = solve(&input, &Ehl2dOptions { grid_tolerance, ..opts(n, n) }, &Silent).unwrap();
    let w = 200.0 / (E_PRIME * rx * rx);
    let u = 0.04 * 1.0 / (E_PRIME * rx);
    let (hd_c, hd_m) = hamrock_dowson_point(w, u, 2e-8 * E_PRIME, ellipticity(rx, ry));
    let nvm = nijenbanning_central_film(200.0, rx, ry, E_PRIME, 1.0, 0.04, 2e-8);
    println!("elliptic M {} L {} hc {} (HD {} NVM {}) hmin {:?} (HD {}) {:?} in {:?}", s.moes_m, s.moes_l, s.central_film, hd_c * rx, nvm, s.min_film, hd_m * rx, s.convergence, t.elapsed());
    // Measured (129², M ≈ 607, L ≈ 11.2, geometric face means; session 29): central 310.2 nm,
    // +1.6 % against the Nijenbanning transcription (305.2 nm) and +8.6 % against Hamrock–Dowson
    // (285.7 nm); minimum 204.8 nm, −1.9 % against Hamrock–Dowson (208.7 nm) — the circular case's
    // pattern (NVM −0.7 %, HD +14 %).
    assert!(rel(s.central_film, nvm) < 0.03, "central {} vs NVM {nvm}", s.central_film);
    assert!(rel(s.central_film, hd_c * rx) < 0.1, "central {} vs HD {}", s.central_film, hd_c * rx);
    assert!(rel(s.min_film.value, hd_m * rx) < 0.05, "min {} vs HD {}", s.min_film.value, hd_m * rx);
}

/// p0 ≈ 1.7 GPa on 129² (3.8 s CPU dev). On 65² the solve is refused (typed, 1.7 s): the side
/// lobes' minimum film changes by 49 % from 33². Before the film floor (issue 16, `ehl2d-8`)
/// Newton stalled on 65² at 2.4e-5 in 190 steps: the arithmetic-mean stage of the continuation
/// pinches the film at a side-lobe node and the fraction-to-boundary rule shrank the step 5× per
/// step.
#[test]
fn ehl2d_heavy_point_contact_converges_at_1_7_gpa() {
    // p0 ≈ 1.7 GPa circular (F = 190 N on R = 10 mm), Roelands + Dowson–Higginson, u_m = 0.5 m/s.
    let lub = oil(0.04, 2e-8);
    let input = point(190.0, 0.01, 0.01, 0.5, lub);
    let t = std::time::Instant::now();
    let s = solve(&input, &opts(129, 129), &Silent).unwrap();
    println!("heavy p0 {} pmax {:?} hc {} hmin {:?} {:?} in {:?}", s.hertz_pressure, s.max_pressure, s.central_film, s.min_film, s.convergence, t.elapsed());
    assert!(s.hertz_pressure > 1.65e9, "p0 {}", s.hertz_pressure);
    assert!(s.min_film.value < s.central_film);
    // The horseshoe: the minimum film sits in the side lobes, off the centre line.
    assert!(s.min_film.y.abs() > 0.3 * s.hertz_half_width, "{:?}", s.min_film);
}

/// A straight roller of `length` with the ends relieved over `relief` each by the radius `rx`
/// (the gap at the end face `relief²/(2 r_x)`). A sharp-edged straight roller has no positive-film
/// solution on this domain: its end faces (`P = 0`) deflect about half as much as the middle, so
/// the film there would be `≈ H_c − W_mid/2 < 0` — the edge singularity of a flat punch (issue 16,
/// `ehl2d-8`: Newton drove those films to zero and stalled).
fn straight_roller(rx: f64, length: f64, relief: f64) -> Geometry2d {
    Geometry2d::Finite { rx, crown: Crown { length, middle_length: length - 2.0 * relief, crown_height: 0.0, end_radius: rx, profile: Default::default() } }
}

/// The long straight roller of the two tests below (20 half-widths long, ends relieved over 2
/// half-widths): w' = 2e5 N/m on R = 10 mm, u_m = 1 m/s, Roelands/DH oil. Returns the input, R_x
/// and the load per length.
pub fn long_straight_roller() -> (Ehl2dInput, f64, f64) {
    let lub = oil(0.04, 2e-8);
    let (rx, w) = (0.01, 2.0e5);
    let hz = tribod::physics::contact::hertz_line(w, rx, 0.5 * E_PRIME);
    let length = 20.0 * hz.half_width;
    let geometry = straight_roller(rx, length, 2.0 * hz.half_width);
    let input = Ehl2dInput { load: w * length, geometry, effective_modulus: E_PRIME, entrainment_velocity: 1.0, lubricant: lub, temperature: lub.reference_temperature };
    (input, rx, w)
}

/// Options of the long straight roller's 129² solves: inlet 5 a, outlet 2 a, grid tolerance 0.1.
pub fn long_straight_roller_options() -> Ehl2dOptions {
    Ehl2dOptions { inlet: Some(5.0), outlet: Some(2.0), grid_tolerance: 0.1, ..opts(129, 129) }
}

/// The long straight roller's cold 129² solve and its warm start, computed once per test binary
/// (≈ 30 s dev; shared with `ehl_2d_transient`).
pub fn long_straight_roller_steady() -> &'static (tribod::physics::ehl::twod::Ehl2dSolution, tribod::physics::ehl::twod::Warm2d) {
    static STEADY: std::sync::OnceLock<(tribod::physics::ehl::twod::Ehl2dSolution, tribod::physics::ehl::twod::Warm2d)> = std::sync::OnceLock::new();
    STEADY.get_or_init(|| {
        let (input, _, _) = long_straight_roller();
        tribod::physics::ehl::twod::solve_from(&input, &long_straight_roller_options(), None, &Silent).unwrap()
    })
}

/// The 1-D line contact of the long roller's mid-section at load per length `w` (N/m).
pub fn line_section(rx: f64, w: f64) -> tribod::physics::ehl::EhlInput<'static> {
    let lub = long_straight_roller().0.lubricant;
    tribod::physics::ehl::EhlInput {
        load_per_length: w,
        reduced_radius: rx,
        effective_modulus: E_PRIME,
        entrainment_velocity: 1.0,
        sliding_velocity: 0.0,
        lubricant: lub,
        temperature: lub.reference_temperature,
        rheology: tribod::physics::ehl::Rheology::default(),
        transient: None,
        warm_start: None,
        asperity: None,
    }
}

/// The 1-D solver's options for [`line_section`]: 512 nodes, the 2-D domain's inlet and outlet.
pub fn line_options() -> tribod::physics::ehl::EhlOptions {
    tribod::physics::ehl::EhlOptions { nodes: 512, inlet: Some(5.0), outlet: Some(2.0), ..Default::default() }
}

/// The mid-section of a long straight roller (20 half-widths, ends relieved over 2 half-widths)
/// against the 1-D line solution at the same load per length. 129×129 (cells 0.055 a × 0.156 a;
/// on 129×65 with a 40 a roller, cells 11× longer across than along, GMRES with the near-field
/// preconditioner does not reach its tolerance in 160 iterations). The grid tolerance is 0.1: the
/// minimum film, at the relieved ends, changes by 24 % from 65×65 (central film 3.5 %).
/// Measured (session 30): h_c 277.47 nm against 279.83 nm (1-D, 512 nodes), −0.84 %; the peak
/// pressure 1.23 GPa at y = ±1.23 mm, where the end relief begins. No coarse level passes the
/// resolution check (the y spacing); the cold start fails its 15-step trial on 129² and the solve
/// goes through 65² (session 34): 59 Newton steps, 29.8 s wall dev (140 steps cold, ehl2d-13).
#[test]
fn ehl2d_long_straight_roller_mid_section_matches_the_line_solution() {
    use tribod::physics::ehl::solve as solve_1d;
    let (_, rx, w) = long_straight_roller();
    let t = std::time::Instant::now();
    let s = &long_straight_roller_steady().0;
    let l1 = solve_1d(&line_section(rx, w), &line_options(), &Silent).unwrap();
    println!("roller hc {} vs 1-D {} ; hmin(centre line) ; pmax {:?} vs {} ; {:?} in {:?}", s.central_film, l1.central_film, s.max_pressure, l1.max_pressure, s.convergence, t.elapsed());
    assert!(rel(s.central_film, l1.central_film) < 0.01, "{} vs {}", s.central_film, l1.central_film);
}

/// Probe (development aid, issue 16): the long straight roller of
/// [`ehl2d_long_straight_roller_mid_section_matches_the_line_solution`] on 65² with grid
/// tolerance 1, for the Newton step counts of its θ continuation (`ehl2d-12`: 107 steps).
#[test]
#[ignore = "probe: Newton steps of the long roller on 65² (issue 16), not a check"]
fn probe_long_straight_roller_on_65() {
    let (input, _, _) = long_straight_roller();
    let o = Ehl2dOptions { inlet: Some(5.0), outlet: Some(2.0), grid_tolerance: 1.0, ..opts(65, 65) };
    let t = std::time::Instant::now();
    let s = solve(&input, &o, &Silent).unwrap();
    println!("roller 65 hc {:.7e} hmin {:.7e} pmax {:?} {:?} in {:?}", s.central_film, s.min_film.value, s.max_pressure, s.convergence, t.elapsed());
}

/// Grid convergence in each direction on the bench's circular contact (M ≈ 300, L ≈ 11, Roelands
/// + Dowson–Higginson; domain −3.5…1.5 a × ±2 a): the central film on 65, 129, 257 nodes along x
/// (33 across, which the film hardly feels) and on 33, 65, 129 across (65 along x). The observed
/// order `log2(|h1 − h2| / |h2 − h3|)` is that of a second-order scheme not yet asymptotic in x
/// (measured 1.5, the inlet's pressure rise into the contact is a few cells wide) and 2 across;
/// the last change is below 2 % (x) and 0.5 % (y).
#[test]
fn ehl2d_grid_convergence_in_both_directions() {
    let lub = oil(0.04, 2e-8);
    let input = Ehl2dInput { temperature: 313.0, ..point(100.0, 0.01, 0.01, 1.0, lub) };
    let hc = |nx: usize, ny: usize| {
        let o = Ehl2dOptions { inlet: Some(3.5), outlet: Some(1.5), side: Some(2.0), grid_tolerance: 1.0, ..opts(nx, ny) };
        let s = solve(&input, &o, &Silent).unwrap();
        println!("{nx}×{ny}: hc {:.5e} hmin {:.5e} grid error {:?}", s.central_film, s.min_film.value, s.grid_error);
        s.central_film
    };
    let x = [hc(65, 33), hc(129, 33), hc(257, 33)];
    let y = [x[0], hc(65, 65), hc(65, 129)];
    for (dir, h, orders, last) in [("x", x, 1.2..=3.0, 0.02), ("y", y, 1.5..=3.0, 0.005)] {
        let order = ((h[0] - h[1]).abs() / (h[1] - h[2]).abs()).log2();
        println!("{dir}: {h:?}, observed order {order:.2}, last change {:.2} %", 100.0 * rel(h[1], h[2]));
        assert!(orders.contains(&order), "{dir}: {h:?} order {order}");
        assert!(rel(h[1], h[2]) < last, "{dir}: {h:?}");
    }
}

/// A grid that does not resolve the film is refused, not reported as converged: the bench's
/// circular contact on 33² changes its films by more than the 5 % grid tolerance from 17²
/// (`SolveError::InvalidInput` naming `Ehl2dOptions.nx`), on 65² it is accepted with its
/// estimate below the tolerance.
#[test]
fn ehl2d_under_resolved_grid_is_refused() {
    let lub = oil(0.04, 2e-8);
    let input = Ehl2dInput { temperature: 313.0, ..point(100.0, 0.01, 0.01, 1.0, lub) };
    let o = |n: usize| Ehl2dOptions { inlet: Some(3.5), outlet: Some(1.5), side: Some(2.0), ..opts(n, n) };
    match solve(&input, &o(33), &Silent) {
        Err(tribod::physics::SolveError::InvalidInput { field, message }) => {
            println!("33²: {message}");
            assert_eq!(field, "Ehl2dOptions.nx");
            assert!(message.contains("does not resolve the film"), "{message}");
        }
        other => panic!("33² accepted: {other:?}"),
    }
    let s = solve(&input, &o(65), &Silent).unwrap();
    println!("65²: hc {} grid error {:?}", s.central_film, s.grid_error);
    let e = s.grid_error.expect("65² has the 33² level");
    assert!(e > 0.0 && e < 0.05, "{e}");
}

/// Seed 000 Table 1 roller (L = 14 mm, L1 = 12 mm, h_td = 4.5 µm, R_d = 12.5 mm; E' = 210 GPa,
/// η0 = 0.152 Pa·s, α = 2.2e-8 1/Pa, 313 K) at the cam nose (127°: F = 954 N, cam radius of
/// curvature 17.5 mm against the 25.5 mm roller, R = 10.37 mm; pure rolling, u_m = 2.77 m/s).
pub fn seed000_nose() -> Ehl2dInput {
    let crown = Crown::SEED000;
    Ehl2dInput { load: 954.0, geometry: Geometry2d::Finite { rx: 0.01037, crown }, effective_modulus: 2.1e11, entrainment_velocity: 2.77, lubricant: Lubricant::SEED000, temperature: 313.0 }
}

/// Largest pressure and smallest film of each row across the roller (`y`, p_max, h_min).
pub fn rows(f: &tribod::physics::ehl::twod::Fields2d) -> Vec<(f64, f64, f64)> {
    let nx = f.x.len();
    f.y.iter()
        .enumerate()
        .map(|(j, &y)| {
            let pm = (0..nx).map(|i| f.pressure[j * nx + i]).fold(0.0, f64::max);
            let hm = (0..nx).map(|i| f.film[j * nx + i]).fold(f64::INFINITY, f64::min);
            (y, pm, hm)
        })
        .collect()
}

/// Seed 000's picture at the nose — edge pressure peaks at the crown transitions `±L1/2` and the
/// minimum film towards the roller's ends — is what eq. 3 *as printed* gives
/// (`CrownProfile::Seed000Eq3`: the middle term `h_td (1 − (2y/L1)²)` relieves the centre by
/// 4.5 µm, so the transitions are the roller's highest points). Measured (dev, 65×129 / 65×257,
/// 19 Newton steps each, 1.9 / 2.9 s): edge peak 1.097 / 1.102 GPa at y = ±6.016 mm (the
/// transition at 6 mm, within one cell), the centre line's p_max 0.061 GPa (the slice model's
/// approach, 2.5 µm, is below the relief: the centre carries only the elastic spread), minimum
/// film 1.121 / 0.902 µm at |y| = 6.13 / 6.18 mm (just outside the transition; its value is not
/// resolved across, 20 % between the grids, the peak is to 0.5 %), central film 1.987 / 1.986 µm.
///
/// With the convex crown (the default reading of eq. 3, `h_td (2y/L1)²`) the same load does not
/// reach the transitions: the slice model's loaded half-length is below L1/2 and the 2-D pressure
/// within 0.15 mm of the transition is < 5 % of its peak (measured 3.7 %: 24 MPa, the elastic
/// spread of the middle's pressure); the peak and the minimum film sit on the middle (measured on
/// 65×129: p_max 0.647 GPa and h_min 1.453 µm on the centre line; an off-centre maximum of
/// 0.621 GPa at ±2.4 mm, grid-dependent; BENCHMARKS.md, issue 16).
#[test]
fn ehl2d_seed000_roller_at_the_nose() {
    use tribod::physics::roller::CrownProfile;
    let half1 = 0.5 * Crown::SEED000.middle_length;
    let mut peaks = Vec::new();
    for ny in [129, 257] {
        let mut input = seed000_nose();
        if let Geometry2d::Finite { crown, .. } = &mut input.geometry {
            crown.profile = CrownProfile::Seed000Eq3;
        }
        let t = std::time::Instant::now();
        // The minimum film at the transition's kink is not resolved across (65×257 moves it by
        // 24 % from 33×129, which the default check refuses): the peak and where things sit are
        // what is asserted.
        let s = solve(&input, &Ehl2dOptions { fields: true, grid_tolerance: 1.0, ..opts(65, ny) }, &Silent).unwrap();
        println!("eq. 3 as printed, 65×{ny}: hc {} hmin {:?} pmax {:?} edge {:?} grid error {:?} {:?} in {:?}", s.central_film, s.min_film, s.max_pressure, s.edge_pressure_peak, s.grid_error, s.convergence, t.elapsed());
        assert!(rel(s.load, 954.0) < 1e-5, "load {}", s.load);
        let cell = 0.014 / (ny - 1) as f64;
        let edge = s.edge_pressure_peak.expect("an edge peak");
        // The edge peak sits on the transition (within a cell) and is the contact's maximum.
        assert!((edge.y.abs() - half1).abs() <= cell, "{edge:?}");
        assert_eq!(edge.value, s.max_pressure.value);
        let r = rows(s.fields.as_ref().unwrap());
        let centre = r.iter().find(|(y, _, _)| y.abs() < 1e-9).unwrap();
        assert!(edge.value > 10.0 * centre.1, "edge {} vs centre {}", edge.value, centre.1);
        // The minimum film towards the ends, beside the transition, well below the centre's.
        assert!(s.min_film.y.abs() > 0.95 * half1, "{:?}", s.min_film);
        assert!(s.min_film.value < 0.7 * centre.2, "{:?} vs centre {}", s.min_film, centre.2);
        peaks.push(edge.value);
    }
    assert!(rel(peaks[0], peaks[1]) < 0.02, "{peaks:?}");

    // The convex crown at the same load: the contact does not reach the transitions.
    let input = seed000_nose();
    let Geometry2d::Finite { rx, crown } = input.geometry else { unreachable!() };
    let slices = crown.distribute(954.0, rx, 0.5 * 2.1e11);
    assert!(0.5 * slices.effective_length < half1, "{slices:?}");
    let s = solve(&input, &Ehl2dOptions { fields: true, ..opts(65, 129) }, &Silent).unwrap();
    let r = rows(s.fields.as_ref().unwrap());
    let at_transition = r.iter().filter(|(y, _, _)| (y.abs() - half1).abs() < 0.15e-3).map(|(_, p, _)| *p).fold(0.0, f64::max);
    println!("convex crown, 65×129: hc {} hmin {:?} pmax {:?} edge {:?}; p at the transition {at_transition}", s.central_film, s.min_film, s.max_pressure, s.edge_pressure_peak);
    println!("slice model: loaded half-length {} m", 0.5 * slices.effective_length);
    assert!(at_transition < 0.05 * s.max_pressure.value, "{at_transition} vs {:?}", s.max_pressure);
    assert!(s.max_pressure.y.abs() < 0.5 * half1 && s.min_film.y.abs() < 0.5 * half1, "{:?} {:?}", s.max_pressure, s.min_film);
}

/// The seed 000 nose case converges (65×129) with a positive film and the load carried.
#[test]
fn ehl2d_seed000_roller_at_the_nose_converges() {
    let input = seed000_nose();
    let s = solve(&input, &opts(65, 129), &Silent).unwrap();
    println!("seed000 nose: hc {} hmin {:?} pmax {:?} edge {:?} {:?}", s.central_film, s.min_film, s.max_pressure, s.edge_pressure_peak, s.convergence);
    assert!(s.min_film.value > 0.0 && s.min_film.value < s.central_film);
    assert!(rel(s.load, 954.0) < 1e-5, "load {}", s.load);
    // The slice model's peak load per length sets the pressure scale; the 2-D peak is near it.
    assert!(s.max_pressure.value > 0.9 * s.hertz_pressure && s.max_pressure.value < 1.5 * s.hertz_pressure, "{:?} vs {}", s.max_pressure, s.hertz_pressure);
}

/// Where the seed 000 cycle's central-film grid error comes from (issue 16, `ehl2d-16`): the
/// spacing along x alone. At the cycle's nose contact point (954.3 N, u_e = 2.098 m/s,
/// R_x = 10.372 mm; cold steady solves, `Ehl2dOptions` domain defaults: inlet 12 a, outlet
/// 2.12 a, a = 125.8 µm) the central film is 1.3338 µm on 65×129 and 65×257 alike (to 1e-4),
/// 1.3518 µm on 129×129 and 129×257 (+1.35 %), 1.3561 µm on 257×65: second order along x
/// (differences 1.80e-2, 4.3e-3 µm), so 65 nodes along x are −1.75 % off the extrapolated
/// 1.3575 µm. A shorter inlet starves the film (8 a: −0.4 … −1.2 % against 12 a at equal
/// spacing). Measured in BENCHMARKS.md ("The cycle's grid error along x").
#[test]
#[ignore = "issue 16: three cold 2-D solves up to 129×129, ≈ 30 s dev at load 4–8 (ehl2d-16)"]
fn ehl2d_seed000_cycle_nose_central_film_grid_error_is_along_x() {
    let input = Ehl2dInput { entrainment_velocity: 2.098, geometry: Geometry2d::Finite { rx: 0.010372, crown: Crown::SEED000 }, load: 954.3, ..seed000_nose() };
    let o = |nx, ny| Ehl2dOptions { tolerance: 1e-6, max_iterations: 60, ..opts(nx, ny) };
    let base = solve(&input, &o(65, 129), &Silent).unwrap();
    let across = solve(&input, &o(65, 257), &Silent).unwrap();
    let along = solve(&input, &o(129, 129), &Silent).unwrap();
    let (dy, dx) = (across.central_film / base.central_film - 1.0, along.central_film / base.central_film - 1.0);
    println!("nose h_c: 65×129 {:.5e}, 65×257 {:.5e} ({dy:+.2e}), 129×129 {:.5e} ({dx:+.2e})", base.central_film, across.central_film, along.central_film);
    // Measured: y refined +0 (to 1e-4), x refined +1.35 %.
    assert!(dy.abs() < 1e-3, "refining across moves the central film by {dy:.2e}");
    assert!(dx > 0.010 && dx < 0.017, "refining along x moves the central film by {dx:.2e}");
}

mod stability {
    use super::*;
    use proptest::prelude::*;
    use tribod::physics::SolveError;

    proptest! {
        #![proptest_config(ProptestConfig { cases: 10, .. ProptestConfig::default() })]
        /// Loads, speeds, ellipticity and crown geometries: converged with finite, positive
        /// films and non-negative pressures, or a typed error — never NaN.
        #[test]
        fn ehl2d_converges_or_fails_typed(
            load in 20.0f64..2000.0,
            u in 0.05f64..10.0,
            ratio in 0.2f64..5.0,
            finite in any::<bool>(),
            crown_um in 0.0f64..20.0,
            middle in 0.5f64..1.0,
        ) {
            let lub = oil(0.04, 2e-8);
            let geometry = if finite {
                Geometry2d::Finite { rx: 0.01, crown: Crown { length: 0.012, middle_length: 0.012 * middle, crown_height: crown_um * 1e-6, end_radius: 0.01, profile: Default::default() } }
            } else {
                Geometry2d::Point { rx: 0.01, ry: 0.01 * ratio }
            };
            let input = Ehl2dInput { load, geometry, effective_modulus: E_PRIME, entrainment_velocity: u, lubricant: lub, temperature: lub.reference_temperature };
            match solve(&input, &opts(33, if finite { 65 } else { 33 }), &Silent) {
                Ok(s) => {
                    prop_assert!(s.convergence.residual <= 1e-7);
                    for v in [s.central_film, s.min_film.value, s.max_pressure.value, s.load] {
                        prop_assert!(v.is_finite());
                    }
                    prop_assert!(s.min_film.value > 0.0 && s.max_pressure.value > 0.0);
                    prop_assert!((s.load / load - 1.0).abs() < 1e-5, "load {} vs {load}", s.load);
                }
                Err(SolveError::NotConverged { residual, .. }) => prop_assert!(!residual.is_nan()),
                Err(SolveError::Physical { .. }) => {}
                // The grid does not resolve the film (`twod::Ehl2dOptions::grid_tolerance`).
                Err(SolveError::InvalidInput { field, .. }) if field == "Ehl2dOptions.nx" => {}
                Err(e) => prop_assert!(false, "unexpected error {e}"),
            }
        }
    }
}

/// A converged 2-D solution (property tests): residual within the default tolerance, finite
/// scalars, a positive minimum film not above the central one, the load `load` (N) carried.
pub fn check_converged(s: &tribod::physics::ehl::twod::Ehl2dSolution, load: f64) -> Result<(), proptest::test_runner::TestCaseError> {
    use proptest::prop_assert;
    prop_assert!(s.convergence.residual <= 1e-7);
    for v in [s.central_film, s.min_film.value, s.max_pressure.value, s.load] {
        prop_assert!(v.is_finite());
    }
    prop_assert!(s.min_film.value > 0.0 && s.min_film.value <= s.central_film);
    prop_assert!((s.load / load - 1.0).abs() < 1e-5, "load {} vs {load}", s.load);
    Ok(())
}

/// A 2-D solve's failure the service reports (property tests): not converged with a residual
/// that is not NaN, a physical failure, or the resolution check's refusal naming the grid.
pub fn check_typed_failure(e: tribod::physics::SolveError) -> Result<(), proptest::test_runner::TestCaseError> {
    use proptest::{prop_assert, prop_assert_eq};
    use tribod::physics::SolveError;
    match e {
        SolveError::NotConverged { residual, .. } => prop_assert!(!residual.is_nan()),
        SolveError::Physical { .. } => {}
        SolveError::InvalidInput { field, .. } => prop_assert_eq!(field, "Ehl2dOptions.nx"),
        e => prop_assert!(false, "unexpected error {e}"),
    }
    Ok(())
}

mod loads {
    use super::*;
    use proptest::prelude::*;

    proptest! {
        #![proptest_config(ProptestConfig { cases: 6, .. ProptestConfig::default() })]
        /// A circular contact on 65² from light loads (0.5 N, p0 ≈ 0.24 GPa) to p0 ≈ 1.7 GPa
        /// (190 N; log-uniform; issue 16):
        /// converged with finite, positive films and the load carried, or a typed error — never
        /// NaN.
        #[test]
        fn ehl2d_point_light_to_1_7_gpa_converges_or_fails_typed(ln_load in 0.5f64.ln()..190.0f64.ln(), u in 0.1f64..2.0) {
            let load = ln_load.exp();
            let input = point(load, 0.01, 0.01, u, oil(0.04, 2e-8));
            match solve(&input, &opts(65, 65), &Silent) {
                Ok(s) => {
                    println!("F {load:.1} N u {u:.2}: p0 {:.3e} hc {:.4e} hmin {:.4e} in {} steps", s.hertz_pressure, s.central_film, s.min_film.value, s.convergence.iterations);
                    prop_assert!(s.hertz_pressure < 1.75e9);
                    check_converged(&s, load)?;
                }
                Err(e) => {
                    println!("F {load:.1} N u {u:.2}: {e}");
                    check_typed_failure(e)?;
                }
            }
        }
    }
}

/// DC-FFT deflection equals the direct double sum of its influence coefficients (the wrap-around
/// padding leaves no periodic images).
#[test]
fn ehl2d_dc_fft_equals_the_direct_sum() {
    let (nx, ny, dx, dy) = (13, 9, 0.3, 0.5);
    let mut d = Deflection::new(nx, ny, dx, dy, 0.7);
    let p: Vec<f64> = (0..nx * ny).map(|k| ((k * 37) % 11) as f64 - 3.0).collect();
    let mut out = vec![0.0; nx * ny];
    d.apply(&p, &mut out);
    for j in 0..ny {
        for i in 0..nx {
            let mut s = 0.0;
            for l in 0..ny {
                for k in 0..nx {
                    s += d.coefficient(i.abs_diff(k), j.abs_diff(l)) * p[l * nx + k];
                }
            }
            assert!((s - out[j * nx + i]).abs() < 1e-10 * s.abs().max(1.0), "{i},{j}: {s} vs {}", out[j * nx + i]);
        }
    }
}

/// Hertz (Johnson eq. 3.41): with the circular scaling `c = 2/π²` the pressure `sqrt(1 − r²)`
/// deflects the surface by `1 − r²/2` inside the contact, so the gap `H0 + r²/2 + W` is flat;
/// to 3e-3 on a 129² grid over [−2, 2]² (cell-constant pressure).
#[test]
fn ehl2d_dc_fft_hertz_pressure_flattens_the_gap() {
    let n = 129;
    let h = 4.0 / (n - 1) as f64;
    let c = 2.0 / (std::f64::consts::PI * std::f64::consts::PI);
    let mut d = Deflection::new(n, n, h, h, c);
    let xy = |k: usize| -2.0 + k as f64 * h;
    let p: Vec<f64> = (0..n * n).map(|k| (1.0 - xy(k % n).powi(2) - xy(k / n).powi(2)).max(0.0).sqrt()).collect();
    let mut w = vec![0.0; n * n];
    d.apply(&p, &mut w);
    let mut worst = 0.0f64;
    for k in 0..n * n {
        let r2 = xy(k % n).powi(2) + xy(k / n).powi(2);
        if r2 < 0.8 {
            worst = worst.max((w[k] - (1.0 - 0.5 * r2)).abs());
        }
    }
    println!("worst deviation {worst}");
    assert!(worst < 3e-3, "{worst}");
}

/// Nijenbanning–Venner–Moes tends to its elastic–piezoviscous asymptote at large M and L (where
/// `H_EP` is the smaller of the piezoviscous pair), and is continuous in λ.
#[test]
fn ehl2d_nijenbanning_formula_limits() {
    use tribod::physics::ehl::formulas::nijenbanning_central;
    let (m, l): (f64, f64) = (1e4, 25.0);
    let q: f64 = 1.0 + 0.63;
    let h_ep = 1.48 * q.powf(-7.0 / 20.0) * m.powf(-1.0 / 12.0) * l.powf(0.75);
    let h = nijenbanning_central(m, l, 1.0);
    println!("H {h} EP {h_ep}");
    assert!(h.is_finite() && h > 0.0);
    let a = nijenbanning_central(50.0, 10.0, 0.5);
    let b = nijenbanning_central(50.0, 10.0, 0.5 * (1.0 + 1e-6));
    assert!((a / b - 1.0).abs() < 1e-5);
}
