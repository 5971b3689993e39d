//! Screen-space reference: the exact AO of the depth buffer, seen as a heightfield.
//!
//! The screen-space methods only know one depth per pixel. This module computes what a perfect
//! method could get from that depth buffer, so that a method's error against the ray-traced
//! reference splits into what the depth buffer cannot know (this image against the ray-traced
//! one) and what the method's sampling loses (the method against this image).
//!
//! The quantity is the ray-traced reference's binary visibility: the fraction of cosine-weighted
//! directions about the normal whose ray meets nothing within `radius` metres. The scene is
//! replaced by the depth buffer with infinite thickness: a ray point is blocked when it lies
//! behind the stored surface at its screen position.
//!
//! * **Surface.** Each pixel centre is lifted to view space from its linear depth. Between pixel
//!   centres the surface is the two triangles of each 2×2 cell (split along the cell's main
//!   diagonal) with *inverse* depth interpolated linearly in screen space: inverse depth is affine
//!   in screen space on any plane, so a planar surface is rebuilt exactly, and creases are cut
//!   by at most one pixel. The image's outer half-pixel border is outside the heightfield, and rays
//!   that leave the screen or cross the near plane see nothing more (the buffer knows nothing there).
//! * **Normal.** From the depth buffer, not the triangles: per axis the one-sided difference whose
//!   neighbour continues the pixel's own plane best (smallest error when the next two pixels
//!   predict its inverse depth), so normals do not bend across creases and silhouettes.
//! * **Dense march.** A ray segment (clipped to the near plane and the screen) is walked in screen
//!   space through every vertical, horizontal and diagonal cell edge it crosses, in order from the
//!   origin. Along the segment both the ray's and the surface's inverse depths are piecewise affine
//!   with breaks only at those edges, so comparing them at the edges and the two ends decides
//!   exactly whether the ray passes behind the surface: no mips and no skipped pixels.
//! * **Sampling.** The same per-pixel generator, stratified lattice, cosine mapping and
//!   self-intersection offset as the ray-traced reference (directions in view space).
//!
//! Sky pixels (depth not finite or not > 0) give ao = 1, std_error = 0, depth = +inf, as in
//! [`RefImage`]; they also never block a ray.

use std::path::Path;

use anyhow::{bail, Result};
use glam::DVec3;

use super::cache;
use super::hash::Fnv64;
use super::image::{shade_image, RefImage};
use super::params::{AoVariant, RefParams};
use super::sampling;
use crate::math::Camera;

/// Bump when the output for the same inputs changes, so stale cached images are not reused.
const SCREEN_ALGORITHM_VERSION: u32 = 1;

/// A depth buffer and the projection it was rendered with.
#[derive(Clone, Debug, PartialEq)]
pub struct DepthBuffer {
    pub width: u32,
    pub height: u32,
    /// View distance (−z_view, metres) at each pixel centre, rows top-down; `f32::INFINITY` (or
    /// anything not finite and > 0) for sky.
    pub linear_depth: Vec<f32>,
    /// Vertical field of view in degrees; the aspect ratio is width / height.
    pub fov_y_deg: f32,
    /// Near clip distance (metres): the buffer knows nothing closer.
    pub near: f32,
}

impl DepthBuffer {
    /// Checks the buffer's size and projection (clear errors instead of NaN later).
    fn validate(&self) -> Result<()> {
        let n = self.width as usize * self.height as usize;
        if self.linear_depth.len() != n {
            bail!(
                "depth buffer of {} values does not match its {}x{} size",
                self.linear_depth.len(),
                self.width,
                self.height
            );
        }
        if !(self.fov_y_deg > 0.0 && self.fov_y_deg < 180.0) {
            bail!(
                "field of view {}° of the depth buffer: use (0, 180)",
                self.fov_y_deg
            );
        }
        if !(self.near > 0.0 && self.near.is_finite()) {
            bail!("near plane {} of the depth buffer: use > 0", self.near);
        }
        Ok(())
    }

    /// The depth buffer of a ray-traced reference image (its `linear_depth`, same pixel centres).
    pub fn from_reference(img: &RefImage, cam: &Camera) -> DepthBuffer {
        DepthBuffer {
            width: img.width,
            height: img.height,
            linear_depth: img.linear_depth.clone(),
            fov_y_deg: cam.fov_y_deg,
            near: cam.near,
        }
    }

