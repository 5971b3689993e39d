//! The engine's SAO (`Res/ao/sao.frag`): the lesson's algorithm with a round disc in view space, the
//! screen radius clamped, sky and sub-pixel discs skipped, as many mip levels as its largest disc
//! needs, and the packed separable blur every engine method uses (`ao::packed`).

use crate::ao::blur::SeparableBlur;
use crate::ao::method_pass::{
    max_radius_pixels, method_defines, normal_source_define, set_common_uniforms, AoInputs,
    AoMethodPass, LOG_MAX_OFFSET,
};
use crate::ao::packed::{PackedOutput, PACKED_BLUR_SHADER};
use crate::ao::settings::{AoMethod, AoSettings};
use crate::gl::texture::max_levels;
use crate::gl::{Gl, ProgramError, ProgramObject, Texture};
use crate::math::Camera;
use crate::res::ResDirs;
use crate::shader_interface::binding;
use anyhow::Result;
use std::rc::Rc;

pub const SHADER: &str = "ao/sao.frag";

/// `aoCounts` = (samples, spiral turns).
pub fn counts(s: &AoSettings) -> [i32; 2] {
    [s.samples.max(1) as i32, s.spiral_turns.max(1) as i32]
}

/// Levels of the linear-depth chain the engine's SAO reads: its samples lie within the clamped
/// screen radius, so the farthest reads level floor(log2(max radius)) − LOG_MAX_OFFSET; capped by
/// what the half-size texture can hold.
pub fn depth_levels(half_width: u32, half_height: u32) -> u32 {
    let radius = max_radius_pixels(half_width, half_height) as u32;
    let top = (31 - radius.max(1).leading_zeros()).saturating_sub(LOG_MAX_OFFSET);
    (top + 1).min(max_levels(half_width, half_height))
}

pub struct SaoMethod {
    program: ProgramObject,
    blur: ProgramObject,
    packed: PackedOutput,
}

impl SaoMethod {
    pub fn build(gl: &Gl, res: &ResDirs, camera: &Camera) -> Result<SaoMethod, ProgramError> {
        let d = method_defines(camera);
        Ok(SaoMethod {
            program: ProgramObject::from_res(gl, res, "simple.vert", SHADER, &d)?,
            blur: ProgramObject::from_res(gl, res, "simple.vert", PACKED_BLUR_SHADER, &d)?,
            packed: PackedOutput::default(),
        })
    }
}

impl AoMethodPass for SaoMethod {
    fn method(&self) -> AoMethod {
        AoMethod::Sao
    }
    fn programs_mut(&mut self) -> Vec<&mut ProgramObject> {
        vec![&mut self.program, &mut self.blur]
    }
    fn update_defines(&mut self, camera: &Camera, s: &AoSettings) -> Result<(), ProgramError> {
        let d = method_defines(camera);
        let mut own = d.clone();
        own.push(normal_source_define(s));
        self.program.set_defines(&own)?;
        self.blur.set_defines(&d)
    }
    fn depth_levels(&self, (w, h): (u32, u32)) -> u32 {
        depth_levels(w, h)
    }
    fn compute(&self, i: &AoInputs) -> Result<()> {
        set_common_uniforms(i.gl, &self.program, i, counts(i.settings));
        i.pass_state().apply(i.gl, None);
        self.program.use_program();
        self.packed.bind_for_method(i.gl, i.targets)?;
        i.targets.tex_depth.bind(binding::INPUT);
        i.bind_normals();
        i.meshes.draw_plane_xy();
        Ok(())
    }
    fn blur(&self, i: &AoInputs, _: &SeparableBlur) -> Result<()> {
        self.packed
            .blur(i.gl, i.targets, i.meshes, &self.blur, i.region)
    }
    fn textures(&self) -> Vec<Rc<Texture>> {
        self.packed.textures()
    }
    fn release_targets(&mut self) {
        self.packed.release();
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
