//! What a `tune` run measures: the two protocols and the run's inputs.

use crate::ao::AoMethod;
use crate::scene::method_file::MethodFile;
use crate::tools::bench::perf;
use anyhow::{bail, Result};
use std::path::PathBuf;

/// Output size and reference of the quick protocol: truths at the output's size, so the search's
/// hundreds of frames stay small.
pub const QUICK: Protocol = Protocol {
    width: 320,
    height: 180,
    ref_scale: 1,
    ref_rays: 256,
    warmup: 1,
    frames: 5,
};

/// The bench's full protocol: 1920×1080 box-averaged by 6 onto the truth.
pub const FULL: Protocol = Protocol {
    width: perf::protocol::FULL.width,
    height: perf::protocol::FULL.height,
    ref_scale: perf::protocol::FULL.ref_scale,
    ref_rays: perf::protocol::FULL.ref_rays,
    warmup: perf::protocol::FULL.warmup,
    frames: perf::protocol::FULL.frames,
};

/// Sizes, truth and timing of a run.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Protocol {
    pub width: u32,
    pub height: u32,
    pub ref_scale: u32,
    pub ref_rays: u32,
    /// Frames before timing, and timed (the median counts), for `--budget`.
    pub warmup: u32,
    pub frames: u32,
}

/// What a run tunes (the CLI fills it from `TuneArgs`; tests build it directly).
#[derive(Clone, Debug)]
pub struct TuneConfig {
    pub scenes: Vec<PathBuf>,
    pub methods: Vec<AoMethod>,
    /// Methods of the user's own (`--method-file`), tuned after the engine's.
    pub method_files: Vec<PathBuf>,
    pub protocol: Protocol,
    pub budget: Option<f64>,
    pub passes: u32,
    pub cache: PathBuf,
    pub out: PathBuf,
    pub progress: bool,
}

impl TuneConfig {
    /// `Err` naming the first input out of range.
    pub fn check(&self) -> Result<()> {
        if self.methods.is_empty() && self.method_files.is_empty() {
            bail!("{}", rust_i18n::t!("tune.no_method"));
        }
        if self.methods.iter().any(|m| !m.info().reads_depth_occluders) {
            bail!("{}", rust_i18n::t!("tune.rtao"));
        }
        if let Some(b) = self.budget {
            if !(b.is_finite() && b > 0.0) {
                bail!("{}", rust_i18n::t!("tune.bad_budget", budget = b));
            }
        }
        if !(1..=10).contains(&self.passes) {
            bail!("{}", rust_i18n::t!("tune.bad_passes", passes = self.passes));
        }
        self.perf_config(Vec::new()).check()
    }

    /// The method files, read and checked (errors name the file, line and column); one with
    /// nothing to search is refused: no parameter, and no budget to open the engine keys it reads.
    pub fn read_method_files(&self) -> Result<Vec<MethodFile>> {
        let mut files = Vec::new();
        for path in &self.method_files {
            let file = MethodFile::read(path)?;
            if file.parameters.is_empty() && self.budget.is_none() {
                bail!(
                    "{}",
                    rust_i18n::t!("tune.no_parameters", path = path.display())
                );
            }
            files.push(file);
        }
        Ok(files)
    }

    /// The bench's configuration for the same sizes, truth and timing (its references, views and
    /// timing take one).
    pub(crate) fn perf_config(&self, scaled: Vec<String>) -> perf::PerfConfig {
        let p = &self.protocol;
        perf::PerfConfig {
            scenes: self.scenes.clone(),
            models: Vec::new(),
            width: p.width,
            height: p.height,
            out: self.out.clone(),
            // Method files alone: the bench's checks want a method, and the lesson chain is the
            // one every run may time.
            methods: if self.methods.is_empty() {
                vec![AoMethod::SaoLesson]
            } else {
                self.methods.clone()
            },
            samples: Vec::new(),
            radii: Vec::new(),
            qualities: Vec::new(),
            ref_rays: p.ref_rays,
            screen_rays: 1,
            ref_scale: p.ref_scale,
            cache: self.cache.clone(),
            warmup: p.warmup,
            frames: p.frames,
            flip: false,
            charts: false,
            progress: self.progress,
            ceilings: false,
            grid: perf::Grid::Quick,
            scaled,
        }
    }
}
