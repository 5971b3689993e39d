//! The probe renders of mutation testing (`grade-step STEP --probe`, run by `grade
//! --mutation-score`). Two numbers per shader, both against the project's shader the mutant was
//! made from:
//! - `tolerance`: the difference on an input the grader's steps never use, in units of the step's
//!   tolerance (above 1 the grader ought to fail the shader);
//! - `listing`: the largest difference of any value of any probe render, in units of float noise
//!   (`tol::EQUIVALENT_REL`); at most 1 the mutant is equivalent (same output).
//!
//! The input is a box scene (a room corner with stairs, a pillar, a ramp and sky) seen obliquely on
//! a non-square 208×120 target (416×240 for the depth buffer), so that slopes, depth edges, creases
//! and the aspect ratio all show; every size divides by 8, so that no level of the mip chain reads
//! past its edge.
//!
//! What is compared for `tolerance`, per step, with the tolerance the step itself uses:
//! - `restore`: every restored distance, in units of its float-precision bound (`tol::RESTORE_ULPS`);
//! - `down-sampling`: every texel of levels 1–3, relative (`tol::DOWN_REL`);
//! - `sao`: on a square target (144×144), the RMSE of 8×8 block means over the pixels the SAO step
//!   compares: facing the camera, away from depth edges (`tol::SAO_BLOCK_RMSE`), and NaN
//!   (`tol::SAO_BAD_PIXEL_FRACTION`);
//! - `simple`: the copy and the composite of another texture than the step's (`tol::SIMPLE_ABS`);
//! - `blur`: the RMSE over non-sky pixels at least 9 texels from the border (the blur's reach: the
//!   step checks the border on its own) (`tol::BLUR_RMSE`), and any change in the sky
//!   (`tol::BLUR_SKY_ABS`).
//!
//! `listing` compares every output value of those renders and of more inputs chosen so that each
//! statement of the lesson's shaders changes some value (`more_probes`): the room seen from the
//! front as well as obliquely, on odd sizes and other aspect ratios; the SAO step on the non-square
//! oblique target, with a disc wide enough to reach the last mip level, and with another radius,
//! sample count and spiral; the blur on white noise, where every tap's weight shows, borders
//! included.

use super::args::Step;
use super::measure::{as_r8, block_means};
use super::passes::{run_blur, run_sao, run_sao_pair, Mips};
use super::rig::{build_rig, Rig, Subject};
use super::scene::{Aabb, SynthScene};
use super::tol;
use crate::ao::AoSettings;
use crate::gl::{Texture, TextureDesc};
use crate::math::depth::delinearize;
use crate::math::{Camera, DepthMode};
use anyhow::Result;
use glam::Vec3;
use std::path::Path;

/// Size of the probe's SAO buffers (level 0 of `texSAODepth`); the depth buffer is twice as large.
pub const PROBE_SIZE: (u32, u32) = (208, 120);
/// The SAO step's probe is square: its frontal scene is framed for it, and on it the lesson's
/// listing (no mip bias, no edge guard) stays within the step's tolerance. The step's own rig is
/// wider than high, where the aspect corrections are checked.
pub const SAO_PROBE_SIZE: (u32, u32) = (144, 144);

/// A difference too large to tell apart (NaN, Inf): finite so that it survives JSON.
pub const HUGE: f64 = 1e30;

/// What the probe found.
pub enum Probe {
    /// The largest difference from the project's output in units of the step's tolerance, and in
    /// units of float noise.
    Difference { tolerance: f64, listing: f64 },
    /// The shader does not compile or link.
    DoesNotBuild,
}

/// The probe scene at `w`×`h`: the room seen obliquely (slopes everywhere) or, for the SAO step,
/// from the front (its comparison is over surfaces facing the camera, as in the step) and from
/// 5–9 m, as far as the step's own scenes: from 3 m the lesson's listing and correct rewrites
/// already differ from the port by 3× the tolerance there (high mip levels without the port's
/// texel snapping), from 5.5 m by 0.7× (and f·f instead of f·f·f by 1.6×).
pub fn probe_scene(w: u32, h: u32, frontal: bool) -> SynthScene {
    let (eye, target) = if frontal {
        (Vec3::new(0.3, 1.6, 5.5), Vec3::new(0.1, 1.0, -3.0))
    } else {
        (Vec3::new(4.2, 2.1, 4.6), Vec3::new(-0.6, 0.7, -1.8))
    };
    SynthScene {
        name: "probe room",
        camera: Camera {
            eye,
            target,
            ..Camera::default()
        },
        boxes: vec![
            // Floor, back wall and left wall (the wall stops at 2.6 m: sky above it).
            Aabb::new([-40.0, -1.0, -40.0], [40.0, 0.0, 40.0]),
            Aabb::new([-6.0, 0.0, -4.0], [6.0, 2.6, -3.0]),
            Aabb::new([-3.0, 0.0, -4.0], [-2.0, 2.6, 3.0]),
            // Stairs against the back wall.
            Aabb::new([-1.8, 0.0, -3.0], [0.6, 0.3, -2.2]),
            Aabb::new([-1.8, 0.3, -3.0], [0.6, 0.6, -2.6]),
            // A pillar in front (depth edges), a low crate, and a thin plate on the floor.
            Aabb::new([1.3, 0.0, -0.4], [1.7, 2.0, 0.0]),
            Aabb::new([-1.4, 0.0, 0.3], [-0.5, 0.5, 1.1]),
            Aabb::new([0.2, 0.0, 1.2], [1.4, 0.06, 2.0]),
        ],
        width: w,
        height: h,
        probes: vec![],
    }
}

