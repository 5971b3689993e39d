//! Writing frames: 8-bit PNG, and Portable Float Map for raw values.

use anyhow::{bail, Context as _, Result};
use std::io::Write as _;
use std::path::Path;

/// Writes single-channel f32 values (rows top-down) as a PFM ("Pf"); PFM rows are bottom-up.
pub fn write_pfm_gray(path: &Path, width: u32, height: u32, values: &[f32]) -> Result<()> {
    if values.len() != (width * height) as usize {
        bail!("PFM: {} values for {width}x{height}", values.len());
    }
    let mut f = std::io::BufWriter::new(
        std::fs::File::create(path).with_context(|| format!("cannot create {}", path.display()))?,
    );
    // Negative scale = little-endian.
    write!(f, "Pf\n{width} {height}\n-1.0\n")?;
    for y in (0..height as usize).rev() {
        for v in &values[y * width as usize..(y + 1) * width as usize] {
            f.write_all(&v.to_le_bytes())?;
        }
    }
    f.flush()?;
    Ok(())
}

/// Writes RGB f32 values (rows top-down) as a PFM ("PF").
pub fn write_pfm_rgb(path: &Path, width: u32, height: u32, rgb: &[f32]) -> Result<()> {
    if rgb.len() != (width * height * 3) as usize {
        bail!("PFM: {} values for {width}x{height}x3", rgb.len());
    }
    let mut f = std::io::BufWriter::new(
        std::fs::File::create(path).with_context(|| format!("cannot create {}", path.display()))?,
    );
    write!(f, "PF\n{width} {height}\n-1.0\n")?;
    let row = width as usize * 3;
    for y in (0..height as usize).rev() {
        for v in &rgb[y * row..(y + 1) * row] {
            f.write_all(&v.to_le_bytes())?;
        }
    }
    f.flush()?;
    Ok(())
}

/// Reads a PFM (either kind) into (width, height, channels, values rows top-down).
pub fn read_pfm(path: &Path) -> Result<(u32, u32, u32, Vec<f32>)> {
    let bytes = std::fs::read(path).with_context(|| format!("cannot read {}", path.display()))?;
    let mut fields = Vec::new();
    let mut pos = 0;
    while fields.len() < 4 && pos < bytes.len() {
        while pos < bytes.len() && bytes[pos].is_ascii_whitespace() {
            pos += 1;
        }
        let start = pos;
        while pos < bytes.len() && !bytes[pos].is_ascii_whitespace() {
            pos += 1;
        }
        fields.push(String::from_utf8_lossy(&bytes[start..pos]).to_string());
    }
    pos += 1; // the single whitespace after the scale
    if fields.len() < 4 {
        bail!("{}: truncated PFM header", path.display());
    }
    let channels = match fields[0].as_str() {
        "Pf" => 1,
        "PF" => 3,
        other => bail!("{}: not a PFM file (magic '{other}')", path.display()),
    };
    let w: u32 = fields[1].parse().context("PFM width")?;
    let h: u32 = fields[2].parse().context("PFM height")?;
    let scale: f32 = fields[3].parse().context("PFM scale")?;
    let n = (w * h * channels) as usize;
    let data = bytes
        .get(pos..pos + n * 4)
        .with_context(|| format!("{}: truncated PFM data", path.display()))?;
    let le = scale < 0.0;
    let vals: Vec<f32> = data
        .chunks_exact(4)
        .map(|b| {
            let a = [b[0], b[1], b[2], b[3]];
            if le {
                f32::from_le_bytes(a)
            } else {
                f32::from_be_bytes(a)
            }
        })
        .collect();
    let row = (w * channels) as usize;
    let mut out = Vec::with_capacity(n);
    for y in (0..h as usize).rev() {
        out.extend_from_slice(&vals[y * row..(y + 1) * row]);
    }
    Ok((w, h, channels, out))
}

/// Maps single-channel values to an 8-bit grey PNG: value × scale, clamped to [0,1].
pub fn gray_to_png(path: &Path, width: u32, height: u32, values: &[f32], scale: f32) -> Result<()> {
    let px: Vec<u8> = values
        .iter()
        .map(|v| ((v * scale).clamp(0.0, 1.0) * 255.0 + 0.5) as u8)
        .collect();
    let img = image::GrayImage::from_raw(width, height, px).context("image size")?;
    img.save(path)
        .with_context(|| format!("cannot write {}", path.display()))
}
