//! The camera path's runs and figures: per frame the PSNR against that frame's truth, the frame-to-frame
//! change where the truth stands still (flicker), the error in pixels the previous frame did not
//! see (ghosting), and the AO passes' time; per run their means after convergence.

use crate::ao::AoMethod;
use crate::math::Camera;
use crate::tools::metrics::psnr_from_mse;
use crate::tools::reference::{pixel_dir, view_direction, RefImage};
use serde::Serialize;

/// One configuration of the run.
#[derive(Clone, Debug, Serialize)]
pub struct PathSetting {
    pub label: String,
    pub method: AoMethod,
    pub accumulate: u32,
    /// A description of the AO settings (for the report).
    pub settings: String,
}

/// One scene, test camera and configuration along the path.
#[derive(Clone, Debug, Serialize)]
pub struct PathRun {
    pub scene: String,
    pub camera: String,
    pub setting: PathSetting,
    pub frames: Vec<FrameScore>,
    pub summary: Summary,
}

/// The whole run.
#[derive(Clone, Debug, Serialize)]
pub struct PathReport {
    pub renderer: String,
    pub width: u32,
    pub height: u32,
    pub ref_scale: u32,
    pub ref_rays: u32,
    pub still_frames: u32,
    pub moving_frames: u32,
    pub accumulate: u32,
    pub orbit_deg_per_frame: f32,
    pub dolly_per_frame: f32,
    pub runs: Vec<PathRun>,
    pub run_s: f64,
}

/// A truth pixel counts as standing still between two frames when it changed by less than this
/// (the truths' own noise is 0.012–0.017 per pixel at 256 rays, so two draws differ by about 0.02).
pub const TRUTH_STILL: f32 = 0.03;
/// A pixel is freshly seen when the previous frame's truth had a surface this much nearer (as a
/// fraction of the depth) where the point projects, or did not see it at all.
pub const DISOCCLUSION_DEPTH: f32 = 0.05;

/// One frame's figures.
#[derive(Clone, Debug, Serialize)]
pub struct FrameScore {
    pub psnr: f64,
    /// Sum of squared errors and count over the freshly seen pixels (pooled over frames).
    pub fresh_sq: f64,
    pub fresh_n: usize,
    /// Sum of squared frame-to-frame changes and count where the truth stands still.
    pub change_sq: f64,
    pub change_n: usize,
    /// CPU time of the AO passes (ms), llvmpipe's threads included.
    pub ao_cpu_ms: f64,
}

/// A run's means.
#[derive(Clone, Debug, Default, Serialize)]
pub struct Summary {
    /// Mean PSNR over the last half of the still segment (after convergence).
    pub still_psnr: f64,
    /// Mean PSNR over the moving segment.
    pub moving_psnr: f64,
    /// RMS frame-to-frame change where the truth stands still: still segment (after its first
    /// frame), moving segment.
    pub still_flicker: f64,
    pub moving_flicker: f64,
    /// RMSE over the freshly seen pixels of the moving segment, and how many there were.
    pub fresh_rmse: f64,
    pub fresh_pixels: usize,
    /// Median CPU time of the AO passes per frame (ms) and its ratio to the lesson's chain on the
    /// same scene and camera.
    pub ao_cpu_ms: f64,
    pub cost_ratio: f64,
}

/// Scores one frame: `values` the engine's AO box-averaged to the truth's size.
pub fn score_frame(
    values: &[f32],
    previous: Option<&[f32]>,
    truth: &RefImage,
    previous_truth: Option<&RefImage>,
    fresh: &[bool],
    ao_cpu_ms: f64,
) -> FrameScore {
    let surface = |i: usize| truth.linear_depth[i].is_finite();
    let (mut sq, mut n) = (0.0f64, 0usize);
    let (mut fresh_sq, mut fresh_n) = (0.0f64, 0usize);
    for (i, v) in values.iter().enumerate().filter(|(i, _)| surface(*i)) {
        let e = (*v as f64 - truth.ao[i] as f64).powi(2);
        sq += e;
        n += 1;
        if fresh[i] {
            fresh_sq += e;
            fresh_n += 1;
        }
    }
    let (mut change_sq, mut change_n) = (0.0f64, 0usize);
    if let (Some(prev), Some(prev_truth)) = (previous, previous_truth) {
        for (i, v) in values.iter().enumerate() {
            let still = surface(i)
                && prev_truth.linear_depth[i].is_finite()
                && (truth.ao[i] - prev_truth.ao[i]).abs() < TRUTH_STILL;
            if still {
                change_sq += (*v as f64 - prev[i] as f64).powi(2);
                change_n += 1;
            }
        }
    }
    FrameScore {
        psnr: psnr_from_mse(sq / n.max(1) as f64),
        fresh_sq,
        fresh_n,
        change_sq,
        change_n,
        ao_cpu_ms,
    }
}

