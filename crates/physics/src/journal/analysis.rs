//! One bearing analysis: load balance over nested grids, then the performance figures.
//!
//! Conventions (dimensionless, seed 002): `P = p (c/R)² / (6ηω)`, `H = h/c`, `Z = z/L`,
//! `W̄ = w (c/R)² / (6ηωRL)`, Sommerfeld number `S = (R/c)² μN/P_avg = 1/(6π W̄)` with
//! `P_avg = w/(2RL)`. Angles as in [`super::film`]: `θ` from the unloaded side (opposite the
//! load), positive in the direction of rotation; the attitude angle `β` is the angle from the
//! load line to the line of centres (mid-plane), positive in the direction of rotation; the
//! maximum film of the mid-plane lies at `θ = β`, the minimum at `θ = β + 180°`.

use super::film::Film;
use super::multigrid::{Hierarchy, Level};
use crate::{Convergence, Observer, SolveError, Termination};
use std::f64::consts::TAU;
use super::balance::*;
use super::problem::*;
use super::figures::*;


/// Validate the problem, then take the caller's workspace when it fits the bearing's grids, or
/// a new one kept in `own` (the start of [`analyse`] and [`analyse_symmetric`]).
fn checked_workspace<'a>(
    bearing: &Bearing,
    operating: &Operating,
    settings: &Settings,
    workspace: Option<&'a mut Workspace>,
    own: &'a mut Option<Workspace>,
) -> Result<&'a mut Workspace, SolveError> {
    validate(bearing, operating, settings)?;
    Ok(match workspace {
        Some(w) if w.fits(bearing, settings) => w,
        _ => own.insert(Workspace::new(bearing, settings)),
    })
}

/// Analyse a bearing at an operating point. `workspace` (optional) keeps the grids and the last
/// pressure between calls; `guess` starts the position search.
pub fn analyse(
    bearing: &Bearing,
    operating: &Operating,
    settings: &Settings,
    workspace: Option<&mut Workspace>,
    guess: Option<Guess>,
    want_fields: bool,
    observer: &dyn Observer,
) -> Result<Analysis, SolveError> {
    let mut own = None;
    let ws = checked_workspace(bearing, operating, settings, workspace, &mut own)?;
    let (film, eps, beta, ev, conv, steps_per_grid) = position(&mut ws.hierarchy, bearing, operating, settings, guess, observer)?;
    figures(&ws.hierarchy.levels[0], bearing, &film, eps, beta, &ev, conv, steps_per_grid, want_fields)
}

/// [`analyse`] of an axially symmetric bearing ([`Bearing::axially_symmetric`]) on a grid with
/// an odd number of axial nodes, solved on the half `Z ∈ [0, ½]` with a mirror condition on
/// the mid-plane (a node row): the same discrete equations as the full grid (the mid-plane's
/// equation halved; [`Hierarchy::mirrored`]), so the same solution to the solver tolerances, for
/// about half the work. The figures are those of the full grid, from the half's pressure
/// unfolded onto it. Any other bearing or grid: [`analyse`].
pub fn analyse_symmetric(
    bearing: &Bearing,
    operating: &Operating,
    settings: &Settings,
    workspace: Option<&mut Workspace>,
    guess: Option<Guess>,
    want_fields: bool,
    observer: &dyn Observer,
) -> Result<Analysis, SolveError> {
    if !(bearing.axially_symmetric() && settings.axial % 2 == 1) {
        return analyse(bearing, operating, settings, workspace, guess, want_fields, observer);
    }
    let mut own = None;
    let ws = checked_workspace(bearing, operating, settings, workspace, &mut own)?;
    let half = ws.half_mut(bearing, settings);
    let (film, eps, beta, ev, conv, steps_per_grid) = position(half, bearing, operating, settings, guess, observer)?;
    let full = &mut ws.hierarchy.levels[0];
    ws.half.as_ref().unwrap().unfold_into(full);
    figures(full, bearing, &film, eps, beta, &ev, conv, steps_per_grid, want_fields)
}

