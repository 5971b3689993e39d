//! The other AO methods of the seeds (and the engine's own SAO, and GTAO), all reading the linear
//! depth mip chain that the lesson's restore and down-sampling passes build, each with its own
//! shader in `Res/ao/`, blurred by a separable bilateral filter and composited like the lesson.

use crate::ao::{SaoLesson, SaoParams};
use crate::config;
use crate::engine::Camera;
use crate::gl::{
    FramebufferObject, Gl, MeshBuffer, ProgramError, ProgramObject, Texture, TextureDesc,
};
use crate::res::ResDirs;
use anyhow::Result;
use serde::{Deserialize, Serialize};
use std::cell::RefCell;
use std::collections::HashMap;
use std::rc::Rc;

/// Names as on the command line (`--method`).
#[derive(
    Clone, Copy, Debug, PartialEq, Eq, Hash, Default, Serialize, Deserialize, clap::ValueEnum,
)]
#[serde(rename_all = "kebab-case")]
pub enum AoMethod {
    /// The lesson's SAO as taught (errata fixed, one 9×9 bilateral blur).
    #[default]
    SaoLesson,
    /// The engine's SAO: round disc in view space, separable blur, small discs and sky skipped.
    Sao,
    /// Sphere sampling with depth comparison (Crytek).
    Crytek,
    /// Normal-oriented hemisphere kernel with range check.
    Hemisphere,
    /// Horizon-based AO (directions × steps).
    Hbao,
    /// UE4-style paired samples.
    AngleBased,
    /// Ground-truth-based AO (analytic cosine-weighted horizon integral).
    Gtao,
}

impl AoMethod {
    pub const ALL: [AoMethod; 7] = [
        AoMethod::SaoLesson,
        AoMethod::Sao,
        AoMethod::Crytek,
        AoMethod::Hemisphere,
        AoMethod::Hbao,
        AoMethod::AngleBased,
        AoMethod::Gtao,
    ];

    pub fn name(self) -> &'static str {
        match self {
            AoMethod::SaoLesson => "sao-lesson",
            AoMethod::Sao => "sao",
            AoMethod::Crytek => "crytek",
            AoMethod::Hemisphere => "hemisphere",
            AoMethod::Hbao => "hbao",
            AoMethod::AngleBased => "angle-based",
            AoMethod::Gtao => "gtao",
        }
    }

    /// The method's fragment shader under `Res/` (the lesson's lives at the top level).
    pub fn shader(self) -> &'static str {
        match self {
            AoMethod::SaoLesson => "sao.frag",
            AoMethod::Sao => "ao/sao.frag",
            AoMethod::Crytek => "ao/crytek.frag",
            AoMethod::Hemisphere => "ao/hemisphere.frag",
            AoMethod::Hbao => "ao/hbao.frag",
            AoMethod::AngleBased => "ao/angle_based.frag",
            AoMethod::Gtao => "ao/gtao.frag",
        }
    }

    /// (first count, second count) the shader reads from `aoCounts`, from the common parameters:
    /// SAO: samples and spiral turns; HBAO: directions and steps; GTAO: slices and steps per side
    /// (the quality preset's when one is set).
    pub fn counts(self, p: &SaoParams) -> [i32; 2] {
        if let (AoMethod::Gtao, Some(q)) = (self, p.quality) {
            let (slices, steps) = q.slices_steps();
            return [slices as i32, steps as i32];
        }
        let s = p.samples.max(1) as i32;
        match self {
            AoMethod::SaoLesson | AoMethod::Sao => [s, p.spiral_turns.max(1) as i32],
            AoMethod::Crytek | AoMethod::Hemisphere => [s, 1],
            AoMethod::AngleBased => [(s / 2).max(1), 1],
            // Directions × steps ≈ samples: 4 directions, the rest as steps.
            AoMethod::Hbao => [4, (s / 4).max(1)],
            AoMethod::Gtao => [2, (s / 4).max(1)],
        }
    }
}

