//! Friction of a lubricated concentrated contact: viscous traction of the film (Newtonian or
//! Eyring, optionally capped by a limiting shear stress) integrated over the contact, plus the
//! asperity friction of the load share carried by the roughness (Greenwood–Tripp).
//!
//! The film model (see [`crate::film`]) reduces a contact to a handful of
//! [`TractionNode`]s — area, local pressure, low-shear viscosity, film thickness — once per contact
//! point; [`viscous_traction`] then evaluates the traction for any sliding velocity cheaply, which
//! is what the roller torque balance needs inside its root finder.
//!
//! Shear stress on the follower's surface at a node for sliding velocity `u_s` (seed 001 eq. 24–25):
//! the Couette part `η u_s / h` plus the node's Poiseuille part `τ_p = −(h/2) dp/dx` (the rolling
//! resistance of the film: it acts on both surfaces alike, against the entrainment, wherever the
//! pressure gradient is resolved — the numerical models' nodes; closed forms carry it as one
//! integrated force, [`crate::film::FilmSolution::rolling_force`]):
//! * Newtonian: `τ = η u_s / h + τ_p`;
//! * Eyring: `τ = τ0 asinh((η u_s / h + τ_p)/τ0)` (seed 001 eq. 25 applied to eq. 24's total, τ0 the
//!   Eyring stress);
//! * limiting shear (optional): `|τ| ≤ Λ p`.

pub mod curve;
pub mod greenwood_tripp;
pub mod micro_slip;

pub use curve::PressureGapCurve;
pub use greenwood_tripp::{f52, Roughness};
pub use micro_slip::{AsperityNode, MicroSlipMap};

/// Shear law of the lubricant film.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Rheology {
    Newtonian,
    /// Eyring with characteristic stress `tau0`, Pa.
    Eyring { tau0: f64 },
}

/// Film traction law.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TractionLaw {
    pub rheology: Rheology,
    /// Limiting shear stress coefficient Λ (`|τ| ≤ Λ p`), if any.
    pub limiting_shear_coefficient: Option<f64>,
}

/// One quadrature node of a contact for the traction integral.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TractionNode {
    /// Area represented by the node, m².
    pub area: f64,
    /// Fluid pressure at the node, Pa.
    pub pressure: f64,
    /// Low-shear viscosity at the node's pressure and temperature, Pa·s.
    pub viscosity: f64,
    /// Film thickness at the node, m (> 0).
    pub film: f64,
    /// Poiseuille shear stress on the surfaces at the node, `−(h/2) dp/dx` along the positive
    /// sense of the surface velocities, Pa (seed 001 eq. 24; 0 where the model does not resolve
    /// the pressure gradient).
    pub poiseuille: f64,
}

/// Viscous traction force (N, same sign as `u_s`) and its derivative with respect to `u_s`
/// (N·s/m) over `nodes`.
pub fn viscous_traction(nodes: &[TractionNode], law: &TractionLaw, sliding_velocity: f64) -> (f64, f64) {
    let v = viscous_traction_local(nodes, law, sliding_velocity);
    (v.force, v.slope)
}

/// [`viscous_traction`] with what bounds its second derivative nearby.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LocalTraction {
    /// Force, N.
    pub force: f64,
    /// dF/du_s, N·s/m.
    pub slope: f64,
    /// |d²F/du_s²| at `u_s`, N·s²/m².
    pub curvature: f64,
    /// Within this distance of `u_s` (m/s) the traction is twice differentiable and
    /// `|d²F/du_s²| ≤ 1.5 × curvature`.
    pub smooth_reach: f64,
}

