//! `rtao` on real Mesa GL: the BVH's std430 layout as GLSL reads it, occluders no depth buffer shows
//! (outside the view, hidden behind another surface), and agreement with the CPU ray tracer that
//! improves with the ray count as Monte-Carlo sampling predicts.

use crate::common;

use glam::Vec3;
use glow::HasContext;
use opengl3d::ao::{AoMethod, AoResolution};
use opengl3d::gl::mesh::MeshData;
use opengl3d::gl::StorageBuffer;
use opengl3d::render::{Engine, View};
use opengl3d::scene::bvh::{FlatBvh, NODE_WORDS, TRIANGLE_WORDS};
use opengl3d::scene::{shapes, SceneDesc};
use opengl3d::tools::reference::{render_reference, RefImage, RefParams, Scene};
use std::path::Path;

pub const W: u32 = 64;
pub const H: u32 = 48;

fn boxed(lo: Vec3, hi: Vec3) -> MeshData {
    let mut m = MeshData::default();
    shapes::add_box(&mut m, lo, hi);
    m
}

/// A floor and the given boxes, seen by `eye` → `target`, rtao at full AO size, unblurred.
pub fn scene(dir: &Path, eye: Vec3, target: Vec3, boxes: &[(&str, Vec3, Vec3)]) -> SceneDesc {
    let meshes: Vec<(&str, MeshData)> = boxes
        .iter()
        .map(|(name, lo, hi)| (*name, boxed(*lo, *hi)))
        .collect();
    let named: Vec<(&str, &MeshData)> = meshes.iter().map(|(n, m)| (*n, m)).collect();
    let mut s = common::floor_and(dir, &named, eye, target, (W, H));
    s.camera.near = 0.1;
    s.camera.far = 40.0;
    s.ao.method = AoMethod::Rtao;
    s.ao.resolution = AoResolution::Full;
    s.ao.blur = false;
    s.ao.radius = 1.0;
    s
}

/// rtao's raw visibility (rows top-down) and the linear depth, with `rays` per pixel.
fn rtao(ctx: &opengl3d::platform::HeadlessContext, s: &SceneDesc, rays: u32) -> (Engine, Vec<f32>) {
    let mut s = s.clone();
    s.ao.rays = rays;
    let mut eng = common::engine(ctx, &s);
    let vis = eng.render_values(View::AoRaw).unwrap();
    common::assert_finite("rtao", &vis);
    assert!(vis.iter().all(|v| (0.0..=1.0).contains(v)));
    (eng, vis)
}

pub fn reference(eng: &Engine, rays: u32) -> RefImage {
    let bvh = Scene::new(eng.world_triangles()).unwrap();
    let params = RefParams {
        radius: eng.ao_settings.radius,
        rays,
        seed: 7,
        ..Default::default()
    };
    render_reference(&bvh, &eng.camera, W, H, &params)
}

pub fn rmse(a: &[f32], b: &[f32]) -> f64 {
    let sum: f64 = a.iter().zip(b).map(|(x, y)| ((x - y) as f64).powi(2)).sum();
    (sum / a.len() as f64).sqrt()
}

