//! The surface-normal pass for the engine's AO methods (`[ao] normals = "geometric"`, the default):
//! the scene drawn once more with `ao/surface_normal.vert/frag`, each pixel keeping the geometric
//! normal of the triangle it sees (octahedral, view space, two 16-bit floats), then brought to the AO
//! buffers' size by `ao/restore_normal.frag` (drawn at that size, as the engine's AO chain draws it,
//! the pass's own target serves as it is). Runs only when the settings ask for it
//! (`AoSettings::uses_surface_normals`).

use super::ao_size_restore::restore_at_ao_size;
use crate::ao::blur::ao_size_target;
use crate::gl::{FramebufferObject, Gl, PassState, ProgramObject, Texture, TextureDesc};
use crate::render::frame::Frame;
use crate::res::ResDirs;
use crate::shader_interface::loc;
use anyhow::{anyhow, Result};
use std::cell::RefCell;
use std::rc::Rc;

pub const SURFACE_SHADER: (&str, &str) = ("ao/surface_normal.vert", "ao/surface_normal.frag");
pub const RESTORE_SHADER: &str = "ao/restore_normal.frag";

/// Two 16-bit floats per texel: the octahedral code round-trips within 1e-3 rad.
const NORMAL_FORMAT: u32 = glow::RG16F;

/// Targets of one size and depth convention.
struct Targets {
    /// Main-size normals, with a depth buffer of their own.
    main: FramebufferObject,
    /// Normals at the AO size; `None` when that is the main size (the main target serves).
    restored: Option<FramebufferObject>,
    key: ((u32, u32), (u32, u32), u32),
}

pub struct NormalPass {
    surface: ProgramObject,
    restore: ProgramObject,
    targets: RefCell<Option<Targets>>,
}

impl NormalPass {
    pub fn new(gl: &Gl, res: &ResDirs) -> Result<NormalPass> {
        let (vert, frag) = SURFACE_SHADER;
        Ok(NormalPass {
            surface: ProgramObject::from_res(gl, res, vert, frag, &[])?,
            restore: ProgramObject::from_res(gl, res, "simple.vert", RESTORE_SHADER, &[])?,
            targets: RefCell::new(None),
        })
    }

    pub fn programs_mut(&mut self) -> [&mut ProgramObject; 2] {
        [&mut self.surface, &mut self.restore]
    }

    /// Draws the opaque objects' normals and returns them at `ao_size`, taken from the texel of each
    /// block that the front depth restore keeps: the nearest in `front_depth` (the main depth
    /// buffer), or in the pass's own depth when `None` (a widened view the main pass did not draw).
    pub fn draw(
        &self,
        f: &Frame,
        front_depth: Option<&Texture>,
        ao_size: (u32, u32),
    ) -> Result<Rc<Texture>> {
        let format = f.depth_mode.internal_format();
        let key = (f.size, ao_size, format);
        let mut slot = self.targets.borrow_mut();
        if slot.as_ref().map(|t| t.key) != Some(key) {
            *slot = None;
            let (w, h) = f.size;
            let color = Rc::new(Texture::new(
                f.gl,
                TextureDesc::target("FBO(surface normals)", w, h, NORMAL_FORMAT),
            )?);
            let depth = Rc::new(Texture::new(
                f.gl,
                TextureDesc::target("FBO(surface-normal depth)", w, h, format).compare(false),
            )?);
            *slot = Some(Targets {
                main: FramebufferObject::new(f.gl, Some(color), Some(depth), 0, 0)?,
                restored: if ao_size == f.size {
                    None
                } else {
                    Some(ao_size_target(
                        f.gl,
                        "FBO(surface normals, AO size)",
                        ao_size,
                        NORMAL_FORMAT,
                    )?)
                },
                key,
            });
        }
        let t = slot.as_ref().expect("created above");
        t.main.bind();
        f.apply(f.scene_depth_state(true));
        // SAFETY: clears of the bound framebuffer.
        unsafe {
            use glow::HasContext;
            f.gl.clear_color(0.0, 0.0, 0.0, 0.0);
            f.gl.clear_depth_f32(f.depth_mode.clear_value());
            f.gl.clear(glow::COLOR_BUFFER_BIT | glow::DEPTH_BUFFER_BIT);
        }
        let p = &self.surface;
        p.set_mat4(loc::VIEW_PROJECTION, &f.scene_view_projection());
        p.set_mat4(loc::VIEW_MATRIX, &f.camera.view());
        p.use_program();
        f.draw_objects(p, false, &f.view_projection());
        f.apply(PassState::FULLSCREEN);
        let normals = t
            .main
            .color_texture()
            .ok_or_else(|| anyhow!("the surface-normal FBO has no colour texture"))?;
        let Some(restored) = &t.restored else {
            // Drawn at the AO size (a block of one texel): the restore would be a plain copy.
            return Ok(normals.clone());
        };
        let own_depth = t.main.depth_texture();
        let front = front_depth
            .or(own_depth.map(|d| d.as_ref()))
            .ok_or_else(|| anyhow!("the surface-normal FBO has no depth texture"))?;
        restore_at_ao_size(f, &self.restore, restored, normals, front)
    }

    /// The depth buffer of the last frame that ran the pass (the widened view's, with a guard band).
    pub fn depth_texture(&self) -> Result<Rc<Texture>> {
        let slot = self.targets.borrow();
        slot.as_ref()
            .and_then(|t| t.main.depth_texture().cloned())
            .ok_or_else(|| anyhow!("the surface-normal pass has not run"))
    }

    /// The normals at the AO size of the last frame that ran the pass.
    pub fn restored(&self) -> Option<Rc<Texture>> {
        let slot = self.targets.borrow();
        slot.as_ref().and_then(|t| {
            t.restored
                .as_ref()
                .unwrap_or(&t.main)
                .color_texture()
                .cloned()
        })
    }

    pub fn textures(&self) -> Vec<Rc<Texture>> {
        let slot = self.targets.borrow();
        let Some(t) = slot.as_ref() else {
            return Vec::new();
        };
        t.main
            .color_texture()
            .into_iter()
            .chain(t.main.depth_texture())
            .chain(t.restored.as_ref().and_then(|r| r.color_texture()))
            .cloned()
            .collect()
    }

    pub fn release_targets(&self) {
        *self.targets.borrow_mut() = None;
    }
}
