//! The lesson's SAO passes, each checked against an independent computation on the CPU.

use crate::common;

use glam::Vec3;
use opengl3d::ao::{AoSettings, SaoLesson};
use opengl3d::gl::{MeshBuffer, Texture, TextureDesc};
use opengl3d::math::depth::linearize;
use opengl3d::math::{Camera, DepthMode};
use opengl3d::render::View;
use opengl3d::res::ResDirs;

fn lesson(
    ctx: &opengl3d::platform::HeadlessContext,
    w: u32,
    h: u32,
    cam: &Camera,
    p: &AoSettings,
) -> (SaoLesson, MeshBuffer) {
    let ao = SaoLesson::new(&ctx.gl, &ResDirs::default(), w, h, cam, p).expect("SAO passes");
    (ao, MeshBuffer::new(&ctx.gl).unwrap())
}

/// Depth-buffer value of a point at view distance `z` (the projection's forward map, f64).
fn depth_of(z: f64, n: f64, f: f64) -> f64 {
    let a = -2.0 * f * n / (f - n);
    let b = (f + n) / (f - n);
    0.5 * ((-(-z) * b + a) / z) + 0.5
}

#[test]
fn restored_linear_depth_matches_cpu_over_the_whole_range() {
    let ctx = common::context();
    let cam = Camera::default();
    let (w, h) = (128u32, 64u32);
    let (ao, meshes) = lesson(&ctx, w, h, &cam, &AoSettings::default());
    let (n, f) = (cam.near as f64, cam.far as f64);
    // Distances log-spaced from near to far, plus exact sky (1.0), one per texel.
    let count = (w * h) as usize;
    let mut d: Vec<f32> = (0..count)
        .map(|i| {
            let t = i as f64 / (count - 1) as f64;
            depth_of(n * (f / n).powf(t), n, f) as f32
        })
        .collect();
    d[count - 1] = 1.0;
    let depth = Texture::new(
        &ctx.gl,
        TextureDesc::target("test depth", w, h, glow::DEPTH_COMPONENT32),
    )
    .unwrap();
    depth.upload_f32(0, 1, &d).unwrap();
    // What the shader really reads: the values as stored (32-bit unorm).
    let stored = depth.read_f32(0, 1);
    ao.restore_depth(&meshes, &depth);
    let got = ao.targets.tex_depth.read_f32(0, 1);
    let (hw, hh) = (w as usize / 2, h as usize / 2);
    let mut worst_f64 = 0.0f64;
    for y in 0..hh {
        for x in 0..hw {
            let at = |dx: usize, dy: usize| stored[(2 * y + dy) * w as usize + 2 * x + dx];
            let dmin = at(0, 0).min(at(1, 0)).min(at(0, 1)).min(at(1, 1));
            let g = got[y * hw + x] as f64;
            if dmin >= 1.0 {
                assert_eq!(g, f, "sky must restore to exactly far");
                continue;
            }
            let exact = linearize(DepthMode::D32, dmin as f64, n, f);
            // An f32 evaluation of A / ((2D − 1) − B) loses up to a few ulps of B (≈ 1.0007) in the
            // subtraction, amplified by 1/|D' − B| near the far plane (the compiler may also
            // reassociate the constants, so the GPU need not match a CPU f32 evaluation bit for bit).
            let b = (f + n) / (f - n);
            let bound =
                4.0 * f32::EPSILON as f64 * (1.0 + b / ((2.0 * dmin as f64 - 1.0) - b).abs());
            let rel = (g - exact).abs() / exact;
            worst_f64 = worst_f64.max(rel / bound);
            assert!(
                rel <= bound,
                "z={exact}: restored {g}, exact {exact}, rel err {rel:e} > bound {bound:e}"
            );
        }
    }
    eprintln!("worst error / f32 bound vs exact: {worst_f64:.3}");
}

