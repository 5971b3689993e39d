//! The command line (`opengl3d`): the demo in a window, or frames rendered headless.

use crate::ao::{AoMethod, CompositeMode, GtaoQuality};
use crate::math::DepthMode;
use crate::platform::{self, HeadlessContext};
use crate::render::{Engine, View};
use crate::res::ResDirs;
use crate::scene::SceneDesc;
use anyhow::{bail, Context as _, Result};
use clap::builder::TypedValueParser as _;
use clap::{Args, Parser, Subcommand, ValueEnum};
use glam::Vec3;
use std::path::{Path, PathBuf};

#[derive(Parser, Debug)]
#[command(
    name = "opengl3d",
    version,
    about = "OpenGL 4.5 course engine with screen-space ambient occlusion (SAO)"
)]
pub struct Cli {
    /// Folder searched for shaders and meshes before the project's own Res/ (a student's working copy).
    #[arg(long, global = true, value_name = "DIR")]
    pub res: Option<PathBuf>,
    #[command(subcommand)]
    pub command: Option<Command>,
}

#[derive(Subcommand, Debug)]
pub enum Command {
    /// Render one frame headless and write it to a PNG or PFM file.
    Render(RenderArgs),
    /// Open the interactive window (WASD + mouse, F1: parameter panel, Space: AO, M: method, V: view,
    /// B: blur, R: reload shaders).
    Window(WindowArgs),
    /// Run the AO lesson at step N (1-12) showing that step's view, or `lesson start DIR` to write a
    /// starting folder whose lesson shaders are stubs.
    Lesson(LessonArgs),
    /// World-space ray-traced ambient occlusion of the scene on the CPU (the ground truth).
    Reference(ReferenceArgs),
    /// Grade a student's shaders (--res DIR) against the lesson's steps; exits non-zero on a failed step.
    Grade(crate::tools::grade::GradeArgs),
    /// (Internal) grade one step in a child process of `grade`; prints one JSON line.
    #[command(hide = true)]
    GradeStep(crate::tools::grade::GradeStepArgs),
    /// Run time against error of the AO methods, or `--stress` for numerical stability.
    Bench(crate::tools::bench::BenchArgs),
    /// Regenerate the demo meshes in Res/meshes.
    GenDemo,
}

#[derive(Args, Debug)]
pub struct ReferenceArgs {
    /// Scene flags; `--radius` is the ray length (m): a ray that hits nothing within it counts as
    /// open (default: the scene's AO radius, so the reference matches what `render` shows).
    #[command(flatten)]
    pub scene: SceneArgs,
    /// Cosine-weighted rays per pixel.
    #[arg(long, default_value_t = 256)]
    pub rays: u32,
    /// Ambient obscurance (hits weighted by (t/R)²) instead of binary visibility.
    #[arg(long, conflicts_with = "screen_space")]
    pub obscurance: bool,
    /// Screen-space reference instead: the same visibility computed exactly from the engine's
    /// full-resolution depth buffer seen as a heightfield (what a perfect screen-space method gets).
    #[arg(long)]
    pub screen_space: bool,
    /// Output: .pfm (raw visibility) or .png.
    #[arg(long, default_value = "out/reference.pfm")]
    pub out: PathBuf,
    /// Folder of cached results (keyed by scene, camera, size and parameters).
    #[arg(long, default_value = "out/reference-cache")]
    pub cache: PathBuf,
}

#[derive(Args, Debug)]
pub struct LessonArgs {
    /// Step number 1-12, or `start`.
    pub step: String,
    /// With `start`: the folder to create (then use it with --res).
    pub dir: Option<PathBuf>,
    #[command(flatten)]
    pub scene: SceneArgs,
    /// Render the step's view to --out instead of opening a window.
    #[arg(long)]
    pub headless: bool,
    #[arg(long, default_value = "out/lesson.png")]
    pub out: PathBuf,
}

#[derive(Copy, Clone, Debug, PartialEq, Eq, ValueEnum)]
pub enum OnOff {
    On,
    Off,
}

