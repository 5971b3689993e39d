//! The desktop window: winit + glutin, a fly camera, AO and view toggles, hot reload of shaders.
//!
//! Keys: W/A/S/D/Q/E move, drag with a mouse button to look, Space toggles AO, M cycles AO methods, V cycles the views
//! (composite, linear depth, raw SAO, blurred SAO), B toggles the blur, R rebuilds every shader, Esc quits.
//! Shaders are also rebuilt automatically within half a second of being saved; a compile error is
//! shown in the title bar and on the console with file:line, and the last working program keeps running.

use crate::engine::{Engine, View};
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
use std::time::{Duration, Instant};
use winit::application::ApplicationHandler;
use winit::dpi::PhysicalSize;
use winit::event::{ElementState, MouseButton, WindowEvent};
use winit::event_loop::{ActiveEventLoop, ControlFlow, EventLoop};
use winit::keyboard::{KeyCode, PhysicalKey};
use winit::window::{Window, WindowId};

struct GlWindowState {
    engine: Engine,
    surface: Surface<WindowSurface>,
    context: PossiblyCurrentContext,
    // Dropped last: the GL objects above need the window's context.
    window: Window,
}

struct App {
    res: ResDirs,
    scene: SceneDesc,
    start_view: View,
    state: Option<GlWindowState>,
    error: Option<anyhow::Error>,
    keys: HashSet<KeyCode>,
    dragging: bool,
    last_cursor: Option<(f64, f64)>,
    yaw: f32,
    pitch: f32,
    last_frame: Instant,
    last_reload_check: Instant,
    shader_error: Option<String>,
    minimised: bool,
    frames_left: Option<u32>,
    screenshot: Option<PathBuf>,
}

/// Opens the window and runs until it is closed (or `frames` frames were shown).
pub fn run(
    res: ResDirs,
    scene: SceneDesc,
    view: View,
    frames: Option<u32>,
    screenshot: Option<PathBuf>,
) -> Result<()> {
    let event_loop = EventLoop::new().context("cannot connect to the display")?;
    let fwd = (Vec3::from(scene.camera.target) - Vec3::from(scene.camera.eye)).normalize_or_zero();
    let mut app = App {
        res,
        scene,
        start_view: view,
        state: None,
        error: None,
        keys: HashSet::new(),
        dragging: false,
        last_cursor: None,
        yaw: fwd.x.atan2(-fwd.z),
        pitch: fwd.y.clamp(-1.0, 1.0).asin(),
        last_frame: Instant::now(),
        last_reload_check: Instant::now(),
        shader_error: None,
        minimised: false,
        frames_left: frames,
        screenshot,
    };
    event_loop.run_app(&mut app).context("event loop")?;
    match app.error {
        Some(e) => Err(e),
        None => Ok(()),
    }
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
        let _ =
            surface.set_swap_interval(&context, SwapInterval::Wait(NonZeroU32::new(1).unwrap()));
        let gl = Rc::new(unsafe {
            glow::Context::from_loader_function_cstr(|s: &CStr| display.get_proc_address(s))
        });
        log::info!("window context: {}", crate::engine::describe_renderer(&gl));
        let size = window.inner_size();
        let mut engine = Engine::new(
            &gl,
            self.res.clone(),
            &self.scene,
            size.width.max(1),
            size.height.max(1),
        )?;
        engine.view = self.start_view;
        Ok(GlWindowState {
            engine,
            surface,
            context,
            window,
        })
    }

    fn update_title(&self) {
        if let Some(s) = &self.state {
            let e = &s.engine;
            let mut t = format!(
                "opengl3d — {} (M) — view: {} (V) — AO {} (Space) — blur {} (B)",
                e.ao_params.method.name(),
                e.view.label(),
                if e.ao_params.enabled { "on" } else { "off" },
                if e.ao_params.blur { "on" } else { "off" }
            );
            if let Some(err) = &self.shader_error {
                t = format!("SHADER ERROR {} — {t}", err.lines().next().unwrap_or(""));
            }
            s.window.set_title(&t);
        }
    }

    fn check_reload(&mut self, force: bool) {
        let Some(s) = self.state.as_mut() else { return };
        let errors = s.engine.hot_reload(force);
        if errors.is_empty() {
            if self.shader_error.take().is_some() || force {
                eprintln!("shaders rebuilt");
            }
        } else {
            let text = errors
                .iter()
                .map(|e| e.to_string())
                .collect::<Vec<_>>()
                .join("\n");
            if self.shader_error.as_deref() != Some(text.as_str()) {
                eprintln!("{text}\n(the last working shaders keep running)");
            }
            self.shader_error = Some(text);
        }
        self.update_title();
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

    fn draw(&mut self) -> Result<()> {
        let Some(s) = self.state.as_mut() else {
            return Ok(());
        };
        if self.minimised {
            return Ok(());
        }
        s.engine.render(None);
        if let Some(n) = self.frames_left {
            if n <= 1 {
                if let Some(path) = &self.screenshot {
                    let (w, h) = s.engine.size();
                    let img = crate::engine::read_rgba8(s.engine.gl(), None, w, h);
                    if let Some(dir) = path.parent().filter(|d| !d.as_os_str().is_empty()) {
                        std::fs::create_dir_all(dir)?;
                    }
                    image::DynamicImage::ImageRgba8(img).to_rgb8().save(path)?;
                    println!("wrote {} ({w}x{h})", path.display());
                }
            }
        }
        s.window.pre_present_notify();
        s.surface.swap_buffers(&s.context).context("swap buffers")?;
        Ok(())
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
                    self.keys.insert(code);
                    if !event.repeat {
                        if let Some(s) = self.state.as_mut() {
                            match code {
                                KeyCode::Escape => event_loop.exit(),
                                KeyCode::Space => {
                                    s.engine.ao_params.enabled = !s.engine.ao_params.enabled
                                }
                                KeyCode::KeyV | KeyCode::Tab => {
                                    s.engine.view = s.engine.view.next()
                                }
                                KeyCode::KeyB => s.engine.ao_params.blur = !s.engine.ao_params.blur,
                                KeyCode::KeyR => self.check_reload(true),
                                KeyCode::KeyM => {
                                    let all = crate::ao::AoMethod::ALL;
                                    let i = all
                                        .iter()
                                        .position(|m| *m == s.engine.ao_params.method)
                                        .unwrap_or(0);
                                    s.engine.ao_params.method = all[(i + 1) % all.len()];
                                    if let Err(e) = s.engine.sync_shader_constants() {
                                        eprintln!("{e}");
                                    }
                                }
                                _ => {}
                            }
                        }
                        self.update_title();
                    }
                } else {
                    self.keys.remove(&code);
                }
            }
            WindowEvent::MouseInput { state, button, .. } => {
                if matches!(button, MouseButton::Left | MouseButton::Right) {
                    self.dragging = state == ElementState::Pressed;
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
