//! `opengl3d bench --stress`: numerical stability of the AO pipeline at the extremes, and linear-depth
//! reconstruction error against distance.
//!
//! Every case builds a small scene from procedural meshes, renders the composite frame and the three
//! value views with every AO method, and counts NaN/Inf values in every output: the main colour
//! buffer, each level of the linear-depth mip chain, the raw and blurred AO buffers, and the
//! `render_values` of the linear-depth, raw-AO and AO views. Visibility must lie in [0, 1] and linear
//! depth must be positive; sky-only frames must be fully visible.

use super::depth_formats::{DepthMode, DepthProbe};
use crate::ao::AoMethod;
use crate::gl::mesh::MeshData;
use crate::platform::HeadlessContext;
use crate::render::{Engine, View};
use crate::res::ResDirs;
use crate::scene::{shapes, ObjectDesc, SceneDesc};
use anyhow::{Context as _, Result};
use glam::Vec3;
use indicatif::{ProgressBar, ProgressStyle};
use serde::Serialize;
use std::path::{Path, PathBuf};
use std::time::Instant;

#[derive(Clone, Debug)]
pub struct StressConfig {
    pub out: PathBuf,
    /// Include the 4096×4096 frame.
    pub large: bool,
    /// Only the first case of each category and one depth configuration (for tests).
    pub quick: bool,
    pub progress: bool,
}

/// One output buffer of one method in one case.
#[derive(Clone, Debug, Serialize)]
pub struct OutputCheck {
    pub method: String,
    pub output: String,
    pub values: usize,
    pub non_finite: usize,
    pub min: f32,
    pub max: f32,
}

#[derive(Clone, Debug, Serialize)]
pub struct CaseResult {
    pub category: String,
    pub name: String,
    pub width: u32,
    pub height: u32,
    pub near: f32,
    pub far: f32,
    pub fov_y: f32,
    pub radius: f32,
    pub intensity: f32,
    pub bias: f32,
    pub methods: Vec<String>,
    /// NaN/Inf values over every output of every method (must be 0).
    pub non_finite: usize,
    /// Failed range checks (visibility outside [0, 1], depth ≤ 0, sky not fully visible, ...).
    pub failures: Vec<String>,
    /// Observations: mean visibility of the non-sky pixels per method, and the like.
    pub notes: Vec<String>,
    pub ok: bool,
    pub ms: f64,
    pub outputs: Vec<OutputCheck>,
}

#[derive(Clone, Debug, Serialize)]
pub struct DepthSample {
    pub distance: f64,
    /// The engine (DEPTH_COMPONENT32, standard Z): restored − exact, metres.
    pub engine_d32: f64,
    /// The stand-alone probe per mode (label, restored − exact), `None` when the mode is unavailable.
    pub probe: Vec<(String, Option<f64>)>,
    /// Theoretical distance step of one depth unit per mode (label, metres).
    pub step: Vec<(String, f64)>,
}

#[derive(Clone, Debug, Serialize)]
pub struct DepthConfigResult {
    pub near: f32,
    pub far: f32,
    pub samples: Vec<DepthSample>,
}

#[derive(Clone, Debug, Serialize)]
pub struct StressReport {
    pub renderer: String,
    pub software: bool,
    pub cases: Vec<CaseResult>,
    pub total_non_finite: usize,
    pub depth_precision: Vec<DepthConfigResult>,
    pub depth_probe_note: String,
    pub skipped: Vec<String>,
    pub run_s: f64,
}

/// Meshes the cases use, written once as OBJ into a folder.
struct Meshes {
    dir: PathBuf,
}

impl Meshes {
    fn new(dir: &Path) -> Result<Meshes> {
        std::fs::create_dir_all(dir)?;
        let mut wall = MeshData::default();
        shapes::add_box(
            &mut wall,
            Vec3::new(-1.0, 0.0, -50.0),
            Vec3::new(0.0, 4.0, 50.0),
        );
        let mut cube = MeshData::default();
        shapes::add_box(&mut cube, Vec3::splat(-1.0), Vec3::splat(1.0));
        let mut quad = MeshData::default();
        shapes::add_quad(
            &mut quad,
            [
                Vec3::new(-1.0, -1.0, 0.0),
                Vec3::new(1.0, -1.0, 0.0),
                Vec3::new(1.0, 1.0, 0.0),
                Vec3::new(-1.0, 1.0, 0.0),
            ],
            Vec3::Z,
        );
        let meshes: [(&str, MeshData); 6] = [
            ("ground", shapes::ground(50.0, 10)),
            ("big-ground", shapes::ground(20000.0, 40)),
            ("wall", wall),
            ("cube", cube),
            ("quad", quad),
            ("sphere", shapes::sphere(0.5, 24, 12)),
        ];
        for (name, m) in meshes {
            std::fs::write(dir.join(format!("{name}.obj")), shapes::to_obj(&m, name))?;
        }
        Ok(Meshes {
            dir: dir.to_path_buf(),
        })
    }

