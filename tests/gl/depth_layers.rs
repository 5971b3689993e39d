//! `vbao` with a second depth layer (`layers = 2`): an occluder hidden under a plate, which the
//! visible surface's slabs cannot reach, darkens the floor beside it as the ray-traced truth does;
//! the screen-space reference with two layers sees it too.

use crate::common::*;
use crate::reference_screen::ref_camera;
use glam::Vec3;
use opengl3d::ao::{AoMethod, AoResolution, AoSettings, SlicePreset};
use opengl3d::gl::mesh::MeshData;
use opengl3d::render::View;
use opengl3d::res::ResDirs;
use opengl3d::scene::{shapes, SceneDesc};
use opengl3d::tools::reference::{
    load_or_render_cached, pixel_dir, render_screen_space, view_direction, AoVariant, Capture,
    DepthBuffer, RefParams, Scene, Surface,
};

const W: u32 = 160;
const H: u32 = 120;

/// A floor; over its x < 0 half a thin plate 1.5 m up; under the plate, flush with its edge, a block
/// 0.9 m high that the camera (straight above the edge) cannot see. R = 1 m, thickness R/2: the
/// plate's slab ends 1 m above the floor, so only the hidden block can shade the floor at x > 0.
pub fn hidden_block(dir: &std::path::Path) -> SceneDesc {
    plate_over(dir, Vec3::new(-0.8, 0.0, -4.0), Vec3::new(0.0, 0.9, 4.0))
}

/// The same plate and floor with the hidden box from `lo` to `hi` under the plate.
pub fn plate_over(dir: &std::path::Path, lo: Vec3, hi: Vec3) -> SceneDesc {
    let mut plate = MeshData::default();
    shapes::add_box(
        &mut plate,
        Vec3::new(-4.0, 1.5, -4.0),
        Vec3::new(0.0, 1.52, 4.0),
    );
    let mut block = MeshData::default();
    shapes::add_box(&mut block, lo, hi);
    let mut desc = SceneDesc::default();
    desc.objects
        .push(object(dir, "plate", &plate, Vec3::ZERO, Vec3::ONE));
    desc.objects
        .push(object(dir, "block", &block, Vec3::ZERO, Vec3::ONE));
    desc.objects.push(object(
        dir,
        "floor",
        &shapes::ground(50.0, 10),
        Vec3::ZERO,
        Vec3::ONE,
    ));
    desc.camera.eye = [0.0, 5.0, 1.0];
    desc.camera.target = [0.6, 0.0, 0.0];
    desc.output.width = W;
    desc.output.height = H;
    desc.bloom.enabled = false;
    desc.ao = AoSettings {
        method: AoMethod::Vbao,
        quality: Some(SlicePreset::Ultra),
        resolution: AoResolution::Full,
        blur: false,
        radius: 1.0,
        ..AoSettings::default()
    };
    desc
}

#[test]
fn a_second_layer_finds_the_occluder_hidden_under_a_plate() {
    let ctx = context();
    let dir = temp_dir("layers-hidden-block");
    let mut desc = hidden_block(&dir);
    let mut visibility = Vec::new();
    for layers in [1, 2] {
        desc.ao.layers = layers;
        let mut e = engine(&ctx, &desc);
        let v = e.render_values(View::AoRaw).unwrap();
        assert_finite("vbao", &v);
        visibility.push(v);
        if layers == 2 {
            // The pass ran and its target is listed with the AO textures.
            assert!(e.second_layer_depth().is_some(), "no second layer");
        }
    }
    let e = engine(&ctx, &desc);
    let (truth, cam) = engine_truth(&e, &desc, &temp_dir("layers-cache"));
    let mean = strip_mean(surface_points(&truth, &cam));
    let (want, one, two) = (mean(&truth.ao), mean(&visibility[0]), mean(&visibility[1]));
    // The truth: a wall 0.9 m high beside the strip shades it well below open sky.
    assert!(want < 0.8, "ray-traced visibility {want}");
    // One layer sees the plate's slab only (1 m up and more): hardly any shade.
    assert!(one > want + 0.1, "one layer {one} vs truth {want}");
    // Two layers find the block: much closer to the truth.
    assert!(
        (two - want).abs() < 0.4 * (one - want).abs(),
        "two layers {two}, one layer {one}, truth {want}"
    );
}

