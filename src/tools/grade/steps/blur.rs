//! The blur step (`sao_blur.frag`): the project's SAO output of the first scene, plus a panel with a
//! depth edge, a noisy flat surface and sky; the edge must stay sharp, the flat surface must be
//! smoothed with its mean kept, nothing may leak into the sky, the response to a single occluded
//! texel must have the taps of the lesson (every blurScale texels, blurRadius each side) and be
//! mirror-symmetric, taps past the border must read the border texel (clamped, as the lesson asks:
//! within its reach of the border, the output must equal the shader's own beside an equally
//! occluded band inside the texture), taps across a small depth step must weigh what the lesson's
//! edge weight gives (measured from the shader's own output, whatever its Gaussian weights), and
//! the RMSE is bounded against the closer of two references: the project's `sao_blur.frag` and the
//! same blur with the course's table (`course_blur`: McGuire and Mara's `SAO_blur.pix` adds 0.3 to
//! the weight of every tap but the centre, and the course folded that into its table, so both are
//! the reference's behaviour). The buffers are wider than high, so x and y
//! cannot be swapped unseen.

use crate::ao::AoSettings;
use crate::i18n::Text;
use crate::tools::grade::measure::{as_r8, mean_and_std};
use crate::tools::grade::passes::{run_blur, run_sao, Mips};
use crate::tools::grade::picture::{Panel, Shade};
use crate::tools::grade::rig::{Rig, Verdict};
use crate::tools::grade::say::say;
use crate::tools::grade::scene::sao_scenes;
use crate::tools::grade::tol;
use anyhow::Result;
use std::collections::BTreeMap;

/// Size of the buffers in the blur step (wider than high, so that x and y cannot be swapped unseen).
pub const BLUR_SIZE: (u32, u32) = (160, 112);

/// A hash in [0, 1) for reproducible noise.
fn noise(x: usize, y: usize) -> f32 {
    let mut v = (x as u32).wrapping_mul(0x8da6_b343) ^ (y as u32).wrapping_mul(0xd816_3841);
    v ^= v >> 13;
    v = v.wrapping_mul(0x5bd1_e995);
    v ^= v >> 15;
    (v >> 8) as f32 / (1u32 << 24) as f32
}

/// The blur's synthetic panel (rows bottom-up): lower half a noisy flat surface at 5 m with sky on
/// its right, the sky's occlusion noisy too (the SAO pass writes 0 there, but a sky texel must come
/// back unchanged whatever it holds: blurred among themselves, noisy sky texels show it); upper half a depth edge, occluded near surface (2 m) left, open far one right. The
/// far side is only 0.5 m behind (a kerb, a table top): the lesson's edge distance (0.15 m) cuts
/// it fully, one ten times too large does not.
fn blur_panel(w: usize, h: usize, far: f32) -> (Vec<f32>, Vec<f32>) {
    let mut depth = vec![0f32; w * h];
    let mut occ = vec![0f32; w * h];
    for y in 0..h {
        for x in 0..w {
            let i = y * w + x;
            if y < h / 2 {
                if x < w * 3 / 4 {
                    depth[i] = 5.0;
                    occ[i] = noise(x, y);
                } else {
                    depth[i] = far;
                    occ[i] = noise(x, y);
                }
            } else if x < w / 2 {
                depth[i] = 2.0;
                occ[i] = 1.0;
            } else {
                depth[i] = 2.5;
                occ[i] = 0.0;
            }
        }
    }
    (depth, occ)
}

/// Where the impulse input has its single occluded texels (one on even, one on odd coordinates).
const IMPULSES: [(usize, usize); 2] = [(40, 40), (89, 87)];
/// How far the impulse response is read around each impulse (the blur's reach is 8 texels).
const IMPULSE_REACH: isize = 10;

