//! `Engine`: owns the scene, the render targets and the passes, and renders a frame in the course's
//! order: shadow map → main FBO (opaque) → ambient occlusion → sky → transparent → bloom → image
//! processing into the output (the window's default framebuffer or a headless FBO).

pub mod camera;
pub mod depth;
pub mod game_object;
pub mod lazy_ao;

pub use camera::{linear_depth_exact, Camera};
pub use depth::DepthMode;
pub use game_object::GameObject;
pub use lazy_ao::LazySaoLesson;

use crate::ao::{AoMethod, AoMethods, CompositeMode, SaoLesson, SaoParams, SaoPrograms};
use crate::config::{binding, loc};
use crate::gl::{
    mesh::MeshData, FramebufferObject, Gl, MeshBuffer, ProgramError, ProgramObject, Texture,
    TextureDesc,
};
use crate::res::ResDirs;
use crate::scene::{BloomDesc, LightDesc, SceneDesc};
use anyhow::{bail, Context as _, Result};
use glam::{Mat3, Mat4, Vec3, Vec4};
use glow::HasContext;
use std::rc::Rc;

/// What the frame shows.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default, clap::ValueEnum)]
pub enum View {
    /// The lit scene with AO blended in.
    #[default]
    Composite,
    /// The half-size linear depth buffer (metres).
    LinearDepth,
    /// The SAO buffer before the blur, as visibility (1 = open).
    AoRaw,
    /// The blurred SAO buffer, as visibility.
    Ao,
}

impl View {
    pub const ALL: [View; 4] = [View::Composite, View::LinearDepth, View::AoRaw, View::Ao];
    pub fn next(self) -> View {
        let i = View::ALL.iter().position(|v| *v == self).unwrap_or(0);
        View::ALL[(i + 1) % View::ALL.len()]
    }
    pub fn label(self) -> &'static str {
        match self {
            View::Composite => "composite",
            View::LinearDepth => "linear depth",
            View::AoRaw => "raw SAO",
            View::Ao => "blurred SAO",
        }
    }
}

/// "vendor / renderer / version" of the current context.
pub fn describe_renderer(gl: &glow::Context) -> String {
    unsafe {
        format!(
            "{} {} (OpenGL {})",
            gl.get_parameter_string(glow::VENDOR),
            gl.get_parameter_string(glow::RENDERER),
            gl.get_parameter_string(glow::VERSION)
        )
    }
}

/// Time and draw calls of one pass of the last frame (`render --stats`).
#[derive(Clone, Debug, serde::Serialize)]
pub struct PassStat {
    pub name: &'static str,
    /// shadow, opaque, ao, sky, transparent, bloom or post.
    pub group: &'static str,
    /// Wall-clock milliseconds between two glFinish calls (timer queries do not measure real time on llvmpipe).
    pub ms: f64,
    /// CPU milliseconds the whole process (llvmpipe's threads included) spent in the pass: unlike
    /// `ms`, barely changed by other programs competing for the cores (benchmarks on shared machines).
    pub cpu_ms: f64,
    pub draw_calls: u64,
}

/// CPU time of the whole process (all threads), in seconds.
pub fn process_cpu_seconds() -> f64 {
    let mut ts = libc::timespec {
        tv_sec: 0,
        tv_nsec: 0,
    };
    // SAFETY: clock_gettime writes one timespec; CLOCK_PROCESS_CPUTIME_ID exists on Linux.
    let rc = unsafe { libc::clock_gettime(libc::CLOCK_PROCESS_CPUTIME_ID, &mut ts) };
    if rc != 0 {
        return 0.0;
    }
    ts.tv_sec as f64 + ts.tv_nsec as f64 * 1e-9
}

const SHADOW_MAP_SIZE: u32 = 2048;
const BLOOM_LEVELS: usize = 6;

pub struct Engine {
    gl: Gl,
    res: ResDirs,
    pub meshes: MeshBuffer,
    pub objects: Vec<GameObject>,
    pub camera: Camera,
    pub light: LightDesc,
    pub bloom: BloomDesc,
    pub ao_params: SaoParams,
    pub view: View,
    prog_standard: ProgramObject,
    prog_shadow: ProgramObject,
    prog_sky: ProgramObject,
    prog_bloom_bright: ProgramObject,
    prog_bloom_down: ProgramObject,
    prog_bloom_up: ProgramObject,
    prog_image: ProgramObject,
    prog_debug: ProgramObject,
    prog_composite_tint: ProgramObject,
    /// The lesson's passes; their targets are created on the first frame that runs AO.
    pub ao: LazySaoLesson,
    /// The other AO methods (built on first use).
    pub methods: AoMethods,
    width: u32,
    height: u32,
    pub fbo_main: FramebufferObject,
    fbo_shadow: FramebufferObject,
    fbo_bloom: Vec<FramebufferObject>,
    /// Main depth buffer convention (`[output] depth`, `--depth`).
    depth_mode: DepthMode,
    /// Loaded once reversed-Z is first used; from then on every depth pass sets its clip range.
    clip_control: Option<depth::ClipControl>,
    /// The reversed-Z linear-depth restore (`Res/ao/restore_depth_reversed.frag`), built with the mode.
    prog_restore_reversed: Option<ProgramObject>,
    /// Headless output (RGBA8), created on demand.
    fbo_output: Option<FramebufferObject>,
    /// Scratch R32F target for value read-back.
    fbo_values: Option<FramebufferObject>,
    black: Texture,
    /// Forces the linear-depth chain's level count (comparisons in tests and benchmarks); `None` = per
    /// method. Applied by `render_image`, `render_values`, `resize` and `sync_shader_constants`.
    pub depth_levels_override: Option<u32>,
    /// When on, each pass is bracketed by glFinish and timed (slower; for `--stats` and benchmarks).
    pub collect_stats: bool,
    /// Objects whose bounds miss the frustum are not drawn (on by default; `bench --skips` turns it
    /// off to measure what it saves).
    pub frustum_culling: bool,
    stats: std::cell::RefCell<Vec<PassStat>>,
}