#[test]
fn each_mip_level_is_the_min_of_its_2x2_parent_texels() {
    let ctx = common::context();
    let cam = Camera::default();
    // Odd sizes on purpose: 203×117 → 101×58 → 50×29 → 25×14.
    let (ao, meshes) = lesson(&ctx, 203, 117, &cam, &AoSettings::default());
    let (w0, h0) = ao.targets.tex_depth.size_at(0);
    let mut seed = 12345u32;
    let level0: Vec<f32> = (0..w0 * h0)
        .map(|_| {
            seed = seed.wrapping_mul(1664525).wrapping_add(1013904223);
            0.35 + (seed >> 8) as f32 / (1u32 << 24) as f32 * 100.0
        })
        .collect();
    ao.targets.tex_depth.upload_f32(0, 1, &level0).unwrap();
    ao.down_sample(&meshes);
    assert_eq!(ao.targets.tex_depth.levels(), 4);
    let mut parent = ao.targets.tex_depth.read_f32(0, 1);
    assert_eq!(parent, level0);
    for level in 1..4 {
        let (pw, ph) = ao.targets.tex_depth.size_at(level - 1);
        let (w, h) = ao.targets.tex_depth.size_at(level);
        let got = ao.targets.tex_depth.read_f32(level, 1);
        for y in 0..h as usize {
            for x in 0..w as usize {
                let at = |dx: usize, dy: usize| {
                    parent[(2 * y + dy).min(ph as usize - 1) * pw as usize
                        + (2 * x + dx).min(pw as usize - 1)]
                };
                let expected = at(0, 0).min(at(1, 0)).min(at(0, 1)).min(at(1, 1));
                assert_eq!(
                    got[y * w as usize + x],
                    expected,
                    "level {level} texel ({x},{y})"
                );
            }
        }
        parent = got;
    }
}

#[test]
fn sao_really_reads_mip_levels_1_to_3() {
    // Level 0 is a flat wall facing the camera at 10 m (no occlusion at all); levels 1–3 claim a
    // surface 1 m closer. Only a shader that really samples the coarse levels sees occlusion.
    let ctx = common::context();
    let cam = Camera::default();
    let params = AoSettings {
        radius: 2.0,
        intensity: 1000.0,
        blur: false,
        ..Default::default()
    };
    let (ao, meshes) = lesson(&ctx, 512, 256, &cam, &params);
    let fill = |level: u32, v: f32| {
        let (w, h) = ao.targets.tex_depth.size_at(level);
        ao.targets
            .tex_depth
            .upload_f32(level, 1, &vec![v; (w * h) as usize])
            .unwrap();
    };
    fill(0, 10.0);
    for l in 1..4 {
        fill(l, 9.0);
    }
    ao.compute_sao(&meshes, &cam, &params);
    let occ = ao.sao_texture().read_f32(0, 1);
    let mean = occ.iter().sum::<f32>() / occ.len() as f32;
    assert!(
        mean > 0.05,
        "mean occlusion {mean}: the coarse levels were not read (mipmap filter lost?)"
    );

    // Control: with every level at 10 m the same wall is open.
    for l in 1..4 {
        fill(l, 10.0);
    }
    ao.compute_sao(&meshes, &cam, &params);
    let occ = ao.sao_texture().read_f32(0, 1);
    let max = occ.iter().cloned().fold(0.0, f32::max);
    assert!(
        max < 0.01,
        "a flat wall must not occlude itself (max {max})"
    );
}

#[test]
fn sao_is_zero_on_open_floor_and_clearly_positive_in_a_crease() {
    let ctx = common::context();
    let dir = common::temp_dir("crease");
    let scene = common::crease_scene(
        &dir,
        Vec3::new(4.0, 2.5, 4.0),
        Vec3::new(0.0, 0.0, 0.0),
        320,
        240,
    );
    let mut eng = common::engine(&ctx, &scene);
    eng.ao_settings.blur = false;
    eng.render_to_ao().unwrap();
    let occ = eng.ao_targets().unwrap().sao_texture().read_f32(0, 1);
    let (w, h) = eng.ao_targets().unwrap().sao_texture().size_at(0);
    let (w, h) = (w as usize, h as usize);
    let (cx, cy) = common::project(&eng, Vec3::new(0.05, 0.05, 0.0), w as u32, h as u32);
    let (fx, fy) = common::project(&eng, Vec3::new(3.0, 0.0, -1.0), w as u32, h as u32);
    let crease = common::mean_around(&occ, w, h, cx, cy, 1);
    let floor = common::mean_around(&occ, w, h, fx, fy, 3);
    assert!(floor < 0.02, "open floor occlusion {floor}");
    assert!(crease > 0.15, "crease occlusion {crease}");
}

