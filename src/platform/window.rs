//! The desktop window: winit + glutin, a fly camera, AO and view toggles, an egui parameter panel,
//! hot reload of shaders.
//!
//! Keys: W/A/S/D/Q/E move, drag with a mouse button to look, Space toggles AO, M cycles AO methods, V cycles the views
//! (composite, linear depth, raw SAO, blurred SAO), B toggles the blur, R rebuilds every shader, F1 shows or
//! hides the parameter panel, Esc quits. Keys and drags go to the camera only when the panel does not use them.
//! The panel (egui, painted over the frame) sets the AO method, composite mode, radius, bias, intensity,
//! sample count, spiral turns, blur and view, and shows the time of each pass (GPU timer queries
//! on a hardware driver, the wall clock on llvmpipe).
//! Shaders are also rebuilt automatically within half a second of being saved; a compile error is
//! shown in the window (red, `file:line: message`, even with the panel hidden), in the title bar and on
//! the console, and the last working program keeps running until the file compiles. When a `--res`
//! shader is already broken at start-up, the project's own shaders run until it is fixed.

use super::panel::{self, Panel};
use super::panel_fonts;
use super::shader_errors::{shader_stamps, ShaderErrorEntry, ShaderErrors};
use crate::gl::ProgramError;
use crate::render::{Engine, View};
use crate::res::ResDirs;
use crate::scene::SceneDesc;
use anyhow::{anyhow, Context as _, Result};
use glam::Vec3;
use glutin::config::{ConfigTemplateBuilder, GlConfig};
use glutin::context::{
    ContextApi, ContextAttributesBuilder, GlProfile, PossiblyCurrentContext, Version,
};
use glutin::display::GetGlDisplay;
use glutin::prelude::*;
use glutin::surface::{Surface, SwapInterval, WindowSurface};
use glutin_winit::{DisplayBuilder, GlWindow};
use raw_window_handle::HasWindowHandle;
use std::collections::HashSet;
use std::ffi::CStr;
use std::num::NonZeroU32;
use std::path::PathBuf;
use std::rc::Rc;
use std::sync::Arc;
use std::time::{Duration, Instant, SystemTime};
use winit::application::ApplicationHandler;
use winit::dpi::PhysicalSize;
use winit::event::{ElementState, MouseButton, WindowEvent};
use winit::event_loop::{ActiveEventLoop, ControlFlow, EventLoop};
use winit::keyboard::{KeyCode, PhysicalKey};
use winit::window::{Window, WindowId};

/// How the window starts.
#[derive(Clone, Debug)]
pub struct WindowOptions {
    pub view: View,
    /// Close after this many frames (scripted runs and tests).
    pub frames: Option<u32>,
    /// Save the last frame to this PNG.
    pub screenshot: Option<PathBuf>,
    /// The screenshot shows what is on screen (panel and error overlay included) instead of the
    /// engine's frame alone, which equals a headless `render`.
    pub screenshot_with_ui: bool,
    pub panel_visible: bool,
    /// Start with per-pass timing on (the panel's "time each pass").
    pub time_passes: bool,
}

impl WindowOptions {
    /// The panel starts visible and screenshots hold the engine's frame alone; for scripted runs
    /// `OPENGL3D_PANEL=off` starts with the panel hidden and `OPENGL3D_SCREENSHOT_UI=1` puts the
    /// panel and overlay into the screenshot; `OPENGL3D_TIME_PASSES=1` starts with per-pass timing on.
    pub fn from_env(view: View, frames: Option<u32>, screenshot: Option<PathBuf>) -> WindowOptions {
        let flag = |name: &str| {
            std::env::var(name)
                .ok()
                .map(|v| v.trim().to_ascii_lowercase())
        };
        WindowOptions {
            view,
            frames,
            screenshot,
            screenshot_with_ui: flag("OPENGL3D_SCREENSHOT_UI")
                .is_some_and(|v| matches!(v.as_str(), "1" | "on" | "yes" | "true")),
            time_passes: flag("OPENGL3D_TIME_PASSES")
                .is_some_and(|v| matches!(v.as_str(), "1" | "on" | "yes" | "true")),
            panel_visible: !flag("OPENGL3D_PANEL")
                .is_some_and(|v| matches!(v.as_str(), "0" | "off" | "no" | "false" | "hidden")),
        }
    }
}

