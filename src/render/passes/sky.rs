//! The sky: a full-screen quad at the far plane, drawn where nothing nearer was.

use crate::gl::{FramebufferObject, Gl, PassState, ProgramObject};
use crate::render::frame::Frame;
use crate::res::ResDirs;
use crate::shader_interface::loc;
use anyhow::Result;

pub struct SkyPass {
    pub program: ProgramObject,
}

impl SkyPass {
    pub fn new(gl: &Gl, res: &ResDirs) -> Result<SkyPass> {
        Ok(SkyPass {
            program: ProgramObject::from_res(gl, res, "sky.vert", "sky.frag", &[])?,
        })
    }

    pub fn draw(&self, f: &Frame, main: &FramebufferObject) {
        main.bind();
        // sky.vert puts the quad at clip z = w (window depth 1 = the far plane for the course's
        // convention); with reversed-Z the far plane is 0, so the window range is squeezed to 0.
        let far = f.depth_mode.clear_value();
        f.apply(PassState {
            depth_range: if f.depth_mode.reversed() {
                (far, far)
            } else {
                (0.0, 1.0)
            },
            ..f.scene_depth_state(false)
        });
        let inv = f.view_projection().inverse();
        self.program.set_mat4(loc::INVERSE_VIEW_PROJECTION, &inv);
        self.program
            .set_vec3(loc::LIGHT_DIRECTION, f.light_direction().to_array());
        self.program.use_program();
        f.meshes.draw_plane_xy();
        f.apply(PassState::FULLSCREEN);
    }
}
