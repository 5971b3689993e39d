//! Temporal accumulation of the screen-space methods (`ao::temporal`, `--accumulate N`): on a still
//! camera the mean over frames comes nearer the truth than one frame; where an object moves away
//! the history of the surface it hid is not used (no ghost); many frames on a moving camera stay
//! finite; and with one frame (or the lesson's SAO) nothing changes.

use crate::common;
use crate::reference_screen::params;

use glam::Vec3;
use opengl3d::ao::{AoMethod, AoResolution, GuardBand, NormalSource, Thickness};
use opengl3d::gl::mesh::MeshData;
use opengl3d::render::{Engine, View};
use opengl3d::scene::{shapes, SceneDesc};
use opengl3d::tools::reference::{render_screen_space, DepthBuffer, RefImage};

const W: u32 = 96;
const H: u32 = 72;
const RADIUS: f32 = 1.0;
const THICKNESS: f32 = 0.5;

/// A floor, a wall and a box 1.2 m in front of the wall (index 2 of the objects), `vbao` with few
/// taps and no blur, so that one frame is noisy.
fn scene(dir: &std::path::Path, accumulate: u32) -> SceneDesc {
    let mut wall = MeshData::default();
    shapes::add_box(
        &mut wall,
        Vec3::new(-20.0, 0.0, -3.5),
        Vec3::new(20.0, 10.0, -3.0),
    );
    let mut block = MeshData::default();
    shapes::add_box(
        &mut block,
        Vec3::new(-1.6, 0.0, -1.8),
        Vec3::new(-0.6, 1.0, -0.8),
    );
    let mut s = common::floor_and(
        dir,
        &[("wall", &wall), ("block", &block)],
        Vec3::new(-1.2, 2.6, 4.2),
        Vec3::new(-0.4, 0.5, -1.8),
        (W, H),
    );
    s.ao.method = AoMethod::Vbao;
    s.ao.resolution = AoResolution::Full;
    s.ao.radius = RADIUS;
    s.ao.thickness = Some(Thickness::Metres(THICKNESS));
    s.ao.bias = 5e-4;
    s.ao.blur = false;
    s.ao.samples = 8;
    s.ao.normals = NormalSource::Depth;
    s.ao.guard_band = GuardBand::Off;
    s.ao.accumulate = accumulate;
    s
}

/// The AO view's visibility after `frames` frames (rows top-down).
fn frames(eng: &mut Engine, frames: u32) -> Vec<f32> {
    let mut out = Vec::new();
    for _ in 0..frames {
        out = eng.render_values(View::Ao).unwrap();
        common::assert_finite("temporal", &out);
    }
    out
}

/// The screen-space truth of the engine's current view with vbao's thickness.
fn truth(eng: &mut Engine) -> RefImage {
    let depth = DepthBuffer::from_engine(eng)
        .unwrap()
        .with_thickness(THICKNESS);
    render_screen_space(&depth, &params(RADIUS, 128)).unwrap()
}

/// RMS error over `pixels` (all surface pixels when `None`).
fn rmse(vis: &[f32], truth: &RefImage, pixels: Option<&[usize]>) -> f64 {
    let all: Vec<usize> = (0..vis.len())
        .filter(|i| truth.linear_depth[*i].is_finite())
        .collect();
    let pixels = pixels.unwrap_or(&all);
    let sum: f64 = pixels
        .iter()
        .map(|i| (vis[*i] as f64 - truth.ao[*i] as f64).powi(2))
        .sum();
    (sum / pixels.len().max(1) as f64).sqrt()
}

#[test]
fn accumulating_frames_on_a_still_camera_comes_nearer_the_truth() {
    let ctx = common::context();
    let dir = common::temp_dir("temporal-still");
    let mut eng = common::engine(&ctx, &scene(&dir, 16));
    let one = frames(&mut eng, 1);
    eng.temporal.restart();
    let many = frames(&mut eng, 16);
    let t = truth(&mut eng);
    let (e1, e16) = (rmse(&one, &t, None), rmse(&many, &t, None));
    // With 2 taps per side, part of one frame's error is the bias of so few steps (the union of
    // their sectors is not the mean of it), which no number of frames removes: 0.054 -> 0.045 here.
    assert!(
        e16 < 0.9 * e1,
        "rmse after 1 frame {e1:.4}, after 16 frames {e16:.4}: the mean should come nearer"
    );
}

