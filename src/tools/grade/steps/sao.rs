//! The SAO step (`sao.frag`): three ray-cast box scenes (a wall on a floor with a crate; a wall
//! seen head-on with a step; a wall seen head-on with a raised panel), 160×160, the same mip chain
//! for both shaders. Checked: NaN; values above 1 (not normalised, when clamping does not hide it);
//! creases occluded (≥ half the reference's); open flat surfaces ≈ 0; the occlusion of a band beside
//! the panel (the falloff's shape); the mean and the RMSE of 8×8 block means over pixels facing the
//! camera and away from depth edges (the per-pixel noise may differ, and the lesson's listing has no
//! mip-bias or edge guard, which this port's `sao.frag` adds: on grazing surfaces and at depth edges
//! they legitimately differ); the 2×2 smoothing (diagonal pixels of each quad facing the camera
//! end up equal); the same occlusion in every direction (`sao_isotropy`); and that far samples
//! come from mip levels 1–3 and near ones from level 0 (the output must move when levels 1–3 are
//! emptied, about as much as the project's does: not much less, not far more).

use crate::ao::AoSettings;
use crate::i18n::Text;
use crate::tools::grade::measure::{as_r8, block_means, rect_mean};
use crate::tools::grade::passes::{run_sao, run_sao_pair, Mips};
use crate::tools::grade::picture::{Panel, Shade};
use crate::tools::grade::rig::{Rig, Verdict};
use crate::tools::grade::say::say;
use crate::tools::grade::scene::{sao_scenes, ProbeKind, SynthScene};
use crate::tools::grade::tol;
use anyhow::Result;
use std::collections::BTreeMap;

/// Size of `texSAODepth` level 0 in the SAO step (square).
pub const SAO_SIZE: u32 = 160;
/// Relative depth change per texel below which a surface counts as facing the camera.
const FLAT_SLOPE: f32 = 0.01;

/// One probe's mean occlusion, the student's (`got`, `raw`) and the reference's (`expected`).
struct ProbeResult {
    scene: &'static str,
    name: &'static str,
    kind: ProbeKind,
    got: f64,
    /// Before clamping to [0, 1] (what the shader wrote).
    raw: f64,
    expected: f64,
}

/// Mean |a − b| over non-sky pixels (after the R8 clamp).
fn mean_abs_change(a: &[f32], b: &[f32], depth: &[f32], far: f32) -> f64 {
    let (mut sum, mut n) = (0.0f64, 0usize);
    for i in 0..depth.len() {
        if depth[i] < far {
            sum += (as_r8(a[i]) - as_r8(b[i])).abs() as f64;
            n += 1;
        }
    }
    sum / n.max(1) as f64
}

/// Pixels away from depth edges: every depth within 2 texels is within 5% of this one (the
/// lesson's normal from dFdx/dFdy is meaningless at an edge; the reference leaves edges open).
fn clean_mask(depth: &[f32], w: usize, h: usize, far: f32) -> Vec<bool> {
    let mut m = vec![false; w * h];
    for y in 0..h {
        for x in 0..w {
            let d0 = depth[y * w + x];
            if d0 >= far {
                continue;
            }
            let mut ok = true;
            for yy in y.saturating_sub(2)..=(y + 2).min(h - 1) {
                for xx in x.saturating_sub(2)..=(x + 2).min(w - 1) {
                    ok &= (depth[yy * w + xx] - d0).abs() <= 0.05 * d0;
                }
            }
            m[y * w + x] = ok;
        }
    }
    m
}

/// Aligned 2×2 quads (even x and y) whose four pixels lie away from depth edges on surfaces facing
/// the camera squarely (depth changing by under 2 cm per texel, as the lesson's 2×2 smoothing asks
/// before it runs): (such quads, those whose diagonal pixels differ by more than
/// `tol::SAO_QUAD_SPREAD`). The lesson's smoothing (x, then y of the result) leaves the quad's mean
/// in all four pixels; taking both derivatives first, as a correct rewrite may, leaves each diagonal
/// pair the mean of the other pair. Either way the diagonal pixels are equal; without the smoothing,
/// or with its sign or pixel parity wrong, they are not.
fn quad_parity(s: &[f32], depth: &[f32], clean: &[bool], w: usize, h: usize) -> (usize, usize) {
    let (mut quads, mut uneven) = (0, 0);
    for y in (2..h.saturating_sub(3)).step_by(2) {
        for x in (2..w.saturating_sub(3)).step_by(2) {
            let px = [(x, y), (x + 1, y + 1), (x + 1, y), (x, y + 1)].map(|(a, b)| b * w + a);
            let square = px.iter().all(|&i| {
                clean[i]
                    && (depth[i + 1] - depth[i - 1]).abs() < 0.02
                    && (depth[i + w] - depth[i - w]).abs() < 0.02
            });
            if !square {
                continue;
            }
            quads += 1;
            let apart =
                |a: usize, b: usize| (s[px[a]] - s[px[b]]).abs() as f64 > tol::SAO_QUAD_SPREAD;
            if apart(0, 1) || apart(2, 3) {
                uneven += 1;
            }
        }
    }
    (quads, uneven)
}

