//! One bearing analysis: load balance over nested grids, then the performance figures.
//!
//! Conventions (dimensionless, seed 002): `P = p (c/R)² / (6ηω)`, `H = h/c`, `Z = z/L`,
//! `W̄ = w (c/R)² / (6ηωRL)`, Sommerfeld number `S = (R/c)² μN/P_avg = 1/(6π W̄)` with
//! `P_avg = w/(2RL)`. Angles as in [`super::film`]: `θ` from the unloaded side (opposite the
//! load), positive in the direction of rotation; the attitude angle `β` is the angle from the
//! load line to the line of centres (mid-plane), positive in the direction of rotation; the
//! maximum film of the mid-plane lies at `θ = β`, the minimum at `θ = β + 180°`.

use super::film::{wrap_angle, Film, Misalignment, Profile};
use super::multigrid::{Hierarchy, LcpReport};
use crate::physics::{ensure_finite, Convergence, Observer, SolveError, Termination};
use std::f64::consts::{PI, TAU};

/// Where the oil enters, which fixes the circumferential pressure boundary condition.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Supply {
    /// Ambient pressure along the axial line at the mid-plane's largest film (a supply groove
    /// that follows the journal) — the assumption of the classical Raimondi & Boyd tables.
    MaxFilm,
    /// Ambient pressure along the axial line at a fixed angle `θ` (rad, from the unloaded side
    /// in the direction of rotation): a real axial groove.
    Angle(f64),
    /// No supply line: the film is periodic around the circumference and the cavitation
    /// condition alone decides where pressure builds.
    Periodic,
}

/// Bearing geometry in dimensionless form.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Bearing {
    /// L/D.
    pub length_to_diameter: f64,
    pub misalignment: Misalignment,
    pub profile: Option<Profile>,
    pub supply: Supply,
}

impl Bearing {
    pub fn plain(length_to_diameter: f64) -> Bearing {
        Bearing { length_to_diameter, misalignment: Misalignment::default(), profile: None, supply: Supply::MaxFilm }
    }
    /// `α = (R/L)² = 1/(4 (L/D)²)` of seed 002 eq. (4).
    pub fn alpha(&self) -> f64 {
        1.0 / (4.0 * self.length_to_diameter * self.length_to_diameter)
    }
    /// The solution turns rigidly with the journal: aligned, unprofiled or profiled (the profile
    /// is axisymmetric), with the supply following the largest film or no supply line.
    pub fn rotation_invariant(&self) -> bool {
        self.misalignment.is_zero() && !matches!(self.supply, Supply::Angle(_))
    }

    fn film(&self, eps: f64, beta: f64) -> Film {
        Film {
            x_mid: eps * beta.cos(),
            y_mid: eps * beta.sin(),
            misalignment: self.misalignment,
            profile: self.profile,
        }
    }
    fn groove_angle(&self, beta: f64) -> (bool, f64) {
        match self.supply {
            Supply::MaxFilm => (true, beta),
            Supply::Angle(a) => (true, a),
            Supply::Periodic => (false, 0.0),
        }
    }
}

/// What fixes the journal position.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Operating {
    /// Mid-plane eccentricity ratio and attitude angle (rad) both given; the load is whatever
    /// the film carries, in whatever direction.
    Position { eccentricity: f64, attitude: f64 },
    /// Mid-plane eccentricity ratio given; the attitude angle puts the film force on the load line.
    Eccentricity(f64),
    /// Carry the dimensionless load `W̄` (along the load line): solve for the mid-plane position.
    Load(f64),
}

/// Resolution, tolerances and caps.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Settings {
    /// Nodes around the circumference, counting the 360° node that repeats 0° (seed 002: 361).
    pub circumferential: usize,
    /// Nodes along the axis, both edges included (seed 002: 181).
    pub axial: usize,
    /// Relative residual of each linear solve and of the complementarity problem.
    pub pressure_tolerance: f64,
    /// Relative load residual `‖F + W‖/W` of the load balance (or `|F_h|/|F|` for a fixed
    /// eccentricity ratio).
    pub load_tolerance: f64,
    /// Cap on load-balance (Newton) steps on the finest grid.
    pub max_load_iterations: u32,
    /// Cap on multigrid cycles per pressure solve.
    pub max_cycles: u32,
    /// Smallest admissible film `h/c`; a position below it is a closed film.
    pub min_film: f64,
}

impl Default for Settings {
    fn default() -> Self {
        Settings {
            circumferential: 181,
            axial: 91,
            pressure_tolerance: 1e-7,
            load_tolerance: 1e-6,
            max_load_iterations: 40,
            max_cycles: 400,
            min_film: 1e-3,
        }
    }
}

/// Pressure and film on the analysis grid (node `(i, j)` at `j·nt + i`; angles absolute).
#[derive(Debug, Clone, PartialEq)]
pub struct Fields {
    /// `θ` of each column, rad in [0, 2π).
    pub theta: Vec<f64>,
    /// `Z` of each row.
    pub z: Vec<f64>,
    pub pressure: Vec<f64>,
    pub film: Vec<f64>,
}