#[test]
fn rtao_bvh_layout_reads_back_through_the_glsl_declaration() {
    let ctx = common::context();
    let gl = &ctx.gl;
    let mut tris = Vec::new();
    for i in 0..7 {
        let a = Vec3::new(i as f32 * 1.5, (i % 3) as f32, -(i as f32));
        tris.push([
            a,
            a + Vec3::new(1.0, 0.2, 0.0),
            a + Vec3::new(0.1, 1.0, 0.5),
        ]);
    }
    let bvh = FlatBvh::build(&tris).unwrap();
    let (nodes, triangles) = (bvh.node_words(), bvh.triangle_words());
    let (n, t) = (bvh.nodes.len(), bvh.triangles.len());
    assert!(n >= 3 && t == 7);
    let declaration =
        std::fs::read_to_string(Path::new(env!("CARGO_MANIFEST_DIR")).join("Res/ao/bvh.glsl"))
            .unwrap();
    // Every field copied out word by word: a layout that differs from the documented one (a vec3
    // padded differently, members swapped) puts other words in other places.
    let source = format!(
        "#version 450\nlayout(local_size_x = 1) in;\n{declaration}\n\
         layout(std430, binding = 2) writeonly buffer Out {{ uint words[]; }};\n\
         void main() {{\n\
           uint i = gl_GlobalInvocationID.x;\n\
           if (i < {n}u) {{\n\
             uint o = i * {NODE_WORDS}u;\n\
             words[o] = floatBitsToUint(nodes[i].lo.x); words[o + 1] = floatBitsToUint(nodes[i].lo.y);\n\
             words[o + 2] = floatBitsToUint(nodes[i].lo.z); words[o + 3] = nodes[i].count;\n\
             words[o + 4] = floatBitsToUint(nodes[i].hi.x); words[o + 5] = floatBitsToUint(nodes[i].hi.y);\n\
             words[o + 6] = floatBitsToUint(nodes[i].hi.z); words[o + 7] = nodes[i].first;\n\
           }} else {{\n\
             uint j = i - {n}u;\n\
             uint o = {n}u * {NODE_WORDS}u + j * {TRIANGLE_WORDS}u;\n\
             vec4 v[3] = vec4[3](triangles[j].v0, triangles[j].e1, triangles[j].e2);\n\
             for (int k = 0; k < 3; ++k) {{\n\
               for (int c = 0; c < 4; ++c) {{ words[o + uint(k * 4 + c)] = floatBitsToUint(v[k][c]); }}\n\
             }}\n\
           }}\n\
         }}\n"
    );
    let out = StorageBuffer::new(
        gl,
        "layout out",
        &vec![0xdead_beef; nodes.len() + triangles.len()],
    )
    .unwrap();
    let node_buffer = StorageBuffer::new(gl, "nodes", &nodes).unwrap();
    let triangle_buffer = StorageBuffer::new(gl, "triangles", &triangles).unwrap();
    // SAFETY: a compute program built, run and deleted here.
    unsafe {
        let shader = gl.create_shader(glow::COMPUTE_SHADER).unwrap();
        gl.shader_source(shader, &source);
        gl.compile_shader(shader);
        assert!(
            gl.get_shader_compile_status(shader),
            "{}",
            gl.get_shader_info_log(shader)
        );
        let program = gl.create_program().unwrap();
        gl.attach_shader(program, shader);
        gl.link_program(program);
        assert!(
            gl.get_program_link_status(program),
            "{}",
            gl.get_program_info_log(program)
        );
        gl.use_program(Some(program));
        node_buffer.bind(0);
        triangle_buffer.bind(1);
        out.bind(2);
        gl.dispatch_compute((n + t) as u32, 1, 1);
        gl.memory_barrier(glow::BUFFER_UPDATE_BARRIER_BIT);
        gl.use_program(None);
        gl.delete_program(program);
        gl.delete_shader(shader);
    }
    let got = out.read_words();
    assert_eq!(&got[..nodes.len()], &nodes[..], "nodes as GLSL reads them");
    assert_eq!(
        &got[nodes.len()..],
        &triangles[..],
        "triangles as GLSL reads them"
    );
}

#[test]
fn rtao_sees_an_occluder_outside_the_view() {
    let ctx = common::context();
    let dir = common::temp_dir("rtao-outside");
    let (eye, target) = (Vec3::new(0.0, 1.0, 0.0), Vec3::new(0.0, 0.0, -3.0));
    // Below and beside the camera: the view's lowest ray leaves 48° below the horizon, this box's
    // nearest face at most 53° down, so no pixel sees it; the floor at the bottom of the view is
    // 0.6 m from that face, well within a 2 m radius.
    let block = (
        "block",
        Vec3::new(-1.5, 0.0, -0.3),
        Vec3::new(1.5, 0.6, 0.5),
    );
    let mut open = scene(&dir, eye, target, &[]);
    let mut blocked = scene(&dir, eye, target, &[block]);
    open.ao.radius = 2.0;
    blocked.ao.radius = 2.0;
    let (eng_open, vis_open) = rtao(&ctx, &open, 16);
    let (mut eng_blocked, vis_blocked) = rtao(&ctx, &blocked, 16);
    let depth_blocked = eng_blocked.render_values(View::LinearDepth).unwrap();
    let mut eng_open = eng_open;
    let depth_open = eng_open.render_values(View::LinearDepth).unwrap();
    assert_eq!(depth_open, depth_blocked, "the box must stay out of view");
    let rows = |v: &[f32], r: std::ops::Range<u32>| {
        let px: Vec<f32> = r
            .flat_map(|y| (0..W).map(move |x| (y * W + x) as usize))
            .map(|i| v[i])
            .collect();
        px.iter().sum::<f32>() / px.len() as f32
    };
    let bottom = H - 6..H;
    let (open_bottom, blocked_bottom) = (
        rows(&vis_open, bottom.clone()),
        rows(&vis_blocked, bottom.clone()),
    );
    eprintln!("bottom rows: open {open_bottom}, with the box out of view {blocked_bottom}");
    assert!(open_bottom > 0.97, "open floor {open_bottom}");
    assert!(
        blocked_bottom < open_bottom - 0.1,
        "{blocked_bottom} vs {open_bottom}"
    );
    // The CPU reference agrees on how much.
    let truth = reference(&eng_blocked, 256);
    let truth_bottom = rows(&truth.ao, bottom);
    assert!(
        (truth_bottom - blocked_bottom).abs() < 0.04,
        "reference {truth_bottom}, rtao {blocked_bottom}"
    );
    // Sky pixels (none in the reference) stay exactly open.
    let sky: Vec<usize> = (0..truth.ao.len())
        .filter(|&i| !truth.linear_depth[i].is_finite())
        .collect();
    assert!(!sky.is_empty(), "the view should show some sky");
    assert!(
        sky.iter().all(|&i| vis_blocked[i] == 1.0),
        "sky must stay 1"
    );
}

