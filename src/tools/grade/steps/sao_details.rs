//! What the SAO step asks at `--level lesson` of the numbers the pages fix, each on a scene that puts
//! it where it acts: the smoothing's 2 cm test (quads whose distance changes by 1.2–1.8 cm per texel
//! are evened out, by 2.4–3.6 cm are not), the edge guard's 10 % (a grazing floor whose distance
//! changes by 6–9 % per texel keeps its normal and so its creases; a silhouette 12–18 % deep does
//! not), the mip bias of `(2^L − 1)` texels of slope (none on level 0: a crease on a grazing floor
//! keeps its occlusion), the last mip level (`maxMipLevel` 3: a wide disc reads it), the tap's
//! `uv` clamped to 0–1 before the snap (taps past the image's border are rebuilt on it, and a convex
//! surface stays open there), and the smoothing leaving the pair's plain mean of clamped values
//! (beside small raised squares where one texel of a pair is fully occluded and the other open).

use crate::ao::AoSettings;
use crate::math::Camera;
use crate::tools::grade::measure::as_r8;
use crate::tools::grade::passes::{run_sao, Mips};
use crate::tools::grade::rig::Rig;
use crate::tools::grade::scene::{facing_wall, floor, Aabb, SynthScene};
use crate::tools::grade::tol;
use anyhow::Result;
use glam::Vec3;
use std::collections::BTreeMap;

/// A floor seen from 0.5 m above it with low walls across it at 2–14 m: creases on a floor whose
/// distance changes by a few per cent per texel, and, farther, by more than the guard's 10 %.
fn grazing_scene((width, height): (u32, u32)) -> SynthScene {
    let wall = |z: f32| Aabb::new([-40.0, 0.0, z - 0.3], [40.0, 0.35, z]);
    SynthScene {
        name: "grazing floor",
        camera: Camera {
            eye: Vec3::new(0.0, 0.5, 0.0),
            target: Vec3::new(0.0, 0.05, -8.0),
            ..Camera::default()
        },
        boxes: vec![
            floor(),
            wall(-2.0),
            wall(-3.5),
            wall(-5.5),
            wall(-8.0),
            wall(-11.0),
            wall(-14.0),
        ],
        width,
        height,
        probes: vec![],
    }
}

/// A floor with rows of low blocks, seen from above and aside: occluded quads on surfaces whose
/// distance changes by every amount from 0 to several centimetres per texel, along x and along y.
fn ribbed_scene((width, height): (u32, u32)) -> SynthScene {
    let mut boxes = vec![floor()];
    for i in 0..12 {
        let z = 2.0 - 1.0 * i as f32;
        boxes.push(Aabb::new([-20.0, 0.0, z - 0.15], [20.0, 0.12, z]));
    }
    for i in 0..12 {
        let x = -6.0 + 1.0 * i as f32;
        boxes.push(Aabb::new([x, 0.0, -20.0], [x + 0.15, 0.12, 4.0]));
    }
    SynthScene {
        name: "ribbed floor",
        camera: Camera {
            eye: Vec3::new(-3.0, 2.4, 5.0),
            target: Vec3::new(1.5, 0.0, -2.0),
            ..Camera::default()
        },
        boxes,
        width,
        height,
        probes: vec![],
    }
}

/// A wall seen head-on at 5 m with panels standing 0.7 m (silhouettes 16 % deep) and 0.3 m (6 %)
/// out of it.
fn panels_scene(size: (u32, u32)) -> SynthScene {
    facing_wall(
        "panels",
        &[
            Aabb::new([-2.0, -1.0, -5.0], [-0.6, 1.0, -4.3]),
            Aabb::new([0.6, -1.0, -5.0], [2.0, 1.0, -4.7]),
        ],
        size,
    )
}

