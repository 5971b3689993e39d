//! What the challenge measures and how: the protocol every entry gets (also handed to the child
//! process as JSON) and the run's settings.

use crate::tools::bench::perf;
use serde::{Deserialize, Serialize};
use std::path::PathBuf;
use std::time::Duration;

/// The measurement every entry gets: small enough that a class of 100 finishes in a lesson's time
/// on a laptop (a 640×360 frame box-averaged onto a 320×180 truth of 256 rays per pixel), with the
/// bench's timing (medians of 5 frames after a warm-up).
#[derive(Clone, Debug, Serialize, Deserialize)]
pub struct ChallengeProtocol {
    pub scenes: Vec<PathBuf>,
    pub width: u32,
    pub height: u32,
    pub ref_scale: u32,
    pub ref_rays: u32,
    pub frames: u32,
    pub warmup: u32,
    pub cache: PathBuf,
}

impl ChallengeProtocol {
    pub fn new(scenes: Vec<PathBuf>, cache: PathBuf) -> ChallengeProtocol {
        ChallengeProtocol {
            scenes,
            width: 640,
            height: 360,
            ref_scale: 2,
            ref_rays: 256,
            frames: 5,
            warmup: 1,
            cache,
        }
    }

    pub(crate) fn perf_config(&self) -> perf::PerfConfig {
        perf::PerfConfig {
            scenes: self.scenes.clone(),
            models: Vec::new(),
            width: self.width,
            height: self.height,
            out: PathBuf::new(),
            methods: Vec::new(),
            samples: Vec::new(),
            radii: Vec::new(),
            qualities: Vec::new(),
            ref_rays: self.ref_rays,
            screen_rays: 1,
            ref_scale: self.ref_scale,
            cache: self.cache.clone(),
            warmup: self.warmup,
            frames: self.frames,
            flip: false,
            charts: false,
            progress: false,
            ceilings: false,
            grid: perf::Grid::Quick,
            scaled: Vec::new(),
        }
    }
}

/// What a challenge run is asked to do.
pub struct ChallengeConfig {
    pub dir: PathBuf,
    pub protocol: ChallengeProtocol,
    /// The most an entry's AO chain may cost, as a multiple of the lesson chain's.
    pub budget: f64,
    pub out: PathBuf,
    /// Per entry, for all its scenes.
    pub timeout: Duration,
    pub progress: bool,
}
