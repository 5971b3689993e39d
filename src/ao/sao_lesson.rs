//! The AO lesson's pipeline (`Engine::DrawAmbientOcclusion` in the course), errata fixed:
//! restore linear depth at half size → 4-level min mip chain → SAO into R8 → 9×9 bilateral blur →
//! blend over the main image with the swizzled R8 texture.
//!
//! Shaders: `Res/sao_restore_depth.frag`, `Res/sao_down_sampling.frag`, `Res/sao.frag`,
//! `Res/sao_blur.frag`, composited with `Res/simple.frag`.

use crate::config::{self, loc, SAO_DEPTH_LEVELS};
use crate::engine::Camera;
use crate::gl::{
    FramebufferObject, Gl, MeshBuffer, ProgramError, ProgramObject, Texture, TextureDesc,
};
use crate::res::ResDirs;
use anyhow::Result;
use glow::HasContext;
use serde::{Deserialize, Serialize};
use std::rc::Rc;

/// The lesson's SAO parameters (the course hard-codes radius 1 m, bias 0.012, intensity 5).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct SaoParams {
    pub enabled: bool,
    /// Which AO method computes the occlusion (`sao-lesson` = the lesson's shaders).
    pub method: crate::ao::AoMethod,
    /// World-space sampling radius (m).
    pub radius: f32,
    /// Distance (m) along the normal below which a sample does not occlude (removes self-occlusion).
    pub bias: f32,
    pub intensity: f32,
    pub samples: u32,
    pub spiral_turns: u32,
    pub blur: bool,
    /// How occlusion reaches the picture.
    pub composite: CompositeMode,
    /// Colour that occluded areas blend toward (`tinted`; black = the lesson's darkening).
    pub tint: [f32; 3],
    /// Visibility is raised to this power before compositing (1 = as computed).
    pub power: f32,
    /// GTAO preset (slices × steps); when set it decides GTAO's sample counts instead of `samples`.
    pub quality: Option<crate::ao::methods::GtaoQuality>,
}

/// How occlusion is applied to the image.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default, Serialize, Deserialize, clap::ValueEnum)]
#[serde(rename_all = "kebab-case")]
pub enum CompositeMode {
    /// The lesson's blend over the whole lit colour (SRC_ALPHA, ONE_MINUS_SRC_ALPHA).
    #[default]
    Blend,
    /// Blend toward `tint` with visibility^`power` (seeds 000 and 003).
    Tinted,
    /// A depth pre-pass, AO, then lighting with AO applied to the ambient term only.
    AmbientOnly,
}

impl Default for SaoParams {
    fn default() -> Self {
        SaoParams {
            enabled: true,
            method: crate::ao::AoMethod::SaoLesson,
            radius: 1.0,
            bias: 0.012,
            intensity: 5.0,
            samples: 11,
            spiral_turns: 3,
            blur: true,
            composite: CompositeMode::Blend,
            tint: [0.0; 3],
            power: 1.0,
            quality: None,
        }
    }
}

impl SaoParams {
    /// Clamps absurd values into a range the shaders handle, and says what was changed.
    pub fn sanitized(mut self) -> (SaoParams, Vec<String>) {
        let mut notes = Vec::new();
        let mut fix = |name: &str, v: &mut f32, lo: f32, hi: f32| {
            let old = *v;
            *v = if v.is_finite() {
                v.clamp(lo, hi)
            } else {
                lo.max(hi.min(1.0))
            };
            if *v != old {
                notes.push(format!("AO {name} {old} is out of range, using {}", *v));
            }
        };
        fix("radius", &mut self.radius, 1e-3, 100.0);
        fix("bias", &mut self.bias, 0.0, 10.0);
        fix("intensity", &mut self.intensity, 0.0, 1000.0);
        fix("power", &mut self.power, 0.05, 20.0);
        for c in &mut self.tint {
            *c = if c.is_finite() {
                c.clamp(0.0, 1.0)
            } else {
                0.0
            };
        }
        if !(1..=256).contains(&self.samples) {
            notes.push(format!(
                "AO samples {} is out of range, using {}",
                self.samples,
                self.samples.clamp(1, 256)
            ));
            self.samples = self.samples.clamp(1, 256);
        }
        if !(1..=64).contains(&self.spiral_turns) {
            self.spiral_turns = self.spiral_turns.clamp(1, 64);
        }
        (self, notes)
    }
}

