//! The colour scale under a picture of differences: a gradient bar with labelled values under it
//! and an optional marker over it (the grader's heat maps: 0 to 1 with the largest difference
//! marked; the signed error maps: −range to +range). The labels are numbers and signs only, so that
//! they read the same in every language, drawn with a tiny built-in pixel font (no font file needed).

use image::{Rgb, RgbImage};

/// Glyphs 5 pixels high, '#' lit; letters are lower case on the bottom three rows.
fn glyph(c: char) -> Option<&'static [&'static str; 5]> {
    Some(match c {
        '0' => &["###", "#.#", "#.#", "#.#", "###"],
        '1' => &[".#.", "##.", ".#.", ".#.", "###"],
        '2' => &["###", "..#", "###", "#..", "###"],
        '3' => &["###", "..#", "###", "..#", "###"],
        '4' => &["#.#", "#.#", "###", "..#", "..#"],
        '5' => &["###", "#..", "###", "..#", "###"],
        '6' => &["###", "#..", "###", "#.#", "###"],
        '7' => &["###", "..#", "..#", ".#.", ".#."],
        '8' => &["###", "#.#", "###", "#.#", "###"],
        '9' => &["###", "#.#", "###", "..#", "###"],
        '.' => &[".", ".", ".", ".", "#"],
        '-' => &["...", "...", "###", "...", "..."],
        '+' => &["...", ".#.", "###", ".#.", "..."],
        '>' => &["#..", ".#.", "..#", ".#.", "#.."],
        'e' => &["...", "###", "#.#", "##.", "###"],
        'm' => &[".....", ".....", "####.", "#.#.#", "#.#.#"],
        'a' => &["...", "...", ".##", "#.#", ".##"],
        'c' => &["...", "...", "###", "#..", "###"],
        'f' => &[".##", "#..", "###", "#..", "#.."],
        's' => &["...", ".##", "#..", "..#", "##."],
        'u' => &["...", "...", "#.#", "#.#", "###"],
        'x' => &["...", "...", "#.#", ".#.", "#.#"],
        'd' => &["..#", "..#", "###", "#.#", "###"],
        'g' => &["...", "###", "#.#", "###", ".##"],
        'h' => &["#..", "#..", "###", "#.#", "#.#"],
        'i' => &["#", ".", "#", "#", "#"],
        'k' => &["#..", "#..", "#.#", "##.", "#.#"],
        'l' => &["#.", "#.", "#.", "#.", "##"],
        'o' => &["...", "...", "###", "#.#", "###"],
        'r' => &["...", "...", "###", "#..", "#.."],
        't' => &[".#.", "###", ".#.", ".#.", ".##"],
        ' ' => &["..", "..", "..", "..", ".."],
        _ => return None,
    })
}

/// Pixels per font pixel.
const ZOOM: u32 = 2;
const TEXT_HEIGHT: u32 = 5 * ZOOM;
const TEXT: Rgb<u8> = Rgb([235, 235, 235]);

/// Width of `text` in pixels (characters without a glyph are left out).
pub fn text_width(text: &str) -> u32 {
    let widths: Vec<u32> = text
        .chars()
        .filter_map(glyph)
        .map(|g| g[0].len() as u32)
        .collect();
    (widths.iter().sum::<u32>() + widths.len().saturating_sub(1) as u32) * ZOOM
}

/// Draws `text` with its top-left corner at (x, y); pixels off the image are skipped.
pub fn draw_text(img: &mut RgbImage, x: u32, y: u32, text: &str) {
    let mut pen = x;
    for g in text.chars().filter_map(glyph) {
        for (row, line) in g.iter().enumerate() {
            for (col, lit) in line.chars().enumerate() {
                if lit != '#' {
                    continue;
                }
                for dy in 0..ZOOM {
                    for dx in 0..ZOOM {
                        let (px, py) = (pen + col as u32 * ZOOM + dx, y + row as u32 * ZOOM + dy);
                        if px < img.width() && py < img.height() {
                            img.put_pixel(px, py, TEXT);
                        }
                    }
                }
            }
        }
        pen += (g[0].len() as u32 + 1) * ZOOM;
    }
}

/// A value as a short label: 3 significant digits, scientific beyond [0.001, 10000).
pub fn label(v: f32) -> String {
    if !v.is_finite() {
        return "-".into();
    }
    let a = v.abs();
    if a == 0.0 {
        "0".into()
    } else if (0.001..10000.0).contains(&a) {
        let decimals = (2 - a.log10().floor() as i32).max(0) as usize;
        let s = format!("{v:.decimals$}");
        if s.contains('.') {
            s.trim_end_matches('0').trim_end_matches('.').to_string()
        } else {
            s
        }
    } else {
        format!("{v:.1e}")
    }
}

/// Height of the strip `draw` and `draw_scale` add under a picture.
pub const HEIGHT: u32 = 6 + TEXT_HEIGHT + 2 + 5 + 1 + BAR_HEIGHT + 3 + TEXT_HEIGHT + 6;
const BAR_HEIGHT: u32 = 14;
/// Space left and right of the bar, so the end labels fit.
const MARGIN: u32 = 10;

