//! Benchmarks: run time against error versus the ray-traced reference, and numerical stress tests.
//!
//! * `opengl3d bench` ([`perf`]): every AO method × quality setting, timed per pass and compared with
//!   the ray-traced ground truth on fixed cameras → `report.json`, `report.md`, `report.svg/png`.
//! * `opengl3d bench --stress` ([`stress`]): extreme planes, radii, intensities, fields of view, sizes
//!   and cameras, NaN/Inf counts of every output, and linear-depth reconstruction error against
//!   distance for several depth formats → `stress.json`, `stress.md`.
//! * `opengl3d bench --skips` ([`skips`]): what each skipped pass saves (AO off, the linear-depth
//!   view, no shadow light, bloom off, frustum culling), as ratios measured in one run → `skips.json`,
//!   `skips.md`.

pub mod camera_path;
mod camera_path_report;
pub mod camera_path_rows;
pub mod camera_path_score;
pub mod catalog;
pub mod depth_formats;
pub(crate) mod limits;
/// The image metrics live beside the bench (the error map uses them too); the old path still works.
pub use super::metrics;
pub mod perf;
pub(crate) mod progress;
pub mod skips;
pub mod stress;
mod timing;

use crate::ao::{AoMethod, SlicePreset};
use crate::res::ResDirs;
use anyhow::{anyhow, Result};
use clap::Args;
use std::path::PathBuf;

#[derive(Args, Debug, Clone)]
pub struct BenchArgs {
    /// Scene files (default: the demo scene). Each is run at its own camera and three variants.
    #[arg(long = "scene")]
    pub scenes: Vec<PathBuf>,
    /// Models (OBJ), each run as a scene of its own: the camera framed from its bounds as
    /// `render --obj` does, with the same three variants, and (without --radii) the radii scaled
    /// by the AO radius the framing chose. The demo scene runs only when a --scene is given too.
    #[arg(long = "obj", value_name = "FILE")]
    pub models: Vec<PathBuf>,
    /// Run the full protocol (1920×1080, references at 1/6, every method's whole grid of
    /// settings, the error split against each method's ceiling) for the options not given.
    /// Without it, the options not given take a quick run's values (a few minutes on two cores)
    /// and the reports list what was scaled down or skipped.
    #[arg(long)]
    pub full: bool,
    /// Output width (quick run 640, full protocol 1920).
    #[arg(long, allow_negative_numbers = true)]
    pub width: Option<u32>,
    /// Output height (quick run 360, full protocol 1080).
    #[arg(long, allow_negative_numbers = true)]
    pub height: Option<u32>,
    /// Output folder for report.json, report.md and the charts (stress.json and stress.md with --stress).
    #[arg(long, default_value = "out/bench")]
    pub out: PathBuf,
    /// Run the numerical stress tests instead.
    #[arg(long)]
    pub stress: bool,
    /// Measure what each skipped pass saves instead (AO off, linear-depth view, no shadow light,
    /// bloom off, frustum culling), writing skips.json and skips.md.
    #[arg(long, conflicts_with = "stress")]
    pub skips: bool,
    /// AO methods by name, comma-separated (default: every method the engine has).
    #[arg(long, value_delimiter = ',')]
    pub methods: Vec<String>,
    /// Methods of your own (method files, see docs/method-file.md), measured beside the engine's
    /// on the same grid, charts and report; repeat for several.
    #[arg(long = "method-file", value_name = "FILE.toml")]
    pub method_files: Vec<PathBuf>,
    /// Sample counts to run (replaces each method's default settings; combined with --radii).
    #[arg(long, value_delimiter = ',', allow_negative_numbers = true)]
    pub samples: Vec<u32>,
    /// Radii in metres to run (replaces each method's default settings; combined with --samples).
    #[arg(long, value_delimiter = ',', allow_negative_numbers = true)]
    pub radii: Vec<f32>,
    /// Quality presets to run for the methods that have them (gtao, vbao): low, medium, high,
    /// ultra, comma-separated; replaces their default settings (combined with --radii, default 1 m).
    #[arg(long = "quality", value_delimiter = ',')]
    pub qualities: Vec<String>,
    /// Rays per pixel of the ray-traced reference (1 to 65536; default 256).
    #[arg(long, allow_negative_numbers = true,
          value_parser = clap::value_parser!(u32).range(1..=limits::MAX_REF_RAYS as i64))]
    pub ref_rays: Option<u32>,
    /// Compute the screen-space references (the ceilings) and split each method's error into the
    /// depth buffer's share and its sampling's (slow; on with --full).
    #[arg(long)]
    pub ceilings: bool,
    /// Rays per pixel of the screen-space references (the error split; test cameras only; 1 to
    /// 65536; default: --ref-rays, so that they trace the ray-traced reference's own rays).
    #[arg(long, allow_negative_numbers = true,
          value_parser = clap::value_parser!(u32).range(1..=limits::MAX_REF_RAYS as i64))]
    pub screen_rays: Option<u32>,
    /// Render the reference at 1/N of the size and box-average the engine's output by N to compare
    /// (1 to 16; quick run 4, full protocol 6).
    #[arg(long, allow_negative_numbers = true,
          value_parser = clap::value_parser!(u32).range(1..=limits::MAX_REF_SCALE as i64))]
    pub ref_scale: Option<u32>,
    /// Folder of cached references; default: `$OPENGL3D_CACHE`, else
    /// `$XDG_CACHE_HOME/opengl3d/reference`, else `~/.cache/opengl3d/reference`.
    #[arg(long)]
    pub cache: Option<PathBuf>,
    /// Frames rendered before timing (quick run 1, full protocol 2).
    #[arg(long, allow_negative_numbers = true)]
    pub warmup: Option<u32>,
    /// Frames timed, the median is reported (quick run 5, full protocol 7).
    #[arg(long, allow_negative_numbers = true)]
    pub frames: Option<u32>,
    /// Skip the FLIP metric (reported as 0).
    #[arg(long)]
    pub no_flip: bool,
    /// With --stress: skip the 4096×4096 frame.
    #[arg(long)]
    pub no_large: bool,
    /// Run `vbao` and `rtao` one frame at a time and accumulated over frames along a camera path
    /// per scene and test camera instead (--frames still frames, then as many moving; truths per frame),
    /// writing camera-path.json, camera-path.md and a chart per scene.
    #[arg(long, conflicts_with_all = ["stress", "skips"])]
    pub camera_path: bool,
    /// With --camera-path: the accumulated configurations' history length in frames (default 16).
    #[arg(long, requires = "camera_path",
          value_parser = clap::value_parser!(u32).range(2..=4096))]
    pub accumulate: Option<u32>,
    /// With --camera-path: the configurations besides the lesson's, `vbao` and/or
    /// `rtao-<full|half|quarter>-<rays>[-noblur]` (default vbao,rtao-quarter-4).
    #[arg(long, requires = "camera_path", value_delimiter = ',')]
    pub path_rows: Vec<String>,
    /// With --camera-path: run the training cameras instead of the test cameras (to choose a
    /// configuration on).
    #[arg(long, requires = "camera_path")]
    pub path_train: bool,
}