/// Eyring: per node `d²τ/du² = −(g²/τ0) φ(x)`, `φ(x) = x/(1 + x²)^{3/2}`, `x = (g u + τ_p)/τ0 =
/// g (u − u_p)/τ0`, `g = η/h`, `u_p = −τ_p/g` (the sliding speed at which the node's stress
/// vanishes). Within a tenth of `|u − u_p|` of `u` the node's `x` moves by at most a tenth of
/// itself, where `|φ|` stays below 1.5 times its value (at most `1/0.9²` for large `x`), hence
/// the reach `0.1 min |u − u_p|` (`0.1 |u|` without Poiseuille stresses). A limiting-shear cap
/// switches on or off where the uncapped stress crosses it; as `|dτ/du| ≤ g`, that is at least
/// `|τ − Λp|/g` away. Newtonian nodes have no curvature.
pub fn viscous_traction_local(nodes: &[TractionNode], law: &TractionLaw, sliding_velocity: f64) -> LocalTraction {
    let u = sliding_velocity;
    let eyring = matches!(law.rheology, Rheology::Eyring { .. });
    let mut out = LocalTraction { force: 0.0, slope: 0.0, curvature: 0.0, smooth_reach: f64::INFINITY };
    for n in nodes {
        let g = n.viscosity / n.film; // shear modulus of the rate: τ_N = g u + τ_p
        let newtonian = g * u + n.poiseuille;
        let (mut tau, mut dtau, mut ddtau) = match law.rheology {
            Rheology::Newtonian => (newtonian, g, 0.0),
            Rheology::Eyring { tau0 } => {
                let x = newtonian / tau0;
                let r2 = x * x + 1.0;
                let r = r2.sqrt();
                // asinh(x) = sign(x) ln(|x| + r), stable for large |x|.
                (tau0 * x.signum() * (x.abs() + r).ln(), g / r, g * g / tau0 * x.abs() / (r2 * r))
            }
        };
        if eyring && g > 0.0 {
            out.smooth_reach = out.smooth_reach.min(0.1 * (u + n.poiseuille / g).abs());
        }
        if let Some(lam) = law.limiting_shear_coefficient {
            let cap = lam * n.pressure.max(0.0);
            if g > 0.0 {
                out.smooth_reach = out.smooth_reach.min((tau.abs() - cap).abs() / g);
            }
            if tau.abs() > cap {
                tau = cap * tau.signum();
                dtau = 0.0;
                ddtau = 0.0;
            }
        }
        out.force += n.area * tau;
        out.slope += n.area * dtau;
        out.curvature += n.area * ddtau;
    }
    out
}

/// The film's rolling (Poiseuille) force on each surface over `nodes`, Newtonian (`Σ A τ_p`), N
/// along the positive sense of the surface velocities (negative: against the entrainment).
pub fn poiseuille_force(nodes: &[TractionNode]) -> f64 {
    nodes.iter().map(|n| n.area * n.poiseuille).sum()
}

/// Friction law of the asperity-borne load share.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum AsperityModel {
    /// Gross sliding: `Q_a = μ_b W_a sign(u_s)` (set-valued at `u_s = 0`: the asperities stick and
    /// transmit any traction up to `μ_b W_a`). Seed 001's "constant asperity friction" case.
    Coulomb,
    /// Partial slip (Carter's 2D rolling-creep law applied to the asperity share; Johnson,
    /// *Contact Mechanics* §8.2): `Q_a/(μ_b W_a) = 1 − (1 − |ξ|/ξ_c)²` for `|ξ| < ξ_c`, 1 beyond,
    /// with creep `ξ = u_s/u_e` (the slide-to-roll ratio) and gross-sliding creep `ξ_c = μ_b b/R`.
    /// A smooth analogue of seed 001's stick–slip asperity friction map.
    Carter,
    /// Seed 001's micro-slip map (eq. 14–23) at the macroscale: each point of the contact has
    /// been displaced tangentially by `δx = SRR (x − x_in)` since it entered at `x_in = −a`
    /// (eq. 22), and its asperities carry `μ_a/μ_lim = g(δx/δx_gs)` of their limiting friction,
    /// sticking–slipping below the gross-sliding displacement `δx_gs` of the rough surface
    /// (eq. 19, 23) and sliding beyond it. Integrated over a semi-elliptic asperity pressure
    /// (eq. 25's asperity term) — see [`micro_slip_share`] — by the closed forms; over the solved
    /// asperity pressure `p_a(x)` node by node (each with its own film) by the numerical film
    /// ([`micro_slip`]). With [`AsperityFriction::map`] the two constants below give way to the
    /// map's `δx_gs(h)` and `n(h)`.
    MicroSlip {
        /// Gross-sliding displacement `δx_gs` of the asperity contact, m (e.g. from a
        /// `rough_contact` job's tangential solution at the working film).
        gross_sliding_displacement: f64,
        /// Exponent `n ≥ 2` of the local shape `μ_a/μ_lim = 1 − (1 − δx/δx_gs)^n`.
        exponent: f64,
    },
}

