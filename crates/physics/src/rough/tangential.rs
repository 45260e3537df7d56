//! Tangential (stick–slip, partial-slip) contact at a solved normal contact (seed 001 eq. 14–18;
//! the model of Bazrafshan et al. 2017, quasi-static, elastic in shear): the flat is displaced
//! rigidly by `δx`; on the contact area the traction `q_x` is bounded by Coulomb,
//! `|q_x| ≤ μ_lim p_a` (eq. 15); where it is below the bound the node sticks, `u_x = δx` (slip
//! `s_x = u_x − δx = 0`, eq. 14); elsewhere it slips with `|q_x| = μ_lim p_a`. Off the contact area
//! `q_x = 0`. `q_y = 0` (seed 001: `F_y = 0`) and `u_y` is not constrained (Mindlin's
//! approximation, exact for Cattaneo–Mindlin's sphere).
//!
//! The normal pressure is an input: the coupling between normal and tangential tractions is
//! proportional to Dundurs' β, zero for elastically similar bodies (seed 001's assumption; for
//! dissimilar bodies it is neglected, see [`RoughMaterial::dundurs_beta`]).
//!
//! Influence: the periodic Cerruti response of the pair (Johnson §3.7 in Fourier form),
//! `û_x = (Σ1/G_i − Σν_i/G_i · k_x²/|k|²) q̂_x / |k|`, zero at `k = 0`: `δx` is the displacement of
//! the flat relative to the mean (macroscopic) tangential displacement of the rough surface.

use super::cg::{BoxCg, Control};
use super::fft::Convolution;
use super::normal::NormalContact;
use super::{RoughMaterial, RoughOptions, RoughSurface};
use crate::{ensure_finite, Convergence, Observer, PhysicalFailure, SolveError};

/// The solved tangential contact.
#[derive(Debug, Clone, PartialEq)]
pub struct TangentialContact {
    /// Shear traction `q_x` per node, Pa.
    pub traction: Vec<f64>,
    /// Rigid tangential displacement `δx` of the flat, m.
    pub displacement: f64,
    /// Asperity friction coefficient `μ_a = F_x/F_z = |q̄|/p̄_a` (seed 001 eq. 16–18), signed like `δx`.
    pub friction_coefficient: f64,
    /// Stick nodes over contact nodes (1: full stick, 0: gross sliding).
    pub stick_fraction: f64,
    /// Stick area over nominal area.
    pub stick_area_fraction: f64,
    pub convergence: Convergence,
}

pub(crate) struct TangentialSolver<'a> {
    normal: &'a NormalContact,
    op: Convolution,
    lower: Vec<f64>,
    upper: Vec<f64>,
    friction: f64,
    /// Displacement at which the whole contact slides, m.
    pub(crate) gross_sliding: f64,
    contact_nodes: usize,
    options: RoughOptions,
}

impl<'a> TangentialSolver<'a> {
    pub(crate) fn new(
        surface: &RoughSurface,
        material: &RoughMaterial,
        normal: &'a NormalContact,
        friction: f64,
        options: &RoughOptions,
    ) -> Result<Self, SolveError> {
        options.check()?;
        if normal.pressure.len() != surface.len() {
            return Err(SolveError::invalid("NormalContact.pressure", "must be the solution on this surface's grid"));
        }
        if !(friction.is_finite() && friction > 0.0) {
            return Err(SolveError::invalid("ContactLimits.friction", "must be finite and > 0"));
        }
        let contact_nodes = normal.pressure.iter().filter(|&&p| p > 0.0).count();
        if contact_nodes == 0 {
            return Err(SolveError::physical(PhysicalFailure::NoContactLoad, "no asperity is in contact: no tangential contact"));
        }
        let (a, b) = material.tangential_compliance();
        let op = Convolution::new(surface.nx, surface.ny, surface.spacing, |kx, ky| {
            let k2 = kx * kx + ky * ky;
            if k2 > 0.0 { (a - b * kx * kx / k2) / k2.sqrt() } else { 0.0 }
        });
        let upper: Vec<f64> = normal.pressure.iter().map(|p| friction * p).collect();
        let lower: Vec<f64> = upper.iter().map(|u| -u).collect();
        // Gross sliding: every contact node at the Coulomb bound is a solution once
        // `δx ≥ (K μ p)_i` on every contact node (the stick condition then fails everywhere).
        let mut u = vec![0.0; upper.len()];
        op.apply(&upper, &mut u, &mut op.workspace());
        let gross_sliding = (0..u.len()).filter(|&i| normal.pressure[i] > 0.0).map(|i| u[i]).fold(f64::MIN, f64::max);
        if !(gross_sliding.is_finite() && gross_sliding > 0.0) {
            return Err(SolveError::NonFinite { quantity: "gross sliding displacement".into() });
        }
        Ok(TangentialSolver { normal, op, lower, upper, friction, gross_sliding, contact_nodes, options: *options })
    }