/// GTAO quality presets (`--quality`, `[ao] quality`): slices × steps per side. Every preset reads
/// level 0 of the half-size linear-depth chain (GTAO's horizon search needs exact depths: the min
/// mip chain would raise horizons); the sample count is what costs.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize, Deserialize, clap::ValueEnum)]
#[serde(rename_all = "kebab-case")]
pub enum GtaoQuality {
    /// 1 slice × 4 steps (8 taps): the blur hides the 4×4 rotation tile.
    Low,
    /// 2 slices × 4 steps (16 taps): the bench's default setting.
    Medium,
    /// 3 slices × 6 steps (36 taps).
    High,
    /// 4 slices × 8 steps (64 taps).
    Ultra,
}

impl GtaoQuality {
    pub const ALL: [GtaoQuality; 4] = [
        GtaoQuality::Low,
        GtaoQuality::Medium,
        GtaoQuality::High,
        GtaoQuality::Ultra,
    ];
    pub fn slices_steps(self) -> (u32, u32) {
        match self {
            GtaoQuality::Low => (1, 4),
            GtaoQuality::Medium => (2, 4),
            GtaoQuality::High => (3, 6),
            GtaoQuality::Ultra => (4, 8),
        }
    }
    pub fn name(self) -> &'static str {
        match self {
            GtaoQuality::Low => "low",
            GtaoQuality::Medium => "medium",
            GtaoQuality::High => "high",
            GtaoQuality::Ultra => "ultra",
        }
    }
}

/// Programs of the non-lesson methods (built on first use) and the separable blur's targets.
pub struct AoMethods {
    gl: Gl,
    res: ResDirs,
    programs: HashMap<AoMethod, ProgramObject>,
    blur: ProgramObject,
    /// Intermediate of the two blur passes (half size, R8), created on the first blur and dropped
    /// by `release_targets` (an engine with AO off owns no AO texture).
    fbo_tmp: RefCell<Option<FramebufferObject>>,
    /// The engine's `sao`: its packed (occlusion, depth) targets and blur, on first use.
    packed: RefCell<Option<PackedSaoTargets>>,
    blur_packed: Option<ProgramObject>,
    defines: Vec<(&'static str, String)>,
}

/// Location of the blur's axis uniform.
const LOC_BLUR_AXIS: i32 = 210;
const LOC_AO_INFO: i32 = 200;
const LOC_NDC_TO_VIEW: i32 = 201;
const LOC_AO_COUNTS: i32 = 202;
const LOC_MAX_RADIUS: i32 = 203;

/// `ao/sao.frag` reads level floor(log2(distance in pixels)) − SAO_LOG_MAX_OFFSET (McGuire's
/// LOG_MAX_OFFSET): 2^3 = 8 samples share a texel of the level they read.
pub const SAO_LOG_MAX_OFFSET: u32 = 3;

/// Largest screen-space radius (pixels of the half-size buffer) a method's disc may have: near the
/// camera the disc could cover the screen (HBAO+ clamps it the same way).
pub fn max_radius_pixels(half_width: u32, half_height: u32) -> f32 {
    0.25 * (half_width.max(half_height) as f32).max(8.0)
}

/// Levels of the linear-depth chain the engine's SAO reads: its samples lie within the clamped
/// screen radius, so the farthest reads level floor(log2(max radius)) − LOG_MAX_OFFSET; capped by
/// what the half-size texture can hold.
pub fn sao_depth_levels(half_width: u32, half_height: u32) -> u32 {
    let radius = max_radius_pixels(half_width, half_height) as u32;
    let top = (31 - radius.max(1).leading_zeros()).saturating_sub(SAO_LOG_MAX_OFFSET);
    (top + 1).min(crate::gl::texture::max_levels(half_width, half_height))
}

fn camera_defines(camera: &Camera) -> Vec<(&'static str, String)> {
    vec![
        ("CAMERA_FAR", crate::ao::sao_lesson::glsl_float(camera.far)),
        ("LOG_MAX_OFFSET", SAO_LOG_MAX_OFFSET.to_string()),
    ]
}

impl AoMethods {
    /// Compiles the blur; targets are created on first use, the methods' programs by `prepare`.
    pub fn new(gl: &Gl, res: &ResDirs, camera: &Camera) -> Result<AoMethods> {
        let defines = camera_defines(camera);
        let blur =
            ProgramObject::from_res(gl, res, "simple.vert", "ao/blur_separable.frag", &defines)?;
        Ok(AoMethods {
            gl: gl.clone(),
            res: res.clone(),
            programs: HashMap::new(),
            blur,
            fbo_tmp: RefCell::new(None),
            packed: RefCell::new(None),
            blur_packed: None,
            defines,
        })
    }

