//! opengl3d: a Rust port of an OpenGL 4.5 course engine and its screen-space ambient occlusion
//! lessons (McGuire's Scalable Ambient Obscurance), running in a window or headless on Mesa.
//!
//! Layers, each using only those before it: `res`, `io` (files) → `gl` (GL object owners, shader
//! preprocessor, pass state) → `math` (camera, depth conventions, frusta) → `shader_interface`
//! (uniform locations and bindings) → `scene` (scene files with the AO settings they carry, demo
//! shapes, game objects) → `ao` (targets, depth chain, blurs, composite, one module per method) →
//! `render` (the Engine and its passes) → `platform` (headless EGL, the window) → `tools`
//! (reference, bench, grader, lessons) → `cli`. `tests/layers.rs` holds the crate to this order.

pub mod ao;
pub mod cli;
pub mod gl;
pub mod i18n;
pub mod io;
pub mod math;
pub mod platform;
pub mod render;
pub mod res;
pub mod res_embedded;
pub mod scene;
pub mod shader_interface;
pub mod tools;

// The messages' texts (locales/*.yml), compiled in; `rust_i18n::t!` looks them up from any module.
rust_i18n::i18n!("locales", fallback = "en");
