//! One row of the bench: a method at one setting, timed at the scene's camera and compared with
//! the references at every bench camera.

use super::config::PerfConfig;
use super::references::{Ceiling, SceneData, ScreenMap};
use super::report::{CameraError, Row};
use crate::ao::AoMethod;
use crate::render::{Engine, View};
use crate::scene::method_file::MethodFile;
use crate::tools::bench::catalog::Setting;
use crate::tools::bench::timing::median;
use crate::tools::metrics::{self, Fit, Gray, Metrics};
use anyhow::{bail, Result};
use std::collections::BTreeMap;

/// Medians of the timed frames.
struct Timing {
    passes: BTreeMap<String, f64>,
    passes_cpu: BTreeMap<String, f64>,
    total_ms: f64,
    total_ms_min: f64,
    total_ms_max: f64,
    total_cpu_ms: f64,
    frame_ms: f64,
}

/// Measures `method` at setting `s` on the scene `sd` (the engine runs at the bench size).
/// With `file`, the method file's method runs in `method`'s place (`user_method::HOST`), with the
/// file's recommended configuration (`[recommended]`) narrowed to what the file reads.
pub fn run_setting(
    engine: &mut Engine,
    sd: &SceneData,
    screen: &ScreenMap,
    (method, file): (AoMethod, Option<&MethodFile>),
    s: &Setting,
    cfg: &PerfConfig,
) -> Result<Row> {
    engine.ao_settings.method = method;
    engine.ao_settings.samples = s.samples;
    if method == AoMethod::Rtao {
        // rtao's "samples" are its rays per pixel and frame.
        engine.ao_settings.rays = s.samples;
    }
    engine.ao_settings.quality = s.quality;
    // The grid decides the count or preset; the method's recommendation the keys the scene leaves
    // unwritten (normals, layers, thickness, guard band, size).
    match file {
        Some(f) => {
            engine.ao_settings = crate::ao::user_method::settings_for(f, &engine.ao_settings)
        }
        None => {
            let written = engine.ao_settings.written;
            engine.ao_settings.written.quality = true;
            // rtao's grid sets its rays, as the others' set their count.
            engine.ao_settings.written.rays |= method == AoMethod::Rtao;
            crate::scene::ao_defaults::apply(&mut engine.ao_settings);
            engine.ao_settings.written = written;
        }
    }
    engine.ao_settings.radius = s.radius;
    engine.ao_settings.enabled = true;
    let scene_camera = sd.cameras[0].camera(&sd.desc.camera);
    engine.camera = scene_camera;
    engine.sync_shader_constants()?;
    let timing = time_frames(engine, cfg)?;

    let views = ao_views(engine, sd, s, cfg)?;
    let ceiling = Ceiling::of(method, &engine.ao_settings);
    let name = file.map_or(method.name(), |f| f.name.as_str());
    let pictures = super::pictures::write(cfg, sd, name, s, &views, (screen, ceiling))?;
    engine.camera = scene_camera;
    engine.sync_shader_constants()?;

    let fit = fit_on_training_cameras(sd, s, &views);
    let shared = super::references::ceiling_shares_truth_rays(cfg);
    let cameras = camera_errors(sd, screen, (s, ceiling, shared), &views, &fit, cfg.flip)?;
    let test: Vec<&CameraError> = cameras.iter().filter(|c| !c.train).collect();
    let raw = mean_metrics(&test, |c| c.raw);
    let mean_of = |f: &dyn Fn(&CameraError) -> f64| {
        test.iter().map(|c| f(c)).sum::<f64>() / test.len().max(1) as f64
    };
    Ok(Row {
        method: name.to_string(),
        setting: s.label(),
        samples: s.samples,
        radius: s.radius,
        width: cfg.width,
        height: cfg.height,
        passes: timing.passes,
        total_ms: timing.total_ms,
        total_ms_min: timing.total_ms_min,
        total_ms_max: timing.total_ms_max,
        frame_ms: timing.frame_ms,
        passes_cpu: timing.passes_cpu,
        total_cpu_ms: timing.total_cpu_ms,
        rmse: raw.rmse,
        mae: raw.mae,
        psnr: raw.psnr,
        ssim: raw.ssim,
        flip: raw.flip,
        fit,
        fitted: mean_metrics(&test, |c| c.fitted),
        depth_buffer_error: Metrics {
            flip: 0.0,
            ..mean_metrics(&test, |c| c.depth_buffer_error)
        },
        sampling_error: Metrics {
            flip: 0.0,
            ..mean_metrics(&test, |c| c.sampling_error)
        },
        ceiling: ceiling.kind(),
        ceiling_label: ceiling.label(),
        ceiling_thickness: ceiling.thickness(),
        parts_psnr: mean_of(&|c| c.parts_psnr),
        split_gap_db: mean_of(&|c| c.raw.psnr - c.parts_psnr),
        split_gap_max_db: test
            .iter()
            .map(|c| (c.raw.psnr - c.parts_psnr).abs())
            .fold(0.0, f64::max),
        cameras,
        pictures,
    })
}

