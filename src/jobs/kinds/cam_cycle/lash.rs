//! Mechanical lash of a `dynamic` load (issue 45 item 1): the spec section, its validation and
//! the summary figures (physics: `ValveTrain::lash` in `physics::valvetrain::model`).

use super::spec::DynamicLoadSpec;
use crate::jobs::kind::Validation;
use serde::{Deserialize, Serialize};
use utoipa::ToSchema;

/// A mechanical valve lash: the clearance in the train with the cam on its base circle. While
/// it is open the valve rests on its seat (required), which carries the spring preload; the
/// cam's opening ramp takes it up (impact: `summary.opening_impact_velocity`) and the closing
/// ramp opens it again (`summary.seating_velocity`). The ramps are the lift law's.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct LashSpec {
    /// Clearance at the valve, m (with a lever the model puts clearance / ratio between cam and
    /// follower).
    pub clearance: f64,
}

/// Validate `load.lash` (paths under `/load`); `max_lift`: the cam's largest lift, m.
pub fn validate_lash(d: &DynamicLoadSpec, v: &mut Validation) {
    let Some(l) = d.lash else { return };
    v.in_range("/load/lash/clearance", l.clearance, 0.0, 0.005);
    v.check(d.seat.is_some(), "/load/seat", "is required with a lash: the seat carries the spring preload while the clearance is open");
    v.warn("/load/lash/clearance", (l.clearance > 1e-3).then(|| format!("a valve lash of {:.3} mm is large (typically 0.1 to 0.5 mm)", l.clearance * 1e3)));
}
