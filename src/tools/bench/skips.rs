//! `opengl3d bench --skips`: what each piece of skipped work saves, measured in one run.
//!
//! Every case renders the same frame in two configurations, alternating frame by frame so that load
//! from other programs falls on both alike: one where the work is needed (AO on, a shadow-casting
//! light, bloom on, culling off…) and one where the engine skips it. Each frame is timed pass by pass
//! (`Engine::collect_stats`: glFinish around every pass, wall clock and process CPU time); the report
//! gives the medians, the saving, the ratio skipped / needed, the passes that did not run and the draw
//! calls, plus the GPU memory the AO targets take when AO is on (none are allocated while it is off).

use super::timing::median;
use super::{limits, progress};
use crate::platform::HeadlessContext;
use crate::render::{Engine, PassStat, View};
use crate::res::ResDirs;
use crate::scene::SceneDesc;
use anyhow::{Context as _, Result};
use glam::Vec3;
use serde::Serialize;
use std::path::{Path, PathBuf};

/// What `run` needs (the CLI fills it from `BenchArgs`; tests build it directly).
#[derive(Clone, Debug)]
pub struct SkipsConfig {
    /// Scene file; `None` = the demo scene.
    pub scene: Option<PathBuf>,
    pub width: u32,
    pub height: u32,
    pub out: PathBuf,
    pub warmup: u32,
    pub frames: u32,
    pub progress: bool,
}

/// Medians of one configuration of a case.
#[derive(Clone, Debug, Serialize)]
pub struct Side {
    /// Median of the per-frame sum of the passes' wall-clock ms.
    pub frame_ms: f64,
    /// Median of the per-frame sum of the passes' process CPU ms (robust to other load).
    pub frame_cpu_ms: f64,
    pub draw_calls: u64,
    /// Passes of the frame, in order.
    pub passes: Vec<String>,
}

#[derive(Clone, Debug, Serialize)]
pub struct Case {
    pub name: String,
    /// What the engine skips in the second configuration.
    pub skip: String,
    pub needed: Side,
    pub skipped: Side,
    /// Passes that ran when needed and not when skipped.
    pub passes_not_run: Vec<String>,
    pub saved_ms: f64,
    pub saved_cpu_ms: f64,
    /// skipped / needed, wall clock and CPU.
    pub ratio: f64,
    pub ratio_cpu: f64,
}

#[derive(Clone, Debug, Serialize)]
pub struct SkipsReport {
    pub renderer: String,
    pub width: u32,
    pub height: u32,
    pub warmup_frames: u32,
    pub timed_frames: u32,
    /// Bytes of the AO targets (all levels) once a frame ran AO, and before any did with AO off.
    pub ao_target_bytes_on: u64,
    pub ao_target_bytes_off: u64,
    pub cases: Vec<Case>,
}

/// One case: a name, what is skipped, and how to put the engine in each configuration.
struct CaseDef {
    name: &'static str,
    skip: &'static str,
    needed: fn(&mut Engine),
    skipped: fn(&mut Engine),
}

fn cases() -> Vec<CaseDef> {
    vec![
        CaseDef {
            name: "AO off",
            skip: "every AO pass (restore, down-sampling, the method, blur, composite)",
            needed: |e| e.ao_settings.enabled = true,
            skipped: |e| e.ao_settings.enabled = false,
        },
        CaseDef {
            name: "linear-depth view",
            skip: "the AO method and its blur (the blurred AO view needs them)",
            needed: |e| e.view = View::Ao,
            skipped: |e| e.view = View::LinearDepth,
        },
        CaseDef {
            name: "no shadow-casting light",
            skip: "the shadow-map pass",
            needed: |e| e.light.shadow = true,
            skipped: |e| e.light.shadow = false,
        },
        CaseDef {
            name: "bloom off",
            skip: "the bloom chain (bright pass, down and up sampling)",
            needed: |e| e.bloom.enabled = true,
            skipped: |e| e.bloom.enabled = false,
        },
        CaseDef {
            name: "frustum culling, camera facing away",
            skip: "objects outside the view (draw calls of the opaque pass)",
            needed: |e| e.frustum_culling = false,
            skipped: |e| e.frustum_culling = true,
        },
    ]
}

fn frame(engine: &mut Engine) -> Result<Vec<PassStat>> {
    // Values of the debug views, the image otherwise: both run every pass of the view.
    if engine.view == View::Composite {
        engine.render_image()?;
    } else {
        engine.render_values(engine.view)?;
    }
    Ok(engine.last_stats())
}

fn side(frames: &[Vec<PassStat>]) -> Side {
    let sum = |f: &Vec<PassStat>, g: fn(&PassStat) -> f64| f.iter().map(g).sum::<f64>();
    Side {
        frame_ms: median(
            &mut frames
                .iter()
                .map(|f| sum(f, |p| p.wall_ms))
                .collect::<Vec<_>>(),
        ),
        frame_cpu_ms: median(
            &mut frames
                .iter()
                .map(|f| sum(f, |p| p.cpu_ms))
                .collect::<Vec<_>>(),
        ),
        draw_calls: frames
            .last()
            .map(|f| f.iter().map(|p| p.draw_calls).sum())
            .unwrap_or(0),
        passes: frames
            .last()
            .map(|f| f.iter().map(|p| p.name.to_string()).collect())
            .unwrap_or_default(),
    }
}

