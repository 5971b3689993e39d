//! The back-face depth pass for `vbao`'s per-pixel thickness (`--thickness backface`): the scene's
//! depth with front faces culled, linearised at the AO buffers' size. Runs only when the settings
//! ask for it (`AoSettings::uses_back_faces`).

use super::ao_size_restore::{DepthLayer, LayerRestore};
use crate::gl::pass_state::Cull;
use crate::gl::{Gl, PassState, ProgramObject, Texture};
use crate::render::frame::Frame;
use crate::res::ResDirs;
use crate::shader_interface::loc;
use anyhow::Result;
use std::rc::Rc;

pub struct BackFacePass {
    restore: LayerRestore,
    layer: DepthLayer,
}

impl BackFacePass {
    pub fn new(gl: &Gl, res: &ResDirs) -> Result<BackFacePass> {
        Ok(BackFacePass {
            restore: LayerRestore::new(gl, res)?,
            layer: DepthLayer::new("back-face"),
        })
    }

    pub fn programs_mut(&mut self) -> [&mut ProgramObject; 2] {
        self.restore.programs_mut()
    }

    /// Draws the back faces with `depth_only` (the shadow program: position only) and returns the
    /// linear back depth at `ao_size`, behind the texels the front restore keeps (`front_depth`: the
    /// main depth buffer).
    pub fn draw(
        &self,
        f: &Frame,
        depth_only: &ProgramObject,
        front_depth: &Texture,
        ao_size: (u32, u32),
    ) -> Result<Rc<Texture>> {
        self.layer.begin(f, ao_size)?;
        f.apply(PassState {
            color_write: false,
            cull: Cull::Front,
            ..f.scene_depth_state(true)
        });
        depth_only.set_mat4(loc::VIEW_PROJECTION, &f.scene_view_projection());
        depth_only.use_program();
        f.draw_objects(depth_only, false, &f.view_projection());
        self.layer.finish(f, &self.restore, front_depth)
    }

    /// The linear back depth of the last frame that ran the pass.
    pub fn linear_depth(&self) -> Option<Rc<Texture>> {
        self.layer.linear_depth()
    }

    pub fn textures(&self) -> Vec<Rc<Texture>> {
        self.layer.textures()
    }

    pub fn release_targets(&self) {
        self.layer.release_targets();
    }
}
