//! What the SAO step measures (`sao` judges it): both sides' output on the step's scenes, summed
//! over all non-sky pixels, those away from depth edges and those also facing the camera; the
//! probes; the 8×8 block means; the 2×2 quads the smoothing evens out; NaN, Inf and out-of-range
//! values; and how much emptying mip levels 1–3 moves each side's output.

use crate::ao::AoSettings;
use crate::tools::grade::measure::{as_r8, block_means, rect_mean};
use crate::tools::grade::passes::{run_sao, Mips};
use crate::tools::grade::picture::{Panel, Shade};
use crate::tools::grade::rig::Rig;
use crate::tools::grade::scene::{ProbeKind, SynthScene};
use crate::tools::grade::tol;
use anyhow::Result;

/// Relative depth change per texel below which a surface counts as facing the camera.
const FLAT_SLOPE: f32 = 0.01;

/// One probe's mean occlusion, the student's (`got`, `raw`) and the reference's (`expected`).
pub(super) struct ProbeResult {
    pub(super) scene: &'static str,
    pub(super) name: &'static str,
    pub(super) kind: ProbeKind,
    pub(super) got: f64,
    /// Before clamping to [0, 1] (what the shader wrote).
    pub(super) raw: f64,
    pub(super) expected: f64,
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

/// How the student's 2×2 smoothing treats the quads the reference's treats (`quad_pattern`).
#[derive(Default, Clone, Copy)]
pub(super) struct Pattern {
    /// Quads that tell: occluded ones, or ones where the reference leaves a pair apart.
    pub(super) quads: usize,
    /// Pairs evened out that the reference leaves apart (across a depth step of 2 cm or more).
    pub(super) smeared: usize,
    /// Pairs the reference evens out and the student leaves apart.
    pub(super) unsmoothed: usize,
    /// Quads the reference evens out whole where the student leaves each diagonal pair the mean of
    /// the other (both derivatives taken of the unsmoothed value).
    pub(super) halved: usize,
}

/// Whether a pair of pixels of `v` is evened out (within the smoothing's spread).
pub(super) fn even(v: &[f32], i: usize, j: usize) -> bool {
    (v[i] - v[j]).abs() as f64 <= tol::SAO_QUAD_SPREAD
}

/// Whether a pair of pixels of `v` is clearly left apart (well beyond the smoothing's spread).
pub(super) fn apart(v: &[f32], i: usize, j: usize) -> bool {
    (v[i] - v[j]).abs() as f64 > tol::SAO_QUAD_APART * tol::SAO_QUAD_SPREAD
}

/// The aligned 2×2 quads of a `w`×`h` image with no sky pixel (`depth` at or beyond `far`): each
/// as its top-left corner and its pixels' indices (top-left, top-right, bottom-left, bottom-right).
pub(super) fn surface_quads(
    depth: &[f32],
    far: f32,
    w: usize,
    h: usize,
) -> impl Iterator<Item = (usize, usize, [usize; 4])> + '_ {
    let corners = (0..h.saturating_sub(1))
        .step_by(2)
        .flat_map(move |y| (0..w.saturating_sub(1)).step_by(2).map(move |x| (x, y)));
    corners.filter_map(move |(x, y)| {
        let quad = [(x, y), (x + 1, y), (x, y + 1), (x + 1, y + 1)].map(|(u, v)| v * w + u);
        quad.iter().all(|&i| depth[i] < far).then_some((x, y, quad))
    })
}

/// Aligned 2×2 quads of non-sky pixels, the student's output `s` against the reference's `r`: where
/// the reference's smoothing evened a pair out (its `|Δz| < 0.02` test passed) the student's must
/// too, with the whole quad's mean where both passed; where the reference left an occluded pair
/// apart, the student's must not be equal.
fn quad_pattern(s: &[f32], r: &[f32], depth: &[f32], far: f32, w: usize, h: usize) -> Pattern {
    let mut p = Pattern::default();
    for (_, _, [a, b, c, e]) in surface_quads(depth, far, w, h) {
        let occluded = (r[a] + r[b] + r[c] + r[e]) as f64 / 4.0 > tol::SAO_QUAD_OCCLUDED;
        let (rx, ry) = (
            even(r, a, b) && even(r, c, e),
            even(r, a, c) && even(r, b, e),
        );
        let (sx, sy) = (
            even(s, a, b) && even(s, c, e),
            even(s, a, c) && even(s, b, e),
        );
        let (r_apart_x, r_apart_y) = (
            !rx && (apart(r, a, b) || apart(r, c, e)),
            !ry && (apart(r, a, c) || apart(r, b, e)),
        );
        if !(occluded || r_apart_x || r_apart_y) {
            continue;
        }
        p.quads += 1;
        if (sx && r_apart_x) || (sy && r_apart_y) {
            p.smeared += 1;
        } else if occluded && rx && ry && !(sx && sy) {
            if even(s, a, e) && even(s, b, c) {
                p.halved += 1;
            } else {
                p.unsmoothed += 1;
            }
        } else if occluded && ((rx && !sx) || (ry && !sy)) {
            p.unsmoothed += 1;
        }
    }
    p
}

