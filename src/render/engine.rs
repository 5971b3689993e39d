//! `Engine`: owns the scene, the render targets and the passes, and renders a frame in the course's
//! order: shadow map → main FBO (opaque) → ambient occlusion → sky → transparent → bloom → image
//! processing into the output (the window's default framebuffer or a headless FBO). Passes whose
//! output a frame does not use are skipped.

use super::frame::Frame;
use super::main_fbo::create_main_fbo;
use super::passes::surface::SurfacePasses;
use super::passes::{bloom::BloomPass, opaque::LitPass, post::PostPass, shadow, sky::SkyPass};
use super::passes::{shadow::ShadowPass, transparent};
use super::stats::{AoTextureInfo, PassStat, PassTimer};
use super::view::View;
use crate::ao::guard_band::GuardTargets;
use crate::ao::temporal::{self, TemporalAccumulation};
use crate::ao::upsample::UpsampleInputs;
use crate::ao::{
    composite, AoMethod, AoPipeline, AoResolution, AoSettings, AoTargets, CompositeMode,
};
use crate::gl::clip_control::ClipControl;
use crate::gl::mesh::MeshData;
use crate::gl::readback::{flip_rows, read_rgba8};
use crate::gl::{
    check_error, FramebufferObject, Gl, MeshBuffer, ProgramError, Texture, TextureDesc,
};
use crate::math::frustum::transformed_bounds;
use crate::math::{Camera, DepthMode};
use crate::res::ResDirs;
use crate::scene::game_object::GameObject;
use crate::scene::{BloomDesc, LightDesc, SceneDesc};
use anyhow::{anyhow, bail, Context as _, Result};
use glam::{Mat4, Vec3, Vec4};
use std::cell::RefCell;
use std::rc::Rc;

mod ao_chain;
mod guard;
mod surface;
mod user_method;

pub struct Engine {
    gl: Gl,
    res: ResDirs,
    pub meshes: MeshBuffer,
    pub objects: Vec<GameObject>,
    pub camera: Camera,
    pub light: LightDesc,
    pub bloom: BloomDesc,
    pub ao_settings: AoSettings,
    pub view: View,
    shadow: ShadowPass,
    /// Back-face depth and surface normals, each run only when the AO settings read it.
    surface: SurfacePasses,
    /// The AO targets of the view widened by a guard band (`[ao] guard_band`).
    guard_targets: GuardTargets,
    lit: LitPass,
    sky: SkyPass,
    bloom_pass: BloomPass,
    post: PostPass,
    /// The AO passes; their targets are created on the first frame that runs AO.
    pub ao: AoPipeline,
    /// The screen-space methods' occlusion accumulated over frames (`--accumulate` > 1).
    pub temporal: TemporalAccumulation,
    width: u32,
    height: u32,
    pub fbo_main: FramebufferObject,
    /// Main depth buffer convention (`[output] depth`, `--depth`).
    depth_mode: DepthMode,
    /// Loaded once reversed-Z is first used; from then on every pass states its clip range.
    clip_control: Option<ClipControl>,
    /// Headless output (RGBA8) and the R32F target of value read-back, created on demand.
    fbo_output: Option<FramebufferObject>,
    fbo_values: Option<FramebufferObject>,
    /// Forces the linear-depth chain's level count (comparisons in tests and benchmarks); `None` = per
    /// method. Applied by `render_image`, `render_values`, `resize` and `sync_shader_constants`.
    pub depth_levels_override: Option<u32>,
    /// When on, each pass is bracketed by glFinish and timed (slower; for `--stats` and benchmarks).
    pub collect_stats: bool,
    /// Objects whose bounds miss the frustum are not drawn (on by default; `bench --skips` turns it
    /// off to measure what it saves).
    pub frustum_culling: bool,
    stats: RefCell<Vec<PassStat>>,
    pass_timer: PassTimer,
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
        let camera = scene.camera.camera();
        let (ao_settings, notes) = scene.ao.sanitized();
        for n in notes {
            log::warn!("{n}");
        }
        let ao = AoPipeline::new(
            gl,
            &res,
            &camera,
            &ao_settings,
            (width, height),
            crate::ao::targets::SAO_DEPTH_LEVELS,
        )?;
        let temporal = TemporalAccumulation::new(gl, &res, &camera)?;
        let mut meshes = MeshBuffer::new(gl)?;
        let mut objects = Vec::new();
        for (i, o) in scene.objects.iter().enumerate() {
            let what = || format!("scene object {} ({})", i + 1, o.mesh);
            let path = scene.mesh_path(&o.mesh, &res).with_context(what)?;
            let mesh = meshes.load_model(&o.mesh, &path).with_context(what)?;
            let data = meshes
                .data(&o.mesh)
                .ok_or_else(|| anyhow!("{}: mesh data missing after loading", what()))?;
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
        for o in objects.iter_mut() {
            o.mesh = meshes
                .get(&o.name)
                .ok_or_else(|| anyhow!("mesh {} missing after loading", o.name))?;
        }
        let fbo_main = create_main_fbo(gl, width, height, DepthMode::D32)?;
        let mut engine = Engine {
            gl: gl.clone(),
            meshes,
            objects,
            camera,
            light: scene.light.clone(),
            bloom: scene.bloom.clone(),
            ao_settings,
            view: View::Composite,
            shadow: ShadowPass::new(gl, &res)?,
            surface: SurfacePasses::new(gl, &res)?,
            guard_targets: GuardTargets::default(),
            lit: LitPass::new(gl, &res)?,
            sky: SkyPass::new(gl, &res)?,
            bloom_pass: BloomPass::new(gl, &res, (width, height))?,
            post: PostPass::new(gl, &res)?,
            ao,
            temporal,
            width,
            height,
            fbo_main,
            depth_mode: DepthMode::D32,
            clip_control: None,
            fbo_output: None,
            fbo_values: None,
            depth_levels_override: None,
            collect_stats: false,
            frustum_culling: true,
            stats: Default::default(),
            pass_timer: PassTimer::new(gl),
            res,
        };
        engine.set_depth_mode(scene.output.depth)?;
        engine.configure_ao_targets()?;
        check_error(gl, "creating the engine")?;
        Ok(engine)
    }

