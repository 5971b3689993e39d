//! The window's egui parameter panel (F1) and the shader-error overlay.
//!
//! Only the UI lives here: the window (`window/mod.rs`) feeds it events, paints it after the engine's
//! frame and acts on what it returns (rebuilding shaders whose compile-time constants changed).

use crate::ao::method::vbao::feature_defines;
use crate::ao::method_pass::normal_source_define;
use crate::ao::settings::{
    AoSettings, NormalUse, SlabHierarchy, POWER_RANGE, RAYS_RANGE, SAMPLES_RANGE,
    SPIRAL_TURNS_RANGE,
};
use crate::ao::user_method::{UserMethod, HOST};
use crate::ao::{AoMethod, AoResolution, CompositeMode, GuardBand, NormalSource, Thickness};
use crate::i18n::Lang;
use crate::platform::window::accumulation::WINDOW_ACCUMULATE;
use crate::platform::window::truth_view::TruthView;
use crate::render::{Engine, PassStat, View};
use egui::{Color32, RichText};
use rust_i18n::t;
use std::collections::HashMap;

/// Width the panel opens at (points); the user may drag its edge.
const PANEL_WIDTH: f32 = 260.0;
/// The panel never covers more than this share of the window, so the scene stays visible.
const PANEL_MAX_SHARE: f32 = 0.6;
/// Slider ends narrower than the ranges the settings accept (`ao::settings`), where a drag across
/// the whole accepted range would leave no precision for the values scenes use: radius and
/// thickness (m, logarithmic), bias (m), intensity; rays per frame.
const RADIUS_SLIDER: (f32, f32) = (0.01, 10.0);
const THICKNESS_SLIDER: (f32, f32) = (0.01, 10.0);
const BIAS_SLIDER: (f32, f32) = (0.0, 0.2);
const INTENSITY_SLIDER: (f32, f32) = (0.0, 50.0);
const RAYS_SLIDER_MAX: u32 = 64;
/// Weight of the newest frame in the smoothed pass times (single frames on llvmpipe jitter a lot).
const TIME_SMOOTHING: f64 = 0.25;

/// Shader errors (`file:line: message` lines) stay on screen in this colour until fixed.
pub const ERROR_RED: Color32 = Color32::from_rgb(255, 70, 60);
const ERROR_BACKGROUND: Color32 = Color32::from_rgba_premultiplied(20, 0, 0, 235);

/// What the window must do after the panel changed parameters.
#[derive(Default, Debug, PartialEq, Eq)]
pub struct PanelActions {
    /// Sample count, spiral turns or method changed: they are `#define`s, so shaders are rebuilt.
    pub sync_shader_constants: bool,
    /// "Rebuild shaders" was clicked (same as R).
    pub reload_shaders: bool,
    /// The truth of this view was asked for (same as T).
    pub compute_truth: bool,
}

pub struct Panel {
    pub visible: bool,
    /// "vendor / renderer / version" of the window's context, shown next to the times.
    renderer: String,
    /// The language of the labels (English when no font can draw the chosen one).
    lang: Lang,
    smoothed_ms: HashMap<&'static str, f64>,
    /// Sample count being dragged: applied on release, as each value costs a shader compile.
    pending_samples: Option<u32>,
    /// `rtao`'s rays per frame being dragged, likewise.
    pending_rays: Option<u32>,
}

impl Panel {
    pub fn new(visible: bool, renderer: String, lang: Lang) -> Panel {
        Panel {
            visible,
            renderer,
            lang,
            smoothed_ms: HashMap::new(),
            pending_samples: None,
            pending_rays: None,
        }
    }

    /// The language of the labels.
    pub fn lang(&self) -> Lang {
        self.lang
    }

    /// Builds the frame's UI: the error overlay (whenever `shader_errors` is non-empty), then the
    /// panel or, when hidden, a one-line hint.
    pub fn show(
        &mut self,
        ui: &mut egui::Ui,
        engine: &mut Engine,
        shader_errors: &[String],
        truth: &mut TruthView,
    ) -> PanelActions {
        let mut actions = PanelActions::default();
        // Before the side panel, so the overlay spans the whole width and stays visible when the
        // panel is hidden.
        if !shader_errors.is_empty() {
            error_overlay(ui, shader_errors, self.lang);
        }
        if self.visible {
            let max_width = (ui.ctx().content_rect().width() * PANEL_MAX_SHARE).max(80.0);
            egui::Panel::left("parameters")
                .default_size(PANEL_WIDTH.min(max_width))
                .max_size(max_width)
                .show(ui, |ui| {
                    egui::ScrollArea::vertical().show(ui, |ui| {
                        self.contents(ui, engine, &mut actions);
                        ui.separator();
                        actions.compute_truth |= truth.panel_section(ui, engine, self.lang);
                    });
                });
        } else {
            egui::Area::new(egui::Id::unique("panel hint"))
                .anchor(egui::Align2::LEFT_TOP, egui::vec2(6.0, 6.0))
                .interactable(false)
                .show(ui.ctx(), |ui| {
                    egui::Frame::popup(ui.style()).show(ui, |ui| {
                        ui.small(label(self.lang, "panel.hint"));
                    });
                });
        }
        let (clean, notes) = engine.ao_settings.sanitized();
        for n in notes {
            log::warn!("{n}");
        }
        engine.ao_settings = clean;
        actions
    }

