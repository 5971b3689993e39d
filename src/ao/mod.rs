//! Ambient-occlusion methods, each with its own passes and shaders.

pub mod sao_lesson;

pub use sao_lesson::{SaoLesson, SaoParams};
