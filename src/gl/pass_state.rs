//! The fixed-function state a draw depends on, stated in full by every pass (three-d style): a pass
//! never inherits depth, cull, blend, mask or clip settings from the pass before it.

use super::clip_control::ClipControl;
use glow::HasContext;

/// Depth test and write.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Depth {
    /// No test, no write (full-screen passes).
    Off,
    /// Test with `func`; write when `write`.
    Test { func: u32, write: bool },
}

/// Blend equation FUNC_ADD with these factors.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Blend {
    pub src: u32,
    pub dst: u32,
}

impl Blend {
    /// Ordinary "over" blending with the source's alpha.
    pub const ALPHA: Blend = Blend {
        src: glow::SRC_ALPHA,
        dst: glow::ONE_MINUS_SRC_ALPHA,
    };
    /// Adding the source (bloom's up-sampling).
    pub const ADD: Blend = Blend {
        src: glow::ONE,
        dst: glow::ONE,
    };
}

/// Face culling (counter-clockwise faces are front faces, GL's default).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Cull {
    None,
    Back,
    /// Draws only back faces: the back-face depth pass (`vbao`'s per-pixel thickness).
    Front,
}

#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PassState {
    pub depth: Depth,
    /// Window-space depth range (`glDepthRange`); squeezed to a point to place a full-screen quad
    /// at one depth.
    pub depth_range: (f32, f32),
    /// Clip-space depth [0, 1] (reversed-Z) instead of OpenGL's [-1, 1]; applied when the engine
    /// loaded `glClipControl`.
    pub clip_zero_to_one: bool,
    /// Which faces are culled; the demo meshes include open planes, so most passes draw both.
    pub cull: Cull,
    pub blend: Option<Blend>,
    /// Colour writes (off for a depth pre-pass).
    pub color_write: bool,
    /// `glPolygonOffset(factor, units)` for filled polygons (shadow-map acne).
    pub polygon_offset: Option<(f32, f32)>,
    /// Only this rectangle of the target is drawn (`glScissor`: x, y, width, height in pixels).
    pub scissor: Option<[i32; 4]>,
}

impl PassState {
    /// A full-screen pass: no depth, no cull, no blend, colour written.
    pub const FULLSCREEN: PassState = PassState {
        depth: Depth::Off,
        depth_range: (0.0, 1.0),
        clip_zero_to_one: false,
        cull: Cull::None,
        blend: None,
        color_write: true,
        polygon_offset: None,
        scissor: None,
    };

    pub fn with_blend(self, blend: Blend) -> PassState {
        PassState {
            blend: Some(blend),
            ..self
        }
    }

    pub fn with_scissor(self, scissor: Option<[i32; 4]>) -> PassState {
        PassState { scissor, ..self }
    }

    /// Sets every piece of state this type names (and turns sRGB writes and dithering off, which no
    /// pass uses).
    pub fn apply(&self, gl: &glow::Context, clip_control: Option<&ClipControl>) {
        if let Some(cc) = clip_control {
            cc.set(self.clip_zero_to_one);
        }
        // SAFETY: plain state setters with valid enums on the current context.
        unsafe {
            match self.depth {
                Depth::Off => {
                    gl.disable(glow::DEPTH_TEST);
                    gl.depth_mask(false);
                }
                Depth::Test { func, write } => {
                    gl.enable(glow::DEPTH_TEST);
                    gl.depth_func(func);
                    gl.depth_mask(write);
                }
            }
            gl.depth_range_f32(self.depth_range.0, self.depth_range.1);
            match self.cull {
                Cull::None => gl.disable(glow::CULL_FACE),
                Cull::Back | Cull::Front => {
                    gl.enable(glow::CULL_FACE);
                    gl.cull_face(if self.cull == Cull::Back {
                        glow::BACK
                    } else {
                        glow::FRONT
                    });
                }
            }
            match self.blend {
                Some(b) => {
                    gl.enable(glow::BLEND);
                    gl.blend_equation(glow::FUNC_ADD);
                    gl.blend_func(b.src, b.dst);
                }
                None => gl.disable(glow::BLEND),
            }
            let c = self.color_write;
            gl.color_mask(c, c, c, c);
            match self.polygon_offset {
                Some((factor, units)) => {
                    gl.enable(glow::POLYGON_OFFSET_FILL);
                    gl.polygon_offset(factor, units);
                }
                None => gl.disable(glow::POLYGON_OFFSET_FILL),
            }
            match self.scissor {
                Some([x, y, w, h]) => {
                    gl.enable(glow::SCISSOR_TEST);
                    gl.scissor(x, y, w, h);
                }
                None => gl.disable(glow::SCISSOR_TEST),
            }
            gl.disable(glow::FRAMEBUFFER_SRGB);
            gl.disable(glow::DITHER);
        }
    }
}
