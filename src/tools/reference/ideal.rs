//! The idealised one-layer visibility: an independent check of the screen-space ceiling.
//!
//! What a screen-space method could know at unlimited resolution with one depth layer: a point is
//! solid when it lies in the view, behind the first surface its camera ray meets, and in front of
//! the nearest back face behind that surface (where the camera ray meets no back face behind it,
//! within the set thickness, in depth, of the surface, as the back-face ceiling assumes). Everything
//! comes from the scene's own triangles, traced with the reference's BVH, and not from any depth
//! buffer: no pixels, no reconstruction, the exact normal. The ceiling with planar patches
//! (`--surface patches`, geometric normals, back faces) rebuilds the same model from the engine's
//! pixels, so the two should agree up to what the pixels lose.
//!
//! Each pixel's rays are those of the ray-traced reference (same visible point, normal, offset,
//! lattice and generator), and each ray is tested at `steps` evenly spaced points within the radius;
//! a ray is blocked as soon as one point is solid. A board thinner than the spacing between two
//! points can be missed where a ray crosses it at a grazing angle.

use glam::DVec3;

use super::camera::{self, Frame};
use super::image::{footprint_mean, shade_image, RefImage};
use super::params::RefParams;
use super::sampling;
use super::scene::Scene;
use crate::math::Camera;

/// How many back faces beyond the first surface the search passes (front faces of other objects
/// between the surface and its back) before it gives up and uses the set thickness.
const MAX_FRONT_FACES_PASSED: usize = 8;

/// The idealised one-layer visibility of `cam`'s view (see the module docs): `thickness` (m, in
/// depth) where a surface has no back face behind it, `steps` points per ray.
pub fn render_ideal_one_layer(
    scene: &Scene,
    cam: &Camera,
    (width, height): (u32, u32),
    params: &RefParams,
    thickness: f32,
    steps: u32,
) -> RefImage {
    let Some(frame) = camera::frame(cam) else {
        return shade_image(width, height, "idealised one layer", false, |_, _| None);
    };
    let view = View {
        scene,
        frame: &frame,
        near: (cam.near as f64).max(0.0),
        far: cam.far as f64,
        aspect: width as f64 / height.max(1) as f64,
        thickness: thickness as f64,
    };
    shade_image(
        width,
        height,
        "idealised one layer",
        params.progress,
        |x, y| {
            let (x, y) = (x as u32, y as u32);
            let n = params.supersample;
            if n <= 1 {
                return shade_pixel(&view, x, y, (width, height), params, steps);
            }
            // The footprint's mean, as the ray-traced truth takes it (`trace.rs`).
            let sub = params.sub_pixel();
            let fine = (width.saturating_mul(n), height.saturating_mul(n));
            Some(footprint_mean(n, |i, j| {
                shade_pixel(&view, x * n + i, y * n + j, fine, &sub, steps).unwrap_or((
                    1.0,
                    0.0,
                    f32::INFINITY,
                ))
            }))
        },
    )
}

struct View<'a> {
    scene: &'a Scene,
    frame: &'a Frame,
    near: f64,
    far: f64,
    aspect: f64,
    thickness: f64,
}

impl View<'_> {
    /// Whether point `x` is inside the one-layer solid.
    fn solid(&self, x: DVec3) -> bool {
        let fr = self.frame;
        let v = x - fr.eye;
        let dist = v.length();
        if dist.is_nan() || dist <= 0.0 {
            return false;
        }
        let dir = v / dist;
        let cos = dir.dot(fr.f);
        if cos.is_nan() || cos <= 0.0 {
            return false;
        }
        // Outside the view nothing is known.
        let ndc_x = dir.dot(fr.s) / (cos * fr.tan_half * self.aspect);
        let ndc_y = dir.dot(fr.u) / (cos * fr.tan_half);
        if ndc_x.abs() > 1.0 || ndc_y.abs() > 1.0 || dist * cos < self.near {
            return false;
        }
        let (t_min, t_max) = (self.near / cos, self.far / cos);
        let Some(front) = self.scene.closest(fr.eye, dir, t_min, t_max, usize::MAX) else {
            return false;
        };
        if dist < front.t {
            return false;
        }
        // The nearest back face behind the surface (what the back-face pass keeps).
        let mut from = front;
        for _ in 0..MAX_FRONT_FACES_PASSED {
            match self.scene.closest(fr.eye, dir, from.t, t_max, from.kept) {
                Some(h) if self.scene.normal64(h.kept).dot(dir) > 0.0 => return dist <= h.t,
                Some(h) => from = h,
                None => break,
            }
        }
        dist <= front.t + self.thickness / cos
    }
}

