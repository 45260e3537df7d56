//! The bearing problem of one analysis: the bearing (geometry, supply), its operating point, the
//! solver settings, the reusable workspace, and what an analysis returns. The analysis
//! ([`super::analysis`]), its load balance and its figures all read these; none of them is
//! imported here.

use super::film::{Film, Misalignment, Profile};
use super::multigrid::{Hierarchy, LcpReport};
use crate::Convergence;

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
    /// Two axial grooves 180° apart, the first at the fixed angle `θ` (rad, as in `Angle`):
    /// the two-axial-groove bearing of the design tables (Someya's *Journal-Bearing Databook*,
    /// grooves on the horizontal plane for a vertical load: `θ = π/2`). The grooves are lines of
    /// ambient pressure (no width); the circumferential grid needs an even number of intervals
    /// for the second line to fall on a node exactly.
    TwoGrooves(f64),
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
        self.misalignment.is_zero() && !matches!(self.supply, Supply::Angle(_) | Supply::TwoGrooves(_))
    }

    /// The film, its supply lines and the edge conditions are symmetric about the mid-plane
    /// `Z = ½`: aligned (no tilt) and without an axial profile. Every supply is an axial line
    /// over the whole length and both edges are at ambient pressure, so the discrete problem is
    /// symmetric on a grid with an odd number of axial nodes ([`analyse_symmetric`]).
    pub fn axially_symmetric(&self) -> bool {
        self.misalignment.is_zero() && self.profile.is_none()
    }

    /// Rotation invariant with the grid following the journal (supply line at the largest
    /// film): the discrete pressure field, relative to the supply line, depends on ε only.
    pub fn turns_with_journal(&self) -> bool {
        self.rotation_invariant() && matches!(self.supply, Supply::MaxFilm)
    }

    pub(super) fn film(&self, eps: f64, beta: f64) -> Film {
        Film {
            x_mid: eps * beta.cos(),
            y_mid: eps * beta.sin(),
            misalignment: self.misalignment,
            profile: self.profile,
        }
    }
    pub(super) fn groove_angle(&self, beta: f64) -> (bool, f64) {
        match self.supply {
            Supply::MaxFilm => (true, beta),
            Supply::Angle(a) | Supply::TwoGrooves(a) => (true, a),
            Supply::Periodic => (false, 0.0),
        }
    }
    /// Number of supply lines (0, 1 or 2).
    pub fn grooves(&self) -> usize {
        match self.supply {
            Supply::Periodic => 0,
            Supply::MaxFilm | Supply::Angle(_) => 1,
            Supply::TwoGrooves(_) => 2,
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
            // Below the discretisation error, not far below it (issue 18, round 11): on the
            // misaligned 361×181 case 1e-6 / 1e-5 move the results by ≤ 1.2e-5 against grid
            // errors of 1.4e-4 (peak pressure) and 3.7e-5 (load), for 17 % less time than
            // 1e-7 / 1e-6. Tighter values remain a request away (`solver` in the bearing spec).
            pressure_tolerance: 1e-6,
            load_tolerance: 1e-5,
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
    pub(super) hierarchy: Hierarchy,
    /// The mirrored half's grids of [`analyse_symmetric`] (made when first needed).
    pub(super) half: Option<Hierarchy>,
    pub(super) grooves: usize,
    pub(super) alpha: f64,
    pub(super) dims: (usize, usize),
}

impl Workspace {
    pub fn new(bearing: &Bearing, settings: &Settings) -> Workspace {
        let nt = settings.circumferential - 1;
        let nz = settings.axial;
        Workspace {
            hierarchy: Hierarchy::with_grooves(nt, nz, bearing.alpha(), bearing.grooves()),
            half: None,
            grooves: bearing.grooves(),
            alpha: bearing.alpha(),
            dims: (settings.circumferential, settings.axial),
        }
    }
    /// Forget the last solution (pressures, cavitation sets, coefficients) without
    /// reallocating: the next analysis gives bit for bit what it gives on a new workspace,
    /// whatever this one solved before (the L9's cases, scheduled dynamically).
    pub fn reset(&mut self) {
        self.hierarchy.reset_state();
        if let Some(h) = &mut self.half {
            h.reset_state();
        }
    }
    /// The mirrored half's grids ([`analyse_symmetric`]), made when first needed.
    pub(super) fn half_mut(&mut self, bearing: &Bearing, settings: &Settings) -> &mut Hierarchy {
        let sweeps = self.hierarchy.sweeps;
        self.half.get_or_insert_with(|| {
            let mut h = Hierarchy::mirrored(settings.circumferential - 1, settings.axial, bearing.alpha(), bearing.grooves());
            h.sweeps = sweeps;
            h
        })
    }
    /// Red–black sweeps before and after each coarse-grid correction (default 1).
    pub fn set_smoothing_sweeps(&mut self, n: usize) {
        self.hierarchy.sweeps = n.max(1);
        if let Some(h) = &mut self.half {
            h.sweeps = n.max(1);
        }
    }
    /// V-cycles spent per level (finest first) since the workspace was built.
    pub fn cycles(&self) -> Vec<u32> {
        self.hierarchy.cycle_count.clone()
    }
    /// Active-set steps per level since the workspace was built.
    pub fn steps(&self) -> Vec<u32> {
        self.hierarchy.step_count.clone()
    }
    /// The grids for `bearing` and `settings` (rebuilt when the workspace does not fit them).
    pub(super) fn hierarchy_mut(&mut self, bearing: &Bearing, settings: &Settings) -> &mut Hierarchy {
        if !self.fits(bearing, settings) {
            *self = Workspace::new(bearing, settings);
        }
        &mut self.hierarchy
    }
    pub(super) fn fits(&self, bearing: &Bearing, settings: &Settings) -> bool {
        self.grooves == bearing.grooves()
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