/// egui on this window: input from winit, painting with glow over the default framebuffer.
struct Gui {
    ctx: egui::Context,
    input: egui_winit::State,
    painter: egui_glow::Painter,
}

struct GlWindowState {
    engine: Engine,
    gui: Gui,
    panel: Panel,
    surface: Surface<WindowSurface>,
    context: PossiblyCurrentContext,
    // Dropped last: the GL objects above need the window's context.
    window: Window,
}

impl Drop for GlWindowState {
    fn drop(&mut self) {
        // egui's painter does not free its GL objects on drop; the context is still current here.
        self.gui.painter.destroy();
    }
}

/// Running on the project's shaders because the student's did not build at start-up.
struct StartupFallback {
    student_res: ResDirs,
    stamps: Vec<(PathBuf, Option<SystemTime>)>,
}

struct App {
    res: ResDirs,
    scene: SceneDesc,
    options: WindowOptions,
    state: Option<GlWindowState>,
    error: Option<anyhow::Error>,
    keys: HashSet<KeyCode>,
    dragging: bool,
    last_cursor: Option<(f64, f64)>,
    yaw: f32,
    pitch: f32,
    last_frame: Instant,
    last_reload_check: Instant,
    shader_errors: ShaderErrors,
    fallback: Option<StartupFallback>,
    minimised: bool,
    frames_left: Option<u32>,
    title: String,
}

/// Opens the window and runs until it is closed (or `frames` frames were shown).
pub fn run(
    res: ResDirs,
    scene: SceneDesc,
    view: View,
    frames: Option<u32>,
    screenshot: Option<PathBuf>,
) -> Result<()> {
    run_with(
        res,
        scene,
        WindowOptions::from_env(view, frames, screenshot),
    )
}

/// winit's message without the source file and line it may carry ("os error at
/// .../linux/mod.rs:788: Failed to open connection to X server"): a user cannot act on those.
fn without_source_location(message: &str) -> String {
    match message.find(".rs:") {
        Some(at) => {
            let rest = &message[at + 4..];
            let rest = rest.trim_start_matches(|c: char| c.is_ascii_digit());
            rest.trim_start_matches(':').trim().to_string()
        }
        None => message.to_string(),
    }
}

/// Opens the window with `options` and runs until it is closed (or the frames were shown).
pub fn run_with(res: ResDirs, scene: SceneDesc, options: WindowOptions) -> Result<()> {
    let event_loop = EventLoop::new().map_err(|e| {
        let cause = without_source_location(&e.to_string());
        anyhow::anyhow!("{}", rust_i18n::t!("window.no_display", cause = cause))
    })?;
    let fwd = (Vec3::from(scene.camera.target) - Vec3::from(scene.camera.eye)).normalize_or_zero();
    let mut app = App {
        res,
        scene,
        state: None,
        error: None,
        keys: HashSet::new(),
        dragging: false,
        last_cursor: None,
        yaw: fwd.x.atan2(-fwd.z),
        pitch: fwd.y.clamp(-1.0, 1.0).asin(),
        last_frame: Instant::now(),
        last_reload_check: Instant::now(),
        shader_errors: ShaderErrors::default(),
        fallback: None,
        minimised: false,
        frames_left: options.frames,
        options,
        title: String::new(),
    };
    event_loop.run_app(&mut app).context("event loop")?;
    match app.error {
        Some(e) => Err(e),
        None => Ok(()),
    }
}

/// The shader error inside an engine start-up error, if that is what stopped it.
fn startup_shader_error(e: &anyhow::Error) -> Option<&ProgramError> {
    e.chain().find_map(|c| c.downcast_ref::<ProgramError>())
}