    fn object(&self, name: &str, position: Vec3, scale: Vec3) -> ObjectDesc {
        ObjectDesc {
            mesh: self.dir.join(format!("{name}.obj")).display().to_string(),
            position: position.to_array(),
            rotation: [0.0; 3],
            scale: scale.to_array(),
            color: [0.8, 0.8, 0.8, 1.0],
        }
    }
}

/// A scene description with no objects and the defaults (no bloom: it does not touch AO).
fn base(w: u32, h: u32, eye: Vec3, target: Vec3) -> SceneDesc {
    let mut s = SceneDesc::default();
    s.output.width = w;
    s.output.height = h;
    s.camera.eye = eye.to_array();
    s.camera.target = target.to_array();
    s.bloom.enabled = false;
    s
}

/// Floor, a wall along Z (a 90° crease), a cube and a sphere: occlusion at several scales.
fn crease(m: &Meshes, w: u32, h: u32) -> SceneDesc {
    let mut s = base(w, h, Vec3::new(4.0, 2.5, 4.0), Vec3::new(0.0, 0.5, 0.0));
    s.objects.push(m.object("ground", Vec3::ZERO, Vec3::ONE));
    s.objects.push(m.object("wall", Vec3::ZERO, Vec3::ONE));
    s.objects
        .push(m.object("cube", Vec3::new(1.5, 0.5, -1.0), Vec3::splat(0.5)));
    s.objects
        .push(m.object("sphere", Vec3::new(1.0, 0.0, 1.5), Vec3::ONE));
    s
}

struct Case {
    category: &'static str,
    name: String,
    scene: SceneDesc,
    methods: Vec<AoMethod>,
    /// Every pixel must be fully visible (sky-only frames).
    all_visible: bool,
}

