//! The second depth layer's back faces (`vbao` with `layers = 2` and `thickness = "backface"`) and the
//! `linear-depth-2` view, on real Mesa GL: two boxes one behind the other on the camera's axis, whose
//! depths follow from their sizes; and `vbao` on the hidden block under a plate, against the ray
//! tracer.

use crate::common::*;
use crate::depth_layers::{engine_truth, hidden_block, plate_over, strip_mean};
use glam::Vec3;
use opengl3d::ao::{AoMethod, AoResolution, AoSettings, Thickness};
use opengl3d::gl::mesh::MeshData;
use opengl3d::math::DepthMode;
use opengl3d::render::View;
use opengl3d::scene::{shapes, SceneDesc};

const W: u32 = 64;
const H: u32 = 48;
/// Depths along the view axis: the wall's front and back, the hidden box's front and back.
const WALL: (f32, f32) = (3.0, 3.2);
const HIDDEN: (f32, f32) = (5.0, 6.0);
/// The hidden box's half width, and the wall's.
const HIDDEN_HALF: f32 = 0.5;
const WALL_HALF: f32 = 2.0;

/// A wall 0.2 m thick 3 m in front of the camera (the origin, looking down −z) and behind it, on the
/// axis, a 1 m box 5 m away that the camera cannot see. R = 1 m: the second layer begins 0.1 m
/// behind the visible surface, so the wall's own back face (a back face, and too close) is never it.
fn wall_and_hidden_box(dir: &std::path::Path) -> SceneDesc {
    let mut wall = MeshData::default();
    shapes::add_box(
        &mut wall,
        Vec3::new(-WALL_HALF, -WALL_HALF, -WALL.1),
        Vec3::new(WALL_HALF, WALL_HALF, -WALL.0),
    );
    let mut hidden = MeshData::default();
    shapes::add_box(
        &mut hidden,
        Vec3::new(-HIDDEN_HALF, -HIDDEN_HALF, -HIDDEN.1),
        Vec3::new(HIDDEN_HALF, HIDDEN_HALF, -HIDDEN.0),
    );
    let mut desc = SceneDesc::default();
    desc.objects
        .push(object(dir, "wall", &wall, Vec3::ZERO, Vec3::ONE));
    desc.objects
        .push(object(dir, "hidden", &hidden, Vec3::ZERO, Vec3::ONE));
    desc.camera.eye = [0.0, 0.0, 0.0];
    desc.camera.target = [0.0, 0.0, -1.0];
    desc.camera.fov_y = 60.0;
    desc.output.width = W;
    desc.output.height = H;
    desc.bloom.enabled = false;
    desc.ao = AoSettings {
        method: AoMethod::Vbao,
        thickness: Some(Thickness::Backface),
        layers: 2,
        resolution: AoResolution::Full,
        blur: false,
        radius: 1.0,
        ..AoSettings::default()
    };
    desc
}

/// What a pixel's ray meets, from the geometry: the hidden box (clear of its edges), the wall only,
/// or nothing; `None` within `margin` metres of an edge.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Hit {
    Hidden,
    WallOnly,
    Sky,
}

/// `x`, `y` from the top-left, in a `w`×`h` image of the 60° camera.
fn hit(x: usize, y: usize, w: usize, h: usize) -> Option<Hit> {
    let t = 30f32.to_radians().tan();
    let aspect = w as f32 / h as f32;
    let nx = ((x as f32 + 0.5) / w as f32 * 2.0 - 1.0) * t * aspect;
    let ny = (1.0 - (y as f32 + 0.5) / h as f32 * 2.0) * t;
    // Lateral position per metre of depth; a box face at depth d spans |x|, |y| <= half.
    let inside = |d: f32, half: f32, margin: f32| {
        nx.abs() * d < half - margin && ny.abs() * d < half - margin
    };
    let outside = |d: f32, half: f32, margin: f32| {
        nx.abs() * d > half + margin || ny.abs() * d > half + margin
    };
    let m = 0.08;
    if inside(HIDDEN.0, HIDDEN_HALF, m) && inside(HIDDEN.1, HIDDEN_HALF, m) {
        Some(Hit::Hidden)
    } else if inside(WALL.0, WALL_HALF, m)
        && outside(HIDDEN.0, HIDDEN_HALF, m)
        && outside(HIDDEN.1, HIDDEN_HALF, m)
    {
        Some(Hit::WallOnly)
    } else if outside(WALL.0, WALL_HALF, m) && outside(WALL.1, WALL_HALF, m) {
        Some(Hit::Sky)
    } else {
        None
    }
}

