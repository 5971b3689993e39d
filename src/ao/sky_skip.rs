//! Passes at the AO size that skip the sky's texels before their shader runs.
//!
//! Every engine method writes the same constant for a sky texel (occlusion 0 and the sky's linear
//! depth, exactly `far`), and so does the packed blur. Where the chain drew its own window depth at
//! the AO size (the surface-normal pass, with a guard band or a quarter-size AO), a pass attaches it,
//! clears its targets to those constants and draws its quad at the sky's depth with the depth test
//! passing only where a surface is nearer, so the sky texels are dropped before shading. A software
//! rasteriser runs a shader's whole body for every block with one live pixel (an early `return` or a
//! `discard` in the shader saves nothing there), so on a lone model under open sky this is most of
//! the method's pass. The results are the same texel for texel.

use super::composite::{sky_farther, surface_pixels_test};
use crate::gl::{FramebufferObject, Gl, PassState, Texture};
use crate::math::DepthMode;
use glow::HasContext;
use std::rc::Rc;

/// The window depth the chain drew at the AO size (the size of the targets it is handed with), in
/// its convention: the sky's texels hold the cleared value.
#[derive(Clone, Copy)]
pub struct AoSizeDepth<'a> {
    pub texture: &'a Rc<Texture>,
    pub mode: DepthMode,
    /// The sky's linear depth, the camera's far plane (what the restores write for it).
    pub far: f32,
}

/// Which texels of an AO-size target a pass shades: those within `region` (all when `None`) and,
/// with `depth`, only where it holds a surface.
#[derive(Clone, Copy, Default)]
pub struct Texels<'a> {
    pub region: Option<[i32; 4]>,
    pub depth: Option<AoSizeDepth<'a>>,
}

impl Texels<'_> {
    /// The sky's linear depth where the sky is skipped, else 0 (nothing reads it then).
    pub fn sky_far(&self) -> f32 {
        self.depth.map_or(0.0, |d| d.far)
    }
}

/// What a pass writes where it skips the sky: per draw buffer of `fbo`, the value its shader writes
/// for a sky texel.
pub struct SkyValues<'a> {
    pub fbo: &'a FramebufferObject,
    pub per_draw_buffer: &'a [[f32; 4]],
}

/// Draws a full-screen pass with `draw` into `target.fbo`, shading `texels`; where it skips the sky,
/// the sky's texels receive `target.per_draw_buffer`.
pub fn draw_texels(gl: &Gl, texels: Texels, target: SkyValues, draw: impl FnOnce()) {
    let state = PassState::FULLSCREEN.with_scissor(texels.region);
    let id = Some(target.fbo.id());
    let depth = texels.depth.filter(|d| {
        let fits = d.texture.size_at(0) == (target.fbo.width(), target.fbo.height());
        // SAFETY: attaching a live depth texture to a framebuffer the caller owns; detached again
        // below (or at once when the framebuffer will not take it), so the framebuffer never holds
        // a texture it does not own.
        fits && unsafe {
            gl.named_framebuffer_texture(id, glow::DEPTH_ATTACHMENT, Some(d.texture.id()), 0);
            let complete = gl.check_named_framebuffer_status(id, glow::FRAMEBUFFER)
                == glow::FRAMEBUFFER_COMPLETE;
            if !complete {
                gl.named_framebuffer_texture(id, glow::DEPTH_ATTACHMENT, None, 0);
            }
            complete
        }
    });
    let Some(depth) = depth else {
        // Every texel shaded: the same result, only slower.
        state.apply(gl, None);
        target.fbo.bind();
        draw();
        return;
    };
    // The clear honours the scissor, so it reaches exactly the texels the draw may reach.
    state.apply(gl, None);
    for (i, value) in target.per_draw_buffer.iter().enumerate() {
        // SAFETY: draw buffer `i` of a complete framebuffer; four floats as the call reads.
        unsafe { gl.clear_named_framebuffer_f32_slice(id, glow::COLOR, i as u32, value) };
    }
    let test = surface_pixels_test(depth.mode.clear_value(), sky_farther(depth.mode));
    test.with_scissor(state.scissor).apply(gl, None);
    target.fbo.bind();
    draw();
    state.apply(gl, None);
    // SAFETY: as above.
    unsafe { gl.named_framebuffer_texture(id, glow::DEPTH_ATTACHMENT, None, 0) };
}