    fn contents(&mut self, ui: &mut egui::Ui, engine: &mut Engine, actions: &mut PanelActions) {
        let lang = self.lang;
        let tr = |key: &str| label(lang, key);
        ui.heading(tr("panel.heading"));
        ui.small(tr("panel.hide_hint"));
        // A method file running in its host's place goes by its own name.
        let shown = engine.ao.own_labels(engine.ao_settings.method);
        let p = &mut engine.ao_settings;
        ui.checkbox(&mut p.enabled, tr("panel.ao_on"));
        let compiled = compiled_choices(p);

        let before = p.method;
        egui::ComboBox::from_label(tr("panel.method"))
            .selected_text(shown.map_or(p.method.name(), |(name, _)| name))
            .show_ui(ui, |ui| {
                for m in AoMethod::ALL {
                    ui.selectable_value(&mut p.method, m, m.name());
                }
            });
        // A method file in the chosen method's place recommends its own configuration.
        let recommended = engine.ao.recommended(p.method);
        if p.method != before {
            crate::scene::ao_defaults::apply_from(p, &recommended);
            actions.sync_shader_constants = true;
        }
        ui.small(format!(
            "{}: {}",
            tr("panel.configuration"),
            crate::scene::ao_defaults::chosen_line_from(p, &recommended)
        ))
        .on_hover_text(tr("panel.configuration_help"));

        // What the method reads decides what the panel offers (`MethodInfo`).
        let info = p.method.info();
        // The engine's methods can run at the main size; the lesson's SAO stays at half as taught.
        let resolution = p.resolution;
        ui.add_enabled_ui(info.engine_chain, |ui| {
            egui::ComboBox::from_label(tr("panel.resolution"))
                .selected_text(p.resolution.name())
                .show_ui(ui, |ui| {
                    for r in AoResolution::ALL {
                        ui.selectable_value(&mut p.resolution, r, r.name());
                    }
                })
        });
        actions.sync_shader_constants |= p.resolution != resolution;
        if info.normals == NormalUse::Chosen {
            let mut geometric = p.normals == NormalSource::Geometric;
            ui.checkbox(&mut geometric, tr("panel.geometric_normals"))
                .on_hover_text(tr("panel.geometric_normals_help"));
            p.normals = if geometric {
                NormalSource::Geometric
            } else {
                NormalSource::Depth
            };
        }
        if info.engine_chain {
            let mut guard = p.guard_band != GuardBand::Off;
            ui.checkbox(&mut guard, tr("panel.guard_band"))
                .on_hover_text(tr("panel.guard_band_help"));
            p.guard_band = match (guard, p.guard_band) {
                (false, _) => GuardBand::Off,
                (true, GuardBand::Off) => GuardBand::Auto,
                (true, g) => g,
            };
        }
        if info.second_layer {
            let mut second = p.layers >= 2;
            ui.checkbox(&mut second, tr("panel.second_layer"))
                .on_hover_text(tr("panel.second_layer_help"));
            p.layers = if second { 2 } else { 1 };
        }
        if info.thickness {
            let mut back_faces = p.thickness == Some(Thickness::Backface);
            if info.back_faces {
                ui.checkbox(&mut back_faces, tr("panel.backface"))
                    .on_hover_text(tr("panel.backface_help"));
            }
            let mut metres = p.thickness_metres();
            let r = ui.add_enabled(
                !back_faces,
                egui::Slider::new(&mut metres, THICKNESS_SLIDER.0..=THICKNESS_SLIDER.1)
                    .logarithmic(true)
                    .suffix(" m")
                    .text(tr("panel.thickness")),
            );
            p.thickness = if back_faces {
                Some(Thickness::Backface)
            } else if r.changed() || matches!(p.thickness, Some(Thickness::Backface)) {
                Some(Thickness::Metres(metres))
            } else {
                p.thickness
            };
        }
        if info.slab_hierarchy {
            // Shows what `auto` decided; a click sets it on or off explicitly.
            let mut hierarchy = p.uses_slab_hierarchy();
            if ui
                .checkbox(&mut hierarchy, tr("panel.slab_hierarchy"))
                .on_hover_text(tr("panel.slab_hierarchy_help"))
                .changed()
            {
                p.slab_hierarchy = if hierarchy {
                    SlabHierarchy::On
                } else {
                    SlabHierarchy::Off
                };
            }
        }

        // The shaders compile only the paths these choices use.
        actions.sync_shader_constants |= compiled_choices(p) != compiled;

        // A method file's parameters, one slider each over the file's range: a change rebuilds its
        // shader with the new #defines.
        if let Some(user) = engine.ao.pass_of_mut::<UserMethod>(HOST) {
            ui.label(format!("{} {}", tr("panel.method_file"), user.file().name));
            let mut changed = Vec::new();
            for param in &user.file().parameters {
                let mut v = param.value;
                let slider = egui::Slider::new(&mut v, param.min..=param.max).text(&param.name);
                if ui.add(slider).changed() {
                    changed.push((param.name.clone(), v));
                }
            }
            for (name, v) in changed {
                actions.sync_shader_constants |= user.set_parameter(&name, v).is_ok();
            }
        }
        let p = &mut engine.ao_settings;

        egui::ComboBox::from_label(tr("panel.composite"))
            .selected_text(composite_name(p.composite))
            .show_ui(ui, |ui| {
                for c in [
                    CompositeMode::Blend,
                    CompositeMode::Tinted,
                    CompositeMode::AmbientOnly,
                ] {
                    ui.selectable_value(&mut p.composite, c, composite_name(c));
                }
            })
            .response
            .on_hover_text(tr("panel.composite_help"));
        if p.composite == CompositeMode::Tinted {
            ui.horizontal(|ui| {
                ui.color_edit_button_rgb(&mut p.tint);
                ui.label(tr("panel.tint"));
            });
            ui.add(
                egui::Slider::new(&mut p.power, POWER_RANGE.0..=POWER_RANGE.1)
                    .logarithmic(true)
                    .text(tr("panel.power")),
            );
        }

        ui.separator();
        ui.add(
            egui::Slider::new(&mut p.radius, RADIUS_SLIDER.0..=RADIUS_SLIDER.1)
                .logarithmic(true)
                .suffix(" m")
                .text(tr("panel.radius")),
        );
        ui.add(
            egui::Slider::new(&mut p.bias, BIAS_SLIDER.0..=BIAS_SLIDER.1)
                .suffix(" m")
                .text(tr("panel.bias")),
        )
        .on_hover_text(tr("panel.bias_help"));
        ui.add(
            egui::Slider::new(&mut p.intensity, INTENSITY_SLIDER.0..=INTENSITY_SLIDER.1)
                .logarithmic(true)
                .text(tr("panel.intensity")),
        );

        // Compile-time constants: apply when the slider is released, not at every step of a drag.
        let mut samples = self.pending_samples.unwrap_or(p.samples);
        let r = ui
            .add(
                egui::Slider::new(&mut samples, SAMPLES_RANGE.0..=SAMPLES_RANGE.1)
                    .logarithmic(true)
                    .text(tr("panel.samples")),
            )
            .on_hover_text(tr("panel.samples_help"));
        if r.dragged() {
            self.pending_samples = Some(samples);
        } else if samples != p.samples || self.pending_samples.is_some() {
            self.pending_samples = None;
            actions.sync_shader_constants |= samples != p.samples;
            p.samples = samples;
        }
        let turns = p.spiral_turns;
        ui.add_enabled(
            info.spiral_turns,
            egui::Slider::new(
                &mut p.spiral_turns,
                SPIRAL_TURNS_RANGE.0..=SPIRAL_TURNS_RANGE.1,
            )
            .text(tr("panel.spiral_turns")),
        )
        .on_hover_text(tr("panel.spiral_help"));
        actions.sync_shader_constants |= p.spiral_turns != turns;
        ui.checkbox(&mut p.blur, tr("panel.blur"));
        if info.rays {
            self.rtao_section(ui, engine, actions);
        }

        ui.separator();
        egui::ComboBox::from_label(tr("panel.view"))
            .selected_text(tr(&format!("view.{}", engine.view.name())))
            .show_ui(ui, |ui| {
                let second_layer = engine.ao_settings.uses_second_layer();
                for v in View::ALL.into_iter().filter(|v| v.available(second_layer)) {
                    ui.selectable_value(&mut engine.view, v, tr(&format!("view.{}", v.name())));
                }
            });
        if ui.button(tr("panel.rebuild")).clicked() {
            actions.reload_shaders = true;
        }

        ui.separator();
        ui.checkbox(&mut engine.collect_stats, tr("panel.time_passes"))
            .on_hover_text(tr("panel.time_passes_help"));
        if engine.collect_stats {
            self.timing_table(ui, &engine.last_stats());
        } else {
            self.smoothed_ms.clear();
        }
    }

