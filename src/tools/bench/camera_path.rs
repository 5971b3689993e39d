//! `opengl3d bench --camera-path`: the screen-space methods accumulated over frames
//! (`ao::temporal`) against the same methods one frame at a time, along a camera path per scene
//! and test camera: a still segment (the accumulation converges), then a slow orbit with a dolly
//! (the history is reprojected). Every frame is scored against the ray-traced truth of its own
//! camera (footprint means, cached like the bench's references); the frame-to-frame change where
//! the truth stands still measures flicker, and the error in pixels the previous frame did not see
//! measures ghosting. `--path-rows` picks the configurations (`camera_path_rows`), `--path-train`
//! runs the training cameras instead, to choose on. Costs are the AO passes' time per frame as a ratio to the lesson's chain in
//! the same run. Writes `camera-path.json`, `camera-path.md` and a chart per scene.

use super::camera_path_report as report;
use super::camera_path_rows::{self as rows, PathRows};
use super::camera_path_score::{self as score, FrameScore, PathReport, PathRun, PathSetting};
use super::catalog;
use super::perf::references as perf_refs;
use crate::ao::{AoMethod, AoSettings, SlicePreset};
use crate::math::Camera;
use crate::platform::HeadlessContext;
use crate::render::{Engine, View};
use crate::res::ResDirs;
use crate::scene::ao_defaults::{self, WrittenKeys};
use crate::tools::reference::{load_or_render_cached, AoVariant, RefImage, RefParams};
use anyhow::{Context as _, Result};
use glam::Quat;
use std::path::PathBuf;

/// What a camera-path run measures.
#[derive(Clone, Debug)]
pub struct CameraPathConfig {
    pub scenes: Vec<PathBuf>,
    /// Models (`--obj`), each a scene of its own framed from its bounds, the radius scaled by the
    /// radius framing chose (as the bench's rows are).
    pub models: Vec<PathBuf>,
    pub width: u32,
    pub height: u32,
    /// The truth is rendered at 1/`ref_scale` and the engine's output box-averaged to it.
    pub ref_scale: u32,
    pub ref_rays: u32,
    pub cache: PathBuf,
    /// Frames of each segment (still, then moving).
    pub frames: u32,
    /// The accumulated configurations' history length (`--accumulate`).
    pub accumulate: u32,
    pub out: PathBuf,
    pub progress: bool,
    /// The configurations besides the lesson's chain.
    pub rows: Vec<PathRows>,
    /// Run the training cameras instead of the test cameras.
    pub train: bool,
}

/// Degrees the orbit turns per frame, and the share of the distance the dolly closes per frame.
pub const ORBIT_DEG_PER_FRAME: f32 = 0.5;
pub const DOLLY_PER_FRAME: f32 = 0.004;
/// The AO radius every configuration uses (m), the bench's default.
pub const RADIUS: f32 = 1.0;

/// `vbao` as a user gets it with `--method vbao` (the recommendation, the scene's written keys
/// kept), or the lesson's set-up with the cheapest preset (`low`, half size, one layer, normals
/// from depth, no guard band).
fn vbao_settings(base: &AoSettings, recommended: bool, radius: f32) -> AoSettings {
    let mut s = AoSettings {
        method: AoMethod::Vbao,
        radius,
        enabled: true,
        ..*base
    };
    if recommended {
        ao_defaults::apply(&mut s);
    } else {
        s.written = WrittenKeys::default();
        ao_defaults::apply_from(&mut s, &ao_defaults::PLAIN);
        s.quality = Some(SlicePreset::Low);
    }
    s
}

/// The configurations at AO radius `radius`: the lesson's chain (the cost unit), then each of
/// `families`.
pub fn settings(
    accumulate: u32,
    base: &AoSettings,
    families: &[PathRows],
    radius: f32,
) -> Vec<(PathSetting, AoSettings)> {
    let mut out = vec![lesson(base, radius)];
    for family in families {
        match *family {
            PathRows::Vbao => out.extend(vbao_rows(accumulate, base, radius)),
            PathRows::Rtao {
                resolution,
                rays,
                blur,
            } => out.extend(rows::rtao_rows(
                base, radius, resolution, rays, blur, accumulate,
            )),
        }
    }
    out
}

/// The lesson's chain, the cost unit.
fn lesson(base: &AoSettings, radius: f32) -> (PathSetting, AoSettings) {
    let lesson = AoSettings {
        method: AoMethod::SaoLesson,
        radius,
        enabled: true,
        ..*base
    };
    (
        PathSetting {
            label: "sao-lesson".into(),
            method: AoMethod::SaoLesson,
            accumulate: 1,
            settings: format!("n11, R {radius} m"),
        },
        lesson,
    )
}

