//! Bounds of the bench's inputs, shared by the command line (clap ranges) and the library entry
//! points (which tests and other callers reach without clap), so both refuse the same values.

use anyhow::{bail, Result};

/// Largest output side: the engine's render targets and the GL implementations we run on
/// (llvmpipe's limit is 16384) do not go further.
pub const MAX_SIDE: u32 = 16384;

/// Rays per pixel of the references. 0 would compute nothing; at 65536 rays the Monte Carlo
/// standard error of a pixel is at most 0.002, far under any method's error, and more rays only
/// cost hours of CPU.
pub const MAX_REF_RAYS: u32 = 65536;

/// The reference is rendered at 1/N of the output size. 1 is full size; at 16 a 1920×1080 bench
/// already compares 120×68 pixels, and coarser images average away the occlusion being measured.
pub const MAX_REF_SCALE: u32 = 16;

/// `Err` unless `width` × `height` is a renderable output size.
pub fn check_size(width: u32, height: u32) -> Result<()> {
    if width == 0 || height == 0 || width > MAX_SIDE || height > MAX_SIDE {
        bail!("--width/--height {width}x{height}: use 1 to {MAX_SIDE}");
    }
    Ok(())
}

/// `Err` unless at least one frame is timed (a median of nothing means nothing).
pub fn check_frames(frames: u32) -> Result<()> {
    if frames == 0 {
        bail!("--frames must be at least 1");
    }
    Ok(())
}

/// `Err` unless `value` of `flag` lies in 1..=`max`.
pub fn check_range(flag: &str, value: u32, max: u32) -> Result<()> {
    if !(1..=max).contains(&value) {
        bail!("{flag} {value}: use 1 to {max}");
    }
    Ok(())
}
