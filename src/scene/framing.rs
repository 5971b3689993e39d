//! Framing a model from its bounds (`render --obj`, `bench --obj`): the camera looks at its
//! bounding sphere from a fixed direction, near and far follow the sphere's distance, and the AO
//! radius follows its size, so a model of any size (a CAD export in millimetres, a 2 km terrain)
//! fills the frame with a sane far/near ratio.

use super::SceneDesc;
use crate::gl::mesh::MeshData;
use glam::Vec3;
use std::collections::HashMap;

/// The values the user set, which framing leaves alone.
#[derive(Clone, Copy, Debug, Default)]
pub struct Fixed {
    pub eye: bool,
    pub target: bool,
    pub near: bool,
    pub far: bool,
    pub radius: bool,
}

/// What [`frame_mesh`] chose.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Framed {
    /// The AO radius (`None` when the radius was fixed), in the drawn scene's units.
    pub radius: Option<f32>,
    /// The diagonal of the model's objects, a ground plane left out ([`objects_diagonal`]), in
    /// the model's own units.
    pub size: f32,
    /// The factor the model is drawn at (1: its own size; 0.001: millimetres taken as metres).
    pub scale: f32,
}

/// Frames a model's mesh in `desc` (its objects the model at the origin) as [`frame_model`] frames
/// bounds, with the AO radius a tenth of the diagonal of the model's objects rather than of
/// everything: a ground plane many times larger than what stands on it would otherwise set it.
/// The radius range is in metres; a model whose radius would leave it (a CAD export in
/// millimetres, one in micrometres) is drawn at a power of 1000 of its size, so that the picture is
/// the one the same model in metres gives, unless a camera value or the radius was fixed in the
/// model's units. `None` for a mesh without vertices.
pub fn frame_mesh(desc: &mut SceneDesc, mesh: &MeshData, fixed: Fixed) -> Option<Framed> {
    let whole = mesh.bounds()?;
    let (lo, hi) = objects_bounds(mesh).unwrap_or(whole);
    let size = (hi - lo).length();
    let camera_fixed = fixed.eye || fixed.target || fixed.near || fixed.far;
    let scale = if fixed.radius || camera_fixed {
        1.0
    } else {
        unit_scale(0.1 * size)
    };
    if scale != 1.0 {
        for o in &mut desc.objects {
            o.scale = o.scale.map(|s| s * scale);
            o.position = o.position.map(|p| p * scale);
        }
    }
    let whole = (whole.0 * scale, whole.1 * scale);
    let radius = frame_sized(desc, (lo * scale, hi * scale), whole, fixed);
    Some(Framed {
        radius,
        size,
        scale,
    })
}

/// The power of 1000 that brings `radius` into the radius range (1 when it is in it already or not
/// finite).
fn unit_scale(radius: f32) -> f32 {
    let (lo, hi) = super::ao_settings::RADIUS_RANGE;
    let mut scale = 1.0f64;
    let r = radius as f64;
    if !r.is_finite() || r <= 0.0 {
        return 1.0;
    }
    while r * scale > hi as f64 && scale > 1e-12 {
        scale *= 1e-3;
    }
    while r * scale < lo as f64 && scale < 1e12 {
        scale *= 1e3;
    }
    scale as f32
}

/// The diagonal of [`objects_bounds`].
pub fn objects_diagonal(mesh: &MeshData) -> Option<f32> {
    objects_bounds(mesh).map(|(lo, hi)| (hi - lo).length())
}

/// The bounds of the mesh's connected parts (triangles joined where they share a corner position),
/// leaving out ground-like parts: flat (thinner than 2 % of their extent) and at least half as wide
/// as the whole model. `None` when nothing but such parts remain.
pub fn objects_bounds(mesh: &MeshData) -> Option<(Vec3, Vec3)> {
    let (all_lo, all_hi) = mesh.bounds()?;
    let widest = (all_hi - all_lo).max_element();
    // Corners welded by their exact position (a box's faces have a vertex each per normal).
    let mut id_of: HashMap<[u32; 3], usize> = HashMap::new();
    let welded: Vec<usize> = mesh
        .vertices
        .iter()
        .map(|v| {
            let key = v.position.map(f32::to_bits);
            let next = id_of.len();
            *id_of.entry(key).or_insert(next)
        })
        .collect();
    let mut parent: Vec<usize> = (0..id_of.len()).collect();
    fn root(parent: &mut [usize], mut i: usize) -> usize {
        while parent[i] != i {
            parent[i] = parent[parent[i]];
            i = parent[i];
        }
        i
    }
    for t in mesh.indices.chunks_exact(3) {
        let a = root(&mut parent, welded[t[0] as usize]);
        for &c in &t[1..] {
            let b = root(&mut parent, welded[c as usize]);
            parent[b] = a;
        }
    }
    let mut parts: HashMap<usize, (Vec3, Vec3)> = HashMap::new();
    for t in mesh.indices.chunks_exact(3) {
        let r = root(&mut parent, welded[t[0] as usize]);
        for &c in t {
            let p = Vec3::from(mesh.vertices[c as usize].position);
            let b = parts.entry(r).or_insert((p, p));
            *b = (b.0.min(p), b.1.max(p));
        }
    }
    let kept = parts.values().filter(|(lo, hi)| {
        let e = *hi - *lo;
        let ground = e.min_element() <= 0.02 * e.max_element() && e.max_element() >= 0.5 * widest;
        !ground
    });
    kept.fold(None, |acc: Option<(Vec3, Vec3)>, &(lo, hi)| {
        Some(acc.map_or((lo, hi), |(a, b)| (a.min(lo), b.max(hi))))
    })
}

