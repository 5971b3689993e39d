//! Normal-oriented hemisphere SSAO (Filion and McNaughton 2008, StarCraft II): the sphere kernel flipped into the surface's
//! hemisphere, with a range check so distant occluders do not count. Shader: `Res/ao/hemisphere.frag`.

use crate::ao::method_pass::ShaderMethod;
use crate::ao::settings::{AoMethod, AoSettings};
use crate::gl::{Gl, ProgramError};
use crate::math::Camera;
use crate::res::ResDirs;

pub const SHADER: &str = "ao/hemisphere.frag";

/// `aoCounts` = (sample count, unused).
pub fn counts(s: &AoSettings) -> [i32; 2] {
    [s.samples.max(1) as i32, 1]
}

pub fn build(gl: &Gl, res: &ResDirs, camera: &Camera) -> Result<ShaderMethod, ProgramError> {
    ShaderMethod::build(AoMethod::Hemisphere, SHADER, counts, gl, res, camera)
}