impl Engine {
    /// Loads every shader and mesh of `scene` and creates targets of `width`×`height`.
    pub fn new(
        gl: &Gl,
        res: ResDirs,
        scene: &SceneDesc,
        width: u32,
        height: u32,
    ) -> Result<Engine> {
        scene.validate()?;
        let (width, height) = (width.max(1), height.max(1));
        let camera = Camera {
            eye: Vec3::from(scene.camera.eye),
            target: Vec3::from(scene.camera.target),
            up: Vec3::Y,
            fov_y_deg: scene.camera.fov_y,
            near: scene.camera.near,
            far: scene.camera.far,
        };
        let (ao_params, notes) = scene.ao.sanitized();
        for n in notes {
            log::warn!("{n}");
        }
        let p = |v: &str, f: &str| ProgramObject::from_res(gl, &res, v, f, &[]);
        let prog_standard = p("standard.vert", "standard.frag")?;
        let prog_shadow = p("shadow.vert", "shadow.frag")?;
        let prog_sky = p("sky.vert", "sky.frag")?;
        let prog_bloom_bright = p("simple.vert", "bloom_bright.frag")?;
        let prog_bloom_down = p("simple.vert", "bloom_down.frag")?;
        let prog_bloom_up = p("simple.vert", "bloom_up.frag")?;
        let prog_image = p("simple.vert", "image_processing.frag")?;
        let prog_debug = p("simple.vert", "debug_view.frag")?;
        let prog_composite_tint = p("simple.vert", "ao/composite_tint.frag")?;
        let ao = LazySaoLesson::new(
            gl,
            SaoPrograms::new(gl, &res, &camera, &ao_params)?,
            (width, height),
            crate::config::SAO_DEPTH_LEVELS as u32,
        );
        let mut methods = AoMethods::new(gl, &res, &camera)?;
        methods.prepare(ao_params.method)?;

        let mut meshes = MeshBuffer::new(gl)?;
        let mut objects = Vec::new();
        for (i, o) in scene.objects.iter().enumerate() {
            let path = res.resolve_data(&o.mesh);
            let mesh = meshes
                .load_obj(&o.mesh, &path)
                .with_context(|| format!("scene object {} ({})", i + 1, o.mesh))?;
            let data = meshes.data(&o.mesh).unwrap();
            let mut obj = GameObject {
                name: o.mesh.clone(),
                mesh,
                position: Vec3::from(o.position),
                rotation: Vec3::from(o.rotation),
                scale: Vec3::from(o.scale),
                color: Vec4::from(o.color),
                bounds: (Vec3::ZERO, Vec3::ZERO),
            };
            obj.bounds = world_bounds(data, &obj.model());
            objects.push(obj);
        }
        // Draw parameters move when meshes are added: refresh them.
        for (o, d) in objects.iter_mut().zip(&scene.objects) {
            o.mesh = meshes.get(&d.mesh).unwrap();
        }

        let depth_mode = scene.output.depth;
        let fbo_main = create_main_fbo(gl, width, height, depth_mode)?;
        let shadow_tex = Rc::new(Texture::new(
            gl,
            TextureDesc::target(
                "FBO(shadow)",
                SHADOW_MAP_SIZE,
                SHADOW_MAP_SIZE,
                glow::DEPTH_COMPONENT32,
            )
            .filter(glow::LINEAR, glow::LINEAR)
            .compare(true),
        )?);
        let fbo_shadow = FramebufferObject::new(gl, None, Some(shadow_tex), 0, 0)?;
        let fbo_bloom = create_bloom_fbos(gl, width, height)?;
        let black = Texture::new(gl, TextureDesc::target("black", 1, 1, glow::RGBA8))?;
        black.upload_f32(0, 4, &[0.0, 0.0, 0.0, 1.0])?;

        let mut engine = Engine {
            gl: gl.clone(),
            res,
            meshes,
            objects,
            camera,
            light: scene.light.clone(),
            bloom: scene.bloom.clone(),
            ao_params,
            view: View::Composite,
            prog_standard,
            prog_shadow,
            prog_sky,
            prog_bloom_bright,
            prog_bloom_down,
            prog_bloom_up,
            prog_image,
            prog_debug,
            prog_composite_tint,
            ao,
            methods,
            width,
            height,
            fbo_main,
            fbo_shadow,
            fbo_bloom,
            depth_mode: DepthMode::D32,
            clip_control: None,
            prog_restore_reversed: None,
            fbo_output: None,
            fbo_values: None,
            black,
            depth_levels_override: None,
            collect_stats: false,
            frustum_culling: true,
            stats: Default::default(),
        };
        engine.set_depth_mode(depth_mode)?;
        engine.configure_ao_targets()?;
        if let Some(e) = crate::gl::take_error(gl) {
            bail!("{e} while creating the engine");
        }
        Ok(engine)
    }

    pub fn gl(&self) -> &Gl {
        &self.gl
    }
    pub fn res(&self) -> &ResDirs {
        &self.res
    }
    pub fn size(&self) -> (u32, u32) {
        (self.width, self.height)
    }

    pub fn depth_mode(&self) -> DepthMode {
        self.depth_mode
    }

