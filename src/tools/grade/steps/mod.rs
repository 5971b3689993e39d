//! The grader's four steps, one file each: each grades the student's pass of a built rig and returns
//! its verdict.

mod blur;
mod down_sampling;
mod restore;
mod sao;
mod sao_isotropy;

pub use blur::{blur, BLUR_SIZE};
pub use down_sampling::down_sampling;
pub use restore::{restore, MAIN_SIZE};
pub use sao::{sao, SAO_SIZE};
