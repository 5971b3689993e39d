//! The grader's pictures (`--out DIR`): expected, actual and a difference heat map per step.

use anyhow::{Context as _, Result};
use std::path::{Path, PathBuf};

/// How values become grey levels.
#[derive(Clone, Copy, Debug)]
pub enum Shade {
    /// A distance in metres, on a log scale from `near` (black) to `far` (white).
    Distance { near: f32, far: f32 },
    /// Occlusion in [0, 1], shown as visibility (white = open), like the AO view.
    Occlusion,
}

/// One image of a step (a test scene or a mip level): expected and actual values, rows bottom-up.
#[derive(Clone, Debug)]
pub struct Panel {
    pub width: usize,
    pub height: usize,
    pub expected: Vec<f32>,
    pub actual: Vec<f32>,
    pub shade: Shade,
    /// Per-texel difference, already scaled so that 1 is full heat (e.g. error / tolerance).
    pub diff: Vec<f32>,
}

impl Panel {
    /// A panel whose difference is |actual − expected| / `scale` (1 = full heat).
    pub fn absolute(
        width: usize,
        height: usize,
        expected: Vec<f32>,
        actual: Vec<f32>,
        shade: Shade,
        scale: f32,
    ) -> Panel {
        let diff = expected
            .iter()
            .zip(&actual)
            .map(|(e, a)| (a - e).abs() / scale)
            .collect();
        Panel {
            width,
            height,
            expected,
            actual,
            shade,
            diff,
        }
    }
}

fn grey(shade: Shade, v: f32) -> [u8; 3] {
    if !v.is_finite() {
        return [255, 0, 255];
    }
    let t = match shade {
        Shade::Distance { near, far } => {
            if v <= 0.0 {
                return [0, 0, 96]; // negative or zero distances: dark blue
            }
            ((v / near).ln() / (far / near).ln()).clamp(0.0, 1.0)
        }
        Shade::Occlusion => 1.0 - v.clamp(0.0, 1.0),
    };
    let g = (t * 255.0 + 0.5) as u8;
    [g, g, g]
}

/// Black → blue → red → yellow → white for t in [0, 1]; NaN is magenta.
pub fn heat(t: f32) -> [u8; 3] {
    if !t.is_finite() {
        return [255, 0, 255];
    }
    let t = t.clamp(0.0, 1.0);
    let stops: [[f32; 3]; 5] = [
        [0.0, 0.0, 0.0],
        [0.0, 0.0, 1.0],
        [1.0, 0.0, 0.0],
        [1.0, 1.0, 0.0],
        [1.0, 1.0, 1.0],
    ];
    let x = t * 4.0;
    let i = (x.floor() as usize).min(3);
    let f = x - i as f32;
    let c = |k: usize| ((stops[i][k] * (1.0 - f) + stops[i + 1][k] * f) * 255.0 + 0.5) as u8;
    [c(0), c(1), c(2)]
}

/// Lays the panels side by side (2 px apart) and writes `<step>-expected.png`, `<step>-actual.png`
/// and `<step>-difference.png` into `dir`.
pub fn write(dir: &Path, step: &str, panels: &[Panel]) -> Result<Vec<PathBuf>> {
    std::fs::create_dir_all(dir).with_context(|| format!("cannot create {}", dir.display()))?;
    let gap = 2usize;
    let width =
        panels.iter().map(|p| p.width).sum::<usize>() + gap * panels.len().saturating_sub(1);
    let height = panels.iter().map(|p| p.height).max().unwrap_or(1);
    let mut written = Vec::new();
    for which in ["expected", "actual", "difference"] {
        let mut img = image::RgbImage::from_pixel(
            width.max(1) as u32,
            height as u32,
            image::Rgb([40, 40, 40]),
        );
        let mut x0 = 0usize;
        for p in panels {
            for y in 0..p.height {
                for x in 0..p.width {
                    let i = y * p.width + x;
                    let c = match which {
                        "expected" => grey(p.shade, p.expected[i]),
                        "actual" => grey(p.shade, p.actual[i]),
                        _ => heat(p.diff[i]),
                    };
                    // Rows are stored bottom-up; images are top-down, bottom-aligned.
                    let row = height - 1 - y;
                    img.put_pixel((x0 + x) as u32, row as u32, image::Rgb(c));
                }
            }
            x0 += p.width + gap;
        }
        let path = dir.join(format!("{step}-{which}.png"));
        img.save(&path)
            .with_context(|| format!("cannot write {}", path.display()))?;
        written.push(path);
    }
    Ok(written)
}