pub struct SaoLesson {
    gl: Gl,
    pub prog_restore_depth: ProgramObject,
    pub prog_down_sampling: ProgramObject,
    pub prog_sao: ProgramObject,
    pub prog_blur: ProgramObject,
    pub prog_simple: ProgramObject,
    /// `texSAODepth`: R32F linear depth, half size, `SAO_DEPTH_LEVELS` levels.
    pub tex_depth: Rc<Texture>,
    pub fbo_depth: Vec<FramebufferObject>,
    pub fbo_sao: FramebufferObject,
    pub fbo_blur: FramebufferObject,
}

/// Camera planes into restore, down-sampling and blur, and sampling constants into SAO (all
/// compile-time constants of the lesson's shaders).
fn set_lesson_defines(
    [restore, down_sampling, blur, sao]: [&mut ProgramObject; 4],
    camera: &Camera,
    params: &SaoParams,
) -> Result<(), ProgramError> {
    let planes = camera_defines(camera);
    restore.set_defines(&planes)?;
    down_sampling.set_defines(&planes)?;
    blur.set_defines(&planes)?;
    sao.set_defines(&sao_defines(camera, params))
}

/// Half of the main size, never 0.
pub fn half_size(width: u32, height: u32) -> (u32, u32) {
    ((width / 2).max(1), (height / 2).max(1))
}

/// The lesson's five programs without their targets: the engine compiles them when it starts (so a
/// shader error shows at once) but creates the targets only when AO first runs.
pub struct SaoPrograms {
    pub restore_depth: ProgramObject,
    pub down_sampling: ProgramObject,
    pub sao: ProgramObject,
    pub blur: ProgramObject,
    pub simple: ProgramObject,
}

impl SaoPrograms {
    pub fn new(gl: &Gl, res: &ResDirs, camera: &Camera, params: &SaoParams) -> Result<SaoPrograms> {
        let planes = camera_defines(camera);
        let p = |frag: &str, defines: &[(&'static str, String)]| {
            ProgramObject::from_res(gl, res, "simple.vert", frag, defines)
        };
        Ok(SaoPrograms {
            restore_depth: p("sao_restore_depth.frag", &planes)?,
            down_sampling: p("sao_down_sampling.frag", &planes)?,
            sao: p("sao.frag", &sao_defines(camera, params))?,
            blur: p("sao_blur.frag", &planes)?,
            simple: p("simple.frag", &[])?,
        })
    }

    fn all_mut(&mut self) -> [&mut ProgramObject; 5] {
        [
            &mut self.restore_depth,
            &mut self.down_sampling,
            &mut self.sao,
            &mut self.blur,
            &mut self.simple,
        ]
    }

    pub fn reload(&mut self, force: bool) -> Vec<ProgramError> {
        reload_programs(self.all_mut(), force)
    }

    pub fn update_defines(
        &mut self,
        camera: &Camera,
        params: &SaoParams,
    ) -> Result<(), ProgramError> {
        set_lesson_defines(
            [
                &mut self.restore_depth,
                &mut self.down_sampling,
                &mut self.blur,
                &mut self.sao,
            ],
            camera,
            params,
        )
    }
}

fn reload_programs(programs: [&mut ProgramObject; 5], force: bool) -> Vec<ProgramError> {
    let mut errors = Vec::new();
    for p in programs {
        if force || p.sources_changed() {
            if let Err(e) = p.reload() {
                errors.push(e);
            }
        }
    }
    errors
}

impl SaoLesson {
    /// The lesson's passes with their targets for a `width`×`height` main image (4 depth levels).
    pub fn new(
        gl: &Gl,
        res: &ResDirs,
        width: u32,
        height: u32,
        camera: &Camera,
        params: &SaoParams,
    ) -> Result<SaoLesson, anyhow::Error> {
        let programs = SaoPrograms::new(gl, res, camera, params)?;
        let targets = create_targets(gl, width, height, SAO_DEPTH_LEVELS as u32)?;
        Ok(SaoLesson::from_parts(gl, programs, targets))
    }

