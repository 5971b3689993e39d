//! File cache for reference images: a stable key and a small binary format.
//!
//! Layout of `<cache_dir>/<key>.bin`, all little-endian:
//! ```text
//! magic      8 bytes  b"OGLAOREF"
//! version    u32      CACHE_FORMAT_VERSION
//! width      u32
//! height     u32
//! key        16 bytes the ASCII hex key (guards against renamed / mixed-up files)
//! ao         width*height f32
//! std_error  width*height f32
//! depth      width*height f32   (f32::INFINITY for sky)
//! checksum   u64      FNV-1a 64 of every byte above
//! ```
//! Any mismatch (short file, wrong magic/version/key/size/checksum) makes the file count as
//! absent, so [`load_or_render_cached`] re-renders and overwrites it.

use std::{
    fs,
    io::{ErrorKind, Write},
    path::{Path, PathBuf},
};

use anyhow::{bail, Context, Result};
use rust_i18n::t;

use super::hash::Fnv64;
use super::image::RefImage;
use super::params::{AoVariant, RefParams};
use super::scene::Scene;
use super::trace::render_reference;
use crate::math::Camera;

const MAGIC: &[u8; 8] = b"OGLAOREF";

/// Bump when the file layout changes.
const CACHE_FORMAT_VERSION: u32 = 1;

/// Bump when the renderer's output for the same inputs changes (sampling, offsets, ...), so
/// stale cached images are not reused.
const ALGORITHM_VERSION: u32 = 1;

/// Stable 16-hex-digit key for a render: FNV-1a 64 over the algorithm version, the triangle
/// hash, every camera field, the image size and every parameter that affects the pixels
/// (`progress` does not). Float fields are hashed by bit pattern.
pub fn cache_key(
    triangles_hash: u64,
    cam: &Camera,
    width: u32,
    height: u32,
    params: &RefParams,
) -> String {
    let mut h = Fnv64::new();
    h.bytes(b"opengl3d-reference-ao");
    h.u32(ALGORITHM_VERSION);
    h.u64(triangles_hash);
    h.vec3(cam.eye);
    h.vec3(cam.target);
    h.vec3(cam.up);
    h.f32(cam.fov_y_deg);
    h.f32(cam.near);
    h.f32(cam.far);
    h.u32(width);
    h.u32(height);
    h.f32(params.radius);
    h.u32(params.rays);
    h.u32(match params.variant {
        AoVariant::Visibility => 0,
        AoVariant::Obscurance => 1,
    });
    h.u64(params.seed);
    // Hashed only when it changes the pixels, so centre-sampled keys stay as they were.
    if params.supersample > 1 {
        h.bytes(b"supersample");
        h.u32(params.supersample);
    }
    format!("{:016x}", h.0)
}

/// Path of the cache file for `key`.
pub fn cache_path(cache_dir: &Path, key: &str) -> PathBuf {
    cache_dir.join(format!("{key}.bin"))
}

fn encode(key: &str, img: &RefImage) -> Result<Vec<u8>> {
    let n = img.width as usize * img.height as usize;
    if img.ao.len() != n || img.std_error.len() != n || img.linear_depth.len() != n {
        bail!(
            "RefImage buffers do not match its {}x{} size",
            img.width,
            img.height
        );
    }
    if key.len() != 16 {
        bail!("cache key must be 16 characters, got {key:?}");
    }
    let mut out = Vec::with_capacity(40 + 12 * n + 8);
    out.extend_from_slice(MAGIC);
    out.extend_from_slice(&CACHE_FORMAT_VERSION.to_le_bytes());
    out.extend_from_slice(&img.width.to_le_bytes());
    out.extend_from_slice(&img.height.to_le_bytes());
    out.extend_from_slice(key.as_bytes());
    for buf in [&img.ao, &img.std_error, &img.linear_depth] {
        for v in buf.iter() {
            out.extend_from_slice(&v.to_le_bytes());
        }
    }
    let mut h = Fnv64::new();
    h.bytes(&out);
    out.extend_from_slice(&h.0.to_le_bytes());
    Ok(out)
}