/// Runs the probe of `step` on the shader in `subject.work_dir`.
pub fn probe(step: Step, subject: &Subject, project_res: &Path) -> Result<Probe> {
    let (w, h) = if step == Step::Sao {
        SAO_PROBE_SIZE
    } else {
        PROBE_SIZE
    };
    let scene = probe_scene(w, h, step == Step::Sao);
    let params = AoSettings::default();
    let rig = match build_rig(subject, project_res, (2 * w, 2 * h), &scene.camera, &params) {
        Ok(r) => r,
        Err(v) if v.message.en.starts_with("grader error") => anyhow::bail!("{}", v.message.en),
        Err(_) => return Ok(Probe::DoesNotBuild),
    };
    let (d, e) = match step {
        Step::Restore => restore(&rig, &scene)?,
        Step::DownSampling => down_sampling(&rig, &scene)?,
        Step::Sao => sao(&rig, &scene, &params)?,
        Step::Blur => blur(&rig, &scene, &occlusion_of(&rig, &scene, &params)?)?,
        Step::Simple => super::steps::simple_probe(&rig)?,
    };
    drop(rig);
    let e = match more_probes(step, subject, project_res)? {
        Some(more) => e.max(more),
        None => return Ok(Probe::DoesNotBuild),
    };
    let finite = |d: f64| if d.is_finite() { d.min(HUGE) } else { HUGE };
    Ok(Probe::Difference {
        tolerance: finite(d),
        listing: finite(e),
    })
}

/// The `listing` difference of `step` on the inputs only the equivalence test uses; `None` when
/// the shader does not build on one of their rigs.
fn more_probes(step: Step, subject: &Subject, project_res: &Path) -> Result<Option<f64>> {
    let d = AoSettings::default();
    // Another radius, sample count and spiral than the step's: each constant of the loop shows.
    let other = AoSettings {
        radius: 0.6 * d.radius,
        samples: 7,
        spiral_turns: 2,
        ..d
    };
    // A disc wide enough near the camera (over 64 texels) that the far taps read the last level.
    let wide = AoSettings { radius: 4.0, ..d };
    // (size of texSAODepth, frontal, settings): odd sizes and other aspect ratios than the
    // step's, so that texel snapping, borders and the aspect corrections meet new cases.
    let inputs: &[((u32, u32), bool, AoSettings)] = match step {
        Step::Simple => &[],
        Step::Sao => &[
            (PROBE_SIZE, false, d),
            (PROBE_SIZE, false, wide),
            ((105, 61), false, other),
            ((71, 71), true, d),
        ],
        _ => &[((105, 61), true, d), ((71, 39), false, d)],
    };
    let mut worst_e = 0.0f64;
    for &((w, h), frontal, params) in inputs {
        let scene = probe_scene(w, h, frontal);
        let rig = match build_rig(subject, project_res, (2 * w, 2 * h), &scene.camera, &params) {
            Ok(r) => r,
            Err(v) if v.message.en.starts_with("grader error") => anyhow::bail!("{}", v.message.en),
            Err(_) => return Ok(None),
        };
        let e = match step {
            Step::Restore => restore(&rig, &scene)?.1,
            Step::DownSampling => down_sampling(&rig, &scene)?.1,
            Step::Sao => sao(&rig, &scene, &params)?.1,
            Step::Blur => {
                let occ = occlusion_of(&rig, &scene, &params)?;
                let noise: Vec<f32> = (0..occ.len()).map(white_noise).collect();
                let a = blur(&rig, &scene, &occ)?.1;
                a.max(blur(&rig, &scene, &noise)?.1)
            }
            Step::Simple => 0.0,
        };
        worst_e = worst_e.max(e);
    }
    Ok(Some(worst_e))
}

