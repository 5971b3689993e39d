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

/// Pixels sampled per side: up to 32 × 32 = 1024 pixels, spread evenly over the image. A defect on
/// 2 % of the surface's pixels puts about 20 of the sample beyond the noise where 0.5 % are allowed.
/// (The CPU traces them in well under a second at 1024 rays on a 100 000-triangle scene.)
const GRID: u32 = 32;

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
    /// Whether the GPU image can stand for the CPU's: at most 0.5 % of the sample (and one pixel)
    /// beyond the noise (a silhouette pixel may see another surface on each), and no bias beyond five
    /// standard errors of the mean (plus 0.005).
    pub fn agrees(&self) -> bool {
        let allowed = 1 + self.pixels / 200;
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::shapes;
    use glam::Vec3;

    /// A floor and a box, traced on the CPU at `rays`.
    fn traced(rays: u32, seed: u64) -> (Scene, Camera, RefParams, RefImage) {
        let mut m = crate::gl::mesh::MeshData::default();
        shapes::add_box(
            &mut m,
            Vec3::new(-4.0, -0.1, -4.0),
            Vec3::new(4.0, 0.0, 4.0),
        );
        shapes::add_box(&mut m, Vec3::new(-0.5, 0.0, -0.5), Vec3::new(0.5, 0.8, 0.5));
        shapes::add_box(
            &mut m,
            Vec3::new(-1.2, 0.0, -1.2),
            Vec3::new(1.2, 1.5, -0.9),
        );
        shapes::add_box(&mut m, Vec3::new(0.7, 0.0, -0.9), Vec3::new(1.0, 1.0, 0.6));
        let scene = Scene::new(m.triangles().collect()).unwrap();
        let cam = Camera {
            eye: Vec3::new(0.6, 1.4, 2.2),
            target: Vec3::new(0.0, 0.3, -0.5),
            ..Camera::default()
        };
        let params = RefParams {
            rays,
            seed,
            ..RefParams::default()
        };
        let img = super::super::render_reference(&scene, &cam, 64, 48, &params);
        (scene, cam, params, img)
    }

    #[test]
    fn an_independent_trace_agrees_and_a_patch_too_bright_does_not() {
        // Another seed: the same estimate with other lattice shifts, as the GPU's are.
        let (scene, cam, params, _) = traced(256, 1);
        let (_, _, _, other) = traced(256, 2);
        let same = cross_check(&scene, &cam, &params, &other);
        assert!(same.pixels > 100, "{same:?}");
        assert!(same.agrees(), "{same:?}");
        // Square blocks too bright where something occludes, as rays left untraced make them: 4×4
        // blocks on a 12-pixel pitch, brought half way to open, on about 2 % of the surface.
        let mut bad = other.clone();
        let mut changed = 0;
        for y in 0..bad.height {
            for x in 0..bad.width {
                let k = bad.index(x, y);
                if x % 12 < 4 && y % 12 < 4 && bad.ao[k] < 0.8 {
                    bad.ao[k] += 0.5 * (1.0 - bad.ao[k]);
                    changed += 1;
                }
            }
        }
        let surface = bad.linear_depth.iter().filter(|d| d.is_finite()).count();
        let share = changed as f64 / surface as f64;
        assert!(share > 0.01 && share < 0.05, "{changed} of {surface}");
        let found = cross_check(&scene, &cam, &params, &bad);
        assert!(!found.agrees(), "{found:?}");
        assert!(require_agreement(&scene, &cam, &params, &bad).is_err());
        // A small bias over the whole picture, too.
        let mut biased = other;
        biased.ao.iter_mut().for_each(|v| *v = (*v + 0.03).min(1.0));
        let found = cross_check(&scene, &cam, &params, &biased);
        assert!(!found.agrees(), "{found:?}");
    }
}
