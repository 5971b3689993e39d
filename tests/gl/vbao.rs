//! `vbao` against closed forms: an open floor is fully visible, a 90° crease darkens as the
//! cosine-weighted share of directions that reach the wall within the radius, and the thickness
//! decides whether a thin plate shadows the wall behind it.

use crate::common;

use glam::Vec3;
use opengl3d::ao::{AoMethod, AoResolution, AoSettings, SlicePreset, Thickness};
use opengl3d::gl::mesh::MeshData;
use opengl3d::math::DepthMode;
use opengl3d::render::{Engine, View};
use opengl3d::scene::shapes;
use opengl3d::scene::SceneDesc;

const W: u32 = 640;
const H: u32 = 480;

/// The raw (unblurred) visibility of `scene` with vbao: its highest preset unless the scene sets a
/// sample count.
fn raw_vbao(
    ctx: &opengl3d::platform::HeadlessContext,
    scene: &mut SceneDesc,
) -> (Engine, Vec<f32>) {
    scene.ao.method = AoMethod::Vbao;
    if scene.ao.samples == AoSettings::default().samples {
        scene.ao.quality = Some(SlicePreset::Ultra);
    }
    scene.ao.blur = false;
    scene.bloom.enabled = false;
    let mut eng = common::engine(ctx, scene);
    let vis = eng.render_values(View::AoRaw).unwrap();
    common::assert_finite("vbao", &vis);
    (eng, vis)
}

/// Mean visibility over the pixels where the world points `points` land (3×3 around each).
fn mean_at(eng: &Engine, vis: &[f32], points: &[Vec3]) -> f32 {
    let sum: f32 = points
        .iter()
        .map(|p| {
            let (x, y) = common::project(eng, *p, W, H);
            // render_values rows are top-down; project() gives bottom-up rows.
            common::mean_around(vis, W as usize, H as usize, x, H as usize - 1 - y, 1)
        })
        .sum();
    sum / points.len() as f32
}

/// Points along a line parallel to Z at (x, y).
fn line_along_z(x: f32, y: f32) -> Vec<Vec3> {
    (-10..=10)
        .map(|i| Vec3::new(x, y, i as f32 * 0.1))
        .collect()
}

#[test]
fn vbao_leaves_an_open_floor_fully_visible() {
    let ctx = common::context();
    let dir = common::temp_dir("vbao-floor");
    let mut scene = SceneDesc::default();
    scene.objects.push(common::object(
        &dir,
        "floor",
        &shapes::ground(50.0, 10),
        Vec3::ZERO,
        Vec3::ONE,
    ));
    scene.camera.eye = [0.0, 2.0, 6.0];
    scene.camera.target = [0.0, 0.0, -4.0];
    scene.output.width = W;
    scene.output.height = H;
    let (_, vis) = raw_vbao(&ctx, &mut scene);
    let below = vis.iter().filter(|v| **v < 0.99).count();
    let min = vis.iter().cloned().fold(1.0, f32::min);
    assert!(
        below as f32 <= 0.01 * vis.len() as f32,
        "{below} of {} floor pixels are occluded by more than 1 % (min visibility {min})",
        vis.len()
    );
}

#[test]
fn vbao_follows_the_closed_form_of_a_right_angle_crease() {
    let ctx = common::context();
    let dir = common::temp_dir("vbao-crease");
    let mut scene = common::crease_scene(&dir, Vec3::new(4.0, 2.5, 4.0), Vec3::ZERO, W, H);
    scene.ao.radius = 1.0;
    // 2 slices x 64 steps: with few steps sectors between two taps' slabs stay open and occlusion
    // comes out low (low, 1 x 4: 0.397 / 0.223 / 0.091); it converges as steps grow.
    scene.ao.samples = 256;
    let (eng, vis) = raw_vbao(&ctx, &mut scene);
    let mut report = Vec::new();
    for d in [0.15f32, 0.35, 0.6] {
        // A floor point d from an infinite wall: cosine-weighted directions project uniformly onto
        // the unit disc, and those reaching the wall within R are the disc segment x <= -d/R.
        let a = d / scene.ao.radius;
        let expected = (a.acos() - a * (1.0 - a * a).sqrt()) / std::f32::consts::PI;
        let occlusion = 1.0 - mean_at(&eng, &vis, &line_along_z(d, 0.0));
        report.push(format!("d {d}: {occlusion:.3} (closed form {expected:.3})"));
        assert!(
            (occlusion - expected).abs() < 0.03,
            "crease occlusion: {}",
            report.join(", ")
        );
    }
    eprintln!("{}", report.join(", "));
}