    /// Switches the main depth buffer's convention (re-creates the main FBO when the format changes).
    pub fn set_depth_mode(&mut self, mode: DepthMode) -> Result<()> {
        if mode.reversed() {
            if self.clip_control.is_none() {
                self.clip_control = Some(depth::ClipControl::load()?);
            }
            if self.prog_restore_reversed.is_none() {
                self.prog_restore_reversed = Some(ProgramObject::from_res(
                    &self.gl,
                    &self.res,
                    "simple.vert",
                    "ao/restore_depth_reversed.frag",
                    &crate::ao::sao_lesson::camera_defines(&self.camera),
                )?);
            }
        }
        if mode != self.depth_mode {
            self.fbo_main = create_main_fbo(&self.gl, self.width, self.height, mode)?;
            self.depth_mode = mode;
        }
        Ok(())
    }

    /// The camera's view-projection for drawing into the main depth buffer (reversed-Z when on).
    /// Culling and the sky's view rays use `camera.view_projection`: the same frustum.
    fn scene_view_projection(&self) -> Mat4 {
        let c = &self.camera;
        depth::projection(self.depth_mode, c.fov_y_deg, self.aspect(), c.near, c.far) * c.view()
    }

    /// Depth state of a pass drawing into the main depth buffer: clip range, test, optional clear.
    fn begin_scene_depth_pass(&self, write: bool) {
        if let Some(cc) = &self.clip_control {
            cc.set(self.depth_mode.reversed());
        }
        unsafe {
            self.gl.enable(glow::DEPTH_TEST);
            self.gl.depth_func(self.depth_mode.nearer_or_equal());
            self.gl.depth_mask(write);
            self.gl.clear_depth_f32(self.depth_mode.clear_value());
        }
    }

    /// Back to OpenGL's default clip range, for every pass that follows (shadow, full-screen, UI).
    fn end_scene_depth_pass(&self) {
        if let Some(cc) = &self.clip_control {
            cc.set(false);
        }
    }

    /// Re-creates size-dependent targets. A 0×0 size (minimised window) keeps the old targets.
    pub fn resize(&mut self, width: u32, height: u32) -> Result<()> {
        if width == 0 || height == 0 || (width, height) == (self.width, self.height) {
            return Ok(());
        }
        self.fbo_main = create_main_fbo(&self.gl, width, height, self.depth_mode)?;
        self.fbo_bloom = create_bloom_fbos(&self.gl, width, height)?;
        self.fbo_output = None;
        self.fbo_values = None;
        self.width = width;
        self.height = height;
        // With AO off the AO targets are not worth keeping at the new size: the next frame that
        // needs them creates them.
        if !self.needs_ao(self.view) {
            self.ao.release_targets();
            self.methods.release_targets();
        }
        self.configure_ao_targets()?;
        Ok(())
    }

    /// Whether a frame showing `view` runs the AO chain.
    fn needs_ao(&self, view: View) -> bool {
        self.ao_params.enabled || view != View::Composite
    }

    /// Level count of the linear-depth chain for the current method and size: the engine's `sao`
    /// reads as many as its largest disc needs, every other method the lesson's 4.
    pub fn wanted_depth_levels(&self) -> u32 {
        if let Some(n) = self.depth_levels_override {
            return n.max(1);
        }
        if self.ao_params.method == AoMethod::Sao {
            let (hw, hh) = crate::ao::sao_lesson::half_size(self.width, self.height);
            crate::ao::methods::sao_depth_levels(hw, hh)
        } else {
            crate::config::SAO_DEPTH_LEVELS as u32
        }
    }

    /// Gives the lazily created AO targets the current size and level count (re-creating existing ones).
    fn configure_ao_targets(&mut self) -> Result<()> {
        let levels = self.wanted_depth_levels();
        self.ao.configure((self.width, self.height), levels)
    }

    /// Every GL texture the engine owns for AO now (half-size depth chain, AO, blur targets,
    /// method targets): empty until a frame runs AO, and after a resize while AO is off.
    pub fn ao_textures(&self) -> Vec<AoTextureInfo> {
        let mut out = Vec::new();
        if let Some(l) = self.ao.get() {
            out.push(AoTextureInfo::of(&l.tex_depth));
            out.push(AoTextureInfo::of(l.sao_texture()));
            out.push(AoTextureInfo::of(l.result_texture(true)));
        }
        out.extend(self.methods.textures().iter().map(|t| AoTextureInfo::of(t)));
        out
    }

    /// Applies changed camera planes or AO sample counts to the shaders (they are compile-time constants).
    pub fn sync_shader_constants(&mut self) -> Result<(), ProgramError> {
        self.methods.update_camera(&self.camera)?;
        self.methods.prepare(self.ao_params.method)?;
        if let Some(p) = &mut self.prog_restore_reversed {
            p.set_defines(&crate::ao::sao_lesson::camera_defines(&self.camera))?;
        }
        let (camera, params) = (self.camera, self.ao_params);
        if let Err(e) = self.configure_ao_targets() {
            log::error!("{e:#}");
        }
        self.ao
            .with_programs(|p| p.update_defines(&camera, &params))
            .unwrap_or(Ok(()))
    }

    /// Rebuilds shaders whose files changed; errors are returned, the last working programs stay.
    pub fn hot_reload(&mut self, force: bool) -> Vec<ProgramError> {
        let mut errors = self
            .ao
            .with_programs(|p| p.reload(force))
            .unwrap_or_default();
        errors.extend(self.methods.reload(force));
        for p in [
            &mut self.prog_standard,
            &mut self.prog_shadow,
            &mut self.prog_sky,
            &mut self.prog_bloom_bright,
            &mut self.prog_bloom_down,
            &mut self.prog_bloom_up,
            &mut self.prog_image,
            &mut self.prog_debug,
            &mut self.prog_composite_tint,
        ]
        .into_iter()
        .chain(self.prog_restore_reversed.as_mut())
        {
            if force || p.sources_changed() {
                if let Err(e) = p.reload() {
                    errors.push(e);
                }
            }
        }
        errors
    }

