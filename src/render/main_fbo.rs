//! The main framebuffer the passes draw into: RGBA16F colour and the depth convention's format
//! (compare mode off: the AO passes read raw depth).

use crate::gl::{FramebufferObject, Gl, Texture, TextureDesc};
use crate::math::DepthMode;
use anyhow::Result;
use std::rc::Rc;

/// The main FBO (colour + depth).
pub fn create_main_fbo(
    gl: &Gl,
    width: u32,
    height: u32,
    mode: DepthMode,
) -> Result<FramebufferObject> {
    let color = Rc::new(Texture::new(
        gl,
        TextureDesc::target("FBO(main color)", width, height, glow::RGBA16F)
            .filter(glow::LINEAR, glow::LINEAR),
    )?);
    let depth = Rc::new(Texture::new(
        gl,
        TextureDesc::target("FBO(main depth)", width, height, mode.internal_format())
            .compare(false),
    )?);
    FramebufferObject::new(gl, Some(color), Some(depth), 0, 0)
}
