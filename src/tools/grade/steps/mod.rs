//! The grader's five steps, one file each: each grades the student's pass of a built rig and returns
//! its verdict.

mod blur;
mod down_sampling;
mod restore;
mod sao;
mod simple;

pub use blur::{blur, BLUR_SIZE};
pub use down_sampling::down_sampling;
pub use restore::{restore, MAIN_SIZE};
pub use sao::{sao, SAO_SIZE};
pub use simple::{simple, SIMPLE_SIZE};
