//! Every AO method renders without NaN/Inf, leaves an open floor (nearly) alone and finds a crease.

use crate::common;

use glam::Vec3;
use opengl3d::ao::AoMethod;
use opengl3d::render::View;

#[test]
fn every_method_is_finite_open_on_a_floor_and_dark_in_a_crease() {
    let ctx = common::context();
    let dir = common::temp_dir("methods");
    let mut report = Vec::new();
    for method in AoMethod::ALL {
        let mut scene = common::crease_scene(
            &dir,
            Vec3::new(4.0, 2.5, 4.0),
            Vec3::new(0.0, 0.0, 0.0),
            320,
            240,
        );
        scene.ao.method = method;
        scene.ao.blur = false;
        scene.ao.samples = 16;
        let mut eng = common::engine(&ctx, &scene);
        let vis = eng.render_values(View::AoRaw).unwrap();
        common::assert_finite(method.name(), &vis);
        assert!(
            vis.iter().all(|v| (0.0..=1.0).contains(v)),
            "{}: visibility outside [0,1]",
            method.name()
        );
        // render_values rows are top-down; project() gives bottom-up rows.
        let flip = |(x, y): (usize, usize)| (x, 239 - y);
        let (cx, cy) = flip(common::project(&eng, Vec3::new(0.05, 0.05, 0.0), 320, 240));
        let (fx, fy) = flip(common::project(&eng, Vec3::new(3.0, 0.0, -1.0), 320, 240));
        let crease = 1.0 - common::mean_around(&vis, 320, 240, cx, cy, 2);
        let floor = 1.0 - common::mean_around(&vis, 320, 240, fx, fy, 4);
        report.push(format!(
            "{}: floor {floor:.3} crease {crease:.3}",
            method.name()
        ));
        assert!(
            floor < 0.1,
            "{}: open floor occlusion {floor}",
            method.name()
        );
        assert!(
            crease > floor + 0.1,
            "{}: crease occlusion {crease} vs floor {floor}",
            method.name()
        );
        // The blurred composite is finite too.
        let img = eng.render_image().unwrap();
        assert_eq!(img.dimensions(), (320, 240));
        common::assert_finite(
            &format!("{} blurred", method.name()),
            &eng.ao_targets()
                .unwrap()
                .result_texture(true)
                .read_f32(0, 1),
        );
    }
    eprintln!("{}", report.join("\n"));
}

#[test]
fn methods_survive_sky_only_tiny_sizes_and_a_camera_inside_geometry() {
    let ctx = common::context();
    let dir = common::temp_dir("methods-odd");
    for method in AoMethod::ALL {
        for (w, h, eye) in [
            (1, 1, Vec3::new(4.0, 2.5, 4.0)),
            (3, 5, Vec3::new(4.0, 2.5, 4.0)),
            (40, 30, Vec3::new(-0.5, 1.0, 0.0)),
        ] {
            let mut scene = common::crease_scene(&dir, eye, Vec3::new(0.0, 0.0, -1.0), w, h);
            scene.ao.method = method;
            let mut eng = common::engine(&ctx, &scene);
            for view in [View::AoRaw, View::Ao] {
                let v = eng.render_values(view).unwrap();
                common::assert_finite(&format!("{} {w}x{h}", method.name()), &v);
            }
        }
        let mut sky = opengl3d::scene::SceneDesc::default();
        sky.output.width = 16;
        sky.output.height = 8;
        sky.ao.method = method;
        let mut eng = common::engine(&ctx, &sky);
        assert!(
            eng.render_values(View::Ao)
                .unwrap()
                .iter()
                .all(|v| *v == 1.0),
            "{}: sky must be fully visible",
            method.name()
        );
    }
}
