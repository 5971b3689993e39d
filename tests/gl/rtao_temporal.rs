//! `rtao` accumulated through camera motion on real Mesa GL: the history is reprojected (not
//! restarted) when the camera moves, so the image stays nearer the CPU ray tracer's than a restarted
//! mean; it starts again when an object moves; the first frame and `--accumulate 1` are the
//! single-frame image; and the mean undoes the intensity curve.

use super::rtao::{reference, rmse, scene};
use crate::common;

use glam::Vec3;
use opengl3d::ao::AoMethod;
use opengl3d::render::{Engine, View};
use opengl3d::scene::SceneDesc;

const EYE: Vec3 = Vec3::new(2.5, 2.0, 3.0);
const TARGET: Vec3 = Vec3::new(0.0, 0.4, 0.0);

/// Two boxes on the floor, rtao at full size, unblurred, one ray per frame, 16 frames.
fn boxes(name: &str) -> SceneDesc {
    let dir = common::temp_dir(name);
    let mut s = scene(
        &dir,
        EYE,
        TARGET,
        &[
            ("a", Vec3::new(-1.0, 0.0, -1.0), Vec3::new(0.0, 1.2, 0.0)),
            ("b", Vec3::new(0.3, 0.0, 0.2), Vec3::new(0.8, 0.5, 0.9)),
        ],
    );
    s.ao.rays = 1;
    s.ao.accumulate = 16;
    s
}

fn frame(eng: &mut Engine) -> Vec<f32> {
    let v = eng.render_values(View::AoRaw).unwrap();
    common::assert_finite("rtao accumulated", &v);
    assert!(v.iter().all(|x| (0.0..=1.0).contains(x)));
    v
}

/// The camera `step` small moves (an orbit of 0.4° and a dolly of 0.4 % each) from the start.
fn moved(eng: &Engine, step: u32) -> opengl3d::math::Camera {
    let turn = glam::Quat::from_rotation_y((-0.4 * step as f32).to_radians());
    let offset = (EYE - TARGET) * (1.0 - 0.004 * step as f32);
    opengl3d::math::Camera {
        eye: TARGET + turn * offset,
        ..eng.camera
    }
}

#[test]
fn rtao_keeps_its_history_through_camera_motion_and_restarts_when_an_object_moves() {
    let ctx = common::context();
    let s = boxes("rtao-temporal-motion");
    let mut eng = common::engine(&ctx, &s);
    for _ in 0..16 {
        frame(&mut eng);
    }
    // Four small moves: the history follows the camera instead of starting again.
    let steps = 4;
    let mut accumulated = Vec::new();
    for k in 1..=steps {
        eng.camera = moved(&eng, k);
        accumulated = frame(&mut eng);
    }
    assert_eq!(eng.ao.accumulated_frames(AoMethod::Rtao), 16);
    assert_eq!(eng.accumulated_frames(), 16);
    let truth = reference(&eng, 4096);

    // What the old restart would give at the same camera: the mean of the frames since it moved.
    let mut restarted = common::engine(&ctx, &s);
    restarted.camera = eng.camera;
    let mut since_move = Vec::new();
    for _ in 0..steps {
        since_move = frame(&mut restarted);
    }
    let mut single_scene = s.clone();
    single_scene.ao.accumulate = 1;
    let mut single = common::engine(&ctx, &single_scene);
    single.camera = eng.camera;
    let one = frame(&mut single);

    let (e_acc, e_restart, e_one) = (
        rmse(&accumulated, &truth.ao),
        rmse(&since_move, &truth.ao),
        rmse(&one, &truth.ao),
    );
    eprintln!("after the move: reprojected {e_acc}, restarted ({steps} frames) {e_restart}, one frame {e_one}");
    assert!(
        e_acc < e_one / 2.5,
        "reprojected {e_acc}, one frame {e_one}"
    );
    assert!(
        e_acc < e_restart * 0.75,
        "reprojected {e_acc}, restarted {e_restart}"
    );

    // Box b moves: the occlusion of what stayed in view changed, and the mean starts again with
    // exactly the single-frame image of the new scene.
    // The floor, a, b: b is the last object.
    let b = eng.objects.len() - 1;
    eng.objects[b].position.x += 0.4;
    let after = frame(&mut eng);
    assert_eq!(eng.ao.accumulated_frames(AoMethod::Rtao), 1);
    single.objects[b].position.x += 0.4;
    let fresh = frame(&mut single);
    assert_eq!(
        after, fresh,
        "the first frame after the move is the single-frame image"
    );
    frame(&mut eng);
    assert_eq!(eng.ao.accumulated_frames(AoMethod::Rtao), 2);
}

#[test]
fn rtao_first_accumulated_frame_is_the_single_frame_image() {
    let ctx = common::context();
    let mut s = boxes("rtao-temporal-first");
    s.ao.blur = true;
    s.ao.rays = 2;
    let mut accumulating = common::engine(&ctx, &s);
    s.ao.accumulate = 1;
    let mut single = common::engine(&ctx, &s);
    for view in [View::Ao, View::AoRaw] {
        accumulating.ao.restart_accumulation();
        let a = accumulating.render_values(view).unwrap();
        let b = single.render_values(view).unwrap();
        common::assert_finite("rtao", &a);
        assert_eq!(a, b, "{view:?}");
    }
    // The frames after it differ: their rays move on along the sequence.
    let next = accumulating.render_values(View::AoRaw).unwrap();
    let again = single.render_values(View::AoRaw).unwrap();
    assert_ne!(next, again);
}

#[test]
fn rtao_mean_undoes_the_intensity_curve() {
    let ctx = common::context();
    let mut s = boxes("rtao-temporal-intensity");
    // Intensity 10 squares the visibility: the mean must be that of the traced visibility, squared,
    // not the mean of each frame's squared 0-or-1 rays (which is the visibility itself).
    s.ao.intensity = 10.0;
    let mut eng = common::engine(&ctx, &s);
    let mut mean = Vec::new();
    for _ in 0..16 {
        mean = frame(&mut eng);
    }
    let truth = reference(&eng, 4096);
    let squared: Vec<f32> = truth.ao.iter().map(|v| v * v).collect();
    let (e_squared, e_plain) = (rmse(&mean, &squared), rmse(&mean, &truth.ao));
    eprintln!("16 frames at intensity 10: against vis² {e_squared}, against vis {e_plain}");
    assert!(e_squared < e_plain * 0.8, "vis² {e_squared}, vis {e_plain}");
}
