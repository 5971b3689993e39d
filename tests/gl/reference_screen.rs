//! The screen-space reference (exact AO of the depth buffer as a heightfield), computed from the
//! engine's depth buffer rendered on real Mesa GL, against closed forms and the ray-traced
//! reference. Pixels are only checked where every point within R of the surface point projects
//! inside the image (the depth buffer knows nothing outside it).

use crate::common::*;
use glam::{Mat4, Vec3, Vec4};
use opengl3d::math::Camera;
use opengl3d::render::Engine;
use opengl3d::res::ResDirs;
use opengl3d::scene::{shapes, SceneDesc};
use opengl3d::tools::reference::{
    load_or_render_cached, load_or_render_screen_cached, render_screen_space, screen_cache_key,
    AoVariant, DepthBuffer, RefImage, RefParams, Scene,
};
use std::f64::consts::PI;

pub(crate) fn params(radius: f32, rays: u32) -> RefParams {
    RefParams {
        radius,
        rays,
        variant: AoVariant::Visibility,
        seed: 5,
        progress: false,
        supersample: 1,
    }
}

pub(crate) fn ref_camera(e: &Engine) -> Camera {
    Camera {
        up: Vec3::Y,
        ..e.camera
    }
}

/// Whether the cube of half-side `r` around `p` (and so the ball of radius r) projects inside
/// the image with a one-pixel margin, entirely beyond the near plane.
pub(crate) fn neighbourhood_on_screen(
    vp: &Mat4,
    near: f32,
    w: u32,
    h: u32,
    p: Vec3,
    r: f32,
) -> bool {
    let (mx, my) = (1.0 - 2.0 / w as f32, 1.0 - 2.0 / h as f32);
    (0..8).all(|k| {
        let c = p + Vec3::new(
            if k & 1 == 0 { -r } else { r },
            if k & 2 == 0 { -r } else { r },
            if k & 4 == 0 { -r } else { r },
        );
        let clip = *vp * Vec4::new(c.x, c.y, c.z, 1.0);
        clip.w > near && (clip.x / clip.w).abs() < mx && (clip.y / clip.w).abs() < my
    })
}

/// Size of pixel `p`'s footprint on the crease scene's surfaces (floor y = 0 or wall x = 0): the
/// depth buffer resolves nothing finer, so the heightfield cuts the crease by about this much.
pub(crate) fn crease_footprint(cam: &Camera, h: u32, p: Vec3) -> f32 {
    let normal = if p.y.abs() < p.x.abs() {
        Vec3::Y
    } else {
        Vec3::X
    };
    let to_p = p - cam.eye;
    let across = to_p.length() * 2.0 * (cam.fov_y_deg.to_radians() * 0.5).tan() / h as f32;
    across / to_p.normalize().dot(normal).abs().max(1e-3)
}

/// Pixels whose surface the depth buffer resolves at the scale of `radius` and that lie at least
/// two footprints away from the crease line.
pub(crate) fn resolved(cam: &Camera, h: u32, p: Vec3, radius: f32) -> bool {
    let f = crease_footprint(cam, h, p);
    f < radius / 4.0 && p.x.max(p.y) > 2.0 * f
}

pub(crate) fn assert_valid(img: &RefImage) {
    for i in 0..img.ao.len() {
        let (a, e, d) = (img.ao[i], img.std_error[i], img.linear_depth[i]);
        assert!(a.is_finite() && (0.0..=1.0).contains(&a), "ao[{i}] = {a}");
        assert!(e.is_finite() && e >= 0.0, "std_error[{i}] = {e}");
        assert!(!d.is_nan() && d > 0.0, "depth[{i}] = {d}");
    }
}

/// Cosine-weighted probability that a ray from a point at distance `d` from an infinite wall
/// perpendicular to the point's surface meets the wall within `r` (the circular segment beyond
/// x = d/r of the unit disk that cosine-weighted directions project to, over π).
pub(crate) fn crease_blocked(d: f64, r: f64) -> f64 {
    let a = (d / r).clamp(0.0, 1.0);
    (a.acos() - a * (1.0 - a * a).sqrt()) / PI
}

