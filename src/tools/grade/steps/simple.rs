//! The texture-display step (`simple.frag`, course section 1.6: the shader that shows the linear
//! distance buffer, and that the composite of lesson 12 draws the occlusion with). Two renders, each
//! through the student's program and the project's:
//! - a copy: a 48×20 RGBA texture whose four channels hold different patterns (ramps along x and y,
//!   two noises), drawn with linear filtering into a target twice its size, as the half-size buffers
//!   are drawn over the full-size image; every channel must come out as `texture()` gives it;
//! - the lesson's composite (`ao::composite::blend`): the R8 occlusion swizzled to (0, 0, 0, occ) and
//!   alpha-blended over a coloured image, which must come out darkened by exactly the occlusion.
//!
//! A wrong copy is named by what it holds: which of the texture's channels (or 0 or 1) each output
//! channel carries (`.r` broadcast, `.rgb` with alpha 1, swapped channels), a flipped or mirrored
//! picture, or nearest-texel reads instead of filtered ones.

use crate::ao::composite;
use crate::gl::{FramebufferObject, PassState, ProgramObject, Texture, TextureDesc};
use crate::shader_interface::binding;
use crate::tools::grade::measure::matches;
use crate::tools::grade::picture::{Panel, Shade};
use crate::tools::grade::rig::{Rig, Verdict};
use crate::tools::grade::say::say;
use crate::tools::grade::tol;
use anyhow::Result;
use glow::HasContext;
use std::collections::BTreeMap;
use std::rc::Rc;

/// Size of the texture the step draws (not square, so that swapped axes show); the targets are
/// twice as large, as the engine draws its half-size buffers over the full-size image.
pub const SIMPLE_SIZE: (u32, u32) = (48, 20);

/// The channels' names, in the order a texel stores them.
const CHANNELS: [&str; 4] = ["r", "g", "b", "a"];

/// A hash in [0, 1) for reproducible noise (`k` picks one of several independent ones).
fn hash(x: usize, y: usize, k: u32) -> f32 {
    let mut v = (x as u32).wrapping_mul(0x8da6_b343)
        ^ (y as u32).wrapping_mul(0xd816_3841)
        ^ k.wrapping_mul(0xcb1a_b31f);
    v ^= v >> 13;
    v = v.wrapping_mul(0x5bd1_e995);
    v ^= v >> 15;
    (v >> 8) as f32 / (1u32 << 24) as f32
}

/// The copy's texture, RGBA rows bottom-up: red ramps left to right, green bottom to top, blue and
/// alpha are two noises, so that no flip, swap or broadcast leaves the picture unchanged.
fn pattern(w: usize, h: usize, seed: u32) -> Vec<f32> {
    let mut v = Vec::with_capacity(w * h * 4);
    for y in 0..h {
        for x in 0..w {
            v.push((x as f32 + 0.5) / w as f32);
            v.push(0.1 + 0.8 * (y as f32 + 0.5) / h as f32);
            v.push(hash(x, y, seed + 1));
            v.push(0.2 + 0.6 * hash(x, y, seed + 2));
        }
    }
    v
}

/// The image the composite darkens (RGBA, rows bottom-up, opaque).
fn main_image(w: usize, h: usize, seed: u32) -> Vec<f32> {
    let mut v = Vec::with_capacity(w * h * 4);
    for y in 0..h {
        for x in 0..w {
            v.extend([
                0.2 + 0.7 * x as f32 / w as f32,
                0.5 + 0.4 * hash(x, y, seed + 3),
                0.7,
                1.0,
            ]);
        }
    }
    v
}

/// A `w`×`h` texture holding `data` (`channels` values per texel), filtered with `filter`.
fn texture(
    rig: &Rig,
    (w, h): (u32, u32),
    format: u32,
    filter: u32,
    channels: u32,
    data: &[f32],
) -> Result<Texture> {
    let t = Texture::new(
        &rig.gl,
        TextureDesc::target("grade simple input", w, h, format).filter(filter, filter),
    )?;
    t.upload_f32(0, channels, data)?;
    Ok(t)
}

/// Draws `input` through `program` into a fresh RGBA32F target of `size`; returns its RGBA texels.
fn draw_copy(
    rig: &Rig,
    program: &ProgramObject,
    input: &Texture,
    (w, h): (u32, u32),
) -> Result<Vec<f32>> {
    let target = Rc::new(Texture::new(
        &rig.gl,
        TextureDesc::target("grade simple", w, h, glow::RGBA32F),
    )?);
    let fbo = FramebufferObject::new(&rig.gl, Some(target.clone()), None, 0, 0)?;
    PassState::FULLSCREEN.apply(&rig.gl, None);
    fbo.bind();
    // SAFETY: plain GL calls on the current context.
    unsafe {
        rig.gl.clear_color(0.0, 0.0, 0.0, 0.0);
        rig.gl.clear(glow::COLOR_BUFFER_BIT);
    }
    program.use_program();
    input.bind(binding::INPUT);
    rig.meshes.draw_plane_xy();
    Ok(target.read_f32(0, 4))
}

