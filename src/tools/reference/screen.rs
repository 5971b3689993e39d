//! Screen-space reference: the exact AO of the depth buffer, seen as a heightfield.
//!
//! The screen-space methods only know one depth per pixel. This module computes what a perfect
//! method could get from that depth buffer, so that a method's error against the ray-traced
//! reference splits into what the depth buffer cannot know (this image against the ray-traced
//! one) and what the method's sampling loses (the method against this image).
//!
//! The quantity is the ray-traced reference's binary visibility: the fraction of cosine-weighted
//! directions about the normal whose ray meets nothing within `radius` metres. The scene is
//! replaced by the depth buffer with infinite thickness by default: a ray point is blocked when it
//! lies behind the stored surface at its screen position. With a finite
//! [`DepthBuffer::thickness`] each surface is instead a slab that thick behind itself along its
//! camera ray, the model `vbao` assumes (`heightfield.rs`), so the reference is the ceiling of a
//! method with that model; with [`DepthBuffer::back_depth`] each slab reaches the back face behind
//! its pixel (`vbao`'s `backface` thickness), the thickness applying where there is none. A [`DepthBuffer::guard_band`] adds pixels around the visible image
//! (rendered over a wider field of view) that occlude but are not shaded.
//!
//! * **Surface.** Each pixel centre is lifted to view space from its linear depth. Two ways to fill
//!   the space between ([`DepthBuffer::surface`]):
//!   - *triangles*: the two triangles of each 2×2 cell (split along the cell's main diagonal) with
//!     *inverse* depth interpolated linearly in screen space: inverse depth is affine in screen
//!     space on any plane, so a planar surface is rebuilt exactly, and creases are cut by at most
//!     one pixel. The buffer's outer half-pixel border is outside the surface. With slabs a
//!     triangle is solid only where its pixels' slabs overlap, so a thin board seen at a grazing
//!     angle (neighbouring depths farther apart than it is thick) has no solid triangle at all.
//!   - *patches* (`patches.rs`): each pixel's footprint holds the plane through its centre with its
//!     normal, solid to its own back face: no connectivity rule, sharp silhouettes, and what the
//!     buffer knows about thin parts kept. On the thin-things scene with geometric normals this
//!     ceiling is about 8 dB above the triangles' (the triangles dropped the boards).
//!
//!   Rays that leave the buffer or cross the near plane see nothing more (the buffer knows
//!   nothing there).
//! * **Normal.** From the depth buffer, not the triangles: per axis the one-sided difference whose
//!   neighbour continues the pixel's own plane best (smallest error when the next two pixels
//!   predict its inverse depth), so normals do not bend across creases and silhouettes.
//! * **Dense march.** A ray segment (clipped to the near plane and the screen) is walked in screen
//!   space through every vertical, horizontal and diagonal cell edge it crosses, in order from the
//!   origin. Along the segment both the ray's and the surface's inverse depths are piecewise affine
//!   with breaks only at those edges, so comparing them at the edges and the two ends decides
//!   exactly whether the ray passes behind the surface: no mips and no skipped pixels.
//! * **Sampling.** The same per-pixel generator, stratified lattice, cosine mapping and size of
//!   self-intersection offset as the ray-traced reference (directions in view space); the offset
//!   goes towards the eye, not along the normal (see `shade_pixel`).
//!
//! Sky pixels (depth not finite or not > 0) give ao = 1, std_error = 0, depth = +inf, as in
//! [`RefImage`]; they also never block a ray.

use std::path::Path;

use anyhow::{bail, Result};
use glam::DVec3;

use super::cache;
use super::depth_buffer::DepthBuffer;
use super::hash::Fnv64;
use super::heightfield::Heightfield;
use super::image::{shade_image, RefImage};
use super::params::{AoVariant, RefParams};
use super::sampling;

/// Bump when the output for the same inputs changes, so stale cached images are not reused.
const SCREEN_ALGORITHM_VERSION: u32 = 9;