    fn aspect(&self) -> f32 {
        self.width as f32 / self.height as f32
    }

    fn light_direction(&self) -> Vec3 {
        Vec3::from(self.light.direction)
            .try_normalize()
            .unwrap_or(Vec3::Y)
    }

    /// Light's view-projection: an orthographic box around every object's bounds.
    fn shadow_matrix(&self) -> Mat4 {
        let (lo, hi) = self
            .objects
            .iter()
            .map(|o| o.bounds)
            .reduce(|a, b| (a.0.min(b.0), a.1.max(b.1)))
            .unwrap_or((Vec3::splat(-1.0), Vec3::splat(1.0)));
        let center = (lo + hi) * 0.5;
        let r = ((hi - lo).length() * 0.5).max(0.1);
        let dir = self.light_direction();
        let up = if dir.cross(Vec3::Y).length_squared() < 1e-6 {
            Vec3::Z
        } else {
            Vec3::Y
        };
        let view = Mat4::look_at_rh(center + dir * r * 2.0, center, up);
        Mat4::orthographic_rh_gl(-r, r, -r, r, 0.01, r * 4.0) * view
    }

    /// Draws the opaque (or transparent) objects whose bounds touch the frustum of `view_projection`.
    fn draw_objects(&self, prog: &ProgramObject, transparent: bool, view_projection: &Mat4) {
        self.meshes.bind();
        let planes = frustum_planes(view_projection);
        for o in self
            .objects
            .iter()
            .filter(|o| o.is_transparent() == transparent)
            .filter(|o| !self.frustum_culling || box_in_frustum(&planes, o.bounds))
        {
            prog.set_mat4(loc::MODEL, &o.model());
            prog.set_vec4(loc::OBJECT_COLOR, o.color.to_array());
            self.meshes.draw(&o.mesh);
        }
    }

    fn draw_shadow_map(&self, shadow: &Mat4) {
        self.fbo_shadow.bind();
        // The shadow map keeps the standard convention whatever the main depth buffer uses.
        if let Some(cc) = &self.clip_control {
            cc.set(false);
        }
        unsafe {
            self.gl.enable(glow::DEPTH_TEST);
            self.gl.depth_func(glow::LEQUAL);
            self.gl.depth_mask(true);
            self.gl.disable(glow::BLEND);
            // Both faces: the demo meshes are not all closed.
            self.gl.disable(glow::CULL_FACE);
            self.gl.clear_depth_f32(1.0);
            self.gl.clear(glow::DEPTH_BUFFER_BIT);
            self.gl.enable(glow::POLYGON_OFFSET_FILL);
            self.gl.polygon_offset(1.5, 2.0);
        }
        self.prog_shadow.set_mat4(loc::VIEW_PROJECTION, shadow);
        self.prog_shadow.use_program();
        self.draw_objects(&self.prog_shadow, false, shadow);
        unsafe { self.gl.disable(glow::POLYGON_OFFSET_FILL) };
    }

    fn setup_standard(&self, shadow: &Mat4) {
        let p = &self.prog_standard;
        p.set_mat4(loc::VIEW_PROJECTION, &self.scene_view_projection());
        p.set_mat4(loc::SHADOW_MATRIX, shadow);
        p.set_vec3(loc::LIGHT_DIRECTION, self.light_direction().to_array());
        p.set_vec3(loc::LIGHT_COLOR, self.light.color);
        p.set_vec3(loc::AMBIENT_COLOR, self.light.ambient);
        p.set_i32(loc::SHADOW_ENABLED, self.light.shadow as i32);
        p.set_i32(loc::AO_AMBIENT_ONLY, 0);
        p.use_program();
        if self.light.shadow {
            self.fbo_shadow
                .depth_texture()
                .unwrap()
                .bind(binding::SHADOW_MAP);
        } else {
            // A sampler2DShadow must not see a non-depth texture even when unused.
            self.fbo_shadow
                .depth_texture()
                .unwrap()
                .bind(binding::SHADOW_MAP);
        }
    }

    fn draw_opaque(&self, shadow: &Mat4) {
        self.fbo_main.bind();
        unsafe {
            self.gl.disable(glow::BLEND);
            self.gl.disable(glow::SCISSOR_TEST);
            // Some demo meshes are open (planes), so both faces are drawn.
            self.gl.disable(glow::CULL_FACE);
            self.gl.clear_color(0.0, 0.0, 0.0, 1.0);
        }
        self.begin_scene_depth_pass(true);
        unsafe {
            self.gl
                .clear(glow::COLOR_BUFFER_BIT | glow::DEPTH_BUFFER_BIT);
        }
        self.setup_standard(shadow);
        self.draw_objects(
            &self.prog_standard,
            false,
            &self.camera.view_projection(self.aspect()),
        );
        self.end_scene_depth_pass();
    }

    /// Depth only (the pre-pass of AO-on-ambient): the AO chain needs depth before lighting.
    fn draw_depth_prepass(&self) {
        self.fbo_main.bind();
        unsafe {
            self.gl.disable(glow::BLEND);
            self.gl.disable(glow::CULL_FACE);
            self.gl.clear_color(0.0, 0.0, 0.0, 1.0);
        }
        self.begin_scene_depth_pass(true);
        unsafe {
            self.gl
                .clear(glow::COLOR_BUFFER_BIT | glow::DEPTH_BUFFER_BIT);
            self.gl.color_mask(false, false, false, false);
        }
        self.prog_shadow
            .set_mat4(loc::VIEW_PROJECTION, &self.scene_view_projection());
        self.prog_shadow.use_program();
        self.draw_objects(
            &self.prog_shadow,
            false,
            &self.camera.view_projection(self.aspect()),
        );
        unsafe { self.gl.color_mask(true, true, true, true) };
        self.end_scene_depth_pass();
    }