/// Per frame, the truth pixels the previous frame did not see: their surface point projects
/// outside the previous image, or behind a surface the previous truth saw nearer there.
pub fn disoccluded(cameras: &[Camera], truths: &[RefImage]) -> Vec<Vec<bool>> {
    let mut out = vec![vec![false; truths.first().map_or(0, |t| t.ao.len())]];
    for k in 1..cameras.len().min(truths.len()) {
        let (cam, prev_cam) = (&cameras[k], &cameras[k - 1]);
        let (t, prev) = (&truths[k], &truths[k - 1]);
        let (w, h) = (t.width, t.height);
        let forward = view_direction(cam);
        let prev_forward = view_direction(prev_cam);
        let aspect = w as f32 / h as f32;
        let prev_vp = prev_cam.view_projection(aspect);
        let mut fresh = vec![false; t.ao.len()];
        for y in 0..h {
            for x in 0..w {
                let i = t.index(x, y);
                let depth = t.linear_depth[i];
                let Some(dir) = pixel_dir(cam, x, y, w, h) else {
                    continue;
                };
                if !depth.is_finite() {
                    continue;
                }
                let p = cam.eye + dir * (depth / dir.dot(forward).max(1e-6));
                let clip = prev_vp * p.extend(1.0);
                let prev_depth = (p - prev_cam.eye).dot(prev_forward);
                if clip.w <= 0.0 || prev_depth <= 0.0 {
                    fresh[i] = true;
                    continue;
                }
                let ndc = clip.truncate() / clip.w;
                let px = ((ndc.x * 0.5 + 0.5) * w as f32).floor();
                let py = ((0.5 - ndc.y * 0.5) * h as f32).floor();
                if px < 0.0 || py < 0.0 || px >= w as f32 || py >= h as f32 {
                    fresh[i] = true;
                    continue;
                }
                let seen = prev.linear_depth[prev.index(px as u32, py as u32)];
                fresh[i] = seen < prev_depth * (1.0 - DISOCCLUSION_DEPTH);
            }
        }
        out.push(fresh);
    }
    out
}

fn mean(v: impl Iterator<Item = f64>) -> f64 {
    let (s, n) = v.fold((0.0, 0usize), |(s, n), x| (s + x, n + 1));
    s / n.max(1) as f64
}

fn rms(frames: &[FrameScore]) -> f64 {
    let sq: f64 = frames.iter().map(|f| f.change_sq).sum();
    let n: usize = frames.iter().map(|f| f.change_n).sum();
    (sq / n.max(1) as f64).sqrt()
}

/// The run's means: `still` frames at the start, the rest moving.
pub fn summarise(frames: &[FrameScore], still: usize) -> Summary {
    let still = still.min(frames.len());
    let (standing, moving) = frames.split_at(still);
    let converged = &standing[still / 2..];
    let fresh_sq: f64 = moving.iter().map(|f| f.fresh_sq).sum();
    let fresh_n: usize = moving.iter().map(|f| f.fresh_n).sum();
    let mut ms: Vec<f64> = frames.iter().map(|f| f.ao_cpu_ms).collect();
    Summary {
        still_psnr: mean(converged.iter().map(|f| f.psnr)),
        moving_psnr: mean(moving.iter().map(|f| f.psnr)),
        still_flicker: rms(standing.get(1..).unwrap_or(&[])),
        moving_flicker: rms(moving),
        fresh_rmse: (fresh_sq / fresh_n.max(1) as f64).sqrt(),
        fresh_pixels: fresh_n,
        ao_cpu_ms: super::timing::median(&mut ms),
        cost_ratio: 0.0,
    }
}

/// Each run's cost as a ratio to the lesson's chain on the same scene and camera.
pub fn set_cost_ratios(runs: &mut [PathRun]) {
    let lesson: Vec<(String, String, f64)> = runs
        .iter()
        .filter(|r| r.setting.method == AoMethod::SaoLesson)
        .map(|r| (r.scene.clone(), r.camera.clone(), r.summary.ao_cpu_ms))
        .collect();
    for r in runs.iter_mut() {
        if let Some((_, _, ms)) = lesson
            .iter()
            .find(|(s, c, _)| *s == r.scene && *c == r.camera)
        {
            r.summary.cost_ratio = r.summary.ao_cpu_ms / ms.max(1e-9);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::Vec3;

    fn flat(w: u32, h: u32, ao: f32, depth: f32) -> RefImage {
        let n = (w * h) as usize;
        RefImage {
            width: w,
            height: h,
            ao: vec![ao; n],
            std_error: vec![0.0; n],
            linear_depth: vec![depth; n],
        }
    }

    #[test]
    fn a_still_camera_reveals_nothing_and_a_wall_moved_nearer_hides_what_it_showed() {
        let cam = Camera {
            eye: Vec3::new(0.0, 0.0, 5.0),
            target: Vec3::ZERO,
            ..Camera::default()
        };
        let far = flat(16, 8, 1.0, 5.0);
        let fresh = disoccluded(&[cam, cam], &[far.clone(), far.clone()]);
        assert!(fresh[1].iter().all(|f| !f), "still camera, same depth");
        // The previous frame saw a surface at 2 m where this one sees 5 m: all of it is new.
        let near = flat(16, 8, 1.0, 2.0);
        let fresh = disoccluded(&[cam, cam], &[near, far]);
        assert!(fresh[1].iter().all(|f| *f));
    }

    #[test]
    fn flicker_counts_only_where_the_truth_stands_still() {
        let t = flat(4, 1, 0.5, 3.0);
        let mut moved = t.clone();
        moved.ao[0] = 0.9;
        let now = [0.6f32, 0.5, 0.5, 0.5];
        let before = [0.5f32, 0.5, 0.5, 0.4];
        let s = score_frame(&now, Some(&before), &moved, Some(&t), &[false; 4], 1.0);
        assert_eq!(s.change_n, 3, "pixel 0's truth moved");
        assert!((s.change_sq - 0.01).abs() < 1e-6);
    }
}
