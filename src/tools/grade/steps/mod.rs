//! The grader's five steps, one file each (and `sao_checkpoint` for the start of `sao.frag` that
//! lessons 6 and 7 write): each grades the student's pass of a built rig and returns its verdict.

mod blur;
mod down_sampling;
mod restore;
mod sao;
mod sao_checkpoint;
mod sao_details;
mod sao_isotropy;
mod sao_lesson;
mod sao_measure;
mod sao_parts;
mod sao_reach;
mod simple;

pub use blur::{blur, course_blur, BLUR_SIZE};
pub use down_sampling::down_sampling;
pub use restore::{restore, MAIN_SIZE};
pub use sao::{sao, SAO_SIZE};
pub use sao_checkpoint::sao_checkpoint;
pub use sao_parts::erratum_name;
pub use simple::{probe_difference as simple_probe, simple, SIMPLE_SIZE};