    /// Lighting after the pre-pass, with occlusion applied to the ambient term only.
    fn draw_opaque_ao_ambient(&self, ao: &SaoLesson, shadow: &Mat4) {
        self.fbo_main.bind();
        unsafe {
            self.gl.disable(glow::BLEND);
            self.gl.disable(glow::CULL_FACE);
        }
        self.begin_scene_depth_pass(false);
        self.setup_standard(shadow);
        let p = &self.prog_standard;
        p.set_i32(loc::AO_AMBIENT_ONLY, 1);
        p.set_vec2(
            loc::INV_SCREEN_SIZE,
            [1.0 / self.width as f32, 1.0 / self.height as f32],
        );
        p.set_f32(loc::AO_POWER, self.ao_params.power);
        ao.result_texture(self.ao_params.blur)
            .bind(binding::AO_AMBIENT);
        self.draw_objects(p, false, &self.camera.view_projection(self.aspect()));
        unsafe { self.gl.depth_mask(true) };
        self.end_scene_depth_pass();
    }

    /// Blends the occlusion over the lit image: the lesson's swizzled blend, or tinted with a power.
    fn draw_ao_composite(&self, ao: &SaoLesson) {
        let params = &self.ao_params;
        if params.composite == CompositeMode::Blend && params.power == 1.0 {
            if params.method == AoMethod::Sao {
                // The engine's SAO leaves sky pixels out of the composite (the lesson's blends all).
                let farther = if self.depth_mode.reversed() {
                    glow::LESS
                } else {
                    glow::GREATER
                };
                ao.composite_geometry_only(
                    &self.meshes,
                    &self.fbo_main,
                    params.blur,
                    self.depth_mode.clear_value(),
                    farther,
                );
            } else {
                ao.composite(&self.meshes, &self.fbo_main, params.blur);
            }
            return;
        }
        let tint = if params.composite == CompositeMode::Tinted {
            params.tint
        } else {
            [0.0; 3]
        };
        let p = &self.prog_composite_tint;
        p.set_vec3(loc::AO_TINT, tint);
        p.set_f32(loc::AO_TINT_POWER, params.power);
        self.fbo_main.bind();
        unsafe {
            self.gl.disable(glow::CULL_FACE);
            self.gl.disable(glow::DEPTH_TEST);
            self.gl.enable(glow::BLEND);
            self.gl.blend_equation(glow::FUNC_ADD);
            self.gl
                .blend_func(glow::SRC_ALPHA, glow::ONE_MINUS_SRC_ALPHA);
        }
        p.use_program();
        ao.result_texture(params.blur).bind(0);
        self.meshes.draw_plane_xy();
        unsafe { self.gl.disable(glow::BLEND) };
    }

    fn draw_sky(&self) {
        self.fbo_main.bind();
        unsafe {
            self.gl.disable(glow::BLEND);
            self.gl.disable(glow::CULL_FACE);
        }
        self.begin_scene_depth_pass(false);
        if self.depth_mode.reversed() {
            // sky.vert puts the quad at clip z = w (window depth 1 = the far plane for the course's
            // convention); with reversed-Z the far plane is 0, so the window range is squeezed to 0.
            unsafe { self.gl.depth_range_f32(0.0, 0.0) };
        }
        let inv = self.camera.view_projection(self.aspect()).inverse();
        self.prog_sky.set_mat4(loc::INVERSE_VIEW_PROJECTION, &inv);
        self.prog_sky
            .set_vec3(loc::LIGHT_DIRECTION, self.light_direction().to_array());
        self.prog_sky.use_program();
        self.meshes.draw_plane_xy();
        unsafe {
            self.gl.depth_range_f32(0.0, 1.0);
            self.gl.depth_mask(true);
        }
        self.end_scene_depth_pass();
    }

    fn draw_transparent(&self, shadow: &Mat4) {
        if !self.objects.iter().any(|o| o.is_transparent()) {
            return;
        }
        self.fbo_main.bind();
        unsafe {
            self.gl.enable(glow::BLEND);
            self.gl.blend_equation(glow::FUNC_ADD);
            self.gl
                .blend_func(glow::SRC_ALPHA, glow::ONE_MINUS_SRC_ALPHA);
            self.gl.disable(glow::CULL_FACE);
        }
        self.begin_scene_depth_pass(false);
        self.setup_standard(shadow);
        self.draw_objects(
            &self.prog_standard,
            true,
            &self.camera.view_projection(self.aspect()),
        );
        unsafe { self.gl.depth_mask(true) };
        self.end_scene_depth_pass();
    }

    fn draw_bloom(&self) {
        if !self.bloom.enabled || self.fbo_bloom.is_empty() {
            return;
        }
        unsafe {
            self.gl.disable(glow::DEPTH_TEST);
            self.gl.disable(glow::CULL_FACE);
            self.gl.disable(glow::BLEND);
        }
        self.prog_bloom_bright
            .set_f32(loc::BLOOM_THRESHOLD, self.bloom.threshold);
        self.prog_bloom_bright.use_program();
        self.fbo_bloom[0].bind();
        self.fbo_main.color_texture().unwrap().bind(0);
        self.meshes.draw_plane_xy();
        self.prog_bloom_down.use_program();
        for i in 1..self.fbo_bloom.len() {
            self.fbo_bloom[i].bind();
            self.fbo_bloom[i - 1].color_texture().unwrap().bind(0);
            self.meshes.draw_plane_xy();
        }
        unsafe {
            self.gl.enable(glow::BLEND);
            self.gl.blend_func(glow::ONE, glow::ONE);
        }
        self.prog_bloom_up.use_program();
        for i in (1..self.fbo_bloom.len()).rev() {
            self.fbo_bloom[i - 1].bind();
            self.fbo_bloom[i].color_texture().unwrap().bind(0);
            self.meshes.draw_plane_xy();
        }
        unsafe { self.gl.disable(glow::BLEND) };
    }

