//! The work and memory model of one cam contact's film by the model a spec's `fidelity` and
//! `ehl` block select (`physics::film::model_for`): shared by `cam_point`, `cam_cycle` and `wear`.

use super::accuracy::LineFamily;
use super::common::{EhlGeometry, EhlSpec, ExtrapolationSpec};
use crate::jobs::cost;
use crate::physics::film::Fidelity;

/// The contact a film is solved for.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ContactKind {
    /// A line contact (flat-faced or roller follower).
    Line(LineFamily),
    /// A point contact (spherical follower): the line model leaves it to the closed form.
    Point,
}

/// What one film costs.
#[derive(Debug, Clone)]
pub struct FilmCost {
    /// A film solved from nothing (the first angle, a cam point), s.
    pub cold: f64,
    /// The cold solve of the isothermal film (a thermal model's starting film), s.
    pub isothermal: f64,
    /// A film along a cycle at an angle step of `step_deg` degrees, s (from `cold` and
    /// `isothermal`).
    pub per_angle: fn(&FilmCost, f64) -> f64,
    /// Share of a cycle's angles that run the numerical model (`auto`: an estimate; the closed
    /// form answers the rest).
    pub numeric_share: f64,
    /// Per full thermal solve along a cycle (0 without the thermal model), s, and the share of
    /// angles solved in full (key points).
    pub thermal_angle: f64,
    pub thermal_share: f64,
    /// Peak memory of one solve, bytes.
    pub bytes: f64,
    /// Memory a cycle keeps per angle (the converged film as the next pass's warm start), bytes.
    pub kept_per_angle: f64,
    /// The spec field that sets the model's resolution (relative to the cam spec).
    pub path: &'static str,
    /// The model in words ("the 2-D EHL solver on 65×129 nodes").
    pub what: String,
}

impl FilmCost {
    /// One angle of a cycle at a step of `step_deg` degrees, s.
    pub fn angle(&self, step_deg: f64) -> f64 {
        (self.per_angle)(self, step_deg)
    }
}

/// Share of a cycle's angles where `auto` runs the numerical model: counted as every angle (the
/// seed 003 `auto` example costs as much as its `accurate` cycle: the closed form's error
/// estimate and the numerical film near zero entrainment).
const AUTO_NUMERIC_SHARE: f64 = 1.0;

/// Share of a thermal cycle's angles solved in full at `carry_tolerance` 0.05 (the seed 000
/// cycle at 720 angles: 2.7 s with it against 51 s without).
const KEY_SHARE_AT_005: f64 = 0.05;

/// The film model's cost for `fidelity` and `ehl` on a contact of `contact`.
pub fn film_cost(fidelity: Fidelity, ehl: &EhlSpec, contact: ContactKind) -> FilmCost {
    let closed = FilmCost {
        cold: 0.0,
        isothermal: 0.0,
        per_angle: |_, _| 0.0,
        numeric_share: 0.0,
        thermal_angle: 0.0,
        thermal_share: 0.0,
        bytes: 0.0,
        kept_per_angle: 0.0,
        path: "/fidelity",
        what: "the closed-form films".into(),
    };
    let share = match fidelity {
        Fidelity::Fast => return closed,
        Fidelity::Accurate => 1.0,
        Fidelity::Auto => AUTO_NUMERIC_SHARE,
    };
    if ehl.geometry == EhlGeometry::Finite {
        let o = ehl.grid_options(contact == ContactKind::Point);
        let n = o.nx as f64 * o.ny as f64;
        let finite = FilmCost {
            cold: cost::ehl_2d_seconds(o.nx, o.ny),
            isothermal: cost::ehl_2d_seconds(o.nx, o.ny),
            per_angle: |f, step| f.isothermal * cost::ehl_2d_step_fraction(step),
            numeric_share: share,
            bytes: cost::ehl_2d_bytes(o.nx, o.ny),
            kept_per_angle: cost::EHL_2D_KEPT_BYTES_PER_NODE * n,
            path: "/ehl/nx",
            what: format!("the 2-D EHL solver on {}×{} nodes", o.nx, o.ny),
            ..closed
        };
        return match &ehl.thermal {
            // The thermal finite-line model: a cold coupled solve, then each angle warm from the
            // previous one, by the angle step as the isothermal 2-D film (the seed 000 example on
            // 33×65 in a dev build: 12 angles 6.7 s of CPU, this model 7.6 s; 36 angles 8.5 s,
            // this model 8.7 s).
            Some(t) => FilmCost {
                cold: finite.cold + cost::ehl_thermal_2d_seconds(o.nx, o.ny, t.film_points, t.solid_points),
                per_angle: |f, step| f.cold * cost::ehl_2d_step_fraction(step),
                what: format!("the thermal 2-D EHL solver on {}×{} nodes", o.nx, o.ny),
                ..finite
            },
            None => finite,
        };
    }
    let ContactKind::Line(family) = contact else { return closed };
    let n = ehl.nodes(family);
    let line = FilmCost {
        cold: cost::ehl_line_seconds(n, ehl.extrapolation == ExtrapolationSpec::Richardson),
        isothermal: cost::ehl_line_seconds(n, ehl.extrapolation == ExtrapolationSpec::Richardson),
        per_angle: |f, _| f.isothermal * cost::WARM_LINE_FRACTION,
        numeric_share: share,
        bytes: cost::ehl_line_bytes(n),
        // A converged line film keeps its pressure, film and traction nodes: ≈ 10 arrays of n.
        kept_per_angle: 80.0 * n as f64,
        path: "/ehl/nodes",
        what: format!("the numerical EHL solver on {n} nodes"),
        ..closed
    };
    match &ehl.thermal {
        Some(t) => FilmCost {
            cold: line.cold + cost::ehl_thermal_seconds(n, t.film_points, t.solid_points),
            thermal_angle: cost::ehl_thermal_angle_seconds(n, t.film_points, t.solid_points),
            // Key points: the full solve only where the conditions moved by more than the
            // carry tolerance.
            thermal_share: t.key_point_tolerance(ehl.accuracy()).map_or(1.0, |c| (KEY_SHARE_AT_005 * (0.05 / c).powf(0.7)).clamp(0.01, 1.0)),
            // The temperature fields of the film and the solids at each angle.
            kept_per_angle: line.kept_per_angle + 6.0 * 8.0 * (t.film_points + 2 * t.solid_points) as f64 * n as f64,
            path: "/ehl/thermal",
            what: format!("the thermal EHL solver on {n} nodes"),
            ..line
        },
        None => line,
    }
}
