//! Validation of the inputs of a 2-D solve and of a transient step.

use super::*;

pub(in crate::ehl::twod) fn validate(input: &Ehl2dInput, options: &Ehl2dOptions) -> Result<(), SolveError> {
    let pos = |v: f64, path: &str| if v.is_finite() && v > 0.0 { Ok(()) } else { Err(SolveError::invalid(path, "must be a finite number > 0")) };
    pos(input.load, "Ehl2dInput.load")?;
    pos(input.effective_modulus, "Ehl2dInput.effective_modulus")?;
    pos(input.temperature, "Ehl2dInput.temperature")?;
    pos(input.entrainment_velocity.abs(), "Ehl2dInput.entrainment_velocity")?;
    pos(input.lubricant.viscosity, "Ehl2dInput.lubricant.viscosity")?;
    if !(input.lubricant.pressure_viscosity.is_finite() && input.lubricant.pressure_viscosity >= 0.0) {
        return Err(SolveError::invalid("Ehl2dInput.lubricant.pressure_viscosity", "must be finite and ≥ 0"));
    }
    match input.geometry {
        Geometry2d::Point { rx, ry } => {
            pos(rx, "Ehl2dInput.geometry.rx")?;
            pos(ry, "Ehl2dInput.geometry.ry")?;
            if !(0.02..=50.0).contains(&(rx / ry)) {
                return Err(SolveError::invalid("Ehl2dInput.geometry", "R_x/R_y must be within 0.02–50"));
            }
        }
        Geometry2d::Finite { rx, crown } => {
            pos(rx, "Ehl2dInput.geometry.rx")?;
            pos(crown.length, "Ehl2dInput.geometry.crown.length")?;
            pos(crown.end_radius, "Ehl2dInput.geometry.crown.end_radius")?;
            if !(crown.middle_length > 0.0 && crown.middle_length <= crown.length) {
                return Err(SolveError::invalid("Ehl2dInput.geometry.crown.middle_length", "must be in (0, length]"));
            }
            if !(crown.crown_height.is_finite() && crown.crown_height >= 0.0) {
                return Err(SolveError::invalid("Ehl2dInput.geometry.crown.crown_height", "must be finite and ≥ 0"));
            }
        }
    }
    for (n, path) in [(options.nx, "Ehl2dOptions.nx"), (options.ny, "Ehl2dOptions.ny")] {
        if !(9..=1025).contains(&n) {
            return Err(SolveError::invalid(path, "must be within 9–1025"));
        }
    }
    if !(options.tolerance.is_finite() && options.tolerance > 0.0) {
        return Err(SolveError::invalid("Ehl2dOptions.tolerance", "must be finite and > 0"));
    }
    if options.max_iterations == 0 {
        return Err(SolveError::invalid("Ehl2dOptions.max_iterations", "must be ≥ 1"));
    }
    if !(options.grid_tolerance.is_finite() && options.grid_tolerance > 0.0) {
        return Err(SolveError::invalid("Ehl2dOptions.grid_tolerance", "must be finite and > 0"));
    }
    if !(1..=3).contains(&options.near_field) {
        return Err(SolveError::invalid("Ehl2dOptions.near_field", "must be within 1–3"));
    }
    for (v, path) in [(options.inlet, "Ehl2dOptions.inlet"), (options.outlet, "Ehl2dOptions.outlet"), (options.side, "Ehl2dOptions.side")] {
        if let Some(v) = v {
            if !(v.is_finite() && v >= 0.5 && v <= 100.0) {
                return Err(SolveError::invalid(path, "must be within 0.5–100 (units of the Hertzian semi-axis)"));
            }
        }
    }
    Ok(())
}

/// A transient step's time step and previous level: `time_step` finite and > 0, the previous
/// level a converged solution of the same contact kind with its pressure and mass per area.
pub(super) fn validate_squeeze(squeeze: &Squeeze2d, finite: bool) -> Result<(), SolveError> {
    if !(squeeze.time_step.is_finite() && squeeze.time_step > 0.0) {
        return Err(SolveError::invalid("Squeeze2d.time_step", "must be a finite number > 0 (s)"));
    }
    let w = squeeze.previous;
    let sized = w.x.len() >= 2 && w.y.len() >= 2 && w.mass.len() == w.x.len() * w.y.len() && w.pressure.len() == w.mass.len();
    let finite_values = w.a.is_finite() && w.a > 0.0 && w.mass.iter().all(|m| m.is_finite() && *m >= 0.0) && (w.sign == 1.0 || w.sign == -1.0);
    if !(sized && finite_values) {
        return Err(SolveError::invalid("Squeeze2d.previous", "must be a converged 2-D solution with its mass per area at every node"));
    }
    if w.finite != finite {
        return Err(SolveError::invalid("Squeeze2d.previous", "must be of the same contact kind (point or finite line) as the input"));
    }
    Ok(())
}
