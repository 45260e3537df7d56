//! Physical bounds of spec fields, with their units (issue 40): wide enough for any real machine,
//! narrow enough that no solver's arithmetic overflows or underflows on an accepted spec. A kind
//! checks a field with [`super::Validation::quantity`]; the bound becomes the field's `minimum` and
//! `maximum` in the OpenAPI document and the message names the unit.

/// A physical quantity's accepted range and unit.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Quantity {
    /// What it is, for messages ("a load").
    pub name: &'static str,
    pub unit: &'static str,
    pub min: f64,
    pub max: f64,
    /// The largest magnitude a valve train or a bearing plausibly has: a legal value above it is
    /// accepted with a warning (usually a unit slip, said by `slip`).
    pub typical: f64,
    /// What a value above `typical` usually is ("millimetres"), for the warning.
    pub slip: &'static str,
}

/// A contact or bearing load, N: a gram-force to a large ship's main bearing.
pub const FORCE: Quantity = Quantity { name: "a force", unit: "N", min: 1e-3, max: 1e8, typical: 1e7, slip: "a load of a whole engine rather than one contact or bearing" };
/// A length of a contact, a face or a lobe, m: 10 µm to 10 m.
pub const LENGTH: Quantity = Quantity { name: "a length", unit: "m", min: 1e-5, max: 10.0, typical: 1.0, slip: "millimetres: SI expects metres" };
/// A radius of curvature or of a body, m: 10 µm to 100 m (nearly flat surfaces).
pub const RADIUS: Quantity = Quantity { name: "a radius", unit: "m", min: 1e-5, max: 100.0, typical: 1.0, slip: "millimetres: SI expects metres" };
/// A small geometric height (a lift, a crown drop, a profile height), m.
pub const HEIGHT: Quantity = Quantity { name: "a height", unit: "m", min: 0.0, max: 1.0, typical: 0.05, slip: "millimetres: SI expects metres" };
/// A surface velocity, m/s (either sign).
pub const VELOCITY: Quantity = Quantity { name: "a velocity", unit: "m/s", min: -1e3, max: 1e3, typical: 100.0, slip: "mm/s or km/h: SI expects m/s" };
/// A dynamic viscosity, Pa·s: a gas-thin oil to a grease.
pub const VISCOSITY: Quantity = Quantity { name: "a viscosity", unit: "Pa·s", min: 1e-5, max: 1e4, typical: 10.0, slip: "mPa·s (centipoise): SI expects Pa·s" };
/// A stress or strength (Eyring stress, limiting shear, yield strength, hardness), Pa.
pub const STRESS: Quantity = Quantity { name: "a stress", unit: "Pa", min: 1e3, max: 1e11, typical: 1e10, slip: "a modulus rather than a stress" };
/// A heat conductivity, W/(m·K).
pub const CONDUCTIVITY: Quantity = Quantity { name: "a conductivity", unit: "W/(m·K)", min: 1e-3, max: 1e4, typical: 500.0, slip: "a wrong unit: metals conduct 10–400 W/(m·K)" };
/// A specific heat, J/(kg·K).
pub const SPECIFIC_HEAT: Quantity = Quantity { name: "a specific heat", unit: "J/(kg·K)", min: 10.0, max: 1e5, typical: 1e4, slip: "a wrong unit: oils and steels hold 400–2500 J/(kg·K)" };
/// A density of a solid or a liquid, kg/m³.
pub const DENSITY: Quantity = Quantity { name: "a density", unit: "kg/m³", min: 10.0, max: 3e4, typical: 2e4, slip: "a wrong unit: SI expects kg/m³" };
/// A rotational speed, rpm.
pub const SPEED_RPM: Quantity = Quantity { name: "a speed", unit: "rpm", min: 1e-3, max: 1e5, typical: 3e4, slip: "rad/s or rev/h: the field is in rpm" };
/// A mass moment of inertia, kg·m².
pub const INERTIA: Quantity = Quantity { name: "an inertia", unit: "kg·m²", min: 0.0, max: 1e3, typical: 10.0, slip: "g·mm² or kg·mm²: SI expects kg·m²" };
/// A Young's modulus, Pa: a soft polymer to above diamond.
pub const MODULUS: Quantity = Quantity { name: "a modulus", unit: "Pa", min: 1e6, max: 1e13, typical: 1.2e12, slip: "a wrong unit: steel is 2.1e11 Pa" };
/// A mass, kg.
pub const MASS: Quantity = Quantity { name: "a mass", unit: "kg", min: 0.0, max: 1e4, typical: 1e3, slip: "grams: SI expects kg" };

/// A bound as an engineer writes it: `0.001`, `25`, `1e8`, `-1000`.
pub fn format_number(x: f64) -> String {
    if x == 0.0 {
        return "0".into();
    }
    let a = x.abs();
    if (1e-3..1e4).contains(&a) {
        let s = format!("{x}");
        if s.len() <= 8 {
            return s;
        }
        return format!("{x:.4}").trim_end_matches('0').trim_end_matches('.').to_string();
    }
    let s = format!("{x:e}");
    s
}

impl Quantity {
    /// "must be between 0.001 N and 1e8 N".
    pub fn rule(&self) -> String {
        format!("must be between {} {} and {} {}", format_number(self.min), self.unit, format_number(self.max), self.unit)
    }

    /// The same quantity with a positive lower bound replaced (e.g. a velocity that must not be
    /// negative).
    /// The warning a legal but implausible value gets: its magnitude is above `typical`.
    pub fn implausible(&self, value: f64) -> Option<String> {
        (value.is_finite() && value.abs() > self.typical).then(|| {
            format!(
                "{} {} is more than {} usually is here ({} {} at most); it looks like {}",
                format_number(value),
                self.unit,
                self.name,
                format_number(self.typical),
                self.unit,
                self.slip
            )
        })
    }

    pub const fn from(self, min: f64) -> Self {
        Quantity { min, ..self }
    }
}