/// The share `Φ(t)` of the limiting asperity traction that a contact transmits at creep
/// `|SRR| = t ξ_m`, `ξ_m = δx_gs/a`, and `(dΦ/dt, bound on |d²Φ/dt²|)`, for
/// [`AsperityModel::MicroSlip`] with the local partial-slip shape `μ_a/μ_lim = g(s) =
/// 1 − (1 − s)^n`, `s = δx/δx_gs ≤ 1` (seed 001 Fig. 7b; `n = 2` is the 2-D Carter/
/// Cattaneo shape; the maps of `physics::rough` at seed 001's surface follow `n ≈ 3` at the
/// working films, BENCHMARKS.md "Mixed lubrication: the micro-slip map").
///
/// With `X = x/a`, `y = 1 + X` (eq. 22: `δx = SRR·a·y`) and the load share of a semi-elliptic
/// asperity pressure `w(X) = (2/π)√(1 − X²)`: `Φ(t) = ∫ g(min(1, t y)) w dX`. In `X = −cos θ`
/// the points beyond `θ* = acos(1 − 1/t)` slide (`θ* = π` for `t ≤ 1/2`); their share is
/// `(2/π)(π/2 − θ*/2 + sin 2θ*/4)`, the rest is a 32-point Gauss–Legendre quadrature of
/// `(2/π) sin²θ g(t(1 − cos θ))` on `[0, θ*]` (exact to round-off for integer `n`).
/// `|Φ''| ≤ (5/4) n(n − 1)`.
pub fn micro_slip_share(t: f64, n: f64) -> (f64, f64, f64) {
    use std::f64::consts::PI;
    let t = t.abs();
    let theta = if t <= 0.5 { PI } else { (1.0 - 1.0 / t).acos() };
    let (s2, c2) = (2.0 * theta).sin_cos();
    let _ = c2;
    let k = 2.0 / PI;
    let sliding = k * (0.5 * PI - 0.5 * theta + 0.25 * s2);
    let (nodes, weights) = gauss_legendre_32();
    let (mut phi, mut dphi) = (sliding, 0.0);
    for (x, w) in nodes.iter().zip(weights) {
        let th = 0.5 * theta * (1.0 + x);
        let (sn, cs) = th.sin_cos();
        let y = 1.0 - cs;
        let s = (t * y).min(1.0);
        let rest = 1.0 - s;
        let wt = 0.5 * theta * w * k * sn * sn;
        phi += wt * (1.0 - rest.powf(n));
        dphi += wt * n * rest.powf(n - 1.0) * y;
    }
    (phi.clamp(0.0, 1.0), dphi.max(0.0), 1.25 * n * (n - 1.0))
}

/// Nodes and weights of the 32-point Gauss–Legendre rule on `[−1, 1]` (Newton on `P_32`).
fn gauss_legendre_32() -> &'static ([f64; 32], [f64; 32]) {
    static RULE: std::sync::OnceLock<([f64; 32], [f64; 32])> = std::sync::OnceLock::new();
    RULE.get_or_init(|| {
        const N: usize = 32;
        let (mut x, mut w) = ([0.0; N], [0.0; N]);
        for i in 0..N {
            let mut z = (std::f64::consts::PI * (i as f64 + 0.75) / (N as f64 + 0.5)).cos();
            let mut dp = 1.0;
            for _ in 0..100 {
                let (mut p0, mut p1) = (1.0, z);
                for j in 2..=N {
                    let p2 = ((2 * j - 1) as f64 * z * p1 - (j - 1) as f64 * p0) / j as f64;
                    p0 = p1;
                    p1 = p2;
                }
                dp = N as f64 * (z * p1 - p0) / (z * z - 1.0);
                let dz = p1 / dp;
                z -= dz;
                if dz.abs() < 1e-16 {
                    break;
                }
            }
            x[i] = z;
            w[i] = 2.0 / ((1.0 - z * z) * dp * dp);
        }
        (x, w)
    })
}

/// Share of the limiting asperity traction from which [`AsperityModel::MicroSlip`] counts as
/// gross sliding: 99 %.
pub const MICRO_SLIP_GROSS_SHARE: f64 = 0.99;

