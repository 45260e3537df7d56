//! Seed 004's closed forms for a multi-arc cam against a spherical tappet face, in the paper's
//! own units (N, mm, MPa), for reproducing its tables (the wear kind builds on them).
//!
//! * Reduced radius of an arc `r_c` against the tappet sphere `r_t` in the rolling plane:
//!   `ρ = r_c r_t/(r_c + r_t)` (Table 1).
//! * Contact width, eq. 2: `B = 2.1 (√(F ρ) (1 − μ²)/√E)^0.67` mm, and contact area, eq. 3:
//!   `A = 4.39 (√(F ρ) (1 − μ²)/√E)^1.34` mm², with the spring force `F = z_n h` (N), ρ in mm and
//!   E in MPa. With E = 2.1e5 MPa and μ = 0.3 they reproduce Table 3 within 1 %. Both scale like
//!   `(Fρ/E)^(1/3)` as a Hertzian circular contact would, but the paper's constants are empirical
//!   (and eq. 3 is not `π B²/4`); the physical model of this project is
//!   [`crate::contact::hertz_point`] with `R_x = ρ`, `R_y = r_t`.
//! * Arc length, eq. 1 as printed: `l = 2αr/360` (α in degrees) — a factor π short of the true
//!   length `παr/180` ([`super::Arc::length`]); reproduced here only to compare with Table 2.

/// Reduced radius of a cam arc `r_cam` and a tappet sphere `r_tappet` (any length unit).
pub fn reduced_radius(r_cam: f64, r_tappet: f64) -> f64 {
    r_cam * r_tappet / (r_cam + r_tappet)
}

fn group(force_n: f64, reduced_radius_mm: f64, youngs_mpa: f64, poisson: f64) -> f64 {
    (force_n * reduced_radius_mm).sqrt() * (1.0 - poisson * poisson) / youngs_mpa.sqrt()
}

/// Seed 004 eq. 2: contact width, mm.
pub fn contact_width_mm(force_n: f64, reduced_radius_mm: f64, youngs_mpa: f64, poisson: f64) -> f64 {
    2.1 * group(force_n, reduced_radius_mm, youngs_mpa, poisson).powf(0.67)
}

/// Seed 004 eq. 3: contact area, mm².
pub fn contact_area_mm2(force_n: f64, reduced_radius_mm: f64, youngs_mpa: f64, poisson: f64) -> f64 {
    4.39 * group(force_n, reduced_radius_mm, youngs_mpa, poisson).powf(1.34)
}

/// Seed 004 eq. 1 as printed: `2αr/360` (α in degrees).
pub fn arc_length_as_printed(angle_deg: f64, radius: f64) -> f64 {
    2.0 * angle_deg * radius / 360.0
}