/// The load `|W̄|` and the position (ε, β) of [`analyse_symmetric`] without its figures (so
/// without the full grid): the same numbers bit for bit (the figures take the load as
/// `hypot(F_v, F_h)` of the last evaluation and wrap β). With `workspace`, its mirrored half
/// is used; without, a half alone is made (no full-grid storage). The load that an aligned
/// reference gives the L9 and the `aligned_eccentricity_ratio` load.
pub fn symmetric_load(
    bearing: &Bearing,
    operating: &Operating,
    settings: &Settings,
    workspace: Option<&mut Workspace>,
    guess: Option<Guess>,
    observer: &dyn Observer,
) -> Result<(f64, Guess), SolveError> {
    if !(bearing.axially_symmetric() && settings.axial % 2 == 1) {
        let a = analyse(bearing, operating, settings, workspace, guess, false, observer)?;
        return Ok((a.load, Guess { eccentricity: a.eccentricity, attitude: a.attitude }));
    }
    validate(bearing, operating, settings)?;
    let mut own;
    let half = match workspace {
        Some(w) if w.fits(bearing, settings) => w.half_mut(bearing, settings),
        _ => {
            own = Hierarchy::mirrored(settings.circumferential - 1, settings.axial, bearing.alpha(), bearing.grooves());
            &mut own
        }
    };
    let (_, eps, beta, ev, _, _) = position(half, bearing, operating, settings, guess, observer)?;
    Ok((ev.fv.hypot(ev.fh), Guess { eccentricity: eps, attitude: wrap_pm(beta) }))
}

/// The position search of [`analyse`] on the grids of `h` (the full grids or a mirrored half):
/// the film at the end, ε, β, the last finest-grid evaluation, its convergence and the steps
/// per grid (full-grid sizes). From the start grid ([`start_level`]) to the finest, each grid
/// starts from the coarser one's solution ([`nested_start`]) and balances the load on it
/// ([`balance_on_level`]).
#[allow(clippy::type_complexity)]
fn position(
    h: &mut Hierarchy,
    bearing: &Bearing,
    operating: &Operating,
    settings: &Settings,
    guess: Option<Guess>,
    observer: &dyn Observer,
) -> Result<(Film, f64, f64, Eval, Convergence, Vec<(usize, usize, u32)>), SolveError> {
    let one_dimensional_load = matches!(operating, Operating::Load(_)) && bearing.turns_with_journal();
    let ks = start_level(h, one_dimensional_load);
    // coarse grids only start the finer ones: solve them loosely where the balance on them is
    // one-dimensional (fixed ε, or a load on a bearing that turns with the journal)
    let coarse_loose = bearing.rotation_invariant() && (!matches!(operating, Operating::Load(_)) || bearing.turns_with_journal());
    // a load balance solves each pressure to the full tolerance as soon as its cavitation set
    // nearly settles (`Hierarchy::eager_tight`); the fixed-eccentricity and fixed-position
    // analyses keep the plain active-set schedule (the roller–pin tables are built on them)
    h.eager_tight = matches!(operating, Operating::Load(_));
    let reuse_coarse = matches!(operating, Operating::Load(_));
    let mut prob = BalanceSearch { bearing, settings, h, coarse_loose, start_level: ks, reuse_coarse };
    let mut steps_per_grid = Vec::new();
    let (mut eps, mut beta) = start_position(&prob, operating, guess)?;
    let mut carried = Carried { jac: None, slope: None, invariant_failed: false };
    let mut final_eval = None;
    let mut final_conv = None;
    // ε at the end of each grid's stage (the start grid's equilibrium, then each predicted one)
    let mut eps_end: Vec<f64> = Vec::new();
    for k in (0..=ks).rev() {
        if k == 0 && k < ks && eps_end.len() >= 2 && one_dimensional_load && !carried.invariant_failed {
            // Start the finest grid at the extrapolated equilibrium: the equilibrium ε of these
            // grids converges as h² and every level halves the spacing, so the finest grid's
            // ε − ε₁ ≈ (ε₁ − ε₂)/4 (Richardson). ROSS 121×41: the start's load error 2.4e-3 →
            // 1.0e-4 (ε 5.6e-4 → 2.4e-5 from the equilibrium), two finest pressure solves instead
            // of three (BENCHMARKS.md, speed fifth round). Not for the two-dimensional balance:
            // the misaligned equilibria do not converge regularly enough on these grids.
            let (e1, e2) = (eps_end[eps_end.len() - 1], eps_end[eps_end.len() - 2]);
            let e_new = eps + 0.25 * (e1 - e2);
            if e_new > 0.0 && prob.feasible(e_new, beta) {
                eps = e_new;
            }
        }
        if k < ks {
            nested_start(&mut prob, operating, k, eps, beta);
        }
        let (ev, conv, steps) = balance_on_level(&mut prob, operating, k, &mut eps, &mut beta, &mut carried, observer)?;
        let level = &prob.h.levels[k];
        steps_per_grid.push((level.nt + 1, full_nz(level), steps));
        eps_end.push(eps);
        if k == 0 {
            final_eval = Some(ev);
            final_conv = Some(conv);
        }
    }
    let ev = final_eval.unwrap();
    let conv = final_conv.unwrap();
    let film = bearing.film(eps, beta);
    if bearing.turns_with_journal() && matches!(operating, Operating::Load(_)) {
        // the attitude was turned after the last pressure solve (exact for this bearing: the
        // pressure relative to the supply line does not change); put the finest grid's film
        // and angles at the final attitude for the figures. (The attitude search at a fixed ε
        // turns the journal after its last solve too and leaves the grid at the previous
        // attitude, a difference of the order of the last turn; kept as it was, since the
        // roller–pin tables of the cam kinds are built on it.)
        let (_, theta0) = bearing.groove_angle(beta);
        prob.h.set_film_level(0, &film, theta0);
    }
    Ok((film, eps, beta, ev, conv, steps_per_grid))
}

