//! Signed error maps: the engine's AO view (visibility, 1 = open) minus a truth image of the same
//! view, box-averaged first when the truth is smaller by a whole factor (the bench's `--ref-scale`
//! rule). Too dark (engine below the truth) is blue, too light orange, 0 white, sky grey; the
//! picture has a labelled colour scale under it. `render --view error --truth FILE` and the bench's
//! `report.html` draw them.

use crate::io::scale_bar::{self, Scale};
use crate::render::{Engine, View};
use crate::tools::metrics;
use anyhow::{bail, Result};
use image::{Rgb, RgbImage};
use rust_i18n::t;
use std::path::Path;

/// The error a full scale of colour stands for when none is chosen (visibility units).
pub const DEFAULT_RANGE: f32 = 0.25;

/// Colour of 0 (no error).
pub const ZERO: [u8; 3] = [255, 255, 255];
/// Colour of −range and below: the engine is too dark (more occlusion than the truth).
pub const TOO_DARK: [u8; 3] = [33, 102, 172];
/// Colour of +range and above: the engine is too light (less occlusion than the truth).
pub const TOO_LIGHT: [u8; 3] = [230, 97, 1];
/// Colour of sky pixels (not compared).
pub const SKY: [u8; 3] = [128, 128, 128];
/// Colour of a difference that is not a number.
pub const NOT_A_NUMBER: [u8; 3] = [255, 0, 255];

/// The engine's view against a truth, at the truth's size (rows top-down).
#[derive(Clone, Debug)]
pub struct ErrorMap {
    pub width: usize,
    pub height: usize,
    /// engine − truth per pixel (sky pixels included: both are 1 there).
    pub diff: Vec<f32>,
    /// Pixels left out of the statistics and drawn grey.
    pub sky: Vec<bool>,
    /// Over the pixels that are not sky.
    pub rmse: f64,
    /// 10·log10(1 / MSE), capped at `metrics::PSNR_CAP_DB`.
    pub psnr: f64,
    pub pixels: usize,
    /// The box each truth pixel averages (1 when the sizes are equal).
    pub factor: usize,
}

/// The whole factor the truth's size (`tw`×`th`) divides the engine's (`ew`×`eh`) by, the same
/// on both axes, or an error naming both sizes.
pub fn factor((ew, eh): (usize, usize), (tw, th): (usize, usize)) -> Result<usize> {
    if tw > 0 && th > 0 && ew.is_multiple_of(tw) && eh.is_multiple_of(th) && ew / tw == eh / th {
        return Ok(ew / tw);
    }
    bail!(
        "{}",
        t!(
            "error_map.bad_size",
            truth = format!("{tw}x{th}"),
            engine = format!("{ew}x{eh}")
        )
    )
}

/// Compares `engine` (`ew`×`eh`, with its sky mask) with `truth` (`tw`×`th`, see [`factor`]). A
/// box-averaged pixel is sky when at least half of its box is.
pub fn compare(
    engine: &[f32],
    sky: &[bool],
    (ew, eh): (usize, usize),
    truth: &[f32],
    (tw, th): (usize, usize),
) -> Result<ErrorMap> {
    let factor = factor((ew, eh), (tw, th))?;
    let (v, _, _) = metrics::downsample(engine, ew, eh, factor);
    let sky_share: Vec<f32> = sky.iter().map(|s| if *s { 1.0 } else { 0.0 }).collect();
    let (sky_share, _, _) = metrics::downsample(&sky_share, ew, eh, factor);
    let sky: Vec<bool> = sky_share.iter().map(|s| *s >= 0.5).collect();
    Ok(at_truth_size(&v, truth, sky, (tw, th), factor))
}

/// The map of `view`, already at the truth's size (`w`×`h`, box-averaged over `factor`²), against
/// `truth`, leaving the `sky` pixels out of the statistics.
pub fn at_truth_size(
    view: &[f32],
    truth: &[f32],
    sky: Vec<bool>,
    (w, h): (usize, usize),
    factor: usize,
) -> ErrorMap {
    let diff: Vec<f32> = view.iter().zip(truth).map(|(e, t)| e - t).collect();
    let (se, n) = diff
        .iter()
        .zip(&sky)
        .filter(|(_, s)| !**s)
        .fold((0.0f64, 0usize), |(se, n), (d, _)| {
            (se + (*d as f64).powi(2), n + 1)
        });
    let mse = if n == 0 { 0.0 } else { se / n as f64 };
    ErrorMap {
        width: w,
        height: h,
        diff,
        sky,
        rmse: mse.sqrt(),
        psnr: metrics::psnr_from_mse(mse),
        pixels: n,
        factor,
    }
}

fn mix(a: [u8; 3], b: [u8; 3], f: f32) -> [u8; 3] {
    let c = |k: usize| (a[k] as f32 * (1.0 - f) + b[k] as f32 * f).round() as u8;
    [c(0), c(1), c(2)]
}

