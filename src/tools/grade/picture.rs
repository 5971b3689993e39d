//! The grader's pictures (`--out DIR`, and the class report's): expected, actual and a difference
//! heat map per step, at least `MIN_WIDTH` pixels wide, the heat map with its colour scale.

use crate::io::scale_bar;
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

/// The narrowest picture written: smaller rigs are enlarged (nearest neighbour, whole factors) so
/// that a texel stays visible and the scale bar has room.
pub const MIN_WIDTH: usize = 256;

/// Lays the panels side by side (2 px apart), enlarges them by a whole factor to at least
/// `MIN_WIDTH` pixels, and writes `<step>-expected.png`, `<step>-actual.png` and
/// `<step>-difference.png` into `dir`. The difference picture has a colour scale under it (0 to 1,
/// the panels' full heat, with a marker at the largest difference).
pub fn write(dir: &Path, step: &str, panels: &[Panel]) -> Result<Vec<PathBuf>> {
    std::fs::create_dir_all(dir).with_context(|| format!("cannot create {}", dir.display()))?;
    let gap = 2usize;
    let width = (panels.iter().map(|p| p.width).sum::<usize>()
        + gap * panels.len().saturating_sub(1))
    .max(1);
    let height = panels.iter().map(|p| p.height).max().unwrap_or(1).max(1);
    let zoom = MIN_WIDTH.div_ceil(width).max(1);
    let max_diff = panels
        .iter()
        .flat_map(|p| p.diff.iter().copied())
        .fold(0.0f32, |m, d| {
            if d.is_nan() || m.is_nan() {
                f32::NAN
            } else {
                m.max(d)
            }
        });
    let mut written = Vec::new();
    for which in ["expected", "actual", "difference"] {
        let bar = if which == "difference" {
            scale_bar::HEIGHT
        } else {
            0
        };
        let mut img = image::RgbImage::from_pixel(
            (width * zoom) as u32,
            (height * zoom) as u32 + bar,
            image::Rgb([40, 40, 40]),
        );
        let mut x0 = 0usize;
        for p in panels {
            for y in 0..p.height {
                for x in 0..p.width {
                    let i = y * p.width + x;
                    let c = image::Rgb(match which {
                        "expected" => grey(p.shade, p.expected[i]),
                        "actual" => grey(p.shade, p.actual[i]),
                        _ => heat(p.diff[i]),
                    });
                    // Rows are stored bottom-up; images are top-down, bottom-aligned.
                    let row = height - 1 - y;
                    for dy in 0..zoom {
                        for dx in 0..zoom {
                            let px = ((x0 + x) * zoom + dx) as u32;
                            img.put_pixel(px, (row * zoom + dy) as u32, c);
                        }
                    }
                }
            }
            x0 += p.width + gap;
        }
        if bar > 0 {
            scale_bar::draw(&mut img, (height * zoom) as u32, max_diff, heat);
        }
        let path = dir.join(format!("{step}-{which}.png"));
        img.save(&path)
            .with_context(|| format!("cannot write {}", path.display()))?;
        written.push(path);
    }
    Ok(written)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_small_rig_is_enlarged_to_256_px_with_a_scale_under_the_heat_map() {
        let dir = std::env::temp_dir().join(format!("opengl3d-picture-{}", std::process::id()));
        // 10×4 texels, bottom-up rows: texel (9, 0) (bottom right) is off by 2 × full scale.
        let expected = vec![0.5f32; 40];
        let mut actual = expected.clone();
        actual[9] = 1.0;
        let panel = Panel::absolute(10, 4, expected, actual, Shade::Occlusion, 0.25);
        let files = write(&dir, "step", &[panel]).unwrap();
        let read = |i: usize| image::open(&files[i]).unwrap().to_rgb8();
        let (expected, difference) = (read(0), read(2));
        // 256 / 10 rounds up to a zoom of 26: 260 px wide, 104 px high, each texel 26×26 px.
        assert_eq!(expected.dimensions(), (260, 104));
        assert_eq!(difference.dimensions(), (260, 104 + scale_bar::HEIGHT));
        // The off texel is the whole bottom-right 26×26 block, full heat (white, the top of the
        // colour scale); its neighbours are 0 (black).
        for (x, y) in [(234, 78), (259, 103), (250, 90)] {
            assert_eq!(difference.get_pixel(x, y).0, heat(1.0), "({x}, {y})");
        }
        for (x, y) in [(233, 103), (259, 77), (0, 0)] {
            assert_eq!(difference.get_pixel(x, y).0, heat(0.0), "({x}, {y})");
        }
        // Under it, the bar runs from the colour of 0 to the colour of 1.
        let bar_rows = (104..difference.height())
            .filter(|&y| {
                difference.get_pixel(10, y).0 == heat(0.0)
                    && difference.get_pixel(249, y).0 == heat(1.0)
            })
            .count();
        assert!(bar_rows >= 10, "{bar_rows} rows of the bar");
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
