//! Visibility-bitmask AO (Therrien et al. 2023): per slice, 32 sectors of equal cosine weight, each
//! depth sample occluding the sectors its slab (surface to `thickness` behind, within the radius)
//! covers. Shader: `Res/ao/vbao.frag`; quality presets shared with `gtao` (`settings::GtaoQuality`).

use crate::ao::method_pass::{units_for_budget, ShaderMethod};
use crate::ao::settings::{AoMethod, AoSettings};
use crate::gl::{Gl, ProgramError};
use crate::math::Camera;
use crate::res::ResDirs;

pub const SHADER: &str = "ao/vbao.frag";

/// Slices when no preset is set: two, as `gtao`, so `--samples N` buys both methods the same depth
/// taps (slices × 2 sides × steps ≈ N).
pub const DEFAULT_SLICES: i32 = 2;

/// `aoCounts` = (slices, steps per side): the preset's when one is set.
pub fn counts(s: &AoSettings) -> [i32; 2] {
    if let Some(q) = s.quality {
        let (slices, steps) = q.slices_steps();
        return [slices as i32, steps as i32];
    }
    [
        DEFAULT_SLICES,
        units_for_budget(s.samples, 2 * DEFAULT_SLICES as u32),
    ]
}

pub fn build(gl: &Gl, res: &ResDirs, camera: &Camera) -> Result<ShaderMethod, ProgramError> {
    ShaderMethod::build(AoMethod::Vbao, SHADER, counts, gl, res, camera)
}