/// A wall facing the camera at 5 m (as linear depth, built texel by texel) with 3 cm squares raised
/// from it, 8 texels wide every 16, their edges on even texels: with a disc 1.4 texels wide and the
/// occlusion saturated, the wall's texel beside a square is fully occluded and the next one not at
/// all, whatever the spiral, so each quad there must end as the pair's plain mean (0.5): the
/// smoothing's half-texel weights, and the clamp to 1 before it.
fn squares_depth((w, h): (usize, usize)) -> Vec<f32> {
    let raised = |v: usize| v % 16 >= 4 && v % 16 < 12;
    (0..w * h)
        .map(|i| {
            if raised(i % w) && raised(i / w) {
                4.97
            } else {
                5.0
            }
        })
        .collect()
}

/// Over the wall's quads beside a square along x (a pixel's left or right neighbour on it, none
/// above or below) and along y: the larger of the two mean |student − reference|.
fn beside_squares(s: &[f32], r: &[f32], depth: &[f32], (w, h): (usize, usize)) -> f64 {
    let mut sums = [(0.0f64, 0usize); 2];
    let wall = |x: usize, y: usize| depth[y * w + x] >= 5.0;
    for y in (2..h.saturating_sub(3)).step_by(2) {
        for x in (2..w.saturating_sub(3)).step_by(2) {
            let quad = [(x, y), (x + 1, y), (x, y + 1), (x + 1, y + 1)];
            if !quad.iter().all(|&(u, v)| wall(u, v)) {
                continue;
            }
            let along_x = quad
                .iter()
                .any(|&(u, v)| !wall(u - 1, v) || !wall(u + 1, v));
            let along_y = quad
                .iter()
                .any(|&(u, v)| !wall(u, v - 1) || !wall(u, v + 1));
            let axis = match (along_x, along_y) {
                (true, false) => 0,
                (false, true) => 1,
                _ => continue,
            };
            for (u, v) in quad {
                sums[axis].0 += (s[v * w + u] - r[v * w + u]).abs() as f64;
                sums[axis].1 += 1;
            }
        }
    }
    sums.iter()
        .map(|(sum, n)| sum / (*n).max(1) as f64)
        .fold(0.0, f64::max)
}

/// A huge box's corner pointing at the camera from 3 m: convex everywhere, so open, its faces
/// receding towards the image's left and bottom borders. A tap past the border rebuilt there (not
/// clamped back into the image) lies in front of the surface it extends and occludes it.
fn corner_scene((width, height): (u32, u32)) -> SynthScene {
    SynthScene {
        name: "convex corner",
        camera: Camera {
            eye: Vec3::new(1.8, 1.6, 1.8),
            target: Vec3::ZERO,
            ..Camera::default()
        },
        boxes: vec![Aabb::new([-100.0; 3], [0.0; 3])],
        width,
        height,
        probes: vec![],
    }
}

/// Mean (student's, reference's) over the wall's pixels with a square's texel beside them.
fn beside_mean(s: &[f32], r: &[f32], depth: &[f32], (w, h): (usize, usize)) -> (f64, f64) {
    let mut sum = (0.0f64, 0.0f64, 0usize);
    let wall = |x: usize, y: usize| depth[y * w + x] >= 5.0;
    for y in 1..h - 1 {
        for x in 1..w - 1 {
            let beside = !wall(x - 1, y) || !wall(x + 1, y) || !wall(x, y - 1) || !wall(x, y + 1);
            if wall(x, y) && beside {
                let i = y * w + x;
                sum = (sum.0 + s[i] as f64, sum.1 + r[i] as f64, sum.2 + 1);
            }
        }
    }
    mean(sum)
}

/// Per aligned 2×2 quad (x, y even): the depth changes along x (both rows) and along y (both
/// columns).
fn quad_slopes(depth: &[f32], w: usize, x: usize, y: usize) -> ([f32; 2], [f32; 2]) {
    let at = |u: usize, v: usize| depth[v * w + u];
    (
        [at(x + 1, y) - at(x, y), at(x + 1, y + 1) - at(x, y + 1)],
        [at(x, y + 1) - at(x, y), at(x + 1, y + 1) - at(x + 1, y)],
    )
}