/// Result of one analysis (dimensionless).
#[derive(Debug, Clone, PartialEq)]
pub struct Analysis {
    /// Film at the final position.
    pub film: Film,
    pub eccentricity: f64,
    /// rad
    pub attitude: f64,
    /// `|W̄|` carried by the film.
    pub load: f64,
    /// Film force on the journal along the load line (negative: against the load).
    pub force_along_load: f64,
    /// Film force perpendicular to the load line (positive 90° ahead in the rotation direction).
    pub force_across_load: f64,
    pub sommerfeld: Option<f64>,
    pub max_pressure: f64,
    /// rad, absolute
    pub max_pressure_theta: f64,
    pub max_pressure_z: f64,
    pub min_film: f64,
    pub min_film_theta: f64,
    pub min_film_z: f64,
    /// `F̄ = F c/(ηωR²L)`: shear force on the journal, Couette shear over the whole circumference
    /// (Raimondi & Boyd) plus the pressure-gradient term.
    pub friction_force: f64,
    /// Couette shear over the whole circumference alone.
    pub couette_force: f64,
    /// `(R/c) f` of the journal from `friction_force` (Raimondi & Boyd definition).
    pub friction_variable: Option<f64>,
    /// `(R/c) f` as seed 002 eq. (9) is read here (Lund & Thomsen's power loss): in the
    /// cavitated zone the oil forms streamers that carry the rupture line's Couette flow, so only
    /// the fraction `H_c/H` of the gap is sheared (`H_c`: film at the rupture line of each
    /// cross-section); plus the pressure-gradient term of the journal.
    pub friction_variable_seed002: Option<f64>,
    /// Couette shear of that reading (the `1/H` integral with the film fraction), `F̄` units.
    pub striated_couette_force: f64,
    /// `Q/(R c N L)`: circumferential inflow across the supply line (periodic film: across the
    /// mid-plane's max-film line).
    pub flow_variable: f64,
    /// `Q_s/(R c N L)`: axial outflow through both edges.
    pub side_flow_variable: f64,
    pub side_flow_ratio: Option<f64>,
    /// Load balance (or attitude search) convergence on the finest grid.
    pub convergence: Convergence,
    /// Last pressure solve on the finest grid.
    pub pressure_solve: LcpReport,
    /// Load-balance steps on each grid, coarsest first, with the grid sizes.
    pub steps_per_grid: Vec<(usize, usize, u32)>,
    pub fields: Option<Fields>,
}

/// The solver state that can be reused between nearby analyses of one grid and L/D.
pub struct Workspace {
    hierarchy: Hierarchy,
    groove: bool,
    alpha: f64,
    dims: (usize, usize),
}

impl Workspace {
    pub fn new(bearing: &Bearing, settings: &Settings) -> Workspace {
        let (groove, _) = bearing.groove_angle(0.0);
        let nt = settings.circumferential - 1;
        let nz = settings.axial;
        Workspace {
            hierarchy: Hierarchy::new(nt, nz, bearing.alpha(), groove),
            groove,
            alpha: bearing.alpha(),
            dims: (settings.circumferential, settings.axial),
        }
    }
    /// Red–black sweeps before and after each coarse-grid correction (default 1).
    pub fn set_smoothing_sweeps(&mut self, n: usize) {
        self.hierarchy.sweeps = n.max(1);
    }
    /// V-cycles spent per level (finest first) since the workspace was built.
    pub fn cycles(&self) -> Vec<u32> {
        self.hierarchy.cycle_count.clone()
    }
    /// Active-set steps per level since the workspace was built.
    pub fn steps(&self) -> Vec<u32> {
        self.hierarchy.step_count.clone()
    }
    fn fits(&self, bearing: &Bearing, settings: &Settings) -> bool {
        self.groove == bearing.groove_angle(0.0).0
            && self.alpha == bearing.alpha()
            && self.dims == (settings.circumferential, settings.axial)
    }
}

/// Journal position in polar form (mid-plane eccentricity ratio, attitude angle).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Guess {
    pub eccentricity: f64,
    pub attitude: f64,
}

struct Eval {
    fv: f64,
    fh: f64,
    rep: LcpReport,
}

struct BalanceSearch<'a> {
    bearing: &'a Bearing,
    settings: &'a Settings,
    h: &'a mut Hierarchy,
    /// Coarse grids serve only as starting guesses (no load balance): solve them loosely.
    coarse_loose: bool,
}