/// The lesson's composite of `occlusion` over `image` through `program`; returns the RGBA texels.
fn draw_composite(
    rig: &Rig,
    program: &ProgramObject,
    occlusion: &Texture,
    image: &[f32],
    (w, h): (u32, u32),
) -> Result<Vec<f32>> {
    let target = Rc::new(Texture::new(
        &rig.gl,
        TextureDesc::target("grade composite", w, h, glow::RGBA32F),
    )?);
    target.upload_f32(0, 4, image)?;
    let fbo = FramebufferObject::new(&rig.gl, Some(target.clone()), None, 0, 0)?;
    composite::blend(&rig.gl, program, occlusion, &fbo, &rig.meshes);
    PassState::FULLSCREEN.apply(&rig.gl, None);
    Ok(target.read_f32(0, 4))
}

/// Both sides' outputs: the copy (and the project's copy with nearest filtering, what a shader
/// reading single texels would give) and the composite.
struct Runs {
    copy_reference: Vec<f32>,
    copy_nearest: Vec<f32>,
    copy: Vec<f32>,
    composite_reference: Vec<f32>,
    composite: Vec<f32>,
}

fn render(rig: &Rig) -> Result<Runs> {
    render_input(rig, SIMPLE_SIZE, 0)
}

/// `render` on a `w`×`h` input made with noise `seed` (0: the step's own).
fn render_input(rig: &Rig, (w, h): (u32, u32), seed: u32) -> Result<Runs> {
    let target = (2 * w, 2 * h);
    let data = pattern(w as usize, h as usize, seed);
    let linear = texture(rig, (w, h), glow::RGBA32F, glow::LINEAR, 4, &data)?;
    let nearest = texture(rig, (w, h), glow::RGBA32F, glow::NEAREST, 4, &data)?;
    let occ: Vec<f32> = (0..(w * h) as usize)
        .map(|i| hash(i % w as usize, i / w as usize, seed + 4))
        .collect();
    let occlusion = texture(rig, (w, h), glow::R8, glow::LINEAR, 1, &occ)?;
    let image = main_image(target.0 as usize, target.1 as usize, seed);
    let (reference, student) = (&rig.reference.prog_simple, &rig.student.prog_simple);
    Ok(Runs {
        copy_reference: draw_copy(rig, reference, &linear, target)?,
        copy_nearest: draw_copy(rig, reference, &nearest, target)?,
        copy: draw_copy(rig, student, &linear, target)?,
        composite_reference: draw_composite(rig, reference, &occlusion, &image, target)?,
        composite: draw_composite(rig, student, &occlusion, &image, target)?,
    })
}

/// Channel `c` of RGBA texels.
fn channel(v: &[f32], c: usize) -> Vec<f32> {
    v.chunks_exact(4).map(|t| t[c]).collect()
}

/// The largest |a − b| over all values (infinite where `a` is not finite) and its index.
fn worst(a: &[f32], b: &[f32]) -> (f64, usize) {
    a.iter()
        .zip(b)
        .map(|(a, b)| {
            if a.is_finite() {
                (*a as f64 - *b as f64).abs()
            } else {
                f64::INFINITY
            }
        })
        .enumerate()
        .fold((0.0, 0), |w, (i, d)| if d > w.0 { (d, i) } else { w })
}

/// `v` with its rows (`flip_y`) or columns reversed: the picture upside down or mirrored.
fn flipped(v: &[f32], w: usize, h: usize, flip_y: bool) -> Vec<f32> {
    let mut out = Vec::with_capacity(v.len());
    for y in 0..h {
        for x in 0..w {
            let (sx, sy) = if flip_y {
                (x, h - 1 - y)
            } else {
                (w - 1 - x, y)
            };
            out.extend_from_slice(&v[(sy * w + sx) * 4..(sy * w + sx) * 4 + 4]);
        }
    }
    out
}

/// Whether `got` matches the prediction `predicted` (RGBA texels) in every channel.
fn same_picture(got: &[f32], predicted: &[f32]) -> bool {
    (0..4).all(|c| {
        let p: Vec<f64> = channel(predicted, c).iter().map(|v| *v as f64).collect();
        matches(&channel(got, c), &p)
    })
}

