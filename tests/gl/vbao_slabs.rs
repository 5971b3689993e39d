//! `vbao`'s slab hierarchy (`[ao] slab_hierarchy`): every coarse texel holds the nearest slab of
//! the level-0 texels under it, checked on the CPU from the level-0 read-back; and a thin fin that
//! sparse taps skip occludes the floor beside it once the taps read the hierarchy.

use crate::common;

use glam::Vec3;
use opengl3d::ao::{AoMethod, SlabHierarchy, SlicePreset, Thickness};
use opengl3d::gl::mesh::MeshData;
use opengl3d::render::{Engine, View};
use opengl3d::scene::shapes;
use opengl3d::scene::SceneDesc;

const W: u32 = 640;
const H: u32 = 480;

/// A floor and a fin 2 cm thick and 0.5 m tall along Z at x = 0, seen from above at a slant: the
/// fin's top is a strip about a pixel wide in the half-size AO buffer.
fn fin_scene(dir: &std::path::Path, hierarchy: SlabHierarchy) -> SceneDesc {
    let mut fin = MeshData::default();
    shapes::add_box(
        &mut fin,
        Vec3::new(-0.01, 0.0, -6.0),
        Vec3::new(0.01, 0.5, 6.0),
    );
    let mut s = common::floor_and(
        dir,
        &[("fin", &fin)],
        Vec3::new(0.0, 4.0, 1.5),
        Vec3::new(0.0, 0.0, -0.5),
        (W, H),
    );
    s.ao.method = AoMethod::Vbao;
    s.ao.radius = 1.0;
    s.ao.blur = false;
    s.ao.thickness = Some(Thickness::Backface);
    // One slice of four steps per side: taps far apart, as in the presets' outer steps.
    s.ao.quality = Some(SlicePreset::Low);
    s.ao.slab_hierarchy = hierarchy;
    s
}

/// A plane slanted towards the camera's right and top, so that the nearest texel of a block is in
/// its last column and row, and a box 0.4 m deep in front of it (back faces); 642x482 makes the AO
/// buffer 321x241, odd, so a level's last texels take the odd column and row below them.
fn slanted_scene(dir: &std::path::Path) -> SceneDesc {
    let z = |x: f32, y: f32| -6.0 + 0.4 * x + 0.3 * y;
    let mut plane = MeshData::default();
    let corners =
        [(-8.0, -6.0), (8.0, -6.0), (8.0, 6.0), (-8.0, 6.0)].map(|(x, y)| Vec3::new(x, y, z(x, y)));
    shapes::add_quad(&mut plane, corners, Vec3::new(-0.4, -0.3, 1.0).normalize());
    let mut block = MeshData::default();
    shapes::add_box(
        &mut block,
        Vec3::new(-1.0, -1.0, -4.4),
        Vec3::new(0.5, 0.5, -4.0),
    );
    let mut s = SceneDesc::default();
    s.objects
        .push(common::object(dir, "plane", &plane, Vec3::ZERO, Vec3::ONE));
    s.objects
        .push(common::object(dir, "block", &block, Vec3::ZERO, Vec3::ONE));
    s.camera.eye = [0.0, 0.0, 0.0];
    s.camera.target = [0.0, 0.0, -1.0];
    s.output.width = 642;
    s.output.height = 482;
    s.bloom.enabled = false;
    s.ao.method = AoMethod::Vbao;
    s.ao.thickness = Some(Thickness::Backface);
    s.ao.slab_hierarchy = SlabHierarchy::On;
    s
}

/// RGBA texels of `level`, rows bottom-up.
fn texels(tex: &opengl3d::gl::Texture, level: u32) -> Vec<[f32; 4]> {
    tex.read_f32(level, 4)
        .chunks_exact(4)
        .map(|c| [c[0], c[1], c[2], c[3]])
        .collect()
}

