//! The screen-space reference over the bench's protocol: the depth buffer at the engine's full size,
//! its visibility averaged over each block of `scale` × `scale` pixels, as the bench box-averages a
//! method's output down to the ray-traced truth's size. Integrating the ceiling from a depth buffer
//! rendered at the truth's size instead loses everything thinner than one of its pixels (chair legs,
//! slats, boards), which the methods, reading the full-size buffer, see.
//!
//! Each pixel of the block gets the same number of rays (its own shifted lattice), so the block's
//! mean weighs every pixel equally; sky pixels count as open, as the method's output does there.
//! A pixel's rays are those the ray-traced truth's footprint mean gives the same sub-pixel (its
//! random stream is its index in the full-size image, its share of the rays the same): where the
//! depth buffer holds the scene, both trace the same directions from the same point, so their
//! difference is what the buffer loses, not two draws of Monte Carlo noise (the idealised layer,
//! `ideal.rs`, shares them the same way).

use anyhow::{bail, Result};

use super::cache;
use super::depth_buffer::DepthBuffer;
use super::hash::Fnv64;
use super::heightfield::Heightfield;
use super::image::{shade_image, RefImage};
use super::params::{AoVariant, RefParams};
use super::sampling;
use super::screen::{ray_start, screen_cache_key, Layers};
use std::path::Path;

/// The largest block side (the bench's `--ref-scale` range).
pub const MAX_SCALE: u32 = 16;

/// Size of the output: the visible buffer divided by `scale`, rounded up (the last blocks of a
/// row or column may be partial, as in the bench's box average).
pub fn box_size(depth: &DepthBuffer, scale: u32) -> (u32, u32) {
    let (w, h) = depth.visible_size();
    (w.div_ceil(scale.max(1)), h.div_ceil(scale.max(1)))
}

/// The screen-space reference of `depth` averaged over blocks of `scale` × `scale` pixels, with at
/// least `params.rays` rays per block (rounded up to whole rays per pixel).
pub fn render_screen_space_box(
    depth: &DepthBuffer,
    scale: u32,
    params: &RefParams,
) -> Result<RefImage> {
    depth.validate()?;
    if params.variant != AoVariant::Visibility {
        bail!("{}", rust_i18n::t!("reference.visibility_only"));
    }
    if !(1..=MAX_SCALE).contains(&scale) {
        bail!("block of {scale} pixels: use 1 to {MAX_SCALE}");
    }
    let (w, h) = box_size(depth, scale);
    if w == 0 || h == 0 {
        bail!(
            "a {}x{} depth buffer has no whole {scale}x{scale} block",
            depth.width,
            depth.height
        );
    }
    let field = Heightfield::new(depth);
    let second = depth.second_layer_buffer().map(|b| Heightfield::new(&b));
    let layers = Layers {
        first: &field,
        second: second.as_ref(),
    };
    let (g, s) = (depth.guard_band as usize, scale as usize);
    let (vis_w, vis_h) = depth.visible_size();
    let (vis_w, vis_h) = (vis_w as usize, vis_h as usize);
    let per_pixel = params.rays.max(1).div_ceil(scale * scale);
    let radius = params.radius as f64;
    Ok(shade_image(
        w,
        h,
        "screen-space reference",
        params.progress,
        |x, y| {
            let (mut open, mut rays, mut centre) = (0u32, 0u32, None);
            for sy in 0..s {
                for sx in 0..s {
                    if x * s + sx >= vis_w || y * s + sy >= vis_h {
                        continue; // past the last whole block
                    }
                    let (vx, vy) = (x * s + sx, y * s + sy);
                    let (bx, by) = (g + vx, g + vy);
                    let stream = (vy * vis_w + vx) as u64;
                    rays += per_pixel;
                    let Some((start, d)) = ray_start(&field, bx, by, params) else {
                        open += per_pixel; // sky: open, as the method writes there
                        continue;
                    };
                    if (sx, sy) == (s / 2, s / 2) {
                        centre = Some(d);
                    }
                    let Some(start) = start else {
                        open += per_pixel;
                        continue;
                    };
                    let mut rng = sampling::Pcg32::for_pixel(params.seed, stream);
                    let shift = (rng.next_f64(), rng.next_f64());
                    for i in 0..per_pixel {
                        let uv = sampling::lattice_point(i, per_pixel, shift);
                        if !start.blocked(&layers, uv, radius) {
                            open += 1;
                        }
                    }
                }
            }
            if open == rays && centre.is_none() {
                return None; // all sky (or open), seen as sky at the centre
            }
            let mean = open as f64 / rays as f64;
            let se = (mean * (1.0 - mean) / rays as f64).max(0.0).sqrt();
            Some((
                mean.clamp(0.0, 1.0) as f32,
                se as f32,
                centre.unwrap_or(f32::INFINITY),
            ))
        },
    ))
}

