//! The composite options: the lesson's blend, tinted with a power, and AO on the ambient term only.

use crate::common;

use glam::Vec3;
use opengl3d::ao::CompositeMode;

fn pixel_at_crease(mode: CompositeMode, ao: bool, tint: [f32; 3]) -> ([f32; 3], [f32; 3]) {
    let ctx = common::context();
    let dir = common::temp_dir(&format!("composite-{mode:?}-{ao}"));
    let mut scene = common::crease_scene(
        &dir,
        Vec3::new(4.0, 2.0, 4.0),
        Vec3::new(0.0, 1.0, 0.0),
        320,
        240,
    );
    scene.light.shadow = false;
    scene.ao.enabled = ao;
    scene.ao.composite = mode;
    scene.ao.tint = tint;
    let mut eng = common::engine(&ctx, &scene);
    let img = eng.render_image().unwrap();
    let rgb = |p: Vec3| {
        let (x, y) = common::project(&eng, p, 320, 240);
        let px = img.get_pixel(x as u32, 239 - y as u32);
        [px[0] as f32, px[1] as f32, px[2] as f32]
    };
    (
        rgb(Vec3::new(0.03, 0.03, 0.0)),
        rgb(Vec3::new(3.0, 0.0, -1.5)),
    )
}

fn lum(c: [f32; 3]) -> f32 {
    (c[0] + c[1] + c[2]) / 3.0
}

#[test]
fn ambient_only_darkens_less_than_the_blend_and_tint_colours_the_crease() {
    let (off_crease, off_floor) = pixel_at_crease(CompositeMode::Blend, false, [0.0; 3]);
    let (blend_crease, blend_floor) = pixel_at_crease(CompositeMode::Blend, true, [0.0; 3]);
    let (amb_crease, amb_floor) = pixel_at_crease(CompositeMode::AmbientOnly, true, [0.0; 3]);
    let (tint_crease, _) = pixel_at_crease(CompositeMode::Tinted, true, [0.9, 0.1, 0.1]);
    eprintln!("crease: off {off_crease:?} blend {blend_crease:?} ambient-only {amb_crease:?} tinted {tint_crease:?}");
    // The crease is lit by the sun too: AO on ambient only must darken, but less than over everything.
    assert!(
        lum(amb_crease) < lum(off_crease) - 2.0,
        "ambient-only should darken the crease"
    );
    assert!(
        lum(amb_crease) > lum(blend_crease) + 2.0,
        "ambient-only should darken less than the lesson's blend"
    );
    // Open floor: unchanged by every mode.
    for f in [blend_floor, amb_floor] {
        assert!(
            (lum(f) - lum(off_floor)).abs() <= 2.0,
            "open floor changed: {f:?} vs {off_floor:?}"
        );
    }
    // A red tint moves the crease toward red compared with the black blend.
    let redness = |c: [f32; 3]| c[0] - (c[1] + c[2]) * 0.5;
    assert!(
        redness(tint_crease) > redness(blend_crease) + 5.0,
        "tint not applied: {tint_crease:?} vs {blend_crease:?}"
    );
}
