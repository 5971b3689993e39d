//! The pictures of `report.html`, in `pictures/` next to it: per scene, each test camera's
//! ray-traced truth at each radius, and each setting's AO view (box-averaged to the truth's size)
//! with its signed error map against that truth (`crate::tools::error_map`); with the error split, the
//! ceiling's own error map too (the screen-space reference the row is split against, same scale).

use super::config::PerfConfig;
use super::references::{Ceiling, SceneData, ScreenMap};
use crate::tools::bench::catalog::Setting;
use crate::tools::error_map;
use anyhow::Result;
use serde::Serialize;

/// The folder, relative to the report.
pub const FOLDER: &str = "pictures";

/// One setting's pictures (paths relative to the report) and the camera they show.
#[derive(Clone, Debug, Serialize)]
pub struct SettingPictures {
    pub camera: String,
    pub truth: String,
    pub ao: String,
    pub error: String,
    /// The error map's PSNR at that camera (dB; the same pixels as the row's raw figure).
    pub psnr: f64,
    /// The ceiling's error map against the same truth and its PSNR (dB), when the run computed it.
    pub ceiling_error: Option<String>,
    pub ceiling_psnr: Option<f64>,
}

/// `text` with anything but ASCII letters, digits, `-` and `.` as `_`: a plain file name.
fn plain(text: &str) -> String {
    text.chars()
        .map(|c| {
            if c.is_ascii_alphanumeric() || c == '-' || c == '.' {
                c
            } else {
                '_'
            }
        })
        .collect()
}

/// Writes, for each test camera of the scene, the truth (shared by the settings of a radius), the
/// AO view and the error map of `method` at `s`; `views` are the box-averaged AO views of every
/// camera; `ceiling`: the screen-space references and the row's ceiling (its map is shared by the
/// rows with that ceiling). Empty when the scene has no test camera.
pub fn write(
    cfg: &PerfConfig,
    sd: &SceneData,
    method: &str,
    s: &Setting,
    views: &[Vec<f32>],
    (screen, ceiling): (&ScreenMap, Ceiling),
) -> Result<Vec<SettingPictures>> {
    let dir = cfg.out.join(FOLDER);
    crate::io::create_dir_all(&dir)?;
    (0..sd.cameras.len())
        .filter(|ci| !sd.cameras[*ci].train)
        .map(|ci| write_camera(cfg, sd, ci, (method, s), &views[ci], (screen, ceiling)))
        .collect()
}

/// [`write`]'s pictures of camera `ci`, whose box-averaged AO view is `view`.
fn write_camera(
    cfg: &PerfConfig,
    sd: &SceneData,
    ci: usize,
    (method, s): (&str, &Setting),
    view: &[f32],
    (screen, ceiling): (&ScreenMap, Ceiling),
) -> Result<SettingPictures> {
    let r = &sd.refs[&(ci, s.radius.to_bits())];
    let (w, h) = (r.width, r.height);
    let dir = cfg.out.join(FOLDER);
    let camera = &sd.cameras[ci].name;
    let stem = plain(&format!("{}-{}", sd.name, camera));
    let truth = format!("{stem}-r{}-truth.png", plain(&s.radius.to_string()));
    crate::io::gray_to_png(&dir.join(&truth), w, h, &r.ao, 1.0)?;
    let setting = plain(&format!("{stem}-{method}-{}", s.label()));
    let (ao, error) = (format!("{setting}-ao.png"), format!("{setting}-error.png"));
    crate::io::gray_to_png(&dir.join(&ao), w, h, view, 1.0)?;
    let map = error_map::at_truth_size(
        view,
        &r.ao,
        r.sky_mask(),
        (w as usize, h as usize),
        cfg.ref_scale as usize,
    );
    error_map::write(&dir.join(&error), &map, error_map::DEFAULT_RANGE)?;
    let rel = |f: &str| format!("{FOLDER}/{f}");
    let mut ceiling_error = None;
    let mut ceiling_psnr = None;
    if let Some(img) = screen.get(&(ci, s.radius.to_bits(), ceiling.key())) {
        if (img.width, img.height) == (w, h) {
            let file = format!(
                "{stem}-r{}-ceiling-{}-error.png",
                plain(&s.radius.to_string()),
                plain(&ceiling.label())
            );
            let map =
                error_map::at_truth_size(&img.ao, &r.ao, r.sky_mask(), (w as usize, h as usize), 1);
            error_map::write(&dir.join(&file), &map, error_map::DEFAULT_RANGE)?;
            ceiling_error = Some(rel(&file));
            ceiling_psnr = Some(map.psnr);
        }
    }
    Ok(SettingPictures {
        camera: camera.clone(),
        truth: rel(&truth),
        ao: rel(&ao),
        error: rel(&error),
        psnr: map.psnr,
        ceiling_error,
        ceiling_psnr,
    })
}
