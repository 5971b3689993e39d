//! The engine's SAO (`Res/ao/sao.frag`): the lesson's algorithm with a round disc in view space, the
//! screen radius clamped, sky and sub-pixel discs skipped, as many mip levels as its largest disc
//! needs, and a packed separable blur: the shader writes occlusion into the shared R8 target and the
//! (occlusion, linear depth) pair into an RG32F target in the same pass, so each blur tap is one fetch.

use crate::ao::blur::{half_size_target, packed_blur, SeparableBlur};
use crate::ao::method_pass::{
    max_radius_pixels, method_defines, set_common_uniforms, AoInputs, AoMethodPass, LOG_MAX_OFFSET,
};
use crate::ao::settings::{AoMethod, AoSettings};
use crate::gl::texture::max_levels;
use crate::gl::{FramebufferObject, Gl, PassState, ProgramError, ProgramObject, Texture};
use crate::math::Camera;
use crate::res::ResDirs;
use crate::shader_interface::binding;
use anyhow::{bail, Result};
use glow::HasContext;
use std::cell::RefCell;
use std::rc::Rc;

pub const SHADER: &str = "ao/sao.frag";
pub const PACKED_BLUR_SHADER: &str = "ao/blur_packed.frag";

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

/// RG32F keeps the depth exact, so the blur's `depth >= far` sky test holds.
struct PackedTargets {
    /// The shared occlusion texture attached as the second target (held so it outlives this FBO,
    /// and to notice when the shared targets were re-created).
    shared_sao: Rc<Texture>,
    packed: Rc<Texture>,
    /// Attachment 0 = `packed`, 1 = the shared occlusion texture; draw buffers map the shader's
    /// output 0 (occlusion) to attachment 1 and output 1 (the pair) to attachment 0.
    fbo_sao_and_packed: FramebufferObject,
    /// Between the two blur passes (RG32F).
    fbo_tmp: FramebufferObject,
}

impl PackedTargets {
    fn new(gl: &Gl, shared_sao: &Rc<Texture>) -> Result<PackedTargets> {
        let size = shared_sao.size_at(0);
        let fbo = half_size_target(gl, "FBO(sao packed)", size, glow::RG32F)?;
        let packed = fbo
            .color_texture()
            .cloned()
            .expect("created with a colour texture");
        // SAFETY: attaching an existing texture to an FBO this function owns.
        unsafe {
            gl.named_framebuffer_texture(
                Some(fbo.id()),
                glow::COLOR_ATTACHMENT1,
                Some(shared_sao.id()),
                0,
            );
            gl.named_framebuffer_draw_buffers(
                Some(fbo.id()),
                &[glow::COLOR_ATTACHMENT1, glow::COLOR_ATTACHMENT0],
            );
            let status = gl.check_named_framebuffer_status(Some(fbo.id()), glow::FRAMEBUFFER);
            if status != glow::FRAMEBUFFER_COMPLETE {
                bail!("packed SAO framebuffer is incomplete (status 0x{status:x})");
            }
        }
        Ok(PackedTargets {
            shared_sao: shared_sao.clone(),
            packed,
            fbo_sao_and_packed: fbo,
            fbo_tmp: half_size_target(gl, "FBO(sao packed blur tmp)", size, glow::RG32F)?,
        })
    }
}

pub struct SaoMethod {
    program: ProgramObject,
    blur: ProgramObject,
    packed: RefCell<Option<PackedTargets>>,
}

impl SaoMethod {
    pub fn build(gl: &Gl, res: &ResDirs, camera: &Camera) -> Result<SaoMethod, ProgramError> {
        let d = method_defines(camera);
        Ok(SaoMethod {
            program: ProgramObject::from_res(gl, res, "simple.vert", SHADER, &d)?,
            blur: ProgramObject::from_res(gl, res, "simple.vert", PACKED_BLUR_SHADER, &d)?,
            packed: RefCell::new(None),
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
    fn update_defines(&mut self, camera: &Camera, _: &AoSettings) -> Result<(), ProgramError> {
        let d = method_defines(camera);
        self.program.set_defines(&d)?;
        self.blur.set_defines(&d)
    }
    fn depth_levels(&self, (w, h): (u32, u32)) -> u32 {
        depth_levels(w, h)
    }
    fn compute(&self, i: &AoInputs) -> Result<()> {
        let shared = i.targets.sao_texture();
        let current = self
            .packed
            .borrow()
            .as_ref()
            .is_some_and(|p| Rc::ptr_eq(&p.shared_sao, shared));
        if !current {
            *self.packed.borrow_mut() = None;
            *self.packed.borrow_mut() = Some(PackedTargets::new(i.gl, shared)?);
        }
        set_common_uniforms(i.gl, &self.program, i, counts(i.settings));
        PassState::FULLSCREEN.apply(i.gl, None);
        self.program.use_program();
        let packed = self.packed.borrow();
        packed
            .as_ref()
            .expect("created above")
            .fbo_sao_and_packed
            .bind();
        i.targets.tex_depth.bind(binding::INPUT);
        i.meshes.draw_plane_xy();
        Ok(())
    }
    fn blur(&self, i: &AoInputs, _: &SeparableBlur) -> Result<()> {
        let packed = self.packed.borrow();
        let Some(t) = packed
            .as_ref()
            .filter(|p| Rc::ptr_eq(&p.shared_sao, i.targets.sao_texture()))
        else {
            bail!("the engine's SAO blur ran before its SAO pass");
        };
        packed_blur(i.gl, &self.blur, &t.packed, &t.fbo_tmp, i.targets, i.meshes);
        Ok(())
    }
    fn textures(&self) -> Vec<Rc<Texture>> {
        self.packed
            .borrow()
            .iter()
            .flat_map(|p| {
                [p.packed.clone()]
                    .into_iter()
                    .chain(p.fbo_tmp.color_texture().cloned())
            })
            .collect()
    }
    fn release_targets(&mut self) {
        *self.packed.get_mut() = None;
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