/// Renders the screen-space reference of `depth` with the ray-traced reference's parameters
/// (visibility only: `Obscurance` is an error). Output layout as [`RefImage`], the size of the
/// visible image ([`DepthBuffer::visible_size`]).
pub fn render_screen_space(depth: &DepthBuffer, params: &RefParams) -> Result<RefImage> {
    depth.validate()?;
    if params.variant != AoVariant::Visibility {
        bail!("{}", rust_i18n::t!("reference.visibility_only"));
    }
    let field = Heightfield::new(depth);
    let second = depth.second_layer_buffer().map(|b| Heightfield::new(&b));
    let layers = Layers {
        first: &field,
        second: second.as_ref(),
    };
    let (w, h) = depth.visible_size();
    let g = depth.guard_band as usize;
    Ok(shade_image(
        w,
        h,
        "screen-space reference",
        params.progress,
        // Each visible pixel keeps the random stream it has without a guard band.
        |x, y| shade_pixel(&layers, x + g, y + g, (y * w as usize + x) as u64, params),
    ))
}

/// The solid the rays meet: the first layer's slabs (or heightfield), and with a second layer its
/// slabs too (each triangulated on its own: a ray is blocked by either).
pub(crate) struct Layers<'a> {
    pub(crate) first: &'a Heightfield,
    pub(crate) second: Option<&'a Heightfield>,
}

impl Layers<'_> {
    fn blocked(&self, origin: DVec3, d: DVec3, radius: f64) -> bool {
        self.first.blocked(origin, d, radius)
            || self.second.is_some_and(|s| s.blocked(origin, d, radius))
    }
}

/// (ao, std_error, linear depth) of buffer pixel (x, y), whose random stream is `stream`; `None`
/// for sky.
fn shade_pixel(
    layers: &Layers,
    x: usize,
    y: usize,
    stream: u64,
    params: &RefParams,
) -> Option<(f32, f32, f32)> {
    let (start, depth) = ray_start(layers.first, x, y, params)?;
    let Some(start) = start else {
        return Some((1.0, 0.0, depth));
    };
    let count = params.rays.max(1);
    let mut rng = sampling::Pcg32::for_pixel(params.seed, stream);
    let shift = (rng.next_f64(), rng.next_f64());
    let mut open = 0u32;
    for i in 0..count {
        let (u, v) = sampling::lattice_point(i, count, shift);
        if !start.blocked(layers, (u, v), params.radius as f64) {
            open += 1;
        }
    }
    let mean = open as f64 / count as f64;
    let se = (mean * (1.0 - mean) / count as f64).max(0.0).sqrt();
    Some((mean.clamp(0.0, 1.0) as f32, se as f32, depth))
}

/// Where a pixel's rays leave from, and its frame for cosine-weighted directions.
pub(crate) struct RayStart {
    origin: DVec3,
    normal: DVec3,
    tangent: DVec3,
    bitangent: DVec3,
}

impl RayStart {
    /// Whether the cosine-weighted direction of lattice point `uv` is blocked within `radius`.
    pub(crate) fn blocked(&self, layers: &Layers, uv: (f64, f64), radius: f64) -> bool {
        let (n, t, b) = (self.normal, self.tangent, self.bitangent);
        let d = sampling::cosine_direction(n, t, b, uv.0, uv.1);
        layers.blocked(self.origin, d, radius)
    }
}

/// Buffer pixel (x, y)'s ray start and linear depth: `None` for sky; a `None` start where the pixel
/// sees nothing (closer than the near plane, or no radius), which is fully open.
pub(crate) fn ray_start(
    field: &Heightfield,
    x: usize,
    y: usize,
    params: &RefParams,
) -> Option<(Option<RayStart>, f32)> {
    let p = field.point(x, y)?;
    let depth = (1.0 / field.inv_at(x, y)) as f32;
    let radius = params.radius as f64;
    if p.z > -field.near || radius.is_nan() || radius <= 0.0 {
        // Closer than the near plane the buffer cannot hold it; no radius, nothing occludes.
        return Some((None, depth));
    }
    let normal = field.normal(x, y, p);
    // The ray-traced reference's offset size (clears rounding at that distance), but towards the
    // eye along the pixel's own ray: the origin stays over the pixel's vertex, in front of every
    // triangle that meets there. Along the normal it could cross the screen into a neighbouring
    // triangle that rises steeply (the one bridging a concave crease) and start inside the solid.
    let origin = p - p.normalize() * (1e-4 * p.length().max(1.0));
    let (tangent, bitangent) = sampling::tangent_frame(normal);
    let start = RayStart {
        origin,
        normal,
        tangent,
        bitangent,
    };
    Some((Some(start), depth))
}

