//! `render --view error [--truth FILE]`: the AO view of the current settings against a truth image
//! (traced here when none is given), written as a signed error map (`crate::tools::error_map`), with PSNR and RMSE on stdout.

use super::args::RenderArgs;
use super::output::{OutFormat, PNG_OR_PFM};
use super::scene_args::load_scene;
use crate::platform::HeadlessContext;
use crate::render::Engine;
use crate::res::ResDirs;
use crate::tools::error_map;
use anyhow::{bail, Result};
use rust_i18n::t;

pub fn run(res: &ResDirs, args: &RenderArgs) -> Result<()> {
    OutFormat::of("--out", &args.out, PNG_OR_PFM)?;
    if !(args.error_range.is_finite() && args.error_range > 0.0) {
        bail!("{}", t!("error_map.bad_range", range = args.error_range));
    }
    if args.stats {
        bail!("{}", t!("error_map.no_stats"));
    }
    let (scene, (tw, th, truth)) = match &args.truth {
        Some(truth_path) => {
            // The truth first: a missing file or a wrong size costs no render.
            let (tw, th, truth) = error_map::read_truth(truth_path)?;
            let scene = load_scene(&args.scene, res)?;
            let (ew, eh) = (scene.output.width as usize, scene.output.height as usize);
            error_map::factor((ew, eh), (tw, th))
                .map_err(|e| anyhow::anyhow!("{}: {e}", truth_path.display()))?;
            (scene, (tw, th, truth))
        }
        None => {
            // No truth given: trace it (or read it from the reference cache), as the window's T.
            let scene = load_scene(&args.scene, res)?;
            let cache = crate::tools::reference::reference_cache_dir(None)?;
            let traced = error_map::traced_truth(res, &scene, &cache)?;
            let key = if traced.cached {
                "error_map.truth_cached"
            } else {
                "error_map.truth_traced"
            };
            let message = t!(
                key,
                size = format!("{}x{}", traced.width, traced.height),
                rays = error_map::TRACED_TRUTH_RAYS,
                radius = scene.ao.radius,
                path = traced.path.display()
            );
            eprintln!("{message}");
            (scene, (traced.width, traced.height, traced.ao))
        }
    };
    let (ew, eh) = (scene.output.width as usize, scene.output.height as usize);
    let ctx = HeadlessContext::new()?;
    let mut engine = Engine::at_output_size(&ctx.gl, res.clone(), &scene)?;
    super::scene_args::use_method_file(&mut engine, args.method_file.as_deref())?;
    let (ao, sky) = error_map::engine_view(&mut engine)?;
    let map = error_map::compare(&ao, &sky, (ew, eh), &truth, (tw, th))?;
    error_map::write(&args.out, &map, args.error_range)?;
    crate::outln!(
        "{}",
        t!(
            "error_map.wrote",
            path = args.out.display(),
            width = tw,
            height = th,
            engine = format!("{ew}x{eh}"),
            factor = map.factor,
            range = args.error_range,
            renderer = ctx.renderer
        )
    );
    crate::outln!(
        "{}",
        t!(
            "error_map.score",
            psnr = format!("{:.2}", map.psnr),
            rmse = format!("{:.4}", map.rmse),
            pixels = map.pixels
        )
    );
    Ok(())
}
