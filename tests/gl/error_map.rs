//! `render --view error --truth FILE`: the sign and scale of the error map on truths whose answer is
//! known (the engine's own AO view, shifted by ±0.2 in places), the box average for a smaller
//! truth, the scale bar, and clear errors.

use crate::common;
use crate::common::{bin, fails_with, run, stderr};
use opengl3d::io::{read_pfm, scale_bar, write_pfm_gray};
use opengl3d::tools::error_map::{self, SKY, TOO_DARK, TOO_LIGHT, ZERO};
use std::path::Path;

const W: u32 = 80;
const H: u32 = 60;

fn size_flags(w: u32, h: u32) -> Vec<String> {
    ["--width", &w.to_string(), "--height", &h.to_string()]
        .map(String::from)
        .to_vec()
}

/// The engine's AO view of the demo at `w`×`h` (rows top-down).
fn ao_view(dir: &Path, w: u32, h: u32) -> Vec<f32> {
    let out = dir.join(format!("ao-{w}x{h}.pfm"));
    let mut args = vec!["render".to_string(), "--view".into(), "ao".into()];
    args.extend(size_flags(w, h));
    args.extend(["--out".into(), out.to_str().unwrap().into()]);
    let o = run(&args);
    assert!(o.status.success(), "{}", stderr(&o));
    let (rw, rh, c, v) = read_pfm(&out).unwrap();
    assert_eq!((rw, rh, c), (w, h, 1));
    v
}

/// Runs `render --view error` at `w`×`h` against `truth`; returns stdout's PSNR.
fn error_render(truth: &Path, w: u32, h: u32, out: &Path, extra: &[&str]) -> f64 {
    let mut args = vec![
        "--lang".to_string(),
        "en".into(),
        "render".into(),
        "--view".into(),
        "error".into(),
        "--truth".into(),
        truth.to_str().unwrap().into(),
    ];
    args.extend(size_flags(w, h));
    args.extend(extra.iter().map(|s| s.to_string()));
    args.extend(["--out".into(), out.to_str().unwrap().into()]);
    let o = run(&args);
    assert!(o.status.success(), "{}", stderr(&o));
    let text = String::from_utf8_lossy(&o.stdout).to_string();
    let psnr = text
        .split("PSNR ")
        .nth(1)
        .and_then(|s| s.split(" dB").next())
        .and_then(|s| s.parse::<f64>().ok());
    psnr.unwrap_or_else(|| panic!("no PSNR on stdout:\n{text}"))
}

/// The colour of map pixel (x, y) in the picture (each pixel is a zoom × zoom block).
fn colour(img: &image::RgbImage, x: usize, y: usize, width: usize) -> [u8; 3] {
    let z = error_map::zoom(width);
    img.get_pixel((x * z + z / 2) as u32, (y * z + z / 2) as u32)
        .0
}