/// Cache key of a screen-space render: FNV-1a 64 over the algorithm version, every depth value,
/// the projection and every parameter that changes the pixels.
pub fn screen_cache_key(depth: &DepthBuffer, params: &RefParams) -> String {
    let mut h = Fnv64::new();
    h.bytes(b"opengl3d-screen-space-ao");
    h.u32(SCREEN_ALGORITHM_VERSION);
    h.u64(depth.content_hash());
    h.f32(params.radius);
    h.u32(params.rays);
    h.u64(params.seed);
    format!("{:016x}", h.0)
}

/// The cached screen-space reference for these inputs, or a fresh render that is then stored
/// (same file format as the ray-traced cache, in the same folder; an unwritable cache is a
/// warning, not an error).
pub fn load_or_render_screen_cached(
    cache_dir: &Path,
    depth: &DepthBuffer,
    params: &RefParams,
) -> Result<RefImage> {
    depth.validate()?;
    let key = screen_cache_key(depth, params);
    if let Some(img) = cache::read_cached(cache_dir, &key) {
        if (img.width, img.height) == depth.visible_size() {
            return Ok(img);
        }
    }
    let img = render_screen_space(depth, params)?;
    cache::store_or_warn(cache_dir, &key, &img);
    Ok(img)
}

#[cfg(test)]
pub(crate) mod tests {
    use super::super::depth_buffer::Surface;
    use super::super::heightfield::EdgeFamily;
    use super::*;
    use glam::DVec3;

    /// A heightfield buffer of `w` × `h` with depth `f(x, y)`, 60° field of view.
    pub(crate) fn buffer(w: u32, h: u32, f: impl Fn(u32, u32) -> f32) -> DepthBuffer {
        DepthBuffer {
            width: w,
            height: h,
            linear_depth: (0..h)
                .flat_map(|y| (0..w).map(move |x| (x, y)))
                .map(|(x, y)| f(x, y))
                .collect(),
            fov_y_deg: 60.0,
            near: 0.1,
            thickness: f32::INFINITY,
            back_depth: None,
            normals: None,
            second_layer: None,
            second_back_depth: None,
            guard_band: 0,
            surface: Surface::Triangles,
        }
    }

    /// A wall facing the camera at 3 m hides a patchwork (columns at 3.3 m and 8 m): normals rebuilt
    /// from it tilt the hidden patches until their corners reach in front of the wall. The second
    /// layer's patches are flat, so nothing lies in front of the wall and its pixels stay open.
    #[test]
    fn the_second_layers_patches_never_reach_in_front_of_the_surface_that_hides_them() {
        let (w, h) = (24u32, 16u32);
        let mut buf = buffer(w, h, |_, _| 3.0).with_thickness(0.5);
        buf.surface = Surface::Patches;
        buf.normals = Some(vec![[0.0, 0.0, 1.0]; (w * h) as usize]);
        buf.second_layer = Some(
            (0..w * h)
                .map(|k| if (k % w) % 2 == 0 { 3.3 } else { 8.0 })
                .collect(),
        );
        let second = buf.second_layer_buffer().unwrap();
        assert_eq!(second.surface, Surface::FlatPatches);
        let params = RefParams {
            radius: 1.0,
            rays: 64,
            ..Default::default()
        };
        let img = render_screen_space(&buf, &params).unwrap();
        for y in 4..h - 4 {
            for x in 4..w - 4 {
                let a = img.ao[(y * w + x) as usize];
                assert_eq!(a, 1.0, "pixel ({x}, {y}) is occluded: {a}");
            }
        }
        // With the hidden layer's normals rebuilt from its depth, its patches did occlude.
        let tilted = Heightfield::new(&DepthBuffer {
            surface: Surface::Patches,
            ..second
        });
        let first = Heightfield::new(&buf);
        let layers = Layers {
            first: &first,
            second: Some(&tilted),
        };
        let blocked = (4..h - 4)
            .flat_map(|y| (4..w - 4).map(move |x| (x, y)))
            .filter(|&(x, y)| {
                let (start, _) = ray_start(&first, x as usize, y as usize, &params).unwrap();
                let start = start.unwrap();
                (0..64).any(|i| {
                    let uv = sampling::lattice_point(i, 64, (0.3, 0.7));
                    start.blocked(&layers, uv, 1.0)
                })
            })
            .count();
        assert!(blocked > 0, "tilted hidden patches blocked nothing");
    }