/// The full grid's axial node count of a level (a mirrored half: its rows up to the mid-plane,
/// mirrored).
fn full_nz(l: &Level) -> usize {
    if l.mirror { 2 * (l.nz - 2) + 1 } else { l.nz }
}

/// The grid the position search starts on: the coarsest grid with at least ~1000 nodes (or the
/// finest); ~500 for a load on a bearing that turns with the journal (`one_dimensional_load`),
/// whose balance is one secant iteration in ε that the next grids only correct (BENCHMARKS.md,
/// journal speed).
fn start_level(h: &Hierarchy, one_dimensional_load: bool) -> usize {
    let min_nodes = if one_dimensional_load { 500 } else { 1000 };
    let mut ks = 0;
    for (k, l) in h.levels.iter().enumerate() {
        if l.nt * full_nz(l) >= min_nodes && l.nt >= 24 && full_nz(l) >= 9 {
            ks = k;
        }
    }
    ks.min(h.levels.len() - 1)
}

/// The unknowns' starting point (the given position; for a fixed ε the guess's attitude or the
/// rough one; for a load the guess or the short-bearing estimate), moved to an open film where
/// the film is closed there: a load's journal pulled towards the centre, a fixed ε's attitude
/// searched around the circle.
fn start_position(prob: &BalanceSearch, operating: &Operating, guess: Option<Guess>) -> Result<(f64, f64), SolveError> {
    let (bearing, settings) = (prob.bearing, prob.settings);
    let (mut eps, mut beta) = match *operating {
        Operating::Position { eccentricity, attitude } => (eccentricity, attitude),
        Operating::Eccentricity(e) => (e, guess.map_or(initial_attitude(e), |g| g.attitude)),
        Operating::Load(w) => match guess {
            Some(g) => (g.eccentricity, g.attitude),
            None => {
                let e = initial_eccentricity(w, bearing.length_to_diameter);
                (e, initial_attitude(e))
            }
        },
    };
    if !prob.feasible(eps, beta) {
        match operating {
            Operating::Load(_) => {
                // pull the journal towards the centre until the film is open
                let mut k = 0;
                while !prob.feasible(eps, beta) && k < 60 {
                    eps *= 0.8;
                    k += 1;
                }
                if !prob.feasible(eps, beta) {
                    return Err(film_closed(settings));
                }
            }
            _ => {
                if let Operating::Eccentricity(_) = operating {
                    // search the attitude for an open film
                    let mut found = false;
                    for n in 0..72 {
                        let b = n as f64 * TAU / 72.0;
                        if prob.feasible(eps, b) {
                            beta = b;
                            found = true;
                            break;
                        }
                    }
                    if !found {
                        return Err(film_closed(settings));
                    }
                } else {
                    return Err(film_closed(settings));
                }
            }
        }
    }
    Ok((eps, beta))
}

