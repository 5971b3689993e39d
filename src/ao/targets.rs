//! The AO-size render targets every AO method shares (half the main size as in the course, or full
//! or quarter: `AoResolution`): the linear-depth mip chain (`texSAODepth`),
//! the occlusion target (`texSAO`) and the blurred one (`texSAOBlur`); created lazily so that an engine
//! that never runs AO owns no AO texture.

use super::settings::AoResolution;
use crate::gl::{FramebufferObject, Gl, Texture, TextureDesc};
use anyhow::Result;
use std::cell::{Cell, OnceCell};
use std::rc::Rc;

/// Levels of the lesson's linear-depth chain (`fboSAODepth[4]` in the course: a count, not a max
/// index). The engine's `sao` reads more (`method::sao::depth_levels`).
pub const SAO_DEPTH_LEVELS: u32 = 4;

/// Half of the main size, never 0: AO runs at half resolution as in the course.
pub fn half_size(width: u32, height: u32) -> (u32, u32) {
    ((width / 2).max(1), (height / 2).max(1))
}

/// Size of the AO buffers for a `width`×`height` main image at `resolution`, never 0.
pub fn ao_size(width: u32, height: u32, resolution: AoResolution) -> (u32, u32) {
    let d = resolution.divisor();
    ((width / d).max(1), (height / d).max(1))
}

/// The AO-size targets (half size as in the lesson; full or quarter for `--ao-resolution`).
pub struct AoTargets {
    /// `texSAODepth`: R32F linear depth in metres at the AO size, one level per `fbo_depth` entry.
    pub tex_depth: Rc<Texture>,
    pub fbo_depth: Vec<FramebufferObject>,
    /// `texSAO`: occlusion (R8; the grader swaps in R32F to read exact values).
    pub fbo_sao: FramebufferObject,
    /// `texSAOBlur`: blurred occlusion, linearly filtered for the composite's up-sampling.
    pub fbo_blur: FramebufferObject,
}

impl AoTargets {
    /// Creates the half-size targets for a `width`×`height` main image.
    pub fn new(gl: &Gl, width: u32, height: u32, depth_levels: u32) -> Result<AoTargets> {
        AoTargets::at_resolution(gl, width, height, depth_levels, AoResolution::Half)
    }

    /// Creates the targets for a `width`×`height` main image at `resolution`.
    pub fn at_resolution(
        gl: &Gl,
        width: u32,
        height: u32,
        depth_levels: u32,
        resolution: AoResolution,
    ) -> Result<AoTargets> {
        let (hw, hh) = ao_size(width, height, resolution);
        // A mipmap filter: with the course's GL_LINEAR, textureLod(…, level) reads level 0 for every level.
        let tex_depth = Rc::new(Texture::new(
            gl,
            TextureDesc::target("FBO(sao depth)", hw, hh, glow::R32F)
                .levels(depth_levels)
                .filter(glow::NEAREST_MIPMAP_NEAREST, glow::NEAREST),
        )?);
        let fbo_depth = (0..tex_depth.levels())
            .map(|level| FramebufferObject::new(gl, Some(tex_depth.clone()), None, level, 0))
            .collect::<Result<Vec<_>>>()?;
        let tex_sao = Rc::new(Texture::new(
            gl,
            TextureDesc::target("FBO(sao)", hw, hh, glow::R8),
        )?);
        let fbo_sao = FramebufferObject::new(gl, Some(tex_sao), None, 0, 0)?;
        // Linear filter: the composite up-samples this half-size texture to the main size.
        let tex_blur = Rc::new(Texture::new(
            gl,
            TextureDesc::target("FBO(sao blur)", hw, hh, glow::R8)
                .filter(glow::LINEAR, glow::LINEAR),
        )?);
        let fbo_blur = FramebufferObject::new(gl, Some(tex_blur), None, 0, 0)?;
        crate::gl::check_error(gl, "creating the AO targets")?;
        Ok(AoTargets {
            tex_depth,
            fbo_depth,
            fbo_sao,
            fbo_blur,
        })
    }

    /// The raw occlusion texture.
    pub fn sao_texture(&self) -> &Rc<Texture> {
        self.fbo_sao
            .color_texture()
            .expect("fbo_sao is created with a colour texture")
    }

    /// The occlusion the composite uses: blurred, or raw when blur is off.
    pub fn result_texture(&self, blurred: bool) -> &Rc<Texture> {
        if blurred {
            self.fbo_blur
                .color_texture()
                .expect("fbo_blur is created with a colour texture")
        } else {
            self.sao_texture()
        }
    }

    /// (width, height) of the AO buffers (the AO size).
    pub fn size(&self) -> (u32, u32) {
        (self.fbo_depth[0].width(), self.fbo_depth[0].height())
    }
}

/// `AoTargets` created on the first frame that needs them. A `OnceCell` so that a frame rendered
/// through `&Engine` can create them (the window toggles AO on and renders without a `&mut` call).
pub struct LazyAoTargets {
    gl: Gl,
    live: OnceCell<AoTargets>,
    /// Main image size and linear-depth level count the targets are (or will be) created with.
    size: Cell<(u32, u32)>,
    depth_levels: Cell<u32>,
    resolution: Cell<AoResolution>,
}

impl LazyAoTargets {
    pub fn new(gl: &Gl, size: (u32, u32), depth_levels: u32) -> LazyAoTargets {
        LazyAoTargets {
            gl: gl.clone(),
            live: OnceCell::new(),
            size: Cell::new(size),
            depth_levels: Cell::new(depth_levels),
            resolution: Cell::new(AoResolution::Half),
        }
    }

    /// The targets, if they exist.
    pub fn get(&self) -> Option<&AoTargets> {
        self.live.get()
    }

    /// The targets, created on first use; an error when GL cannot allocate them.
    pub fn get_or_create(&self) -> Result<&AoTargets> {
        if let Some(t) = self.live.get() {
            return Ok(t);
        }
        let (w, h) = self.size.get();
        let targets = AoTargets::at_resolution(
            &self.gl,
            w,
            h,
            self.depth_levels.get(),
            self.resolution.get(),
        )?;
        Ok(self.live.get_or_init(|| targets))
    }

    /// Sets the main size, level count and resolution; existing targets are re-created when any
    /// changed.
    pub fn configure(
        &mut self,
        size: (u32, u32),
        depth_levels: u32,
        resolution: AoResolution,
    ) -> Result<()> {
        let changed = size != self.size.get()
            || depth_levels != self.depth_levels.get()
            || resolution != self.resolution.get();
        self.size.set(size);
        self.depth_levels.set(depth_levels);
        self.resolution.set(resolution);
        if changed && self.live.get().is_some() {
            self.live = OnceCell::new();
            self.get_or_create()?;
        }
        Ok(())
    }

    /// Level count the linear-depth chain has (or will have when created).
    pub fn depth_levels(&self) -> u32 {
        match self.live.get() {
            Some(t) => t.tex_depth.levels(),
            None => self.depth_levels.get(),
        }
    }

    /// Deletes the targets (re-created on next use).
    pub fn release(&mut self) {
        self.live = OnceCell::new();
    }
}
