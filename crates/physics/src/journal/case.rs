//! One bearing case end to end: the operating point (or the heat balance that finds the film
//! viscosity), the analysis at it, and the dynamic coefficients asked for, in figures.
//!
//! Progress: 0 "load" (or "heat balance"), 0.3 "analysis", 0.8 "dynamic coefficients" /
//! "moment coefficients", 1 "done".

use super::dynamics::{coefficients, tilt_coefficients};
use super::heat_balance::{self, HeatBalance, ThermalBalance};
use super::operating::{resolve_load, LoadDemand, Size};
use super::threshold::{dynamic_figures, moment_figures, DynamicFigures, MomentFigures};
use super::{analyse, Analysis, Bearing, Dimensions, Settings, Workspace};
use crate::{Observer, SolveError};

/// A bearing case.
#[derive(Debug, Clone, PartialEq)]
pub struct Case {
    pub bearing: Bearing,
    pub settings: Settings,
    pub load: LoadDemand,
    /// Size and speed (SI figures and a force need them).
    pub size: Option<Size>,
    /// Film viscosity, Pa·s (absent with `heat`, which finds it).
    pub viscosity: Option<f64>,
    /// A heat balance instead of a given viscosity.
    pub heat: Option<HeatBalance>,
    /// Keep the pressure and film fields.
    pub want_fields: bool,
    /// The 2×2 stiffness and damping.
    pub dynamic_coefficients: bool,
    /// The 4×4 force and moment coefficients (the 2×2 then come from the same solves).
    pub moment_coefficients: bool,
}

impl Case {
    /// The SI scales at the given viscosity, when size, speed and viscosity are known.
    pub fn dimensions(&self) -> Option<Dimensions> {
        let s = self.size?;
        Some(s.with_viscosity(self.viscosity?))
    }
}

/// What a case gives.
#[derive(Debug, Clone, PartialEq)]
pub struct Solution {
    pub analysis: Analysis,
    /// Target `W̄` of the load balance (absent for a fixed position or eccentricity ratio).
    pub target: Option<f64>,
    /// The SI scales at the film viscosity of the analysis (the heat balance's with `heat`).
    pub dimensions: Option<Dimensions>,
    pub thermal: Option<ThermalBalance>,
    pub dynamic: Option<DynamicFigures>,
    pub moment: Option<MomentFigures>,
}

/// Solve `case` (see the module docs).
pub fn solve(case: &Case, observer: &dyn Observer) -> Result<Solution, SolveError> {
    let (bearing, settings) = (&case.bearing, &case.settings);
    let mut ws = Workspace::new(bearing, settings);
    let (analysis, target, dimensions, thermal) = match &case.heat {
        Some(heat) => {
            // Progress moves with the solver's own checks (one per balance or Newton step).
            let stage = crate::Stage::new(observer, 0.0, 0.8, 40.0, "heat balance");
            let b = heat_balance::solve(bearing, settings, &case.load, case.size.as_ref(), case.want_fields, heat, &mut ws, &stage)?;
            (b.analysis, b.target, Some(b.dimensions), Some(b.thermal))
        }
        None => {
            let d = case.dimensions();
            let p = resolve_load(bearing, settings, &case.load, d.as_ref(), None, &crate::Stage::new(observer, 0.0, 0.3, 20.0, "load"))?;
            let a = analyse(bearing, &p.operating, settings, Some(&mut ws), p.guess, case.want_fields, &crate::Stage::new(observer, 0.3, 0.8, 20.0, "analysis"))?;
            (a, p.target, d, None)
        }
    };
    let (mut dynamic, mut moment) = (None, None);
    if case.moment_coefficients {
        // the 4×4 set; its translations block is `coefficients`' computation from the same state
        let c = tilt_coefficients(bearing, &analysis, settings, &mut ws, &crate::Stage::new(observer, 0.8, 1.0, 20.0, "moment coefficients"))?;
        if case.dynamic_coefficients {
            dynamic = Some(dynamic_figures(&c.translation(), analysis.load, dimensions.as_ref()));
        }
        moment = Some(moment_figures(&c, analysis.load, dimensions.as_ref()));
    } else if case.dynamic_coefficients {
        let c = coefficients(bearing, &analysis, settings, &mut ws, &crate::Stage::new(observer, 0.8, 1.0, 20.0, "dynamic coefficients"))?;
        dynamic = Some(dynamic_figures(&c, analysis.load, dimensions.as_ref()));
    }
    observer.progress(1.0, "done");
    Ok(Solution { analysis, target, dimensions, thermal, dynamic, moment })
}
