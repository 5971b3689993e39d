//! The screen-space reference with slabs of finite thickness (the model `vbao` uses) and with a
//! guard band, from depth buffers rendered on real Mesa GL, against closed forms.

use crate::common::*;
use crate::reference_screen::{
    assert_valid, crease_blocked, neighbourhood_on_screen, params, ref_camera, resolved,
};
use glam::Vec3;
use opengl3d::gl::mesh::MeshData;
use opengl3d::res::ResDirs;
use opengl3d::scene::{shapes, SceneDesc};
use opengl3d::tools::reference::{
    load_or_render_cached, render_screen_space, DepthBuffer, RefImage, Scene,
};
use std::f64::consts::PI;

/// Cosine-weighted fraction of directions about the normal of a wall point that end, after R
/// metres, beyond a line at distance `a` on the wall (towards −x) and at least `c` above the wall:
/// the unit disk that cosine-weighted directions project to, cut to the disk of radius
/// ρ₀ = √(1 − (c/R)²) (height ≥ c at R) and to the circular segment beyond a/R, over π.
pub(crate) fn slab_blocked(a: f64, c: f64, r: f64) -> f64 {
    let rho2 = 1.0 - (c / r).powi(2);
    if rho2 <= 0.0 {
        return 0.0;
    }
    let (rho, d) = (rho2.sqrt(), a / r);
    if d >= rho {
        return 0.0;
    }
    (rho2 * (d / rho).acos() - d * (rho2 - d * d).sqrt()) / PI
}

#[test]
fn slab_closed_form_reduces_to_the_crease() {
    // No height condition (c = 0): the crease's circular segment.
    for a in [0.0, 0.3, 0.7, 0.99] {
        assert!((slab_blocked(a, 0.0, 1.0) - crease_blocked(a, 1.0)).abs() < 1e-12);
    }
    assert_eq!(slab_blocked(0.1, 1.2, 1.0), 0.0);
    assert!((slab_blocked(0.0, 0.0, 1.0) - 0.5).abs() < 1e-12);
}

