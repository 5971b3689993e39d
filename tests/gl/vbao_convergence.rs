//! As its sample count grows, `vbao` converges to the screen-space ceiling with the same thickness:
//! the same depth buffer as slabs of the same thickness, integrated exactly per triangle with
//! Monte Carlo rays (`reference --screen-space --thickness T`).

use crate::common;
use crate::reference_screen::{params, ref_camera};

use glam::Vec3;
use opengl3d::ao::{AoMethod, AoResolution, Thickness};
use opengl3d::gl::mesh::MeshData;
use opengl3d::render::{Engine, View};
use opengl3d::scene::{shapes, SceneDesc};
use opengl3d::tools::reference::{render_screen_space, DepthBuffer, RefImage};

const W: u32 = 160;
const H: u32 = 120;
const RADIUS: f32 = 1.0;
const THICKNESS: f32 = 0.3;
const CEILING_RAYS: u32 = 1024;

/// A floor, a wall behind, a box standing on the floor near the wall and a thin plate standing
/// free: creases (floor–wall, box–floor, box–wall), an overhang-free corner, a slab thinner than
/// T, silhouettes against the wall. The camera stays far enough (depth > 3 m) that vbao's screen
/// radius is never clamped (max 40 px at 160×120 against 104 px/m at 1 m).
fn scene(dir: &std::path::Path) -> SceneDesc {
    let mut wall = MeshData::default();
    shapes::add_box(
        &mut wall,
        Vec3::new(-20.0, 0.0, -3.5),
        Vec3::new(20.0, 10.0, -3.0),
    );
    let mut block = MeshData::default();
    shapes::add_box(
        &mut block,
        Vec3::new(-1.4, 0.0, -2.7),
        Vec3::new(-0.6, 0.8, -1.9),
    );
    let mut plate = MeshData::default();
    shapes::add_box(
        &mut plate,
        Vec3::new(0.5, 0.0, -1.51),
        Vec3::new(1.5, 1.2, -1.49),
    );
    let mut s = SceneDesc::default();
    s.objects.push(common::object(
        dir,
        "floor",
        &shapes::ground(50.0, 10),
        Vec3::ZERO,
        Vec3::ONE,
    ));
    for (name, mesh) in [("wall", &wall), ("block", &block), ("plate", &plate)] {
        s.objects
            .push(common::object(dir, name, mesh, Vec3::ZERO, Vec3::ONE));
    }
    s.camera.eye = [0.8, 2.6, 4.2];
    s.camera.target = [0.0, 0.5, -1.8];
    s.output.width = W;
    s.output.height = H;
    s.bloom.enabled = false;
    s.ao.method = AoMethod::Vbao;
    s.ao.resolution = AoResolution::Full;
    s.ao.radius = RADIUS;
    // The ceiling lifts its rays' origin 1e-4·|p| off the surface (about 0.5 mm here).
    s.ao.bias = 5e-4;
    s.ao.thickness = Some(Thickness::Metres(THICKNESS));
    s.ao.blur = false;
    s
}

/// vbao's raw visibility (rows top-down) with `samples` depth taps per pixel.
fn vbao_at(eng: &mut Engine, samples: u32) -> Vec<f32> {
    eng.ao_settings.samples = samples;
    eng.ao_settings.quality = None;
    let vis = eng.render_values(View::AoRaw).unwrap();
    common::assert_finite("vbao", &vis);
    vis
}

struct Errors {
    pixel_mae: f64,
    pixel_rmse: f64,
    block_mae: f64,
    block_rmse: f64,
    block_bias: f64,
}

/// Errors of `vis` against the ceiling over non-sky pixels, and over the 4×4 blocks (aligned with
/// vbao's 4×4 rotation tile) whose 16 pixels are all surface.
fn errors(vis: &[f32], ceiling: &RefImage) -> Errors {
    let (w, h) = (W as usize, H as usize);
    let (mut n, mut sa, mut ss) = (0.0f64, 0.0f64, 0.0f64);
    for i in 0..w * h {
        if ceiling.linear_depth[i].is_finite() {
            let e = vis[i] as f64 - ceiling.ao[i] as f64;
            n += 1.0;
            sa += e.abs();
            ss += e * e;
        }
    }
    let (mut nb, mut ba, mut bs, mut bb) = (0.0f64, 0.0f64, 0.0f64, 0.0f64);
    for by in 0..h / 4 {
        for bx in 0..w / 4 {
            let idx: Vec<usize> = (0..16)
                .map(|k| (by * 4 + k / 4) * w + bx * 4 + k % 4)
                .collect();
            if idx.iter().any(|i| !ceiling.linear_depth[*i].is_finite()) {
                continue;
            }
            let e = idx
                .iter()
                .map(|i| vis[*i] as f64 - ceiling.ao[*i] as f64)
                .sum::<f64>()
                / 16.0;
            nb += 1.0;
            ba += e.abs();
            bs += e * e;
            bb += e;
        }
    }
    Errors {
        pixel_mae: sa / n,
        pixel_rmse: (ss / n).sqrt(),
        block_mae: ba / nb,
        block_rmse: (bs / nb).sqrt(),
        block_bias: bb / nb,
    }
}

#[test]
fn vbao_converges_to_the_screen_space_ceiling_with_the_same_thickness() {
    let ctx = common::context();
    let dir = common::temp_dir("vbao-convergence");
    let desc = scene(&dir);
    let mut eng = common::engine(&ctx, &desc);
    let depth = DepthBuffer::from_engine(&mut eng)
        .unwrap()
        .with_thickness(THICKNESS);
    let _cam = ref_camera(&eng);
    let t0 = std::time::Instant::now();
    let ceiling = render_screen_space(&depth, &params(RADIUS, CEILING_RAYS)).unwrap();
    eprintln!("ceiling: {:.1} s", t0.elapsed().as_secs_f64());
    let raw: Vec<u8> = ceiling.ao.iter().chain(ceiling.std_error.iter()).chain(ceiling.linear_depth.iter()).flat_map(|v| v.to_le_bytes()).collect();
    std::fs::write(format!("/tmp/conv-ceiling-{CEILING_RAYS}.f32"), raw).unwrap();
    let sky = ceiling
        .linear_depth
        .iter()
        .filter(|d| !d.is_finite())
        .count();
    let min_depth = ceiling
        .linear_depth
        .iter()
        .copied()
        .fold(f32::INFINITY, f32::min);
    eprintln!("sky pixels {sky}, nearest depth {min_depth}");
    for samples in [8u32, 16, 32, 64, 128, 256] {
        let vis = vbao_at(&mut eng, samples);
        let raw: Vec<u8> = vis.iter().flat_map(|v| v.to_le_bytes()).collect();
        std::fs::write(format!("/tmp/conv-vbao-{samples}.f32"), raw).unwrap();
        let e = errors(&vis, &ceiling);
        eprintln!(
            "samples {samples}: pixel mae {:.4} rmse {:.4}; 4x4 block mae {:.4} rmse {:.4} bias {:+.4}",
            e.pixel_mae, e.pixel_rmse, e.block_mae, e.block_rmse, e.block_bias
        );
    }
}
