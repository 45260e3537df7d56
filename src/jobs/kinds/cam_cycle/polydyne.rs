//! The polydyne's dynamic correction of a `synthesised` profile (`dynamic_correction`): the
//! train's effective mass, stiffness and spring rate — given, or from the `dynamic` load
//! (`physics::valvetrain::polydyne`) — and the corrected cam in the cycle
//! (`physics::cam::synthesis::dynamic`).

use super::spec::CamCycleSpec;
use super::synthesis::synthesised;
use crate::physics::cam::cycle::CycleSpec;
use crate::physics::cam::CamProfile;
use crate::physics::valvetrain::polydyne::PolydyneTrain;
use crate::physics::SolveError;

/// The design speed (rpm) and the train of a profile with `dynamic_correction`, each value as
/// given or from `from_load` (the `dynamic` load's train); `None` without a correction. A value
/// neither given nor derivable is refused naming its field.
pub fn train_of(spec: &CamCycleSpec, from_load: Option<PolydyneTrain>) -> Result<Option<(f64, PolydyneTrain)>, SolveError> {
    let Some(c) = synthesised(&spec.cam.profile).and_then(|s| s.dynamic_correction) else { return Ok(None) };
    let need = |v: Option<f64>, derived: Option<f64>, field: &str| {
        v.or(derived).ok_or_else(|| {
            SolveError::invalid(format!("/cam/profile/dynamic_correction/{field}"), "is required without a dynamic load to take it from (kg for the mass, N/m for the stiffness)")
        })
    };
    let mass = need(c.mass, from_load.map(|t| t.mass), "mass")?;
    let stiffness = need(c.stiffness, from_load.map(|t| t.stiffness), "stiffness")?;
    let spring_rate = c.spring_rate.or(from_load.map(|t| t.spring_rate)).unwrap_or(0.0);
    Ok(Some((c.design_speed_rpm, PolydyneTrain { mass, stiffness, spring_rate })))
}

/// Replace the cycle's synthesised law by the corrected one, if the profile asks for it.
pub fn apply(spec: &CamCycleSpec, cycle: &mut CycleSpec, from_load: Option<PolydyneTrain>) -> Result<(), SolveError> {
    let Some((rpm, train)) = train_of(spec, from_load)? else { return Ok(()) };
    let CamProfile::Synthesised { base_radius, law } = cycle.profile else { return Ok(()) };
    let omega = crate::physics::units::rpm_to_rad_per_s(rpm);
    let law = law.with_correction(train.correction(omega)).map_err(|e| match e {
        SolveError::InvalidInput { message, .. } => SolveError::invalid("/cam/profile/dynamic_correction", message),
        other => other,
    })?;
    cycle.profile = CamProfile::Synthesised { base_radius, law };
    Ok(())
}