    /// Converts raw window-space depth values D in [0, 1] (rows top-down) written with `mode`'s
    /// projection and these planes; the mode's cleared value (1 for D32, 0 for reversed-Z) is sky.
    fn from_window_depth(
        width: u32,
        height: u32,
        window_depth: &[f32],
        mode: crate::math::DepthMode,
        fov_y_deg: f32,
        near: f32,
        far: f32,
    ) -> Result<DepthBuffer> {
        if !(far > near && far.is_finite()) {
            bail!("far plane {far} must be finite and beyond the near plane {near}");
        }
        let linear_depth = window_depth
            .iter()
            .map(|&d| {
                if d.is_finite() && (0.0..=1.0).contains(&d) && d != mode.clear_value() {
                    let z = crate::math::depth::linearize(mode, d as f64, near as f64, far as f64);
                    if z.is_finite() && z > 0.0 {
                        return z as f32;
                    }
                }
                f32::INFINITY
            })
            .collect();
        let buf = DepthBuffer {
            width,
            height,
            linear_depth,
            fov_y_deg,
            near,
        };
        buf.validate()?;
        Ok(buf)
    }

    /// The engine's full-resolution depth buffer at its current camera and size: renders the
    /// opaque pass (through the linear-depth view, which runs no AO method) and reads the main
    /// framebuffer's depth texture back.
    pub fn from_engine(engine: &mut crate::render::Engine) -> Result<DepthBuffer> {
        engine.render_values(crate::render::View::LinearDepth)?;
        let Some(tex) = engine.fbo_main.depth_texture() else {
            bail!("the engine's main framebuffer has no depth texture");
        };
        let (w, h) = (tex.width(), tex.height());
        let mut raw = tex.read_f32(0, 1);
        if let Some(e) = crate::gl::take_error(engine.gl()) {
            bail!("{e} while reading the depth buffer");
        }
        crate::gl::readback::flip_rows(&mut raw, w as usize, h as usize);
        let cam = engine.camera;
        let mode = engine.depth_mode();
        DepthBuffer::from_window_depth(w, h, &raw, mode, cam.fov_y_deg, cam.near, cam.far)
    }

    /// Stable content hash (every depth value's bits and the projection), for cache keys.
    fn content_hash(&self) -> u64 {
        let mut h = Fnv64::new();
        h.u32(self.width);
        h.u32(self.height);
        h.f32(self.fov_y_deg);
        h.f32(self.near);
        for d in &self.linear_depth {
            h.f32(*d);
        }
        h.0
    }
}

/// Inverse depths of the buffer and its projection, in f64.
struct Heightfield {
    w: usize,
    h: usize,
    /// 1 / depth per pixel (rows top-down); 0 for sky (a surface at infinity blocks nothing).
    inv: Vec<f64>,
    /// tan(fov/2) · aspect and tan(fov/2): view-space x/−z and y/−z at the image edges.
    sx: f64,
    sy: f64,
    near: f64,
    /// Distance from the eye beyond which no stored surface lies (for unbounded rays).
    max_dist: f64,
}

impl Heightfield {
    fn new(buf: &DepthBuffer) -> Heightfield {
        let (w, h) = (buf.width as usize, buf.height as usize);
        let sy = (buf.fov_y_deg as f64).to_radians() * 0.5;
        let sy = sy.tan();
        let sx = sy * w as f64 / h.max(1) as f64;
        let inv: Vec<f64> = buf
            .linear_depth
            .iter()
            .map(|&d| {
                if d.is_finite() && d > 0.0 {
                    1.0 / d as f64
                } else {
                    0.0
                }
            })
            .collect();
        let max_depth = buf
            .linear_depth
            .iter()
            .filter(|d| d.is_finite() && **d > 0.0)
            .fold(0.0f64, |m, d| m.max(*d as f64));
        Heightfield {
            w,
            h,
            inv,
            sx,
            sy,
            near: buf.near as f64,
            max_dist: max_depth * (1.0 + sx * sx + sy * sy).sqrt(),
        }
    }

    #[inline]
    fn inv_at(&self, i: usize, j: usize) -> f64 {
        self.inv[j * self.w + i]
    }

    /// View-space position of pixel (i, j)'s centre; `None` for sky.
    fn point(&self, i: usize, j: usize) -> Option<DVec3> {
        let inv = self.inv_at(i, j);
        if inv <= 0.0 {
            return None;
        }
        let ndc_x = 2.0 * (i as f64 + 0.5) / self.w as f64 - 1.0;
        let ndc_y = 1.0 - 2.0 * (j as f64 + 0.5) / self.h as f64;
        Some(DVec3::new(ndc_x * self.sx, ndc_y * self.sy, -1.0) / inv)
    }

    /// Grid coordinates (pixel centre (i, j) at (i, j)) and inverse depth of a view-space point
    /// in front of the camera.
    #[inline]
    fn project(&self, q: DVec3) -> (f64, f64, f64) {
        let inv = 1.0 / -q.z;
        let ndc_x = q.x * inv / self.sx;
        let ndc_y = q.y * inv / self.sy;
        (
            (ndc_x + 1.0) * 0.5 * self.w as f64 - 0.5,
            (1.0 - ndc_y) * 0.5 * self.h as f64 - 0.5,
            inv,
        )
    }

