//! `opengl3d bench`: run time against error of each AO method and quality setting.
//!
//! Timing: the full frame (composite view, every pass) is rendered with `Engine::collect_stats`, which
//! brackets each pass with glFinish and times it by a GL timer query on a hardware driver, by the
//! wall clock on llvmpipe (whose timer queries measure nothing useful; `crate::gl::PassClock`). After
//! `warmup` frames, `frames` frames are timed at the scene's own camera; each pass
//! reports its median, and the AO chain (every pass of the "ao" group: restore, down-sampling, the
//! method, blur, composite) the median of its per-frame sum.
//!
//! Error: the blurred AO view (`render_values(View::Ao)`, visibility, output size) of every bench
//! camera against the CPU ray-traced reference (binary visibility, cosine-weighted rays of length =
//! the setting's radius) on the reference's non-sky pixels, raw and after fitting `min(1, a·v^b)` on
//! the training cameras; rows report the mean over the test cameras.
//!
//! Error split: a screen-space reference (`reference::render_screen_space`, the exact visibility of
//! the engine's depth buffer rendered at the reference's size, seen as a heightfield) separates what
//! the depth buffer cannot know (screen-space reference against ray-traced) from what the method's
//! sampling loses (method against screen-space reference).
//!
//! Files: `config.rs` (inputs), `protocol.rs` (the quick and full protocols, the estimate),
//! `references.rs` (ground truth), `setting.rs` (one row), `run.rs` (the loop), `report.rs` (the
//! figures), `markdown.rs` and `chart.rs` (their presentation),
//! `pictures.rs` and `html.rs` (`report.html`: truth, AO view and signed error map per setting).

pub(crate) mod chart;
mod config;
mod html;
mod markdown;
mod pictures;
pub mod protocol;
pub(crate) mod references;
mod report;
mod run;
pub(crate) mod setting;

pub use config::PerfConfig;
pub use protocol::Grid;
pub use report::{CameraError, ReferenceInfo, Report, Row};
pub use run::{run, run_with_method_files};
