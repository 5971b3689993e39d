//! `FramebufferObject`: colour and/or depth texture attachments at a chosen mip level.

use super::{Gl, Texture};
use anyhow::{bail, Result};
use glow::HasContext;
use std::rc::Rc;

pub struct FramebufferObject {
    gl: Gl,
    id: glow::Framebuffer,
    color: Option<Rc<Texture>>,
    depth: Option<Rc<Texture>>,
    color_level: u32,
    width: u32,
    height: u32,
}

impl FramebufferObject {
    /// Attaches `color` at `color_level` and `depth` at `depth_level`; the FBO's size is the size of the
    /// attached level (the course reported level 0's size for every level, which hid missing viewports).
    pub fn new(
        gl: &Gl,
        color: Option<Rc<Texture>>,
        depth: Option<Rc<Texture>>,
        color_level: u32,
        depth_level: u32,
    ) -> Result<FramebufferObject> {
        let (width, height) = match (&color, &depth) {
            (Some(c), _) => c.size_at(color_level),
            (None, Some(d)) => d.size_at(depth_level),
            (None, None) => bail!("framebuffer needs at least one attachment"),
        };
        unsafe {
            let id = gl
                .create_named_framebuffer()
                .map_err(|e| anyhow::anyhow!("glCreateFramebuffers: {e}"))?;
            if let Some(c) = &color {
                if color_level >= c.levels() {
                    bail!(
                        "framebuffer: '{}' has no level {color_level}",
                        c.desc().name
                    );
                }
                gl.named_framebuffer_texture(
                    Some(id),
                    glow::COLOR_ATTACHMENT0,
                    Some(c.id()),
                    color_level as i32,
                );
                gl.named_framebuffer_draw_buffer(Some(id), glow::COLOR_ATTACHMENT0);
            } else {
                gl.named_framebuffer_draw_buffer(Some(id), glow::NONE);
            }
            if let Some(d) = &depth {
                gl.named_framebuffer_texture(
                    Some(id),
                    glow::DEPTH_ATTACHMENT,
                    Some(d.id()),
                    depth_level as i32,
                );
            }
            let fbo = FramebufferObject {
                gl: gl.clone(),
                id,
                color,
                depth,
                color_level,
                width,
                height,
            };
            let status = gl.check_named_framebuffer_status(Some(id), glow::FRAMEBUFFER);
            if status != glow::FRAMEBUFFER_COMPLETE {
                bail!("framebuffer is incomplete (status 0x{status:x})");
            }
            Ok(fbo)
        }
    }

    /// Binds for drawing and sets the viewport to the attachment's size at its level.
    pub fn bind(&self) {
        unsafe {
            self.gl.bind_framebuffer(glow::FRAMEBUFFER, Some(self.id));
            self.gl
                .viewport(0, 0, self.width as i32, self.height as i32);
        }
    }
    pub fn id(&self) -> glow::Framebuffer {
        self.id
    }
    pub fn width(&self) -> u32 {
        self.width
    }
    pub fn height(&self) -> u32 {
        self.height
    }
    pub fn color_texture(&self) -> Option<&Rc<Texture>> {
        self.color.as_ref()
    }
    pub fn depth_texture(&self) -> Option<&Rc<Texture>> {
        self.depth.as_ref()
    }
    pub fn color_level(&self) -> u32 {
        self.color_level
    }
}

impl Drop for FramebufferObject {
    fn drop(&mut self) {
        unsafe { self.gl.delete_framebuffer(self.id) }
    }
}
