//! The ray-traced reference through `rtao`'s shader (`reference --gpu`): the same visibility (rays of
//! length R, cosine-weighted, a hit within R blocks the ray) from the surface each pixel's centre sees,
//! with all of a pixel's rays in one stratified lattice as `trace.rs` draws them, no blur and no
//! accumulation. The surface comes from the depth buffer at full AO resolution and its normal from
//! the surface-normal pass, where the CPU traces a primary ray; both land on the same triangle at the
//! pixel centre, so the two agree within their Monte-Carlo noise.

use super::cache::{cache_key, read_cached, store_or_warn};
use super::hash::Fnv64;
use super::image::{footprint_mean, RefImage};
use super::params::{AoVariant, RefParams};
use crate::ao::{AoMethod, AoResolution, GuardBand};
use crate::platform::HeadlessContext;
use crate::render::{Engine, View};
use crate::res::ResDirs;
use crate::scene::SceneDesc;
use anyhow::{bail, Result};
use rust_i18n::t;
use std::path::Path;

/// The most rays one GPU reference pass traces per pixel (`[ao] rays`' bound).
pub const MAX_GPU_RAYS: u32 = crate::ao::settings::RAYS_RANGE.1;

/// Renders the reference of `scene`'s camera at its output size on the GPU.
pub fn render_reference_gpu(
    res: &ResDirs,
    scene: &SceneDesc,
    params: &RefParams,
) -> Result<RefImage> {
    if params.variant != AoVariant::Visibility {
        bail!("{}", t!("reference.gpu_visibility_only"));
    }
    if params.rays == 0 || params.rays > MAX_GPU_RAYS {
        bail!("{}", t!("reference.gpu_rays", max = MAX_GPU_RAYS));
    }
    let mut scene = scene.clone();
    let ao = &mut scene.ao;
    ao.enabled = true;
    ao.method = AoMethod::Rtao;
    ao.resolution = AoResolution::Full;
    ao.guard_band = GuardBand::Off;
    ao.blur = false;
    ao.radius = params.radius;
    ao.intensity = 5.0; // the identity: occlusion as traced
                        // With a footprint, every sub-pixel of an image `supersample` times larger gets its share.
    let footprint = params.supersample.max(1);
    ao.rays = params.sub_pixel().rays;
    ao.accumulate = 1;
    ao.stratified = true;
    let (out_w, out_h) = (scene.output.width, scene.output.height);
    scene.output.width = out_w.saturating_mul(footprint);
    scene.output.height = out_h.saturating_mul(footprint);
    let ctx = HeadlessContext::new()?;
    let mut engine = Engine::at_output_size(&ctx.gl, res.clone(), &scene)?;
    let ao = engine.render_values(View::AoRaw)?;
    let depth = engine.render_values(View::LinearDepth)?;
    let far = engine.camera.far;
    let n = scene.ao.rays as f32;
    let (w, h) = engine.size();
    let mut img = RefImage {
        width: w,
        height: h,
        ao: Vec::with_capacity(ao.len()),
        std_error: Vec::with_capacity(ao.len()),
        linear_depth: Vec::with_capacity(ao.len()),
    };
    for (&v, &z) in ao.iter().zip(&depth) {
        let sky = z.is_nan() || z >= far;
        let v = if sky { 1.0 } else { v.clamp(0.0, 1.0) };
        img.ao.push(v);
        img.std_error.push((v * (1.0 - v) / n).max(0.0).sqrt());
        img.linear_depth.push(if sky { f32::INFINITY } else { z });
    }
    if footprint == 1 {
        return Ok(img);
    }
    let mut mean = RefImage {
        width: out_w,
        height: out_h,
        ao: Vec::with_capacity(out_w as usize * out_h as usize),
        std_error: Vec::with_capacity(out_w as usize * out_h as usize),
        linear_depth: Vec::with_capacity(out_w as usize * out_h as usize),
    };
    for y in 0..out_h {
        for x in 0..out_w {
            let (a, e, d) = footprint_mean(footprint, |i, j| {
                let k = img.index(x * footprint + i, y * footprint + j);
                (img.ao[k], img.std_error[k], img.linear_depth[k])
            });
            mean.ao.push(a);
            mean.std_error.push(e);
            mean.linear_depth.push(d);
        }
    }
    Ok(mean)
}

/// [`render_reference_gpu`] through the reference's cache folder: the same file format, under a key
/// of its own (the CPU key hashed again with a GPU marker), so the two estimators never share an entry.
pub fn load_or_render_gpu_cached(
    cache_dir: &Path,
    res: &ResDirs,
    scene: &SceneDesc,
    triangles_hash: u64,
    params: &RefParams,
) -> Result<RefImage> {
    let cam = scene.camera.camera();
    let (w, h) = (scene.output.width, scene.output.height);
    let mut hash = Fnv64::new();
    hash.bytes(b"gpu");
    hash.bytes(cache_key(triangles_hash, &cam, w, h, params).as_bytes());
    let key = format!("{:016x}", hash.0);
    if let Some(img) = read_cached(cache_dir, &key) {
        if (img.width, img.height) == (w, h) {
            return Ok(img);
        }
    }
    let img = render_reference_gpu(res, scene, params)?;
    store_or_warn(cache_dir, &key, &img);
    Ok(img)
}