    /// `new` at the scene's `[output]` size (headless renders).
    pub fn at_output_size(gl: &Gl, res: ResDirs, scene: &SceneDesc) -> Result<Engine> {
        Engine::new(gl, res, scene, scene.output.width, scene.output.height)
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
        if mode.reversed() && self.clip_control.is_none() {
            self.clip_control = Some(ClipControl::get().map_err(|e| anyhow!(e))?);
        }
        self.prepare_restores(mode, &self.ao_settings.clone())?;
        if mode != self.depth_mode {
            self.fbo_main = create_main_fbo(&self.gl, self.width, self.height, mode)?;
            self.depth_mode = mode;
        }
        Ok(())
    }

    /// Re-creates size-dependent targets. A 0×0 size (minimised window) keeps the old targets.
    pub fn resize(&mut self, width: u32, height: u32) -> Result<()> {
        if width == 0 || height == 0 || (width, height) == (self.width, self.height) {
            return Ok(());
        }
        self.fbo_main = create_main_fbo(&self.gl, width, height, self.depth_mode)?;
        self.bloom_pass.resize(&self.gl, (width, height))?;
        self.fbo_output = None;
        self.fbo_values = None;
        self.width = width;
        self.height = height;
        // With AO off the AO targets are not worth keeping at the new size: the next frame that
        // needs them creates them.
        if !self.needs_ao(self.view) {
            self.ao.release_targets();
            self.temporal.release_targets();
            self.surface.release_targets();
            self.guard_targets.release();
        }
        self.configure_ao_targets()
    }

    /// Whether a frame showing `view` runs the AO chain.
    fn needs_ao(&self, view: View) -> bool {
        self.ao_settings.enabled || view != View::Composite
    }

    /// Level count of the linear-depth chain for the current method and size: the engine's `sao`
    /// reads as many as its largest disc needs, every other method the lesson's 4.
    pub fn wanted_depth_levels(&self) -> u32 {
        match self.depth_levels_override {
            Some(n) => n.max(1),
            None => self.ao.wanted_depth_levels(
                self.ao_settings.method,
                self.size(),
                self.ao_settings.effective_resolution(),
            ),
        }
    }

