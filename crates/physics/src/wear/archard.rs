//! Archard wear of one steady revolution of a cam–follower pair, from the cycle's kinematics,
//! loads, Hertz contact and film ([`crate::cam::cycle`]).
//!
//! Archard (1953), local form: `dh/dt = k p v_s` with `k` the dimensional wear coefficient
//! (m³/(N·m) = 1/Pa; `k = K/H` for the dimensionless coefficient `K` and the hardness `H` of the
//! wearing body), `p` the contact pressure and `v_s` the sliding speed. Integrated over the
//! revolution, a pass of the contact over a surface point removes `k (|v_s|/u) ∫ p dx` there, `u`
//! the speed of the contact relative to that surface; [`super::deposit`] spreads each cam step's
//! pass over the surface cells it touches, so the worn volume is exactly `k ∫ F |v_s| dt`.
//!
//! * Pressure, where the cycle's film model is a closed form (fidelity `fast`, the closed-form
//!   angles of `auto`, point contacts): the Hertz semi-ellipse of the cycle
//!   (`hertz_max_pressure`, `hertz_half_width` along the rolling direction: line contacts, and the
//!   centre line of a point contact's track).
//! * Pressure, where the numerical EHL model ran (fidelity `accurate`, the numerical angles of
//!   `auto`; the cycle returns its [`FilmProfile`] there): the converged pressure along the
//!   rolling direction, spike and exit constriction included, tabulated on the solver's nodes
//!   ([`Band::Tabulated`]).
//! * Mixed lubrication (`LoadShare::Asperity`): only the asperity-carried share of the load wears;
//!   the fluid-borne share does not. Closed forms: the Greenwood–Tripp share `W_a/W` of the
//!   cycle's film (asperity pressure at the central film over the Hertz area) applied to the Hertz
//!   profile. Numerical film: the Greenwood–Tripp asperity pressure `p_a(h(x))` at the local film
//!   of every node — it peaks at the exit constriction, where the film is thinnest — scaled so
//!   that it carries exactly the share `W_a/W` the film model reported (the same node sum, capped
//!   at the load). `LoadShare::Full`: the whole load wears (dry or boundary contact, or a wear
//!   coefficient measured under the same lubrication): the Hertz or the EHL pressure.
//! * Orientation of a tabulated band: the film model's `x` points the way positive entrainment
//!   carries the oil, along which the cam surface moves (`u_c > 0`) relative to the contact, so the
//!   contact advances over the cam towards `−x`: a cam point at arc length `σ` sees the pressure at
//!   `x = −(σ − c)` (`c` the contact centre). On a flat face the contact moves at `u_f` along the
//!   face coordinate (`d(s')/dt = ω s''`), so the face too sees `x = −(e − c)`. The exit spike
//!   (`x > 0` for positive entrainment) therefore lands on the part of the cam the contact has
//!   already passed.
//! * Sliding: the cycle's `u_c − u_f`: the kinematic sliding `ω(r_b + s)` of a flat face, the
//!   roller's slip from its torque balance, the spin-free sliding of a spherical tappet.
//! * Cam surface: cell `k` is the stretch of cam surface the contact crosses during cam step `k`
//!   (width `u_c Δt`, `u_c` the cam surface speed relative to the contact point), so cam angle `θ_k`
//!   labels the cam point that meets the follower at `θ_k` — once per revolution.
//! * Flat follower face (non-rotating): the contact runs along the face at `d(s')/dt = ω s''`; its
//!   wear is recorded on fixed bins of face position (turning points, where the contact dwells,
//!   wear most). Roller: its surface meets the cam many times per revolution at varying phase,
//!   so its wear is spread evenly over the circumference (reported as a mean depth).

use super::deposit::{Band, Bins, PeriodicCells, TabulatedBand};
use crate::cam::cycle::{CycleOutput, CycleSpec, FollowerKind};
use crate::film::FilmProfile;
use crate::{ensure_finite, SolveError};

