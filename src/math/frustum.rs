//! View-frustum planes and box tests (culling, shadow fitting).

use glam::{Mat4, Vec3, Vec4};

/// The six planes (a, b, c, d with a·x + b·y + c·z + d ≥ 0 inside) of a view-projection's frustum.
pub fn frustum_planes(m: &Mat4) -> [Vec4; 6] {
    let r = |i: usize| m.row(i);
    [
        r(3) + r(0),
        r(3) - r(0),
        r(3) + r(1),
        r(3) - r(1),
        r(3) + r(2),
        r(3) - r(2),
    ]
}

/// Conservative test: false only when the box lies entirely outside one plane.
pub fn box_in_frustum(planes: &[Vec4; 6], (lo, hi): (Vec3, Vec3)) -> bool {
    planes.iter().all(|p| {
        // The box corner farthest along the plane normal.
        let c = Vec3::new(
            if p.x >= 0.0 { hi.x } else { lo.x },
            if p.y >= 0.0 { hi.y } else { lo.y },
            if p.z >= 0.0 { hi.z } else { lo.z },
        );
        p.truncate().dot(c) + p.w >= 0.0
    })
}

/// World-space bounds of the box `(lo, hi)` transformed by `m` (all eight corners).
pub fn transformed_bounds((lo, hi): (Vec3, Vec3), m: &Mat4) -> (Vec3, Vec3) {
    let mut b = (Vec3::splat(f32::MAX), Vec3::splat(f32::MIN));
    for i in 0..8 {
        let c = Vec3::new(
            if i & 1 == 0 { lo.x } else { hi.x },
            if i & 2 == 0 { lo.y } else { hi.y },
            if i & 4 == 0 { lo.z } else { hi.z },
        );
        let p = m.transform_point3(c);
        b = (b.0.min(p), b.1.max(p));
    }
    b
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::math::camera::Camera;

    #[test]
    fn frustum_test_keeps_visible_boxes_and_drops_those_behind() {
        let cam = Camera {
            eye: Vec3::ZERO,
            target: Vec3::new(0.0, 0.0, -1.0),
            ..Default::default()
        };
        let planes = frustum_planes(&cam.view_projection(1.0));
        let unit = |c: Vec3| (c - Vec3::splat(0.5), c + Vec3::splat(0.5));
        assert!(box_in_frustum(&planes, unit(Vec3::new(0.0, 0.0, -5.0))));
        assert!(
            !box_in_frustum(&planes, unit(Vec3::new(0.0, 0.0, 5.0))),
            "behind the camera"
        );
        assert!(
            !box_in_frustum(&planes, unit(Vec3::new(50.0, 0.0, -5.0))),
            "far to the right"
        );
        assert!(
            !box_in_frustum(&planes, unit(Vec3::new(0.0, 0.0, -2000.0))),
            "beyond the far plane"
        );
        // A box around the camera straddles every plane: kept.
        assert!(box_in_frustum(
            &planes,
            (Vec3::splat(-10.0), Vec3::splat(10.0))
        ));
    }
}
