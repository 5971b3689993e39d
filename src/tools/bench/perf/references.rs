//! The bench's ground truth: the ray-traced reference of every camera and radius of a scene, and
//! the screen-space references (from the engine's depth buffer) of its test cameras. Both come from
//! the reference cache when it has them.

use super::config::PerfConfig;
use crate::ao::guard_band::guard_band_pixels;
use crate::ao::settings::LAYER_SEPARATION_OF_RADIUS;
use crate::ao::{AoMethod, AoSettings, NormalSource, Thickness};
use crate::render::Engine;
use crate::res::ResDirs;
use crate::scene::framing;
use crate::scene::SceneDesc;
use crate::tools::bench::catalog::{self, BenchCamera};
use crate::tools::reference::{
    cache_key, cache_path, load_or_render_cached, load_or_render_screen_box_cached,
    screen_box_cache_key, AoVariant, Capture, DepthBuffer, RefImage, RefParams, Scene, Surface,
};
use anyhow::{Context as _, Result};
use indicatif::ProgressBar;
use std::collections::BTreeMap;
use std::path::Path;
use std::time::Instant;

/// References keyed by (camera index, radius bits).
pub type RefMap = BTreeMap<(usize, u32), RefImage>;

/// A scene as the bench runs it: its description at the bench size, its cameras and the
/// ray-traced reference of each camera and radius.
pub struct SceneData {
    pub name: String,
    pub desc: SceneDesc,
    pub cameras: Vec<BenchCamera>,
    pub refs: RefMap,
    /// The settings' radii are multiplied by this on this scene: 1 for a scene file, the AO
    /// radius framing chose for a model (`--obj`) when no `--radii` are given.
    pub radius_scale: f32,
}

/// How many references were rendered this run or read from the cache, and the seconds spent
/// rendering.
#[derive(Default)]
pub struct RenderCount {
    pub rendered: usize,
    pub cached: usize,
    pub render_s: f64,
}

impl RenderCount {
    fn add(&mut self, hit: bool, started: Instant) {
        if hit {
            self.cached += 1;
        } else {
            self.rendered += 1;
            self.render_s += started.elapsed().as_secs_f64();
        }
    }
}

/// Visibility, the quantity the engine's AO view shows, with a fixed seed so that cached files
/// are reused across runs. Each pixel is the mean over the footprint of the `ref_scale`² engine
/// pixels the comparison box-averages onto it: at pixel centres the truth would stand for one
/// point of that footprint, and a board thinner than a reference pixel would be all or nothing
/// there while it is a share of the engine's average (on the thin-things scene's test cameras the
/// ray-traced truth itself, traced at 1920×1080 and box-averaged, was only 29.4 / 28.7 dB from the
/// centre-sampled 320×180 one).
fn params(radius: f32, cfg: &PerfConfig, progress: bool) -> RefParams {
    RefParams {
        rays: cfg.ref_rays,
        supersample: cfg.ref_scale,
        ..screen_params(radius, cfg.ref_rays, progress)
    }
}

/// Whether each pixel of the block-averaged screen-space references traces the rays the
/// ray-traced reference traces for the same sub-pixel (`screen_box.rs`): the same seed, and the
/// same share of the rays per sub-pixel.
pub fn ceiling_shares_truth_rays(cfg: &PerfConfig) -> bool {
    shares_rays(cfg.ref_rays, cfg.screen_rays, cfg.ref_scale)
}

/// Whether `screen_rays` per block of `scale`² pixels give each pixel the share of `ref_rays` the
/// truth's footprint mean gives each sub-pixel.
fn shares_rays(ref_rays: u32, screen_rays: u32, scale: u32) -> bool {
    let per_pixel = |rays: u32| rays.max(1).div_ceil(scale.max(1).pow(2));
    per_pixel(screen_rays) == per_pixel(ref_rays)
}

/// The screen-space references' parameters: the depth buffer's pixel centres at the reference's
/// size.
fn screen_params(radius: f32, rays: u32, progress: bool) -> RefParams {
    RefParams {
        radius,
        rays,
        variant: AoVariant::Visibility,
        seed: 1,
        progress,
        supersample: 1,
    }
}

