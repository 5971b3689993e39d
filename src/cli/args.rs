//! The command line's arguments (clap); the domain types they fill carry no clap derives.
//!
//! Numeric flags accept a leading minus so `--fov -30` reaches the range check (with a message naming
//! the flag) instead of clap reading `-3` as an unknown flag.

use crate::ao::{
    AoMethod, AoResolution, CompositeMode, GuardBand, NormalSource, SlabHierarchy, SlicePreset,
    Thickness,
};
use crate::i18n::Lang;
use crate::math::DepthMode;
use crate::render::View;
use clap::builder::TypedValueParser as _;
use clap::{Args, ValueEnum};
use glam::Vec3;
use std::path::PathBuf;

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

/// The language flag, accepted by every command.
#[derive(Args, Debug, Clone, Default)]
pub struct LangArgs {
    /// Language of the messages: en or ja (default: from LC_ALL, LC_MESSAGES or LANG; `--json`
    /// keeps English keys and messages, adding `message_localised` in Japanese).
    #[arg(long, global = true, value_parser = choice(&Lang::ALL, Lang::code))]
    pub lang: Option<Lang>,
}

/// `--surface` of the screen-space reference.
#[derive(clap::ValueEnum, Clone, Copy, Debug, PartialEq, Eq)]
pub enum SurfaceArg {
    Auto,
    Triangles,
    Patches,
}

#[derive(Args, Debug)]
pub struct ReferenceArgs {
    /// Scene flags; `--radius` is the ray length (m): a ray that hits nothing within it counts as
    /// open (default: the scene's AO radius, so the reference matches what `render` shows).
    #[command(flatten)]
    pub scene: SceneArgs,
    /// Cosine-weighted rays per pixel.
    #[arg(long, default_value_t = 256, allow_negative_numbers = true)]
    pub rays: u32,
    /// Ambient obscurance (hits weighted by (t/R)²) instead of binary visibility.
    #[arg(long, conflicts_with = "screen_space")]
    pub obscurance: bool,
    /// Screen-space reference instead: the same visibility computed exactly from the engine's
    /// full-resolution depth buffer seen as a heightfield (what a perfect screen-space method gets).
    /// There `--guard-band PX|auto` renders the depth buffer wider on each side (same pixel size,
    /// wider field of view) so that surfaces just off screen can occlude; `--thickness M` makes each
    /// depth sample a slab M metres thick (the model `vbao` uses), `--thickness backface` a slab
    /// reaching the back face behind it, `--layers 2` adds the second depth layer's slabs, and
    /// `--normals geometric` takes each pixel's triangle normal.
    #[arg(long)]
    pub screen_space: bool,
    /// Each pixel the mean over its footprint, N×N sub-pixels (the bench's `--ref-scale N` truth,
    /// which an engine image N times larger box-averaged by N is compared with): the ray tracer
    /// (and --ideal) traces every sub-pixel's centre with rays/N² rays (rounded up); with --screen-space the depth
    /// buffer is rendered N times wider and taller and the visibility averaged over each N×N block.
    /// The output keeps the scene's size.
    #[arg(long, default_value_t = 1, value_parser = clap::value_parser!(u32).range(1..=16))]
    pub supersample: u32,
    /// With --screen-space: how the surface is rebuilt from the pixels: `patches` (each pixel's
    /// plane over its footprint, slabs to the exact back face: what the depth buffer knows),
    /// `triangles` (two per cell of pixel centres, a triangle solid only where its pixels' slabs
    /// overlap, back faces never closer than the thickness) or `auto` (default: patches with
    /// `--normals geometric`, triangles with normals rebuilt from depth, which tilt the patches).
    #[arg(long, value_enum, default_value_t = SurfaceArg::Auto)]
    pub surface: SurfaceArg,
    /// Output: .pfm (raw visibility) or .png.
    #[arg(long, default_value = "out/reference.pfm")]
    pub out: PathBuf,
    /// Folder of cached results (keyed by scene, camera, size and parameters); default:
    /// `$OPENGL3D_CACHE`, else `$XDG_CACHE_HOME/opengl3d/reference`, else
    /// `~/.cache/opengl3d/reference`.
    #[arg(long)]
    pub cache: Option<PathBuf>,
    /// Trace on the GPU through `rtao`'s shader (the same visibility, up to 1024 rays per pixel),
    /// cached beside the CPU's results.
    #[arg(long, conflicts_with_all = ["screen_space", "obscurance"])]
    pub gpu: bool,
    /// The idealised one-layer visibility instead, traced on the scene's triangles: a point is solid
    /// when it lies in the view between the first surface its camera ray meets and the nearest back
    /// face behind it (the scene's AO thickness where none). What the planar-patch ceiling rebuilds
    /// from pixels, without them: an independent check of it.
    #[arg(long, conflicts_with_all = ["screen_space", "obscurance", "gpu"])]
    pub ideal: bool,
    /// With --ideal: points tested along each ray (evenly spaced within the radius).
    #[arg(long, default_value_t = 128, value_parser = clap::value_parser!(u32).range(1..=4096))]
    pub ideal_steps: u32,
}