/// Nested iteration: the coarser solution at this position starts grid `k`.
fn nested_start(prob: &mut BalanceSearch, operating: &Operating, k: usize, eps: f64, beta: f64) {
    let film = prob.bearing.film(eps, beta);
    let (_, theta0) = prob.bearing.groove_angle(beta);
    prob.h.set_film_from(k, &film, theta0);
    prob.h.interpolate_up(k);
    if matches!(operating, Operating::Load(_)) {
        // two projected Gauss–Seidel sweeps settle the interpolated free boundary: the
        // first solve on this grid then takes fewer active-set steps and V-cycles
        // (misaligned 361×181: finest 4 steps/7 cycles → 3/6, 181×91 3/7 → 2/5; ROSS
        // 121×21 3/6 → 2/3; BENCHMARKS.md, speed fourth round). The fixed-eccentricity
        // and fixed-position analyses keep the plain start (the roller–pin tables of
        // the cam kinds are built on them).
        prob.h.projected_sweeps(k, 2);
    }
}

/// What the position search carries from grid to grid: the two-dimensional load balance's
/// Jacobian, the one-dimensional balance's secant slope, and whether the one-dimensional balance
/// has failed (the general Newton iteration from then on).
struct Carried {
    jac: Option<[[f64; 2]; 2]>,
    slope: Option<f64>,
    invariant_failed: bool,
}

/// The stage of grid `k` of the position search: one evaluation at a fixed position, the attitude
/// search at a fixed ε, or the load balance (one-dimensional where the bearing turns with the
/// journal, else two-dimensional). The start grid solves cold; the grids between it and the
/// finest only pass a start on (one solve and one Newton/secant step each).
fn balance_on_level(
    prob: &mut BalanceSearch,
    operating: &Operating,
    k: usize,
    eps: &mut f64,
    beta: &mut f64,
    carried: &mut Carried,
    observer: &dyn Observer,
) -> Result<(Eval, Convergence, u32), SolveError> {
    let (bearing, settings, ks) = (prob.bearing, prob.settings, prob.start_level);
    let cold = k == ks;
    let predict = k > 0 && k < ks;
    let coarse_load_tol = if bearing.turns_with_journal() { 1e-4 } else { 1e-5 };
    let tol_load = if k == 0 { settings.load_tolerance } else { settings.load_tolerance.max(coarse_load_tol) };
    let cap = if k == 0 { settings.max_load_iterations } else { settings.max_load_iterations.max(60) };
    match *operating {
        Operating::Position { .. } => {
            let ev = prob.eval(k, *eps, *beta, cold)?;
            let conv = Convergence { iterations: 0, residual: 0.0, tolerance: settings.load_tolerance, termination: Termination::Converged };
            Ok((ev, conv, 0))
        }
        Operating::Eccentricity(_) => attitude_search(prob, k, *eps, beta, cold, tol_load, cap, observer),
        Operating::Load(w) if bearing.turns_with_journal() && !carried.invariant_failed => {
            match load_balance_invariant(prob, k, w, eps, beta, &mut carried.slope, cold, predict, tol_load, cap, observer)? {
                Some(out) => Ok(out),
                None => {
                    // no progress on the one-dimensional iteration: the general Newton
                    // iteration from here on
                    carried.invariant_failed = true;
                    load_balance(prob, k, w, eps, beta, &mut carried.jac, false, false, tol_load, cap, observer)
                }
            }
        }
        Operating::Load(w) => match load_balance(prob, k, w, eps, beta, &mut carried.jac, cold, predict, tol_load, cap, observer) {
            Err(SolveError::NotConverged { .. }) if k == ks => rescan_and_balance(prob, k, w, eps, beta, &mut carried.jac, tol_load, cap, observer),
            other => other,
        },
    }
}