#[test]
fn blur_keeps_a_depth_edge_sharp_and_smooths_within_a_surface() {
    let ctx = common::context();
    let cam = Camera::default();
    let (ao, meshes) = lesson(&ctx, 128, 64, &cam, &AoSettings::default());
    let (w, h) = ao.targets.tex_depth.size_at(0);
    let (w, h) = (w as usize, h as usize);
    // Left half near (2 m) and fully occluded, right half far (10 m) and open.
    let depth: Vec<f32> = (0..w * h)
        .map(|i| if i % w < w / 2 { 2.0 } else { 10.0 })
        .collect();
    let occ: Vec<f32> = (0..w * h)
        .map(|i| if i % w < w / 2 { 1.0 } else { 0.0 })
        .collect();
    ao.targets.tex_depth.upload_f32(0, 1, &depth).unwrap();
    ao.sao_texture().upload_f32(0, 1, &occ).unwrap();
    ao.blur(&meshes);
    let out = ao.result_texture(true).read_f32(0, 1);
    for y in 0..h {
        for x in [w / 2 - 2, w / 2 - 1] {
            assert!(
                (out[y * w + x] - 1.0).abs() < 1.0 / 255.0,
                "near side at ({x},{y}) = {}",
                out[y * w + x]
            );
        }
        for x in [w / 2, w / 2 + 1] {
            assert!(
                out[y * w + x] < 1.0 / 255.0,
                "far side at ({x},{y}) = {}",
                out[y * w + x]
            );
        }
    }
    // Control: the same occlusion step on one flat surface is smoothed across.
    ao.targets
        .tex_depth
        .upload_f32(0, 1, &vec![5.0; w * h])
        .unwrap();
    ao.blur(&meshes);
    let out = ao.result_texture(true).read_f32(0, 1);
    let v = out[(h / 2) * w + w / 2];
    assert!(
        v > 0.05 && v < 0.95,
        "within one surface the blur must mix both sides, got {v}"
    );
}

#[test]
fn composite_darkens_the_crease_and_leaves_open_floor_and_sky_alone() {
    let ctx = common::context();
    let dir = common::temp_dir("composite");
    let mut scene = common::crease_scene(
        &dir,
        Vec3::new(4.0, 2.0, 4.0),
        Vec3::new(0.0, 1.0, 0.0),
        320,
        240,
    );
    scene.light.shadow = false;
    let mut on = common::engine(&ctx, &scene);
    let img_on = on.render_image().unwrap();
    scene.ao.enabled = false;
    let mut off = common::engine(&ctx, &scene);
    let img_off = off.render_image().unwrap();
    // Image rows are top-down; project() gives GL (bottom-up) rows.
    let lum = |img: &image::RgbaImage, x: usize, y: usize| {
        let p = img.get_pixel(x as u32, (239 - y) as u32);
        (p[0] as f32 + p[1] as f32 + p[2] as f32) / 3.0
    };
    let (cx, cy) = common::project(&on, Vec3::new(0.03, 0.03, 0.0), 320, 240);
    let (fx, fy) = common::project(&on, Vec3::new(3.0, 0.0, -1.5), 320, 240);
    // A sky pixel: restored depth is exactly far, in the top row.
    let depth = on.render_values(View::LinearDepth).unwrap();
    let sx = (0..320)
        .rev()
        .find(|&x| depth[x] >= on.camera.far)
        .expect("some sky in the top row");
    let sy = 239usize;
    assert!(
        lum(&img_on, cx, cy) < lum(&img_off, cx, cy) - 10.0,
        "crease: {} with AO vs {} without",
        lum(&img_on, cx, cy),
        lum(&img_off, cx, cy)
    );
    assert!(
        (lum(&img_on, fx, fy) - lum(&img_off, fx, fy)).abs() <= 2.0,
        "open floor changed: {} vs {}",
        lum(&img_on, fx, fy),
        lum(&img_off, fx, fy)
    );
    assert_eq!(
        img_on.get_pixel(sx as u32, (239 - sy) as u32),
        img_off.get_pixel(sx as u32, (239 - sy) as u32),
        "sky changed"
    );
    // And the AO view says the same thing as visibility: sky exactly 1.
    let vis = on.render_values(View::Ao).unwrap();
    assert_eq!(vis[(239 - sy) * 320 + sx], 1.0);
}