/// How the roller runs on the cam at one instant (seed 001 §"Tangential contact", eq. 15–23).
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum SlipRegime {
    /// No sliding: the asperities stick (`u_s = 0`), or in a full film the slide-to-roll ratio
    /// stays below [`FULL_FILM_SKID_SRR`].
    Rolling,
    /// Partial slip of the asperity contact: part of it sticks, part slips (Carter below its
    /// gross-sliding creep).
    MicroSlip,
    /// The whole asperity contact slides (Coulomb asperities with any sliding; Carter at or
    /// beyond its gross-sliding creep), or a full film at `|SRR| ≥` [`FULL_FILM_SKID_SRR`].
    GrossSliding,
}

/// Slide-to-roll ratio from which a full-film contact (no asperity load) counts as
/// [`SlipRegime::GrossSliding`] (skidding): 1 %, the order at which roller-follower studies
/// (seed 000 §4) speak of skidding. Without asperities there is no stick, so the split between
/// rolling and sliding of a film is a convention; this one is documented in the API.
pub const FULL_FILM_SKID_SRR: f64 = 0.01;

/// Asperity friction parameters.
#[derive(Debug, Clone, PartialEq)]
pub struct AsperityFriction {
    /// Boundary (asperity) friction coefficient μ_b.
    pub coefficient: f64,
    pub model: AsperityModel,
    /// [`AsperityModel::MicroSlip`]: `δx_gs(h)` and `n(h)` per film (seed 001 eq. 19, 23), in
    /// place of the model's constants. `None`: the constants.
    pub map: Option<std::sync::Arc<MicroSlipMap>>,
}

/// The asperity part of a contact's traction at one instant.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct AsperityContact {
    /// Load carried by the asperities, N.
    pub load: f64,
    /// Creep scale of the partial-slip law ([`AsperityFriction::creep_scale`]): Carter's
    /// gross-sliding creep ξ_c = μ_b b/R, the micro-slip map's δx_gs/b.
    pub gross_sliding_creep: f64,
    /// Local shape exponent `n` of [`AsperityModel::MicroSlip`] at this contact's film (0 for the
    /// other laws).
    pub exponent: f64,
}

impl AsperityFriction {
    /// A law without a micro-slip map.
    pub fn new(coefficient: f64, model: AsperityModel) -> Self {
        AsperityFriction { coefficient, model, map: None }
    }

    /// `(δx_gs, n)` of [`AsperityModel::MicroSlip`] at film `h` (m): the map's, or the model's
    /// constants; `None` for the other laws.
    pub fn micro_slip_at(&self, film: f64) -> Option<(f64, f64)> {
        match self.model {
            AsperityModel::MicroSlip { gross_sliding_displacement, exponent } => {
                Some(self.map.as_ref().map_or((gross_sliding_displacement, exponent), |m| m.at(film)))
            }
            _ => None,
        }
    }

    /// The asperity contact of a film carrying `load` (N) with half-width `half_width` and reduced
    /// radius `radius` (m) in the rolling direction and (central) film `film` (m):
    /// [`Self::creep_scale`] and the micro-slip exponent at that film.
    pub fn contact(&self, load: f64, half_width: f64, radius: f64, film: f64) -> AsperityContact {
        match self.micro_slip_at(film) {
            Some((d, n)) => AsperityContact { load, gross_sliding_creep: if half_width > 0.0 { d / half_width } else { 0.0 }, exponent: n },
            None => AsperityContact { load, gross_sliding_creep: self.creep_scale(half_width, radius), exponent: 0.0 },
        }
    }

    /// The nodes of a solved asperity pressure for the local micro-slip map
    /// ([`micro_slip::asperity_nodes`]; `x`, `film`, `pressure`, `cell` per grid node, m, m, Pa,
    /// m): empty for the laws other than [`AsperityModel::MicroSlip`], which use the load alone.
    pub fn asperity_nodes(&self, x: &[f64], film: &[f64], pressure: &[f64], cell: &[f64], length: f64, entrainment: f64) -> Vec<AsperityNode> {
        if self.micro_slip_at(0.0).is_none() || pressure.is_empty() {
            return Vec::new();
        }
        micro_slip::asperity_nodes(x, film, pressure, cell, length, entrainment, |h| self.micro_slip_at(h).expect("micro-slip"))
    }