#[test]
fn the_engine_against_itself_is_white_and_shifted_truths_get_their_sign() {
    let dir = common::temp_dir("error-map-sign");
    let ao = ao_view(&dir, W, H);
    let (w, h) = (W as usize, H as usize);

    // The same picture: PSNR at the cap, every compared pixel white.
    let same = dir.join("same.pfm");
    write_pfm_gray(&same, W, H, &ao).unwrap();
    let out = dir.join("same.png");
    let psnr = error_render(&same, W, H, &out, &[]);
    assert!(psnr >= 60.0, "PSNR {psnr} dB against its own output");
    let img = image::open(&out).unwrap().to_rgb8();
    let z = error_map::zoom(w) as u32;
    assert_eq!(img.dimensions(), (W * z, H * z + scale_bar::HEIGHT));
    let (mut white, mut sky) = (0, 0);
    for y in 0..h {
        for x in 0..w {
            match colour(&img, x, y, w) {
                c if c == ZERO => white += 1,
                c if c == SKY => sky += 1,
                c => panic!("pixel ({x}, {y}) is {c:?}, neither white nor sky"),
            }
        }
    }
    assert!(white > w * h / 2, "{white} white pixels, {sky} sky");

    // The truth 0.2 brighter in the left half of the bottom quarter of rows (the engine too dark
    // there) and 0.2 darker in its right half (too light); at a range of 0.1 both are full colour.
    let mut shifted = ao.clone();
    let quarter = |x: usize, y: usize| match (y >= h * 3 / 4, x < w / 2) {
        (false, _) => 0,
        (true, true) => 1,
        (true, false) => 2,
    };
    for y in 0..h {
        for x in 0..w {
            shifted[y * w + x] += [0.0, 0.2, -0.2][quarter(x, y)];
        }
    }
    let truth = dir.join("shifted.pfm");
    write_pfm_gray(&truth, W, H, &shifted).unwrap();
    let out = dir.join("shifted.png");
    let psnr = error_render(&truth, W, H, &out, &["--error-range", "0.1"]);
    assert!(
        (5.0..20.0).contains(&psnr),
        "PSNR {psnr} dB with a quarter of the pixels off by 0.2"
    );
    let img = image::open(&out).unwrap().to_rgb8();
    let mut seen = [0usize; 3];
    for y in 0..h {
        for x in 0..w {
            let c = colour(&img, x, y, w);
            if c == SKY {
                continue;
            }
            let q = quarter(x, y);
            assert_eq!(c, [ZERO, TOO_DARK, TOO_LIGHT][q], "pixel ({x}, {y})");
            seen[q] += 1;
        }
    }
    assert!(seen[1] > 100 && seen[2] > 100, "{seen:?}");

    // The scale bar under the map: both ends' colours and light label text.
    let bar_top = H * z;
    let strip: Vec<[u8; 3]> = (bar_top..img.height())
        .flat_map(|y| (0..img.width()).map(move |x| (x, y)))
        .map(|(x, y)| img.get_pixel(x, y).0)
        .collect();
    let count = |c: [u8; 3]| strip.iter().filter(|p| **p == c).count();
    let blue = strip
        .iter()
        .filter(|p| p[2] as i32 > p[0] as i32 + 60)
        .count();
    let orange = strip
        .iter()
        .filter(|p| p[0] as i32 > p[2] as i32 + 60)
        .count();
    assert!(
        blue > 500 && orange > 500,
        "the bar: {blue} blue, {orange} orange"
    );
    assert!(
        count(TOO_DARK) > 0 && count(TOO_LIGHT) > 0,
        "the bar's ends"
    );
    assert!(
        count([235, 235, 235]) > 200,
        "the labels (-0.1, 0, +0.1 and the largest error)"
    );

    // The raw difference as PFM: −0.2 and +0.2 where shifted.
    let raw = dir.join("difference.pfm");
    error_render(&truth, W, H, &raw, &[]);
    let (rw, rh, c, d) = read_pfm(&raw).unwrap();
    assert_eq!((rw, rh, c), (W, H, 1));
    let (x, y) = (w / 4, h - 2);
    assert!((d[y * w + x] + 0.2).abs() < 1e-5, "{}", d[y * w + x]);
    assert!((d[y * w + w - 1 - x] - 0.2).abs() < 1e-5);
    assert!(d[0].abs() < 1e-6);
}

#[test]
fn a_truth_at_half_size_is_compared_with_the_box_average() {
    let dir = common::temp_dir("error-map-half");
    let ao = ao_view(&dir, 2 * W, 2 * H);
    let (w, h) = (W as usize, H as usize);
    let mut half = vec![0.0f32; w * h];
    for y in 0..h {
        for x in 0..w {
            let at = |dx: usize, dy: usize| ao[(2 * y + dy) * 2 * w + 2 * x + dx];
            half[y * w + x] = (at(0, 0) + at(1, 0) + at(0, 1) + at(1, 1)) / 4.0;
        }
    }
    let truth = dir.join("half.pfm");
    write_pfm_gray(&truth, W, H, &half).unwrap();
    let psnr = error_render(&truth, 2 * W, 2 * H, &dir.join("half.png"), &[]);
    assert!(psnr >= 60.0, "PSNR {psnr} dB against its own box average");
}