fn cases(m: &Meshes, large: bool) -> (Vec<Case>, Vec<String>) {
    let all = AoMethod::ALL.to_vec();
    let (w, h) = (160, 90);
    let mut v = Vec::new();
    let mut skipped = Vec::new();
    let mut push = |category: &'static str, name: String, scene: SceneDesc| {
        v.push(Case {
            category,
            name,
            scene,
            methods: all.clone(),
            all_visible: false,
        });
    };
    for near in [0.01f32, 0.1, 0.35, 1.0] {
        for far in [100.0f32, 1e3, 1e4, 1e5, 1e6] {
            let mut s = crease(m, w, h);
            s.camera.near = near;
            s.camera.far = far;
            push("near/far", format!("near {near} far {far}"), s);
        }
    }
    for r in [1e-3f32, 1e-2, 0.1, 1.0, 10.0, 100.0] {
        let mut s = crease(m, w, h);
        s.ao.radius = r;
        push("radius", format!("radius {r} m"), s);
    }
    for i in [0.0f32, 1e-3, 1.0, 5.0, 100.0, 1000.0] {
        let mut s = crease(m, w, h);
        s.ao.intensity = i;
        push("intensity", format!("intensity {i}"), s);
    }
    for b in [0.0f32, 10.0] {
        let mut s = crease(m, w, h);
        s.ao.bias = b;
        push("bias", format!("bias {b} m"), s);
    }
    for n in [1u32, 256] {
        let mut s = crease(m, w, h);
        s.ao.samples = n;
        push("samples", format!("samples {n}"), s);
    }
    for fov in [10.0f32, 30.0, 90.0, 120.0, 150.0] {
        let mut s = crease(m, w, h);
        s.camera.fov_y = fov;
        push("fov", format!("fov {fov}°"), s);
    }
    for (sw, sh) in [(1u32, 1u32), (3, 5), (5, 3), (4097, 3), (3, 4097)] {
        push("size", format!("{sw}×{sh}"), crease(m, sw, sh));
    }
    if large {
        let s = crease(m, 4096, 4096);
        v.push(Case {
            category: "size",
            name: "4096×4096".into(),
            scene: s,
            // One method at this size keeps the stress run within minutes on software GL.
            methods: vec![AoMethod::SaoLesson],
            all_visible: false,
        });
    } else {
        skipped.push("4096×4096 (--no-large)".to_string());
    }
    let mut push = |category: &'static str, name: String, scene: SceneDesc| {
        v.push(Case {
            category,
            name,
            scene,
            methods: all.clone(),
            all_visible: false,
        });
    };
    // Camera inside geometry: inside the cube, inside the wall, and in the floor.
    let mut s = crease(m, w, h);
    s.camera.eye = [1.5, 0.5, -1.0];
    s.camera.target = [0.0, 0.5, 0.0];
    push("inside", "eye inside the cube".into(), s);
    let mut s = crease(m, w, h);
    s.camera.eye = [-0.5, 2.0, 0.0];
    s.camera.target = [3.0, 0.0, 0.0];
    push("inside", "eye inside the wall".into(), s);
    let mut s = crease(m, w, h);
    s.camera.eye = [3.0, 0.0, 3.0];
    s.camera.target = [0.0, 0.5, 0.0];
    push("inside", "eye on the floor plane".into(), s);
    // A facing plane at, just before and just after the near plane.
    for (label, k) in [
        ("0.999", 0.999f32),
        ("exactly", 1.0),
        ("1.001", 1.001),
        ("2×", 2.0),
    ] {
        let mut s = base(w, h, Vec3::ZERO, Vec3::NEG_Z);
        let near = s.camera.near;
        let d = near * k;
        s.objects.push(m.object(
            "quad",
            Vec3::new(0.0, 0.0, -d),
            Vec3::new(4.0 * d, 4.0 * d, 1.0),
        ));
        // And a floor, so that the plane's edge has something to occlude.
        s.objects
            .push(m.object("ground", Vec3::new(0.0, -0.5 * d, 0.0), Vec3::ONE));
        push(
            "near plane",
            format!("facing plane at {label} near ({d} m)"),
            s,
        );
    }
    // Grazing views of a large open plane: eye 1 m up, looking at the ground z metres away.
    for z in [1.0f32, 10.0, 100.0, 1000.0] {
        let mut s = base(w, h, Vec3::new(0.0, 1.0, 0.0), Vec3::new(0.0, 0.0, -z));
        s.objects
            .push(m.object("big-ground", Vec3::ZERO, Vec3::ONE));
        push("grazing", format!("open plane, look at z = {z} m"), s);
    }
    // Sky only.
    for (sw, sh) in [(64u32, 48u32), (1, 1), (4097, 3)] {
        v.push(Case {
            category: "sky",
            name: format!("sky only {sw}×{sh}"),
            scene: base(sw, sh, Vec3::new(0.0, 1.6, 6.0), Vec3::ZERO),
            methods: all.clone(),
            all_visible: true,
        });
    }
    // One-pixel and sub-pixel objects against the sky and in front of a far wall.
    for (label, dist) in [("about 1 px", 100.0f32), ("about 0.25 px", 400.0)] {
        let mut s = base(w, h, Vec3::new(0.0, 0.5, 0.0), Vec3::new(0.0, 0.5, -1.0));
        s.objects
            .push(m.object("sphere", Vec3::new(0.0, 0.0, -dist), Vec3::ONE));
        v.push(Case {
            category: "tiny object",
            name: format!("sphere {label}, sky behind"),
            scene: s.clone(),
            methods: all.clone(),
            all_visible: false,
        });
        s.objects
            .push(m.object("quad", Vec3::new(0.0, 0.5, -dist - 5.0), Vec3::splat(dist)));
        v.push(Case {
            category: "tiny object",
            name: format!("sphere {label}, wall 5 m behind"),
            scene: s,
            methods: all.clone(),
            all_visible: false,
        });
    }
    (v, skipped)
}

fn check(out: &mut Vec<OutputCheck>, method: AoMethod, name: &str, v: &[f32]) -> usize {
    let bad = v.iter().filter(|x| !x.is_finite()).count();
    let (mut lo, mut hi) = (f32::INFINITY, f32::NEG_INFINITY);
    for x in v.iter().filter(|x| x.is_finite()) {
        lo = lo.min(*x);
        hi = hi.max(*x);
    }
    out.push(OutputCheck {
        method: method.name().into(),
        output: name.into(),
        values: v.len(),
        non_finite: bad,
        min: if lo.is_finite() { lo } else { 0.0 },
        max: if hi.is_finite() { hi } else { 0.0 },
    });
    bad
}

