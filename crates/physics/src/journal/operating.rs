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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::Silent;

    fn dims() -> Dimensions {
        Size { radius: 0.05, length: 0.04, clearance: 6e-5, omega: 100.0 * PI }.with_viscosity(0.02)
    }

    /// A force is `W̄ = w / load_scale`, a Sommerfeld number `W̄ = 1/(6πS)`; a force without
    /// dimensions is refused; fixed positions resolve without a target.
    #[test]
    fn demands_resolve_to_operating_points() {
        let (b, s) = (Bearing::plain(1.0), Settings::default());
        let r = |demand: LoadDemand, d: Option<&Dimensions>| resolve_load(&b, &s, &demand, d, None, &Silent);
        let d = dims();
        let p = r(LoadDemand::Force(8000.0), Some(&d)).unwrap();
        assert_eq!(p.operating, Operating::Load(8000.0 / d.load_scale()));
        assert_eq!(p.target, Some(8000.0 / d.load_scale()));
        let p = r(LoadDemand::Sommerfeld(0.1), None).unwrap();
        assert_eq!(p.target, Some(1.0 / (6.0 * PI * 0.1)));
        assert!(matches!(r(LoadDemand::Force(1.0), None), Err(SolveError::InvalidInput { .. })));
        let p = r(LoadDemand::Position { eccentricity: 0.5, attitude: 0.7 }, None).unwrap();
        assert_eq!((p.operating, p.guess, p.target), (Operating::Position { eccentricity: 0.5, attitude: 0.7 }, None, None));
    }

    /// The aligned reference drops misalignment and profile: a misaligned, profiled bearing has
    /// its plain twin's reference.
    #[test]
    fn the_aligned_reference_is_the_plain_bearings() {
        let s = Settings { circumferential: 37, axial: 11, ..Settings::default() };
        let plain = Bearing::plain(1.0);
        let tilted = Bearing { misalignment: Misalignment { vertical: 0.3, horizontal: 0.2 }, profile: Some(super::super::Profile { order: 2, height: 0.4, length_fraction: 0.2 }), ..plain };
        let a = aligned_reference(&plain, &s, 0.6, None, &Silent).unwrap();
        let b = aligned_reference(&tilted, &s, 0.6, None, &Silent).unwrap();
        assert_eq!(a, b);
        assert!(a.0 > 0.0);
    }
}