/// A value in [0, 1) that looks random for index `i` (a fixed integer hash).
fn white_noise(i: usize) -> f32 {
    let mut x = (i as u32).wrapping_mul(0x9E37_79B9) ^ 0x85EB_CA6B;
    x ^= x >> 15;
    x = x.wrapping_mul(0x2C1B_3C6D);
    x ^= x >> 12;
    (x >> 8) as f32 / (1u32 << 24) as f32
}

/// Largest difference between `s` and `r` in units of float noise (`tol::EQUIVALENT_REL` of the
/// value, or of 1 below 1); values with the same bits (NaN, Inf included) agree.
pub fn listing_difference(s: &[f32], r: &[f32]) -> f64 {
    if s.len() != r.len() {
        return HUGE;
    }
    s.iter()
        .zip(r)
        .map(|(s, r)| {
            if s.to_bits() == r.to_bits() || (s.is_nan() && r.is_nan()) {
                return 0.0;
            }
            let e =
                (*s as f64 - *r as f64).abs() / (tol::EQUIVALENT_REL * (*r as f64).abs().max(1.0));
            if e.is_finite() {
                e.min(HUGE)
            } else {
                HUGE
            }
        })
        .fold(0.0, f64::max)
}

/// Largest `|a − b| / scale(b)`, NaN and Inf counting as `HUGE`.
fn worst(a: &[f32], b: &[f32], scale: impl Fn(usize, f64) -> f64) -> f64 {
    a.iter()
        .zip(b)
        .enumerate()
        .map(|(i, (s, r))| {
            let e = (*s as f64 - *r as f64).abs() / scale(i, *r as f64);
            if e.is_finite() {
                e
            } else {
                HUGE
            }
        })
        .fold(0.0, f64::max)
}

fn restore(rig: &Rig, scene: &SynthScene) -> Result<(f64, f64)> {
    let (w, h) = (2 * scene.width as usize, 2 * scene.height as usize);
    let big = SynthScene {
        width: w as u32,
        height: h as u32,
        ..scene.clone()
    };
    let (n, f) = (scene.camera.near as f64, scene.camera.far as f64);
    let depth: Vec<f32> = big
        .depth()
        .iter()
        .map(|z| {
            if *z >= scene.camera.far {
                1.0
            } else {
                delinearize(DepthMode::D32, *z as f64, n, f) as f32
            }
        })
        .collect();
    let tex = Texture::new(
        &rig.gl,
        TextureDesc::target("probe depth", w as u32, h as u32, glow::DEPTH_COMPONENT32),
    )?;
    tex.upload_f32(0, 1, &depth)?;
    let stored = tex.read_f32(0, 1);
    rig.reference.restore_depth(&rig.meshes, &tex);
    rig.student.restore_depth(&rig.meshes, &tex);
    let r = rig.reference.targets.tex_depth.read_f32(0, 1);
    let s = rig.student.targets.tex_depth.read_f32(0, 1);
    // The float-precision bound of the restore step, at the nearest depth of each 2×2 block.
    let b = (f + n) / (f - n);
    let bw = w / 2;
    let exact = listing_difference(&s, &r);
    let d = worst(&s, &r, |i, r| {
        let (x, y) = (2 * (i % bw), 2 * (i / bw));
        let dv = [(0, 0), (1, 0), (0, 1), (1, 1)]
            .iter()
            .map(|(dx, dy)| stored[(y + dy) * w + x + dx] as f64)
            .fold(1.0, f64::min);
        let bound =
            tol::RESTORE_ULPS * f32::EPSILON as f64 * (1.0 + b / ((2.0 * dv - 1.0) - b).abs());
        r.abs() * bound
    });
    Ok((d, exact))
}

fn down_sampling(rig: &Rig, scene: &SynthScene) -> Result<(f64, f64)> {
    let depth = scene.depth();
    let (mut diff, mut exact) = (0.0f64, 0.0f64);
    let mut levels = Vec::new();
    for lesson in [&rig.reference, &rig.student] {
        lesson.targets.tex_depth.upload_f32(0, 1, &depth)?;
        lesson.down_sample(&rig.meshes);
        let t = &lesson.targets.tex_depth;
        levels.push(
            (1..t.levels())
                .map(|l| t.read_f32(l, 1))
                .collect::<Vec<_>>(),
        );
    }
    for (r, s) in levels[0].iter().zip(&levels[1]) {
        diff = diff.max(worst(s, r, |_, r| tol::DOWN_REL * r.abs()));
        exact = exact.max(listing_difference(s, r));
    }
    Ok((diff, exact))
}

