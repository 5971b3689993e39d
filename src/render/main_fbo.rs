//! The main framebuffer the passes draw into: RGBA16F colour and the depth convention's format
//! (compare mode off: the AO passes read raw depth), and a second framebuffer over the same colour
//! alone, for passes that read the main depth while they draw (a texture attached to the
//! framebuffer being drawn must not be sampled).

use crate::gl::{FramebufferObject, Gl, Texture, TextureDesc};
use crate::math::DepthMode;
use anyhow::Result;
use std::rc::Rc;

/// The main FBO (colour + depth) and the same colour alone.
pub fn create_main_fbos(
    gl: &Gl,
    width: u32,
    height: u32,
    mode: DepthMode,
) -> Result<(FramebufferObject, FramebufferObject)> {
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
    let color_only = FramebufferObject::new(gl, Some(color.clone()), None, 0, 0)?;
    Ok((
        FramebufferObject::new(gl, Some(color), Some(depth), 0, 0)?,
        color_only,
    ))
}
