//! One run of `tune` on the engine: the truths first (the bench's cached references at each
//! scene's radius), then per scene and method the search, each configuration scored by the mean
//! PSNR of its training cameras; the test cameras are rendered only for the scene's own table and
//! the chosen one.

use super::config::TuneConfig;
use super::search::{self, Score};
use super::space;
use crate::ao::{AoMethod, AoSettings};
use crate::platform::HeadlessContext;
use crate::render::Engine;
use crate::res::ResDirs;
use crate::tools::bench::perf::references::{self, RenderCount, SceneData};
use crate::tools::bench::perf::setting::{ao_chain_ms, camera_view, raw_error};
use crate::tools::bench::perf::PerfConfig;
use crate::tools::bench::progress;
use anyhow::{bail, Context as _, Result};
use serde::Serialize;
use std::collections::BTreeMap;
use std::path::PathBuf;

/// One method tuned on one scene.
#[derive(Clone, Debug, Serialize)]
pub struct MethodResult {
    pub scene: String,
    pub scene_path: PathBuf,
    pub method: AoMethod,
    /// The scene's `[ao]` with the method set, and the chosen table.
    pub default: AoSettings,
    pub tuned: AoSettings,
    /// The keys searched.
    pub keys: Vec<&'static str>,
    /// Mean PSNR (dB) of the training and of the test cameras.
    pub train_default: f64,
    pub train_tuned: f64,
    pub test_default: f64,
    pub test_tuned: f64,
    /// With `--budget`: the AO time of the scene's table and of the chosen one over the lesson
    /// chain's, as measured during the search.
    pub cost: Option<Cost>,
    /// Distinct configurations scored, and how many were over the budget.
    pub evaluated: usize,
    pub over_budget: usize,
    pub width: u32,
    pub height: u32,
    pub ref_scale: u32,
    pub ref_rays: u32,
}

#[derive(Clone, Copy, Debug, Serialize)]
pub struct Cost {
    pub budget: f64,
    pub default_ratio: f64,
    pub tuned_ratio: f64,
}

