//! The lesson's SAO as taught (McGuire et al. 2012, errata fixed): `Res/sao.frag` samples a spiral of
//! `SAO_SAMPLE_COUNT` taps in a disc, reading deeper mip levels for farther taps, then the lesson's
//! 9×9 bilateral blur (`Res/sao_blur.frag`).

use crate::ao::blur::lesson_blur;
use crate::ao::depth_chain::camera_defines;
use crate::ao::method_pass::{AoInputs, AoMethodPass};
use crate::ao::method_row::MethodRow;
use crate::ao::settings::{AoMethod, AoSettings};
use crate::ao::targets::AoTargets;
use crate::gl::{Gl, MeshBuffer, PassState, ProgramError, ProgramObject};
use crate::math::camera::fov_scale;
use crate::math::Camera;
use crate::res::ResDirs;
use crate::shader_interface::{binding, loc, LESSON_SAO_SAMPLERS, LESSON_SAO_UNIFORMS};
use anyhow::Result;

pub const BLUR_SHADER: &str = "sao_blur.frag";

pub const ROW: MethodRow = MethodRow {
    build: |gl, res, camera, settings| {
        Ok(Box::new(SaoLessonMethod::build(gl, res, camera, settings)?))
    },
    uniforms: LESSON_SAO_UNIFORMS,
    samplers: LESSON_SAO_SAMPLERS,
};

/// Camera planes plus the sample count and spiral turns, compile-time constants of `sao.frag`.
pub fn sao_defines(camera: &Camera, settings: &AoSettings) -> Vec<(&'static str, String)> {
    let mut d = camera_defines(camera);
    d.push(("SAO_SAMPLE_COUNT", settings.samples.to_string()));
    d.push(("SAO_SPIRAL_TURNS", settings.spiral_turns.to_string()));
    d
}

/// `sao.frag` → `texSAO` (occlusion).
pub fn compute_sao(
    gl: &Gl,
    program: &ProgramObject,
    targets: &AoTargets,
    meshes: &MeshBuffer,
    camera: &Camera,
    settings: &AoSettings,
) {
    let fov = fov_scale(camera.fov_y_deg);
    let r = settings.radius;
    program.set_vec4(
        loc::SAO_INFO,
        [
            r * r,
            0.5 * r * fov,
            settings.bias,
            settings.intensity / r.powi(6),
        ],
    );
    // The aspect ratio of the buffer actually sampled (the course used a fixed 1920×1080).
    let (w, h) = targets.size();
    program.set_vec2(loc::NDC_TO_VIEW, [w as f32 / h as f32 / fov, 1.0 / fov]);
    PassState::FULLSCREEN.apply(gl, None);
    program.use_program();
    targets.fbo_sao.bind();
    targets.tex_depth.bind(binding::INPUT);
    meshes.draw_plane_xy();
}

/// The lesson's SAO and blur programs.
pub struct SaoLessonMethod {
    pub sao: ProgramObject,
    pub blur: ProgramObject,
}

impl SaoLessonMethod {
    pub fn build(
        gl: &Gl,
        res: &ResDirs,
        camera: &Camera,
        settings: &AoSettings,
    ) -> Result<SaoLessonMethod, ProgramError> {
        Ok(SaoLessonMethod {
            sao: ProgramObject::from_res(
                gl,
                res,
                "simple.vert",
                AoMethod::SaoLesson.info().shader,
                &sao_defines(camera, settings),
            )?,
            blur: ProgramObject::from_res(
                gl,
                res,
                "simple.vert",
                BLUR_SHADER,
                &camera_defines(camera),
            )?,
        })
    }
}

impl AoMethodPass for SaoLessonMethod {
    fn method(&self) -> AoMethod {
        AoMethod::SaoLesson
    }
    fn programs_mut(&mut self) -> Vec<&mut ProgramObject> {
        vec![&mut self.sao, &mut self.blur]
    }
    fn update_defines(
        &mut self,
        camera: &Camera,
        settings: &AoSettings,
    ) -> Result<(), ProgramError> {
        self.sao.set_defines(&sao_defines(camera, settings))?;
        self.blur.set_defines(&camera_defines(camera))
    }
    fn compute(&self, i: &AoInputs) -> Result<()> {
        compute_sao(i.gl, &self.sao, i.targets, i.meshes, i.camera, i.settings);
        Ok(())
    }
    fn blur(&self, i: &AoInputs) -> Result<()> {
        lesson_blur(i.gl, &self.blur, i.targets, i.meshes);
        Ok(())
    }
}