/// Which part of the contact load wears the surfaces.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum LoadShare {
    /// The Greenwood–Tripp asperity share of the cycle's film.
    Asperity,
    /// The whole load.
    Full,
}

/// Archard coefficients.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ArchardParams {
    /// Wear coefficient of the cam, m³/(N·m) (= 1/Pa).
    pub cam_coefficient: f64,
    /// Wear coefficient of the follower, m³/(N·m).
    pub follower_coefficient: f64,
    pub load_share: LoadShare,
}

/// Wear of one revolution.
#[derive(Debug, Clone)]
pub struct RevolutionWear {
    /// Cam wear depth per revolution at the cam point of each cam angle, m (along the normal).
    pub cam_depth: Vec<f64>,
    /// The cam surface cells (arc length), m.
    pub cells: PeriodicCells,
    /// Cam volume worn per revolution `k ∫ f_a F |v_s| dt`, m³.
    pub cam_volume: f64,
    /// Follower volume worn per revolution, m³.
    pub follower_volume: f64,
    /// Flat follower face: wear depth per revolution on the face bins, m.
    pub face_depth: Option<Vec<f64>>,
    /// Share of the load that wears, per cam angle.
    pub worn_share: Vec<f64>,
    /// Duration of the revolution, s.
    pub period: f64,
}

fn series<'a>(v: &'a Option<Vec<f64>>, name: &str) -> Result<&'a [f64], SolveError> {
    v.as_deref().ok_or_else(|| SolveError::invalid("", format!("the wear model needs the cycle's {name}")))
}

/// Archard wear of the revolution `out` of `spec` (steady running). `face` gives the bins of a
/// flat follower's face (ignored for other followers).
pub fn revolution_wear(
    spec: &CycleSpec,
    out: &CycleOutput,
    params: &ArchardParams,
    face: Option<Bins>,
) -> Result<RevolutionWear, SolveError> {
    let s = &out.series;
    let n = s.angle.len();
    let load = series(&s.contact_load, "contact loads")?;
    let p0 = series(&s.hertz_max_pressure, "Hertz pressure")?;
    let b = series(&s.hertz_half_width, "Hertz width")?;
    let share: Vec<f64> = match params.load_share {
        LoadShare::Full => vec![1.0; n],
        LoadShare::Asperity => {
            if spec.roughness.sigma > 0.0 {
                series(&s.asperity_load_fraction, "asperity load share (a film)")?.to_vec()
            } else {
                // Smooth surfaces: the film carries everything.
                vec![0.0; n]
            }
        }
    };
    let period = out.duration;
    let dt = period / n as f64;
    let mut widths = Vec::with_capacity(n);
    for (k, &uc) in s.cam_surface_velocity.iter().enumerate() {
        if !(uc > 0.0) {
            return Err(SolveError::physical(
                crate::PhysicalFailure::CamSurfaceReversal,
                format!(
                    "the cam surface speed relative to the contact is {uc:.4} m/s at {:.2}°: the wear \
                     model needs the contact to advance over the cam",
                    s.angle[k].to_degrees()
                ),
            ));
        }
        widths.push(uc * dt);
    }
    let cells = PeriodicCells::new(&widths);
    // Angles where the numerical film ran: its pressure profile.
    let mut profile: Vec<Option<&FilmProfile>> = vec![None; n];
    for (i, p) in &out.profiles {
        if let Some(slot) = profile.get_mut(*i) {
            *slot = Some(p);
        }
    }
    let per_length = s.load_per_length.as_deref();
    let mut volume = vec![0.0; n];
    let (mut cam_volume, mut follower_volume) = (0.0, 0.0);
    let mut face_volume = face.map(|f| vec![0.0; f.n]);
    for k in 0..n {
        let vs = s.sliding_velocity[k].abs();
        let fa = share[k];
        let work = fa * load[k] * vs * dt; // J: the wearing load times its sliding distance
        cam_volume += params.cam_coefficient * work;
        follower_volume += params.follower_coefficient * work;
        let band = match (profile[k], per_length) {
            (Some(p), Some(w)) => numerical_band(spec, params.load_share, p, fa * w[k])?,
            _ => None,
        }
        .unwrap_or(Band::Hertz { p0: fa * p0[k], b: b[k] });
        cells.deposit(k, &band, params.cam_coefficient * vs * dt, &mut volume);
        if let (Some(bins), Some(fv)) = (face, face_volume.as_mut()) {
            let x = s.contact_offset[k];
            let half = 0.5 * s.follower_surface_velocity[k] * dt;
            bins.deposit(x - half, x + half, &band, params.follower_coefficient * vs * dt, fv);
        }
    }
    let cam_depth: Vec<f64> = volume.iter().enumerate().map(|(j, v)| v / cells.width(j)).collect();
    let face_depth = match (face, face_volume) {
        (Some(bins), Some(fv)) => Some(fv.iter().map(|v| v / bins.width()).collect::<Vec<_>>()),
        _ => None,
    };
    ensure_finite("cam wear per revolution", cam_depth.iter().chain(face_depth.iter().flatten()))?;
    ensure_finite("worn volume", [&cam_volume, &follower_volume])?;
    Ok(RevolutionWear { cam_depth, cells, cam_volume, follower_volume, face_depth, worn_share: share, period })
}

