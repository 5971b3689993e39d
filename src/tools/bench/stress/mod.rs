//! `opengl3d bench --stress`: numerical stability of the AO pipeline at the extremes, and linear-depth
//! reconstruction error against distance.
//!
//! Every case builds a small scene from procedural meshes, renders the composite frame and the three
//! value views with every AO method, and counts NaN/Inf values in every output: the main colour
//! buffer, each level of the linear-depth mip chain, the raw and blurred AO buffers, and the
//! `render_values` of the linear-depth, raw-AO and AO views. Visibility must lie in [0, 1] and linear
//! depth must be positive; sky-only frames must be fully visible.
//!
//! Files: `cases.rs` (the scenes), `checks.rs` (one case), `depth.rs` (the depth table), `run.rs`
//! (the loop), `report.rs` and `markdown.rs` (the results).

mod cases;
mod checks;
mod depth;
mod markdown;
mod report;
mod run;

pub use report::{CaseResult, DepthConfigResult, DepthSample, OutputCheck, StressReport};
pub use run::{run, StressConfig};
