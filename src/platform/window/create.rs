//! Opening the window: the GL context on winit + glutin, egui's painter, and the engine on the
//! chosen shaders or, when a student's shader does not build at start-up, on the project's own.

use super::accumulation::{window_accumulate, AccumulationWatch};
use super::truth_view::TruthView;
use super::{App, GlWindowState, Gui, StartupFallback};
use crate::gl::ProgramError;
use crate::platform::panel::Panel;
use crate::platform::panel_fonts;
use crate::platform::shader_errors::{shader_stamps, ShaderErrorEntry};
use crate::render::Engine;
use crate::res::ResDirs;
use anyhow::{anyhow, Context as _, Result};
use glutin::config::{ConfigTemplateBuilder, GlConfig};
use glutin::context::{ContextApi, ContextAttributesBuilder, GlProfile, Version};
use glutin::display::GetGlDisplay;
use glutin::prelude::*;
use glutin::surface::SwapInterval;
use glutin_winit::{DisplayBuilder, GlWindow};
use raw_window_handle::HasWindowHandle;
use std::ffi::CStr;
use std::num::NonZeroU32;
use std::rc::Rc;
use std::sync::Arc;
use winit::dpi::PhysicalSize;
use winit::event_loop::ActiveEventLoop;
use winit::window::Window;

/// The shader error inside an engine start-up error, if that is what stopped it.
fn startup_shader_error(e: &anyhow::Error) -> Option<&ProgramError> {
    e.chain().find_map(|c| c.downcast_ref::<ProgramError>())
}

impl App {
    pub(super) fn create(&mut self, event_loop: &ActiveEventLoop) -> Result<GlWindowState> {
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
        engine.ao_settings.accumulate = window_accumulate(engine.ao_settings.accumulate);

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
            truth: TruthView::new(self.options.truth.as_ref().map(|t| t.0.clone())),
            accumulation: AccumulationWatch::default(),
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
            Ok(mut e) => {
                if let Some(file) = &self.options.method_file {
                    e.use_method_file(file.clone())?;
                }
                return Ok(e);
            }
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
    pub(super) fn retry_student_shaders(&mut self) {
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
                if let Some(file) = &self.options.method_file {
                    if let Err(e) = engine.use_method_file(file.clone()) {
                        self.shader_errors.record_any(&e);
                    }
                }
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
}
