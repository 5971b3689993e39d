//! The engine's SAO (`Res/ao/sao.frag`): the lesson's algorithm with a round disc in view space, the
//! screen radius clamped, sky and sub-pixel discs skipped, as many mip levels as its largest disc
//! needs, and the packed separable blur every engine method uses (`ao::packed`), on the shared skeleton (`ShaderMethod`).

use crate::ao::method_pass::{
    max_radius_pixels, AoInputs, AoMethodPass, ShaderMethod, LOG_MAX_OFFSET,
};
use crate::ao::method_row::MethodRow;
use crate::ao::settings::{AoMethod, AoSettings};
use crate::gl::texture::max_levels;
use crate::gl::{ProgramError, ProgramObject, Texture};
use crate::math::Camera;
use crate::shader_interface::{AO_METHOD_SAMPLERS, AO_METHOD_UNIFORMS};
use anyhow::Result;
use std::rc::Rc;

/// `aoCounts` = (samples, spiral turns).
pub fn counts(s: &AoSettings) -> [i32; 2] {
    [s.samples.max(1) as i32, s.spiral_turns.max(1) as i32]
}

/// Levels of the linear-depth chain the engine's SAO reads: its samples lie within the clamped
/// screen radius, so the farthest reads level floor(log2(max radius)) − LOG_MAX_OFFSET; capped by
/// what the AO-size texture can hold.
pub fn depth_levels(ao_width: u32, ao_height: u32) -> u32 {
    let radius = max_radius_pixels(ao_width, ao_height) as u32;
    let top = (31 - radius.max(1).leading_zeros()).saturating_sub(LOG_MAX_OFFSET);
    (top + 1).min(max_levels(ao_width, ao_height))
}

pub const ROW: MethodRow = MethodRow {
    build: |gl, res, camera, _| Ok(Box::new(SaoMethod::build(gl, res, camera)?)),
    uniforms: AO_METHOD_UNIFORMS,
    samplers: AO_METHOD_SAMPLERS,
};

/// The shared skeleton, with as many depth levels as its largest disc reads.
pub struct SaoMethod {
    pass: ShaderMethod,
}

impl SaoMethod {
    pub fn build(
        gl: &crate::gl::Gl,
        res: &crate::res::ResDirs,
        camera: &Camera,
    ) -> Result<SaoMethod, ProgramError> {
        let pass = ShaderMethod::build(AoMethod::Sao, counts, gl, res, camera)?;
        Ok(SaoMethod { pass })
    }

    /// The skeleton it runs (its packed target, for tests and tools that read the pair).
    pub fn pass(&self) -> &ShaderMethod {
        &self.pass
    }
}

impl AoMethodPass for SaoMethod {
    fn method(&self) -> AoMethod {
        AoMethod::Sao
    }
    fn programs_mut(&mut self) -> Vec<&mut ProgramObject> {
        self.pass.programs_mut()
    }
    fn update_defines(&mut self, camera: &Camera, s: &AoSettings) -> Result<(), ProgramError> {
        self.pass.update_defines(camera, s)
    }
    fn depth_levels(&self, (w, h): (u32, u32)) -> u32 {
        depth_levels(w, h)
    }
    fn compute(&self, inputs: &AoInputs) -> Result<()> {
        self.pass.compute(inputs)
    }
    fn blur(&self, inputs: &AoInputs) -> Result<()> {
        self.pass.blur(inputs)
    }
    fn textures(&self) -> Vec<Rc<Texture>> {
        self.pass.textures()
    }
    fn release_targets(&mut self) {
        self.pass.release_targets();
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn level_count_follows_the_largest_disc() {
        // 1920×1080 → 960×540 half size, radius clamp 240 px: log2 → 7, minus 3 → level 4.
        assert_eq!(depth_levels(960, 540), 5);
        // 640 → clamp 160 → level 4; 512 → 128 → level 4; 511 → 127.75 → level 3.
        assert_eq!(depth_levels(640, 360), 5);
        assert_eq!(depth_levels(512, 100), 5);
        assert_eq!(depth_levels(511, 100), 4);
        // Tiny buffers: one level, never more than the texture holds.
        assert_eq!(depth_levels(4, 4), 1);
        assert_eq!(depth_levels(8192, 2), 9);
    }
}