    /// Inverse depth of the triangulated surface at grid point (x, y), inside [0, w−1]×[0, h−1].
    #[inline]
    fn surface(&self, x: f64, y: f64) -> f64 {
        let i = (x.floor() as isize).clamp(0, self.w as isize - 2) as usize;
        let j = (y.floor() as isize).clamp(0, self.h as isize - 2) as usize;
        let (fx, fy) = (x - i as f64, y - j as f64);
        let a = self.inv_at(i, j);
        let d = self.inv_at(i + 1, j + 1);
        if fx >= fy {
            let b = self.inv_at(i + 1, j);
            a + fx * (b - a) + fy * (d - b)
        } else {
            let c = self.inv_at(i, j + 1);
            a + fy * (c - a) + fx * (d - c)
        }
    }

    /// Error of predicting pixel k's inverse depth from the next two pixels in direction `step`
    /// along one axis (`None` if the neighbour is missing or sky; large if only one exists).
    fn side_error(&self, at: &dyn Fn(isize) -> Option<f64>, step: isize) -> Option<f64> {
        let c = at(0)?;
        let n1 = at(step)?;
        Some(match at(2 * step) {
            Some(n2) => (c - (2.0 * n1 - n2)).abs(),
            None => f64::MAX,
        })
    }

    /// Unit normal at pixel (i, j) from the depth buffer, facing the camera (see the module docs).
    fn normal(&self, i: usize, j: usize, p: DVec3) -> DVec3 {
        let facing = -p.normalize_or(DVec3::Z);
        let tangent = |horizontal: bool| -> Option<DVec3> {
            let at = |k: isize| -> Option<f64> {
                let (x, y) = if horizontal {
                    (i as isize + k, j as isize)
                } else {
                    (i as isize, j as isize + k)
                };
                if x < 0 || y < 0 || x >= self.w as isize || y >= self.h as isize {
                    return None;
                }
                let v = self.inv_at(x as usize, y as usize);
                (v > 0.0).then_some(v)
            };
            let fwd = self.side_error(&at, 1);
            let back = self.side_error(&at, -1);
            let use_fwd = match (fwd, back) {
                (Some(f), Some(b)) => f <= b,
                (Some(_), None) => true,
                (None, Some(_)) => false,
                (None, None) => return None,
            };
            let (x, y) = match (horizontal, use_fwd) {
                (true, true) => (i + 1, j),
                (true, false) => (i - 1, j),
                (false, true) => (i, j + 1),
                (false, false) => (i, j - 1),
            };
            let q = self.point(x, y)?;
            Some(if use_fwd { q - p } else { p - q })
        };
        let n = match (tangent(true), tangent(false)) {
            (Some(tx), Some(ty)) => tx.cross(ty).try_normalize(),
            _ => None,
        };
        match n {
            Some(n) if n.dot(facing) < 0.0 => -n,
            Some(n) => n,
            // A pixel without usable neighbours on an axis: assume it faces the camera.
            None => facing,
        }
    }

    /// Whether the segment `o + t·d`, t in (0, t_max], passes behind the surface (see the
    /// module docs). `d` is a unit vector, `o` lies in front of the near plane.
    fn blocked(&self, o: DVec3, d: DVec3, t_max: f64) -> bool {
        if self.w < 2 || self.h < 2 {
            return false; // no cell between pixel centres: no surface to pass behind
        }
        // Beyond max_dist + |o| from o, every point is deeper than any stored surface, so the
        // first crossing (if any) happened before: the cap loses nothing.
        let mut t1 = t_max.min(2.0 * (self.max_dist + o.length()));
        let near_z = -self.near;
        if d.z > 0.0 {
            t1 = t1.min((near_z - o.z) / d.z);
        }
        if t1.is_nan() || t1 <= 0.0 || o.z > near_z {
            return false;
        }
        let (ax, ay, aw) = self.project(o);
        let (bx, by, bw) = self.project(o + d * t1);
        let (dx, dy, dw) = (bx - ax, by - ay, bw - aw);
        // Clip s in [0, 1] to the grid [0, w−1] × [0, h−1].
        let (mut s0, mut s1) = (0.0f64, 1.0f64);
        for (start, delta, hi) in [(ax, dx, (self.w - 1) as f64), (ay, dy, (self.h - 1) as f64)] {
            if delta == 0.0 {
                if start < 0.0 || start > hi {
                    return false;
                }
                continue;
            }
            let (ta, tb) = ((0.0 - start) / delta, (hi - start) / delta);
            s0 = s0.max(ta.min(tb));
            s1 = s1.min(ta.max(tb));
        }
        if s0.is_nan() || s1.is_nan() || s0 > s1 {
            return false;
        }
        let behind = |s: f64| -> bool {
            let x = (ax + s * dx).clamp(0.0, (self.w - 1) as f64);
            let y = (ay + s * dy).clamp(0.0, (self.h - 1) as f64);
            aw + s * dw < self.surface(x, y)
        };
        if behind(s0) {
            return true;
        }
        // The three families of cell edges the segment crosses: x = integer, y = integer,
        // x − y = integer. Each gives evenly spaced s; they are merged in increasing order.
        let mut families = [
            EdgeFamily::new(ax, dx, s0),
            EdgeFamily::new(ay, dy, s0),
            EdgeFamily::new(ax - ay, dx - dy, s0),
        ];
        loop {
            let (k, s) = families
                .iter()
                .enumerate()
                .map(|(k, f)| (k, f.next_s))
                .min_by(|a, b| a.1.total_cmp(&b.1))
                .unwrap();
            if s.is_nan() || s1.is_nan() || s >= s1 {
                break;
            }
            if behind(s) {
                return true;
            }
            families[k].advance();
        }
        behind(s1)
    }
}

