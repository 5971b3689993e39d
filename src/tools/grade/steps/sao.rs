//! The SAO step (`sao.frag`): three ray-cast box scenes (a wall on a floor with a crate; a wall
//! seen head-on with a step; a wall seen head-on with a raised panel), 240×160, the same mip chain
//! for both shaders (`sao_measure`). Checked: NaN and Inf; values above 1 (not normalised, when
//! clamping does not hide it); creases occluded (≥ half the reference's); weak occlusion not the
//! reference's times one factor (a sum never divided by N); the same occlusion in every direction
//! (`sao_isotropy`; told here when it is stretched along x or y, an aspect correction wrong or
//! missing, which distorts every measure after it); open flat surfaces ≈ 0; the occlusion of a band
//! beside the panel (the falloff's shape); the mean and the RMSE of 8×8 block means over pixels
//! facing the camera and away from depth edges (the per-pixel noise may differ, and the lesson's
//! listing has no mip-bias or edge guard, which this port's `sao.frag` adds: on grazing surfaces and
//! at depth edges they legitimately differ); the 2×2 smoothing (diagonal pixels of each quad facing
//! the camera end up equal), from the lesson that teaches it on; the direction check again, for a
//! spread not along an axis; and that far samples come from mip levels 1–3 and near ones from
//! level 0 (the output must move when levels 1–3 are emptied, about as much as the project's does:
//! not much less, not far more); and that fully occluded pixels reach 1 (the intensity raised a
//! hundredfold: where the project's output is 1, the student's must be too); last, that samples
//! beyond the sampling radius count 0 (the wall beside a panel keeps its occlusion with a near post
//! in the disc, `sao_reach`). At `--level lesson`, also the numbers the pages fix (`sao_details`).

use super::sao_measure::{measure, mip_change, saturation, Measured, ProbeResult};
use super::sao_parts::{Parts, NORMAL, OCCLUSION, SAMPLING, SMOOTHING, VIEW};
use crate::ao::AoSettings;
use crate::i18n::Text;
use crate::tools::grade::args::Level;
use crate::tools::grade::rig::{Rig, Verdict};
use crate::tools::grade::say::say;
use crate::tools::grade::scene::{sao_scenes, ProbeKind};
use crate::tools::grade::tol;
use std::collections::BTreeMap;

/// Size of `texSAODepth` level 0 in the SAO step (3:2, so that x and y cannot be swapped unseen).
pub const SAO_SIZE: (u32, u32) = (240, 160);

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

/// The quartiles of `v` (at least 4 values).
fn quartiles(v: &[f64]) -> Option<[f64; 3]> {
    if v.len() < 4 {
        return None;
    }
    let mut v = v.to_vec();
    v.sort_by(f64::total_cmp);
    Some([1, 2, 3].map(|k| v[k * (v.len() - 1) / 4]))
}

/// Whether the occlusion is the reference's times one factor wherever it is weak (the student's 8×8
/// block means ÷ the reference's, `ratios`): the sum scaled wrong after the loop, most often never
/// divided by the sample count `samples`. Adds the quartiles to `metrics`.
fn scaled(ratios: &[f64], samples: u32, metrics: &mut BTreeMap<String, f64>) -> Option<Text> {
    let [lo, mid, hi] = quartiles(ratios)?;
    // The quartiles' ratio is reported only: a wrong falloff spreads the ratios about as little.
    metrics.insert("scale_blocks".into(), ratios.len() as f64);
    metrics.insert("scale_median".into(), mid);
    metrics.insert("scale_quartiles".into(), hi / lo.max(1e-9));
    if mid < tol::SAO_SCALE_MIN {
        return None;
    }
    let times = format!("{mid:.1}");
    Some(if (mid / samples as f64 - 1.0).abs() < 0.25 {
        say!("grade.verdict.sao_scaled_count", times = times, n = samples)
    } else {
        say!("grade.verdict.sao_scaled", times = times)
    })
}

