//! `opengl3d bench`: run time against error of each AO method and quality setting.
//!
//! Timing: the full frame (composite view, every pass) is rendered with `Engine::collect_stats`, which
//! brackets each pass with glFinish and reads a wall clock (on llvmpipe timer queries measure nothing
//! useful). After `warmup` frames, `frames` frames are timed at the scene's own camera; each pass
//! reports its median, and the AO chain (every pass of the "ao" group: restore, down-sampling, the
//! method, blur, composite) the median of its per-frame sum.
//!
//! Error: the blurred AO view (`render_values(View::Ao)`, visibility, output size) of every bench
//! camera against the CPU ray-traced reference (binary visibility, cosine-weighted rays of length =
//! the setting's radius) on the reference's non-sky pixels, raw and after fitting `min(1, a·v^b)` on
//! the training cameras; rows report the mean over the test cameras.
//!
//! Error split: a screen-space reference (`reference::render_screen_space`, the exact visibility of
//! the engine's depth buffer rendered at the reference's size, seen as a heightfield) separates what
//! the depth buffer cannot know (screen-space reference against ray-traced) from what the method's
//! sampling loses (method against screen-space reference).

use super::catalog::{self, BenchCamera, Setting};
use super::metrics::{self, Fit, Gray, Metrics};
use crate::ao::AoMethod;
use crate::math::Camera;
use crate::platform::HeadlessContext;
use crate::render::{Engine, View};
use crate::res::ResDirs;
use crate::scene::SceneDesc;
use crate::tools::reference::{
    load_or_render_cached, load_or_render_screen_cached, screen_cache_key, AoVariant, DepthBuffer,
    RefCamera, RefImage, RefParams, Scene,
};
use anyhow::{bail, Context as _, Result};
use glam::Vec3;
use indicatif::{ProgressBar, ProgressStyle};
use serde::Serialize;
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::time::Instant;

/// Everything a bench run needs (the CLI fills it from `BenchArgs`; tests build it directly).
#[derive(Clone, Debug)]
pub struct PerfConfig {
    pub scenes: Vec<PathBuf>,
    pub width: u32,
    pub height: u32,
    pub out: PathBuf,
    pub methods: Vec<AoMethod>,
    /// Overrides of the settings grid (empty = each method's defaults).
    pub samples: Vec<u32>,
    pub radii: Vec<f32>,
    pub ref_rays: u32,
    /// Rays per pixel of the screen-space references (a dense march per ray is far slower than a
    /// BVH ray; they are rendered for the test cameras only, where the split is reported).
    pub screen_rays: u32,
    /// The reference is rendered at width/ref_scale × height/ref_scale and the engine's output is
    /// box-averaged by the same factor before comparing.
    pub ref_scale: u32,
    pub cache: PathBuf,
    pub warmup: u32,
    pub frames: u32,
    pub flip: bool,
    pub charts: bool,
    pub progress: bool,
}

/// Error of one camera.
#[derive(Clone, Debug, Serialize)]
pub struct CameraError {
    pub scene: String,
    pub camera: String,
    pub train: bool,
    pub raw: Metrics,
    /// After the fit (test cameras only; the training cameras repeat the raw figures' pixels).
    pub fitted: Metrics,
    /// The screen-space reference (exact AO of the depth buffer) against the ray-traced one: what
    /// the depth buffer cannot know at this camera and radius, whatever the method (no FLIP).
    pub depth_buffer_error: Metrics,
    /// The method (raw) against the screen-space reference: what its sampling loses (no FLIP).
    pub sampling_error: Metrics,
}

/// One row: a method at one setting.
#[derive(Clone, Debug, Serialize)]
pub struct Row {
    pub method: String,
    pub setting: String,
    pub samples: u32,
    pub radius: f32,
    pub width: u32,
    pub height: u32,
    /// Median wall-clock ms of each pass of the frame (AO passes and the others), by pass name.
    pub passes: BTreeMap<String, f64>,
    /// Median of the per-frame sum of the AO passes (group "ao").
    pub total_ms: f64,
    pub total_ms_min: f64,
    pub total_ms_max: f64,
    /// Median of the whole frame (every pass).
    pub frame_ms: f64,
    /// Median CPU ms of each pass (the process's CPU time, all threads): robust to other load.
    pub passes_cpu: BTreeMap<String, f64>,
    /// Median of the per-frame CPU ms of the AO passes.
    pub total_cpu_ms: f64,
    /// Raw error, mean over the test cameras.
    pub rmse: f64,
    pub mae: f64,
    pub psnr: f64,
    pub ssim: f64,
    pub flip: f64,
    /// The fitted map min(1, a·v^b) (from the training cameras) and the error after it (test cameras).
    pub fit: Fit,
    pub fitted: Metrics,
    /// Error split, means over the test cameras: the screen-space reference against the
    /// ray-traced one (the depth buffer's limit), and the method against the screen-space
    /// reference (its sampling).
    pub depth_buffer_error: Metrics,
    pub sampling_error: Metrics,
    pub cameras: Vec<CameraError>,
}