impl BalanceSearch<'_> {
    fn feasible(&self, eps: f64, beta: f64) -> bool {
        eps >= 0.0 && self.bearing.film(eps, beta).min_film().0 > self.settings.min_film
    }

    /// Pressure tolerance on level `k`: the requested one on the finest grid; coarser grids only
    /// start the next grid (and, in a load balance, steer it), so they stop earlier.
    fn tol_at(&self, k: usize) -> f64 {
        if k == 0 {
            self.settings.pressure_tolerance
        } else if self.coarse_loose {
            self.settings.pressure_tolerance.max(1e-5)
        } else {
            self.settings.pressure_tolerance.max(1e-7)
        }
    }

    /// Pressure solve on level `k` at the position, warm-started from the level's current pressure.
    fn eval(&mut self, k: usize, eps: f64, beta: f64, cold: bool) -> Result<Eval, SolveError> {
        let tol = self.tol_at(k);
        self.eval_tol(k, eps, beta, cold, tol)
    }

    /// [`BalanceSearch::eval`] with an explicit pressure tolerance (inexact Newton steps).
    fn eval_tol(&mut self, k: usize, eps: f64, beta: f64, cold: bool, tol: f64) -> Result<Eval, SolveError> {
        let film = self.bearing.film(eps, beta);
        let (_, theta0) = self.bearing.groove_angle(beta);
        self.h.set_film_from(k, &film, theta0);
        let rep = if cold {
            self.h.nested_solve(k, tol, 60, self.settings.max_cycles)
        } else {
            self.h.solve_lcp(k, tol, 60, self.settings.max_cycles)
        };
        if !rep.converged {
            return Err(SolveError::NotConverged {
                solver: "journal pressure (active set + multigrid CG)",
                iterations: rep.cycles,
                residual: rep.residual,
                tolerance: tol,
                history: vec![rep.residual],
            });
        }
        let l = &self.h.levels[k];
        let (mut fv, mut fh) = (0.0, 0.0);
        for j in 1..l.nz - 1 {
            let row = &l.u[j * l.nt..(j + 1) * l.nt];
            for i in 0..l.nt {
                fv += row[i] * l.cos_n[i];
                fh += row[i] * l.sin_n[i];
            }
        }
        let s = l.dt * l.dz;
        // seed 002 eq. (6)-(7): film force components on the journal
        Ok(Eval { fv: fv * s, fh: fh * s, rep })
    }
}

/// Residual of the load balance: (ln(|F|/W), angle of F from the required direction).
fn load_residual(e: &Eval, w: f64) -> [f64; 2] {
    let mag = e.fv.hypot(e.fh);
    let ang = wrap_pm(e.fh.atan2(e.fv) - PI);
    [if mag > 0.0 { (mag / w).ln() } else { -50.0 }, ang]
}

fn relative_load_error(e: &Eval, w: f64) -> f64 {
    (e.fv + w).hypot(e.fh) / w
}

fn wrap_pm(a: f64) -> f64 {
    let w = wrap_angle(a + PI) - PI;
    if w <= -PI { w + TAU } else { w }
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
    validate(bearing, operating, settings)?;
    let mut own;
    let ws = match workspace {
        Some(w) if w.fits(bearing, settings) => w,
        _ => {
            own = Workspace::new(bearing, settings);
            &mut own
        }
    };
    let nlev = ws.hierarchy.levels.len();
    // start level: the coarsest grid with at least ~1000 nodes (or the finest)
    let mut ks = 0;
    for (k, l) in ws.hierarchy.levels.iter().enumerate() {
        if l.nt * l.nz >= 1000 && l.nt >= 24 && l.nz >= 9 {
            ks = k;
        }
    }
    let ks = ks.min(nlev - 1);
    let coarse_loose = !matches!(operating, Operating::Load(_)) && bearing.rotation_invariant();
    let mut prob = BalanceSearch { bearing, settings, h: &mut ws.hierarchy, coarse_loose };
    let mut steps_per_grid = Vec::new();

    // unknowns and starting point
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

    let dims = |p: &BalanceSearch, k: usize| (p.h.levels[k].nt + 1, p.h.levels[k].nz);
    let mut jac: Option<[[f64; 2]; 2]> = None;
    let mut final_eval = None;
    let mut final_conv = None;
    for k in (0..=ks).rev() {
        if k < ks {
            // nested iteration: the coarser solution at this position starts this grid
            let film = bearing.film(eps, beta);
            let (_, theta0) = bearing.groove_angle(beta);
            prob.h.set_film_from(k, &film, theta0);
            prob.h.interpolate_up(k);
        }
        let cold = k == ks;
        let tol_load = if k == 0 { settings.load_tolerance } else { settings.load_tolerance.max(1e-5) };
        let cap = if k == 0 { settings.max_load_iterations } else { settings.max_load_iterations.max(60) };
        let (ev, conv, steps) = match *operating {
            Operating::Position { .. } => {
                let ev = prob.eval(k, eps, beta, cold)?;
                let conv = Convergence { iterations: 0, residual: 0.0, tolerance: settings.load_tolerance, termination: Termination::Converged };
                (ev, conv, 0)
            }
            Operating::Eccentricity(_) => attitude_search(&mut prob, k, eps, &mut beta, cold, tol_load, cap, observer)?,
            Operating::Load(w) => {
                match load_balance(&mut prob, k, w, &mut eps, &mut beta, &mut jac, cold, tol_load, cap, observer) {
                    Err(SolveError::NotConverged { .. }) if k == ks => {
                        // Newton from the starting guess stalled on the coarse grid (misalignment
                        // can make the force map far from linear): scan the journal positions for
                        // the best start and try once more.
                        let (e0, b0) = scan_positions(&mut prob, k, w)?;
                        eps = e0;
                        beta = b0;
                        jac = None;
                        match load_balance(&mut prob, k, w, &mut eps, &mut beta, &mut jac, false, tol_load, cap, observer) {
                            Err(SolveError::NotConverged { residual, .. }) => {
                                return Err(SolveError::physical(
                                    crate::physics::PhysicalFailure::NoEquilibriumPosition,
                                    format!(
                                        "no journal position carries this load along the load line (best relative load residual {residual:.3e}); \
                                         the misalignment's own film force is comparable with the load"
                                    ),
                                ));
                            }
                            other => other?,
                        }
                    }
                    other => other?,
                }
            }
        };
        steps_per_grid.push((dims(&prob, k).0, dims(&prob, k).1, steps));
        if k == 0 {
            final_eval = Some(ev);
            final_conv = Some(conv);
        }
    }
    let ev = final_eval.unwrap();
    let conv = final_conv.unwrap();
    let film = bearing.film(eps, beta);
    let out = figures(prob.h, bearing, &film, eps, beta, &ev, conv, steps_per_grid, want_fields)?;
    Ok(out)
}

