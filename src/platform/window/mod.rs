//! The desktop window: winit + glutin, a fly camera, AO and view toggles, an egui parameter panel,
//! hot reload of shaders.
//!
//! Keys: W/A/S/D/Q/E move, drag with a mouse button to look, Space toggles AO, M cycles AO methods, V cycles the views
//! (composite, linear depth, raw SAO, blurred SAO), B toggles the blur, R rebuilds every shader, F1 shows or
//! hides the parameter panel, T traces the truth of the view and shows the current method's error map
//! against it (`truth_view.rs`), Esc quits. Keys and drags go to the camera only when the panel does not use them.
//! The panel (egui, painted over the frame) sets the AO method, composite mode, radius, bias, intensity,
//! sample count, spiral turns, blur and view, and shows the time of each pass (GPU timer queries
//! on a hardware driver, the wall clock on llvmpipe).
//! Shaders are also rebuilt automatically within half a second of being saved; a compile error is
//! shown in the window (red, `file:line: message`, even with the panel hidden), in the title bar and on
//! the console, and the last working program keeps running until the file compiles. When a `--res`
//! shader is already broken at start-up, the project's own shaders run until it is fixed.
//! The AO is averaged over frames, through the camera's motion (`accumulation.rs`).

pub mod accumulation;
mod create;
pub mod truth;
pub mod truth_view;

use super::panel::{self, Panel};
use super::shader_errors::ShaderErrors;
use crate::render::{Engine, View};
use crate::res::ResDirs;
use crate::scene::SceneDesc;
use accumulation::AccumulationWatch;
use anyhow::{Context as _, Result};
use glam::Vec3;
use glutin::context::PossiblyCurrentContext;
use glutin::prelude::*;
use glutin::surface::{Surface, WindowSurface};
use std::collections::HashSet;
use std::num::NonZeroU32;
use std::path::PathBuf;
use std::time::{Duration, Instant, SystemTime};
use truth::TruthTools;
use truth_view::TruthView;
use winit::application::ApplicationHandler;
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
    /// The ray tracer behind T (the truth view); without one the panel says it is unavailable.
    pub truth: Option<TruthTools>,
    /// Ask for the truth of the first frame's view at start-up (scripted runs: `OPENGL3D_TRUTH=1`).
    pub truth_at_start: bool,
    /// A method file's method, run in the place of the engine method that reads the most inputs.
    pub method_file: Option<crate::scene::method_file::MethodFile>,
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
            truth: None,
            truth_at_start: flag("OPENGL3D_TRUTH")
                .is_some_and(|v| matches!(v.as_str(), "1" | "on" | "yes" | "true")),
            panel_visible: !flag("OPENGL3D_PANEL")
                .is_some_and(|v| matches!(v.as_str(), "0" | "off" | "no" | "false" | "hidden")),
            method_file: None,
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
    truth: TruthView,
    accumulation: AccumulationWatch,
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

impl App {
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
        if s.accumulation
            .changed(&s.engine.ao_settings, s.engine.size())
        {
            s.engine.ao.restart_accumulation();
            // The screen-space methods' history too: it follows the camera, not the settings.
            s.engine.temporal.restart();
        }
        if std::mem::take(&mut self.options.truth_at_start) {
            // Scripted runs wait for the truth, so that their frames show its map.
            s.truth.report = true;
            s.truth.request(&s.engine);
            s.truth.state.wait();
        }
        s.truth.update(&mut s.engine);
        if !s
            .engine
            .view
            .available(s.engine.ao_settings.uses_second_layer())
        {
            // The second layer's view outlives the setting that drew it: show the first layer.
            s.engine.view = View::LinearDepth;
        }
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
        let (panel, engine, truth) = (&mut s.panel, &mut s.engine, &mut s.truth);
        let output = s.gui.ctx.run_ui(raw_input, |ui| {
            actions = panel.show(ui, engine, &errors, truth);
            truth.map_window(ui.ctx(), engine, panel.lang());
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
        if actions.compute_truth {
            let s = self.state.as_mut().unwrap();
            s.truth.request(&s.engine);
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
            KeyCode::KeyV | KeyCode::Tab => {
                let second_layer = s.engine.ao_settings.uses_second_layer();
                s.engine.view = s.engine.view.next(second_layer);
            }
            KeyCode::KeyB => s.engine.ao_settings.blur = !s.engine.ao_settings.blur,
            KeyCode::KeyR => self.check_reload(true),
            KeyCode::KeyT => s.truth.request(&s.engine),
            KeyCode::KeyM => {
                let all = crate::ao::AoMethod::ALL;
                let i = all
                    .iter()
                    .position(|m| *m == s.engine.ao_settings.method)
                    .unwrap_or(0);
                s.engine.ao_settings.method = all[(i + 1) % all.len()];
                crate::scene::ao_defaults::apply(&mut s.engine.ao_settings);
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
