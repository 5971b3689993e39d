//! The command line (`opengl3d`): the demo in a window, or frames rendered headless.

mod args;
mod challenge;
mod help_text;
mod output;
mod render_error;
mod render_path;
mod res_check;
mod scene_args;
mod usage_errors;

pub use args::{
    parse_vec3, LangArgs, LessonArgs, OnOff, ReferenceArgs, RenderArgs, RenderView, SceneArgs,
    SurfaceArg, WindowArgs,
};
pub use output::{write_view, OutFormat, PNG_OR_PFM};
pub use res_check::{check_res, ResUse};
pub use scene_args::load_scene;

use crate::platform::{self, HeadlessContext};
use crate::render::{Engine, View};
use crate::res::ResDirs;
use anyhow::{bail, Context as _, Result};
use clap::{CommandFactory, FromArgMatches, Parser, Subcommand};
use rust_i18n::t;
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
    #[command(flatten)]
    pub lang: LangArgs,
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
    /// (Internal) measure one entry of `grade --challenge` in a child process; prints one JSON line.
    #[cfg(feature = "bench")]
    #[command(hide = true)]
    ChallengeEntry(crate::tools::challenge::entry::ChallengeEntryArgs),
    /// Run time against error of the AO methods, or `--stress` for numerical stability.
    #[cfg(feature = "bench")]
    Bench(crate::tools::bench::BenchArgs),
    /// Search each AO method's free [ao] parameters on a scene's training cameras against the
    /// ray-traced truth; writes the best [ao] table and the held-out test cameras' PSNR.
    #[cfg(feature = "bench")]
    Tune(crate::tools::tune::TuneArgs),
    /// Regenerate the demo meshes in Res/meshes (with --res DIR: in DIR/meshes).
    GenDemo,
}

/// What `command` reads from `--res` (checked before it runs).
fn res_use(command: &Option<Command>) -> Option<ResUse> {
    Some(match command {
        Some(Command::Lesson(a)) if a.step.as_deref().is_none_or(|s| s == "start") => return None,
        Some(Command::Lesson(a)) => {
            // A step that does not exist is reported by the lesson itself.
            let n = a.step.as_deref()?.parse().ok()?;
            crate::tools::lesson::view_for_step(n).ok()?;
            ResUse::AnyOf(crate::tools::lesson::shaders_for_step(n))
        }
        // The grader checks the student's folder itself, with its own messages.
        Some(Command::Grade(_)) | Some(Command::GradeStep(_)) => return None,
        Some(Command::Reference(a)) if !a.screen_space => ResUse::Scenes,
        Some(Command::GenDemo) => ResUse::Folder,
        _ => ResUse::ShadersOrScenes,
    })
}