#[derive(Args, Debug)]
pub struct LessonArgs {
    /// Step number 1-12, `start`, or `edition` (without it, the steps are listed).
    pub step: Option<String>,
    /// With `start`: the folder to create (then use it with --res); with `edition`: the folder for
    /// the class edition (the pages without their folded answers, and the stubs).
    pub dir: Option<PathBuf>,
    /// With `start`: write what a teacher publishes for a class into DIR instead: `classroom50`
    /// (a template repository, the Classroom 50 autograder bundle and the assignment's settings) or
    /// `actions` (a template repository with a plain GitHub Actions workflow). Both name this
    /// grader's version; see docs/grade/classroom.md.
    #[arg(long, value_enum, value_name = "KIND")]
    pub classroom: Option<ClassroomArg>,
    /// With --classroom: the points of each step (`STEP=N,...`, as `grade --points`; 100 in all by
    /// default: restore 20, down-sampling 10, simple 10, sao 50, blur 10).
    #[arg(long, value_name = "STEP=N,...", requires = "classroom")]
    pub points: Option<String>,
    /// With --classroom: the class's copy of opengl3d on GitHub (OWNER/REPO), whose Release of
    /// this version's tag holds the prebuilt grader (default: a placeholder to replace).
    #[arg(long, value_name = "OWNER/REPO", requires = "classroom")]
    pub grader_repo: Option<String>,
    /// With `edition`: the folder of the lesson pages to copy (default: lessons/ of the source tree
    /// this opengl3d was built from, when it is still there).
    #[arg(long, value_name = "DIR")]
    pub pages: Option<PathBuf>,
    #[command(flatten)]
    pub scene: SceneArgs,
    /// Render the step's view to --out instead of opening a window.
    #[arg(long)]
    pub headless: bool,
    /// The picture written with --headless or when there is no display (.png or .pfm).
    #[arg(long, default_value = "out/lesson.png")]
    pub out: PathBuf,
}

/// `lesson start --classroom KIND`.
#[derive(Copy, Clone, Debug, PartialEq, Eq, ValueEnum)]
pub enum ClassroomArg {
    /// Classroom 50: a template repository and the autograder bundle.
    Classroom50,
    /// Plain GitHub Actions: a template repository with its workflow.
    Actions,
}