impl BenchArgs {
    pub fn perf_config(&self) -> Result<perf::PerfConfig> {
        // Named by the flag, before any scene is loaded (the plan checks each setting again).
        if let Some(r) = self.radii.iter().find(|r| !(**r > 0.0 && **r <= 100.0)) {
            anyhow::bail!("{}", rust_i18n::t!("bench.bad_radius", radius = r));
        }
        if let Some(n) = self.samples.iter().find(|n| !(1..=256).contains(*n)) {
            anyhow::bail!("{}", rust_i18n::t!("bench.bad_samples", n = n));
        }
        let methods = if self.methods.is_empty() {
            AoMethod::ALL.to_vec()
        } else {
            self.methods
                .iter()
                .map(|n| catalog::method_by_name(n))
                .collect::<Result<Vec<_>>>()?
        };
        let qualities = self
            .qualities
            .iter()
            .map(|n| {
                SlicePreset::from_name(n.trim()).ok_or_else(|| {
                    let names = SlicePreset::ALL.map(SlicePreset::name).join(", ");
                    anyhow!("unknown quality preset '{n}': use one of {names}")
                })
            })
            .collect::<Result<Vec<_>>>()?;
        let given = perf::protocol::Given {
            width: self.width,
            height: self.height,
            ref_scale: self.ref_scale,
            ref_rays: self.ref_rays,
            screen_rays: self.screen_rays,
            warmup: self.warmup,
            frames: self.frames,
            ceilings: self.ceilings,
            settings: !(self.samples.is_empty()
                && self.radii.is_empty()
                && self.qualities.is_empty()),
        };
        let base = if self.full {
            perf::protocol::FULL
        } else {
            perf::protocol::QUICK
        };
        let (p, scaled) = perf::protocol::resolve(&given, &base);
        Ok(perf::PerfConfig {
            scenes: self.scenes.clone(),
            models: self.models.clone(),
            width: p.width,
            height: p.height,
            out: self.out.clone(),
            methods,
            samples: self.samples.clone(),
            radii: self.radii.clone(),
            qualities,
            ref_rays: p.ref_rays,
            screen_rays: p.screen_rays,
            ref_scale: p.ref_scale,
            cache: crate::tools::reference::reference_cache_dir(self.cache.as_deref())?,
            warmup: p.warmup,
            frames: p.frames,
            flip: !self.no_flip,
            charts: true,
            progress: true,
            ceilings: p.ceilings,
            grid: p.grid,
            scaled,
        })
    }
}

