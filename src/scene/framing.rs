//! Framing a model from its bounds (`render --obj`, `bench --obj`): the camera looks at its
//! bounding sphere from a fixed direction, near and far follow the sphere's distance, and the AO
//! radius follows its size, so a model of any size (a CAD export in millimetres, a 2 km terrain)
//! fills the frame with a sane far/near ratio.

use super::SceneDesc;
use glam::Vec3;

/// The values the user set, which framing leaves alone.
#[derive(Clone, Copy, Debug, Default)]
pub struct Fixed {
    pub eye: bool,
    pub target: bool,
    pub near: bool,
    pub far: bool,
    pub radius: bool,
}

/// Frames the bounds `lo`..`hi` in `desc`'s camera and AO radius, except what `fixed` keeps.
/// Returns the AO radius it chose (`None` when the radius was fixed).
pub fn frame_model(desc: &mut SceneDesc, lo: Vec3, hi: Vec3, fixed: Fixed) -> Option<f32> {
    let c = &mut desc.camera;
    let center = (lo + hi) * 0.5;
    let half = (hi - lo).length() * 0.5;
    // A model that is a single point: any size frames it.
    let r = if half > 0.0 { half } else { 1.0 };
    if !fixed.target {
        c.target = center.to_array();
    }
    if !fixed.eye {
        let dist = r / (c.fov_y.to_radians() * 0.5).sin() * 1.1;
        c.eye = (Vec3::from(c.target) + Vec3::new(0.55, 0.45, 1.0).normalize() * dist).to_array();
    }
    let d = Vec3::from(c.eye).distance(center);
    // Room to step back in the window, and a near plane well in front of the model (or a tenth of
    // its size when the eye is close), never more than 1e4 below far.
    let far = (d + r) * 2.0;
    let near = ((d - r) * 0.5).min(r * 0.1).max(far * 1e-4);
    if !fixed.far {
        c.far = far;
    }
    if !fixed.near {
        c.near = near;
    }
    if fixed.radius {
        return None;
    }
    // The AO radius follows the model's size as the camera does: 1 m would be nothing on a model in
    // millimetres and everything on a terrain. A tenth of the diagonal darkens creases, feet and
    // gaps of a model without burying it.
    let (lo_r, hi_r) = crate::ao::settings::RADIUS_RANGE;
    let radius = (0.2 * r).clamp(lo_r, hi_r);
    let radius = (radius * 1e4).round() / 1e4;
    desc.ao.radius = if radius > 0.0 { radius } else { lo_r };
    Some(desc.ao.radius)
}
