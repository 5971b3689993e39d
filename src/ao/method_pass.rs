//! What every AO method provides (`AoMethodPass`), the inputs a frame hands it, and the uniforms the
//! engine's method shaders share through `Res/ao/common.glsl`.

use super::blur::BLUR_REACH;
use super::packed::{PackedOutput, PACKED_BLUR_SHADER};
use super::settings::{AoMethod, AoSettings};
use super::sky_skip::{AoSizeDepth, Texels};
use super::targets::{AoTargets, SAO_DEPTH_LEVELS};
use crate::gl::preprocess::glsl_float;
use crate::gl::{Gl, MeshBuffer, ProgramError, ProgramObject, Texture};
use crate::math::camera::fov_scale;
use crate::math::Camera;
use crate::res::ResDirs;
use crate::scene::game_object::GameObject;
use crate::shader_interface::{binding, loc};
use anyhow::Result;
use glow::HasContext;
use std::any::Any;
use std::rc::Rc;

/// What a frame hands a method.
pub struct AoInputs<'a> {
    pub gl: &'a Gl,
    pub meshes: &'a MeshBuffer,
    pub targets: &'a AoTargets,
    pub camera: &'a Camera,
    pub settings: &'a AoSettings,
    /// Linear depth of the back faces at the AO size, when the settings ask for it.
    pub back_depth: Option<&'a Texture>,
    /// Octahedral view-space surface normals at the AO size, when the settings ask for them.
    pub normals: Option<&'a Texture>,
    /// Linear depth of the second depth layer at the AO size, when the settings ask for it.
    pub second_depth: Option<&'a Texture>,
    /// Linear depth of the second layer's back faces at the AO size, when the settings ask for it.
    pub second_back_depth: Option<&'a Texture>,
    /// The scene's objects (`rtao` traces their triangles).
    pub objects: &'a [GameObject],
    /// The texels of `targets` the frame reads (x, y, width, height), where the method and its blur
    /// draw: inside a guard band, the view and the blur's reach around it
    /// (`guard_band::read_region`). `None`: all of them.
    pub region: Option<[i32; 4]>,
    /// The window depth the chain drew at the AO size, when it drew one (`sky_skip`): the engine's
    /// methods and their blur shade only its surface texels.
    pub ao_size_depth: Option<AoSizeDepth<'a>>,
    /// This frame's (rotation, step offset) in [0, 1) for `common.glsl`'s `aoFrameJitter`: the
    /// temporal accumulation's sequence (`ao/temporal.rs`), [0, 0] when frames are not accumulated.
    pub frame_jitter: [f32; 2],
}

impl<'a> AoInputs<'a> {
    /// The texels a method's pass and its blur shade: `region`, and with `sky_skip` (where the
    /// method's shader allows it) only the surface texels of `ao_size_depth`.
    pub fn texels(&self, sky_skip: bool) -> Texels<'a> {
        Texels {
            region: self.region,
            depth: self.ao_size_depth.filter(|_| sky_skip),
        }
    }

    /// Binds the surface normals (when the frame has them) where `common.glsl` reads them.
    pub fn bind_normals(&self) {
        if let Some(n) = self.normals {
            n.bind(binding::SURFACE_NORMALS);
        }
    }
}

/// One AO method: its programs, how it fills the occlusion target, and how its output is blurred.
/// What only one method has (`rtao`'s BVH and running mean, `vbao`'s slab hierarchy) is asked of
/// that method's own type (`AoPipeline::pass_of`).
pub trait AoMethodPass: Any {
    fn method(&self) -> AoMethod;
    /// The names statistics and reports give its pass and its blur when they are not the method's
    /// (a method file's own).
    fn own_labels(&self) -> Option<(&'static str, &'static str)> {
        None
    }
    /// Every program it owns (hot reload, define updates).
    fn programs_mut(&mut self) -> Vec<&mut ProgramObject>;
    /// Re-injects the compile-time constants that follow the camera and the settings.
    fn update_defines(
        &mut self,
        camera: &Camera,
        settings: &AoSettings,
    ) -> Result<(), ProgramError>;
    /// Levels of the linear-depth chain it reads, for an AO buffer of `ao_size`.
    fn depth_levels(&self, _ao_size: (u32, u32)) -> u32 {
        SAO_DEPTH_LEVELS
    }
    /// Writes occlusion into `inputs.targets.fbo_sao` (and whatever else the method keeps).
    fn compute(&self, inputs: &AoInputs) -> Result<()>;
    /// Blurs the occlusion into `inputs.targets.fbo_blur`.
    fn blur(&self, inputs: &AoInputs) -> Result<()>;
    /// Size-dependent textures it owns now.
    fn textures(&self) -> Vec<Rc<Texture>> {
        Vec::new()
    }
    /// Drops size-dependent textures (re-created on next use).
    fn release_targets(&mut self) {}
}

/// The whole number of units (steps, directions' steps, pairs) whose `taps_per_unit` depth taps come
/// nearest to the `samples` budget, at least 1: `--samples N` buys every method N taps per pixel, to
/// within half a unit, so the bench compares equal budgets (truncating gave `gtao` 8 taps for 11).
pub fn units_for_budget(samples: u32, taps_per_unit: u32) -> i32 {
    let unit = taps_per_unit.max(1);
    ((samples + unit / 2) / unit).max(1) as i32
}

