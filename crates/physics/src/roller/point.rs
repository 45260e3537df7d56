//! Point analysis of a roller follower (seed 001): the quasi-static torque balance of eq. 26 at a
//! fixed operating point (load, reduced radius, cam surface speed),
//!
//! `R_f F_t(u_s) = μ_rp R_pin F + I ω̇_r`,
//!
//! solved for the sliding velocity `u_s` (the film is re-solved at the entrainment
//! `u_e = u_c − u_s/2` until it is consistent). The contact point is taken as fixed (no
//! curvature-driven motion around the roller), as in seed 001.
//!
//! Thresholds:
//! * Coulomb asperities stick up to `μ_b W_a`: below the pin friction
//!   `μ_rp* = (R_f μ_b W_a − I ω̇)/(R_pin F)` the roller rolls without sliding (SRR = 0); the
//!   minimum cam–roller friction that still drives the roller is then `μ_b W_a/F` (seed 001's
//!   "gross sliding" case).
//! * Carter asperities creep: any resisting torque gives SRR > 0; the asperity share slides
//!   grossly from SRR = ξ_c = μ_b b/R, reached at the pin friction reported as the gross-sliding
//!   threshold.

use super::monotone_root;
use crate::film::{ContactInput, FilmModel, FilmSolution, Traction};
use crate::friction::micro_slip::nodal_saturation_creep;
use crate::friction::{micro_slip_share, AsperityModel, MICRO_SLIP_GROSS_SHARE};
use crate::SolveError;

/// A fixed operating point of a roller follower.
#[derive(Clone, Copy)]
pub struct PointCase<'a> {
    pub model: &'a dyn FilmModel,
    /// Contact description; `entrainment_velocity` and `sliding_velocity` are overwritten.
    pub input: ContactInput<'a>,
    /// Cam surface velocity u_c, m/s (> 0).
    pub cam_surface_velocity: f64,
    /// Roller outer radius R_f, m.
    pub roller_radius: f64,
    /// Pin radius, m.
    pub pin_radius: f64,
    /// Inertia torque I ω̇_r, N·m.
    pub inertia_torque: f64,
    /// The film at zero sliding solved from cold (`model.solve` at `input` with the entrainment
    /// `cam_surface_velocity`, no sliding, no time step, no previous solution), when the caller
    /// has it: used instead of solving it again (`None`: solved where needed).
    pub rolling: Option<&'a FilmSolution>,
}

/// The balance at one roller–pin friction coefficient.
#[derive(Debug, Clone, PartialEq)]
pub struct PointBalance {
    pub pin_friction: f64,
    /// u_s = u_c − u_r, m/s.
    pub sliding_velocity: f64,
    pub slide_roll_ratio: f64,
    /// Required cam–roller friction coefficient F_t/F.
    pub cam_roller_friction: f64,
    pub traction: Traction,
    pub film: FilmSolution,
    /// The asperities stick: the roller rolls without sliding.
    pub sticking: bool,
    /// Rolling, micro-slip or gross sliding.
    pub regime: crate::friction::SlipRegime,
}

