//! Operating-limit checks of a plain bearing (ISO 7902-3 / DIN 31652-3 style): the minimum film
//! against the permissible one (the surfaces' roughness plus an allowance), the specific load
//! `W/(L D)` and the maximum bulk temperature against their permissible values.

/// Permissible values.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct OperatingLimits {
    /// Journal roughness Rz, m.
    pub journal_roughness: f64,
    /// Bearing (bore) roughness Rz, m.
    pub bearing_roughness: f64,
    /// Extra allowance in the permissible film, m.
    pub film_allowance: f64,
    /// Permissible maximum bulk temperature, K.
    pub max_temperature: f64,
    /// Permissible specific load `W/(L D)`, Pa.
    pub max_specific_load: f64,
}

/// One check.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LimitCheck {
    pub value: f64,
    pub limit: f64,
    pub pass: bool,
    /// `(value − limit)/limit` for a lower limit, `(limit − value)/limit` for an upper one.
    pub margin: f64,
}

/// The checks of one operating point.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LimitChecks {
    /// Minimum film, m, against `journal_roughness + bearing_roughness + film_allowance`.
    pub min_film: LimitCheck,
    /// Specific load `W/(L D)`, Pa.
    pub specific_load: LimitCheck,
    /// Maximum bulk temperature, K (with a heat balance).
    pub max_temperature: Option<LimitCheck>,
    /// Every check passes.
    pub pass: bool,
}

/// Check a bearing of radius `radius` and length `length` (m) with minimum film `min_film` (m)
/// under the load `force` (N), at the maximum bulk temperature `max_temperature` (K) when known.
pub fn check_limits(min_film: f64, force: f64, radius: f64, length: f64, max_temperature: Option<f64>, lim: &OperatingLimits) -> LimitChecks {
    let lower = |value: f64, limit: f64| LimitCheck { value, limit, pass: value >= limit, margin: if limit > 0.0 { (value - limit) / limit } else { 0.0 } };
    let upper = |value: f64, limit: f64| LimitCheck { value, limit, pass: value <= limit, margin: (limit - value) / limit };
    let min_film = lower(min_film, lim.journal_roughness + lim.bearing_roughness + lim.film_allowance);
    let specific_load = upper(force / (2.0 * radius * length), lim.max_specific_load);
    let max_temperature = max_temperature.map(|t| upper(t, lim.max_temperature));
    let pass = min_film.pass && specific_load.pass && max_temperature.is_none_or(|c| c.pass);
    LimitChecks { min_film, specific_load, max_temperature, pass }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn checks_pass_and_fail_with_their_margins() {
        let lim = OperatingLimits { journal_roughness: 2e-6, bearing_roughness: 3e-6, film_allowance: 1e-6, max_temperature: 383.15, max_specific_load: 5e6 };
        // 8 kN on R = 50 mm, L = 40 mm: 2 MPa
        let c = check_limits(12e-6, 8000.0, 0.05, 0.04, Some(390.0), &lim);
        assert!(c.min_film.pass && (c.min_film.margin - 1.0).abs() < 1e-12);
        assert!(c.specific_load.pass && (c.specific_load.value - 2e6).abs() < 1e-6);
        let t = c.max_temperature.unwrap();
        assert!(!t.pass && t.margin < 0.0);
        assert!(!c.pass);
        assert!(check_limits(12e-6, 8000.0, 0.05, 0.04, None, &lim).pass);
    }
}
