//! Shared helpers for the GL tests: a headless context per test thread, scenes built from generated
//! meshes in a temporary folder, and projection of world points to pixels.
#![allow(dead_code)]

use glam::{Vec3, Vec4};
use opengl3d::gl::mesh::MeshData;
use opengl3d::platform::HeadlessContext;
use opengl3d::render::Engine;
use opengl3d::res::ResDirs;
use opengl3d::scene::{shapes, ObjectDesc, SceneDesc};
use std::path::{Path, PathBuf};

pub fn context() -> HeadlessContext {
    HeadlessContext::new().expect("headless GL 4.5 context (Mesa EGL)")
}

/// A fresh temporary folder under the target dir (kept for inspection after a failure).
pub fn temp_dir(name: &str) -> PathBuf {
    let d = Path::new(env!("CARGO_TARGET_TMPDIR")).join(format!("{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

/// Writes `mesh` as OBJ into `dir` and returns an object description for it.
pub fn object(dir: &Path, name: &str, mesh: &MeshData, position: Vec3, scale: Vec3) -> ObjectDesc {
    let p = dir.join(format!("{name}.obj"));
    if !p.exists() {
        std::fs::write(&p, shapes::to_obj(mesh, name)).unwrap();
    }
    ObjectDesc {
        mesh: p.display().to_string(),
        position: position.to_array(),
        rotation: [0.0; 3],
        scale: scale.to_array(),
        color: [0.8, 0.8, 0.8, 1.0],
    }
}

/// The ground (50 m, y = 0) and `meshes` (name, mesh, untransformed) after it, seen from `eye`
/// towards `target` at `w`×`h`, bloom off: the set-up the AO tests share.
pub fn floor_and(
    dir: &Path,
    meshes: &[(&str, &MeshData)],
    eye: Vec3,
    target: Vec3,
    (w, h): (u32, u32),
) -> SceneDesc {
    let mut s = SceneDesc::default();
    s.objects.push(object(
        dir,
        "floor",
        &shapes::ground(50.0, 10),
        Vec3::ZERO,
        Vec3::ONE,
    ));
    for (name, mesh) in meshes {
        s.objects
            .push(object(dir, name, mesh, Vec3::ZERO, Vec3::ONE));
    }
    s.camera.eye = eye.to_array();
    s.camera.target = target.to_array();
    s.output.width = w;
    s.output.height = h;
    s.bloom.enabled = false;
    s
}

/// A floor (y = 0) and a wall (the plane x = 0, extending to −x): a 90° crease along the Z axis.
pub fn crease_scene(dir: &Path, eye: Vec3, target: Vec3, w: u32, h: u32) -> SceneDesc {
    let mut wall = MeshData::default();
    shapes::add_box(
        &mut wall,
        Vec3::new(-1.0, 0.0, -50.0),
        Vec3::new(0.0, 4.0, 50.0),
    );
    floor_and(dir, &[("wall", &wall)], eye, target, (w, h))
}

pub fn engine(ctx: &HeadlessContext, scene: &SceneDesc) -> Engine {
    Engine::new(
        &ctx.gl,
        ResDirs::default(),
        scene,
        scene.output.width,
        scene.output.height,
    )
    .expect("engine")
}

/// Pixel (x, y from the bottom, GL convention) of world point `p` in a `w`×`h` buffer.
pub fn project(engine: &Engine, p: Vec3, w: u32, h: u32) -> (usize, usize) {
    let (ew, eh) = engine.size();
    let clip = engine.camera.view_projection(ew as f32 / eh as f32) * Vec4::new(p.x, p.y, p.z, 1.0);
    let ndc = clip.truncate() / clip.w;
    let x = ((ndc.x * 0.5 + 0.5) * w as f32)
        .floor()
        .clamp(0.0, w as f32 - 1.0) as usize;
    let y = ((ndc.y * 0.5 + 0.5) * h as f32)
        .floor()
        .clamp(0.0, h as f32 - 1.0) as usize;
    (x, y)
}

/// Mean of a square window of radius `r` around (x, y) in a row-major bottom-up buffer.
pub fn mean_around(data: &[f32], w: usize, h: usize, x: usize, y: usize, r: usize) -> f32 {
    let mut sum = 0.0;
    let mut n = 0.0;
    for yy in y.saturating_sub(r)..=(y + r).min(h - 1) {
        for xx in x.saturating_sub(r)..=(x + r).min(w - 1) {
            sum += data[yy * w + xx];
            n += 1.0;
        }
    }
    sum / n
}

pub fn assert_finite(label: &str, data: &[f32]) {
    let bad = data.iter().filter(|v| !v.is_finite()).count();
    assert_eq!(
        bad,
        0,
        "{label}: {bad} of {} values are NaN or Inf",
        data.len()
    );
}

/// World-space surface point of every non-sky pixel: (pixel index, point).
pub fn surface_points(
    img: &opengl3d::tools::reference::RefImage,
    cam: &opengl3d::math::Camera,
) -> Vec<(usize, Vec3)> {
    let fwd = opengl3d::tools::reference::view_direction(cam);
    let mut out = Vec::new();
    for y in 0..img.height {
        for x in 0..img.width {
            let i = img.index(x, y);
            let depth = img.linear_depth[i];
            if depth.is_finite() {
                let dir = opengl3d::tools::reference::pixel_dir(cam, x, y, img.width, img.height)
                    .unwrap();
                out.push((i, cam.eye + dir * (depth / dir.dot(fwd))));
            }
        }
    }
    out
}

/// The `opengl3d` binary under test, its reference cache in a temp folder (never the user's).
pub fn bin() -> std::process::Command {
    let mut c = std::process::Command::new(env!("CARGO_BIN_EXE_opengl3d"));
    c.env(opengl3d::tools::reference::CACHE_ENV, test_cache());
    c
}

/// The reference cache of the tests' command-line runs.
pub fn test_cache() -> PathBuf {
    std::env::temp_dir().join("opengl3d-tests-reference-cache")
}

/// Runs the binary with `args` and waits for it.
pub fn run<S: AsRef<std::ffi::OsStr>>(args: &[S]) -> std::process::Output {
    bin().args(args).output().expect("run opengl3d")
}

pub fn stderr(o: &std::process::Output) -> String {
    String::from_utf8_lossy(&o.stderr).to_string()
}

/// Runs `args`, expects a failure whose message holds every needle (and no panic), and returns the
/// message.
pub fn fails_with<S: AsRef<std::ffi::OsStr>>(args: &[S], needles: &[&str]) -> String {
    let o = run(args);
    let shown: Vec<String> = args
        .iter()
        .map(|a| a.as_ref().to_string_lossy().into_owned())
        .collect();
    assert!(!o.status.success(), "should fail: {shown:?}");
    let e = stderr(&o);
    for n in needles {
        assert!(
            e.contains(n),
            "error for {shown:?} should mention '{n}', got:\n{e}"
        );
    }
    assert!(!e.contains("panicked"), "must not panic:\n{e}");
    e
}

/// Mean visibility of `img` over `pixels` (indices into its rows).
pub fn mean_over(img: &opengl3d::tools::reference::RefImage, pixels: &[usize]) -> f64 {
    pixels.iter().map(|i| img.ao[*i] as f64).sum::<f64>() / pixels.len().max(1) as f64
}

/// The engine's `sao` at `radius` m and `intensity` (blurred or not), and what its passes draw
/// with: for the tests that drive one method's passes on synthetic depth.
pub fn sao_pass(
    ctx: &HeadlessContext,
    radius: f32,
    intensity: f32,
    blur: bool,
) -> (
    opengl3d::ao::AoSettings,
    opengl3d::gl::MeshBuffer,
    opengl3d::ao::method::sao::SaoMethod,
) {
    let settings = opengl3d::ao::AoSettings {
        method: opengl3d::ao::AoMethod::Sao,
        radius,
        intensity,
        blur,
        ..Default::default()
    };
    let meshes = opengl3d::gl::MeshBuffer::new(&ctx.gl).unwrap();
    let camera = opengl3d::math::Camera::default();
    let sao =
        opengl3d::ao::method::sao::SaoMethod::build(&ctx.gl, &ResDirs::default(), &camera).unwrap();
    (settings, meshes, sao)
}

/// A method's inputs with nothing but the depth chain in `targets` (no surface passes, no sky
/// skip, no jitter), over `region`.
pub fn depth_only_inputs<'a>(
    ctx: &'a HeadlessContext,
    meshes: &'a opengl3d::gl::MeshBuffer,
    targets: &'a opengl3d::ao::AoTargets,
    camera: &'a opengl3d::math::Camera,
    settings: &'a opengl3d::ao::AoSettings,
    region: Option<[i32; 4]>,
) -> opengl3d::ao::method_pass::AoInputs<'a> {
    opengl3d::ao::method_pass::AoInputs {
        gl: &ctx.gl,
        meshes,
        targets,
        camera,
        settings,
        back_depth: None,
        normals: None,
        second_depth: None,
        second_back_depth: None,
        objects: &[],
        region,
        ao_size_depth: None,
        frame_jitter: [0.0; 2],
    }
}
