use super::*;

/// Convectively cooled surface of a roller of outer radius `radius`, bore `bore_radius` and
/// length `length`: outer cylinder plus both annular end faces, m².
pub fn roller_cooled_area(radius: f64, bore_radius: f64, length: f64) -> f64 {
    TAU * radius * length + TAU * (radius * radius - bore_radius * bore_radius)
}

/// `(η, d ln η/dT)` of `lub` at ambient pressure and temperature `t` (K): Barus `−β`; Roelands
/// `ln η = ln η0 + A1 (θ(T) − 1)`, `θ = ((T − 138)/(T0 − 138))^(−S0)`, so
/// `d ln η/dT = −A1 S0 θ/(T − 138)` (0 where the law's floor `T − 138 ≥ 1` is active).
pub fn viscosity_and_log_slope(lub: &Lubricant, t: f64) -> (f64, f64) {
    let eta = lub.viscosity_at(0.0, t);
    let slope = match lub.viscosity_model {
        ViscosityModel::Barus => -lub.temperature_viscosity,
        ViscosityModel::Roelands => {
            let a1 = lub.viscosity.ln() - ROELANDS_LN_ETA_INF;
            let t0 = lub.reference_temperature;
            let s0 = lub.temperature_viscosity * (t0 - 138.0) / a1;
            if t - 138.0 > 1.0 {
                let theta = ((t - 138.0) / (t0 - 138.0)).powf(-s0);
                -a1 * s0 * theta / (t - 138.0)
            } else {
                0.0
            }
        }
    };
    (eta, slope)
}

impl FinitePin {
    /// The dimensionless load `x = ln W̄ = ln(W/(6ηΩRL(R/c)²))` of seed 002's scaling.
    pub(super) fn evaluate(&self, omega: f64, load: f64, t: f64) -> AtTemperature {
        let (r, c, l) = (self.pin_radius, self.clearance, self.length);
        let (eta, dln_eta) = viscosity_and_log_slope(&self.lubricant, t);
        let scale = 6.0 * eta * omega * r * l * (r / c) * (r / c);
        // W = 0 gives x = −∞: the light-load continuation handles it (ε = 0, Petroff).
        let x = (load / scale).ln().max(-700.0);
        let p = self.table.at(x);
        // T = F̄ ηΩR³L/c; x falls with Ω and with η: ∂x/∂Ω = −1/Ω, ∂x/∂T_e = −d ln η/dT.
        let torque = p.friction_force * eta * omega * r * r * r * l / c;
        let gain = 1.0 - p.d_ln_friction;
        // Q_s = Q̄s R c L Ω/(2π)
        let qs = p.side_flow * r * c * l * omega / TAU;
        AtTemperature {
            viscosity: eta,
            point: p,
            torque,
            torque_omega: torque / omega * gain,
            torque_temp: torque * gain * dln_eta,
            side_flow: qs,
            side_flow_omega: qs / omega * (1.0 - p.d_ln_side_flow),
            side_flow_temp: -qs * p.d_ln_side_flow * dln_eta,
        }
    }

