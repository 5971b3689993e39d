//! `--ao-resolution full`: the engine's methods run on one linear-depth texel per pixel, restored
//! exactly (both depth conventions), while the lesson's SAO stays at half size as taught.

use crate::common;

use glam::Vec3;
use opengl3d::ao::{AoMethod, AoResolution, CompositeMode};
use opengl3d::math::DepthMode;
use opengl3d::render::View;
use opengl3d::scene::SceneDesc;
use opengl3d::tools::reference::{pixel_dir, view_direction};

const W: u32 = 64;
const H: u32 = 48;

/// A floor seen obliquely: the exact view distance changes from pixel to pixel.
fn floor_scene(dir: &std::path::Path) -> SceneDesc {
    common::floor_and(
        dir,
        &[],
        Vec3::new(0.0, 2.0, 0.0),
        Vec3::new(0.0, 0.0, -4.0),
        (W, H),
    )
}

/// The floor's exact view distance (−z_view) at the centre of pixel (x, y), row 0 at the top;
/// `None` where the ray misses the floor.
fn exact_depth(scene: &SceneDesc, x: u32, y: u32) -> Option<f32> {
    exact_depth_at(scene, x, y, (W, H))
}

#[test]
fn full_resolution_restores_every_pixel_exactly_in_both_depth_conventions() {
    let ctx = common::context();
    let dir = common::temp_dir("ao-full");
    for mode in [DepthMode::D32, DepthMode::D32fReversed] {
        let mut scene = floor_scene(&dir);
        scene.output.depth = mode;
        scene.ao.method = AoMethod::Vbao;
        let mut worst = [0.0f32; 2];
        for (i, resolution) in [AoResolution::Full, AoResolution::Half]
            .into_iter()
            .enumerate()
        {
            scene.ao.resolution = resolution;
            let mut eng = common::engine(&ctx, &scene);
            let v = eng.render_values(View::LinearDepth).unwrap();
            let size = eng.ao_targets().unwrap().size();
            let expected_size = match resolution {
                AoResolution::Full => (W, H),
                AoResolution::Half => (W / 2, H / 2),
                AoResolution::Quarter => (W / 4, H / 4),
            };
            assert_eq!(size, expected_size, "{mode:?} {resolution:?}");
            for y in 0..H {
                for x in 0..W {
                    if let Some(d) = exact_depth(&scene, x, y) {
                        let got = v[(y * W + x) as usize];
                        worst[i] = worst[i].max((got - d).abs() / d);
                    }
                }
            }
        }
        eprintln!(
            "{mode:?}: worst relative depth error, full {:e}, half {:e}",
            worst[0], worst[1]
        );
        // Full: the restore's f32 arithmetic only. Half: each texel holds the nearest of 2x2.
        assert!(worst[0] < 1e-4, "{mode:?} full: {:e}", worst[0]);
        assert!(worst[1] > 10.0 * worst[0], "{mode:?} half {:e}", worst[1]);
    }
}

/// The floor's exact view distance at the centre of texel (x, y) of a `w`×`h` image of the scene's
/// camera, row 0 at the top.
fn exact_depth_at(scene: &SceneDesc, x: u32, y: u32, (w, h): (u32, u32)) -> Option<f32> {
    let cam = scene.camera.camera();
    let d = pixel_dir(&cam, x, y, w, h)?;
    if d.y >= -1e-6 {
        return None;
    }
    let t = cam.eye.y / -d.y;
    (t < 50.0).then(|| t * d.dot(view_direction(&cam)))
}

/// At a quarter of the size the engine draws the depth itself: each texel is the exact depth at its
/// own centre (no nearest-of-block), in both conventions, and the composite still fills the image.
#[test]
fn quarter_resolution_draws_each_texels_own_depth() {
    let ctx = common::context();
    let dir = common::temp_dir("ao-quarter");
    for mode in [DepthMode::D32, DepthMode::D32fReversed] {
        let mut scene = floor_scene(&dir);
        scene.output.depth = mode;
        scene.ao.method = AoMethod::Vbao;
        scene.ao.resolution = AoResolution::Quarter;
        let mut eng = common::engine(&ctx, &scene);
        let ao = eng.render_values(View::Ao).unwrap();
        common::assert_finite("quarter", &ao);
        let size = eng.ao_targets().unwrap().size();
        assert_eq!(size, (W / 4, H / 4), "{mode:?}");
        let depth = eng.ao_targets().unwrap().tex_depth.read_f32(0, 1);
        let (w, h) = size;
        let mut worst = 0.0f32;
        let mut checked = 0;
        for y in 0..h {
            for x in 0..w {
                if let Some(d) = exact_depth_at(&scene, x, y, size) {
                    // Read-back rows are bottom-up.
                    let got = depth[((h - 1 - y) * w + x) as usize];
                    worst = worst.max((got - d).abs() / d);
                    checked += 1;
                }
            }
        }
        assert!(
            checked > (w * h / 3) as usize,
            "{mode:?}: only {checked} texels see the floor"
        );
        assert!(
            worst < 1e-4,
            "{mode:?}: worst relative depth error {worst:e}"
        );
    }
}