pub fn run() -> Result<()> {
    let argv: Vec<std::ffi::OsString> = std::env::args_os().collect();
    // The language is known before parsing so that `--help` is written in it.
    let lang = crate::i18n::from_env(usage_errors::lang_in_args(&argv));
    crate::i18n::set(lang);
    let command = match lang {
        crate::i18n::Lang::Ja => help_text::japanese(Cli::command()),
        crate::i18n::Lang::En => Cli::command(),
    };
    let cli = command
        .try_get_matches_from(&argv)
        .and_then(|m| Cli::from_arg_matches(&m))
        .unwrap_or_else(|e| usage_errors::exit(e, &argv));
    crate::i18n::set(crate::i18n::from_env(cli.lang.lang));
    if let (Some(dir), Some(what)) = (&cli.res, res_use(&cli.command)) {
        check_res(dir, what)?;
    }
    let res = ResDirs::with_override(cli.res.as_deref());
    match cli.command {
        Some(Command::Render(args)) => render(&res, &args),
        #[cfg(not(feature = "window"))]
        Some(Command::Window(_)) => bail!("{}", t!("cli.no_window_feature")),
        #[cfg(feature = "window")]
        Some(Command::Window(args)) => {
            if let Some(shot) = &args.screenshot {
                OutFormat::of("--screenshot", shot, &[OutFormat::Png])?;
            }
            let scene = load_scene(&args.scene, &res)?;
            let mut options = window_options(args.view, args.frames, args.screenshot);
            options.method_file = args
                .method_file
                .as_deref()
                .map(crate::scene::method_file::MethodFile::read)
                .transpose()?;
            options.screenshot_with_ui |= args.screenshot_ui;
            options.panel_visible &= !args.no_panel;
            options.time_passes |= args.time_passes;
            platform::window::run_with(res, scene, options)
        }
        Some(Command::Lesson(args)) => lesson(&res, cli.res.as_deref(), &args),
        Some(Command::Reference(args)) => reference(&res, &args),
        Some(Command::Grade(args)) if args.challenge.is_some() => challenge::run(&res, &args),
        #[cfg(feature = "bench")]
        Some(Command::ChallengeEntry(args)) => {
            crate::tools::challenge::entry::run_entry(&res, &args)
        }
        Some(Command::Grade(args)) => {
            let code = crate::tools::grade::run(&res, cli.res.as_deref(), &args)?;
            if code != 0 {
                std::process::exit(code);
            }
            Ok(())
        }
        #[cfg(feature = "bench")]
        Some(Command::Bench(args)) => crate::tools::bench::run(&res, &args),
        #[cfg(feature = "bench")]
        Some(Command::Tune(args)) => crate::tools::tune::run_cli(&res, &args),
        Some(Command::GradeStep(args)) => crate::tools::grade::run_step(cli.res.as_deref(), &args),
        Some(Command::GenDemo) => {
            let dir = match &cli.res {
                Some(d) => d.join("meshes"),
                None => crate::res::project_res_dir().join("meshes"),
            };
            for p in crate::scene::shapes::write_demo_meshes(&dir)? {
                crate::outln!("wrote {}", p.display());
            }
            Ok(())
        }
        None => {
            #[cfg(feature = "window")]
            if platform::display_available() {
                let scene = load_scene(&SceneArgs::default(), &res)?;
                match platform::window::run_with(
                    res.clone(),
                    scene,
                    window_options(View::Composite, None, None),
                ) {
                    Ok(()) => return Ok(()),
                    Err(e) => {
                        eprintln!("{}", t!("cli.window_failed", error = format!("{e:#}")))
                    }
                }
            } else {
                eprintln!("{}", t!("cli.no_display", path = "out/frame.png"));
            }
            #[cfg(not(feature = "window"))]
            eprintln!("{}", no_window_reason(Path::new("out/frame.png")));
            let args = RenderArgs {
                scene: SceneArgs::default(),
                view: RenderView::Engine(View::Composite),
                method_file: None,
                truth: None,
                error_range: crate::tools::error_map::DEFAULT_RANGE,
                out: PathBuf::from("out/frame.png"),
                stats: false,
                camera_path: None,
            };
            render(&res, &args)
        }
    }
}