    /// Binds the output: `None` = the default framebuffer (window) at the engine's size.
    fn bind_output(&self, target: Option<&FramebufferObject>) {
        match target {
            Some(f) => f.bind(),
            None => unsafe {
                self.gl.bind_framebuffer(glow::FRAMEBUFFER, None);
                self.gl
                    .viewport(0, 0, self.width as i32, self.height as i32);
            },
        }
        unsafe {
            self.gl.disable(glow::DEPTH_TEST);
            self.gl.disable(glow::CULL_FACE);
            self.gl.disable(glow::BLEND);
            self.gl.disable(glow::FRAMEBUFFER_SRGB);
            self.gl.disable(glow::DITHER);
        }
    }

    fn draw_image_processing(&self, target: Option<&FramebufferObject>) {
        self.bind_output(target);
        self.prog_image.set_mat3(loc::COLOR_MATRIX, &Mat3::IDENTITY);
        let bloom_on = self.bloom.enabled && !self.fbo_bloom.is_empty();
        self.prog_image.set_f32(
            loc::BLOOM_STRENGTH,
            if bloom_on { self.bloom.strength } else { 0.0 },
        );
        self.prog_image.use_program();
        self.fbo_main.color_texture().unwrap().bind(0);
        if bloom_on {
            self.fbo_bloom[0].color_texture().unwrap().bind(1);
        } else {
            self.black.bind(1);
        }
        self.meshes.draw_plane_xy();
    }

    /// Shows one AO buffer as grey (window and PNG of the debug views).
    fn draw_debug_view(
        &self,
        ao: &SaoLesson,
        target: Option<&FramebufferObject>,
        view: View,
        raw_values: bool,
    ) {
        self.bind_output(target);
        let (mode, tex, scale) = match view {
            View::LinearDepth => (0, &ao.tex_depth, 0.02),
            View::AoRaw => (1, ao.sao_texture(), 1.0),
            _ => (1, ao.result_texture(self.ao_params.blur), 1.0),
        };
        self.prog_debug.set_i32(loc::DEBUG_VIEW_MODE, mode);
        self.prog_debug
            .set_f32(loc::DEBUG_VIEW_SCALE, if raw_values { 1.0 } else { scale });
        self.prog_debug.use_program();
        tex.bind(0);
        self.meshes.draw_plane_xy();
    }

    /// Renders one frame into `target` (`None` = default framebuffer) showing `self.view`.
    pub fn render(&self, target: Option<&FramebufferObject>) {
        self.render_inner(target, self.view, false);
    }

    /// Passes of the last frame rendered with `collect_stats` on.
    pub fn last_stats(&self) -> Vec<PassStat> {
        self.stats.borrow().clone()
    }

    fn pass(&self, name: &'static str, group: &'static str, f: impl FnOnce()) {
        if !self.collect_stats {
            f();
            return;
        }
        unsafe { self.gl.finish() };
        let calls = self.meshes.draw_calls.get();
        let t = std::time::Instant::now();
        let cpu = process_cpu_seconds();
        f();
        unsafe { self.gl.finish() };
        let ms = t.elapsed().as_secs_f64() * 1e3;
        let cpu_ms = (process_cpu_seconds() - cpu) * 1e3;
        self.stats.borrow_mut().push(PassStat {
            name,
            group,
            ms,
            cpu_ms,
            draw_calls: self.meshes.draw_calls.get() - calls,
        });
    }

