//! World-space triangle soup with an obvhs compressed wide BVH for ray queries.
//!
//! obvhs shares this crate's glam version; its vector types are still never named here:
//! values cross the boundary as `[f32; 3]` and `.into()` (type inference picks obvhs's `Vec3A`).
//! The BVH only culls with f32 boxes; the triangle test itself runs in f64 so that the
//! self-intersection offset (1e-4 m) stays far above the rounding error even on the
//! kilometre-sized ground quads used by the tests.

use std::time::Duration;

use anyhow::{bail, Result};
use glam::{DVec3, Vec3};

use super::hash::Fnv64;
use obvhs::{
    cwbvh::{builder::build_cwbvh_from_tris, CwBvh},
    ray::{Ray, RayHit},
    triangle::Triangle,
    BvhBuildParams,
};

/// A ray/triangle hit.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Hit {
    /// Distance from the ray origin along the (normalised) ray direction.
    pub t: f32,
    /// Index of the triangle in the list given to [`Scene::new`] (degenerate ones included, so
    /// the caller's indices stay valid).
    pub triangle: usize,
    /// Unit geometric normal `normalize((v1 - v0) x (v2 - v0))`, not flipped towards the ray.
    pub normal: Vec3,
}

/// Triangle data kept for the f64 intersection test (Möller–Trumbore form).
#[derive(Clone, Copy, Debug)]
struct Tri {
    v0: DVec3,
    e1: DVec3,
    e2: DVec3,
    normal: DVec3,
}

/// Internal closest-hit record in f64.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Hit64 {
    pub t: f64,
    /// Index into the kept (non-degenerate) triangle list.
    pub kept: usize,
}

/// Triangles in world space plus a BVH over them.
pub struct Scene {
    tris: Vec<Tri>,
    /// For each kept triangle, its index in the caller's input list.
    original_index: Vec<usize>,
    input_count: usize,
    /// `None` for a scene without (usable) triangles: obvhs is not asked to build an empty BVH.
    bvh: Option<CwBvh>,
    content_hash: u64,
}

/// Barycentric tolerance: triangles are grown by this fraction of their edges so that rays
/// cannot slip through the shared edge of two adjacent triangles due to rounding.
const BARY_EPS: f64 = 1e-10;

/// Ray/triangle test in f64. Returns `t` in `[t_min, t_max]` (units of `dir`), if any.
#[inline]
fn intersect_tri(tri: &Tri, o: DVec3, d: DVec3, t_min: f64, t_max: f64) -> Option<f64> {
    let p = d.cross(tri.e2);
    let det = tri.e1.dot(p);
    if det == 0.0 || !det.is_finite() {
        return None; // ray parallel to the triangle plane
    }
    let inv = 1.0 / det;
    let s = o - tri.v0;
    let u = s.dot(p) * inv;
    if !(-BARY_EPS..=1.0 + BARY_EPS).contains(&u) {
        return None;
    }
    let q = s.cross(tri.e1);
    let v = d.dot(q) * inv;
    if v < -BARY_EPS || u + v > 1.0 + BARY_EPS {
        return None;
    }
    let t = tri.e2.dot(q) * inv;
    (t >= t_min && t <= t_max && t.is_finite()).then_some(t)
}

/// Stable hash of a triangle list (vertex bit patterns, in order), for [`super::cache::cache_key`].
fn hash_triangles(triangles: &[[Vec3; 3]]) -> u64 {
    let mut h = Fnv64::new();
    h.u64(triangles.len() as u64);
    for t in triangles {
        for v in t {
            h.vec3(*v);
        }
    }
    h.0
}