/// Renders one frame headless per `args` and writes it.
pub fn render(res: &ResDirs, args: &RenderArgs) -> Result<()> {
    let view = match args.view {
        RenderView::Error if args.camera_path.is_some() => {
            bail!("{}", t!("render.path_not_error"))
        }
        RenderView::Error => return render_error::run(res, args),
        RenderView::Engine(v) => v,
    };
    if args.truth.is_some() {
        bail!("{}", t!("error_map.truth_needs_view"));
    }
    OutFormat::of("--out", &args.out, PNG_OR_PFM)?;
    let scene = load_scene(&args.scene, res)?;
    let ctx = HeadlessContext::new()?;
    let mut engine = Engine::at_output_size(&ctx.gl, res.clone(), &scene)?;
    scene_args::use_method_file(&mut engine, args.method_file.as_deref())?;
    engine.view = view;
    if args.stats {
        // One frame first, unmeasured: the first frame compiles every shader (Mesa compiles on
        // first draw) and allocates the targets, which is not what a pass costs.
        write_view(&mut engine, view, &args.out)?;
    }
    // `--accumulate N` (`rtao`, and the screen-space methods through `ao::temporal`): the first
    // N - 1 frames build up the running mean the written one ends.
    let earlier = scene.ao.accumulate.saturating_sub(1 + args.stats as u32);
    let accumulates = crate::ao::temporal::applies(&engine.ao_settings);
    if scene.ao.method == crate::ao::AoMethod::Rtao || accumulates {
        for _ in 0..earlier {
            engine.render_to_ao()?;
        }
    }
    if let Some(frames) = args.camera_path {
        render_path::run(&mut engine, view, &args.out, frames)?;
        return Ok(());
    }
    engine.collect_stats = args.stats;
    write_view(&mut engine, view, &args.out)?;
    let cut = engine.ao.cut_pixels(engine.ao_settings.method);
    if cut > 0 {
        let message = t!("render.rtao_cut", pixels = cut);
        eprintln!("{}", t!("render.warning", message = message));
    }
    let msg = t!(
        "render.wrote",
        path = args.out.display(),
        width = scene.output.width,
        height = scene.output.height,
        view = view_label(view),
        renderer = ctx.renderer
    );
    if args.stats {
        eprintln!("{msg}");
        let recommended = engine.ao.recommended(engine.ao_settings.method);
        let keys = crate::scene::ao_defaults::chosen_line_from(&engine.ao_settings, &recommended);
        let method = engine.ao.own_labels(engine.ao_settings.method);
        let method = method.map_or(engine.ao_settings.method.name(), |(name, _)| name);
        eprintln!(
            "{}",
            t!("render.ao_configuration", method = method, keys = keys)
        );
        // Each pass names its clock too: a pass timed inside another falls back to the wall clock.
        let clock = crate::gl::PassClock::of_context(&ctx.gl);
        let method = engine.ao_settings.method;
        let json = serde_json::json!({
            "renderer": ctx.renderer,
            "clock": clock.name(),
            "timing": clock.description(),
            "passes": engine.last_stats(),
            "bvh": engine.ao.bvh_stats(method),
            "accumulated_frames": engine.accumulated_frames(),
            "ao_configuration": crate::scene::ao_defaults::chosen_from(&engine.ao_settings, &recommended),
        });
        crate::outln!("{json}");
    } else {
        crate::outln!("{msg}");
    }
    Ok(())
}

/// What `opengl3d lesson` prints without a step: the steps and how to begin.
/// The view's name in the chosen language (`view.<name>` keys).
fn view_label(view: crate::render::View) -> String {
    let key = format!("view.{}", view.name());
    let label = t!(&key);
    label.into_owned()
}

/// Whether `s` is set in full-width characters (CJK), which take two columns each.
fn is_wide(s: &str) -> bool {
    s.chars().any(|c| c as u32 >= 0x3000)
}

fn lesson_overview() -> String {
    use crate::tools::lesson::{shaders_for_step, view_for_step, STEPS};
    let mut s = t!("lesson.overview_usage").into_owned();
    for n in 1..=STEPS {
        let view = view_for_step(n)
            .map(view_label)
            .unwrap_or_else(|_| "?".into());
        let files = shaders_for_step(n).join(", ");
        // Pad by characters shown, not bytes: the Japanese labels are wider per byte.
        let width = view.chars().count() * if is_wide(&view) { 2 } else { 1 };
        let pad = 17usize.saturating_sub(width);
        let (n, view) = (format!("{n:>2}"), format!("{view}{}", " ".repeat(pad)));
        s.push_str(&t!(
            "lesson.overview_step",
            n = n,
            view = view,
            files = files
        ));
    }
    s.push_str(&t!("lesson.overview_pages"));
    s
}

