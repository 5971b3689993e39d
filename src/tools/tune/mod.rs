//! `opengl3d tune`: each AO method's free `[ao]` parameters searched on a scene's training cameras
//! against the ray-traced truth, the best table written as TOML to paste into the scene file, and
//! the held-out test cameras' PSNR of the chosen table next to the scene's own.
//!
//! Everything is measured with the bench's machinery (`bench::perf`): its cameras (two train, two
//! test), its cached references, its AO view box-averaged to the reference's size, its PSNR on
//! the reference's surface pixels, and its frame timing for `--budget`.
//!
//! Files: `space.rs` (which keys each method reads, and their values), `file_space.rs` (the same
//! for a method file: its parameters, the engine keys it reads), `search.rs` (coordinate descent,
//! generic over both), `config.rs` (the protocols and a run's inputs), `evaluate.rs` (one scene and
//! method on the engine), `output.rs` and `method_text.rs` (TOML, markdown, the tuned method file).

mod config;
mod evaluate;
pub mod file_space;
pub mod method_text;
mod output;
pub mod search;
pub mod space;

pub use config::{Protocol, TuneConfig, FULL, QUICK};
pub use evaluate::{FileResult, MethodResult, ParameterResult};

use crate::ao::AoMethod;
use crate::res::ResDirs;
use crate::tools::bench::catalog;
use anyhow::Result;
use clap::Args;
use std::path::PathBuf;

#[derive(Args, Debug, Clone)]
pub struct TuneArgs {
    /// Scene files (default: the demo scene); each is tuned on its own training cameras.
    #[arg(long = "scene")]
    pub scenes: Vec<PathBuf>,
    /// AO methods by name, comma-separated (default: every method but rtao, or none with
    /// --method-file).
    #[arg(long, value_delimiter = ',')]
    pub methods: Vec<String>,
    /// A method of your own (see docs/method-file.md), repeatable: searches its [[parameter]]s
    /// over their ranges (and with --budget the engine keys it reads); writes the method file with
    /// the chosen defaults into --out.
    #[arg(long = "method-file", value_name = "FILE.toml")]
    pub method_files: Vec<PathBuf>,
    /// Only configurations whose AO chain costs at most RATIO times the lesson chain's
    /// (sao-lesson with the scene's [ao]), both timed in this run; opens the keys that cost
    /// (samples or preset, resolution, normals, guard band, layers, back faces).
    #[arg(long, value_name = "RATIO", allow_negative_numbers = true)]
    pub budget: Option<f64>,
    /// The full protocol: 1920×1080 against references at 1/6 (box-averaged), instead of 320×180
    /// against references at the same size.
    #[arg(long)]
    pub full: bool,
    /// Coordinate-descent passes at most (each tries every value of every key once).
    #[arg(long, default_value_t = 2, allow_negative_numbers = true)]
    pub passes: u32,
    /// Rays per pixel of the references (default 256).
    #[arg(long, allow_negative_numbers = true)]
    pub ref_rays: Option<u32>,
    /// Folder of cached references (as `bench --cache`).
    #[arg(long)]
    pub cache: Option<PathBuf>,
    /// Output folder for the TOML tables and tune.md.
    #[arg(long, default_value = "out/tune")]
    pub out: PathBuf,
}

impl TuneArgs {
    pub fn config(&self) -> Result<TuneConfig> {
        let methods = if self.methods.is_empty() && !self.method_files.is_empty() {
            Vec::new()
        } else if self.methods.is_empty() {
            AoMethod::ALL
                .into_iter()
                // A ray-traced method has nothing to fit to the truth (`tune.rtao`).
                .filter(|m| m.info().reads_depth_occluders)
                .collect()
        } else {
            self.methods
                .iter()
                .map(|n| catalog::method_by_name(n))
                .collect::<Result<Vec<_>>>()?
        };
        let mut protocol = if self.full { FULL } else { QUICK };
        if let Some(r) = self.ref_rays {
            protocol.ref_rays = r;
        }
        Ok(TuneConfig {
            scenes: self.scenes.clone(),
            methods,
            method_files: self.method_files.clone(),
            protocol,
            budget: self.budget,
            passes: self.passes,
            cache: crate::tools::reference::reference_cache_dir(self.cache.as_deref())?,
            out: self.out.clone(),
            progress: true,
        })
    }
}

/// Tunes every method on every scene, writes `SCENE-METHOD.toml` and `tune.md` into `cfg.out`, and
/// returns the results (scene by scene, method by method).
pub fn run(res: &ResDirs, cfg: &TuneConfig) -> Result<Vec<MethodResult>> {
    cfg.check()?;
    let results = evaluate::run(res, cfg)?;
    output::write(&results, cfg)?;
    Ok(results)
}

/// The command: runs, prints each table with its figures, says where the files are.
pub fn run_cli(res: &ResDirs, args: &TuneArgs) -> Result<()> {
    let cfg = args.config()?;
    let results = run(res, &cfg)?;
    for r in &results {
        crate::outln!("{}", output::summary(r));
        if r.file.is_some() {
            crate::outln!("{}", output::parameter_lines(r));
        }
        crate::outln!("{}", output::toml_table(r)?);
    }
    crate::outln!(
        "{}",
        rust_i18n::t!("tune.wrote", path = cfg.out.join("tune.md").display())
    );
    for r in &results {
        if let Some(f) = &r.file {
            let tuned = cfg.out.join(output::tuned_file_name(r, f));
            crate::outln!(
                "{}",
                rust_i18n::t!("tune.wrote_method_file", path = tuned.display())
            );
        }
    }
    Ok(())
}