/// The colour of `t` = error / range: white at 0, `TOO_DARK` at −1 and below, `TOO_LIGHT` at +1
/// and above, linear in between.
pub fn diverging(t: f32) -> [u8; 3] {
    if t.is_nan() {
        return NOT_A_NUMBER;
    }
    if t < 0.0 {
        mix(ZERO, TOO_DARK, (-t).min(1.0))
    } else {
        mix(ZERO, TOO_LIGHT, t.min(1.0))
    }
}

/// The narrowest picture drawn: smaller maps are enlarged by a whole factor (nearest neighbour).
pub const MIN_WIDTH: usize = 320;

/// The whole factor a `width`-pixel map is enlarged by in its picture.
pub fn zoom(width: usize) -> usize {
    MIN_WIDTH.div_ceil(width.max(1)).max(1)
}

/// The picture: each pixel `zoom(width)`² pixels (sky grey), the colour scale under it from
/// −`range` ("too dark") to +`range` ("too light"), with a marker at the
/// largest error (by magnitude, with its sign) outside the sky.
pub fn picture(map: &ErrorMap, range: f32) -> RgbImage {
    let z = zoom(map.width);
    let (w, h) = ((map.width * z) as u32, (map.height * z) as u32);
    let mut img = RgbImage::from_pixel(w, h + scale_bar::HEIGHT, Rgb([40, 40, 40]));
    for y in 0..map.height {
        for x in 0..map.width {
            let i = y * map.width + x;
            let c = if map.sky[i] {
                SKY
            } else {
                diverging(map.diff[i] / range)
            };
            for dy in 0..z {
                for dx in 0..z {
                    img.put_pixel((x * z + dx) as u32, (y * z + dy) as u32, Rgb(c));
                }
            }
        }
    }
    let worst = map
        .diff
        .iter()
        .zip(&map.sky)
        .filter(|(_, s)| !**s)
        .map(|(d, _)| *d)
        .fold(0.0f32, |m, d| {
            if d.is_nan() || m.is_nan() {
                f32::NAN
            } else if d.abs() > m.abs() {
                d
            } else {
                m
            }
        });
    let signed = |v: f32| {
        if v > 0.0 {
            format!("+{}", scale_bar::label(v))
        } else {
            scale_bar::label(v)
        }
    };
    // Numbers only, in every language: the colours say which side is too dark.
    let ticks = [
        (0.0, signed(-range)),
        (0.5, "0".to_string()),
        (1.0, signed(range)),
    ];
    let scale = Scale {
        ticks: &ticks,
        marker: Some((0.5 + 0.5 * worst / range, signed(worst))),
    };
    scale_bar::draw_scale(&mut img, h, &scale, |t| diverging(2.0 * t - 1.0));
    img
}

/// Writes the map: `.pfm` the raw signed difference at the truth's size, anything else the picture
/// (PNG).
pub fn write(path: &Path, map: &ErrorMap, range: f32) -> Result<()> {
    crate::io::create_parent(path)?;
    let pfm = path
        .extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("pfm"));
    if pfm {
        crate::io::write_pfm_gray(path, map.width as u32, map.height as u32, &map.diff)
    } else {
        crate::io::write_png(path, &picture(map, range))
    }
}

/// The engine's AO view and its sky mask (the pixels whose linear depth reaches the far plane),
/// rows top-down.
pub fn engine_view(engine: &mut Engine) -> Result<(Vec<f32>, Vec<bool>)> {
    let ao = engine.render_values(View::Ao)?;
    let far = engine.camera.far;
    let sky = engine
        .render_values(View::LinearDepth)?
        .iter()
        .map(|d| d.is_nan() || *d >= far * (1.0 - 1e-4))
        .collect();
    Ok((ao, sky))
}

/// The widest truth `render --view error` traces itself when no `--truth` is given: at the bench's
/// size (320×180 for a 1920×1080 render), a trace takes seconds, not minutes, on two cores.
pub const TRACED_TRUTH_MAX_WIDTH: u32 = 320;

/// Rays per pixel of a traced truth: `opengl3d reference`'s default and the bench's, so all three
/// share cached files.
pub const TRACED_TRUTH_RAYS: u32 = 256;

/// The whole factor a `width`×`height` render is divided by for its traced truth: the smallest
/// factor of both sides that brings the width to [`TRACED_TRUTH_MAX_WIDTH`] or less (1 when the
/// sides share no such factor).
pub fn traced_truth_factor(width: u32, height: u32) -> u32 {
    let wanted = width.div_ceil(TRACED_TRUTH_MAX_WIDTH).max(1);
    let common = gcd(width, height);
    (wanted..=common)
        .find(|f| common.is_multiple_of(*f))
        .unwrap_or(1)
}

fn gcd(a: u32, b: u32) -> u32 {
    if b == 0 {
        a
    } else {
        gcd(b, a % b)
    }
}

/// A truth traced for the scene's camera and radius.
pub struct TracedTruth {
    pub width: usize,
    pub height: usize,
    pub ao: Vec<f32>,
    /// Read from the reference cache instead of traced.
    pub cached: bool,
    /// The file it is cached in.
    pub path: std::path::PathBuf,
}