    pub(crate) fn solve(&self, displacement: f64, initial: Option<&[f64]>, observer: &dyn Observer) -> Result<TangentialContact, SolveError> {
        if !displacement.is_finite() {
            return Err(SolveError::invalid("displacement", "must be finite"));
        }
        let n = self.upper.len();
        let sign = if displacement < 0.0 { -1.0 } else { 1.0 };
        let delta = displacement.abs();
        let fz: f64 = self.normal.pressure.iter().sum();
        if delta >= self.gross_sliding {
            return Ok(TangentialContact {
                traction: self.upper.iter().map(|q| sign * q).collect(),
                displacement,
                friction_coefficient: sign * self.friction,
                stick_fraction: 0.0,
                stick_area_fraction: 0.0,
                convergence: Convergence::closed_form(),
            });
        }
        let x0 = match initial {
            Some(q) if q.len() == n && q.iter().all(|v| v.is_finite()) => q.iter().map(|v| sign * v).collect(),
            Some(_) => return Err(SolveError::invalid("initial traction", "must hold one finite value per node")),
            None => vec![0.0; n],
        };
        let target = vec![0.0; n];
        // Gradient K q − δx: minus the slip (eq. 14); zero on stick nodes.
        let s = BoxCg {
            op: &self.op,
            target: &target,
            lower: &self.lower,
            upper: &self.upper,
            control: Control::Shift(-delta),
            scale: self.gross_sliding,
            tolerance: self.options.tolerance,
            max_iterations: self.options.max_iterations,
            solver: "rough tangential contact",
        }
        .solve(x0, observer)?;
        let traction: Vec<f64> = s.x.iter().map(|q| sign * q).collect();
        ensure_finite("rough contact shear traction", &traction)?;
        let stick = (0..n).filter(|&i| s.x[i] > self.lower[i] && s.x[i] < self.upper[i]).count();
        let fx: f64 = traction.iter().sum();
        Ok(TangentialContact {
            displacement,
            friction_coefficient: fx / fz,
            stick_fraction: stick as f64 / self.contact_nodes as f64,
            stick_area_fraction: stick as f64 / n as f64,
            traction,
            convergence: s.convergence,
        })
    }
}

/// The rigid tangential displacement at which the whole contact slides (stick area → 0,
/// `μ_a → μ_lim`), m: `max over the contact area of u_x(μ_lim p_a)`.
pub fn gross_sliding_displacement(
    surface: &RoughSurface,
    material: &RoughMaterial,
    normal: &NormalContact,
    friction: f64,
) -> Result<f64, SolveError> {
    Ok(TangentialSolver::new(surface, material, normal, friction, &RoughOptions::default())?.gross_sliding)
}

/// Solves the partial-slip problem for the rigid displacement `displacement` (m) at the normal
/// contact `normal` with Coulomb coefficient `friction`. `initial` warm-starts the traction.
pub fn solve_tangential(
    surface: &RoughSurface,
    material: &RoughMaterial,
    normal: &NormalContact,
    friction: f64,
    displacement: f64,
    options: &RoughOptions,
    initial: Option<&[f64]>,
    observer: &dyn Observer,
) -> Result<TangentialContact, SolveError> {
    TangentialSolver::new(surface, material, normal, friction, options)?.solve(displacement, initial, observer)
}