    /// Drops the size-dependent targets (re-created at the right size on next use).
    pub fn release_targets(&mut self) {
        self.fbo_tmp = RefCell::new(None);
        self.packed = RefCell::new(None);
    }

    /// The textures this object currently owns.
    pub fn textures(&self) -> Vec<Rc<Texture>> {
        let tmp = self.fbo_tmp.borrow();
        let mut out: Vec<Rc<Texture>> = tmp
            .iter()
            .filter_map(|f| f.color_texture().cloned())
            .collect();
        if let Some(p) = self.packed.borrow().as_ref() {
            out.push(p.packed.clone());
            out.extend(p.fbo_tmp.color_texture().cloned());
        }
        out
    }

    /// Builds the method's program if needed (errors name the file and line).
    pub fn prepare(&mut self, method: AoMethod) -> Result<(), ProgramError> {
        if method == AoMethod::Sao && self.blur_packed.is_none() {
            self.blur_packed = Some(ProgramObject::from_res(
                &self.gl,
                &self.res,
                "simple.vert",
                "ao/blur_packed.frag",
                &self.defines,
            )?);
        }
        if method == AoMethod::SaoLesson || self.programs.contains_key(&method) {
            return Ok(());
        }
        let p = ProgramObject::from_res(
            &self.gl,
            &self.res,
            "simple.vert",
            method.shader(),
            &self.defines,
        )?;
        self.programs.insert(method, p);
        Ok(())
    }

    pub fn update_camera(&mut self, camera: &Camera) -> Result<(), ProgramError> {
        let d = camera_defines(camera);
        if d == self.defines {
            return Ok(());
        }
        self.defines = d.clone();
        self.blur.set_defines(&d)?;
        if let Some(p) = &mut self.blur_packed {
            p.set_defines(&d)?;
        }
        for p in self.programs.values_mut() {
            p.set_defines(&d)?;
        }
        Ok(())
    }

    pub fn reload(&mut self, force: bool) -> Vec<ProgramError> {
        let mut errors = Vec::new();
        for p in self
            .programs
            .values_mut()
            .chain(std::iter::once(&mut self.blur))
            .chain(self.blur_packed.as_mut())
        {
            if force || p.sources_changed() {
                if let Err(e) = p.reload() {
                    errors.push(e);
                }
            }
        }
        errors
    }

    /// Runs `method` into the lesson's SAO target (occlusion, R8, half size).
    pub fn compute(
        &self,
        method: AoMethod,
        lesson: &SaoLesson,
        meshes: &MeshBuffer,
        camera: &Camera,
        params: &SaoParams,
    ) {
        let Some(p) = self.programs.get(&method) else {
            log::error!("AO method {} was not prepared", method.name());
            return;
        };
        let (w, h) = (
            lesson.fbo_depth[0].width() as f32,
            lesson.fbo_depth[0].height() as f32,
        );
        let fov_scale = config::fov_scale(camera.fov_y_deg);
        // Pixels (of the half-size buffer) per metre at 1 m distance.
        let proj_scale = 0.5 * h * fov_scale;
        p.set_vec4(
            LOC_AO_INFO,
            [params.radius, params.bias, params.intensity, proj_scale],
        );
        p.set_vec2(LOC_NDC_TO_VIEW, [w / h / fov_scale, 1.0 / fov_scale]);
        let c = method.counts(params);
        if p.has_location(LOC_AO_COUNTS) {
            unsafe {
                use glow::HasContext;
                self.gl.program_uniform_2_i32(
                    p.id(),
                    Some(&glow::NativeUniformLocation(LOC_AO_COUNTS as u32)),
                    c[0],
                    c[1],
                );
            }
        }
        p.set_f32(LOC_MAX_RADIUS, max_radius_pixels(w as u32, h as u32));
        fullscreen_state(&self.gl);
        p.use_program();
        let packed = (method == AoMethod::Sao && self.blur_packed.is_some())
            .then(|| self.packed_targets(lesson))
            .flatten();
        match &packed {
            // Occlusion into the lesson's target as every method, and the pair for the blur.
            Some(t) => t.fbo_sao_and_packed.bind(),
            None => lesson.fbo_sao.bind(),
        }
        lesson.tex_depth.bind(0);
        meshes.draw_plane_xy();
    }