/// Loads the scene at `path` at the bench size with its cameras, and its triangles for the ray
/// tracer (the references come from [`trace_references`]).
pub fn load_scene(res: &ResDirs, path: &Path, cfg: &PerfConfig) -> Result<(SceneData, Scene)> {
    scene_at(res, path, (cfg.width, cfg.height))
}

/// The scene file at `path` at `size`, with its cameras and triangles.
pub fn scene_at(res: &ResDirs, path: &Path, size: (u32, u32)) -> Result<(SceneData, Scene)> {
    let mut desc = SceneDesc::load(path)?;
    (desc.output.width, desc.output.height) = size;
    let name = path
        .file_stem()
        .map(|s| s.to_string_lossy().into_owned())
        .unwrap_or_else(|| "scene".into());
    scene_data(res, name, desc, 1.0)
}

/// A scene of its cameras (the scene's own and its variants) and triangles.
fn scene_data(
    res: &ResDirs,
    name: String,
    desc: SceneDesc,
    radius_scale: f32,
) -> Result<(SceneData, Scene)> {
    let cameras = catalog::camera_variants(&desc.camera);
    let bvh = Scene::new(desc.world_triangles(res)?)?;
    let sd = SceneData {
        name,
        desc,
        cameras,
        refs: BTreeMap::new(),
        radius_scale,
    };
    Ok((sd, bvh))
}

/// Loads one model as the whole scene (as `render --obj` does: the demo's light and AO, the
/// camera framed from the model's bounds), with the same camera variants as a scene file. Without
/// `--radii` the settings' radii (in metres for the demo's scale) are multiplied by the radius
/// framing chose, so that they follow the model's size.
pub fn load_model(res: &ResDirs, path: &Path, cfg: &PerfConfig) -> Result<(SceneData, Scene)> {
    model_scene(res, path, (cfg.width, cfg.height), cfg.radii.is_empty())
}

/// A model as the whole scene at `size` (see `load_model`); with `scale_radius` its radius scale
/// is the radius framing chose, else 1.
pub fn model_scene(
    res: &ResDirs,
    path: &Path,
    size: (u32, u32),
    scale_radius: bool,
) -> Result<(SceneData, Scene)> {
    let found = path
        .canonicalize()
        .with_context(|| rust_i18n::t!("render.obj_not_found", path = path.display()))?;
    let data = crate::gl::mesh::MeshData::load_model(&found)?;
    let mut desc = SceneDesc::single_obj(&found);
    (desc.output.width, desc.output.height) = size;
    let framed = match data.bounds() {
        Some((lo, hi)) => framing::frame_model(&mut desc, lo, hi, framing::Fixed::default()),
        None => None,
    };
    let scale = match framed {
        Some(radius) if scale_radius => radius,
        _ => 1.0,
    };
    let name = path
        .file_stem()
        .map(|s| s.to_string_lossy().into_owned())
        .unwrap_or_else(|| "model".into());
    scene_data(res, name, desc, scale)
}

/// The cache key of every reference of `sd` at `radii` (camera index, radius, key).
fn reference_keys(
    sd: &SceneData,
    bvh: &Scene,
    radii: &[f32],
    cfg: &PerfConfig,
) -> Vec<(usize, f32, String)> {
    let (rw, rh) = cfg.reference_size();
    let mut keys = Vec::new();
    for (ci, cam) in sd.cameras.iter().enumerate() {
        for &r in radii {
            let camera = cam.camera(&sd.desc.camera);
            let key = cache_key(bvh.content_hash(), &camera, rw, rh, &params(r, cfg, false));
            keys.push((ci, r, key));
        }
    }
    keys
}

/// How many of the scene's references at `radii` are not in the cache yet.
pub fn missing_references(sd: &SceneData, bvh: &Scene, radii: &[f32], cfg: &PerfConfig) -> usize {
    reference_keys(sd, bvh, radii, cfg)
        .iter()
        .filter(|(_, _, key)| !cache_path(&cfg.cache, key).is_file())
        .count()
}