/// `ao/sao.frag` reads level floor(log2(distance in pixels)) − LOG_MAX_OFFSET (McGuire's
/// LOG_MAX_OFFSET): 2^3 = 8 samples share a texel of the level they read.
pub const LOG_MAX_OFFSET: u32 = 3;

/// Largest screen-space radius (pixels of the AO buffer, whatever its size) a method's disc may have: near the
/// camera the disc could cover the screen (HBAO+ clamps it the same way, to a quarter of the view).
pub fn max_radius_pixels(ao_width: u32, ao_height: u32) -> f32 {
    0.25 * (ao_width.max(ao_height) as f32).max(8.0)
}

/// The defines every method shader of `Res/ao/` and its blur read: the one place they are written
/// (the shaders have no fallback values that could disagree).
pub fn method_defines(camera: &Camera) -> Vec<(&'static str, String)> {
    vec![
        ("CAMERA_FAR", glsl_float(camera.far)),
        ("LOG_MAX_OFFSET", LOG_MAX_OFFSET.to_string()),
        ("BLUR_REACH", BLUR_REACH.to_string()),
    ]
}

/// The blurs' defines: `method_defines` and, for a method with a Gaussian of its own
/// (`MethodInfo::blur_sigma`), its `BLUR_WEIGHTS` under `settings`.
pub fn blur_defines(
    camera: &Camera,
    blur_sigma: Option<fn(u32) -> f32>,
    settings: &AoSettings,
) -> Vec<(&'static str, String)> {
    let mut defines = method_defines(camera);
    defines.extend(super::blur::weights_define(
        blur_sigma.map(|f| f(settings.rays)),
    ));
    defines
}

/// `common.glsl`'s compile-time choice of where the normal comes from (`AO_SURFACE_NORMALS`): one
/// path compiled instead of both behind a uniform, which a software rasteriser would run both of.
/// The engine draws the surface normals exactly when `uses_surface_normals` says so.
pub fn normal_source_define(settings: &AoSettings) -> (&'static str, String) {
    let on = settings.uses_surface_normals();
    ("AO_SURFACE_NORMALS", u8::from(on).to_string())
}

/// Sets `common.glsl`'s uniforms for a frame.
pub fn set_common_uniforms(gl: &Gl, program: &ProgramObject, inputs: &AoInputs, counts: [i32; 2]) {
    let (w, h) = inputs.targets.size();
    let fov = fov_scale(inputs.camera.fov_y_deg);
    // Pixels (of the AO buffer) per metre at 1 m distance.
    let proj_scale = 0.5 * h as f32 * fov;
    let s = inputs.settings;
    program.set_vec4(loc::AO_INFO, [s.radius, s.bias, s.intensity, proj_scale]);
    program.set_vec2(loc::NDC_TO_VIEW, [w as f32 / h as f32 / fov, 1.0 / fov]);
    if program.has_location(loc::AO_COUNTS) {
        let location = glow::NativeUniformLocation(loc::AO_COUNTS as u32);
        // SAFETY: an ivec2 uniform at a location the interface test checks.
        unsafe { gl.program_uniform_2_i32(program.id(), Some(&location), counts[0], counts[1]) };
    }
    program.set_f32(loc::MAX_RADIUS_PIXELS, max_radius_pixels(w, h));
    if program.has_location(loc::AO_THICKNESS) {
        program.set_f32(loc::AO_THICKNESS, s.thickness_metres());
    }
    if program.has_location(loc::AO_BACK_FACES) {
        program.set_i32(loc::AO_BACK_FACES, inputs.back_depth.is_some() as i32);
    }
    if program.has_location(loc::AO_LAYERS) {
        program.set_i32(loc::AO_LAYERS, 1 + inputs.second_depth.is_some() as i32);
    }
    if program.has_location(loc::AO_LAYER_BACK_FACES) {
        let on = inputs.second_depth.is_some() && inputs.second_back_depth.is_some();
        program.set_i32(loc::AO_LAYER_BACK_FACES, on as i32);
    }
    if program.has_location(loc::AO_SURFACE_NORMALS) {
        program.set_i32(loc::AO_SURFACE_NORMALS, inputs.normals.is_some() as i32);
    }
    // Temporal accumulation: where this frame's sample pattern starts.
    if program.has_location(loc::AO_FRAME_JITTER) {
        program.set_vec2(loc::AO_FRAME_JITTER, inputs.frame_jitter);
    }
}

/// A method that is one shader of `Res/ao/` reading `common.glsl`'s uniforms and writing occlusion,
/// blurred with the packed blur.
pub struct ShaderMethod {
    method: AoMethod,
    program: ProgramObject,
    blur: ProgramObject,
    packed: PackedOutput,
    /// (first, second) of `aoCounts` from the settings.
    counts: CountsFn,
    /// The method's own Gaussian for its blur (`MethodInfo::blur_sigma`); `None` for a method
    /// file's shader, which keeps the shared one.
    blur_sigma: Option<fn(u32) -> f32>,
    /// Whether its shader writes `WriteOcclusion(0.0, z)` for every sky texel and nothing else, so
    /// that its pass and blur may skip the sky (`sky_skip`): the engine's own shaders do; a method
    /// file's shader may write anything there.
    skips_sky: bool,
}