    /// The packed targets for `lesson`'s current SAO texture (re-created when it changed).
    fn packed_targets(&self, lesson: &SaoLesson) -> Option<std::cell::Ref<'_, PackedSaoTargets>> {
        let current = self
            .packed
            .borrow()
            .as_ref()
            .is_some_and(|p| Rc::ptr_eq(&p.lesson_sao, lesson.sao_texture()));
        if !current {
            *self.packed.borrow_mut() = None;
            match PackedSaoTargets::new(&self.gl, lesson.sao_texture()) {
                Ok(t) => *self.packed.borrow_mut() = Some(t),
                Err(e) => {
                    log::error!("packed SAO targets: {e:#}; using the plain blur");
                    return None;
                }
            }
        }
        std::cell::Ref::filter_map(self.packed.borrow(), |p| p.as_ref()).ok()
    }

    /// The blur of `method`'s output: the packed one for the engine's `sao` (one fetch per tap),
    /// else the plain separable blur.
    pub fn blur_method(&self, method: AoMethod, lesson: &SaoLesson, meshes: &MeshBuffer) {
        let packed = match (&self.blur_packed, method) {
            (Some(prog), AoMethod::Sao) => self
                .packed
                .borrow()
                .as_ref()
                .filter(|p| Rc::ptr_eq(&p.lesson_sao, lesson.sao_texture()))
                .is_some()
                .then_some(prog),
            _ => None,
        };
        let Some(prog) = packed else {
            self.blur(lesson, meshes);
            return;
        };
        let guard = self.packed.borrow();
        let t = guard.as_ref().expect("checked above");
        fullscreen_state(&self.gl);
        prog.use_program();
        unsafe {
            use glow::HasContext;
            let loc = glow::NativeUniformLocation(LOC_BLUR_AXIS as u32);
            self.gl.program_uniform_2_i32(prog.id(), Some(&loc), 1, 0);
            t.fbo_tmp.bind();
            t.packed.bind(0);
            meshes.draw_plane_xy();
            self.gl.program_uniform_2_i32(prog.id(), Some(&loc), 0, 1);
            lesson.fbo_blur.bind();
            t.fbo_tmp.color_texture().unwrap().bind(0);
            meshes.draw_plane_xy();
        }
    }

    /// Two-pass separable bilateral blur: SAO target → intermediate → the lesson's blur target.
    pub fn blur(&self, lesson: &SaoLesson, meshes: &MeshBuffer) {
        let size = lesson.sao_texture().size_at(0);
        let mut tmp = self.fbo_tmp.borrow_mut();
        if tmp.as_ref().map(|f| (f.width(), f.height())) != Some(size) {
            *tmp = None;
            match tmp_target(&self.gl, size) {
                Ok(f) => *tmp = Some(f),
                Err(e) => {
                    log::error!("separable blur skipped: {e:#}");
                    return;
                }
            }
        }
        let fbo_tmp = tmp.as_ref().expect("created above");
        fullscreen_state(&self.gl);
        self.blur.use_program();
        unsafe {
            use glow::HasContext;
            let loc = glow::NativeUniformLocation(LOC_BLUR_AXIS as u32);
            lesson.tex_depth.bind(1);
            self.gl
                .program_uniform_2_i32(self.blur.id(), Some(&loc), 1, 0);
            fbo_tmp.bind();
            lesson.sao_texture().bind(0);
            meshes.draw_plane_xy();
            self.gl
                .program_uniform_2_i32(self.blur.id(), Some(&loc), 0, 1);
            lesson.fbo_blur.bind();
            fbo_tmp.color_texture().unwrap().bind(0);
            meshes.draw_plane_xy();
        }
    }
}