#[test]
fn the_ray_traced_truth_gives_a_finite_psnr() {
    let dir = common::temp_dir("error-map-reference");
    let truth = dir.join("truth.pfm");
    let mut args: Vec<String> = ["reference", "--rays", "16", "--radius", "1", "--cache"]
        .map(String::from)
        .to_vec();
    args.push(dir.join("cache").to_str().unwrap().into());
    args.extend(size_flags(W, H));
    args.extend(["--out".into(), truth.to_str().unwrap().into()]);
    let o = run(&args);
    assert!(o.status.success(), "{}", stderr(&o));
    let psnr = error_render(&truth, W, H, &dir.join("e.png"), &["--radius", "1"]);
    assert!((5.0..60.0).contains(&psnr), "PSNR {psnr} dB");
}

#[test]
fn bad_truths_give_clear_errors() {
    let dir = common::temp_dir("error-map-bad");
    let missing = dir.join("nothere.pfm");
    let out = dir.join("e.png");
    let (m, o) = (missing.to_str().unwrap(), out.to_str().unwrap());
    fails_with(
        &[
            "--lang", "en", "render", "--view", "error", "--truth", m, "--out", o,
        ],
        &["nothere.pfm", "cannot read the truth"],
    );
    fails_with(
        &[
            "--lang", "ja", "render", "--view", "error", "--truth", m, "--out", o,
        ],
        &["nothere.pfm", "リファレンス"],
    );
    let odd = dir.join("odd.pfm");
    write_pfm_gray(&odd, 30, 20, &[0.5; 600]).unwrap();
    let mut args: Vec<String> = ["--lang", "en", "render", "--view", "error", "--truth"]
        .map(String::from)
        .to_vec();
    args.push(odd.to_str().unwrap().into());
    args.extend(size_flags(W, H));
    args.extend(["--out".into(), o.into()]);
    fails_with(&args, &["odd.pfm", "30x20", "80x60"]);
}

/// PSNR (dB) on a `render --view error` run's stdout.
fn psnr_of(o: &std::process::Output) -> f64 {
    let text = String::from_utf8_lossy(&o.stdout).to_string();
    text.split("PSNR ")
        .nth(1)
        .and_then(|s| s.split(" dB").next())
        .and_then(|s| s.parse::<f64>().ok())
        .unwrap_or_else(|| panic!("no PSNR on stdout:\n{text}"))
}

#[test]
fn without_a_truth_it_traces_one_then_reads_it_from_the_cache() {
    let dir = common::temp_dir("error-map-traced");
    let (cache, other_cache) = (dir.join("cache"), dir.join("other-cache"));
    let out = dir.join("e.png");
    let mut args: Vec<String> = ["--lang", "en", "render", "--view", "error"]
        .map(String::from)
        .to_vec();
    args.extend(size_flags(W, H));
    args.extend(["--out".into(), out.to_str().unwrap().into()]);
    let env = opengl3d::tools::reference::CACHE_ENV;
    let first = bin().env(env, &cache).args(&args).output().unwrap();
    assert!(first.status.success(), "{}", stderr(&first));
    assert!(
        stderr(&first).contains("traced the truth"),
        "{}",
        stderr(&first)
    );
    let traced = psnr_of(&first);
    assert!(image::open(&out).is_ok());
    let second = bin().env(env, &cache).args(&args).output().unwrap();
    assert!(
        stderr(&second).contains("read from the reference cache"),
        "{}",
        stderr(&second)
    );
    assert_eq!(psnr_of(&second), traced);

    // `opengl3d reference` (its own cache, so it traces anew) gives the truth compared against.
    let truth = dir.join("truth.pfm");
    let mut reference: Vec<String> = ["reference"].map(String::from).to_vec();
    reference.extend(size_flags(W, H));
    reference.extend(["--out".into(), truth.to_str().unwrap().into()]);
    let o = bin()
        .env(env, &other_cache)
        .args(&reference)
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", stderr(&o));
    let given = error_render(&truth, W, H, &dir.join("given.png"), &[]);
    assert!(
        (given - traced).abs() < 1e-9,
        "traced {traced} dB, given {given} dB"
    );
    // Not the engine against itself: the AO view misses the truth somewhere.
    assert!(traced < 40.0, "{traced} dB");
}
