//! The heat balance of one bearing case (ISO 7902-1 / DIN 31652-2 bulk model, [`super::heat`]):
//! bearing analyses at trial viscosities until the film's effective temperature reproduces
//! itself. Each analysis is a warm-started load-balanced one at the operating point the demand
//! gives at that viscosity (a force is a different `W̄` at every viscosity).
//!
//! The lubricant is an ISO VG grade or a two-point curve, both through Walther's law (ASTM D341)
//! `log10 log10(ν + 0.7) = a − b log10 T` (ν mm²/s, T K); a curve's dynamic viscosities are
//! turned into kinematic ones with the (constant) density, `ν = η/ρ · 10⁶`.

use super::heat::{balance, Cooling, Flows, Oil, Walther};
use super::operating::{resolve_load, LoadDemand, Size};
use super::{analyse, Analysis, Bearing, Dimensions, Guess, Settings, Workspace};
use crate::{Convergence, Observer, SolveError};

/// Where the viscosity–temperature law comes from.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum ViscosityData {
    /// An ISO VG grade, with the oil's kinematic viscosity at 100 °C (mm²/s) when known.
    IsoVg { grade: u32, viscosity_100c: Option<f64> },
    /// Two points `(temperature K, dynamic viscosity Pa·s)`.
    Curve([(f64, f64); 2]),
}

/// The lubricant of a heat balance.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Lubricant {
    pub viscosity: ViscosityData,
    /// kg/m³ (taken constant).
    pub density: f64,
    /// J/(kg·K).
    pub specific_heat: f64,
}

/// A heat balance's inputs: the lubricant and where the heat goes.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct HeatBalance {
    pub lubricant: Lubricant,
    /// Oil supply temperature `T_s`, K.
    pub supply_temperature: f64,
    /// Hot-oil carry-over factor `κ` in [0, 1].
    pub carry_over: f64,
    /// Heat conducted through the housing: `(k_A W/K, ambient temperature K)`.
    pub housing: Option<(f64, f64)>,
    /// Tolerance on the effective temperature, K.
    pub tolerance: f64,
    /// Cap on bearing analyses.
    pub max_iterations: u32,
}

/// The balance found.
#[derive(Debug, Clone, PartialEq)]
pub struct ThermalBalance {
    /// Effective film temperature, K.
    pub effective_temperature: f64,
    /// Film viscosity at it, Pa·s.
    pub viscosity: f64,
    /// mm²/s.
    pub kinematic_viscosity: f64,
    /// `T_1`, film inlet after mixing, K.
    pub inlet_temperature: f64,
    /// `T_2`, film outlet, K.
    pub outlet_temperature: f64,
    /// Maximum bulk temperature (= `T_2` in the bulk model), K.
    pub max_temperature: f64,
    /// K.
    pub supply_temperature: f64,
    /// Friction power, W.
    pub power_loss: f64,
    /// Film inflow `Q`, m³/s.
    pub film_inflow: f64,
    /// Side leakage `Q_s`, m³/s.
    pub side_flow: f64,
    /// Supply oil needed `Q_s + (1 − κ)(Q − Q_s)`, m³/s.
    pub supply_flow: f64,
    /// Bearing analyses, |T_eff − T| in K, tolerance.
    pub convergence: Convergence,
}

/// The last analysis of a balance and what it was made with.
#[derive(Debug, Clone, PartialEq)]
pub struct Balanced {
    pub analysis: Analysis,
    /// Target `W̄` of its load balance.
    pub target: Option<f64>,
    /// The SI scales at its viscosity.
    pub dimensions: Dimensions,
    pub thermal: ThermalBalance,
}

/// The oil of `lubricant`: its Walther law and heat capacity.
pub fn oil(lubricant: &Lubricant) -> Result<Oil, SolveError> {
    let lu = lubricant;
    let law = match lu.viscosity {
        ViscosityData::IsoVg { grade, viscosity_100c } => Walther::iso_vg(grade, viscosity_100c)?,
        ViscosityData::Curve(c) => {
            let nu = |p: &(f64, f64)| p.1 / lu.density * 1e6;
            Walther::through(c[0].0, nu(&c[0]), c[1].0, nu(&c[1]))?
        }
    };
    Ok(Oil { law, density: lu.density, specific_heat: lu.specific_heat })
}

/// The heat balance of the bearing `bearing` on the grid of `settings` carrying `demand`:
/// analyses (on `ws`, each starting from the last one's position) at trial viscosities until the
/// effective temperature reproduces itself. `size` is required (its absence is an error at the
/// first analysis); `want_fields` keeps the fields of each analysis.
#[allow(clippy::too_many_arguments)]
pub fn solve(
    bearing: &Bearing,
    settings: &Settings,
    demand: &LoadDemand,
    size: Option<&Size>,
    want_fields: bool,
    heat: &HeatBalance,
    ws: &mut Workspace,
    observer: &dyn Observer,
) -> Result<Balanced, SolveError> {
    let oil = oil(&heat.lubricant)?;
    let cool = Cooling {
        supply_temperature: heat.supply_temperature,
        carry_over: heat.carry_over,
        housing: heat.housing,
        tolerance: heat.tolerance,
        max_iterations: heat.max_iterations,
    };
    let mut guess: Option<Guess> = None;
    let mut last: Option<(Dimensions, Analysis, Option<f64>)> = None;
    let b = balance(&oil, &cool, observer, |eta| {
        let d = size.map(|s| s.with_viscosity(eta)).ok_or_else(|| SolveError::invalid("HeatBalance.size", "needs dimensions"))?;
        let p = resolve_load(bearing, settings, demand, Some(&d), None, observer)?;
        let a = analyse(bearing, &p.operating, settings, Some(&mut *ws), guess.or(p.guess), want_fields, observer)?;
        guess = Some(Guess { eccentricity: a.eccentricity, attitude: a.attitude });
        let f = Flows { power: d.power(a.friction_force), inflow: d.flow(a.flow_variable), side_flow: d.flow(a.side_flow_variable) };
        last = Some((d, a, p.target));
        Ok(f)
    })?;
    let (dimensions, analysis, target) = last.expect("the balance ran at least one analysis");
    let tt = b.temperatures;
    let thermal = ThermalBalance {
        effective_temperature: b.temperature,
        viscosity: b.viscosity,
        kinematic_viscosity: b.viscosity / oil.density * 1e6,
        inlet_temperature: tt.inlet,
        outlet_temperature: tt.outlet,
        max_temperature: tt.outlet,
        supply_temperature: heat.supply_temperature,
        power_loss: b.flows.power,
        film_inflow: b.flows.inflow,
        side_flow: b.flows.side_flow,
        supply_flow: tt.supply_flow,
        convergence: b.convergence,
    };
    let th = &thermal;
    crate::ensure_finite(
        "heat balance",
        [th.effective_temperature, th.viscosity, th.inlet_temperature, th.outlet_temperature, th.power_loss, th.film_inflow, th.side_flow, th.supply_flow].iter(),
    )?;
    Ok(Balanced { analysis, target, dimensions, thermal })
}
