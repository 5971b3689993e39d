//! One step of the grader, run in a child process (`opengl3d grade-step STEP`): fixed inputs go
//! through the student's shader and through the project's own, and the outputs are checked. Each
//! step uses the project's passes for everything but the graded file.
//!
//! - restore: a 256×128 DEPTH_COMPONENT32 buffer of known depths (log-spaced from near to far,
//!   scrambled over the image, 2×2 blocks whose nearest texel moves around, sky and half-sky blocks)
//!   against the exact f64 inverse of the projection of the nearest of each 2×2 block, within float
//!   precision. Failures are matched against what common mistakes would output (max, no ×2, raw depth,
//!   wrong sign, D' = 2D + 1, the ×0.01 debug scale, average, one texel) to name the mistake.
//! - down-sampling: random distances (and sky) in level 0; levels 1–3 must be exactly the min of
//!   their 2×2 parent texels; mistakes are named the same way (max, no ×2, always level 0, ...).
//! - sao: three ray-cast box scenes (a wall on a floor with a crate; a wall seen head-on with a step;
//!   a wall seen head-on with a raised panel), 160×160, the same mip chain for both shaders. Checked:
//!   NaN; values above 1 (not normalised, when clamping does not hide it); creases occluded
//!   (≥ half the reference's); open flat surfaces ≈ 0; the occlusion of a band beside the panel
//!   (the falloff's shape); the mean and the RMSE of 8×8 block means over pixels facing the camera
//!   and away from depth edges (the per-pixel noise may differ, and the lesson's listing has no
//!   mip-bias or edge guard, which this port's `sao.frag` adds: on grazing surfaces and at depth
//!   edges they legitimately differ); and that far samples come from mip levels 1–3 (the output
//!   must move when those levels are emptied, about as much as the project's does).
//! - blur: the project's SAO output of the first scene, plus a panel with a depth edge, a noisy flat
//!   surface and sky; the edge must stay sharp, the flat surface must be smoothed with its mean kept,
//!   nothing may leak into the sky, and the RMSE against the project's `sao_blur.frag` is bounded
//!   (loosely: the lesson's listing has wider weights).
//!
//! Both the student's and the project's passes render into R32F targets (the engine's are R8), so an
//! output that is not normalised shows its real size instead of being clamped to 1.

use super::picture::{Panel, Shade};
use super::scene::{sao_scenes, ProbeKind, SynthScene};
use super::Step;
use crate::ao::{AoSettings, SaoLesson};
use crate::gl::{FramebufferObject, Gl, MeshBuffer, ProgramError, Texture, TextureDesc};
use crate::math::depth::{delinearize, linearize};
use crate::math::{Camera, DepthMode};
use crate::platform::headless::{DevicePreference, HeadlessContext};
use crate::res::ResDirs;
use anyhow::Result;
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::rc::Rc;

/// Tolerances, set by running the lesson's listings (errata fixed), correct rewrites and typical
/// mistakes (tests/mutants/). Measured on Mesa llvmpipe; "listing" is the lesson's code as printed.
pub mod tol {
    /// Restore: allowed error in units of the float-precision bound ε·(1 + B / |D' − B|) (the
    /// conditioning of A / (D' − B) in f32). Worst seen: project 0.14×, listing 0.14×, rewrite
    /// n·f / (f − D(f − n)) 0.24× of this; mistakes ≥ 10⁵×.
    pub const RESTORE_ULPS: f64 = 8.0;
    /// Down-sampling: relative error allowed (a min is exact; this only forgives a conversion).
    pub const DOWN_REL: f64 = 1e-6;
    /// SAO: an open, flat surface may show at most the reference's occlusion (itself at most this)
    /// plus this. Listing: 0.008 on the open floor (reference 0); a zero bias gives 0.28.
    pub const SAO_OPEN_ABS: f64 = 0.05;
    /// SAO: a crease must reach at least this fraction of the reference's occlusion (reference
    /// 0.76–0.84; listing ≥ 0.73, rewrite ≥ 0.66; flipped normal ≤ 0.08, no max(…, 0) 0.04–0.42)...
    pub const SAO_CREASE_FRACTION: f64 = 0.5;
    /// ...and at least this much.
    pub const SAO_CREASE_MIN: f64 = 0.08;
    /// SAO: mean occlusion over pixels facing the camera, away from depth edges, relative to the
    /// reference (listing +10%, rewrite +8%, f·f falloff +36%, no max(…, 0) −94%).
    pub const SAO_MEAN_REL: f64 = 0.25;
    /// SAO: mean occlusion of the band beside a step, relative to the reference (listing +8%,
    /// rewrite +3%, f·f falloff +42%, output written in the loop +91%).
    pub const SAO_FALLOFF_REL: f64 = 0.2;
    /// SAO: RMSE of 8×8 block means against the reference, same pixels as the mean (listing 0.021,
    /// rewrite 0.018, f·f 0.034, no max(…, 0) 0.115, flipped normal 0.21).
    pub const SAO_BLOCK_RMSE: f64 = 0.035;
    /// SAO: a raw output above this (on more than 1% of the pixels) is not normalised
    /// (output written in the loop: 5.9% of the pixels, up to 13.1).
    pub const SAO_RAW_MAX: f64 = 1.05;
    /// SAO: emptying mip levels 1–3 must move the student's output by at least this fraction of
    /// what it moves the project's (listing 1.24, rewrite 1.25; every sample from level 0: 0)...
    pub const SAO_MIP_USE: f64 = 0.25;
    /// ...when the project's own output moves by more than this (mean |Δ| per non-sky pixel; it
    /// moves by 0.0034 on the three scenes); otherwise the scenes do not exercise the mips and the
    /// check is skipped.
    pub const SAO_MIP_CHANGE_MIN: f64 = 0.001;
    /// Blur: the mean of a blurred flat noisy surface may move this much (listing 0.0000, no
    /// division by totalWeight 0.49 → 5.70).
    pub const BLUR_MEAN_ABS: f64 = 0.03;
    /// Blur: at a depth edge the near side must stay above 1 − this and the far side below this
    /// (listing 1.00 | 0.00; no edge weight 0.52 | 0.48).
    pub const BLUR_EDGE_ABS: f64 = 0.05;
    /// Blur: the noise left on a flat surface, as a fraction of the input's standard deviation
    /// (input 0.290; reference 0.038, listing 0.036).
    pub const BLUR_SMOOTHING: f64 = 0.6;
    /// Blur: RMSE against the reference on a real SAO buffer (listing 0.046 with its wider
    /// weights, rewrite 0.000; no edge weight 0.080, no normalisation 0.112).
    pub const BLUR_RMSE: f64 = 0.07;
}

