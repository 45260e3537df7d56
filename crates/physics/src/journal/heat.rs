//! Heat balance of a journal bearing (ISO 7902-1 / DIN 31652-2 approach): the film's effective
//! temperature from the friction power against the heat carried away by the oil flows and,
//! optionally, conducted through the housing, iterated with the lubricant's viscosity–temperature
//! law.
//!
//! Bulk (global) model, per the standards: one effective temperature sets the viscosity of the
//! whole film. With `T_s` the supply temperature, `Q` the film inflow at the supply line, `Q_s`
//! the side leakage (both from the isoviscous analysis at the current viscosity), `P` the
//! friction power, `κ` the hot-oil carry-over factor (the share of the recirculating flow
//! `Q − Q_s` that re-enters the film at the outlet temperature `T_2` instead of being replaced by
//! fresh oil):
//! - film inlet (mixing at the supply line): `T_1 = T_s + κ (Q − Q_s)/Q · (T_2 − T_s)`;
//! - effective temperature `T_eff = (T_1 + T_2)/2` (DIN 31652-2);
//! - energy: `P = ρ c_p [Q_s (T_eff − T_s) + (1 − κ)(Q − Q_s)(T_2 − T_s)] + k_A (T_eff − T_amb)`
//!   — the side leakage leaves at the mean film temperature, the drained recirculating oil at
//!   `T_2`, the housing conducts `k_A` W/K to the ambient.
//!
//! With `κ = 0` and no housing term this is Raimondi & Boyd's temperature rise
//! `ΔT = P/(ρ c_p (Q − Q_s/2))` (Trans. ASLE 1, 1958; Shigley eq. 12-15 in SI); the fresh-oil
//! need is then the film inflow `Q`. With `κ = 1` only the side leakage is replaced.
//! The maximum bulk temperature is `T_2` (the film leaves the loaded zone at it); local hot
//! spots above it are outside a bulk model.

use crate::{Convergence, Observer, SolveError, Termination};

/// Walther's law (ASTM D341): `log10 log10(ν + 0.7) = a − b log10 T`, ν in mm²/s, T in K.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Walther {
    pub a: f64,
    pub b: f64,
}

/// Typical kinematic viscosity at 100 °C (mm²/s) of ISO VG mineral oils of viscosity index
/// ≈ 95–100 (ISO 3448 fixes only the 40 °C value, the grade; the 100 °C values are the usual
/// catalogue figures for such oils).
pub const ISO_VG_100C: [(u32, f64); 13] = [
    (10, 2.6),
    (15, 3.4),
    (22, 4.3),
    (32, 5.4),
    (46, 6.8),
    (68, 8.7),
    (100, 11.2),
    (150, 14.7),
    (220, 19.0),
    (320, 24.0),
    (460, 30.5),
    (680, 39.0),
    (1000, 50.0),
];

const CELSIUS_40: f64 = 313.15;
const CELSIUS_100: f64 = 373.15;

impl Walther {
    /// The law through two points `(T, ν)`, K and mm²/s.
    pub fn through(t1: f64, nu1: f64, t2: f64, nu2: f64) -> Result<Walther, SolveError> {
        let ok = t1 > 0.0 && t2 > 0.0 && (t1 - t2).abs() > 1e-6 && nu1 > 0.0 && nu2 > 0.0 && t1.is_finite() && t2.is_finite();
        if !ok {
            return Err(SolveError::invalid("Lubricant.viscosity_curve", "two points at distinct positive temperatures with positive viscosities"));
        }
        let y = |nu: f64| (nu + 0.7).log10().log10();
        let (y1, y2) = (y(nu1), y(nu2));
        let b = (y1 - y2) / (t2.log10() - t1.log10());
        if !(b > 0.0) || !b.is_finite() {
            return Err(SolveError::invalid("Lubricant.viscosity_curve", "the viscosity must fall with temperature"));
        }
        Ok(Walther { a: y1 + b * t1.log10(), b })
    }

