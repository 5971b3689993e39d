//! The AO passes as the engine runs them: the shared depth chain, the selected method (built on
//! first use), its blur, and the composite programs; targets created on the first frame that needs
//! AO. The engine decides the pass order; this type owns what the passes need.

use super::depth_chain::DepthChain;
use super::method::rtao::RtaoMethod;
use super::method::vbao::VbaoMethod;
use super::method_pass::{AoInputs, AoMethodPass};
use super::settings::AoResolution;
use super::settings::{AoMethod, AoSettings};
use super::targets::{ao_size, AoTargets, LazyAoTargets};
use super::upsample::BilateralUpsample;
use crate::gl::{Gl, ProgramError, ProgramObject, Texture};
use crate::math::{Camera, DepthMode};
use crate::res::ResDirs;
use anyhow::{anyhow, Result};
use std::any::Any;
use std::collections::HashMap;
use std::rc::Rc;

pub struct AoPipeline {
    gl: Gl,
    res: ResDirs,
    pub targets: LazyAoTargets,
    pub depth_chain: DepthChain,
    methods: HashMap<AoMethod, Box<dyn AoMethodPass>>,
    /// The recommendation of the method file running in `user_method::HOST`'s place, if one does.
    user_recommended: Option<crate::scene::ao_defaults::Recommended>,
    /// `simple.frag` (the lesson's composite) and `ao/composite_tint.frag`.
    pub composite_simple: ProgramObject,
    pub composite_tint: ProgramObject,
    /// AO of the engine's methods at the AO size → main size, depth-aware.
    pub upsample: BilateralUpsample,
}

impl AoPipeline {
    /// Compiles the depth chain, the lesson's method, the selected one, the blur and the composite
    /// (a shader error shows at once); targets wait for the first frame with AO.
    pub fn new(
        gl: &Gl,
        res: &ResDirs,
        camera: &Camera,
        settings: &AoSettings,
        size: (u32, u32),
        depth_levels: u32,
    ) -> Result<AoPipeline> {
        let fullscreen = |frag: &str, d: &[(&str, String)]| {
            ProgramObject::from_res(gl, res, "simple.vert", frag, d)
        };
        let mut p = AoPipeline {
            gl: gl.clone(),
            res: res.clone(),
            targets: LazyAoTargets::new(gl, size, depth_levels),
            depth_chain: DepthChain::new(gl, res, camera)?,
            methods: HashMap::new(),
            user_recommended: None,
            composite_simple: fullscreen("simple.frag", &[])?,
            composite_tint: fullscreen("ao/composite_tint.frag", &[])?,
            upsample: BilateralUpsample::new(
                fullscreen(super::upsample::SHADER, &[])?,
                fullscreen(super::upsample::COMPOSITE_SHADER, &[])?,
                fullscreen(
                    super::upsample::COMPOSITE_SHADER,
                    &[(super::upsample::POWER_ONE_DEFINE, "1".into())],
                )?,
            ),
        };
        p.prepare(AoMethod::SaoLesson, camera, settings)?;
        p.prepare(settings.method, camera, settings)?;
        Ok(p)
    }

    /// Builds `method`'s programs if needed (errors name the file and line).
    pub fn prepare(
        &mut self,
        method: AoMethod,
        camera: &Camera,
        settings: &AoSettings,
    ) -> Result<(), ProgramError> {
        if !self.methods.contains_key(&method) {
            let m = super::method::build(method, &self.gl, &self.res, camera, settings)?;
            self.methods.insert(method, m);
        }
        Ok(())
    }

    /// Builds what the depth convention and the AO resolution need (the reversed-Z and full-size
    /// restores).
    pub fn prepare_depth_mode(
        &mut self,
        mode: DepthMode,
        resolution: AoResolution,
        camera: &Camera,
    ) -> Result<(), ProgramError> {
        self.depth_chain.prepare(&self.gl, mode, resolution, camera)
    }

    /// Runs a method file's method in the place of `user::HOST` from now on (`None`: the engine's
    /// own method again, rebuilt on the next `prepare`).
    pub fn set_user_method(&mut self, method: Option<super::user_method::UserMethod>) {
        let host = super::user_method::HOST;
        self.user_recommended = method.as_ref().map(|m| m.file().recommended);
        match method {
            Some(m) => self.methods.insert(host, Box::new(m)),
            None => self.methods.remove(&host),
        };
    }

    /// What `method` recommends for the keys a scene leaves unwritten: a method file's own where
    /// one runs in its place, else the engine method's.
    pub fn recommended(&self, method: AoMethod) -> crate::scene::ao_defaults::Recommended {
        match self.user_recommended {
            Some(r) if method == super::user_method::HOST => r,
            _ => crate::scene::ao_defaults::recommended(method),
        }
    }

    /// The names of a method file's pass and blur where one runs in `method`'s place.
    pub fn own_labels(&self, method: AoMethod) -> Option<(&'static str, &'static str)> {
        self.methods.get(&method).and_then(|m| m.own_labels())
    }

    /// The method's passes; an error when `prepare` was not called for it.
    pub fn method(&self, method: AoMethod) -> Result<&dyn AoMethodPass> {
        self.methods
            .get(&method)
            .map(|m| m.as_ref())
            .ok_or_else(|| anyhow!("AO method {} was not prepared", method.name()))
    }

