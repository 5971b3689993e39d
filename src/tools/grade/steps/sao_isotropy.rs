//! Part of the SAO step: is the occlusion the same in every direction? A wall seen head-on with a
//! square panel raised in its middle: the wall is occluded along all four sides of the panel, and a
//! shader whose samples cover the whole disc (the spiral over 2π, whatever the pixel's start angle)
//! occludes the four bands alike. One whose samples favour some directions (a spiral over π, start
//! angles in half the circle) darkens some sides more than others. One whose disc or rebuilt
//! positions are stretched along x or y (`aspectFix` left out, `ndcToView` swapped: seen because the
//! step's target is wider than high) occludes left and right unlike below and above.

use crate::ao::AoSettings;
use crate::tools::grade::measure::{as_r8, rect_mean};
use crate::tools::grade::rig::Rig;
use crate::tools::grade::scene::{facing_wall, Aabb, SynthScene};
use anyhow::Result;
use glam::Vec3;

fn panel_scene(size: (u32, u32)) -> SynthScene {
    facing_wall(
        "square panel",
        &[Aabb::new([-1.0, -1.0, -5.0], [1.0, 1.0, -4.75])],
        size,
    )
}

/// Mean occlusion of the wall beside each side of the panel (left, right, bottom, top).
fn bands(occ: &[f32], scene: &SynthScene) -> [f64; 4] {
    let w = scene.width as usize;
    // Beyond 1.12 m the wall is not hidden by the panel's rim (seen from straight in front).
    let band = |a: [f32; 2], b: [f32; 2]| {
        let p = |v: [f32; 2]| scene.project(Vec3::new(v[0], v[1], -5.0));
        rect_mean(occ, w, p(a), p(b), as_r8)
    };
    [
        band([-1.5, -0.8], [-1.12, 0.8]),
        band([1.12, -0.8], [1.5, 0.8]),
        band([-0.8, -1.5], [0.8, -1.12]),
        band([-0.8, 1.12], [0.8, 1.5]),
    ]
}

/// Whether the bands differ between the axes rather than within them: left ≈ right and bottom ≈ top,
/// but the two pairs apart. That is a disc stretched along x or y, the aspect ratio uncorrected
/// (or corrected on the wrong axis), not a spiral that favours some directions.
fn stretched([l, r, b, t]: [f64; 4]) -> bool {
    let between = ((l + r) - (b + t)).abs() * 0.5;
    between > 2.0 * ((l - r).abs() + (b - t).abs()).max(1e-9) * 0.5
}

/// (max − min) / mean of the four bands' occlusion: 0 when the occlusion is isotropic.
fn spread(b: [f64; 4]) -> f64 {
    let mean = b.iter().sum::<f64>() / 4.0;
    let (lo, hi) = b
        .iter()
        .fold((f64::MAX, f64::MIN), |(lo, hi), v| (lo.min(*v), hi.max(*v)));
    (hi - lo) / mean.max(1e-6)
}

/// The spread of the four bands, the student's and the reference's, and whether the student's is a
/// stretched disc (`stretched`).
pub fn anisotropy(rig: &Rig, params: &AoSettings, size: (u32, u32)) -> Result<(f64, f64, bool)> {
    let scene = panel_scene(size);
    let depth = scene.depth();
    let (r, s) = rig.sao_pair(&scene.camera, &depth, params)?;
    let student = bands(&s, &scene);
    Ok((
        spread(student),
        spread(bands(&r, &scene)),
        stretched(student),
    ))
}