    /// Traction (N, sign of `u_s`), slope (N·s/m) and `(|d²Q_a/du_s²| bound, reach)` of the
    /// asperities for sliding `u_s` and entrainment `u_e`: over the solved `nodes` when there are
    /// any ([`micro_slip::nodal_traction`]), else [`Self::traction`] and [`Self::curvature`] of
    /// `contact`.
    pub fn traction_local(&self, contact: &AsperityContact, nodes: &[AsperityNode], sliding: f64, entrainment: f64) -> (f64, f64, (f64, f64)) {
        if !nodes.is_empty() && matches!(self.model, AsperityModel::MicroSlip { .. }) {
            let (f, s, bound, reach) = micro_slip::nodal_traction(nodes, self.coefficient, sliding, entrainment);
            return (f, s, (bound, reach));
        }
        let (f, s) = self.traction(contact, sliding, entrainment);
        (f, s, self.curvature(contact, sliding, entrainment))
    }

    /// Traction (N, sign of `u_s`) and slope (N·s/m) for sliding `u_s` and entrainment `u_e`.
    /// For [`AsperityModel::Coulomb`] at `u_s = 0` the value is 0: the caller treats the jump of
    /// height `±μ_b W_a` there ([`Self::stick_limit`]).
    pub fn traction(&self, contact: &AsperityContact, sliding: f64, entrainment: f64) -> (f64, f64) {
        let q = self.coefficient * contact.load;
        if q == 0.0 || sliding == 0.0 {
            let slope = match self.model {
                AsperityModel::Carter if entrainment.abs() > 0.0 && contact.gross_sliding_creep > 0.0 => {
                    2.0 * q / (contact.gross_sliding_creep * entrainment.abs())
                }
                AsperityModel::MicroSlip { .. } if entrainment.abs() > 0.0 && contact.gross_sliding_creep > 0.0 => {
                    contact.exponent * q / (contact.gross_sliding_creep * entrainment.abs())
                }
                _ => 0.0,
            };
            return (0.0, slope);
        }
        match self.model {
            AsperityModel::Coulomb => (q * sliding.signum(), 0.0),
            AsperityModel::MicroSlip { .. } => {
                let scale = contact.gross_sliding_creep * entrainment.abs();
                if !(scale > 0.0) {
                    return (q * sliding.signum(), 0.0);
                }
                let (phi, dphi, _) = micro_slip_share(sliding / scale, contact.exponent);
                (q * sliding.signum() * phi, q * dphi / scale)
            }
            AsperityModel::Carter => {
                let ue = entrainment.abs();
                let xc = contact.gross_sliding_creep;
                if !(ue > 0.0 && xc > 0.0) {
                    return (q * sliding.signum(), 0.0);
                }
                let r = (sliding.abs() / ue) / xc;
                if r >= 1.0 {
                    (q * sliding.signum(), 0.0)
                } else {
                    (q * sliding.signum() * (1.0 - (1.0 - r).powi(2)), 2.0 * q * (1.0 - r) / (xc * ue))
                }
            }
        }
    }

    /// `(|d²Q_a/du_s²|, reach)` at fixed entrainment: the curvature is constant within `reach`
    /// of `sliding`, which stops short of the law's kinks and jumps (`u_s = 0`, and Carter's
    /// gross-sliding point `|u_s| = ξ_c |u_e|`).
    pub fn curvature(&self, contact: &AsperityContact, sliding: f64, entrainment: f64) -> (f64, f64) {
        let q = self.coefficient * contact.load;
        if q == 0.0 {
            return (0.0, f64::INFINITY);
        }
        let (ue, xc) = (entrainment.abs(), contact.gross_sliding_creep);
        match self.model {
            AsperityModel::Carter if ue > 0.0 && xc > 0.0 => {
                let gross = xc * ue;
                let reach = sliding.abs().min((sliding.abs() - gross).abs());
                (if sliding.abs() < gross { 2.0 * q / (gross * gross) } else { 0.0 }, reach)
            }
            // |Φ''| ≤ (5/4) n(n − 1) everywhere ([`micro_slip_share`]); the sign of the
            // curvature flips at u_s = 0, so the reach stops there.
            AsperityModel::MicroSlip { .. } if ue > 0.0 && xc > 0.0 => {
                (micro_slip_share(0.0, contact.exponent).2 * q / (xc * ue).powi(2), sliding.abs())
            }
            _ => (0.0, sliding.abs()),
        }
    }