    /// Joins compiled programs and created targets.
    pub fn from_parts(gl: &Gl, programs: SaoPrograms, targets: SaoTargets) -> SaoLesson {
        let SaoPrograms {
            restore_depth,
            down_sampling,
            sao,
            blur,
            simple,
        } = programs;
        let (tex_depth, fbo_depth, fbo_sao, fbo_blur) = targets;
        SaoLesson {
            gl: gl.clone(),
            prog_restore_depth: restore_depth,
            prog_down_sampling: down_sampling,
            prog_sao: sao,
            prog_blur: blur,
            prog_simple: simple,
            tex_depth,
            fbo_depth,
            fbo_sao,
            fbo_blur,
        }
    }

    /// Deletes the targets and keeps the programs.
    pub fn into_programs(self) -> SaoPrograms {
        SaoPrograms {
            restore_depth: self.prog_restore_depth,
            down_sampling: self.prog_down_sampling,
            sao: self.prog_sao,
            blur: self.prog_blur,
            simple: self.prog_simple,
        }
    }

    /// Re-creates the half-size targets for a new main size.
    pub fn resize(&mut self, width: u32, height: u32) -> Result<()> {
        self.resize_with_levels(width, height, SAO_DEPTH_LEVELS as u32)
    }

    /// Re-creates the targets with `depth_levels` levels in the linear-depth chain (clamped to what
    /// the half size allows).
    pub fn resize_with_levels(&mut self, width: u32, height: u32, depth_levels: u32) -> Result<()> {
        let (t, d, s, b) = create_targets(&self.gl, width, height, depth_levels)?;
        self.tex_depth = t;
        self.fbo_depth = d;
        self.fbo_sao = s;
        self.fbo_blur = b;
        Ok(())
    }

    /// Rebuilds programs whose files changed (or all when `force`); returns the errors, keeping the
    /// previous programs running.
    pub fn reload(&mut self, force: bool) -> Vec<ProgramError> {
        reload_programs(
            [
                &mut self.prog_restore_depth,
                &mut self.prog_down_sampling,
                &mut self.prog_sao,
                &mut self.prog_blur,
                &mut self.prog_simple,
            ],
            force,
        )
    }

    /// Makes the injected camera planes and sampling constants follow the scene.
    pub fn update_defines(
        &mut self,
        camera: &Camera,
        params: &SaoParams,
    ) -> Result<(), ProgramError> {
        set_lesson_defines(
            [
                &mut self.prog_restore_depth,
                &mut self.prog_down_sampling,
                &mut self.prog_blur,
                &mut self.prog_sao,
            ],
            camera,
            params,
        )
    }

    /// Common state of every full-screen AO pass: no cull, no depth test, no blend.
    fn fullscreen_state(&self) {
        unsafe {
            self.gl.disable(glow::CULL_FACE);
            self.gl.disable(glow::DEPTH_TEST);
            self.gl.depth_mask(false);
            self.gl.disable(glow::BLEND);
            self.gl.disable(glow::SCISSOR_TEST);
        }
    }

    /// main depth → `texSAODepth` level 0 (linear metres, half size, nearest of 2×2).
    pub fn restore_depth(&self, meshes: &MeshBuffer, main_depth: &Texture) {
        self.fullscreen_state();
        self.prog_restore_depth.use_program();
        self.fbo_depth[0].bind();
        main_depth.bind(0);
        meshes.draw_plane_xy();
    }