fn no_attitude(eps: f64) -> SolveError {
    SolveError::physical(
        crate::physics::PhysicalFailure::NoEquilibriumAttitude,
        format!("with this misalignment no attitude angle puts the film force on the load line at eccentricity ratio {eps}"),
    )
}

fn film_closed(settings: &Settings) -> SolveError {
    SolveError::physical(
        crate::physics::PhysicalFailure::FilmClosed,
        format!(
            "the journal would touch the bearing: no position with a film above h/c = {} carries this load with this misalignment",
            settings.min_film
        ),
    )
}

/// Short-bearing (Ocvirk) estimate of the eccentricity ratio that carries `w`, corrected for
/// L/D; only a starting point.
fn initial_eccentricity(w: f64, ld: f64) -> f64 {
    // Ocvirk: W̄ = (L/D)² ε/(1−ε²)² · π/4·sqrt(π²(1−ε²)+16ε²)/... in seed-002 scaling ≈
    // W̄ ≈ (L/D)²/6 · ε π sqrt(1 − ε² + (16/π²) ε²) / (1−ε²)² ; solved by bisection.
    let f = |e: f64| {
        let g = (ld * ld).min(1.0) / 6.0 * e * PI * (1.0 - e * e + 16.0 / (PI * PI) * e * e).sqrt() / (1.0 - e * e).powi(2);
        g - w
    };
    let (mut a, mut b) = (1e-6, 0.98);
    if f(b) < 0.0 {
        return 0.9;
    }
    if f(a) > 0.0 {
        return 1e-4;
    }
    for _ in 0..60 {
        let m = 0.5 * (a + b);
        if f(m) > 0.0 { b = m } else { a = m }
    }
    (0.5 * (a + b)).clamp(1e-4, 0.95)
}

/// A rough attitude angle for `ε` (between the long- and short-bearing curves).
fn initial_attitude(e: f64) -> f64 {
    let e = e.clamp(0.0, 0.999);
    (PI / 4.0 * (1.0 - e * e).sqrt() / e.max(1e-9)).atan()
}