/// The outcome of one step.
pub struct Verdict {
    pub passed: bool,
    pub message: String,
    pub metrics: BTreeMap<String, f64>,
    pub panels: Vec<Panel>,
}

impl Verdict {
    fn fail(message: impl Into<String>) -> Verdict {
        Verdict {
            passed: false,
            message: message.into(),
            metrics: BTreeMap::new(),
            panels: Vec::new(),
        }
    }
}

/// The project's passes and the student's, sharing one GL context.
struct Rig {
    gl: Gl,
    meshes: MeshBuffer,
    reference: SaoLesson,
    student: SaoLesson,
}

/// Where the graded file comes from, for messages.
pub struct Subject<'a> {
    /// Folder the student's file was copied into (searched first).
    pub work_dir: &'a Path,
    /// Folder the file really lives in (shown in messages instead of `work_dir`).
    pub shown_dir: &'a Path,
}

impl Subject<'_> {
    /// Replaces the private copy's path by the student's in an error message.
    fn rewrite(&self, msg: &str) -> String {
        msg.replace(
            &self.work_dir.display().to_string(),
            &self.shown_dir.display().to_string(),
        )
    }
}

fn context() -> Result<HeadlessContext> {
    // Mesa's software device first: grading must not depend on the GPU, and a shader that never
    // ends must not hang a real one.
    HeadlessContext::with_preference(DevicePreference::Software).or_else(|_| HeadlessContext::new())
}

/// Replaces the R8 SAO and blur targets by R32F ones of the same size.
fn float_targets(gl: &Gl, lesson: &mut SaoLesson) -> Result<()> {
    let (w, h) = lesson.targets.tex_depth.size_at(0);
    let make = |name: &str| -> Result<FramebufferObject> {
        let t = Rc::new(Texture::new(
            gl,
            TextureDesc::target(name, w, h, glow::R32F),
        )?);
        FramebufferObject::new(gl, Some(t), None, 0, 0)
    };
    lesson.targets.fbo_sao = make("grade sao")?;
    lesson.targets.fbo_blur = make("grade blur")?;
    Ok(())
}

/// A one-line message for a shader that does not build.
fn build_error_message(e: &anyhow::Error, subject: &Subject) -> String {
    let text = match e.downcast_ref::<ProgramError>() {
        Some(ProgramError::Compile { messages, .. }) => {
            let mut m = format!("does not compile: {}", messages.join(" | "));
            if messages.len() > 3 {
                m = format!(
                    "does not compile: {} | … ({} more)",
                    messages[..3].join(" | "),
                    messages.len() - 3
                );
            }
            m
        }
        Some(ProgramError::Link { log, .. }) => {
            format!("does not link: {}", log.replace('\n', " | "))
        }
        Some(other) => other.to_string(),
        None => format!("cannot be built: {e:#}"),
    };
    subject.rewrite(&text)
}

