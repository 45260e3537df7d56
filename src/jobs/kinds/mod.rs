//! One module per job kind: its spec, its output, validation and the call into `physics`.

pub mod bearing;
pub mod bearing_optimisation;
pub mod cam_common;
pub mod cam_cycle;
pub mod cam_point;
pub mod ehl_point;
pub mod hertz;
pub mod sweep;
pub mod wear;
#[cfg(feature = "test-kinds")]
pub mod test_sleep;