#[allow(clippy::too_many_arguments)]
fn attitude_search(
    p: &mut BalanceSearch,
    k: usize,
    eps: f64,
    beta: &mut f64,
    cold: bool,
    tol: f64,
    cap: u32,
    observer: &dyn Observer,
) -> Result<(Eval, Convergence, u32), SolveError> {
    let mut ev = p.eval(k, eps, *beta, cold)?;
    let resid = |e: &Eval| {
        let m = e.fv.hypot(e.fh);
        if m > 0.0 { wrap_pm(e.fh.atan2(e.fv) - PI) } else { 0.0 }
    };
    let mut r = resid(&ev);
    let mut it = 0;
    let mut history = vec![r.abs()];
    if eps == 0.0 {
        return Ok((ev, Convergence { iterations: 0, residual: 0.0, tolerance: tol, termination: Termination::Converged }, 0));
    }
    if p.bearing.rotation_invariant() {
        // aligned film, supply following the journal or none: turning the journal turns the
        // pressure field and the force rigidly, so one exact step puts the force on the load line
        let mag = ev.fv.hypot(ev.fh);
        *beta = wrap_pm(*beta - r);
        ev.fv = -mag;
        ev.fh = 0.0;
        return Ok((ev, Convergence { iterations: 1, residual: 0.0, tolerance: tol, termination: Termination::Converged }, 1));
    }
    let mut scanned = false;
    let mut slope = 1.0f64;
    while r.abs() > tol {
        observer.check()?;
        if it >= cap {
            return Err(SolveError::NotConverged { solver: "journal attitude search", iterations: it, residual: r.abs(), tolerance: tol, history });
        }
        it += 1;
        // Newton on the force angle with a secant slope: the force turns with the journal,
        // d(angle)/dβ = 1 exactly without misalignment and with a groove that follows the
        // journal, otherwise the slope is learnt from the steps taken.
        let mut step = (-r / slope).clamp(-1.0, 1.0);
        let mut accepted = false;
        for _ in 0..30 {
            let b = *beta + step;
            if p.feasible(eps, b) {
                let e2 = p.eval(k, eps, b, false)?;
                let r2 = resid(&e2);
                if r2.abs() < r.abs() {
                    let s_new = (r2 - r) / (b - *beta);
                    if s_new.is_finite() && s_new.abs() > 1e-3 {
                        slope = s_new;
                    }
                    *beta = b;
                    ev = e2;
                    r = r2;
                    accepted = true;
                    break;
                }
            }
            step *= 0.5;
        }
        history.push(r.abs());
        if !accepted {
            if scanned {
                return Err(no_attitude(eps));
            }
            // misalignment can make the force angle a non-monotone function of β: scan the
            // circle for a sign change of the residual and bisect it
            scanned = true;
            let n = 72;
            let mut prev: Option<(f64, f64)> = None;
            let mut bracket = None;
            for m in 0..=n {
                let b = m as f64 * TAU / n as f64;
                if !p.feasible(eps, b) {
                    prev = None;
                    continue;
                }
                let e2 = p.eval(k, eps, b, false)?;
                let r2 = resid(&e2);
                if let Some((b0, r0)) = prev {
                    if r0 * r2 <= 0.0 && (r0 - r2).abs() < PI {
                        bracket = Some((b0, r0, b));
                        break;
                    }
                }
                prev = Some((b, r2));
            }
            let (mut a, ra, mut b) = bracket.ok_or_else(|| no_attitude(eps))?;
            for _ in 0..60 {
                let m = 0.5 * (a + b);
                let e2 = p.eval(k, eps, m, false)?;
                let rm = resid(&e2);
                ev = e2;
                r = rm;
                *beta = m;
                if rm.abs() <= tol {
                    break;
                }
                if (rm > 0.0) == (ra > 0.0) { a = m } else { b = m }
            }
            history.push(r.abs());
            if r.abs() > tol {
                return Err(no_attitude(eps));
            }
        }
    }
    *beta = wrap_pm(*beta);
    Ok((ev, Convergence { iterations: it, residual: r.abs(), tolerance: tol, termination: Termination::Converged }, it))
}