/// A flat surface at 5 m, open but for single fully occluded texels: blurred, each shows the blur's
/// footprint and weights (its impulse response).
fn impulse_panel(w: usize, h: usize) -> (Vec<f32>, Vec<f32>) {
    let mut occ = vec![0f32; w * h];
    for (x, y) in IMPULSES {
        occ[y * w + x] = 1.0;
    }
    (vec![5.0; w * h], occ)
}

/// A flat surface at 5 m, open but for its outermost ring of texels, fully occluded. Within the
/// blur's reach of the border, taps past it read the border texel again when clamped to the
/// texture, as the lesson asks, and nothing (or whatever the driver returns) when they are not.
fn border_panel(w: usize, h: usize) -> (Vec<f32>, Vec<f32>) {
    let occ = (0..w * h)
        .map(|i| {
            let (x, y) = (i % w, i / w);
            f32::from(u8::from(x == 0 || y == 0 || x == w - 1 || y == h - 1))
        })
        .collect();
    (vec![5.0; w * h], occ)
}

/// The lesson's `edgeDistance` (m): a tap whose depth differs by δ weighs max(0, 1 − δ / it).
const EDGE_DISTANCE: f64 = 0.15;
/// Depth steps of `edge_weight_panel` (m), one band of rows each from the bottom: none, then two
/// that the lesson's edge weight only partly cuts (to 2/3 and 1/3).
const EDGE_STEPS: [f32; 3] = [0.0, 0.05, 0.10];

/// A surface at 5 m, fully occluded left of the middle column and open from it on, whose open side
/// lies `EDGE_STEPS[k]` behind in band k (a third of the rows each).
fn edge_weight_panel(w: usize, h: usize) -> (Vec<f32>, Vec<f32>) {
    let band = |y: usize| (y * EDGE_STEPS.len() / h).min(EDGE_STEPS.len() - 1);
    let open = |i: usize| i % w >= w / 2;
    let depth = (0..w * h)
        .map(|i| {
            5.0 + if open(i) {
                EDGE_STEPS[band(i / w)]
            } else {
                0.0
            }
        })
        .collect();
    let occ = (0..w * h).map(|i| f32::from(u8::from(!open(i)))).collect();
    (depth, occ)
}

/// The weight the shader gives taps across each nonzero step of `edge_weight_panel`, from its own
/// output `s` at the first open column (mean over each band's rows beyond the blur's reach of the
/// others). With a the Gaussian weight of the taps on the occluded side and b of those on the open
/// side, the output is a·e / (b + a·e) across a step weighted e, and a / (a + b) with no step: so
/// e = odds(output) / odds(output with no step), whatever the Gaussian weights are.
fn edge_weights(s: &[f32], w: usize, h: usize) -> Vec<f64> {
    let n = EDGE_STEPS.len();
    let odds = |k: usize| {
        let rows = k * h / n + 9..(k + 1) * h / n - 9;
        let count = rows.len().max(1) as f64;
        let o = rows.map(|y| s[y * w + w / 2] as f64).sum::<f64>() / count;
        o / (1.0 - o)
    };
    let flat = odds(0);
    (1..n).map(|k| odds(k) / flat).collect()
}

/// Where `band_panel` has its bands: the columns `BAND_X - 8 ..= BAND_X` and the rows
/// `h - BAND_FROM_TOP - 8 ..= h - BAND_FROM_TOP`.
const BAND_X: usize = 40;
const BAND_FROM_TOP: usize = 20;

/// The same surface inside the texture: an occluded band as wide as the blur's reach plus one
/// (9 texels) down the columns `BAND_X`, and one across the rows. Blurred, a pixel k texels beside a
/// band sees what a pixel k texels inside the border sees when the reads past it are clamped (the
/// border texel repeated over the blur's reach), with the shader's own weights.
fn band_panel(w: usize, h: usize) -> (Vec<f32>, Vec<f32>) {
    let top = h - BAND_FROM_TOP;
    let occ = (0..w * h)
        .map(|i| {
            let (x, y) = (i % w, i / w);
            f32::from(u8::from(
                (BAND_X - 8..=BAND_X).contains(&x) || (top - 8..=top).contains(&y),
            ))
        })
        .collect();
    (vec![5.0; w * h], occ)
}