/// What the SAO step measures on its scenes (`_s` the student's, `_r` the reference's), before
/// judging. Sums run over non-sky pixels: all of them, those away from depth edges (`clean`), and
/// those also facing the camera (`flat`).
struct Measured {
    panels: Vec<Panel>,
    /// Non-sky pixels.
    count: usize,
    /// Non-sky pixels that are NaN or Inf, above `tol::SAO_RAW_MAX`, below −0.01.
    nan: usize,
    over: usize,
    negative: usize,
    sum_s: f64,
    sum_r: f64,
    sum_raw: f64,
    clean_s: f64,
    clean_r: f64,
    clean_n: usize,
    flat_s: f64,
    flat_r: f64,
    flat_n: usize,
    max_raw: f64,
    /// Sum of squared differences of 8×8 block means, and the number of blocks.
    blocks_sq: (f64, usize),
    /// The largest block difference: (difference, scene, x, y).
    worst_block: (f64, &'static str, usize, usize),
    probes: Vec<ProbeResult>,
    sky_max: f64,
    /// Quads checked for the 2×2 smoothing, and those left uneven (`quad_parity`).
    quads: (usize, usize),
}

fn measure(rig: &Rig, params: &AoSettings, scenes: &[SynthScene]) -> Result<Measured> {
    let mut panels = vec![];
    let (mut sum_s, mut sum_r, mut sum_raw, mut count) = (0.0f64, 0.0f64, 0.0f64, 0usize);
    let (mut clean_s, mut clean_r, mut clean_n) = (0.0f64, 0.0f64, 0usize);
    let (mut flat_s, mut flat_r, mut flat_n) = (0.0f64, 0.0f64, 0usize);
    let (mut nan, mut over, mut negative) = (0usize, 0usize, 0usize);
    let mut max_raw = 0.0f64;
    let mut blocks_sq = (0.0f64, 0usize);
    let mut worst_block = (0.0f64, "", 0usize, 0usize);
    let mut probes = vec![];
    let mut sky_max = 0.0f64;
    let mut quads = (0usize, 0usize);
    for scene in scenes {
        let (w, h) = (scene.width as usize, scene.height as usize);
        let depth = scene.depth();
        let far = scene.camera.far;
        let (r, raw) = run_sao_pair(
            &rig.reference,
            &rig.student,
            &rig.meshes,
            &scene.camera,
            &depth,
            params,
        )?;
        let s: Vec<f32> = raw.iter().map(|v| as_r8(*v)).collect();
        let clean = clean_mask(&depth, w, h, far);
        let flat: Vec<bool> = (0..w * h)
            .map(|i| {
                let (x, y) = (i % w, i / w);
                if !clean[i] || x == 0 || y == 0 || x == w - 1 || y == h - 1 {
                    return false;
                }
                let sx = (depth[i + 1] - depth[i - 1]).abs() * 0.5;
                let sy = (depth[i + w] - depth[i - w]).abs() * 0.5;
                (sx + sy) / depth[i] < FLAT_SLOPE
            })
            .collect();
        for i in 0..w * h {
            if depth[i] >= far {
                // Sky: what SAO writes there is never seen (the sky is drawn over it and the
                // blur skips it), so it is not graded.
                sky_max = sky_max.max(s[i] as f64);
                continue;
            }
            count += 1;
            if !raw[i].is_finite() {
                nan += 1;
                continue;
            }
            sum_raw += raw[i] as f64;
            max_raw = max_raw.max(raw[i] as f64);
            if raw[i] as f64 > tol::SAO_RAW_MAX {
                over += 1;
            }
            if raw[i] < -0.01 {
                negative += 1;
            }
            sum_s += s[i] as f64;
            sum_r += r[i] as f64;
            if flat[i] {
                flat_s += s[i] as f64;
                flat_r += r[i] as f64;
                flat_n += 1;
            }
            if clean[i] {
                clean_s += s[i] as f64;
                clean_r += r[i] as f64;
                clean_n += 1;
            }
        }
        let (q, uneven) = quad_parity(&s, &depth, &clean, w, h);
        quads = (quads.0 + q, quads.1 + uneven);
        let bs = block_means(&s, &flat, w, h, 8);
        let br = block_means(&r, &flat, w, h, 8);
        for (k, (a, b)) in bs.iter().zip(&br).enumerate() {
            if let (Some(a), Some(b)) = (a, b) {
                let d = a - b;
                blocks_sq.0 += d * d;
                blocks_sq.1 += 1;
                if d.abs() > worst_block.0.abs() {
                    worst_block = (d, scene.name, (k % (w / 8)) * 8 + 4, (k / (w / 8)) * 8 + 4);
                }
            }
        }
        for p in &scene.probes {
            let a = scene.project(p.at);
            let b = match p.to {
                Some(to) => scene.project(to),
                None => a,
            };
            let grow = |(x, y): (usize, usize), d: isize| {
                (
                    (x as isize + d).clamp(0, w as isize - 1) as usize,
                    (y as isize + d).clamp(0, h as isize - 1) as usize,
                )
            };
            let (a, b) = if p.to.is_some() {
                (a, b)
            } else {
                (grow(a, -2), grow(b, 2))
            };
            probes.push(ProbeResult {
                scene: scene.name,
                name: p.name,
                kind: p.kind,
                got: rect_mean(&s, w, a, b, |v| v),
                raw: rect_mean(&raw, w, a, b, |v| if v.is_finite() { v } else { 0.0 }),
                expected: rect_mean(&r, w, a, b, |v| v),
            });
        }
        panels.push(Panel::absolute(w, h, r, s, Shade::Occlusion, 0.5));
    }
    Ok(Measured {
        panels,
        count,
        nan,
        over,
        negative,
        sum_s,
        sum_r,
        sum_raw,
        clean_s,
        clean_r,
        clean_n,
        flat_s,
        flat_r,
        flat_n,
        max_raw,
        blocks_sq,
        worst_block,
        probes,
        sky_max,
        quads,
    })
}

/// How much emptying mip levels 1–3 moves the output, summed over `scenes`: (student, reference).
fn mip_change(rig: &Rig, params: &AoSettings, scenes: &[SynthScene]) -> Result<(f64, f64)> {
    let (mut mip_s, mut mip_r) = (0.0f64, 0.0f64);
    for scene in scenes {
        let depth = scene.depth();
        let far = scene.camera.far;
        let run = |lesson, mips| run_sao(lesson, &rig.meshes, &scene.camera, &depth, params, mips);
        let change = |lesson| -> Result<f64> {
            let with = run(lesson, Mips::Filled)?;
            let without = run(lesson, Mips::Emptied)?;
            Ok(mean_abs_change(&with, &without, &depth, far))
        };
        mip_r += change(&rig.reference)?;
        mip_s += change(&rig.student)?;
    }
    Ok((mip_s, mip_r))
}

/// A probe's or scene's name (`scene.rs`) in the language `l`.
pub(super) fn place(l: &str, name: &str) -> String {
    use rust_i18n::t;
    match name {
        "corner" => t!("grade.verdict.place_corner", locale = l),
        "facing wall" => t!("grade.verdict.place_facing_wall", locale = l),
        "relief" => t!("grade.verdict.place_relief", locale = l),
        "open floor" => t!("grade.verdict.place_open_floor", locale = l),
        "wall-floor crease" => t!("grade.verdict.place_wall_floor_crease", locale = l),
        "crate-floor crease" => t!("grade.verdict.place_crate_floor_crease", locale = l),
        "open wall" => t!("grade.verdict.place_open_wall", locale = l),
        "step-floor crease" => t!("grade.verdict.place_step_floor_crease", locale = l),
        "wall beside the panel" => t!("grade.verdict.place_wall_beside_panel", locale = l),
        "open panel" => t!("grade.verdict.place_open_panel", locale = l),
        other => return other.to_string(),
    }
    .into_owned()
}

/// Grades the student's SAO pass of `rig`.
pub fn sao(rig: &Rig, params: &AoSettings) -> Verdict {
    let scenes = sao_scenes(SAO_SIZE);
    let Measured {
        panels,
        count,
        nan,
        over,
        negative,
        sum_s,
        sum_r,
        sum_raw,
        clean_s,
        clean_r,
        clean_n,
        flat_s,
        flat_r,
        flat_n,
        max_raw,
        blocks_sq,
        worst_block,
        probes,
        sky_max,
        quads,
    } = match measure(rig, params, &scenes) {
        Ok(m) => m,
        Err(e) => return Verdict::grader_error(&e),
    };
    let n = count.max(1) as f64;
    let valid = (count - nan).max(1) as f64;
    let (mean_s, mean_r, mean_raw) = (sum_s / valid, sum_r / valid, sum_raw / valid);
    let (cmean_s, cmean_r) = (
        clean_s / clean_n.max(1) as f64,
        clean_r / clean_n.max(1) as f64,
    );
    let (fmean_s, fmean_r) = (flat_s / flat_n.max(1) as f64, flat_r / flat_n.max(1) as f64);
    let rmse = (blocks_sq.0 / blocks_sq.1.max(1) as f64).sqrt();
    let mut metrics = BTreeMap::new();
    metrics.insert("mean".into(), mean_s);
    metrics.insert("mean_reference".into(), mean_r);
    metrics.insert("mean_clean".into(), cmean_s);
    metrics.insert("mean_clean_reference".into(), cmean_r);
    metrics.insert("mean_raw".into(), mean_raw);
    metrics.insert("mean_flat".into(), fmean_s);
    metrics.insert("mean_flat_reference".into(), fmean_r);
    metrics.insert("flat_fraction".into(), flat_n as f64 / count.max(1) as f64);
    metrics.insert("max_raw".into(), max_raw);
    metrics.insert("block_rmse".into(), rmse);
    metrics.insert("nan_fraction".into(), nan as f64 / n);
    metrics.insert("over_one_fraction".into(), over as f64 / n);
    metrics.insert("negative_fraction".into(), negative as f64 / n);
    metrics.insert("sky_max".into(), sky_max);
    let uneven = quads.1 as f64 / quads.0.max(1) as f64;
    metrics.insert("uneven_quad_fraction".into(), uneven);
    let mean_err = (fmean_s - fmean_r) / fmean_r.max(1e-6);
    let falloff_err = probes
        .iter()
        .filter(|p| p.kind == ProbeKind::Falloff)
        .map(|p| p.got / p.expected.max(1e-6) - 1.0)
        .fold(0.0f64, |a, b| if b.abs() > a.abs() { b } else { a });
    metrics.insert("mean_flat_error".into(), mean_err);
    metrics.insert("falloff_error".into(), falloff_err);
    for p in &probes {
        metrics.insert(format!("probe {} / {}", p.scene, p.name), p.got);
        metrics.insert(
            format!("probe {} / {} (reference)", p.scene, p.name),
            p.expected,
        );
    }
    let verdict = |passed: bool, message: Text| Verdict {
        passed,
        message,
        metrics: metrics.clone(),
        panels: panels.clone(),
    };
    let f2 = |v: f64| format!("{v:.2}");
    let f3 = |v: f64| format!("{v:.3}");
    // The reference must itself meet the probes, or every verdict below is meaningless.
    if let Some(p) = probes.iter().find(|p| match p.kind {
        ProbeKind::Crease => p.expected < 0.3,
        ProbeKind::Open => p.expected > tol::SAO_OPEN_ABS,
        ProbeKind::Falloff => p.expected < 0.05,
    }) {
        let got = f2(p.expected);
        return verdict(
            false,
            say!(
                l => "grade.verdict.sao_reference_off",
                got = got,
                probe = place(l, p.name),
                scene = place(l, p.scene)
            ),
        );
    }
    if nan as f64 > tol::SAO_BAD_PIXEL_FRACTION * n {
        let percent = format!("{:.1}", 100.0 * nan as f64 / n);
        return verdict(false, say!("grade.verdict.sao_nan", percent = percent));
    }
    let creases: Vec<&ProbeResult> = probes
        .iter()
        .filter(|p| p.kind == ProbeKind::Crease)
        .collect();
    if max_raw.abs() < 1e-3 && negative == 0 {
        return verdict(false, say!("grade.verdict.sao_zero"));
    }
    // Values above 1 are clamped by the engine's R8 target: they are a mistake when what is left
    // after clamping still differs (a sum that was never averaged), a detail when it does not.
    let overflow = over as f64 > tol::SAO_BAD_PIXEL_FRACTION * n;
    let distorted = mean_err.abs() > tol::SAO_MEAN_REL || falloff_err.abs() > tol::SAO_FALLOFF_REL;
    // The scenes always hold creases, so one is found to quote.
    let worst_crease = creases.iter().max_by(|a, b| a.raw.total_cmp(&b.raw));
    if let (true, Some(worst)) = (overflow && distorted, worst_crease) {
        let (got, expected, max) = (
            format!("{:.1}", worst.raw),
            f2(worst.expected),
            format!("{max_raw:.1}"),
        );
        return verdict(
            false,
            say!(
                l => "grade.verdict.sao_not_normalised",
                got = got,
                probe = place(l, worst.name),
                scene = place(l, worst.scene),
                expected = expected,
                max = max
            ),
        );
    }
    if let Some(p) = creases
        .iter()
        .find(|p| p.got < (tol::SAO_CREASE_FRACTION * p.expected).max(tol::SAO_CREASE_MIN))
    {
        let all_dark = creases.iter().all(|p| p.got < 0.25 * p.expected);
        let negative_terms = negative as f64 > 0.05 * n;
        let (got, expected) = (f2(p.got), f2(p.expected));
        let message = Text::new(|l| {
            let hint = if negative_terms {
                rust_i18n::t!("grade.verdict.sao_hint_negative", locale = l)
            } else if all_dark {
                rust_i18n::t!("grade.verdict.sao_hint_flipped_normal", locale = l)
            } else {
                rust_i18n::t!("grade.verdict.sao_hint_weak_crease", locale = l)
            };
            rust_i18n::t!(
                "grade.verdict.sao_crease",
                locale = l,
                probe = place(l, p.name),
                scene = place(l, p.scene),
                got = got,
                expected = expected,
                hint = hint
            )
            .into_owned()
        });
        return verdict(false, message);
    }
    if let Some(p) = probes.iter().find(|p| {
        p.kind == ProbeKind::Open && p.got > p.expected.min(tol::SAO_OPEN_ABS) + tol::SAO_OPEN_ABS
    }) {
        let (got, expected) = (f2(p.got), f2(p.expected));
        return verdict(
            false,
            say!(
                l => "grade.verdict.sao_open_occluded",
                probe = place(l, p.name),
                scene = place(l, p.scene),
                got = got,
                expected = expected
            ),
        );
    }
    for p in probes.iter().filter(|p| p.kind == ProbeKind::Falloff) {
        let ratio = p.got / p.expected.max(1e-6);
        if (ratio - 1.0).abs() > tol::SAO_FALLOFF_REL {
            let (got, expected) = (f3(p.got), f3(p.expected));
            let percent = format!("{:.0}", tol::SAO_FALLOFF_REL * 100.0);
            return verdict(
                false,
                if ratio > 1.0 {
                    say!(
                        l => "grade.verdict.sao_falloff_slow",
                        probe = place(l, p.name),
                        scene = place(l, p.scene),
                        got = got,
                        expected = expected,
                        percent = percent
                    )
                } else {
                    say!(
                        l => "grade.verdict.sao_falloff_fast",
                        probe = place(l, p.name),
                        scene = place(l, p.scene),
                        got = got,
                        expected = expected,
                        percent = percent
                    )
                },
            );
        }
    }
    if mean_err.abs() > tol::SAO_MEAN_REL {
        let (got, expected) = (f3(fmean_s), f3(fmean_r));
        let percent = format!("{:.0}", tol::SAO_MEAN_REL * 100.0);
        return verdict(
            false,
            if mean_err > 0.0 {
                say!(
                    "grade.verdict.sao_mean_strong",
                    got = got,
                    expected = expected,
                    percent = percent
                )
            } else {
                say!(
                    "grade.verdict.sao_mean_weak",
                    got = got,
                    expected = expected,
                    percent = percent
                )
            },
        );
    }
    if uneven > tol::SAO_UNEVEN_QUADS {
        return verdict(false, {
            let percent = format!("{:.0}", 100.0 * uneven);
            say!("grade.verdict.sao_no_smoothing", percent = percent)
        });
    }
    if rmse > tol::SAO_BLOCK_RMSE {
        let (rmse, diff) = (f3(rmse), format!("{:+.2}", worst_block.0));
        return verdict(
            false,
            say!(
                l => "grade.verdict.sao_rmse",
                rmse = rmse,
                tolerance = tol::SAO_BLOCK_RMSE,
                diff = diff,
                scene = place(l, worst_block.1),
                x = worst_block.2,
                y = worst_block.3
            ),
        );
    }
    // Far samples must come from the min mip chain (levels 1–3), as the lesson teaches: a shader that
    // reads level 0 for every sample passes the comparisons above on these small scenes, but thrashes
    // the texture cache on a real screen. Measured by how much the output moves when levels 1–3 are
    // emptied, relative to how much the project's own shader moves.
    let (mip_s, mip_r) = match mip_change(rig, params, &scenes) {
        Ok(change) => change,
        Err(e) => return Verdict::grader_error(&e),
    };
    let mip_use = mip_s / mip_r.max(1e-9);
    let (aniso_s, aniso_r) = match super::sao_isotropy::anisotropy(rig, params, SAO_SIZE) {
        Ok(a) => a,
        Err(e) => return Verdict::grader_error(&e),
    };
    let mut metrics = metrics.clone();
    metrics.insert("anisotropy".into(), aniso_s);
    metrics.insert("anisotropy_reference".into(), aniso_r);
    metrics.insert("mip_change".into(), mip_s / scenes.len() as f64);
    metrics.insert("mip_change_reference".into(), mip_r / scenes.len() as f64);
    metrics.insert("mip_use".into(), mip_use);
    let verdict = |passed: bool, message: Text| Verdict {
        passed,
        message,
        metrics: metrics.clone(),
        panels: panels.clone(),
    };
    if mip_r / scenes.len() as f64 > tol::SAO_MIP_CHANGE_MIN && mip_use < tol::SAO_MIP_USE {
        let got = format!("{:.4}", mip_s / scenes.len() as f64);
        let reference = format!("{:.4}", mip_r / scenes.len() as f64);
        return verdict(
            false,
            say!(
                "grade.verdict.sao_no_mips",
                got = got,
                reference = reference
            ),
        );
    }
    if aniso_s > tol::SAO_ANISOTROPY {
        let (spread, reference) = (
            format!("{:.0}", 100.0 * aniso_s),
            format!("{:.0}", 100.0 * aniso_r),
        );
        return verdict(
            false,
            say!(
                "grade.verdict.sao_anisotropy",
                spread = spread,
                reference = reference
            ),
        );
    }
    if mip_r / scenes.len() as f64 > tol::SAO_MIP_CHANGE_MIN && mip_use > tol::SAO_MIP_USE_MAX {
        let got = format!("{:.4}", mip_s / scenes.len() as f64);
        let reference = format!("{:.4}", mip_r / scenes.len() as f64);
        return verdict(
            false,
            say!(
                "grade.verdict.sao_near_mips",
                got = got,
                reference = reference
            ),
        );
    }
    let creases = creases
        .iter()
        .map(|p| format!("{:.2}", p.got))
        .collect::<Vec<_>>()
        .join("/");
    let (mean, reference, rmse) = (f3(fmean_s), f3(fmean_r), f3(rmse));
    let max = format!("{max_raw:.1}");
    let message = Text::new(|l| {
        let falloff = probes
            .iter()
            .filter(|p| p.kind == ProbeKind::Falloff)
            .map(|p| {
                let (got, expected) = (f3(p.got), f3(p.expected));
                rust_i18n::t!(
                    "grade.verdict.sao_falloff_pair",
                    locale = l,
                    got = got,
                    expected = expected
                )
                .into_owned()
            })
            .collect::<Vec<_>>()
            .join(", ");
        let note = if overflow {
            rust_i18n::t!(
                "grade.verdict.sao_pass_overflow_note",
                locale = l,
                max = max
            )
            .into_owned()
        } else {
            String::new()
        };
        rust_i18n::t!(
            "grade.verdict.sao_pass",
            locale = l,
            mean = mean,
            reference = reference,
            rmse = rmse,
            creases = creases,
            falloff = falloff,
            note = note
        )
        .into_owned()
    });
    verdict(true, message)
}
