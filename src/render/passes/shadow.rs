//! The shadow map: depth from the light's orthographic view of every opaque object's bounds.

use crate::gl::pass_state::Depth;
use crate::gl::{FramebufferObject, Gl, PassState, ProgramObject, Texture, TextureDesc};
use crate::render::frame::Frame;
use crate::res::ResDirs;
use crate::shader_interface::loc;
use anyhow::Result;
use glam::{Mat4, Vec3};
use std::rc::Rc;

/// 2048² keeps the demo's 10 m scene at ~5 mm per texel.
pub const SHADOW_MAP_SIZE: u32 = 2048;

pub struct ShadowPass {
    /// `shadow.vert` + `shadow.frag`: position only (also the depth pre-pass's program).
    pub program: ProgramObject,
    pub fbo: FramebufferObject,
}

impl ShadowPass {
    pub fn new(gl: &Gl, res: &ResDirs) -> Result<ShadowPass> {
        let tex = Rc::new(Texture::new(
            gl,
            TextureDesc::target(
                "FBO(shadow)",
                SHADOW_MAP_SIZE,
                SHADOW_MAP_SIZE,
                glow::DEPTH_COMPONENT32,
            )
            .filter(glow::LINEAR, glow::LINEAR)
            .compare(true),
        )?);
        Ok(ShadowPass {
            program: ProgramObject::from_res(gl, res, "shadow.vert", "shadow.frag", &[])?,
            fbo: FramebufferObject::new(gl, None, Some(tex), 0, 0)?,
        })
    }

    pub fn depth_texture(&self) -> &Rc<Texture> {
        self.fbo
            .depth_texture()
            .expect("the shadow FBO is created with a depth texture")
    }

    pub fn draw(&self, f: &Frame, shadow: &Mat4) {
        self.fbo.bind();
        // The shadow map keeps the standard convention whatever the main depth buffer uses; both
        // faces are drawn (the demo meshes are not all closed); the offset removes acne.
        f.apply(PassState {
            depth: Depth::Test {
                func: glow::LEQUAL,
                write: true,
            },
            polygon_offset: Some((1.5, 2.0)),
            ..PassState::FULLSCREEN
        });
        unsafe {
            use glow::HasContext;
            f.gl.clear_depth_f32(1.0);
            f.gl.clear(glow::DEPTH_BUFFER_BIT);
        }
        self.program.set_mat4(loc::VIEW_PROJECTION, shadow);
        self.program.use_program();
        f.draw_objects(&self.program, false, shadow);
        f.apply(PassState::FULLSCREEN);
    }
}

/// Light's view-projection: an orthographic box around every object's bounds.
pub fn shadow_matrix(f: &Frame) -> Mat4 {
    let (lo, hi) = f
        .objects
        .iter()
        .map(|o| o.bounds)
        .reduce(|a, b| (a.0.min(b.0), a.1.max(b.1)))
        .unwrap_or((Vec3::splat(-1.0), Vec3::splat(1.0)));
    let center = (lo + hi) * 0.5;
    let r = ((hi - lo).length() * 0.5).max(0.1);
    let dir = f.light_direction();
    let up = if dir.cross(Vec3::Y).length_squared() < 1e-6 {
        Vec3::Z
    } else {
        Vec3::Y
    };
    let view = glam::camera::rh::view::look_at_mat4(center + dir * r * 2.0, center, up);
    glam::camera::rh::proj::opengl::orthographic(-r, r, -r, r, 0.01, r * 4.0) * view
}