/// Ray-traces (or reads from the cache) the reference of every camera of `sd` at `radii`;
/// `done` counts the references of the whole run so far, of `total`, for the progress lines.
pub fn trace_references(
    sd: &mut SceneData,
    bvh: &Scene,
    radii: &[f32],
    cfg: &PerfConfig,
    count: &mut RenderCount,
    (done, total): (&mut usize, usize),
) {
    let (rw, rh) = cfg.reference_size();
    for (ci, r, key) in reference_keys(sd, bvh, radii, cfg) {
        let params = params(r, cfg, cfg.progress);
        let camera = sd.cameras[ci].camera(&sd.desc.camera);
        let hit = cache_path(&cfg.cache, &key).is_file();
        *done += 1;
        if cfg.progress {
            eprintln!(
                "reference {done}/{total} {}/{} R = {r} m, {rw}x{rh}, {} rays: {}",
                sd.name,
                sd.cameras[ci].name,
                cfg.ref_rays,
                if hit { "cached" } else { "rendering" }
            );
        }
        let t = Instant::now();
        let img = load_or_render_cached(&cfg.cache, bvh, &camera, rw, rh, &params);
        count.add(hit, t);
        sd.refs.insert((ci, r.to_bits()), img);
    }
}

/// Screen-space references keyed by (camera index, radius bits, ceiling).
pub type ScreenMap = BTreeMap<(usize, u32, CeilingKey), RefImage>;

/// A [`Ceiling`] as a map key: its kind and its thickness's bits.
pub type CeilingKey = (u8, u32);

/// The screen-space reference a method is split against: the depth buffer with the method's own
/// model of what lies behind a depth sample.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Ceiling {
    /// Infinitely thick surfaces: what the horizon methods assume.
    Heightfield,
    /// Every depth sample a slab this many metres thick: `vbao` with a thickness in metres.
    Slabs(f32),
    /// Each pixel's slab reaches the back face behind it, `fallback` metres thick where there is
    /// none: `vbao` with `thickness = "backface"`.
    BackFaces { fallback: f32 },
}

impl Ceiling {
    /// The ceiling of `method` under `ao`: `vbao` takes each sample as a slab of
    /// `AoSettings::thickness_metres` (the settings' radius and `[ao] thickness`) or, with
    /// `backface`, reaching its back face (that thickness where there is none, as vbao.frag does);
    /// every other method treats the depth buffer as a heightfield.
    pub fn of(method: AoMethod, ao: &AoSettings) -> Ceiling {
        match (method, ao.thickness) {
            (AoMethod::Vbao, Some(Thickness::Backface)) => Ceiling::BackFaces {
                fallback: ao.thickness_metres(),
            },
            (AoMethod::Vbao, _) => Ceiling::Slabs(ao.thickness_metres()),
            _ => Ceiling::Heightfield,
        }
    }

    pub fn key(self) -> CeilingKey {
        match self {
            Ceiling::Heightfield => (0, 0),
            Ceiling::Slabs(t) => (1, t.to_bits()),
            Ceiling::BackFaces { fallback } => (2, fallback.to_bits()),
        }
    }

    /// The kind, as the report's JSON names it.
    pub fn kind(self) -> &'static str {
        match self {
            Ceiling::Heightfield => "heightfield",
            Ceiling::Slabs(_) => "slabs",
            Ceiling::BackFaces { .. } => "back faces",
        }
    }

    /// The fixed thickness (m): the slabs', or the back-face ceiling's where there is no back
    /// face; `None` for the heightfield.
    pub fn thickness(self) -> Option<f32> {
        match self {
            Ceiling::Heightfield => None,
            Ceiling::Slabs(t) | Ceiling::BackFaces { fallback: t } => Some(t),
        }
    }

    /// The report's label: "∞", "0.25 m", "back faces (0.25 m where none)".
    pub fn label(self) -> String {
        match self {
            Ceiling::Heightfield => "∞".into(),
            Ceiling::Slabs(t) => format!("{t} m"),
            Ceiling::BackFaces { fallback } => format!("back faces ({fallback} m where none)"),
        }
    }
}

