//! The camera (a GameObject in the course): position, look-at target, vertical fov and clip planes,
//! with the course's defaults.

use glam::{Mat4, Vec3};

/// Vertical field of view of the course's camera, in degrees.
pub const FOV_Y_DEG: f32 = 60.0;
/// Near plane distance in metres (the course's `near`).
pub const NEAR: f32 = 0.35;
/// Far plane distance in metres (the course's `far`).
pub const FAR: f32 = 1000.0;

/// The course's `GetFovScale()`: 1 / tan(fovY / 2), ≈ 1.732 for 60°.
pub fn fov_scale(fov_y_deg: f32) -> f32 {
    1.0 / (fov_y_deg.to_radians() * 0.5).tan()
}

#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Camera {
    pub eye: Vec3,
    pub target: Vec3,
    pub up: Vec3,
    pub fov_y_deg: f32,
    pub near: f32,
    pub far: f32,
}

impl Default for Camera {
    fn default() -> Self {
        Camera {
            eye: Vec3::new(0.0, 1.6, 6.0),
            target: Vec3::ZERO,
            up: Vec3::Y,
            fov_y_deg: FOV_Y_DEG,
            near: NEAR,
            far: FAR,
        }
    }
}

impl Camera {
    /// A usable up vector: +Y unless the view is (nearly) vertical, then +Z or −Z.
    fn safe_up(&self) -> Vec3 {
        let fwd = (self.target - self.eye).normalize_or_zero();
        if fwd.cross(self.up).length_squared() > 1e-8 {
            self.up
        } else if fwd.y < 0.0 {
            Vec3::NEG_Z
        } else {
            Vec3::Z
        }
    }
    pub fn view(&self) -> Mat4 {
        glam::camera::rh::view::look_at_mat4(self.eye, self.target, self.safe_up())
    }
    /// The course's projection: OpenGL clip space, depth D = 0.5·(−z·B + A)/(−z) + 0.5.
    pub fn projection(&self, aspect: f32) -> Mat4 {
        glam::camera::rh::proj::opengl::perspective(
            self.fov_y_deg.to_radians(),
            aspect.max(1e-6),
            self.near,
            self.far,
        )
    }
    pub fn view_projection(&self, aspect: f32) -> Mat4 {
        self.projection(aspect) * self.view()
    }
    /// Unit vector the camera looks along.
    pub fn forward(&self) -> Vec3 {
        (self.target - self.eye).normalize_or_zero()
    }
}
