//! Transient steps of the 2-D EHL solver (`physics::ehl::twod::solve_transient`, issue 16
//! deliverable 1): the large-Δt limit is the steady solve, a small Δt freezes the film after a
//! load step and the steps relax to the new steady film, the long straight roller's mid-section
//! follows the 1-D transient line solution through the same load step, and a property test over
//! load jumps and time steps.

use crate::ehl_2d::{line_options, line_section, long_straight_roller, long_straight_roller_options, long_straight_roller_steady, oil, opts, point, rel};
use tribod::physics::ehl::twod::{solve_from, solve_transient, Ehl2dInput, Ehl2dOptions, Ehl2dSolution, Kept2d, Squeeze2d, Warm2d};
use tribod::physics::Silent;

/// The circular contact of these tests: R = 10 mm, u_m = 1 m/s, Roelands + Dowson–Higginson
/// (η0 = 0.04 Pa·s, α = 2e-8 1/Pa), at load `f` (N); 65², no half-grid check.
fn circular(f: f64) -> Ehl2dInput {
    point(f, 0.01, 0.01, 1.0, oil(0.04, 2e-8))
}

fn circular_options() -> Ehl2dOptions {
    Ehl2dOptions { grid_tolerance: 1.0, grid_check: false, ..opts(65, 65) }
}

/// The passage time `a/u_m` of a solution, s.
fn passage(s: &Ehl2dSolution, u: f64) -> f64 {
    s.hertz_half_width / u
}

/// One transient step from `previous` over `dt` (s).
fn step(input: &Ehl2dInput, o: &Ehl2dOptions, previous: &Warm2d, dt: f64, kept: &mut Kept2d) -> (Ehl2dSolution, Warm2d) {
    solve_transient(input, o, Squeeze2d { previous, time_step: dt }, None, None, kept, &Silent).unwrap()
}

/// The circular contact's steady solution at 100 N, shared by the tests below.
fn circular_steady() -> &'static (Ehl2dSolution, Warm2d) {
    static STEADY: std::sync::OnceLock<(Ehl2dSolution, Warm2d)> = std::sync::OnceLock::new();
    STEADY.get_or_init(|| solve_from(&circular(100.0), &circular_options(), None, &Silent).unwrap())
}

/// Δt → ∞ is the steady solve of the new load: after a +30 % load step, the step's films differ
/// from the steady ones by `O(1/ΔT)` (`ΔT = Δt u_m/a`, the squeeze term `κ = λ/ΔT` against the
/// wedge term). Measured (65², dev): 1.43e-4 (h_c) and 3.19e-4 (h_min) at ΔT = 1e3; asserted:
/// below 1e-4 at ΔT = 1e4, and ten times less than at 1e3 within a factor 2 (first order).
#[test]
fn ehl2d_transient_large_time_step_is_the_steady_solution() {
    let (s0, w0) = circular_steady();
    let o = circular_options();
    let (steady, _) = solve_from(&circular(130.0), &o, Some(w0), &Silent).unwrap();
    let mut errors = Vec::new();
    for passages in [1e3, 1e4] {
        let (s, _) = step(&circular(130.0), &o, w0, passages * passage(s0, 1.0), &mut Kept2d::default());
        let (dc, dm) = (rel(s.central_film, steady.central_film), rel(s.min_film.value, steady.min_film.value));
        println!("ΔT {passages:e}: h_c {:.7e} vs steady {:.7e} ({dc:.2e}), h_min {:.7e} vs {:.7e} ({dm:.2e}); {:?}, {:?} sub-steps; steady {:?}", s.central_film, steady.central_film, s.min_film.value, steady.min_film.value, s.convergence, s.substeps, steady.convergence);
        assert_eq!(s.substeps, Some(1));
        errors.push((dc, dm));
    }
    let ((c3, m3), (c4, m4)) = (errors[0], errors[1]);
    assert!(c4 < 1e-4 && m4 < 1e-4, "ΔT 1e4: h_c {c4:e}, h_min {m4:e}");
    for ratio in [c3 / c4, m3 / m4] {
        assert!((5.0..20.0).contains(&ratio), "{errors:?}");
    }
    // The resolution check (`grid_check`) of a step is the check solve of the same step on 33²:
    // at ΔT = 1e4 its estimate is the steady one's.
    let checked = Ehl2dOptions { grid_check: true, ..o };
    let (steady, _) = solve_from(&circular(130.0), &checked, Some(w0), &Silent).unwrap();
    let (s, _) = step(&circular(130.0), &checked, w0, 1e4 * passage(s0, 1.0), &mut Kept2d::default());
    println!("grid error: steady {:?}, step {:?}", steady.grid_error, s.grid_error);
    let (e_steady, e_step) = (steady.grid_error.unwrap(), s.grid_error.unwrap());
    assert!((e_step - e_steady).abs() < 1e-3 * e_steady, "{e_step} vs {e_steady}");
}

