//! One module per job kind: its spec, its output, validation and the call into `physics`.

pub mod accuracy;
pub mod bearing;
pub mod bearing_optimisation;
pub mod common;
pub mod contact;
pub mod cam_cycle;
pub mod cam_optimisation;
pub mod cam_point;
pub mod ehl_point;
pub mod film_cost;
pub mod hertz;
pub mod rough_contact;
pub mod sweep;
pub mod thermal_spec;
pub mod wear;
#[cfg(feature = "test-kinds")]
pub mod test_sleep;

use super::kind::{DynKind, Registered};

/// The kinds that solve one case — every kind but the composite `sweep`, which runs cases of
/// these (and so looks them up here rather than in `jobs::registry`, which lists it).
pub static CASE_KINDS: &[&dyn DynKind] = &[
    &Registered::<hertz::Hertz>::new(),
    &Registered::<bearing::BearingKind>::new(),
    &Registered::<bearing_optimisation::BearingOptimisation>::new(),
    &Registered::<cam_cycle::CamCycle>::new(),
    &Registered::<cam_optimisation::CamOptimisation>::new(),
    &Registered::<cam_point::CamPoint>::new(),
    &Registered::<ehl_point::EhlPoint>::new(),
    &Registered::<wear::Wear>::new(),
    &Registered::<rough_contact::RoughContact>::new(),
];

/// The case kind named `name` (test kinds included in test builds).
pub fn case_kind(name: &str) -> Option<&'static dyn DynKind> {
    CASE_KINDS.iter().chain(TEST_KINDS).copied().find(|k| k.name() == name)
}

/// Kinds compiled only into test builds (feature `test-kinds`): runnable, but neither listed nor
/// documented, so the OpenAPI document is the same in every build.
#[cfg(feature = "test-kinds")]
pub static TEST_KINDS: &[&dyn DynKind] = &[&Registered::<test_sleep::TestSleep>::new()];
#[cfg(not(feature = "test-kinds"))]
pub static TEST_KINDS: &[&dyn DynKind] = &[];