#[derive(Clone, Debug, Serialize)]
pub struct Report {
    pub renderer: String,
    pub software: bool,
    pub timing: String,
    pub cpus: usize,
    pub width: u32,
    pub height: u32,
    pub reference: ReferenceInfo,
    pub warmup_frames: u32,
    pub timed_frames: u32,
    pub scenes: Vec<String>,
    pub cameras: Vec<(String, BenchCamera)>,
    pub rows: Vec<Row>,
    /// Wall-clock seconds of the whole run (reference renders included when not cached).
    pub run_s: f64,
    /// /proc/loadavg (1, 5, 15 min) when the timing started and when it ended: other processes
    /// on the machine slow the frames down.
    pub load_before: Option<[f64; 3]>,
    pub load_after: Option<[f64; 3]>,
}

fn load_average() -> Option<[f64; 3]> {
    let s = std::fs::read_to_string("/proc/loadavg").ok()?;
    let v: Vec<f64> = s
        .split_whitespace()
        .take(3)
        .filter_map(|x| x.parse().ok())
        .collect();
    (v.len() == 3).then(|| [v[0], v[1], v[2]])
}

#[derive(Clone, Debug, Serialize)]
pub struct ReferenceInfo {
    pub rays: u32,
    pub width: u32,
    pub height: u32,
    pub variant: &'static str,
    pub rendered: usize,
    pub cached: usize,
    pub render_s: f64,
    /// Screen-space references (same size, rays and radii, from the engine's depth buffer
    /// rendered at that size): rendered this run, read from the cache, seconds spent.
    pub screen_rays: u32,
    pub screen_rendered: usize,
    pub screen_cached: usize,
    pub screen_render_s: f64,
}

pub(crate) fn median(v: &mut [f64]) -> f64 {
    if v.is_empty() {
        return 0.0;
    }
    v.sort_by(|a, b| a.total_cmp(b));
    let n = v.len();
    if n % 2 == 1 {
        v[n / 2]
    } else {
        0.5 * (v[n / 2 - 1] + v[n / 2])
    }
}

fn ref_camera(c: &BenchCamera, desc: &SceneDesc) -> RefCamera {
    RefCamera {
        eye: c.eye.into(),
        target: c.target.into(),
        up: Vec3::Y,
        fov_y_deg: c.fov_y,
        near: desc.camera.near,
        far: desc.camera.far,
    }
}

fn engine_camera(c: &BenchCamera, desc: &SceneDesc) -> Camera {
    Camera {
        eye: c.eye.into(),
        target: c.target.into(),
        up: Vec3::Y,
        fov_y_deg: c.fov_y,
        near: desc.camera.near,
        far: desc.camera.far,
    }
}

fn bar(len: u64, template: &str, show: bool) -> ProgressBar {
    if !show {
        return ProgressBar::hidden();
    }
    let b = ProgressBar::new(len);
    if let Ok(s) = ProgressStyle::with_template(template) {
        b.set_style(s.progress_chars("=> "));
    }
    b
}

struct SceneData {
    name: String,
    desc: SceneDesc,
    cameras: Vec<BenchCamera>,
    /// (camera index, radius bits) → reference.
    refs: BTreeMap<(usize, u32), RefImage>,
}