fn lesson(res: &ResDirs, student: Option<&Path>, args: &LessonArgs) -> Result<()> {
    let Some(step) = args.step.as_deref() else {
        if args.classroom.is_some() {
            bail!("{}", t!("classroom.only_with_start", step = ""));
        }
        crate::outln!("{}", lesson_overview());
        return Ok(());
    };
    if args.classroom.is_some() && step != "start" {
        bail!("{}", t!("classroom.only_with_start", step = step));
    }
    if args.pages.is_some() && step != "edition" {
        bail!("{}", t!("edition.pages_only_with_edition", step = step));
    }
    if step == "edition" {
        let dir = args.dir.as_ref().with_context(|| t!("edition.usage"))?;
        let lang = crate::i18n::current();
        let written = crate::tools::lesson_edition::write(dir, args.pages.as_deref(), lang)?;
        crate::outln!(
            "{}",
            t!(
                "edition.wrote",
                count = written.pages,
                withheld = written.withheld,
                dir = dir.display()
            )
        );
        return Ok(());
    }
    if step == "start" {
        let dir = args
            .dir
            .as_ref()
            .with_context(|| t!("lesson.start_usage"))?;
        if let Some(kind) = args.classroom {
            return classroom_start(dir, kind.into(), args);
        }
        let files = crate::tools::lesson::start(dir, crate::i18n::current())?;
        let shown = dir.display();
        crate::outln!(
            "{}",
            t!("lesson.start_wrote", count = files.len(), dir = shown)
        );
        let stubs: Vec<&str> = crate::tools::lesson::LESSON_SHADERS
            .iter()
            .copied()
            .filter(|f| files.contains(&dir.join(f)))
            .collect();
        match stubs.len() {
            0 => crate::outln!("{}", t!("lesson.start_kept_all", dir = shown)),
            n if n == crate::tools::lesson::LESSON_SHADERS.len() => {
                crate::outln!("{}", t!("lesson.start_all_stubs", count = n))
            }
            _ => crate::outln!(
                "{}",
                t!("lesson.start_some_stubs", stubs = stubs.join(", "))
            ),
        }
        crate::outln!(
            "  opengl3d lesson 2 --res {}",
            shell_word(&dir.display().to_string())
        );
        return Ok(());
    }
    let n: u32 = step.parse().map_err(|_| {
        let steps = crate::tools::lesson::STEPS;
        anyhow::anyhow!("{}", t!("lesson.not_a_step", step = step, steps = steps))
    })?;
    let view = crate::tools::lesson::view_for_step(n)?;
    if args.headless || !platform::display_available() {
        OutFormat::of("--out", &args.out, PNG_OR_PFM)?;
    }
    if let Some(dir) = student {
        for f in crate::tools::lesson::shaders_for_step(n) {
            if !dir.join(f).is_file() {
                let dir = dir.display();
                eprintln!("{}", t!("lesson.missing_shader", dir = dir, file = f));
            }
        }
    }
    crate::outln!("{}", t!("lesson.showing", n = n, view = view_label(view)));
    let scene = load_scene(&args.scene, res)?;
    if args.headless || !platform::display_available() {
        if !args.headless {
            eprintln!("{}", no_window_reason(&args.out));
        }
        let ctx = HeadlessContext::new()?;
        let mut engine = Engine::at_output_size(&ctx.gl, res.clone(), &scene)?;
        engine.view = view;
        write_view(&mut engine, view, &args.out)?;
        crate::outln!("{}", t!("lesson.wrote", path = args.out.display()));
        Ok(())
    } else {
        #[cfg(feature = "window")]
        return platform::window::run_with(res.clone(), scene, window_options(view, None, None));
        #[cfg(not(feature = "window"))]
        unreachable!("display_available() is false without the window")
    }
}

/// `word` as one shell word: quoted when it holds anything but plain path characters.
fn shell_word(word: &str) -> String {
    let plain = !word.is_empty()
        && word
            .chars()
            .all(|c| c.is_ascii_alphanumeric() || matches!(c, '/' | '.' | '_' | '-' | '+' | ':'));
    if plain {
        word.to_string()
    } else {
        format!("'{}'", word.replace('\'', "'\\''"))
    }
}