impl Scene {
    /// Builds the scene. Triangles with a non-finite vertex or (near-)zero area are skipped
    /// because their normal is undefined; an empty list gives a valid scene where every ray
    /// misses. Errors only if the list is too long to index with `u32` (an obvhs limit).
    pub fn new(triangles: Vec<[Vec3; 3]>) -> Result<Scene> {
        if triangles.len() >= u32::MAX as usize {
            bail!("too many triangles for the BVH: {}", triangles.len());
        }
        let content_hash = hash_triangles(&triangles);
        let mut tris = Vec::with_capacity(triangles.len());
        let mut original_index = Vec::with_capacity(triangles.len());
        let mut bvh_tris = Vec::with_capacity(triangles.len());
        for (i, t) in triangles.iter().enumerate() {
            // The rule the GPU BVH shares (`scene::bvh`): no normal, no triangle.
            let Some(normal) = crate::scene::bvh::usable_triangle(t) else {
                continue;
            };
            let v0 = t[0].as_dvec3();
            let e1 = t[1].as_dvec3() - v0;
            let e2 = t[2].as_dvec3() - v0;
            tris.push(Tri { v0, e1, e2, normal });
            original_index.push(i);
            bvh_tris.push(Triangle {
                v0: t[0].to_array().into(),
                v1: t[1].to_array().into(),
                v2: t[2].to_array().into(),
            });
        }
        let bvh = if bvh_tris.is_empty() {
            None
        } else {
            Some(build_cwbvh_from_tris(
                &bvh_tris,
                BvhBuildParams::medium_build(),
                &mut Duration::default(),
            ))
        };
        Ok(Scene {
            tris,
            original_index,
            input_count: triangles.len(),
            bvh,
            content_hash,
        })
    }

    /// Number of triangles actually in the scene (degenerate input triangles excluded).
    pub fn triangle_count(&self) -> usize {
        self.tris.len()
    }

    /// Number of input triangles skipped as degenerate by [`Scene::new`].
    pub fn skipped_count(&self) -> usize {
        self.input_count - self.tris.len()
    }

    /// Stable hash of the input triangle list (vertex bit patterns in order, FNV-1a 64), for cache keys.
    pub fn content_hash(&self) -> u64 {
        self.content_hash
    }

    /// Closest hit along `origin + t * normalize(dir)` with `0 <= t <= t_max`.
    /// Returns `None` for a miss or for a zero / non-finite direction or origin.
    pub fn intersect(&self, origin: Vec3, dir: Vec3, t_max: f32) -> Option<Hit> {
        let o = origin.as_dvec3();
        let d = dir.as_dvec3().normalize_or_zero();
        if d == DVec3::ZERO || !o.is_finite() {
            return None;
        }
        let h = self.closest(o, d, 0.0, t_max as f64, usize::MAX)?;
        Some(Hit {
            t: h.t as f32,
            triangle: self.original_index[h.kept],
            normal: self.tris[h.kept].normal.as_vec3(),
        })
    }

    /// Geometric unit normal of a kept triangle.
    pub(crate) fn normal64(&self, kept: usize) -> DVec3 {
        self.tris[kept].normal
    }

    /// Builds the f32 ray obvhs traverses with. Its `tmax` only bounds box culling; the
    /// exact range test happens in f64 inside the closures.
    fn bvh_ray(o: DVec3, d: DVec3, t_max: f64) -> Ray {
        let tmax = if t_max.is_finite() {
            // Round outwards so f32 culling never rejects a hit the f64 test would accept.
            (t_max as f32) * (1.0 + 1e-6) + 1e-6
        } else {
            f32::INFINITY
        };
        Ray::new(
            o.as_vec3().to_array().into(),
            d.as_vec3().to_array().into(),
            0.0,
            tmax,
        )
    }

    /// Closest hit with `t` in `[t_min, t_max]`; `o`, `d` finite, `d` unit length.
    /// `skip` is a kept-triangle index to ignore (the surface a secondary ray starts on).
    pub(crate) fn closest(
        &self,
        o: DVec3,
        d: DVec3,
        t_min: f64,
        t_max: f64,
        skip: usize,
    ) -> Option<Hit64> {
        let bvh = self.bvh.as_ref()?;
        if t_max.is_nan() || t_min.is_nan() || t_max < t_min {
            return None;
        }
        let mut best: Option<Hit64> = None;
        let mut best_t = t_max;
        let mut hit = RayHit::none();
        bvh.ray_traverse(Self::bvh_ray(o, d, t_max), &mut hit, |_ray, id| {
            let kept = bvh.primitive_indices[id] as usize;
            if kept == skip {
                return f32::INFINITY;
            }
            match intersect_tri(&self.tris[kept], o, d, t_min, best_t) {
                Some(t) => {
                    best_t = t;
                    best = Some(Hit64 { t, kept });
                    // Slightly enlarged so obvhs' f32 shrinking of the ray never culls a box
                    // holding a hit that is closer in f64.
                    (t as f32) * (1.0 + 1e-6) + 1e-6
                }
                None => f32::INFINITY,
            }
        });
        best
    }

