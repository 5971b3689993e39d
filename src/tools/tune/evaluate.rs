//! One run of `tune` on the engine: the truths first (the bench's cached references at each
//! scene's radius), then per scene and method the search, each configuration scored by the mean
//! PSNR of its training cameras; the test cameras are rendered only for the scene's own table and
//! the chosen one.

use super::config::TuneConfig;
use super::file_space::{self, FileChoice, FileConfig};
use super::search::{self, Apply, Axis, Score};
use super::space;
use crate::ao::{user_method, AoMethod, AoSettings};
use crate::platform::HeadlessContext;
use crate::render::Engine;
use crate::res::ResDirs;
use crate::tools::bench::perf::references::{self, RenderCount, SceneData};
use crate::tools::bench::perf::setting::{ao_chain_ms, camera_view, raw_error};
use crate::tools::bench::perf::PerfConfig;
use crate::tools::bench::progress;
use anyhow::{bail, Context as _, Result};
use indicatif::ProgressBar;
use serde::Serialize;
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

/// One method tuned on one scene.
#[derive(Clone, Debug, Serialize)]
pub struct MethodResult {
    pub scene: String,
    pub scene_path: PathBuf,
    /// The engine's method, or for a method file the one whose place it takes.
    pub method: AoMethod,
    /// A method file's name, path and parameters (`tune --method-file`).
    pub file: Option<FileResult>,
    /// The scene's `[ao]` with the method set, and the chosen table.
    pub default: AoSettings,
    pub tuned: AoSettings,
    /// The keys searched (a method file's parameters by their names).
    pub keys: Vec<String>,
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

/// A method file tuned: which, and its parameters' defaults and chosen values.
#[derive(Clone, Debug, Serialize)]
pub struct FileResult {
    pub name: String,
    pub path: PathBuf,
    pub parameters: Vec<ParameterResult>,
}

#[derive(Clone, Debug, Serialize)]
pub struct ParameterResult {
    pub name: String,
    pub default: f32,
    pub tuned: f32,
}

impl MethodResult {
    /// The method's name in reports: the method file's own, or the engine's.
    pub fn name(&self) -> &str {
        match &self.file {
            Some(f) => &f.name,
            None => self.method.name(),
        }
    }
}

#[derive(Clone, Copy, Debug, Serialize)]
pub struct Cost {
    pub budget: f64,
    pub default_ratio: f64,
    pub tuned_ratio: f64,
}

pub fn run(res: &ResDirs, cfg: &TuneConfig) -> Result<Vec<MethodResult>> {
    // A broken method file is refused before any truth is traced.
    let files = cfg.read_method_files()?;
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

    let budgeted = cfg.budget.is_some();
    type Plan = (AoMethod, AoSettings, Vec<AoSettings>, Vec<space::Axis>);
    let plans: Vec<Vec<Plan>> = loaded
        .iter()
        .map(|(_, sd, _)| {
            cfg.methods
                .iter()
                .map(|&m| {
                    let start = start_of(sd, m);
                    let starts = space::starts(m, &start, budgeted);
                    (m, start, starts, space::axes(m, &start, budgeted))
                })
                .collect()
        })
        .collect();
    type FilePlan = (FileConfig, Vec<FileConfig>, Vec<Axis<FileChoice>>);
    let file_plans: Vec<Vec<FilePlan>> = loaded
        .iter()
        .map(|(_, sd, _)| {
            files
                .iter()
                .map(|f| {
                    let start = file_space::start(f, &start_of(sd, user_method::HOST));
                    let starts = file_space::starts(f, &start, budgeted);
                    let axes = file_space::axes(f, &start, budgeted);
                    (start, starts, axes)
                })
                .collect()
        })
        .collect();
    // The bar counts configurations; its length is the most the searches can score (a search
    // that converges early jumps ahead), plus the test cameras' two tables per method.
    let steps: usize =
        plans
            .iter()
            .flatten()
            .map(|(_, _, starts, axes)| search::max_evaluations(starts.len(), axes, cfg.passes) + 2)
            .chain(file_plans.iter().flatten().map(|(_, starts, axes)| {
                search::max_evaluations(starts.len(), axes, cfg.passes) + 2
            }))
            .sum();
    let pb = progress::bar(
        steps as u64,
        "tune {bar:40} {pos}/{len} configurations [{elapsed_precise} < {eta_precise}] {msg}",
        cfg.progress,
    );
    let ctx = HeadlessContext::new()?;
    let mut results = Vec::new();
    let mut position = 0u64;
    for (((path, sd, _), plan), file_plan) in loaded.iter().zip(plans).zip(file_plans) {
        let mut engine = Engine::new(&ctx.gl, res.clone(), &sd.desc, perf.width, perf.height)?;
        let lesson = start_of(sd, AoMethod::SaoLesson);
        let run = Run {
            sd,
            cfg,
            perf: &perf,
            lesson: &lesson,
            pb: &pb,
        };
        for (method, start, starts, axes) in plan {
            pb.set_message(format!("{} {}", sd.name, method.name()));
            let mut set = |engine: &mut Engine, ao: &AoSettings| -> Result<()> {
                engine.ao_settings = *ao;
                Ok(())
            };
            let signature = |ao: &AoSettings| format!("{:?}", space::cost_signature(ao));
            let t = run
                .tune(&mut engine, (&start, &starts, &axes), &mut set, signature)
                .with_context(|| format!("{} {}", sd.name, method.name()))?;
            position += (search::max_evaluations(starts.len(), &axes, cfg.passes) + 2) as u64;
            pb.set_position(position);
            results.push(run.result(path, method, (start, t.best), &axes, &t.figures, None));
        }
        for (file, (start, starts, axes)) in files.iter().zip(file_plan) {
            pb.set_message(format!("{} {}", sd.name, file.name));
            // The shader is rebuilt only when a parameter changes (its values are `#define`s).
            let mut built: Option<Vec<f32>> = None;
            let mut set = |engine: &mut Engine, c: &FileConfig| -> Result<()> {
                if built.as_ref() != Some(&c.values) {
                    engine.use_method_file(file_space::with_values(file, &c.values))?;
                    built = Some(c.values.clone());
                }
                engine.ao_settings = c.ao;
                Ok(())
            };
            let t = run
                .tune(
                    &mut engine,
                    (&start, &starts, &axes),
                    &mut set,
                    file_space::cost_signature,
                )
                .with_context(|| format!("{} {}", sd.name, file.path.display()))?;
            engine.ao.set_user_method(None);
            position += (search::max_evaluations(starts.len(), &axes, cfg.passes) + 2) as u64;
            pb.set_position(position);
            let tuned_file = FileResult {
                name: file.name.clone(),
                path: file.path.clone(),
                parameters: file
                    .parameters
                    .iter()
                    .zip(&t.best.values)
                    .map(|(p, v)| ParameterResult {
                        name: p.name.clone(),
                        default: p.default,
                        tuned: *v,
                    })
                    .collect(),
            };
            let method = user_method::HOST;
            let pair = (start.ao, t.best.ao);
            results.push(run.result(path, method, pair, &axes, &t.figures, Some(tuned_file)));
        }
    }
    pb.finish_and_clear();
    Ok(results)
}

/// What a search measured, whatever its configurations are.
struct Figures {
    train_default: f64,
    train_tuned: f64,
    test_default: f64,
    test_tuned: f64,
    cost: Option<Cost>,
    evaluated: usize,
    over_budget: usize,
}

struct Tuned<C> {
    best: C,
    figures: Figures,
}

/// One scene's share of a run: what every search on it scores against.
struct Run<'a> {
    sd: &'a SceneData,
    cfg: &'a TuneConfig,
    perf: &'a PerfConfig,
    /// The lesson chain whose AO time the budget is a ratio of.
    lesson: &'a AoSettings,
    pb: &'a ProgressBar,
}

