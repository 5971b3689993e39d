//! The camera (a GameObject in the course): position, look-at target, vertical fov and clip planes.

use crate::config;
use glam::{Mat4, Vec3};

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
            fov_y_deg: config::FOV_Y_DEG,
            near: config::NEAR,
            far: config::FAR,
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
        Mat4::look_at_rh(self.eye, self.target, self.safe_up())
    }
    /// The course's projection: OpenGL clip space, depth D = 0.5·(−z·B + A)/(−z) + 0.5.
    pub fn projection(&self, aspect: f32) -> Mat4 {
        Mat4::perspective_rh_gl(
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

/// Linear view distance (−z_view, metres) from a depth-buffer value, in f64: the exact inverse of the
/// projection that `sao_restore_depth.frag` computes in f32.
pub fn linear_depth_exact(d: f64, near: f64, far: f64) -> f64 {
    let a = -2.0 * far * near / (far - near);
    let b = (far + near) / (far - near);
    a / ((2.0 * d - 1.0) - b)
}