/// Frames the bounds `lo`..`hi` in `desc`'s camera and AO radius, except what `fixed` keeps.
/// Returns the AO radius it chose (`None` when the radius was fixed).
pub fn frame_model(desc: &mut SceneDesc, lo: Vec3, hi: Vec3, fixed: Fixed) -> Option<f32> {
    frame_sized(desc, (lo, hi), (lo, hi), fixed)
}

/// [`frame_model`] of the bounds `objects` (camera and radius), with a far plane that also takes
/// in `whole`, the bounds of everything (a ground plane around the objects).
fn frame_sized(
    desc: &mut SceneDesc,
    (lo, hi): (Vec3, Vec3),
    whole: (Vec3, Vec3),
    fixed: Fixed,
) -> Option<f32> {
    let size = (hi - lo).length();
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
    let eye = Vec3::from(c.eye);
    let farthest = (0..8)
        .map(|i| {
            let pick = |bit: usize, a: f32, b: f32| if i >> bit & 1 == 0 { a } else { b };
            let (a, b) = whole;
            Vec3::new(pick(0, a.x, b.x), pick(1, a.y, b.y), pick(2, a.z, b.z)).distance(eye)
        })
        .fold(0.0f32, f32::max);
    let far = ((d + r) * 2.0).max(farthest * 1.05);
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
    let (lo_r, hi_r) = super::ao_settings::RADIUS_RANGE;
    let radius = (0.1 * size).clamp(lo_r, hi_r);
    let radius = (radius * 1e4).round() / 1e4;
    desc.ao.radius = if radius > 0.0 { radius } else { lo_r };
    Some(desc.ao.radius)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::shapes;

    fn boxes(unit: f32) -> MeshData {
        let mut m = MeshData::default();
        let s = |v: Vec3| v * unit;
        // A ground slab 28 m wide and three boxes about 1 m tall on it.
        shapes::add_box(
            &mut m,
            s(Vec3::new(-14.0, -0.05, -14.0)),
            s(Vec3::new(14.0, 0.0, 14.0)),
        );
        shapes::add_box(
            &mut m,
            s(Vec3::new(-1.0, 0.0, -0.5)),
            s(Vec3::new(0.0, 1.0, 0.5)),
        );
        shapes::add_box(
            &mut m,
            s(Vec3::new(0.3, 0.0, -0.4)),
            s(Vec3::new(1.0, 0.6, 0.3)),
        );
        shapes::add_box(
            &mut m,
            s(Vec3::new(-0.4, 0.0, 0.8)),
            s(Vec3::new(0.4, 1.4, 1.2)),
        );
        m
    }

    #[test]
    fn the_radius_follows_the_objects_not_the_ground_in_any_unit() {
        let metres = boxes(1.0);
        let diagonal = objects_diagonal(&metres).unwrap();
        // The boxes span x -1..1, y 0..1.4, z -0.5..1.2.
        let expected = Vec3::new(2.0, 1.4, 1.7).length();
        assert!(
            (diagonal - expected).abs() < 1e-5,
            "{diagonal} vs {expected}"
        );
        let mut desc_m = SceneDesc::single_obj(std::path::Path::new("m.obj"));
        let mut desc_mm = desc_m.clone();
        let m = frame_mesh(&mut desc_m, &metres, Fixed::default()).unwrap();
        let mm = frame_mesh(&mut desc_mm, &boxes(1000.0), Fixed::default()).unwrap();
        assert_eq!(m.scale, 1.0);
        assert!((mm.scale - 1e-3).abs() < 1e-9, "{}", mm.scale);
        let (rm, rmm) = (m.radius.unwrap(), mm.radius.unwrap());
        assert!((rm - rmm).abs() < 1e-3 * rm, "{rm} vs {rmm}");
        assert!((rm - 0.1 * expected).abs() < 1e-3, "{rm}");
        let close = |a: [f32; 3], b: [f32; 3]| Vec3::from(a).distance(Vec3::from(b)) < 1e-3;
        assert!(close(desc_m.camera.eye, desc_mm.camera.eye));
        assert!((desc_m.camera.far - desc_mm.camera.far).abs() < 1e-3 * desc_m.camera.far);
        assert_eq!(desc_mm.objects[0].scale, [1e-3; 3]);
        // A fixed camera keeps the model in its own units.
        let mut fixed_desc = SceneDesc::single_obj(std::path::Path::new("mm.obj"));
        let fixed = Fixed {
            eye: true,
            ..Fixed::default()
        };
        let kept = frame_mesh(&mut fixed_desc, &boxes(1000.0), fixed).unwrap();
        assert_eq!(kept.scale, 1.0);
    }

    #[test]
    fn a_lone_ground_plane_is_its_own_size() {
        let mut m = MeshData::default();
        shapes::add_box(
            &mut m,
            Vec3::new(-5.0, -0.01, -5.0),
            Vec3::new(5.0, 0.0, 5.0),
        );
        assert_eq!(objects_diagonal(&m), None);
        assert_eq!(unit_scale(0.5), 1.0);
        assert_eq!(unit_scale(f32::NAN), 1.0);
        assert!((unit_scale(2845.0) - 1e-3).abs() < 1e-9);
        assert!((unit_scale(1e-5) - 1e3).abs() < 1e-3);
    }
}