impl From<ClassroomArg> for crate::tools::classroom::ClassroomKind {
    fn from(a: ClassroomArg) -> Self {
        match a {
            ClassroomArg::Classroom50 => Self::Classroom50,
            ClassroomArg::Actions => Self::Actions,
        }
    }
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
    /// Load one model as the whole scene (identity transform, demo lighting and AO): a Wavefront
    /// OBJ, or glTF 2.0 (`.gltf`, `.glb`) with its node transforms.
    #[arg(long, value_name = "FILE", visible_alias = "model")]
    pub obj: Option<PathBuf>,
    /// Camera position, "x,y,z".
    #[arg(long, value_parser = parse_vec3, allow_hyphen_values = true)]
    pub eye: Option<Vec3>,
    /// Point the camera looks at, "x,y,z" (up is +Y).
    #[arg(long, value_parser = parse_vec3, allow_hyphen_values = true)]
    pub target: Option<Vec3>,
    /// Vertical field of view in degrees.
    #[arg(long, allow_negative_numbers = true)]
    pub fov: Option<f32>,
    /// Distance to the near plane in metres (default: the scene file's).
    #[arg(long, allow_negative_numbers = true)]
    pub near: Option<f32>,
    /// Distance to the far plane in metres (default: the scene file's).
    #[arg(long, allow_negative_numbers = true)]
    pub far: Option<f32>,
    /// Output width in pixels.
    #[arg(long, allow_negative_numbers = true)]
    pub width: Option<u32>,
    /// Output height in pixels.
    #[arg(long, allow_negative_numbers = true)]
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
    #[arg(long, conflicts_with = "quality", allow_negative_numbers = true)]
    pub samples: Option<u32>,
    /// GTAO/VBAO quality preset (slices × steps per side): gtao low 1×4, medium 2×4, high 3×6, ultra
    /// 4×8; vbao 1×4, 1×8, 1×16, 1×32 (default: the method's recommended configuration,
    /// docs/bench/defaults.md).
    #[arg(long, value_parser = choice(&SlicePreset::ALL, SlicePreset::name))]
    pub quality: Option<SlicePreset>,
    /// AO radius in metres.
    #[arg(long, allow_negative_numbers = true)]
    pub radius: Option<f32>,
    /// Size the engine's AO methods run at: half (the course's), full, or quarter (a sixteenth of the
    /// pixels, for large outputs); `sao-lesson` stays at half (default: the method's recommended
    /// configuration, docs/bench/defaults.md).
    #[arg(long, value_parser = choice(&AoResolution::ALL, AoResolution::name))]
    pub ao_resolution: Option<AoResolution>,
    /// Where the engine's AO methods take each pixel's normal: geometric (the triangle's own, from a
    /// pass over the geometry) or depth (rebuilt from neighbouring depths, no extra pass); default:
    /// the method's recommended configuration.
    #[arg(long, value_parser = choice(&NormalSource::ALL, NormalSource::name))]
    pub normals: Option<NormalSource>,
    /// Pixels the engine's AO covers beyond each edge of the view, so that occluders just off
    /// screen count: auto (the radius's size at the camera's focus distance, at most 1/12 of the
    /// larger side), a number, or 0 (none); default: the method's recommended configuration.
    #[arg(long, value_name = "auto|PX", value_parser = GuardBand::parse)]
    pub guard_band: Option<GuardBand>,
    /// How far (m) behind each depth sample `vbao` takes the surface to extend, or `backface`: each
    /// pixel's own, from a depth pass of the back faces (default: the method's recommended
    /// configuration, `backface` for `vbao`).
    #[arg(long, allow_negative_numbers = true, value_parser = Thickness::parse)]
    pub thickness: Option<Thickness>,
    /// Depth layers `vbao` marches: 1 (the visible surface) or 2 (also the nearest surface hidden at
    /// least a tenth of the radius behind it, from one more depth pass; with `--thickness backface`
    /// its slabs reach its own back faces, from another); default: the method's recommended
    /// configuration (2 for `vbao`).
    #[arg(long, value_parser = clap::value_parser!(u32).range(1..=2))]
    pub layers: Option<u32>,
    /// Whether `vbao`'s taps read the slab hierarchy (the nearest slab under a texel as wide as the
    /// gap to the previous tap, so thin things between taps count): auto (on with `--thickness
    /// backface`, the default), on, off.
    #[arg(long, value_parser = choice(&SlabHierarchy::ALL, SlabHierarchy::name))]
    pub slab_hierarchy: Option<SlabHierarchy>,
    /// `rtao`: rays per pixel and frame (1 to 1024; default: the method's recommended configuration, 4).
    #[arg(long, allow_negative_numbers = true)]
    pub rays_per_pixel: Option<u32>,
    /// `rtao` and the screen-space methods: frames averaged (1 = none; `render` draws that many
    /// frames and writes the last). Each frame traces the next rays (`rtao`) or turns the samples
    /// (the screen-space methods) and blends the previous frames' result reprojected through the
    /// camera's motion; `rtao` starts again when an object moves.
    #[arg(long, allow_negative_numbers = true)]
    pub accumulate: Option<u32>,
    /// How AO reaches the picture: the lesson's blend, tinted, or on the ambient term only.
    #[arg(long, value_parser = choice(&CompositeMode::ALL, CompositeMode::name))]
    pub composite: Option<CompositeMode>,
    /// Tint colour for `--composite tinted`, "r,g,b" in 0..1.
    #[arg(long, value_parser = parse_vec3, allow_hyphen_values = true)]
    pub tint: Option<Vec3>,
    /// Power applied to visibility before compositing.
    #[arg(long, allow_negative_numbers = true)]
    pub power: Option<f32>,
}

