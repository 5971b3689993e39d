//! The tools built on the engine: the ray-traced reference, the bench, the parameter tuner, the grader, the student's
//! lesson loop and the teacher's GitHub Classroom repository.

pub mod bench;
pub mod classroom;
pub mod error_map;
pub mod grade;
pub mod lesson;
pub mod reference;
pub mod tune;
pub mod window_truth;