/// The crossings of `u(s) = u0 + s·du` with the integers, in increasing s from `s_from`.
struct EdgeFamily {
    u0: f64,
    du: f64,
    /// Next integer to cross.
    k: f64,
    next_s: f64,
}

impl EdgeFamily {
    fn new(u0: f64, du: f64, s_from: f64) -> EdgeFamily {
        if du == 0.0 || !du.is_finite() {
            return EdgeFamily {
                u0,
                du,
                k: 0.0,
                next_s: f64::INFINITY,
            };
        }
        let u = u0 + s_from * du;
        let k = if du > 0.0 {
            u.floor() + 1.0
        } else {
            u.ceil() - 1.0
        };
        EdgeFamily {
            u0,
            du,
            k,
            next_s: (k - u0) / du,
        }
    }

    fn advance(&mut self) {
        self.k += self.du.signum();
        self.next_s = (self.k - self.u0) / self.du;
    }
}

/// Renders the screen-space reference of `depth` with the ray-traced reference's parameters
/// (visibility only: `Obscurance` is an error). Output layout as [`RefImage`].
pub fn render_screen_space(depth: &DepthBuffer, params: &RefParams) -> Result<RefImage> {
    depth.validate()?;
    if params.variant != AoVariant::Visibility {
        bail!("{}", rust_i18n::t!("reference.visibility_only"));
    }
    let field = Heightfield::new(depth);
    Ok(shade_image(
        depth.width,
        depth.height,
        "screen-space reference",
        params.progress,
        |x, y| shade_pixel(&field, x, y, params),
    ))
}

/// (ao, std_error, linear depth) of one pixel; `None` for sky.
fn shade_pixel(
    field: &Heightfield,
    x: usize,
    y: usize,
    params: &RefParams,
) -> Option<(f32, f32, f32)> {
    let p = field.point(x, y)?;
    let depth = (1.0 / field.inv_at(x, y)) as f32;
    if p.z > -field.near {
        return Some((1.0, 0.0, depth)); // closer than the near plane: the buffer cannot hold it
    }
    let radius = params.radius as f64;
    if radius.is_nan() || radius <= 0.0 {
        return Some((1.0, 0.0, depth));
    }
    let nrm = field.normal(x, y, p);
    // Same offset as the ray-traced reference: clears rounding at that distance.
    let origin = p + nrm * (1e-4 * p.length().max(1.0));
    let (tan, bit) = sampling::tangent_frame(nrm);
    let count = params.rays.max(1);
    let mut rng = sampling::Pcg32::for_pixel(params.seed, (y * field.w + x) as u64);
    let shift = (rng.next_f64(), rng.next_f64());
    let mut open = 0u32;
    for i in 0..count {
        let (u, v) = sampling::lattice_point(i, count, shift);
        let d = sampling::cosine_direction(nrm, tan, bit, u, v);
        if !field.blocked(origin, d, radius) {
            open += 1;
        }
    }
    let mean = open as f64 / count as f64;
    let se = (mean * (1.0 - mean) / count as f64).max(0.0).sqrt();
    Some((mean.clamp(0.0, 1.0) as f32, se as f32, depth))
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
        if (img.width, img.height) == (depth.width, depth.height) {
            return Ok(img);
        }
    }
    let img = render_screen_space(depth, params)?;
    cache::store_or_warn(cache_dir, &key, &img);
    Ok(img)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn buffer(w: u32, h: u32, f: impl Fn(u32, u32) -> f32) -> DepthBuffer {
        DepthBuffer {
            width: w,
            height: h,
            linear_depth: (0..h)
                .flat_map(|y| (0..w).map(move |x| (x, y)))
                .map(|(x, y)| f(x, y))
                .collect(),
            fov_y_deg: 60.0,
            near: 0.1,
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
}