#[derive(Args, Debug, Clone, Default)]
pub struct SceneArgs {
    /// Scene file (TOML); default: Res/scenes/demo.toml.
    #[arg(long, value_name = "FILE", conflicts_with = "obj")]
    pub scene: Option<PathBuf>,
    /// Load one OBJ as the whole scene (identity transform, demo lighting and AO).
    #[arg(long, value_name = "FILE")]
    pub obj: Option<PathBuf>,
    /// Camera position, "x,y,z".
    #[arg(long, value_parser = parse_vec3, allow_hyphen_values = true)]
    pub eye: Option<Vec3>,
    /// Point the camera looks at, "x,y,z" (up is +Y).
    #[arg(long, value_parser = parse_vec3, allow_hyphen_values = true)]
    pub target: Option<Vec3>,
    /// Vertical field of view in degrees.
    #[arg(long)]
    pub fov: Option<f32>,
    #[arg(long)]
    pub near: Option<f32>,
    #[arg(long)]
    pub far: Option<f32>,
    #[arg(long)]
    pub width: Option<u32>,
    #[arg(long)]
    pub height: Option<u32>,
    /// Main depth buffer: d32 (the course's) or d32f-reversed (reversed-Z: far surfaces keep precision).
    #[arg(long, value_parser = choice(&DepthMode::ALL, DepthMode::name))]
    pub depth: Option<DepthMode>,
    /// Ambient occlusion on or off.
    #[arg(long, value_enum)]
    pub ao: Option<OnOff>,
    /// AO method.
    #[arg(long, value_parser = choice(&AoMethod::ALL, AoMethod::name))]
    pub method: Option<AoMethod>,
    /// AO sample count (per method: samples, or directions × steps); overrides a scene's GTAO quality.
    #[arg(long, conflicts_with = "quality")]
    pub samples: Option<u32>,
    /// GTAO quality preset: low 1×4, medium 2×4, high 3×6, ultra 4×8 (slices × steps per side).
    #[arg(long, value_parser = choice(&GtaoQuality::ALL, GtaoQuality::name))]
    pub quality: Option<GtaoQuality>,
    /// AO radius in metres.
    #[arg(long)]
    pub radius: Option<f32>,
    /// How AO reaches the picture: the lesson's blend, tinted, or on the ambient term only.
    #[arg(long, value_parser = choice(&CompositeMode::ALL, CompositeMode::name))]
    pub composite: Option<CompositeMode>,
    /// Tint colour for `--composite tinted`, "r,g,b" in 0..1.
    #[arg(long, value_parser = parse_vec3)]
    pub tint: Option<Vec3>,
    /// Power applied to visibility before compositing.
    #[arg(long)]
    pub power: Option<f32>,
}

#[derive(Args, Debug)]
pub struct RenderArgs {
    #[command(flatten)]
    pub scene: SceneArgs,
    /// What to write: the lit composite, linear depth (m), raw SAO or blurred SAO (visibility, 1 = open).
    #[arg(long, value_parser = choice(&View::ALL, View::name), default_value = "composite")]
    pub view: View,
    /// Output file: .png (8-bit) or .pfm (raw floats).
    #[arg(long, default_value = "out/frame.png")]
    pub out: PathBuf,
    /// Print each pass of the frame (name, group, ms, draw calls) as JSON on stdout.
    #[arg(long)]
    pub stats: bool,
}

#[derive(Args, Debug)]
pub struct WindowArgs {
    #[command(flatten)]
    pub scene: SceneArgs,
    #[arg(long, value_parser = choice(&View::ALL, View::name), default_value = "composite")]
    pub view: View,
    /// Close after this many frames (for scripted runs and tests).
    #[arg(long)]
    pub frames: Option<u32>,
    /// Save the last frame shown to this PNG (with --frames): the engine's frame, as `render` draws it.
    #[arg(long)]
    pub screenshot: Option<PathBuf>,
    /// The screenshot holds what is on screen, parameter panel and error overlay included.
    #[arg(long)]
    pub screenshot_ui: bool,
    /// Start with the parameter panel hidden (F1 shows it). Also: OPENGL3D_PANEL=off.
    #[arg(long)]
    pub no_panel: bool,
    /// Start with per-pass timing on (the panel's "time each pass"). Also: OPENGL3D_TIME_PASSES=1.
    #[arg(long)]
    pub time_passes: bool,
}

/// A parser for one of `all`, by the names `name` gives (the domain types know their names; only
/// the command line knows clap).
pub fn choice<T: Copy + Send + Sync + 'static>(
    all: &'static [T],
    name: fn(T) -> &'static str,
) -> impl clap::builder::TypedValueParser<Value = T> {
    let names: Vec<&'static str> = all.iter().map(|v| name(*v)).collect();
    clap::builder::PossibleValuesParser::new(names).map(move |s: String| {
        *all.iter()
            .find(|v| name(**v) == s)
            .expect("clap accepted only listed names")
    })
}

