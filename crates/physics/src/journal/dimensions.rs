//! From the dimensionless analysis to SI: the scales of seed 002's groups for a bearing of
//! given size, speed and viscosity (Raimondi & Boyd's variables).

use std::f64::consts::PI;

/// Size, speed and viscosity of a bearing.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Dimensions {
    /// Journal radius R, m.
    pub radius: f64,
    /// Bearing length L, m.
    pub length: f64,
    /// Radial clearance c, m.
    pub clearance: f64,
    /// Journal speed ω, rad/s.
    pub omega: f64,
    /// Film viscosity η, Pa·s.
    pub viscosity: f64,
}

impl Dimensions {
    /// Pressure scale `6ηω(R/c)²`, Pa: `p = P · scale`.
    pub fn pressure_scale(&self) -> f64 {
        6.0 * self.viscosity * self.omega * (self.radius / self.clearance).powi(2)
    }
    /// Load scale `6ηωRL(R/c)²`, N: `w = W̄ · scale`.
    pub fn load_scale(&self) -> f64 {
        self.pressure_scale() * self.radius * self.length
    }
    /// Film `h = H c`, m.
    pub fn film(&self, h: f64) -> f64 {
        h * self.clearance
    }
    /// Friction coefficient from the friction variable `(R/c) f`.
    pub fn friction_coefficient(&self, friction_variable: f64) -> f64 {
        friction_variable * self.clearance / self.radius
    }
    /// Volume flow from the flow variable `Q/(R c N L)` (N in rev/s), m³/s.
    pub fn flow(&self, flow_variable: f64) -> f64 {
        flow_variable * self.radius * self.clearance * self.omega / (2.0 * PI) * self.length
    }
    /// Power loss from the dimensionless friction force `F c/(ηωR²L)`, W.
    pub fn power(&self, friction_force: f64) -> f64 {
        let force_scale = self.viscosity * self.omega * self.radius * self.radius * self.length / self.clearance;
        friction_force * force_scale * self.radius * self.omega
    }
}