/// What the SAO step measures on its scenes (`_s` the student's, `_r` the reference's), before
/// judging. Sums run over non-sky pixels: all of them, those away from depth edges (`clean`), and
/// those also facing the camera (`flat`).
pub(super) struct Measured {
    pub(super) panels: Vec<Panel>,
    /// Non-sky pixels.
    pub(super) count: usize,
    /// Non-sky pixels that are NaN or Inf, above `tol::SAO_RAW_MAX`, below −0.01.
    pub(super) nan: usize,
    /// Of those, the pixels that are ±Inf.
    pub(super) inf: usize,
    pub(super) over: usize,
    pub(super) negative: usize,
    pub(super) sum_s: f64,
    pub(super) sum_r: f64,
    pub(super) sum_raw: f64,
    pub(super) clean_s: f64,
    pub(super) clean_r: f64,
    pub(super) clean_n: usize,
    pub(super) flat_s: f64,
    pub(super) flat_r: f64,
    pub(super) flat_n: usize,
    pub(super) max_raw: f64,
    /// Sum of squared differences of 8×8 block means, and the number of blocks.
    pub(super) blocks_sq: (f64, usize),
    /// The largest block difference: (difference, scene, x, y).
    pub(super) worst_block: (f64, &'static str, usize, usize),
    pub(super) probes: Vec<ProbeResult>,
    pub(super) sky_max: f64,
    /// Student ÷ reference of the 8×8 block means where the reference's is low enough that the
    /// student's stays below 1 even if scaled by the sample count (a sum never averaged).
    pub(super) block_ratios: Vec<f64>,
    /// Quads checked for the 2×2 smoothing, and those left uneven (`quad_parity`).
    pub(super) quads: (usize, usize),
    /// The 2×2 smoothing against the reference's, quad by quad.
    pub(super) pattern: Pattern,
    /// Pixels at depth edges (not sky, not `clean`): the student's mean, the reference's, how many.
    pub(super) edge: (f64, f64, usize),
    /// Pixels of the 2×2 quads that straddle a silhouette (their distances apart by more than 20 %
    /// of the nearest, no sky), which the lesson's `onEdge` leaves open: the same three.
    pub(super) straddle: (f64, f64, usize),
}

/// Sums over the pixels of aligned 2×2 quads whose distances differ by more than 20 % of the
/// nearest (no sky): (the student's, the reference's, how many pixels).
fn straddling(
    s: &[f32],
    r: &[f32],
    depth: &[f32],
    far: f32,
    w: usize,
    h: usize,
) -> (f64, f64, usize) {
    let mut sum = (0.0f64, 0.0f64, 0usize);
    for y in (0..h.saturating_sub(1)).step_by(2) {
        for x in (0..w.saturating_sub(1)).step_by(2) {
            let quad = [(x, y), (x + 1, y), (x, y + 1), (x + 1, y + 1)].map(|(u, v)| v * w + u);
            let d = quad.map(|i| depth[i]);
            let (lo, hi) = (
                d.iter().fold(f32::MAX, |a, b| a.min(*b)),
                d.iter().fold(0f32, |a, b| a.max(*b)),
            );
            if hi >= far || hi - lo <= 0.2 * lo {
                continue;
            }
            for i in quad {
                sum = (sum.0 + s[i] as f64, sum.1 + r[i] as f64, sum.2 + 1);
            }
        }
    }
    sum
}

pub(super) fn measure(rig: &Rig, params: &AoSettings, scenes: &[SynthScene]) -> Result<Measured> {
    let mut panels = vec![];
    let (mut sum_s, mut sum_r, mut sum_raw, mut count) = (0.0f64, 0.0f64, 0.0f64, 0usize);
    let (mut clean_s, mut clean_r, mut clean_n) = (0.0f64, 0.0f64, 0usize);
    let (mut flat_s, mut flat_r, mut flat_n) = (0.0f64, 0.0f64, 0usize);
    let (mut nan, mut inf, mut over, mut negative) = (0usize, 0usize, 0usize, 0usize);
    let mut max_raw = 0.0f64;
    let mut blocks_sq = (0.0f64, 0usize);
    let mut worst_block = (0.0f64, "", 0usize, 0usize);
    let mut probes = vec![];
    let mut sky_max = 0.0f64;
    let mut quads = (0usize, 0usize);
    let mut pattern = Pattern::default();
    let mut edge = (0.0f64, 0.0f64, 0usize);
    let mut straddle = (0.0f64, 0.0f64, 0usize);
    let mut block_ratios = vec![];
    let low = 0.5 / params.samples.max(1) as f64;
    for scene in scenes {
        let (w, h) = (scene.width as usize, scene.height as usize);
        let depth = scene.depth();
        let far = scene.camera.far;
        let (r, raw) = rig.sao_pair(&scene.camera, &depth, params)?;
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
                inf += usize::from(raw[i].is_infinite());
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
            } else {
                edge = (edge.0 + s[i] as f64, edge.1 + r[i] as f64, edge.2 + 1);
            }
        }
        let (q, uneven) = quad_parity(&s, &depth, &clean, w, h);
        quads = (quads.0 + q, quads.1 + uneven);
        let qp = quad_pattern(
            &s,
            &r.iter().map(|v| as_r8(*v)).collect::<Vec<_>>(),
            &depth,
            far,
            w,
            h,
        );
        pattern.quads += qp.quads;
        pattern.smeared += qp.smeared;
        pattern.unsmoothed += qp.unsmoothed;
        pattern.halved += qp.halved;
        let st = straddling(&s, &r, &depth, far, w, h);
        straddle = (straddle.0 + st.0, straddle.1 + st.1, straddle.2 + st.2);
        let bs = block_means(&s, &flat, w, h, 8);
        let br = block_means(&r, &flat, w, h, 8);
        for (k, (a, b)) in bs.iter().zip(&br).enumerate() {
            if let (Some(a), Some(b)) = (a, b) {
                if (tol::SAO_SCALE_FLOOR..=low).contains(b) {
                    block_ratios.push(a / b);
                }
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
        edge: (
            edge.0 / edge.2.max(1) as f64,
            edge.1 / edge.2.max(1) as f64,
            edge.2,
        ),
        straddle: (
            straddle.0 / straddle.2.max(1) as f64,
            straddle.1 / straddle.2.max(1) as f64,
            straddle.2,
        ),
    })
}