/// After a +30 % load step a step of 0.01 passage times keeps the central film within 1 % of the
/// previous one (the squeeze term resists; measured −0.36 %). Steps of 0.5 passage times then
/// relax it to the new steady film, not monotonically: the central film first rises above the old
/// one (to 2.2 times the old film's distance from the new steady one at t = 1–1.5 a/u_m, measured)
/// — the 1-D transient line solution does the same through the same load step
/// (`ehl2d_transient_long_roller_follows_the_line_solution`: 279.8 → 278.2 → 288.3 → 274.2 nm
/// at 0.05, 0.25, 1.25, 6.25 a/u_m) — and from there decays geometrically, by 0.51, 0.47, 0.46 per step
/// (backward Euler's `1/(1 + Δt/τ)`: a time constant `τ ≈ 0.44 a/u_m`). Asserted: the
/// overshoot peak 1.5–3, a monotone decay after it with ratios 0.35–0.6 per step, and a distance
/// below 0.15 after 4 a/u_m.
#[test]
fn ehl2d_transient_small_time_step_freezes_the_film_and_relaxes_to_steady() {
    let (s0, w0) = circular_steady();
    let o = circular_options();
    let input = circular(130.0);
    let (steady, _) = solve_from(&input, &o, Some(w0), &Silent).unwrap();
    let tp = passage(s0, 1.0);
    let mut kept = Kept2d::default();
    let (frozen, _) = step(&input, &o, w0, 0.01 * tp, &mut kept);
    println!("Δt 0.01 a/u: h_c {:.5e} (previous {:.5e}, new steady {:.5e})", frozen.central_film, s0.central_film, steady.central_film);
    assert!(rel(frozen.central_film, s0.central_film) < 0.01);
    let mut h = vec![s0.central_film];
    let mut w = w0.clone();
    for _ in 0..8 {
        let (s, next) = step(&input, &o, &w, 0.5 * tp, &mut kept);
        h.push(s.central_film);
        w = next;
    }
    let gap: Vec<f64> = h.iter().map(|hk| (hk - steady.central_film) / (s0.central_film - steady.central_film)).collect();
    println!("Δt 0.5 a/u: h_c {h:?}; relative distance to the new steady film {gap:?}");
    let peak = (0..gap.len()).max_by(|&a, &b| gap[a].total_cmp(&gap[b])).unwrap();
    assert!((1.5..3.0).contains(&gap[peak]), "{gap:?}");
    for k in peak + 1..gap.len() {
        assert!(gap[k] > 0.0 && gap[k] < gap[k - 1], "{gap:?}");
    }
    for k in gap.len() - 3..gap.len() {
        assert!((0.35..0.6).contains(&(gap[k] / gap[k - 1])), "{gap:?}");
    }
    assert!(gap[gap.len() - 1] < 0.15, "{gap:?}");
}