/// What `render` writes: one of the engine's views, or the AO view's error against a truth.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum RenderView {
    Engine(View),
    Error,
}

impl RenderView {
    pub const ALL: [RenderView; 6] = [
        RenderView::Engine(View::Composite),
        RenderView::Engine(View::LinearDepth),
        RenderView::Engine(View::SecondLayerDepth),
        RenderView::Engine(View::AoRaw),
        RenderView::Engine(View::Ao),
        RenderView::Error,
    ];
    pub fn name(self) -> &'static str {
        match self {
            RenderView::Engine(v) => v.name(),
            RenderView::Error => "error",
        }
    }
}

#[derive(Args, Debug)]
pub struct RenderArgs {
    #[command(flatten)]
    pub scene: SceneArgs,
    /// What to write: the lit composite, linear depth (m), the second depth layer's (`vbao` with
    /// `--layers 2`), raw SAO or blurred SAO (visibility, 1 = open), or `error`: the blurred AO view
    /// minus the truth (`--truth`, else traced), box-averaged to the truth's size (too dark blue, too light orange, sky grey,
    /// with a colour scale; PSNR and RMSE on stdout).
    #[arg(long, value_parser = choice(&RenderView::ALL, RenderView::name), default_value = "composite")]
    pub view: RenderView,
    /// A method of your own: a method file (TOML naming a GLSL shader beside it, what it reads, its
    /// parameters; see docs/method-file.md), run where an engine method runs.
    #[arg(long, value_name = "FILE.toml", conflicts_with = "method")]
    pub method_file: Option<PathBuf>,
    /// With `--view error`: the truth, a one-channel PFM of visibility (e.g. `opengl3d reference`'s)
    /// at the output size divided by a whole factor; without it the truth is ray-traced (at most
    /// 320 pixels wide, 256 rays) and kept in the reference cache.
    #[arg(long, value_name = "FILE.pfm")]
    pub truth: Option<PathBuf>,
    /// With `--view error`: the error drawn at full colour (visibility units).
    #[arg(long, default_value_t = crate::tools::error_map::DEFAULT_RANGE, allow_negative_numbers = true)]
    pub error_range: f32,
    /// Output file: .png (8-bit) or .pfm (raw floats; `--view error`: the signed difference).
    #[arg(long, default_value = "out/frame.png")]
    pub out: PathBuf,
    /// Print each pass of the frame (name, group, ms, draw calls) as JSON on stdout, measured on a
    /// second frame (the first compiles the shaders).
    #[arg(long)]
    pub stats: bool,
    /// Draw this many frames along a camera path (after the `--accumulate` frames standing still):
    /// orbiting the scene camera's target to the left while closing in, as `bench --camera-path`
    /// moves; each frame is written beside `--out` with its number (out/frame-000.png, …), and an
    /// accumulating method's history follows the motion.
    #[arg(long, value_name = "FRAMES", conflicts_with = "stats",
          value_parser = clap::value_parser!(u32).range(1..=100_000))]
    pub camera_path: Option<u32>,
}

#[derive(Args, Debug)]
pub struct WindowArgs {
    #[command(flatten)]
    pub scene: SceneArgs,
    /// The view shown first (V cycles through them).
    #[arg(long, value_parser = choice(&View::ALL, View::name), default_value = "composite")]
    pub view: View,
    /// A method of your own: a method file (TOML naming a GLSL shader beside it, what it reads, its
    /// parameters; see docs/method-file.md), run where an engine method runs (its shader reloads when saved;
    /// its parameters are sliders in the panel).
    #[arg(long, value_name = "FILE.toml", conflicts_with = "method")]
    pub method_file: Option<PathBuf>,
    /// Close after this many frames (for scripted runs and tests).
    #[arg(long, allow_negative_numbers = true)]
    pub frames: Option<u32>,
    /// Save the last frame shown to this PNG (with --frames): the engine's frame, as `render` draws it.
    #[arg(long, requires = "frames")]
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

pub fn parse_vec3(s: &str) -> Result<Vec3, String> {
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