/// `lesson start --classroom KIND DIR`.
fn classroom_start(
    dir: &Path,
    kind: crate::tools::classroom::ClassroomKind,
    args: &LessonArgs,
) -> Result<()> {
    use crate::tools::classroom::{self, ClassroomKind, ClassroomOptions};
    let points = match &args.points {
        Some(spec) => crate::tools::grade::points::Points::parse(spec)?,
        None => Default::default(),
    };
    let grader_repo = args
        .grader_repo
        .clone()
        .unwrap_or_else(|| classroom::GRADER_REPO_PLACEHOLDER.to_string());
    classroom::check_grader_repo(&grader_repo)?;
    let options = ClassroomOptions {
        kind,
        points,
        grader_repo,
        lang: crate::i18n::current(),
    };
    let files = classroom::start(dir, &options)?;
    crate::outln!(
        "{}",
        t!(
            "lesson.start_wrote",
            count = files.len(),
            dir = dir.display()
        )
    );
    let key = match kind {
        ClassroomKind::Classroom50 => "classroom.wrote_c50",
        ClassroomKind::Actions => "classroom.wrote_actions",
    };
    crate::outln!(
        "{}",
        t!(
            key,
            dir = dir.display(),
            version = classroom::GRADER_VERSION,
            tag = classroom::grader_tag(),
            repo = options.grader_repo
        )
    );
    if args.grader_repo.is_none() {
        crate::outln!(
            "{}",
            t!(
                "classroom.placeholder_repo",
                placeholder = classroom::GRADER_REPO_PLACEHOLDER
            )
        );
    }
    Ok(())
}

/// Why a picture is written to `path` instead of a window opening.
fn no_window_reason(path: &Path) -> String {
    if cfg!(feature = "window") {
        t!("cli.no_display", path = path.display()).into_owned()
    } else {
        t!("cli.no_window_build", path = path.display()).into_owned()
    }
}

/// The window's options from the environment, with the CPU ray tracer behind its truth view (T).
#[cfg(feature = "window")]
fn window_options(
    view: View,
    frames: Option<u32>,
    screenshot: Option<std::path::PathBuf>,
) -> platform::window::WindowOptions {
    let mut options = platform::window::WindowOptions::from_env(view, frames, screenshot);
    options.truth = Some(platform::window::truth::TruthTools(std::sync::Arc::new(
        crate::tools::window_truth::CpuTruth::new(),
    )));
    options
}

