//! `ehl.accuracy` (issue 46 item 3): how accurate a spec wants its films, and the cheapest
//! settings that the measured tables say meet it — the line grid and the thermal cycle's key
//! points — for the fields the spec leaves out. A field the spec sets wins.
//!
//! The tables are measured, not modelled: the largest relative error of the central and the
//! minimum film at any of 720 angles against the grid-converged cycle (Richardson of 385 + 767
//! nodes, Newton tolerance 1e-8), worst of the two reference cycles — seed 000's steady roller
//! and seed 003's cycloidal flat follower (mixed, Eyring) —
//! `cargo bench --bench cam -- fidelity nodes=96,128,160,192,208,224,240,256,272,288,384` (BENCHMARKS.md,
//! "Accuracy targets").

use serde::Serialize;
use utoipa::ToSchema;

/// The films' accuracy a spec gets when it does not say: 1 % at every angle.
pub const DEFAULT_ACCURACY: f64 = 0.01;

/// The line contacts the ladders were measured on: a roller follower (seed 000's steady roller,
/// where the films' worst angles are the base circle's light load) and a flat-faced follower
/// (seed 003's cycloidal cam, mixed, Eyring, through two entrainment reversals).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum LineFamily {
    Roller,
    FlatFaced,
}

/// A rung of a line-contact ladder: the fine grid's nodes of a Richardson pair and the largest
/// film error measured with it.
#[derive(Debug, Clone, Copy)]
pub struct LineRung {
    pub nodes: usize,
    pub error: f64,
}

const fn rung(nodes: usize, error: f64) -> LineRung {
    LineRung { nodes, error }
}

/// The ladders, cheapest first (worst of h_c and h_min at any of 720 angles). One grid without
/// extrapolation is never cheaper for the same error (192 nodes alone: 4.4 %, about the cost of
/// the 128 + 64 pair: 2.7 %).
const ROLLER_LADDER: [LineRung; 11] = [
    rung(96, 0.048),
    rung(128, 0.027),
    rung(160, 0.0236),
    rung(192, 0.0187),
    rung(208, 0.0153),
    rung(224, 0.0132),
    rung(240, 0.0129),
    rung(256, 0.0101),
    rung(272, 0.0107),
    rung(288, 0.0088),
    rung(384, 0.0040),
];
const FLAT_LADDER: [LineRung; 11] = [
    rung(96, 0.051),
    rung(128, 0.023),
    rung(160, 0.0151),
    rung(192, 0.0117),
    rung(208, 0.0083),
    rung(224, 0.0069),
    rung(240, 0.0061),
    rung(256, 0.0044),
    rung(272, 0.0048),
    rung(288, 0.0039),
    rung(384, 0.0020),
];

/// Below a ladder's finest measured rung: the reference grid itself, its error estimated from
/// the second order of the 384-node rung.
const FINEST: LineRung = rung(767, 0.001);

fn ladder(family: LineFamily) -> &'static [LineRung] {
    match family {
        LineFamily::Roller => &ROLLER_LADDER,
        LineFamily::FlatFaced => &FLAT_LADDER,
    }
}

/// The cheapest rung whose measured error is within `accuracy`.
pub fn line_rung(accuracy: f64, family: LineFamily) -> LineRung {
    ladder(family).iter().copied().find(|r| r.error <= accuracy * (1.0 + 1e-9)).unwrap_or(FINEST)
}

/// The measured error of a grid of `nodes` when it is a rung of the ladder and runs as one
/// (a Richardson pair of the isothermal line model).
pub fn rung_error(nodes: usize, isothermal_pair: bool, family: LineFamily) -> Option<f64> {
    isothermal_pair.then(|| ladder(family).iter().chain([&FINEST]).find(|r| r.nodes == nodes).map(|r| r.error)).flatten()
}

/// The thermal cycle's key points (`ehl.thermal.carry_tolerance`) against the largest error of
/// films and slide-to-roll ratio they add to the every-angle cycle (seed 000, 720 angles,
/// `cargo bench --bench thermal -- cycle`; 0.01: seed 001's nose, 36 angles), loosest first.
const CARRY_LADDER: [(f64, f64); 4] = [(0.1, 0.0327), (0.05, 0.0094), (0.02, 0.0076), (0.01, 0.0031)];

/// The loosest key-point tolerance whose measured error is within `accuracy`; `None` (every
/// angle in full) below the ladder.
pub fn carry_tolerance(accuracy: f64) -> Option<f64> {
    CARRY_LADDER.iter().find(|(_, e)| *e <= accuracy * (1.0 + 1e-9)).map(|(c, _)| *c)
}

/// The measured error a key-point tolerance adds (a rung of the ladder; 0 for every angle).
pub fn carry_error(tolerance: f64) -> Option<f64> {
    CARRY_LADDER.iter().find(|(c, _)| *c == tolerance).map(|(_, e)| *e)
}

/// The numerical film's settings as they ran: the accuracy asked for, what it chose where the
/// spec left a field out, and the error measured with those settings on the reference cycles.
#[derive(Debug, Clone, PartialEq, Serialize, ToSchema)]
pub struct EhlSettingsUsed {
    /// The films' target accuracy: relative error at any angle (`ehl.accuracy`, default 0.01).
    pub accuracy: f64,
    /// Grid nodes of the line model (the fine grid of the Richardson pair): the spec's, or the
    /// cheapest rung of the measured ladder within the accuracy.
    pub nodes: usize,
    /// Whether `nodes` came from the accuracy (true) or the spec.
    pub nodes_from_accuracy: bool,
    /// The thermal cycle's key-point tolerance (relative), when the thermal line model ran with
    /// key points (absent: every angle in full).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub carry_tolerance: Option<f64>,
    /// The largest relative film error measured on the reference cycles with these settings
    /// (the grid's rung; with the thermal key points, plus their measured error). Absent when the
    /// spec's own grid is not a measured rung.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub measured_error: Option<f64>,
}
