//! The lesson's AO passes as the engine holds them: programs compiled when the engine starts (a shader
//! error shows at once), targets created on the first frame that needs AO. An engine that never runs
//! AO (AO off, composite view) owns no AO texture.

use crate::ao::{sao_lesson, SaoLesson, SaoPrograms};
use crate::gl::Gl;
use anyhow::{anyhow, Result};
use std::cell::{Cell, OnceCell, RefCell};
use std::ops::Deref;

pub struct LazySaoLesson {
    gl: Gl,
    /// The programs while no target exists.
    waiting: RefCell<Option<SaoPrograms>>,
    /// Programs and targets once AO ran. A `OnceCell` so that `Engine::render(&self)` can create it
    /// (the window toggles AO on and renders without a `&mut` call in between).
    live: OnceCell<SaoLesson>,
    /// Main image size and linear-depth level count the targets are (or will be) created with.
    size: Cell<(u32, u32)>,
    depth_levels: Cell<u32>,
}

impl LazySaoLesson {
    pub fn new(gl: &Gl, programs: SaoPrograms, size: (u32, u32), depth_levels: u32) -> Self {
        LazySaoLesson {
            gl: gl.clone(),
            waiting: RefCell::new(Some(programs)),
            live: OnceCell::new(),
            size: Cell::new(size),
            depth_levels: Cell::new(depth_levels),
        }
    }

    /// The passes with their targets, if they exist.
    pub fn get(&self) -> Option<&SaoLesson> {
        self.live.get()
    }

    /// The passes, creating the targets on first use.
    pub fn get_or_create(&self) -> Result<&SaoLesson> {
        if let Some(l) = self.live.get() {
            return Ok(l);
        }
        let (w, h) = self.size.get();
        let targets = sao_lesson::create_targets(&self.gl, w, h, self.depth_levels.get())?;
        let programs = self
            .waiting
            .borrow_mut()
            .take()
            .ok_or_else(|| anyhow!("AO programs are missing"))?;
        Ok(self
            .live
            .get_or_init(|| SaoLesson::from_parts(&self.gl, programs, targets)))
    }

    /// Sets the size and level count; existing targets are re-created when either changed.
    pub fn configure(&mut self, size: (u32, u32), depth_levels: u32) -> Result<()> {
        let changed = size != self.size.get() || depth_levels != self.depth_levels.get();
        self.size.set(size);
        self.depth_levels.set(depth_levels);
        if let (true, Some(l)) = (changed, self.live.get_mut()) {
            l.resize_with_levels(size.0, size.1, depth_levels)?;
        }
        Ok(())
    }

    /// Level count the linear-depth chain has (or will have when created).
    pub fn depth_levels(&self) -> u32 {
        match self.live.get() {
            Some(l) => l.tex_depth.levels(),
            None => self.depth_levels.get(),
        }
    }

    /// Deletes the targets, keeping the programs.
    pub fn release_targets(&mut self) {
        if let Some(l) = self.live.take() {
            *self.waiting.get_mut() = Some(l.into_programs());
        }
    }

    /// Runs `f` on the programs wherever they are now.
    pub fn with_programs<T>(&mut self, f: impl FnOnce(&mut dyn ProgramsMut) -> T) -> Option<T> {
        if let Some(l) = self.live.get_mut() {
            return Some(f(l));
        }
        self.waiting
            .get_mut()
            .as_mut()
            .map(|p| f(p as &mut dyn ProgramsMut))
    }
}

/// What the engine does to the AO programs whether or not targets exist.
pub trait ProgramsMut {
    fn reload(&mut self, force: bool) -> Vec<crate::gl::ProgramError>;
    fn update_defines(
        &mut self,
        camera: &crate::engine::Camera,
        params: &crate::ao::SaoParams,
    ) -> Result<(), crate::gl::ProgramError>;
}

impl ProgramsMut for SaoLesson {
    fn reload(&mut self, force: bool) -> Vec<crate::gl::ProgramError> {
        SaoLesson::reload(self, force)
    }
    fn update_defines(
        &mut self,
        camera: &crate::engine::Camera,
        params: &crate::ao::SaoParams,
    ) -> Result<(), crate::gl::ProgramError> {
        SaoLesson::update_defines(self, camera, params)
    }
}

impl ProgramsMut for SaoPrograms {
    fn reload(&mut self, force: bool) -> Vec<crate::gl::ProgramError> {
        SaoPrograms::reload(self, force)
    }
    fn update_defines(
        &mut self,
        camera: &crate::engine::Camera,
        params: &crate::ao::SaoParams,
    ) -> Result<(), crate::gl::ProgramError> {
        SaoPrograms::update_defines(self, camera, params)
    }
}

/// `engine.ao.tex_depth`, `engine.ao.sao_texture()`… as before the targets became lazy: reading the
/// passes creates their targets. Creation fails only when GL cannot allocate the half-size textures.
impl Deref for LazySaoLesson {
    type Target = SaoLesson;
    fn deref(&self) -> &SaoLesson {
        match self.get_or_create() {
            Ok(l) => l,
            Err(e) => panic!("cannot create the AO targets: {e:#}"),
        }
    }
}
