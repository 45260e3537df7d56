//! The list of job kinds (the case kinds of `jobs::kinds` and `sweep`), and lookup by name.

use super::kind::{DynKind, Registered};
use super::kinds;
use std::sync::LazyLock;

/// Every kind the service runs, in the order `GET /v1/kinds` and the OpenAPI document list them:
/// the case kinds (`jobs::kinds::CASE_KINDS`; a new kind is one line there) and `sweep`.
pub static KINDS: LazyLock<Vec<&'static dyn DynKind>> = LazyLock::new(|| {
    let mut all = kinds::CASE_KINDS.to_vec();
    all.push(&SWEEP);
    all
});

static SWEEP: Registered<kinds::sweep::Sweep> = Registered::new();



/// The kind named `name`.
pub fn find(name: &str) -> Option<&'static dyn DynKind> {
    KINDS.iter().chain(kinds::TEST_KINDS).copied().find(|k| k.name() == name)
}

/// The names of all kinds, for error messages.
pub fn names() -> Vec<&'static str> {
    KINDS.iter().map(|k| k.name()).collect()
}