    /// `rtao`: rays per frame, the running mean and its frame count, the BVH's cost.
    fn rtao_section(&mut self, ui: &mut egui::Ui, engine: &mut Engine, actions: &mut PanelActions) {
        let tr = |key: &str| label(self.lang, key);
        let code = self.lang.code();
        let p = &mut engine.ao_settings;
        let mut rays = self.pending_rays.unwrap_or(p.rays);
        let r = ui.add(
            egui::Slider::new(&mut rays, RAYS_RANGE.0..=RAYS_SLIDER_MAX)
                .logarithmic(true)
                .text(tr("panel.rays")),
        );
        if r.dragged() {
            self.pending_rays = Some(rays);
        } else if rays != p.rays || self.pending_rays.is_some() {
            self.pending_rays = None;
            actions.sync_shader_constants |= rays != p.rays;
            p.rays = rays;
        }
        let mut accumulate = p.accumulate > 1;
        ui.checkbox(&mut accumulate, tr("panel.accumulate"))
            .on_hover_text(tr("panel.accumulate_help"));
        p.accumulate = match (accumulate, p.accumulate) {
            (false, _) => 1,
            (true, 1) => WINDOW_ACCUMULATE,
            (true, n) => n,
        };
        if accumulate {
            let frames = engine.ao.accumulated_frames(p.method);
            ui.small(t!(
                "panel.frames",
                locale = code,
                n = frames,
                max = p.accumulate
            ));
        }
        if let Some(b) = engine.ao.bvh_stats(p.method) {
            let mib = format!("{:.2}", b.bytes as f64 / (1024.0 * 1024.0));
            let ms = format!("{:.1}", b.build_ms);
            ui.small(t!(
                "panel.bvh",
                locale = code,
                triangles = b.triangles,
                nodes = b.nodes,
                mib = mib,
                ms = ms,
                builds = b.builds
            ));
        }
    }

