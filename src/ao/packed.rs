//! The targets of the packed blur every engine method uses: the method's pass writes occlusion into
//! the shared R8 target and the (occlusion, linear depth) pair into an RG32F target at once
//! (`WriteOcclusion` in `Res/ao/common.glsl`), so each tap of the blur (`Res/ao/blur_packed.frag`)
//! is one fetch instead of two (McGuire packs the blur key beside the AO value the same way).

use super::blur::{ao_size_target, packed_blur};
use super::sky_skip::{draw_texels, SkyValues, Texels};
use super::targets::AoTargets;
use crate::gl::{FramebufferObject, Gl, MeshBuffer, ProgramObject, Texture};
use anyhow::{bail, Result};
use glow::HasContext;
use std::cell::RefCell;
use std::rc::Rc;

pub const PACKED_BLUR_SHADER: &str = "ao/blur_packed.frag";

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
        let fbo = ao_size_target(gl, "FBO(ao packed)", size, glow::RG32F)?;
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
                bail!("packed AO framebuffer is incomplete (status 0x{status:x})");
            }
        }
        Ok(PackedTargets {
            shared_sao: shared_sao.clone(),
            packed,
            fbo_sao_and_packed: fbo,
            fbo_tmp: ao_size_target(gl, "FBO(ao packed blur tmp)", size, glow::RG32F)?,
        })
    }
}

/// A method's packed targets, created on its first pass and re-created with the shared targets.
#[derive(Default)]
pub struct PackedOutput {
    targets: RefCell<Option<PackedTargets>>,
}

impl PackedOutput {
    /// Draws the method's pass (`draw`, its program and inputs bound) into both outputs, shading
    /// `texels`, creating the targets if needed; where the sky is skipped its texels receive what
    /// every engine method writes there (`sky_skip`).
    pub fn draw_method(
        &self,
        gl: &Gl,
        shared_targets: &AoTargets,
        texels: Texels,
        draw: impl FnOnce(),
    ) -> Result<()> {
        let shared = shared_targets.sao_texture();
        let current = self
            .targets
            .borrow()
            .as_ref()
            .is_some_and(|p| Rc::ptr_eq(&p.shared_sao, shared));
        if !current {
            *self.targets.borrow_mut() = None;
            *self.targets.borrow_mut() = Some(PackedTargets::new(gl, shared)?);
        }
        let targets = self.targets.borrow();
        let fbo = &targets.as_ref().expect("created above").fbo_sao_and_packed;
        // Draw buffer 0 is the occlusion, 1 the (occlusion, linear depth) pair.
        let sky = [[0.0; 4], [0.0, texels.sky_far(), 0.0, 0.0]];
        let target = SkyValues {
            fbo,
            per_draw_buffer: &sky,
        };
        draw_texels(gl, texels, target, draw);
        Ok(())
    }

    /// The packed blur into the shared blur target (`program`: `ao/blur_packed.frag`), shading
    /// `texels` (`AoInputs::texels`).
    pub fn blur(
        &self,
        gl: &Gl,
        shared_targets: &AoTargets,
        meshes: &MeshBuffer,
        program: &ProgramObject,
        texels: Texels,
    ) -> Result<()> {
        let targets = self.targets.borrow();
        let Some(t) = targets
            .as_ref()
            .filter(|p| Rc::ptr_eq(&p.shared_sao, shared_targets.sao_texture()))
        else {
            bail!("the AO blur ran before the method's pass");
        };
        packed_blur(
            gl,
            program,
            &t.packed,
            &t.fbo_tmp,
            shared_targets,
            meshes,
            texels,
        );
        Ok(())
    }

    /// The (occlusion, linear depth) pair the method's pass wrote last.
    pub fn packed_texture(&self) -> Option<Rc<Texture>> {
        self.targets.borrow().as_ref().map(|p| p.packed.clone())
    }

    pub fn textures(&self) -> Vec<Rc<Texture>> {
        self.targets
            .borrow()
            .iter()
            .flat_map(|p| {
                [p.packed.clone()]
                    .into_iter()
                    .chain(p.fbo_tmp.color_texture().cloned())
            })
            .collect()
    }

    pub fn release(&mut self) {
        *self.targets.get_mut() = None;
    }
}