fn parse_vec3(s: &str) -> Result<Vec3, String> {
    let v: Vec<f32> = s
        .split(',')
        .map(|p| {
            p.trim()
                .parse::<f32>()
                .map_err(|_| format!("'{p}' is not a number"))
        })
        .collect::<Result<_, _>>()?;
    if v.len() != 3 || v.iter().any(|x| !x.is_finite()) {
        return Err(format!("expected three finite numbers 'x,y,z', got '{s}'"));
    }
    Ok(Vec3::new(v[0], v[1], v[2]))
}

/// Loads the scene the arguments describe, with overrides applied and checked.
pub fn load_scene(args: &SceneArgs, res: &ResDirs) -> Result<SceneDesc> {
    let mut desc = if let Some(obj) = &args.obj {
        let path = obj
            .canonicalize()
            .with_context(|| format!("{}: OBJ file not found", obj.display()))?;
        let mut d = SceneDesc::single_obj(&path.display().to_string());
        // Frame the object unless the camera is given.
        let data = crate::gl::mesh::MeshData::load_obj(&path)?;
        if let Some((lo, hi)) = data.bounds() {
            let c = (lo + hi) * 0.5;
            let r = ((hi - lo).length() * 0.5).max(0.01);
            let dist = r / (d.camera.fov_y.to_radians() * 0.5).sin() * 1.1;
            d.camera.target = c.to_array();
            d.camera.eye = (c + Vec3::new(0.55, 0.45, 1.0).normalize() * dist).to_array();
            d.camera.near = (dist - r).max(0.01).min(crate::math::camera::NEAR);
        }
        d
    } else {
        let path = match &args.scene {
            Some(p) => p.clone(),
            None => res
                .find("scenes/demo.toml")
                .map_err(|e| anyhow::anyhow!("{e}"))?,
        };
        SceneDesc::load(&path)?
    };
    let c = &mut desc.camera;
    if let Some(v) = args.eye {
        c.eye = v.to_array();
    }
    if let Some(v) = args.target {
        c.target = v.to_array();
    }
    if let Some(v) = args.fov {
        c.fov_y = v;
    }
    if let Some(v) = args.near {
        c.near = v;
    }
    if let Some(v) = args.far {
        c.far = v;
    }
    if let Some(w) = args.width {
        desc.output.width = w;
    }
    if let Some(h) = args.height {
        desc.output.height = h;
    }
    if let Some(d) = args.depth {
        desc.output.depth = d;
    }
    if let Some(ao) = args.ao {
        desc.ao.enabled = ao == OnOff::On;
    }
    if let Some(m) = args.method {
        desc.ao.method = m;
    }
    if let Some(n) = args.samples {
        if n == 0 || n > 256 {
            bail!("--samples {n}: use 1 to 256");
        }
        desc.ao.samples = n;
        // An explicit count wins over a preset from the scene file.
        desc.ao.quality = None;
    }
    if let Some(q) = args.quality {
        desc.ao.quality = Some(q);
    }
    if let Some(c) = args.composite {
        desc.ao.composite = c;
    }
    if let Some(t) = args.tint {
        if t.min_element() < 0.0 || t.max_element() > 1.0 {
            bail!("--tint {t}: each channel must be between 0 and 1");
        }
        desc.ao.tint = t.to_array();
    }
    if let Some(p) = args.power {
        if !(p.is_finite() && (0.05..=20.0).contains(&p)) {
            bail!("--power {p}: use a power between 0.05 and 20");
        }
        desc.ao.power = p;
    }
    if let Some(r) = args.radius {
        if !(r.is_finite() && r > 0.0 && r <= 100.0) {
            bail!("--radius {r}: use a radius in metres between 0 and 100");
        }
        desc.ao.radius = r;
    }
    desc.validate()?;
    Ok(desc)
}