/// Counts of the pixels of each kind whose value is `want(kind)` within 1 mm (rows top-down).
fn check_depths(label: &str, v: &[f32], w: usize, h: usize, want: impl Fn(Hit) -> f32) {
    let mut counts = [(0, 0); 3];
    for y in 0..h {
        for x in 0..w {
            let Some(kind) = hit(x, y, w, h) else {
                continue;
            };
            let c = &mut counts[kind as usize];
            c.0 += 1;
            let (got, expect) = (v[y * w + x], want(kind));
            if (got - expect).abs() <= 1e-3 * expect.max(1.0) {
                c.1 += 1;
            } else if c.0 - c.1 <= 3 {
                eprintln!("{label}: pixel ({x}, {y}) {kind:?}: {got}, want {expect}");
            }
        }
    }
    for (kind, (n, ok)) in [Hit::Hidden, Hit::WallOnly, Hit::Sky]
        .into_iter()
        .zip(counts)
    {
        assert!(n >= 4, "{label}: only {n} {kind:?} pixels");
        assert_eq!(
            ok, n,
            "{label}: {ok} of {n} {kind:?} pixels at the known depth"
        );
    }
}

/// Rows bottom-up (GL) to top-down.
fn top_down(mut v: Vec<f32>, w: usize, h: usize) -> Vec<f32> {
    opengl3d::gl::readback::flip_rows(&mut v, w, h);
    v
}

#[test]
fn the_second_layers_back_faces_lie_at_the_hidden_boxs_back_in_both_depth_modes() {
    let ctx = context();
    let dir = temp_dir("layer2-back-boxes");
    let desc = wall_and_hidden_box(&dir);
    let far = desc.camera.far;
    for mode in DepthMode::ALL {
        let mut e = engine(&ctx, &desc);
        e.set_depth_mode(mode).unwrap();
        e.collect_stats = true;
        let v = e.render_values(View::AoRaw).unwrap();
        assert_finite("vbao", &v);
        let names: Vec<_> = e.last_stats().iter().map(|s| s.name).collect();
        assert!(names.contains(&"second layer back faces"), "{names:?}");
        let (w, h) = (W as usize, H as usize);
        let layer = top_down(e.second_layer_depth().unwrap().read_f32(0, 1), w, h);
        let back = top_down(e.second_layer_back_depth().unwrap().read_f32(0, 1), w, h);
        let label = format!("{mode:?}");
        // On the axis the hidden box's faces are planes of constant view depth: 5 m and 6 m; the
        // wall's back face (3.2 m) is in front of the second layer and never its back.
        check_depths(&format!("{label} layer 2"), &layer, w, h, |k| match k {
            Hit::Hidden => HIDDEN.0,
            _ => far,
        });
        check_depths(&format!("{label} layer 2 back"), &back, w, h, |k| match k {
            Hit::Hidden => HIDDEN.1,
            _ => far,
        });
    }
}

#[test]
fn at_half_size_the_second_layers_back_is_the_hidden_boxs_back_where_a_block_sees_only_it() {
    let ctx = context();
    let dir = temp_dir("layer2-back-half");
    let mut desc = wall_and_hidden_box(&dir);
    desc.ao.resolution = AoResolution::Half;
    let mut e = engine(&ctx, &desc);
    e.render_values(View::AoRaw).unwrap();
    let (w, h) = ((W / 2) as usize, (H / 2) as usize);
    let back = top_down(e.second_layer_back_depth().unwrap().read_f32(0, 1), w, h);
    // A half-size texel's 2×2 block sees one kind where the full-size pixel grid does.
    let far = desc.camera.far;
    let mut hidden = 0;
    for y in 0..h {
        for x in 0..w {
            let kinds: Vec<_> = (0..4)
                .map(|i| hit(2 * x + i % 2, 2 * y + i / 2, 2 * w, 2 * h))
                .collect();
            let Some(kind) = kinds[0].filter(|k| kinds.iter().all(|o| *o == Some(*k))) else {
                continue;
            };
            let want = if kind == Hit::Hidden { HIDDEN.1 } else { far };
            hidden += (kind == Hit::Hidden) as usize;
            let got = back[y * w + x];
            assert!(
                (got - want).abs() <= 1e-3 * want,
                "texel ({x}, {y}) {kind:?}: {got}, want {want}"
            );
        }
    }
    assert!(hidden >= 4, "{hidden} texels over the hidden box");
}