#[allow(clippy::too_many_arguments)]
fn load_balance(
    p: &mut BalanceSearch,
    k: usize,
    w: f64,
    eps: &mut f64,
    beta: &mut f64,
    jac: &mut Option<[[f64; 2]; 2]>,
    cold: bool,
    tol: f64,
    cap: u32,
    observer: &dyn Observer,
) -> Result<(Eval, Convergence, u32), SolveError> {
    // Inexact Newton: trial pressures are solved to a tolerance tied to the load error, the
    // accepted point is then re-solved to the full tolerance before convergence is declared.
    let mut full = p.tol_at(k);
    let inexact = |err: f64, full: f64| (1e-3 * err).clamp(full, full.max(1e-5));
    let mut ev = p.eval_tol(k, *eps, *beta, cold, if cold { full } else { inexact(1e-2, full) })?;
    let mut exact = cold || inexact(1e-2, full) <= full;
    let mut r = load_residual(&ev, w);
    let mut err = relative_load_error(&ev, w);
    let mut history = vec![err];
    let mut it = 0;
    let mut blocked = 0;
    // Stagnation guard: a light load on a strongly misaligned journal is the small difference of
    // large opposing forces (the tilt's pressure peaks at the two edges), so the pressure
    // tolerance, relative to the pressure field, can leave a load error above `tol` relative to
    // the load. When the error stops falling, tighten the pressure tolerance (to 1e-12 at most)
    // and rebuild the Jacobian. (Proptest case: L/D 1.59, W = 0.0017, vertical tilt 0.74.)
    let mut best = err;
    let mut stalled = 0;
    loop {
        if err < 0.5 * best {
            best = err;
            stalled = 0;
        } else {
            stalled += 1;
        }
        if stalled >= 4 && err < 1e-3 && full > 1e-12 && err > tol {
            full = (full * 1e-2).max(1e-12);
            stalled = 0;
            ev = p.eval_tol(k, *eps, *beta, false, full)?;
            exact = true;
            r = load_residual(&ev, w);
            err = relative_load_error(&ev, w);
            best = err;
            *jac = Some(fd_jacobian(p, k, w, *eps, *beta, &r)?);
            continue;
        }
        if err <= tol {
            if exact {
                break;
            }
            ev = p.eval_tol(k, *eps, *beta, false, full)?;
            exact = true;
            r = load_residual(&ev, w);
            err = relative_load_error(&ev, w);
            continue;
        }
        observer.check()?;
        if it >= cap {
            if r[0] < 0.0 && near_closure(p, *eps, *beta) {
                return Err(film_closed(p.settings));
            }
            return Err(SolveError::NotConverged { solver: "journal load balance", iterations: it, residual: err, tolerance: tol, history });
        }
        it += 1;
        if jac.is_none() {
            *jac = Some(fd_jacobian(p, k, w, *eps, *beta, &r)?);
        }
        let j = jac.unwrap();
        let det = j[0][0] * j[1][1] - j[0][1] * j[1][0];
        let (mut de, mut db) = if det.abs() > 1e-300 {
            ((-r[0] * j[1][1] + r[1] * j[0][1]) / det, (r[0] * j[1][0] - r[1] * j[0][0]) / det)
        } else {
            (-r[0] / j[0][0].max(1e-12), -r[1])
        };
        // keep steps moderate: the eccentricity moves at most halfway to 0 or to 1
        let lim_e = 0.5 * if de > 0.0 { 1.0 - *eps } else { *eps };
        if de.abs() > lim_e {
            let s = lim_e / de.abs();
            de *= s;
            db *= s;
        }
        if db.abs() > 0.5 {
            let s = 0.5 / db.abs();
            de *= s;
            db *= s;
        }
        let norm0 = r[0].hypot(r[1]);
        let mut t = 1.0;
        let mut accepted = false;
        let mut infeasible = false;
        for _ in 0..40 {
            let (e1, b1) = (*eps + t * de, *beta + t * db);
            if e1 > 0.0 && p.feasible(e1, b1) {
                // near convergence the trial is likely the answer: solve it fully at once
                let t_p = if err < 1e3 * tol { full } else { inexact(err, full) };
                let ev1 = p.eval_tol(k, e1, b1, false, t_p)?;
                exact = t_p <= full;
                let r1 = load_residual(&ev1, w);
                let norm1 = r1[0].hypot(r1[1]);
                if norm1 < norm0 || t < 1e-3 {
                    // Broyden update of the Jacobian with the step actually taken
                    let s = [e1 - *eps, b1 - *beta];
                    let y = [r1[0] - r[0], r1[1] - r[1]];
                    let ss = s[0] * s[0] + s[1] * s[1];
                    if ss > 0.0 {
                        let mut jn = j;
                        for a in 0..2 {
                            let js = j[a][0] * s[0] + j[a][1] * s[1];
                            for b in 0..2 {
                                jn[a][b] += (y[a] - js) * s[b] / ss;
                            }
                        }
                        *jac = Some(jn);
                    }
                    *eps = e1;
                    *beta = b1;
                    ev = ev1;
                    r = r1;
                    accepted = true;
                    break;
                }
            } else {
                infeasible = true;
            }
            t *= 0.5;
        }
        err = relative_load_error(&ev, w);
        history.push(err);
        if !accepted {
            if infeasible && r[0] < 0.0 {
                return Err(film_closed(p.settings));
            }
            // a stale Jacobian: rebuild it once before giving up
            blocked += 1;
            if blocked > 2 {
                if r[0] < 0.0 && near_closure(p, *eps, *beta) {
                    return Err(film_closed(p.settings));
                }
                return Err(SolveError::NotConverged { solver: "journal load balance", iterations: it, residual: err, tolerance: tol, history });
            }
            *jac = Some(fd_jacobian(p, k, w, *eps, *beta, &r)?);
            ev = p.eval(k, *eps, *beta, false)?;
        }
    }
    *beta = wrap_pm(*beta);
    Ok((ev, Convergence { iterations: it, residual: err, tolerance: tol, termination: Termination::Converged }, it))
}

/// Evaluate the load residual over a polar grid of mid-plane positions on level `k` and return
/// the best feasible one.
fn scan_positions(p: &mut BalanceSearch, k: usize, w: f64) -> Result<(f64, f64), SolveError> {
    let mut best = (f64::INFINITY, 0.5, 0.0);
    for ie in 1..=19 {
        let e = ie as f64 * 0.05;
        for ib in 0..24 {
            let b = ib as f64 * TAU / 24.0;
            if !p.feasible(e, b) {
                continue;
            }
            let ev = p.eval(k, e, b, false)?;
            let err = relative_load_error(&ev, w);
            if err < best.0 {
                best = (err, e, b);
            }
        }
    }
    if best.0.is_infinite() {
        return Err(film_closed(p.settings));
    }
    p.eval(k, best.1, best.2, false)?;
    Ok((best.1, best.2))
}

/// The film at the position is within a factor 10 of the closure floor: a load that still
/// cannot be reached there needs a closed film.
fn near_closure(p: &BalanceSearch, eps: f64, beta: f64) -> bool {
    p.bearing.film(eps, beta).min_film().0 < 10.0 * p.settings.min_film
}