/// Runs the benchmark and writes report.json, report.md and the charts into `cfg.out`.
pub fn run(res: &ResDirs, cfg: &PerfConfig) -> Result<Report> {
    let t0 = Instant::now();
    if cfg.width == 0 || cfg.height == 0 || cfg.width > 16384 || cfg.height > 16384 {
        bail!(
            "--width/--height {}x{}: use 1 to 16384",
            cfg.width,
            cfg.height
        );
    }
    if cfg.methods.is_empty() {
        bail!("no AO method to run");
    }
    if cfg.frames == 0 {
        bail!("--frames must be at least 1");
    }
    let ref_scale = cfg.ref_scale.max(1);
    let (rw, rh) = (
        cfg.width.div_ceil(ref_scale),
        cfg.height.div_ceil(ref_scale),
    );
    std::fs::create_dir_all(&cfg.out)
        .with_context(|| format!("cannot create {}", cfg.out.display()))?;

    let scene_paths: Vec<PathBuf> = if cfg.scenes.is_empty() {
        vec![res
            .find("scenes/demo.toml")
            .map_err(|e| anyhow::anyhow!("{e}"))?]
    } else {
        cfg.scenes.clone()
    };
    let plan: Vec<(AoMethod, Vec<Setting>)> = cfg
        .methods
        .iter()
        .map(|m| (*m, catalog::settings_for(*m, &cfg.samples, &cfg.radii)))
        .collect();
    for (_, settings) in &plan {
        for s in settings {
            let ok = (1..=256).contains(&s.samples) && s.radius > 0.0 && s.radius <= 100.0;
            if !ok {
                bail!(
                    "setting {}: samples must be 1-256 and radius in (0, 100] m",
                    s.label()
                );
            }
        }
    }
    let mut radii: Vec<f32> = plan
        .iter()
        .flat_map(|(_, s)| s.iter().map(|s| s.radius))
        .collect();
    radii.sort_by(|a, b| a.total_cmp(b));
    radii.dedup();

    // References first: they are the slow part, and cached for later runs.
    let mut scenes = Vec::new();
    let (mut rendered, mut cached, mut render_s) = (0usize, 0usize, 0.0f64);
    for path in &scene_paths {
        let mut desc = SceneDesc::load(path)?;
        desc.output.width = cfg.width;
        desc.output.height = cfg.height;
        let name = path
            .file_stem()
            .map(|s| s.to_string_lossy().into_owned())
            .unwrap_or_else(|| "scene".into());
        let cameras = catalog::camera_variants(&desc.camera);
        let bvh = Scene::new(desc.world_triangles(res)?)?;
        let mut refs = BTreeMap::new();
        for (ci, cam) in cameras.iter().enumerate() {
            for &r in &radii {
                let params = RefParams {
                    radius: r,
                    rays: cfg.ref_rays,
                    variant: AoVariant::Visibility,
                    seed: 1,
                    progress: cfg.progress,
                };
                let rc = ref_camera(cam, &desc);
                let key =
                    crate::tools::reference::cache_key(bvh.content_hash(), &rc, rw, rh, &params);
                let hit = crate::tools::reference::cache_path(&cfg.cache, &key).is_file();
                if cfg.progress {
                    eprintln!(
                        "reference {name}/{} R = {r} m, {rw}x{rh}, {} rays: {}",
                        cam.name,
                        cfg.ref_rays,
                        if hit { "cached" } else { "rendering" }
                    );
                }
                let t = Instant::now();
                let img = load_or_render_cached(&cfg.cache, &bvh, &rc, rw, rh, &params)?;
                if hit {
                    cached += 1;
                } else {
                    rendered += 1;
                    render_s += t.elapsed().as_secs_f64();
                }
                refs.insert((ci, r.to_bits()), img);
            }
        }
        scenes.push(SceneData {
            name,
            desc,
            cameras,
            refs,
        });
    }

    let ctx = HeadlessContext::new()?;
    let timing = if ctx.software {
        "wall clock around glFinish per pass (software GL: Mesa llvmpipe; timer queries do not measure real time there)"
    } else {
        "wall clock around glFinish per pass (hardware GL)"
    };
    let total_settings: usize = plan.iter().map(|(_, s)| s.len()).sum::<usize>() * scenes.len();
    let pb = bar(
        total_settings as u64,
        "bench {bar:40} {pos}/{len} settings [{elapsed_precise} < {eta_precise}] {msg}",
        cfg.progress,
    );
    let load_before = load_average();
    let mut rows = Vec::new();
    let mut screen_stats = ScreenStats::default();
    for sd in &scenes {
        // The engine starts at the reference's size for the screen-space references' depth
        // buffers (same pixel centres as the ray-traced reference), then runs at the bench size.
        let mut engine = Engine::new(&ctx.gl, res.clone(), &sd.desc, rw, rh)?;
        let screen = screen_references(&mut engine, sd, &radii, cfg, &pb, &mut screen_stats)?;
        engine.resize(cfg.width, cfg.height)?;
        for (method, settings) in &plan {
            for s in settings {
                pb.set_message(format!("{} {} {}", sd.name, method.name(), s.label()));
                let row = run_setting(&mut engine, sd, &screen, *method, s, cfg, ref_scale)
                    .with_context(|| format!("{} {} {}", sd.name, method.name(), s.label()))?;
                rows.push(row);
                pb.inc(1);
            }
        }
    }
    pb.finish_and_clear();

    let report = Report {
        renderer: ctx.renderer.clone(),
        software: ctx.software,
        timing: timing.to_string(),
        cpus: std::thread::available_parallelism().map_or(1, |n| n.get()),
        width: cfg.width,
        height: cfg.height,
        reference: ReferenceInfo {
            rays: cfg.ref_rays,
            width: rw,
            height: rh,
            variant: "visibility (binary, cosine-weighted rays of length R)",
            rendered,
            cached,
            render_s,
            screen_rays: cfg.screen_rays,
            screen_rendered: screen_stats.rendered,
            screen_cached: screen_stats.cached,
            screen_render_s: screen_stats.render_s,
        },
        warmup_frames: cfg.warmup,
        timed_frames: cfg.frames,
        scenes: scenes.iter().map(|s| s.name.clone()).collect(),
        cameras: scenes
            .iter()
            .flat_map(|s| s.cameras.iter().map(|c| (s.name.clone(), c.clone())))
            .collect(),
        rows,
        run_s: t0.elapsed().as_secs_f64(),
        load_before,
        load_after: load_average(),
    };
    write_outputs(&report, cfg)?;
    Ok(report)
}

