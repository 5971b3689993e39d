//! The size of a guard band (`[ao] guard_band`, `--guard-band`) and the widened camera that covers it:
//! the same pixel size and pixel centres as the view, a margin of whole pixels on each side.

use super::blur::BLUR_REACH;
use super::settings::{
    AoResolution, GuardBand, GUARD_BAND_AUTO_MAX_OF_SIDE, GUARD_BAND_MAX_OF_SIDE,
};
use super::targets::AoTargets;
use crate::gl::{Gl, Texture};
use crate::math::camera::fov_scale;
use crate::math::Camera;
use anyhow::Result;
use glow::HasContext;
use std::cell::RefCell;
use std::rc::Rc;

/// The radius's projected size at the camera's focus distance (eye to target), in output pixels, is
/// how far off screen an occluder of a surface there can lie; surfaces nearer than the focus need more
/// and are capped. Below this the margin is not worth a pass over its pixels.
const GUARD_BAND_MIN_PIXELS: u32 = 8;

/// A frame's guard band.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct GuardFrame {
    /// Output pixels beyond each edge.
    pub pixels: u32,
    /// The camera that covers the view and the margin (wider field of view, same axis).
    pub camera: Camera,
    /// The output size with the margin.
    pub size: (u32, u32),
}

/// The margin (output pixels, a multiple of 4 so that half- and quarter-size AO texels keep their
/// blocks) that `band` asks for with `camera`, a `size` output and AO `radius`; 0 = none.
pub fn guard_band_pixels(band: GuardBand, camera: &Camera, size: (u32, u32), radius: f32) -> u32 {
    let side = size.0.max(size.1) as f32;
    let px = match band {
        GuardBand::Off => return 0,
        GuardBand::Pixels(p) => p.min((GUARD_BAND_MAX_OF_SIDE * side) as u32),
        GuardBand::Auto => {
            let cap = ((GUARD_BAND_AUTO_MAX_OF_SIDE * side) as u32).max(GUARD_BAND_MIN_PIXELS);
            let focus = (camera.target - camera.eye).length().max(camera.near);
            let projected = radius * 0.5 * size.1 as f32 * fov_scale(camera.fov_y_deg) / focus;
            if !projected.is_finite() {
                cap
            } else {
                (projected.ceil() as u32).clamp(GUARD_BAND_MIN_PIXELS, cap)
            }
        }
    };
    px.next_multiple_of(4)
}

/// The camera and size that add `pixels` on each side of a `size` view of `camera` with the same
/// pixel centres; `None` when the widened field of view would reach 179°.
pub fn widen(camera: &Camera, size: (u32, u32), pixels: u32) -> Option<GuardFrame> {
    let (w, h) = size;
    let (gw, gh) = (w + 2 * pixels, h + 2 * pixels);
    let half = (camera.fov_y_deg as f64).to_radians() * 0.5;
    let wide = 2.0 * (half.tan() * gh as f64 / h.max(1) as f64).atan();
    if !wide.is_finite() || wide.to_degrees() >= 179.0 {
        return None;
    }
    Some(GuardFrame {
        pixels,
        camera: Camera {
            fov_y_deg: wide.to_degrees() as f32,
            ..*camera
        },
        size: (gw, gh),
    })
}

/// Copies the inner `dst`-sized part of `src`, `offset` texels in from its lower-left corner.
fn copy_inner(gl: &Gl, src: &Texture, dst: &Texture, offset: u32) {
    let (w, h) = dst.size_at(0);
    // SAFETY: both textures are live 2D textures of the same format; the region lies inside both
    // (src is dst's size plus 2·offset on each axis).
    unsafe {
        gl.copy_image_sub_data(
            src.id(),
            glow::TEXTURE_2D,
            0,
            offset as i32,
            offset as i32,
            0,
            dst.id(),
            glow::TEXTURE_2D,
            0,
            0,
            0,
            0,
            w as i32,
            h as i32,
            1,
        );
    }
}

/// Copies the inner part of the guarded targets' depth (level 0), raw and blurred occlusion into
/// the view's targets.
pub fn crop(gl: &Gl, guarded: &AoTargets, view: &AoTargets, offset: u32, blurred: bool) {
    copy_inner(gl, &guarded.tex_depth, &view.tex_depth, offset);
    copy_inner(gl, guarded.sao_texture(), view.sao_texture(), offset);
    if blurred {
        copy_inner(
            gl,
            guarded.result_texture(true),
            view.result_texture(true),
            offset,
        );
    }
}