    /// An ISO VG grade: ν(40 °C) = grade, ν(100 °C) from [`ISO_VG_100C`] or the given value.
    pub fn iso_vg(grade: u32, nu_100c: Option<f64>) -> Result<Walther, SolveError> {
        let nu100 = match nu_100c {
            Some(v) => v,
            None => ISO_VG_100C
                .iter()
                .find(|(g, _)| *g == grade)
                .map(|(_, v)| *v)
                .ok_or_else(|| SolveError::invalid("Lubricant.iso_vg", "one of 10, 15, 22, 32, 46, 68, 100, 150, 220, 320, 460, 680, 1000"))?,
        };
        Walther::through(CELSIUS_40, grade as f64, CELSIUS_100, nu100)
    }

    /// Kinematic viscosity at `t` K, mm²/s.
    pub fn kinematic(&self, t: f64) -> f64 {
        10f64.powf(10f64.powf(self.a - self.b * t.log10())) - 0.7
    }
}

/// The oil: viscosity–temperature law and the heat capacity of the flows.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Oil {
    pub law: Walther,
    /// kg/m³ (taken constant).
    pub density: f64,
    /// J/(kg·K).
    pub specific_heat: f64,
}

impl Oil {
    /// Dynamic viscosity at `t` K, Pa·s.
    pub fn viscosity(&self, t: f64) -> f64 {
        self.density * self.law.kinematic(t) * 1e-6
    }
}

/// Where the heat goes.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Cooling {
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

/// What the isoviscous analysis gives the heat balance at one viscosity: friction power (W),
/// film inflow and side leakage (m³/s).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Flows {
    pub power: f64,
    pub inflow: f64,
    pub side_flow: f64,
}

/// Temperatures of the balance at given flows, K.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Temperatures {
    /// `T_1`, film inlet after mixing.
    pub inlet: f64,
    /// `T_2`, film outlet (the bulk maximum).
    pub outlet: f64,
    pub effective: f64,
    /// Fresh oil the supply must deliver, m³/s: the side leakage plus the drained recirculation.
    pub supply_flow: f64,
}

/// Solve the linear energy balance of the module docs for the temperatures.
pub fn temperatures(f: &Flows, oil: &Oil, cool: &Cooling) -> Result<Temperatures, SolveError> {
    let rc = oil.density * oil.specific_heat;
    let (q, qs) = (f.inflow, f.side_flow.min(f.inflow));
    if !(q > 0.0) {
        return Err(SolveError::physical(crate::PhysicalFailure::NoLoad, "no oil flows through the film: the heat balance has no carrier".to_string()));
    }
    let k = cool.carry_over;
    let r = k * (q - qs) / q;
    let (ha, tamb) = cool.housing.unwrap_or((0.0, cool.supply_temperature));
    let den = rc * (qs * 0.5 * (1.0 + r) + (1.0 - k) * (q - qs)) + ha * 0.5 * (1.0 + r);
    if !(den > 0.0) {
        return Err(SolveError::physical(crate::PhysicalFailure::NoLoad, "no heat leaves the bearing (no side leakage, full carry-over, no housing)".to_string()));
    }
    let ts = cool.supply_temperature;
    let dt = (f.power - ha * (ts - tamb)) / den;
    Ok(Temperatures {
        inlet: ts + r * dt,
        outlet: ts + dt,
        effective: ts + 0.5 * (1.0 + r) * dt,
        supply_flow: qs + (1.0 - k) * (q - qs),
    })
}

/// Result of the coupled balance.
#[derive(Debug, Clone, PartialEq)]
pub struct Balance {
    /// The effective temperature found: the viscosity is the law's at it; the balance's
    /// `temperatures.effective` agrees with it within the tolerance.
    pub temperature: f64,
    pub temperatures: Temperatures,
    /// Viscosity at the effective temperature, Pa·s.
    pub viscosity: f64,
    pub flows: Flows,
    /// On the effective temperature: iterations = bearing analyses, residual in K.
    pub convergence: Convergence,
}