/// What each output channel of `got` carries: one of the reference's channels ("r", "g", "b", "a"),
/// or the constant "0" or "1"; `None` when a channel is none of these.
fn carried(got: &[f32], reference: &[f32]) -> Option<[&'static str; 4]> {
    let n = got.len() / 4;
    let mut out = ["?"; 4];
    for (c, slot) in out.iter_mut().enumerate() {
        let g = channel(got, c);
        let candidates = (0..4)
            .map(|k| {
                let p: Vec<f64> = channel(reference, k).iter().map(|v| *v as f64).collect();
                (CHANNELS[k], p)
            })
            .chain([("0", vec![0.0; n]), ("1", vec![1.0; n])]);
        *slot = candidates.into_iter().find(|(_, p)| matches(&g, p))?.0;
    }
    Some(out)
}

/// Grades the student's `simple.frag` of `rig`.
pub fn simple(rig: &Rig) -> Verdict {
    let runs = match render(rig) {
        Ok(r) => r,
        Err(e) => return Verdict::grader_error(&e),
    };
    let (tw, th) = (2 * SIMPLE_SIZE.0 as usize, 2 * SIMPLE_SIZE.1 as usize);
    let (copy_err, copy_at) = worst(&runs.copy, &runs.copy_reference);
    let (comp_err, comp_at) = worst(&runs.composite, &runs.composite_reference);
    let mut metrics = BTreeMap::new();
    metrics.insert("copy_max_error".into(), copy_err);
    metrics.insert("composite_max_error".into(), comp_err);
    // One panel per channel of the copy, then the composite's red channel (its darkening).
    let mut panels: Vec<Panel> = (0..4)
        .map(|c| {
            Panel::absolute(
                tw,
                th,
                channel(&runs.copy_reference, c),
                channel(&runs.copy, c),
                Shade::Occlusion,
                0.25,
            )
        })
        .collect();
    panels.push(Panel::absolute(
        tw,
        th,
        channel(&runs.composite_reference, 0),
        channel(&runs.composite, 0),
        Shade::Occlusion,
        0.25,
    ));
    let verdict = |passed: bool, message| Verdict {
        passed,
        message,
        metrics: metrics.clone(),
        panels: panels.clone(),
        parts: Vec::new(),
    };
    let copy_ok = copy_err <= tol::SIMPLE_ABS;
    if copy_ok && comp_err <= tol::SIMPLE_ABS {
        let worst = format!("{:.1e}", copy_err.max(comp_err));
        return verdict(true, say!("grade.verdict.simple_pass", worst = worst));
    }
    if !copy_ok {
        let identity = ["r", "g", "b", "a"];
        if let Some(holds) = carried(&runs.copy, &runs.copy_reference).filter(|h| *h != identity) {
            let got = holds.join(", ");
            let message = if holds == ["0"; 4] {
                say!("grade.verdict.simple_zero")
            } else if holds == ["r", "g", "b", "1"] {
                say!("grade.verdict.simple_alpha_one", got = got)
            } else if holds[..3].iter().all(|c| *c == "r") {
                say!("grade.verdict.simple_broadcast", got = got)
            } else {
                say!("grade.verdict.simple_swapped", got = got)
            };
            return verdict(false, message);
        }
        let w = tw;
        if same_picture(&runs.copy, &flipped(&runs.copy_reference, w, th, true)) {
            return verdict(false, say!("grade.verdict.simple_upside_down"));
        }
        if same_picture(&runs.copy, &flipped(&runs.copy_reference, w, th, false)) {
            return verdict(false, say!("grade.verdict.simple_mirrored"));
        }
        if same_picture(&runs.copy, &runs.copy_nearest) {
            return verdict(false, say!("grade.verdict.simple_nearest"));
        }
        let (texel, c) = (copy_at / 4, copy_at % 4);
        return verdict(
            false,
            say!(
                "grade.verdict.simple_differs",
                channel = CHANNELS[c],
                x = texel % w,
                y = texel / w,
                got = format!("{:.3}", runs.copy[copy_at]),
                expected = format!("{:.3}", runs.copy_reference[copy_at]),
                tolerance = tol::SIMPLE_ABS
            ),
        );
    }
    let texel = comp_at / 4;
    verdict(
        false,
        say!(
            "grade.verdict.simple_composite",
            x = texel % tw,
            y = texel / tw,
            got = format!("{:.3}", runs.composite[comp_at]),
            expected = format!("{:.3}", runs.composite_reference[comp_at])
        ),
    )
}

/// The mutation probe of this step: the copy and the composite of an input the step never uses
/// (another size and other noise), the largest difference from the project's in units of
/// `tol::SIMPLE_ABS` and of float noise (`tol::EQUIVALENT_REL`: the values lie in [0, 1]).
pub fn probe_difference(rig: &Rig) -> Result<(f64, f64)> {
    let runs = render_input(rig, (36, 28), 10)?;
    let copy = worst(&runs.copy, &runs.copy_reference).0;
    let composite = worst(&runs.composite, &runs.composite_reference).0;
    let d = copy.max(composite);
    Ok((d / tol::SIMPLE_ABS, d / tol::EQUIVALENT_REL))
}