    /// A box seen from above and in front: its front face (z = −3, facing the camera) meets its top
    /// (y = −0.5, from z = −3 to −4) in a convex edge, with a far wall behind. A pixel whose centre
    /// lies on the top spreads the top's plane over its footprint, and below the edge that plane
    /// comes in front of the front face; the front face's pixels must stay open (every ray leaves
    /// towards +z, where nothing is).
    #[test]
    fn a_convex_edge_does_not_shade_the_face_below_it() {
        convex_edge_leaves_the_front_face_open(|_| -0.5);
    }

    /// The same box with its top seen nearly edge-on (the capital of a pillar level with the eye):
    /// one row of pixels holds the top, its centre 0.9 m behind the edge, which lies 0.15 of a
    /// pixel below it. The front face's pixel below is nearer than that centre and outside the top
    /// pixel's slab at the edge they share, yet the top's plane spread over the lower half of the
    /// footprint reaches a metre towards the eye, in front of the front face (0.56 without the
    /// crossing rule of `Patches::with_convex_edges`).
    #[test]
    fn a_convex_edge_seen_edge_on_does_not_shade_the_face_below_it() {
        // The top at the height of the view ray 0.15 of a pixel below the first row under the
        // horizon, at the front face's depth.
        convex_edge_leaves_the_front_face_open(|probe| {
            let r = (0..probe.h)
                .find(|&y| probe.point(0, y).unwrap().y < 0.0)
                .unwrap();
            let (a, b) = (probe.point(0, r).unwrap(), probe.point(0, r + 1).unwrap());
            3.0 * (0.85 * a.y + 0.15 * b.y)
        });
    }

    /// A box whose front face (z = −3) meets its top (y = `y_top(probe)`, to z = −4) in a convex
    /// edge, a far wall behind; `probe`'s pixel centres lie at depth 1 on their view rays.
    fn convex_edge_leaves_the_front_face_open(y_top: impl Fn(&Heightfield) -> f64) {
        let (w, h) = (32u32, 48u32);
        let probe = Heightfield::new(&buffer(w, h, |_, _| 1.0));
        let (y_top, front, back) = (y_top(&probe), 3.0f64, 4.0f64);
        let hit = |x: u32, y: u32| -> (f32, [f32; 3], f32) {
            let e = probe.point(x as usize, y as usize).unwrap(); // depth 1: the view ray
            if e.y * front < y_top {
                return (front as f32, [0.0, 0.0, 1.0], back as f32);
            }
            let d = y_top / e.y;
            if e.y < 0.0 && d <= back {
                return (d as f32, [0.0, 1.0, 0.0], back as f32);
            }
            (10.0, [0.0, 0.0, 1.0], f32::INFINITY)
        };
        let mut buf = buffer(w, h, |x, y| hit(x, y).0).with_thickness(0.5);
        buf.surface = Surface::Patches;
        buf.normals = Some(
            (0..h)
                .flat_map(|y| (0..w).map(move |x| (x, y)))
                .map(|(x, y)| hit(x, y).1)
                .collect(),
        );
        buf.back_depth = Some(
            (0..h)
                .flat_map(|y| (0..w).map(move |x| (x, y)))
                .map(|(x, y)| hit(x, y).2)
                .collect(),
        );
        let x = w / 2;
        let first_front = (0..h).find(|&y| hit(x, y).0 == front as f32).unwrap();
        let top = first_front - 1;
        assert_eq!(hit(x, top).1, [0.0, 1.0, 0.0], "the row above is the top");
        // The top pixel's own plane at the edge it shares with the row below lies in front of the
        // front face there: without the convex edge it would stand in front of that face.
        let field = Heightfield::new(&buf);
        let p = field.point(x as usize, top as usize).unwrap();
        let n = field.normal(x as usize, top as usize, p);
        let along = |d: f64| {
            // Depth of the top's plane on the ray half a pixel below the top pixel's centre.
            let e = probe.point(x as usize, top as usize).unwrap();
            let e2 = probe.point(x as usize, first_front as usize).unwrap();
            let mid = 0.5 * (e + e2);
            n.dot(p) / n.dot(mid) * d
        };
        assert!(
            along(1.0) < front - 0.01,
            "the top's plane does not come forward: {}",
            along(1.0)
        );
        let params = RefParams {
            radius: 1.0,
            rays: 64,
            ..Default::default()
        };
        let img = render_screen_space(&buf, &params).unwrap();
        for y in first_front..first_front + 3 {
            for x in 4..w - 4 {
                let a = img.ao[(y * w + x) as usize];
                assert_eq!(a, 1.0, "front-face pixel ({x}, {y}) is occluded: {a}");
            }
        }
    }

