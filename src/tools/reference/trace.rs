//! Ground-truth ambient occlusion by world-space ray tracing on the CPU.
//!
//! The screen-space AO techniques of the course are approximations; this module computes what
//! they approximate, so they can be compared per pixel.
//!
//! For every pixel a primary ray from the eye through the pixel centre finds the visible surface
//! (the first hit whose view depth lies in `[near, far]`, like the GL clip planes). At that point
//! `p`, with the geometric normal `n` of the hit triangle turned towards the camera, `rays`
//! cosine-weighted directions are traced from `p + n * eps`, where
//! `eps = 1e-4 * max(1, |p - eye|)` metres: large enough to clear f32 rounding of the hit point
//! at that distance, small enough not to open visible gaps in creases.
//!
//! * [`AoVariant::Visibility`]: ao = fraction of rays with no hit within `radius`.
//! * [`AoVariant::Obscurance`]: each ray scores 1 on a miss and `(t / radius)^2` (clamped to
//!   `[0, 1]`) for a hit at distance `t`; ao = mean score.
//!
//! Sampling is deterministic: each pixel has its own generator seeded from
//! `(params.seed, pixel index)`, so results do not depend on thread scheduling. The `rays`
//! directions of a pixel form a randomly shifted 2-D lattice (stratified; see
//! `sampling.rs`), which is unbiased with much lower variance than independent samples; the
//! reported `std_error` uses the independent-sample formula and is therefore conservative.
//!
//! Sky pixels (no surface in `[near, far]`) get ao = 1, std_error = 0, depth = +inf.
//! Outputs never contain NaN: degenerate triangles are dropped by [`Scene::new`], and degenerate
//! cameras / parameters fall back to the documented defaults below.

use super::camera::{self, Frame};
use super::image::{footprint_mean, shade_image, RefImage};
use super::params::{AoVariant, RefParams};
use super::sampling;
use super::scene::Scene;
use crate::math::Camera;
use std::sync::atomic::{AtomicBool, Ordering};

/// Per-pixel result: (ao, std_error, linear_depth).
type PixelOut = (f32, f32, f32);
const SKY: PixelOut = (1.0, 0.0, f32::INFINITY);

/// Renders the reference AO image. Never panics on odd input: a zero width or height gives
/// empty buffers, an unusable camera (non-finite eye, fov outside (0, 180)) gives all sky.
pub fn render_reference(
    scene: &Scene,
    cam: &Camera,
    width: u32,
    height: u32,
    params: &RefParams,
) -> RefImage {
    render_reference_watched(scene, cam, width, height, params, &|| true)
}

/// [`render_reference`] that calls `row_done` after each row and leaves the remaining pixels sky
/// once it returns false (the window's progress bar, and a trace nobody waits for any more).
pub fn render_reference_watched(
    scene: &Scene,
    cam: &Camera,
    width: u32,
    height: u32,
    params: &RefParams,
    row_done: &(dyn Fn() -> bool + Sync),
) -> RefImage {
    let Some(frame) = camera::frame(cam) else {
        // A camera with no usable frame: nothing to trace (all sky).
        return shade_image(width, height, "reference AO", false, |_, _| None);
    };
    let stopped = AtomicBool::new(false);
    shade_image(width, height, "reference AO", params.progress, |x, y| {
        if stopped.load(Ordering::Relaxed) {
            return None;
        }
        let (x, y) = (x as u32, y as u32);
        let pixel = if params.supersample > 1 {
            shade_footprint(scene, &frame, cam, x, y, width, height, params)
        } else {
            shade_pixel(scene, &frame, cam, x, y, width, height, params)
        };
        if x + 1 == width && !row_done() {
            stopped.store(true, Ordering::Relaxed);
        }
        Some(pixel)
    })
}

/// Pixel (x, y) of the image [`render_reference`] renders, alone: (ao, std_error, linear depth);
/// `None` for a camera without a usable frame. The GPU reference's cross-check traces a sample of
/// its pixels this way.
pub(super) fn trace_pixel(
    scene: &Scene,
    cam: &Camera,
    (x, y): (u32, u32),
    (width, height): (u32, u32),
    params: &RefParams,
) -> Option<(f32, f32, f32)> {
    let frame = camera::frame(cam)?;
    Some(if params.supersample > 1 {
        shade_footprint(scene, &frame, cam, x, y, width, height, params)
    } else {
        shade_pixel(scene, &frame, cam, x, y, width, height, params)
    })
}