#[test]
fn rtao_sees_an_occluder_hidden_behind_another_surface() {
    let ctx = common::context();
    let dir = common::temp_dir("rtao-hidden");
    // Looking straight down on a table top; a block under it is hidden by the top in every pixel,
    // yet the floor beside the table lies within the radius of the block's sides.
    let (eye, target) = (Vec3::new(0.0, 6.0, 0.01), Vec3::ZERO);
    let top = ("top", Vec3::new(-1.0, 1.0, -1.0), Vec3::new(1.0, 1.05, 1.0));
    let block = (
        "under",
        Vec3::new(-0.9, 0.0, -0.9),
        Vec3::new(0.9, 0.9, 0.9),
    );
    let without = scene(&dir, eye, target, &[top]);
    let with = scene(&dir, eye, target, &[top, block]);
    let (mut eng_without, vis_without) = rtao(&ctx, &without, 16);
    let (mut eng_with, vis_with) = rtao(&ctx, &with, 16);
    let depth_without = eng_without.render_values(View::LinearDepth).unwrap();
    let depth_with = eng_with.render_values(View::LinearDepth).unwrap();
    assert_eq!(depth_without, depth_with, "the block must be hidden");
    // The floor pixels next to the table: visibility falls, and as much as the reference says.
    let truth_with = reference(&eng_with, 256);
    let truth_without = reference(&eng_without, 256);
    let ring: Vec<usize> = (0..truth_with.ao.len())
        .filter(|&i| {
            let d = truth_with.linear_depth[i];
            d > 5.9 && truth_without.ao[i] - truth_with.ao[i] > 0.15
        })
        .collect();
    assert!(
        ring.len() > 20,
        "{} floor pixels near the table",
        ring.len()
    );
    let mean = |v: &[f32]| ring.iter().map(|&i| v[i] as f64).sum::<f64>() / ring.len() as f64;
    let (with_rtao, without_rtao) = (mean(&vis_with), mean(&vis_without));
    let with_truth = common::mean_over(&truth_with, &ring);
    eprintln!("beside the table: rtao {without_rtao} -> {with_rtao}, reference {with_truth}");
    assert!(with_rtao < without_rtao - 0.1);
    assert!((with_rtao - with_truth).abs() < 0.04);
}