#[test]
fn each_coarse_texel_holds_the_nearest_slab_under_it() {
    let ctx = common::context();
    let dir = common::temp_dir("vbao-slabs-levels");
    let s = slanted_scene(&dir);
    let mut eng = common::engine(&ctx, &s);
    eng.render_values(View::AoRaw).unwrap();
    let tex = eng.ao.slab_hierarchy().expect("the hierarchy was built");
    let (w, h) = (tex.width() as usize, tex.height() as usize);
    assert!(
        (w, h) == (321, 241) && tex.levels() >= 6,
        "{w}x{h}, {} levels",
        tex.levels()
    );
    // Level 0: each texel's own depth, its back face, its own coordinates.
    let depth = eng.ao.targets().unwrap().tex_depth.read_f32(0, 1);
    let back = eng.back_face_depth().expect("back faces").read_f32(0, 1);
    let far = s.camera.far;
    let thickness = s.ao.thickness_metres();
    let level0 = texels(&tex, 0);
    for (i, t) in level0.iter().enumerate() {
        let (x, y) = ((i % w) as f32, (i / w) as f32);
        assert_eq!((t[2], t[3]), (x, y), "level 0 texel {i} names another");
        if depth[i] >= far {
            assert!(t[0] >= far && t[1] == 0.0, "sky texel {i}: {t:?}");
            continue;
        }
        let own_back = if back[i] > depth[i] && back[i] < far {
            back[i]
        } else {
            depth[i] + thickness
        };
        assert_eq!(t[0], depth[i], "front of texel {i}");
        assert!((t[1] - own_back).abs() < 1e-4, "back of texel {i}: {t:?}");
    }
    // Coarser levels against the nearest front over each texel's footprint, computed here from
    // level 0 alone. A footprint is the 2^k square under the texel, the last column (row) of a level
    // also taking the finer level's odd last one.
    let mut fronts_checked = 0;
    for level in 1..tex.levels() {
        let (lw, lh) = tex.size_at(level);
        let coarse = texels(&tex, level);
        let span = |i: usize, n: usize, size: usize| {
            let lo = i << level;
            let hi = if i + 1 == n { size } else { (i + 1) << level };
            lo..hi
        };
        for cy in 0..lh as usize {
            for cx in 0..lw as usize {
                let (xs, ys) = (span(cx, lw as usize, w), span(cy, lh as usize, h));
                let mut nearest = far;
                for y in ys.clone() {
                    for x in xs.clone() {
                        nearest = nearest.min(level0[y * w + x][0]);
                    }
                }
                let t = coarse[cy * lw as usize + cx];
                assert_eq!(t[0].min(far), nearest, "level {level} ({cx}, {cy}) front");
                if nearest >= far {
                    continue;
                }
                // Its coordinates name a level-0 texel of the footprint with that front, whose own
                // back it keeps.
                let (ox, oy) = (t[2] as usize, t[3] as usize);
                assert!(
                    xs.contains(&ox) && ys.contains(&oy),
                    "level {level} ({cx}, {cy}) names ({ox}, {oy}), outside {xs:?} x {ys:?}"
                );
                let own = level0[oy * w + ox];
                assert_eq!((own[0], own[1]), (t[0], t[1]), "level {level} ({cx}, {cy})");
                fronts_checked += 1;
            }
        }
    }
    assert!(fronts_checked > 100, "{fronts_checked} coarse texels");
}

/// Mean raw occlusion of the floor beside the fin, and the engine.
fn occlusion_beside_fin(ctx: &opengl3d::platform::HeadlessContext, s: &SceneDesc) -> f32 {
    let mut eng: Engine = common::engine(ctx, s);
    let vis = eng.render_values(View::AoRaw).unwrap();
    common::assert_finite("vbao", &vis);
    let mut sum = 0.0;
    let mut n = 0;
    for side in [-0.3f32, 0.3] {
        for i in -8..=8 {
            let p = Vec3::new(side, 0.0, i as f32 * 0.1);
            let (x, y) = common::project(&eng, p, W, H);
            sum += common::mean_around(&vis, W as usize, H as usize, x, H as usize - 1 - y, 1);
            n += 1;
        }
    }
    1.0 - sum / n as f32
}

/// Share of cosine-weighted directions from a floor point `a` m from a vertical fin `h` m tall
/// that meet it within `r` m (the fin taken as a plane): directions project uniformly onto the unit
/// disc, (x, z) to height sqrt(1 - x^2 - z^2), and the fin is met when x <= -a / r and the height
/// there is at most h / r of the way (t = a / (-x r) <= 1 and t r y <= h). Midpoint rule on a grid.
fn fin_occlusion(a: f32, h: f32, r: f32) -> f32 {
    let n = 2000;
    let (mut inside, mut hit) = (0u64, 0u64);
    for i in 0..n {
        for j in 0..n {
            let x = -1.0 + (i as f64 + 0.5) * 2.0 / n as f64;
            let z = -1.0 + (j as f64 + 0.5) * 2.0 / n as f64;
            let rho2 = x * x + z * z;
            if rho2 > 1.0 {
                continue;
            }
            inside += 1;
            let y = (1.0 - rho2).sqrt();
            let ar = (a / r) as f64;
            if x <= -ar && y * ar / -x <= (h / r) as f64 {
                hit += 1;
            }
        }
    }
    hit as f32 / inside as f32
}

#[test]
fn a_thin_fin_between_two_taps_occludes_with_the_hierarchy() {
    let ctx = common::context();
    let dir = common::temp_dir("vbao-slabs-fin");
    let off = occlusion_beside_fin(&ctx, &fin_scene(&dir, SlabHierarchy::Off));
    let on = occlusion_beside_fin(&ctx, &fin_scene(&dir, SlabHierarchy::On));
    // The floor points are 0.3 m from the fin's middle, 0.29 m from its faces.
    let truth = fin_occlusion(0.29, 0.5, 1.0);
    eprintln!(
        "floor beside the fin: occlusion {off:.3} without, {on:.3} with the hierarchy (exact {truth:.3})"
    );
    assert!(
        off < 0.5 * truth,
        "the taps alone should skip the fin here, or the scene tests nothing: {off} vs {truth}"
    );
    assert!(
        (on - truth).abs() < 0.1 && on > off + 0.1,
        "the hierarchy must find the fin the taps skip: {on} (without {off}, exact {truth})"
    );
}
