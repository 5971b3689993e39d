//! Crytek's SSAO (Mittring 2007, "Finding Next Gen: CryEngine 2"): points in a sphere around the pixel, occluded when the depth buffer is
//! nearer than the point. Shader: `Res/ao/crytek.frag`.

use crate::ao::method_pass::ShaderMethod;
use crate::ao::settings::{AoMethod, AoSettings};
use crate::gl::{Gl, ProgramError};
use crate::math::Camera;
use crate::res::ResDirs;

pub const SHADER: &str = "ao/crytek.frag";

/// `aoCounts` = (sample count, unused).
pub fn counts(s: &AoSettings) -> [i32; 2] {
    [s.samples.max(1) as i32, 1]
}

pub fn build(gl: &Gl, res: &ResDirs, camera: &Camera) -> Result<ShaderMethod, ProgramError> {
    ShaderMethod::build(AoMethod::Crytek, SHADER, counts, gl, res, camera)
}
