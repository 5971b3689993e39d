//! The shape of a method's row in the layer of the methods (`ao::method::row` gives each one's):
//! in its own file, so that the methods' files and the table that lists them do not use each other.

use super::method_pass::AoMethodPass;
use super::settings::AoSettings;
use crate::gl::{Gl, ProgramError};
use crate::math::Camera;
use crate::res::ResDirs;
use crate::shader_interface::{Sampler, Uniform};

/// Builds a method's passes (its programs compiled for `camera` and `settings`).
pub type BuildFn =
    fn(&Gl, &ResDirs, &Camera, &AoSettings) -> Result<Box<dyn AoMethodPass>, ProgramError>;

/// How the engine builds one method, and what its occlusion shader (`MethodInfo::shader`) declares.
pub struct MethodRow {
    pub build: BuildFn,
    pub uniforms: &'static [Uniform],
    pub samplers: &'static [Sampler],
}
