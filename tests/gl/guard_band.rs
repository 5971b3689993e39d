//! The engine's guard band: the widened view's inner part lands exactly on the view's texels, and an
//! occluder just off screen darkens the pixels beside the edge as the closed form says, which it
//! cannot do without the band.

use crate::common;

use glam::Vec3;
use opengl3d::ao::{AoMethod, AoResolution, GuardBand, NormalSource, SlicePreset, Thickness};
use opengl3d::render::View;

const W: u32 = 480;
const H: u32 = 320;

#[test]
fn the_inner_part_of_the_widened_depth_is_the_views_depth() {
    let ctx = common::context();
    let dir = common::temp_dir("guard-band-align");
    let mut scene = common::crease_scene(
        &dir,
        Vec3::new(3.0, 2.0, 4.0),
        Vec3::new(0.0, 0.5, 0.0),
        W,
        H,
    );
    scene.ao.method = AoMethod::Vbao;
    scene.ao.quality = Some(SlicePreset::Low);
    // With surface passes the engine draws its own depth at the AO size with or without a margin.
    scene.ao.normals = NormalSource::Geometric;
    let mut eng = common::engine(&ctx, &scene);
    eng.render_values(View::AoRaw).unwrap();
    let plain = eng.ao_targets().unwrap().tex_depth.read_f32(0, 1);
    eng.ao_settings.guard_band = GuardBand::Pixels(40);
    eng.collect_stats = true;
    eng.render_values(View::AoRaw).unwrap();
    assert!(
        eng.last_stats().iter().any(|s| s.name == "guard band crop"),
        "the guard band ran"
    );
    let guarded = eng.ao_targets().unwrap().tex_depth.read_f32(0, 1);
    // Same rays through the same pixel centres; the widened projection rounds differently, and a
    // triangle edge passing within rounding of a centre may flip a texel.
    assert_depths_agree(&plain, &guarded);
}

/// Looking straight down at the floor with the wall (the plane x = 0) just beyond one edge: the
/// floor at distance d from it is occluded by the cosine-weighted share of directions that reach the
/// wall within R (the closed form of `vbao.rs`). Without a guard band no method sees the wall.
#[test]
fn an_occluder_just_off_screen_darkens_the_pixels_beside_the_edge() {
    let ctx = common::context();
    let dir = common::temp_dir("guard-band-offscreen");
    let eye = Vec3::new(2.2, 2.4, 0.0);
    let mut scene = common::crease_scene(&dir, eye, Vec3::new(2.2, 0.0, 0.01), W, H);
    scene.ao.method = AoMethod::Vbao;
    scene.ao.samples = 256;
    scene.ao.blur = false;
    scene.ao.radius = 1.0;
    let mut occlusion = Vec::new();
    let mut expected = Vec::new();
    for band in [GuardBand::Off, GuardBand::Pixels(160)] {
        scene.ao.guard_band = band;
        let mut eng = common::engine(&ctx, &scene);
        let vis = eng.render_values(View::AoRaw).unwrap();
        let (mut sum, mut want, mut n) = (0.0, 0.0, 0.0);
        for d in [0.25f32, 0.35, 0.45] {
            let a = d / scene.ao.radius;
            let closed = (a.acos() - a * (1.0 - a * a).sqrt()) / std::f32::consts::PI;
            for i in -5..=5 {
                let p = Vec3::new(d, 0.0, i as f32 * 0.1);
                let (x, y) = common::project(&eng, p, W, H);
                let edge = x.min(W as usize - 1 - x);
                assert!(
                    edge > 0 && edge < W as usize / 4,
                    "{p} is near an edge: {x}"
                );
                sum += 1.0 - vis[(H as usize - 1 - y) * W as usize + x];
                want += closed;
                n += 1.0;
            }
        }
        occlusion.push(sum / n);
        expected.push(want / n);
    }
    eprintln!(
        "mean occlusion beside the edge: none {:.3}, 160 px {:.3}, closed form {:.3}",
        occlusion[0], occlusion[1], expected[0]
    );
    assert!(
        occlusion[0] < 0.1 * expected[0],
        "without a band: {:.3}",
        occlusion[0]
    );
    // Seen from above, the wall's face is edge-on: even the widened depth buffer holds it as a thin
    // strip of texels, so the band recovers most, not all, of the closed form.
    assert!(
        occlusion[1] > 0.5 * expected[1] && occlusion[1] < 1.1 * expected[1],
        "with a band: {:.3} (closed form {:.3})",
        occlusion[1],
        expected[1]
    );
}

