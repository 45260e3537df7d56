//! Flash temperature of a sliding concentrated contact: Blok's partition of the frictional heat
//! between two surfaces moving through a band source (Jaeger's moving band, high Péclet number).
//!
//! A uniform flux `q` over a band of half-width `b` passing over a surface at speed `V` heats it
//! like a semi-infinite solid for the transit time `2b/V`; the exit (maximum) temperature rise is
//! `θ = 1.596 q √b / √(k ρ c V)` (and the band mean is 2/3 of it: 1.064). Blok's postulate — equal
//! maximum temperatures of both surfaces — splits the heat so that
//! `θ_f = 1.596 q √b / (√(k1 ρ1 c1 V1) + √(k2 ρ2 c2 V2))`.
//! The high-Péclet form diverges as `V → 0`; each speed is floored at `2κ/b` (Péclet number 1),
//! which bounds the stationary-source limit at about `q b/k` — a regularisation, not a model of
//! the low-Péclet regime.

/// Thermal properties of a solid.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ThermalSolid {
    /// Conductivity k, W/(m·K).
    pub conductivity: f64,
    /// Density ρ, kg/m³.
    pub density: f64,
    /// Specific heat c, J/(kg·K).
    pub specific_heat: f64,
}

impl ThermalSolid {
    /// Steel of seed 000 Table 1: k = 46 W/(m·K), ρ = 7850 kg/m³, c = 470 J/(kg·K).
    pub const STEEL: ThermalSolid = ThermalSolid { conductivity: 46.0, density: 7850.0, specific_heat: 470.0 };

    /// Diffusivity κ = k/(ρc), m²/s.
    pub fn diffusivity(&self) -> f64 {
        self.conductivity / (self.density * self.specific_heat)
    }
}

/// Maximum flash temperature rise (K) of a band contact of half-width `b` (m) and nominal area
/// `area` (m²) dissipating `power` (W), with surface speeds `v1`, `v2` relative to the contact
/// (m/s, sign ignored).
pub fn flash_temperature(power: f64, half_width: f64, area: f64, v1: f64, v2: f64, s1: &ThermalSolid, s2: &ThermalSolid) -> f64 {
    if !(power > 0.0 && half_width > 0.0 && area > 0.0) {
        return 0.0;
    }
    let q = power / area;
    let speed = |v: f64, s: &ThermalSolid| v.abs().max(2.0 * s.diffusivity() / half_width);
    let c1 = (s1.conductivity * s1.density * s1.specific_heat * speed(v1, s1)).sqrt();
    let c2 = (s2.conductivity * s2.density * s2.specific_heat * speed(v2, s2)).sqrt();
    1.596 * q * half_width.sqrt() / (c1 + c2)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn one_moving_surface_matches_the_transient_half_space() {
        // Heat all into surface 1 (surface 2 an insulator): θ = (2q/k) √(κ t/π), t = 2b/V.
        let s = ThermalSolid::STEEL;
        let insulator = ThermalSolid { conductivity: 1e-30, density: 1.0, specific_heat: 1.0 };
        let (b, v, q) = (1e-4, 5.0, 1e8);
        let theta = flash_temperature(q * 2.0 * b * 0.01, b, 2.0 * b * 0.01, v, 0.0, &s, &insulator);
        let t = 2.0 * b / v;
        let exact = 2.0 * q / s.conductivity * (s.diffusivity() * t / std::f64::consts::PI).sqrt();
        assert!((theta / exact - 1.0).abs() < 1e-3, "{theta} vs {exact}");
    }

    #[test]
    fn equal_surfaces_share_equally_and_zero_power_is_zero() {
        let s = ThermalSolid::STEEL;
        let one = flash_temperature(100.0, 1e-4, 1e-6, 4.0, 4.0, &s, &s);
        let single = flash_temperature(100.0, 1e-4, 1e-6, 4.0, 0.0, &s, &ThermalSolid { conductivity: 1e-30, ..s });
        assert!((one / single - 0.5).abs() < 1e-12);
        assert_eq!(flash_temperature(0.0, 1e-4, 1e-6, 4.0, 4.0, &s, &s), 0.0);
        assert!(flash_temperature(1.0, 1e-4, 1e-6, 0.0, 0.0, &s, &s).is_finite());
    }
}