pub(crate) fn crease_engine(
    ctx: &opengl3d::platform::HeadlessContext,
    name: &str,
    w: u32,
    h: u32,
) -> (Engine, SceneDesc) {
    let dir = temp_dir(name);
    let mut desc = crease_scene(
        &dir,
        Vec3::new(2.5, 1.6, 2.0),
        Vec3::new(0.2, 0.25, 0.0),
        w,
        h,
    );
    desc.camera.fov_y = 70.0;
    (engine(ctx, &desc), desc)
}

#[test]
fn open_plane_is_unoccluded() {
    let ctx = context();
    let dir = temp_dir("screen-open-plane");
    let (w, h) = (64, 36);
    let mut desc = SceneDesc::default();
    desc.objects.push(object(
        &dir,
        "floor",
        &shapes::ground(50.0, 10),
        Vec3::ZERO,
        Vec3::ONE,
    ));
    desc.output.width = w;
    desc.output.height = h;
    desc.bloom.enabled = false;
    let mut e = engine(&ctx, &desc);
    let views = [
        // Oblique with the horizon in view (sky above), and steeply from above.
        (Vec3::new(0.0, 2.0, 0.0), Vec3::new(0.0, 0.0, -10.0)),
        (Vec3::new(0.4, 6.0, 1.5), Vec3::new(0.0, 0.0, 0.0)),
    ];
    for (k, (eye, target)) in views.into_iter().enumerate() {
        e.camera.eye = eye;
        e.camera.target = target;
        let depth = DepthBuffer::from_engine(&mut e).unwrap();
        assert_eq!((depth.width, depth.height), (w, h));
        for radius in [0.5, 5.0] {
            let img = render_screen_space(&depth, &params(radius, 64)).unwrap();
            assert_valid(&img);
            let surface = img.linear_depth.iter().filter(|d| d.is_finite()).count();
            assert!(surface > 1000, "view {k}: {surface} surface pixels");
            for (i, a) in img.ao.iter().enumerate() {
                assert_eq!(*a, 1.0, "view {k}, R {radius}: pixel {i} ao {a}");
            }
        }
        if k == 0 {
            assert!(depth.linear_depth.iter().any(|d| !d.is_finite()), "no sky");
        }
    }
}

#[test]
fn crease_matches_the_closed_form() {
    let ctx = context();
    let (w, h) = (96, 72);
    let (mut e, _) = crease_engine(&ctx, "screen-crease", w, h);
    let depth = DepthBuffer::from_engine(&mut e).unwrap();
    let cam = ref_camera(&e);
    let vp = e.camera.view_projection(w as f32 / h as f32);
    let dist = |p: Vec3| p.x.max(p.y).max(0.0) as f64;

    for radius in [0.5f32, 1.0] {
        let img = render_screen_space(&depth, &params(radius, 512)).unwrap();
        assert_valid(&img);
        let (mut checked, mut sum_err, mut sum_var) = (0usize, 0.0f64, 0.0f64);
        let (mut near_wall, mut far_from_wall) = (false, false);
        for (i, p) in surface_points(&img, &cam) {
            // The surface must be the floor or the wall face.
            assert!(p.y.abs() < 2e-3 || p.x.abs() < 2e-3, "pixel {i} at {p}");
            if !neighbourhood_on_screen(&vp, cam.near, w, h, p, radius)
                || !resolved(&cam, h, p, radius)
            {
                continue;
            }
            let want = 1.0 - crease_blocked(dist(p), radius as f64);
            let (ao, se) = (img.ao[i] as f64, img.std_error[i] as f64);
            assert!(
                (ao - want).abs() <= 4.0 * se + 0.03,
                "R {radius}: pixel {i} at {p}: ao {ao} vs {want} (se {se})"
            );
            checked += 1;
            sum_err += ao - want;
            sum_var += se * se;
            near_wall |= dist(p) < 0.5 * radius as f64;
            far_from_wall |= dist(p) > radius as f64;
        }
        assert!(checked > 100, "R {radius}: only {checked} pixels checked");
        assert!(
            near_wall && far_from_wall,
            "R {radius}: view lacks a range of distances"
        );
        let n = checked as f64;
        let mean_err = sum_err / n;
        assert!(
            mean_err.abs() <= 4.0 * sum_var.sqrt() / n + 0.005,
            "R {radius}: mean error {mean_err} over {n} pixels"
        );
    }

    // With a radius far beyond the scene's scale, the resolved pixels at the bottom of the crease
    // see the wall cover half of their cosine-weighted hemisphere.
    let img = render_screen_space(&depth, &params(50.0, 128)).unwrap();
    let bottom: Vec<(usize, Vec3)> = surface_points(&img, &cam)
        .into_iter()
        .filter(|(_, p)| {
            dist(*p) < 0.05
                && crease_footprint(&cam, h, *p) < 0.1
                && neighbourhood_on_screen(&vp, cam.near, w, h, *p, 1.0)
        })
        .collect();
    assert!(bottom.len() >= 2, "{} pixels at the bottom", bottom.len());
    let mut mean = 0.0;
    for (i, p) in &bottom {
        let (ao, se) = (img.ao[*i] as f64, img.std_error[*i] as f64);
        let want = 1.0 - crease_blocked(dist(*p), 50.0);
        assert!((want - 0.5).abs() < 0.01);
        // Rays meeting the wall beyond 1 m may leave the screen: at d < 0.05 m they are at most
        // crease_blocked(0.05, 50) − crease_blocked(0.05, 1) ≈ 0.03 of the hemisphere.
        assert!(
            (ao - want).abs() <= 4.0 * se + 0.04,
            "pixel {i} at {p}: ao {ao}, want {want}"
        );
        mean += ao / bottom.len() as f64;
    }
    assert!((mean - 0.5).abs() < 0.04, "mean at the bottom {mean}");
}

