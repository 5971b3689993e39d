//! No NaN or Inf in any buffer of the pipeline, whatever the scene and size.

use crate::common;

use glam::Vec3;
use opengl3d::gl::mesh::MeshData;
use opengl3d::render::{Engine, View};
use opengl3d::scene::{shapes, SceneDesc};

/// Renders every view and checks every intermediate buffer.
fn check_all_buffers(label: &str, eng: &mut Engine) {
    let img = eng.render_image().unwrap();
    assert_eq!(img.dimensions(), eng.size());
    common::assert_finite(
        &format!("{label}: main colour"),
        &eng.fbo_main.color_texture().unwrap().read_f32(0, 4),
    );
    let t = &eng.ao_targets().unwrap().tex_depth;
    for level in 0..t.levels() {
        let v = t.read_f32(level, 1);
        common::assert_finite(&format!("{label}: linear depth level {level}"), &v);
        assert!(
            v.iter().all(|d| *d > 0.0),
            "{label}: linear depth level {level} has a non-positive distance"
        );
    }
    common::assert_finite(
        &format!("{label}: SAO"),
        &eng.ao_targets().unwrap().sao_texture().read_f32(0, 1),
    );
    common::assert_finite(
        &format!("{label}: blurred SAO"),
        &eng.ao_targets()
            .unwrap()
            .result_texture(true)
            .read_f32(0, 1),
    );
    for view in [View::LinearDepth, View::AoRaw, View::Ao] {
        let v = eng.render_values(view).unwrap();
        common::assert_finite(&format!("{label}: {view:?} values"), &v);
        if view != View::LinearDepth {
            assert!(
                v.iter().all(|a| (0.0..=1.0).contains(a)),
                "{label}: visibility outside [0,1]"
            );
        }
    }
}

#[test]
fn sky_only_frame_is_finite_and_fully_visible() {
    let ctx = common::context();
    let mut scene = SceneDesc::default();
    scene.output.width = 64;
    scene.output.height = 48;
    let mut eng = common::engine(&ctx, &scene);
    check_all_buffers("sky only", &mut eng);
    let v = eng.render_values(View::Ao).unwrap();
    assert!(v.iter().all(|a| *a == 1.0), "sky must be fully visible");
}

#[test]
fn camera_inside_a_box_is_finite() {
    let ctx = common::context();
    let dir = common::temp_dir("inside-box");
    let mut scene = SceneDesc::default();
    let mut cube = MeshData::default();
    shapes::add_box(&mut cube, Vec3::splat(-1.0), Vec3::splat(1.0));
    scene.objects.push(common::object(
        &dir,
        "cube",
        &cube,
        Vec3::ZERO,
        Vec3::splat(2.0),
    ));
    scene.camera.eye = [0.3, 0.2, 0.1];
    scene.camera.target = [1.0, 0.0, -1.0];
    scene.output.width = 96;
    scene.output.height = 64;
    let mut eng = common::engine(&ctx, &scene);
    check_all_buffers("inside a box", &mut eng);
}

#[test]
fn tiny_and_odd_sizes_are_finite() {
    let ctx = common::context();
    let dir = common::temp_dir("odd-sizes");
    for (w, h) in [(1, 1), (3, 5), (5, 3), (2, 1), (33, 17)] {
        let mut scene = common::crease_scene(&dir, Vec3::new(4.0, 2.5, 4.0), Vec3::ZERO, w, h);
        scene.bloom.enabled = true;
        let mut eng = common::engine(&ctx, &scene);
        check_all_buffers(&format!("{w}x{h}"), &mut eng);
    }
}

#[test]
fn camera_at_the_near_plane_of_a_wall_is_finite() {
    let ctx = common::context();
    let dir = common::temp_dir("near-wall");
    // The eye 0.36 m from the wall with near = 0.35: the wall fills the view, almost on the near plane.
    let mut scene = common::crease_scene(
        &dir,
        Vec3::new(0.36, 1.0, 0.0),
        Vec3::new(0.0, 1.0, 0.0),
        80,
        60,
    );
    scene.ao.radius = 100.0;
    let mut eng = common::engine(&ctx, &scene);
    check_all_buffers("near plane", &mut eng);
}

#[test]
fn resizing_keeps_buffers_finite_and_zero_size_is_ignored() {
    let ctx = common::context();
    let dir = common::temp_dir("resize");
    let scene = common::crease_scene(&dir, Vec3::new(4.0, 2.5, 4.0), Vec3::ZERO, 64, 48);
    let mut eng = common::engine(&ctx, &scene);
    eng.resize(0, 0).unwrap();
    assert_eq!(
        eng.size(),
        (64, 48),
        "a minimised (0×0) window keeps the old targets"
    );
    eng.resize(31, 7).unwrap();
    assert_eq!(eng.size(), (31, 7));
    check_all_buffers("after resize", &mut eng);
}