    /// `restore_depth` with another program of the same interface (the engine's reversed-Z restore).
    pub fn restore_depth_with(
        &self,
        program: &ProgramObject,
        meshes: &MeshBuffer,
        main_depth: &Texture,
    ) {
        self.fullscreen_state();
        program.use_program();
        self.fbo_depth[0].bind();
        main_depth.bind(0);
        meshes.draw_plane_xy();
    }

    /// Levels 1.. of `texSAODepth`, each the min of 2×2 texels of the level above.
    pub fn down_sample(&self, meshes: &MeshBuffer) {
        self.fullscreen_state();
        self.prog_down_sampling.use_program();
        self.tex_depth.bind(0);
        for i in 1..self.fbo_depth.len() {
            // Limit sampling to the levels already written so that the level being written is not
            // also readable (no feedback loop), keeping the lesson's texelFetch(…, mipLevel) valid.
            self.tex_depth.set_level_range(0, i as u32 - 1);
            self.fbo_depth[i].bind();
            self.prog_down_sampling
                .set_i32(loc::SAO_MIP_LEVEL, i as i32 - 1);
            meshes.draw_plane_xy();
        }
        self.tex_depth
            .set_level_range(0, self.tex_depth.levels() - 1);
    }

    /// `sao.frag` → `texSAO` (occlusion, R8).
    pub fn compute_sao(&self, meshes: &MeshBuffer, camera: &Camera, params: &SaoParams) {
        self.fullscreen_state();
        let p = &self.prog_sao;
        let fov_scale = config::fov_scale(camera.fov_y_deg);
        let r = params.radius;
        p.set_vec4(
            loc::SAO_INFO,
            [
                r * r,
                0.5 * r * fov_scale,
                params.bias,
                params.intensity / r.powi(6),
            ],
        );
        // The aspect ratio of the buffer actually sampled (the course used a fixed 1920×1080).
        let (w, h) = (
            self.fbo_depth[0].width() as f32,
            self.fbo_depth[0].height() as f32,
        );
        p.set_vec2(loc::SAO_NDC_TO_VIEW, [w / h / fov_scale, 1.0 / fov_scale]);
        p.use_program();
        self.fbo_sao.bind();
        self.tex_depth.bind(0);
        meshes.draw_plane_xy();
    }

    /// `sao_blur.frag`: `texSAO` → `texSAOBlur`.
    pub fn blur(&self, meshes: &MeshBuffer) {
        self.fullscreen_state();
        self.prog_blur.use_program();
        self.fbo_blur.bind();
        self.sao_texture().bind(0);
        self.tex_depth.bind(1);
        meshes.draw_plane_xy();
    }

    /// The occlusion texture the composite uses: blurred, or raw when blur is off.
    pub fn result_texture(&self, blurred: bool) -> &Rc<Texture> {
        if blurred {
            self.fbo_blur.color_texture().unwrap()
        } else {
            self.sao_texture()
        }
    }
    pub fn sao_texture(&self) -> &Rc<Texture> {
        self.fbo_sao.color_texture().unwrap()
    }

    /// Darkens the main image: colour × (1 − occlusion) by blending a texture whose RGB reads 0 and A
    /// reads the occlusion. Sets its own viewport (the printed listing lost it).
    pub fn composite(&self, meshes: &MeshBuffer, main: &FramebufferObject, blurred: bool) {
        self.fullscreen_state();
        self.composite_inner(meshes, main, blurred);
    }