/// The long straight roller (`ehl_2d::long_straight_roller`, 129²) through a +30 % load step
/// and time steps of 0.05, 0.2, 1 and 5 passage times, against the 1-D transient line solution
/// (512 nodes, `physics::ehl::Transient`) at the same load per length and time steps: the
/// mid-section's central film follows the line solution's within the steady agreement
/// (−0.84 %) plus a margin. Measured (dev, session 35): −0.78, −0.80, −1.23, −1.20 % at
/// 0.05, 0.25, 1.25, 6.25 a/u_m (the film's rise and fall of 288.3/274.2 nm followed within
/// 0.4 points of the steady offset; 4–10 Newton steps per step, no sub-steps); asserted: within
/// 1.5 % at every step (the steady offset, the 129² grid's, plus 0.66 points for the moving film's).
#[test]
fn ehl2d_transient_long_roller_follows_the_line_solution() {
    use tribod::physics::ehl::{solve as solve_1d, Transient};
    let (input, rx, w) = long_straight_roller();
    let (s0, w0) = long_straight_roller_steady();
    let o = Ehl2dOptions { grid_check: false, ..long_straight_roller_options() };
    let t = std::time::Instant::now();
    let l0 = solve_1d(&line_section(rx, w), &line_options(), &Silent).unwrap();
    let stepped = Ehl2dInput { load: 1.3 * input.load, ..input };
    let tp = passage(s0, 1.0);
    let (mut warm, mut state) = (w0.clone(), l0.state.clone());
    let mut kept = Kept2d::default();
    let mut worst = rel(s0.central_film, l0.central_film);
    println!("steady: h_c {:.5e} vs 1-D {:.5e}", s0.central_film, l0.central_film);
    for dt in [0.05, 0.2, 1.0, 5.0].map(|f| f * tp) {
        let (s, next) = step(&stepped, &o, &warm, dt, &mut kept);
        let mut line = line_section(rx, 1.3 * w);
        line.transient = Some(Transient { previous: &state, time_step: dt });
        let l = solve_1d(&line, &line_options(), &Silent).unwrap();
        let d = rel(s.central_film, l.central_film);
        println!("Δt {:.3e} s: h_c {:.5e} vs 1-D {:.5e} ({:+.2} %), {} Newton steps, {:?} sub-steps", dt, s.central_film, l.central_film, 100.0 * (s.central_film / l.central_film - 1.0), s.convergence.iterations, s.substeps);
        worst = worst.max(d);
        warm = next;
        state = l.state;
    }
    println!("the steps and the 1-D solves (the shared cold solve not counted) in {:?}", t.elapsed());
    assert!(worst < 0.015, "largest difference {worst}");
}

/// Seed 003 Figs. 4–6 (issue 42 item 2), a probe (the CI runs the same on 49×65: *lib*
/// `seed003_figs_4_6_squeeze_thickens_the_film_and_raises_the_edge_spike`): a prescribed
/// approach (squeeze) velocity on the long straight roller (finite line, ends relieved over 2 a; 129², the shared steady solve). The
/// 2-D solver takes squeeze only as history (`Squeeze2d`: a previous state and a time step); a
/// prescribed uniform approach `v` is the fixed point `ρ̄h_prev = ρ̄h + v Δt` (the previous
/// level's `Warm2d.mass` set from the new solution's), so the backward-Euler term is `−v` at
/// every node (Δt = 5 passage times; the fixed point settles to 1e-4 in h_c within 5 solves).
/// Paper: at the same load more squeeze gives a thicker film and larger edge spikes. Measured
/// (dev, 5.6 min with the shared steady solve): steady h_c 277.5 nm, h_min 110.9 nm, edge peak
/// 1.226 GPa; v = 1 mm/s: 421.8 nm, 205.0 nm, 1.247 GPa; v = 3 mm/s: 680.5 nm, 282.4 nm,
/// 2.41 GPa — the paper's direction for both (asserted). Ignored: far over the debug budget.
#[test]
#[ignore = "probe: seed 003 Figs. 4-6 with a prescribed squeeze velocity on the long roller (issue 42 item 2), 5.6 min dev"]
fn probe_seed003_prescribed_squeeze_on_the_long_roller() {
    let (input, _, _) = long_straight_roller();
    let (s0, w0) = long_straight_roller_steady();
    let o = Ehl2dOptions { grid_check: false, ..long_straight_roller_options() };
    let dt = 5.0 * passage(s0, 1.0);
    let mut kept = Kept2d::default();
    let edge = |s: &Ehl2dSolution| s.edge_pressure_peak.as_ref().map_or(f64::NAN, |e| e.value);
    println!("steady: h_c {:.5e} m, h_min {:.5e} m, p_max {:.4e} Pa, edge peak {:.4e} Pa", s0.central_film, s0.min_film.value, s0.max_pressure.value, edge(s0));
    let mut films = vec![(s0.central_film, s0.min_film.value, edge(s0))];
    for v in [1e-3, 3e-3] {
        let mut prev = w0.clone();
        let mut mass = w0.mass.clone();
        let mut last = s0.central_film;
        for it in 0..8 {
            prev.mass = mass.iter().map(|m| m + v * dt).collect();
            let (s, next) = solve_transient(&input, &o, Squeeze2d { previous: &prev, time_step: dt }, Some(&prev), None, &mut kept, &Silent).unwrap();
            println!(
                "v {v:.0e} m/s, iteration {it}: h_c {:.5e} m, h_min {:.5e} m, p_max {:.4e} Pa, edge peak {:.4e} Pa, {} Newton steps",
                s.central_film, s.min_film.value, s.max_pressure.value, edge(&s), s.convergence.iterations
            );
            mass = next.mass;
            let settled = rel(s.central_film, last) < 1e-4;
            last = s.central_film;
            if settled || it == 7 {
                assert!(settled, "the fixed point did not settle: {last}");
                films.push((s.central_film, s.min_film.value, edge(&s)));
                break;
            }
        }
    }
    for w in films.windows(2) {
        assert!(w[1].0 > w[0].0 && w[1].1 > w[0].1, "thicker with squeeze: {films:?}");
        assert!(w[1].2 > w[0].2, "edge spike grows with squeeze: {films:?}");
    }
}