/// Renders `cfg.warmup` frames, then times `cfg.frames` frames pass by pass.
fn time_frames(engine: &mut Engine, cfg: &PerfConfig) -> Result<Timing> {
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
    let medians = |m: BTreeMap<String, Vec<f64>>| -> BTreeMap<String, f64> {
        m.into_iter()
            .map(|(k, mut v)| (k, median(&mut v)))
            .collect()
    };
    Ok(Timing {
        passes: medians(per_pass),
        passes_cpu: medians(per_pass_cpu),
        total_cpu_ms: median(&mut chain_cpu),
        total_ms_min: chain.iter().copied().fold(f64::INFINITY, f64::min),
        total_ms_max: chain.iter().copied().fold(0.0, f64::max),
        total_ms: median(&mut chain),
        frame_ms: median(&mut frame),
    })
}

/// The blurred AO view of every bench camera, box-averaged to the references' size.
fn ao_views(
    engine: &mut Engine,
    sd: &SceneData,
    s: &Setting,
    cfg: &PerfConfig,
) -> Result<Vec<Vec<f32>>> {
    (0..sd.cameras.len())
        .map(|ci| camera_view(engine, sd, ci, s.radius, cfg))
        .collect()
}

/// The blurred AO view of camera `ci` under the engine's AO settings, box-averaged to the size of
/// its reference at `radius` (also what `opengl3d tune` scores).
pub(crate) fn camera_view(
    engine: &mut Engine,
    sd: &SceneData,
    ci: usize,
    radius: f32,
    cfg: &PerfConfig,
) -> Result<Vec<f32>> {
    let (w, h) = (cfg.width as usize, cfg.height as usize);
    engine.camera = sd.cameras[ci].camera(&sd.desc.camera);
    engine.sync_shader_constants()?;
    // `rtao` with `[ao] accumulate = N`: the view ends N frames at this camera.
    if engine.ao_settings.method == AoMethod::Rtao {
        for _ in 1..engine.ao_settings.accumulate {
            engine.render_to_ao()?;
        }
    }
    let v = engine.render_values(View::Ao)?;
    let (v, dw, dh) = metrics::downsample(&v, w, h, cfg.ref_scale as usize);
    let r = &sd.refs[&(ci, radius.to_bits())];
    if (dw, dh) != (r.width as usize, r.height as usize) {
        bail!(
            "reference size {}x{} does not match {dw}x{dh}",
            r.width,
            r.height
        );
    }
    Ok(v)
}

/// The error of camera `ci`'s view against its reference at `radius`, on the reference's surface
/// (non-sky) pixels.
pub(crate) fn raw_error(
    sd: &SceneData,
    ci: usize,
    radius: f32,
    view: &[f32],
    flip: bool,
) -> Metrics {
    let r = &sd.refs[&(ci, radius.to_bits())];
    let (rw, rh) = (r.width as usize, r.height as usize);
    let mask = r.sky_mask().iter().map(|s| !s).collect::<Vec<bool>>();
    metrics::compare(
        Gray::new(rw, rh, &r.ao),
        Gray::new(rw, rh, view),
        Some(&mask),
        flip,
    )
}

/// Median AO-chain milliseconds (every pass of the "ao" group) of `cfg.frames` frames at the
/// engine's camera after `cfg.warmup` frames, as the bench times a setting.
pub(crate) fn ao_chain_ms(engine: &mut Engine, cfg: &PerfConfig) -> Result<f64> {
    Ok(time_frames(engine, cfg)?.total_ms)
}

/// Fits `min(1, a·v^b)` on the training cameras' surface pixels (at most ~400k pixel pairs,
/// evenly strided).
fn fit_on_training_cameras(sd: &SceneData, s: &Setting, views: &[Vec<f32>]) -> Fit {
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
    metrics::fit_power(&pairs)
}

