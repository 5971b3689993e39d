//! Image error metrics for single-channel visibility images in [0, 1], evaluated on masked pixels
//! (the reference's non-sky pixels): RMSE, MAE, PSNR, SSIM and FLIP, plus the fit of a method's free
//! intensity/contrast (`v' = min(1, a·v^b)`) and box downsampling.

use rayon::prelude::*;
use serde::Serialize;

/// PSNR reported for identical images (the MSE is 0): a finite cap so JSON stays numeric.
pub const PSNR_CAP_DB: f64 = 100.0;

/// Error of a test image against a reference on the masked pixels.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize)]
pub struct Metrics {
    pub rmse: f64,
    pub mae: f64,
    /// 10·log10(1 / MSE), peak 1, capped at [`PSNR_CAP_DB`].
    pub psnr: f64,
    /// Mean SSIM (Gaussian window σ = 1.5, 11×11; C1 = 0.01², C2 = 0.03²) over the masked pixels.
    pub ssim: f64,
    /// Mean LDR-FLIP error (NVIDIA ꟻLIP, 67 pixels per degree) over the masked pixels; the images are
    /// shown as grey sRGB values, as the PNGs of the AO views are.
    pub flip: f64,
    /// Pixels compared.
    pub pixels: usize,
}

/// A `width`×`height` single-channel image, rows top-down.
#[derive(Clone, Copy, Debug)]
pub struct Gray<'a> {
    pub width: usize,
    pub height: usize,
    pub data: &'a [f32],
}

