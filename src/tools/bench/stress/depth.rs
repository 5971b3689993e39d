//! Linear-depth reconstruction error against distance: the engine's own depth path and the
//! stand-alone probe of each depth format (`bench::depth_formats`).

use super::cases::{base, Meshes};
use super::report::{DepthConfigResult, DepthSample};
use crate::platform::HeadlessContext;
use crate::render::{Engine, View};
use crate::res::ResDirs;
use crate::tools::bench::depth_formats::{DepthFormat, DepthProbe};
use anyhow::Result;
use glam::Vec3;
use indicatif::ProgressBar;

/// Distances for the depth table: 1, 2 and 5 per decade (× 1.037 so that they are not round), within
/// (near, far), plus just past near and just before far.
fn depth_distances(near: f64, far: f64) -> Vec<f64> {
    let mut v = vec![near * 1.01];
    let mut k = near.log10().floor() as i32;
    while 10f64.powi(k) < far {
        for m in [1.0, 2.0, 5.0] {
            let d = m * 10f64.powi(k) * 1.037;
            if d > near * 1.01 && d < far * 0.99 {
                v.push(d);
            }
        }
        k += 1;
    }
    v.push(far * 0.99);
    v
}

/// The engine's restored linear depth of a facing plane at each distance (DEPTH_COMPONENT32).
fn engine_depths(
    ctx: &HeadlessContext,
    res: &ResDirs,
    m: &Meshes,
    near: f32,
    far: f32,
    distances: &[f64],
) -> Result<Vec<f32>> {
    let mut s = base(8, 8, Vec3::ZERO, Vec3::NEG_Z);
    s.camera.near = near;
    s.camera.far = far;
    s.light.shadow = false;
    s.objects
        .push(m.object("quad", Vec3::new(0.0, 0.0, -1.0), Vec3::ONE));
    let mut eng = Engine::new(&ctx.gl, res.clone(), &s, 8, 8)?;
    let mut out = Vec::new();
    for &d in distances {
        let d32 = d as f32;
        eng.objects[0].position = Vec3::new(0.0, 0.0, -d32);
        eng.objects[0].scale = Vec3::new(3.0 * d32, 3.0 * d32, 1.0);
        // The engine culls objects by their world bounds: keep them in step with the move.
        eng.objects[0].bounds = (
            Vec3::new(-3.0 * d32, -3.0 * d32, -d32),
            Vec3::new(3.0 * d32, 3.0 * d32, -d32),
        );
        let v = eng.render_values(View::LinearDepth)?;
        out.push(v[4 * 8 + 4]);
    }
    Ok(out)
}

/// (near, far) planes of the depth table; the quick run (tests) uses the first only.
pub const DEPTH_CONFIGS: [(f32, f32); 5] = [
    (0.35, 1000.0),
    (0.01, 100.0),
    (0.1, 1e4),
    (1.0, 1e6),
    (0.01, 1e6),
];

/// The linear-depth error against distance for each (near, far) in `configs`: the engine's, and the
/// stand-alone probe's per depth format; with a note on whether reversed-Z could be measured.
pub fn measure(
    ctx: &HeadlessContext,
    res: &ResDirs,
    meshes: &Meshes,
    configs: &[(f32, f32)],
    pb: &ProgressBar,
) -> Result<(Vec<DepthConfigResult>, String)> {
    let probe = DepthProbe::new(&ctx.gl, res)?;
    let mut depth_precision = Vec::new();
    for &(near, far) in configs {
        pb.set_message(format!("depth precision near {near} far {far}"));
        let distances = depth_distances(near as f64, far as f64);
        let eng = engine_depths(ctx, res, meshes, near, far, &distances)?;
        let mut per_mode = Vec::new();
        for mode in DepthFormat::ALL {
            let v = if probe.supports(mode) {
                Some(probe.measure(mode, near, far, &distances)?)
            } else {
                None
            };
            per_mode.push((mode, v));
        }
        let samples = distances
            .iter()
            .enumerate()
            .map(|(i, &d)| DepthSample {
                distance: d,
                engine_d32: eng[i] as f64 - d,
                probe: per_mode
                    .iter()
                    .map(|(m, v)| (m.label().to_string(), v.as_ref().map(|v| v[i] as f64 - d)))
                    .collect(),
                step: DepthFormat::ALL
                    .iter()
                    .map(|m| {
                        (
                            m.label().to_string(),
                            m.theoretical_step(d, near as f64, far as f64),
                        )
                    })
                    .collect(),
            })
            .collect();
        depth_precision.push(DepthConfigResult { near, far, samples });
        pb.inc(1);
    }
    let note = match &probe.clip_control_error {
        None => {
            "glClipControl loaded through the context's loader; reversed-Z measured".to_string()
        }
        Some(e) => format!("reversed-Z not measured: {e}"),
    };
    Ok((depth_precision, note))
}
