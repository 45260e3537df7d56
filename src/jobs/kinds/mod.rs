//! One module per job kind: its spec, its output, validation and the call into `physics`.

pub mod ehl_point;
pub mod hertz;
pub mod sweep;
#[cfg(feature = "test-kinds")]
pub mod test_sleep;