impl<'a> Gray<'a> {
    pub fn new(width: usize, height: usize, data: &'a [f32]) -> Gray<'a> {
        assert_eq!(
            data.len(),
            width * height,
            "image buffer does not match its size"
        );
        Gray {
            width,
            height,
            data,
        }
    }
}

/// Mean squared and mean absolute error over the masked pixels (`None` = every pixel).
pub fn mse_mae(a: &[f32], b: &[f32], mask: Option<&[bool]>) -> (f64, f64, usize) {
    assert_eq!(a.len(), b.len());
    let (se, ae, n) = a
        .par_iter()
        .zip(b.par_iter())
        .enumerate()
        .filter(|(i, _)| mask.is_none_or(|m| m[*i]))
        .map(|(_, (x, y))| {
            let d = (*x as f64) - (*y as f64);
            (d * d, d.abs(), 1usize)
        })
        .reduce(|| (0.0, 0.0, 0), |p, q| (p.0 + q.0, p.1 + q.1, p.2 + q.2));
    if n == 0 {
        (0.0, 0.0, 0)
    } else {
        (se / n as f64, ae / n as f64, n)
    }
}

/// PSNR in dB for a peak of 1, capped at [`PSNR_CAP_DB`].
pub fn psnr_from_mse(mse: f64) -> f64 {
    if mse <= 0.0 {
        return PSNR_CAP_DB;
    }
    (10.0 * (1.0 / mse).log10()).min(PSNR_CAP_DB)
}

/// Separable Gaussian blur with clamp-to-edge borders.
fn gaussian_blur(img: &[f64], w: usize, h: usize, kernel: &[f64]) -> Vec<f64> {
    let r = kernel.len() / 2;
    let mut tmp = vec![0.0; w * h];
    tmp.par_chunks_mut(w).enumerate().for_each(|(y, row)| {
        for (x, out) in row.iter_mut().enumerate() {
            let mut s = 0.0;
            for (k, wk) in kernel.iter().enumerate() {
                let xx = (x + k).saturating_sub(r).min(w - 1);
                s += wk * img[y * w + xx];
            }
            *out = s;
        }
    });
    let mut out = vec![0.0; w * h];
    out.par_chunks_mut(w).enumerate().for_each(|(y, row)| {
        for (x, o) in row.iter_mut().enumerate() {
            let mut s = 0.0;
            for (k, wk) in kernel.iter().enumerate() {
                let yy = (y + k).saturating_sub(r).min(h - 1);
                s += wk * tmp[yy * w + x];
            }
            *o = s;
        }
    });
    out
}

fn gaussian_kernel(sigma: f64, radius: usize) -> Vec<f64> {
    let k: Vec<f64> = (0..=2 * radius)
        .map(|i| {
            let x = i as f64 - radius as f64;
            (-x * x / (2.0 * sigma * sigma)).exp()
        })
        .collect();
    let s: f64 = k.iter().sum();
    k.into_iter().map(|v| v / s).collect()
}

/// Per-pixel SSIM map (Wang et al. 2004: Gaussian window σ = 1.5 truncated to 11×11, dynamic range 1).
fn ssim_map(a: Gray, b: Gray) -> Vec<f64> {
    assert_eq!((a.width, a.height), (b.width, b.height));
    let (w, h) = (a.width, a.height);
    if w == 0 || h == 0 {
        return Vec::new();
    }
    let k = gaussian_kernel(1.5, 5);
    let x: Vec<f64> = a.data.iter().map(|v| *v as f64).collect();
    let y: Vec<f64> = b.data.iter().map(|v| *v as f64).collect();
    let xx: Vec<f64> = x.iter().map(|v| v * v).collect();
    let yy: Vec<f64> = y.iter().map(|v| v * v).collect();
    let xy: Vec<f64> = x.iter().zip(&y).map(|(p, q)| p * q).collect();
    let mx = gaussian_blur(&x, w, h, &k);
    let my = gaussian_blur(&y, w, h, &k);
    let sxx = gaussian_blur(&xx, w, h, &k);
    let syy = gaussian_blur(&yy, w, h, &k);
    let sxy = gaussian_blur(&xy, w, h, &k);
    const C1: f64 = 0.01 * 0.01;
    const C2: f64 = 0.03 * 0.03;
    (0..w * h)
        .into_par_iter()
        .map(|i| {
            let (mx, my) = (mx[i], my[i]);
            // Variances can come out a hair negative from rounding.
            let vx = (sxx[i] - mx * mx).max(0.0);
            let vy = (syy[i] - my * my).max(0.0);
            let cxy = sxy[i] - mx * my;
            ((2.0 * mx * my + C1) * (2.0 * cxy + C2)) / ((mx * mx + my * my + C1) * (vx + vy + C2))
        })
        .collect()
}

/// Mean of `map` over the masked pixels (`None` = all); 1 if the mask selects nothing.
fn masked_mean(map: &[f64], mask: Option<&[bool]>) -> f64 {
    let (s, n) = map
        .iter()
        .enumerate()
        .filter(|(i, _)| mask.is_none_or(|m| m[*i]))
        .fold((0.0, 0usize), |(s, n), (_, v)| (s + v, n + 1));
    if n == 0 {
        1.0
    } else {
        s / n as f64
    }
}

/// Mean SSIM over the masked pixels.
pub fn ssim(a: Gray, b: Gray, mask: Option<&[bool]>) -> f64 {
    masked_mean(&ssim_map(a, b), mask)
}

#[cfg(feature = "bench")]
fn to_srgb8_rgb(v: &[f32]) -> Vec<u8> {
    v.iter()
        .flat_map(|x| {
            let g = (x.clamp(0.0, 1.0) * 255.0).round() as u8;
            [g, g, g]
        })
        .collect()
}

#[cfg(feature = "bench")]
/// Per-pixel LDR-FLIP error map (NVIDIA ꟻLIP through the `nv-flip` crate), 67 pixels per degree.
fn flip_map(reference: Gray, test: Gray) -> Vec<f32> {
    assert_eq!(
        (reference.width, reference.height),
        (test.width, test.height)
    );
    let (w, h) = (reference.width as u32, reference.height as u32);
    if w == 0 || h == 0 {
        return Vec::new();
    }
    let r = nv_flip::FlipImageRgb8::with_data(w, h, &to_srgb8_rgb(reference.data));
    let t = nv_flip::FlipImageRgb8::with_data(w, h, &to_srgb8_rgb(test.data));
    nv_flip::flip(r, t, nv_flip::DEFAULT_PIXELS_PER_DEGREE).to_vec()
}

/// Mean FLIP over the masked pixels.
#[cfg(feature = "bench")]
pub fn flip(reference: Gray, test: Gray, mask: Option<&[bool]>) -> f64 {
    let m: Vec<f64> = flip_map(reference, test)
        .iter()
        .map(|v| *v as f64)
        .collect();
    masked_mean(&m, mask).clamp(0.0, 1.0)
}

/// Every metric of `test` against `reference` on the masked pixels. `with_flip = false` skips FLIP
/// (the slowest) and reports 0 for it.
#[cfg(feature = "bench")]
pub fn compare(reference: Gray, test: Gray, mask: Option<&[bool]>, with_flip: bool) -> Metrics {
    let (mse, mae, pixels) = mse_mae(reference.data, test.data, mask);
    Metrics {
        rmse: mse.sqrt(),
        mae,
        psnr: psnr_from_mse(mse),
        ssim: ssim(reference, test, mask),
        flip: if with_flip {
            flip(reference, test, mask)
        } else {
            0.0
        },
        pixels,
    }
}

/// Averages `factor`×`factor` blocks (the last partial blocks average what they have). Rows top-down.
pub fn downsample(
    data: &[f32],
    width: usize,
    height: usize,
    factor: usize,
) -> (Vec<f32>, usize, usize) {
    if factor <= 1 {
        return (data.to_vec(), width, height);
    }
    let (ow, oh) = (width.div_ceil(factor), height.div_ceil(factor));
    let mut out = vec![0.0f32; ow * oh];
    out.par_chunks_mut(ow).enumerate().for_each(|(oy, row)| {
        for (ox, o) in row.iter_mut().enumerate() {
            let (mut s, mut n) = (0.0f64, 0usize);
            for y in oy * factor..((oy + 1) * factor).min(height) {
                for x in ox * factor..((ox + 1) * factor).min(width) {
                    s += data[y * width + x] as f64;
                    n += 1;
                }
            }
            *o = (s / n.max(1) as f64) as f32;
        }
    });
    (out, ow, oh)
}

/// The free intensity/contrast of a method: visibility `v` is mapped to `min(1, a·v^b)`.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Fit {
    pub a: f64,
    pub b: f64,
}

