//! Writing frames: 8-bit PNG, and Portable Float Map for raw values. Every I/O error names its file
//! and says which of the usual causes it is (no such folder, permission denied, a folder in the way).

pub mod scale_bar;
pub mod stdout;

use anyhow::{bail, Context as _, Result};
use std::path::Path;

/// An I/O error on `path` in words: "{path}: cannot {verb}: <cause> (<os message>)".
pub fn io_error(path: &Path, verb: &str, e: &std::io::Error) -> anyhow::Error {
    use std::io::ErrorKind as K;
    let shown = path.display();
    let cause = match e.kind() {
        K::NotFound => match path.parent().filter(|p| !p.as_os_str().is_empty()) {
            Some(dir) if !dir.is_dir() => format!("folder {} does not exist", dir.display()),
            _ => "no such file".to_string(),
        },
        K::PermissionDenied => "permission denied".to_string(),
        K::IsADirectory => "it is a folder".to_string(),
        K::NotADirectory => "a part of the path is a file, not a folder".to_string(),
        K::AlreadyExists => "a file is in the way".to_string(),
        _ if path.is_dir() => "it is a folder".to_string(),
        _ => "I/O error".to_string(),
    };
    anyhow::anyhow!("{shown}: cannot {verb}: {cause} ({e})")
}

/// Reads `path` whole, refusing more than `limit` bytes: a larger file, or an endless one such as
/// `/dev/zero`, is an error naming the file and the limit instead of a read that fills memory. A
/// folder, a missing or unreadable file are errors that say which.
pub fn read_capped(path: &Path, limit: u64) -> Result<Vec<u8>> {
    use std::io::Read as _;
    let shown = path.display();
    let meta = std::fs::metadata(path).map_err(|e| io_error(path, "read", &e))?;
    if meta.is_dir() {
        bail!("{}", rust_i18n::t!("io.is_folder", path = shown));
    }
    let too_large = || {
        let mib = limit as f64 / (1024.0 * 1024.0);
        anyhow::anyhow!("{}", rust_i18n::t!("io.too_large", path = shown, mib = mib))
    };
    if meta.is_file() && meta.len() > limit {
        return Err(too_large());
    }
    let file = open_without_waiting(path).map_err(|e| io_error(path, "read", &e))?;
    let mut bytes = Vec::new();
    file.take(limit + 1)
        .read_to_end(&mut bytes)
        .map_err(|e| io_error(path, "read", &e))?;
    if bytes.len() as u64 > limit {
        return Err(too_large());
    }
    Ok(bytes)
}

/// Opens `path` for reading without waiting for a writer: a FIFO nobody writes to would block the
/// open forever, and read this way it reads as empty. Reads then block as usual (a pipe with a
/// writer, such as a shell's `<(command)`, is read to its end).
#[cfg(unix)]
fn open_without_waiting(path: &Path) -> std::io::Result<std::fs::File> {
    use std::os::unix::fs::OpenOptionsExt as _;
    use std::os::unix::io::AsRawFd as _;
    let file = std::fs::OpenOptions::new()
        .read(true)
        .custom_flags(libc::O_NONBLOCK)
        .open(path)?;
    // SAFETY: fcntl on a descriptor this function owns, changing only its O_NONBLOCK flag.
    unsafe {
        let fd = file.as_raw_fd();
        let flags = libc::fcntl(fd, libc::F_GETFL);
        if flags >= 0 {
            libc::fcntl(fd, libc::F_SETFL, flags & !libc::O_NONBLOCK);
        }
    }
    Ok(file)
}

/// Elsewhere (Windows) a named pipe is not a path a student's file can be: a plain open.
#[cfg(not(unix))]
fn open_without_waiting(path: &Path) -> std::io::Result<std::fs::File> {
    std::fs::File::open(path)
}

/// Writes `bytes` to `path` (errors as `io_error`).
pub fn write_file(path: &Path, bytes: &[u8]) -> Result<()> {
    std::fs::write(path, bytes).map_err(|e| io_error(path, "write", &e))
}