#[test]
fn the_second_layer_back_faces_run_only_with_both_back_faces_and_two_layers() {
    let ctx = context();
    let dir = temp_dir("layer2-back-when");
    let base = wall_and_hidden_box(&dir);
    for (thickness, layers) in [(Some(Thickness::Backface), 1), (None, 2)] {
        let mut desc = base.clone();
        desc.ao.thickness = thickness;
        desc.ao.layers = layers;
        let mut e = engine(&ctx, &desc);
        e.collect_stats = true;
        e.render_values(View::AoRaw).unwrap();
        let names: Vec<_> = e.last_stats().iter().map(|s| s.name).collect();
        assert!(
            !names.contains(&"second layer back faces"),
            "{thickness:?}, {layers}: {names:?}"
        );
        assert!(e.second_layer_back_depth().is_none());
    }
}

#[test]
fn the_linear_depth_2_view_shows_the_box_behind_the_wall_and_sky_elsewhere() {
    let ctx = context();
    let dir = temp_dir("layer2-view");
    let mut desc = wall_and_hidden_box(&dir);
    // The view follows the AO size: the default half size, the first layer's view's.
    desc.ao.resolution = AoResolution::Half;
    let far = desc.camera.far;
    let mut e = engine(&ctx, &desc);
    assert_eq!(
        View::from_name("linear-depth-2"),
        Some(View::SecondLayerDepth)
    );
    let (w, h) = (W as usize, H as usize);
    let second = e.render_values(View::SecondLayerDepth).unwrap();
    let first = e.render_values(View::LinearDepth).unwrap();
    // Where the first layer is the wall, the second is the hidden box's front (5 m) or sky; where
    // the first is sky, so is the second.
    let mut seen = [0; 3];
    for y in 0..h {
        for x in 0..w {
            let Some(kind) = hit(x, y, w, h) else {
                continue;
            };
            // Half size: a pixel's texel is its 2×2 block's; keep the pixels whose block is one kind.
            let (bx, by) = (x & !1, y & !1);
            if (0..4).any(|i| hit(bx + i % 2, by + i / 2, w, h) != Some(kind)) {
                continue;
            }
            seen[kind as usize] += 1;
            let i = y * w + x;
            let (want_first, want_second) = match kind {
                Hit::Hidden => (WALL.0, HIDDEN.0),
                Hit::WallOnly => (WALL.0, far),
                Hit::Sky => (far, far),
            };
            assert!(
                (first[i] - want_first).abs() <= 1e-3 * want_first,
                "first ({x}, {y}) {kind:?}: {}",
                first[i]
            );
            assert!(
                (second[i] - want_second).abs() <= 1e-3 * want_second,
                "second ({x}, {y}) {kind:?}: {}",
                second[i]
            );
        }
    }
    assert!(
        seen.iter().all(|n| *n >= 16),
        "{seen:?} pixels of each kind"
    );
    // With one layer there is nothing to show: a clear error, not a stale texture.
    e.ao_settings.layers = 1;
    let err = e
        .render_values(View::SecondLayerDepth)
        .unwrap_err()
        .to_string();
    assert!(err.contains("--layers 2"), "{err}");
}

#[test]
fn the_window_skips_the_second_layers_view_without_a_second_layer() {
    assert_eq!(View::LinearDepth.next(false), View::AoRaw);
    assert_eq!(View::LinearDepth.next(true), View::SecondLayerDepth);
    assert!(!View::SecondLayerDepth.available(false));
    assert!(View::ALL.iter().all(|v| v.available(true)));
}

