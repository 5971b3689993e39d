//! The second depth layer for `vbao` (`--layers 2`, `[ao] layers = 2`): the nearest front face at
//! least a minimum separation behind the visible surface (Mara et al. 2016's deep G-buffer rule),
//! linearised at the AO buffers' size. Runs only when the settings ask for it
//! (`AoSettings::uses_second_layer`).

use super::ao_size_restore::restore_at_ao_size;
use crate::ao::blur::half_size_target;
use crate::gl::pass_state::Cull;
use crate::gl::{FramebufferObject, Gl, PassState, ProgramObject, Texture, TextureDesc};
use crate::render::frame::Frame;
use crate::res::ResDirs;
use crate::shader_interface::{binding, loc};
use anyhow::{anyhow, Result};
use std::cell::RefCell;
use std::rc::Rc;

pub const LAYER_SHADER: &str = "ao/second_layer.frag";
/// The restore keeps, per AO texel, the layer behind the texel the front restore keeps: the same
/// rule as the back faces', so one shader serves both.
pub const RESTORE_SHADER: &str = super::back_faces::RESTORE_SHADER;

/// Targets of one size and depth convention.
struct Targets {
    /// Main-size depth of the second layer.
    depth: FramebufferObject,
    /// Its linear depth (m) at the AO size; `far` where nothing lies behind.
    linear: FramebufferObject,
    key: ((u32, u32), (u32, u32), u32),
}

pub struct SecondLayerPass {
    layer: ProgramObject,
    restore: ProgramObject,
    targets: RefCell<Option<Targets>>,
}

impl SecondLayerPass {
    pub fn new(gl: &Gl, res: &ResDirs) -> Result<SecondLayerPass> {
        Ok(SecondLayerPass {
            layer: ProgramObject::from_res(gl, res, "shadow.vert", LAYER_SHADER, &[])?,
            restore: ProgramObject::from_res(gl, res, "simple.vert", RESTORE_SHADER, &[])?,
            targets: RefCell::new(None),
        })
    }

    pub fn programs_mut(&mut self) -> [&mut ProgramObject; 2] {
        [&mut self.layer, &mut self.restore]
    }

    /// Draws the front faces at least `separation` metres behind `front_depth` (the main depth
    /// buffer) and returns their linear depth at `ao_size`.
    pub fn draw(
        &self,
        f: &Frame,
        front_depth: &Texture,
        separation: f32,
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
                TextureDesc::target("FBO(second layer depth)", w, h, format).compare(false),
            )?);
            *slot = Some(Targets {
                depth: FramebufferObject::new(f.gl, None, Some(depth), 0, 0)?,
                linear: half_size_target(
                    f.gl,
                    "FBO(second layer linear depth)",
                    ao_size,
                    glow::R32F,
                )?,
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
        // Front faces only: behind a closed object's front the next surface that can occlude is
        // another object's front, and its own back face is the back-face pass's business.
        f.apply(PassState {
            color_write: false,
            cull: Cull::Back,
            ..f.scene_depth_state(true)
        });
        let c = f.camera;
        let reversed = if f.depth_mode.reversed() { 1.0 } else { 0.0 };
        self.layer.use_program();
        self.layer
            .set_vec3(loc::UPSAMPLE_DEPTH_PLANES, [c.near, c.far, reversed]);
        self.layer.set_f32(loc::LAYER_SEPARATION, separation);
        self.layer
            .set_mat4(loc::VIEW_PROJECTION, &f.scene_view_projection());
        front_depth.bind(binding::INPUT);
        f.draw_objects(&self.layer, false, &f.view_projection());
        f.apply(PassState::FULLSCREEN);
        let layer = t
            .depth
            .depth_texture()
            .ok_or_else(|| anyhow!("the second-layer FBO has no depth texture"))?;
        restore_at_ao_size(f, &self.restore, &t.linear, layer, front_depth)
    }

    /// The second layer's linear depth from the last frame that ran the pass.
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