/// How a method turns the settings into `aoCounts`.
pub type CountsFn = Box<dyn Fn(&AoSettings) -> [i32; 2]>;

impl ShaderMethod {
    /// `method`'s shader (`MethodInfo::shader`) and the packed blur, with `counts` for `aoCounts`.
    pub fn build(
        method: AoMethod,
        counts: fn(&AoSettings) -> [i32; 2],
        gl: &Gl,
        res: &ResDirs,
        camera: &Camera,
    ) -> Result<ShaderMethod, ProgramError> {
        let defines = method_defines(camera);
        let shader = method.info().shader;
        let program = ProgramObject::from_res(gl, res, "simple.vert", shader, &defines)?;
        let blur_sigma = method.info().blur_sigma;
        let mut built = ShaderMethod::assemble(
            method,
            program,
            Box::new(counts),
            blur_sigma,
            gl,
            res,
            camera,
        )?;
        built.skips_sky = true;
        Ok(built)
    }

    /// A method whose occlusion program is already built (a method file's shader, outside `Res/`).
    pub fn with_program(
        method: AoMethod,
        program: ProgramObject,
        counts: CountsFn,
        gl: &Gl,
        res: &ResDirs,
        camera: &Camera,
    ) -> Result<ShaderMethod, ProgramError> {
        ShaderMethod::assemble(method, program, counts, None, gl, res, camera)
    }

    /// `program` with the packed blur, compiled with the method's own Gaussian if it has one (for
    /// the default settings until `update_defines_with` brings the frame's).
    fn assemble(
        method: AoMethod,
        program: ProgramObject,
        counts: CountsFn,
        blur_sigma: Option<fn(u32) -> f32>,
        gl: &Gl,
        res: &ResDirs,
        camera: &Camera,
    ) -> Result<ShaderMethod, ProgramError> {
        let defines = blur_defines(camera, blur_sigma, &AoSettings::default());
        let blur = ProgramObject::from_res(gl, res, "simple.vert", PACKED_BLUR_SHADER, &defines)?;
        Ok(ShaderMethod {
            method,
            program,
            blur,
            packed: PackedOutput::default(),
            counts,
            blur_sigma,
            skips_sky: false,
        })
    }

    /// Follows `camera` and `settings`, with `extra` compile-time choices of the method's own.
    pub fn update_defines_with(
        &mut self,
        camera: &Camera,
        settings: &AoSettings,
        extra: &[(&str, String)],
    ) -> Result<(), ProgramError> {
        let defines = method_defines(camera);
        let mut own: Vec<(&str, String)> = defines.clone();
        own.push(normal_source_define(settings));
        own.extend(extra.iter().cloned());
        self.program.set_defines(&own)?;
        let blur = blur_defines(camera, self.blur_sigma, settings);
        self.blur.set_defines(&blur)
    }

    /// The occlusion program (for a method that sets uniforms of its own before `compute`).
    pub fn program(&self) -> &ProgramObject {
        &self.program
    }

    /// The (occlusion, depth) target it writes and blurs.
    pub fn packed(&self) -> &PackedOutput {
        &self.packed
    }
}

impl AoMethodPass for ShaderMethod {
    fn method(&self) -> AoMethod {
        self.method
    }
    fn programs_mut(&mut self) -> Vec<&mut ProgramObject> {
        vec![&mut self.program, &mut self.blur]
    }
    fn update_defines(&mut self, camera: &Camera, s: &AoSettings) -> Result<(), ProgramError> {
        self.update_defines_with(camera, s, &[])
    }
    fn compute(&self, inputs: &AoInputs) -> Result<()> {
        set_common_uniforms(
            inputs.gl,
            &self.program,
            inputs,
            (self.counts)(inputs.settings),
        );
        self.program.use_program();
        inputs.targets.tex_depth.bind(binding::INPUT);
        if let Some(back) = inputs.back_depth {
            back.bind(binding::SECOND_INPUT);
        }
        if let Some(second) = inputs.second_depth {
            second.bind(binding::SECOND_LAYER);
        }
        if let Some(back) = inputs.second_back_depth {
            back.bind(binding::SECOND_LAYER_BACK);
        }
        inputs.bind_normals();
        self.packed.draw_method(
            inputs.gl,
            inputs.targets,
            inputs.texels(self.skips_sky),
            || inputs.meshes.draw_plane_xy(),
        )
    }
    fn blur(&self, inputs: &AoInputs) -> Result<()> {
        self.packed.blur(
            inputs.gl,
            inputs.targets,
            inputs.meshes,
            &self.blur,
            inputs.texels(self.skips_sky),
        )
    }
    fn textures(&self) -> Vec<Rc<Texture>> {
        self.packed.textures()
    }
    fn release_targets(&mut self) {
        self.packed.release();
    }
}