#[test]
fn the_lessons_sao_stays_at_half_size_whatever_the_setting() {
    let ctx = common::context();
    let dir = common::temp_dir("ao-full-lesson");
    let mut scene = floor_scene(&dir);
    scene.ao.method = AoMethod::SaoLesson;
    scene.ao.resolution = AoResolution::Full;
    let mut eng = common::engine(&ctx, &scene);
    common::assert_finite("sao-lesson", &eng.render_values(View::Ao).unwrap());
    assert_eq!(eng.ao_targets().unwrap().size(), (W / 2, H / 2));
    // Switching the method to an engine one re-creates the targets at full size.
    eng.ao_settings.method = AoMethod::Gtao;
    common::assert_finite("gtao", &eng.render_values(View::Ao).unwrap());
    assert_eq!(eng.ao_targets().unwrap().size(), (W, H));
}

/// Bilinear up-sampling of a `w`×`h` bottom-up half-size image to `2w`×`2h` top-down, as a linear
/// texture filter does (clamped at the border).
fn linear_upsample(half: &[f32], w: usize, h: usize) -> Vec<f32> {
    let at = |x: isize, y: isize| {
        let x = x.clamp(0, w as isize - 1) as usize;
        let y = y.clamp(0, h as isize - 1) as usize;
        half[y * w + x]
    };
    let (fw, fh) = (2 * w, 2 * h);
    let mut out = vec![0.0; fw * fh];
    for y in 0..fh {
        for x in 0..fw {
            let hx = (x as f32 + 0.5) * 0.5 - 0.5;
            let hy = (y as f32 + 0.5) * 0.5 - 0.5;
            let (bx, by) = (hx.floor(), hy.floor());
            let (fx, fy) = (hx - bx, hy - by);
            let (bx, by) = (bx as isize, by as isize);
            let v = at(bx, by) * (1.0 - fx) * (1.0 - fy)
                + at(bx + 1, by) * fx * (1.0 - fy)
                + at(bx, by + 1) * (1.0 - fx) * fy
                + at(bx + 1, by + 1) * fx * fy;
            // Rows top-down, as render_values gives them.
            out[(fh - 1 - y) * fw + x] = v;
        }
    }
    out
}

#[test]
fn half_size_ao_is_upsampled_depth_aware_at_silhouettes() {
    let ctx = common::context();
    let path = opengl3d::res::project_res_dir().join("scenes/demo.toml");
    let mut scene = opengl3d::scene::SceneFile::read(&path).unwrap().desc;
    let (w, h) = (320usize, 180usize);
    scene.output.width = w as u32;
    scene.output.height = h as u32;
    scene.ao.method = AoMethod::Gtao;
    let mut eng = common::engine(&ctx, &scene);
    let upsampled = eng.render_values(View::Ao).unwrap();
    // Visibility is 1 − occlusion: the texture holds occlusion.
    let half: Vec<f32> = eng
        .ao_targets()
        .unwrap()
        .result_texture(true)
        .read_f32(0, 1)
        .iter()
        .map(|o| 1.0 - o)
        .collect();
    let linear = linear_upsample(&half, w / 2, h / 2);
    eng.ao_settings.resolution = AoResolution::Full;
    let full = eng.render_values(View::Ao).unwrap();
    let depth = eng.render_values(View::LinearDepth).unwrap();
    // Silhouette pixels: a 4-neighbour more than 10 % farther or nearer.
    let mut err = [0.0f64; 2];
    let mut count = 0;
    for y in 1..h - 1 {
        for x in 1..w - 1 {
            let i = y * w + x;
            let z = depth[i];
            let edge = [i - 1, i + 1, i - w, i + w]
                .iter()
                .any(|&j| (depth[j] - z).abs() > 0.1 * z.min(depth[j]));
            if edge && z < scene.camera.far {
                err[0] += (upsampled[i] - full[i]).abs() as f64;
                err[1] += (linear[i] - full[i]).abs() as f64;
                count += 1;
            }
        }
    }
    assert!(count > 100, "{count} silhouette pixels");
    let (bilateral, linear) = (err[0] / count as f64, err[1] / count as f64);
    eprintln!("silhouettes ({count} px): mean |AO - full-size AO| bilateral {bilateral:.4}, linear {linear:.4}");
    // Measured 0.0129 against 0.0162 (the shader with its depth weights removed gives exactly the
    // linear figure): ask for a tenth better, so a lost depth test fails.
    assert!(
        bilateral < 0.9 * linear,
        "bilateral {bilateral} vs linear {linear}"
    );
}

