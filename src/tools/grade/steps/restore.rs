//! The restore step (`sao_restore_depth.frag`): a 256×128 DEPTH_COMPONENT32 buffer of known depths
//! (log-spaced from near to far, scrambled over the image, 2×2 blocks whose nearest texel moves
//! around, sky and half-sky blocks) against the exact f64 inverse of the projection of the nearest of
//! each 2×2 block, within float precision. Failures are matched against what common mistakes would
//! output (max, no ×2, raw depth, wrong sign, D' = 2D + 1, the ×0.01 debug scale, average, one
//! texel) to name the mistake.

use crate::gl::{Texture, TextureDesc};
use crate::i18n::Text;
use crate::math::depth::{delinearize, linearize};
use crate::math::{Camera, DepthMode};
use crate::tools::grade::measure::matches;
use crate::tools::grade::picture::{Panel, Shade};
use crate::tools::grade::rig::{Rig, Verdict};
use crate::tools::grade::say::say;
use crate::tools::grade::tol;
use std::collections::BTreeMap;

/// Size of the main depth buffer the step restores (the output is half of it).
pub const MAIN_SIZE: (u32, u32) = (256, 128);

/// Depth-buffer value of a point at view distance `z` (the course's D32 projection, f64).
fn depth_of(z: f64, n: f64, f: f64) -> f64 {
    delinearize(DepthMode::D32, z, n, f)
}

