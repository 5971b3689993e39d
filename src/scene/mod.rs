//! Scene descriptions: small TOML files in `Res/scenes/`, their checks, and the demo meshes' generator.

pub mod ao_defaults;
pub mod ao_method;
pub mod ao_resolution;
pub mod ao_settings;
mod ao_written;
pub mod bvh;
mod check;
mod desc;
mod file;
pub mod framing;
pub mod furniture;
pub mod game_object;
pub mod method_file;
mod method_inputs;
mod places;
mod primitives;
pub mod shapes;

pub use check::{Issue, MAX_DEPTH_RATIO};
pub use desc::{BloomDesc, CameraDesc, LightDesc, ObjectDesc, OutputDesc, SceneDesc};
pub use file::SceneFile;
pub use places::KeyPlaces;
