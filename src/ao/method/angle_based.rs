//! UE4-style angle-based SSAO (Mittring 2012, the Elemental demo): samples in mirrored pairs, occlusion from the angle the
//! pair makes over the pixel. Shader: `Res/ao/angle_based.frag`.

use crate::ao::method_pass::{units_for_budget, ShaderMethod};
use crate::ao::settings::{AoMethod, AoSettings};
use crate::gl::{Gl, ProgramError};
use crate::math::Camera;
use crate::res::ResDirs;

pub const SHADER: &str = "ao/angle_based.frag";

/// `aoCounts` = (pairs, unused): each pair is two taps, so pairs = samples / 2.
pub fn counts(s: &AoSettings) -> [i32; 2] {
    [units_for_budget(s.samples, 2), 1]
}

pub fn build(gl: &Gl, res: &ResDirs, camera: &Camera) -> Result<ShaderMethod, ProgramError> {
    ShaderMethod::build(AoMethod::AngleBased, SHADER, counts, gl, res, camera)
}