fn run_case(ctx: &HeadlessContext, res: &ResDirs, case: &Case) -> Result<CaseResult> {
    let t = Instant::now();
    let s = &case.scene;
    let (w, h) = (s.output.width, s.output.height);
    let mut eng = Engine::new(&ctx.gl, res.clone(), s, w, h)?;
    let mut outputs = Vec::new();
    let mut failures = Vec::new();
    let mut notes = Vec::new();
    let mut non_finite = 0;
    let (mut visibility, mut surface_px) = (Vec::new(), 0usize);
    for &method in &case.methods {
        eng.ao_settings.method = method;
        eng.sync_shader_constants()?;
        let mn = method.name();
        let img = eng.render_image()?;
        if img.dimensions() != (w, h) {
            failures.push(format!("{mn}: composite is {:?}", img.dimensions()));
        }
        non_finite += check(
            &mut outputs,
            method,
            "main colour (RGBA16F)",
            &eng.fbo_main.color_texture().unwrap().read_f32(0, 4),
        );
        for level in 0..eng.ao_targets()?.tex_depth.levels() {
            let v = eng.ao_targets()?.tex_depth.read_f32(level, 1);
            non_finite += check(
                &mut outputs,
                method,
                &format!("linear depth level {level}"),
                &v,
            );
            if v.iter().any(|d| *d <= 0.0) {
                failures.push(format!(
                    "{mn}: linear depth level {level} has a distance ≤ 0"
                ));
            }
        }
        non_finite += check(
            &mut outputs,
            method,
            "AO buffer",
            &eng.ao_targets()?.sao_texture().read_f32(0, 1),
        );
        non_finite += check(
            &mut outputs,
            method,
            "blurred AO buffer",
            &eng.ao_targets()?.result_texture(true).read_f32(0, 1),
        );
        let depth = eng.render_values(View::LinearDepth)?;
        non_finite += check(&mut outputs, method, "values: linear depth", &depth);
        if depth.iter().any(|d| *d <= 0.0) {
            failures.push(format!("{mn}: linear-depth view has a distance ≤ 0"));
        }
        let far = eng.camera.far;
        for view in [View::AoRaw, View::Ao] {
            let v = eng.render_values(view)?;
            non_finite += check(
                &mut outputs,
                method,
                &format!("values: {}", view.label()),
                &v,
            );
            if v.iter().any(|a| !(0.0..=1.0).contains(a)) {
                failures.push(format!("{mn}: {} outside [0, 1]", view.label()));
            }
            if case.all_visible && v.iter().any(|a| *a != 1.0) {
                failures.push(format!(
                    "{mn}: sky-only frame is not fully visible in the {} view",
                    view.label()
                ));
            }
            if view == View::Ao {
                // Mean visibility of surface pixels (those nearer than far).
                let (sum, n) = v
                    .iter()
                    .zip(&depth)
                    .filter(|(a, d)| a.is_finite() && **d < far)
                    .fold((0.0f64, 0usize), |(s, n), (a, _)| (s + *a as f64, n + 1));
                if n > 0 {
                    visibility.push(format!("{mn} {:.3}", sum / n as f64));
                    surface_px = n;
                }
            }
        }
        if let Some(e) = crate::gl::take_error(&ctx.gl) {
            failures.push(format!("{mn}: {e}"));
        }
    }
    if visibility.is_empty() {
        notes.push("no surface pixel".to_string());
    } else {
        notes.push(format!(
            "mean surface visibility ({surface_px} px): {}",
            visibility.join(", ")
        ));
    }
    Ok(CaseResult {
        category: case.category.into(),
        name: case.name.clone(),
        width: w,
        height: h,
        near: s.camera.near,
        far: s.camera.far,
        fov_y: s.camera.fov_y,
        radius: eng.ao_settings.radius,
        intensity: eng.ao_settings.intensity,
        bias: eng.ao_settings.bias,
        methods: case.methods.iter().map(|m| m.name().to_string()).collect(),
        non_finite,
        ok: non_finite == 0 && failures.is_empty(),
        failures,
        notes,
        ms: t.elapsed().as_secs_f64() * 1e3,
        outputs,
    })
}