pub fn run(res: &ResDirs, cfg: &TuneConfig) -> Result<Vec<MethodResult>> {
    let perf = cfg.perf_config(Vec::new());
    let paths: Vec<PathBuf> = if cfg.scenes.is_empty() {
        vec![res
            .find("scenes/demo.toml")
            .map_err(|e| anyhow::anyhow!("{e}"))?]
    } else {
        cfg.scenes.clone()
    };
    let mut loaded = Vec::new();
    for path in &paths {
        if !path.is_file() {
            bail!("{}", rust_i18n::t!("tune.no_scene", path = path.display()));
        }
        let (sd, bvh) =
            references::load_scene(res, path, &perf).with_context(|| path.display().to_string())?;
        if !sd.cameras.iter().any(|c| c.train) {
            bail!(
                "{}",
                rust_i18n::t!("tune.no_training", path = path.display())
            );
        }
        loaded.push((path.clone(), sd, bvh));
    }
    // The truths: every camera at the scene's radius (cached across runs).
    let total: usize = loaded.iter().map(|(_, sd, _)| sd.cameras.len()).sum();
    let (mut done, mut count) = (0, RenderCount::default());
    for (_, sd, bvh) in &mut loaded {
        let radius = sd.desc.ao.radius;
        references::trace_references(sd, bvh, &[radius], &perf, &mut count, (&mut done, total));
    }

    type Plan = (AoMethod, AoSettings, Vec<AoSettings>, Vec<space::Axis>);
    let plans: Vec<Vec<Plan>> = loaded
        .iter()
        .map(|(_, sd, _)| {
            cfg.methods
                .iter()
                .map(|&m| {
                    let start = start_of(sd, m);
                    let budgeted = cfg.budget.is_some();
                    let starts = space::starts(m, &start, budgeted);
                    (m, start, starts, space::axes(m, &start, budgeted))
                })
                .collect()
        })
        .collect();
    // The bar counts configurations; its length is the most the searches can score (a search
    // that converges early jumps ahead), plus the test cameras' two tables per method.
    let steps: usize = plans
        .iter()
        .flatten()
        .map(|(_, _, starts, axes)| search::max_evaluations(starts.len(), axes, cfg.passes) + 2)
        .sum();
    let pb = progress::bar(
        steps as u64,
        "tune {bar:40} {pos}/{len} configurations [{elapsed_precise} < {eta_precise}] {msg}",
        cfg.progress,
    );
    let ctx = HeadlessContext::new()?;
    let mut results = Vec::new();
    let mut position = 0u64;
    for ((path, sd, _), plan) in loaded.iter().zip(plans) {
        let mut engine = Engine::new(&ctx.gl, res.clone(), &sd.desc, perf.width, perf.height)?;
        let lesson = start_of(sd, AoMethod::SaoLesson);
        for (method, start, starts, axes) in plan {
            pb.set_message(format!("{} {}", sd.name, method.name()));
            // Each configuration's AO time over the lesson chain's, timed just before it (the
            // ratio survives the load of other programs better than either time alone).
            let mut ratios: BTreeMap<String, f64> = BTreeMap::new();
            let score = |ao: &AoSettings| -> Result<Score> {
                pb.inc(1);
                if let Some(limit) = cfg.budget {
                    let signature = format!("{:?}", space::cost_signature(ao));
                    let ratio = match ratios.get(&signature) {
                        Some(r) => *r,
                        None => {
                            let lesson_ms = cost_ms(&mut engine, sd, &lesson, &perf)?;
                            let r = cost_ms(&mut engine, sd, ao, &perf)? / lesson_ms.max(1e-6);
                            ratios.insert(signature, r);
                            r
                        }
                    };
                    if ratio > limit {
                        return Ok(None);
                    }
                }
                mean_psnr(&mut engine, sd, ao, &perf, true).map(Some)
            };
            let found = search::search(&starts, &axes, cfg.passes, score)
                .with_context(|| format!("{} {}", sd.name, method.name()))?;
            let train_default = match found.start_score {
                Some(s) => s,
                None => mean_psnr(&mut engine, sd, &start, &perf, true)?,
            };
            let test_default = mean_psnr(&mut engine, sd, &start, &perf, false)?;
            let test_tuned = mean_psnr(&mut engine, sd, &found.best, &perf, false)?;
            let ratio_of = |ao: &AoSettings| {
                ratios
                    .get(&format!("{:?}", space::cost_signature(ao)))
                    .copied()
            };
            let cost = match (cfg.budget, ratio_of(&start), ratio_of(&found.best)) {
                (Some(budget), Some(default_ratio), Some(tuned_ratio)) => Some(Cost {
                    budget,
                    default_ratio,
                    tuned_ratio,
                }),
                _ => None,
            };
            position += (search::max_evaluations(starts.len(), &axes, cfg.passes) + 2) as u64;
            pb.set_position(position);
            results.push(MethodResult {
                scene: sd.name.clone(),
                scene_path: path.clone(),
                method,
                default: start,
                tuned: found.best,
                keys: axes.iter().map(|a| a.key).collect(),
                train_default,
                train_tuned: found.best_score,
                test_default,
                test_tuned,
                cost,
                evaluated: found.evaluated,
                over_budget: found.over_budget,
                width: perf.width,
                height: perf.height,
                ref_scale: perf.ref_scale,
                ref_rays: perf.ref_rays,
            });
        }
    }
    pb.finish_and_clear();
    Ok(results)
}

/// The scene's `[ao]` running `method`: where every search starts, and what "default" means.
fn start_of(sd: &SceneData, method: AoMethod) -> AoSettings {
    AoSettings {
        method,
        enabled: true,
        ..sd.desc.ao
    }
}

/// Mean PSNR (dB) of the training (`train`) or test cameras with the engine's AO set to `ao`, each
/// against its reference at the scene's radius (the bench's raw error).
fn mean_psnr(
    engine: &mut Engine,
    sd: &SceneData,
    ao: &AoSettings,
    perf: &PerfConfig,
    train: bool,
) -> Result<f64> {
    engine.ao_settings = *ao;
    let (mut sum, mut n) = (0.0, 0);
    for (ci, cam) in sd.cameras.iter().enumerate() {
        if cam.train != train {
            continue;
        }
        let view = camera_view(engine, sd, ci, sd.desc.ao.radius, perf)?;
        sum += raw_error(sd, ci, sd.desc.ao.radius, &view, false).psnr;
        n += 1;
    }
    Ok(sum / n.max(1) as f64)
}

/// Median AO-chain ms of `ao` at the scene's own camera, timed as the bench times a setting.
fn cost_ms(engine: &mut Engine, sd: &SceneData, ao: &AoSettings, perf: &PerfConfig) -> Result<f64> {
    engine.ao_settings = *ao;
    engine.camera = sd.cameras[0].camera(&sd.desc.camera);
    engine.sync_shader_constants()?;
    ao_chain_ms(engine, perf)
}
