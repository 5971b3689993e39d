//! The truth view of the window: asks for the truth of the current camera (T or the panel's
//! button), compares the current method's AO with it while the settings change, and shows the
//! signed error map with its PSNR in a floating window. GL work stays on the window's thread; only
//! the tracing runs on a worker (`truth.rs`).

use super::truth::{
    truth_size, ErrorPicture, Stale, Truth, TruthBackend, TruthKey, TruthRequest, TruthState,
    TruthStatus,
};
use crate::ao::{AoMethod, AoSettings};
use crate::i18n::Lang;
use crate::render::{Engine, View};
use anyhow::Result;
use glam::Vec3;
use rust_i18n::t;
use std::collections::hash_map::DefaultHasher;
use std::hash::{Hash, Hasher};
use std::sync::Arc;
use std::time::{Duration, Instant};

/// The map follows slider drags at most this often (each comparison renders the frame twice more).
const FOLLOW_INTERVAL: Duration = Duration::from_millis(150);
/// While `rtao` accumulates, the map is refreshed this often.
const ACCUMULATION_INTERVAL: Duration = Duration::from_millis(500);
/// Width of the error map in the floating window (points).
const MAP_WIDTH: f32 = 320.0;
/// A failed trace or comparison (the panel's shader-error red).
const FAILURE_RED: egui::Color32 = egui::Color32::from_rgb(255, 70, 60);

/// The engine's AO view (visibility, rows top-down) against `truth`, box-averaged to the truth's
/// size, through `backend`'s error map. Sky: linear depth at the far plane, as `render --view error`.
pub fn evaluate(
    engine: &mut Engine,
    truth: &Truth,
    backend: &dyn TruthBackend,
) -> Result<ErrorPicture> {
    let ao = engine.render_values(View::Ao)?;
    let far = engine.camera.far;
    let sky: Vec<bool> = engine
        .render_values(View::LinearDepth)?
        .iter()
        .map(|d| d.is_nan() || *d >= far * (1.0 - 1e-4))
        .collect();
    let (w, h) = engine.size();
    backend.error_map(&ao, &sky, (w as usize, h as usize), truth)
}

/// Identifies the objects the truth sees: names and model matrices.
pub fn scene_key(engine: &Engine) -> u64 {
    let mut h = DefaultHasher::new();
    for o in &engine.objects {
        o.name.hash(&mut h);
        for v in o.model().to_cols_array() {
            v.to_bits().hash(&mut h);
        }
    }
    h.finish()
}

/// The key of the truth the engine's current view needs (None when the window's size has no
/// whole fraction to trace at).
pub fn view_key(engine: &Engine) -> Option<TruthKey> {
    let (w, h) = engine.size();
    let size = truth_size(w, h)?;
    Some(TruthKey::new(
        &engine.camera,
        engine.ao_settings.radius,
        size,
        scene_key(engine),
    ))
}

/// When the map was last drawn, and for what.
struct Compared {
    at: Instant,
    key: TruthKey,
    settings: AoSettings,
    frames: u32,
}

pub struct TruthView {
    backend: Option<Arc<dyn TruthBackend>>,
    pub state: TruthState,
    /// The scene's triangles for the last scene key (rebuilt when objects move).
    triangles: Option<(u64, Arc<Vec<[Vec3; 3]>>)>,
    picture: Option<ErrorPicture>,
    compared: Option<Compared>,
    texture: Option<egui::TextureHandle>,
    texture_stale: bool,
    comparison_error: Option<String>,
    /// The floating map window is open.
    pub shown: bool,
    /// Print each new score on stdout (scripted runs).
    pub report: bool,
}

impl TruthView {
    pub fn new(backend: Option<Arc<dyn TruthBackend>>) -> TruthView {
        TruthView {
            backend,
            state: TruthState::default(),
            triangles: None,
            picture: None,
            compared: None,
            texture: None,
            texture_stale: false,
            comparison_error: None,
            shown: false,
            report: false,
        }
    }

    /// Asks for the truth of the engine's view (T, the panel's button) and opens the map.
    pub fn request(&mut self, engine: &Engine) {
        self.shown = true;
        let (Some(backend), Some(key)) = (self.backend.clone(), view_key(engine)) else {
            return;
        };
        let scene = scene_key(engine);
        let triangles = match &self.triangles {
            Some((k, t)) if *k == scene => t.clone(),
            _ => {
                let t = Arc::new(engine.world_triangles());
                self.triangles = Some((scene, t.clone()));
                t
            }
        };
        let (width, height) = truth_size(engine.size().0, engine.size().1).unwrap_or((1, 1));
        let request = TruthRequest {
            camera: engine.camera,
            radius: engine.ao_settings.radius,
            width,
            height,
            footprint: engine.size().0 / width.max(1),
            triangles,
        };
        self.state.request(key, request, backend);
    }