    #[test]
    fn edge_families_cross_every_integer_in_order() {
        let mut f = EdgeFamily::new(0.25, 3.0, 0.0);
        let mut crossings = Vec::new();
        while f.next_s <= 1.0 {
            crossings.push(0.25 + f.next_s * 3.0);
            f.advance();
        }
        assert_eq!(crossings.len(), 3);
        for (c, want) in crossings.iter().zip([1.0, 2.0, 3.0]) {
            assert!((c - want).abs() < 1e-12, "{crossings:?}");
        }
        let mut f = EdgeFamily::new(2.0, -1.5, 0.0);
        assert!((2.0 - 1.5 * f.next_s - 1.0).abs() < 1e-12);
        f.advance();
        assert!((2.0 - 1.5 * f.next_s - 0.0).abs() < 1e-12);
        assert_eq!(EdgeFamily::new(1.0, 0.0, 0.0).next_s, f64::INFINITY);
    }

    #[test]
    fn fronto_parallel_wall_blocks_rays_behind_it_only() {
        // A wall at depth 5 filling the view: a ray from depth 4 going deeper is blocked once it
        // passes depth 5, one going towards the camera never is.
        let field = Heightfield::new(&buffer(32, 24, |_, _| 5.0));
        let o = DVec3::new(0.0, 0.0, -4.0);
        assert!(field.blocked(o, DVec3::new(0.0, 0.0, -1.0), 1.5));
        assert!(!field.blocked(o, DVec3::new(0.0, 0.0, -1.0), 0.9));
        assert!(!field.blocked(o, DVec3::new(0.1, 0.0, 1.0).normalize(), 10.0));
        // Sky blocks nothing.
        let sky = Heightfield::new(&buffer(32, 24, |_, _| f32::INFINITY));
        assert!(!sky.blocked(o, DVec3::new(0.0, 0.0, -1.0), 100.0));
    }

    #[test]
    fn slabs_block_only_within_their_thickness() {
        let wall = |t: f32| Heightfield::new(&buffer(32, 24, |_, _| 5.0).with_thickness(t));
        let deeper = DVec3::new(0.0, 0.0, -1.0);
        // From depth 4 going deeper: the slab [5, 5.5] is met after 1 m.
        let o = DVec3::new(0.0, 0.0, -4.0);
        assert!(wall(0.5).blocked(o, deeper, 1.2));
        assert!(!wall(0.5).blocked(o, deeper, 0.9));
        // From depth 5.7, behind the slab: going deeper meets nothing (the heightfield would
        // block at once), coming back crosses the slab after 0.2 m.
        let behind = DVec3::new(0.0, 0.0, -5.7);
        assert!(!wall(0.5).blocked(behind, deeper, 10.0));
        assert!(wall(f32::INFINITY).blocked(behind, deeper, 10.0));
        assert!(wall(0.5).blocked(behind, -deeper, 0.3));
        assert!(!wall(0.5).blocked(behind, -deeper, 0.15));
    }