#[derive(Default)]
struct ScreenStats {
    rendered: usize,
    cached: usize,
    render_s: f64,
}

/// Screen-space reference of every camera and radius, from the engine's depth buffer at its
/// current size: (camera index, radius bits) → image.
fn screen_references(
    engine: &mut Engine,
    sd: &SceneData,
    radii: &[f32],
    cfg: &PerfConfig,
    pb: &ProgressBar,
    stats: &mut ScreenStats,
) -> Result<BTreeMap<(usize, u32), RefImage>> {
    let mut out = BTreeMap::new();
    for (ci, cam) in sd.cameras.iter().enumerate().filter(|(_, c)| !c.train) {
        engine.camera = engine_camera(cam, &sd.desc);
        engine.sync_shader_constants()?;
        let depth = DepthBuffer::from_engine(engine)?;
        for &r in radii {
            let params = RefParams {
                radius: r,
                rays: cfg.screen_rays,
                variant: AoVariant::Visibility,
                seed: 1,
                progress: cfg.progress,
            };
            let key = screen_cache_key(&depth, &params);
            let hit = crate::tools::reference::cache_path(&cfg.cache, &key).is_file();
            if cfg.progress {
                pb.suspend(|| {
                    eprintln!(
                        "screen-space reference {}/{} R = {r} m, {}x{}, {} rays: {}",
                        sd.name,
                        cam.name,
                        depth.width,
                        depth.height,
                        cfg.screen_rays,
                        if hit { "cached" } else { "rendering" }
                    )
                });
            }
            let t = Instant::now();
            let img = pb.suspend(|| load_or_render_screen_cached(&cfg.cache, &depth, &params))?;
            if hit {
                stats.cached += 1;
            } else {
                stats.rendered += 1;
                stats.render_s += t.elapsed().as_secs_f64();
            }
            out.insert((ci, r.to_bits()), img);
        }
    }
    Ok(out)
}