/// The engine's `sao` writes occlusion into the lesson's R8 target (raw view, blur off) and the
/// (occlusion, linear depth) pair into an RG32F target in the same pass; the packed blur then reads
/// one texture per tap. RG32F keeps the depth exact, so the blur's `depth >= far` sky test holds.
struct PackedSaoTargets {
    /// The lesson's texture attached as the second target (held so it outlives this FBO, and to
    /// notice when the lesson re-created its targets).
    lesson_sao: Rc<Texture>,
    packed: Rc<Texture>,
    /// Attachment 0 = `packed`, 1 = the lesson's SAO texture; draw buffers map the shader's output
    /// 0 (occlusion) to attachment 1 and output 1 (the pair) to attachment 0.
    fbo_sao_and_packed: FramebufferObject,
    /// Between the two blur passes (RG32F).
    fbo_tmp: FramebufferObject,
}

impl PackedSaoTargets {
    fn new(gl: &Gl, lesson_sao: &Rc<Texture>) -> Result<PackedSaoTargets> {
        use glow::HasContext;
        let (w, h) = lesson_sao.size_at(0);
        let packed = Rc::new(Texture::new(
            gl,
            TextureDesc::target("FBO(sao packed)", w, h, glow::RG32F),
        )?);
        let fbo = FramebufferObject::new(gl, Some(packed.clone()), None, 0, 0)?;
        unsafe {
            gl.named_framebuffer_texture(
                Some(fbo.id()),
                glow::COLOR_ATTACHMENT1,
                Some(lesson_sao.id()),
                0,
            );
            gl.named_framebuffer_draw_buffers(
                Some(fbo.id()),
                &[glow::COLOR_ATTACHMENT1, glow::COLOR_ATTACHMENT0],
            );
            let status = gl.check_named_framebuffer_status(Some(fbo.id()), glow::FRAMEBUFFER);
            if status != glow::FRAMEBUFFER_COMPLETE {
                anyhow::bail!("packed SAO framebuffer is incomplete (status 0x{status:x})");
            }
        }
        let tmp = Rc::new(Texture::new(
            gl,
            TextureDesc::target("FBO(sao packed blur tmp)", w, h, glow::RG32F),
        )?);
        let fbo_tmp = FramebufferObject::new(gl, Some(tmp), None, 0, 0)?;
        Ok(PackedSaoTargets {
            lesson_sao: lesson_sao.clone(),
            packed,
            fbo_sao_and_packed: fbo,
            fbo_tmp,
        })
    }
}

fn fullscreen_state(gl: &Gl) {
    use glow::HasContext;
    unsafe {
        gl.disable(glow::CULL_FACE);
        gl.disable(glow::DEPTH_TEST);
        gl.depth_mask(false);
        gl.disable(glow::BLEND);
        gl.disable(glow::SCISSOR_TEST);
    }
}

fn tmp_target(gl: &Gl, (w, h): (u32, u32)) -> Result<FramebufferObject> {
    let tex = Rc::new(Texture::new(
        gl,
        TextureDesc::target("FBO(ao blur tmp)", w, h, glow::R8),
    )?);
    FramebufferObject::new(gl, Some(tex), None, 0, 0)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sao_level_count_follows_the_largest_disc() {
        // 1920×1080 → 960×540 half size, radius clamp 240 px: log2 → 7, minus 3 → level 4.
        assert_eq!(sao_depth_levels(960, 540), 5);
        // 640 → clamp 160 → level 4; 512 → 128 → level 4; 511 → 127.75 → level 3.
        assert_eq!(sao_depth_levels(640, 360), 5);
        assert_eq!(sao_depth_levels(512, 100), 5);
        assert_eq!(sao_depth_levels(511, 100), 4);
        // Tiny buffers: one level, never more than the texture holds.
        assert_eq!(sao_depth_levels(4, 4), 1);
        assert_eq!(sao_depth_levels(8192, 2), 9);
    }
}
