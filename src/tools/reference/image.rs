//! The reference's output image and the parallel per-pixel driver both references render with.

use indicatif::{ProgressBar, ProgressStyle};
use rayon::prelude::*;

/// Result of a reference render. All buffers are row-major, `width * height` long, row 0 at
/// the top of the image.
#[derive(Clone, Debug, PartialEq)]
pub struct RefImage {
    /// Image width in pixels.
    pub width: u32,
    /// Image height in pixels.
    pub height: u32,
    /// AO in [0, 1] (1 = unoccluded).
    pub ao: Vec<f32>,
    /// Standard error of `ao`: `sqrt(p(1-p)/N)` for visibility, sample standard deviation /
    /// `sqrt(N)` for obscurance; 0 for sky.
    pub std_error: Vec<f32>,
    /// View-space depth (distance along the view direction, i.e. `-z_view`) in metres,
    /// `f32::INFINITY` for sky.
    pub linear_depth: Vec<f32>,
}

impl RefImage {
    /// Mean of `std_error` over non-sky pixels (0 if there are none).
    pub fn mean_std_error(&self) -> f32 {
        let (sum, count) = self
            .std_error
            .iter()
            .zip(&self.linear_depth)
            .filter(|(_, d)| d.is_finite())
            .fold((0.0f64, 0usize), |(s, c), (e, _)| (s + *e as f64, c + 1));
        if count == 0 {
            0.0
        } else {
            (sum / count as f64) as f32
        }
    }

    /// `true` where the pixel saw no surface.
    pub fn sky_mask(&self) -> Vec<bool> {
        self.linear_depth.iter().map(|d| !d.is_finite()).collect()
    }

    /// Row-major index of pixel (x, y), row 0 = top.
    pub fn index(&self, x: u32, y: u32) -> usize {
        y as usize * self.width as usize + x as usize
    }
}

/// One pixel from the `n`×`n` sub-pixels of its footprint, `sub(i, j)` giving each one's (ao,
/// std_error, linear depth) as a pixel of an image `n` times wider and taller: the mean ao, so that a
/// board thinner than the pixel counts by the share of it that it covers, as in that image
/// box-averaged by `n`. Sky sub-pixels count as open (ao 1), as the engine's AO view is there; the
/// pixel is sky when at least half of them are (the error map's rule), else its depth is that of
/// the sub-pixel nearest its centre that saw a surface.
pub(crate) fn footprint_mean(
    n: u32,
    mut sub: impl FnMut(u32, u32) -> (f32, f32, f32),
) -> (f32, f32, f32) {
    let n = n.max(1);
    let centre = (n as f32 - 1.0) / 2.0;
    let (mut ao, mut variance, mut sky) = (0.0f64, 0.0f64, 0u32);
    let mut nearest = (f32::INFINITY, f32::INFINITY); // (distance² to the centre, depth)
    for j in 0..n {
        for i in 0..n {
            let (a, e, d) = sub(i, j);
            ao += a as f64;
            variance += (e as f64) * (e as f64);
            if d.is_finite() {
                let r2 = (i as f32 - centre).powi(2) + (j as f32 - centre).powi(2);
                if r2 < nearest.0 {
                    nearest = (r2, d);
                }
            } else {
                sky += 1;
            }
        }
    }
    let count = (n * n) as f64;
    let depth = if 2 * sky >= n * n {
        f32::INFINITY
    } else {
        nearest.1
    };
    ((ao / count) as f32, (variance.sqrt() / count) as f32, depth)
}

/// Runs `shade` over every pixel in parallel (rows on rayon, a progress bar labelled `what`):
/// `Some((ao, std_error, linear depth))`, or `None` for sky (ao 1, error 0, depth ∞).
pub(crate) fn shade_image(
    width: u32,
    height: u32,
    what: &str,
    progress: bool,
    shade: impl Fn(usize, usize) -> Option<(f32, f32, f32)> + Sync,
) -> RefImage {
    let n = width as usize * height as usize;
    let mut ao = vec![1.0f32; n];
    let mut std_error = vec![0.0f32; n];
    let mut linear_depth = vec![f32::INFINITY; n];
    let w = width as usize;
    if n > 0 {
        let bar = progress.then(|| rows_bar(what, height));
        ao.par_chunks_mut(w)
            .zip(std_error.par_chunks_mut(w))
            .zip(linear_depth.par_chunks_mut(w))
            .enumerate()
            .for_each(|(y, ((ao_row, se_row), depth_row))| {
                for x in 0..w {
                    if let Some((a, e, d)) = shade(x, y) {
                        ao_row[x] = a;
                        se_row[x] = e;
                        depth_row[x] = d;
                    }
                }
                if let Some(bar) = &bar {
                    bar.inc(1);
                }
            });
        if let Some(bar) = bar {
            bar.finish_and_clear();
        }
    }
    RefImage {
        width,
        height,
        ao,
        std_error,
        linear_depth,
    }
}

/// A progress bar over the `height` rows of an image, labelled `what`.
fn rows_bar(what: &str, height: u32) -> ProgressBar {
    let bar = ProgressBar::new(height as u64);
    let template =
        format!("{what} {{bar:40}} {{pos}}/{{len}} rows [{{elapsed_precise}} < {{eta_precise}}]");
    if let Ok(style) = ProgressStyle::with_template(&template) {
        bar.set_style(style);
    }
    bar
}