fn reference(res: &ResDirs, args: &ReferenceArgs) -> Result<()> {
    use crate::tools::reference::{load_or_render_cached, AoVariant, RefParams, Scene};
    let format = OutFormat::of("--out", &args.out, PNG_OR_PFM)?;
    let mut scene = load_scene(&args.scene, res)?;
    // The engine's ranges, as `render` applies them: the truth traces what the methods are given.
    let (ao, notes) = scene.ao.sanitized();
    for note in notes {
        eprintln!("{}", t!("render.warning", message = note));
    }
    scene.ao = ao;
    // Only the screen-space reference has a thickness: the ray tracer sees the real triangles.
    // `backface`: each pixel's slab reaches its back face, and where there is none it has vbao's
    // fixed thickness for this radius (`AoSettings::thickness_metres`: the scene's `[ao] thickness`
    // set to backface leaves the default fraction of the radius).
    let (thickness, back_faces) = match (args.scene.thickness, args.screen_space) {
        (Some(_), false) => {
            bail!("--thickness applies to the screen-space reference: add --screen-space")
        }
        (Some(crate::ao::Thickness::Metres(t)), true) => (t, false),
        (Some(crate::ao::Thickness::Backface), true) => (scene.ao.thickness_metres(), true),
        (None, _) => (f32::INFINITY, false),
    };
    if args.scene.normals.is_some() && !args.screen_space {
        bail!("--normals applies to the screen-space reference (the ray tracer uses each triangle's own): add --screen-space")
    }
    if args.scene.guard_band.is_some() && !args.screen_space {
        bail!("--guard-band applies to the screen-space reference (the ray tracer sees the whole scene): add --screen-space")
    }
    // One --radius flag (the scene's): the AO radius is the ray length.
    let radius = scene.ao.radius;
    if radius.is_nan() || radius <= 0.0 || args.rays == 0 || args.rays > 1 << 20 {
        bail!("{}", t!("reference.bad_params", max = 1 << 20));
    }
    let tris = scene.world_triangles(res)?;
    let bvh = Scene::new(tris)?;
    let cam = scene.camera.camera();
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
        supersample: 1,
    };
    let (w, h) = (scene.output.width, scene.output.height);
    let cache = crate::tools::reference::reference_cache_dir(args.cache.as_deref())?;
    let guard_px = match scene.ao.guard_band {
        crate::ao::GuardBand::Pixels(p) => p,
        band => crate::ao::guard_band::guard_band_pixels(band, &cam, (w, h), radius),
    };
    if args.surface != SurfaceArg::Auto && !args.screen_space {
        bail!("--surface applies to the screen-space reference: add --screen-space")
    }
    let mut surface = None;
    let img = if args.screen_space {
        use crate::tools::reference::DepthBuffer;
        let n = args.supersample;
        let mut big = scene.clone();
        big.output.width = w * n;
        big.output.height = h * n;
        let ctx = HeadlessContext::new()?;
        let mut engine = Engine::at_output_size(&ctx.gl, res.clone(), &big)?;
        let what = crate::tools::reference::Capture {
            back_faces,
            normals: scene.ao.normals == crate::ao::NormalSource::Geometric,
            second_layer: (scene.ao.layers >= 2).then(|| scene.ao.layer_separation_metres()),
        };
        let mut depth =
            DepthBuffer::capture(&mut engine, guard_px * n, what)?.with_thickness(thickness);
        use crate::tools::reference::Surface;
        depth.surface = match args.surface {
            SurfaceArg::Auto => Surface::for_normals(what.normals),
            SurfaceArg::Triangles => Surface::Triangles,
            SurfaceArg::Patches => Surface::Patches,
        };
        surface = Some(depth.surface);
        if n > 1 {
            crate::tools::reference::load_or_render_screen_box_cached(&cache, &depth, n, &params)?
        } else {
            crate::tools::reference::load_or_render_screen_cached(&cache, &depth, &params)?
        }
    } else if args.ideal {
        crate::tools::reference::render_ideal_one_layer(
            &bvh,
            &cam,
            (w, h),
            &RefParams {
                supersample: args.supersample,
                ..params
            },
            scene.ao.thickness_metres(),
            args.ideal_steps,
        )
    } else {
        // The ray tracer's footprint mean (the screen-space one box-averages its own way above).
        let params = RefParams {
            supersample: args.supersample,
            ..params
        };
        if args.gpu {
            crate::tools::reference::load_or_render_gpu_cached(&cache, res, &scene, &bvh, &params)?
        } else {
            load_or_render_cached(&cache, &bvh, &cam, w, h, &params)
        }
    };
    crate::io::create_parent(&args.out)?;
    match format {
        OutFormat::Pfm => crate::io::write_pfm_gray(&args.out, w, h, &img.ao)?,
        OutFormat::Png => crate::io::gray_to_png(&args.out, w, h, &img.ao, 1.0)?,
    }
    let sky = img.sky_mask().iter().filter(|s| **s).count();
    let kind = if args.screen_space {
        let slabs = if back_faces {
            t!("backface_ceiling.slabs", thickness = thickness)
        } else if thickness.is_finite() {
            t!("reference.slabs", thickness = thickness)
        } else {
            t!("reference.infinite_thickness")
        };
        let guard = t!("reference.guard_band", px = guard_px);
        let normals = t!("reference.normals", source = scene.ao.normals.name());
        let surface = match surface {
            Some(crate::tools::reference::Surface::Patches) => t!("reference.surface_patches"),
            _ => t!("reference.surface_triangles"),
        };
        let surface = t!("reference.surface", name = surface);
        format!(
            "{}, {surface}, {slabs}, {normals}, {guard}",
            t!("reference.kind_screen")
        )
    } else if args.ideal {
        t!(
            "reference.kind_ideal",
            thickness = scene.ao.thickness_metres(),
            steps = args.ideal_steps
        )
        .into_owned()
    } else if args.gpu {
        t!("reference.kind_gpu").into_owned()
    } else {
        t!("reference.kind_rays").into_owned()
    };
    let error = format!("{:.4}", img.mean_std_error());
    crate::outln!(
        "{}",
        t!(
            "reference.wrote",
            path = args.out.display(),
            kind = kind,
            width = w,
            height = h,
            triangles = bvh.triangle_count(),
            radius = radius,
            rays = args.rays,
            error = error,
            sky = sky
        )
    );
    Ok(())
}