/// Forward-difference Jacobian of the load residual in (ε, β); restores the level's pressure.
fn fd_jacobian(p: &mut BalanceSearch, k: usize, w: f64, eps: f64, beta: f64, r0: &[f64; 2]) -> Result<[[f64; 2]; 2], SolveError> {
    let saved = p.h.levels[k].u.clone();
    let mut de = 1e-4 * (1.0 - eps).min(eps).max(1e-6);
    if !p.feasible(eps + de, beta) {
        de = -de;
    }
    let e1 = p.eval(k, eps + de, beta, false)?;
    p.h.levels[k].u.copy_from_slice(&saved);
    let r1 = load_residual(&e1, w);
    let db = 1e-4;
    let db = if p.feasible(eps, beta + db) { db } else { -db };
    let e2 = p.eval(k, eps, beta + db, false)?;
    p.h.levels[k].u.copy_from_slice(&saved);
    let r2 = load_residual(&e2, w);
    // restore the coefficients of the base point
    let film = p.bearing.film(eps, beta);
    let (_, theta0) = p.bearing.groove_angle(beta);
    p.h.set_film_from(k, &film, theta0);
    Ok([[(r1[0] - r0[0]) / de, (r2[0] - r0[0]) / db], [(r1[1] - r0[1]) / de, (r2[1] - r0[1]) / db]])
}

#[allow(clippy::too_many_arguments)]
fn figures(
    h: &Hierarchy,
    bearing: &Bearing,
    film: &Film,
    eps: f64,
    beta: f64,
    ev: &Eval,
    convergence: Convergence,
    steps_per_grid: Vec<(usize, usize, u32)>,
    want_fields: bool,
) -> Result<Analysis, SolveError> {
    let l = &h.levels[0];
    let (nt, nz, dt, dz) = (l.nt, l.nz, l.dt, l.dz);
    let alpha = bearing.alpha();
    let u = &l.u;
    let load = ev.fv.hypot(ev.fh);

    // peak pressure, refined by a parabola through the neighbours in each direction
    let (mut kmax, mut pmax) = (0, 0.0);
    for (k, &v) in u.iter().enumerate() {
        if v > pmax {
            pmax = v;
            kmax = k;
        }
    }
    let (im, jm) = (kmax % nt, kmax / nt);
    let (mut p_peak, mut th_peak, mut z_peak) = (pmax, l.theta(im), jm as f64 * dz);
    if pmax > 0.0 && jm > 0 && jm + 1 < nz {
        let at = |i: usize, j: usize| u[j * nt + i];
        let (pw, pe) = (at((im + nt - 1) % nt, jm), at((im + 1) % nt, jm));
        let (ps, pn) = (at(im, jm - 1), at(im, jm + 1));
        let mut extra = 0.0;
        let ct = pw - 2.0 * pmax + pe;
        if ct < 0.0 {
            let d = (0.5 * (pw - pe) / ct).clamp(-0.5, 0.5);
            th_peak += d * dt;
            extra += -0.125 * (pe - pw).powi(2) / ct;
        }
        let cz = ps - 2.0 * pmax + pn;
        if cz < 0.0 {
            let d = (0.5 * (ps - pn) / cz).clamp(-0.5, 0.5);
            z_peak += d * dz;
            extra += -0.125 * (pn - ps).powi(2) / cz;
        }
        p_peak += extra;
    }
    let (hmin, th_min, z_min) = film.min_film();

    // friction on the journal: F̄ = ∫∫ (1/H + 3 H ∂P/∂θ) dθ dZ, the pressure term integrated by
    // parts to −3 ∫∫ P ∂H/∂θ (P is periodic or zero on the supply line).
    let (mut couette, mut press) = (0.0, 0.0);
    for j in 0..nz {
        let z = j as f64 * dz;
        let r = film.row(z);
        let a = 1.0 + r.gamma;
        let wz = if j == 0 || j + 1 == nz { 0.5 } else { 1.0 };
        let disc = a * a - r.x * r.x - r.y * r.y;
        if disc <= 0.0 {
            return Err(SolveError::physical(crate::physics::PhysicalFailure::FilmClosed, "the film closes in the friction integral"));
        }
        couette += wz * TAU / disc.sqrt();
        let row = &u[j * nt..(j + 1) * nt];
        let mut s = 0.0;
        for i in 0..nt {
            let dh = -r.x * l.sin_n[i] + r.y * l.cos_n[i];
            s += row[i] * dh;
        }
        press += wz * (-3.0 * s * dt);
    }
    couette *= dz;
    press *= dz;
    let friction_force = couette + press;
    let striated = striated_couette(l, film);
    let (friction_variable, friction_variable_seed002, sommerfeld) = if load > 0.0 {
        (Some(friction_force / (6.0 * load)), Some((striated + press) / (6.0 * load)), Some(1.0 / (6.0 * PI * load)))
    } else {
        (None, None, None)
    };

    // flows. Inflow across the supply line (column 0 with a groove; otherwise the column nearest
    // the mid-plane's largest film): Q/(RcNL) = π ∫ (H − H³ ∂P/∂θ) dZ.
    let (groove, _) = bearing.groove_angle(beta);
    let i0 = if groove {
        0
    } else {
        let t = wrap_angle(beta - l.theta0);
        ((t / dt).round() as usize) % nt
    };
    let mut q = 0.0;
    for j in 0..nz {
        let wz = if j == 0 || j + 1 == nz { 0.5 } else { 1.0 };
        let at = |i: usize| u[j * nt + (i % nt)];
        let dp = if groove {
            (-3.0 * at(0) + 4.0 * at(1) - at(2)) / (2.0 * dt)
        } else {
            (at(i0 + 1) - at(i0 + nt - 1)) / (2.0 * dt)
        };
        let hh = l.h[j * nt + i0];
        q += wz * (hh - hh * hh * hh * dp);
    }
    let flow = PI * q * dz;
    // side flow: Qs/(RcNL) = πα Σ_edges ∫ H³ |∂P/∂Z| dθ, one-sided second-order differences
    let mut qs = 0.0;
    for i in 0..nt {
        let at = |j: usize| u[j * nt + i];
        let d0 = (4.0 * at(1) - at(2)) / (2.0 * dz);
        let d1 = (4.0 * at(nz - 2) - at(nz - 3)) / (2.0 * dz);
        let h0 = l.h[i];
        let h1 = l.h[(nz - 1) * nt + i];
        qs += h0 * h0 * h0 * d0 + h1 * h1 * h1 * d1;
    }
    let side = PI * alpha * qs * dt;
    let side_flow_ratio = if flow > 0.0 { Some(side / flow) } else { None };

    let fields = want_fields.then(|| Fields {
        theta: (0..nt).map(|i| wrap_angle(l.theta(i))).collect(),
        z: (0..nz).map(|j| j as f64 * dz).collect(),
        pressure: u.clone(),
        film: l.h.clone(),
    });
    let out = Analysis {
        film: *film,
        eccentricity: eps,
        attitude: wrap_pm(beta),
        load,
        force_along_load: ev.fv,
        force_across_load: ev.fh,
        sommerfeld,
        max_pressure: p_peak,
        max_pressure_theta: wrap_angle(th_peak),
        max_pressure_z: z_peak,
        min_film: hmin,
        min_film_theta: th_min,
        min_film_z: z_min,
        friction_force,
        couette_force: couette,
        friction_variable,
        friction_variable_seed002,
        striated_couette_force: striated,
        flow_variable: flow,
        side_flow_variable: side,
        side_flow_ratio,
        convergence,
        pressure_solve: ev.rep,
        steps_per_grid,
        fields,
    };
    ensure_finite(
        "journal bearing result",
        [
            &out.eccentricity, &out.attitude, &out.load, &out.max_pressure, &out.min_film, &out.friction_force,
            &out.flow_variable, &out.side_flow_variable, &out.force_along_load, &out.force_across_load,
        ],
    )?;
    if let Some(f) = &out.fields {
        ensure_finite("pressure field", f.pressure.iter())?;
    }
    Ok(out)
}