#[test]
fn the_screen_space_ceiling_with_two_layers_sees_the_hidden_block_too() {
    let ctx = context();
    let dir = temp_dir("layers-ceiling");
    let desc = hidden_block(&dir);
    let mut e = engine(&ctx, &desc);
    let separation = desc.ao.layer_separation_metres();
    let capture = |e: &mut opengl3d::render::Engine, second_layer| {
        let what = Capture {
            second_layer,
            ..Capture::default()
        };
        captured(e, what, &desc)
    };
    let one = capture(&mut e, None);
    let two = capture(&mut e, Some(separation));
    let second = two.second_layer.as_ref().expect("second layer captured");
    // Under the plate the second layer is the block's top (depth 5 − 0.9 = 4.1 straight below
    // the eye); past the plate's edge only the floor's far side could be, and it is one-sided.
    let cam = ref_camera(&e);
    let (w, h) = (W as usize, H as usize);
    let (mut under_plate, mut block_tops) = (0, 0);
    for (i, p) in surface_points_of(&one, &cam) {
        if p.y > 1.4 && p.x < -0.1 && p.x > -0.7 && p.z.abs() < 0.5 {
            under_plate += 1;
            // The block's top, seen through the plate: its depth along the camera ray is the
            // plate's depth scaled by the heights below the eye (5 − 0.9) / (5 − 1.52).
            let want = one.linear_depth[i] * (5.0 - 0.9) / (5.0 - 1.52);
            if (second[i] - want).abs() < 0.01 * want {
                block_tops += 1;
            }
        }
    }
    assert!(
        under_plate > 50,
        "{under_plate} plate pixels over the block"
    );
    assert!(
        block_tops as f64 > 0.95 * under_plate as f64,
        "{block_tops} of {under_plate} plate pixels have the block's top as second layer"
    );
    assert_eq!(second.len(), w * h);
    let params = RefParams {
        radius: 1.0,
        rays: 32,
        variant: AoVariant::Visibility,
        seed: 3,
        progress: false,
        supersample: 1,
    };
    let ceiling_one = render_screen_space(&one, &params).unwrap();
    let ceiling_two = render_screen_space(&two, &params).unwrap();
    let mean = strip_mean(surface_points_of(&one, &cam));
    let (a, b) = (mean(&ceiling_one.ao), mean(&ceiling_two.ao));
    assert!(
        a > 0.95,
        "one-layer ceiling {a}: the plate's slab is out of reach"
    );
    assert!(b < a - 0.2, "two-layer ceiling {b} against one layer {a}");
}

/// The engine's depth buffer with what `what` asks for, its slabs the scene's set thickness.
fn captured(e: &mut opengl3d::render::Engine, what: Capture, desc: &SceneDesc) -> DepthBuffer {
    DepthBuffer::capture(e, 0, what)
        .unwrap()
        .with_thickness(desc.ao.thickness_metres())
}

/// World points of a captured depth buffer's pixels (rows top-down), as the reference's
/// `surface_points` gives for its images.
fn surface_points_of(buf: &DepthBuffer, cam: &opengl3d::math::Camera) -> Vec<(usize, Vec3)> {
    let fwd = view_direction(cam);
    let mut out = Vec::new();
    for y in 0..buf.height {
        for x in 0..buf.width {
            let i = (y * buf.width + x) as usize;
            let depth = buf.linear_depth[i];
            if depth.is_finite() {
                let dir = pixel_dir(cam, x, y, buf.width, buf.height).unwrap();
                out.push((i, cam.eye + dir * (depth / dir.dot(fwd))));
            }
        }
    }
    out
}

/// The ray-traced truth of `e`'s view of `desc` (R 1 m, 256 rays at pixel centres, cached in
/// `cache`), and the camera it was traced from.
pub fn engine_truth(
    e: &opengl3d::render::Engine,
    desc: &SceneDesc,
    cache: &std::path::Path,
) -> (opengl3d::tools::reference::RefImage, opengl3d::math::Camera) {
    let cam = ref_camera(e);
    let scene = Scene::new(desc.world_triangles(&ResDirs::default()).unwrap()).unwrap();
    let params = RefParams {
        radius: 1.0,
        rays: 256,
        variant: AoVariant::Visibility,
        seed: 7,
        progress: false,
        supersample: 1,
    };
    let (w, h) = e.size();
    (
        load_or_render_cached(cache, &scene, &cam, w, h, &params),
        cam,
    )
}