impl App {
    fn create(&mut self, event_loop: &ActiveEventLoop) -> Result<GlWindowState> {
        let (w, h) = (self.scene.output.width, self.scene.output.height);
        let attrs = Window::default_attributes()
            .with_title("opengl3d")
            .with_inner_size(PhysicalSize::new(w, h));
        let template = ConfigTemplateBuilder::new()
            .with_alpha_size(8)
            .with_depth_size(0);
        let (window, config) = DisplayBuilder::new()
            .with_window_attributes(Some(attrs))
            .build(event_loop, template, |configs| {
                // Prefer single-sampled configs: the engine renders into its own FBOs.
                configs
                    .min_by_key(|c| (c.num_samples(), c.srgb_capable() as u8))
                    .expect("at least one GL config")
            })
            .map_err(|e| anyhow!("cannot create a GL window: {e}"))?;
        let window = window.ok_or_else(|| anyhow!("no window was created"))?;
        let raw = window.window_handle().map_err(|e| anyhow!("{e}"))?.as_raw();
        let display = config.display();
        let ctx_attrs = ContextAttributesBuilder::new()
            .with_profile(GlProfile::Core)
            .with_context_api(ContextApi::OpenGl(Some(Version::new(4, 5))))
            .build(Some(raw));
        let not_current = unsafe { display.create_context(&config, &ctx_attrs) }
            .context("cannot create an OpenGL 4.5 core context")?;
        let surface_attrs = window
            .build_surface_attributes(Default::default())
            .map_err(|e| anyhow!("{e}"))?;
        let surface = unsafe { display.create_window_surface(&config, &surface_attrs) }
            .context("window surface")?;
        let context = not_current.make_current(&surface).context("make current")?;
        // Without vsync the window still works (it only draws more frames than shown).
        if let Err(e) =
            surface.set_swap_interval(&context, SwapInterval::Wait(NonZeroU32::new(1).unwrap()))
        {
            log::warn!("vsync unavailable: {e}");
        }
        // Two function tables for the same context: the engine shares an Rc, egui wants an Arc.
        let load = || unsafe {
            glow::Context::from_loader_function_cstr(|s: &CStr| display.get_proc_address(s))
        };
        let gl = Rc::new(load());
        crate::gl::clip_control::register_loader(|s| display.get_proc_address(s));
        #[allow(clippy::arc_with_non_send_sync)]
        let gui_gl = Arc::new(load());
        let renderer = crate::gl::describe_renderer(&gl);
        log::info!("window context: {renderer}");
        let size = window.inner_size();
        let mut engine = self.create_engine(&gl, size)?;
        engine.view = self.options.view;
        engine.collect_stats = self.options.time_passes;

        let painter = egui_glow::Painter::new(gui_gl, "", None, false)
            .map_err(|e| anyhow!("cannot set up the parameter panel's painter: {e}"))?;
        let ctx = egui::Context::default();
        let fonts = panel_fonts::install_fonts(
            &ctx,
            crate::i18n::current(),
            &panel_fonts::known_cjk_fonts(),
        );
        for warning in &fonts.warnings {
            eprintln!("{warning}");
        }
        let input = egui_winit::State::new(
            ctx.clone(),
            egui::ViewportId::ROOT,
            event_loop,
            Some(window.scale_factor() as f32),
            event_loop.system_theme(),
            Some(painter.max_texture_side()),
        );
        // Scripts (and the tests) wait for this line before touching shader files.
        crate::outln!(
            "window {}x{} on {renderer}; F1 shows or hides the parameter panel",
            size.width,
            size.height
        );
        Ok(GlWindowState {
            engine,
            gui: Gui {
                ctx,
                input,
                painter,
            },
            panel: Panel::new(self.options.panel_visible, renderer, fonts.lang),
            surface,
            context,
            window,
        })
    }

    /// The engine on the chosen shaders or, when a student's shader does not build, on the
    /// project's own ones (the error goes to the overlay and the folder is watched for a fix).
    fn create_engine(&mut self, gl: &crate::gl::Gl, size: PhysicalSize<u32>) -> Result<Engine> {
        let (w, h) = (size.width.max(1), size.height.max(1));
        let err = match Engine::new(gl, self.res.clone(), &self.scene, w, h) {
            Ok(e) => return Ok(e),
            Err(e) => e,
        };
        let dirs = self.res.dirs();
        let Some(shader_error) = startup_shader_error(&err).filter(|_| dirs.len() > 1) else {
            return Err(err);
        };
        let project = ResDirs::only(vec![dirs[dirs.len() - 1].clone()]);
        let engine = match Engine::new(gl, project.clone(), &self.scene, w, h) {
            Ok(e) => e,
            // The project's shaders do not help either: report the first problem.
            Err(_) => return Err(err),
        };
        eprintln!(
            "{shader_error}\n(running the project's own shaders until this compiles; save the file to retry)"
        );
        self.shader_errors
            .record(std::slice::from_ref(shader_error));
        self.fallback = Some(StartupFallback {
            stamps: shader_stamps(&self.res),
            student_res: std::mem::replace(&mut self.res, project),
        });
        Ok(engine)
    }

