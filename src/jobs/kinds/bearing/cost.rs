//! The work and memory model of a `bearing` job.

use super::*;
use crate::jobs::cost::Cost;

/// Analyses a heat balance typically needs (each a warm-started load-balanced analysis).
const HEAT_BALANCE_ANALYSES: f64 = 1.5;

/// The work and memory model of one `bearing` job: load-balanced analyses on the grid
/// (`jobs::cost::bearing_analysis_seconds`), times the heat balance's iterations, plus the
/// coefficients' adjoint solves (2 for the 2×2 set, 4 for the 4×4 set, each about one analysis).
pub fn bearing_cost(spec: &BearingSpec) -> Cost {
    let nodes = spec.grid.circumferential.saturating_mul(spec.grid.axial);
    let one = crate::jobs::cost::bearing_analysis_seconds(nodes);
    let mut analyses = if spec.thermal.is_some() { HEAT_BALANCE_ANALYSES } else { 1.0 };
    // A misaligned journal's film is not symmetric about the mid-plane: the whole grid, twice
    // the work of the aligned half (seed 002's misaligned case).
    if spec.misalignment.is_some() {
        analyses *= 2.0;
    }
    if spec.outputs.contains(&BearingOutput::MomentCoefficients) {
        analyses += 4.0 * 0.5;
    } else if spec.outputs.contains(&BearingOutput::DynamicCoefficients) {
        analyses += 2.0 * 0.5;
    }
    // The multigrid hierarchy (≈ 4/3 of the fine grid) of about 16 arrays of the grid (peak
    // resident memory: 43 MB at 721×361).
    let bytes = 16.0 * 8.0 * 4.0 / 3.0 * nodes as f64 + crate::jobs::cost::MIB;
    let what = format!("{analyses:.0} bearing analyses on {} × {} nodes", spec.grid.circumferential, spec.grid.axial);
    Cost::new(crate::jobs::cost::JOB_OVERHEAD_S + analyses * one, bytes)
        .work_at("/grid", what.clone())
        .memory_at("/grid", what)
}
