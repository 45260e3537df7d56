//! Unit conversions at the edge between specs (engineering units) and physics (SI). One place per
//! conversion, so every kind turns the same input into the same number.

use std::f64::consts::PI;

/// Shaft speed: revolutions per minute → angular velocity, rad/s (ω = 2π·n/60).
pub fn rpm_to_rad_per_s(rpm: f64) -> f64 {
    rpm * (2.0 * PI / 60.0)
}

/// Shaft speed: angular velocity, rad/s → revolutions per minute (n = ω·60/2π), evaluated as
/// `ω · 60 / (2π)` (the bearing kind's threshold speed has always been computed so).
pub fn rad_per_s_to_rpm(rad_per_s: f64) -> f64 {
    rad_per_s * 60.0 / (2.0 * PI)
}

/// Shaft speed: revolutions per minute → revolutions per second, 1/s.
pub fn rpm_to_rev_per_s(rpm: f64) -> f64 {
    rpm / 60.0
}

/// Running time of `revolutions` at `rpm`, hours.
pub fn hours_for_revolutions(revolutions: f64, rpm: f64) -> f64 {
    revolutions / (rpm * 60.0)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn speed_conversions() {
        assert!((rpm_to_rad_per_s(3000.0) - 314.159_265_358_979_3).abs() < 1e-12);
        assert_eq!(rpm_to_rev_per_s(3000.0), 50.0);
        assert_eq!(hours_for_revolutions(180_000.0, 3000.0), 1.0);
        assert!((rad_per_s_to_rpm(rpm_to_rad_per_s(3000.0)) - 3000.0).abs() < 1e-9);
    }
}

/// Seconds to hours.
pub fn seconds_to_hours(seconds: f64) -> f64 {
    seconds / 3600.0
}