/// The truth of `scene`'s view traced by `opengl3d reference`'s CPU ray tracer (visibility at the
/// AO radius, [`TRACED_TRUTH_RAYS`] rays, each pixel the mean over the footprint of the
/// `factor`² render pixels it stands for, as the bench's truths), read from the reference cache
/// in `cache_dir` when it holds it, otherwise traced with a progress bar on stderr and stored
/// there (an unwritable cache is a warning).
pub fn traced_truth(
    res: &crate::res::ResDirs,
    scene: &crate::scene::SceneDesc,
    cache_dir: &Path,
) -> Result<TracedTruth> {
    use crate::tools::reference::{self as reference, AoVariant, RefParams};
    let (w, h) = (scene.output.width, scene.output.height);
    let f = traced_truth_factor(w, h);
    let (tw, th) = (w / f, h / f);
    let bvh = reference::Scene::new(scene.world_triangles(res)?)?;
    let cam = scene.camera.camera();
    let params = RefParams {
        radius: scene.ao.radius,
        rays: TRACED_TRUTH_RAYS,
        variant: AoVariant::Visibility,
        seed: 1,
        progress: true,
        supersample: f,
    };
    let key = reference::cache_key(bvh.content_hash(), &cam, tw, th, &params);
    let path = reference::cache_path(cache_dir, &key);
    let found = reference::read_cached(cache_dir, &key).filter(|i| (i.width, i.height) == (tw, th));
    let cached = found.is_some();
    let img = match found {
        Some(img) => img,
        None => {
            let img = reference::render_reference(&bvh, &cam, tw, th, &params);
            if let Err(e) = reference::write_cached(cache_dir, &key, &img) {
                let message = format!("{e:#}");
                eprintln!("{}", t!("render.warning", message = message));
            }
            img
        }
    };
    Ok(TracedTruth {
        width: tw as usize,
        height: th as usize,
        ao: img.ao,
        cached,
        path,
    })
}

/// Reads a single-channel truth PFM (rows top-down): errors name the file.
pub fn read_truth(path: &Path) -> Result<(usize, usize, Vec<f32>)> {
    let (w, h, c, v) = crate::io::read_pfm(path).map_err(|e| {
        anyhow::anyhow!(
            "{}",
            t!(
                "error_map.truth_unreadable",
                path = path.display(),
                error = format!("{e:#}")
            )
        )
    })?;
    if c != 1 {
        bail!(
            "{}",
            t!(
                "error_map.truth_channels",
                path = path.display(),
                channels = c
            )
        );
    }
    Ok((w as usize, h as usize, v))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_smaller_truth_is_compared_with_the_box_average() {
        // 4×2 engine, 2×1 truth: boxes of 2×2.
        let engine = [0.2, 0.4, 1.0, 1.0, 0.6, 0.8, 1.0, 1.0];
        let sky = [false, false, true, true, false, false, true, true];
        let m = compare(&engine, &sky, (4, 2), &[0.7, 1.0], (2, 1)).unwrap();
        assert_eq!((m.width, m.height, m.factor), (2, 1, 2));
        assert!((m.diff[0] - (0.5 - 0.7)).abs() < 1e-6);
        assert_eq!(m.sky, [false, true]);
        assert_eq!(m.pixels, 1);
        assert!((m.rmse - 0.2).abs() < 1e-6);
        assert!((m.psnr - 10.0 * (1.0f64 / 0.04).log10()).abs() < 1e-4);
    }

    #[test]
    fn a_truth_of_another_shape_is_refused_naming_both_sizes() {
        let e = compare(&[0.0; 12], &[false; 12], (4, 3), &[0.0; 6], (3, 2)).unwrap_err();
        let msg = format!("{e}");
        assert!(msg.contains("3x2") && msg.contains("4x3"), "{msg}");
        // A whole factor on one axis only is refused too.
        assert!(compare(&[0.0; 16], &[false; 16], (4, 4), &[0.0; 4], (2, 2)).is_ok());
        assert!(compare(&[0.0; 16], &[false; 16], (4, 4), &[0.0; 8], (2, 4)).is_err());
    }

    #[test]
    fn a_traced_truth_is_at_most_320_wide_by_a_whole_factor() {
        assert_eq!(traced_truth_factor(1920, 1080), 6);
        assert_eq!(traced_truth_factor(1280, 720), 4);
        assert_eq!(traced_truth_factor(320, 180), 1);
        assert_eq!(traced_truth_factor(80, 60), 1);
        assert_eq!(traced_truth_factor(1000, 700), 4);
        // 1001×700 share only 7: 143×100.
        assert_eq!(traced_truth_factor(1001, 700), 7);
        // Sides that share no factor large enough: the render's own size.
        assert_eq!(traced_truth_factor(641, 360), 1);
    }

    #[test]
    fn the_colours_diverge_from_white() {
        assert_eq!(diverging(0.0), ZERO);
        assert_eq!(diverging(-1.0), TOO_DARK);
        assert_eq!(diverging(-3.0), TOO_DARK);
        assert_eq!(diverging(1.0), TOO_LIGHT);
        let half = diverging(-0.5);
        assert!(half[2] > half[0], "a half-dark error is bluish: {half:?}");
        assert_eq!(diverging(f32::NAN), NOT_A_NUMBER);
    }
}