/// Screen-space reference of every test camera and (radius, ceiling) pair, from the engine's depth
/// buffer at the bench size, its visibility averaged over each `ref_scale`² block (the truth's
/// pixel footprint).
pub fn screen_references(
    engine: &mut Engine,
    sd: &SceneData,
    ceilings: &[(f32, Ceiling)],
    cfg: &PerfConfig,
    pb: &ProgressBar,
    count: &mut RenderCount,
) -> Result<ScreenMap> {
    let mut out = BTreeMap::new();
    // The ceilings read what the scene's engine methods read: its normals and its guard band.
    let normals = sd.desc.ao.normals == NormalSource::Geometric;
    for (ci, cam) in sd.cameras.iter().enumerate().filter(|(_, c)| !c.train) {
        let camera = cam.camera(&sd.desc.camera);
        engine.camera = camera;
        engine.sync_shader_constants()?;
        // Captured once per camera and (guard band, back faces, second layer's separation bits).
        let mut captured: BTreeMap<(u32, bool, Option<u32>), DepthBuffer> = BTreeMap::new();
        for &(r, ceiling) in ceilings {
            let params = screen_params(r, cfg.screen_rays, cfg.progress);
            let band =
                guard_band_pixels(sd.desc.ao.guard_band, &camera, (cfg.width, cfg.height), r);
            let guard = band;
            let back_faces = matches!(ceiling, Ceiling::BackFaces { .. });
            // The scene's second layer, its separation following the ceiling's radius.
            let second_layer = (sd.desc.ao.layers >= 2).then_some(LAYER_SEPARATION_OF_RADIUS * r);
            let slot = (guard, back_faces, second_layer.map(f32::to_bits));
            let buffer = match captured.get(&slot) {
                Some(b) => b.clone(),
                None => {
                    let what = Capture {
                        back_faces,
                        normals,
                        second_layer,
                    };
                    let b = DepthBuffer::capture(engine, guard, what)?;
                    captured.insert(slot, b.clone());
                    b
                }
            };
            let mut depth = match ceiling {
                Ceiling::Heightfield => buffer,
                Ceiling::Slabs(t) | Ceiling::BackFaces { fallback: t } => buffer.with_thickness(t),
            };
            depth.surface = Surface::for_normals(normals);
            let key = screen_box_cache_key(&depth, cfg.ref_scale, &params);
            let hit = cache_path(&cfg.cache, &key).is_file();
            if cfg.progress {
                pb.suspend(|| {
                    eprintln!(
                        "screen-space reference {}/{} R = {r} m, ceiling {}, {}x{}, {} rays: {}",
                        sd.name,
                        cam.name,
                        ceiling.label(),
                        depth.width,
                        depth.height,
                        cfg.screen_rays,
                        if hit { "cached" } else { "rendering" }
                    )
                });
            }
            let t = Instant::now();
            let img = pb.suspend(|| {
                load_or_render_screen_box_cached(&cfg.cache, &depth, cfg.ref_scale, &params)
            })?;
            count.add(hit, t);
            out.insert((ci, r.to_bits(), ceiling.key()), img);
        }
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_ceiling_shares_the_truths_rays_at_the_same_share_per_pixel() {
        // 256 rays over 6×6 sub-pixels: 8 each; 280 rounds to 8 too, 250 to 7.
        assert!(shares_rays(256, 256, 6));
        assert!(shares_rays(256, 280, 6));
        assert!(!shares_rays(256, 250, 6));
        assert!(!shares_rays(256, 64, 6));
        assert!(shares_rays(64, 64, 1));
    }

    #[test]
    fn each_method_is_split_against_its_own_thickness_model() {
        let ao = |thickness| AoSettings {
            radius: 0.8,
            thickness,
            ..AoSettings::default()
        };
        let half = crate::ao::settings::DEFAULT_THICKNESS_OF_RADIUS * 0.8;
        assert_eq!(Ceiling::of(AoMethod::Vbao, &ao(None)), Ceiling::Slabs(half));
        assert_eq!(
            Ceiling::of(AoMethod::Vbao, &ao(Some(Thickness::Metres(0.3)))),
            Ceiling::Slabs(0.3)
        );
        let back = Ceiling::of(AoMethod::Vbao, &ao(Some(Thickness::Backface)));
        assert_eq!(back, Ceiling::BackFaces { fallback: half });
        for m in [AoMethod::Gtao, AoMethod::SaoLesson] {
            let c = Ceiling::of(m, &ao(Some(Thickness::Backface)));
            assert_eq!(
                (c, c.thickness(), c.label()),
                (Ceiling::Heightfield, None, "∞".into())
            );
        }
        // Same thickness, different ceilings: different keys and labels.
        assert_ne!(back.key(), Ceiling::Slabs(half).key());
        assert_eq!(back.label(), format!("back faces ({half} m where none)"));
        assert_eq!((back.kind(), back.thickness()), ("back faces", Some(half)));
    }
}