/// `vbao`'s visibility (raw, rows top-down) with two layers and the set thickness, then with back
/// faces; the means over the floor strip beside the hidden box of the ray-traced truth and of both
/// runs; and the floor pixels out of the hidden box's reach.
fn constant_and_back_faces(
    label: &str,
    desc: &mut SceneDesc,
) -> ([Vec<f32>; 2], [f64; 3], Vec<usize>) {
    let ctx = context();
    let mut runs = Vec::new();
    for thickness in [None, Some(Thickness::Backface)] {
        desc.ao.thickness = thickness;
        desc.ao.layers = 2;
        let mut e = engine(&ctx, desc);
        let v = e.render_values(View::AoRaw).unwrap();
        assert_finite("vbao", &v);
        runs.push(v);
    }
    let e = engine(&ctx, desc);
    let (truth, cam) = engine_truth(&e, desc, &temp_dir(&format!("{label}-cache")));
    let points = surface_points(&truth, &cam);
    // Floor more than R from the plate's edge and the hidden box: no second layer within reach.
    let far_floor = points
        .iter()
        .filter(|(_, p)| p.y.abs() < 1e-3 && p.x > 1.5 && p.z.abs() < 1.0)
        .map(|(i, _)| *i)
        .collect();
    let mean = strip_mean(points);
    let means = [mean(&truth.ao), mean(&runs[0]), mean(&runs[1])];
    eprintln!(
        "{label}: truth {:.4}, set thickness {:.4}, back faces {:.4}",
        means[0], means[1], means[2]
    );
    let [a, b] = <[Vec<f32>; 2]>::try_from(runs).unwrap();
    ([a, b], means, far_floor)
}

/// Pixels out of the hidden box's reach do not change.
fn assert_unchanged(runs: &[Vec<f32>; 2], pixels: &[usize]) {
    assert!(pixels.len() > 50, "{} far floor pixels", pixels.len());
    for &i in pixels {
        let (a, b) = (runs[0][i], runs[1][i]);
        assert!((a - b).abs() < 1e-5, "far floor pixel {i}: {a} vs {b}");
    }
}

#[test]
fn vbao_with_the_second_layers_back_faces_darkens_beside_the_hidden_block_and_not_past_the_truth() {
    let dir = temp_dir("layer2-back-block");
    // The plate (2 cm) and the floor (no back face) take the set thickness in the first layer
    // either way, so the two runs differ only in the hidden block's slab: R/2 from its top (0.9 m
    // down to 0.4 m), or with its back faces down to its bottom on the floor.
    let mut desc = hidden_block(&dir);
    let (runs, [want, constant, backs], far) = constant_and_back_faces("layer2-block", &mut desc);
    assert!(
        backs < constant - 0.02,
        "back faces {backs} vs set thickness {constant} (truth {want})"
    );
    assert!(
        backs > want - 0.05,
        "back faces {backs} darker than the truth {want}"
    );
    assert_unchanged(&runs, &far);
}

#[test]
fn vbao_with_the_second_layers_back_faces_leaves_light_under_a_hidden_thin_board() {
    let dir = temp_dir("layer2-back-board");
    // A 2 cm board 0.6 m up under the plate: with the set thickness its slab is a wall from 0.62 m
    // down to 0.12 m beside the strip; with its back faces it is R/8 thick (exactly 2 cm leaves the
    // strip nearly open: 0.98 against the truth's 0.83, the taps' slabs not covering the board).
    let lo = Vec3::new(-0.8, 0.6, -4.0);
    let mut desc = plate_over(&dir, lo, Vec3::new(0.0, 0.62, 4.0));
    let (runs, [want, constant, backs], far) = constant_and_back_faces("layer2-board", &mut desc);
    assert!(
        constant < want - 0.05,
        "set thickness {constant} not darker than the truth {want}"
    );
    assert!(
        backs > constant + 0.05,
        "back faces {backs} vs set thickness {constant} (truth {want})"
    );
    assert!(
        (backs - want).abs() < 0.5 * (constant - want).abs(),
        "back faces {backs}, set thickness {constant}, truth {want}"
    );
    assert_unchanged(&runs, &far);
}