/// Counts of the smoothing's 2 cm test on occluded quads: (quads whose depth changes by 1.2–1.8 cm
/// per texel along an axis that the reference evens out along it, of those the student leaves
/// apart; quads changing by 2.4–3.6 cm the reference leaves apart, of those the student evens out).
#[derive(Default)]
struct Threshold {
    below: usize,
    below_apart: usize,
    above: usize,
    above_even: usize,
}

fn threshold(s: &[f32], r: &[f32], depth: &[f32], far: f32, w: usize, h: usize) -> Threshold {
    use super::sao_measure::{apart, even as eq, surface_quads};
    let mut t = Threshold::default();
    for (x, y, [a, b, c, e]) in surface_quads(depth, far, w, h) {
        if ((r[a] + r[b] + r[c] + r[e]) as f64 / 4.0) <= tol::SAO_QUAD_OCCLUDED {
            continue;
        }
        let (dx, dy) = quad_slopes(depth, w, x, y);
        let band = |d: [f32; 2], lo: f32, hi: f32| d.iter().all(|v| (lo..hi).contains(&v.abs()));
        // Along x the pairs are (a, b) and (c, e); along y, after the x step, (a, c), (b, e).
        let axes = [(dx, [(a, b), (c, e)]), (dy, [(a, c), (b, e)])];
        for (d, pairs) in axes {
            let r_even = pairs.iter().all(|&(i, j)| eq(r, i, j));
            let s_even = pairs.iter().all(|&(i, j)| eq(s, i, j));
            if band(d, 0.012, 0.018) && r_even {
                t.below += 1;
                t.below_apart += usize::from(!s_even);
            }
            if band(d, 0.024, 0.036) && pairs.iter().any(|&(i, j)| apart(r, i, j)) {
                t.above += 1;
                t.above_even += usize::from(s_even);
            }
        }
    }
    t
}

/// Sums (student's, reference's, how many) over the pixels of aligned quads whose largest depth
/// change per texel, relative to the depth, lies in `lo..hi` (below 0.05: no quad straddling a
/// silhouette), those where the reference is occluded when `occluded_only` is set.
fn slope_band(
    s: &[f32],
    r: &[f32],
    depth: &[f32],
    (w, h): (usize, usize),
    (lo, hi): (f32, f32),
    occluded_only: bool,
) -> (f64, f64, usize) {
    let mut sum = (0.0f64, 0.0f64, 0usize);
    for y in (0..h.saturating_sub(1)).step_by(2) {
        for x in (0..w.saturating_sub(1)).step_by(2) {
            let (dx, dy) = quad_slopes(depth, w, x, y);
            let z = depth[y * w + x];
            let rel = dx.iter().chain(&dy).fold(0f32, |m, v| m.max(v.abs())) / z;
            if !(lo..hi).contains(&rel) {
                continue;
            }
            for i in [(x, y), (x + 1, y), (x, y + 1), (x + 1, y + 1)].map(|(u, v)| v * w + u) {
                if occluded_only && (r[i] as f64) <= tol::SAO_QUAD_OCCLUDED {
                    continue;
                }
                sum = (sum.0 + s[i] as f64, sum.1 + r[i] as f64, sum.2 + 1);
            }
        }
    }
    sum
}