/// The mean over pixel (x, y)'s footprint ([`footprint_mean`]): the `n`×`n` pixels an image `n`
/// times wider and taller has there, each traced as [`shade_pixel`] traces a pixel, with
/// `rays / n²` rays (rounded up).
#[allow(clippy::too_many_arguments)]
fn shade_footprint(
    scene: &Scene,
    frame: &Frame,
    cam: &Camera,
    x: u32,
    y: u32,
    width: u32,
    height: u32,
    params: &RefParams,
) -> PixelOut {
    let n = params.supersample;
    let sub = params.sub_pixel();
    let (fine_w, fine_h) = (width.saturating_mul(n), height.saturating_mul(n));
    footprint_mean(n, |i, j| {
        shade_pixel(
            scene,
            frame,
            cam,
            x * n + i,
            y * n + j,
            fine_w,
            fine_h,
            &sub,
        )
    })
}

#[allow(clippy::too_many_arguments)]
fn shade_pixel(
    scene: &Scene,
    frame: &Frame,
    cam: &Camera,
    x: u32,
    y: u32,
    width: u32,
    height: u32,
    params: &RefParams,
) -> PixelOut {
    let dir = frame.pixel_dir(x, y, width, height);
    // cos of the angle to the view axis converts view depth <-> distance along the ray.
    let cos_axis = dir.dot(frame.f);
    if !dir.is_finite() || cos_axis.is_nan() || cos_axis <= 0.0 {
        return SKY;
    }
    let near = (cam.near as f64).max(0.0);
    let far = cam.far as f64; // NaN far -> no valid range -> sky
    let Some(hit) = scene.closest(frame.eye, dir, near / cos_axis, far / cos_axis, usize::MAX)
    else {
        return SKY;
    };
    let depth = (hit.t * cos_axis) as f32;
    let p = frame.eye + dir * hit.t;

    // Geometric normal, turned towards the viewer (the course meshes are not consistently
    // wound, and AO is wanted on whichever side is seen).
    let mut nrm = scene.normal64(hit.kept);
    if nrm.dot(-dir) < 0.0 {
        nrm = -nrm;
    }
    let radius = params.radius as f64;
    if radius.is_nan() || radius <= 0.0 {
        return (1.0, 0.0, depth); // nothing can occlude within a zero radius
    }
    let eps = 1e-4 * hit.t.max(1.0);
    let origin = p + nrm * eps;
    let (tan, bit) = sampling::tangent_frame(nrm);

    let count = params.rays.max(1);
    let pixel_index = y as u64 * width as u64 + x as u64;
    let mut rng = sampling::Pcg32::for_pixel(params.seed, pixel_index);
    let shift = (rng.next_f64(), rng.next_f64());

    // Accumulate score and squared score (f64: N can be large).
    let (mut sum, mut sum_sq) = (0.0f64, 0.0f64);
    for i in 0..count {
        let (u, v) = sampling::lattice_point(i, count, shift);
        let d = sampling::cosine_direction(nrm, tan, bit, u, v);
        // The hit triangle itself is skipped: a ray leaving its front side cannot meet it.
        let score = match params.variant {
            AoVariant::Visibility => {
                if scene.occluded(origin, d, 0.0, radius, hit.kept) {
                    0.0
                } else {
                    1.0
                }
            }
            AoVariant::Obscurance => match scene.closest(origin, d, 0.0, radius, hit.kept) {
                None => 1.0,
                Some(h) => {
                    let r = h.t / radius; // radius > 0; infinite radius gives 0
                    (r * r).clamp(0.0, 1.0)
                }
            },
        };
        sum += score;
        sum_sq += score * score;
    }
    let nf = count as f64;
    let mean = sum / nf;
    let se = match params.variant {
        AoVariant::Visibility => (mean * (1.0 - mean) / nf).max(0.0).sqrt(),
        AoVariant::Obscurance => {
            if count < 2 {
                0.0
            } else {
                let var = ((sum_sq - sum * mean) / (nf - 1.0)).max(0.0);
                (var / nf).sqrt()
            }
        }
    };
    (mean.clamp(0.0, 1.0) as f32, se as f32, depth)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::tools::reference::camera::{pixel_dir, view_direction};
    use crate::tools::reference::image::footprint_mean;
    use glam::Vec3;

    /// Two triangles forming the square [-s, s]^2 in the plane z = z0 (facing +Z).
    fn quad_z(z0: f32, s: f32) -> Vec<[Vec3; 3]> {
        let a = Vec3::new(-s, -s, z0);
        let b = Vec3::new(s, -s, z0);
        let c = Vec3::new(s, s, z0);
        let d = Vec3::new(-s, s, z0);
        vec![[a, b, c], [a, c, d]]
    }

    fn cam_down_neg_z(near: f32, far: f32) -> Camera {
        Camera {
            eye: Vec3::ZERO,
            target: Vec3::NEG_Z,
            up: Vec3::Y,
            fov_y_deg: 60.0,
            near,
            far,
        }
    }

    fn params() -> RefParams {
        RefParams {
            radius: 1.0,
            rays: 4,
            ..Default::default()
        }
    }

    #[test]
    fn linear_depth_of_facing_plane_is_its_distance() {
        let scene = Scene::new(quad_z(-7.5, 100.0)).unwrap();
        let img = render_reference(&scene, &cam_down_neg_z(0.1, 100.0), 9, 6, &params());
        for &d in &img.linear_depth {
            assert!((d - 7.5).abs() < 1e-5, "depth {d}");
        }
        // Off-axis: a camera looking along +X at the plane x = 4 (depth 4 everywhere).
        let scene = Scene::new(
            quad_z(0.0, 100.0)
                .into_iter()
                .map(|t| t.map(|v| Vec3::new(4.0, v.y, v.x)))
                .collect(),
        )
        .unwrap();
        let cam = Camera {
            target: Vec3::X,
            ..cam_down_neg_z(0.1, 100.0)
        };
        let img = render_reference(&scene, &cam, 7, 5, &params());
        for &d in &img.linear_depth {
            assert!((d - 4.0).abs() < 1e-5, "depth {d}");
        }
        // Oblique view of the same plane: ray length 4 / dir.x, depth = length * cos(axis).
        let cam = Camera {
            target: Vec3::new(1.0, 0.3, 0.2),
            ..cam
        };
        let img = render_reference(&scene, &cam, 7, 5, &params());
        for y in 0..5 {
            for x in 0..7 {
                let dir = pixel_dir(&cam, x, y, 7, 5).unwrap();
                let expected = 4.0 / dir.x * dir.dot(view_direction(&cam));
                let d = img.linear_depth[img.index(x, y)];
                assert!(
                    (d - expected).abs() < 1e-5 * expected,
                    "depth {d} vs {expected}"
                );
            }
        }
    }

    #[test]
    fn near_and_far_clip_like_gl() {
        // A plane beyond `far` is sky; one closer than `near` is looked through.
        let scene = Scene::new(quad_z(-50.0, 1000.0)).unwrap();
        let img = render_reference(&scene, &cam_down_neg_z(0.1, 40.0), 4, 4, &params());
        assert!(img.sky_mask().iter().all(|&s| s));
        assert!(img.ao.iter().all(|&a| a == 1.0) && img.std_error.iter().all(|&e| e == 0.0));
        assert_eq!(img.mean_std_error(), 0.0);

        let mut tris = quad_z(-0.05, 1000.0);
        tris.extend(quad_z(-3.0, 1000.0));
        let scene = Scene::new(tris).unwrap();
        let img = render_reference(&scene, &cam_down_neg_z(0.1, 40.0), 4, 4, &params());
        for &d in &img.linear_depth {
            assert!((d - 3.0).abs() < 1e-5, "depth {d}");
        }
    }

    #[test]
    fn pixel_layout_row_zero_is_top() {
        let cam = cam_down_neg_z(0.1, 10.0);
        let top = pixel_dir(&cam, 0, 0, 4, 4).unwrap();
        let bottom = pixel_dir(&cam, 0, 3, 4, 4).unwrap();
        assert!(top.y > 0.0 && bottom.y < 0.0 && top.x < 0.0);
        // Pixel centre of a 1x1 image is the view axis.
        assert!((pixel_dir(&cam, 0, 0, 1, 1).unwrap() - Vec3::NEG_Z).length() < 1e-6);
    }

    #[test]
    fn render_is_deterministic() {
        let mut tris = quad_z(-2.0, 10.0);
        tris.push([
            Vec3::new(0.0, 0.0, -2.0),
            Vec3::new(1.0, 0.0, -1.0),
            Vec3::new(0.0, 1.0, -1.5),
        ]);
        let scene = Scene::new(tris).unwrap();
        let p = RefParams {
            rays: 16,
            seed: 3,
            ..params()
        };
        let a = render_reference(&scene, &cam_down_neg_z(0.1, 100.0), 8, 8, &p);
        let b = render_reference(&scene, &cam_down_neg_z(0.1, 100.0), 8, 8, &p);
        assert_eq!(a, b);
        assert!(a.ao.iter().any(|&v| v < 1.0));
    }

    #[test]
    fn a_footprint_is_the_box_average_of_the_larger_image() {
        // A floor with a thin post standing on it: pixels the post crosses are partly open floor.
        let mut tris = quad_z(-3.0, 10.0);
        let post = |x0: f32| {
            let (a, b) = (
                Vec3::new(x0, -10.0, -2.6),
                Vec3::new(x0 + 0.03, -10.0, -2.6),
            );
            let (c, d) = (Vec3::new(x0 + 0.03, 10.0, -2.6), Vec3::new(x0, 10.0, -2.6));
            [[a, b, c], [a, c, d]]
        };
        tris.extend(post(0.1));
        let scene = Scene::new(tris).unwrap();
        let cam = cam_down_neg_z(0.1, 100.0);
        let n = 3;
        let fine = render_reference(
            &scene,
            &cam,
            8 * n,
            6 * n,
            &RefParams {
                rays: 4,
                ..params()
            },
        );
        let wide = RefParams {
            rays: 4 * n * n,
            supersample: n,
            ..params()
        };
        let mean = render_reference(&scene, &cam, 8, 6, &wide);
        // Each sub-pixel is traced as the larger image's pixel, with its seed: the same rays.
        for y in 0..6 {
            for x in 0..8 {
                let mut sum = 0.0;
                for j in 0..n {
                    for i in 0..n {
                        sum += fine.ao[fine.index(x * n + i, y * n + j)];
                    }
                }
                let expected = sum / (n * n) as f32;
                let got = mean.ao[mean.index(x, y)];
                assert!(
                    (got - expected).abs() < 1e-6,
                    "({x}, {y}): {got} vs {expected}"
                );
            }
        }
        // Some pixel is neither all post nor all floor: the share the centre alone cannot give.
        let centre = render_reference(
            &scene,
            &cam,
            8,
            6,
            &RefParams {
                rays: 36,
                ..params()
            },
        );
        assert!(mean.ao != centre.ao);
    }

    #[test]
    fn a_footprint_is_sky_when_half_of_it_is_and_takes_the_central_depth() {
        // 2x2 sub-pixels: two sky, two surfaces at depths 5 (nearer the centre: all are equally
        // near, the first wins) and 7.
        let subs = [
            (0.5, 0.1, 5.0),
            (1.0, 0.0, f32::INFINITY),
            (1.0, 0.0, f32::INFINITY),
            (0.5, 0.1, 7.0),
        ];
        let (ao, se, depth) = footprint_mean(2, |i, j| subs[(j * 2 + i) as usize]);
        assert!(
            (ao - 0.75).abs() < 1e-6 && depth.is_infinite(),
            "{ao} {depth}"
        );
        assert!((se - (0.02f32).sqrt() / 4.0).abs() < 1e-6, "{se}");
        // One sky sub-pixel of four: a surface, at the depth nearest the centre.
        let subs = [
            (0.5, 0.0, 5.0),
            (1.0, 0.0, f32::INFINITY),
            (0.2, 0.0, 6.0),
            (0.5, 0.0, 7.0),
        ];
        let (ao, _, depth) = footprint_mean(2, |i, j| subs[(j * 2 + i) as usize]);
        assert!((ao - 0.55).abs() < 1e-6 && depth == 5.0, "{ao} {depth}");
        // 3x3: the middle sub-pixel's depth, though a corner is nearer the camera.
        let (_, _, depth) = footprint_mean(3, |i, j| {
            (1.0, 0.0, if (i, j) == (1, 1) { 9.0 } else { 2.0 })
        });
        assert_eq!(depth, 9.0);
    }
}
