//! The work and memory model of one cam contact's film by the model a spec's `fidelity` and
//! `ehl` block select (`physics::film::model_for`): shared by `cam_point`, `cam_cycle` and `wear`.

use super::common::{EhlGeometry, EhlSpec, ExtrapolationSpec};
use crate::jobs::cost;
use crate::physics::film::Fidelity;

/// The contact a film is solved for.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ContactKind {
    /// A line contact (flat-faced or roller follower).
    Line,
    /// A point contact (spherical follower): the line model leaves it to the closed form.
    Point,
}

/// What one film costs.
#[derive(Debug, Clone, PartialEq)]
pub struct FilmCost {
    /// A film solved from nothing (the first angle, a cam point), s.
    pub cold: f64,
    /// A film solved from the previous angle's (along a cycle), s.
    pub warm: f64,
    /// Share of a cycle's angles that run the numerical model (`auto`: an estimate; the closed
    /// form answers the rest).
    pub numeric_share: f64,
    /// Peak memory of one solve, bytes.
    pub bytes: f64,
    /// Memory a cycle keeps per angle (the converged film as the next cycle's warm start), bytes.
    pub kept_per_angle: f64,
    /// The spec field that sets the model's resolution (relative to the cam spec).
    pub path: &'static str,
    /// The model in words ("the 2-D EHL solver on 65×129 nodes").
    pub what: String,
}

/// Share of a cycle's angles where `auto` runs the numerical model (measured on the seed 003
/// `auto` example and the seed 000 roller; BENCHMARKS.md, "The `auto` rules").
const AUTO_NUMERIC_SHARE: f64 = 0.3;

/// The film model's cost for `fidelity` and `ehl` on a contact of `contact`.
pub fn film_cost(fidelity: Fidelity, ehl: &EhlSpec, contact: ContactKind) -> FilmCost {
    let closed = FilmCost {
        cold: cost::FAST_ANGLE_S,
        warm: cost::FAST_ANGLE_S,
        numeric_share: 0.0,
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
        let n = (o.nx * o.ny) as f64;
        return FilmCost {
            cold: cost::ehl_2d_seconds(o.nx, o.ny),
            warm: cost::ehl_2d_step_seconds(o.nx, o.ny),
            numeric_share: share,
            bytes: cost::ehl_2d_bytes(o.nx, o.ny),
            kept_per_angle: cost::EHL_2D_KEPT_BYTES_PER_NODE * n,
            path: "/ehl/nx",
            what: format!("the 2-D EHL solver on {}×{} nodes", o.nx, o.ny),
        };
    }
    if contact == ContactKind::Point {
        return closed;
    }
    let n = ehl.nodes;
    let richardson = ehl.extrapolation == ExtrapolationSpec::Richardson;
    let line = cost::ehl_line_seconds(n, richardson);
    let bytes = cost::ehl_line_bytes(n);
    // A converged line film keeps its pressure, film and traction nodes: ≈ 10 arrays of n.
    let kept = 80.0 * n as f64;
    match &ehl.thermal {
        Some(t) => {
            let thermal = cost::ehl_thermal_seconds(n, t.film_points, t.solid_points);
            // Key points: the full solve only where the conditions moved by more than the carry
            // tolerance (≈ 5 % of the angles at 0.05 on the seed 000 cycle).
            let keys = t.carry_tolerance.map_or(1.0, |c| (KEY_SHARE_AT_005 * (0.05 / c).powf(0.7)).clamp(0.01, 1.0));
            FilmCost {
                cold: line + thermal,
                warm: thermal * keys + line * 0.3,
                numeric_share: share,
                bytes,
                kept_per_angle: kept * (1.0 + t.film_points as f64),
                path: "/ehl/thermal",
                what: format!("the thermal EHL solver on {n} nodes"),
            }
        }
        None => FilmCost {
            cold: line,
            warm: line * WARM_LINE_FRACTION,
            numeric_share: share,
            bytes,
            kept_per_angle: kept,
            path: "/ehl/nodes",
            what: format!("the numerical EHL solver on {n} nodes"),
        },
    }
}

/// Share of a thermal cycle's angles solved in full at `carry_tolerance` 0.05.
const KEY_SHARE_AT_005: f64 = 0.1;

/// A warm line-contact step along a cycle against a cold solve.
const WARM_LINE_FRACTION: f64 = 0.4;