    /// One frame. Passes whose output is not used are skipped: no shadow pass without a
    /// shadow-casting light, no AO passes with AO off, only restore + down-sampling for the
    /// linear-depth view, no transparent pass without transparent objects, no bloom chain when off.
    fn render_inner(&self, target: Option<&FramebufferObject>, view: View, raw_values: bool) {
        self.stats.borrow_mut().clear();
        let shadow = self.shadow_matrix();
        // The AO targets are created here on the first frame that needs them; if GL cannot
        // allocate them the frame is drawn without AO (and says why).
        let ao_chain = if self.needs_ao(view) {
            match self.ao.get_or_create() {
                Ok(ao) => Some(ao),
                Err(e) => {
                    log::error!("AO skipped: {e:#}");
                    None
                }
            }
        } else {
            None
        };
        if self.light.shadow && view == View::Composite {
            self.pass("shadow map", "shadow", || self.draw_shadow_map(&shadow));
        }
        let ambient_only = view == View::Composite
            && ao_chain.is_some()
            && self.ao_params.enabled
            && self.ao_params.composite == CompositeMode::AmbientOnly;
        if ambient_only {
            self.pass("depth pre-pass", "opaque", || self.draw_depth_prepass());
        } else {
            self.pass("opaque", "opaque", || self.draw_opaque(&shadow));
        }
        if let Some(ao) = ao_chain {
            let depth = self.fbo_main.depth_texture().unwrap();
            let m = &self.meshes;
            self.pass("sao restore depth", "ao", || {
                self.restore_linear_depth(ao, depth)
            });
            self.pass("sao down sampling", "ao", || ao.down_sample(m));
            let method = self.ao_params.method;
            if view != View::LinearDepth && method == AoMethod::SaoLesson {
                self.pass("sao", "ao", || {
                    ao.compute_sao(m, &self.camera, &self.ao_params)
                });
                if self.ao_params.blur && view != View::AoRaw {
                    self.pass("sao blur", "ao", || ao.blur(m));
                }
            } else if view != View::LinearDepth {
                let methods = &self.methods;
                self.pass(method.name(), "ao", || {
                    methods.compute(method, ao, m, &self.camera, &self.ao_params)
                });
                if self.ao_params.blur && view != View::AoRaw {
                    self.pass("separable blur", "ao", || {
                        methods.blur_method(method, ao, m)
                    });
                }
            }
            if ambient_only {
                self.pass("opaque", "opaque", || {
                    self.draw_opaque_ao_ambient(ao, &shadow)
                });
            } else if view == View::Composite {
                self.pass("sao composite", "ao", || self.draw_ao_composite(ao));
            }
        }
        if view != View::Composite {
            if let Some(ao) = ao_chain {
                self.pass("debug view", "post", || {
                    self.draw_debug_view(ao, target, view, raw_values)
                });
            }
            return;
        }
        self.pass("sky", "sky", || self.draw_sky());
        if self.objects.iter().any(|o| o.is_transparent()) {
            self.pass("transparent", "transparent", || {
                self.draw_transparent(&shadow)
            });
        }
        if self.bloom.enabled && !self.fbo_bloom.is_empty() {
            self.pass("bloom", "bloom", || self.draw_bloom());
        }
        self.pass("image processing", "post", || {
            self.draw_image_processing(target)
        });
    }

    /// Renders into the headless RGBA8 output and reads it back (rows top-down).
    pub fn render_image(&mut self) -> Result<image::RgbaImage> {
        self.methods.prepare(self.ao_params.method)?;
        self.configure_ao_targets()?;
        if self.fbo_output.is_none() {
            let tex = Rc::new(Texture::new(
                &self.gl,
                TextureDesc::target("FBO(output)", self.width, self.height, glow::RGBA8),
            )?);
            self.fbo_output = Some(FramebufferObject::new(&self.gl, Some(tex), None, 0, 0)?);
        }
        let out = self.fbo_output.as_ref().unwrap();
        self.render(Some(out));
        let img = read_rgba8(&self.gl, Some(out.id()), self.width, self.height);
        if let Some(e) = crate::gl::take_error(&self.gl) {
            bail!("{e} while rendering");
        }
        Ok(img)
    }

    /// Renders `view` as raw values at the output size (rows top-down): linear depth in metres or
    /// ambient visibility (1 = open). For `Composite`, the luminance-free RGB is not available: use `render_image`.
    pub fn render_values(&mut self, view: View) -> Result<Vec<f32>> {
        self.methods.prepare(self.ao_params.method)?;
        self.configure_ao_targets()?;
        if view == View::Composite {
            bail!("the composite view has colour, not values: write it as PNG");
        }
        if self.fbo_values.is_none() {
            let tex = Rc::new(Texture::new(
                &self.gl,
                TextureDesc::target("FBO(values)", self.width, self.height, glow::R32F),
            )?);
            self.fbo_values = Some(FramebufferObject::new(&self.gl, Some(tex), None, 0, 0)?);
        }
        let fbo = self.fbo_values.as_ref().unwrap();
        self.render_inner(Some(fbo), view, true);
        let mut v = fbo.color_texture().unwrap().read_f32(0, 1);
        flip_rows(&mut v, self.width as usize, self.height as usize);
        if let Some(e) = crate::gl::take_error(&self.gl) {
            bail!("{e} while rendering");
        }
        Ok(v)
    }

    /// Main depth → linear depth level 0, with the restore that matches the depth convention.
    fn restore_linear_depth(&self, ao: &SaoLesson, depth: &Texture) {
        match (&self.prog_restore_reversed, self.depth_mode.reversed()) {
            (Some(p), true) => ao.restore_depth_with(p, &self.meshes, depth),
            _ => ao.restore_depth(&self.meshes, depth),
        }
    }

    /// Runs the frame's passes up to the AO chain without drawing the output (tests inspect buffers).
    pub fn render_to_ao(&self) {
        let shadow = self.shadow_matrix();
        if self.light.shadow {
            self.draw_shadow_map(&shadow);
        }
        self.draw_opaque(&shadow);
        let ao: &SaoLesson = &self.ao;
        self.restore_linear_depth(ao, self.fbo_main.depth_texture().unwrap());
        ao.down_sample(&self.meshes);
        ao.compute_sao(&self.meshes, &self.camera, &self.ao_params);
        if self.ao_params.blur {
            ao.blur(&self.meshes);
        }
    }

    /// Triangles of every opaque object in world space (for the ray-traced reference).
    pub fn world_triangles(&self) -> Vec<[Vec3; 3]> {
        let mut out = Vec::new();
        for o in &self.objects {
            let m = o.model();
            if let Some(d) = self.meshes.data(&o.name) {
                out.extend(d.triangles().map(|t| t.map(|p| m.transform_point3(p))));
            }
        }
        out
    }
}

/// One texture the engine owns for AO (`Engine::ao_textures`).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct AoTextureInfo {
    pub name: String,
    pub width: u32,
    pub height: u32,
    pub levels: u32,
    pub internal_format: u32,
    /// Bytes of storage, all levels.
    pub bytes: u64,
}

