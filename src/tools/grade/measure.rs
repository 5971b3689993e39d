//! Measurements shared by the steps: comparing outputs with predictions, and statistics over
//! images stored row by row (`w` texels wide).

use super::tol;

/// Fraction of the texels where `got` is finite and matches `predicted` (what a given mistake would
/// output) within `tol::MISTAKE_MATCH_REL`.
pub fn match_fraction(got: &[f32], predicted: &[f64]) -> f64 {
    let n = got.len().max(1);
    let ok = got
        .iter()
        .zip(predicted)
        .filter(|(g, p)| {
            let g = **g as f64;
            g.is_finite() && (g - **p).abs() <= tol::MISTAKE_MATCH_REL * p.abs() + 1e-6
        })
        .count();
    ok as f64 / n as f64
}

/// Whether the predictions of a mistake match `got` well enough to name the mistake.
pub fn matches(got: &[f32], predicted: &[f64]) -> bool {
    match_fraction(got, predicted) >= tol::MISTAKE_MATCH_FRACTION
}

/// What a shader's output looks like once stored in the engine's R8 target.
pub fn as_r8(v: f32) -> f32 {
    if v.is_finite() {
        v.clamp(0.0, 1.0)
    } else {
        0.0
    }
}

/// Means of `b`×`b` blocks over the pixels where `mask` is true (blocks at least half covered).
pub fn block_means(data: &[f32], mask: &[bool], w: usize, h: usize, b: usize) -> Vec<Option<f64>> {
    let mut out = Vec::new();
    for by in 0..h / b {
        for bx in 0..w / b {
            let (mut s, mut n) = (0.0f64, 0usize);
            for y in by * b..(by + 1) * b {
                for x in bx * b..(bx + 1) * b {
                    if mask[y * w + x] {
                        s += data[y * w + x] as f64;
                        n += 1;
                    }
                }
            }
            out.push((n * 2 >= b * b).then(|| s / n as f64));
        }
    }
    out
}

/// Mean of `f(v)` over the rectangle with corners `(x0, y0)` and `(x1, y1)` (inclusive, any order).
pub fn rect_mean(
    data: &[f32],
    w: usize,
    (x0, y0): (usize, usize),
    (x1, y1): (usize, usize),
    f: impl Fn(f32) -> f32,
) -> f64 {
    let (xa, xb) = (x0.min(x1), x0.max(x1));
    let (ya, yb) = (y0.min(y1), y0.max(y1));
    let mut sum = 0.0;
    let mut n = 0.0;
    for y in ya..=yb {
        for x in xa..=xb {
            sum += f(data[y * w + x]) as f64;
            n += 1.0;
        }
    }
    sum / n
}

/// Mean and standard deviation.
pub fn mean_and_std(v: impl Iterator<Item = f64>) -> (f64, f64) {
    let v: Vec<f64> = v.collect();
    let n = v.len().max(1) as f64;
    let mean = v.iter().sum::<f64>() / n;
    let var = v.iter().map(|x| (x - mean) * (x - mean)).sum::<f64>() / n;
    (mean, var.sqrt())
}