fn run_setting(
    engine: &mut Engine,
    sd: &SceneData,
    screen: &BTreeMap<(usize, u32), RefImage>,
    method: AoMethod,
    s: &Setting,
    cfg: &PerfConfig,
    ref_scale: u32,
) -> Result<Row> {
    engine.ao_settings.method = method;
    engine.ao_settings.samples = s.samples;
    engine.ao_settings.quality = s.quality;
    engine.ao_settings.radius = s.radius;
    engine.ao_settings.enabled = true;
    engine.camera = engine_camera(&sd.cameras[0], &sd.desc);
    engine.sync_shader_constants()?;

    // Timing at the scene's camera.
    engine.collect_stats = true;
    for _ in 0..cfg.warmup {
        engine.render_image()?;
    }
    let mut per_pass: BTreeMap<String, Vec<f64>> = BTreeMap::new();
    let mut per_pass_cpu: BTreeMap<String, Vec<f64>> = BTreeMap::new();
    let (mut chain, mut frame, mut chain_cpu) = (Vec::new(), Vec::new(), Vec::new());
    for _ in 0..cfg.frames {
        engine.render_image()?;
        let stats = engine.last_stats();
        let (mut ao, mut ao_cpu, mut all) = (0.0, 0.0, 0.0);
        for p in &stats {
            per_pass.entry(p.name.to_string()).or_default().push(p.ms);
            per_pass_cpu
                .entry(p.name.to_string())
                .or_default()
                .push(p.cpu_ms);
            all += p.ms;
            if p.group == "ao" {
                ao += p.ms;
                ao_cpu += p.cpu_ms;
            }
        }
        chain.push(ao);
        chain_cpu.push(ao_cpu);
        frame.push(all);
    }
    engine.collect_stats = false;
    let passes: BTreeMap<String, f64> = per_pass
        .into_iter()
        .map(|(k, mut v)| (k, median(&mut v)))
        .collect();
    let passes_cpu: BTreeMap<String, f64> = per_pass_cpu
        .into_iter()
        .map(|(k, mut v)| (k, median(&mut v)))
        .collect();
    let total_cpu_ms = median(&mut chain_cpu);
    let total_ms_min = chain.iter().copied().fold(f64::INFINITY, f64::min);
    let total_ms_max = chain.iter().copied().fold(0.0, f64::max);
    let total_ms = median(&mut chain);
    let frame_ms = median(&mut frame);

    // Error at every camera.
    let (w, h) = (cfg.width as usize, cfg.height as usize);
    let mut views = Vec::new();
    for (ci, cam) in sd.cameras.iter().enumerate() {
        engine.camera = engine_camera(cam, &sd.desc);
        engine.sync_shader_constants()?;
        let v = engine.render_values(View::Ao)?;
        let (v, dw, dh) = metrics::downsample(&v, w, h, ref_scale as usize);
        let r = &sd.refs[&(ci, s.radius.to_bits())];
        if (dw, dh) != (r.width as usize, r.height as usize) {
            bail!(
                "reference size {}x{} does not match {dw}x{dh}",
                r.width,
                r.height
            );
        }
        views.push(v);
    }
    engine.camera = engine_camera(&sd.cameras[0], &sd.desc);
    engine.sync_shader_constants()?;

    // Fit on the training cameras (at most ~400k pixel pairs, evenly strided).
    let mut pairs = Vec::new();
    for (ci, cam) in sd.cameras.iter().enumerate() {
        if !cam.train {
            continue;
        }
        let r = &sd.refs[&(ci, s.radius.to_bits())];
        let n = r.ao.len();
        let stride = (n / 200_000).max(1);
        for i in (0..n).step_by(stride) {
            if r.linear_depth[i].is_finite() {
                pairs.push((views[ci][i], r.ao[i]));
            }
        }
    }
    let fit = metrics::fit_power(&pairs);

    let mut cameras = Vec::new();
    for (ci, cam) in sd.cameras.iter().enumerate() {
        let r = &sd.refs[&(ci, s.radius.to_bits())];
        let (rw, rh) = (r.width as usize, r.height as usize);
        let mask = r.sky_mask().iter().map(|s| !s).collect::<Vec<bool>>();
        let reference = Gray::new(rw, rh, &r.ao);
        let raw = metrics::compare(
            reference,
            Gray::new(rw, rh, &views[ci]),
            Some(&mask),
            cfg.flip && !cam.train,
        );
        let fitted = if cam.train {
            Metrics::default()
        } else {
            let f = fit.apply_all(&views[ci]);
            metrics::compare(reference, Gray::new(rw, rh, &f), Some(&mask), cfg.flip)
        };
        // The split uses the ray-traced reference's mask too, so the three figures cover the
        // same pixels.
        // Training cameras have no screen-space reference (the split is reported on test cameras).
        let (depth_buffer_error, sampling_error) = match screen.get(&(ci, s.radius.to_bits())) {
            None => (Metrics::default(), Metrics::default()),
            Some(ss) => {
                if (ss.width, ss.height) != (r.width, r.height) {
                    bail!(
                        "screen-space reference size {}x{} does not match {rw}x{rh}",
                        ss.width,
                        ss.height
                    );
                }
                let ss_gray = Gray::new(rw, rh, &ss.ao);
                (
                    metrics::compare(reference, ss_gray, Some(&mask), false),
                    metrics::compare(ss_gray, Gray::new(rw, rh, &views[ci]), Some(&mask), false),
                )
            }
        };
        cameras.push(CameraError {
            scene: sd.name.clone(),
            camera: cam.name.clone(),
            train: cam.train,
            raw,
            fitted,
            depth_buffer_error,
            sampling_error,
        });
    }
    let test: Vec<&CameraError> = cameras.iter().filter(|c| !c.train).collect();
    let mean = |f: &dyn Fn(&Metrics) -> f64, fitted: bool| {
        if test.is_empty() {
            return 0.0;
        }
        test.iter()
            .map(|c| f(if fitted { &c.fitted } else { &c.raw }))
            .sum::<f64>()
            / test.len() as f64
    };
    let pixels: usize = test.iter().map(|c| c.raw.pixels).sum();
    let fitted = Metrics {
        rmse: mean(&|m| m.rmse, true),
        mae: mean(&|m| m.mae, true),
        psnr: mean(&|m| m.psnr, true),
        ssim: mean(&|m| m.ssim, true),
        flip: mean(&|m| m.flip, true),
        pixels,
    };
    let mean_of = |pick: &dyn Fn(&CameraError) -> Metrics| {
        let n = test.len().max(1) as f64;
        let sum = |f: &dyn Fn(&Metrics) -> f64| test.iter().map(|c| f(&pick(c))).sum::<f64>() / n;
        Metrics {
            rmse: sum(&|m| m.rmse),
            mae: sum(&|m| m.mae),
            psnr: sum(&|m| m.psnr),
            ssim: sum(&|m| m.ssim),
            flip: 0.0,
            pixels,
        }
    };
    let depth_buffer_error = mean_of(&|c| c.depth_buffer_error);
    let sampling_error = mean_of(&|c| c.sampling_error);
    Ok(Row {
        method: method.name().to_string(),
        setting: s.label(),
        samples: s.samples,
        radius: s.radius,
        width: cfg.width,
        height: cfg.height,
        passes,
        total_ms,
        total_ms_min,
        total_ms_max,
        frame_ms,
        passes_cpu,
        total_cpu_ms,
        rmse: mean(&|m| m.rmse, false),
        mae: mean(&|m| m.mae, false),
        psnr: mean(&|m| m.psnr, false),
        ssim: mean(&|m| m.ssim, false),
        flip: mean(&|m| m.flip, false),
        fit,
        fitted,
        depth_buffer_error,
        sampling_error,
        cameras,
    })
}