/// Find the effective temperature `T` with `T = T_eff(flows(η(T)))`: bracket the root of
/// `g(T) = T_eff − T` (decreasing: a hotter film is thinner and makes less heat), then the
/// Illinois variant of regula falsi. `analyse` runs the bearing at a viscosity (Pa·s).
pub fn balance(
    oil: &Oil,
    cool: &Cooling,
    observer: &dyn Observer,
    mut analyse: impl FnMut(f64) -> Result<Flows, SolveError>,
) -> Result<Balance, SolveError> {
    let mut evals = 0u32;
    let mut history = Vec::new();
    let mut eval = |t: f64, evals: &mut u32, history: &mut Vec<f64>| -> Result<(f64, Temperatures, Flows, f64), SolveError> {
        observer.check()?;
        if *evals >= cool.max_iterations {
            return Err(SolveError::NotConverged {
                solver: "bearing heat balance",
                iterations: *evals,
                residual: history.last().copied().unwrap_or(f64::INFINITY),
                tolerance: cool.tolerance,
                history: history.clone(),
            });
        }
        *evals += 1;
        let eta = oil.viscosity(t);
        if !(eta.is_finite() && eta > 0.0) {
            return Err(SolveError::invalid("Lubricant", format!("the viscosity law gives no positive viscosity at {t:.1} K")));
        }
        let f = analyse(eta)?;
        let tt = temperatures(&f, oil, cool)?;
        let g = tt.effective - t;
        history.push(g.abs());
        Ok((g, tt, f, eta))
    };
    let done = |t: f64, g: f64, tt: Temperatures, f: Flows, eta: f64, evals: u32| Balance {
        temperature: t,
        temperatures: tt,
        viscosity: eta,
        flows: f,
        convergence: Convergence { iterations: evals, residual: g.abs(), tolerance: cool.tolerance, termination: Termination::Converged },
    };
    // bracket: start at the supply temperature (plus the housing's pull), step towards the root
    let mut a = cool.supply_temperature;
    let (mut ga, tt, f, eta) = eval(a, &mut evals, &mut history)?;
    if ga.abs() <= cool.tolerance {
        return Ok(done(a, ga, tt, f, eta, evals));
    }
    let mut step = ga.clamp(-50.0, 50.0);
    let (mut b, mut gb);
    loop {
        b = (a + step).max(150.0);
        let (g, tt, f, eta) = eval(b, &mut evals, &mut history)?;
        gb = g;
        if g.abs() <= cool.tolerance {
            return Ok(done(b, g, tt, f, eta, evals));
        }
        if (g > 0.0) != (ga > 0.0) {
            break;
        }
        a = b;
        ga = g;
        step *= 2.0;
    }
    // Illinois
    let mut side = 0;
    loop {
        let c = (a * gb - b * ga) / (gb - ga);
        let (gc, tt, f, eta) = eval(c, &mut evals, &mut history)?;
        if gc.abs() <= cool.tolerance || (b - a).abs() < 1e-9 {
            return Ok(done(c, gc, tt, f, eta, evals));
        }
        if (gc > 0.0) == (gb > 0.0) {
            b = c;
            gb = gc;
            if side == -1 {
                ga *= 0.5;
            }
            side = -1;
        } else {
            a = c;
            ga = gc;
            if side == 1 {
                gb *= 0.5;
            }
            side = 1;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn walther_reproduces_its_points() {
        let w = Walther::iso_vg(46, None).unwrap();
        assert!((w.kinematic(313.15) - 46.0).abs() < 1e-9);
        assert!((w.kinematic(373.15) - 6.8).abs() < 1e-9);
        // monotone, between the points
        let mid = w.kinematic(343.15);
        assert!(mid < 46.0 && mid > 6.8);
    }

    #[test]
    fn raimondi_boyd_rise_without_carry_over() {
        let oil = Oil { law: Walther::iso_vg(32, None).unwrap(), density: 860.0, specific_heat: 2000.0 };
        let cool = Cooling { supply_temperature: 320.0, carry_over: 0.0, housing: None, tolerance: 0.01, max_iterations: 30 };
        let f = Flows { power: 500.0, inflow: 2e-5, side_flow: 1e-5 };
        let t = temperatures(&f, &oil, &cool).unwrap();
        let dt = 500.0 / (860.0 * 2000.0 * (2e-5 - 0.5e-5));
        assert!((t.outlet - 320.0 - dt).abs() < 1e-9);
        assert!((t.effective - 320.0 - 0.5 * dt).abs() < 1e-9);
        assert_eq!(t.inlet, 320.0);
        // energy: side leakage at T_eff, drained recirculation at T_2
        let carried = 860.0 * 2000.0 * (1e-5 * (t.effective - 320.0) + 1e-5 * (t.outlet - 320.0));
        assert!((carried - 500.0).abs() < 1e-9);
    }

    #[test]
    fn balance_finds_the_fixed_point() {
        // a made-up bearing: power ∝ η, flows fixed
        let oil = Oil { law: Walther::iso_vg(68, None).unwrap(), density: 870.0, specific_heat: 1950.0 };
        let cool = Cooling { supply_temperature: 313.15, carry_over: 0.5, housing: Some((5.0, 293.15)), tolerance: 1e-3, max_iterations: 40 };
        let b = balance(&oil, &cool, &crate::Silent, |eta| Ok(Flows { power: 2e4 * eta, inflow: 3e-6, side_flow: 2e-6 })).unwrap();
        let t = temperatures(&b.flows, &oil, &cool).unwrap();
        assert!((t.effective - b.temperatures.effective).abs() < 1e-9);
        assert!((oil.viscosity(b.temperature) - b.viscosity).abs() < 1e-12);
        assert!((b.temperature - b.temperatures.effective).abs() <= 1e-3);
        assert!(b.convergence.residual <= 1e-3);
    }

    use proptest::prelude::*;
    proptest! {
        #![proptest_config(ProptestConfig { cases: 64, ..ProptestConfig::default() })]
        /// Over wide ranges of grade, supply temperature, carry-over, housing and a power that
        /// falls with the viscosity like a bearing's: the balance converges to a fixed point
        /// within its tolerance, or fails with a typed error.
        #[test]
        fn balance_converges_or_fails_typed(
            grade in prop::sample::select(vec![10u32, 22, 46, 100, 220, 460, 1000]),
            ts in 280.0f64..360.0,
            kappa in 0.0f64..1.0,
            housing in prop::option::of((0.0f64..50.0, 270.0f64..320.0)),
            p0 in 1e2f64..1e6,
            q in 1e-7f64..1e-3,
            ratio in 0.05f64..1.0,
        ) {
            let oil = Oil { law: Walther::iso_vg(grade, None).unwrap(), density: 870.0, specific_heat: 2000.0 };
            let cool = Cooling { supply_temperature: ts, carry_over: kappa, housing, tolerance: 1e-3, max_iterations: 60 };
            let r = balance(&oil, &cool, &crate::Silent, |eta| {
                Ok(Flows { power: p0 * (eta / 0.05).powf(0.8), inflow: q, side_flow: ratio * q })
            });
            match r {
                Ok(b) => {
                    prop_assert!(b.convergence.residual <= 1e-3);
                    prop_assert!(b.viscosity.is_finite() && b.viscosity > 0.0);
                    let t = temperatures(&b.flows, &oil, &cool).unwrap();
                    prop_assert!((t.effective - b.temperatures.effective).abs() < 1e-9);
                }
                Err(SolveError::NotConverged { .. }) | Err(SolveError::InvalidInput { .. }) => {}
                Err(e) => prop_assert!(false, "{e:?}"),
            }
        }
    }
}
