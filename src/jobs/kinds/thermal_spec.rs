//! The thermal EHL model's part of a spec (`ehl.thermal`): oil heat properties, the resolution
//! across film and solids, and the cycle's key points.

use crate::jobs::kind::Validation;
use crate::jobs::quantity as Q;
use crate::physics::ehl::thermal::{FilmHeat, ThermalBodies, ThermalOptions};
use crate::physics::film::ThermalFilmSettings;
use crate::physics::thermal::ThermalSolid;
use serde::{Deserialize, Serialize};
use utoipa::ToSchema;

/// The thermal EHL model's oil properties and resolution.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct EhlThermalSpec {
    /// Oil conductivity k_f, W/(m·K). Default 0.14 (seed 000 Table 1).
    #[serde(default = "default_oil_conductivity")]
    pub oil_conductivity: f64,
    /// Oil specific heat c_f, J/(kg·K). Default 1700 (seed 000 Table 1).
    #[serde(default = "default_oil_specific_heat")]
    pub oil_specific_heat: f64,
    /// Number of temperature levels across the film, 3–41. Default 7.
    #[serde(default = "default_film_points")]
    pub film_points: usize,
    /// Number of nodes in each solid from the surface to the depth 3.15 b, 4–81. Default 16.
    #[serde(default = "default_solid_points")]
    pub solid_points: usize,
    /// Key points (cam kinds): the full thermal solve only where the operating conditions moved
    /// by more than this from every key point solved so far — the largest of `|Δ ln w'|`,
    /// `|Δ ln u_m|`, `|Δ ln R|` and `|Δ SRR|` — and elsewhere the nearest key point's thermal film
    /// reduction, temperatures and traction table carried onto the closed form's change between
    /// the two (series `model`: `thermal_carried`), from a key on the same isothermal grid
    /// layout. Key points are solved quasi-steady (no squeeze or ∂T/∂t history); where the
    /// conditions jump (by more than this within the film's transit time), the full transient
    /// solve runs at every angle until its film agrees with the carried one to a tenth of this.
    /// The carried traction's closed-form ratio is calibrated between each key and the one
    /// before it. 0 (the full solve at every angle) or 0.001–0.5. Default (line geometry): the
    /// loosest whose measured error is within `ehl.accuracy` — 0.05 at the default 1 %: seed 000
    /// at 720 angles keeps films and slide-to-roll ratio within 0.94 % of the every-angle cycle in
    /// 0.8 s against its 8–10.5 s (release; BENCHMARKS.md, "Thermal EHL"); 0.02 within 0.76 %,
    /// 0.01 within 0.31 %, 0.1 within 3.3 %.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub carry_tolerance: Option<f64>,
}



fn default_oil_conductivity() -> f64 {
    0.14
}
fn default_oil_specific_heat() -> f64 {
    1700.0
}
fn default_film_points() -> usize {
    7
}
fn default_solid_points() -> usize {
    16
}

impl EhlThermalSpec {
    /// The model's settings with the heat properties of body 1 (the cam, `z = 0`) and body 2.
    pub fn settings(&self, body_1: ThermalSolid, body_2: ThermalSolid, accuracy: f64) -> ThermalFilmSettings {
        ThermalFilmSettings {
            options: ThermalOptions { film_points: self.film_points, solid_points: self.solid_points, ..ThermalOptions::default() },
            bodies: ThermalBodies { film: FilmHeat { conductivity: self.oil_conductivity, specific_heat: self.oil_specific_heat }, body_1, body_2 },
            carry_tolerance: self.key_point_tolerance(accuracy),
        }
    }

    /// The key points' tolerance the line model uses: the spec's, else the loosest whose
    /// measured error is within the films' `accuracy` (0.05 at the default 1 %), none (every
    /// angle) at 0.
    pub fn key_point_tolerance(&self, accuracy: f64) -> Option<f64> {
        match self.carry_tolerance {
            None => crate::jobs::kinds::accuracy::carry_tolerance(accuracy),
            Some(t) if t == 0.0 => None,
            Some(t) => Some(t),
        }
    }

    pub fn validate(&self, path: &str, v: &mut Validation) {
        v.quantity(&format!("{path}/oil_conductivity"), self.oil_conductivity, Q::CONDUCTIVITY);
        v.quantity(&format!("{path}/oil_specific_heat"), self.oil_specific_heat, Q::SPECIFIC_HEAT);
        v.count_in_range(&format!("{path}/film_points"), self.film_points, 3, 41);
        v.count_in_range(&format!("{path}/solid_points"), self.solid_points, 4, 81);
        if let Some(t) = self.carry_tolerance.filter(|t| *t != 0.0) {
            v.in_range(&format!("{path}/carry_tolerance"), t, 0.001, 0.5);
        }
    }
}