/// Role of a pass in the AO chain (the table's columns), from its name.
fn pass_role(name: &str) -> &'static str {
    if name.contains("restore") {
        "restore"
    } else if name.contains("down sampling") {
        "down"
    } else if name.contains("composite") {
        "composite"
    } else if name.contains("blur") {
        "blur"
    } else {
        "ao"
    }
}

const AO_PASS_ROLES: [&str; 5] = ["restore", "down", "ao", "blur", "composite"];
const NON_AO_PASSES: [&str; 7] = [
    "shadow map",
    "opaque",
    "sky",
    "transparent",
    "bloom",
    "image processing",
    "debug view",
];

fn role_ms(row: &Row, role: &str) -> Option<f64> {
    role_sum(&row.passes, role)
}

fn role_sum(passes: &BTreeMap<String, f64>, role: &str) -> Option<f64> {
    let v: Vec<f64> = passes
        .iter()
        .filter(|(k, _)| !NON_AO_PASSES.contains(&k.as_str()) && pass_role(k) == role)
        .map(|(_, v)| *v)
        .collect();
    (!v.is_empty()).then(|| v.iter().sum())
}

fn write_outputs(report: &Report, cfg: &PerfConfig) -> Result<()> {
    let json = serde_json::to_string_pretty(report)?;
    std::fs::write(cfg.out.join("report.json"), json)?;
    std::fs::write(cfg.out.join("report.md"), markdown(report, cfg))?;
    if cfg.charts {
        if let Err(e) = super::chart::write_charts(report, &cfg.out) {
            eprintln!("charts not written: {e:#}");
        }
    }
    Ok(())
}

fn f(v: f64, digits: usize) -> String {
    format!("{v:.digits$}")
}