/// `vbao` in two set-ups, each one frame at a time and accumulated, and the recommended one
/// accumulated without its blur.
fn vbao_rows(accumulate: u32, base: &AoSettings, radius: f32) -> Vec<(PathSetting, AoSettings)> {
    let mut out = Vec::new();
    let mut push = |short: &str, s: AoSettings| {
        let frames = match s.accumulate {
            1 => String::new(),
            n => format!(" ×{n}"),
        };
        let unblurred = if s.blur { "" } else { ", no blur" };
        let label = format!("vbao {short}{frames}{unblurred}");
        let what = format!("{}{unblurred}", ao_defaults::chosen_line(&s));
        let setting = PathSetting {
            label,
            method: AoMethod::Vbao,
            accumulate: s.accumulate,
            settings: what,
        };
        out.push((setting, s));
    };
    for (recommended, short) in [(true, "default"), (false, "low")] {
        for n in [1, accumulate] {
            let s = AoSettings {
                accumulate: n,
                ..vbao_settings(base, recommended, radius)
            };
            push(short, s);
        }
    }
    // Accumulated without the blur: the frames average the noise the blur would, without its
    // smoothing across edges.
    let unblurred = AoSettings {
        accumulate,
        blur: false,
        ..vbao_settings(base, true, radius)
    };
    push("default", unblurred);
    out
}

/// The path from `start`: `still` frames at it, then `moving` frames orbiting its target to the
/// left while closing in, the first of them still at `start` (each one step further than the last).
pub fn path(start: &Camera, still: u32, moving: u32) -> Vec<Camera> {
    let offset = start.eye - start.target;
    (0..still + moving)
        .map(|i| {
            let k = i.saturating_sub(still) as f32;
            if k == 0.0 {
                // Exactly the start: `target + (eye - target)` may round to another eye.
                return *start;
            }
            let turn = Quat::from_rotation_y((-ORBIT_DEG_PER_FRAME * k).to_radians());
            let eye = start.target + turn * offset * (1.0 - DOLLY_PER_FRAME * k);
            Camera { eye, ..*start }
        })
        .collect()
}

/// The truth's parameters: footprint means over the `ref_scale`² engine pixels, the bench's seed.
fn truth_params(cfg: &CameraPathConfig, radius: f32) -> RefParams {
    RefParams {
        radius,
        rays: cfg.ref_rays,
        variant: AoVariant::Visibility,
        seed: 1,
        progress: false,
        supersample: cfg.ref_scale,
    }
}

/// Runs every scene's test cameras along the path and writes the report and charts.
pub fn run(res: &ResDirs, cfg: &CameraPathConfig) -> Result<PathReport> {
    let t0 = std::time::Instant::now();
    std::fs::create_dir_all(&cfg.out)
        .with_context(|| format!("cannot create {}", cfg.out.display()))?;
    // The demo scene when neither a scene nor a model is named.
    let scenes: Vec<PathBuf> = if cfg.scenes.is_empty() && cfg.models.is_empty() {
        vec![res
            .find("scenes/demo.toml")
            .map_err(|e| anyhow::anyhow!("{e}"))?]
    } else {
        cfg.scenes.clone()
    };
    let ctx = HeadlessContext::new()?;
    let (rw, rh) = (cfg.width / cfg.ref_scale, cfg.height / cfg.ref_scale);
    let size = (cfg.width, cfg.height);
    let files = scenes.iter().map(|f| (f, false));
    let models = cfg.models.iter().map(|f| (f, true));
    let mut runs = Vec::new();
    for (path_file, is_model) in files.chain(models) {
        let (sd, bvh) = if is_model {
            perf_refs::model_scene(res, path_file, size, true)?
        } else {
            perf_refs::scene_at(res, path_file, size)?
        };
        let (name, desc) = (sd.name, sd.desc);
        let radius = RADIUS * sd.radius_scale;
        let mut engine = Engine::new(&ctx.gl, res.clone(), &desc, cfg.width, cfg.height)?;
        let base = engine.ao_settings;
        for cam in catalog::camera_variants(&desc.camera)
            .iter()
            .filter(|c| c.train == cfg.train)
        {
            let cameras = path(&cam.camera(&desc.camera), cfg.frames, cfg.frames);
            let truths: Vec<RefImage> = cameras
                .iter()
                .enumerate()
                .map(|(i, c)| {
                    if cfg.progress {
                        eprintln!(
                            "truth {name}/{} frame {}/{}",
                            cam.name,
                            i + 1,
                            cameras.len()
                        );
                    }
                    load_or_render_cached(&cfg.cache, &bvh, c, rw, rh, &truth_params(cfg, radius))
                })
                .collect();
            let fresh = score::disoccluded(&cameras, &truths);
            for (setting, s) in settings(cfg.accumulate, &base, &cfg.rows, radius) {
                if cfg.progress {
                    eprintln!("{name}/{} {}", cam.name, setting.label);
                }
                let frames = run_path(&mut engine, &s, &cameras, &truths, &fresh, cfg)?;
                let summary = score::summarise(&frames, cfg.frames as usize);
                runs.push(PathRun {
                    scene: name.clone(),
                    camera: cam.name.clone(),
                    setting,
                    frames,
                    summary,
                });
            }
        }
    }
    score::set_cost_ratios(&mut runs);
    let report = PathReport {
        renderer: ctx.renderer.clone(),
        width: cfg.width,
        height: cfg.height,
        ref_scale: cfg.ref_scale,
        ref_rays: cfg.ref_rays,
        still_frames: cfg.frames,
        moving_frames: cfg.frames,
        accumulate: cfg.accumulate,
        orbit_deg_per_frame: ORBIT_DEG_PER_FRAME,
        dolly_per_frame: DOLLY_PER_FRAME,
        runs,
        run_s: t0.elapsed().as_secs_f64(),
    };
    report::write(&report, &cfg.out)?;
    Ok(report)
}

