//! Mechanical lash of a `dynamic` load (issue 45 item 1): the spec section, its validation and
//! the summary figures (physics: `ValveTrain::lash` in `physics::valvetrain::model`); the spec
//! type is in `train_spec.rs`.

use super::spec::DynamicLoadSpec;
use crate::jobs::kind::Validation;

/// Validate `load.lash` (paths under `/load`).
pub fn validate_lash(d: &DynamicLoadSpec, v: &mut Validation) {
    let Some(l) = d.lash else { return };
    v.in_range("/load/lash/clearance", l.clearance, 0.0, 0.005);
    v.check(d.seat.is_some(), "/load/seat", "is required with a lash: the seat carries the spring preload while the clearance is open");
    v.warn("/load/lash/clearance", (l.clearance > 1e-3).then(|| format!("a valve lash of {:.3} mm is large (typically 0.1 to 0.5 mm)", l.clearance * 1e3)));
}
