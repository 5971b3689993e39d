//! Joint bilateral up-sampling of the engine's half-size AO to the main size
//! (`Res/ao/upsample_bilateral.frag`): silhouettes keep their own occlusion instead of the linear
//! filter's blocky halo. The lesson's `sao-lesson` keeps the course's linear filter.

use super::blur::half_size_target;
use crate::gl::{FramebufferObject, Gl, MeshBuffer, PassState, ProgramObject, Texture};
use crate::math::{Camera, DepthMode};
use crate::shader_interface::{binding, loc};
use anyhow::Result;
use std::cell::RefCell;
use std::rc::Rc;

pub const SHADER: &str = "ao/upsample_bilateral.frag";

pub struct BilateralUpsample {
    pub program: ProgramObject,
    /// Main-size R8 target, (re)created when the main size changes.
    target: RefCell<Option<FramebufferObject>>,
}

/// What one up-sampling reads.
pub struct UpsampleInputs<'a> {
    pub occlusion: &'a Texture,
    pub half_depth: &'a Texture,
    pub main_depth: &'a Texture,
    pub camera: &'a Camera,
    pub mode: DepthMode,
}

impl BilateralUpsample {
    pub fn new(program: ProgramObject) -> BilateralUpsample {
        BilateralUpsample {
            program,
            target: RefCell::new(None),
        }
    }

    /// Up-samples `inputs.occlusion` to the main depth buffer's size; returns the result.
    pub fn run(
        &self,
        gl: &Gl,
        meshes: &MeshBuffer,
        inputs: &UpsampleInputs,
    ) -> Result<Rc<Texture>> {
        let size = (inputs.main_depth.width(), inputs.main_depth.height());
        let mut target = self.target.borrow_mut();
        if target.as_ref().map(|f| (f.width(), f.height())) != Some(size) {
            *target = None;
            // Nearest filtering (the default): the composite reads it texel for texel.
            *target = Some(half_size_target(gl, "FBO(ao upsampled)", size, glow::R8)?);
        }
        let fbo = target.as_ref().expect("created above");
        PassState::FULLSCREEN.apply(gl, None);
        self.program.use_program();
        let reversed = if inputs.mode.reversed() { 1.0 } else { 0.0 };
        self.program.set_vec3(
            loc::UPSAMPLE_DEPTH_PLANES,
            [inputs.camera.near, inputs.camera.far, reversed],
        );
        fbo.bind();
        inputs.occlusion.bind(binding::INPUT);
        inputs.half_depth.bind(binding::SECOND_INPUT);
        inputs.main_depth.bind(binding::THIRD_INPUT);
        meshes.draw_plane_xy();
        fbo.color_texture()
            .cloned()
            .ok_or_else(|| anyhow::anyhow!("the up-sampling target has no colour texture"))
    }

    pub fn textures(&self) -> Vec<Rc<Texture>> {
        self.target
            .borrow()
            .iter()
            .filter_map(|f| f.color_texture().cloned())
            .collect()
    }

    pub fn release_targets(&self) {
        *self.target.borrow_mut() = None;
    }
}