    /// The slip regime at sliding `u_s` and entrainment `u_e` ([`SlipRegime`]); the
    /// slide-to-roll ratio is `u_s/u_e`. With solved `nodes` (the local micro-slip map) the
    /// share is that of their [`micro_slip::nodal_capacity`].
    pub fn regime(&self, contact: &AsperityContact, nodes: &[AsperityNode], sliding: f64, entrainment: f64) -> SlipRegime {
        if sliding == 0.0 {
            return SlipRegime::Rolling;
        }
        let srr = if entrainment != 0.0 { (sliding / entrainment).abs() } else { f64::INFINITY };
        if !(contact.load > 0.0 && self.coefficient > 0.0) {
            return if srr < FULL_FILM_SKID_SRR { SlipRegime::Rolling } else { SlipRegime::GrossSliding };
        }
        match self.model {
            AsperityModel::Coulomb => SlipRegime::GrossSliding,
            AsperityModel::Carter => {
                if srr < contact.gross_sliding_creep { SlipRegime::MicroSlip } else { SlipRegime::GrossSliding }
            }
            AsperityModel::MicroSlip { .. } if !nodes.is_empty() => {
                let cap = micro_slip::nodal_capacity(nodes, 1.0);
                let q = micro_slip::nodal_traction(nodes, 1.0, srr, 1.0).0;
                if cap > 0.0 && q < MICRO_SLIP_GROSS_SHARE * cap { SlipRegime::MicroSlip } else { SlipRegime::GrossSliding }
            }
            AsperityModel::MicroSlip { .. } => {
                let xm = contact.gross_sliding_creep;
                if xm > 0.0 && micro_slip_share(srr / xm, contact.exponent).0 < MICRO_SLIP_GROSS_SHARE { SlipRegime::MicroSlip } else { SlipRegime::GrossSliding }
            }
        }
    }

    /// The creep scale of the partial-slip laws for a contact of half-width `half_width` (m) and
    /// reduced radius `radius` (m) in the rolling direction: Carter's gross-sliding creep
    /// `μ_b b/R`, the micro-slip map's `δx_gs/b` (0 for Coulomb, which has none).
    pub fn creep_scale(&self, half_width: f64, radius: f64) -> f64 {
        match self.model {
            AsperityModel::Coulomb | AsperityModel::Carter => self.coefficient * half_width / radius,
            AsperityModel::MicroSlip { gross_sliding_displacement, .. } => {
                if half_width > 0.0 { gross_sliding_displacement / half_width } else { 0.0 }
            }
        }
    }