/// Renders `cameras` in order with `settings` from an empty history, scoring each frame.
fn run_path(
    engine: &mut Engine,
    settings: &AoSettings,
    cameras: &[Camera],
    truths: &[RefImage],
    fresh: &[Vec<bool>],
    cfg: &CameraPathConfig,
) -> Result<Vec<FrameScore>> {
    engine.ao_settings = *settings;
    engine.camera = cameras[0];
    engine.sync_shader_constants()?;
    // One frame unscored and untimed: the first frame compiles the shaders and creates targets.
    engine.render_values(View::Ao)?;
    engine.temporal.restart();
    engine.ao.restart_accumulation();
    engine.collect_stats = true;
    let mut out = Vec::new();
    let mut previous: Option<Vec<f32>> = None;
    for (i, (camera, truth)) in cameras.iter().zip(truths).enumerate() {
        engine.camera = *camera;
        let values = engine.render_values(View::Ao)?;
        let ao_ms: f64 = engine
            .last_stats()
            .iter()
            .filter(|p| p.group == "ao")
            .map(|p| p.cpu_ms)
            .sum();
        let (small, _, _) = crate::tools::metrics::downsample(
            &values,
            cfg.width as usize,
            cfg.height as usize,
            cfg.ref_scale as usize,
        );
        let prev_truth = i.checked_sub(1).map(|p| &truths[p]);
        out.push(score::score_frame(
            &small,
            previous.as_deref(),
            truth,
            prev_truth,
            &fresh[i],
            ao_ms,
        ));
        previous = Some(small);
    }
    engine.collect_stats = false;
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::Vec3;

    #[test]
    fn the_path_stands_still_then_orbits_and_closes_in() {
        let start = Camera {
            eye: Vec3::new(0.0, 2.0, 10.0),
            target: Vec3::ZERO,
            ..Camera::default()
        };
        let p = path(&start, 3, 4);
        assert_eq!(p.len(), 7);
        assert!(p[..3].iter().all(|c| c.eye == start.eye));
        let d = |c: &Camera| (c.eye - c.target).length();
        // The moving segment starts where the still one stands and moves from its second frame.
        assert_eq!(p[3].eye, start.eye);
        for w in p[3..].windows(2) {
            assert!(d(&w[1]) < d(&w[0]), "the dolly closes in");
            assert!(w[1].eye.x < w[0].eye.x, "the orbit turns left");
        }
    }

    #[test]
    fn every_vbao_setting_comes_one_frame_and_accumulated() {
        let families = [PathRows::Vbao, PathRows::parse("rtao-quarter-2").unwrap()];
        let s = settings(16, &AoSettings::default(), &families, RADIUS);
        assert_eq!(s[0].0.method, AoMethod::SaoLesson);
        assert_eq!(s.iter().filter(|(p, _)| p.accumulate == 16).count(), 4);
        assert_eq!(
            s.iter().filter(|(p, _)| p.method == AoMethod::Rtao).count(),
            2
        );
        assert!(s.iter().all(|(p, a)| p.accumulate == a.accumulate));
    }

    #[test]
    fn the_vbao_default_row_runs_what_method_vbao_gets() {
        let s = settings(16, &AoSettings::default(), &[PathRows::Vbao], RADIUS);
        let (row, a) = &s[1];
        assert_eq!(row.label, "vbao default");
        let r = ao_defaults::recommended(AoMethod::Vbao);
        assert_eq!(
            (
                a.quality,
                a.resolution,
                a.normals,
                a.guard_band,
                a.layers,
                a.thickness
            ),
            (
                r.quality,
                r.resolution,
                r.normals,
                r.guard_band,
                r.layers,
                r.thickness
            )
        );
        // A key the scene file wrote is kept, as `render --method vbao` keeps it.
        let base = AoSettings {
            layers: 1,
            written: WrittenKeys {
                layers: true,
                ..WrittenKeys::default()
            },
            ..AoSettings::default()
        };
        let s = settings(16, &base, &[PathRows::Vbao], RADIUS);
        assert_eq!(s[1].1.layers, 1);
        let low = s.iter().find(|(p, _)| p.label == "vbao low").unwrap();
        assert_eq!(low.1.quality, Some(SlicePreset::Low));
    }
}
