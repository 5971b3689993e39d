//! Lit geometry with `standard.vert/frag`: the opaque pass, the depth pre-pass of AO-on-ambient, and
//! the lighting after it with occlusion applied to the ambient term only.

use super::shadow::ShadowPass;
use crate::gl::{FramebufferObject, Gl, PassState, ProgramObject, Texture};
use crate::render::frame::Frame;
use crate::res::ResDirs;
use crate::shader_interface::{binding, loc};
use anyhow::Result;
use glam::Mat4;
use glow::HasContext;

pub struct LitPass {
    pub standard: ProgramObject,
}

impl LitPass {
    pub fn new(gl: &Gl, res: &ResDirs) -> Result<LitPass> {
        Ok(LitPass {
            standard: ProgramObject::from_res(gl, res, "standard.vert", "standard.frag", &[])?,
        })
    }

    /// The standard program's per-frame uniforms and the shadow map.
    pub fn setup(&self, f: &Frame, shadow: &ShadowPass, shadow_matrix: &Mat4) {
        let p = &self.standard;
        p.set_mat4(loc::VIEW_PROJECTION, &f.scene_view_projection());
        p.set_mat4(loc::SHADOW_MATRIX, shadow_matrix);
        p.set_vec3(loc::LIGHT_DIRECTION, f.light_direction().to_array());
        p.set_vec3(loc::LIGHT_COLOR, f.light.color);
        p.set_vec3(loc::AMBIENT_COLOR, f.light.ambient);
        p.set_i32(loc::SHADOW_ENABLED, f.light.shadow as i32);
        p.set_i32(loc::AO_AMBIENT_ONLY, 0);
        p.use_program();
        // Bound even when shadows are off: a sampler2DShadow must not see a non-depth texture.
        shadow.depth_texture().bind(binding::SHADOW_MAP);
    }

    /// Clears the main FBO and draws the opaque objects lit.
    pub fn draw_opaque(
        &self,
        f: &Frame,
        main: &FramebufferObject,
        shadow: &ShadowPass,
        shadow_matrix: &Mat4,
    ) {
        main.bind();
        f.apply(f.scene_depth_state(true));
        clear_main(f);
        self.setup(f, shadow, shadow_matrix);
        f.draw_objects(&self.standard, false, &f.view_projection());
        f.apply(PassState::FULLSCREEN);
    }

    /// Depth only (the pre-pass of AO-on-ambient): the AO chain needs depth before lighting.
    pub fn draw_depth_prepass(
        &self,
        f: &Frame,
        main: &FramebufferObject,
        depth_only: &ProgramObject,
    ) {
        main.bind();
        f.apply(f.scene_depth_state(true));
        clear_main(f);
        f.apply(PassState {
            color_write: false,
            ..f.scene_depth_state(true)
        });
        depth_only.set_mat4(loc::VIEW_PROJECTION, &f.scene_view_projection());
        depth_only.use_program();
        f.draw_objects(depth_only, false, &f.view_projection());
        f.apply(PassState::FULLSCREEN);
    }

    /// Lighting after the pre-pass, with `occlusion`^`power` applied to the ambient term only.
    pub fn draw_ao_ambient(
        &self,
        f: &Frame,
        main: &FramebufferObject,
        shadow: &ShadowPass,
        shadow_matrix: &Mat4,
        occlusion: &Texture,
        power: f32,
    ) {
        main.bind();
        f.apply(f.scene_depth_state(false));
        self.setup(f, shadow, shadow_matrix);
        let p = &self.standard;
        p.set_i32(loc::AO_AMBIENT_ONLY, 1);
        let (w, h) = f.size;
        p.set_vec2(loc::INV_SCREEN_SIZE, [1.0 / w as f32, 1.0 / h as f32]);
        p.set_f32(loc::AO_POWER, power);
        occlusion.bind(binding::AO_AMBIENT);
        f.draw_objects(p, false, &f.view_projection());
        f.apply(PassState::FULLSCREEN);
    }
}

/// Black colour and the convention's far depth (the state must allow depth writes).
fn clear_main(f: &Frame) {
    unsafe {
        f.gl.clear_color(0.0, 0.0, 0.0, 1.0);
        f.gl.clear_depth_f32(f.depth_mode.clear_value());
        f.gl.clear(glow::COLOR_BUFFER_BIT | glow::DEPTH_BUFFER_BIT);
    }
}