    /// Level count of the linear-depth chain `method` reads for a main image of `size` with AO at
    /// `resolution`.
    pub fn wanted_depth_levels(
        &self,
        method: AoMethod,
        (w, h): (u32, u32),
        resolution: AoResolution,
    ) -> u32 {
        let buffer = ao_size(w, h, resolution);
        match self.methods.get(&method) {
            Some(m) => m.depth_levels(buffer),
            None => super::targets::SAO_DEPTH_LEVELS,
        }
    }

    /// The targets, created on first use.
    pub fn targets(&self) -> Result<&AoTargets> {
        self.targets.get_or_create()
    }

    /// Drops every size-dependent texture (re-created at the right size on next use).
    pub fn release_targets(&mut self) {
        self.targets.release();
        self.upsample.release_targets();
        for m in self.methods.values_mut() {
            m.release_targets();
        }
    }

    /// Every AO texture that exists now.
    pub fn textures(&self) -> Vec<Rc<Texture>> {
        let mut out = Vec::new();
        if let Some(t) = self.targets.get() {
            out.push(t.tex_depth.clone());
            out.push(t.sao_texture().clone());
            out.push(t.result_texture(true).clone());
        }
        out.extend(self.upsample.textures());
        for m in self.methods.values() {
            out.extend(m.textures());
        }
        out
    }

    fn programs_mut(&mut self) -> Vec<&mut ProgramObject> {
        let mut v = self.depth_chain.programs_mut();
        v.push(&mut self.composite_simple);
        v.push(&mut self.composite_tint);
        v.push(&mut self.upsample.program);
        v.push(&mut self.upsample.composite_program);
        v.push(&mut self.upsample.composite_power_one);
        for m in self.methods.values_mut() {
            v.extend(m.programs_mut());
        }
        v
    }

    /// Rebuilds programs whose files changed (all when `force`); the last working ones stay.
    pub fn reload(&mut self, force: bool) -> Vec<ProgramError> {
        let mut errors = Vec::new();
        for p in self.programs_mut() {
            if force || p.sources_changed() {
                if let Err(e) = p.reload() {
                    errors.push(e);
                }
            }
        }
        errors
    }

    /// Makes the compile-time camera planes and sample counts follow `camera` and `settings`.
    pub fn update_defines(
        &mut self,
        camera: &Camera,
        settings: &AoSettings,
    ) -> Result<(), ProgramError> {
        self.depth_chain.update_camera(camera)?;
        for m in self.methods.values_mut() {
            m.update_defines(camera, settings)?;
        }
        Ok(())
    }

    /// Runs the method's occlusion pass.
    pub fn compute(&self, method: AoMethod, inputs: &AoInputs) -> Result<()> {
        self.method(method)?.compute(inputs)
    }

    /// `method`'s passes as their own type `T`, when it is prepared and is one.
    pub fn pass_of<T: AoMethodPass>(&self, method: AoMethod) -> Option<&T> {
        let pass: &dyn Any = self.methods.get(&method)?.as_ref();
        pass.downcast_ref::<T>()
    }

    /// `pass_of`, to change it (a method file's parameters).
    pub fn pass_of_mut<T: AoMethodPass>(&mut self, method: AoMethod) -> Option<&mut T> {
        let pass: &mut dyn Any = self.methods.get_mut(&method)?.as_mut();
        pass.downcast_mut::<T>()
    }

    /// The BVH `method` traces, once built (`rtao`), with its build time and size.
    pub fn bvh_stats(&self, method: AoMethod) -> Option<crate::scene::bvh::BvhStats> {
        self.pass_of::<RtaoMethod>(method)?.bvh_stats()
    }

    /// Frames averaged into `method`'s last output (1 without accumulation).
    pub fn accumulated_frames(&self, method: AoMethod) -> u32 {
        self.pass_of::<RtaoMethod>(method)
            .map_or(1, |m| m.accumulated_frames())
    }

    /// Whether `method`'s last frame started its mean again (`RtaoMethod::restarted`; false for the
    /// methods without one).
    pub fn rtao_restarted(&self, method: AoMethod) -> bool {
        self.pass_of::<RtaoMethod>(method)
            .is_some_and(|m| m.restarted())
    }

    /// Pixels of `method`'s last pass whose rays were cut short (`RtaoMethod::cut_pixels`).
    pub fn cut_pixels(&self, method: AoMethod) -> u32 {
        self.pass_of::<RtaoMethod>(method)
            .map_or(0, |m| m.cut_pixels())
    }

    /// Starts every method's running mean again at its next frame.
    pub fn restart_accumulation(&self) {
        for &method in self.methods.keys() {
            if let Some(m) = self.pass_of::<RtaoMethod>(method) {
                m.restart_accumulation();
            }
        }
    }

    /// The slab hierarchy from the last frame that built one (a method that reads it, `vbao`).
    pub fn slab_hierarchy(&self) -> Option<Rc<Texture>> {
        self.methods
            .keys()
            .find_map(|&m| self.pass_of::<VbaoMethod>(m)?.slab_hierarchy())
    }

    /// Runs the method's blur.
    pub fn blur(&self, method: AoMethod, inputs: &AoInputs) -> Result<()> {
        self.method(method)?.blur(inputs)
    }
}