/// Compares the blur of `border_panel` (`s`) within the blur's reach of each side with the blur of
/// `band_panel` (`bands`) beside the matching band, away from corners and the other band; returns
/// the largest difference as (difference, x, y, expected).
fn border_fault(s: &[f32], bands: &[f32], w: usize, h: usize) -> (f64, usize, usize, f32) {
    let top = h - BAND_FROM_TOP;
    let mut worst = (0.0f64, 0, 0, 0.0f32);
    let mut compare = |x: usize, y: usize, ex: usize, ey: usize| {
        let (got, expected) = (s[y * w + x], bands[ey * w + ex]);
        let d = (got - expected) as f64;
        // A NaN is the worst difference there is.
        if d.abs() > worst.0.abs() || (d.is_nan() && !worst.0.is_nan()) {
            worst = (d, x, y, expected);
        }
    };
    for k in 0..8 {
        // Left and right sides, on rows clear of the corners and of the band across.
        for y in 20..top - 20 {
            compare(k, y, BAND_X + k, y);
            compare(w - 1 - k, y, BAND_X - 8 - k, y);
        }
        // Bottom and top sides, on columns clear of the corners and of the band down.
        for x in BAND_X + 20..w - 20 {
            compare(x, k, x, top + k);
            compare(x, h - 1 - k, x, top - 8 - k);
        }
    }
    worst
}

/// The impulse responses around `IMPULSES` in `v`, each as (dx, dy) → value.
fn responses(v: &[f32], w: usize) -> Vec<Vec<((isize, isize), f32)>> {
    IMPULSES
        .iter()
        .map(|&(x, y)| {
            let mut out = Vec::new();
            for dy in -IMPULSE_REACH..=IMPULSE_REACH {
                for dx in -IMPULSE_REACH..=IMPULSE_REACH {
                    let (px, py) = ((x as isize + dx) as usize, (y as isize + dy) as usize);
                    out.push(((dx, dy), v[py * w + px]));
                }
            }
            out
        })
        .collect()
}

/// What is wrong with the student's impulse responses `s` next to the reference's `r`: a tap
/// missing or added (the footprint), or a response that is not mirror-symmetric (x, y, and x↔y:
/// the weights are gaussian[|x|]·gaussian[|y|]); `None` when nothing is.
fn impulse_fault(s: &[f32], r: &[f32], w: usize) -> Option<Text> {
    for (rs, rr) in responses(s, w).iter().zip(responses(r, w)) {
        let peak = rs
            .iter()
            .map(|(_, v)| v.abs())
            .fold(0.0f32, f32::max)
            .max(1e-12);
        let small = |v: f32| v.abs() <= tol::BLUR_IMPULSE_REL * peak;
        let at = |dx: isize, dy: isize| {
            let n = 2 * IMPULSE_REACH + 1;
            rs[((dy + IMPULSE_REACH) * n + dx + IMPULSE_REACH) as usize].1
        };
        // An extra tap first: it says more (blurScale ignored) than the taps it leaves out.
        for added in [true, false] {
            for (((dx, dy), v), (_, e)) in rs.iter().zip(&rr) {
                if small(*e) == small(*v) || small(*e) != added {
                    continue;
                }
                let (dx, dy) = (*dx, *dy);
                return Some(if added {
                    say!("grade.verdict.blur_impulse_extra", dx = dx, dy = dy)
                } else {
                    say!("grade.verdict.blur_impulse_missing", dx = dx, dy = dy)
                });
            }
        }
        for ((dx, dy), v) in rs.iter() {
            let (dx, dy) = (*dx, *dy);
            for (axis, m) in [
                ("grade.verdict.axis_left_right", at(-dx, dy)),
                ("grade.verdict.axis_up_down", at(dx, -dy)),
                ("grade.verdict.axis_diagonal", at(dy, dx)),
            ] {
                if (v - m).abs() > tol::BLUR_IMPULSE_REL * peak {
                    let (got, mirror) = (format!("{v:.4}"), format!("{m:.4}"));
                    return Some(say!(
                        l => "grade.verdict.blur_not_symmetric",
                        axis = rust_i18n::t!(axis, locale = l),
                        got = got,
                        mirror = mirror,
                        dx = dx,
                        dy = dy
                    ));
                }
            }
        }
    }
    None
}

