//! Part of the SAO step: occluders farther than the sampling radius do not count. A wall seen head-on
//! with a raised panel on its left half (the wall beside it is occluded, as in the step's relief scene)
//! and a post 1.5 m in front of the wall, beside that band: the samples of the band that land on
//! the post are far beyond the radius, where the falloff f = max(RADIUS2 − vv, 0) is 0. A falloff that
//! goes below 0 there (the max dropped or taken with a negative bound) subtracts those samples from
//! the panel's occlusion; the step's own scenes have no such near object, so only this shows it.

use crate::ao::AoSettings;
use crate::tools::grade::measure::{as_r8, rect_mean};
use crate::tools::grade::rig::Rig;
use crate::tools::grade::scene::{facing_wall, Aabb, SynthScene};
use anyhow::Result;
use glam::Vec3;

fn post_scene(size: (u32, u32)) -> SynthScene {
    facing_wall(
        "post",
        &[
            Aabb::new([-60.0, -60.0, -5.0], [0.0, 60.0, -4.75]),
            // Seen from the eye it hides x 0.85–1.45 of the wall: 0.1 m right of the band.
            Aabb::new([0.595, -60.0, -3.6], [1.015, 60.0, -3.5]),
        ],
        size,
    )
}

/// Mean occlusion of the wall between the panel and the post (away from both edges), the student's
/// and the reference's.
pub fn beside_a_near_post(rig: &Rig, params: &AoSettings, size: (u32, u32)) -> Result<(f64, f64)> {
    let scene = post_scene(size);
    let depth = scene.depth();
    let (r, s) = rig.sao_pair(&scene.camera, &depth, params)?;
    let w = scene.width as usize;
    let (a, b) = (
        scene.project(Vec3::new(0.12, -1.5, -5.0)),
        scene.project(Vec3::new(0.75, 1.5, -5.0)),
    );
    Ok((rect_mean(&s, w, a, b, as_r8), rect_mean(&r, w, a, b, as_r8)))
}