/// Newton from the starting guess stalled on the coarse grid `k` (misalignment can make the force
/// map far from linear): scan the journal positions for the best start and try once more; a
/// second stall means no position carries the load.
#[allow(clippy::too_many_arguments)]
fn rescan_and_balance(
    prob: &mut BalanceSearch,
    k: usize,
    w: f64,
    eps: &mut f64,
    beta: &mut f64,
    jac: &mut Option<[[f64; 2]; 2]>,
    tol_load: f64,
    cap: u32,
    observer: &dyn Observer,
) -> Result<(Eval, Convergence, u32), SolveError> {
    let (e0, b0) = scan_positions(prob, k, w)?;
    *eps = e0;
    *beta = b0;
    *jac = None;
    match load_balance(prob, k, w, eps, beta, jac, false, false, tol_load, cap, observer) {
        Err(SolveError::NotConverged { residual, .. }) => Err(SolveError::physical(
            crate::PhysicalFailure::NoEquilibriumPosition,
            format!(
                "no journal position carries this load along the load line (best relative load residual {residual:.3e}); \
                 the misalignment's own film force is comparable with the load"
            ),
        )),
        other => other,
    }
}

fn validate(bearing: &Bearing, operating: &Operating, s: &Settings) -> Result<(), SolveError> {
    let bad = |p: &str, m: &str| Err(SolveError::invalid(p, m));
    if !(bearing.length_to_diameter.is_finite() && bearing.length_to_diameter > 0.0) {
        return bad("Bearing.length_to_diameter", "must be > 0");
    }
    if s.circumferential < 9 || s.axial < 5 {
        return bad("Settings.grid", "at least 9 circumferential and 5 axial nodes");
    }
    if !(s.pressure_tolerance > 0.0 && s.load_tolerance > 0.0) {
        return bad("Settings.tolerances", "tolerances must be > 0");
    }
    match *operating {
        Operating::Position { eccentricity, attitude } => {
            if !(eccentricity.is_finite() && (0.0..1.0).contains(&eccentricity) && attitude.is_finite()) {
                return bad("Operating.eccentricity", "must be in [0, 1)");
            }
        }
        Operating::Eccentricity(e) => {
            if !(e.is_finite() && (0.0..1.0).contains(&e)) {
                return bad("Operating.eccentricity", "must be in [0, 1)");
            }
        }
        Operating::Load(w) => {
            if !(w.is_finite() && w > 0.0) {
                return bad("Operating.load", "the load must be > 0");
            }
        }
    }
    if let Some(p) = bearing.profile {
        if !(1..=3).contains(&p.order) || !(p.height >= 0.0) || !(p.length_fraction > 0.0 && p.length_fraction <= 0.5) {
            return bad("Bearing.profile", "order 1-3, height >= 0, length_fraction in (0, 0.5]");
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::journal::film::{Misalignment, Profile};
    use crate::Silent;
    use proptest::prelude::*;

    /// Largest relative difference between the half-domain and the full-domain analyses over
    /// the pressure field (relative to the peak), the load, ε, the attitude (rad, against 1),
    /// the peak pressure, both flows and, where `friction`, both frictions; the fields compared
    /// on the same full grid. At a fixed eccentricity ratio the attitude search leaves the grid at
    /// the attitude of its last solve and turns the journal after it ([`analyse`]); the
    /// friction's pressure term is taken on that grid, so it differs by the order of the last
    /// turn, which depends on the coarse grids (not the same on the half): there the frictions
    /// are compared through fixed-position analyses at each result's (ε, β).
    fn half_against_full(b: &Bearing, op: &Operating, s: &Settings, friction: bool) -> f64 {
        let full = analyse(b, op, s, None, None, true, &Silent).unwrap();
        let half = analyse_symmetric(b, op, s, None, None, true, &Silent).unwrap();
        let (pf, ph) = (full.fields.as_ref().unwrap(), half.fields.as_ref().unwrap());
        assert_eq!((pf.theta.len(), pf.z.len()), (ph.theta.len(), ph.z.len()));
        assert_eq!(full.steps_per_grid.last().map(|g| (g.0, g.1)), half.steps_per_grid.last().map(|g| (g.0, g.1)));
        let pmax = full.max_pressure.max(1e-300);
        let mut worst = pf.pressure.iter().zip(&ph.pressure).map(|(a, b)| (a - b).abs() / pmax).fold(0.0, f64::max);
        let rel = |a: f64, b: f64| (a - b).abs() / a.abs().max(b.abs()).max(1e-300);
        let mut pairs = vec![
            (full.load, half.load),
            (full.flow_variable, half.flow_variable),
            (full.side_flow_variable, half.side_flow_variable),
            (full.max_pressure, half.max_pressure),
            (full.eccentricity, half.eccentricity),
        ];
        if friction {
            pairs.push((full.friction_force, half.friction_force));
            pairs.push((full.friction_variable_seed002.unwrap(), half.friction_variable_seed002.unwrap()));
        }
        for (a, b) in pairs {
            worst = worst.max(rel(a, b));
        }
        worst.max(wrap_pm(full.attitude - half.attitude).abs())
    }

    /// [`half_against_full`] at a fixed eccentricity ratio (no frictions), then the frictions
    /// (and all else) through fixed-position analyses at each one's (ε, β), and a load
    /// balance for the full domain's load.
    fn all_against_full(b: &Bearing, eps: f64, s: &Settings) -> f64 {
        let mut worst = half_against_full(b, &Operating::Eccentricity(eps), s, false);
        let full = analyse(b, &Operating::Eccentricity(eps), s, None, None, false, &Silent).unwrap();
        let at = Operating::Position { eccentricity: full.eccentricity, attitude: full.attitude };
        worst = worst.max(half_against_full(b, &at, s, true));
        if b.turns_with_journal() {
            worst = worst.max(half_against_full(b, &Operating::Load(full.load), s, true));
        }
        worst
    }

    /// The seed case's reference (L/D 1.25, ε 0.6, supply at the largest film) on a 121×61 grid:
    /// solved tightly, the half domain gives the full domain's solution to 1e-9 (the discrete
    /// equations are the same); at the default tolerances to their size (1e-6 / 1e-5). Also a
    /// fixed groove, two grooves and a periodic film.
    #[test]
    fn the_mirrored_half_solves_the_full_grid_equations() {
        let b = Bearing::plain(1.25);
        let tight = Settings { circumferential: 121, axial: 61, pressure_tolerance: 1e-11, load_tolerance: 1e-10, ..Settings::default() };
        let d = all_against_full(&b, 0.6, &tight);
        assert!(d < 1e-9, "tight: {d:e}");
        let loose = Settings { circumferential: 121, axial: 61, ..Settings::default() };
        let d = all_against_full(&b, 0.6, &loose);
        assert!(d < 2e-5, "default tolerances: {d:e}");
        for (b, eps) in [
            (Bearing { supply: Supply::Angle(1.0), ..Bearing::plain(0.8) }, 0.5),
            (Bearing { supply: Supply::TwoGrooves(std::f64::consts::FRAC_PI_2), ..Bearing::plain(1.0) }, 0.7),
            (Bearing { supply: Supply::Periodic, ..Bearing::plain(1.5) }, 0.4),
        ] {
            let d = all_against_full(&b, eps, &tight);
            assert!(d < 1e-8, "{b:?} ε {eps}: {d:e}");
        }
    }

    /// `symmetric_load` gives `analyse_symmetric`'s load and position bit for bit, with and
    /// without a workspace.
    #[test]
    fn the_symmetric_load_is_that_of_the_symmetric_analysis() {
        let s = Settings { circumferential: 91, axial: 45, ..Settings::default() };
        let b = Bearing::plain(1.25);
        let op = Operating::Eccentricity(0.6);
        let a = analyse_symmetric(&b, &op, &s, None, None, false, &Silent).unwrap();
        let mut ws = Workspace::new(&b, &s);
        for w in [None, Some(&mut ws)] {
            let (load, g) = symmetric_load(&b, &op, &s, w, None, &Silent).unwrap();
            assert_eq!([load, g.eccentricity, g.attitude].map(f64::to_bits), [a.load, a.eccentricity, a.attitude].map(f64::to_bits));
        }
    }

    /// Not symmetric (tilted or profiled) or an even axial node count: the full grid, bit for bit.
    #[test]
    fn an_asymmetric_problem_or_an_even_grid_takes_the_full_domain() {
        let s = Settings { circumferential: 61, axial: 31, ..Settings::default() };
        let even = Settings { axial: 30, ..s };
        let tilted = Bearing { misalignment: Misalignment { vertical: 0.3, horizontal: 0.2 }, ..Bearing::plain(1.0) };
        let profiled = Bearing { profile: Some(Profile { order: 2, height: 0.4, length_fraction: 0.2 }), ..Bearing::plain(1.0) };
        assert!(!tilted.axially_symmetric() && !profiled.axially_symmetric() && Bearing::plain(1.0).axially_symmetric());
        for (b, s) in [(tilted, s), (profiled, s), (Bearing::plain(1.0), even)] {
            let op = Operating::Eccentricity(0.5);
            let a = analyse(&b, &op, &s, None, None, false, &Silent).unwrap();
            let h = analyse_symmetric(&b, &op, &s, None, None, false, &Silent).unwrap();
            assert_eq!(a, h);
        }
    }

    proptest! {
        #![proptest_config(ProptestConfig { cases: 24, ..ProptestConfig::default() })]
        /// Over ε, L/D and grids (odd axial counts, coarse to medium, so that the hierarchies'
        /// coarsening differs): the half domain's analyses (fixed ε, fixed position, load)
        /// equal the full domain's to the (tight) solver tolerance.
        #[test]
        fn the_mirrored_half_equals_the_full_domain(
            eps in 0.05f64..0.9,
            ld in 0.25f64..2.0,
            nt in 24usize..100,
            half_rows in 2usize..40,
        ) {
            let s = Settings { circumferential: nt + 1, axial: 2 * half_rows + 1, pressure_tolerance: 1e-11, load_tolerance: 1e-10, ..Settings::default() };
            let d = all_against_full(&Bearing::plain(ld), eps, &s);
            prop_assert!(d < 1e-8, "ε {eps}, L/D {ld}, grid {}×{}: {d:e}", s.circumferential, s.axial);
        }
    }

    /// After `Workspace::reset` an analysis gives bit for bit what it gives on a new workspace,
    /// whatever the workspace solved before (the L9 schedules its cases dynamically on it).
    #[test]
    fn a_reset_workspace_analyses_like_a_new_one() {
        let s = Settings { circumferential: 91, axial: 46, ..Settings::default() };
        let tilted = |profile| Bearing { misalignment: Misalignment { vertical: 0.56, horizontal: 0.56 }, profile, ..Bearing::plain(1.25) };
        let aligned = Bearing::plain(1.25);
        let reference = analyse(&aligned, &Operating::Eccentricity(0.6), &s, None, None, false, &Silent).unwrap();
        let guess = Some(Guess { eccentricity: reference.eccentricity, attitude: reference.attitude });
        let load = Operating::Load(reference.load);
        let cases = [
            tilted(None),
            tilted(Some(Profile { order: 1, height: 0.1, length_fraction: 0.01 })),
            tilted(Some(Profile { order: 3, height: 1.0, length_fraction: 0.2 })),
        ];
        let key = |a: &Analysis| [a.eccentricity, a.attitude, a.max_pressure, a.min_film, a.friction_force].map(f64::to_bits);
        let fresh: Vec<_> = cases
            .iter()
            .map(|b| key(&analyse(b, &load, &s, Some(&mut Workspace::new(b, &s)), guess, false, &Silent).unwrap()))
            .collect();
        // one workspace, the reference first, the cases in two orders
        let mut ws = Workspace::new(&aligned, &s);
        analyse(&aligned, &Operating::Eccentricity(0.6), &s, Some(&mut ws), None, false, &Silent).unwrap();
        for order in [[0, 1, 2], [2, 0, 1]] {
            for i in order {
                ws.reset();
                let a = analyse(&cases[i], &load, &s, Some(&mut ws), guess, false, &Silent).unwrap();
                assert_eq!(key(&a), fresh[i], "case {i}");
            }
        }
    }
}