/// Pixels of quads straddling a silhouette whose depth jumps by 12–18 % of the nearest: (student's
/// mean, reference's, how many).
fn straddle_band(s: &[f32], r: &[f32], depth: &[f32], (w, h): (usize, usize)) -> (f64, f64, usize) {
    let mut sum = (0.0f64, 0.0f64, 0usize);
    for y in (0..h.saturating_sub(1)).step_by(2) {
        for x in (0..w.saturating_sub(1)).step_by(2) {
            let quad = [(x, y), (x + 1, y), (x, y + 1), (x + 1, y + 1)].map(|(u, v)| v * w + u);
            let d = quad.map(|i| depth[i]);
            let lo = d.iter().fold(f32::MAX, |a, b| a.min(*b));
            let hi = d.iter().fold(0f32, |a, b| a.max(*b));
            if !(0.12 * lo..0.18 * lo).contains(&(hi - lo)) {
                continue;
            }
            for i in quad {
                sum = (sum.0 + s[i] as f64, sum.1 + r[i] as f64, sum.2 + 1);
            }
        }
    }
    sum
}

/// Mean occlusion (student's, reference's) of the non-sky pixels within 6 texels of the border.
fn border_band(
    s: &[f32],
    r: &[f32],
    depth: &[f32],
    far: f32,
    (w, h): (usize, usize),
) -> (f64, f64) {
    let mut sum = (0.0f64, 0.0f64, 0usize);
    for y in 0..h {
        for x in 0..w {
            let i = y * w + x;
            let near_border = x < 6 || y < 6 || x + 6 >= w || y + 6 >= h;
            if near_border && depth[i] < far {
                sum = (sum.0 + s[i] as f64, sum.1 + r[i] as f64, sum.2 + 1);
            }
        }
    }
    let n = sum.2.max(1) as f64;
    (sum.0 / n, sum.1 / n)
}

fn mean(sum: (f64, f64, usize)) -> (f64, f64) {
    let n = sum.2.max(1) as f64;
    (sum.0 / n, sum.1 / n)
}

