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
        let r = Quat::from_euler(EulerRot::YXZ, self.rotation.y.to_radians(), self.rotation.x.to_radians(), self.rotation.z.to_radians());
        Mat4::from_scale_rotation_translation(self.scale, r, self.position)
    }
    pub fn is_transparent(&self) -> bool {
        self.color.w < 0.999
    }
}
