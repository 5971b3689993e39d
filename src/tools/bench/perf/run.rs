//! The bench's run loop: references first (the slow, cached part), then every method and setting on
//! every scene, then the report files.

use super::config::PerfConfig;
use super::references::{self, Ceiling, RenderCount};
use super::report::{ReferenceInfo, Report};
use super::setting::run_setting;
use super::{chart, html, markdown};
use crate::ao::{AoMethod, AoSettings};
use crate::platform::HeadlessContext;
use crate::render::Engine;
use crate::res::ResDirs;
use crate::tools::bench::catalog::{self, Setting};
use crate::tools::bench::progress;
use crate::tools::bench::timing::load_average;
use anyhow::{bail, Context as _, Result};
use std::path::PathBuf;
use std::time::Instant;

/// Runs the benchmark and writes report.json, report.md, report.html (with `pictures/`) and the
/// charts into `cfg.out`.
pub fn run(res: &ResDirs, cfg: &PerfConfig) -> Result<Report> {
    let t0 = Instant::now();
    cfg.check()?;
    let (rw, rh) = cfg.reference_size();
    std::fs::create_dir_all(&cfg.out)
        .with_context(|| format!("cannot create {}", cfg.out.display()))?;

    let scene_paths: Vec<PathBuf> = if cfg.scenes.is_empty() {
        vec![res
            .find("scenes/demo.toml")
            .map_err(|e| anyhow::anyhow!("{e}"))?]
    } else {
        cfg.scenes.clone()
    };
    let plan = plan(cfg)?;
    let mut radii: Vec<f32> = plan
        .iter()
        .flat_map(|(_, s)| s.iter().map(|s| s.radius))
        .collect();
    radii.sort_by(|a, b| a.total_cmp(b));
    radii.dedup();

    // References first: they are the slow part, and cached for later runs.
    let mut traced = RenderCount::default();
    let scenes = scene_paths
        .iter()
        .map(|path| references::load_scene(res, path, &radii, cfg, &mut traced))
        .collect::<Result<Vec<_>>>()?;

    let ctx = HeadlessContext::new()?;
    let timing = if ctx.software {
        "wall clock around glFinish per pass (software GL: Mesa llvmpipe; timer queries do not measure real time there)"
    } else {
        "wall clock around glFinish per pass (hardware GL)"
    };
    let total_settings: usize = plan.iter().map(|(_, s)| s.len()).sum::<usize>() * scenes.len();
    let pb = progress::bar(
        total_settings as u64,
        "bench {bar:40} {pos}/{len} settings [{elapsed_precise} < {eta_precise}] {msg}",
        cfg.progress,
    );
    let load_before = load_average();
    let mut rows = Vec::new();
    let mut screen_count = RenderCount::default();
    for sd in &scenes {
        // The screen-space references read the depth buffer at the bench size, as the methods do,
        // and average their visibility over the blocks the bench averages the methods' output over.
        let mut engine = Engine::new(&ctx.gl, res.clone(), &sd.desc, cfg.width, cfg.height)?;
        let ceilings = ceilings(&plan, &engine.ao_settings);
        let screen =
            references::screen_references(&mut engine, sd, &ceilings, cfg, &pb, &mut screen_count)?;
        engine.resize(cfg.width, cfg.height)?;
        for (method, settings) in &plan {
            for s in settings {
                pb.set_message(format!("{} {} {}", sd.name, method.name(), s.label()));
                let row = run_setting(&mut engine, sd, &screen, *method, s, cfg)
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

/// The settings of every method, checked against what the engine accepts.
fn plan(cfg: &PerfConfig) -> Result<Vec<(AoMethod, Vec<Setting>)>> {
    let plan: Vec<(AoMethod, Vec<Setting>)> = cfg
        .methods
        .iter()
        .map(|m| {
            (
                *m,
                catalog::settings_for(*m, &cfg.samples, &cfg.radii, &cfg.qualities),
            )
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

/// report.json, report.md, report.html (its pictures are written with each row) and (when a font is found) the charts; a chart that cannot be drawn is
/// reported on stderr and the run still succeeds, the tables being the result.
fn write_outputs(report: &Report, cfg: &PerfConfig) -> Result<()> {
    let json_path = cfg.out.join("report.json");
    let json = serde_json::to_string_pretty(report)?;
    std::fs::write(&json_path, json)
        .with_context(|| format!("cannot write {}", json_path.display()))?;
    let md_path = cfg.out.join("report.md");
    std::fs::write(&md_path, markdown::markdown(report, cfg)?)
        .with_context(|| format!("cannot write {}", md_path.display()))?;
    crate::io::write_file(&cfg.out.join("report.html"), html::html(report).as_bytes())?;
    if cfg.charts {
        if let Err(e) = chart::write_charts(report, &cfg.out) {
            eprintln!("charts not written: {e:#}");
        }
    }
    Ok(())
}