/// The measures, as metrics named `detail_*` (the student's, and `_reference`).
pub(super) fn details(
    rig: &Rig,
    params: &AoSettings,
    size: (u32, u32),
) -> Result<BTreeMap<String, f64>> {
    let mut m = BTreeMap::new();
    let mut put = |name: &str, (s, r): (f64, f64)| {
        m.insert(format!("detail_{name}"), s);
        m.insert(format!("detail_{name}_reference"), r);
    };
    let (w, h) = (size.0 as usize, size.1 as usize);
    let r8 = |v: Vec<f32>| v.into_iter().map(as_r8).collect::<Vec<_>>();

    let ribbed = ribbed_scene(size);
    let depth = ribbed.depth();
    let (r, s) = rig.sao_pair(&ribbed.camera, &depth, params)?;
    let (r, s) = (r8(r), r8(s));
    let t = threshold(&s, &r, &depth, ribbed.camera.far, w, h);
    let share = |n: usize, of: usize| n as f64 / of.max(1) as f64;
    put(
        "below_2cm_apart",
        (share(t.below_apart, t.below), t.below as f64),
    );
    put(
        "above_2cm_even",
        (share(t.above_even, t.above), t.above as f64),
    );

    let grazing = grazing_scene(size);
    let depth = grazing.depth();
    let (r, s) = rig.sao_pair(&grazing.camera, &depth, params)?;
    let (r, s) = (r8(r), r8(s));
    put(
        "grazing_gentle",
        mean(slope_band(&s, &r, &depth, (w, h), (0.0, 0.05), true)),
    );

    let corner = corner_scene(size);
    let depth = corner.depth();
    let (r, s) = rig.sao_pair(&corner.camera, &depth, params)?;
    let (r, s) = (r8(r), r8(s));
    put(
        "convex_border",
        border_band(&s, &r, &depth, corner.camera.far, (w, h)),
    );

    let panels = panels_scene(size);
    let depth = panels.depth();
    let (r, s) = rig.sao_pair(&panels.camera, &depth, params)?;
    let (r, s) = (r8(r), r8(s));
    put(
        "straddle_12_18",
        mean(straddle_band(&s, &r, &depth, (w, h))),
    );

    // A disc wide enough that the outer taps read level 3; emptying that level alone.
    let wide = AoSettings {
        radius: 4.0,
        ..*params
    };
    let far = panels.camera.far;
    let change = |lesson| -> Result<f64> {
        let run = |mips| run_sao(lesson, &rig.meshes, &panels.camera, &depth, &wide, mips);
        let (with, without) = (run(Mips::Filled)?, run(Mips::LastEmptied)?);
        let (mut sum, mut n) = (0.0f64, 0usize);
        for i in (0..depth.len()).filter(|&i| depth[i] < far) {
            sum += (as_r8(with[i]) - as_r8(without[i])).abs() as f64;
            n += 1;
        }
        Ok(sum / n.max(1) as f64)
    };
    put(
        "last_level",
        (change(&rig.student)?, change(&rig.reference)?),
    );

    let depth = squares_depth((w, h));
    let tiny = AoSettings {
        radius: 0.05,
        intensity: 100.0 * params.intensity,
        ..*params
    };
    let (r, s) = rig.sao_pair(&panels.camera, &depth, &tiny)?;
    let (r, s) = (r8(r), r8(s));
    put(
        "beside_squares",
        (
            beside_squares(&s, &r, &depth, (w, h)),
            r.iter().map(|v| *v as f64).sum::<f64>() / r.len() as f64,
        ),
    );

    // The same squares at the lesson's intensity: the wall beside them is occluded by the taps
    // that cross into a square, so its mean tells how far from the pixel the taps lie.
    let small = AoSettings {
        radius: 0.05,
        ..*params
    };
    let (r, s) = rig.sao_pair(&panels.camera, &depth, &small)?;
    put(
        "beside_squares_mean",
        beside_mean(&r8(s), &r8(r), &depth, (w, h)),
    );

    // The same squares with the lesson's radius (a disc 27 texels wide): beside a square, only the
    // nearest taps (1.2 texels out for the first) reach it close enough to count, so the wall's ring
    // tells where the first taps lie.
    let (r, s) = rig.sao_pair(&panels.camera, &depth, params)?;
    put(
        "beside_squares_ring",
        beside_mean(&r8(s), &r8(r), &depth, (w, h)),
    );

    // Three times the intensity: many pixels reach 1 before the smoothing.
    let strong = AoSettings {
        intensity: 3.0 * params.intensity,
        ..*params
    };
    let (r, s) = rig.sao_pair(&ribbed.camera, &ribbed.depth(), &strong)?;
    let (r, s) = (r8(r), r8(s));
    let n = r.len() as f64;
    put(
        "strong_mean",
        (
            s.iter().map(|v| *v as f64).sum::<f64>() / n,
            r.iter().map(|v| *v as f64).sum::<f64>() / n,
        ),
    );
    Ok(m)
}