    fn timing_table(&mut self, ui: &mut egui::Ui, stats: &[PassStat]) {
        let renderer = &self.renderer;
        // Each figure's clock: the GPU's timer query on a hardware driver, else the wall clock.
        let gpu = stats
            .iter()
            .any(|s| s.clock == crate::gl::PassClock::GpuTimer);
        let (caption, unit) = if gpu {
            ("panel.times_caption_gpu", "panel.ms_gpu")
        } else {
            ("panel.times_caption", "panel.ms")
        };
        ui.small(t!(caption, locale = self.lang.code(), renderer = renderer));
        let tr = |key: &str| label(self.lang, key);
        self.smoothed_ms
            .retain(|name, _| stats.iter().any(|s| s.name == *name));
        egui::Grid::new("pass times")
            .num_columns(3)
            .striped(true)
            .show(ui, |ui| {
                ui.strong(tr("panel.pass"));
                ui.strong(tr("panel.group"));
                ui.strong(tr(unit));
                ui.end_row();
                let mut total = 0.0;
                for s in stats {
                    let ms = self
                        .smoothed_ms
                        .entry(s.name)
                        .and_modify(|m| *m += (s.ms - *m) * TIME_SMOOTHING)
                        .or_insert(s.ms);
                    total += *ms;
                    ui.label(s.name);
                    ui.label(s.group);
                    ui.monospace(format!("{ms:7.2}"));
                    ui.end_row();
                }
                ui.strong(tr("panel.total"));
                ui.label("");
                ui.monospace(format!("{total:7.2}"));
                ui.end_row();
            });
    }
}

/// The panel's text `key` (a `panel.` key of locales/*.yml) in `lang`.
fn label(lang: Lang, key: &str) -> String {
    t!(key, locale = lang.code()).into_owned()
}

fn composite_name(c: CompositeMode) -> &'static str {
    match c {
        CompositeMode::Blend => "blend",
        CompositeMode::Tinted => "tinted",
        CompositeMode::AmbientOnly => "ambient-only",
    }
}