/// Runs every case and writes skips.json and skips.md into `cfg.out`.
pub fn run(res: &ResDirs, cfg: &SkipsConfig) -> Result<SkipsReport> {
    limits::check_size(cfg.width, cfg.height)?;
    limits::check_frames(cfg.frames)?;
    let path = match &cfg.scene {
        Some(p) => p.clone(),
        None => res
            .find("scenes/demo.toml")
            .map_err(|e| anyhow::anyhow!("{e}"))?,
    };
    let mut desc = SceneDesc::load(&path)?;
    desc.output.width = cfg.width;
    desc.output.height = cfg.height;
    // Every case starts from the work being needed; AO with the engine's own SAO.
    desc.ao.enabled = true;
    desc.light.shadow = true;
    desc.bloom.enabled = true;
    let ctx = HeadlessContext::new()?;

    // Memory: a fresh engine with AO off has no AO targets; one AO frame creates them.
    let mut off = desc.clone();
    off.ao.enabled = false;
    let mut engine = Engine::new(&ctx.gl, res.clone(), &off, cfg.width, cfg.height)?;
    engine.render_image()?;
    let ao_target_bytes_off: u64 = engine.ao_textures().iter().map(|t| t.bytes).sum();
    engine.ao_settings.enabled = true;
    engine.render_image()?;
    let ao_target_bytes_on: u64 = engine.ao_textures().iter().map(|t| t.bytes).sum();
    drop(engine);

    let defs = cases();
    let per_case = (cfg.warmup + cfg.frames) as u64 * 2;
    let bar = progress::bar(
        defs.len() as u64 * per_case,
        "skips {bar:30} {pos}/{len} frames {msg}",
        cfg.progress,
    );
    let mut out = Vec::new();
    for def in &defs {
        bar.set_message(def.name);
        let mut engine = Engine::new(&ctx.gl, res.clone(), &desc, cfg.width, cfg.height)?;
        engine.collect_stats = true;
        if def.name.starts_with("frustum") {
            // Look from the scene's camera away from its target: most objects leave the view.
            let back = engine.camera.eye * 2.0 - engine.camera.target;
            engine.camera.target = back + Vec3::new(0.0, -0.2, 0.0);
        }
        let (mut needed, mut skipped) = (Vec::new(), Vec::new());
        for i in 0..cfg.warmup + cfg.frames {
            (def.needed)(&mut engine);
            let a = frame(&mut engine)?;
            (def.skipped)(&mut engine);
            let b = frame(&mut engine)?;
            if i >= cfg.warmup {
                needed.push(a);
                skipped.push(b);
            }
            bar.inc(2);
        }
        let (needed, skipped) = (side(&needed), side(&skipped));
        let passes_not_run = needed
            .passes
            .iter()
            .filter(|p| !skipped.passes.contains(p))
            .cloned()
            .collect();
        out.push(Case {
            name: def.name.to_string(),
            skip: def.skip.to_string(),
            saved_ms: needed.frame_ms - skipped.frame_ms,
            saved_cpu_ms: needed.frame_cpu_ms - skipped.frame_cpu_ms,
            ratio: skipped.frame_ms / needed.frame_ms.max(1e-9),
            ratio_cpu: skipped.frame_cpu_ms / needed.frame_cpu_ms.max(1e-9),
            needed,
            skipped,
            passes_not_run,
        });
    }
    bar.finish_and_clear();
    let report = SkipsReport {
        renderer: crate::gl::describe_renderer(&ctx.gl),
        width: cfg.width,
        height: cfg.height,
        warmup_frames: cfg.warmup,
        timed_frames: cfg.frames,
        ao_target_bytes_on,
        ao_target_bytes_off,
        cases: out,
    };
    write(&report, &cfg.out)?;
    Ok(report)
}

fn write(report: &SkipsReport, dir: &Path) -> Result<()> {
    std::fs::create_dir_all(dir).with_context(|| format!("cannot create {}", dir.display()))?;
    let json_path = dir.join("skips.json");
    std::fs::write(&json_path, serde_json::to_string_pretty(report)?)
        .with_context(|| format!("cannot write {}", json_path.display()))?;
    let md_path = dir.join("skips.md");
    std::fs::write(&md_path, markdown(report))
        .with_context(|| format!("cannot write {}", md_path.display()))?;
    Ok(())
}

fn markdown(r: &SkipsReport) -> String {
    let mut s = format!(
        "# What skipped work saves\n\n`opengl3d bench --skips` at {}×{} on **{}**: each case renders the frame \
         with the work needed and with it skipped, alternating, {} warm-up and {} timed frames each; \
         medians of the per-frame sum of the passes (glFinish around each pass; wall ms, and process \
         CPU ms, which other load barely moves). Ratio = skipped / needed.\n\n",
        r.width, r.height, r.renderer, r.warmup_frames, r.timed_frames
    );
    s.push_str(
        "| case | skipped work | passes not run | needed ms (CPU) | skipped ms (CPU) | saved ms | ratio (CPU) | draw calls |\n\
         |---|---|---|---:|---:|---:|---:|---:|\n",
    );
    for c in &r.cases {
        s.push_str(&format!(
            "| {} | {} | {} | {:.1} ({:.1}) | {:.1} ({:.1}) | {:.1} | {:.2} ({:.2}) | {} → {} |\n",
            c.name,
            c.skip,
            if c.passes_not_run.is_empty() {
                "–".to_string()
            } else {
                c.passes_not_run.join(", ")
            },
            c.needed.frame_ms,
            c.needed.frame_cpu_ms,
            c.skipped.frame_ms,
            c.skipped.frame_cpu_ms,
            c.saved_ms,
            c.ratio,
            c.ratio_cpu,
            c.needed.draw_calls,
            c.skipped.draw_calls
        ));
    }
    s.push_str(&format!(
        "\nAO targets: {:.1} MiB once a frame runs AO, {} bytes in an engine that has only run with AO off.\n",
        r.ao_target_bytes_on as f64 / (1024.0 * 1024.0),
        r.ao_target_bytes_off
    ));
    s
}