/// (visibility, std error, linear depth) of pixel (x, y); `None` for sky.
fn shade_pixel(
    view: &View,
    x: u32,
    y: u32,
    (width, height): (u32, u32),
    params: &RefParams,
    steps: u32,
) -> Option<(f32, f32, f32)> {
    let fr = view.frame;
    let dir = fr.pixel_dir(x, y, width, height);
    let cos_axis = dir.dot(fr.f);
    if !dir.is_finite() || cos_axis.is_nan() || cos_axis <= 0.0 {
        return None;
    }
    let hit = view.scene.closest(
        fr.eye,
        dir,
        view.near / cos_axis,
        view.far / cos_axis,
        usize::MAX,
    )?;
    let depth = (hit.t * cos_axis) as f32;
    let radius = params.radius as f64;
    if radius.is_nan() || radius <= 0.0 {
        return Some((1.0, 0.0, depth));
    }
    // The reference's origin, normal and directions (trace.rs).
    let mut n = view.scene.normal64(hit.kept);
    if n.dot(-dir) < 0.0 {
        n = -n;
    }
    let origin = fr.eye + dir * hit.t + n * (1e-4 * hit.t.max(1.0));
    let (t, b) = sampling::tangent_frame(n);
    let count = params.rays.max(1);
    let mut rng = sampling::Pcg32::for_pixel(params.seed, y as u64 * width as u64 + x as u64);
    let shift = (rng.next_f64(), rng.next_f64());
    let steps = steps.max(1);
    let mut open = 0u32;
    for i in 0..count {
        let (u, v) = sampling::lattice_point(i, count, shift);
        let d = sampling::cosine_direction(n, t, b, u, v);
        let blocked =
            (0..steps).any(|k| view.solid(origin + d * (radius * (k as f64 + 0.5) / steps as f64)));
        if !blocked {
            open += 1;
        }
    }
    let mean = open as f64 / count as f64;
    let se = (mean * (1.0 - mean) / count as f64).max(0.0).sqrt();
    Some((mean as f32, se as f32, depth))
}

#[cfg(test)]
mod tests {
    use super::super::trace::render_reference;
    use super::*;
    use glam::Vec3;

    /// Two triangles of an axis-aligned rectangle at height `y` facing up (+y).
    fn quad_up(x0: f32, x1: f32, z0: f32, z1: f32, y: f32) -> [[Vec3; 3]; 2] {
        let (a, b, c, d) = (
            Vec3::new(x0, y, z0),
            Vec3::new(x1, y, z0),
            Vec3::new(x1, y, z1),
            Vec3::new(x0, y, z1),
        );
        // Counter-clockwise seen from above: normal (b − a) × (d − a) points up.
        [[a, d, b], [b, d, c]]
    }