fn build_rig(
    subject: &Subject,
    project_res: &Path,
    main_w: u32,
    main_h: u32,
    camera: &Camera,
    params: &AoSettings,
) -> std::result::Result<(HeadlessContext, Rig), Verdict> {
    let internal =
        |what: &str, e: anyhow::Error| Verdict::fail(format!("grader error ({what}): {e:#}"));
    let ctx = context().map_err(|e| internal("no OpenGL 4.5 context", e))?;
    let gl = ctx.gl.clone();
    let reference_res = ResDirs::only(vec![project_res.to_path_buf()]);
    let mut reference = SaoLesson::new(&gl, &reference_res, main_w, main_h, camera, params)
        .map_err(|e| internal("the project's own shaders do not build", e))?;
    let student_res = ResDirs::only(vec![
        subject.work_dir.to_path_buf(),
        project_res.to_path_buf(),
    ]);
    let mut student = SaoLesson::new(&gl, &student_res, main_w, main_h, camera, params)
        .map_err(|e| Verdict::fail(build_error_message(&e, subject)))?;
    float_targets(&gl, &mut reference).map_err(|e| internal("targets", e))?;
    float_targets(&gl, &mut student).map_err(|e| internal("targets", e))?;
    let meshes = MeshBuffer::new(&gl).map_err(|e| internal("meshes", e))?;
    Ok((
        ctx,
        Rig {
            gl,
            meshes,
            reference,
            student,
        },
    ))
}

/// Grades one step; `subject.work_dir` holds a copy of the graded file.
pub fn grade(step: Step, subject: &Subject, project_res: &Path) -> Verdict {
    let camera = Camera::default();
    let params = AoSettings::default();
    let (main_w, main_h) = match step {
        Step::Restore | Step::DownSampling => (256, 128),
        Step::Sao => (2 * SAO_SIZE, 2 * SAO_SIZE),
        Step::Blur => (2 * BLUR_SIZE, 2 * BLUR_SIZE),
    };
    let (_ctx, rig) = match build_rig(subject, project_res, main_w, main_h, &camera, &params) {
        Ok(r) => r,
        Err(v) => return v,
    };
    let v = match step {
        Step::Restore => restore(&rig, &camera),
        Step::DownSampling => down_sampling(&rig),
        Step::Sao => sao(&rig, &params),
        Step::Blur => blur(&rig, &params),
    };
    let _ = crate::gl::take_error(&rig.gl);
    v
}

// ---------------------------------------------------------------------------------------------
// Restore

/// View distance of a D32 depth-buffer value (the projection's inverse, f64).
fn linearize_d32(d: f64, n: f64, f: f64) -> f64 {
    linearize(DepthMode::D32, d, n, f)
}

/// Depth-buffer value of a point at view distance `z` (the projection's forward map, f64).
fn depth_of(z: f64, n: f64, f: f64) -> f64 {
    delinearize(DepthMode::D32, z, n, f)
}

/// Fraction of finite texels where `got` matches `predicted` to 0.1 %.
fn match_fraction(got: &[f32], predicted: &[f64]) -> f64 {
    let n = got.len().max(1);
    let ok = got
        .iter()
        .zip(predicted)
        .filter(|(g, p)| {
            let g = **g as f64;
            g.is_finite() && (g - **p).abs() <= 1e-3 * p.abs() + 1e-6
        })
        .count();
    ok as f64 / n as f64
}

