//! Bloom: bright pass into half size, a chain of down-samples, then added back up the chain.

use crate::gl::pass_state::Blend;
use crate::gl::{
    FramebufferObject, Gl, MeshBuffer, PassState, ProgramObject, Texture, TextureDesc,
};
use crate::res::ResDirs;
use crate::scene::BloomDesc;
use crate::shader_interface::{binding, loc};
use anyhow::Result;
use std::rc::Rc;

/// Six halvings from half size reach ~15 px at 1920×1080: wide enough for the glow, and the chain
/// stops earlier on small images (`targets` keeps levels of at least 4×4).
pub const BLOOM_LEVELS: usize = 6;

pub struct BloomPass {
    bright: ProgramObject,
    down: ProgramObject,
    up: ProgramObject,
    fbos: Vec<FramebufferObject>,
}

impl BloomPass {
    pub fn new(gl: &Gl, res: &ResDirs, (w, h): (u32, u32)) -> Result<BloomPass> {
        let p = |frag: &str| ProgramObject::from_res(gl, res, "simple.vert", frag, &[]);
        Ok(BloomPass {
            bright: p("bloom_bright.frag")?,
            down: p("bloom_down.frag")?,
            up: p("bloom_up.frag")?,
            fbos: targets(gl, w, h)?,
        })
    }

    pub fn programs_mut(&mut self) -> [&mut ProgramObject; 3] {
        [&mut self.bright, &mut self.down, &mut self.up]
    }

    pub fn resize(&mut self, gl: &Gl, (w, h): (u32, u32)) -> Result<()> {
        self.fbos = targets(gl, w, h)?;
        Ok(())
    }

    /// Whether bloom runs for `desc` (an image too small for one level has none).
    pub fn active(&self, desc: &BloomDesc) -> bool {
        desc.enabled && !self.fbos.is_empty()
    }

    /// The result (level 0), when the chain exists.
    pub fn result(&self) -> Option<&Rc<Texture>> {
        self.fbos.first().and_then(|f| f.color_texture())
    }

    pub fn draw(&self, gl: &Gl, meshes: &MeshBuffer, main_color: &Texture, desc: &BloomDesc) {
        let level = |i: usize| -> &Rc<Texture> {
            self.fbos[i]
                .color_texture()
                .expect("bloom levels have colour textures")
        };
        PassState::FULLSCREEN.apply(gl, None);
        self.bright.set_f32(loc::BLOOM_THRESHOLD, desc.threshold);
        self.bright.use_program();
        self.fbos[0].bind();
        main_color.bind(binding::INPUT);
        meshes.draw_plane_xy();
        self.down.use_program();
        for i in 1..self.fbos.len() {
            self.fbos[i].bind();
            level(i - 1).bind(binding::INPUT);
            meshes.draw_plane_xy();
        }
        PassState::FULLSCREEN.with_blend(Blend::ADD).apply(gl, None);
        self.up.use_program();
        for i in (1..self.fbos.len()).rev() {
            self.fbos[i - 1].bind();
            level(i).bind(binding::INPUT);
            meshes.draw_plane_xy();
        }
        PassState::FULLSCREEN.apply(gl, None);
    }
}

fn targets(gl: &Gl, width: u32, height: u32) -> Result<Vec<FramebufferObject>> {
    let mut out = Vec::new();
    let (mut w, mut h) = (width / 2, height / 2);
    while out.len() < BLOOM_LEVELS && w >= 4 && h >= 4 {
        let tex = Rc::new(Texture::new(
            gl,
            TextureDesc::target(&format!("FBO(bloom {})", out.len()), w, h, glow::RGBA16F)
                .filter(glow::LINEAR, glow::LINEAR),
        )?);
        out.push(FramebufferObject::new(gl, Some(tex), None, 0, 0)?);
        w /= 2;
        h /= 2;
    }
    Ok(out)
}