/// Distances for the depth table: 1, 2 and 5 per decade (× 1.037 so that they are not round), within
/// (near, far), plus just past near and just before far.
pub fn depth_distances(near: f64, far: f64) -> Vec<f64> {
    let mut v = vec![near * 1.01];
    let mut k = near.log10().floor() as i32;
    while 10f64.powi(k) < far {
        for m in [1.0, 2.0, 5.0] {
            let d = m * 10f64.powi(k) * 1.037;
            if d > near * 1.01 && d < far * 0.99 {
                v.push(d);
            }
        }
        k += 1;
    }
    v.push(far * 0.99);
    v
}

/// The engine's restored linear depth of a facing plane at each distance (DEPTH_COMPONENT32).
fn engine_depths(
    ctx: &HeadlessContext,
    res: &ResDirs,
    m: &Meshes,
    near: f32,
    far: f32,
    distances: &[f64],
) -> Result<Vec<f32>> {
    let mut s = base(8, 8, Vec3::ZERO, Vec3::NEG_Z);
    s.camera.near = near;
    s.camera.far = far;
    s.light.shadow = false;
    s.objects
        .push(m.object("quad", Vec3::new(0.0, 0.0, -1.0), Vec3::ONE));
    let mut eng = Engine::new(&ctx.gl, res.clone(), &s, 8, 8)?;
    let mut out = Vec::new();
    for &d in distances {
        let d32 = d as f32;
        eng.objects[0].position = Vec3::new(0.0, 0.0, -d32);
        eng.objects[0].scale = Vec3::new(3.0 * d32, 3.0 * d32, 1.0);
        // The engine culls objects by their world bounds: keep them in step with the move.
        eng.objects[0].bounds = (
            Vec3::new(-3.0 * d32, -3.0 * d32, -d32),
            Vec3::new(3.0 * d32, 3.0 * d32, -d32),
        );
        let v = eng.render_values(View::LinearDepth)?;
        out.push(v[4 * 8 + 4]);
    }
    Ok(out)
}

pub const DEPTH_CONFIGS: [(f32, f32); 5] = [
    (0.35, 1000.0),
    (0.01, 100.0),
    (0.1, 1e4),
    (1.0, 1e6),
    (0.01, 1e6),
];

pub fn run(res: &ResDirs, cfg: &StressConfig) -> Result<StressReport> {
    let t0 = Instant::now();
    std::fs::create_dir_all(&cfg.out)
        .with_context(|| format!("cannot create {}", cfg.out.display()))?;
    let mesh_dir = std::env::temp_dir().join(format!("opengl3d-stress-{}", std::process::id()));
    let meshes = Meshes::new(&mesh_dir)?;
    let ctx = HeadlessContext::new()?;
    let (mut cases, mut skipped) = cases(&meshes, cfg.large);
    if cfg.quick {
        let mut seen = Vec::new();
        let before = cases.len();
        cases.retain(|c| {
            let first = !seen.contains(&c.category);
            seen.push(c.category);
            first
        });
        skipped.push(format!(
            "{} cases (quick run: first case of each category)",
            before - cases.len()
        ));
    }
    let depth_configs: &[(f32, f32)] = if cfg.quick {
        &DEPTH_CONFIGS[..1]
    } else {
        &DEPTH_CONFIGS
    };
    let pb = if cfg.progress {
        let b = ProgressBar::new((cases.len() + depth_configs.len()) as u64);
        if let Ok(s) =
            ProgressStyle::with_template("stress {bar:40} {pos}/{len} [{elapsed_precise}] {msg}")
        {
            b.set_style(s.progress_chars("=> "));
        }
        b
    } else {
        ProgressBar::hidden()
    };
    let mut results = Vec::new();
    for case in &cases {
        pb.set_message(format!("{}: {}", case.category, case.name));
        let r = run_case(&ctx, res, case).with_context(|| format!("stress case {}", case.name))?;
        results.push(r);
        pb.inc(1);
    }

    let probe = DepthProbe::new(&ctx.gl)?;
    let mut depth_precision = Vec::new();
    for &(near, far) in depth_configs {
        pb.set_message(format!("depth precision near {near} far {far}"));
        let distances = depth_distances(near as f64, far as f64);
        let eng = engine_depths(&ctx, res, &meshes, near, far, &distances)?;
        let mut per_mode = Vec::new();
        for mode in DepthMode::ALL {
            let v = if probe.supports(mode) {
                Some(probe.measure(mode, near, far, &distances)?)
            } else {
                None
            };
            per_mode.push((mode, v));
        }
        let samples = distances
            .iter()
            .enumerate()
            .map(|(i, &d)| DepthSample {
                distance: d,
                engine_d32: eng[i] as f64 - d,
                probe: per_mode
                    .iter()
                    .map(|(m, v)| (m.label().to_string(), v.as_ref().map(|v| v[i] as f64 - d)))
                    .collect(),
                step: DepthMode::ALL
                    .iter()
                    .map(|m| {
                        (
                            m.label().to_string(),
                            m.theoretical_step(d, near as f64, far as f64),
                        )
                    })
                    .collect(),
            })
            .collect();
        depth_precision.push(DepthConfigResult { near, far, samples });
        pb.inc(1);
    }
    pb.finish_and_clear();
    let depth_probe_note = match &probe.clip_control_error {
        None => "glClipControl loaded through eglGetProcAddress; reversed-Z measured".to_string(),
        Some(e) => format!("reversed-Z not measured: {e}"),
    };
    drop(probe);
    let _ = std::fs::remove_dir_all(&mesh_dir);

    let total_non_finite = results.iter().map(|r| r.non_finite).sum();
    let report = StressReport {
        renderer: ctx.renderer.clone(),
        software: ctx.software,
        cases: results,
        total_non_finite,
        depth_precision,
        depth_probe_note,
        skipped,
        run_s: t0.elapsed().as_secs_f64(),
    };
    std::fs::write(
        cfg.out.join("stress.json"),
        serde_json::to_string_pretty(&report)?,
    )?;
    std::fs::write(cfg.out.join("stress.md"), markdown(&report))?;
    Ok(report)
}