pub fn run() -> Result<()> {
    let cli = Cli::parse();
    let res = ResDirs::with_override(cli.res.as_deref());
    match cli.command {
        Some(Command::Render(args)) => render(&res, &args),
        Some(Command::Window(args)) => {
            let scene = load_scene(&args.scene, &res)?;
            let mut options =
                platform::window::WindowOptions::from_env(args.view, args.frames, args.screenshot);
            options.screenshot_with_ui |= args.screenshot_ui;
            options.panel_visible &= !args.no_panel;
            options.time_passes |= args.time_passes;
            platform::window::run_with(res, scene, options)
        }
        Some(Command::Lesson(args)) => lesson(&res, cli.res.as_deref(), &args),
        Some(Command::Reference(args)) => reference(&res, &args),
        Some(Command::Grade(args)) => {
            let code = crate::tools::grade::run(&res, cli.res.as_deref(), &args)?;
            if code != 0 {
                std::process::exit(code);
            }
            Ok(())
        }
        Some(Command::Bench(args)) => crate::tools::bench::run(&res, &args),
        Some(Command::GradeStep(args)) => crate::tools::grade::run_step(cli.res.as_deref(), &args),
        Some(Command::GenDemo) => {
            let dir = crate::res::project_res_dir().join("meshes");
            for p in crate::scene::shapes::write_demo_meshes(&dir)? {
                println!("wrote {}", p.display());
            }
            Ok(())
        }
        None => {
            if platform::display_available() {
                let scene = load_scene(&SceneArgs::default(), &res)?;
                match platform::window::run(res.clone(), scene, View::Composite, None, None) {
                    Ok(()) => return Ok(()),
                    Err(e) => {
                        eprintln!("could not open a window ({e:#}); rendering headless instead")
                    }
                }
            } else {
                eprintln!("no display found (DISPLAY / WAYLAND_DISPLAY unset): rendering one frame headless");
            }
            let args = RenderArgs {
                scene: SceneArgs::default(),
                view: View::Composite,
                out: PathBuf::from("out/frame.png"),
                stats: false,
            };
            render(&res, &args)
        }
    }
}

/// Renders one frame headless per `args` and writes it.
pub fn render(res: &ResDirs, args: &RenderArgs) -> Result<()> {
    let scene = load_scene(&args.scene, res)?;
    let ctx = HeadlessContext::new()?;
    let mut engine = Engine::new(
        &ctx.gl,
        res.clone(),
        &scene,
        scene.output.width,
        scene.output.height,
    )?;
    engine.view = args.view;
    engine.collect_stats = args.stats;
    write_view(&mut engine, args.view, &args.out)?;
    let msg = format!(
        "wrote {} ({}x{}, {}, {})",
        args.out.display(),
        scene.output.width,
        scene.output.height,
        args.view.label(),
        ctx.renderer
    );
    if args.stats {
        eprintln!("{msg}");
        let timing = if ctx.software {
            "wall clock around glFinish (llvmpipe)"
        } else {
            "wall clock around glFinish"
        };
        let json = serde_json::json!({ "renderer": ctx.renderer, "timing": timing, "passes": engine.last_stats() });
        println!("{json}");
    } else {
        println!("{msg}");
    }
    Ok(())
}

/// Renders `view` and writes it as PNG or PFM depending on the extension.
pub fn write_view(engine: &mut Engine, view: View, out: &Path) -> Result<()> {
    if let Some(dir) = out.parent().filter(|d| !d.as_os_str().is_empty()) {
        std::fs::create_dir_all(dir)
            .with_context(|| format!("cannot create folder {}", dir.display()))?;
    }
    let ext = out
        .extension()
        .and_then(|e| e.to_str())
        .map(str::to_ascii_lowercase);
    let (w, h) = engine.size();
    match (ext.as_deref(), view) {
        (Some("png"), View::Composite) => {
            let img = engine.render_image()?;
            image::DynamicImage::ImageRgba8(img)
                .to_rgb8()
                .save(out)
                .with_context(|| format!("cannot write {}", out.display()))?;
        }
        (Some("png"), View::LinearDepth) => {
            let v = engine.render_values(view)?;
            // Scale by the farthest non-sky distance so the picture uses the whole grey range.
            let far = engine.camera.far;
            let max = v
                .iter()
                .copied()
                .filter(|d| *d < far)
                .fold(0.0f32, f32::max)
                .max(1e-6);
            crate::io::gray_to_png(out, w, h, &v, 1.0 / max)?;
        }
        (Some("png"), _) => {
            let v = engine.render_values(view)?;
            crate::io::gray_to_png(out, w, h, &v, 1.0)?;
        }
        (Some("pfm"), View::Composite) => {
            let img = engine.render_image()?;
            let rgb: Vec<f32> = img
                .pixels()
                .flat_map(|p| [p[0], p[1], p[2]].map(|c| c as f32 / 255.0))
                .collect();
            crate::io::write_pfm_rgb(out, w, h, &rgb)?;
        }
        (Some("pfm"), _) => {
            let v = engine.render_values(view)?;
            crate::io::write_pfm_gray(out, w, h, &v)?;
        }
        _ => bail!("{}: output must end in .png or .pfm", out.display()),
    }
    Ok(())
}

