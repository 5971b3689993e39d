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
use super::scene::Scene;
use crate::ao::{AoMethod, AoResolution, GuardBand};
use crate::platform::HeadlessContext;
use crate::render::{Engine, View};
use crate::res::ResDirs;
use crate::scene::SceneDesc;
use anyhow::{bail, Result};
use rust_i18n::t;
use std::path::Path;

/// The most rays the GPU reference traces per pixel (`[ao] rays`' bound).
pub const MAX_GPU_RAYS: u32 = crate::ao::settings::RAYS_RANGE.1;

/// Rays per pixel of one pass: a pixel's rays are traced in passes of at most this many (points of
/// the same lattice), halved while the shader reports pixels whose rays the driver cut short
/// (llvmpipe ends a shader invocation's loops after 65535 iterations in all: a rippled sphere of
/// 6 400 triangles at 1024 rays in one pass meets it on 350 of its 64×48 pixels, `tests/gl/rtao_dense.rs`;
/// passes of 64 rays met it on no pixel of three models of 62 000 triangles at 320×180).
const PASS_RAYS: u32 = 64;

/// Renders the reference of `scene`'s camera at its output size on the GPU. The rays go in passes
/// (see [`PASS_RAYS`]); a pass the driver cut short is traced again with fewer rays, and one ray
/// per pass cut short is an error, never an image.
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
    let total = params.sub_pixel().rays;
    ao.rays = total.min(PASS_RAYS);
    ao.accumulate = 1;
    ao.stratified = true;
    let (out_w, out_h) = (scene.output.width, scene.output.height);
    scene.output.width = out_w.saturating_mul(footprint);
    scene.output.height = out_h.saturating_mul(footprint);
    let ctx = HeadlessContext::new()?;
    let mut engine = Engine::at_output_size(&ctx.gl, res.clone(), &scene)?;
    let depth = engine.render_values(View::LinearDepth)?;
    // The rays' sum per pixel, pass by pass (each pass's value is its own rays' mean).
    let mut sum = vec![0.0f64; depth.len()];
    let (mut done, mut per_pass) = (0u32, PASS_RAYS);
    while done < total {
        let rays = per_pass.min(total - done);
        engine.ao_settings.rays = rays;
        engine.ao_settings.lattice_slice = (done, total);
        let ao = engine.render_values(View::AoRaw)?;
        let cut = engine.ao.cut_pixels(AoMethod::Rtao);
        if cut > 0 {
            if rays == 1 {
                bail!("{}", t!("reference.gpu_cut", pixels = cut));
            }
            per_pass = rays / 2;
            continue;
        }
        for (s, v) in sum.iter_mut().zip(&ao) {
            *s += *v as f64 * rays as f64;
        }
        done += rays;
    }
    let far = engine.camera.far;
    let n = total as f32;
    let (w, h) = engine.size();
    let mut img = RefImage {
        width: w,
        height: h,
        ao: Vec::with_capacity(sum.len()),
        std_error: Vec::with_capacity(sum.len()),
        linear_depth: Vec::with_capacity(sum.len()),
    };
    for (&s, &z) in sum.iter().zip(&depth) {
        let sky = z.is_nan() || z >= far;
        let v = if sky {
            1.0
        } else {
            (s / total as f64).clamp(0.0, 1.0) as f32
        };
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
/// A new image is first checked against `cpu` (the same triangles for the CPU tracer) on a sample of
/// its pixels ([`super::gpu_check`]): one that disagrees is an error and is not stored.
pub fn load_or_render_gpu_cached(
    cache_dir: &Path,
    res: &ResDirs,
    scene: &SceneDesc,
    cpu: &Scene,
    params: &RefParams,
) -> Result<RefImage> {
    let cam = scene.camera.camera();
    let (w, h) = (scene.output.width, scene.output.height);
    let mut hash = Fnv64::new();
    // "2": images traced in one pass may be cut short by the driver (see `PASS_RAYS`).
    hash.bytes(b"gpu2");
    hash.bytes(cache_key(cpu.content_hash(), &cam, w, h, params).as_bytes());
    let key = format!("{:016x}", hash.0);
    if let Some(img) = read_cached(cache_dir, &key) {
        if (img.width, img.height) == (w, h) {
            return Ok(img);
        }
    }
    let img = render_reference_gpu(res, scene, params)?;
    let check = super::gpu_check::require_agreement(cpu, &cam, params, &img)?;
    if params.progress {
        let mean = format!("{:+.4}", check.mean_difference);
        eprintln!(
            "{}",
            t!("reference.gpu_checked", pixels = check.pixels, mean = mean)
        );
    }
    store_or_warn(cache_dir, &key, &img);
    Ok(img)
}