/// How much emptying mip levels 1–3 moves the output, summed over `scenes`: (student, reference).
pub(super) fn mip_change(
    rig: &Rig,
    params: &AoSettings,
    scenes: &[SynthScene],
) -> Result<(f64, f64)> {
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

/// How far the output reaches where the occlusion saturates: with the intensity raised a hundred
/// times, the median of the student's output (clamped to [0, 1], as stored) over the pixels of
/// `scenes` where the reference's is 1 (the course clamps the occlusion with min(1.0, …): a fully
/// occluded pixel is 1), and how many such pixels there are.
pub(super) fn saturation(
    rig: &Rig,
    params: &AoSettings,
    scenes: &[SynthScene],
) -> Result<(f64, usize)> {
    let strong = AoSettings {
        intensity: 100.0 * params.intensity,
        ..*params
    };
    let mut got = Vec::new();
    for scene in scenes {
        let depth = scene.depth();
        let (r, s) = rig.sao_pair(&scene.camera, &depth, &strong)?;
        got.extend(
            r.iter()
                .zip(&s)
                .filter(|(r, _)| as_r8(**r) >= 0.999)
                .map(|(_, s)| as_r8(*s) as f64),
        );
    }
    got.sort_by(f64::total_cmp);
    Ok((got.get(got.len() / 2).copied().unwrap_or(1.0), got.len()))
}
