//! The step the back-face and surface-normal passes share: a full-screen program that brings their
//! input to the AO buffers' size, keeping for each AO texel the value behind the texel of its block
//! whose front depth is nearest (the texel the depth restore keeps). The engine's AO chain draws
//! these passes at the AO size itself (`render/engine/guard.rs`), a block of one texel; the tools'
//! read-backs of the layers draw them at the main size.

use crate::ao::blur::ao_size_target;
use crate::gl::{FramebufferObject, Gl, PassState, ProgramObject, Texture, TextureDesc};
use crate::render::frame::Frame;
use crate::res::ResDirs;
use crate::shader_interface::{binding, loc};
use anyhow::{anyhow, Result};
use std::cell::RefCell;
use std::rc::Rc;

/// Runs `program` (`ao/restore_back_depth.frag` or `ao/restore_normal.frag`) from `input` and the
/// main depth `front_depth` into `target`, and returns the target's texture.
pub fn restore_at_ao_size(
    f: &Frame,
    program: &ProgramObject,
    target: &FramebufferObject,
    input: &Texture,
    front_depth: &Texture,
) -> Result<Rc<Texture>> {
    program.use_program();
    let reversed = if f.depth_mode.reversed() { 1.0 } else { 0.0 };
    let c = f.camera;
    program.set_vec3(loc::UPSAMPLE_DEPTH_PLANES, [c.near, c.far, reversed]);
    // Main texels per AO texel: 1 when the pass was drawn at the AO size, else the resolution's
    // divisor (the AO size is the main size divided and rounded down).
    let block = (f.size.0 / target.width().max(1)).max(1) as i32;
    program.set_i32(loc::BACK_DEPTH_BLOCK, block);
    target.bind();
    input.bind(binding::INPUT);
    front_depth.bind(binding::SECOND_INPUT);
    f.meshes.draw_plane_xy();
    target
        .color_texture()
        .cloned()
        .ok_or_else(|| anyhow!("the AO-size target has no colour texture"))
}

/// `ao/restore_back_depth.frag` built twice: for any block size, and for a block of one texel (the
/// pass drawn at the AO size, as the engine's AO chain draws it), where the texel's own depth is the
/// answer and the general loop's bookkeeping would cost as much as the rest of the pass.
pub struct LayerRestore {
    general: ProgramObject,
    one_texel: ProgramObject,
}

/// The shader that linearises a depth layer at the AO size (back faces, second layer).
pub const RESTORE_SHADER: &str = "ao/restore_back_depth.frag";

/// The define that builds the one-texel restore.
pub const ONE_TEXEL_DEFINE: &str = "RESTORE_ONE_TEXEL";

impl LayerRestore {
    pub fn new(gl: &Gl, res: &ResDirs) -> Result<LayerRestore> {
        let shader = RESTORE_SHADER;
        let one = [(ONE_TEXEL_DEFINE, "1".to_string())];
        Ok(LayerRestore {
            general: ProgramObject::from_res(gl, res, "simple.vert", shader, &[])?,
            one_texel: ProgramObject::from_res(gl, res, "simple.vert", shader, &one)?,
        })
    }

    pub fn programs_mut(&mut self) -> [&mut ProgramObject; 2] {
        [&mut self.general, &mut self.one_texel]
    }

    /// The build for `target` drawn from a pass of `f`'s size.
    fn for_target(&self, f: &Frame, target: &FramebufferObject) -> &ProgramObject {
        if f.size == (target.width(), target.height()) {
            &self.one_texel
        } else {
            &self.general
        }
    }
}

/// The targets of a depth pass over the geometry whose result is restored to the AO size (the back
/// faces, the second depth layer and its back faces): a main-size depth buffer and its linear depth at the AO size,
/// made again when the sizes or the depth format change.
struct LayerTargets {
    depth: FramebufferObject,
    linear: FramebufferObject,
    key: ((u32, u32), (u32, u32), u32),
}

/// A depth pass's targets, created on first use.
pub struct DepthLayer {
    name: &'static str,
    targets: RefCell<Option<LayerTargets>>,
}

impl DepthLayer {
    /// `name` labels the GL objects ("back-face", "second layer", ...).
    pub fn new(name: &'static str) -> DepthLayer {
        DepthLayer {
            name,
            targets: RefCell::new(None),
        }
    }

    /// Binds the main-size depth target (made for this frame's sizes), cleared to the far value;
    /// the caller then sets its state and draws.
    pub fn begin(&self, f: &Frame, ao_size: (u32, u32)) -> Result<()> {
        let format = f.depth_mode.internal_format();
        let key = (f.size, ao_size, format);
        let mut slot = self.targets.borrow_mut();
        if slot.as_ref().map(|t| t.key) != Some(key) {
            *slot = None;
            let (w, h) = f.size;
            let label = format!("FBO({} depth)", self.name);
            let depth = Rc::new(Texture::new(
                f.gl,
                TextureDesc::target(&label, w, h, format).compare(false),
            )?);
            let label = format!("FBO({} linear depth)", self.name);
            *slot = Some(LayerTargets {
                depth: FramebufferObject::new(f.gl, None, Some(depth), 0, 0)?,
                linear: ao_size_target(f.gl, &label, ao_size, glow::R32F)?,
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
        Ok(())
    }

    /// After the draw: the linear depth at the AO size, behind the texels the front restore keeps
    /// (`front_depth`: the main depth buffer), through `restore` (`ao/restore_back_depth.frag`).
    pub fn finish(
        &self,
        f: &Frame,
        restore: &LayerRestore,
        front_depth: &Texture,
    ) -> Result<Rc<Texture>> {
        f.apply(PassState::FULLSCREEN);
        let slot = self.targets.borrow();
        let t = slot
            .as_ref()
            .ok_or_else(|| anyhow!("{} pass finished before it began", self.name))?;
        let depth = t
            .depth
            .depth_texture()
            .ok_or_else(|| anyhow!("the {} FBO has no depth texture", self.name))?;
        let program = restore.for_target(f, &t.linear);
        restore_at_ao_size(f, program, &t.linear, depth, front_depth)
    }

    /// The main-size depth buffer the last frame drew (window depth).
    pub fn depth_texture(&self) -> Option<Rc<Texture>> {
        let slot = self.targets.borrow();
        slot.as_ref().and_then(|t| t.depth.depth_texture().cloned())
    }

    /// The linear depth at the AO size of the last frame that ran the pass.
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