    /// True if anything is hit with `t` in `[t_min, t_max]` (early exit on the first hit).
    pub(crate) fn occluded(&self, o: DVec3, d: DVec3, t_min: f64, t_max: f64, skip: usize) -> bool {
        let Some(bvh) = self.bvh.as_ref() else {
            return false;
        };
        if t_max.is_nan() || t_min.is_nan() || t_max < t_min {
            return false;
        }
        !bvh.ray_traverse_miss(Self::bvh_ray(o, d, t_max), |_ray, id| {
            let kept = bvh.primitive_indices[id] as usize;
            if kept == skip {
                return f32::INFINITY;
            }
            match intersect_tri(&self.tris[kept], o, d, t_min, t_max) {
                Some(_) => 0.0, // below any positive tmax: obvhs stops at the first hit
                None => f32::INFINITY,
            }
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn single_triangle_hit_and_miss() {
        let s = Scene::new(vec![[
            Vec3::new(-1.0, -1.0, -5.0),
            Vec3::new(1.0, -1.0, -5.0),
            Vec3::new(0.0, 1.0, -5.0),
        ]])
        .unwrap();
        assert_eq!(s.triangle_count(), 1);
        let h = s.intersect(Vec3::ZERO, Vec3::NEG_Z, 100.0).unwrap();
        assert!((h.t - 5.0).abs() < 1e-5);
        assert_eq!(h.triangle, 0);
        assert!((h.normal - Vec3::Z).length() < 1e-6);
        assert!(s.intersect(Vec3::ZERO, Vec3::NEG_Z, 4.0).is_none());
        assert!(s.intersect(Vec3::ZERO, Vec3::Z, 100.0).is_none());
        assert!(s
            .intersect(Vec3::ZERO, Vec3::new(3.0, 0.0, -1.0), 100.0)
            .is_none());
        assert!(s.intersect(Vec3::ZERO, Vec3::ZERO, 100.0).is_none());
    }

    #[test]
    fn degenerate_triangles_are_skipped_and_indices_kept() {
        let good = [
            Vec3::new(0.0, 0.0, -2.0),
            Vec3::new(1.0, 0.0, -2.0),
            Vec3::new(0.0, 1.0, -2.0),
        ];
        let s = Scene::new(vec![
            [Vec3::ZERO; 3],
            [Vec3::ZERO, Vec3::X, Vec3::X * 2.0],
            [Vec3::NAN, Vec3::X, Vec3::Y],
            good,
        ])
        .unwrap();
        assert_eq!(s.triangle_count(), 1);
        assert_eq!(s.skipped_count(), 3);
        let h = s
            .intersect(Vec3::new(0.2, 0.2, 0.0), Vec3::NEG_Z, f32::INFINITY)
            .unwrap();
        assert_eq!(h.triangle, 3);
    }

    #[test]
    fn empty_scene_misses() {
        let s = Scene::new(vec![]).unwrap();
        assert_eq!(s.triangle_count(), 0);
        assert!(s.intersect(Vec3::ZERO, Vec3::X, f32::INFINITY).is_none());
    }

    #[test]
    fn closest_of_many() {
        // A stack of parallel quads: the nearest must win regardless of BVH order.
        let mut tris = Vec::new();
        for k in (1..=20).rev() {
            let z = -(k as f32);
            tris.push([
                Vec3::new(-1.0, -1.0, z),
                Vec3::new(1.0, -1.0, z),
                Vec3::new(1.0, 1.0, z),
            ]);
            tris.push([
                Vec3::new(-1.0, -1.0, z),
                Vec3::new(1.0, 1.0, z),
                Vec3::new(-1.0, 1.0, z),
            ]);
        }
        let s = Scene::new(tris).unwrap();
        for (x, y) in [(0.1, 0.3), (-0.5, 0.2), (0.0, 0.0), (0.9, -0.9)] {
            let h = s.intersect(Vec3::new(x, y, 0.0), Vec3::NEG_Z, 1e9).unwrap();
            assert!((h.t - 1.0).abs() < 1e-6, "t = {}", h.t);
        }
    }
}