/// A wall facing the camera at depth 5 and, in front of it, a plate 2 cm thick covering the left
/// half of the view (its edge on the camera's axis), its back 2 m from the wall. Seen from the
/// camera, each wall point to the right of the plate at distance a from the edge line is blocked by
/// the slab model when its ray, after R, has crossed to x < 0 and risen to the slab's back.
#[test]
fn thin_plate_in_front_of_a_wall_matches_the_closed_form() {
    let ctx = context();
    let dir = temp_dir("slab-plate");
    let (w, h) = (128u32, 96u32);
    let mut wall = MeshData::default();
    shapes::add_box(
        &mut wall,
        Vec3::new(-20.0, -20.0, -6.0),
        Vec3::new(20.0, 20.0, -5.0),
    );
    let mut plate = MeshData::default();
    shapes::add_box(
        &mut plate,
        Vec3::new(-20.0, -20.0, -3.0),
        Vec3::new(0.0, 20.0, -2.98),
    );
    let mut desc = SceneDesc::default();
    desc.objects
        .push(object(&dir, "wall", &wall, Vec3::ZERO, Vec3::ONE));
    desc.objects
        .push(object(&dir, "plate", &plate, Vec3::ZERO, Vec3::ONE));
    desc.camera.eye = [0.0, 0.0, 0.0];
    desc.camera.target = [0.0, 0.0, -1.0];
    desc.camera.fov_y = 60.0;
    desc.output.width = w;
    desc.output.height = h;
    desc.bloom.enabled = false;
    let mut e = engine(&ctx, &desc);
    let depth = DepthBuffer::from_engine(&mut e).unwrap();
    let cam = ref_camera(&e);
    let radius = 1.0f32;
    let p = params(radius, 512);
    let scene = Scene::new(desc.world_triangles(&ResDirs::default()).unwrap()).unwrap();
    let rt = load_or_render_cached(&temp_dir("slab-plate-cache"), &scene, &cam, w, h, &p);
    // The slab's back lies at depth 2.98 + T: c = 5 − (2.98 + T) above the wall (0 when infinite).
    let footprint = 5.0 * 2.0 * (30.0f64.to_radians()).tan() / h as f64;
    let cases = [(0.1f32, 1.92f64), (1.52, 0.5), (f32::INFINITY, 0.0)];
    let mut open_means = Vec::new();
    for (thickness, c) in cases {
        let img = render_screen_space(&depth.clone().with_thickness(thickness), &p).unwrap();
        assert_valid(&img);
        let (mut checked, mut sum_err, mut sum_var, mut mean_ao) = (0usize, 0.0, 0.0, 0.0);
        for (i, q) in surface_points(&img, &cam) {
            // Wall points right of the edge, two and a half footprints clear of it, whose rays
            // (depth 4 to 5, within R) stay on the screen.
            let a = q.x as f64;
            if (q.z + 5.0).abs() > 1e-3
                || a < 2.5 * footprint
                || a + 1.0 > 3.0
                || q.y.abs() + 1.0 > 2.25
            {
                continue;
            }
            let want = 1.0 - slab_blocked(a, c, radius as f64);
            let (ao, se) = (img.ao[i] as f64, img.std_error[i] as f64);
            if c > radius as f64 {
                // Nothing within reach: every ray is open, exactly, as in the ray-traced truth.
                assert_eq!(ao, 1.0, "T {thickness}: wall pixel {i} at {q}");
                assert_eq!(rt.ao[i], 1.0, "ray-traced pixel {i} at {q}");
            }
            assert!(
                (ao - want).abs() <= 4.0 * se + 0.03,
                "T {thickness}: pixel {i} at {q}: ao {ao} vs {want} (se {se})"
            );
            checked += 1;
            sum_err += ao - want;
            sum_var += se * se;
            mean_ao += ao;
        }
        assert!(
            checked > 300,
            "T {thickness}: only {checked} pixels checked"
        );
        let n = checked as f64;
        assert!(
            (sum_err / n).abs() <= 4.0 * sum_var.sqrt() / n + 0.005,
            "T {thickness}: mean error {} over {n} pixels",
            sum_err / n
        );
        open_means.push(mean_ao / n);
    }
    // Thicker slabs close more of the wall beside the plate.
    assert!(
        open_means[0] > open_means[1] + 0.02 && open_means[1] > open_means[2] + 0.02,
        "{open_means:?}"
    );
}

/// The largest depth difference between the pixels of one cell of the depth buffer (2×2 pixel
/// centres), over the cells a ray of length `reach` from a surface point no deeper than `deepest`
/// can enter: the thickness the slabs need for every such cell to be solid.
fn needed_thickness(depth: &DepthBuffer, deepest: f32, reach: f32) -> f32 {
    let (w, h) = (depth.width as usize, depth.height as usize);
    let mut need = 0.0f32;
    for j in 0..h - 1 {
        for i in 0..w - 1 {
            let c = [(i, j), (i + 1, j), (i, j + 1), (i + 1, j + 1)]
                .map(|(x, y)| depth.linear_depth[y * w + x]);
            let lo = c.iter().copied().fold(f32::INFINITY, f32::min);
            let hi = c.iter().copied().fold(0.0f32, f32::max);
            if hi.is_finite() && lo <= deepest + reach {
                need = need.max(hi - lo);
            }
        }
    }
    need
}