    #[test]
    fn back_faces_extend_slabs_never_thin_them_and_missing_ones_fall_back_to_the_thickness() {
        let deeper = DVec3::new(0.0, 0.0, -1.0);
        let o = DVec3::new(0.0, 0.0, -4.0);
        let behind = DVec3::new(0.0, 0.0, -5.7);
        // A wall at depth 5 whose back faces lie at `back`, with a fallback thickness `t`.
        let wall = |back: f32, t: f32| {
            let mut b = buffer(32, 24, |_, _| 5.0).with_thickness(t);
            b.back_depth = Some(vec![back; 32 * 24]);
            Heightfield::new(&b)
        };
        // Back faces at 5.5 beyond the 0.3 m thickness: the slab is [5, 5.5].
        assert!(wall(5.5, 0.3).blocked(o, deeper, 1.2));
        assert!(!wall(5.5, 0.3).blocked(o, deeper, 0.9));
        assert!(!wall(5.5, 0.3).blocked(behind, deeper, 10.0));
        assert!(wall(5.5, 0.3).blocked(behind, -deeper, 0.3));
        assert!(!wall(5.5, 0.3).blocked(behind, -deeper, 0.15));
        // Back faces at 5.1, nearer than the thickness: the slab keeps [5, 5.3].
        let inside = DVec3::new(0.0, 0.0, -5.5);
        assert!(wall(5.1, 0.3).blocked(inside, -deeper, 0.3));
        assert!(!wall(5.1, 0.3).blocked(inside, -deeper, 0.15));
        // No back face (none, or none deeper than the surface): the 2 m slab [5, 7].
        for none in [f32::INFINITY, 5.0, 4.0, f32::NAN] {
            assert!(wall(none, 2.0).blocked(behind, deeper, 0.5), "back {none}");
            let beyond = DVec3::new(0.0, 0.0, -7.2);
            assert!(
                !wall(none, 2.0).blocked(beyond, deeper, 10.0),
                "back {none}"
            );
            assert!(wall(none, 2.0).blocked(beyond, -deeper, 0.3), "back {none}");
            assert!(
                !wall(none, 2.0).blocked(beyond, -deeper, 0.15),
                "back {none}"
            );
        }
    }

    #[test]
    fn each_pixel_keeps_its_own_back_face() {
        // Left half: a plate at depth 3 with its back at 3.02 (a slab of the 0.5 m thickness, which
        // a back face never thins); right half: a wall at depth 5 with its back at 6. A ray at
        // constant depth 4.5 from the wall's side towards the plate's passes behind the plate's slab
        // (open), one at depth 3.01 passes through the plate (blocked), and any single thickness
        // that reaches 4.5 behind the plate blocks the first.
        let mut b = buffer(64, 48, |x, _| if x < 32 { 3.0 } else { 5.0 }).with_thickness(0.5);
        b.back_depth = Some(
            (0..48)
                .flat_map(|_| (0..64).map(|x| if x < 32 { 3.02f32 } else { 6.0 }))
                .collect(),
        );
        let field = Heightfield::new(&b);
        let left = DVec3::new(-1.0, 0.0, 0.0);
        assert!(!field.blocked(DVec3::new(1.0, 0.0, -4.5), left, 2.0));
        assert!(field.blocked(DVec3::new(0.5, 0.0, -3.01), left, 1.0));
        // The wall's slab is [5, 6], not [5, 5.5] (the fallback): open behind 6 only.
        let behind_wall = DVec3::new(1.0, 0.0, -6.2);
        let deeper = DVec3::new(0.0, 0.0, -1.0);
        assert!(!field.blocked(behind_wall, deeper, 10.0));
        assert!(field.blocked(behind_wall, -deeper, 0.3));
        assert!(!field.blocked(behind_wall, -deeper, 0.15));
        assert!(field.blocked(DVec3::new(1.0, 0.0, -4.0), deeper, 1.1));
        let uniform = Heightfield::new(
            &buffer(64, 48, |x, _| if x < 32 { 3.0 } else { 5.0 }).with_thickness(1.6),
        );
        assert!(uniform.blocked(DVec3::new(1.0, 0.0, -4.5), left, 2.0));
        // A silhouette triangle (plate and wall pixels) is empty: the plate's slab (to 3.5) ends in
        // front of the wall's front (5).
        assert!(!field.triangle_is_solid([(31, 10), (32, 11), (32, 10)]));
        assert!(field.triangle_is_solid([(30, 10), (31, 11), (31, 10)]));
    }