mod stability {
    use super::*;
    use crate::ehl_2d::{check_converged, check_typed_failure};
    use proptest::prelude::*;

    proptest! {
        #![proptest_config(ProptestConfig { cases: 4, .. ProptestConfig::default() })]
        /// Load jumps ×0.5…×2 and time steps 0.01…1000 passage times from the circular contact's
        /// steady solution: converged with finite, positive films and the load carried, or a
        /// typed error — never NaN.
        #[test]
        fn ehl2d_transient_step_converges_or_fails_typed(jump in 0.5f64..2.0, log_dt in -2.0f64..3.0) {
            let (s0, w0) = circular_steady();
            let dt = 10f64.powf(log_dt) * passage(s0, 1.0);
            let input = circular(100.0 * jump);
            let squeeze = Squeeze2d { previous: w0, time_step: dt };
            match solve_transient(&input, &circular_options(), squeeze, None, None, &mut Kept2d::default(), &Silent) {
                Ok((s, next)) => {
                    println!("×{jump:.2}, Δt {:.1e} a/u: h_c {:.4e} h_min {:.4e}, {} steps, {:?} sub-steps", 10f64.powf(log_dt), s.central_film, s.min_film.value, s.convergence.iterations, s.substeps);
                    check_converged(&s, input.load)?;
                    prop_assert!(next.mass.iter().all(|m| m.is_finite() && *m > 0.0));
                }
                Err(e) => {
                    println!("×{jump:.2}, Δt {:.1e} a/u: {e}", 10f64.powf(log_dt));
                    check_typed_failure(e)?;
                }
            }
        }
    }
}

/// A time step that is not finite and positive, and a previous level without its mass per area
/// or of the other contact kind, are refused naming the field.
#[test]
fn ehl2d_transient_inputs_are_validated() {
    use tribod::physics::SolveError;
    let (_, w0) = circular_steady();
    let o = circular_options();
    let refused = |input: &Ehl2dInput, previous: &Warm2d, dt: f64| match solve_transient(input, &o, Squeeze2d { previous, time_step: dt }, None, None, &mut Kept2d::default(), &Silent) {
        Err(SolveError::InvalidInput { field, .. }) => field,
        other => panic!("accepted: {other:?}"),
    };
    for dt in [0.0, -1e-6, f64::NAN, f64::INFINITY] {
        assert_eq!(refused(&circular(100.0), w0, dt), "Squeeze2d.time_step");
    }
    let empty = Warm2d { mass: Vec::new(), ..w0.clone() };
    assert_eq!(refused(&circular(100.0), &empty, 1e-6), "Squeeze2d.previous");
    let (roller, _, _) = long_straight_roller();
    assert_eq!(refused(&roller, w0, 1e-6), "Squeeze2d.previous");
}

