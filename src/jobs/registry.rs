//! The list of job kinds. Adding a kind is one line here.

use super::kind::{DynKind, Registered};
use super::kinds;

/// Every kind the service runs, in the order `GET /v1/kinds` and the OpenAPI document list them.
pub static KINDS: &[&dyn DynKind] = &[
    &Registered::<kinds::hertz::Hertz>::new(),
    &Registered::<kinds::bearing::BearingKind>::new(),
    &Registered::<kinds::bearing_optimisation::BearingOptimisation>::new(),
    &Registered::<kinds::cam_cycle::CamCycle>::new(),
    &Registered::<kinds::cam_point::CamPoint>::new(),
    &Registered::<kinds::ehl_point::EhlPoint>::new(),
    &Registered::<kinds::wear::Wear>::new(),
    &Registered::<kinds::sweep::Sweep>::new(),
];

/// Kinds compiled only into test builds (feature `test-kinds`): runnable, but neither listed nor
/// documented, so the OpenAPI document is the same in every build.
#[cfg(feature = "test-kinds")]
static TEST_KINDS: &[&dyn DynKind] = &[&Registered::<kinds::test_sleep::TestSleep>::new()];
#[cfg(not(feature = "test-kinds"))]
static TEST_KINDS: &[&dyn DynKind] = &[];

/// The kind named `name`.
pub fn find(name: &str) -> Option<&'static dyn DynKind> {
    KINDS.iter().chain(TEST_KINDS).copied().find(|k| k.name() == name)
}

/// The names of all kinds, for error messages.
pub fn names() -> Vec<&'static str> {
    KINDS.iter().map(|k| k.name()).collect()
}
