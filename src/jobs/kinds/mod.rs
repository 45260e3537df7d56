//! One module per job kind: its spec, its output, validation and the call into `physics`.

pub mod cam_common;
pub mod cam_cycle;
pub mod cam_point;
pub mod hertz;
#[cfg(feature = "test-kinds")]
pub mod test_sleep;