    /// Gives the lazily created AO targets the current size and level count (re-creating existing ones).
    fn configure_ao_targets(&mut self) -> Result<()> {
        let levels = self.wanted_depth_levels();
        let resolution = self.ao_settings.effective_resolution();
        self.ao.targets.configure(self.size(), levels, resolution)
    }

    /// The AO targets, created if no frame created them yet (tests and tools inspect them).
    pub fn ao_targets(&self) -> Result<&AoTargets> {
        self.ao.targets()
    }

    /// Every GL texture the engine owns for AO now: empty until a frame runs AO, and after a resize
    /// while AO is off.
    pub fn ao_textures(&self) -> Vec<AoTextureInfo> {
        self.ao
            .textures()
            .iter()
            .chain(self.surface.textures().iter())
            .chain(self.guard_targets.textures().iter())
            .chain(self.temporal.textures().iter())
            .map(|t| AoTextureInfo::of(t))
            .collect()
    }

    /// Builds the depth restores `mode` and `settings` need: the AO size's, and for the engine's
    /// methods the one-to-one restore of the depth they draw at the AO size themselves (`guard`).
    fn prepare_restores(&mut self, mode: DepthMode, settings: &AoSettings) -> Result<()> {
        let camera = self.camera;
        let resolution = settings.effective_resolution();
        self.ao.prepare_depth_mode(mode, resolution, &camera)?;
        if settings.method.info().engine_chain {
            self.ao
                .prepare_depth_mode(mode, AoResolution::Full, &camera)?;
        }
        Ok(())
    }

    /// Applies changed camera planes, AO method or sample counts to the shaders (compile-time
    /// constants) and the targets' level count.
    pub fn sync_shader_constants(&mut self) -> Result<()> {
        let (camera, settings) = (self.camera, self.ao_settings);
        self.ao.prepare(settings.method, &camera, &settings)?;
        self.prepare_restores(self.depth_mode, &settings)?;
        self.ao.update_defines(&camera, &settings)?;
        self.temporal.update_defines(&camera)?;
        self.configure_ao_targets()
    }

    /// Rebuilds shaders whose files changed; errors are returned, the last working programs stay.
    pub fn hot_reload(&mut self, force: bool) -> Vec<ProgramError> {
        let mut errors = self.ao.reload(force);
        let [b0, b1, b2] = self.bloom_pass.programs_mut();
        let [t0, t1] = self.temporal.programs_mut();
        let mut programs = self.surface.programs_mut();
        programs.extend([
            &mut self.lit.standard,
            &mut self.shadow.program,
            &mut self.sky.program,
            &mut self.post.image,
            &mut self.post.debug,
            t0,
            t1,
            b0,
            b1,
            b2,
        ]);
        for p in programs {
            if force || p.sources_changed() {
                if let Err(e) = p.reload() {
                    errors.push(e);
                }
            }
        }
        errors
    }

