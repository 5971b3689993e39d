//! The GPU reference checked against the CPU tracer on a sample of its pixels: a driver that ends a
//! shader's work early, or a traversal that misses triangles, would make the picture wrong in
//! patches, and a truth that is wrong in patches cannot be told from a method that is. The CPU
//! traces the same surface point with its own lattice shift, so the two differ only by their
//! Monte-Carlo noise, plus the 8-bit storage of each GPU pass (1/510 at most).

use super::image::RefImage;
use super::params::RefParams;
use super::scene::Scene;
use super::trace::trace_pixel;
use crate::math::Camera;
use anyhow::{bail, Result};
use rayon::prelude::*;
use rust_i18n::t;

/// Pixels sampled per side: up to 16 × 16 = 256 pixels, spread evenly over the image. A defect that
/// covers 2 % of the surface is met by the sample with probability 1 − 0.98^256 > 99 %.
const GRID: u32 = 16;

/// How far apart a pixel's two values may lie: this many of their combined standard errors (which
/// overstate a stratified lattice's noise), plus `SLACK` for the GPU's 8-bit passes and the surface
/// point it reads back from the depth buffer.
const SIGMAS: f64 = 5.0;
const SLACK: f64 = 0.02;

/// What the sample found.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CrossCheck {
    /// Pixels traced on both (sky on either side left out).
    pub pixels: usize,
    /// Pixels whose values differ beyond the noise.
    pub outliers: usize,
    /// Mean GPU − CPU over the sample, and its standard error.
    pub mean_difference: f64,
    pub mean_error: f64,
    /// The largest GPU − CPU difference, and where.
    pub worst: (f64, u32, u32),
}

impl CrossCheck {
    /// Whether the GPU image can stand for the CPU's: at most 1 % of the sample (and one pixel)
    /// beyond the noise, and no bias beyond five standard errors of the mean (plus 0.005).
    pub fn agrees(&self) -> bool {
        let allowed = 1 + self.pixels / 100;
        self.outliers <= allowed
            && self.mean_difference.abs() <= SIGMAS * self.mean_error + SLACK / 4.0
    }
}

/// Traces a sample of `gpu`'s pixels on the CPU (`scene` seen by `cam`, the same `params`).
pub fn cross_check(scene: &Scene, cam: &Camera, params: &RefParams, gpu: &RefImage) -> CrossCheck {
    let (w, h) = (gpu.width, gpu.height);
    let (nx, ny) = (GRID.min(w), GRID.min(h));
    let pixels: Vec<(u32, u32)> = (0..ny)
        .flat_map(|j| (0..nx).map(move |i| (i, j)))
        .map(|(i, j)| ((2 * i + 1) * w / (2 * nx), (2 * j + 1) * h / (2 * ny)))
        .collect();
    let cpu_params = RefParams {
        progress: false,
        ..*params
    };
    let pairs: Vec<(f64, f64, u32, u32)> = pixels
        .par_iter()
        .filter_map(|&(x, y)| {
            let k = gpu.index(x, y);
            if !gpu.linear_depth[k].is_finite() {
                return None;
            }
            let (ao, err, depth) = trace_pixel(scene, cam, (x, y), (w, h), &cpu_params)?;
            if !depth.is_finite() {
                return None;
            }
            let d = (gpu.ao[k] - ao) as f64;
            let sigma = ((gpu.std_error[k] as f64).powi(2) + (err as f64).powi(2)).sqrt();
            Some((d, sigma, x, y))
        })
        .collect();
    let outliers = pairs
        .iter()
        .filter(|(d, sigma, ..)| d.abs() > SIGMAS * sigma + SLACK)
        .count();
    let m = pairs.len().max(1) as f64;
    let mean_difference = pairs.iter().map(|p| p.0).sum::<f64>() / m;
    let mean_error = pairs.iter().map(|p| p.1 * p.1).sum::<f64>().sqrt() / m;
    let worst = pairs
        .iter()
        .map(|&(d, _, x, y)| (d, x, y))
        .max_by(|a, b| a.0.abs().total_cmp(&b.0.abs()))
        .unwrap_or((0.0, 0, 0));
    CrossCheck {
        pixels: pairs.len(),
        outliers,
        mean_difference,
        mean_error,
        worst,
    }
}

/// [`cross_check`], as an error when the GPU image disagrees.
pub fn require_agreement(
    scene: &Scene,
    cam: &Camera,
    params: &RefParams,
    gpu: &RefImage,
) -> Result<CrossCheck> {
    let c = cross_check(scene, cam, params, gpu);
    if !c.agrees() {
        let (worst, x, y) = c.worst;
        let message = t!(
            "reference.gpu_disagrees",
            outliers = c.outliers,
            pixels = c.pixels,
            mean = format!("{:+.4}", c.mean_difference),
            worst = format!("{worst:+.3}"),
            x = x,
            y = y
        );
        bail!("{message}");
    }
    Ok(c)
}