    /// Half-height of the traction jump at `u_s = 0` (N): `μ_b W_a` for Coulomb, 0 for the
    /// partial-slip laws.
    pub fn stick_limit(&self, contact: &AsperityContact) -> f64 {
        match self.model {
            AsperityModel::Coulomb => self.coefficient * contact.load,
            AsperityModel::Carter | AsperityModel::MicroSlip { .. } => 0.0,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn node() -> TractionNode {
        TractionNode { area: 1e-6, pressure: 1e9, viscosity: 100.0, film: 0.5e-6, poiseuille: 0.0 }
    }

    #[test]
    fn newtonian_and_eyring_agree_at_low_shear_and_eyring_saturates() {
        let n = [node()];
        let newton = TractionLaw { rheology: Rheology::Newtonian, limiting_shear_coefficient: None };
        let eyring = TractionLaw { rheology: Rheology::Eyring { tau0: 5e6 }, limiting_shear_coefficient: None };
        let u = 1e-6; // τ_N = 100·1e-6/0.5e-6 = 200 Pa ≪ τ0
        let (fn_, sn) = viscous_traction(&n, &newton, u);
        let (fe, se) = viscous_traction(&n, &eyring, u);
        assert!((fn_ - 200.0 * 1e-6).abs() < 1e-15 && (fe / fn_ - 1.0).abs() < 1e-9);
        assert!((se / sn - 1.0).abs() < 1e-9);
        // High shear: τ = τ0 asinh(x) with x = 2e8·1/5e6 = 40 → τ0 ln(40 + √1601).
        let (fe, _) = viscous_traction(&n, &eyring, 1.0);
        assert!((fe / (1e-6 * 5e6 * (40.0f64 + 1601f64.sqrt()).ln()) - 1.0).abs() < 1e-12);
        // Odd in u_s.
        assert_eq!(viscous_traction(&n, &eyring, -1.0).0, -fe);
        // Limiting shear caps at Λp.
        let capped = TractionLaw { limiting_shear_coefficient: Some(0.01), ..eyring };
        assert!((viscous_traction(&n, &capped, 1.0).0 - 1e-6 * 1e7).abs() < 1e-9);
    }

    #[test]
    fn eyring_slope_matches_finite_differences() {
        let n = [node(), TractionNode { pressure: 2e8, viscosity: 0.5, ..node() }];
        let law = TractionLaw { rheology: Rheology::Eyring { tau0: 5e6 }, limiting_shear_coefficient: None };
        for u in [1e-4, 0.01, 0.3] {
            let h = 1e-6 * u;
            let fd = (viscous_traction(&n, &law, u + h).0 - viscous_traction(&n, &law, u - h).0) / (2.0 * h);
            let s = viscous_traction(&n, &law, u).1;
            assert!((fd / s - 1.0).abs() < 1e-6, "u={u}: {fd} vs {s}");
        }
    }

    #[test]
    fn local_curvature_is_the_second_derivative_and_bounds_it_within_reach() {
        let n = [node(), TractionNode { pressure: 2e8, viscosity: 0.5, ..node() }];
        let eyring = TractionLaw { rheology: Rheology::Eyring { tau0: 5e6 }, limiting_shear_coefficient: None };
        // x from 1e-4 (Newtonian-like) through the knee (x ≈ 0.7) to the logarithmic range.
        for u in [-0.3, 1e-9, 1e-6, 3.5e-3 / 2.0, 0.01, 0.3, 30.0] {
            let local = viscous_traction_local(&n, &eyring, u);
            let h = 1e-3 * u.abs();
            let fd = (viscous_traction(&n, &eyring, u + h).1 - viscous_traction(&n, &eyring, u - h).1) / (2.0 * h);
            // (At u = 1e-9 the slope changes below its round-off: no finite difference.)
            if u.abs() >= 1e-6 {
                assert!((fd.abs() - local.curvature).abs() <= 1e-3 * local.curvature, "u={u}: {fd} vs {}", local.curvature);
            }
            assert_eq!(local.smooth_reach, 0.1 * u.abs());
            for k in -10..=10 {
                let v = u + local.smooth_reach * k as f64 / 10.0;
                let c = viscous_traction_local(&n, &eyring, v).curvature;
                assert!(c <= 1.5 * local.curvature * (1.0 + 1e-12), "u={u}, v={v}: {c} vs {}", local.curvature);
            }
        }
        // Newtonian: straight; a limiting-shear cap limits the reach to where it switches.
        let newtonian = TractionLaw { rheology: Rheology::Newtonian, limiting_shear_coefficient: None };
        let l = viscous_traction_local(&n, &newtonian, 0.1);
        assert_eq!((l.curvature, l.smooth_reach), (0.0, f64::INFINITY));
        let capped = TractionLaw { rheology: Rheology::Newtonian, limiting_shear_coefficient: Some(0.01) };
        // Node 1: g = 2e8 s⁻¹·Pa/(m/s), cap 1e7 Pa at u = 0.05 m/s.
        let l = viscous_traction_local(&[node()], &capped, 0.04);
        assert!((l.smooth_reach - 0.01).abs() < 1e-12, "{}", l.smooth_reach);
    }

    #[test]
    fn micro_slip_share_is_the_integral_of_the_local_map() {
        // Midpoint rule of Φ(t) = ∫ g(min(1, t(1+X))) (2/π)√(1−X²) dX in θ, g = 1 − (1 − s)^n.
        let quad = |t: f64, n: f64| {
            let m = 200_000;
            (0..m)
                .map(|k| {
                    let th = std::f64::consts::PI * (k as f64 + 0.5) / m as f64;
                    let s = (t * (1.0 - th.cos())).min(1.0);
                    (1.0 - (1.0 - s).powf(n)) * (2.0 / std::f64::consts::PI) * th.sin().powi(2) * std::f64::consts::PI / m as f64
                })
                .sum::<f64>()
        };
        for n in [2.0, 3.0, 4.5] {
            for t in [0.0, 0.1, 0.5, 0.7, 1.0, 2.0, 5.0, 40.0] {
                let (phi, dphi, bound) = micro_slip_share(t, n);
                assert!((phi - quad(t, n)).abs() < 1e-8, "n={n} t={t}: {phi} vs {}", quad(t, n));
                let h = 1e-6;
                let (lo, hi) = ((t - h).max(0.0), t + h);
                let fd = (micro_slip_share(hi, n).0 - micro_slip_share(lo, n).0) / (hi - lo);
                assert!((dphi - fd).abs() < 1e-5 * dphi.max(1.0), "n={n} t={t}: {dphi} vs {fd}");
                let fd2 = (micro_slip_share(hi, n).1 - micro_slip_share(lo, n).1) / (hi - lo);
                assert!(fd2 <= 1e-6 && -fd2 <= bound * (1.0 + 1e-6), "n={n} t={t}: {fd2} vs {bound}");
            }
        }
        // n = 2, small creep: Φ = 2t − 5t²/4; Φ → 1 like 1 − O(t^−3/2).
        assert!((micro_slip_share(0.2, 2.0).0 - (0.4 - 1.25 * 0.04)).abs() < 1e-13);
        assert!(micro_slip_share(1e4, 3.0).0 > 0.9999);
        let a = AsperityFriction::new(0.12, AsperityModel::MicroSlip { gross_sliding_displacement: 0.2e-6, exponent: 3.0 });
        let c = a.contact(1000.0, 2e-4, 0.01, 0.3e-6);
        assert!((c.gross_sliding_creep - 1e-3).abs() < 1e-15);
        let ue = 4.0;
        // Initial slope n μ W_a/(ξ_m u_e) (∫ y w dX = 1); odd in u_s.
        assert!((a.traction(&c, 0.0, ue).1 - 3.0 * 120.0 / (1e-3 * ue)).abs() < 1e-9);
        assert!((a.traction(&c, 1e-9, ue).1 / a.traction(&c, 0.0, ue).1 - 1.0).abs() < 1e-4);
        let (q, _) = a.traction(&c, 1e-3 * ue, ue);
        assert_eq!(a.traction(&c, -1e-3 * ue, ue).0, -q);
        assert!(a.stick_limit(&c) == 0.0 && a.regime(&c, &[], 0.5e-3 * ue, ue) == SlipRegime::MicroSlip);
        assert_eq!(a.regime(&c, &[], 0.5 * ue, ue), SlipRegime::GrossSliding);
    }

    #[test]
    fn carter_creep_curve() {
        let a = AsperityFriction::new(0.12, AsperityModel::Carter);
        let c = AsperityContact { load: 1000.0, gross_sliding_creep: 0.003, exponent: 0.0 };
        let ue = 4.0;
        // Half the gross-sliding creep: 1 − (1/2)² = 3/4 of μ_b W_a.
        let (q, _) = a.traction(&c, 0.5 * 0.003 * ue, ue);
        assert!((q - 0.75 * 120.0).abs() < 1e-9);
        assert_eq!(a.traction(&c, 0.01 * ue, ue).0, 120.0);
        assert_eq!(a.traction(&c, -0.01 * ue, ue).0, -120.0);
        // Initial slope 2 μ_b W_a/(ξ_c u_e).
        assert!((a.traction(&c, 0.0, ue).1 - 2.0 * 120.0 / (0.003 * ue)).abs() < 1e-9);
        let coulomb = AsperityFriction { model: AsperityModel::Coulomb, ..a.clone() };
        assert_eq!(coulomb.stick_limit(&c), 120.0);
        assert_eq!(a.stick_limit(&c), 0.0);
        // Curvature: −2 μ_b W_a/(ξ_c u_e)² inside, 0 beyond; the reach stops at the kinks.
        let gross = 0.003 * ue;
        let (k, reach) = a.curvature(&c, 0.25 * gross, ue);
        assert!((k - 2.0 * 120.0 / (gross * gross)).abs() < 1e-6 * k && (reach - 0.25 * gross).abs() < 1e-15);
        let (k, reach) = a.curvature(&c, 0.9 * gross, ue);
        assert!(k > 0.0 && (reach - 0.1 * gross).abs() < 1e-15);
        assert_eq!(a.curvature(&c, 2.0 * gross, ue).0, 0.0);
        assert_eq!(coulomb.curvature(&c, -0.5, ue), (0.0, 0.5));
    }
}