/// The wearing pressure of a numerical film `profile` as a band along the surface (offset
/// `d = −x`, see the module docs) carrying `worn_per_length` (N/m: the worn share times the load
/// per length): the EHL pressure (`LoadShare::Full`) or the Greenwood–Tripp asperity pressure at
/// the local film (`LoadShare::Asperity`), scaled to that load. `None` when the profile carries
/// nothing to scale (the caller falls back to the Hertz band).
pub fn numerical_band(spec: &CycleSpec, share: LoadShare, profile: &FilmProfile, worn_per_length: f64) -> Result<Option<Band>, SolveError> {
    if !(worn_per_length > 0.0) {
        return Ok(None);
    }
    let d: Vec<f64> = profile.x.iter().rev().map(|x| -x).collect();
    let p: Vec<f64> = match share {
        LoadShare::Full => profile.pressure.iter().rev().map(|p| p.max(0.0)).collect(),
        LoadShare::Asperity => {
            profile.film.iter().rev().map(|h| spec.roughness.asperity_pressure(*h, spec.contact_modulus)).collect()
        }
    };
    let Some(band) = TabulatedBand::new(d, p) else {
        return Err(SolveError::invalid("", "the numerical film profile is not a valid pressure band"));
    };
    let total = band.integral();
    if !(total > 0.0) {
        return Ok(None);
    }
    Ok(Some(Band::Tabulated(band.scaled(worn_per_length / total))))
}

/// Bins over the flat follower face covering the contact path of `out` with a margin of the
/// widest contact on each side; `None` for other followers.
pub fn face_bins(spec: &CycleSpec, out: &CycleOutput, count: usize) -> Option<Bins> {
    if !matches!(spec.follower, FollowerKind::Flat { .. }) {
        return None;
    }
    let s = &out.series;
    let bmax = s.hertz_half_width.as_ref()?.iter().copied().fold(0.0, f64::max);
    // Numerical pressure profiles reach further (the inlet): cover them too.
    let reach = out.profiles.iter().flat_map(|(_, p)| [p.x.first(), p.x.last()]).flatten().fold(0.0, |m: f64, x| m.max(x.abs()));
    let margin = if reach > 0.0 { (1.5 * bmax).max(reach) } else { 1.5 * bmax };
    let lo = s.contact_offset.iter().copied().fold(f64::INFINITY, f64::min) - margin;
    let hi = s.contact_offset.iter().copied().fold(f64::NEG_INFINITY, f64::max) + margin;
    (hi > lo && lo.is_finite() && hi.is_finite()).then_some(Bins { lo, hi, n: count.max(8) })
}