/// What the strip under a picture shows.
pub struct Scale<'a> {
    /// (position along the bar in [0, 1], label) under the bar: each label centred on its
    /// position, moved inwards where it would pass the bar's ends.
    pub ticks: &'a [(f32, String)],
    /// A downward triangle over the bar at this position (clamped to [0, 1], NaN at the right
    /// end), its label over it.
    pub marker: Option<(f32, String)>,
}

/// Draws `scale` into the strip of `img` that starts at row `top` (HEIGHT rows, the image's
/// width): the bar coloured by `colour(t)` from t = 0 (left) to 1 (right).
pub fn draw_scale(img: &mut RgbImage, top: u32, scale: &Scale, colour: impl Fn(f32) -> [u8; 3]) {
    let width = img.width();
    let (x0, x1) = (MARGIN, width.saturating_sub(MARGIN).max(MARGIN + 1));
    let span = (x1 - x0 - 1).max(1) as f32;
    let label_y = top + 6;
    let marker_y = label_y + TEXT_HEIGHT + 2;
    let bar_y = marker_y + 5 + 1;
    let ticks_y = bar_y + BAR_HEIGHT + 3;
    for x in x0..x1.min(width) {
        let c = Rgb(colour((x - x0) as f32 / span));
        for y in bar_y..bar_y + BAR_HEIGHT {
            img.put_pixel(x, y, c);
        }
    }
    let at = |t: f32| x0 + (t.clamp(0.0, 1.0) * span).round() as u32;
    // Text centred on x, kept between the bar's ends (one font pixel beyond them).
    let place = |x: u32, w: u32| {
        x.saturating_sub(w / 2).clamp(
            x0.saturating_sub(ZOOM),
            (x1 + ZOOM).saturating_sub(w).max(x0.saturating_sub(ZOOM)),
        )
    };
    for (t, text) in scale.ticks {
        draw_text(img, place(at(*t), text_width(text)), ticks_y, text);
    }
    if let Some((t, text)) = &scale.marker {
        let t = if t.is_nan() { 1.0 } else { *t };
        let mx = at(t);
        for row in 0..5u32 {
            let half = 4 - row;
            for x in mx.saturating_sub(half)..=(mx + half).min(width - 1) {
                img.put_pixel(x, marker_y + row, TEXT);
            }
        }
        let w = text_width(text);
        let lx = mx.saturating_sub(w / 2).min(width.saturating_sub(w + ZOOM));
        draw_text(img, lx, label_y, text);
    }
}

/// The heat maps' scale: the bar coloured by `heat` from 0 (left) to 1 (right), "0" and "1" (the
/// step's full scale) under its ends, and above it a marker at `max` (the largest difference in the
/// picture) labelled with its value; over 1 the marker stays at the right end and its label says
/// "VALUE > 1", so "2 > 1" reads as twice the full scale.
pub fn draw(img: &mut RgbImage, top: u32, max: f32, heat: impl Fn(f32) -> [u8; 3]) {
    let t = if max.is_finite() { max } else { 1.0 };
    let text = if max > 1.0 || !max.is_finite() {
        format!("{} > 1", label(max))
    } else {
        label(max)
    };
    let scale = Scale {
        ticks: &[(0.0, "0".into()), (1.0, "1".into())],
        marker: Some((t, text)),
    };
    draw_scale(img, top, &scale, heat);
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn labels_keep_three_significant_digits() {
        assert_eq!(label(0.0), "0");
        assert_eq!(label(1.0), "1");
        assert_eq!(label(0.7346), "0.735");
        assert_eq!(label(3.4), "3.4");
        assert_eq!(label(123.456), "123");
        assert_eq!(label(0.00012), "1.2e-4");
        assert_eq!(label(f32::NAN), "-");
    }

    #[test]
    fn every_label_character_has_a_glyph_of_five_even_rows() {
        for c in "0123456789.-+e >".chars() {
            let g = glyph(c).unwrap_or_else(|| panic!("no glyph for {c:?}"));
            assert!(g.iter().all(|r| r.len() == g[0].len()), "{c:?}");
        }
        // Text is as wide as its glyphs plus one pixel between them, zoomed.
        assert_eq!(text_width("10"), (3 + 1 + 3) * ZOOM);
    }

    #[test]
    fn the_bar_runs_from_the_colour_of_0_to_the_colour_of_1() {
        let mut img = RgbImage::from_pixel(300, HEIGHT, Rgb([40, 40, 40]));
        draw(&mut img, 0, 0.5, |t| [(t * 255.0).round() as u8, 0, 0]);
        let bar_row = HEIGHT - 6 - TEXT_HEIGHT - 3 - BAR_HEIGHT / 2;
        assert_eq!(img.get_pixel(MARGIN, bar_row).0, [0, 0, 0]);
        assert_eq!(img.get_pixel(300 - MARGIN - 1, bar_row).0, [255, 0, 0]);
        // The marker's tip sits over the middle of the bar.
        let tip_row = bar_row - BAR_HEIGHT / 2 - 2;
        let lit: Vec<u32> = (0..300)
            .filter(|&x| img.get_pixel(x, tip_row).0 == TEXT.0)
            .collect();
        assert_eq!(
            lit,
            [MARGIN + (0.5 * (300 - 2 * MARGIN - 1) as f32).round() as u32]
        );
    }
}
