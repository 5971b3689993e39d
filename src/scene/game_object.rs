//! `GameObject`: a mesh placed in the world with a colour.

use crate::gl::StaticMesh;
use glam::{EulerRot, Mat4, Quat, Vec3, Vec4};

#[derive(Clone, Debug)]
pub struct GameObject {
    pub name: String,
    pub mesh: StaticMesh,
    pub position: Vec3,
    /// Degrees: yaw (Y), pitch (X), roll (Z), applied in that order.
    pub rotation: Vec3,
    pub scale: Vec3,
    pub color: Vec4,
    /// World-space bounds of the transformed mesh (for shadow fitting and culling).
    pub bounds: (Vec3, Vec3),
}

impl GameObject {
    pub fn model(&self) -> Mat4 {
        model_matrix(self.position, self.rotation, self.scale)
    }
    pub fn is_transparent(&self) -> bool {
        self.color.w < 0.999
    }
}

/// Model matrix from position, Euler degrees (yaw Y, pitch X, roll Z) and scale.
pub fn model_matrix(position: Vec3, rotation_deg: Vec3, scale: Vec3) -> Mat4 {
    let r = Quat::from_euler(
        EulerRot::YXZ,
        rotation_deg.y.to_radians(),
        rotation_deg.x.to_radians(),
        rotation_deg.z.to_radians(),
    );
    Mat4::from_scale_rotation_translation(scale, r, position)
}