    /// Once per frame, before the engine draws: takes in a finished trace and, while the view's truth
    /// is ready and the map is open, compares the current settings with it when they changed.
    pub fn update(&mut self, engine: &mut Engine) {
        self.state.poll();
        let (Some(backend), true) = (self.backend.clone(), self.shown) else {
            return;
        };
        let Some(key) = view_key(engine) else { return };
        let TruthStatus::Ready(truth) = self.state.status(&key) else {
            return;
        };
        let settings = engine.ao_settings;
        let frames = engine.ao.accumulated_frames(settings.method);
        let now = Instant::now();
        let due = match &self.compared {
            None => true,
            Some(c) => {
                let changed = c.key != key || c.settings != settings;
                let accumulating = settings.method == AoMethod::Rtao && c.frames != frames;
                let waited = now - c.at;
                // Another truth: compare at once, not to show the last truth's map meanwhile.
                c.key != key
                    || (changed && waited >= FOLLOW_INTERVAL)
                    || (accumulating && waited >= ACCUMULATION_INTERVAL)
            }
        };
        if !due {
            return;
        }
        self.compared = Some(Compared {
            at: now,
            key,
            settings,
            frames,
        });
        match evaluate(engine, &truth, backend.as_ref()) {
            Ok(p) => {
                if self.report {
                    crate::outln!(
                        "{}",
                        t!(
                            "truth.psnr",
                            psnr = format!("{:.2}", p.psnr),
                            rmse = format!("{:.4}", p.rmse)
                        )
                    );
                }
                self.picture = Some(p);
                self.texture_stale = true;
                self.comparison_error = None;
            }
            Err(e) => self.comparison_error = Some(format!("{e:#}")),
        }
    }

    /// The panel's truth section: state, progress bar, the button. True when the button was
    /// clicked (compute the truth of this view).
    pub fn panel_section(&mut self, ui: &mut egui::Ui, engine: &Engine, lang: Lang) -> bool {
        let tr = |key: &str| t!(key, locale = lang.code()).into_owned();
        ui.strong(tr("truth.heading"));
        if self.backend.is_none() {
            ui.small(tr("truth.unavailable"));
            return false;
        }
        let Some(key) = view_key(engine) else {
            let (w, h) = engine.size();
            ui.small(t!(
                "truth.no_size",
                locale = lang.code(),
                size = format!("{w}x{h}")
            ));
            return false;
        };
        let status = self.state.status(&key);
        match &status {
            TruthStatus::Off => {
                ui.small(tr("truth.off"));
            }
            TruthStatus::Computing(share) => {
                ui.add(
                    egui::ProgressBar::new(*share)
                        .show_percentage()
                        .text(tr("truth.computing")),
                );
            }
            TruthStatus::Ready(truth) => {
                let size = format!("{}x{}", truth.width, truth.height);
                ui.small(t!("truth.ready", locale = lang.code(), size = size));
                match (&self.picture, &self.comparison_error) {
                    (_, Some(e)) => {
                        ui.colored_label(FAILURE_RED, e);
                    }
                    (Some(p), None) => {
                        ui.label(psnr_text(p, lang));
                    }
                    _ => {}
                }
            }
            TruthStatus::Stale(why) => {
                let reason = match why {
                    Stale::Camera => "truth.stale_camera",
                    Stale::Radius => "truth.stale_radius",
                    Stale::Scene => "truth.stale_scene",
                    Stale::Size => "truth.stale_size",
                };
                ui.colored_label(egui::Color32::YELLOW, tr(reason));
            }
            TruthStatus::Failed(e) => {
                ui.colored_label(
                    FAILURE_RED,
                    t!("truth.failed", locale = lang.code(), error = e),
                );
            }
        }
        let label = match status {
            TruthStatus::Off => "truth.compute",
            TruthStatus::Ready(_) => "truth.show",
            _ => "truth.recompute",
        };
        let clicked = ui
            .add_enabled(
                !matches!(status, TruthStatus::Computing(_)),
                egui::Button::new(tr(label)),
            )
            .on_hover_text(tr("truth.help"))
            .clicked();
        if matches!(status, TruthStatus::Ready(_)) {
            ui.checkbox(&mut self.shown, tr("truth.show_map"));
        }
        clicked
    }

    /// The floating window with the error map, while open and the view's truth is ready.
    pub fn map_window(&mut self, ctx: &egui::Context, engine: &Engine, lang: Lang) {
        let ready = view_key(engine)
            .is_some_and(|k| matches!(self.state.status(&k), TruthStatus::Ready(_)));
        if !self.shown || !ready {
            return;
        }
        let Some(picture) = &self.picture else { return };
        if self.texture_stale || self.texture.is_none() {
            let img = &picture.image;
            let size = [img.width() as usize, img.height() as usize];
            let colour = egui::ColorImage::from_rgb(size, img.as_raw());
            match &mut self.texture {
                Some(t) => t.set(colour, egui::TextureOptions::NEAREST),
                None => {
                    self.texture = Some(ctx.load_texture(
                        "truth error map",
                        colour,
                        egui::TextureOptions::NEAREST,
                    ))
                }
            }
            self.texture_stale = false;
        }
        let Some(texture) = &self.texture else { return };
        let title = t!(
            "truth.window_title",
            locale = lang.code(),
            method = engine.ao_settings.method.name()
        );
        let [w, h] = texture.size();
        // Small windows keep most of the scene in sight.
        let width = MAP_WIDTH.min(ctx.content_rect().width() * 0.45);
        let size = egui::vec2(width, width * h as f32 / w.max(1) as f32);
        let text = psnr_text(picture, lang);
        let legend = t!("truth.legend", locale = lang.code());
        egui::Window::new(title.as_ref())
            .id(egui::Id::unique("truth error map"))
            .open(&mut self.shown)
            .anchor(egui::Align2::RIGHT_TOP, egui::vec2(-6.0, 6.0))
            .resizable(false)
            .show(ctx, |ui| {
                ui.image((texture.id(), size));
                ui.label(text);
                ui.small(legend);
            });
    }
}

fn psnr_text(p: &ErrorPicture, lang: Lang) -> String {
    t!(
        "truth.psnr",
        locale = lang.code(),
        psnr = format!("{:.2}", p.psnr),
        rmse = format!("{:.4}", p.rmse)
    )
    .into_owned()
}