/// With surface passes the engine draws its own depth at the AO size: each texel is the depth at its
/// centre, which is what an engine of the AO size restores one to one from its own main depth.
#[test]
fn the_depth_drawn_at_the_ao_size_is_the_depth_at_each_texel_centre() {
    let ctx = common::context();
    let dir = common::temp_dir("ao-size-depth");
    let eye = Vec3::new(3.0, 2.0, 4.0);
    let target = Vec3::new(0.0, 0.5, 0.0);
    let mut scene = common::crease_scene(&dir, eye, target, W, H);
    scene.ao.method = AoMethod::Vbao;
    scene.ao.thickness = Some(Thickness::Backface);
    let mut eng = common::engine(&ctx, &scene);
    eng.render_values(View::AoRaw).unwrap();
    let drawn = eng.ao_targets().unwrap().tex_depth.read_f32(0, 1);

    let mut small = common::crease_scene(&dir, eye, target, W / 2, H / 2);
    small.ao.method = AoMethod::Vbao;
    small.ao.resolution = AoResolution::Full;
    let mut eng = common::engine(&ctx, &small);
    eng.render_values(View::AoRaw).unwrap();
    let restored = eng.ao_targets().unwrap().tex_depth.read_f32(0, 1);
    assert_depths_agree(&drawn, &restored);
}

/// Two linear-depth images of one view agree within 1e-4 (relative) at all but one texel in a
/// thousand (an edge passing within rounding of a texel centre may flip it).
fn assert_depths_agree(a: &[f32], b: &[f32]) {
    assert_eq!(a.len(), b.len());
    let differ = a
        .iter()
        .zip(b)
        .filter(|(x, y)| (*x - *y).abs() > 1e-4 * x.abs().max(1.0))
        .count();
    assert!(
        differ * 1000 <= a.len(),
        "{differ} of {} texels differ",
        a.len()
    );
}

/// With a margin the method and its blur draw only the view and the blur's reach around it
/// (`guard_band::read_region`): the blurred view is the same, texel for texel, as when they draw
/// everything, and the rest of the margin is left undrawn.
#[test]
fn drawing_only_the_read_region_leaves_the_blurred_view_unchanged() {
    use opengl3d::ao::blur::BLUR_REACH;
    use opengl3d::ao::guard_band::read_region;
    use opengl3d::ao::method_pass::AoMethodPass;
    use opengl3d::ao::AoTargets;
    use opengl3d::math::Camera;

    let ctx = common::context();
    let (w, h) = (96u32, 64u32);
    let (guarded, offset) = ((w / 2, h / 2), 6u32);
    let view = (guarded.0 - 2 * offset, guarded.1 - 2 * offset);
    let cam = Camera::default();
    let (settings, meshes, sao) = common::sao_pass(&ctx, 1.0, 4.0, true);
    // A bumpy surface 2–4 m away: occlusion that varies from texel to texel, which the blur mixes.
    let depth_at = |x: f32, y: f32| 3.0 + 0.6 * (x * 0.7).sin() * (y * 0.5).cos();
    let blurred = |region: Option<[i32; 4]>| {
        let targets = AoTargets::new(&ctx.gl, w, h, 3).unwrap();
        for l in 0..3 {
            let (lw, lh) = targets.tex_depth.size_at(l);
            let s = (1u32 << l) as f32;
            let v: Vec<f32> = (0..lw * lh)
                .map(|i| depth_at(((i % lw) as f32 + 0.5) * s, ((i / lw) as f32 + 0.5) * s))
                .collect();
            targets.tex_depth.upload_f32(l, 1, &v).unwrap();
        }
        let inputs = common::depth_only_inputs(&ctx, &meshes, &targets, &cam, &settings, region);
        sao.compute(&inputs).unwrap();
        sao.blur(&inputs).unwrap();
        targets.result_texture(true).read_f32(0, 1)
    };
    let region = read_region(guarded, view, offset);
    assert_eq!(
        region,
        [
            (offset - BLUR_REACH) as i32,
            (offset - BLUR_REACH) as i32,
            (view.0 + 2 * BLUR_REACH) as i32,
            (view.1 + 2 * BLUR_REACH) as i32
        ]
    );
    let all = blurred(None);
    let part = blurred(Some(region));
    let gw = guarded.0 as usize;
    let at = |v: &[f32], x: u32, y: u32| v[y as usize * gw + x as usize];
    let (mut varied, mut undrawn) = (0, 0);
    for y in 0..guarded.1 {
        for x in 0..guarded.0 {
            let in_view =
                (offset..offset + view.0).contains(&x) && (offset..offset + view.1).contains(&y);
            if in_view {
                assert_eq!(at(&all, x, y), at(&part, x, y), "view texel ({x}, {y})");
                varied += (at(&all, x, y) != at(&all, offset, offset)) as usize;
            } else if at(&all, x, y) != at(&part, x, y) {
                undrawn += 1;
            }
        }
    }
    assert!(
        varied > 100,
        "the blurred view is not flat ({varied} texels differ from one)"
    );
    assert!(undrawn > 0, "the margin beyond the blur's reach was drawn");
}
