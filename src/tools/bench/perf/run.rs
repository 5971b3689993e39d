//! The bench's run loop: references first (the slow, cached part), then every method and setting on
//! every scene, then the report files.

use super::config::PerfConfig;
use super::protocol::{self, Grid, Work};
use super::references::{self, Ceiling, RenderCount};
use super::report::{ReferenceInfo, Report};
use super::setting::run_setting;
use super::{chart, html, markdown};
use crate::ao::user_method::HOST;
use crate::ao::{AoMethod, AoSettings};
use crate::platform::HeadlessContext;
use crate::render::Engine;
use crate::res::ResDirs;
use crate::scene::method_file::MethodFile;
use crate::tools::bench::catalog::{self, Setting};
use crate::tools::bench::progress;
use crate::tools::bench::timing::load_average;
use anyhow::{bail, Context as _, Result};
use std::path::PathBuf;
use std::time::Instant;

/// Runs the benchmark and writes report.json, report.md, report.html (with `pictures/`) and the
/// charts into `cfg.out`.
pub fn run(res: &ResDirs, cfg: &PerfConfig) -> Result<Report> {
    run_with_method_files(res, cfg, &[])
}

/// `run`, with the methods of `files` (method files) measured beside the engine's, at the same
/// settings grid (their sample budget; no presets), named by their files' `name`.
pub fn run_with_method_files(
    res: &ResDirs,
    cfg: &PerfConfig,
    files: &[MethodFile],
) -> Result<Report> {
    let t0 = Instant::now();
    cfg.check()?;
    let (rw, rh) = cfg.reference_size();
    std::fs::create_dir_all(&cfg.out)
        .with_context(|| format!("cannot create {}", cfg.out.display()))?;

    let scene_paths: Vec<PathBuf> = if cfg.scenes.is_empty() && cfg.models.is_empty() {
        vec![res
            .find("scenes/demo.toml")
            .map_err(|e| anyhow::anyhow!("{e}"))?]
    } else {
        cfg.scenes.clone()
    };
    let plan = plan(cfg)?;
    let mut loaded = scene_paths
        .iter()
        .map(|path| references::load_scene(res, path, cfg))
        .chain(
            cfg.models
                .iter()
                .map(|path| references::load_model(res, path, cfg)),
        )
        .collect::<Result<Vec<_>>>()?;
    // Each scene's settings: a model's radii follow its size (`SceneData::radius_scale`).
    let plans: Vec<Plan> = loaded
        .iter()
        .map(|(sd, _)| scaled_plan(&plan, sd.radius_scale))
        .collect();
    let ctx = HeadlessContext::new()?;
    let mut work = Work {
        settings: plans.iter().flatten().map(|(_, s)| s.len()).sum::<usize>()
            + files.len() * file_settings(cfg).len() * plans.len(),
        cameras: loaded.first().map_or(0, |(sd, _)| sd.cameras.len()),
        mean_radius: mean(&radii_of(&plan)),
        ..Work::default()
    };
    for ((sd, bvh), plan) in loaded.iter().zip(&plans) {
        let radii = radii_of(plan);
        let missing = references::missing_references(sd, bvh, &radii, cfg);
        work.references += missing;
        work.cached += sd.cameras.len() * radii.len() - missing;
        if cfg.ceilings {
            // One per test camera and radius, twice for vbao (its slabs besides the heightfield).
            let kinds = 1 + plan.iter().any(|(m, _)| *m == AoMethod::Vbao) as usize;
            work.screen_references +=
                sd.cameras.iter().filter(|c| !c.train).count() * radii.len() * kinds;
        }
    }
    if cfg.progress {
        announce(cfg, &ctx, &work, loaded.len());
    }

    // References first: they are the slow part, and cached for later runs.
    let mut traced = RenderCount::default();
    let mut done = 0;
    let total_refs = work.references + work.cached;
    for ((sd, bvh), plan) in loaded.iter_mut().zip(&plans) {
        let progress = (&mut done, total_refs);
        references::trace_references(sd, bvh, &radii_of(plan), cfg, &mut traced, progress);
    }
    let scenes: Vec<_> = loaded.into_iter().map(|(sd, _)| sd).collect();

    let clock = crate::gl::PassClock::of_context(&ctx.gl);
    let total_settings = work.settings;
    let pb = progress::bar(
        total_settings as u64,
        "bench {bar:40} {pos}/{len} settings [{elapsed_precise} < {eta_precise}] {msg}",
        cfg.progress,
    );
    let load_before = load_average();
    let mut rows = Vec::new();
    let mut screen_count = RenderCount::default();
    for (sd, plan) in scenes.iter().zip(&plans) {
        // The screen-space references read the depth buffer at the bench size, the one the
        // methods read, averaged over the blocks the comparison box-averages (as the ray-traced
        // truth averages each pixel's footprint): at the truth's own size a board thinner than one
        // of its pixels would be missing from the buffer the ceiling integrates.
        let mut engine = Engine::new(&ctx.gl, res.clone(), &sd.desc, cfg.width, cfg.height)?;
        let screen = if cfg.ceilings {
            let ceilings = ceilings(plan, &engine.ao_settings);
            references::screen_references(&mut engine, sd, &ceilings, cfg, &pb, &mut screen_count)?
        } else {
            Default::default()
        };
        for (method, settings) in plan {
            for s in settings {
                pb.set_message(format!("{} {} {}", sd.name, method.name(), s.label()));
                let row = run_setting(&mut engine, sd, &screen, (*method, None), s, cfg)
                    .with_context(|| format!("{} {} {}", sd.name, method.name(), s.label()))?;
                rows.push(row);
                pb.inc(1);
            }
        }
        for file in files {
            engine.use_method_file(file.clone())?;
            for s in &file_settings(cfg) {
                pb.set_message(format!("{} {} {}", sd.name, file.name, s.label()));
                let row = run_setting(&mut engine, sd, &screen, (HOST, Some(file)), s, cfg)
                    .with_context(|| {
                        format!("{} {} {}", sd.name, file.path.display(), s.label())
                    })?;
                rows.push(row);
                pb.inc(1);
            }
            engine.ao.set_user_method(None);
        }
    }
    pb.finish_and_clear();

    let report = Report {
        renderer: ctx.renderer.clone(),
        software: ctx.software,
        timing: clock.description().to_string(),
        clock,
        full_protocol: cfg.scaled.is_empty(),
        scaled: cfg.scaled.clone(),
        ceilings: cfg.ceilings,
        cpus: std::thread::available_parallelism().map_or(1, |n| n.get()),
        width: cfg.width,
        height: cfg.height,
        reference: ReferenceInfo {
            rays: cfg.ref_rays,
            width: rw,
            height: rh,
            variant: "visibility (binary, cosine-weighted rays of length R)",
            rendered: traced.rendered,
            cached: traced.cached,
            render_s: traced.render_s,
            screen_rays: cfg.screen_rays,
            screen_rendered: screen_count.rendered,
            screen_cached: screen_count.cached,
            screen_render_s: screen_count.render_s,
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

/// Prints what the run will do and how long it should take, before anything slow starts.
fn announce(cfg: &PerfConfig, ctx: &HeadlessContext, work: &Work, scenes: usize) {
    let p = protocol::Protocol {
        width: cfg.width,
        height: cfg.height,
        ref_scale: cfg.ref_scale,
        ref_rays: cfg.ref_rays,
        screen_rays: cfg.screen_rays,
        warmup: cfg.warmup,
        frames: cfg.frames,
        ceilings: cfg.ceilings,
        grid: cfg.grid,
    };
    let cores = std::thread::available_parallelism().map_or(1, |n| n.get());
    let (rw, rh) = cfg.reference_size();
    eprintln!(
        "{}",
        rust_i18n::t!(
            "bench.plan",
            settings = work.settings,
            scenes = scenes,
            width = cfg.width,
            height = cfg.height,
            refs = work.references,
            cached = work.cached,
            ref_width = rw,
            ref_height = rh,
            rays = cfg.ref_rays
        )
    );
    if ctx.software {
        let estimate = protocol::minutes(protocol::estimate_seconds(&p, work, cores));
        eprintln!(
            "{}",
            rust_i18n::t!("bench.estimate", time = estimate, cores = cores)
        );
    }
    if !cfg.scaled.is_empty() {
        eprintln!(
            "{}",
            rust_i18n::t!("bench.quick", command = protocol::FULL_COMMAND)
        );
        for line in &cfg.scaled {
            eprintln!("  - {line}");
        }
    }
}

/// Every (radius, ceiling) whose screen-space reference the plan's error split needs: each
/// setting's radius with its method's thickness model (`Ceiling::of`) under the scene's AO
/// settings.
fn ceilings(plan: &[(AoMethod, Vec<Setting>)], scene_ao: &AoSettings) -> Vec<(f32, Ceiling)> {
    let mut out: Vec<(f32, Ceiling)> = Vec::new();
    for (method, settings) in plan {
        for s in settings {
            let ao = AoSettings {
                radius: s.radius,
                ..*scene_ao
            };
            let pair = (s.radius, Ceiling::of(*method, &ao));
            if !out.contains(&pair) {
                out.push(pair);
            }
        }
    }
    out
}

/// Every method with its settings.
type Plan = Vec<(AoMethod, Vec<Setting>)>;

/// The radii of `plan`, ascending, each once.
fn radii_of(plan: &Plan) -> Vec<f32> {
    let mut radii: Vec<f32> = plan
        .iter()
        .flat_map(|(_, s)| s.iter().map(|s| s.radius))
        .collect();
    radii.sort_by(|a, b| a.total_cmp(b));
    radii.dedup();
    radii
}

fn mean(v: &[f32]) -> f64 {
    v.iter().map(|x| *x as f64).sum::<f64>() / v.len().max(1) as f64
}

/// `plan` with every radius times `scale` (within the engine's radius range, four significant
/// digits): a model framed from its bounds is measured at radii that follow its size.
fn scaled_plan(plan: &Plan, scale: f32) -> Plan {
    if scale == 1.0 {
        return plan.clone();
    }
    let (lo, hi) = crate::ao::settings::RADIUS_RANGE;
    let round = |r: f32| {
        let digits = 10f32.powi(3 - r.abs().log10().floor() as i32);
        (r * digits).round() / digits
    };
    plan.iter()
        .map(|(m, settings)| {
            let scaled = settings
                .iter()
                .map(|s| Setting {
                    radius: round((s.radius * scale).clamp(lo, hi)),
                    ..*s
                })
                .collect();
            (*m, scaled)
        })
        .collect()
}

/// The settings of every method, checked against what the engine accepts.
/// A method file's settings: the grid's sample counts and radii (the quick grid when none are
/// given), without presets.
fn file_settings(cfg: &PerfConfig) -> Vec<Setting> {
    let given = !(cfg.samples.is_empty() && cfg.radii.is_empty());
    if cfg.grid == Grid::Quick && !given {
        catalog::quick_settings()
    } else {
        catalog::settings_for(AoMethod::Hbao, &cfg.samples, &cfg.radii, &[])
    }
}

fn plan(cfg: &PerfConfig) -> Result<Plan> {
    let plan: Vec<(AoMethod, Vec<Setting>)> = cfg
        .methods
        .iter()
        .map(|m| {
            let given =
                !(cfg.samples.is_empty() && cfg.radii.is_empty() && cfg.qualities.is_empty());
            let settings = if cfg.grid == Grid::Quick && !given {
                catalog::quick_settings()
            } else {
                catalog::settings_for(*m, &cfg.samples, &cfg.radii, &cfg.qualities)
            };
            (*m, settings)
        })
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
    Ok(plan)
}

/// report.json, report.md, (when a font is found) the charts, and report.html (its pictures are written with each row, the
/// main chart is drawn in it); a chart that cannot be drawn is
/// reported on stderr and the run still succeeds, the tables being the result.
fn write_outputs(report: &Report, cfg: &PerfConfig) -> Result<()> {
    let json_path = cfg.out.join("report.json");
    let json = serde_json::to_string_pretty(report)?;
    std::fs::write(&json_path, json)
        .with_context(|| format!("cannot write {}", json_path.display()))?;
    let md_path = cfg.out.join("report.md");
    std::fs::write(&md_path, markdown::markdown(report, cfg)?)
        .with_context(|| format!("cannot write {}", md_path.display()))?;
    // The charts first: the page shows the main one.
    let mut chart_svg = None;
    if cfg.charts {
        match chart::write_charts(report, &cfg.out) {
            Ok(files) => {
                let main = cfg.out.join("report.svg");
                if files.contains(&main) {
                    chart_svg = std::fs::read_to_string(&main).ok();
                }
            }
            Err(e) => eprintln!("charts not written: {e:#}"),
        }
    }
    let page = html::html(report, chart_svg.as_deref());
    crate::io::write_file(&cfg.out.join("report.html"), page.as_bytes())
}