impl PointCase<'_> {
    /// The film at sliding velocity `sliding`; `warm` (a solution at a nearby sliding velocity,
    /// no time step: not a squeeze history) lets a numerical model start from it.
    fn film_at(&self, sliding: f64, warm: Option<&FilmSolution>) -> Result<FilmSolution, SolveError> {
        if let Some(rolling) = self.rolling.filter(|_| sliding == 0.0 && warm.is_none()) {
            return Ok(rolling.clone());
        }
        let mut input = self.input;
        input.entrainment_velocity = self.cam_surface_velocity - 0.5 * sliding;
        input.sliding_velocity = sliding;
        input.time_step = 0.0;
        self.model.solve(&input, warm)
    }

    fn input_at(&self, sliding: f64) -> ContactInput<'_> {
        let mut input = self.input;
        input.entrainment_velocity = self.cam_surface_velocity - 0.5 * sliding;
        input.sliding_velocity = sliding;
        input
    }

    /// Solve the balance for roller–pin friction `mu_rp`.
    pub fn balance(&self, mu_rp: f64) -> Result<PointBalance, SolveError> {
        let load = self.input.load;
        let required = (mu_rp * self.pin_radius * load + self.inertia_torque) / self.roller_radius;
        let uc = self.cam_surface_velocity;
        let mut us = 0.0;
        let mut film = self.film_at(0.0, None)?;
        for _ in 0..20 {
            let input = self.input_at(us);
            let stick = self.model.traction(&film, &input, 0.0).stick_limit;
            let jumps = [if stick > 0.0 { 0.0 } else { f64::NAN }];
            let f = |x: f64, side: i8| {
                let inp = self.input_at(x);
                let t = self.model.traction(&film, &inp, x);
                let v = if x == 0.0 && side != 0 { t.force + side as f64 * t.stick_limit } else { t.force };
                (v - required, t.slope)
            };
            let next = monotone_root(f, &jumps, us, uc.abs().max(1e-6) * 1e-3)?;
            let converged = (next - us).abs() <= 1e-10 * uc.abs().max(1e-12);
            us = next;
            film = self.film_at(us, Some(&film))?;
            if converged {
                break;
            }
        }
        let input = self.input_at(us);
        let mut traction = self.model.traction(&film, &input, us);
        let sticking = us == 0.0 && required != 0.0;
        if us == 0.0 {
            traction.force = required;
        }
        let ur = uc - us;
        let regime = self.input.asperity_friction.regime(&film.asperity, &film.asperity_nodes, us, uc - 0.5 * us);
        Ok(PointBalance {
            pin_friction: mu_rp,
            sliding_velocity: us,
            slide_roll_ratio: crate::contact::slide_roll_ratio(uc, ur),
            cam_roller_friction: traction.force / load,
            traction,
            film,
            sticking,
            regime,
        })
    }

    /// Roller–pin friction at which the asperity traction saturates: the stick limit for
    /// Coulomb asperities, gross sliding (SRR = ξ_c) for Carter, 99 % of the limiting traction
    /// for the micro-slip map ([`MICRO_SLIP_GROSS_SHARE`]). `None` without asperity load.
    pub fn gross_sliding_pin_friction(&self) -> Result<Option<f64>, SolveError> {
        let film = self.film_at(0.0, None)?;
        let load = self.input.load;
        if film.asperity.load <= 0.0 {
            return Ok(None);
        }
        let traction = match self.input.asperity_friction.model {
            // The stick capacity on top of the film's traction at zero sliding (its rolling
            // resistance).
            AsperityModel::Coulomb => self.input.asperity_friction.coefficient * film.asperity.load + self.model.traction(&film, &self.input_at(0.0), 0.0).force,
            AsperityModel::Carter | AsperityModel::MicroSlip { .. } => {
                // Carter saturates at SRR = ξ_c; the micro-slip map reaches the gross-sliding
                // share (99 %) at SRR = t99 ξ_m (semi-elliptic), or where the solved nodes
                // transmit 99 % of what they can (the local map).
                let xc = match self.input.asperity_friction.model {
                    AsperityModel::MicroSlip { .. } if !film.asperity_nodes.is_empty() => {
                        nodal_saturation_creep(&film.asperity_nodes, MICRO_SLIP_GROSS_SHARE).unwrap_or(0.0)
                    }
                    AsperityModel::MicroSlip { .. } => micro_slip_gross_creep(film.asperity.exponent) * film.asperity.gross_sliding_creep,
                    _ => film.asperity.gross_sliding_creep,
                };
                let us = xc * self.cam_surface_velocity / (1.0 + 0.5 * xc);
                let film = self.film_at(us, Some(&film))?;
                self.model.traction(&film, &self.input_at(us), us).force
            }
        };
        // 0 when the film's rolling resistance alone exceeds what the asperities transmit: the
        // roller then slides at any pin friction.
        Ok(Some(((self.roller_radius * traction - self.inertia_torque) / (self.pin_radius * load)).max(0.0)))
    }

    /// Minimum cam–roller friction coefficient that still drives the roller (seed 001): the most
    /// the contact transmits while the asperities stick, `(μ_b W_a + F_R)/F` for Coulomb
    /// asperities (`F_R ≤ 0` the film's rolling resistance, which the stuck asperities must
    /// overcome too), 0 for the partial-slip laws (their traction vanishes with the sliding).
    pub fn min_cam_roller_friction(&self) -> Result<f64, SolveError> {
        let film = self.film_at(0.0, None)?;
        Ok(match self.input.asperity_friction.model {
            AsperityModel::Coulomb => {
                let rolling = self.model.traction(&film, &self.input_at(0.0), 0.0).force;
                (self.input.asperity_friction.coefficient * film.asperity.load + rolling).max(0.0) / self.input.load
            }
            AsperityModel::Carter | AsperityModel::MicroSlip { .. } => 0.0,
        })
    }
}

/// `t` at which [`micro_slip_share`] reaches [`MICRO_SLIP_GROSS_SHARE`] (bisection; Φ increases).
fn micro_slip_gross_creep(exponent: f64) -> f64 {
    let (mut lo, mut hi) = (0.0, 1e6);
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if micro_slip_share(mid, exponent).0 < MICRO_SLIP_GROSS_SHARE { lo = mid } else { hi = mid }
    }
    hi
}
