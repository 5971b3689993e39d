//! Ambient-occlusion methods, each with its own passes and shaders.

pub mod methods;
pub mod sao_lesson;

pub use methods::{AoMethod, AoMethods, GtaoQuality};
pub use sao_lesson::{CompositeMode, SaoLesson, SaoParams, SaoPrograms};
