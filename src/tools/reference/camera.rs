//! The reference's view of the engine's [`Camera`]: a robust f64 frame and primary-ray directions.
//! Free functions, because the camera type belongs to the engine.

use crate::math::Camera;
use glam::{DVec3, Vec3};

/// Orthonormal camera frame in f64: forward, right, up, and tan(fov/2).
#[derive(Clone, Copy, Debug)]
pub(crate) struct Frame {
    pub eye: DVec3,
    pub f: DVec3,
    pub s: DVec3,
    pub u: DVec3,
    pub tan_half: f64,
}

/// Camera frame, made robust: eye == target falls back to looking down -Z, and an `up`
/// parallel to the view direction is replaced by a perpendicular one, instead of producing
/// NaN. `None` if the eye is not finite or the field of view is not in (0, 180) degrees.
pub(crate) fn frame(cam: &Camera) -> Option<Frame> {
    let eye = cam.eye.as_dvec3();
    let fov = cam.fov_y_deg as f64;
    if !(eye.is_finite() && fov > 0.0 && fov < 180.0) {
        return None;
    }
    let f = (cam.target.as_dvec3() - eye)
        .try_normalize()
        .unwrap_or(DVec3::NEG_Z);
    let s = f
        .cross(cam.up.as_dvec3())
        .try_normalize()
        .unwrap_or_else(|| f.any_orthonormal_vector());
    let u = s.cross(f);
    Some(Frame {
        eye,
        f,
        s,
        u,
        tan_half: (fov.to_radians() * 0.5).tan(),
    })
}

/// Unit view direction the reference traces along (`normalize(target - eye)`, -Z if they
/// coincide or the camera is unusable).
pub fn view_direction(cam: &Camera) -> Vec3 {
    frame(cam).map_or(Vec3::NEG_Z, |fr| fr.f.as_vec3())
}

/// Unit direction of the primary ray through the centre of pixel (x, y) of a
/// `width` x `height` image (row 0 = top). `None` for an unusable camera or empty image.
pub fn pixel_dir(cam: &Camera, x: u32, y: u32, width: u32, height: u32) -> Option<Vec3> {
    if width == 0 || height == 0 {
        return None;
    }
    let fr = frame(cam)?;
    Some(fr.pixel_dir(x, y, width, height).as_vec3())
}

impl Frame {
    pub(crate) fn pixel_dir(&self, x: u32, y: u32, width: u32, height: u32) -> DVec3 {
        let aspect = width as f64 / height as f64;
        let ndc_x = 2.0 * (x as f64 + 0.5) / width as f64 - 1.0;
        let ndc_y = 1.0 - 2.0 * (y as f64 + 0.5) / height as f64;
        (self.f + self.s * (ndc_x * self.tan_half * aspect) + self.u * (ndc_y * self.tan_half))
            .normalize()
    }
}
