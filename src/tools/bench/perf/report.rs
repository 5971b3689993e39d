//! The bench's report: one row per method and setting, with its timings and errors, and what
//! the run measured against. Serialised as `report.json`; `markdown.rs` and `chart.rs` render it.

use crate::tools::bench::catalog::BenchCamera;
use crate::tools::metrics::{Fit, Metrics};
use serde::Serialize;
use std::collections::BTreeMap;

/// Error of one camera.
#[derive(Clone, Debug, Serialize)]
pub struct CameraError {
    pub scene: String,
    pub camera: String,
    pub train: bool,
    pub raw: Metrics,
    /// After the fit (test cameras only; the training cameras repeat the raw figures' pixels).
    pub fitted: Metrics,
    /// The screen-space reference (exact AO of the depth buffer) against the ray-traced one: what
    /// the depth buffer cannot know at this camera and radius, whatever the method (no FLIP).
    pub depth_buffer_error: Metrics,
    /// The method (raw) against the screen-space reference: what its sampling loses (no FLIP).
    pub sampling_error: Metrics,
    /// RMS over the pixels of the screen-space reference's standard error: its Monte Carlo noise,
    /// which both parts contain and the total does not (test cameras; 0 on training cameras).
    pub ceiling_noise_rms: f64,
    /// The part of that noise the ray-traced reference does not share: `ceiling_noise_rms`, or 0 when
    /// the screen-space reference traced the ray-traced one's own rays (`--screen-rays` equal to
    /// `--ref-rays`), where its noise is the truth's: in the sampling part and the total alike, and
    /// not in the depth-buffer part.
    pub ceiling_own_noise_rms: f64,
    /// 10·log10(1 / (RMSE_depth_buffer² + RMSE_sampling² − 2·ceiling_own_noise_rms²)): the raw PSNR the
    /// method would have if the two parts' errors added up in squares (test cameras; 0 errors give
    /// the cap).
    pub parts_psnr: f64,
}

/// One row: a method at one setting.
#[derive(Clone, Debug, Serialize)]
pub struct Row {
    pub method: String,
    pub setting: String,
    pub samples: u32,
    pub radius: f32,
    pub width: u32,
    pub height: u32,
    /// Median wall-clock ms of each pass of the frame (AO passes and the others), by pass name.
    pub passes: BTreeMap<String, f64>,
    /// Median of the per-frame sum of the AO passes (group "ao").
    pub total_ms: f64,
    pub total_ms_min: f64,
    pub total_ms_max: f64,
    /// Median of the whole frame (every pass).
    pub frame_ms: f64,
    /// Median CPU ms of each pass (the process's CPU time, all threads): robust to other load.
    pub passes_cpu: BTreeMap<String, f64>,
    /// Median of the per-frame CPU ms of the AO passes.
    pub total_cpu_ms: f64,
    /// Raw error, mean over the test cameras.
    pub rmse: f64,
    pub mae: f64,
    pub psnr: f64,
    pub ssim: f64,
    pub flip: f64,
    /// The fitted map min(1, a·v^b) (from the training cameras) and the error after it (test cameras).
    pub fit: Fit,
    pub fitted: Metrics,
    /// Error split, means over the test cameras: the screen-space reference against the
    /// ray-traced one (the depth buffer's limit), and the method against the screen-space
    /// reference (its sampling).
    pub depth_buffer_error: Metrics,
    pub sampling_error: Metrics,
    /// Which screen-space reference this row is split against, the method's own model of what
    /// lies behind a depth sample: "heightfield" (infinitely thick), "slabs" (`vbao` with a
    /// thickness in metres) or "back faces" (`vbao` with `thickness = "backface"`).
    pub ceiling: &'static str,
    /// The same as the report's tables print it ("∞", "0.25 m", "back faces (0.25 m where none)").
    pub ceiling_label: String,
    /// Thickness (m) of the depth buffer's surfaces in that reference: the slabs', or for back
    /// faces that of the pixels without one; `None` (left out of the JSON) for the heightfield.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub ceiling_thickness: Option<f32>,
    /// Means over the test cameras of `CameraError::parts_psnr` and of (raw PSNR − parts PSNR);
    /// the largest |raw PSNR − parts PSNR| of a test camera. The split adds up when the gap is small.
    pub parts_psnr: f64,
    pub split_gap_db: f64,
    pub split_gap_max_db: f64,
    pub cameras: Vec<CameraError>,
    /// Each test camera's truth, AO view and error map (`report.html`'s pictures).
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub pictures: Vec<super::pictures::SettingPictures>,
}

#[derive(Clone, Debug, Serialize)]
pub struct Report {
    pub renderer: String,
    pub software: bool,
    /// The clock of every time in the report (`crate::gl::GpuClock::description`).
    pub timing: String,
    /// That clock: "gpu timer" (hardware GL) or "wall clock" (software GL).
    pub clock: crate::gl::PassClock,
    /// Whether the run followed the full protocol; else `scaled` lists what it scaled down or
    /// skipped (`perf::protocol`).
    pub full_protocol: bool,
    pub scaled: Vec<String>,
    /// Whether the screen-space references (the error split) were computed.
    pub ceilings: bool,
    pub cpus: usize,
    pub width: u32,
    pub height: u32,
    pub reference: ReferenceInfo,
    pub warmup_frames: u32,
    pub timed_frames: u32,
    pub scenes: Vec<String>,
    pub cameras: Vec<(String, BenchCamera)>,
    pub rows: Vec<Row>,
    /// Wall-clock seconds of the whole run (reference renders included when not cached).
    pub run_s: f64,
    /// /proc/loadavg (1, 5, 15 min) when the timing started and when it ended: other processes
    /// on the machine slow the frames down.
    pub load_before: Option<[f64; 3]>,
    pub load_after: Option<[f64; 3]>,
}

#[derive(Clone, Debug, Serialize)]
pub struct ReferenceInfo {
    pub rays: u32,
    pub width: u32,
    pub height: u32,
    pub variant: &'static str,
    pub rendered: usize,
    pub cached: usize,
    pub render_s: f64,
    /// Screen-space references (same size, rays and radii, from the engine's depth buffer
    /// rendered at that size): rendered this run, read from the cache, seconds spent.
    pub screen_rays: u32,
    pub screen_rendered: usize,
    pub screen_cached: usize,
    pub screen_render_s: f64,
}
