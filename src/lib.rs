//! opengl3d: a Rust port of an OpenGL 4.5 course engine and its screen-space ambient occlusion
//! lessons (McGuire's Scalable Ambient Obscurance), running in a window or headless on Mesa.
//!
//! Layout: `gl` (GL object owners) · `engine` (Engine, camera, game objects) · `ao` (AO methods and
//! their passes) · `scene` (scene files, demo meshes) · `context` (window, headless) · `io` (images)
//! · `reference` (ray-traced ground truth) · `cli` (the command line).

pub mod ao;
pub mod bench;
pub mod cli;
pub mod config;
pub mod context;
pub mod engine;
pub mod gl;
pub mod grade;
pub mod io;
pub mod lesson;
pub mod reference;
pub mod res;
pub mod scene;
