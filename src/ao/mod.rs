//! Ambient occlusion: settings, the shared AO-size targets and depth chain, the blurs and the
//! composite (with the bilateral up-sampling of the AO to the main size), and one module per method
//! under `method/` (its shader beside it in `Res/ao/`; its row in `method/mod.rs`).

pub mod blur;
pub mod composite;
pub mod depth_chain;
pub mod guard_band;
pub mod lesson;
pub mod method;
pub mod method_pass;
pub mod method_row;
pub mod packed;
pub mod pipeline;
pub use crate::scene::ao_resolution as resolution;
/// The settings live with the scene that carries them (its `[ao]` table), below this layer.
pub use crate::scene::ao_settings as settings;
pub mod sky_skip;
pub mod slab_hierarchy;
pub mod targets;
pub mod temporal;
pub mod upsample;
pub mod user_method;

pub use lesson::SaoLesson;
pub use pipeline::AoPipeline;
pub use settings::{
    AoMethod, AoResolution, AoSettings, CompositeMode, GuardBand, NormalSource, SlabHierarchy,
    SlicePreset, Thickness, LAYER2_MIN_THICKNESS_OF_SET,
};
pub use targets::AoTargets;
