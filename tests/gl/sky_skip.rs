//! The engine methods' pass and blur shade only the surface texels of the AO-size window depth
//! (`ao::sky_skip`): the results are the same texel for texel as when every texel is shaded, in both
//! depth conventions, and texels the depth marks as sky really are skipped.

use super::common;
use opengl3d::ao::method_pass::{AoInputs, AoMethodPass};
use opengl3d::ao::sky_skip::AoSizeDepth;
use opengl3d::ao::AoTargets;
use opengl3d::gl::{Texture, TextureDesc};
use opengl3d::math::{Camera, DepthMode};
use std::rc::Rc;

const W: u32 = 48;
const H: u32 = 32;

/// A bumpy surface 2–4 m away inside a rectangle of the AO size, sky (exactly `far`) around it.
fn on_surface(x: f32, y: f32) -> bool {
    (8.0..40.0).contains(&x) && (6.0..26.0).contains(&y)
}

fn linear_depth(x: f32, y: f32, far: f32) -> f32 {
    if on_surface(x, y) {
        3.0 + 0.6 * (x * 0.7).sin() * (y * 0.5).cos()
    } else {
        far
    }
}

struct Outputs {
    raw: Vec<f32>,
    packed: Vec<f32>,
    blurred: Vec<f32>,
}

/// The method's pass and blur over the rectangle, shading the surface texels of a window depth whose
/// surface is `marked` (texel centre → surface?) when `marked` is given, every texel otherwise.
fn run(mode: DepthMode, marked: Option<&dyn Fn(f32, f32) -> bool>) -> Outputs {
    run_with_window(mode, marked, (W, H))
}

/// `run` with a window depth of `size` (the AO size: W×H).
fn run_with_window(
    mode: DepthMode,
    marked: Option<&dyn Fn(f32, f32) -> bool>,
    (ww, wh): (u32, u32),
) -> Outputs {
    let ctx = common::context();
    let cam = Camera::default();
    let (settings, meshes, sao) = common::sao_pass(&ctx, 1.0, 4.0, true);
    let targets = AoTargets::new(&ctx.gl, 2 * W, 2 * H, 3).unwrap();
    for l in 0..3 {
        let (lw, lh) = targets.tex_depth.size_at(l);
        let s = (1u32 << l) as f32;
        let v: Vec<f32> = (0..lw * lh)
            .map(|i| {
                let (x, y) = (((i % lw) as f32 + 0.5) * s, ((i / lw) as f32 + 0.5) * s);
                linear_depth(x, y, cam.far)
            })
            .collect();
        targets.tex_depth.upload_f32(l, 1, &v).unwrap();
    }
    let window = marked.map(|surface| {
        let desc = TextureDesc::target("window depth", ww, wh, mode.internal_format());
        let tex = Rc::new(Texture::new(&ctx.gl, desc).unwrap());
        let v: Vec<f32> = (0..ww * wh)
            .map(|i| {
                let (x, y) = ((i % ww) as f32 + 0.5, (i / ww) as f32 + 0.5);
                if surface(x, y) {
                    0.5
                } else {
                    mode.clear_value()
                }
            })
            .collect();
        tex.upload_f32(0, 1, &v).unwrap();
        tex
    });
    let inputs = AoInputs {
        ao_size_depth: window.as_ref().map(|texture| AoSizeDepth {
            texture,
            mode,
            far: cam.far,
        }),
        ..common::depth_only_inputs(&ctx, &meshes, &targets, &cam, &settings, None)
    };
    // Stale values from an earlier frame must not show through where the pass skips.
    for fbo in [&targets.fbo_sao, &targets.fbo_blur] {
        fbo.bind();
        // SAFETY: clears of the bound framebuffer.
        unsafe {
            use glow::HasContext;
            ctx.gl.clear_color(0.7, 0.7, 0.7, 0.7);
            ctx.gl.clear(glow::COLOR_BUFFER_BIT);
        }
    }
    sao.compute(&inputs).unwrap();
    sao.blur(&inputs).unwrap();
    let packed = sao.pass().packed().packed_texture().unwrap();
    Outputs {
        raw: targets.sao_texture().read_f32(0, 1),
        packed: packed.read_f32(0, 2),
        blurred: targets.result_texture(true).read_f32(0, 1),
    }
}

fn bits(v: &[f32]) -> Vec<u32> {
    v.iter().map(|x| x.to_bits()).collect()
}

#[test]
fn skipping_the_sky_leaves_every_output_texel_unchanged() {
    for mode in [DepthMode::D32, DepthMode::D32fReversed] {
        let all = run(mode, None);
        let skipped = run(mode, Some(&on_surface));
        assert!(
            all.raw.iter().any(|&o| o > 0.05),
            "the surface should be occluded somewhere"
        );
        assert_eq!(
            bits(&all.raw),
            bits(&skipped.raw),
            "{mode:?}: raw occlusion"
        );
        assert_eq!(
            bits(&all.packed),
            bits(&skipped.packed),
            "{mode:?}: packed pair"
        );
        assert_eq!(
            bits(&all.blurred),
            bits(&skipped.blurred),
            "{mode:?}: blurred occlusion"
        );
    }
}

#[test]
fn texels_the_window_depth_calls_sky_are_not_shaded() {
    // The window depth marks only the left half of the surface: the right half is written as sky.
    let left = |x: f32, y: f32| on_surface(x, y) && x < 24.0;
    for mode in [DepthMode::D32, DepthMode::D32fReversed] {
        let all = run(mode, None);
        let skipped = run(mode, Some(&left));
        let mut occluded_right = 0;
        for i in 0..(W * H) as usize {
            let (x, y) = ((i as u32 % W) as f32 + 0.5, (i as u32 / W) as f32 + 0.5);
            if left(x, y) {
                assert_eq!(all.raw[i], skipped.raw[i], "{mode:?}: shaded texel {x},{y}");
            } else {
                assert_eq!(skipped.raw[i], 0.0, "{mode:?}: skipped texel {x},{y}");
                assert_eq!(skipped.packed[2 * i + 1], Camera::default().far);
                occluded_right += usize::from(on_surface(x, y) && all.raw[i] > 0.0);
            }
        }
        assert!(
            occluded_right > 20,
            "{mode:?}: the right half should have occlusion when shaded ({occluded_right} texels)"
        );
    }
}

#[test]
fn a_window_depth_of_another_size_is_not_used() {
    // Marking only the left half would change the right half's texels if it were used.
    let left = |x: f32, y: f32| on_surface(x, y) && x < 24.0;
    let all = run(DepthMode::D32, None);
    let other = run_with_window(DepthMode::D32, Some(&left), (W + 1, H));
    assert_eq!(bits(&all.raw), bits(&other.raw));
    assert_eq!(bits(&all.blurred), bits(&other.blurred));
}
