//! Output files: the format is decided from the extension before anything is rendered, so a typo
//! in `--out` costs nothing; writes go through `crate::io` (errors name the file and the cause).

use crate::render::{Engine, View};
use anyhow::{bail, Result};
use rust_i18n::t;
use std::path::Path;

/// What an output file holds.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum OutFormat {
    /// 8-bit PNG.
    Png,
    /// Portable Float Map (raw values).
    Pfm,
}

impl OutFormat {
    /// The format `path`'s extension names, or an error naming the flag and the file.
    pub fn of(flag: &str, path: &Path, allowed: &[OutFormat]) -> Result<OutFormat> {
        let ext = path
            .extension()
            .map(|e| e.to_string_lossy().to_ascii_lowercase());
        let format = match ext.as_deref() {
            Some("png") => Some(OutFormat::Png),
            Some("pfm") => Some(OutFormat::Pfm),
            _ => None,
        };
        match format {
            Some(f) if allowed.contains(&f) => Ok(f),
            _ => {
                let names: Vec<&str> = allowed
                    .iter()
                    .map(|f| match f {
                        OutFormat::Png => ".png",
                        OutFormat::Pfm => ".pfm",
                    })
                    .collect();
                let exts = names.join(&t!("cli.or"));
                bail!(
                    "{}",
                    t!(
                        "cli.out_format",
                        flag = flag,
                        path = path.display(),
                        exts = exts
                    )
                )
            }
        }
    }
}

/// Both formats.
pub const PNG_OR_PFM: &[OutFormat] = &[OutFormat::Png, OutFormat::Pfm];

/// Renders `view` and writes it as PNG or PFM depending on the extension.
pub fn write_view(engine: &mut Engine, view: View, out: &Path) -> Result<()> {
    let format = OutFormat::of("--out", out, PNG_OR_PFM)?;
    crate::io::create_parent(out)?;
    let (w, h) = engine.size();
    match (format, view) {
        (OutFormat::Png, View::Composite) => {
            let img = engine.render_image()?;
            crate::io::write_png(out, &image::DynamicImage::ImageRgba8(img).to_rgb8())?;
        }
        (OutFormat::Png, View::LinearDepth | View::SecondLayerDepth) => {
            let v = engine.render_values(view)?;
            // Scale by the farthest non-sky distance so the picture uses the whole grey range.
            let far = engine.camera.far;
            let max = v
                .iter()
                .copied()
                .filter(|d| *d < far)
                .fold(0.0f32, f32::max)
                .max(1e-6);
            crate::io::gray_to_png(out, w, h, &v, 1.0 / max)?;
        }
        (OutFormat::Png, _) => {
            let v = engine.render_values(view)?;
            crate::io::gray_to_png(out, w, h, &v, 1.0)?;
        }
        (OutFormat::Pfm, View::Composite) => {
            let img = engine.render_image()?;
            let rgb: Vec<f32> = img
                .pixels()
                .flat_map(|p| [p[0], p[1], p[2]].map(|c| c as f32 / 255.0))
                .collect();
            crate::io::write_pfm_rgb(out, w, h, &rgb)?;
        }
        (OutFormat::Pfm, _) => {
            let v = engine.render_values(view)?;
            crate::io::write_pfm_gray(out, w, h, &v)?;
        }
    }
    Ok(())
}
