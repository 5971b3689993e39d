//! The window's truth (`window`, key T): the CPU ray tracer of `opengl3d reference` and the error map
//! of `render --view error`, handed to the window, which sits below the tools.

use crate::platform::window::truth::{
    ErrorPicture, Truth, TruthBackend, TruthProgress, TruthRequest,
};
use crate::tools::error_map;
use crate::tools::reference::{
    cache_key, read_cached, render_reference_watched, write_cached, AoVariant, RefParams, Scene,
};
use anyhow::{bail, Result};
use std::path::PathBuf;

/// Rays per pixel of the window's truth: `opengl3d reference`'s default, so both share cached files.
pub const TRUTH_RAYS: u32 = 256;

/// The CPU ray tracer, with the reference cache when there is one.
pub struct CpuTruth {
    pub cache_dir: Option<PathBuf>,
    pub rays: u32,
}

impl CpuTruth {
    /// The tracer at [`TRUTH_RAYS`], caching in the reference cache folder when it can be found.
    pub fn new() -> CpuTruth {
        CpuTruth {
            cache_dir: crate::tools::reference::reference_cache_dir(None).ok(),
            rays: TRUTH_RAYS,
        }
    }

    /// The parameters `opengl3d reference` traces with at `radius` (visibility, seed 1).
    pub fn params(&self, radius: f32) -> RefParams {
        RefParams {
            radius,
            rays: self.rays,
            variant: AoVariant::Visibility,
            seed: 1,
            progress: false,
            supersample: 1,
        }
    }
}

impl Default for CpuTruth {
    fn default() -> Self {
        CpuTruth::new()
    }
}

impl TruthBackend for CpuTruth {
    fn trace(&self, r: &TruthRequest, progress: &TruthProgress) -> Result<Truth> {
        let scene = Scene::new(r.triangles.as_ref().clone())?;
        let params = RefParams {
            supersample: r.footprint.max(1),
            ..self.params(r.radius)
        };
        let key = cache_key(scene.content_hash(), &r.camera, r.width, r.height, &params);
        let cached = self.cache_dir.as_ref().and_then(|d| read_cached(d, &key));
        let img = match cached.filter(|i| (i.width, i.height) == (r.width, r.height)) {
            Some(img) => img,
            None => {
                let img = render_reference_watched(
                    &scene,
                    &r.camera,
                    r.width,
                    r.height,
                    &params,
                    &|| {
                        progress.row_done();
                        !progress.cancelled()
                    },
                );
                if progress.cancelled() {
                    bail!("cancelled");
                }
                if let Some(dir) = &self.cache_dir {
                    // An unwritable cache only costs a trace next time.
                    if let Err(e) = write_cached(dir, &key, &img) {
                        log::warn!("{e:#}");
                    }
                }
                img
            }
        };
        Ok(Truth {
            width: img.width,
            height: img.height,
            ao: img.ao,
        })
    }

    fn error_map(
        &self,
        ao: &[f32],
        sky: &[bool],
        engine_size: (usize, usize),
        truth: &Truth,
    ) -> Result<ErrorPicture> {
        let size = (truth.width as usize, truth.height as usize);
        let map = error_map::compare(ao, sky, engine_size, &truth.ao, size)?;
        Ok(ErrorPicture {
            image: error_map::picture(&map, error_map::DEFAULT_RANGE),
            psnr: map.psnr,
            rmse: map.rmse,
        })
    }
}
