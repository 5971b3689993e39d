//! The down-sampling step (`sao_down_sampling.frag`): random distances (and sky) in level 0;
//! levels 1–3 must be exactly the min of their 2×2 parent texels; mistakes are named by predicting
//! what they would output (max, no ×2, always level 0, average, one texel).

use crate::tools::grade::measure::matches;
use crate::tools::grade::picture::{Panel, Shade};
use crate::tools::grade::rig::{Rig, Verdict};
use crate::tools::grade::say::say;
use crate::tools::grade::tol;
use std::collections::BTreeMap;

struct Level {
    w: usize,
    h: usize,
    v: Vec<f32>,
}

impl Level {
    fn at(&self, x: usize, y: usize) -> f32 {
        self.v[y.min(self.h - 1) * self.w + x.min(self.w - 1)]
    }
    /// The next level: `op` of the 2×2 texels at (2x + ox, 2y + oy) for (ox, oy) in {0,1}², each
    /// output texel reading at `scale`·(x, y).
    fn reduce(&self, w: usize, h: usize, scale: usize, op: &dyn Fn([f32; 4]) -> f32) -> Level {
        let mut v = Vec::with_capacity(w * h);
        for y in 0..h {
            for x in 0..w {
                let (sx, sy) = (scale * x, scale * y);
                v.push(op([
                    self.at(sx, sy),
                    self.at(sx + 1, sy),
                    self.at(sx, sy + 1),
                    self.at(sx + 1, sy + 1),
                ]));
            }
        }
        Level { w, h, v }
    }
}

fn min4(q: [f32; 4]) -> f32 {
    q[0].min(q[1]).min(q[2].min(q[3]))
}
fn max4(q: [f32; 4]) -> f32 {
    q[0].max(q[1]).max(q[2].max(q[3]))
}

/// Grades the student's down-sampling pass of `rig`.
pub fn down_sampling(rig: &Rig) -> Verdict {
    let s = &rig.student;
    let (w0, h0) = s.targets.tex_depth.size_at(0);
    let mut seed = 0x2545_f491u32;
    let mut rnd = || {
        seed = seed.wrapping_mul(1664525).wrapping_add(1013904223);
        (seed >> 8) as f32 / (1u32 << 24) as f32
    };
    let far = crate::math::camera::FAR;
    let level0: Vec<f32> = (0..w0 * h0)
        .map(|_| {
            let u = rnd();
            if rnd() < 0.05 {
                far
            } else {
                0.35 * (200.0f32 / 0.35).powf(u)
            }
        })
        .collect();
    if let Err(e) = s.targets.tex_depth.upload_f32(0, 1, &level0) {
        return Verdict::grader_error(&e);
    }
    s.down_sample(&rig.meshes);
    let levels = s.targets.tex_depth.levels() as usize;
    let base = Level {
        w: w0 as usize,
        h: h0 as usize,
        v: level0,
    };
    let mut expected = vec![];
    let mut got = vec![];
    // The expected levels 1.., each reduced from the expected level above it.
    let mut chain: Vec<Level> = vec![];
    for l in 1..levels {
        let (w, h) = s.targets.tex_depth.size_at(l as u32);
        let parent = chain.last().unwrap_or(&base);
        let e = parent.reduce(w as usize, h as usize, 2, &min4);
        got.push(Level {
            w: w as usize,
            h: h as usize,
            v: s.targets.tex_depth.read_f32(l as u32, 1),
        });
        chain.push(e);
    }
    expected.extend(chain.iter().map(|l| l.v.clone()));
    let is_bad = |g: f32, e: f32| {
        let err = (g as f64 - e as f64).abs();
        err.is_nan() || err > tol::DOWN_REL * e.abs() as f64
    };
    let mut metrics = BTreeMap::new();
    let mut panels = vec![];
    let mut first_bad: Option<(usize, usize, usize)> = None; // (level, index, count)
    let mut total = 0usize;
    for (k, (g, e)) in got.iter().zip(&expected).enumerate() {
        let count = g.v.iter().zip(e).filter(|(a, b)| is_bad(**a, **b)).count();
        total += g.v.len();
        metrics.insert(format!("level{}_wrong", k + 1), count as f64);
        if first_bad.is_none() {
            if let Some(i) = g.v.iter().zip(e).position(|(a, b)| is_bad(*a, *b)) {
                first_bad = Some((k + 1, i, count));
            }
        }
        panels.push(Panel {
            width: g.w,
            height: g.h,
            expected: e.clone(),
            actual: g.v.clone(),
            shade: Shade::Distance {
                near: crate::math::camera::NEAR,
                far: 200.0,
            },
            diff: g
                .v
                .iter()
                .zip(e)
                .map(|(a, b)| if is_bad(*a, *b) { 1.0 } else { 0.0 })
                .collect(),
        });
    }
    let Some((level, i, count)) = first_bad else {
        let last = levels - 1;
        return Verdict {
            passed: true,
            message: say!("grade.verdict.down_pass", last = last, total = total),
            metrics,
            panels,
            parts: Vec::new(),
        };
    };
    // What would common mistakes have written into this level (from a correct parent)?
    let k = level - 1;
    let parent = if k == 0 { &base } else { &chain[k - 1] };
    let (w, h) = (got[k].w, got[k].h);
    let g = &got[k].v;
    let made_by = |pred: &Level| {
        let p: Vec<f64> = pred.v.iter().map(|v| *v as f64).collect();
        matches(g, &p)
    };
    let message = if g.iter().all(|v| *v == g[0]) {
        say!("grade.verdict.down_constant", level = level, value = g[0])
    } else if made_by(&parent.reduce(w, h, 2, &max4)) {
        say!("grade.verdict.down_max", level = level)
    } else if made_by(&parent.reduce(w, h, 1, &min4)) {
        say!("grade.verdict.down_no_x2", level = level)
    } else if level >= 2 && made_by(&base.reduce(w, h, 2, &min4)) {
        say!(
            "grade.verdict.down_level_0",
            level = level,
            parent = level - 1
        )
    } else if made_by(&parent.reduce(w, h, 2, &|q| (q[0] + q[1] + q[2] + q[3]) / 4.0)) {
        say!("grade.verdict.down_average", level = level)
    } else if made_by(&parent.reduce(w, h, 2, &|q| q[0])) {
        say!("grade.verdict.down_one_texel", level = level)
    } else {
        let (x, y) = (i % w, i / w);
        say!(
            "grade.verdict.down_wrong",
            level = level,
            x = x,
            y = y,
            got = g[i],
            expected = expected[k][i],
            parent = level - 1,
            count = count,
            texels = g.len()
        )
    };
    Verdict {
        passed: false,
        message,
        metrics,
        panels,
        parts: Vec::new(),
    }
}
