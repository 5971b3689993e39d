//! The tools built on the engine: the ray-traced reference, the bench, the grader and the student's
//! lesson loop.

pub mod bench;
pub mod error_map;
pub mod grade;
pub mod lesson;
pub mod reference;