/// Couette shear `∫∫ φ/H dθ dZ` with the film fraction `φ = 1` where the film is pressurised
/// and `φ = H_c/H` in the cavitated zone of each cross-section, `H_c` being the film at the
/// rupture line (located between nodes from `√P`, which is linear in θ there because the
/// Reynolds condition makes `P` and `∂P/∂θ` vanish together). A cross-section without a
/// rupture line (the edges, or pressure up to the supply line) counts as full.
fn striated_couette(l: &super::multigrid::Level, film: &Film) -> f64 {
    let (nt, nz, dt, dz) = (l.nt, l.nz, l.dt, l.dz);
    let u = &l.u;
    let mut total = 0.0;
    for j in 0..nz {
        let wz = if j == 0 || j + 1 == nz { 0.5 } else { 1.0 };
        let row = &u[j * nt..(j + 1) * nt];
        let h = &l.h[j * nt..(j + 1) * nt];
        // rupture: a pressurised node followed by a cavitated one (not the supply node 0)
        let mut hc = None;
        for i in 0..nt {
            let i1 = (i + 1) % nt;
            if i1 != 0 && row[i] > 0.0 && row[i1] <= 0.0 {
                let iw = (i + nt - 1) % nt;
                let (s1, s2) = (row[iw].max(0.0).sqrt(), row[i].sqrt());
                let t = if s1 > s2 { (s2 / (s1 - s2)).min(1.0) } else { 1.0 };
                let theta_c = l.theta(i) + t * dt;
                let z = j as f64 * dz;
                hc = Some(film.h(theta_c, z));
            }
        }
        let mut s = 0.0;
        for i in 0..nt {
            let phi = match hc {
                Some(c) if row[i] <= 0.0 => (c / h[i]).min(1.0),
                _ => 1.0,
            };
            s += phi / h[i];
        }
        total += wz * s * dt;
    }
    total * dz
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