impl Fit {
    pub const IDENTITY: Fit = Fit { a: 1.0, b: 1.0 };
    pub fn apply(&self, v: f32) -> f32 {
        let x = (v.clamp(0.0, 1.0) as f64).powf(self.b) * self.a;
        x.clamp(0.0, 1.0) as f32
    }
    pub fn apply_all(&self, v: &[f32]) -> Vec<f32> {
        v.par_iter().map(|x| self.apply(*x)).collect()
    }
}

fn fit_sse(pairs: &[(f32, f32)], a: f64, b: f64) -> f64 {
    pairs
        .par_iter()
        .map(|(v, r)| {
            let x = ((*v as f64).powf(b) * a).clamp(0.0, 1.0);
            let d = x - *r as f64;
            d * d
        })
        .sum()
}

/// Least-squares fit of `min(1, a·v^b)` to the reference over `(v, reference)` pairs: a grid over
/// b (0.05–20, log-spaced) with the best a for each, then a shrinking pattern search in (ln a, ln b).
pub fn fit_power(pairs: &[(f32, f32)]) -> Fit {
    if pairs.is_empty() {
        return Fit::IDENTITY;
    }
    let mut best = (f64::INFINITY, 1.0f64, 1.0f64);
    for i in 0..=60 {
        let b = (0.05f64.ln() + (20.0f64.ln() - 0.05f64.ln()) * i as f64 / 60.0).exp();
        // Best a ignoring the clamp: minimises Σ(a·x − r)².
        let (sxr, sxx) = pairs
            .par_iter()
            .map(|(v, r)| {
                let x = (*v as f64).powf(b);
                (x * *r as f64, x * x)
            })
            .reduce(|| (0.0, 0.0), |p, q| (p.0 + q.0, p.1 + q.1));
        let a = if sxx > 0.0 {
            (sxr / sxx).clamp(1e-3, 1e3)
        } else {
            1.0
        };
        let e = fit_sse(pairs, a, b);
        if e < best.0 {
            best = (e, a, b);
        }
    }
    let (mut e, mut la, mut lb) = (best.0, best.1.ln(), best.2.ln());
    let mut step = 0.25;
    for _ in 0..60 {
        let mut improved = false;
        for (da, db) in [(step, 0.0), (-step, 0.0), (0.0, step), (0.0, -step)] {
            let (na, nb) = (la + da, (lb + db).clamp(-6.0, 4.0));
            let ne = fit_sse(pairs, na.exp(), nb.exp());
            if ne < e {
                (e, la, lb) = (ne, na, nb);
                improved = true;
            }
        }
        if !improved {
            step *= 0.5;
            if step < 1e-4 {
                break;
            }
        }
    }
    Fit {
        a: la.exp(),
        b: lb.exp(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn fit_recovers_a_power_map() {
        let pairs: Vec<(f32, f32)> = (0..1000)
            .map(|i| {
                let v = i as f32 / 999.0;
                (v, (0.9 * (v as f64).powf(2.0)) as f32)
            })
            .collect();
        let f = fit_power(&pairs);
        assert!(
            (f.a - 0.9).abs() < 1e-2 && (f.b - 2.0).abs() < 2e-2,
            "{f:?}"
        );
    }

    #[test]
    fn downsample_averages_blocks() {
        let d = [1.0, 3.0, 5.0, 7.0, 0.0, 0.0, 2.0, 2.0, 9.0];
        let (o, w, h) = downsample(&d, 3, 3, 2);
        assert_eq!((w, h), (2, 2));
        assert_eq!(o, vec![2.75, 2.5, 2.0, 9.0]);
    }
}
