//! Deterministic dry rough contact (seed 001, "Asperity contact component", eq. 8–23): the normal
//! contact of a rough surface against a rigid flat with a plastic pressure cap, the asperity
//! pressure–film curve `p̄_a(h)` and the micro-slip (stick–slip) friction map `μ_a(h, δx)` that the
//! mixed-lubrication model consumes.
//!
//! * [`surface`]: periodic rough surfaces (Gaussian random, measured table), their summary and
//!   the combined surface of two rough bodies (sum of heights: the equivalent rough-on-flat
//!   problem, seed 001 §"Asperity contact component").
//! * [`normal`]: the normal problem (seed 001 eq. 10) by the constrained conjugate gradient of
//!   Polonsky & Keer (Wear 231, 1999) extended with the box constraint `0 ≤ p ≤ p_lim`, on a
//!   periodic domain with FFT influence coefficients; load-, separation- and film-controlled.
//! * [`tangential`]: the partial-slip problem (seed 001 eq. 14–18) with the Coulomb bound
//!   `|q_x| ≤ μ_lim p_a`, same method, Cerruti influence coefficients.
//! * [`maps`]: [`AsperityMaps`], the precalculated `p̄_a(h)` (eq. 11–12) and `μ_a(h, δx)`
//!   (eq. 19) with smooth monotone interpolants and their derivatives.
//!
//! Conventions: heights `z` point towards the rigid flat; the gap is `g = d − z + u_z` with `d`
//! the separation between the flat and the mean plane of the (deformed) rough surface and `u_z`
//! the elastic displacement away from the flat. The periodic half-space has no mean (k = 0)
//! displacement (it is the macroscopic, EHL-scale deformation), so `d` is the mean separation and,
//! for an elastic contact, equals the mean gap `h` of eq. 9.
//!
//! Moduli: every formula here takes Johnson's `E* = 1/Σ(1−ν²)/E` ([`RoughMaterial::contact_modulus`]).
//! Seed 001 eq. 4 defines `E' = 2/Σ(1−ν²)/E = 2E*` (Hamrock–Dowson, `contact::effective_modulus`),
//! so its eq. 10 kernel `u_z = 2/(πE') ∫∫ p/r` is Johnson's `1/(πE*) ∫∫ p/r` (eq. 3.22 summed over
//! both bodies); in Fourier space `û_z = 2 p̂ /(E* |k|)` (Johnson §13.1).

pub mod maps;
pub mod normal;
pub mod surface;
pub mod tangential;

mod cg;
pub(crate) mod fft;
mod pchip;

pub use maps::{AsperityMaps, MapGrids};
pub use normal::{solve_normal, NormalContact, NormalControl};
pub use surface::{RoughSurface, SurfaceSummary};
pub use tangential::{gross_sliding_displacement, solve_tangential, TangentialContact};

use super::contact::{contact_modulus, Elastic};
use super::SolveError;

/// Largest grid side (nodes per direction) the solvers accept: a 1024×1024 grid holds about
/// 18 arrays of 8 MiB (≈ 150 MiB with the FFT buffers).
pub const MAX_GRID_SIDE: usize = 1024;

/// The two elastic bodies of the rough contact.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RoughMaterial {
    pub body1: Elastic,
    pub body2: Elastic,
}

impl RoughMaterial {
    /// Both bodies checked: `E > 0` finite, `0 ≤ ν < 0.5`.
    pub fn new(body1: Elastic, body2: Elastic) -> Result<Self, SolveError> {
        for (name, b) in [("RoughMaterial.body1", body1), ("RoughMaterial.body2", body2)] {
            if !(b.youngs_modulus.is_finite() && b.youngs_modulus > 0.0) {
                return Err(SolveError::invalid(name, "Young's modulus must be finite and > 0"));
            }
            if !(b.poisson_ratio.is_finite() && (0.0..0.5).contains(&b.poisson_ratio)) {
                return Err(SolveError::invalid(name, "Poisson's ratio must be in [0, 0.5)"));
            }
        }
        Ok(RoughMaterial { body1, body2 })
    }