    /// After a start-up failure: rebuilds the engine on the student's shaders once they were saved again.
    fn retry_student_shaders(&mut self) {
        let (Some(fb), Some(s)) = (self.fallback.as_mut(), self.state.as_mut()) else {
            return;
        };
        let stamps = shader_stamps(&fb.student_res);
        if stamps == fb.stamps {
            return;
        }
        fb.stamps = stamps;
        let (w, h) = s.engine.size();
        match Engine::new(s.engine.gl(), fb.student_res.clone(), &self.scene, w, h) {
            Ok(mut engine) => {
                engine.camera = s.engine.camera;
                engine.view = s.engine.view;
                engine.ao_settings = s.engine.ao_settings;
                engine.collect_stats = s.engine.collect_stats;
                self.shader_errors.clear();
                if let Err(e) = engine.sync_shader_constants() {
                    self.shader_errors.record_any(&e);
                }
                s.engine = engine;
                self.res = fb.student_res.clone();
                self.fallback = None;
                let dir = self.res.dirs()[0].display();
                eprintln!("{}", rust_i18n::t!("window.rebuilt_using", dir = dir));
            }
            Err(e) => {
                let text = match startup_shader_error(&e) {
                    Some(p) => p.to_string(),
                    None => format!("{e:#}"),
                };
                if self.shader_errors.text() != text {
                    eprintln!("{text}\n{}", rust_i18n::t!("window.project_shaders_run"));
                }
                self.shader_errors.clear();
                match startup_shader_error(&e) {
                    Some(p) => {
                        self.shader_errors.record(std::slice::from_ref(p));
                    }
                    None => self.shader_errors.entries.push(ShaderErrorEntry {
                        file: None,
                        stamp: None,
                        text,
                    }),
                }
            }
        }
        self.update_title();
    }

    fn update_title(&mut self) {
        if let Some(s) = &self.state {
            let e = &s.engine;
            let on_off = |on: bool| rust_i18n::t!(if on { "window.on" } else { "window.off" });
            let view_key = format!("view.{}", e.view.name());
            let mut t = rust_i18n::t!(
                "window.title",
                method = e.ao_settings.method.name(),
                view = rust_i18n::t!(&view_key),
                ao = on_off(e.ao_settings.enabled),
                blur = on_off(e.ao_settings.blur)
            )
            .into_owned();
            if let Some(first) = self.shader_errors.entries.first() {
                let error = first.text.lines().next().unwrap_or("");
                t = rust_i18n::t!("window.title_error", error = error, title = t).into_owned();
            }
            // Setting the title is a round trip to the display server: only on change.
            if t != self.title {
                s.window.set_title(&t);
                self.title = t;
            }
        }
    }

    fn check_reload(&mut self, force: bool) {
        if self.fallback.is_some() {
            self.retry_student_shaders();
        }
        let Some(s) = self.state.as_mut() else { return };
        let had_errors = !self.shader_errors.is_empty();
        let errors = s.engine.hot_reload(force);
        if force && self.fallback.is_none() {
            self.shader_errors.clear();
        } else {
            self.shader_errors.drop_fixed(&errors);
        }
        let new = self.shader_errors.record(&errors);
        if new {
            let text = errors
                .iter()
                .map(|e| e.to_string())
                .collect::<Vec<_>>()
                .join("\n");
            eprintln!("{text}\n{}", rust_i18n::t!("window.last_working_run"));
        }
        if self.shader_errors.is_empty() && (had_errors || force) {
            // Constants changed while a shader was broken were not applied: apply them now.
            match s.engine.sync_shader_constants() {
                Ok(()) => eprintln!("{}", rust_i18n::t!("window.rebuilt")),
                Err(e) => {
                    eprintln!("{e:#}");
                    self.shader_errors.record_any(&e);
                }
            }
        }
        self.update_title();
    }

    fn sync_constants(&mut self) {
        let Some(s) = self.state.as_mut() else { return };
        if let Err(e) = s.engine.sync_shader_constants() {
            if self.shader_errors.record_any(&e) {
                eprintln!("{e:#}");
            }
        }
    }