#[test]
fn rtao_error_against_the_reference_falls_as_monte_carlo_predicts() {
    let ctx = common::context();
    let dir = common::temp_dir("rtao-convergence");
    let s = scene(
        &dir,
        Vec3::new(2.5, 2.0, 3.0),
        Vec3::new(0.0, 0.4, 0.0),
        &[
            ("a", Vec3::new(-1.0, 0.0, -1.0), Vec3::new(0.0, 1.2, 0.0)),
            ("b", Vec3::new(0.3, 0.0, 0.2), Vec3::new(0.8, 0.5, 0.9)),
            ("c", Vec3::new(-0.5, 0.9, 0.3), Vec3::new(0.6, 1.0, 1.0)),
        ],
    );
    let (eng, _) = rtao(&ctx, &s, 1);
    let truth = reference(&eng, 2048);
    let surface: Vec<usize> = (0..truth.ao.len())
        .filter(|&i| truth.linear_depth[i].is_finite())
        .collect();
    // One independent ray per pixel has variance v (1 - v) about the true visibility v.
    let predicted_one = (surface
        .iter()
        .map(|&i| (truth.ao[i] * (1.0 - truth.ao[i])) as f64)
        .sum::<f64>()
        / truth.ao.len() as f64)
        .sqrt();
    let errors: Vec<f64> = [1u32, 4, 64]
        .iter()
        .map(|&n| rmse(&rtao(&ctx, &s, n).1, &truth.ao))
        .collect();
    eprintln!("rmse at 1, 4, 64 rays: {errors:?}; predicted at 1 ray {predicted_one}");
    assert!(
        predicted_one > 0.05,
        "the scene should have partly occluded pixels"
    );
    assert!(
        errors[0] > 0.6 * predicted_one && errors[0] < 1.4 * predicted_one,
        "1 ray: {} vs {predicted_one}",
        errors[0]
    );
    // 1/sqrt(n): 2x from 1 to 4 rays, 4x from 4 to 64 (stratified sequences only do better).
    assert!(errors[1] < errors[0] / 1.6, "{errors:?}");
    assert!(errors[2] < errors[1] / 3.0, "{errors:?}");
    assert!(errors[2] < 0.03, "{errors:?}");
}

#[test]
fn rtao_gpu_reference_agrees_with_the_cpu_reference_at_1024_rays() {
    let dir = common::temp_dir("rtao-gpu-reference");
    let s = scene(
        &dir,
        Vec3::new(-2.0, 1.6, 2.8),
        Vec3::new(0.0, 0.3, 0.0),
        &[
            ("a", Vec3::new(-1.0, 0.0, -1.0), Vec3::new(0.0, 1.2, 0.0)),
            ("b", Vec3::new(0.3, 0.0, 0.2), Vec3::new(0.8, 0.5, 0.9)),
        ],
    );
    let res = opengl3d::res::ResDirs::default();
    let params = RefParams {
        radius: 1.0,
        rays: 1024,
        seed: 3,
        ..Default::default()
    };
    let gpu = opengl3d::tools::reference::render_reference_gpu(&res, &s, &params).unwrap();
    let cpu_scene = Scene::new(s.world_triangles(&res).unwrap()).unwrap();
    let cpu = render_reference(&cpu_scene, &s.camera.camera(), W, H, &params);
    common::assert_finite("gpu reference", &gpu.ao);
    assert_eq!(gpu.sky_mask(), cpu.sky_mask(), "both see the same surfaces");
    let mse = rmse(&gpu.ao, &cpu.ao).powi(2);
    let psnr = 10.0 * (1.0 / mse).log10();
    let occluded = cpu.ao.iter().filter(|v| **v < 0.9).count();
    eprintln!("GPU vs CPU reference at 1024 rays: {psnr:.1} dB ({occluded} pixels below 0.9)");
    assert!(
        occluded > 100,
        "the scene should have occlusion to agree on"
    );
    assert!(psnr >= 45.0, "{psnr:.1} dB");
    // Through the cache: written once, then read back as it was rendered.
    let cache = dir.join("cache");
    let cached = |p: &RefParams| {
        opengl3d::tools::reference::load_or_render_gpu_cached(&cache, &res, &s, &cpu_scene, p)
            .unwrap()
    };
    let few = RefParams { rays: 16, ..params };
    let first = cached(&few);
    assert_eq!(std::fs::read_dir(&cache).unwrap().count(), 1);
    assert_eq!(cached(&few), first);
    // Depths agree too (the GPU's come from the depth buffer).
    for (g, c) in gpu.linear_depth.iter().zip(&cpu.linear_depth) {
        assert!(g == c || (g - c).abs() < 1e-3 * c, "depth {g} vs {c}");
    }
    // Each pixel the mean over its footprint (2×2 sub-pixels of 256 rays), on both tracers.
    let wide = RefParams {
        supersample: 2,
        ..params
    };
    let gpu2 = opengl3d::tools::reference::render_reference_gpu(&res, &s, &wide).unwrap();
    let cpu2 = render_reference(&cpu_scene, &s.camera.camera(), W, H, &wide);
    assert_eq!((gpu2.width, gpu2.height), (W, H));
    common::assert_finite("gpu footprint reference", &gpu2.ao);
    let psnr2 = 10.0 * (1.0 / rmse(&gpu2.ao, &cpu2.ao).powi(2)).log10();
    eprintln!("GPU vs CPU footprint reference: {psnr2:.1} dB");
    assert!(psnr2 >= 45.0, "{psnr2:.1} dB");
    // The footprint is not the centre: silhouettes and contacts average over it.
    let moved = rmse(&cpu2.ao, &cpu.ao);
    assert!(moved > 2.0 * rmse(&gpu2.ao, &cpu2.ao), "{moved}");
}