    /// State at roller speed `omega` (rad/s, either sign) and pin load `load` (N, its magnitude
    /// is used). `warm` holds the last film temperature (NaN: none) and is updated.
    pub fn state(&self, omega: f64, load: f64, warm: &std::cell::Cell<f64>) -> FinitePinState {
        let t0 = self.ambient_temperature;
        let w = load.abs();
        let speed = omega.abs();
        if speed == 0.0 || !speed.is_finite() {
            // No speed, no film: the heavy-load continuation's limit (ε → 1) under load.
            let (eta, _) = viscosity_and_log_slope(&self.lubricant, t0);
            let p = self.table.at(if w > 0.0 { 700.0 } else { -700.0 });
            return FinitePinState {
                torque: 0.0,
                torque_slope: 0.0,
                film_temperature: t0,
                viscosity: eta,
                eccentricity: p.eccentricity,
                attitude: p.attitude,
                side_flow: 0.0,
                power: 0.0,
                heat_to_side_flow: 0.0,
                heat_to_convection: 0.0,
                iterations: 0,
            };
        }
        let (at, rise, slope, iterations) = match self.thermal {
            None => {
                let at = self.evaluate(speed, w, t0);
                let slope = at.torque_omega;
                (at, 0.0, slope, 0)
            }
            Some(th) => {
                let rc = th.oil_density * th.oil_specific_heat;
                let ka = th.convection_coefficient * th.cooled_area;
                // Unknown: the rise r = T_e − T0 (kept apart from T0 so that tiny rises close the
                // balance to full relative precision). G(r) = T Ω − (ρ c Q_s + k A) r: decreasing
                // in r (η falls, so T Ω falls and Q_s rises), G(0) = P(T0) > 0 and
                // G(P(T0)/K(T0)) ≤ 0.
                let g = |a: &AtTemperature, r: f64| a.torque * speed - (rc * a.side_flow + ka) * r;
                let dg = |a: &AtTemperature, r: f64| speed * a.torque_temp - rc * a.side_flow_temp * r - (rc * a.side_flow + ka);
                // Bracket [0, P(T0)/K(T0)] (from the cold state, computed only when a warm start
                // is missing or Newton leaves the bracket).
                let cold_bound = || {
                    let cold = self.evaluate(speed, w, t0);
                    let bound = cold.torque * speed / (rc * cold.side_flow + ka);
                    (cold, bound)
                };
                let mut lo = 0.0;
                let mut hi = f64::INFINITY;
                let mut iterations = 0;
                let mut r = warm.get() - t0;
                if !(r > 0.0 && r.is_finite()) {
                    let (cold, bound) = cold_bound();
                    iterations += 1;
                    hi = bound;
                    let newton = -g(&cold, 0.0) / dg(&cold, 0.0);
                    r = if newton > lo && newton < hi { newton } else { 0.5 * (lo + hi) };
                }
                let mut at = self.evaluate(speed, w, t0 + r);
                iterations += 1;
                // Bracketed Newton: quadratic from a warm start (two or three evaluations); a
                // step leaving the bracket bisects. Done after a Newton step below 1e-8 of the
                // rise (taken and evaluated: Newton being quadratic, the error left is ~1e-16 r).
                for _ in 0..200 {
                    let gv = g(&at, r);
                    if gv > 0.0 { lo = r } else { hi = r }
                    let d = dg(&at, r);
                    let newton = if d < 0.0 { r - gv / d } else { f64::NAN };
                    let next = if newton > lo && newton < hi {
                        newton
                    } else {
                        if !hi.is_finite() {
                            let (_, bound) = cold_bound();
                            iterations += 1;
                            hi = bound.max(lo);
                        }
                        0.5 * (lo + hi)
                    };
                    let step = (next - r).abs();
                    let done = step <= 1e-8 * r || hi - lo <= 1e-12 * r;
                    r = next;
                    at = self.evaluate(speed, w, t0 + r);
                    iterations += 1;
                    if done {
                        break;
                    }
                }
                // dr/dΩ = −G_Ω/G_r (implicit function), G_Ω = T + Ω ∂T/∂Ω − ρc ∂Q_s/∂Ω r
                let g_omega = at.torque + speed * at.torque_omega - rc * at.side_flow_omega * r;
                let g_r = dg(&at, r);
                let dr = if g_r < 0.0 { -g_omega / g_r } else { 0.0 };
                let slope = at.torque_omega + at.torque_temp * dr;
                warm.set(t0 + r);
                (at, r, slope, iterations)
            }
        };
        let (rc, ka) = self.thermal.map_or((0.0, 0.0), |th| (th.oil_density * th.oil_specific_heat, th.convection_coefficient * th.cooled_area));
        let temp = t0 + rise;
        FinitePinState {
            torque: at.torque * omega.signum(),
            // T is odd in Ω, so dT/dΩ is even
            torque_slope: slope,
            film_temperature: temp,
            viscosity: at.viscosity,
            eccentricity: at.point.eccentricity,
            attitude: at.point.attitude,
            side_flow: at.side_flow,
            power: at.torque * speed,
            heat_to_side_flow: rc * at.side_flow * rise,
            heat_to_convection: ka * rise,
            iterations,
        }
    }
}