    fn frame(&self) -> Frame<'_> {
        Frame {
            gl: &self.gl,
            meshes: &self.meshes,
            objects: &self.objects,
            camera: &self.camera,
            light: &self.light,
            depth_mode: self.depth_mode,
            clip_control: self.clip_control.as_ref(),
            size: self.size(),
            frustum_culling: self.frustum_culling,
        }
    }

    /// Renders one frame into `target` (`None` = default framebuffer) showing `self.view`.
    pub fn render(&self, target: Option<&FramebufferObject>) -> Result<()> {
        self.render_inner(target, self.view, false)
    }

    /// Passes of the last frame rendered with `collect_stats` on.
    pub fn last_stats(&self) -> Vec<PassStat> {
        self.stats.borrow().clone()
    }

    /// Runs one pass, timed by `PassTimer` (glFinish around it) when `collect_stats` is on.
    fn pass<T>(&self, name: &'static str, group: &'static str, f: impl FnOnce() -> T) -> T {
        if !self.collect_stats {
            return f();
        }
        let calls = self.meshes.draw_calls.get();
        let (out, t) = self.pass_timer.time(&self.gl, f);
        self.stats.borrow_mut().push(PassStat {
            name,
            group,
            ms: t.ms,
            clock: t.clock,
            wall_ms: t.wall_ms,
            cpu_ms: t.cpu_ms,
            draw_calls: self.meshes.draw_calls.get() - calls,
        });
        out
    }

    /// One frame. Passes whose output is not used are skipped: no shadow pass without a
    /// shadow-casting light, no AO passes with AO off, only restore + down-sampling for the
    /// linear-depth view, no transparent pass without transparent objects, no bloom chain when off.
    fn render_inner(
        &self,
        target: Option<&FramebufferObject>,
        view: View,
        raw_values: bool,
    ) -> Result<()> {
        self.stats.borrow_mut().clear();
        if view == View::SecondLayerDepth && !self.ao_settings.uses_second_layer() {
            bail!(
                "the {} view shows vbao's second depth layer: use --method vbao --layers 2 \
                 ([ao] layers = 2)",
                view.name()
            );
        }
        let f = self.frame();
        let shadow_matrix = shadow::shadow_matrix(&f);
        let ao_targets = if self.needs_ao(view) {
            Some(self.ao.targets()?)
        } else {
            None
        };
        let settings = &self.ao_settings;
        if self.light.shadow && view == View::Composite {
            self.pass("shadow map", "shadow", || {
                self.shadow.draw(&f, &shadow_matrix)
            });
        }
        let ambient_only = view == View::Composite
            && ao_targets.is_some()
            && settings.enabled
            && settings.composite == CompositeMode::AmbientOnly;
        if ambient_only {
            self.pass("depth pre-pass", "opaque", || {
                self.lit
                    .draw_depth_prepass(&f, &self.fbo_main, &self.shadow.program)
            });
        } else {
            self.pass("opaque", "opaque", || {
                self.lit
                    .draw_opaque(&f, &self.fbo_main, &self.shadow, &shadow_matrix)
            });
        }
        if let Some(targets) = ao_targets {
            self.run_ao(&f, targets, view)?;
            self.accumulate_over_frames(targets, view)?;
        }
        let blend_while_upsampling = view == View::Composite
            && !ambient_only
            && ao_targets.is_some_and(|t| self.needs_upsample(t, view));
        if let (true, Some(targets)) = (blend_while_upsampling, ao_targets) {
            self.pass("bilateral composite", "ao", || {
                self.draw_bilateral_composite(targets)
            })?;
        } else if let Some(targets) = ao_targets {
            let occlusion = self.full_size_occlusion(targets, view)?;
            let occlusion = occlusion.as_ref();
            if ambient_only {
                self.pass("opaque", "opaque", || {
                    self.lit.draw_ao_ambient(
                        &f,
                        &self.fbo_main,
                        &self.shadow,
                        &shadow_matrix,
                        occlusion,
                        settings.power,
                    )
                });
            } else if view == View::Composite {
                let label = settings.method.info().composite_label;
                self.pass(label, "ao", || self.draw_ao_composite(occlusion));
            }
            if view != View::Composite {
                let second = self.second_layer_depth();
                let tex = match view {
                    View::LinearDepth => &targets.tex_depth,
                    View::SecondLayerDepth => second
                        .as_deref()
                        .ok_or_else(|| anyhow!("the second depth layer was not drawn"))?,
                    View::AoRaw => targets.sao_texture(),
                    _ => occlusion,
                };
                self.pass("debug view", "post", || {
                    self.post.draw_debug(
                        &self.gl,
                        &self.meshes,
                        target,
                        self.size(),
                        view,
                        tex,
                        raw_values,
                    )
                });
                return check_error(&self.gl, "rendering");
            }
        }
        self.pass("sky", "sky", || self.sky.draw(&f, &self.fbo_main));
        if transparent::needed(&f) {
            self.pass("transparent", "transparent", || {
                transparent::draw(&f, &self.lit, &self.fbo_main, &self.shadow, &shadow_matrix)
            });
        }
        let main_color = self.main_color()?;
        let bloom_on = self.bloom_pass.active(&self.bloom);
        if bloom_on {
            self.pass("bloom", "bloom", || {
                self.bloom_pass
                    .draw(&self.gl, &self.meshes, main_color, &self.bloom)
            });
        }
        let bloom = self
            .bloom_pass
            .result()
            .filter(|_| bloom_on)
            .map(|t| (t.as_ref(), self.bloom.strength));
        self.pass("image processing", "post", || {
            self.post.draw_image(
                &self.gl,
                &self.meshes,
                target,
                self.size(),
                main_color,
                bloom,
            )
        });
        check_error(&self.gl, "rendering")
    }

    fn main_color(&self) -> Result<&Rc<Texture>> {
        self.fbo_main
            .color_texture()
            .ok_or_else(|| anyhow!("the main FBO has no colour texture"))
    }

    /// The occlusion at the main size for the composite and the AO view: the engine's methods at half
    /// size are up-sampled depth-aware; the lesson's SAO keeps the course's linear filter, and
    /// full-size AO needs nothing.
    fn full_size_occlusion(&self, targets: &AoTargets, view: View) -> Result<Rc<Texture>> {
        if !self.needs_upsample(targets, view) {
            return Ok(targets.result_texture(self.ao_settings.blur).clone());
        }
        let inputs = self.upsample_inputs(targets)?;
        self.pass("bilateral upsample", "ao", || {
            self.ao.upsample.run(&self.gl, &self.meshes, &inputs)
        })
    }

    /// Whether `view` shows the AO up-sampled from half size (the engine's methods; the lesson's SAO
    /// keeps the course's linear filter, the raw view shows the half-size texels as they are).
    fn needs_upsample(&self, targets: &AoTargets, view: View) -> bool {
        targets.size() != self.size()
            && self.ao_settings.method.info().engine_chain
            && view != View::AoRaw
            && !view.is_depth()
    }

    fn upsample_inputs<'a>(&'a self, targets: &'a AoTargets) -> Result<UpsampleInputs<'a>> {
        Ok(UpsampleInputs {
            occlusion: targets.result_texture(self.ao_settings.blur),
            ao_depth: &targets.tex_depth,
            main_depth: self
                .fbo_main
                .depth_texture()
                .ok_or_else(|| anyhow!("the main FBO has no depth texture"))?,
            camera: &self.camera,
            mode: self.depth_mode,
        })
    }

    /// The blended composites of half-size AO: up-sampled and blended in one pass.
    fn draw_bilateral_composite(&self, targets: &AoTargets) -> Result<()> {
        let s = &self.ao_settings;
        let tint = if s.composite == CompositeMode::Tinted {
            s.tint
        } else {
            [0.0; 3]
        };
        let inputs = self.upsample_inputs(targets)?;
        let (gl, meshes, main) = (&self.gl, &self.meshes, &self.fbo_main);
        self.ao
            .upsample
            .composite(gl, meshes, &inputs, main, tint, s.power);
        Ok(())
    }

    /// Blends the occlusion over the lit image: the lesson's swizzled blend (the engine's SAO leaves
    /// sky pixels out), or tinted with a power.
    fn draw_ao_composite(&self, occlusion: &Texture) {
        let s = &self.ao_settings;
        let (gl, meshes, main) = (&self.gl, &self.meshes, &self.fbo_main);
        if s.composite == CompositeMode::Blend && s.power == 1.0 {
            let simple = &self.ao.composite_simple;
            if s.method.info().blend_leaves_sky {
                let farther = if self.depth_mode.reversed() {
                    glow::LESS
                } else {
                    glow::GREATER
                };
                let sky = self.depth_mode.clear_value();
                composite::blend_geometry_only(gl, simple, occlusion, main, meshes, sky, farther);
            } else {
                composite::blend(gl, simple, occlusion, main, meshes);
            }
            return;
        }
        let tint = if s.composite == CompositeMode::Tinted {
            s.tint
        } else {
            [0.0; 3]
        };
        composite::tinted(
            gl,
            &self.ao.composite_tint,
            occlusion,
            main,
            meshes,
            tint,
            s.power,
        );
    }

    /// Renders into the headless RGBA8 output and reads it back (rows top-down).
    pub fn render_image(&mut self) -> Result<image::RgbaImage> {
        self.sync_shader_constants()?;
        if self.fbo_output.is_none() {
            let tex = Rc::new(Texture::new(
                &self.gl,
                TextureDesc::target("FBO(output)", self.width, self.height, glow::RGBA8),
            )?);
            self.fbo_output = Some(FramebufferObject::new(&self.gl, Some(tex), None, 0, 0)?);
        }
        let out = self.fbo_output.as_ref().expect("created above");
        self.render(Some(out))?;
        let img = read_rgba8(&self.gl, Some(out.id()), self.width, self.height);
        check_error(&self.gl, "reading the frame back")?;
        Ok(img)
    }

    /// Renders `view` as raw values at the output size (rows top-down): linear depth in metres or
    /// ambient visibility (1 = open). `Composite` has colour, not values: use `render_image`.
    pub fn render_values(&mut self, view: View) -> Result<Vec<f32>> {
        if view == View::Composite {
            bail!("the composite view has colour, not values: write it as PNG");
        }
        self.sync_shader_constants()?;
        if self.fbo_values.is_none() {
            let tex = Rc::new(Texture::new(
                &self.gl,
                TextureDesc::target("FBO(values)", self.width, self.height, glow::R32F),
            )?);
            self.fbo_values = Some(FramebufferObject::new(&self.gl, Some(tex), None, 0, 0)?);
        }
        let fbo = self.fbo_values.as_ref().expect("created above");
        self.render_inner(Some(fbo), view, true)?;
        let tex = fbo
            .color_texture()
            .ok_or_else(|| anyhow!("the value target has no colour texture"))?;
        let mut v = tex.read_f32(0, 1);
        flip_rows(&mut v, self.width as usize, self.height as usize);
        check_error(&self.gl, "reading values back")?;
        Ok(v)
    }

    /// Runs the frame's passes up to the AO chain (blur included when on) without drawing the
    /// output: tests inspect the AO buffers.
    pub fn render_to_ao(&self) -> Result<()> {
        let f = self.frame();
        let shadow_matrix = shadow::shadow_matrix(&f);
        if self.light.shadow {
            self.shadow.draw(&f, &shadow_matrix);
        }
        self.lit
            .draw_opaque(&f, &self.fbo_main, &self.shadow, &shadow_matrix);
        let targets = self.ao.targets()?;
        self.run_ao(&f, targets, View::Ao)?;
        self.accumulate_over_frames(targets, View::Ao)?;
        check_error(&self.gl, "rendering the AO chain")
    }

    /// Blends the frame's occlusion with the previous frames' (`ao::temporal`) when the settings
    /// accumulate; not in the depth views, nor in the raw view of a screen-space method, which shows
    /// one pass (`rtao`'s raw view shows its unblurred mean, as the GPU reference reads it).
    fn accumulate_over_frames(&self, targets: &AoTargets, view: View) -> Result<()> {
        let s = &self.ao_settings;
        let rtao = s.method == AoMethod::Rtao;
        if !temporal::applies(s) || view.is_depth() || (view == View::AoRaw && !rtao) {
            return Ok(());
        }
        if rtao && self.ao.rtao_restarted(s.method) {
            // An object moved or a setting changed: the occlusion of what stayed in view changed too.
            self.temporal.restart();
        }
        let blurred = s.blur && view != View::AoRaw;
        let raw_from = if rtao {
            crate::ao::method::rtao::blurred_frames(s, blurred)
        } else {
            0
        };
        let (gl, meshes) = (&self.gl, &self.meshes);
        self.pass("temporal accumulation", "ao", || {
            self.temporal
                .run(gl, meshes, targets, &self.camera, s, blurred, raw_from)
        })
    }

    /// Triangles of every object in world space (for the ray-traced reference).
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

fn world_bounds(data: &MeshData, m: &Mat4) -> (Vec3, Vec3) {
    transformed_bounds(data.bounds().unwrap_or((Vec3::ZERO, Vec3::ZERO)), m)
}