fn restore(rig: &Rig, cam: &Camera) -> Verdict {
    let (w, h) = (256usize, 128usize);
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
        Err(e) => return Verdict::fail(format!("grader error: {e:#}")),
    };
    if let Err(e) = depth.upload_f32(0, 1, &d) {
        return Verdict::fail(format!("grader error: {e:#}"));
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
    let lin = |dv: f64| linearize_d32(dv.min(1.0), n, f);
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
    let verdict = |passed: bool, message: String| Verdict {
        passed,
        message,
        metrics: metrics.clone(),
        panels: panels.clone(),
    };
    if bad == 0 {
        return verdict(
            true,
            format!(
                "restored distances match the exact inverse of the projection at all {nb} texels, \
                 sky included (worst error {:.2} of the float-precision tolerance)",
                worst.0
            ),
        );
    }
    let p10 = got[probe];
    if got.iter().all(|v| *v == got[0]) {
        return verdict(
            false,
            format!(
                "writes {} at every texel: outColor must be the restored distance in metres",
                got[0]
            ),
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
        .map(|(name, p)| (*name, match_fraction(&got, p)))
        .find(|(_, frac)| *frac >= 0.9);
    let message = match found.map(|(n, _)| n) {
        Some("max") => "keeps the farthest texel of each 2×2 block (max instead of min?): \
                        the nearest depth (min) must win"
            .to_string(),
        Some("no-x2") => "reads the wrong texels: the depth buffer is twice the size of the output, \
                          so the texel coordinate is ivec2(gl_FragCoord.xy) * 2"
            .to_string(),
        Some("raw") => format!(
            "writes the raw depth-buffer value instead of a distance: at z=10 m got {p10:.4}; \
             invert the projection, A / (D' − B)"
        ),
        Some("negative") => format!(
            "restored distance has the wrong sign at z=10 m: got {p10:.3}; the distance in front of \
             the camera is positive, A / (D' − B) with D' = 2D − 1"
        ),
        Some("2D+1") => format!(
            "uses D' = 2D + 1 (a typo in the lesson's text): at z=10 m got {p10:.3}; it must be D' = 2D − 1"
        ),
        Some("x0.01") => format!(
            "is still multiplied by 0.01 (the lesson's temporary debug scale): at z=10 m got {p10:.3}; remove it"
        ),
        Some("average") => "averages the depths of each 2×2 block: depth is not linear, take the \
                            nearest (min) of the four"
            .to_string(),
        Some("one-texel") => "reads one texel of each 2×2 block: take the nearest (min) of the four"
            .to_string(),
        _ => {
            let i = worst.1;
            let (bx, by) = (i % bw, i / bw);
            if nonfinite > 0 {
                format!(
                    "writes NaN or Inf at {nonfinite} of {nb} texels (e.g. texel ({bx},{by}), \
                     expected {:.3} m)",
                    expected[i]
                )
            } else if bad == bad_sky {
                format!(
                    "sky (depth 1.0) must restore to the far plane, {} m: got {} at texel ({bx},{by})",
                    f, got[i]
                )
            } else if (p10 as f64 - 10.0).abs() > 10.0 * bound(depth_of(10.0, n, f)) * 10.0 {
                format!(
                    "restored distance is wrong at z=10 m: got {p10:.4}; {bad} of {nb} texels are \
                     out of tolerance (worst at z={:.3} m: got {})",
                    expected[i], got[i]
                )
            } else {
                format!(
                    "{bad} of {nb} texels are out of tolerance; worst at z={:.3} m (texel ({bx},{by})): \
                     got {}, error {:.1}× the float-precision tolerance",
                    expected[i], got[i], worst.0
                )
            }
        }
    };
    verdict(false, message)
}

// ---------------------------------------------------------------------------------------------
// Down-sampling

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

fn down_sampling(rig: &Rig) -> Verdict {
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
        return Verdict::fail(format!("grader error: {e:#}"));
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
    let mut parent = &base;
    let mut chain: Vec<Level> = vec![];
    for l in 1..levels {
        let (w, h) = s.targets.tex_depth.size_at(l as u32);
        let e = parent.reduce(w as usize, h as usize, 2, &min4);
        got.push(Level {
            w: w as usize,
            h: h as usize,
            v: s.targets.tex_depth.read_f32(l as u32, 1),
        });
        chain.push(e);
        parent = chain.last().unwrap();
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
        if count > 0 && first_bad.is_none() {
            let i = g.v.iter().zip(e).position(|(a, b)| is_bad(*a, *b)).unwrap();
            first_bad = Some((k + 1, i, count));
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
        return Verdict {
            passed: true,
            message: format!(
                "levels 1–{} are exactly the min of their 2×2 parent texels ({total} texels checked)",
                levels - 1
            ),
            metrics,
            panels,
        };
    };
    // What would common mistakes have written into this level (from a correct parent)?
    let k = level - 1;
    let parent = if k == 0 { &base } else { &chain[k - 1] };
    let (w, h) = (got[k].w, got[k].h);
    let g = &got[k].v;
    let frac = |pred: &Level| {
        let p: Vec<f64> = pred.v.iter().map(|v| *v as f64).collect();
        match_fraction(g, &p)
    };
    let message = if g.iter().all(|v| *v == g[0]) {
        format!(
            "level {level} is {} at every texel: outColor must be the min of the 2×2 texels of \
             level mipLevel",
            g[0]
        )
    } else if frac(&parent.reduce(w, h, 2, &max4)) >= 0.9 {
        format!("level {level} keeps the farthest of each 2×2 block (max instead of min?): the nearest (min) must win")
    } else if frac(&parent.reduce(w, h, 1, &min4)) >= 0.9 {
        format!(
            "level {level} reads the wrong texels: the source level is twice the size of the target, \
             so the texel coordinate is ivec2(gl_FragCoord.xy) * 2"
        )
    } else if level >= 2 && frac(&base.reduce(w, h, 2, &min4)) >= 0.9 {
        format!(
            "level {level} is made from level 0, not level {}: pass mipLevel to texelFetch",
            level - 1
        )
    } else if frac(&parent.reduce(w, h, 2, &|q| (q[0] + q[1] + q[2] + q[3]) / 4.0)) >= 0.9 {
        format!("level {level} averages each 2×2 block: take the nearest (min) of the four")
    } else if frac(&parent.reduce(w, h, 2, &|q| q[0])) >= 0.9 {
        format!(
            "level {level} copies one texel of each 2×2 block: take the nearest (min) of the four"
        )
    } else {
        let (x, y) = (i % w, i / w);
        format!(
            "level {level} texel ({x},{y}) is {}, expected {} (the min of its 2×2 parent texels in \
             level {}); {count} of {} texels of level {level} are wrong",
            g[i],
            expected[k][i],
            level - 1,
            g.len()
        )
    };
    Verdict {
        passed: false,
        message,
        metrics,
        panels,
    }
}

// ---------------------------------------------------------------------------------------------
// SAO

/// Size of `texSAODepth` level 0 in the SAO step (square).
const SAO_SIZE: u32 = 160;
/// Relative depth change per texel below which a surface counts as facing the camera.
const FLAT_SLOPE: f32 = 0.01;
/// Size of the buffers in the blur step (square).
const BLUR_SIZE: u32 = 128;

/// What a shader's output looks like once stored in the engine's R8 target.
fn as_r8(v: f32) -> f32 {
    if v.is_finite() {
        v.clamp(0.0, 1.0)
    } else {
        0.0
    }
}

/// Means of `b`×`b` blocks over the pixels where `mask` is true (blocks at least half covered).
fn block_means(data: &[f32], mask: &[bool], w: usize, h: usize, b: usize) -> Vec<Option<f64>> {
    let mut out = Vec::new();
    for by in 0..h / b {
        for bx in 0..w / b {
            let (mut s, mut n) = (0.0f64, 0usize);
            for y in by * b..(by + 1) * b {
                for x in bx * b..(bx + 1) * b {
                    if mask[y * w + x] {
                        s += data[y * w + x] as f64;
                        n += 1;
                    }
                }
            }
            out.push((n * 2 >= b * b).then(|| s / n as f64));
        }
    }
    out
}

struct ProbeResult {
    scene: &'static str,
    name: &'static str,
    kind: ProbeKind,
    got: f64,
    /// Before clamping to [0, 1] (what the shader wrote).
    raw: f64,
    expected: f64,
}

fn run_sao(
    lesson: &SaoLesson,
    meshes: &MeshBuffer,
    scene: &SynthScene,
    depth: &[f32],
    params: &AoSettings,
) -> Vec<f32> {
    run_sao_mips(lesson, meshes, scene, depth, params, true)
}

/// `run_sao`; without `mips`, every level above 0 is pushed to the far plane after down-sampling:
/// samples read from levels 1–3 then see nothing, so the output changes only where a shader reads
/// the mips.
fn run_sao_mips(
    lesson: &SaoLesson,
    meshes: &MeshBuffer,
    scene: &SynthScene,
    depth: &[f32],
    params: &AoSettings,
    mips: bool,
) -> Vec<f32> {
    lesson.targets.tex_depth.upload_f32(0, 1, depth).ok();
    lesson.down_sample(meshes);
    for level in (1..lesson.targets.tex_depth.levels()).filter(|_| !mips) {
        let (w, h) = lesson.targets.tex_depth.size_at(level);
        let far = vec![scene.camera.far; (w * h) as usize];
        lesson.targets.tex_depth.upload_f32(level, 1, &far).ok();
    }
    lesson.compute_sao(meshes, &scene.camera, params);
    lesson.sao_texture().read_f32(0, 1)
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

fn rect_mean(
    data: &[f32],
    w: usize,
    (x0, y0): (usize, usize),
    (x1, y1): (usize, usize),
    f: impl Fn(f32) -> f32,
) -> f64 {
    let (xa, xb) = (x0.min(x1), x0.max(x1));
    let (ya, yb) = (y0.min(y1), y0.max(y1));
    let mut sum = 0.0;
    let mut n = 0.0;
    for y in ya..=yb {
        for x in xa..=xb {
            sum += f(data[y * w + x]) as f64;
            n += 1.0;
        }
    }
    sum / n
}

fn sao(rig: &Rig, params: &AoSettings) -> Verdict {
    let scenes = sao_scenes(SAO_SIZE);
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
    for scene in &scenes {
        let (w, h) = (scene.width as usize, scene.height as usize);
        let depth = scene.depth();
        let far = scene.camera.far;
        let r = run_sao(&rig.reference, &rig.meshes, scene, &depth, params);
        let raw = run_sao(&rig.student, &rig.meshes, scene, &depth, params);
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
    let verdict = |passed: bool, message: String| Verdict {
        passed,
        message,
        metrics: metrics.clone(),
        panels: panels.clone(),
    };
    // The reference must itself meet the probes, or every verdict below is meaningless.
    if let Some(p) = probes.iter().find(|p| match p.kind {
        ProbeKind::Crease => p.expected < 0.3,
        ProbeKind::Open => p.expected > tol::SAO_OPEN_ABS,
        ProbeKind::Falloff => p.expected < 0.05,
    }) {
        return verdict(
            false,
            format!(
                "grader error: the project's own sao.frag gives {:.2} on the {} ({}), outside what \
                 the grader expects of it",
                p.expected, p.name, p.scene
            ),
        );
    }
    if nan as f64 > 0.01 * n {
        return verdict(
            false,
            format!(
                "writes NaN at {:.1}% of the pixels: guard normalize() where the cross product is zero",
                100.0 * nan as f64 / n
            ),
        );
    }
    let creases: Vec<&ProbeResult> = probes
        .iter()
        .filter(|p| p.kind == ProbeKind::Crease)
        .collect();
    if max_raw.abs() < 1e-3 && negative == 0 {
        return verdict(
            false,
            "writes 0 at every pixel: the occlusion is never summed, or never written to outColor"
                .to_string(),
        );
    }
    // Values above 1 are clamped by the engine's R8 target: they are a mistake when what is left
    // after clamping still differs (a sum that was never averaged), a detail when it does not.
    let overflow = over as f64 > 0.01 * n;
    if overflow && (mean_err.abs() > tol::SAO_MEAN_REL || falloff_err.abs() > tol::SAO_FALLOFF_REL)
    {
        let worst = creases
            .iter()
            .max_by(|a, b| a.raw.total_cmp(&b.raw))
            .unwrap();
        return verdict(
            false,
            format!(
                "output is not normalised: mean occlusion {:.1} in the {} ({}), expected about {:.2} \
                 (values up to {max_raw:.1}, and occlusion must stay within 0–1); after the loop \
                 divide the sum by samplingCount, multiply by INTENSITY, clamp with min(1.0, …), \
                 then write outColor once",
                worst.raw, worst.name, worst.scene, worst.expected
            ),
        );
    }
    if let Some(p) = creases
        .iter()
        .find(|p| p.got < (tol::SAO_CREASE_FRACTION * p.expected).max(tol::SAO_CREASE_MIN))
    {
        let all_dark = creases.iter().all(|p| p.got < 0.25 * p.expected);
        let hint = if negative as f64 > 0.05 * n {
            "the output is negative in many places: clamp each sample's term with max(…, 0) \
             before adding it (negative terms must not cancel positive ones)"
        } else if all_dark {
            "no crease is occluded: is the normal flipped? cross(dFdx(p), dFdy(p)) must point \
             towards the camera (+z in view space), and vn = dot(v, normal) with v = sample − pixel"
        } else {
            "occlusion is too weak where surfaces meet: check the sign of vn and the bias, that \
             the average is multiplied by INTENSITY, and that each sample's term is clamped with \
             max(…, 0) (negative terms must not cancel positive ones)"
        };
        return verdict(
            false,
            format!(
                "{} ({}): occlusion {:.2}, expected about {:.2}; {hint}",
                p.name, p.scene, p.got, p.expected
            ),
        );
    }
    if let Some(p) = probes.iter().find(|p| {
        p.kind == ProbeKind::Open && p.got > p.expected.min(tol::SAO_OPEN_ABS) + tol::SAO_OPEN_ABS
    }) {
        return verdict(
            false,
            format!(
                "the {} ({}) is flat and open but occluded: {:.2}, expected about {:.2}; \
                 check the bias (vn − BIAS) and the normal",
                p.name, p.scene, p.got, p.expected
            ),
        );
    }
    for p in probes.iter().filter(|p| p.kind == ProbeKind::Falloff) {
        let ratio = p.got / p.expected.max(1e-6);
        if (ratio - 1.0).abs() > tol::SAO_FALLOFF_REL {
            let hint = if ratio > 1.0 {
                "it fades too slowly: the falloff is f·f·f with f = max(RADIUS2 − vv, 0)"
            } else {
                "it fades too fast: the falloff is f·f·f with f = max(RADIUS2 − vv, 0), divided by (vv + 0.001)"
            };
            return verdict(
                false,
                format!(
                    "occlusion of the {} ({}) is {:.3}, expected about {:.3} (±{:.0}%): {hint}",
                    p.name,
                    p.scene,
                    p.got,
                    p.expected,
                    tol::SAO_FALLOFF_REL * 100.0
                ),
            );
        }
    }
    if mean_err.abs() > tol::SAO_MEAN_REL {
        let hint = if mean_err > 0.0 {
            "too strong: the falloff is f·f·f with f = max(RADIUS2 − vv, 0), divided by \
             (vv + 0.001), averaged over samplingCount and scaled by INTENSITY once"
        } else {
            "too weak: clamp each sample's term with max(…, 0) before adding it (negative terms \
             must not cancel positive ones); the falloff is f·f·f"
        };
        return verdict(
            false,
            format!(
                "mean occlusion {fmean_s:.3}, expected about {fmean_r:.3} (±{:.0}%; surfaces facing \
                 the camera, away from depth edges): {hint}",
                tol::SAO_MEAN_REL * 100.0
            ),
        );
    }
    if rmse > tol::SAO_BLOCK_RMSE {
        return verdict(
            false,
            format!(
                "occlusion differs from the reference: RMSE of 8×8 block means {rmse:.3} (tolerance {}); \
                 largest difference {:+.2} in the {} scene around texel ({}, {})",
                tol::SAO_BLOCK_RMSE,
                worst_block.0,
                worst_block.1,
                worst_block.2,
                worst_block.3
            ),
        );
    }
    // Far samples must come from the min mip chain (levels 1–3), as the lesson teaches: a shader that
    // reads level 0 for every sample passes the comparisons above on these small scenes, but thrashes
    // the texture cache on a real screen. Measured by how much the output moves when levels 1–3 are
    // emptied, relative to how much the project's own shader moves.
    let (mut mip_s, mut mip_r) = (0.0f64, 0.0f64);
    for scene in &scenes {
        let depth = scene.depth();
        let far = scene.camera.far;
        let with = |l: &SaoLesson| run_sao(l, &rig.meshes, scene, &depth, params);
        let without = |l: &SaoLesson| run_sao_mips(l, &rig.meshes, scene, &depth, params, false);
        mip_r += mean_abs_change(&with(&rig.reference), &without(&rig.reference), &depth, far);
        mip_s += mean_abs_change(&with(&rig.student), &without(&rig.student), &depth, far);
    }
    let mip_use = mip_s / mip_r.max(1e-9);
    let mut metrics = metrics.clone();
    metrics.insert("mip_change".into(), mip_s / scenes.len() as f64);
    metrics.insert("mip_change_reference".into(), mip_r / scenes.len() as f64);
    metrics.insert("mip_use".into(), mip_use);
    let verdict = |passed: bool, message: String| Verdict {
        passed,
        message,
        metrics: metrics.clone(),
        panels: panels.clone(),
    };
    if mip_r / scenes.len() as f64 > tol::SAO_MIP_CHANGE_MIN && mip_use < tol::SAO_MIP_USE {
        return verdict(
            false,
            format!(
                "never reads the mip levels 1–3: emptying them changes the output by {:.4} on \
                 average, the project's sao.frag by {:.4}; read each sample with \
                 textureLod(texDepth, uv, mipLevel) where mipLevel = clamp(findMSB(int(ssR)) − \
                 logMipOffset, 0, maxMipLevel) grows with the sample's distance in pixels",
                mip_s / scenes.len() as f64,
                mip_r / scenes.len() as f64
            ),
        );
    }
    let falloff = probes
        .iter()
        .filter(|p| p.kind == ProbeKind::Falloff)
        .map(|p| format!("{:.3} (reference {:.3})", p.got, p.expected))
        .collect::<Vec<_>>()
        .join(", ");
    let crease_txt = creases
        .iter()
        .map(|p| format!("{:.2}", p.got))
        .collect::<Vec<_>>()
        .join("/");
    let note = if overflow {
        format!(
            " (note: the output goes up to {max_raw:.1}; the engine's 8-bit target clamps it, but \
             the lesson clamps with min(1.0, …))"
        )
    } else {
        String::new()
    };
    verdict(
        true,
        format!(
            "mean occlusion {fmean_s:.3} (reference {fmean_r:.3}), block RMSE {rmse:.3}, creases \
             {crease_txt}, falloff beside a step {falloff}, open surfaces ≈ 0{note}"
        ),
    )
}

// ---------------------------------------------------------------------------------------------
// Blur

/// A hash in [0, 1) for reproducible noise.
fn noise(x: usize, y: usize) -> f32 {
    let mut v = (x as u32).wrapping_mul(0x8da6_b343) ^ (y as u32).wrapping_mul(0xd816_3841);
    v ^= v >> 13;
    v = v.wrapping_mul(0x5bd1_e995);
    v ^= v >> 15;
    (v >> 8) as f32 / (1u32 << 24) as f32
}

/// The blur's synthetic panel (rows bottom-up): lower half a noisy flat surface at 5 m with sky on
/// its right; upper half a depth edge, occluded near surface (2 m) left, open far one (10 m) right.
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
                    occ[i] = 0.0;
                }
            } else if x < w / 2 {
                depth[i] = 2.0;
                occ[i] = 1.0;
            } else {
                depth[i] = 10.0;
                occ[i] = 0.0;
            }
        }
    }
    (depth, occ)
}

