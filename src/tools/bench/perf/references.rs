//! The bench's ground truth: the ray-traced reference of every camera and radius of a scene, and
//! the screen-space references (from the engine's depth buffer) of its test cameras. Both come from
//! the reference cache when it has them.

use super::config::PerfConfig;
use crate::ao::{AoMethod, AoSettings};
use crate::render::Engine;
use crate::res::ResDirs;
use crate::scene::SceneDesc;
use crate::tools::bench::catalog::{self, BenchCamera};
use crate::tools::reference::{
    cache_key, cache_path, load_or_render_cached, load_or_render_screen_cached, screen_cache_key,
    AoVariant, DepthBuffer, RefImage, RefParams, Scene,
};
use anyhow::Result;
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
/// are reused across runs.
fn params(radius: f32, rays: u32, progress: bool) -> RefParams {
    RefParams {
        radius,
        rays,
        variant: AoVariant::Visibility,
        seed: 1,
        progress,
    }
}

/// Loads the scene at `path` at the bench size and its ray-traced references at `radii`.
pub fn load_scene(
    res: &ResDirs,
    path: &Path,
    radii: &[f32],
    cfg: &PerfConfig,
    count: &mut RenderCount,
) -> Result<SceneData> {
    let (rw, rh) = cfg.reference_size();
    let mut desc = SceneDesc::load(path)?;
    desc.output.width = cfg.width;
    desc.output.height = cfg.height;
    let name = path
        .file_stem()
        .map(|s| s.to_string_lossy().into_owned())
        .unwrap_or_else(|| "scene".into());
    let cameras = catalog::camera_variants(&desc.camera);
    let bvh = Scene::new(desc.world_triangles(res)?)?;
    let mut refs = BTreeMap::new();
    for (ci, cam) in cameras.iter().enumerate() {
        for &r in radii {
            let params = params(r, cfg.ref_rays, cfg.progress);
            let camera = cam.camera(&desc.camera);
            let key = cache_key(bvh.content_hash(), &camera, rw, rh, &params);
            let hit = cache_path(&cfg.cache, &key).is_file();
            if cfg.progress {
                eprintln!(
                    "reference {name}/{} R = {r} m, {rw}x{rh}, {} rays: {}",
                    cam.name,
                    cfg.ref_rays,
                    if hit { "cached" } else { "rendering" }
                );
            }
            let t = Instant::now();
            let img = load_or_render_cached(&cfg.cache, &bvh, &camera, rw, rh, &params);
            count.add(hit, t);
            refs.insert((ci, r.to_bits()), img);
        }
    }
    Ok(SceneData {
        name,
        desc,
        cameras,
        refs,
    })
}

/// Screen-space references keyed by (camera index, radius bits, thickness bits).
pub type ScreenMap = BTreeMap<(usize, u32, u32), RefImage>;

/// The thickness the ceiling of `method` gives the depth buffer's surfaces: the method's own model
/// of what lies behind a depth sample. `vbao` takes each sample as a slab of
/// `AoSettings::thickness_metres` (the settings' radius and `[ao] thickness`); every other method
/// treats the depth buffer as a heightfield, infinitely thick.
pub fn ceiling_thickness(method: AoMethod, ao: &AoSettings) -> f32 {
    match method {
        AoMethod::Vbao => ao.thickness_metres(),
        _ => f32::INFINITY,
    }
}

/// Screen-space reference of every test camera and (radius, thickness) pair, from the engine's
/// depth buffer at its current size (the reference's, so that the pixel centres match).
pub fn screen_references(
    engine: &mut Engine,
    sd: &SceneData,
    ceilings: &[(f32, f32)],
    cfg: &PerfConfig,
    pb: &ProgressBar,
    count: &mut RenderCount,
) -> Result<ScreenMap> {
    let mut out = BTreeMap::new();
    for (ci, cam) in sd.cameras.iter().enumerate().filter(|(_, c)| !c.train) {
        engine.camera = cam.camera(&sd.desc.camera);
        engine.sync_shader_constants()?;
        let heightfield = DepthBuffer::from_engine(engine)?;
        for &(r, thickness) in ceilings {
            let params = params(r, cfg.screen_rays, cfg.progress);
            let depth = heightfield.clone().with_thickness(thickness);
            let key = screen_cache_key(&depth, &params);
            let hit = cache_path(&cfg.cache, &key).is_file();
            if cfg.progress {
                pb.suspend(|| {
                    eprintln!(
                        "screen-space reference {}/{} R = {r} m, thickness {thickness} m, {}x{}, {} rays: {}",
                        sd.name,
                        cam.name,
                        depth.width,
                        depth.height,
                        cfg.screen_rays,
                        if hit { "cached" } else { "rendering" }
                    )
                });
            }
            let t = Instant::now();
            let img = pb.suspend(|| load_or_render_screen_cached(&cfg.cache, &depth, &params))?;
            count.add(hit, t);
            out.insert((ci, r.to_bits(), thickness.to_bits()), img);
        }
    }
    Ok(out)
}
