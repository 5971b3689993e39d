//! The Engine (pass order only), its passes, the frame they share, views and statistics.

pub mod engine;
pub mod frame;
mod main_fbo;
pub mod passes;
pub mod stats;
pub mod view;

pub use engine::Engine;
pub use stats::PassStat;
pub use view::View;
