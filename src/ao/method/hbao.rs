//! Horizon-based AO (Bavoil, Sainz and Dimitrov 2008): marches screen-space directions, keeps the highest horizon per
//! direction. Shader: `Res/ao/hbao.frag`.

use crate::ao::method_pass::{units_for_budget, ShaderMethod};
use crate::ao::settings::{AoMethod, AoSettings};
use crate::gl::{Gl, ProgramError};
use crate::math::Camera;
use crate::res::ResDirs;

pub const SHADER: &str = "ao/hbao.frag";

/// Four directions (the fewest that cover both screen axes both ways); the rest of the sample
/// budget goes to steps per direction, so directions × steps ≈ samples.
pub const DIRECTIONS: i32 = 4;

/// `aoCounts` = (directions, steps per direction).
pub fn counts(s: &AoSettings) -> [i32; 2] {
    [DIRECTIONS, units_for_budget(s.samples, DIRECTIONS as u32)]
}

pub fn build(gl: &Gl, res: &ResDirs, camera: &Camera) -> Result<ShaderMethod, ProgramError> {
    ShaderMethod::build(AoMethod::Hbao, SHADER, counts, gl, res, camera)
}