/// Whether `source` takes the cross product with the y derivative first (`cross(dFdy(…), …)`,
/// `cross(dpdy, …)`, whatever the names): the lesson's order is x first.
fn cross_reversed(source: &str) -> bool {
    source.split("cross").skip(1).any(|rest| {
        let args = rest.trim_start().strip_prefix('(').unwrap_or("");
        let first: String = args
            .chars()
            .take_while(|c| *c != ',')
            .filter(|c| !c.is_whitespace())
            .collect();
        let first = first.to_ascii_lowercase();
        first.contains("dfdy")
            || ["dy", "dpdy", "ddy"].contains(&first.as_str())
            || first.ends_with("_dy")
    })
}

/// Grades the student's SAO pass of `rig` as lesson step `lesson` has it (`None`: finished): before
/// `SAO_SMOOTHING_STEP` the 2×2 smoothing is not taught yet, so it is neither asked for nor told.
/// `level`: `Lesson` also asks what the pages teach beyond the course's listing (`sao_lesson`);
/// `source`: the student's file, read for derivatives inside branches.
pub fn sao(
    rig: &Rig,
    params: &AoSettings,
    lesson: Option<u32>,
    level: Level,
    source: Option<&str>,
) -> Verdict {
    let smoothing_step = crate::tools::lesson::SAO_SMOOTHING_STEP;
    let smoothing_taught = lesson.is_none_or(|n| n >= smoothing_step);
    let scenes = sao_scenes(SAO_SIZE);
    let Measured {
        panels,
        count,
        nan,
        inf,
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
        block_ratios,
        quads,
        pattern,
        edge,
        straddle,
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
    metrics.insert(
        crate::tools::grade::rig::NONFINITE_METRIC.into(),
        nan as f64 / n,
    );
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
    let scale = scaled(&block_ratios, params.samples, &mut metrics);
    // The same occlusion in every direction: told early when it is stretched along an axis (an
    // aspect correction wrong or missing distorts every measure after this one).
    let (aniso_s, aniso_r, stretched) = match super::sao_isotropy::anisotropy(rig, params, SAO_SIZE)
    {
        Ok(a) => a,
        Err(e) => return Verdict::grader_error(&e),
    };
    metrics.insert("anisotropy".into(), aniso_s);
    metrics.insert("anisotropy_reference".into(), aniso_r);
    // Occluders beyond the radius count 0: the band beside the panel keeps its occlusion with a
    // near post in the disc (`sao_reach`).
    let (near_s, near_r) = match super::sao_reach::beside_a_near_post(rig, params, SAO_SIZE) {
        Ok(v) => v,
        Err(e) => return Verdict::grader_error(&e),
    };
    metrics.insert("beside_near_post".into(), near_s);
    metrics.insert("beside_near_post_reference".into(), near_r);
    let (spread, spread_reference) = (
        format!("{:.0}", 100.0 * aniso_s),
        format!("{:.0}", 100.0 * aniso_r),
    );
    let f2 = |v: f64| format!("{v:.2}");
    let f3 = |v: f64| format!("{v:.3}");
    // The reference must itself meet the probes, or every verdict below is meaningless.
    if let Some(p) = probes.iter().find(|p| match p.kind {
        ProbeKind::Crease => p.expected < 0.3,
        ProbeKind::Open => p.expected > tol::SAO_OPEN_ABS,
        ProbeKind::Falloff => p.expected < 0.05,
    }) {
        let got = f2(p.expected);
        let mut v = Verdict::fail(say!(
            l => "grade.verdict.sao_reference_off",
            got = got,
            probe = place(l, p.name),
            scene = place(l, p.scene)
        ));
        v.metrics = metrics;
        v.panels = panels;
        return v;
    }
    let mut parts = Parts::new(smoothing_taught);
    // From the source: llvmpipe gives a derivative inside a branch the expected value, so no
    // picture shows it. The course's listing takes dFdx(occlusion) inside its `if` (erratum 22).
    if let Some((line, in_smoothing)) = source.and_then(super::sao_lesson::derivative_in_branch) {
        let message = say!("grade.verdict.sao_derivative_in_branch", line = line);
        if in_smoothing {
            parts.fail_keeping(SMOOTHING, message, Some(22));
        } else {
            parts.fail(NORMAL, message);
        }
    }
    let creases: Vec<&ProbeResult> = probes
        .iter()
        .filter(|p| p.kind == ProbeKind::Crease)
        .collect();
    // Values above 1 are clamped by the engine's R8 target: they are a mistake when what is left
    // after clamping still differs (a sum that was never averaged), a detail when it does not.
    let overflow = over as f64 > tol::SAO_BAD_PIXEL_FRACTION * n;
    let distorted = mean_err.abs() > tol::SAO_MEAN_REL || falloff_err.abs() > tol::SAO_FALLOFF_REL;
    // The scenes always hold creases, so one is found to quote.
    let worst_crease = creases.iter().max_by(|a, b| a.raw.total_cmp(&b.raw));
    if nan as f64 > tol::SAO_BAD_PIXEL_FRACTION * n {
        let percent = format!("{:.1}", 100.0 * nan as f64 / n);
        // Inf is a division by zero or an overflow, in what is written; NaN alone, most often
        // normalize() of a zero vector.
        if inf > 0 {
            let inf = format!("{:.1}", 100.0 * inf as f64 / n);
            parts.break_all(
                VIEW,
                say!("grade.verdict.sao_inf", percent = percent, inf = inf),
            );
        } else {
            parts.break_all(NORMAL, say!("grade.verdict.sao_nan", percent = percent));
        }
    } else if max_raw.abs() < 1e-3 && negative == 0 {
        parts.break_all(OCCLUSION, say!("grade.verdict.sao_zero"));
    } else if let (true, Some(worst)) = (overflow && distorted, worst_crease) {
        let (got, expected, max) = (
            format!("{:.1}", worst.raw),
            f2(worst.expected),
            format!("{max_raw:.1}"),
        );
        parts.break_all(
            VIEW,
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
        .filter(|_| !parts.broken())
    {
        let all_dark = creases.iter().all(|p| p.got < 0.25 * p.expected);
        let negative_terms = negative as f64 > 0.05 * n;
        let flipped = all_dark && !negative_terms;
        // A z of the wrong sign in GetViewSpacePosition mirrors the scene, which reverses the cross
        // product: the output is that of a reversed cross product, so the source tells which.
        let cross_reversed = source.is_some_and(cross_reversed);
        let (got, expected) = (f2(p.got), f2(p.expected));
        let message = Text::new(|l| {
            let hint = if negative_terms {
                rust_i18n::t!("grade.verdict.sao_hint_negative", locale = l)
            } else if flipped && !cross_reversed {
                rust_i18n::t!("grade.verdict.sao_hint_flipped_z", locale = l)
            } else if flipped {
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
        // A normal pointing away from the camera finds no occluder anywhere: nothing after it
        // can be measured.
        if flipped {
            parts.break_all(NORMAL, message);
        } else {
            parts.fail(OCCLUSION, message);
        }
    }
    // Open surfaces first: a bias of the wrong sign (vn + BIAS) occludes every open surface, which
    // also makes the weak occlusion look scaled.
    let opens: Vec<&ProbeResult> = probes
        .iter()
        .filter(|p| p.kind == ProbeKind::Open)
        .collect();
    if !parts.broken() && opens.iter().all(|p| p.got > tol::SAO_OPEN_ALL_DARK) {
        let got = opens
            .iter()
            .map(|p| f2(p.got))
            .collect::<Vec<_>>()
            .join("/");
        parts.fail(OCCLUSION, say!("grade.verdict.sao_bias_sign", got = got));
    }
    if let Some(p) = probes
        .iter()
        .find(|p| {
            p.kind == ProbeKind::Open
                && p.got > p.expected.min(tol::SAO_OPEN_ABS) + tol::SAO_OPEN_ABS
        })
        .filter(|_| !parts.broken())
    {
        let (got, expected) = (f2(p.got), f2(p.expected));
        parts.fail(
            OCCLUSION,
            say!(
                l => "grade.verdict.sao_open_occluded",
                probe = place(l, p.name),
                scene = place(l, p.scene),
                got = got,
                expected = expected
            ),
        );
    }
    let scale_wrong = scale.is_some();
    if let Some(message) = scale.filter(|_| !parts.broken()) {
        parts.fail(OCCLUSION, message);
    }
    if !parts.broken() && stretched && aniso_s > tol::SAO_ANISOTROPY {
        // A disc stretched on screen (the course's own form, erratum 20) leaves the occlusion's
        // measures within their tolerances; positions rebuilt with a wrong aspect ratio distort
        // every one of them.
        let disc_only = !scale_wrong
            && mean_err.abs() <= tol::SAO_MEAN_REL
            && falloff_err.abs() <= tol::SAO_FALLOFF_REL;
        if disc_only {
            parts.fail_keeping(
                SAMPLING,
                say!(
                    "grade.verdict.sao_stretched_disc",
                    spread = spread,
                    reference = spread_reference
                ),
                Some(20),
            );
        } else {
            parts.break_all(
                NORMAL,
                say!(
                    "grade.verdict.sao_stretched_positions",
                    spread = spread,
                    reference = spread_reference
                ),
            );
        }
    }
    if parts.broken() {
        return parts.verdict(say!("grade.verdict.part_pass"), metrics, panels);
    }
    for p in probes.iter().filter(|p| p.kind == ProbeKind::Falloff) {
        let ratio = p.got / p.expected.max(1e-6);
        if (ratio - 1.0).abs() > tol::SAO_FALLOFF_REL {
            let (got, expected) = (f3(p.got), f3(p.expected));
            let percent = format!("{:.0}", tol::SAO_FALLOFF_REL * 100.0);
            parts.fail(
                OCCLUSION,
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
        parts.fail(
            OCCLUSION,
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
    if smoothing_taught && uneven > tol::SAO_UNEVEN_QUADS {
        let percent = format!("{:.0}", 100.0 * uneven);
        parts.fail(
            SMOOTHING,
            say!("grade.verdict.sao_no_smoothing", percent = percent),
        );
    }
    if rmse > tol::SAO_BLOCK_RMSE {
        let (rmse, diff) = (f3(rmse), format!("{:+.2}", worst_block.0));
        parts.fail(
            VIEW,
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
    let (saturated, saturated_n) = match saturation(rig, params, &scenes) {
        Ok(s) => s,
        Err(e) => return Verdict::grader_error(&e),
    };
    metrics.insert("saturated_median".into(), saturated);
    metrics.insert("mip_change".into(), mip_s / scenes.len() as f64);
    metrics.insert("mip_change_reference".into(), mip_r / scenes.len() as f64);
    metrics.insert("mip_use".into(), mip_use);
    let mips_read = mip_r / scenes.len() as f64 > tol::SAO_MIP_CHANGE_MIN;
    let (mip_got, mip_reference) = (
        format!("{:.4}", mip_s / scenes.len() as f64),
        format!("{:.4}", mip_r / scenes.len() as f64),
    );
    // The mip use is measured against the reference's: only meaningful when the occlusion term is.
    let mips_read = mips_read && !parts.failed(OCCLUSION);
    if mips_read && mip_use < tol::SAO_MIP_USE {
        parts.fail(
            SAMPLING,
            say!(
                "grade.verdict.sao_no_mips",
                got = mip_got,
                reference = mip_reference
            ),
        );
    }
    if saturated_n > 0 && saturated < tol::SAO_SATURATED_MEDIAN {
        let got = format!("{saturated:.2}");
        parts.fail(
            OCCLUSION,
            say!("grade.verdict.sao_not_saturated", got = got),
        );
    }
    if aniso_s > tol::SAO_ANISOTROPY {
        parts.fail(
            SAMPLING,
            say!(
                "grade.verdict.sao_anisotropy",
                spread = spread,
                reference = spread_reference
            ),
        );
    }
    if mips_read && mip_use > tol::SAO_MIP_USE_MAX {
        parts.fail(
            SAMPLING,
            say!(
                "grade.verdict.sao_near_mips",
                got = mip_got,
                reference = mip_reference
            ),
        );
    }
    if (near_s / near_r.max(1e-6) - 1.0).abs() > tol::SAO_NEAR_POST_REL {
        let (got, expected) = (f3(near_s), f3(near_r));
        let percent = format!("{:.0}", tol::SAO_NEAR_POST_REL * 100.0);
        parts.fail(
            OCCLUSION,
            say!(
                "grade.verdict.sao_far_occluders",
                got = got,
                expected = expected,
                percent = percent
            ),
        );
    }
    // What the pages add to the listing, measured against the reference only where the occlusion
    // term itself agrees with it (a wrong term darkens edges and floors for its own reason).
    if level == Level::Lesson && !parts.failed(OCCLUSION) {
        let details = match super::sao_details::details(rig, params, SAO_SIZE) {
            Ok(d) => d,
            Err(e) => return Verdict::grader_error(&e),
        };
        let (edge_s, edge_r, _) = edge;
        let (straddle_s, straddle_r, straddle_n) = straddle;
        metrics.insert("edge_mean".into(), edge_s);
        metrics.insert("edge_mean_reference".into(), edge_r);
        metrics.insert("straddle_mean".into(), straddle_s);
        metrics.insert("straddle_mean_reference".into(), straddle_r);
        if straddle_n > 0 && straddle_s - straddle_r > tol::SAO_EDGE_DARKER {
            let (got, expected) = (f3(straddle_s), f3(straddle_r));
            parts.fail(
                NORMAL,
                say!("grade.verdict.sao_outlines", got = got, expected = expected),
            );
        }
        let ((far_s, far_r), (near_s, near_r)) =
            match super::sao_lesson::low_floor(rig, params, SAO_SIZE) {
                Ok(v) => v,
                Err(e) => return Verdict::grader_error(&e),
            };
        metrics.insert("low_floor_far".into(), far_s);
        metrics.insert("low_floor_far_reference".into(), far_r);
        metrics.insert("low_floor_near".into(), near_s);
        metrics.insert("low_floor_near_reference".into(), near_r);
        // Off-centre taps darken the band beside every depth edge and, with no edge guard, the far
        // floor seen at a grazing angle.
        if far_s - far_r > tol::SAO_LOW_FLOOR || edge_s - edge_r > tol::SAO_EDGE_BAND {
            let message = if far_s - far_r > tol::SAO_LOW_FLOOR {
                let (got, expected) = (f3(far_s), f3(far_r));
                say!(
                    "grade.verdict.sao_no_texel_snap",
                    got = got,
                    expected = expected
                )
            } else {
                let (got, expected) = (f3(edge_s), f3(edge_r));
                say!(
                    "grade.verdict.sao_no_texel_snap_edges",
                    got = got,
                    expected = expected
                )
            };
            parts.fail(SAMPLING, message);
        } else if near_s - near_r > tol::SAO_LOW_FLOOR {
            let (got, expected) = (f3(near_s), f3(near_r));
            parts.fail(
                OCCLUSION,
                say!(
                    "grade.verdict.sao_no_mip_bias",
                    got = got,
                    expected = expected
                ),
            );
        }
        let quads = pattern.quads.max(1) as f64;
        let share = |n: usize| n as f64 / quads;
        metrics.insert("quads_smeared".into(), share(pattern.smeared));
        metrics.insert("quads_halved".into(), share(pattern.halved));
        metrics.insert("quads_unsmoothed".into(), share(pattern.unsmoothed));
        let percent = |n: usize| format!("{:.0}", 100.0 * share(n));
        if !smoothing_taught {
        } else if share(pattern.smeared) > tol::SAO_PATTERN_FRACTION {
            let percent = percent(pattern.smeared);
            parts.fail(
                SMOOTHING,
                say!("grade.verdict.sao_smoothing_smeared", percent = percent),
            );
        } else if share(pattern.halved) > tol::SAO_PATTERN_FRACTION {
            let percent = percent(pattern.halved);
            parts.fail(
                SMOOTHING,
                say!("grade.verdict.sao_smoothing_halved", percent = percent),
            );
        } else if share(pattern.unsmoothed) > tol::SAO_PATTERN_FRACTION {
            let percent = percent(pattern.unsmoothed);
            parts.fail(
                SMOOTHING,
                say!("grade.verdict.sao_no_smoothing", percent = percent),
            );
        }
        // After the checks above, whose messages name the pages' missing pieces first.
        let judged = super::sao_details::judge(&details, smoothing_taught, |p| parts.failed(p));
        for (part, message) in judged {
            parts.fail(part, message);
        }
        metrics.extend(details);
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
        let mut note = if overflow {
            rust_i18n::t!(
                "grade.verdict.sao_pass_overflow_note",
                locale = l,
                max = max
            )
            .into_owned()
        } else {
            String::new()
        };
        if !smoothing_taught {
            note.push_str(&rust_i18n::t!(
                "grade.verdict.sao_pass_smoothing_later_note",
                locale = l,
                lesson = smoothing_step
            ));
        }
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
    parts.verdict(message, metrics, panels)
}