fn sci(v: f64) -> String {
    if v == 0.0 {
        "0".into()
    } else {
        format!("{v:.2e}")
    }
}

fn markdown(r: &StressReport) -> String {
    use std::fmt::Write as _;
    let mut s = String::new();
    let _ = writeln!(s, "# AO numerical stress report\n");
    let _ = writeln!(
        s,
        "`opengl3d bench --stress` on **{}**, {:.0} s.\n",
        r.renderer, r.run_s
    );
    let failed = r.cases.iter().filter(|c| !c.ok).count();
    let _ = writeln!(
        s,
        "**{} cases, {} NaN/Inf values in all outputs, {} cases with a failed check.**\n",
        r.cases.len(),
        r.total_non_finite,
        failed
    );
    let _ = writeln!(
        s,
        "Each case renders the composite frame and the linear-depth, raw-AO and AO value views with \
         each listed method and counts NaN/Inf in: the main colour buffer (RGBA16F), every level of the \
         linear-depth mip chain, the raw and blurred AO buffers, and the three value views. Checks: \
         visibility in [0, 1], linear depth > 0, sky-only frames fully visible (1). Notes give the mean \
         AO-view visibility of surface pixels (an open plane should stay near 1: lower values there are \
         false occlusion).\n"
    );
    if !r.skipped.is_empty() {
        let _ = writeln!(s, "Skipped: {}.\n", r.skipped.join(", "));
    }
    let _ = writeln!(s, "| category | case | size | near | far | fov | radius | intensity | methods | NaN/Inf | result | ms | notes |");
    let _ = writeln!(
        s,
        "|---|---|---|---:|---:|---:|---:|---:|---|---:|---|---:|---|"
    );
    for c in &r.cases {
        let methods = if c.methods.len() == AoMethod::ALL.len() {
            "all".to_string()
        } else {
            c.methods.join(", ")
        };
        let result = if c.ok {
            "ok".to_string()
        } else {
            format!("**FAIL**: {}", c.failures.join("; "))
        };
        let _ = writeln!(
            s,
            "| {} | {} | {}×{} | {} | {} | {}° | {} | {} | {} | {} | {} | {:.0} | {} |",
            c.category,
            c.name,
            c.width,
            c.height,
            c.near,
            c.far,
            c.fov_y,
            c.radius,
            c.intensity,
            methods,
            c.non_finite,
            result,
            c.ms,
            c.notes.join("; ")
        );
    }
    let _ = writeln!(
        s,
        "\n## Linear-depth reconstruction error against distance\n"
    );
    let _ = writeln!(
        s,
        "A plane facing the camera (60° fov) at a known distance z; the table gives restored − exact \
         distance in metres. **engine D32** is the engine itself (`render_values(View::LinearDepth)`: \
         DEPTH_COMPONENT32 main depth, `sao_restore_depth.frag`). The **probe** columns come from a small \
         stand-alone pipeline in `src/bench/depth_formats.rs` that draws the same plane into a depth \
         texture of the named format and restores it with the same formula in GLSL (standard: \
         `A / ((2d − 1) − B)`, GL [-1, 1] clip space, LEQUAL); reversed-Z uses \
         `glClipControl(GL_LOWER_LEFT, GL_ZERO_TO_ONE)`, DEPTH32F, GREATER, cleared to 0, restored with \
         `n·f / (d·(f − n) + n)`. The engine itself has no option for its depth format: those columns \
         are what such an option would give. Steps are the theoretical distance of one depth-buffer \
         unit, quantisation only, without the f32 arithmetic of projection and restore (unorm: \
         z²(f − n)/(f·n)·2⁻ᴺ; D32F standard: 2⁻²³ of NDC; reversed D32F: d·2⁻²³ with d ≈ n/z). The \
         sample at 0.99·far can round onto the far plane and read back as sky (= far). \
         {}\n",
        r.depth_probe_note
    );
    // Summary: the largest relative error per mode, over distances up to half of far (the last
    // sample, at 0.99·far, can round onto the far plane and read back as sky = far).
    if let Some(first) = r.depth_precision.first().and_then(|c| c.samples.first()) {
        let labels: Vec<String> = first
            .probe
            .iter()
            .map(|p| p.0.replace("DEPTH_COMPONENT", "D"))
            .collect();
        let _ = writeln!(s, "Largest |restored − exact| / z for z ≤ far / 2:\n");
        let _ = writeln!(
            s,
            "| near | far | engine D32 | {} |",
            labels
                .iter()
                .map(|l| format!("probe {l}"))
                .collect::<Vec<_>>()
                .join(" | ")
        );
        let _ = writeln!(s, "|---:|---:|---:|{}", "---:|".repeat(labels.len()));
        for c in &r.depth_precision {
            let near_half: Vec<&DepthSample> = c
                .samples
                .iter()
                .filter(|x| x.distance <= c.far as f64 * 0.5)
                .collect();
            let worst = |f: &dyn Fn(&DepthSample) -> Option<f64>| {
                near_half
                    .iter()
                    .filter_map(|x| f(x).map(|e| (e / x.distance).abs()))
                    .fold(None, |m: Option<f64>, v| Some(m.map_or(v, |m| m.max(v))))
                    .map_or("n/a".to_string(), sci)
            };
            let probes: Vec<String> = (0..labels.len())
                .map(|i| worst(&|x: &DepthSample| x.probe[i].1))
                .collect();
            let _ = writeln!(
                s,
                "| {} | {} | {} | {} |",
                c.near,
                c.far,
                worst(&|x: &DepthSample| Some(x.engine_d32)),
                probes.join(" | ")
            );
        }
        let _ = writeln!(s);
    }
    for c in &r.depth_precision {
        let _ = writeln!(s, "### near {} m, far {} m\n", c.near, c.far);
        let labels: Vec<String> = c.samples.first().map_or(Vec::new(), |x| {
            x.probe.iter().map(|p| p.0.clone()).collect()
        });
        let _ = writeln!(
            s,
            "| z (m) | engine D32 | {} | step D24 | step D32F | step D32F rev-Z |",
            labels
                .iter()
                .map(|l| format!("probe {}", l.replace("DEPTH_COMPONENT", "D")))
                .collect::<Vec<_>>()
                .join(" | ")
        );
        let _ = writeln!(
            s,
            "|---:|---:|{}---:|---:|---:|",
            "---:|".repeat(labels.len())
        );
        for x in &c.samples {
            let probe: Vec<String> = x
                .probe
                .iter()
                .map(|p| p.1.map_or("n/a".into(), sci))
                .collect();
            let step = |label: &str| {
                x.step
                    .iter()
                    .find(|p| p.0 == label)
                    .map_or("".into(), |p| sci(p.1))
            };
            let _ = writeln!(
                s,
                "| {:.4} | {} | {} | {} | {} | {} |",
                x.distance,
                sci(x.engine_d32),
                probe.join(" | "),
                step(DepthMode::D24.label()),
                step(DepthMode::D32F.label()),
                step(DepthMode::D32FReversed.label())
            );
        }
        let _ = writeln!(s);
    }
    s
}
