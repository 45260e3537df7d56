//! The list of job kinds. Adding a kind is one line here.

use super::kind::{DynKind, Registered};
use super::kinds;

/// Every kind the service runs, in the order `GET /v1/kinds` lists them.
pub static KINDS: &[&dyn DynKind] = &[
    &Registered::<kinds::hertz::Hertz>::new(),
    &Registered::<kinds::cam_cycle::CamCycle>::new(),
    &Registered::<kinds::cam_point::CamPoint>::new(),
    #[cfg(feature = "test-kinds")]
    &Registered::<kinds::test_sleep::TestSleep>::new(),
];

/// The kind named `name`.
pub fn find(name: &str) -> Option<&'static dyn DynKind> {
    KINDS.iter().copied().find(|k| k.name() == name)
}

/// The names of all kinds, for error messages.
pub fn names() -> Vec<&'static str> {
    KINDS.iter().map(|k| k.name()).collect()
}
