//! The lesson's AO chain as one object (`Engine::DrawAmbientOcclusion` in the course, errata fixed):
//! restore linear depth at half size → 4-level min mip chain → SAO → 9×9 bilateral blur → blend over
//! the main image. The grader and the tests drive it pass by pass; the engine runs the same pass
//! functions through `AoPipeline`.
//!
//! Shaders: `Res/sao_restore_depth.frag`, `Res/sao_down_sampling.frag`, `Res/sao.frag`,
//! `Res/sao_blur.frag`, composited with `Res/simple.frag`.

use super::blur::lesson_blur;
use super::composite;
use super::depth_chain::{self, DepthChain};
use super::method::sao_lesson::{compute_sao, SaoLessonMethod};
use super::settings::AoSettings;
use super::targets::{AoTargets, SAO_DEPTH_LEVELS};
use crate::gl::{FramebufferObject, Gl, MeshBuffer, ProgramError, ProgramObject, Texture};
use crate::math::Camera;
use crate::res::ResDirs;
use anyhow::Result;
use std::rc::Rc;

pub struct SaoLesson {
    gl: Gl,
    pub prog_restore_depth: ProgramObject,
    pub prog_down_sampling: ProgramObject,
    pub prog_sao: ProgramObject,
    pub prog_blur: ProgramObject,
    pub prog_simple: ProgramObject,
    pub targets: AoTargets,
}

impl SaoLesson {
    /// The lesson's passes with their targets for a `width`×`height` main image (4 depth levels).
    pub fn new(
        gl: &Gl,
        res: &ResDirs,
        width: u32,
        height: u32,
        camera: &Camera,
        settings: &AoSettings,
    ) -> Result<SaoLesson> {
        let chain = DepthChain::new(gl, res, camera)?;
        let method = SaoLessonMethod::build(gl, res, camera, settings)?;
        Ok(SaoLesson {
            gl: gl.clone(),
            prog_restore_depth: chain.restore,
            prog_down_sampling: chain.down_sampling,
            prog_sao: method.sao,
            prog_blur: method.blur,
            prog_simple: ProgramObject::from_res(gl, res, "simple.vert", "simple.frag", &[])?,
            targets: AoTargets::new(gl, width, height, SAO_DEPTH_LEVELS)?,
        })
    }

    /// Rebuilds programs whose files changed (or all when `force`); returns the errors, keeping the
    /// previous programs running.
    pub fn reload(&mut self, force: bool) -> Vec<ProgramError> {
        let mut errors = Vec::new();
        for p in [
            &mut self.prog_restore_depth,
            &mut self.prog_down_sampling,
            &mut self.prog_sao,
            &mut self.prog_blur,
            &mut self.prog_simple,
        ] {
            if force || p.sources_changed() {
                if let Err(e) = p.reload() {
                    errors.push(e);
                }
            }
        }
        errors
    }

    /// main depth → `texSAODepth` level 0.
    pub fn restore_depth(&self, meshes: &MeshBuffer, main_depth: &Texture) {
        depth_chain::restore(
            &self.gl,
            &self.prog_restore_depth,
            &self.targets.fbo_depth[0],
            meshes,
            main_depth,
        );
    }

    /// Levels 1.. of `texSAODepth`.
    pub fn down_sample(&self, meshes: &MeshBuffer) {
        depth_chain::down_sample(&self.gl, &self.prog_down_sampling, &self.targets, meshes);
    }

    /// `sao.frag` → `texSAO`.
    pub fn compute_sao(&self, meshes: &MeshBuffer, camera: &Camera, settings: &AoSettings) {
        compute_sao(
            &self.gl,
            &self.prog_sao,
            &self.targets,
            meshes,
            camera,
            settings,
        );
    }

    /// `sao_blur.frag`: `texSAO` → `texSAOBlur`.
    pub fn blur(&self, meshes: &MeshBuffer) {
        lesson_blur(&self.gl, &self.prog_blur, &self.targets, meshes);
    }

    /// Darkens `main` by the (blurred) occlusion with the lesson's blend.
    pub fn composite(&self, meshes: &MeshBuffer, main: &FramebufferObject, blurred: bool) {
        composite::blend(
            &self.gl,
            &self.prog_simple,
            self.result_texture(blurred),
            main,
            meshes,
        );
    }

    /// The whole chain: restore → down-sample → SAO → blur (when on).
    pub fn run(
        &self,
        meshes: &MeshBuffer,
        main_depth: &Texture,
        camera: &Camera,
        settings: &AoSettings,
    ) {
        self.restore_depth(meshes, main_depth);
        self.down_sample(meshes);
        self.compute_sao(meshes, camera, settings);
        if settings.blur {
            self.blur(meshes);
        }
    }

    pub fn sao_texture(&self) -> &Rc<Texture> {
        self.targets.sao_texture()
    }
    pub fn result_texture(&self, blurred: bool) -> &Rc<Texture> {
        self.targets.result_texture(blurred)
    }
}