fn decode(key: &str, bytes: &[u8]) -> Option<RefImage> {
    const HEADER: usize = 8 + 4 + 4 + 4 + 16;
    if bytes.len() < HEADER + 8 || &bytes[..8] != MAGIC {
        return None;
    }
    let u32_at = |i: usize| u32::from_le_bytes(bytes[i..i + 4].try_into().unwrap());
    if u32_at(8) != CACHE_FORMAT_VERSION || &bytes[20..36] != key.as_bytes() {
        return None;
    }
    let (width, height) = (u32_at(12), u32_at(16));
    let n = (width as usize).checked_mul(height as usize)?;
    let expected = n.checked_mul(12)?.checked_add(HEADER + 8)?;
    if bytes.len() != expected {
        return None;
    }
    let (body, sum) = bytes.split_at(bytes.len() - 8);
    let mut h = Fnv64::new();
    h.bytes(body);
    if h.0 != u64::from_le_bytes(sum.try_into().unwrap()) {
        return None;
    }
    let floats = |k: usize| -> Vec<f32> {
        let start = HEADER + k * 4 * n;
        bytes[start..start + 4 * n]
            .chunks_exact(4)
            .map(|c| f32::from_le_bytes(c.try_into().unwrap()))
            .collect()
    };
    Some(RefImage {
        width,
        height,
        ao: floats(0),
        std_error: floats(1),
        linear_depth: floats(2),
    })
}

/// Writes `img` as the cache file for `key` (atomically: temp file + rename, so a crashed or
/// concurrent writer never leaves a half-written file under the final name).
pub fn write_cached(cache_dir: &Path, key: &str, img: &RefImage) -> Result<PathBuf> {
    fs::create_dir_all(cache_dir)
        .with_context(|| format!("creating cache dir {}", cache_dir.display()))?;
    let bytes = encode(key, img)?;
    let path = cache_path(cache_dir, key);
    let tmp = cache_dir.join(format!("{key}.bin.tmp{}", std::process::id()));
    let written = write_synced(&tmp, &bytes).and_then(|()| {
        fs::rename(&tmp, &path)
            .with_context(|| format!("renaming {} to {}", tmp.display(), path.display()))
    });
    if let Err(e) = written {
        // Do not leave the partial temp file behind; say so when even that fails.
        if tmp.exists() {
            if let Err(rm) = fs::remove_file(&tmp) {
                return Err(e.context(format!("and {} could not be removed: {rm}", tmp.display())));
            }
        }
        return Err(e);
    }
    Ok(path)
}

fn write_synced(path: &Path, bytes: &[u8]) -> Result<()> {
    let mut f = fs::File::create(path).with_context(|| format!("creating {}", path.display()))?;
    f.write_all(bytes)
        .with_context(|| format!("writing {}", path.display()))?;
    f.sync_all()
        .with_context(|| format!("syncing {}", path.display()))
}

/// Reads the cache file for `key`; `None` if it is missing or not a valid file for that key.
/// A file that exists but cannot be read is reported on stderr (and then rendered again).
pub fn read_cached(cache_dir: &Path, key: &str) -> Option<RefImage> {
    let path = cache_path(cache_dir, key);
    match fs::read(&path) {
        Ok(bytes) => decode(key, &bytes),
        Err(e) if matches!(e.kind(), ErrorKind::NotFound | ErrorKind::NotADirectory) => None,
        Err(e) => {
            eprintln!(
                "{}",
                t!(
                    "reference.cache_unreadable",
                    path = path.display(),
                    error = e
                )
            );
            None
        }
    }
}

/// Stores a fresh render in the cache. A cache that cannot be written only costs a render next
/// time, so the failure is a warning naming the file, and the caller keeps its result.
pub(crate) fn store_or_warn(cache_dir: &Path, key: &str, img: &RefImage) {
    if let Err(e) = write_cached(cache_dir, key, img) {
        let error = format!("{e:#}");
        eprintln!(
            "{}",
            t!(
                "reference.cache_not_written",
                path = cache_path(cache_dir, key).display(),
                error = error
            )
        );
    }
}

/// Returns the cached image for these inputs if `cache_dir/<key>.bin` holds a valid one,
/// otherwise renders with [`render_reference`] and stores the result (an unwritable
/// cache is a warning, not an error). The key uses [`Scene::content_hash`].
pub fn load_or_render_cached(
    cache_dir: &Path,
    scene: &Scene,
    cam: &Camera,
    width: u32,
    height: u32,
    params: &RefParams,
) -> RefImage {
    let key = cache_key(scene.content_hash(), cam, width, height, params);
    if let Some(img) = read_cached(cache_dir, &key) {
        if img.width == width && img.height == height {
            return img;
        }
    }
    let img = render_reference(scene, cam, width, height, params);
    store_or_warn(cache_dir, &key, &img);
    img
}
