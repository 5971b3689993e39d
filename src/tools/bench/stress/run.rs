//! The stress run: every case, then the depth table, then `stress.json` and `stress.md`.

use super::cases::{all_cases, Meshes};
use super::checks::run_case;
use super::report::StressReport;
use super::{depth, markdown};
use crate::platform::HeadlessContext;
use crate::res::ResDirs;
use crate::tools::bench::progress;
use anyhow::{Context as _, Result};
use std::path::PathBuf;
use std::time::Instant;

/// What a stress run covers (the CLI fills it from `BenchArgs`; tests build it directly).
#[derive(Clone, Debug)]
pub struct StressConfig {
    pub out: PathBuf,
    /// Include the 4096×4096 frame.
    pub large: bool,
    /// Only the first case of each category and one depth configuration (for tests).
    pub quick: bool,
    pub progress: bool,
}

/// Runs every case and the depth table, and writes stress.json and stress.md into `cfg.out`.
pub fn run(res: &ResDirs, cfg: &StressConfig) -> Result<StressReport> {
    let t0 = Instant::now();
    std::fs::create_dir_all(&cfg.out)
        .with_context(|| format!("cannot create {}", cfg.out.display()))?;
    let mesh_dir = std::env::temp_dir().join(format!("opengl3d-stress-{}", std::process::id()));
    let meshes = Meshes::new(&mesh_dir)?;
    let ctx = HeadlessContext::new()?;
    let (mut cases, mut skipped) = all_cases(&meshes, cfg.large);
    if cfg.quick {
        let mut seen = Vec::new();
        let before = cases.len();
        cases.retain(|c| {
            let first = !seen.contains(&c.category);
            seen.push(c.category);
            first
        });
        skipped.push(format!(
            "{} cases (quick run: first case of each category)",
            before - cases.len()
        ));
    }
    let depth_configs: &[(f32, f32)] = if cfg.quick {
        &depth::DEPTH_CONFIGS[..1]
    } else {
        &depth::DEPTH_CONFIGS
    };
    let pb = progress::bar(
        (cases.len() + depth_configs.len()) as u64,
        "stress {bar:40} {pos}/{len} [{elapsed_precise}] {msg}",
        cfg.progress,
    );
    let mut results = Vec::new();
    for case in &cases {
        pb.set_message(format!("{}: {}", case.category, case.name));
        let r = run_case(&ctx, res, case).with_context(|| format!("stress case {}", case.name))?;
        results.push(r);
        pb.inc(1);
    }

    let (depth_precision, depth_probe_note) =
        depth::measure(&ctx, res, &meshes, depth_configs, &pb)?;
    pb.finish_and_clear();
    // Removes the temporary mesh folder (a warning if that fails).
    drop(meshes);
    let total_non_finite = results.iter().map(|r| r.non_finite).sum();
    let report = StressReport {
        renderer: ctx.renderer.clone(),
        software: ctx.software,
        cases: results,
        total_non_finite,
        depth_precision,
        depth_probe_note,
        skipped,
        run_s: t0.elapsed().as_secs_f64(),
    };
    let json_path = cfg.out.join("stress.json");
    std::fs::write(&json_path, serde_json::to_string_pretty(&report)?)
        .with_context(|| format!("cannot write {}", json_path.display()))?;
    let md_path = cfg.out.join("stress.md");
    std::fs::write(&md_path, markdown::markdown(&report)?)
        .with_context(|| format!("cannot write {}", md_path.display()))?;
    Ok(report)
}