fn lesson(res: &ResDirs, student: Option<&Path>, args: &LessonArgs) -> Result<()> {
    if args.step == "start" {
        let dir = args
            .dir
            .as_ref()
            .context("usage: opengl3d lesson start DIR")?;
        let files = crate::tools::lesson::start(dir)?;
        println!("wrote {} files to {}", files.len(), dir.display());
        println!("the four lesson shaders are stubs: follow lessons/README.md, then run");
        println!("  opengl3d lesson 2 --res {}", dir.display());
        return Ok(());
    }
    let n: u32 = args.step.parse().map_err(|_| {
        anyhow::anyhow!(
            "'{}' is not a step: use 1-{} or start",
            args.step,
            crate::tools::lesson::STEPS
        )
    })?;
    let view = crate::tools::lesson::view_for_step(n)?;
    if let Some(dir) = student {
        for f in crate::tools::lesson::shaders_for_step(n) {
            if !dir.join(f).is_file() {
                eprintln!(
                    "note: {} has no {f}; using the project's own",
                    dir.display()
                );
            }
        }
    }
    println!("lesson step {n}: showing {}", view.label());
    let scene = load_scene(&args.scene, res)?;
    if args.headless || !platform::display_available() {
        let ctx = HeadlessContext::new()?;
        let mut engine = Engine::new(
            &ctx.gl,
            res.clone(),
            &scene,
            scene.output.width,
            scene.output.height,
        )?;
        engine.view = view;
        write_view(&mut engine, view, &args.out)?;
        println!("wrote {}", args.out.display());
        Ok(())
    } else {
        platform::window::run(res.clone(), scene, view, None, None)
    }
}

fn reference(res: &ResDirs, args: &ReferenceArgs) -> Result<()> {
    use crate::tools::reference::{load_or_render_cached, AoVariant, RefParams, Scene};
    let scene = load_scene(&args.scene, res)?;
    // One --radius flag (the scene's): the AO radius is the ray length.
    let radius = scene.ao.radius;
    if radius.is_nan() || radius <= 0.0 || args.rays == 0 || args.rays > 1 << 20 {
        bail!("--radius must be > 0 and --rays between 1 and {}", 1 << 20);
    }
    let tris = scene.world_triangles(res)?;
    let bvh = Scene::new(tris)?;
    let c = &scene.camera;
    let cam = crate::math::Camera {
        eye: c.eye.into(),
        target: c.target.into(),
        up: Vec3::Y,
        fov_y_deg: c.fov_y,
        near: c.near,
        far: c.far,
    };
    let params = RefParams {
        radius,
        rays: args.rays,
        variant: if args.obscurance {
            AoVariant::Obscurance
        } else {
            AoVariant::Visibility
        },
        seed: 1,
        progress: true,
    };
    let (w, h) = (scene.output.width, scene.output.height);
    let img = if args.screen_space {
        let ctx = HeadlessContext::new()?;
        let mut engine = Engine::new(&ctx.gl, res.clone(), &scene, w, h)?;
        let depth = crate::tools::reference::DepthBuffer::from_engine(&mut engine)?;
        crate::tools::reference::load_or_render_screen_cached(&args.cache, &depth, &params)?
    } else {
        load_or_render_cached(&args.cache, &bvh, &cam, w, h, &params)
    };
    if let Some(dir) = args.out.parent().filter(|d| !d.as_os_str().is_empty()) {
        std::fs::create_dir_all(dir).with_context(|| format!("cannot create {}", dir.display()))?;
    }
    match args.out.extension().and_then(|e| e.to_str()) {
        Some("pfm") => crate::io::write_pfm_gray(&args.out, w, h, &img.ao)?,
        Some("png") => crate::io::gray_to_png(&args.out, w, h, &img.ao, 1.0)?,
        _ => bail!("{}: output must end in .png or .pfm", args.out.display()),
    }
    let sky = img.sky_mask().iter().filter(|s| **s).count();
    println!(
        "wrote {} ({}, {w}x{h}, {} triangles, R = {} m, {} rays/pixel, mean std error {:.4}, {} sky pixels)",
        args.out.display(),
        if args.screen_space { "screen-space, from the depth buffer" } else { "ray-traced" },
        bvh.triangle_count(),
        radius,
        args.rays,
        img.mean_std_error(),
        sky
    );
    Ok(())
}