pub fn run(res: &ResDirs, args: &BenchArgs) -> Result<()> {
    if args.stress {
        let cfg = stress::StressConfig {
            out: args.out.clone(),
            large: !args.no_large,
            quick: false,
            progress: true,
        };
        let report = stress::run(res, &cfg)?;
        crate::outln!(
            "wrote {} and {}: {} cases, {} NaN/Inf values, {} failed checks",
            args.out.join("stress.json").display(),
            args.out.join("stress.md").display(),
            report.cases.len(),
            report.total_non_finite,
            report.cases.iter().filter(|c| !c.ok).count()
        );
        return Ok(());
    }
    if args.skips {
        let cfg = skips::SkipsConfig {
            scene: args.scenes.first().cloned(),
            width: args.width.unwrap_or(perf::protocol::FULL.width),
            height: args.height.unwrap_or(perf::protocol::FULL.height),
            out: args.out.clone(),
            warmup: args.warmup.unwrap_or(perf::protocol::FULL.warmup),
            frames: args.frames.unwrap_or(perf::protocol::FULL.frames),
            progress: true,
        };
        let report = skips::run(res, &cfg)?;
        for c in &report.cases {
            crate::outln!(
                "{:<36} saves {:7.1} ms of {:7.1} (ratio {:.2}, CPU {:.2}); draw calls {} → {}",
                c.name,
                c.saved_ms,
                c.needed.frame_ms,
                c.ratio,
                c.ratio_cpu,
                c.needed.draw_calls,
                c.skipped.draw_calls
            );
        }
        crate::outln!("wrote {}", args.out.join("skips.md").display());
        return Ok(());
    }
    if args.camera_path {
        return run_camera_path(res, args);
    }
    let cfg = args.perf_config()?;
    let files = args
        .method_files
        .iter()
        .map(|f| crate::scene::method_file::MethodFile::read(f))
        .collect::<Result<Vec<_>>>()?;
    let report = perf::run_with_method_files(res, &cfg, &files)?;
    crate::outln!(
        "wrote {} ({} rows, {}x{}, {} s)",
        cfg.out.join("report.md").display(),
        report.rows.len(),
        report.width,
        report.height,
        report.run_s.round()
    );
    Ok(())
}

/// `bench --camera-path`: 960×540, truths at 1/6 with 256 rays and 24 frames per segment unless
/// the flags say otherwise.
fn run_camera_path(res: &ResDirs, args: &BenchArgs) -> Result<()> {
    let cfg = camera_path::CameraPathConfig {
        scenes: args.scenes.clone(),
        models: args.models.clone(),
        width: args.width.unwrap_or(960).max(16),
        height: args.height.unwrap_or(540).max(16),
        ref_scale: args.ref_scale.unwrap_or(6),
        ref_rays: args.ref_rays.unwrap_or(256),
        cache: crate::tools::reference::reference_cache_dir(args.cache.as_deref())?,
        frames: args.frames.unwrap_or(24).max(2),
        accumulate: args.accumulate.unwrap_or(16),
        out: args.out.clone(),
        progress: true,
        rows: if args.path_rows.is_empty() {
            camera_path_rows::DEFAULT_ROWS.to_vec()
        } else {
            args.path_rows.iter().map(String::as_str).collect()
        }
        .into_iter()
        .map(camera_path_rows::PathRows::parse)
        .collect::<Result<_>>()?,
        train: args.path_train,
    };
    let report = camera_path::run(res, &cfg)?;
    crate::outln!(
        "wrote {} ({} runs, {} s)",
        cfg.out.join("camera-path.md").display(),
        report.runs.len(),
        report.run_s.round()
    );
    Ok(())
}
