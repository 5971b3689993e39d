//! `vbao`'s slab hierarchy (`settings::SlabHierarchy`): an RGBA32F mip chain at the AO size
//! holding, per texel, the nearest slab under it (front and back, linear metres) and the level-0
//! texel it comes from, so that `vbao` puts it on its own camera ray. Built by
//! `ao/slab_hierarchy.frag` before `vbao`'s pass when the settings ask for it. A far tap reads the
//! level whose texels are about half as wide as the gap to the previous tap, so a thin board
//! between two taps still occludes (Greene, Kass and Miller, "Hierarchical Z-buffer visibility", 1993, for
//! depth pyramids).

use super::method_pass::AoInputs;
use crate::gl::texture::max_levels;
use crate::gl::{
    FramebufferObject, Gl, PassState, ProgramError, ProgramObject, Texture, TextureDesc,
};
use crate::res::ResDirs;
use crate::shader_interface::{binding, loc};
use anyhow::Result;
use std::cell::RefCell;
use std::rc::Rc;

pub const SHADER: &str = "ao/slab_hierarchy.frag";

/// Levels for an AO buffer of `w`×`h`: the coarsest texel is as wide as the largest screen radius
/// (`max_radius_pixels`, a quarter of the larger side), since no gap between taps is wider; so two
/// levels fewer than a full chain.
pub fn levels_for(w: u32, h: u32) -> u32 {
    max_levels(w, h).saturating_sub(2).max(1)
}

struct Targets {
    tex: Rc<Texture>,
    /// One per level.
    fbos: Vec<FramebufferObject>,
}

/// The build program and the hierarchy's texture (created on first use, at the AO size).
pub struct SlabLevels {
    pub program: ProgramObject,
    targets: RefCell<Option<Targets>>,
}

impl SlabLevels {
    pub fn new(
        gl: &Gl,
        res: &ResDirs,
        defines: &[(&str, String)],
    ) -> Result<SlabLevels, ProgramError> {
        Ok(SlabLevels {
            program: ProgramObject::from_res(gl, res, "simple.vert", SHADER, defines)?,
            targets: RefCell::new(None),
        })
    }

    /// The hierarchy of the last build.
    pub fn texture(&self) -> Option<Rc<Texture>> {
        self.targets.borrow().as_ref().map(|t| t.tex.clone())
    }

    pub fn release(&mut self) {
        *self.targets.get_mut() = None;
    }

    /// Builds every level from the frame's linear depth (and back faces when it has them).
    pub fn build(&self, inputs: &AoInputs) -> Result<Rc<Texture>> {
        let gl = inputs.gl;
        let (w, h) = inputs.targets.size();
        let stale = self
            .targets
            .borrow()
            .as_ref()
            .is_none_or(|t| (t.tex.width(), t.tex.height()) != (w, h));
        if stale {
            *self.targets.borrow_mut() = None;
            // Nearest filtering: the shaders read it with texelFetch only.
            let tex = Rc::new(Texture::new(
                gl,
                TextureDesc::target("FBO(vbao slabs)", w, h, glow::RGBA32F)
                    .levels(levels_for(w, h))
                    .filter(glow::NEAREST_MIPMAP_NEAREST, glow::NEAREST),
            )?);
            let fbos = (0..tex.levels())
                .map(|level| FramebufferObject::new(gl, Some(tex.clone()), None, level, 0))
                .collect::<Result<Vec<_>>>()?;
            *self.targets.borrow_mut() = Some(Targets { tex, fbos });
        }
        let targets = self.targets.borrow();
        let t = targets.as_ref().expect("created above");
        let p = &self.program;
        let s = inputs.settings;
        PassState::FULLSCREEN.apply(gl, None);
        p.use_program();
        p.set_f32(loc::AO_THICKNESS, s.thickness_metres());
        p.set_i32(loc::AO_BACK_FACES, inputs.back_depth.is_some() as i32);
        inputs.targets.tex_depth.bind(binding::INPUT);
        if let Some(back) = inputs.back_depth {
            back.bind(binding::SECOND_INPUT);
        }
        for (level, fbo) in t.fbos.iter().enumerate() {
            // Level 0 comes from the depths (the hierarchy is not bound while its level 0 is
            // written); each other from the one before, the only level the pass may sample (no
            // feedback loop with the level it writes).
            let read = level as i32 - 1;
            if read < 0 {
                inputs.targets.tex_depth.bind(binding::THIRD_INPUT);
            } else {
                t.tex.set_level_range(0, read as u32);
                t.tex.bind(binding::THIRD_INPUT);
            }
            p.set_i32(loc::SAO_MIP_LEVEL, read);
            fbo.bind();
            inputs.meshes.draw_plane_xy();
        }
        t.tex.set_level_range(0, t.tex.levels() - 1);
        crate::gl::check_error(gl, "building vbao's slab hierarchy")?;
        Ok(t.tex.clone())
    }
}