    fn composite_inner(&self, meshes: &MeshBuffer, main: &FramebufferObject, blurred: bool) {
        let tex = self.result_texture(blurred);
        tex.set_swizzle([glow::ZERO, glow::ZERO, glow::ZERO, glow::RED]);
        unsafe {
            self.gl.enable(glow::BLEND);
            self.gl.blend_equation(glow::FUNC_ADD);
            self.gl
                .blend_func(glow::SRC_ALPHA, glow::ONE_MINUS_SRC_ALPHA);
        }
        self.prog_simple.use_program();
        main.bind();
        tex.bind(0);
        meshes.draw_plane_xy();
        // Other readers (debug views, tests) see plain R again.
        tex.set_swizzle([glow::RED, glow::GREEN, glow::BLUE, glow::ALPHA]);
        unsafe { self.gl.disable(glow::BLEND) };
    }

    /// `composite` limited to pixels where geometry was drawn: the quad sits at the depth buffer's
    /// cleared value (`sky_depth`) and passes the test (`farther_func`, strict) only where something
    /// nearer was written, so sky pixels (nothing to darken) are neither shaded nor blended.
    pub fn composite_geometry_only(
        &self,
        meshes: &MeshBuffer,
        main: &FramebufferObject,
        blurred: bool,
        sky_depth: f32,
        farther_func: u32,
    ) {
        self.fullscreen_state();
        unsafe {
            self.gl.enable(glow::DEPTH_TEST);
            self.gl.depth_func(farther_func);
            self.gl.depth_range_f32(sky_depth, sky_depth);
        }
        self.composite_inner(meshes, main, blurred);
        unsafe {
            self.gl.depth_range_f32(0.0, 1.0);
            self.gl.disable(glow::DEPTH_TEST);
        }
    }

    /// The whole chain: restore → down-sample → SAO → blur (when on).
    pub fn run(
        &self,
        meshes: &MeshBuffer,
        main_depth: &Texture,
        camera: &Camera,
        params: &SaoParams,
    ) {
        self.restore_depth(meshes, main_depth);
        self.down_sample(meshes);
        self.compute_sao(meshes, camera, params);
        if params.blur {
            self.blur(meshes);
        }
    }
}

/// CAMERA_NEAR / CAMERA_FAR as the restore, down-sampling and blur shaders read them.
pub fn camera_defines(camera: &Camera) -> Vec<(&'static str, String)> {
    vec![
        ("CAMERA_NEAR", glsl_float(camera.near)),
        ("CAMERA_FAR", glsl_float(camera.far)),
    ]
}

fn sao_defines(camera: &Camera, params: &SaoParams) -> Vec<(&'static str, String)> {
    let mut d = camera_defines(camera);
    d.push(("SAO_SAMPLE_COUNT", params.samples.to_string()));
    d.push(("SAO_SPIRAL_TURNS", params.spiral_turns.to_string()));
    d
}

/// A float literal GLSL accepts, exact for f32 (Rust's shortest round-trip form plus a '.0' if needed).
pub fn glsl_float(v: f32) -> String {
    let s = format!("{v:?}");
    if s.contains('.') || s.contains('e') || s.contains("inf") || s.contains("NaN") {
        s
    } else {
        format!("{s}.0")
    }
}

/// The lesson's half-size targets: linear-depth chain, one FBO per level, SAO, blurred SAO.
pub type SaoTargets = (
    Rc<Texture>,
    Vec<FramebufferObject>,
    FramebufferObject,
    FramebufferObject,
);

/// Creates the lesson's targets for a `width`×`height` main image.
pub fn create_targets(gl: &Gl, width: u32, height: u32, depth_levels: u32) -> Result<SaoTargets> {
    let (hw, hh) = half_size(width, height);
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
    // Linear filter: the composite upsamples this half-size texture to the main size.
    let tex_blur = Rc::new(Texture::new(
        gl,
        TextureDesc::target("FBO(sao blur)", hw, hh, glow::R8).filter(glow::LINEAR, glow::LINEAR),
    )?);
    let fbo_blur = FramebufferObject::new(gl, Some(tex_blur), None, 0, 0)?;
    let _ = unsafe { gl.get_error() };
    Ok((tex_depth, fbo_depth, fbo_sao, fbo_blur))
}
