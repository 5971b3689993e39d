//! The surface-normal pass: every texel the AO methods read carries the normal of the face it sees
//! (checked against the faces' known normals, at creases and silhouettes too), it runs only when the
//! settings read normals, and it shows in the frame's pass list.

use crate::common;

use glam::Vec3;
use opengl3d::ao::{AoMethod, GuardBand, NormalSource, SlicePreset};
use opengl3d::render::View;

const W: u32 = 480;
const H: u32 = 320;

/// The crease seen from the +x side: only the floor (+y) and the wall's face x = 0 (+x) are in view.
fn crease(dir: &std::path::Path) -> opengl3d::scene::SceneDesc {
    let mut s = common::crease_scene(
        dir,
        Vec3::new(3.0, 2.0, 4.0),
        Vec3::new(0.0, 0.5, 0.0),
        W,
        H,
    );
    s.ao.method = AoMethod::Vbao;
    s.ao.quality = Some(SlicePreset::Low);
    // At the view's size (a guard band widens the targets; guard_band.rs tests it).
    s.ao.guard_band = GuardBand::Off;
    s.ao.normals = NormalSource::Geometric;
    s
}

fn angle(a: Vec3, b: Vec3) -> f32 {
    a.normalize().dot(b.normalize()).clamp(-1.0, 1.0).acos()
}

#[test]
fn every_texel_carries_the_normal_of_the_face_it_sees() {
    let ctx = common::context();
    let dir = common::temp_dir("surface-normals");
    let mut eng = common::engine(&ctx, &crease(&dir));
    let depth = eng.render_values(View::LinearDepth).unwrap();
    assert!(!depth.is_empty());
    eng.render_values(View::AoRaw).unwrap();
    let normals = eng
        .surface_normals()
        .expect("vbao with geometric normals ran the pass");
    let (aw, ah) = eng.ao_targets().unwrap().size();
    assert_eq!(normals.len(), (aw * ah) as usize);
    let view = eng.camera.view();
    let floor = view.transform_vector3(Vec3::Y);
    let wall = view.transform_vector3(Vec3::X);
    // Half-size linear depth (rows bottom-up, like the normals) tells sky texels apart.
    let half_depth = eng.ao_targets().unwrap().tex_depth.read_f32(0, 1);
    let far = eng.camera.far;
    let (mut on_floor, mut on_wall, mut worst) = (0, 0, 0.0f32);
    for (i, n) in normals.iter().enumerate() {
        if half_depth[i] >= far {
            continue;
        }
        let n = Vec3::from(*n);
        assert!(
            (n.length() - 1.0).abs() < 1e-4,
            "texel {i}: |n| = {}",
            n.length()
        );
        let (af, aw_) = (angle(n, floor), angle(n, wall));
        worst = worst.max(af.min(aw_));
        if af < aw_ {
            on_floor += 1;
        } else {
            on_wall += 1;
        }
    }
    // RG16F octahedral codes round-trip within 1e-3 rad; a normal rebuilt from depth is off by tens
    // of degrees at the crease and the wall's silhouette.
    assert!(
        worst < 3e-3,
        "largest angle to the nearest face normal: {worst} rad"
    );
    assert!(
        on_floor > 1000 && on_wall > 1000,
        "floor {on_floor}, wall {on_wall}"
    );
    // Texels right beside the crease, on each side of it.
    for (p, want, what) in [
        (Vec3::new(0.1, 0.0, 0.3), floor, "floor beside the crease"),
        (Vec3::new(0.0, 0.1, 0.3), wall, "wall beside the crease"),
    ] {
        let (x, y) = common::project(&eng, p, aw, ah);
        let n = Vec3::from(normals[y * aw as usize + x]);
        assert!(angle(n, want) < 3e-3, "{what}: {n} vs {want}");
    }
}

#[test]
fn the_pass_runs_only_when_a_method_reads_normals_and_shows_in_the_stats() {
    let ctx = common::context();
    let dir = common::temp_dir("surface-normals-stats");
    let mut eng = common::engine(&ctx, &crease(&dir));
    eng.collect_stats = true;
    let has_pass = |eng: &opengl3d::render::Engine| {
        eng.last_stats().iter().any(|s| s.name == "surface normals")
    };
    eng.render_values(View::AoRaw).unwrap();
    assert!(has_pass(&eng), "geometric normals run the pass");
    let named = |eng: &opengl3d::render::Engine| {
        eng.ao_textures()
            .iter()
            .filter(|t| t.name.contains("surface normals"))
            .count()
    };
    // The AO chain draws the pass at the AO size, where its own target serves: no copy.
    assert_eq!(named(&eng), 1, "one normal target, drawn at the AO size");
    for (method, normals) in [
        (AoMethod::Vbao, NormalSource::Depth),
        (AoMethod::SaoLesson, NormalSource::Geometric),
        (AoMethod::Crytek, NormalSource::Geometric),
    ] {
        eng.ao_settings.method = method;
        eng.ao_settings.normals = normals;
        eng.sync_shader_constants().unwrap();
        eng.render_values(View::AoRaw).unwrap();
        assert!(
            !has_pass(&eng),
            "{} with {} normals must not run the pass",
            method.name(),
            normals.name()
        );
    }
    // With a guard band the pass draws the widened view's depth, whatever the normals; the stats
    // name it for what the method reads.
    eng.ao_settings.method = AoMethod::Vbao;
    eng.ao_settings.normals = NormalSource::Depth;
    eng.ao_settings.guard_band = GuardBand::Auto;
    eng.sync_shader_constants().unwrap();
    eng.render_values(View::AoRaw).unwrap();
    assert!(!has_pass(&eng), "no normals are read");
    assert!(
        eng.last_stats().iter().any(|s| s.name == "surface depth"),
        "the guard band's depth comes from the pass"
    );
}
