//! The tools built on the engine: the ray-traced reference, the bench, the parameter tuner, the grader, the student's
//! lesson loop and the teacher's class repositories (Classroom 50 and GitHub Actions).

#[cfg(feature = "bench")]
pub mod bench;
#[cfg(feature = "bench")]
pub mod challenge;
pub mod classroom;
pub mod error_map;
pub mod grade;
pub mod lesson;
pub mod lesson_edition;
pub mod metrics;
pub mod reference;
#[cfg(feature = "bench")]
pub mod tune;
#[cfg(feature = "window")]
pub mod window_truth;