/// A 2 cm plate 1.5 m in front of a wall, seen from the front, and points on the wall beside the
/// plate's silhouette: more than R = 1 m from any part of the plate, so nothing occludes them.
fn plate_scene(dir: &std::path::Path) -> (SceneDesc, Vec<Vec3>) {
    let mut wall = MeshData::default();
    shapes::add_box(
        &mut wall,
        Vec3::new(-20.0, -10.0, -3.0),
        Vec3::new(20.0, 10.0, -2.0),
    );
    let mut plate = MeshData::default();
    shapes::add_box(
        &mut plate,
        Vec3::new(-0.5, 0.0, -0.51),
        Vec3::new(0.5, 2.0, -0.49),
    );
    let mut s = SceneDesc::default();
    s.objects
        .push(common::object(dir, "wall", &wall, Vec3::ZERO, Vec3::ONE));
    s.objects
        .push(common::object(dir, "plate", &plate, Vec3::ZERO, Vec3::ONE));
    s.camera.eye = [0.3, 1.0, 3.0];
    s.camera.target = [0.0, 1.0, -2.0];
    s.output.width = W;
    s.output.height = H;
    s.ao.radius = 1.0;
    // The plate's right edge (x = 0.5 at z = -0.5) hides the wall up to x = 0.586.
    let beside = (-4..=4)
        .map(|i| Vec3::new(0.65, 1.0 + i as f32 * 0.05, -2.0))
        .collect();
    (s, beside)
}

#[test]
fn thickness_decides_whether_a_thin_plate_shadows_the_wall_behind_it() {
    let ctx = common::context();
    let dir = common::temp_dir("vbao-plate");
    let (base, beside) = plate_scene(&dir);
    let at = |thickness: Thickness| {
        let mut s = base.clone();
        s.ao.thickness = Some(thickness);
        let (eng, vis) = raw_vbao(&ctx, &mut s);
        mean_at(&eng, &vis, &beside)
    };
    let thin = at(Thickness::Metres(0.05));
    let solid = at(Thickness::Metres(100.0));
    let back = at(Thickness::Backface);
    eprintln!(
        "wall beside the plate: thickness 0.05 m {thin:.3}, 100 m {solid:.3}, back faces {back:.3}"
    );
    assert!(
        thin > 0.97,
        "a 5 cm slab must not shadow a wall 1.5 m behind it: {thin}"
    );
    assert!(
        solid < thin - 0.1,
        "a 100 m slab reaches the wall behind the plate's edge: {solid} vs {thin}"
    );
    assert!(
        back > 0.97,
        "the plate's back faces make it 2 cm thick: {back}"
    );
}

#[test]
fn back_face_depth_of_a_box_is_its_depth_extent() {
    let ctx = common::context();
    let dir = common::temp_dir("vbao-backface");
    // A box 0.7 m deep, its front face 3 m from the camera and filling the view's centre.
    let mut boxed = MeshData::default();
    shapes::add_box(
        &mut boxed,
        Vec3::new(-2.0, -2.0, -3.7),
        Vec3::new(2.0, 2.0, -3.0),
    );
    for mode in [DepthMode::D32, DepthMode::D32fReversed] {
        for resolution in [AoResolution::Half, AoResolution::Full] {
            let mut s = SceneDesc::default();
            s.objects
                .push(common::object(&dir, "box", &boxed, Vec3::ZERO, Vec3::ONE));
            s.camera.eye = [0.0, 0.0, 0.0];
            s.camera.target = [0.0, 0.0, -1.0];
            s.output.width = 64;
            s.output.height = 48;
            s.output.depth = mode;
            s.ao.method = AoMethod::Vbao;
            s.ao.thickness = Some(Thickness::Backface);
            s.ao.resolution = resolution;
            let mut eng = common::engine(&ctx, &s);
            eng.render_values(View::Ao).unwrap();
            let back = eng.back_face_depth().expect("the back-face pass ran");
            let (w, h) = (back.width() as usize, back.height() as usize);
            let values = back.read_f32(0, 1);
            // The central quarter sees the box's front face at 3 m and its back face at 3.7 m.
            for y in h / 4..3 * h / 4 {
                for x in w / 4..3 * w / 4 {
                    let v = values[y * w + x];
                    assert!(
                        (v - 3.7).abs() < 1e-3,
                        "{mode:?} {resolution:?}: back depth {v} at ({x}, {y})"
                    );
                }
            }
        }
    }
    // Without `backface` the pass does not run.
    let (mut s, _) = plate_scene(&dir);
    s.ao.method = AoMethod::Vbao;
    let mut eng = common::engine(&ctx, &s);
    eng.render_values(View::Ao).unwrap();
    assert!(eng.back_face_depth().is_none());
}