/// Floor and wall meeting at 90°, seen from above so that neighbouring pixels are close in depth:
/// with slabs at least as thick as the largest step between neighbouring pixels the rays can
/// reach, every triangle is solid and the slabs give the crease's closed form, as the heightfield
/// does. Thinner slabs leave the steepest cells open, and rays leak through them (brighter).
#[test]
fn crease_stays_exact_with_enough_thickness() {
    let ctx = context();
    let dir = temp_dir("slab-crease");
    let (w, h) = (96u32, 72u32);
    let mut desc = crease_scene(
        &dir,
        Vec3::new(2.2, 3.4, 2.4),
        Vec3::new(0.3, 0.3, 0.0),
        w,
        h,
    );
    desc.camera.fov_y = 70.0;
    let mut e = engine(&ctx, &desc);
    let depth = DepthBuffer::from_engine(&mut e).unwrap();
    let cam = ref_camera(&e);
    let vp = e.camera.view_projection(w as f32 / h as f32);
    let dist = |p: Vec3| p.x.max(p.y).max(0.0) as f64;
    let radius = 1.0f32;
    let checked_points = |img: &RefImage| -> Vec<(usize, Vec3)> {
        surface_points(img, &cam)
            .into_iter()
            .filter(|(_, p)| {
                neighbourhood_on_screen(&vp, cam.near, w, h, *p, radius)
                    && resolved(&cam, h, *p, radius)
            })
            .collect()
    };
    let probe = render_screen_space(&depth, &params(radius, 1)).unwrap();
    let deepest = checked_points(&probe)
        .iter()
        .map(|(i, _)| probe.linear_depth[*i])
        .fold(0.0f32, f32::max);
    let need = needed_thickness(&depth, deepest, radius);
    assert!(
        need > 0.0 && need < radius,
        "this view's steepest cell: {need} m"
    );
    let mut mean_errors = Vec::new();
    for thickness in [need / 4.0, need, 2.0 * radius] {
        let img = render_screen_space(
            &depth.clone().with_thickness(thickness),
            &params(radius, 512),
        )
        .unwrap();
        assert_valid(&img);
        let (mut checked, mut sum_err, mut sum_var) = (0usize, 0.0f64, 0.0f64);
        for (i, p) in checked_points(&img) {
            let want = 1.0 - crease_blocked(dist(p), radius as f64);
            let (ao, se) = (img.ao[i] as f64, img.std_error[i] as f64);
            if thickness >= need {
                assert!(
                    (ao - want).abs() <= 4.0 * se + 0.03,
                    "T {thickness}: pixel {i} at {p}: ao {ao} vs {want} (se {se})"
                );
            }
            checked += 1;
            sum_err += ao - want;
            sum_var += se * se;
        }
        assert!(
            checked > 100,
            "T {thickness}: only {checked} pixels checked"
        );
        let mean = sum_err / checked as f64;
        let bound = 4.0 * sum_var.sqrt() / checked as f64 + 0.005;
        if thickness >= need {
            assert!(mean.abs() <= bound, "T {thickness}: mean error {mean}");
        }
        mean_errors.push((mean, bound));
    }
    let (leak, bound) = mean_errors[0];
    assert!(
        leak > bound,
        "T = need / 4 = {}: mean error {leak}",
        need / 4.0
    );
}

