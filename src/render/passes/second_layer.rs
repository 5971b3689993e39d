//! The second depth layer for `vbao` (`--layers 2`, `[ao] layers = 2`): the nearest front face at
//! least a minimum separation behind the visible surface (Mara et al. 2016's deep G-buffer rule),
//! linearised at the AO buffers' size, and with `thickness = "backface"` the nearest back face behind
//! that layer's front. Runs only when the settings ask for it (`AoSettings::uses_second_layer`,
//! `AoSettings::uses_second_layer_back_faces`).

use super::ao_size_restore::{DepthLayer, LayerRestore};
use crate::gl::pass_state::Cull;
use crate::gl::{Gl, PassState, ProgramObject, Texture};
use crate::render::frame::Frame;
use crate::res::ResDirs;
use crate::shader_interface::{binding, loc};
use anyhow::{anyhow, Result};
use std::rc::Rc;

pub const LAYER_SHADER: &str = "ao/second_layer.frag";
pub struct SecondLayerPass {
    program: ProgramObject,
    /// Keeps, per AO texel, the layer behind the texel the front restore keeps: the same rule as the
    /// back faces', so one shader serves both.
    restore: LayerRestore,
    layer: DepthLayer,
    back: DepthLayer,
}

impl SecondLayerPass {
    pub fn new(gl: &Gl, res: &ResDirs) -> Result<SecondLayerPass> {
        Ok(SecondLayerPass {
            program: ProgramObject::from_res(gl, res, "shadow.vert", LAYER_SHADER, &[])?,
            restore: LayerRestore::new(gl, res)?,
            layer: DepthLayer::new("second layer"),
            back: DepthLayer::new("second layer back-face"),
        })
    }

    pub fn programs_mut(&mut self) -> [&mut ProgramObject; 3] {
        let [a, b] = self.restore.programs_mut();
        [&mut self.program, a, b]
    }

    /// Draws the front faces at least `separation` metres behind `front_depth` (the main depth
    /// buffer) and returns their linear depth at `ao_size` ('far' where none).
    pub fn draw(
        &self,
        f: &Frame,
        front_depth: &Texture,
        separation: f32,
        ao_size: (u32, u32),
    ) -> Result<Rc<Texture>> {
        self.layer.begin(f, ao_size)?;
        // Front faces only: behind a closed object's front the next surface that can occlude is
        // another object's front, and its own back face is the back-face pass's business.
        f.apply(PassState {
            color_write: false,
            cull: Cull::Back,
            ..f.scene_depth_state(true)
        });
        self.set_uniforms(f, separation);
        front_depth.bind(binding::INPUT);
        f.draw_objects(&self.program, false, &f.view_projection());
        self.layer.finish(f, &self.restore, front_depth)
    }

    /// After `draw` in the same frame: the nearest back faces behind the second layer's front,
    /// their linear depth at `ao_size` ('far' where none), kept behind the same texels as the
    /// layer's. The layer program with no separation and the layer as its "front" discards every
    /// back face not behind it, so the depth test keeps the one that closes the hidden object (the
    /// first layer's own back faces lie in front of it).
    pub fn draw_back_faces(
        &self,
        f: &Frame,
        front_depth: &Texture,
        ao_size: (u32, u32),
    ) -> Result<Rc<Texture>> {
        let layer = self
            .layer
            .depth_texture()
            .ok_or_else(|| anyhow!("the second layer's back faces were asked before the layer"))?;
        self.back.begin(f, ao_size)?;
        f.apply(PassState {
            color_write: false,
            cull: Cull::Front,
            ..f.scene_depth_state(true)
        });
        self.set_uniforms(f, 0.0);
        layer.bind(binding::INPUT);
        f.draw_objects(&self.program, false, &f.view_projection());
        self.back.finish(f, &self.restore, front_depth)
    }

    fn set_uniforms(&self, f: &Frame, separation: f32) {
        let c = f.camera;
        let reversed = if f.depth_mode.reversed() { 1.0 } else { 0.0 };
        self.program.use_program();
        self.program
            .set_vec3(loc::UPSAMPLE_DEPTH_PLANES, [c.near, c.far, reversed]);
        self.program.set_f32(loc::LAYER_SEPARATION, separation);
        self.program
            .set_mat4(loc::VIEW_PROJECTION, &f.scene_view_projection());
    }

    /// The second layer's linear depth from the last frame that ran the pass.
    pub fn linear_depth(&self) -> Option<Rc<Texture>> {
        self.layer.linear_depth()
    }

    /// The linear depth of the second layer's back faces from the last frame that drew them.
    pub fn back_linear_depth(&self) -> Option<Rc<Texture>> {
        self.back.linear_depth()
    }

    pub fn textures(&self) -> Vec<Rc<Texture>> {
        let mut t = self.layer.textures();
        t.extend(self.back.textures());
        t
    }

    pub fn release_targets(&self) {
        self.layer.release_targets();
        self.back.release_targets();
    }
}