/// The pixels the SAO step compares (as its own masks do): not sky, no depth edge in the 5×5
/// neighbourhood (depths within 5%), and facing the camera (depth changing by less than 1% per
/// texel). At edges the lesson's normal is meaningless and on slopes the port's mip bias and texel
/// snapping differ from the lesson on purpose, so there neither is wrong.
fn compared(depth: &[f32], w: usize, h: usize, far: f32) -> Vec<bool> {
    (0..w * h)
        .map(|i| {
            let (x, y) = ((i % w) as isize, (i / w) as isize);
            let d0 = depth[i];
            let inner = x > 0 && y > 0 && x < w as isize - 1 && y < h as isize - 1;
            let flat = inner && {
                let sx = (depth[i + 1] - depth[i - 1]).abs() * 0.5;
                let sy = (depth[i + w] - depth[i - w]).abs() * 0.5;
                (sx + sy) / d0 < 0.01
            };
            d0 < far
                && flat
                && (-2..=2).all(|dy| {
                    (-2..=2).all(|dx| {
                        let (xx, yy) = (x + dx, y + dy);
                        xx < 0
                            || yy < 0
                            || xx >= w as isize
                            || yy >= h as isize
                            || (depth[yy as usize * w + xx as usize] - d0).abs() <= 0.05 * d0
                    })
                })
        })
        .collect()
}

fn sao(rig: &Rig, scene: &SynthScene, params: &AoSettings) -> Result<(f64, f64)> {
    let (w, h) = (scene.width as usize, scene.height as usize);
    let depth = scene.depth();
    let far = scene.camera.far;
    let (r, raw) = run_sao_pair(
        &rig.reference,
        &rig.student,
        &rig.meshes,
        &scene.camera,
        &depth,
        params,
    )?;
    let sky = depth.iter().filter(|d| **d >= far).count();
    let nan = raw
        .iter()
        .zip(&depth)
        .filter(|(v, d)| **d < far && !v.is_finite())
        .count();
    let nan_part = nan as f64 / (w * h - sky).max(1) as f64 / tol::SAO_BAD_PIXEL_FRACTION;
    let exact = listing_difference(&raw, &r);
    let s: Vec<f32> = raw.iter().map(|v| as_r8(*v)).collect();
    let r: Vec<f32> = r.iter().map(|v| as_r8(*v)).collect();
    let mask = compared(&depth, w, h, far);
    let (bs, br) = (
        block_means(&s, &mask, w, h, 8),
        block_means(&r, &mask, w, h, 8),
    );
    let (mut sq, mut n) = (0.0f64, 0usize);
    for (a, b) in bs.iter().zip(&br) {
        if let (Some(a), Some(b)) = (a, b) {
            sq += (a - b) * (a - b);
            n += 1;
        }
    }
    let rmse = (sq / n.max(1) as f64).sqrt();
    Ok(((rmse / tol::SAO_BLOCK_RMSE).max(nan_part), exact))
}

/// The project's occlusion of `scene`, as the blur step reads it (stored in R8).
fn occlusion_of(rig: &Rig, scene: &SynthScene, params: &AoSettings) -> Result<Vec<f32>> {
    let occ = run_sao(
        &rig.reference,
        &rig.meshes,
        &scene.camera,
        &scene.depth(),
        params,
        Mips::Filled,
    )?;
    Ok(occ.iter().map(|v| as_r8(*v)).collect())
}

/// The blur of `occ` on `scene`'s depth.
fn blur(rig: &Rig, scene: &SynthScene, occ: &[f32]) -> Result<(f64, f64)> {
    let (w, h) = (scene.width as usize, scene.height as usize);
    let depth = scene.depth();
    let far = scene.camera.far;
    let r = run_blur(&rig.reference, &rig.meshes, &depth, occ)?;
    let raw = run_blur(&rig.student, &rig.meshes, &depth, occ)?;
    let exact = listing_difference(&raw, &r);
    if raw.iter().any(|v| !v.is_finite()) {
        return Ok((HUGE, exact));
    }
    let s: Vec<f32> = raw.iter().map(|v| as_r8(*v)).collect();
    // The course's table is the reference's behaviour as much as the project's (the blur step).
    let course = super::steps::course_blur(occ, &depth, w, h, far);
    const REACH: usize = 9;
    let (mut sq, mut sq_course, mut n, mut sky) = (0.0f64, 0.0f64, 0usize, 0.0f64);
    for y in 0..h {
        for x in 0..w {
            let i = y * w + x;
            let d = (s[i] - r[i]) as f64;
            if depth[i] >= far {
                sky = sky.max(d.abs());
            } else if (REACH..w - REACH).contains(&x) && (REACH..h - REACH).contains(&y) {
                let dc = (s[i] - course[i]) as f64;
                sq += d * d;
                sq_course += dc * dc;
                n += 1;
            }
        }
    }
    let rmse = (sq.min(sq_course) / n.max(1) as f64).sqrt();
    Ok(((rmse / tol::BLUR_RMSE).max(sky / tol::BLUR_SKY_ABS), exact))
}