/// The sub-steps `details`' metrics fail, each with its message: what differs, and the page's line.
/// `failed`: the sub-steps already failed. A wrong normal or wrong taps darken borders and squares
/// for their own reason, and a wrong smoothing moves every mean, so after those only what does not
/// rest on them is judged (the message would name another cause).
pub(super) fn judge(
    m: &BTreeMap<String, f64>,
    smoothing_taught: bool,
    failed: impl Fn(&str) -> bool,
) -> Vec<(&'static str, crate::i18n::Text)> {
    use super::sao_parts::{NORMAL, OCCLUSION, SAMPLING, SMOOTHING};
    let normal_failed = failed(NORMAL);
    let taps_failed = normal_failed || failed(SAMPLING);
    let smoothing_failed = taps_failed || failed(SMOOTHING);
    use crate::tools::grade::say::say;
    let get = |k: &str| m.get(&format!("detail_{k}")).copied().unwrap_or(0.0);
    let reference = |k: &str| get(&format!("{k}_reference"));
    let (f3, pc) = (
        |v: f64| format!("{v:.3}"),
        |v: f64| format!("{:.0}", 100.0 * v),
    );
    let mut out = Vec::new();
    let (straddle, straddle_r) = (get("straddle_12_18"), reference("straddle_12_18"));
    if straddle - straddle_r > tol::SAO_EDGE_DARKER {
        let (got, expected) = (f3(straddle), f3(straddle_r));
        out.push((
            NORMAL,
            say!(
                "grade.verdict.sao_guard_loose",
                got = got,
                expected = expected
            ),
        ));
    }
    let (border, border_r) = (get("convex_border"), reference("convex_border"));
    // A loose edge test also darkens the corner's edges, which reach the border.
    if out.is_empty() && !normal_failed && border - border_r > tol::SAO_BORDER_DARKER {
        let (got, expected) = (f3(border), f3(border_r));
        out.push((
            SAMPLING,
            say!(
                "grade.verdict.sao_border_unclamped",
                got = got,
                expected = expected
            ),
        ));
    }
    let (small, small_r) = (get("beside_squares_mean"), reference("beside_squares_mean"));
    if !smoothing_failed && small_r > 0.0 && (small / small_r - 1.0).abs() > tol::SAO_SMALL_DISC_REL
    {
        let (got, expected) = (f3(small), f3(small_r));
        out.push((
            OCCLUSION,
            say!(
                "grade.verdict.sao_small_disc",
                got = got,
                expected = expected
            ),
        ));
    }
    let (ring, ring_r) = (get("beside_squares_ring"), reference("beside_squares_ring"));
    if !smoothing_failed && ring_r > 0.0 && (ring / ring_r - 1.0).abs() > tol::SAO_FIRST_TAPS_REL {
        let (got, expected) = (f3(ring), f3(ring_r));
        out.push((
            SAMPLING,
            say!(
                "grade.verdict.sao_first_taps",
                got = got,
                expected = expected
            ),
        ));
    }
    let (last, last_r) = (get("last_level"), reference("last_level"));
    if last_r > tol::SAO_MIP_CHANGE_MIN && last < tol::SAO_MIP_USE * last_r {
        let (got, expected) = (format!("{last:.4}"), format!("{last_r:.4}"));
        out.push((
            SAMPLING,
            say!(
                "grade.verdict.sao_no_last_level",
                got = got,
                expected = expected
            ),
        ));
    }
    // Creases on sloped floors: the low floor's first (its taps read levels 1–3), then the ribbed
    // floor's (both normals kept by a 10 % edge test).
    let weak = |k: &str| {
        let (s, r) = (get(k), reference(k));
        (r > 0.0 && s < (1.0 - tol::SAO_SLOPED_REL) * r).then(|| (f3(s), f3(r)))
    };
    if smoothing_failed {
    } else if let Some((got, expected)) = weak("grazing_gentle") {
        out.push((
            OCCLUSION,
            say!(
                "grade.verdict.sao_grazing_crease_weak",
                got = got,
                expected = expected
            ),
        ));
    } else if let Some((got, expected)) = weak("strong_mean") {
        out.push((
            OCCLUSION,
            say!(
                "grade.verdict.sao_sloped_weak",
                got = got,
                expected = expected
            ),
        ));
    }
    if smoothing_taught && !smoothing_failed {
        let (below, above) = (get("below_2cm_apart"), get("above_2cm_even"));
        if below > tol::SAO_THRESHOLD_BELOW {
            let percent = pc(below);
            out.push((
                SMOOTHING,
                say!("grade.verdict.sao_threshold_low", percent = percent),
            ));
        } else if above > tol::SAO_THRESHOLD_ABOVE {
            let percent = pc(above);
            out.push((
                SMOOTHING,
                say!("grade.verdict.sao_threshold_high", percent = percent),
            ));
        } else if get("beside_squares") > tol::SAO_BESIDE_SQUARES_ABS {
            let got = f3(get("beside_squares"));
            out.push((
                SMOOTHING,
                say!("grade.verdict.sao_smoothing_not_mean", got = got),
            ));
        }
    }
    out
}