/// Both sides' blur of a real SAO buffer (`a`: the project's occlusion of the first SAO scene) and
/// of the synthetic panel (`b`, whose input occlusion is `occ_b`).
struct Runs {
    depth_a: Vec<f32>,
    occ_a: Vec<f32>,
    /// White noise blurred over the same depth (every tap's weight shows), both sides.
    noise_a: Vec<f32>,
    reference_n: Vec<f32>,
    raw_n: Vec<f32>,
    reference_a: Vec<f32>,
    raw_a: Vec<f32>,
    occ_b: Vec<f32>,
    reference_b: Vec<f32>,
    raw_b: Vec<f32>,
    /// The impulse panel, the reference's and the student's.
    reference_c: Vec<f32>,
    raw_c: Vec<f32>,
    /// The student's blur of the border panel, of the band panel and of the edge-weight panel.
    raw_d: Vec<f32>,
    raw_e: Vec<f32>,
    raw_f: Vec<f32>,
}

fn render(rig: &Rig, params: &AoSettings, far: f32) -> Result<Runs> {
    let (w, h) = (BLUR_SIZE.0 as usize, BLUR_SIZE.1 as usize);
    let scene = &sao_scenes(BLUR_SIZE)[0];
    let depth_a = scene.depth();
    let occ_a = run_sao(
        &rig.reference,
        &rig.meshes,
        &scene.camera,
        &depth_a,
        params,
        Mips::Filled,
    )?;
    let reference_a = run_blur(&rig.reference, &rig.meshes, &depth_a, &occ_a)?;
    let raw_a = run_blur(&rig.student, &rig.meshes, &depth_a, &occ_a)?;
    let noise_a: Vec<f32> = (0..w * h).map(|i| noise(i % w, i / w)).collect();
    let reference_n = run_blur(&rig.reference, &rig.meshes, &depth_a, &noise_a)?;
    let raw_n = run_blur(&rig.student, &rig.meshes, &depth_a, &noise_a)?;
    let (depth_b, occ_b) = blur_panel(w, h, far);
    let reference_b = run_blur(&rig.reference, &rig.meshes, &depth_b, &occ_b)?;
    let raw_b = run_blur(&rig.student, &rig.meshes, &depth_b, &occ_b)?;
    let (depth_c, occ_c) = impulse_panel(w, h);
    let reference_c = run_blur(&rig.reference, &rig.meshes, &depth_c, &occ_c)?;
    let raw_c = run_blur(&rig.student, &rig.meshes, &depth_c, &occ_c)?;
    let (depth_d, occ_d) = border_panel(w, h);
    let raw_d = run_blur(&rig.student, &rig.meshes, &depth_d, &occ_d)?;
    let (depth_e, occ_e) = band_panel(w, h);
    let raw_e = run_blur(&rig.student, &rig.meshes, &depth_e, &occ_e)?;
    let (depth_f, occ_f) = edge_weight_panel(w, h);
    let raw_f = run_blur(&rig.student, &rig.meshes, &depth_f, &occ_f)?;
    Ok(Runs {
        depth_a,
        occ_a,
        noise_a,
        reference_n,
        raw_n,
        reference_a,
        raw_a,
        occ_b,
        reference_b,
        raw_b,
        reference_c,
        raw_c,
        raw_d,
        raw_e,
        raw_f,
    })
}

/// The course's Gaussian table, centre first: McGuire and Mara's weights with the 0.3 that
/// `SAO_blur.pix` adds to every tap but the centre folded in.
const COURSE_GAUSSIAN: [f64; 5] = [0.153170, 0.444893, 0.422649, 0.392902, 0.362970];