/// Grades the student's restore pass of `rig` for the camera `cam`.
pub fn restore(rig: &Rig, cam: &Camera) -> Verdict {
    let (w, h) = (MAIN_SIZE.0 as usize, MAIN_SIZE.1 as usize);
    let (bw, bh) = (w / 2, h / 2);
    let nb = bw * bh;
    let (n, f) = (cam.near as f64, cam.far as f64);
    let (zmin, zmax) = (n * 1.05, 0.95 * f / 1.4);
    let factors = [1.0, 1.06, 1.18, 1.4];
    let corners = [(0usize, 0usize), (1, 0), (1, 1), (0, 1)];
    // One block (the middle) is exactly 10 m away, for messages.
    let probe = (bh / 2) * bw + bw / 2;
    let mut d = vec![0f32; w * h];
    for by in 0..bh {
        for bx in 0..bw {
            let i = by * bw + bx;
            // Distances scrambled over the image, so that reading the wrong texels shows.
            let k = (i * 7919) % nb;
            let z = if i == probe {
                10.0
            } else {
                zmin * (zmax / zmin).powf(k as f64 / (nb - 1) as f64)
            };
            let (rot, step) = (i % 4, if (i / 4) % 2 == 1 { 3 } else { 1 });
            for (j, (dx, dy)) in corners.iter().enumerate() {
                let fi = (j * step + rot) % 4;
                let mut dv = depth_of(z * factors[fi], n, f);
                // Some blocks are sky, some half sky (the nearest texel still wins).
                if i % 37 == 0 || (i % 37 == 1 && fi >= 2) {
                    dv = 1.0;
                }
                d[(2 * by + dy) * w + 2 * bx + dx] = dv as f32;
            }
        }
    }
    let depth = match Texture::new(
        &rig.gl,
        TextureDesc::target("grade depth", w as u32, h as u32, glow::DEPTH_COMPONENT32),
    ) {
        Ok(t) => t,
        Err(e) => return Verdict::grader_error(&e),
    };
    if let Err(e) = depth.upload_f32(0, 1, &d) {
        return Verdict::grader_error(&e);
    }
    // What the shader really reads: the values as stored (32-bit unorm).
    let stored: Vec<f64> = depth.read_f32(0, 1).iter().map(|v| *v as f64).collect();
    rig.student.restore_depth(&rig.meshes, &depth);
    let got = rig.student.targets.tex_depth.read_f32(0, 1);

    let at = |x: usize, y: usize| stored[y.min(h - 1) * w + x.min(w - 1)];
    let block = |bx: usize, by: usize, pick: fn(f64, f64) -> f64| {
        let (x, y) = (2 * bx, 2 * by);
        pick(
            pick(at(x, y), at(x + 1, y)),
            pick(at(x, y + 1), at(x + 1, y + 1)),
        )
    };
    let lin = |dv: f64| linearize(DepthMode::D32, dv.min(1.0), n, f);
    let b = (f + n) / (f - n);
    let bound = |dv: f64| {
        tol::RESTORE_ULPS * f32::EPSILON as f64 * (1.0 + b / ((2.0 * dv - 1.0) - b).abs())
    };
    let mut expected = vec![0f64; nb];
    let mut ratio = vec![0f32; nb];
    let mut worst = (0.0f64, 0usize);
    let mut bad = 0usize;
    let mut bad_sky = 0usize;
    let mut nonfinite = 0usize;
    for by in 0..bh {
        for bx in 0..bw {
            let i = by * bw + bx;
            let dmin = block(bx, by, f64::min);
            let e = lin(dmin);
            expected[i] = e;
            let g = got[i] as f64;
            let r = if g.is_finite() {
                (g - e).abs() / e / bound(dmin)
            } else {
                nonfinite += 1;
                f64::INFINITY
            };
            ratio[i] = r as f32;
            if r > 1.0 {
                bad += 1;
                if dmin >= 1.0 {
                    bad_sky += 1;
                }
            }
            if r > worst.0 || (r.is_nan() && !worst.0.is_nan()) {
                worst = (r, i);
            }
        }
    }
    let mut metrics = BTreeMap::new();
    metrics.insert("worst_error_over_tolerance".into(), worst.0);
    metrics.insert("texels_out_of_tolerance".into(), bad as f64);
    metrics.insert("probe_10m".into(), got[probe] as f64);
    metrics.insert(
        crate::tools::grade::rig::NONFINITE_METRIC.into(),
        nonfinite as f64 / nb as f64,
    );
    let panels = vec![Panel {
        width: bw,
        height: bh,
        expected: expected.iter().map(|v| *v as f32).collect(),
        actual: got.clone(),
        shade: Shade::Distance {
            near: cam.near,
            far: cam.far,
        },
        diff: ratio.iter().map(|r| (r / 2.0).min(1.0)).collect(),
    }];
    let verdict = |passed: bool, message: Text| Verdict {
        passed,
        message,
        metrics: metrics.clone(),
        panels: panels.clone(),
        parts: Vec::new(),
    };
    if bad == 0 {
        let worst = format!("{:.2}", worst.0);
        return verdict(
            true,
            say!("grade.verdict.restore_pass", texels = nb, worst = worst),
        );
    }
    let p10 = got[probe];
    if got.iter().all(|v| *v == got[0]) {
        return verdict(
            false,
            say!("grade.verdict.restore_constant", value = got[0]),
        );
    }
    // Recognise common mistakes by predicting what they would output.
    let mut hypotheses: Vec<(&str, Vec<f64>)> = Vec::new();
    let per_block = |g: &dyn Fn(usize, usize) -> f64| -> Vec<f64> {
        (0..nb).map(|i| g(i % bw, i / bw)).collect()
    };
    hypotheses.push(("max", per_block(&|bx, by| lin(block(bx, by, f64::max)))));
    hypotheses.push((
        "no-x2",
        per_block(&|bx, by| {
            lin(at(bx, by)
                .min(at(bx + 1, by))
                .min(at(bx, by + 1))
                .min(at(bx + 1, by + 1)))
        }),
    ));
    hypotheses.push(("raw", per_block(&|bx, by| block(bx, by, f64::min))));
    hypotheses.push(("negative", expected.iter().map(|e| -e).collect()));
    let a = -2.0 * f * n / (f - n);
    hypotheses.push((
        "2D+1",
        per_block(&|bx, by| a / ((2.0 * block(bx, by, f64::min) + 1.0) - b)),
    ));
    hypotheses.push(("x0.01", expected.iter().map(|e| e * 0.01).collect()));
    hypotheses.push((
        "average",
        per_block(&|bx, by| {
            let (x, y) = (2 * bx, 2 * by);
            lin((at(x, y) + at(x + 1, y) + at(x, y + 1) + at(x + 1, y + 1)) / 4.0)
        }),
    ));
    hypotheses.push(("one-texel", per_block(&|bx, by| lin(at(2 * bx, 2 * by)))));
    let found = hypotheses
        .iter()
        .find(|(_, p)| matches(&got, p))
        .map(|(name, _)| *name);
    let (got4, got3) = (format!("{p10:.4}"), format!("{p10:.3}"));
    let message = match found {
        Some("max") => say!("grade.verdict.restore_max"),
        Some("no-x2") => say!("grade.verdict.restore_no_x2"),
        Some("raw") => say!("grade.verdict.restore_raw", got = got4),
        Some("negative") => say!("grade.verdict.restore_negative", got = got3),
        Some("2D+1") => say!("grade.verdict.restore_2d_plus_1", got = got3),
        Some("x0.01") => say!("grade.verdict.restore_debug_scale", got = got3),
        Some("average") => say!("grade.verdict.restore_average"),
        Some("one-texel") => say!("grade.verdict.restore_one_texel"),
        _ => {
            let i = worst.1;
            let (bx, by) = (i % bw, i / bw);
            let expected_i = format!("{:.3}", expected[i]);
            if nonfinite > 0 {
                say!(
                    "grade.verdict.restore_nan",
                    count = nonfinite,
                    texels = nb,
                    x = bx,
                    y = by,
                    expected = expected_i
                )
            } else if bad == bad_sky {
                say!(
                    "grade.verdict.restore_sky",
                    far = f,
                    got = got[i],
                    x = bx,
                    y = by
                )
            } else if (p10 as f64 - 10.0).abs() > 10.0 * bound(depth_of(10.0, n, f)) * 10.0 {
                say!(
                    "grade.verdict.restore_wrong_at_10m",
                    got = got4,
                    bad = bad,
                    texels = nb,
                    at = expected_i,
                    worst = got[i]
                )
            } else {
                let ratio = format!("{:.1}", worst.0);
                say!(
                    "grade.verdict.restore_out_of_tolerance",
                    bad = bad,
                    texels = nb,
                    at = expected_i,
                    x = bx,
                    y = by,
                    got = got[i],
                    ratio = ratio
                )
            }
        }
    };
    verdict(false, message)
}