/// The mean over the floor pixels beside the hidden block's face (away from the view's borders, so
/// no off-screen occluder matters) of an image with these pixels' world points.
pub fn strip_mean(points: Vec<(usize, Vec3)>) -> impl Fn(&[f32]) -> f64 {
    let strip: Vec<usize> = points
        .into_iter()
        .filter(|(_, p)| p.y.abs() < 1e-3 && p.x > 0.05 && p.x < 0.4 && p.z.abs() < 0.5)
        .map(|(i, _)| i)
        .collect();
    assert!(
        strip.len() > 100,
        "{} floor pixels in the strip",
        strip.len()
    );
    move |v: &[f32]| strip.iter().map(|&i| v[i] as f64).sum::<f64>() / strip.len() as f64
}

#[test]
fn the_ceilings_second_layer_reaches_its_own_back_faces() {
    let ctx = context();
    let dir = temp_dir("layers-ceiling-board");
    // A 2 cm board under the plate instead of the block: with the set thickness (0.5 m) its slab is
    // a wall down to 0.4 m; to its back face (never thinner than a quarter of that) it stays thin.
    // Geometric normals and planar patches, where back faces are taken exactly (the triangulated
    // surface keeps every slab at least the set thickness).
    let desc = plate_over(&dir, Vec3::new(-0.8, 0.88, -4.0), Vec3::new(0.0, 0.9, 4.0));
    let mut e = engine(&ctx, &desc);
    let separation = desc.ao.layer_separation_metres();
    let capture = |e: &mut opengl3d::render::Engine, back_faces| {
        let what = Capture {
            back_faces,
            normals: true,
            second_layer: Some(separation),
        };
        DepthBuffer {
            surface: Surface::Patches,
            ..captured(e, what, &desc)
        }
    };
    let set = capture(&mut e, false);
    let exact = capture(&mut e, true);
    assert!(set.second_back_depth.is_none());
    let back = exact
        .second_back_depth
        .as_ref()
        .expect("the second layer's back faces captured");
    // Over the board its back face is the underside, 0.88 m up: the plate's depth along the
    // camera ray scaled by the heights below the eye.
    let cam = ref_camera(&e);
    let (mut over_board, mut undersides) = (0, 0);
    for (i, p) in surface_points_of(&exact, &cam) {
        if p.y > 1.4 && p.x < -0.1 && p.x > -0.7 && p.z.abs() < 0.5 {
            over_board += 1;
            let want = exact.linear_depth[i] * (5.0 - 0.88) / (5.0 - 1.52);
            if (back[i] - want).abs() < 0.01 * want {
                undersides += 1;
            }
        }
    }
    assert!(over_board > 50, "{over_board} plate pixels over the board");
    assert!(
        undersides as f64 > 0.95 * over_board as f64,
        "{undersides} of {over_board} plate pixels have the board's underside as the second layer's back face"
    );
    let params = RefParams {
        radius: 1.0,
        rays: 64,
        variant: AoVariant::Visibility,
        seed: 3,
        progress: false,
        supersample: 1,
    };
    let with_set = render_screen_space(&set, &params).unwrap();
    let with_back = render_screen_space(&exact, &params).unwrap();
    let (truth, truth_cam) = engine_truth(&e, &desc, &temp_dir("layers-board-cache"));
    let mean = strip_mean(surface_points(&truth, &truth_cam));
    let (want, a, b) = (mean(&truth.ao), mean(&with_set.ao), mean(&with_back.ao));
    eprintln!("floor beside the board: truth {want:.3}, set thickness {a:.3}, back faces {b:.3}");
    // The wall of the set thickness shades the floor beside the board; the board does much less.
    assert!(
        (b - want).abs() < 0.5 * (a - want).abs(),
        "ceiling with the second layer's back faces {b}, with the set thickness {a}, truth {want}"
    );
}
