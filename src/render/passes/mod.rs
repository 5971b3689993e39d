//! The engine's passes, each owning its programs and stating its render state.

pub mod ao_size_restore;
pub mod back_faces;
pub mod bloom;
pub mod normals;
pub mod opaque;
pub mod post;
pub mod second_layer;
pub mod shadow;
pub mod sky;
pub mod surface;
pub mod transparent;