    /// Seed 001 Table 1: both bodies E = 200 GPa, ν = 0.3.
    pub fn seed001() -> Self {
        let steel = Elastic { youngs_modulus: 200e9, poisson_ratio: 0.3 };
        RoughMaterial { body1: steel, body2: steel }
    }

    /// Johnson's `E* = 1/Σ(1−ν²)/E`, Pa (seed 001 eq. 4's `E'` is `2E*`).
    pub fn contact_modulus(&self) -> f64 {
        contact_modulus(self.body1, self.body2)
    }

    /// Dundurs' second parameter β (Johnson eq. 5.4). The solvers neglect the coupling between
    /// normal and tangential tractions, which is exact for β = 0 (elastically similar bodies, as
    /// in seed 001: "all interacting solids share similar material properties").
    pub fn dundurs_beta(&self) -> f64 {
        let g = |b: Elastic| b.youngs_modulus / (2.0 * (1.0 + b.poisson_ratio));
        let (g1, g2) = (g(self.body1), g(self.body2));
        let (n1, n2) = (self.body1.poisson_ratio, self.body2.poisson_ratio);
        ((1.0 - 2.0 * n1) / g1 - (1.0 - 2.0 * n2) / g2) / (2.0 * ((1.0 - n1) / g1 + (1.0 - n2) / g2))
    }

    /// Relative tangential compliance of the pair in Fourier space (Cerruti, Johnson §3.7):
    /// `û_x = (a − b k_x²/|k|²) q̂_x / |k|` with `a = Σ 1/G_i`, `b = Σ ν_i/G_i`. Returns `(a, b)`.
    pub(crate) fn tangential_compliance(&self) -> (f64, f64) {
        let g = |b: Elastic| b.youngs_modulus / (2.0 * (1.0 + b.poisson_ratio));
        let (g1, g2) = (g(self.body1), g(self.body2));
        (1.0 / g1 + 1.0 / g2, self.body1.poisson_ratio / g1 + self.body2.poisson_ratio / g2)
    }
}

/// Upper limits of the asperity tractions (seed 001 Table 1: `p_a,lim` = 6 GPa, `μ_a,lim` = 0.12).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ContactLimits {
    /// Plastic flow pressure `p_a,lim`, Pa (`f64::INFINITY`: purely elastic).
    pub pressure: f64,
    /// Coulomb coefficient `μ_a,lim` of the boundary layers (sliding friction).
    pub friction: f64,
}

impl ContactLimits {
    /// Seed 001 Table 1.
    pub const SEED001: ContactLimits = ContactLimits { pressure: 6e9, friction: 0.12 };

    pub(crate) fn check(&self) -> Result<(), SolveError> {
        if !(self.pressure > 0.0) || self.pressure.is_nan() {
            return Err(SolveError::invalid("ContactLimits.pressure", "must be > 0 (infinity: elastic)"));
        }
        if !(self.friction.is_finite() && self.friction > 0.0) {
            return Err(SolveError::invalid("ContactLimits.friction", "must be finite and > 0"));
        }
        Ok(())
    }
}

/// Resolution is the surface grid; these bound the iterations.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RoughOptions {
    /// Complementarity residual (largest violation of the contact conditions: gap on the free
    /// nodes, negative gap on the open nodes, positive gap on the capped ones) relative to the
    /// surface's peak-to-valley height (normal) or to the tangential displacement (tangential).
    pub tolerance: f64,
    /// Conjugate-gradient iteration cap of one solve.
    pub max_iterations: u32,
}

impl Default for RoughOptions {
    fn default() -> Self {
        RoughOptions { tolerance: 1e-7, max_iterations: 3000 }
    }
}

impl RoughOptions {
    pub(crate) fn check(&self) -> Result<(), SolveError> {
        if !(self.tolerance.is_finite() && self.tolerance > 0.0 && self.tolerance < 1.0) {
            return Err(SolveError::invalid("RoughOptions.tolerance", "must be in (0, 1)"));
        }
        if self.max_iterations == 0 {
            return Err(SolveError::invalid("RoughOptions.max_iterations", "must be ≥ 1"));
        }
        Ok(())
    }
}