/// The lesson's blur with the course's table, on the CPU: `occ` blurred over `depth` (w × h, sky at
/// `far` kept as it is), 9×9 taps 2 texels apart, clamped to the texture, each weighted by the
/// product of the table's entries and by max(0, 1 − |Δdepth| / 0.15).
pub fn course_blur(occ: &[f32], depth: &[f32], w: usize, h: usize, far: f32) -> Vec<f32> {
    let (radius, scale, edge_distance) = (4isize, 2isize, 0.15f64);
    let mut out = occ.to_vec();
    for y in 0..h {
        for x in 0..w {
            let i = y * w + x;
            let d = depth[i] as f64;
            if depth[i] >= far {
                continue;
            }
            let g = &COURSE_GAUSSIAN;
            let (mut sum, mut total) = (occ[i] as f64 * g[0] * g[0], g[0] * g[0]);
            for ty in -radius..=radius {
                for tx in -radius..=radius {
                    if tx == 0 && ty == 0 {
                        continue;
                    }
                    let sx = (x as isize + tx * scale).clamp(0, w as isize - 1) as usize;
                    let sy = (y as isize + ty * scale).clamp(0, h as isize - 1) as usize;
                    let j = sy * w + sx;
                    let edge = (1.0 - (depth[j] as f64 - d).abs() / edge_distance).max(0.0);
                    let weight = g[tx.unsigned_abs()] * g[ty.unsigned_abs()] * edge;
                    sum += occ[j] as f64 * weight;
                    total += weight;
                }
            }
            out[i] = (sum / total) as f32;
        }
    }
    out
}

/// The RMSE of `s` against `r` over the pixels of `mask`, and the largest difference with its
/// index.
fn rmse_against(s: &[f32], r: &[f32], mask: &[bool]) -> (f64, (f64, usize)) {
    let (mut sq, mut cnt, mut worst) = (0.0f64, 0usize, (0.0f64, 0usize));
    for i in (0..s.len()).filter(|i| mask[*i]) {
        let d = (s[i] - r[i]) as f64;
        sq += d * d;
        cnt += 1;
        if d.abs() > worst.0.abs() {
            worst = (d, i);
        }
    }
    ((sq / cnt.max(1) as f64).sqrt(), worst)
}