/// Red, monospaced `file:line: message` lines along the bottom of the window.
fn error_overlay(ui: &mut egui::Ui, shader_errors: &[String], lang: Lang) {
    let frame = egui::Frame::NONE
        .fill(ERROR_BACKGROUND)
        .inner_margin(egui::Margin::same(6));
    egui::Panel::bottom("shader errors")
        .frame(frame)
        .resizable(false)
        .show(ui, |ui| {
            ui.add(
                egui::Label::new(
                    RichText::new(label(lang, "panel.error_title")).color(Color32::WHITE),
                )
                .truncate(),
            );
            // Lines are not wrapped (long paths would push the message out of sight): scroll sideways.
            egui::ScrollArea::both()
                .max_height(ui.ctx().content_rect().height() * 0.4)
                .show(ui, |ui| {
                    // Paths under the working directory are shown relative to it: shorter lines.
                    let cwd = std::env::current_dir()
                        .map(|d| format!("{}/", d.display()))
                        .unwrap_or_default();
                    for line in shader_errors.iter().flat_map(|e| e.lines()) {
                        let line = match line.strip_prefix(cwd.as_str()) {
                            Some(rest) if !cwd.is_empty() => rest,
                            _ => line,
                        };
                        ui.add(
                            egui::Label::new(RichText::new(line).monospace().color(ERROR_RED))
                                .extend(),
                        );
                    }
                });
        });
}

/// The settings the AO shaders are compiled for (`vbao`'s inputs, the normal source): a change needs
/// `sync_shader_constants`.
fn compiled_choices(s: &AoSettings) -> Vec<(&'static str, String)> {
    let mut v = feature_defines(s);
    v.push(normal_source_define(s));
    v
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_options_the_shaders_are_compiled_for_ask_for_a_rebuild_and_the_others_do_not() {
        let vbao = AoSettings {
            method: AoMethod::Vbao,
            ..Default::default()
        };
        let changed = |s: AoSettings| compiled_choices(&s) != compiled_choices(&vbao);
        assert!(changed(AoSettings {
            thickness: Some(Thickness::Backface),
            ..vbao
        }));
        assert!(changed(AoSettings {
            normals: NormalSource::Geometric,
            ..vbao
        }));
        assert!(changed(AoSettings { layers: 2, ..vbao }));
        assert!(changed(AoSettings {
            slab_hierarchy: SlabHierarchy::On,
            ..vbao
        }));
        assert!(!changed(AoSettings {
            intensity: 2.0,
            radius: 0.5,
            ..vbao
        }));
    }

    /// The keys of a locale file (`key: "value"` lines).
    fn keys(text: &str) -> Vec<&str> {
        text.lines()
            .filter(|l| !l.starts_with(' ') && !l.starts_with('#'))
            .filter_map(|l| l.split_once(':').map(|(k, _)| k))
            .collect()
    }

    #[test]
    fn every_label_of_the_panel_is_written_in_english_and_in_japanese() {
        // The panel's code, without these tests.
        let source = include_str!("panel.rs")
            .split("#[cfg(test)]")
            .next()
            .unwrap();
        let keys_after = |source: &'static str, prefix: &'static str| {
            source
                .split(prefix)
                .skip(1)
                .filter_map(|rest| rest.split_once('"').map(|(k, _)| k))
                .filter(|k| {
                    !k.is_empty() && k.chars().all(|c| c.is_ascii_alphanumeric() || c == '_')
                })
                .map(move |k| format!("{}{k}", &prefix[1..]))
                .collect::<Vec<_>>()
        };
        let mut used = keys_after(source, "\"panel.");
        assert!(used.len() >= 20, "{used:?}");
        // The truth view's section and map window.
        let truth = keys_after(include_str!("window/truth_view.rs"), "\"truth.");
        assert!(truth.len() >= 10, "{truth:?}");
        used.extend(truth);
        let (en, ja) = (
            keys(include_str!("../../locales/en.yml")),
            keys(include_str!("../../locales/ja.yml")),
        );
        for key in used {
            assert!(en.contains(&key.as_str()), "{key} missing from en.yml");
            assert!(ja.contains(&key.as_str()), "{key} missing from ja.yml");
            let (e, j) = (label(Lang::En, &key), label(Lang::Ja, &key));
            assert_ne!(e, j, "{key} is not translated");
            assert!(!j.contains(&key), "{key}: {j}");
            assert!(!j.is_ascii(), "{key}: {j} is not Japanese");
        }
    }
}