    #[test]
    fn rays_pass_behind_a_plate_thinner_than_the_gap() {
        // Left half: a plate at depth 3; right half: a wall at depth 5. A ray at constant depth
        // 4.5 from the wall's side towards the plate's passes 1.5 m behind the plate's surface.
        let field = |t: f32| {
            Heightfield::new(
                &buffer(64, 48, |x, _| if x < 32 { 3.0 } else { 5.0 }).with_thickness(t),
            )
        };
        let o = DVec3::new(1.0, 0.0, -4.5);
        let left = DVec3::new(-1.0, 0.0, 0.0);
        assert!(
            !field(0.5).blocked(o, left, 2.0),
            "through the silhouette's gap"
        );
        assert!(field(1.6).blocked(o, left, 2.0), "into the slab [3, 4.6]");
        assert!(field(f32::INFINITY).blocked(o, left, 2.0));
        // Not far enough to reach the plate's side of the screen.
        assert!(!field(1.6).blocked(o, left, 0.5));
    }

    #[test]
    fn normals_of_a_tilted_plane_are_exact_and_odd_input_stays_finite() {
        // The plane z = -3 - 0.5·x in view space, rendered into the buffer through the projection.
        let (w, h) = (20u32, 14u32);
        let probe = Heightfield::new(&buffer(w, h, |_, _| 1.0));
        let depth = |x: u32, y: u32| {
            let ray = probe.point(x as usize, y as usize).unwrap(); // depth 1: the view ray
                                                                    // −z = 3 + 0.5·x with x = ray.x·depth → depth = 3 / (1 − 0.5·ray.x)
            (3.0 / (1.0 - 0.5 * ray.x)) as f32
        };
        let field = Heightfield::new(&buffer(w, h, depth));
        let want = DVec3::new(0.5, 0.0, 1.0).normalize();
        for (i, j) in [(0, 0), (5, 7), (19, 13), (10, 0)] {
            let p = field.point(i, j).unwrap();
            let n = field.normal(i, j, p);
            assert!((n - want).length() < 1e-5, "pixel {i},{j}: {n}");
        }
        for (w, h) in [(0, 0), (1, 1), (1, 5), (2, 1)] {
            let img = render_screen_space(
                &buffer(w, h, |x, _| if x == 0 { 2.0 } else { f32::INFINITY }),
                &RefParams {
                    rays: 8,
                    ..Default::default()
                },
            )
            .unwrap();
            assert!(img
                .ao
                .iter()
                .all(|a| a.is_finite() && (0.0..=1.0).contains(a)));
        }
        assert!(render_screen_space(
            &buffer(2, 2, |_, _| 1.0),
            &RefParams {
                variant: AoVariant::Obscurance,
                ..Default::default()
            }
        )
        .is_err());
        let mut bad = buffer(2, 2, |_, _| 1.0);
        bad.linear_depth.pop();
        assert!(render_screen_space(&bad, &RefParams::default()).is_err());
    }