/// Grades the student's blur pass of `rig`.
pub fn blur(rig: &Rig, params: &AoSettings) -> Verdict {
    let (w, h) = (BLUR_SIZE.0 as usize, BLUR_SIZE.1 as usize);
    let far = sao_scenes(BLUR_SIZE)[0].camera.far;
    let Runs {
        depth_a,
        occ_a,
        noise_a,
        reference_n,
        raw_n,
        reference_a: r_a,
        raw_a,
        occ_b,
        reference_b: r_b,
        raw_b,
        reference_c: r_c,
        raw_c,
        raw_d,
        raw_e,
        raw_f,
    } = match render(rig, params, far) {
        Ok(runs) => runs,
        Err(e) => return Verdict::grader_error(&e),
    };

    let nan = raw_a
        .iter()
        .chain(&raw_b)
        .chain(&raw_c)
        .chain(&raw_d)
        .chain(&raw_e)
        .chain(&raw_f)
        .filter(|v| !v.is_finite())
        .count();
    let s_a: Vec<f32> = raw_a.iter().map(|v| as_r8(*v)).collect();
    let s_b: Vec<f32> = raw_b.iter().map(|v| as_r8(*v)).collect();
    // Flat noisy surface, away from its borders by more than the blur's reach (8 texels).
    let flat = |v: &[f32]| {
        mean_and_std(
            (12..h / 2 - 12)
                .flat_map(|y| (12..w * 3 / 4 - 12).map(move |x| (x, y)))
                .map(|(x, y)| v[y * w + x] as f64),
        )
    };
    let (in_mean, in_std) = flat(&occ_b);
    let (raw_mean, _) = flat(&raw_b);
    let (out_mean, out_std) = flat(&s_b);
    let (_, ref_std) = flat(&r_b);
    // The depth edge: the two columns on each side, over the middle rows of the upper half.
    let rows = h / 2 + 10..h - 10;
    let near_min = rows
        .clone()
        .flat_map(|y| [w / 2 - 2, w / 2 - 1].map(|x| s_b[y * w + x]))
        .fold(1.0f32, f32::min) as f64;
    let far_max = rows
        .flat_map(|y| [w / 2, w / 2 + 1].map(|x| s_b[y * w + x]))
        .fold(0.0f32, f32::max) as f64;
    // How far a sky texel moves from its input.
    let sky_max = (0..h / 2)
        .flat_map(|y| (w * 3 / 4..w).map(move |x| (x, y)))
        .map(|(x, y)| (s_b[y * w + x] - occ_b[y * w + x]).abs())
        .fold(0.0f32, f32::max) as f64;
    // Against the closer reference on the real buffer (non-sky pixels): the project's blur, or the
    // same with the course's table.
    let mask: Vec<bool> = depth_a.iter().map(|d| *d < far).collect();
    let course = course_blur(&occ_a, &depth_a, w, h, far);
    let (rmse_port, worst_port) = rmse_against(&s_a, &r_a, &mask);
    let (rmse_course, worst_course) = rmse_against(&s_a, &course, &mask);
    // The same on white noise, where every tap's weight shows (a changed table entry does).
    let s_n: Vec<f32> = raw_n.iter().map(|v| as_r8(*v)).collect();
    let course_n = course_blur(&noise_a, &depth_a, w, h, far);
    let (noise_port, worst_noise_port) = rmse_against(&s_n, &reference_n, &mask);
    let (noise_course, worst_noise_course) = rmse_against(&s_n, &course_n, &mask);
    let (rmse, worst) = [
        if rmse_course < rmse_port {
            (rmse_course, worst_course)
        } else {
            (rmse_port, worst_port)
        },
        if noise_course < noise_port {
            (noise_course, worst_noise_course)
        } else {
            (noise_port, worst_noise_port)
        },
    ]
    .into_iter()
    .max_by(|a, b| a.0.total_cmp(&b.0))
    .unwrap_or((0.0, (0.0, 0)));
    let border = border_fault(&raw_d, &raw_e, w, h);
    let mut metrics = BTreeMap::new();
    metrics.insert("flat_mean_in".into(), in_mean);
    metrics.insert("flat_mean_out".into(), out_mean);
    metrics.insert("flat_mean_raw".into(), raw_mean);
    metrics.insert("flat_std_in".into(), in_std);
    metrics.insert("flat_std_out".into(), out_std);
    metrics.insert("flat_std_reference".into(), ref_std);
    metrics.insert("edge_near_min".into(), near_min);
    metrics.insert("edge_far_max".into(), far_max);
    metrics.insert("sky_max".into(), sky_max);
    metrics.insert("rmse".into(), rmse);
    metrics.insert("rmse_port_table".into(), rmse_port);
    metrics.insert("rmse_course_table".into(), rmse_course);
    metrics.insert("rmse_noise_port_table".into(), noise_port);
    metrics.insert("rmse_noise_course_table".into(), noise_course);
    metrics.insert("nan".into(), nan as f64);
    metrics.insert(
        crate::tools::grade::rig::NONFINITE_METRIC.into(),
        nan as f64 / (6 * w * h) as f64,
    );
    metrics.insert("border_difference".into(), border.0);
    let edge_weights = edge_weights(&raw_f, w, h);
    // Metrics go out as JSON numbers: a weight that cannot be measured is left out.
    for (step, e) in EDGE_STEPS[1..].iter().zip(&edge_weights) {
        if e.is_finite() {
            metrics.insert(format!("edge_weight_{step:.2}"), *e);
        }
    }
    let panels = vec![
        Panel::absolute(w, h, r_a, s_a, Shade::Occlusion, 0.25),
        Panel::absolute(w, h, r_b, s_b, Shade::Occlusion, 0.25),
    ];
    let verdict = |passed: bool, message: Text| Verdict {
        passed,
        message,
        metrics: metrics.clone(),
        panels: panels.clone(),
        parts: Vec::new(),
    };
    let f2 = |v: f64| format!("{v:.2}");
    let f3 = |v: f64| format!("{v:.3}");
    if nan > 0 {
        return verdict(false, say!("grade.verdict.blur_nan", count = nan));
    }
    if (raw_mean - in_mean).abs() > tol::BLUR_MEAN_ABS {
        let (got, expected) = (f2(raw_mean), f2(in_mean));
        return verdict(
            false,
            if raw_mean > in_mean {
                say!(
                    "grade.verdict.blur_mean_high",
                    got = got,
                    expected = expected
                )
            } else {
                say!(
                    "grade.verdict.blur_mean_low",
                    got = got,
                    expected = expected
                )
            },
        );
    }
    if far_max > tol::BLUR_EDGE_ABS {
        let (far, near) = (f2(far_max), f2(near_min));
        return verdict(
            false,
            say!("grade.verdict.blur_across_edge", far = far, near = near),
        );
    }
    if near_min < 1.0 - tol::BLUR_EDGE_ABS {
        let near = f2(near_min);
        return verdict(false, say!("grade.verdict.blur_edge_drop", near = near));
    }
    if out_std > tol::BLUR_SMOOTHING * in_std {
        let (input, output, reference) = (f3(in_std), f3(out_std), f3(ref_std));
        let allowed = f3(tol::BLUR_SMOOTHING * in_std);
        return verdict(
            false,
            say!(
                "grade.verdict.blur_no_smoothing",
                input = input,
                output = output,
                reference = reference,
                allowed = allowed
            ),
        );
    }
    if sky_max > tol::BLUR_SKY_ABS {
        let sky = f2(sky_max);
        return verdict(false, say!("grade.verdict.blur_sky", sky = sky));
    }
    if let Some(fault) = impulse_fault(&raw_c, &r_c, w) {
        return verdict(false, fault);
    }
    for (step, e) in EDGE_STEPS[1..].iter().zip(&edge_weights) {
        let expected = (1.0 - *step as f64 / EDGE_DISTANCE).max(0.0);
        // Also when not finite (an output of exactly 0 or 1 beside the step).
        if !e.is_finite() || (e - expected).abs() > tol::BLUR_EDGE_WEIGHT_ABS {
            let (got, expected, step) = (f2(*e), f2(expected), f2(*step as f64));
            return verdict(
                false,
                say!(
                    "grade.verdict.blur_edge_weight",
                    step = step,
                    got = got,
                    expected = expected
                ),
            );
        }
    }
    if border.0.abs() > tol::BLUR_BORDER_ABS {
        let (x, y) = (border.1, border.2);
        let (got, expected) = (f2(raw_d[y * w + x] as f64), f2(border.3 as f64));
        return verdict(
            false,
            say!(
                "grade.verdict.blur_border",
                x = x,
                y = y,
                got = got,
                expected = expected
            ),
        );
    }
    if rmse > tol::BLUR_RMSE {
        let (x, y) = (worst.1 % w, worst.1 / w);
        let (rmse, diff) = (f3(rmse), format!("{:+.2}", worst.0));
        return verdict(
            false,
            say!(
                "grade.verdict.blur_rmse",
                rmse = rmse,
                tolerance = tol::BLUR_RMSE,
                diff = diff,
                x = x,
                y = y
            ),
        );
    }
    let (near, far, input, output, rmse) =
        (f2(near_min), f2(far_max), f3(in_std), f3(out_std), f3(rmse));
    verdict(
        true,
        say!(
            "grade.verdict.blur_pass",
            near = near,
            far = far,
            input = input,
            output = output,
            rmse = rmse
        ),
    )
}
