//! What every scene pass of one frame reads: the objects, camera, light and depth convention, and
//! the helpers that turn them into matrices and render state.

use crate::gl::clip_control::ClipControl;
use crate::gl::pass_state::Depth;
use crate::gl::{Gl, MeshBuffer, PassState, ProgramObject};
use crate::math::depth::projection;
use crate::math::frustum::{box_in_frustum, frustum_planes};
use crate::math::{Camera, DepthMode};
use crate::scene::game_object::GameObject;
use crate::scene::LightDesc;
use crate::shader_interface::loc;
use glam::{Mat4, Vec3};

pub struct Frame<'a> {
    pub gl: &'a Gl,
    pub meshes: &'a MeshBuffer,
    pub objects: &'a [GameObject],
    pub camera: &'a Camera,
    pub light: &'a LightDesc,
    pub depth_mode: DepthMode,
    /// Loaded once reversed-Z is first used; from then on every pass states its clip range.
    pub clip_control: Option<&'a ClipControl>,
    pub size: (u32, u32),
    /// Objects whose bounds miss the frustum are not drawn.
    pub frustum_culling: bool,
}

impl Frame<'_> {
    pub fn aspect(&self) -> f32 {
        self.size.0 as f32 / self.size.1 as f32
    }

    /// Towards the light, unit length (straight up when the scene gives a zero vector).
    pub fn light_direction(&self) -> Vec3 {
        Vec3::from(self.light.direction)
            .try_normalize()
            .unwrap_or(Vec3::Y)
    }

    /// The camera's view-projection for drawing into the main depth buffer (reversed-Z when on).
    pub fn scene_view_projection(&self) -> Mat4 {
        let c = self.camera;
        projection(self.depth_mode, c.fov_y_deg, self.aspect(), c.near, c.far) * c.view()
    }

    /// The course's view-projection: culling and the sky's view rays (the same frustum as
    /// `scene_view_projection`).
    pub fn view_projection(&self) -> Mat4 {
        self.camera.view_projection(self.aspect())
    }

    /// State of a pass drawing into the main depth buffer: the convention's clip range and test.
    pub fn scene_depth_state(&self, write: bool) -> PassState {
        PassState {
            depth: Depth::Test {
                func: self.depth_mode.nearer_or_equal(),
                write,
            },
            clip_zero_to_one: self.depth_mode.reversed(),
            ..PassState::FULLSCREEN
        }
    }

    pub fn apply(&self, state: PassState) {
        state.apply(self.gl, self.clip_control);
    }

    /// Draws the opaque (or transparent) objects whose bounds touch the frustum of `view_projection`.
    pub fn draw_objects(&self, prog: &ProgramObject, transparent: bool, view_projection: &Mat4) {
        self.meshes.bind();
        let planes = frustum_planes(view_projection);
        for o in self
            .objects
            .iter()
            .filter(|o| o.is_transparent() == transparent)
            .filter(|o| !self.frustum_culling || box_in_frustum(&planes, o.bounds))
        {
            prog.set_mat4(loc::MODEL, &o.model());
            prog.set_vec4(loc::OBJECT_COLOR, o.color.to_array());
            self.meshes.draw(&o.mesh);
        }
    }
}
