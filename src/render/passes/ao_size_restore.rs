//! The step the back-face and surface-normal passes share: a full-screen program that brings a
//! main-size input to the AO buffers' size, keeping for each AO texel the value behind the texel of its
//! block whose front depth is nearest (the texel the depth restore keeps).

use crate::gl::{FramebufferObject, ProgramObject, Texture};
use crate::render::frame::Frame;
use crate::shader_interface::{binding, loc};
use anyhow::{anyhow, Result};
use std::rc::Rc;

/// Runs `program` (`ao/restore_back_depth.frag` or `ao/restore_normal.frag`) from `input` and the
/// main depth `front_depth` into `target`, and returns the target's texture.
pub fn restore_at_ao_size(
    f: &Frame,
    program: &ProgramObject,
    target: &FramebufferObject,
    input: &Texture,
    front_depth: &Texture,
) -> Result<Rc<Texture>> {
    program.use_program();
    let reversed = if f.depth_mode.reversed() { 1.0 } else { 0.0 };
    let c = f.camera;
    program.set_vec3(loc::UPSAMPLE_DEPTH_PLANES, [c.near, c.far, reversed]);
    let block = if (target.width(), target.height()) == f.size {
        1
    } else {
        2
    };
    program.set_i32(loc::BACK_DEPTH_BLOCK, block);
    target.bind();
    input.bind(binding::INPUT);
    front_depth.bind(binding::SECOND_INPUT);
    f.meshes.draw_plane_xy();
    target
        .color_texture()
        .cloned()
        .ok_or_else(|| anyhow!("the AO-size target has no colour texture"))
}