#[test]
fn agrees_with_the_ray_traced_reference_without_hidden_geometry() {
    let ctx = context();
    let (w, h) = (96, 54);
    let (mut e, desc) = crease_engine(&ctx, "screen-vs-rt", w, h);
    let depth = DepthBuffer::from_engine(&mut e).unwrap();
    let cam = ref_camera(&e);
    let vp = e.camera.view_projection(w as f32 / h as f32);
    let scene = Scene::new(desc.world_triangles(&ResDirs::default()).unwrap()).unwrap();
    let radius = 1.0;
    let cache = temp_dir("screen-vs-rt-cache");
    let rt = load_or_render_cached(&cache, &scene, &cam, w, h, &params(radius, 256));
    let ss = load_or_render_screen_cached(&cache, &depth, &params(radius, 256)).unwrap();
    assert_valid(&ss);
    // Same pixels are surface, at the same depth (GL rasterisation vs ray casting).
    for i in 0..rt.ao.len() {
        let (a, b) = (rt.linear_depth[i], ss.linear_depth[i]);
        assert_eq!(a.is_finite(), b.is_finite(), "pixel {i}: sky mismatch");
        if a.is_finite() {
            assert!((a - b).abs() < 1e-4 * a, "pixel {i}: depth {a} vs {b}");
        }
    }
    let (mut checked, mut sum_diff, mut sum_var, mut occluded) = (0usize, 0.0f64, 0.0f64, 0usize);
    for (i, p) in surface_points(&rt, &cam) {
        if !neighbourhood_on_screen(&vp, cam.near, w, h, p, radius) || !resolved(&cam, h, p, radius)
        {
            continue;
        }
        let d = ss.ao[i] as f64 - rt.ao[i] as f64;
        let var = (ss.std_error[i] as f64).powi(2) + (rt.std_error[i] as f64).powi(2);
        assert!(
            d.abs() <= 4.0 * var.sqrt() + 0.03,
            "pixel {i} at {p}: screen-space {} vs ray-traced {}",
            ss.ao[i],
            rt.ao[i]
        );
        checked += 1;
        sum_diff += d;
        sum_var += var;
        occluded += (rt.ao[i] < 0.9) as usize;
    }
    assert!(
        checked > 150 && occluded > 30,
        "{checked} pixels, {occluded} occluded"
    );
    let mean = sum_diff / checked as f64;
    assert!(
        mean.abs() <= 4.0 * sum_var.sqrt() / checked as f64 + 0.005,
        "mean difference {mean} over {checked} pixels"
    );

    // The cache returns what was stored, keyed by the depth values themselves.
    let again = load_or_render_screen_cached(&cache, &depth, &params(radius, 256)).unwrap();
    assert_eq!(again, ss);
    let mut moved = depth.clone();
    moved.linear_depth[0] += 0.01;
    assert_ne!(
        screen_cache_key(&moved, &params(radius, 256)),
        screen_cache_key(&depth, &params(radius, 256))
    );
}