impl AoTextureInfo {
    fn of(t: &Texture) -> AoTextureInfo {
        let d = t.desc();
        let texel = match d.internal_format {
            glow::R8 => 1,
            glow::R16F | glow::RG8 => 2,
            glow::R32F | glow::RG16F | glow::RGBA8 => 4,
            glow::RG32F | glow::RGBA16F => 8,
            _ => 16,
        };
        let bytes = (0..t.levels())
            .map(|l| {
                let (w, h) = t.size_at(l);
                w as u64 * h as u64 * texel
            })
            .sum();
        AoTextureInfo {
            name: d.name.clone(),
            width: d.width,
            height: d.height,
            levels: t.levels(),
            internal_format: d.internal_format,
            bytes,
        }
    }
}

/// The six planes (a, b, c, d with a·x + b·y + c·z + d ≥ 0 inside) of a view-projection's frustum.
pub fn frustum_planes(m: &Mat4) -> [Vec4; 6] {
    let r = |i: usize| m.row(i);
    [
        r(3) + r(0),
        r(3) - r(0),
        r(3) + r(1),
        r(3) - r(1),
        r(3) + r(2),
        r(3) - r(2),
    ]
}

/// Conservative test: false only when the box lies entirely outside one plane.
pub fn box_in_frustum(planes: &[Vec4; 6], (lo, hi): (Vec3, Vec3)) -> bool {
    planes.iter().all(|p| {
        // The box corner farthest along the plane normal.
        let c = Vec3::new(
            if p.x >= 0.0 { hi.x } else { lo.x },
            if p.y >= 0.0 { hi.y } else { lo.y },
            if p.z >= 0.0 { hi.z } else { lo.z },
        );
        p.truncate().dot(c) + p.w >= 0.0
    })
}

fn world_bounds(data: &MeshData, m: &Mat4) -> (Vec3, Vec3) {
    let (lo, hi) = data.bounds().unwrap_or((Vec3::ZERO, Vec3::ZERO));
    let mut b = (Vec3::splat(f32::MAX), Vec3::splat(f32::MIN));
    for i in 0..8 {
        let c = Vec3::new(
            if i & 1 == 0 { lo.x } else { hi.x },
            if i & 2 == 0 { lo.y } else { hi.y },
            if i & 4 == 0 { lo.z } else { hi.z },
        );
        let p = m.transform_point3(c);
        b = (b.0.min(p), b.1.max(p));
    }
    b
}

/// The main FBO: RGBA16F colour + the mode's depth format, compare mode off (the AO passes read raw depth).
fn create_main_fbo(gl: &Gl, width: u32, height: u32, mode: DepthMode) -> Result<FramebufferObject> {
    let color = Rc::new(Texture::new(
        gl,
        TextureDesc::target("FBO(main color)", width, height, glow::RGBA16F)
            .filter(glow::LINEAR, glow::LINEAR),
    )?);
    let depth = Rc::new(Texture::new(
        gl,
        TextureDesc::target("FBO(main depth)", width, height, mode.internal_format())
            .compare(false),
    )?);
    FramebufferObject::new(gl, Some(color), Some(depth), 0, 0)
}

fn create_bloom_fbos(gl: &Gl, width: u32, height: u32) -> Result<Vec<FramebufferObject>> {
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

/// Reads RGBA8 pixels of a framebuffer (`None` = default) and returns them top-down.
pub fn read_rgba8(
    gl: &glow::Context,
    fbo: Option<glow::Framebuffer>,
    width: u32,
    height: u32,
) -> image::RgbaImage {
    let mut data = vec![0u8; (width * height * 4) as usize];
    unsafe {
        gl.bind_framebuffer(glow::READ_FRAMEBUFFER, fbo);
        if fbo.is_none() {
            gl.read_buffer(glow::BACK);
        }
        gl.pixel_store_i32(glow::PACK_ALIGNMENT, 1);
        gl.read_pixels(
            0,
            0,
            width as i32,
            height as i32,
            glow::RGBA,
            glow::UNSIGNED_BYTE,
            glow::PixelPackData::Slice(Some(&mut data)),
        );
        gl.bind_framebuffer(glow::READ_FRAMEBUFFER, None);
    }
    flip_rows(&mut data, (width * 4) as usize, height as usize);
    image::RgbaImage::from_raw(width, height, data).expect("buffer size matches")
}

/// GL rows are bottom-up; images are top-down.
pub fn flip_rows<T: Copy>(data: &mut [T], row_len: usize, rows: usize) {
    for y in 0..rows / 2 {
        let (a, b) = data.split_at_mut((rows - 1 - y) * row_len);
        a[y * row_len..(y + 1) * row_len].swap_with_slice(&mut b[..row_len]);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn frustum_test_keeps_visible_boxes_and_drops_those_behind() {
        let cam = Camera {
            eye: Vec3::ZERO,
            target: Vec3::new(0.0, 0.0, -1.0),
            ..Default::default()
        };
        let planes = frustum_planes(&cam.view_projection(1.0));
        let unit = |c: Vec3| (c - Vec3::splat(0.5), c + Vec3::splat(0.5));
        assert!(box_in_frustum(&planes, unit(Vec3::new(0.0, 0.0, -5.0))));
        assert!(
            !box_in_frustum(&planes, unit(Vec3::new(0.0, 0.0, 5.0))),
            "behind the camera"
        );
        assert!(
            !box_in_frustum(&planes, unit(Vec3::new(50.0, 0.0, -5.0))),
            "far to the right"
        );
        assert!(
            !box_in_frustum(&planes, unit(Vec3::new(0.0, 0.0, -2000.0))),
            "beyond the far plane"
        );
        // A box around the camera straddles every plane: kept.
        assert!(box_in_frustum(
            &planes,
            (Vec3::splat(-10.0), Vec3::splat(10.0))
        ));
    }
}