impl Run<'_> {
    /// Searches `axes` from `starts` (the first is the default, `start`): `set` puts a
    /// configuration into the engine, `signature` names its cost (configurations with the same
    /// one are timed once). Each is scored by the mean PSNR of the training cameras, and with a
    /// budget timed just after the lesson chain (the ratio survives the load of other programs
    /// better than either time alone); the test cameras are rendered for the start and the best.
    fn tune<C, V>(
        &self,
        engine: &mut Engine,
        (start, starts, axes): (&C, &[C], &[Axis<V>]),
        set: &mut dyn FnMut(&mut Engine, &C) -> Result<()>,
        signature: impl Fn(&C) -> String,
    ) -> Result<Tuned<C>>
    where
        C: Clone + PartialEq + std::fmt::Debug,
        V: Apply<C>,
    {
        let (sd, perf) = (self.sd, self.perf);
        let mut ratios: BTreeMap<String, f64> = BTreeMap::new();
        let found = {
            let score = |c: &C| -> Result<Score> {
                self.pb.inc(1);
                if let Some(limit) = self.cfg.budget {
                    let ratio = match ratios.get(&signature(c)) {
                        Some(r) => *r,
                        None => {
                            engine.ao_settings = *self.lesson;
                            let lesson_ms = cost_ms(engine, sd, perf)?;
                            set(engine, c)?;
                            let r = cost_ms(engine, sd, perf)? / lesson_ms.max(1e-6);
                            ratios.insert(signature(c), r);
                            r
                        }
                    };
                    if ratio > limit {
                        return Ok(None);
                    }
                }
                set(engine, c)?;
                mean_psnr(engine, sd, perf, true).map(Some)
            };
            search::search(starts, axes, self.cfg.passes, score)?
        };
        let train_default = match found.start_score {
            Some(s) => s,
            None => {
                set(engine, start)?;
                mean_psnr(engine, sd, perf, true)?
            }
        };
        set(engine, start)?;
        let test_default = mean_psnr(engine, sd, perf, false)?;
        set(engine, &found.best)?;
        let test_tuned = mean_psnr(engine, sd, perf, false)?;
        let ratio_of = |c: &C| ratios.get(&signature(c)).copied();
        let cost = match (self.cfg.budget, ratio_of(start), ratio_of(&found.best)) {
            (Some(budget), Some(default_ratio), Some(tuned_ratio)) => Some(Cost {
                budget,
                default_ratio,
                tuned_ratio,
            }),
            _ => None,
        };
        Ok(Tuned {
            figures: Figures {
                train_default,
                train_tuned: found.best_score,
                test_default,
                test_tuned,
                cost,
                evaluated: found.evaluated,
                over_budget: found.over_budget,
            },
            best: found.best,
        })
    }

    fn result<V>(
        &self,
        path: &Path,
        method: AoMethod,
        (default, tuned): (AoSettings, AoSettings),
        axes: &[Axis<V>],
        f: &Figures,
        file: Option<FileResult>,
    ) -> MethodResult {
        MethodResult {
            scene: self.sd.name.clone(),
            scene_path: path.to_path_buf(),
            method,
            file,
            default,
            tuned,
            keys: axes.iter().map(|a| a.key.clone()).collect(),
            train_default: f.train_default,
            train_tuned: f.train_tuned,
            test_default: f.test_default,
            test_tuned: f.test_tuned,
            cost: f.cost,
            evaluated: f.evaluated,
            over_budget: f.over_budget,
            width: self.perf.width,
            height: self.perf.height,
            ref_scale: self.perf.ref_scale,
            ref_rays: self.perf.ref_rays,
        }
    }
}

/// The scene's `[ao]` running `method`: where every search starts, and what "default" means.
fn start_of(sd: &SceneData, method: AoMethod) -> AoSettings {
    AoSettings {
        method,
        enabled: true,
        ..sd.desc.ao
    }
}

/// Mean PSNR (dB) of the training (`train`) or test cameras with the engine's AO as set, each
/// against its reference at the scene's radius (the bench's raw error).
fn mean_psnr(engine: &mut Engine, sd: &SceneData, perf: &PerfConfig, train: bool) -> Result<f64> {
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

/// Median AO-chain ms of the engine's AO as set, at the scene's own camera, timed as the bench
/// times a setting.
fn cost_ms(engine: &mut Engine, sd: &SceneData, perf: &PerfConfig) -> Result<f64> {
    engine.camera = sd.cameras[0].camera(&sd.desc.camera);
    engine.sync_shader_constants()?;
    ao_chain_ms(engine, perf)
}
