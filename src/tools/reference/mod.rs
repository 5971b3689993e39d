//! Ground-truth ambient occlusion on the CPU: world-space ray tracing of the scene's triangles
//! ([`render_reference`], see `trace.rs` for the method), and the exact AO of a depth buffer seen as
//! a heightfield ([`render_screen_space`]), both cached on disk.
//!
//! The screen-space AO techniques of the course are approximations; this module computes what
//! they approximate, so they can be compared per pixel. Cameras are the engine's own
//! [`crate::math::Camera`]; `camera.rs` adds the reference's robust frame and ray directions.

mod cache;
mod cache_dir;
mod camera;
mod depth_buffer;
mod gpu;
mod gpu_check;
mod hash;
mod heightfield;
mod ideal;
mod image;
mod params;
mod patches;
mod sampling;
mod scene;
mod screen;
mod screen_box;
mod trace;

pub use cache::{cache_key, cache_path, load_or_render_cached, read_cached, write_cached};
pub use cache_dir::{reference_cache_dir, CACHE_ENV};
pub use camera::{pixel_dir, view_direction};
pub use depth_buffer::{Capture, DepthBuffer, Surface};
pub use gpu::{load_or_render_gpu_cached, render_reference_gpu, MAX_GPU_RAYS};
pub use gpu_check::{cross_check, CrossCheck};
pub use ideal::render_ideal_one_layer;
pub use image::RefImage;
pub use params::{AoVariant, RefParams};
pub use scene::{Hit, Scene};
pub use screen::{load_or_render_screen_cached, render_screen_space, screen_cache_key};
pub use screen_box::{
    load_or_render_screen_box_cached, render_screen_space_box, screen_box_cache_key,
};
pub use trace::{render_reference, render_reference_watched};
