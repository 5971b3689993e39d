//! Triangulating one OBJ polygon: projected onto its best-fit plane, then cut into triangles by
//! ear clipping, so concave outlines (an L, a star, a letter) keep their shape where a fan from the
//! first corner would cover the notches.

use glam::{DVec2, DVec3};

/// The polygon's normal by Newell's method (the best-fit plane's, for a non-planar outline too),
/// scaled by twice its area; zero for a polygon without area.
pub fn newell_normal(points: &[DVec3]) -> DVec3 {
    let mut n = DVec3::ZERO;
    for (i, a) in points.iter().enumerate() {
        let b = points[(i + 1) % points.len()];
        n += DVec3::new(
            (a.y - b.y) * (a.z + b.z),
            (a.z - b.z) * (a.x + b.x),
            (a.x - b.x) * (a.y + b.y),
        );
    }
    n
}

/// Triangles of the polygon `points` (outline order) as index triples into `points`, wound as the
/// outline is (counter-clockwise seen from the front stays so). Empty when the polygon has no area.
pub fn triangulate(points: &[DVec3]) -> Vec<[usize; 3]> {
    if points.len() == 3 {
        return vec![[0, 1, 2]];
    }
    let normal = newell_normal(points);
    let Some(n) = normal.try_normalize() else {
        return Vec::new();
    };
    // An orthonormal basis of the plane: (u, v, n) right-handed, so the outline's turning sense in
    // 2D is its sense seen from the front.
    let u = n.any_orthonormal_vector();
    let v = n.cross(u);
    let origin = points[0];
    let flat: Vec<[f64; 2]> = points
        .iter()
        .map(|p| {
            let d = *p - origin;
            [d.dot(u), d.dot(v)]
        })
        .collect();
    let mut indices: Vec<u32> = Vec::new();
    earcut::Earcut::new().earcut(flat.iter().copied(), &[] as &[u32], &mut indices);
    let corner = |i: u32| DVec2::from(flat[i as usize]);
    indices
        .chunks_exact(3)
        .map(|t| {
            let (a, b, c) = (corner(t[0]), corner(t[1]), corner(t[2]));
            let t = t.iter().map(|&i| i as usize).collect::<Vec<_>>();
            // Keep the outline's winding: the front face stays the front face.
            if (b - a).perp_dot(c - a) < 0.0 {
                [t[0], t[2], t[1]]
            } else {
                [t[0], t[1], t[2]]
            }
        })
        .collect()
}