    fn move_camera(&mut self, dt: f32) {
        let Some(s) = self.state.as_mut() else { return };
        let fwd = Vec3::new(
            self.yaw.sin() * self.pitch.cos(),
            self.pitch.sin(),
            -self.yaw.cos() * self.pitch.cos(),
        );
        let right = fwd.cross(Vec3::Y).normalize_or_zero();
        let mut d = Vec3::ZERO;
        for (k, v) in [
            (KeyCode::KeyW, fwd),
            (KeyCode::KeyS, -fwd),
            (KeyCode::KeyD, right),
            (KeyCode::KeyA, -right),
            (KeyCode::KeyE, Vec3::Y),
            (KeyCode::KeyQ, -Vec3::Y),
        ] {
            if self.keys.contains(&k) {
                d += v;
            }
        }
        let speed = if self.keys.contains(&KeyCode::ShiftLeft) {
            8.0
        } else {
            3.0
        };
        let cam = &mut s.engine.camera;
        cam.eye += d.normalize_or_zero() * speed * dt;
        cam.target = cam.eye + fwd;
    }

    fn save_screenshot(&self, s: &GlWindowState) -> Result<()> {
        let Some(path) = &self.options.screenshot else {
            return Ok(());
        };
        let (w, h) = s.engine.size();
        let img = crate::gl::readback::read_rgba8(s.engine.gl(), None, w, h);
        if let Some(dir) = path.parent().filter(|d| !d.as_os_str().is_empty()) {
            std::fs::create_dir_all(dir)
                .with_context(|| format!("cannot create the folder {}", dir.display()))?;
        }
        image::DynamicImage::ImageRgba8(img)
            .to_rgb8()
            .save(path)
            .with_context(|| format!("cannot write the screenshot {}", path.display()))?;
        crate::outln!("wrote {} ({w}x{h})", path.display());
        Ok(())
    }

    fn draw(&mut self) -> Result<()> {
        if self.minimised || self.state.is_none() {
            return Ok(());
        }
        let last_frame = self.frames_left.is_some_and(|n| n <= 1);
        let s = self.state.as_mut().unwrap();
        if let Err(e) = s.engine.render(None) {
            // Shown like a shader error and retried next frame: the window stays usable.
            if self.shader_errors.record_any(&e) {
                eprintln!("frame failed: {e:#}");
            }
        }
        if last_frame && !self.options.screenshot_with_ui {
            self.save_screenshot(self.state.as_ref().unwrap())?;
        }

        let s = self.state.as_mut().unwrap();
        let errors = self.shader_errors.lines();
        let raw_input = s.gui.input.take_egui_input(&s.window);
        let mut actions = panel::PanelActions::default();
        let (panel, engine) = (&mut s.panel, &mut s.engine);
        let output = s.gui.ctx.run_ui(raw_input, |ui| {
            actions = panel.show(ui, engine, &errors);
        });
        s.gui
            .input
            .handle_platform_output(&s.window, output.platform_output);
        let primitives = s.gui.ctx.tessellate(output.shapes, output.pixels_per_point);
        let mut textures = output.textures_delta;
        let size = s.window.inner_size();
        s.gui.painter.paint_and_update_textures(
            [size.width, size.height],
            output.pixels_per_point,
            &primitives,
            &mut textures,
        );
        if last_frame && self.options.screenshot_with_ui {
            self.save_screenshot(self.state.as_ref().unwrap())?;
        }
        let s = self.state.as_mut().unwrap();
        s.window.pre_present_notify();
        s.surface.swap_buffers(&s.context).context("swap buffers")?;

        if actions.sync_shader_constants {
            self.sync_constants();
        }
        if actions.reload_shaders {
            self.check_reload(true);
        }
        self.update_title();
        Ok(())
    }

    /// The window's own keys (camera, toggles), when egui does not want the keyboard.
    fn on_key_pressed(&mut self, event_loop: &ActiveEventLoop, code: KeyCode) {
        let Some(s) = self.state.as_mut() else { return };
        match code {
            KeyCode::Escape => event_loop.exit(),
            KeyCode::F1 => s.panel.visible = !s.panel.visible,
            KeyCode::Space => s.engine.ao_settings.enabled = !s.engine.ao_settings.enabled,
            KeyCode::KeyV | KeyCode::Tab => s.engine.view = s.engine.view.next(),
            KeyCode::KeyB => s.engine.ao_settings.blur = !s.engine.ao_settings.blur,
            KeyCode::KeyR => self.check_reload(true),
            KeyCode::KeyM => {
                let all = crate::ao::AoMethod::ALL;
                let i = all
                    .iter()
                    .position(|m| *m == s.engine.ao_settings.method)
                    .unwrap_or(0);
                s.engine.ao_settings.method = all[(i + 1) % all.len()];
                self.sync_constants();
            }
            _ => {}
        }
        self.update_title();
    }
}