/// Probe (development aid, `BENCHMARKS.md` issue 16, `ehl2d-14`): Newton steps, GMRES iterations
/// and factorisations of a warm steady solve and of transient steps at several Δt, the circular
/// contact's +30 % load step on 65² (no half-grid check). Counts are process-wide: run alone
/// (`cargo test --test it probe_transient_work -- --ignored --nocapture --test-threads 1`).
#[test]
#[ignore = "probe: counted work of transient steps (issue 16), not a check"]
fn probe_transient_work() {
    use std::sync::atomic::Ordering::Relaxed;
    use tribod::physics::film::work::{FINITE_FACTORISATIONS, FINITE_GMRES_ITERATIONS};
    let (s0, w0) = circular_steady();
    let o = circular_options();
    let input = circular(130.0);
    let counted = |what: &str, run: &dyn Fn() -> Ehl2dSolution| {
        let (g, f) = (FINITE_GMRES_ITERATIONS.load(Relaxed), FINITE_FACTORISATIONS.load(Relaxed));
        let s = run();
        println!("{what}: {} Newton steps, {} GMRES iterations, {} factorisations, {:?} sub-steps, h_c {:.5e}", s.convergence.iterations, FINITE_GMRES_ITERATIONS.load(Relaxed) - g, FINITE_FACTORISATIONS.load(Relaxed) - f, s.substeps, s.central_film);
    };
    counted("warm steady", &|| solve_from(&input, &o, Some(w0), &Silent).unwrap().0);
    for passages in [0.01, 0.1, 0.5, 1.0, 10.0, 1e3] {
        counted(&format!("transient Δt {passages} a/u"), &|| step(&input, &o, w0, passages * passage(s0, 1.0), &mut Kept2d::default()).0);
    }
}

/// The sub-step fallback: a load drop to half in 0.1 a/u_m with Newton capped at 2 steps per
/// stage does not converge as one step but as four of Δt/4 (measured, dev: 213 Newton steps in
/// all, failed attempts included), and the film is the whole step's (cap 5: one step, 33 Newton
/// steps) up to the time discretisation: 208.288 against 208.253 nm (+0.017 %, backward Euler's
/// first-order error). Asserted: 4 sub-steps, within 0.1 %. (The case is chosen by the cap: a
/// better Newton may converge it whole; then pick a smaller cap. The cap 3 split it in two until
/// the single-precision near-field factor of issue 46, which converges it whole in 36 steps.)
#[test]
fn ehl2d_transient_failed_step_is_split_into_sub_steps() {
    let (s0, w0) = circular_steady();
    let input = circular(50.0);
    let squeeze = Squeeze2d { previous: w0, time_step: 0.1 * passage(s0, 1.0) };
    let capped = |cap: u32| solve_transient(&input, &Ehl2dOptions { max_iterations: cap, ..circular_options() }, squeeze, None, None, &mut Kept2d::default(), &Silent).unwrap().0;
    let (split, whole) = (capped(2), capped(5));
    println!("cap 2: {:?} sub-steps, {} Newton steps, h_c {:.6e}; cap 5: {:?}, {}, h_c {:.6e}", split.substeps, split.convergence.iterations, split.central_film, whole.substeps, whole.convergence.iterations, whole.central_film);
    assert_eq!((split.substeps, whole.substeps), (Some(4), Some(1)));
    assert!(rel(split.central_film, whole.central_film) < 1e-3);
}

/// The previous level is mapped by physical position also through a reversal of the entrainment
/// (`Warm2d::sign`; the solver's frame is mirrored for `u_m < 0`): a step of 0.01 a/u_m after the
/// speed flips from +1 to −1 m/s keeps the old film, its minimum in the old exit at x > 0 (the
/// steady solve at −1 m/s has it at x < 0, mirrored).
#[test]
fn ehl2d_transient_step_through_a_reversal_keeps_the_film_in_place() {
    let (s0, w0) = circular_steady();
    let o = circular_options();
    let reversed = Ehl2dInput { entrainment_velocity: -1.0, ..circular(100.0) };
    let (steady, _) = solve_from(&reversed, &o, None, &Silent).unwrap();
    let (s, next) = step(&reversed, &o, w0, 0.01 * passage(s0, 1.0), &mut Kept2d::default());
    println!("min film before {:?}, after the flip {:?}, steady reversed {:?}; h_c {:.5e} → {:.5e}", s0.min_film, s.min_film, steady.min_film, s0.central_film, s.central_film);
    assert!(s0.min_film.x > 0.0 && steady.min_film.x < 0.0);
    assert!(s.min_film.x > 0.0, "{:?}", s.min_film);
    assert!(rel(s.central_film, s0.central_film) < 0.01);
    assert_eq!((w0.sign, next.sign), (1.0, -1.0));
}