    /// A floor and a wall leaning back from the camera meet in a concave crease; the triangles
    /// that bridge the crease cut in front of the corner. A wall pixel next to the crease was
    /// lifted along its normal, which points down the screen, into the bridging triangle: its rays
    /// started inside the solid and the pixel came out fully occluded (0) where the corner gives
    /// about one half.
    #[test]
    fn pixels_beside_a_concave_crease_do_not_start_inside_the_solid() {
        // View-space planes of a far wall-floor crease seen from above (a scene of the
        // vbao-convergence test), as n · X = c.
        let wall_n = DVec3::new(0.1322, -0.3248, 0.9365).normalize();
        let wall_c = wall_n.dot(DVec3::new(-3.8602, -0.2434, -7.2281));
        let floor_n = DVec3::new(0.0, 0.9448, 0.3278).normalize();
        let floor_c = floor_n.dot(DVec3::new(-3.7919, -0.2435, -7.2306));
        let (w, h) = (160u32, 120u32);
        let t = (30.0f64).to_radians().tan();
        let depth = buffer(w, h, |x, y| {
            let ray = DVec3::new(
                (2.0 * (x as f64 + 0.5) / w as f64 - 1.0) * t * w as f64 / h as f64,
                (1.0 - 2.0 * (y as f64 + 0.5) / h as f64) * t,
                -1.0,
            );
            // Depth along each plane; the visible surface of a concave corner is the nearer.
            let hit = |n: DVec3, c: f64| {
                let d = c / n.dot(ray);
                if d > 0.0 {
                    d
                } else {
                    f64::INFINITY
                }
            };
            hit(wall_n, wall_c).min(hit(floor_n, floor_c)) as f32
        });
        for (thickness, surface) in [
            (0.5, Surface::Triangles),
            (f32::INFINITY, Surface::Triangles),
            (0.5, Surface::Patches),
            (f32::INFINITY, Surface::Patches),
        ] {
            let img = render_screen_space(
                &DepthBuffer {
                    surface,
                    ..depth.clone().with_thickness(thickness)
                },
                &RefParams {
                    radius: 1.0,
                    rays: 64,
                    ..Default::default()
                },
            )
            .unwrap();
            let darkest = img.ao.iter().copied().fold(1.0f32, f32::min);
            let zeros = img.ao.iter().filter(|a| **a == 0.0).count();
            assert!(
                darkest > 0.3,
                "T {thickness} {surface:?}: darkest pixel {darkest}, {zeros} pixels fully occluded"
            );
        }
    }

    /// A 2 cm board tilted away from the camera (view-space plane z = −3 − 1.5·y): neighbouring
    /// rows lie 0.1 to 5 m apart in depth, far more than the board is thick.
    fn tilted_board(surface: Surface) -> (DepthBuffer, DVec3) {
        let (w, h) = (20u32, 14u32);
        let probe = Heightfield::new(&buffer(w, h, |_, _| 1.0));
        let depth = |x: u32, y: u32| {
            let ray = probe.point(x as usize, y as usize).unwrap();
            (3.0 / (1.0 - 1.5 * ray.y)) as f32
        };
        let mut b = buffer(w, h, depth).with_thickness(0.01);
        b.back_depth = Some(b.linear_depth.iter().map(|d| d + 0.02).collect());
        b.surface = surface;
        (b, DVec3::new(0.0, -1.5, 1.0).normalize())
    }

    /// The triangulated surface keeps a triangle only where its pixels' slabs overlap, so a thin
    /// board seen at a grazing angle has no solid triangle and rays pass through it; the patches
    /// keep each pixel's plane and block them. Rays beneath the board stay open in both.
    #[test]
    fn patches_keep_a_thin_board_seen_edge_on_that_triangles_drop() {
        for (surface, blocks) in [(Surface::Triangles, false), (Surface::Patches, true)] {
            let (b, n) = tilted_board(surface);
            let field = Heightfield::new(&b);
            for (i, j) in [(10, 7), (4, 3), (15, 10)] {
                let p = field.point(i, j).unwrap();
                // From 10 cm beneath the board (beyond its back) up through it.
                let below = p - n * 0.1;
                assert_eq!(field.blocked(below, n, 0.2), blocks, "{surface:?} {i},{j}");
                assert!(!field.blocked(below, n, 0.05), "{surface:?} {i},{j}");
                // Along the board, beneath it: nothing in the way.
                let along = n.cross(DVec3::X).normalize();
                assert!(!field.blocked(below, along, 0.3), "{surface:?} {i},{j}");
            }
        }
    }

    /// Every pixel of a plane, however grazing, is open: its own patch and its neighbours' rebuild
    /// the plane exactly, with no staircase to start a ray inside.
    #[test]
    fn a_grazing_plane_is_open_everywhere_with_patches() {
        let (b, _) = tilted_board(Surface::Patches);
        let img = render_screen_space(
            &b,
            &RefParams {
                radius: 1.0,
                rays: 64,
                ..Default::default()
            },
        )
        .unwrap();
        assert!(img.ao.iter().all(|a| *a == 1.0), "{:?}", img.ao);
    }
}
