//! The back-face depth pass for `vbao`'s per-pixel thickness (`--thickness backface`): the scene's
//! depth with front faces culled, linearised at the AO buffers' size. Runs only when the settings
//! ask for it (`AoSettings::uses_back_faces`).

use super::ao_size_restore::restore_at_ao_size;
use crate::ao::blur::half_size_target;
use crate::gl::pass_state::Cull;
use crate::gl::{FramebufferObject, Gl, PassState, ProgramObject, Texture, TextureDesc};
use crate::render::frame::Frame;
use crate::res::ResDirs;
use crate::shader_interface::loc;
use anyhow::{anyhow, Result};
use std::cell::RefCell;
use std::rc::Rc;

pub const RESTORE_SHADER: &str = "ao/restore_back_depth.frag";

/// Targets of one size and depth convention.
struct Targets {
    /// Main-size depth of the back faces.
    depth: FramebufferObject,
    /// Linear back depth (m) at the AO size.
    linear: FramebufferObject,
    key: ((u32, u32), (u32, u32), u32),
}

pub struct BackFacePass {
    restore: ProgramObject,
    targets: RefCell<Option<Targets>>,
}

impl BackFacePass {
    pub fn new(gl: &Gl, res: &ResDirs) -> Result<BackFacePass> {
        Ok(BackFacePass {
            restore: ProgramObject::from_res(gl, res, "simple.vert", RESTORE_SHADER, &[])?,
            targets: RefCell::new(None),
        })
    }

    pub fn program_mut(&mut self) -> &mut ProgramObject {
        &mut self.restore
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
        let format = f.depth_mode.internal_format();
        let key = (f.size, ao_size, format);
        let mut slot = self.targets.borrow_mut();
        if slot.as_ref().map(|t| t.key) != Some(key) {
            *slot = None;
            let (w, h) = f.size;
            let depth = Rc::new(Texture::new(
                f.gl,
                TextureDesc::target("FBO(back-face depth)", w, h, format).compare(false),
            )?);
            *slot = Some(Targets {
                depth: FramebufferObject::new(f.gl, None, Some(depth), 0, 0)?,
                linear: half_size_target(f.gl, "FBO(back-face linear depth)", ao_size, glow::R32F)?,
                key,
            });
        }
        let t = slot.as_ref().expect("created above");
        t.depth.bind();
        f.apply(f.scene_depth_state(true));
        // SAFETY: clears of the bound framebuffer.
        unsafe {
            use glow::HasContext;
            f.gl.clear_depth_f32(f.depth_mode.clear_value());
            f.gl.clear(glow::DEPTH_BUFFER_BIT);
        }
        f.apply(PassState {
            color_write: false,
            cull: Cull::Front,
            ..f.scene_depth_state(true)
        });
        depth_only.set_mat4(loc::VIEW_PROJECTION, &f.scene_view_projection());
        depth_only.use_program();
        f.draw_objects(depth_only, false, &f.view_projection());
        f.apply(PassState::FULLSCREEN);
        let back = t
            .depth
            .depth_texture()
            .ok_or_else(|| anyhow!("the back-face FBO has no depth texture"))?;
        restore_at_ao_size(f, &self.restore, &t.linear, back, front_depth)
    }

    /// The linear back depth of the last frame that ran the pass.
    pub fn linear_depth(&self) -> Option<Rc<Texture>> {
        let slot = self.targets.borrow();
        slot.as_ref()
            .and_then(|t| t.linear.color_texture().cloned())
    }

    pub fn textures(&self) -> Vec<Rc<Texture>> {
        let slot = self.targets.borrow();
        let Some(t) = slot.as_ref() else {
            return Vec::new();
        };
        t.depth
            .depth_texture()
            .into_iter()
            .chain(t.linear.color_texture())
            .cloned()
            .collect()
    }

    pub fn release_targets(&self) {
        *self.targets.borrow_mut() = None;
    }
}