#[test]
fn rtao_flags_out_of_range_are_clear_errors() {
    common::fails_with(
        &["render", "--method", "rtao", "--rays-per-pixel", "0"],
        &["--rays-per-pixel 0", "1024"],
    );
    common::fails_with(&["render", "--accumulate", "0"], &["--accumulate 0"]);
    common::fails_with(
        &["reference", "--gpu", "--rays", "2000"],
        &["--gpu", "1024"],
    );
    common::fails_with(&["reference", "--gpu", "--obscurance"], &["--obscurance"]);
}

#[test]
fn rtao_stats_show_the_bvh_and_the_accumulated_frames() {
    let out = common::temp_dir("rtao-stats").join("frame.png");
    let o = common::run(&[
        "render",
        "--method",
        "rtao",
        "--width",
        "32",
        "--height",
        "24",
        "--accumulate",
        "3",
        "--stats",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", common::stderr(&o));
    let json: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    let bvh = &json["bvh"];
    assert!(bvh["triangles"].as_u64().unwrap() > 1000, "{json}");
    assert!(bvh["nodes"].as_u64().unwrap() > 100 && bvh["bytes"].as_u64().unwrap() > 10_000);
    assert!(bvh["build_ms"].as_f64().unwrap() > 0.0);
    // Built once for every frame of the still view.
    assert_eq!(bvh["builds"].as_u64(), Some(1));
    assert_eq!(json["accumulated_frames"].as_u64(), Some(3), "{json}");
}

#[test]
fn rtao_accumulated_frames_come_closer_to_the_reference_and_restart_on_change() {
    let ctx = common::context();
    let dir = common::temp_dir("rtao-accumulation");
    let mut s = scene(
        &dir,
        Vec3::new(2.5, 2.0, 3.0),
        Vec3::new(0.0, 0.4, 0.0),
        &[
            ("a", Vec3::new(-1.0, 0.0, -1.0), Vec3::new(0.0, 1.2, 0.0)),
            ("b", Vec3::new(0.3, 0.0, 0.2), Vec3::new(0.8, 0.5, 0.9)),
        ],
    );
    s.ao.rays = 1;
    s.ao.accumulate = 16;
    let mut eng = common::engine(&ctx, &s);
    let truth = reference(&eng, 2048);
    let one = eng.render_values(View::AoRaw).unwrap();
    assert_eq!(eng.ao.accumulated_frames(AoMethod::Rtao), 1);
    let mut mean = one.clone();
    for _ in 1..16 {
        mean = eng.render_values(View::AoRaw).unwrap();
    }
    assert_eq!(eng.ao.accumulated_frames(AoMethod::Rtao), 16);
    common::assert_finite("accumulated rtao", &mean);
    let (e1, e16) = (rmse(&one, &truth.ao), rmse(&mean, &truth.ao));
    eprintln!("rmse after 1 frame {e1}, after 16 frames {e16}");
    // 16 frames of 1 ray: a quarter of the noise of one (stratified across frames does better).
    assert!(e16 < e1 / 2.5, "1 frame {e1}, 16 frames {e16}");

    // A moved camera keeps the mean (the history is reprojected: `rtao_temporal.rs`); a restart
    // (what the window does on any change of setting) and a resize start it again.
    eng.camera.eye.x += 0.05;
    eng.render_values(View::AoRaw).unwrap();
    assert_eq!(eng.ao.accumulated_frames(AoMethod::Rtao), 16);
    eng.ao.restart_accumulation();
    eng.render_values(View::AoRaw).unwrap();
    assert_eq!(eng.ao.accumulated_frames(AoMethod::Rtao), 1);
    eng.render_values(View::AoRaw).unwrap();
    assert_eq!(eng.ao.accumulated_frames(AoMethod::Rtao), 2);
    eng.ao.restart_accumulation();
    eng.render_values(View::AoRaw).unwrap();
    assert_eq!(eng.ao.accumulated_frames(AoMethod::Rtao), 1);
    eng.render_values(View::AoRaw).unwrap();
    eng.resize(W * 2, H * 2).unwrap();
    eng.render_values(View::AoRaw).unwrap();
    assert_eq!(eng.ao.accumulated_frames(AoMethod::Rtao), 1);
}