/// An open floor seen horizontally, and a pillar standing on it just beyond the right edge of the
/// screen: without a guard band the depth buffer knows nothing of it and the floor is open; with
/// one, the floor beside it is occluded about as much as the ray tracer finds.
#[test]
fn guard_band_lets_an_off_screen_pillar_occlude() {
    let ctx = context();
    let dir = temp_dir("slab-guard");
    let (w, h) = (96u32, 54u32);
    let mut pillar = MeshData::default();
    // Its inner face x = 3.4 projects beyond the right edge (x / depth > tan 30° · 16/9) at every
    // depth of the pillar (2.8 to 3.2).
    shapes::add_box(
        &mut pillar,
        Vec3::new(3.4, 0.0, -3.2),
        Vec3::new(3.8, 2.0, -2.8),
    );
    let mut desc = SceneDesc::default();
    desc.objects.push(object(
        &dir,
        "floor",
        &shapes::ground(50.0, 10),
        Vec3::ZERO,
        Vec3::ONE,
    ));
    desc.objects
        .push(object(&dir, "pillar", &pillar, Vec3::ZERO, Vec3::ONE));
    desc.camera.eye = [0.0, 1.0, 0.0];
    desc.camera.target = [0.0, 1.0, -1.0];
    desc.camera.fov_y = 60.0;
    desc.output.width = w;
    desc.output.height = h;
    desc.bloom.enabled = false;
    let mut e = engine(&ctx, &desc);
    let plain = DepthBuffer::from_engine(&mut e).unwrap();
    let camera = e.camera;
    let guard = 24;
    let wide = DepthBuffer::from_engine_with_guard_band(&mut e, guard).unwrap();
    // The engine is left as it was; the wide buffer's inner pixels have the same centres.
    assert_eq!(e.size(), (w, h));
    assert_eq!(e.camera, camera);
    assert_eq!((wide.width, wide.height), (w + 2 * guard, h + 2 * guard));
    assert_eq!(wide.visible_size(), (w, h));
    let g = guard as usize;
    for y in 0..h as usize {
        for x in 0..w as usize {
            let a = plain.linear_depth[y * w as usize + x];
            let b = wide.linear_depth[(y + g) * wide.width as usize + x + g];
            assert_eq!(a.is_finite(), b.is_finite(), "pixel {x},{y}: {a} vs {b}");
            if a.is_finite() {
                assert!((a - b).abs() <= 1e-4 * a, "pixel {x},{y}: {a} vs {b}");
            }
        }
    }
    // The pillar is in the guard band only.
    let off_screen_nearer = (0..wide.height as usize)
        .flat_map(|y| (0..wide.width as usize).map(move |x| (x, y)))
        .filter(|(x, _)| *x >= g + w as usize)
        .any(|(x, y)| {
            let d = wide.linear_depth[y * wide.width as usize + x];
            d.is_finite() && d < 3.3 && y < g + h as usize / 2
        });
    assert!(off_screen_nearer, "the pillar must be in the guard band");

    let p = params(1.0, 256);
    let without = render_screen_space(&plain, &p).unwrap();
    let with = render_screen_space(&wide, &p).unwrap();
    assert_valid(&with);
    assert_eq!((with.width, with.height), (w, h));
    let cam = ref_camera(&e);
    let scene = Scene::new(desc.world_triangles(&ResDirs::default()).unwrap()).unwrap();
    let rt = load_or_render_cached(&temp_dir("slab-guard-cache"), &scene, &cam, w, h, &p);
    let (mut near, mut far) = (Vec::new(), Vec::new());
    for (i, q) in surface_points(&without, &cam) {
        assert_eq!(without.ao[i], 1.0, "without a guard band: pixel {i} at {q}");
        if q.y.abs() > 1e-3 {
            continue;
        }
        // Near: beside and in front of the pillar, where its visible faces are all there is
        // within R (behind it the heightfield adds its shadow). Far: more than R from the pillar
        // and from that shadow, which projects beyond the right edge at every depth.
        if q.x > 2.6 && (-3.2..=-2.5).contains(&q.z) {
            near.push(i);
        } else if q.x < 1.5 {
            far.push(i);
        }
    }
    assert!(
        near.len() >= 5 && far.len() > 500,
        "{} near, {} far",
        near.len(),
        far.len()
    );
    let truth = mean_over(&rt, &near);
    assert!(
        truth < 0.97,
        "the pillar must occlude the floor near it: {truth}"
    );
    let seen = mean_over(&with, &near);
    assert!(seen < 0.99, "with the guard band: {seen}");
    assert!(
        (seen - truth).abs() < 0.05,
        "with the guard band {seen}, ray-traced {truth}"
    );
    for i in far {
        assert_eq!(with.ao[i], 1.0, "far from the pillar: pixel {i}");
    }
}

#[test]
fn cli_takes_thickness_and_guard_band_for_the_screen_space_reference() {
    let dir = temp_dir("slab-cli");
    let out = dir.join("ss.pfm");
    let o = run(&[
        "reference",
        "--screen-space",
        "--thickness",
        "0.3",
        "--guard-band",
        "8",
        "--width",
        "32",
        "--height",
        "18",
        "--rays",
        "4",
        "--radius",
        "0.5",
        "--out",
        out.to_str().unwrap(),
        "--cache",
        dir.join("cache").to_str().unwrap(),
    ]);
    let stdout = String::from_utf8_lossy(&o.stdout);
    assert!(o.status.success(), "{stdout}\n{}", stderr(&o));
    assert!(
        stdout.contains("slabs 0.3 m thick") && stdout.contains("guard band 8 px"),
        "{stdout}"
    );
    // The output is the visible size, not the guard band's.
    assert!(std::fs::read(&out).unwrap().starts_with(b"Pf\n32 18\n"));
    fails_with(
        &["reference", "--thickness", "0.3", "--rays", "4"],
        &["--thickness", "--screen-space"],
    );
    fails_with(&["reference", "--guard-band", "8"], &["--screen-space"]);
    fails_with(
        &[
            "reference",
            "--screen-space",
            "--guard-band",
            "9000",
            "--rays",
            "4",
        ],
        &["guard band"],
    );
}
