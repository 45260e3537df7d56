//! One module per job kind: its spec, its output, validation and the call into `physics`.

pub mod bearing;
pub mod bearing_optimisation;
pub mod hertz;
#[cfg(feature = "test-kinds")]
pub mod test_sleep;