    /// A closed box, every face wound outwards.
    fn cube(min: Vec3, max: Vec3) -> Vec<[Vec3; 3]> {
        let c = |x: bool, y: bool, z: bool| {
            Vec3::new(
                if x { max.x } else { min.x },
                if y { max.y } else { min.y },
                if z { max.z } else { min.z },
            )
        };
        let centre = (min + max) * 0.5;
        let faces = [
            [
                c(false, false, false),
                c(false, true, false),
                c(false, true, true),
                c(false, false, true),
            ],
            [
                c(true, false, false),
                c(true, true, false),
                c(true, true, true),
                c(true, false, true),
            ],
            [
                c(false, false, false),
                c(true, false, false),
                c(true, false, true),
                c(false, false, true),
            ],
            [
                c(false, true, false),
                c(true, true, false),
                c(true, true, true),
                c(false, true, true),
            ],
            [
                c(false, false, false),
                c(true, false, false),
                c(true, true, false),
                c(false, true, false),
            ],
            [
                c(false, false, true),
                c(true, false, true),
                c(true, true, true),
                c(false, true, true),
            ],
        ];
        let mut tris = Vec::new();
        for [a, b, cc, d] in faces {
            for mut tri in [[a, b, cc], [a, cc, d]] {
                let n = (tri[1] - tri[0]).cross(tri[2] - tri[0]);
                if n.dot(tri[0] - centre) < 0.0 {
                    tri.swap(1, 2);
                }
                tris.push(tri);
            }
        }
        tris
    }

    fn camera() -> Camera {
        Camera {
            eye: Vec3::new(0.0, 3.0, 4.0),
            target: Vec3::new(0.0, 0.0, 0.0),
            fov_y_deg: 50.0,
            near: 0.1,
            far: 100.0,
            ..Camera::default()
        }
    }

    fn params() -> RefParams {
        RefParams {
            radius: 1.0,
            rays: 32,
            seed: 7,
            ..Default::default()
        }
    }

    /// A closed box on a floor, all in view: everything a ray can meet is a visible surface or
    /// inside a box column, so the one-layer model is the scene and the image equals the ray-traced
    /// one (same rays) wherever the ray leaves no point unseen.
    #[test]
    fn a_box_on_a_floor_is_all_one_layer_knows() {
        let mut tris: Vec<[Vec3; 3]> = quad_up(-20.0, 20.0, -20.0, 20.0, 0.0).to_vec();
        tris.extend(cube(Vec3::new(-0.4, 0.0, -0.4), Vec3::new(0.4, 0.6, 0.4)));
        let scene = Scene::new(tris).unwrap();
        let size = (48, 36);
        let truth = render_reference(&scene, &camera(), size.0, size.1, &params());
        let ideal = render_ideal_one_layer(&scene, &camera(), size, &params(), 0.5, 256);
        let mse: f64 = truth
            .ao
            .iter()
            .zip(&ideal.ao)
            .map(|(a, b)| ((a - b) as f64).powi(2))
            .sum::<f64>()
            / truth.ao.len() as f64;
        let psnr = -10.0 * mse.log10();
        assert!(psnr > 35.0, "{psnr} dB");
        // The floor beside the box is occluded (not a trivially open image).
        assert!(ideal.ao.iter().any(|a| *a < 0.8));
    }

    /// A block hidden behind a wall is invisible to one layer: the floor beside it, seen past the
    /// wall's end, is darker in the ray-traced image than in the idealised one, and the idealised
    /// image is the same with and without the block.
    #[test]
    fn a_block_hidden_behind_a_wall_is_missed() {
        let mut tris: Vec<[Vec3; 3]> = quad_up(-20.0, 20.0, -20.0, 20.0, 0.0).to_vec();
        tris.extend(cube(
            Vec3::new(-0.5, 0.0, -0.025),
            Vec3::new(0.5, 1.0, 0.025),
        ));
        let wall_only = Scene::new(tris.clone()).unwrap();
        tris.extend(cube(Vec3::new(0.2, 0.0, -0.35), Vec3::new(0.5, 0.4, -0.1)));
        let scene = Scene::new(tris).unwrap();
        let size = (48, 36);
        let truth = render_reference(&scene, &camera(), size.0, size.1, &params());
        let ideal = render_ideal_one_layer(&scene, &camera(), size, &params(), 0.5, 256);
        let without = render_ideal_one_layer(&wall_only, &camera(), size, &params(), 0.5, 256);
        assert_eq!(ideal.ao, without.ao);
        let sum = |img: &RefImage| img.ao.iter().map(|a| *a as f64).sum::<f64>();
        assert!(
            sum(&truth) < sum(&ideal) - 1.0,
            "{} {}",
            sum(&truth),
            sum(&ideal)
        );
    }
}
