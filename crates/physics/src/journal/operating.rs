//! The operating point of a bearing case: what the film is asked to carry — a fixed position, a
//! fixed eccentricity ratio, or a load given as a force, a Sommerfeld number or the load of an
//! aligned reference bearing — resolved to the analysis' [`Operating`] with a starting guess and
//! the load-balance target.
//!
//! Scaling (seed 002): `W̄ = w (c/R)²/(6ηωRL)`, so a force `w` is `W̄ = w / (6ηωRL(R/c)²)`
//! ([`Dimensions::load_scale`]); the Sommerfeld number `S = (R/c)² μN/P_avg = 1/(6πW̄)`.

use super::{symmetric_load, Bearing, Dimensions, Guess, Misalignment, Operating, Settings, Workspace};
use crate::{Observer, SolveError};
use std::f64::consts::PI;

/// What the film is asked to carry.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum LoadDemand {
    /// A fully fixed position: mid-plane eccentricity ratio and attitude angle (rad).
    Position { eccentricity: f64, attitude: f64 },
    /// A fixed mid-plane eccentricity ratio; the attitude angle puts the film force on the load line.
    Eccentricity(f64),
    /// The load an aligned, unprofiled bearing of the same L/D, supply and grid carries at this
    /// eccentricity ratio (seed 002 uses 0.6).
    AlignedEccentricity(f64),
    /// A load, N (needs the bearing's [`Dimensions`]).
    Force(f64),
    /// The load of this Sommerfeld number `S = 1/(6πW̄)`.
    Sommerfeld(f64),
}

/// Size and speed of a bearing: the SI inputs of [`Dimensions`] but the film viscosity (which a
/// heat balance finds).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Size {
    /// Journal radius R, m.
    pub radius: f64,
    /// Bearing length L, m.
    pub length: f64,
    /// Radial clearance c, m.
    pub clearance: f64,
    /// Journal speed ω, rad/s.
    pub omega: f64,
}

impl Size {
    /// The SI scales at film viscosity `viscosity` (Pa·s).
    pub fn with_viscosity(&self, viscosity: f64) -> Dimensions {
        Dimensions { radius: self.radius, length: self.length, clearance: self.clearance, omega: self.omega, viscosity }
    }
}

/// A demand resolved for the analysis.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct OperatingPoint {
    pub operating: Operating,
    /// A starting position (the aligned reference's, when one was solved).
    pub guess: Option<Guess>,
    /// Target `W̄` of the load balance (absent for a fixed position or eccentricity ratio).
    pub target: Option<f64>,
}

/// Resolve `demand` to the analysis' operating point (the aligned reference is solved here when
/// needed, with `workspace` for its grids when given; the result does not depend on what the
/// workspace held). `dimensions` scale a force.
pub fn resolve_load(
    bearing: &Bearing,
    settings: &Settings,
    demand: &LoadDemand,
    dimensions: Option<&Dimensions>,
    workspace: Option<&mut Workspace>,
    observer: &dyn Observer,
) -> Result<OperatingPoint, SolveError> {
    let point = |operating, guess, target| OperatingPoint { operating, guess, target };
    Ok(match *demand {
        LoadDemand::Position { eccentricity, attitude } => point(Operating::Position { eccentricity, attitude }, None, None),
        LoadDemand::Eccentricity(e) => point(Operating::Eccentricity(e), None, None),
        LoadDemand::AlignedEccentricity(e) => {
            let (w, guess) = aligned_reference(bearing, settings, e, workspace, observer)?;
            point(Operating::Load(w), Some(guess), Some(w))
        }
        LoadDemand::Force(f) => {
            let d = dimensions.ok_or_else(|| SolveError::invalid("Operating.force", "needs dimensions"))?;
            let w = f / d.load_scale();
            point(Operating::Load(w), None, Some(w))
        }
        LoadDemand::Sommerfeld(s) => {
            let w = 1.0 / (6.0 * PI * s);
            point(Operating::Load(w), None, Some(w))
        }
    })
}

/// The load (W̄) the aligned, unprofiled version of `bearing` (same L/D and supply) carries on
/// the grid of `settings` at eccentricity ratio `e`, and its position.
pub fn aligned_reference(
    bearing: &Bearing,
    settings: &Settings,
    e: f64,
    workspace: Option<&mut Workspace>,
    observer: &dyn Observer,
) -> Result<(f64, Guess), SolveError> {
    let mut b = *bearing;
    b.misalignment = Misalignment::default();
    b.profile = None;
    // aligned and unprofiled: symmetric about the mid-plane, solved on half the axial grid
    // (the same discrete equations; an even axial node count takes the full grid)
    symmetric_load(&b, &Operating::Eccentricity(e), settings, workspace, None, observer)
}