/// Creates `dir` and its parents (errors as `io_error`).
pub fn create_dir_all(dir: &Path) -> Result<()> {
    std::fs::create_dir_all(dir).map_err(|e| io_error(dir, "create the folder", &e))
}

/// Creates the folder an output file goes into, if it names one.
pub fn create_parent(path: &Path) -> Result<()> {
    match path.parent().filter(|d| !d.as_os_str().is_empty()) {
        Some(dir) => create_dir_all(dir),
        None => Ok(()),
    }
}

/// Encodes an image as PNG in memory, then writes it (so a write error names the file and its cause).
pub fn write_png<P, C>(path: &Path, img: &image::ImageBuffer<P, C>) -> Result<()>
where
    P: image::PixelWithColorType,
    [P::Subpixel]: image::EncodableLayout,
    C: std::ops::Deref<Target = [P::Subpixel]>,
{
    let mut bytes = std::io::Cursor::new(Vec::new());
    img.write_to(&mut bytes, image::ImageFormat::Png)
        .with_context(|| format!("{}: cannot encode the PNG", path.display()))?;
    write_file(path, bytes.get_ref())
}

/// A PFM file's bytes: header, then rows bottom-up as little-endian floats (`channels` per pixel).
fn pfm_bytes(magic: &str, width: u32, height: u32, channels: usize, values: &[f32]) -> Vec<u8> {
    // Negative scale = little-endian.
    let mut out = format!("{magic}\n{width} {height}\n-1.0\n").into_bytes();
    let row = width as usize * channels;
    for y in (0..height as usize).rev() {
        for v in &values[y * row..(y + 1) * row] {
            out.extend_from_slice(&v.to_le_bytes());
        }
    }
    out
}

/// Writes single-channel f32 values (rows top-down) as a PFM ("Pf"); PFM rows are bottom-up.
pub fn write_pfm_gray(path: &Path, width: u32, height: u32, values: &[f32]) -> Result<()> {
    if values.len() != (width * height) as usize {
        bail!(
            "{}: PFM: {} values for {width}x{height}",
            path.display(),
            values.len()
        );
    }
    write_file(path, &pfm_bytes("Pf", width, height, 1, values))
}

/// Writes RGB f32 values (rows top-down) as a PFM ("PF").
pub fn write_pfm_rgb(path: &Path, width: u32, height: u32, rgb: &[f32]) -> Result<()> {
    if rgb.len() != (width * height * 3) as usize {
        bail!(
            "{}: PFM: {} values for {width}x{height}x3",
            path.display(),
            rgb.len()
        );
    }
    write_file(path, &pfm_bytes("PF", width, height, 3, rgb))
}

/// Reads a PFM (either kind) into (width, height, channels, values rows top-down).
pub fn read_pfm(path: &Path) -> Result<(u32, u32, u32, Vec<f32>)> {
    let bytes = std::fs::read(path).map_err(|e| io_error(path, "read", &e))?;
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
    let shown = path.display();
    let w: u32 = fields[1]
        .parse()
        .with_context(|| format!("{shown}: PFM width"))?;
    let h: u32 = fields[2]
        .parse()
        .with_context(|| format!("{shown}: PFM height"))?;
    let scale: f32 = fields[3]
        .parse()
        .with_context(|| format!("{shown}: PFM scale"))?;
    let n = (w as usize)
        .checked_mul(h as usize)
        .and_then(|p| p.checked_mul(channels as usize))
        .with_context(|| format!("{shown}: PFM size {w}x{h} is too large"))?;
    let data = bytes
        .get(pos..pos.saturating_add(n.saturating_mul(4)))
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
    let img = image::GrayImage::from_raw(width, height, px).with_context(|| {
        format!(
            "{}: {} values for {width}x{height}",
            path.display(),
            values.len()
        )
    })?;
    write_png(path, &img)
}