#[test]
fn the_first_accumulated_frame_is_the_single_frame_and_sao_lesson_is_untouched() {
    let ctx = common::context();
    let dir = common::temp_dir("temporal-first");
    let single = frames(&mut common::engine(&ctx, &scene(&dir, 1)), 1);
    let first = frames(&mut common::engine(&ctx, &scene(&dir, 16)), 1);
    assert_eq!(single, first, "frame 0 turns nothing and has no history");
    let lesson = |accumulate: u32| {
        let mut s = scene(&dir, accumulate);
        s.ao = opengl3d::ao::AoSettings {
            accumulate,
            ..Default::default()
        };
        let mut eng = common::engine(&ctx, &s);
        (0..3).map(|_| eng.render_image().unwrap()).last().unwrap()
    };
    assert!(
        lesson(1).as_raw() == lesson(8).as_raw(),
        "sao-lesson with --accumulate 8 differs from one frame"
    );
}

#[test]
fn an_object_moving_away_leaves_no_ghost_where_it_stood() {
    let ctx = common::context();
    let dir = common::temp_dir("temporal-ghost");
    let mut eng = common::engine(&ctx, &scene(&dir, 32));
    eng.frustum_culling = false;
    let before = frames(&mut eng, 16);
    let depth_before = eng.render_values(View::LinearDepth).unwrap();
    // The box moves 2.5 m to the right: where it stood, the wall and the floor behind it show.
    eng.objects[2].position += Vec3::new(2.5, 0.0, 0.0);
    let depth_after = eng.render_values(View::LinearDepth).unwrap();
    let revealed: Vec<usize> = (0..depth_after.len())
        .filter(|i| depth_after[*i] > depth_before[*i] + 0.5)
        .collect();
    assert!(revealed.len() > 100, "{} pixels revealed", revealed.len());
    let after = frames(&mut eng, 1);
    let t = truth(&mut eng);
    let ghost = rmse(&before, &t, Some(&revealed));
    let accumulated = rmse(&after, &t, Some(&revealed));
    // One frame of a fresh engine at the moved box (no history).
    let mut fresh = common::engine(&ctx, &scene(&dir, 1));
    fresh.objects[2].position += Vec3::new(2.5, 0.0, 0.0);
    fresh.frustum_culling = false;
    let single = rmse(&frames(&mut fresh, 1), &t, Some(&revealed));
    assert!(
        ghost > 2.0 * single,
        "the stale history ({ghost:.4}) is not far enough from the truth for this test to see a \
         ghost (one frame: {single:.4})"
    );
    assert!(
        accumulated <= 1.1 * single + 0.01,
        "revealed pixels: rmse {accumulated:.4} after the move against {single:.4} for one \
         frame (stale history: {ghost:.4})"
    );
}

#[test]
fn many_frames_on_a_moving_camera_stay_finite_and_in_range() {
    let ctx = common::context();
    let dir = common::temp_dir("temporal-orbit");
    let mut s = scene(&dir, 64);
    s.ao.blur = true;
    s.ao.resolution = AoResolution::Half;
    let mut eng = common::engine(&ctx, &s);
    let (eye, target) = (eng.camera.eye, eng.camera.target);
    for i in 0..96 {
        let a = i as f32 * 0.05;
        let offset = eye - target;
        let (sin, cos) = a.sin_cos();
        let turned = Vec3::new(
            offset.x * cos - offset.z * sin,
            offset.y,
            offset.x * sin + offset.z * cos,
        );
        eng.camera.eye = target + turned * (1.0 + 0.3 * (a * 2.0).sin());
        let vis = eng.render_values(View::Ao).unwrap();
        common::assert_finite("orbit", &vis);
        assert!(
            vis.iter().all(|v| (0.0..=1.0).contains(v)),
            "frame {i}: visibility outside [0, 1]"
        );
    }
    assert_eq!(eng.temporal.frames(), 96);
    // The mean holds at most `accumulate` frames, as `render --stats` reports it.
    assert_eq!(eng.accumulated_frames(), 64);
}

#[test]
fn render_stats_count_the_frames_a_screen_space_method_accumulated() {
    let dir = common::temp_dir("temporal-stats");
    let out = dir.join("vbao.png");
    let frames_of = |extra: &[&str]| {
        let mut args = vec![
            "render", "--method", "vbao", "--width", "160", "--height", "90",
        ];
        args.extend_from_slice(extra);
        args.extend_from_slice(&["--stats", "--out", out.to_str().unwrap()]);
        let o = common::run(&args);
        assert!(o.status.success(), "{}", common::stderr(&o));
        let json: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
        json["accumulated_frames"].as_u64()
    };
    assert_eq!(frames_of(&["--accumulate", "3"]), Some(3));
    assert_eq!(frames_of(&[]), Some(1));
}