/// The texels of the guarded targets (`guarded`, AO size) the frame reads: the view's (`view` texels
/// from `offset` on each axis) and the blur's reach around them, as (x, y, width, height). The method
/// and its blur draw only there (`AoInputs::region`): the rest of the margin is read as depth,
/// never as occlusion.
pub fn read_region(guarded: (u32, u32), view: (u32, u32), offset: u32) -> [i32; 4] {
    let reach = BLUR_REACH;
    let lo = offset.saturating_sub(reach);
    let x1 = (offset + view.0 + reach).min(guarded.0);
    let y1 = (offset + view.1 + reach).min(guarded.1);
    [lo as i32, lo as i32, (x1 - lo) as i32, (y1 - lo) as i32]
}

/// AO texels of a margin of `pixels` output pixels.
pub fn ao_offset(pixels: u32, resolution: AoResolution) -> u32 {
    pixels / resolution.divisor()
}

/// The AO targets of the widened view: created at the size a frame needs, kept while it stays.
#[derive(Default)]
pub struct GuardTargets {
    slot: RefCell<Option<(GuardKey, Rc<AoTargets>)>>,
}

/// Widened output size, linear-depth levels, AO resolution.
type GuardKey = ((u32, u32), u32, AoResolution);

impl GuardTargets {
    /// The targets for a widened output of `size`, created or re-created when the key changed.
    pub fn get(
        &self,
        gl: &Gl,
        size: (u32, u32),
        depth_levels: u32,
        resolution: AoResolution,
    ) -> Result<Rc<AoTargets>> {
        let key = (size, depth_levels, resolution);
        let mut slot = self.slot.borrow_mut();
        if let Some((k, t)) = slot.as_ref() {
            if *k == key {
                return Ok(t.clone());
            }
        }
        *slot = None;
        let t = Rc::new(AoTargets::at_resolution(
            gl,
            size.0,
            size.1,
            depth_levels,
            resolution,
        )?);
        *slot = Some((key, t.clone()));
        Ok(t)
    }

    pub fn textures(&self) -> Vec<Rc<Texture>> {
        match self.slot.borrow().as_ref() {
            Some((_, t)) => vec![
                t.tex_depth.clone(),
                t.sao_texture().clone(),
                t.result_texture(true).clone(),
            ],
            None => Vec::new(),
        }
    }

    pub fn release(&self) {
        *self.slot.borrow_mut() = None;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_read_region_is_the_view_and_the_blur_reach_within_the_targets() {
        // A 40-texel margin: the view and 4 texels around it.
        assert_eq!(read_region((560, 350), (480, 270), 40), [36, 36, 488, 278]);
        // A margin narrower than the reach: clamped to the targets.
        assert_eq!(read_region((482, 272), (480, 270), 1), [0, 0, 482, 272]);
    }

    #[test]
    fn the_widened_view_keeps_the_pixel_size_and_centres() {
        let cam = Camera::default();
        let g = widen(&cam, (640, 360), 40).unwrap();
        assert_eq!(g.size, (720, 440));
        // tan(half fov) per pixel is the same.
        let per_px = |c: &Camera, h: u32| (c.fov_y_deg.to_radians() * 0.5).tan() / h as f32;
        assert!((per_px(&g.camera, 440) - per_px(&cam, 360)).abs() < 1e-7);
        assert!(widen(&cam, (640, 360), 100_000).is_none());
    }

    #[test]
    fn margins_are_multiples_of_four_capped_and_follow_the_radius() {
        let cam = Camera::default(); // focus distance ≈ 6.2 m
        let size = (1920, 1080);
        assert_eq!(guard_band_pixels(GuardBand::Off, &cam, size, 1.0), 0);
        assert_eq!(
            guard_band_pixels(GuardBand::Pixels(33), &cam, size, 1.0),
            36
        );
        assert_eq!(
            guard_band_pixels(GuardBand::Pixels(5000), &cam, size, 1.0),
            480
        );
        // 0.2 m at 6.2 m with a 60° field of view over 1080 rows: about 30 pixels; 1 m would be
        // about 150 (under the cap, 160 = 1/12 of 1920); the smallest band is 8 pixels.
        let small = guard_band_pixels(GuardBand::Auto, &cam, size, 0.2);
        assert!(
            (28..=32).contains(&small) && small.is_multiple_of(4),
            "{small}"
        );
        let one = guard_band_pixels(GuardBand::Auto, &cam, size, 1.0);
        assert!((144..=156).contains(&one) && one.is_multiple_of(4), "{one}");
        // 3 m would be about 450: capped at 160.
        assert_eq!(guard_band_pixels(GuardBand::Auto, &cam, size, 3.0), 160);
        assert_eq!(guard_band_pixels(GuardBand::Auto, &cam, size, 1e-3), 8);
    }
}