fn run_blur(lesson: &SaoLesson, meshes: &MeshBuffer, depth: &[f32], occ: &[f32]) -> Vec<f32> {
    lesson.targets.tex_depth.upload_f32(0, 1, depth).ok();
    lesson.sao_texture().upload_f32(0, 1, occ).ok();
    lesson.blur(meshes);
    lesson.result_texture(true).read_f32(0, 1)
}

fn stats(v: impl Iterator<Item = f64>) -> (f64, f64) {
    let v: Vec<f64> = v.collect();
    let n = v.len().max(1) as f64;
    let mean = v.iter().sum::<f64>() / n;
    let var = v.iter().map(|x| (x - mean) * (x - mean)).sum::<f64>() / n;
    (mean, var.sqrt())
}

fn blur(rig: &Rig, params: &AoSettings) -> Verdict {
    let (w, h) = (BLUR_SIZE as usize, BLUR_SIZE as usize);
    // A real SAO buffer: the project's occlusion of the corner scene.
    let scene = &sao_scenes(BLUR_SIZE)[0];
    let far = scene.camera.far;
    let depth_a = scene.depth();
    let occ_a = run_sao(&rig.reference, &rig.meshes, scene, &depth_a, params);
    let r_a = run_blur(&rig.reference, &rig.meshes, &depth_a, &occ_a);
    let raw_a = run_blur(&rig.student, &rig.meshes, &depth_a, &occ_a);
    // The synthetic panel.
    let (depth_b, occ_b) = blur_panel(w, h, far);
    let r_b = run_blur(&rig.reference, &rig.meshes, &depth_b, &occ_b);
    let raw_b = run_blur(&rig.student, &rig.meshes, &depth_b, &occ_b);

    let nan = raw_a
        .iter()
        .chain(&raw_b)
        .filter(|v| !v.is_finite())
        .count();
    let s_a: Vec<f32> = raw_a.iter().map(|v| as_r8(*v)).collect();
    let s_b: Vec<f32> = raw_b.iter().map(|v| as_r8(*v)).collect();
    // Flat noisy surface, away from its borders by more than the blur's reach (8 texels).
    let flat = |v: &[f32]| {
        stats(
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
    let sky_max = (0..h / 2)
        .flat_map(|y| (w * 3 / 4..w).map(move |x| (x, y)))
        .map(|(x, y)| s_b[y * w + x])
        .fold(0.0f32, f32::max) as f64;
    // Against the reference on the real buffer (non-sky pixels).
    let mask: Vec<bool> = depth_a.iter().map(|d| *d < far).collect();
    let (mut sq, mut cnt, mut worst) = (0.0f64, 0usize, (0.0f64, 0usize));
    for i in 0..w * h {
        if mask[i] {
            let d = (s_a[i] - r_a[i]) as f64;
            sq += d * d;
            cnt += 1;
            if d.abs() > worst.0.abs() {
                worst = (d, i);
            }
        }
    }
    let rmse = (sq / cnt.max(1) as f64).sqrt();
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
    metrics.insert("nan".into(), nan as f64);
    let panels = vec![
        Panel::absolute(w, h, r_a, s_a, Shade::Occlusion, 0.25),
        Panel::absolute(w, h, r_b, s_b, Shade::Occlusion, 0.25),
    ];
    let verdict = |passed: bool, message: String| Verdict {
        passed,
        message,
        metrics: metrics.clone(),
        panels: panels.clone(),
    };
    if nan > 0 {
        return verdict(false, format!("writes NaN or Inf at {nan} pixels"));
    }
    if (raw_mean - in_mean).abs() > tol::BLUR_MEAN_ABS {
        let hint = if raw_mean > in_mean {
            "the output is not normalised: divide the weighted sum by totalWeight (the sum of the weights used)"
        } else {
            "the weighted sum must be divided by the sum of the weights actually used (totalWeight)"
        };
        return verdict(
            false,
            format!(
                "a blurred flat surface must keep its mean occlusion: got {raw_mean:.2}, expected \
                 {in_mean:.2}; {hint}"
            ),
        );
    }
    if far_max > tol::BLUR_EDGE_ABS {
        return verdict(
            false,
            format!(
                "blurs across a depth edge: next to the edge the far, open side is {far_max:.2} \
                 (expected 0.00) and the near, occluded side {near_min:.2} (expected 1.00); weight \
                 each sample by max(0, 1 − edgeSharpness·|sampleDepth − depth|)"
            ),
        );
    }
    if near_min < 1.0 - tol::BLUR_EDGE_ABS {
        return verdict(
            false,
            format!(
                "next to a depth edge a fully occluded surface drops to {near_min:.2} (expected \
                 1.00): divide the weighted sum by totalWeight, the sum of the weights actually \
                 used (samples across the edge get weight 0)"
            ),
        );
    }
    if out_std > tol::BLUR_SMOOTHING * in_std {
        return verdict(
            false,
            format!(
                "does not smooth a flat surface: noise std {in_std:.3} → {out_std:.3} (the reference \
                 leaves {ref_std:.3}; at most {:.3} allowed)",
                tol::BLUR_SMOOTHING * in_std
            ),
        );
    }
    if sky_max > 0.02 {
        return verdict(
            false,
            format!(
                "occlusion leaks into the sky ({sky_max:.2}): sky pixels must be kept as they are"
            ),
        );
    }
    if rmse > tol::BLUR_RMSE {
        let (x, y) = (worst.1 % w, worst.1 / w);
        return verdict(
            false,
            format!(
                "differs from the reference blur: RMSE {rmse:.3} (tolerance {}); largest difference \
                 {:+.2} at texel ({x}, {y})",
                tol::BLUR_RMSE,
                worst.0
            ),
        );
    }
    verdict(
        true,
        format!(
            "keeps depth edges ({near_min:.2} | {far_max:.2}), smooths flat surfaces (noise std \
             {in_std:.3} → {out_std:.3}, mean kept), RMSE {rmse:.3} against the reference"
        ),
    )
}

/// Copies `file` into a fresh `dir` (so that only this file of the student's is used), with the
/// files it `#include`s (resolved next to it, as the engine does), keeping their relative paths.
/// A missing include is not an error here: building the shader reports it with file:line.
pub fn stage(file: &Path, dir: &Path) -> Result<PathBuf> {
    let _ = std::fs::remove_dir_all(dir);
    std::fs::create_dir_all(dir)?;
    let to = dir.join(file.file_name().unwrap());
    std::fs::copy(file, &to)?;
    let from_dir = file.parent().unwrap_or(Path::new("."));
    for name in included_files(&std::fs::read(file)?) {
        let rel = Path::new(&name);
        // Only paths below the shader's folder: the copy must stay inside `dir`.
        if rel.is_absolute()
            || rel
                .components()
                .any(|c| !matches!(c, std::path::Component::Normal(_)))
        {
            continue;
        }
        let (src, dst) = (from_dir.join(rel), dir.join(rel));
        if src.is_file() {
            if let Some(parent) = dst.parent() {
                std::fs::create_dir_all(parent)?;
            }
            std::fs::copy(&src, &dst)?;
        }
    }
    Ok(to)
}

/// The file names of `#include "name"` lines (ASCII directives; the rest of the file may be in
/// any encoding).
fn included_files(bytes: &[u8]) -> Vec<String> {
    String::from_utf8_lossy(bytes)
        .lines()
        .filter_map(|l| l.trim_start().strip_prefix("#include"))
        .map(|rest| rest.trim().trim_matches('"').to_string())
        .filter(|name| !name.is_empty())
        .collect()
}
