//! Camera, projections and depth conventions, frusta: plain math with no GL state.

pub mod camera;
pub mod depth;
pub mod frustum;
pub mod octahedral;

pub use camera::Camera;
pub use depth::DepthMode;