fn markdown(r: &Report, cfg: &PerfConfig) -> String {
    use std::fmt::Write as _;
    let mut s = String::new();
    let _ = writeln!(s, "# AO benchmark: run time against error\n");
    let _ = writeln!(
        s,
        "`opengl3d bench` at {}×{} on **{}** ({} CPU threads visible).\n",
        r.width, r.height, r.renderer, r.cpus
    );
    let _ = writeln!(s, "## How it was measured\n");
    let _ = writeln!(
        s,
        "- **Timing**: {}. The whole frame (composite view: shadow, opaque, AO chain, sky, bloom, \
         image processing) is rendered {} times to warm up, then {} times timed, at the scene's own \
         camera. Each pass's column is its median wall ms (and, in brackets, its median CPU ms); **AO ms** is the median of the per-frame sum of \
         the AO passes (restore + down-sampling + the method + blur + composite); the range is the \
         fastest and slowest frame. **AO CPU ms** is the median CPU time the process (llvmpipe's \
         rasteriser threads included) spent in the same passes (`clock_gettime(CLOCK_PROCESS_CPUTIME_ID)`): \
         it barely moves when other programs load the machine, so it is the fairer cost to compare \
         settings by; on an idle machine wall ≈ CPU / threads for well-parallelised passes. Frame ms is \
         the median whole frame. Timing brackets every pass with \
         glFinish, so passes do not overlap: the sum is slower than an untimed frame.",
        r.timing, r.warmup_frames, r.timed_frames
    );
    let _ = writeln!(
        s,
        "- **Ground truth**: CPU ray tracing of the same triangles ({}), {} rays per pixel, ray length = the \
         setting's radius, at {}×{}{}. Cached under `{}` ({} rendered in {:.0} s this run, {} read from \
         the cache).",
        r.reference.variant,
        r.reference.rays,
        r.reference.width,
        r.reference.height,
        if r.reference.width != r.width {
            format!(
                " (the engine's {}×{} output is box-averaged {}× before comparing)",
                r.width, r.height, cfg.ref_scale
            )
        } else {
            " (the engine's output size)".to_string()
        },
        cfg.cache.display(),
        r.reference.rendered,
        r.reference.render_s,
        r.reference.cached
    );
    let _ = writeln!(
        s,
        "- **Error**: the blurred AO view (`render_values(View::Ao)`, ambient visibility, 1 = open) \
         against the reference on non-sky pixels: RMSE, MAE, PSNR (peak 1, capped at {} dB), SSIM \
         (Gaussian σ = 1.5, 11×11), FLIP (LDR ꟻLIP, 67 px/°, images shown as grey sRGB). \
         **Raw** is the method as configured (scene intensity and bias). **Fitted** maps visibility \
         through min(1, a·v^b), with a and b least-squares fitted on the training cameras and reported \
         on the test cameras only.",
        metrics::PSNR_CAP_DB
    );
    let _ = writeln!(
        s,
        "- **Error split**: a **screen-space reference** is computed from the engine's own depth \
         buffer, rendered at the reference's size ({}×{}, so its pixel centres are the ray-traced \
         reference's): the same visibility (radius and sampling; {} rays per pixel, test cameras only), but with the \
         scene replaced by the depth buffer seen as a heightfield of infinite thickness (inverse \
         depth interpolated between pixel centres, normals from the depth buffer) and every ray \
         marched exactly through every pixel cell it crosses, without mips; rays leaving the screen \
         count as open. It is what a perfect screen-space method could compute. **Depth-buffer \
         error** = screen-space reference against the ray-traced one (hidden surfaces, thickness, \
         off-screen occluders: the same for every method at a camera and radius); **sampling \
         error** = the method (raw) against the screen-space reference (what its samples, mips, \
         blur and intensity lose). Both on the ray-traced reference's non-sky pixels, means over \
         the test cameras, without FLIP; both include the two references' Monte Carlo noise. \
         Cached under the same folder ({} rendered in {:.0} s this run, {} read from the cache).",
        r.reference.width,
        r.reference.height,
        r.reference.screen_rays,
        r.reference.screen_rendered,
        r.reference.screen_render_s,
        r.reference.screen_cached
    );
    let _ = writeln!(s, "- **Cameras** (train / test):");
    for (scene, c) in &r.cameras {
        let _ = writeln!(
            s,
            "  - {scene}/{}: eye {:?}, target {:?}, fov {}° — {}",
            c.name,
            c.eye,
            c.target,
            c.fov_y,
            if c.train { "train" } else { "test" }
        );
    }
    let load = |l: &Option<[f64; 3]>| {
        l.map_or("unknown".to_string(), |l| {
            format!("{:.2} {:.2} {:.2}", l[0], l[1], l[2])
        })
    };
    let _ = writeln!(
        s,
        "- Error figures are the mean over the test cameras. Load average (1/5/15 min) when timing \
         started: {}, when it ended: {}, on {} CPU threads: other processes on the machine slow frames \
         down, so compare settings through the fastest frame (range) as well as the median, and treat \
         differences under ~10–20% as noise.\n",
        load(&r.load_before),
        load(&r.load_after),
        r.cpus
    );
    let _ = writeln!(s, "## Results\n");
    let _ = writeln!(
        s,
        "| method | setting | restore | down | AO pass | blur | composite | **AO ms** (range) | AO CPU ms | frame ms | RMSE | MAE | PSNR dB | SSIM | FLIP | fit a, b | fitted RMSE | fitted PSNR | fitted SSIM | fitted FLIP |"
    );
    let _ = writeln!(s, "|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---|---:|---:|---:|---:|");
    for row in &r.rows {
        let roles: Vec<String> = AO_PASS_ROLES
            .iter()
            .map(
                |role| match (role_ms(row, role), role_sum(&row.passes_cpu, role)) {
                    (Some(w), Some(c)) => format!("{} ({})", f(w, 1), f(c, 0)),
                    _ => "–".into(),
                },
            )
            .collect();
        let _ = writeln!(
            s,
            "| {} | {} | {} | **{}** ({}–{}) | {} | {} | {} | {} | {} | {} | {} | {}, {} | {} | {} | {} | {} |",
            row.method,
            row.setting,
            roles.join(" | "),
            f(row.total_ms, 1),
            f(row.total_ms_min, 1),
            f(row.total_ms_max, 1),
            f(row.total_cpu_ms, 1),
            f(row.frame_ms, 0),
            f(row.rmse, 4),
            f(row.mae, 4),
            f(row.psnr, 2),
            f(row.ssim, 4),
            f(row.flip, 4),
            f(row.fit.a, 3),
            f(row.fit.b, 3),
            f(row.fitted.rmse, 4),
            f(row.fitted.psnr, 2),
            f(row.fitted.ssim, 4),
            f(row.fitted.flip, 4),
        );
    }
    // Best settings.
    let best = |key: &dyn Fn(&Row) -> f64| {
        r.rows
            .iter()
            .max_by(|a, b| key(a).total_cmp(&key(b)))
            .map(|row| format!("{} {}", row.method, row.setting))
            .unwrap_or_default()
    };
    let _ = writeln!(s);
    let _ = writeln!(
        s,
        "Best raw PSNR: {}. Best fitted PSNR: {}.\n",
        best(&|r| r.psnr),
        best(&|r| r.fitted.psnr)
    );
    let _ = writeln!(s, "## Error split: depth buffer against sampling\n");
    let _ = writeln!(
        s,
        "| method | setting | vs ray-traced RMSE | PSNR dB | depth-buffer RMSE | depth-buffer PSNR dB | sampling RMSE | sampling PSNR dB | sampling SSIM |"
    );
    let _ = writeln!(s, "|---|---|---:|---:|---:|---:|---:|---:|---:|");
    for row in &r.rows {
        let _ = writeln!(
            s,
            "| {} | {} | {} | {} | {} | {} | {} | {} | {} |",
            row.method,
            row.setting,
            f(row.rmse, 4),
            f(row.psnr, 2),
            f(row.depth_buffer_error.rmse, 4),
            f(row.depth_buffer_error.psnr, 2),
            f(row.sampling_error.rmse, 4),
            f(row.sampling_error.psnr, 2),
            f(row.sampling_error.ssim, 4),
        );
    }
    let _ = writeln!(
        s,
        "\nThe depth-buffer columns depend only on the camera and radius. In squared error the \
         method's error against the ray-traced reference is the sum of the two parts plus a cross \
         term (the two can partly cancel, e.g. a method that under-darkens where the depth buffer \
         over-darkens).\n"
    );
    let _ = writeln!(s, "## Per camera (PSNR dB, raw / fitted)\n");
    if let Some(first) = r.rows.first() {
        let header: Vec<String> = first
            .cameras
            .iter()
            .map(|c| format!("{}{}", c.camera, if c.train { " (train)" } else { "" }))
            .collect();
        let _ = writeln!(s, "| method | setting | {} |", header.join(" | "));
        let _ = writeln!(s, "|---|---|{}", "---:|".repeat(header.len()));
        for row in &r.rows {
            let cells: Vec<String> = row
                .cameras
                .iter()
                .map(|c| {
                    if c.train {
                        f(c.raw.psnr, 2)
                    } else {
                        format!("{} / {}", f(c.raw.psnr, 2), f(c.fitted.psnr, 2))
                    }
                })
                .collect();
            let _ = writeln!(
                s,
                "| {} | {} | {} |",
                row.method,
                row.setting,
                cells.join(" | ")
            );
        }
    }
    let _ = writeln!(
        s,
        "\nCharts: `report.svg` (and `report.png` when a TrueType font was found): RMSE against the AO \
         chain's median wall ms (left) and CPU ms (right), raw (filled) and fitted (hollow), one colour \
         per method, each raw point labelled with its setting.\n\nRun time of the whole bench: {:.0} s.",
        r.run_s
    );
    s
}

/// Default output folder when none is given.
pub fn default_out() -> &'static Path {
    Path::new("out/bench")
}