impl ApplicationHandler for App {
    fn resumed(&mut self, event_loop: &ActiveEventLoop) {
        if self.state.is_some() {
            return;
        }
        match self.create(event_loop) {
            Ok(s) => {
                self.state = Some(s);
                self.update_title();
                event_loop.set_control_flow(ControlFlow::Poll);
            }
            Err(e) => {
                self.error = Some(e);
                event_loop.exit();
            }
        }
    }

    fn window_event(&mut self, event_loop: &ActiveEventLoop, _id: WindowId, event: WindowEvent) {
        let (consumed, egui_wants_keyboard, pointer_over_egui) = match self.state.as_mut() {
            Some(s) => {
                let r = s.gui.input.on_window_event(&s.window, &event);
                (
                    r.consumed,
                    s.gui.ctx.egui_wants_keyboard_input(),
                    s.gui.ctx.is_pointer_over_egui(),
                )
            }
            None => (false, false, false),
        };
        match event {
            WindowEvent::CloseRequested => event_loop.exit(),
            WindowEvent::Resized(size) => {
                // Minimised windows report 0×0: keep the targets and stop drawing until restored.
                self.minimised = size.width == 0 || size.height == 0;
                if let (Some(s), false) = (self.state.as_mut(), self.minimised) {
                    s.surface.resize(
                        &s.context,
                        NonZeroU32::new(size.width).unwrap(),
                        NonZeroU32::new(size.height).unwrap(),
                    );
                    if let Err(e) = s.engine.resize(size.width, size.height) {
                        eprintln!("resize to {}x{} failed: {e:#}", size.width, size.height);
                    }
                }
            }
            WindowEvent::KeyboardInput { event, .. } => {
                let PhysicalKey::Code(code) = event.physical_key else {
                    return;
                };
                if event.state == ElementState::Pressed {
                    // Typing into a panel field must not move the camera or toggle things.
                    if consumed || egui_wants_keyboard {
                        return;
                    }
                    self.keys.insert(code);
                    if !event.repeat {
                        self.on_key_pressed(event_loop, code);
                    }
                } else {
                    // Releases always count, or a key pressed before focusing a field would stick.
                    self.keys.remove(&code);
                }
            }
            WindowEvent::Focused(false) => self.keys.clear(),
            WindowEvent::MouseInput { state, button, .. } => {
                if matches!(button, MouseButton::Left | MouseButton::Right) {
                    // A drag that starts on the panel belongs to the panel.
                    self.dragging =
                        state == ElementState::Pressed && !consumed && !pointer_over_egui;
                }
            }
            WindowEvent::CursorMoved { position, .. } => {
                if let (true, Some((x0, y0))) = (self.dragging, self.last_cursor) {
                    self.yaw += (position.x - x0) as f32 * 0.004;
                    self.pitch = (self.pitch - (position.y - y0) as f32 * 0.004).clamp(-1.5, 1.5);
                    self.move_camera(0.0);
                }
                self.last_cursor = Some((position.x, position.y));
            }
            WindowEvent::RedrawRequested => {
                let now = Instant::now();
                let dt = (now - self.last_frame).as_secs_f32().min(0.1);
                self.last_frame = now;
                if !self.keys.is_empty() {
                    self.move_camera(dt);
                }
                if now - self.last_reload_check > Duration::from_millis(400) {
                    self.last_reload_check = now;
                    self.check_reload(false);
                }
                if let Err(e) = self.draw() {
                    self.error = Some(e);
                    event_loop.exit();
                    return;
                }
                if let Some(n) = self.frames_left.as_mut() {
                    *n = n.saturating_sub(1);
                    if *n == 0 {
                        event_loop.exit();
                    }
                }
            }
            _ => {}
        }
    }

    fn about_to_wait(&mut self, _event_loop: &ActiveEventLoop) {
        if let Some(s) = &self.state {
            if self.minimised {
                // Nothing to draw: don't spin.
                std::thread::sleep(Duration::from_millis(50));
            }
            s.window.request_redraw();
        }
    }

    fn exiting(&mut self, _event_loop: &ActiveEventLoop) {
        // GL objects must go while the context is still current.
        self.state = None;
    }
}