#[test]
fn hidden_geometry_is_what_the_depth_buffer_cannot_know() {
    // A thin horizontal slab floating above the floor, seen from above: the floor under it is
    // hidden, so a floor point beside it sees, in the depth buffer, an infinitely thick block
    // where the ray tracer sees open space under the slab. The screen-space reference must be
    // darker there, never lighter by more than the noise.
    let ctx = context();
    let dir = temp_dir("screen-hidden");
    let (w, h) = (64, 36);
    let mut slab = opengl3d::gl::mesh::MeshData::default();
    shapes::add_box(
        &mut slab,
        Vec3::new(-1.0, 0.6, -1.0),
        Vec3::new(1.0, 0.7, 1.0),
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
        .push(object(&dir, "slab", &slab, Vec3::ZERO, Vec3::ONE));
    desc.camera.eye = [0.5, 4.0, 3.0];
    desc.camera.target = [0.0, 0.0, 0.0];
    desc.output.width = w;
    desc.output.height = h;
    desc.bloom.enabled = false;
    let mut e = engine(&ctx, &desc);
    let depth = DepthBuffer::from_engine(&mut e).unwrap();
    let cam = ref_camera(&e);
    let scene = Scene::new(desc.world_triangles(&ResDirs::default()).unwrap()).unwrap();
    let p = params(1.0, 256);
    let cache = temp_dir("screen-hidden-cache");
    let rt = load_or_render_cached(&cache, &scene, &cam, w, h, &p);
    let ss = render_screen_space(&depth, &p).unwrap();
    let vp = e.camera.view_projection(w as f32 / h as f32);
    // Floor pixels by their distance from the slab's outline (in the floor plane).
    let (mut beside, mut beside_n, mut away_n) = (0.0f64, 0usize, 0usize);
    for (i, q) in surface_points(&rt, &cam) {
        if q.y.abs() > 1e-3 || !neighbourhood_on_screen(&vp, cam.near, w, h, q, 1.0) {
            continue;
        }
        let gap = (q.x.abs() - 1.0).max(q.z.abs() - 1.0);
        let d = ss.ao[i] as f64 - rt.ao[i] as f64;
        let se = ((ss.std_error[i] as f64).powi(2) + (rt.std_error[i] as f64).powi(2)).sqrt();
        if gap > 1.2 {
            // Nothing within R: both must be open.
            assert!(
                d.abs() <= 4.0 * se + 1e-6,
                "pixel {i} at {q}: {} vs {}",
                ss.ao[i],
                rt.ao[i]
            );
            assert_eq!(rt.ao[i], 1.0);
            away_n += 1;
        } else if gap > 0.1 && gap < 0.5 {
            beside += -d;
            beside_n += 1;
        }
    }
    assert!(
        away_n > 100 && beside_n > 20,
        "{away_n} pixels away, {beside_n} beside"
    );
    let darkening = beside / beside_n as f64;
    assert!(
        darkening > 0.05,
        "floor beside the slab: mean darkening {darkening}"
    );
}

#[test]
fn cli_writes_the_screen_space_reference() {
    let dir = temp_dir("screen-cli");
    let out = dir.join("ss.pfm");
    let run = crate::common::bin()
        .args([
            "reference",
            "--screen-space",
            "--width",
            "32",
            "--height",
            "18",
        ])
        .args(["--rays", "4", "--radius", "0.5", "--out"])
        .arg(&out)
        .arg("--cache")
        .arg(dir.join("cache"))
        .output()
        .unwrap();
    let stdout = String::from_utf8_lossy(&run.stdout);
    assert!(
        run.status.success(),
        "{stdout}\n{}",
        String::from_utf8_lossy(&run.stderr)
    );
    assert!(
        stdout.contains("screen-space") && stdout.contains("R = 0.5 m"),
        "{stdout}"
    );
    // PFM header "Pf\n32 18\n-1.0\n" then 32·18 little-endian floats in [0, 1].
    let bytes = std::fs::read(&out).unwrap();
    let header_end = bytes
        .iter()
        .enumerate()
        .filter(|(_, b)| **b == b'\n')
        .nth(2)
        .unwrap()
        .0;
    assert!(bytes.starts_with(b"Pf\n32 18\n"));
    let values: Vec<f32> = bytes[header_end + 1..]
        .chunks_exact(4)
        .map(|c| f32::from_le_bytes(c.try_into().unwrap()))
        .collect();
    assert_eq!(values.len(), 32 * 18);
    assert!(values.iter().all(|v| (0.0..=1.0).contains(v)));
    assert!(
        values.iter().any(|v| *v < 1.0),
        "the demo scene has occlusion"
    );
    // Obscurance is not something the screen-space reference computes: a clear error.
    let run = crate::common::bin()
        .args(["reference", "--screen-space", "--obscurance"])
        .output()
        .unwrap();
    assert!(!run.status.success());
}

#[test]
fn cli_writes_the_reference_when_its_cache_cannot_be_written() {
    let dir = temp_dir("ref-cli-cache-file");
    // A cache "folder" that is a file: no cache file can be created under it.
    let cache = dir.join("cache-is-a-file");
    std::fs::write(&cache, b"not a folder").unwrap();
    for mode in [&[][..], &["--screen-space"][..]] {
        let out = dir.join(format!("ref{}.pfm", mode.len()));
        let run = crate::common::bin()
            .arg("reference")
            .args(mode)
            .args(["--width", "16", "--height", "9", "--rays", "4", "--out"])
            .arg(&out)
            .arg("--cache")
            .arg(&cache)
            .output()
            .unwrap();
        let stderr = String::from_utf8_lossy(&run.stderr);
        assert!(run.status.success(), "{mode:?}: {stderr}");
        assert!(out.is_file(), "{mode:?}: --out not written");
        // The warning names the cache file it could not write.
        let warning = stderr
            .lines()
            .find(|l| l.contains("warning: reference cache"))
            .unwrap_or_else(|| panic!("{mode:?}: no cache warning in {stderr}"));
        assert!(
            warning.contains(&format!("{}/", cache.display())) && warning.contains(".bin"),
            "{warning}"
        );
    }
    assert_eq!(std::fs::read(&cache).unwrap(), b"not a folder");
}

/// The depth buffer is decoded by the convention it was written with: reversed-Z finds the same sky
/// and the same distances as the course's D32 (it once decoded reversed-Z with the D32 formula and
/// found no sky at all).
#[test]
fn reversed_z_depth_buffer_decodes_like_d32() {
    use opengl3d::math::DepthMode;
    let ctx = context();
    let (w, h) = (96, 72);
    let (mut e, _) = crease_engine(&ctx, "screen-reversed", w, h);
    // Looking up over the crease: floor, wall and sky.
    e.camera.target = e.camera.eye + Vec3::new(-1.0, 0.6, -1.0);
    let d32 = DepthBuffer::from_engine(&mut e).unwrap();
    e.set_depth_mode(DepthMode::D32fReversed).unwrap();
    let reversed = DepthBuffer::from_engine(&mut e).unwrap();
    let sky = |d: &DepthBuffer| d.linear_depth.iter().filter(|z| !z.is_finite()).count();
    assert!(sky(&d32) > 0, "the crease view must show some sky");
    assert_eq!(sky(&reversed), sky(&d32), "sky pixels: reversed-Z vs D32");
    let worst = d32
        .linear_depth
        .iter()
        .zip(&reversed.linear_depth)
        .filter(|(a, _)| a.is_finite())
        .map(|(a, b)| ((a - b) / a).abs())
        .fold(0.0f32, f32::max);
    // D32 quantises depth to 2^-32 of the window range: ~1e-5 relative at these distances.
    assert!(worst < 1e-3, "relative depth difference {worst}");
}