/// The error of every camera: raw, fitted (test cameras), and the split into the depth buffer's
/// share and the sampling's (test cameras, which have screen-space references).
fn camera_errors(
    sd: &SceneData,
    screen: &ScreenMap,
    (s, ceiling, shared_rays): (&Setting, Ceiling, bool),
    views: &[Vec<f32>],
    fit: &Fit,
    flip: bool,
) -> Result<Vec<CameraError>> {
    let mut cameras = Vec::new();
    for (ci, cam) in sd.cameras.iter().enumerate() {
        let r = &sd.refs[&(ci, s.radius.to_bits())];
        let (rw, rh) = (r.width as usize, r.height as usize);
        let mask = r.sky_mask().iter().map(|s| !s).collect::<Vec<bool>>();
        let reference = Gray::new(rw, rh, &r.ao);
        let raw = raw_error(sd, ci, s.radius, &views[ci], flip && !cam.train);
        let fitted = if cam.train {
            Metrics::default()
        } else {
            let f = fit.apply_all(&views[ci]);
            metrics::compare(reference, Gray::new(rw, rh, &f), Some(&mask), flip)
        };
        // The split uses the ray-traced reference's mask too, so the three figures cover the
        // same pixels. Training cameras have no screen-space reference (the split is reported on
        // test cameras).
        let key = (ci, s.radius.to_bits(), ceiling.key());
        let (depth_buffer_error, sampling_error, ceiling_noise_rms) = match screen.get(&key) {
            None => (Metrics::default(), Metrics::default(), 0.0),
            Some(ss) => {
                if (ss.width, ss.height) != (r.width, r.height) {
                    bail!(
                        "screen-space reference size {}x{} does not match {rw}x{rh}",
                        ss.width,
                        ss.height
                    );
                }
                let ss_gray = Gray::new(rw, rh, &ss.ao);
                let (sum, n) = ss
                    .std_error
                    .iter()
                    .zip(&mask)
                    .filter(|(_, m)| **m)
                    .fold((0.0f64, 0usize), |(s, n), (e, _)| {
                        (s + (*e as f64).powi(2), n + 1)
                    });
                (
                    metrics::compare(reference, ss_gray, Some(&mask), false),
                    metrics::compare(ss_gray, Gray::new(rw, rh, &views[ci]), Some(&mask), false),
                    (sum / n.max(1) as f64).sqrt(),
                )
            }
        };
        // What the method's MSE would be if its error were the two parts' errors added in squares
        // (uncorrelated). Drawn on rays of its own, the screen-space reference's Monte Carlo noise
        // is in both parts and not in the total, so its variance is taken out twice (the ray-traced
        // reference's noise is in the total and in the depth-buffer part alike). On the truth's own
        // rays its noise is the truth's: in the sampling part and the total, not in the
        // depth-buffer part, and nothing is taken out.
        let ceiling_own_noise_rms = if shared_rays { 0.0 } else { ceiling_noise_rms };
        let parts_mse = depth_buffer_error.rmse.powi(2) + sampling_error.rmse.powi(2)
            - 2.0 * ceiling_own_noise_rms.powi(2);
        let parts_psnr = metrics::psnr_from_mse(parts_mse.max(0.0));
        cameras.push(CameraError {
            scene: sd.name.clone(),
            camera: cam.name.clone(),
            train: cam.train,
            raw,
            fitted,
            depth_buffer_error,
            sampling_error,
            ceiling_noise_rms,
            ceiling_own_noise_rms,
            parts_psnr,
        });
    }
    Ok(cameras)
}

/// Mean of the picked figures over the test cameras (all zero without test cameras); `pixels` is
/// the test cameras' raw pixel count.
fn mean_metrics(test: &[&CameraError], pick: impl Fn(&CameraError) -> Metrics) -> Metrics {
    let n = test.len().max(1) as f64;
    let mean = |f: &dyn Fn(&Metrics) -> f64| test.iter().map(|c| f(&pick(c))).sum::<f64>() / n;
    Metrics {
        rmse: mean(&|m| m.rmse),
        mae: mean(&|m| m.mae),
        psnr: mean(&|m| m.psnr),
        ssim: mean(&|m| m.ssim),
        flip: mean(&|m| m.flip),
        pixels: test.iter().map(|c| c.raw.pixels).sum(),
    }
}