/// The main colour (RGBA16F, rows bottom-up) after the last frame.
fn main_colour(eng: &opengl3d::render::Engine) -> Vec<f32> {
    eng.fbo_main.color_texture().unwrap().read_f32(0, 4)
}

#[test]
fn the_blended_composites_darken_by_the_upsampled_occlusion() {
    let ctx = common::context();
    let dir = common::temp_dir("composite-while-upsampling");
    let (w, h) = (160usize, 120usize);
    let mut scene = common::crease_scene(
        &dir,
        Vec3::new(4.0, 2.0, 4.0),
        Vec3::new(0.0, 1.0, 0.0),
        w as u32,
        h as u32,
    );
    scene.light.shadow = false;
    scene.bloom.enabled = false;
    scene.ao.method = AoMethod::Gtao;
    let mut eng = common::engine(&ctx, &scene);
    eng.ao_settings.enabled = false;
    eng.render_image().unwrap();
    let lit = main_colour(&eng);
    eng.ao_settings.enabled = true;
    // The AO view goes through the separate up-sampling pass (into R8); rows top-down.
    let visibility = eng.render_values(View::Ao).unwrap();
    let darkened = visibility.iter().filter(|v| **v < 0.9).count();
    assert!(darkened > 200, "only {darkened} pixels occluded");
    let tint = [0.9f32, 0.2, 0.1];
    for (mode, power) in [(CompositeMode::Blend, 1.0f32), (CompositeMode::Tinted, 2.0)] {
        eng.ao_settings.composite = mode;
        eng.ao_settings.power = power;
        eng.ao_settings.tint = tint;
        eng.render_image().unwrap();
        let out = main_colour(&eng);
        let mut worst = 0.0f32;
        for y in 0..h {
            for x in 0..w {
                let v = visibility[(h - 1 - y) * w + x];
                let alpha = 1.0 - v.powf(power);
                let target = if mode == CompositeMode::Blend {
                    [0.0; 3]
                } else {
                    tint
                };
                for (c, toward) in target.iter().enumerate() {
                    let i = (y * w + x) * 4 + c;
                    let expected = lit[i] * (1.0 - alpha) + toward * alpha;
                    // The view's R8 rounding (half a step of 1/255 in alpha) and RGBA16F storage.
                    let allowed = (lit[i] + toward) * power / 510.0 + 2e-3 * expected + 1e-3;
                    let err = (out[i] - expected).abs();
                    assert!(
                        err <= allowed,
                        "{mode:?} at ({x}, {y}) channel {c}: {} vs lit {} x visibility {v} -> {expected}",
                        out[i],
                        lit[i]
                    );
                    worst = worst.max(err);
                }
            }
        }
        eprintln!("{mode:?}: largest difference from lit colour x visibility {worst:.5}");
    }
}

/// Half-size AO up-sampled to the main size leaves the sky exactly open: the half-size texels beside a
/// silhouette belong to the surface, and no sky pixel takes their occlusion.
#[test]
fn upsampled_ao_leaves_every_sky_pixel_open() {
    let ctx = common::context();
    let dir = common::temp_dir("ao-sky");
    // The crease seen from low down: the wall's top edge and the floor's far edge meet the sky.
    let mut scene = common::crease_scene(
        &dir,
        Vec3::new(3.0, 1.0, 4.0),
        Vec3::new(0.0, 2.5, 0.0),
        320,
        240,
    );
    for method in [AoMethod::Vbao, AoMethod::Gtao, AoMethod::Sao] {
        scene.ao.method = method;
        let mut eng = common::engine(&ctx, &scene);
        let vis = eng.render_values(View::Ao).unwrap();
        let depth = eng.render_values(View::LinearDepth).unwrap();
        let far = eng.camera.far;
        let sky: Vec<f32> = vis
            .iter()
            .zip(&depth)
            .filter(|(_, d)| **d >= far)
            .map(|(v, _)| *v)
            .collect();
        let occluded = vis.iter().filter(|v| **v < 0.9).count();
        assert!(
            sky.len() > 1000 && occluded > 100,
            "{}: {} sky, {occluded} occluded",
            method.name(),
            sky.len()
        );
        let leaks = sky.iter().filter(|v| **v != 1.0).count();
        assert_eq!(leaks, 0, "{}: {leaks} sky pixels below 1", method.name());
    }
}
