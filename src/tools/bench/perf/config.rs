//! What a bench run measures (the CLI fills it from `BenchArgs`; tests build it directly).

use super::protocol::Grid;
use crate::ao::AoMethod;
use crate::tools::bench::limits::{self, MAX_REF_RAYS, MAX_REF_SCALE};
use anyhow::{bail, Result};
use std::path::PathBuf;

/// Everything a bench run needs.
#[derive(Clone, Debug)]
pub struct PerfConfig {
    pub scenes: Vec<PathBuf>,
    /// Models (`--obj`), each run as a scene of its own framed from its bounds.
    pub models: Vec<PathBuf>,
    pub width: u32,
    pub height: u32,
    pub out: PathBuf,
    pub methods: Vec<AoMethod>,
    /// Overrides of the settings grid (empty = each method's defaults).
    pub samples: Vec<u32>,
    pub radii: Vec<f32>,
    /// Presets of the methods that have them (gtao, vbao), replacing their defaults.
    pub qualities: Vec<crate::ao::SlicePreset>,
    pub ref_rays: u32,
    /// Rays per pixel of the screen-space references (a dense march per ray is far slower than a
    /// BVH ray; they are rendered for the test cameras only, where the split is reported).
    pub screen_rays: u32,
    /// The reference is rendered at width/ref_scale × height/ref_scale and the engine's output is
    /// box-averaged by the same factor before comparing.
    pub ref_scale: u32,
    pub cache: PathBuf,
    pub warmup: u32,
    pub frames: u32,
    pub flip: bool,
    pub charts: bool,
    pub progress: bool,
    /// Screen-space references for the error split against each method's ceiling (slow: only
    /// when asked, `--ceilings` or `--full`).
    pub ceilings: bool,
    /// Each method's full settings grid or the quick one (when no settings are given).
    pub grid: Grid,
    /// What the run scaled down or skipped against the full protocol, one line each (the
    /// reports list them; empty for the full protocol).
    pub scaled: Vec<String>,
}

impl PerfConfig {
    /// `Err` naming the first input out of its range (see `bench::limits` for the bounds).
    pub fn check(&self) -> Result<()> {
        limits::check_size(self.width, self.height)?;
        if self.methods.is_empty() {
            bail!("no AO method to run");
        }
        limits::check_frames(self.frames)?;
        limits::check_range("--ref-rays", self.ref_rays, MAX_REF_RAYS)?;
        limits::check_range("--screen-rays", self.screen_rays, MAX_REF_RAYS)?;
        limits::check_range("--ref-scale", self.ref_scale, MAX_REF_SCALE)
    }

    /// Size of the references: the output size divided by `ref_scale`, rounded up.
    pub fn reference_size(&self) -> (u32, u32) {
        (
            self.width.div_ceil(self.ref_scale),
            self.height.div_ceil(self.ref_scale),
        )
    }
}