/// Cache key of a block-averaged render: the plain render's key and the block size.
pub fn screen_box_cache_key(depth: &DepthBuffer, scale: u32, params: &RefParams) -> String {
    let mut h = Fnv64::new();
    h.bytes(screen_cache_key(depth, params).as_bytes());
    h.bytes(b"block average");
    h.u32(scale);
    format!("{:016x}", h.0)
}

/// The cached block-averaged screen-space reference, or a fresh render that is then stored.
pub fn load_or_render_screen_box_cached(
    cache_dir: &Path,
    depth: &DepthBuffer,
    scale: u32,
    params: &RefParams,
) -> Result<RefImage> {
    depth.validate()?;
    let key = screen_box_cache_key(depth, scale, params);
    if let Some(img) = cache::read_cached(cache_dir, &key) {
        if (img.width, img.height) == box_size(depth, scale) {
            return Ok(img);
        }
    }
    let img = render_screen_space_box(depth, scale, params)?;
    cache::store_or_warn(cache_dir, &key, &img);
    Ok(img)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::tools::reference::render_screen_space;
    use crate::tools::reference::screen::tests::buffer;

    /// A step: depth 3 m left of column `edge`, 5 m right of it (a wall's edge in front of a
    /// farther one), infinitely thick.
    fn step(w: u32, h: u32, edge: u32) -> DepthBuffer {
        buffer(w, h, |x, _| if x < edge { 3.0 } else { 5.0 })
    }

    fn params(rays: u32) -> RefParams {
        RefParams {
            radius: 1.0,
            rays,
            variant: AoVariant::Visibility,
            seed: 9,
            progress: false,
            supersample: 1,
        }
    }

    #[test]
    fn blocks_of_one_pixel_are_the_plain_reference() {
        let depth = step(24, 16, 13);
        let plain = render_screen_space(&depth, &params(32)).unwrap();
        let boxed = render_screen_space_box(&depth, 1, &params(32)).unwrap();
        assert_eq!(plain.ao, boxed.ao);
        assert!(
            plain.ao.iter().any(|a| *a < 0.9),
            "the step occludes nothing"
        );
    }

    #[test]
    fn a_block_is_the_mean_of_its_pixels() {
        // The plain reference with a quarter of the rays per pixel, averaged over 2×2 blocks,
        // against the block-averaged one: each pixel draws the same rays in both (its stream is its
        // index in the full-size image, as the ray-traced truth's sub-pixels), so they are equal.
        let depth = step(32, 24, 15);
        let plain = render_screen_space(&depth, &params(1024)).unwrap();
        let boxed = render_screen_space_box(&depth, 2, &params(4096)).unwrap();
        assert_eq!((boxed.width, boxed.height), (16, 12));
        let mut worst: f64 = 0.0;
        for y in 0..12usize {
            for x in 0..16usize {
                let mean = [(0, 0), (1, 0), (0, 1), (1, 1)]
                    .iter()
                    .map(|(dx, dy)| plain.ao[(2 * y + dy) * 32 + 2 * x + dx] as f64)
                    .sum::<f64>()
                    / 4.0;
                worst = worst.max((boxed.ao[y * 16 + x] as f64 - mean).abs());
            }
        }
        assert!(worst < 1e-6, "worst block differs by {worst}");
        // Blocks astride the edge (columns 14 and 15) mix an occluded and an open pixel.
        let astride = boxed.ao[5 * 16 + 7] as f64;
        assert!(astride < 0.95, "the block at the edge is open: {astride}");
    }

    #[test]
    fn partial_blocks_and_bad_scales() {
        let depth = step(10, 7, 4);
        assert_eq!(box_size(&depth, 3), (4, 3));
        assert_eq!(
            render_screen_space_box(&depth, 3, &params(9))
                .unwrap()
                .width,
            4
        );
        assert!(render_screen_space_box(&depth, 0, &params(9)).is_err());
        assert!(render_screen_space_box(&depth, MAX_SCALE + 1, &params(9)).is_err());
    }
}
