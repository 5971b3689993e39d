//! Transparent objects, blended over the opaque image after the sky (depth tested, not written).

use super::opaque::LitPass;
use super::shadow::ShadowPass;
use crate::gl::pass_state::Blend;
use crate::gl::{FramebufferObject, PassState};
use crate::render::frame::Frame;
use glam::Mat4;

/// Whether the scene has anything for this pass (it is skipped otherwise).
pub fn needed(f: &Frame) -> bool {
    f.objects.iter().any(|o| o.is_transparent())
}

pub fn draw(
    f: &Frame,
    lit: &LitPass,
    main: &FramebufferObject,
    shadow: &ShadowPass,
    shadow_matrix: &Mat4,
) {
    main.bind();
    f.apply(f.scene_depth_state(false).with_blend(Blend::ALPHA));
    lit.setup(f, shadow, shadow_matrix);
    f.draw_objects(&lit.standard, true, &f.view_projection());
    f.apply(PassState::FULLSCREEN);
}
