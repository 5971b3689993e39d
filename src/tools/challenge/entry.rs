//! One entry of the class challenge, measured in a child process of `grade --challenge` (the hidden
//! `challenge-entry` command): its method file on every scene's test cameras against the ray-traced
//! truth, its AO chain's time over the lesson chain's, measured side by side, and whether it renders
//! exactly what one of the engine's methods renders. Prints one JSON line.

use super::protocol::ChallengeProtocol;
use crate::ao::user_method::settings_for;
use crate::ao::{AoMethod, AoSettings};
use crate::platform::HeadlessContext;
use crate::render::Engine;
use crate::res::ResDirs;
use crate::scene::method_file::MethodFile;
use crate::tools::bench::perf::references::{self, RenderCount, SceneData};
use crate::tools::bench::perf::setting::{ao_chain_ms, camera_view, raw_error};
use crate::tools::error_map;
use anyhow::Result;
use clap::Args;
use serde::{Deserialize, Serialize};
use std::path::{Path, PathBuf};

#[derive(Args, Debug)]
pub struct ChallengeEntryArgs {
    /// The entry's method file.
    #[arg(long)]
    pub file: PathBuf,
    /// Where its pictures go.
    #[arg(long)]
    pub out: PathBuf,
    /// The protocol, as JSON (the parent's `ChallengeProtocol`).
    #[arg(long)]
    pub protocol: String,
}

/// What the child found, or why it could not.
#[derive(Clone, Debug, Serialize, Deserialize)]
pub enum EntryOutcome {
    Measured(EntryScore),
    Failed(String),
}

#[derive(Clone, Debug, Serialize, Deserialize)]
pub struct EntryScore {
    pub name: String,
    /// Per scene: mean PSNR (dB) of its test cameras, and the AO chain's time over the lesson's.
    pub scenes: Vec<SceneScore>,
    /// The engine method whose occlusion it reproduces exactly, if any.
    pub same_as: Option<String>,
}

#[derive(Clone, Debug, Serialize, Deserialize)]
pub struct SceneScore {
    pub scene: String,
    pub psnr: f64,
    pub cost_ratio: f64,
    /// Its AO and its error map at the scene's first test camera (relative to the report).
    pub ao_picture: String,
    pub error_picture: String,
}

pub fn run_entry(res: &ResDirs, args: &ChallengeEntryArgs) -> Result<()> {
    let outcome = match evaluate(res, args) {
        Ok(score) => EntryOutcome::Measured(score),
        Err(e) => EntryOutcome::Failed(format!("{e:#}")),
    };
    crate::outln!("{}", serde_json::to_string(&outcome)?);
    Ok(())
}

/// The engine's methods an entry could copy (the lesson's chain and the ray tracer are not
/// method-file shaped).
fn copyable() -> impl Iterator<Item = AoMethod> {
    AoMethod::ALL
        .into_iter()
        .filter(|m| !matches!(m, AoMethod::SaoLesson | AoMethod::Rtao))
}

fn evaluate(res: &ResDirs, args: &ChallengeEntryArgs) -> Result<EntryScore> {
    let protocol: ChallengeProtocol = serde_json::from_str(&args.protocol)?;
    let file = MethodFile::read(&args.file)?;
    let perf = protocol.perf_config();
    let ctx = HeadlessContext::new()?;
    let mut scenes = Vec::new();
    let mut same_as: Option<String> = None;
    let mut differs_from: Vec<AoMethod> = Vec::new();
    for path in &protocol.scenes {
        let (mut sd, bvh) = references::load_scene(res, path, &perf)?;
        let radius = sd.desc.ao.radius;
        // The parent traced the truths: these are cache reads.
        let (mut done, total) = (0, sd.cameras.len());
        references::trace_references(
            &mut sd,
            &bvh,
            &[radius],
            &perf,
            &mut RenderCount::default(),
            (&mut done, total),
        );
        let mut engine = Engine::new(&ctx.gl, res.clone(), &sd.desc, perf.width, perf.height)?;
        let scene_ao = AoSettings {
            enabled: true,
            ..sd.desc.ao
        };
        engine.camera = sd.cameras[0].camera(&sd.desc.camera);
        engine.ao_settings = AoSettings {
            method: AoMethod::SaoLesson,
            ..scene_ao
        };
        engine.sync_shader_constants()?;
        let lesson_ms = ao_chain_ms(&mut engine, &perf)?;
        engine.ao_settings = scene_ao;
        engine.use_method_file(file.clone())?;
        let entry_ms = ao_chain_ms(&mut engine, &perf)?;
        let test: Vec<usize> = (0..sd.cameras.len())
            .filter(|&ci| !sd.cameras[ci].train)
            .collect();
        let mut views = Vec::new();
        let mut psnr = 0.0;
        for &ci in &test {
            let view = camera_view(&mut engine, &sd, ci, radius, &perf)?;
            psnr += raw_error(&sd, ci, radius, &view, false).psnr;
            views.push(view);
        }
        psnr /= test.len().max(1) as f64;
        let (ao_picture, error_picture) = pictures(&args.out, &sd, test[0], radius, &views[0])?;
        // A copy renders what an engine method renders with the same settings, on every camera.
        let entry_settings = settings_for(&file, &scene_ao);
        engine.ao.set_user_method(None);
        let candidates: Vec<AoMethod> = copyable().filter(|m| !differs_from.contains(m)).collect();
        for m in candidates {
            engine.ao_settings = AoSettings {
                method: m,
                ..entry_settings
            };
            let mut same = true;
            for (k, &ci) in test.iter().enumerate() {
                same &= camera_view(&mut engine, &sd, ci, radius, &perf)? == views[k];
            }
            if !same {
                differs_from.push(m);
            }
        }
        same_as = copyable()
            .find(|m| !differs_from.contains(m))
            .map(|m| m.name().to_string());
        scenes.push(SceneScore {
            scene: sd.name.clone(),
            psnr,
            cost_ratio: entry_ms / lesson_ms.max(1e-6),
            ao_picture,
            error_picture,
        });
    }
    Ok(EntryScore {
        name: file.name,
        scenes,
        same_as,
    })
}

/// The entry's AO and error map at camera `ci`, at the truth's size, in `out`; their file names.
fn pictures(
    out: &Path,
    sd: &SceneData,
    ci: usize,
    radius: f32,
    view: &[f32],
) -> Result<(String, String)> {
    let truth = &sd.refs[&(ci, radius.to_bits())];
    let (w, h) = (truth.width as usize, truth.height as usize);
    let ao_name = format!("{}-ao.png", sd.name);
    let error_name = format!("{}-error.png", sd.name);
    crate::io::create_dir_all(out)?;
    crate::io::gray_to_png(&out.join(&ao_name), w as u32, h as u32, view, 1.0)?;
    let map = error_map::at_truth_size(view, &truth.ao, truth.sky_mask(), (w, h), 1);
    error_map::write(&out.join(&error_name), &map, error_map::DEFAULT_RANGE)?;
    Ok((ao_name, error_name))
}
