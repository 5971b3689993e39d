//! `stress.md`: the stress report as tables.

use super::report::{DepthSample, StressReport};
use crate::ao::AoMethod;
use crate::tools::bench::depth_formats::DepthFormat;
use std::fmt::{self, Write as _};

fn sci(v: f64) -> String {
    if v == 0.0 {
        "0".into()
    } else {
        format!("{v:.2e}")
    }
}

/// `stress.md`: the cases table, the depth summary and one depth table per (near, far).
pub fn markdown(r: &StressReport) -> Result<String, fmt::Error> {
    let mut s = String::new();
    writeln!(s, "# AO numerical stress report\n")?;
    writeln!(
        s,
        "`opengl3d bench --stress` on **{}**, {:.0} s.\n",
        r.renderer, r.run_s
    )?;
    let failed = r.cases.iter().filter(|c| !c.ok).count();
    writeln!(
        s,
        "**{} cases, {} NaN/Inf values in all outputs, {} cases with a failed check.**\n",
        r.cases.len(),
        r.total_non_finite,
        failed
    )?;
    writeln!(
        s,
        "Each case renders the composite frame and the linear-depth, raw-AO and AO value views with \
         each listed method and counts NaN/Inf in: the main colour buffer (RGBA16F), every level of the \
         linear-depth mip chain, the raw and blurred AO buffers, and the three value views. Checks: \
         visibility in [0, 1], linear depth > 0, sky-only frames fully visible (1). Notes give the mean \
         AO-view visibility of surface pixels (an open plane should stay near 1: lower values there are \
         false occlusion).\n"
    )?;
    if !r.skipped.is_empty() {
        writeln!(s, "Skipped: {}.\n", r.skipped.join(", "))?;
    }
    writeln!(s, "| category | case | size | near | far | fov | radius | intensity | methods | NaN/Inf | result | ms | notes |")?;
    writeln!(
        s,
        "|---|---|---|---:|---:|---:|---:|---:|---|---:|---|---:|---|"
    )?;
    for c in &r.cases {
        let methods = if c.methods.len() == AoMethod::ALL.len() {
            "all".to_string()
        } else {
            c.methods.join(", ")
        };
        let result = if c.ok {
            "ok".to_string()
        } else {
            format!("**FAIL**: {}", c.failures.join("; "))
        };
        writeln!(
            s,
            "| {} | {} | {}×{} | {} | {} | {}° | {} | {} | {} | {} | {} | {:.0} | {} |",
            c.category,
            c.name,
            c.width,
            c.height,
            c.near,
            c.far,
            c.fov_y,
            c.radius,
            c.intensity,
            methods,
            c.non_finite,
            result,
            c.ms,
            c.notes.join("; ")
        )?;
    }
    writeln!(
        s,
        "\n## Linear-depth reconstruction error against distance\n"
    )?;
    writeln!(
        s,
        "A plane facing the camera (60° fov) at a known distance z; the table gives restored − exact \
         distance in metres. **engine D32** is the engine itself (`render_values(View::LinearDepth)`: \
         DEPTH_COMPONENT32 main depth, `sao_restore_depth.frag`). The **probe** columns come from `src/tools/bench/depth_formats.rs`, \
         which reuses the engine's parts (its projection for the convention, `shadow.vert` drawing the \
         same plane into a depth texture of the named format, and the engine's restore shader: \
         `sao_restore_depth.frag`, `A / ((2d − 1) − B)`, GL [-1, 1] clip space, LEQUAL; reversed-Z \
         `ao/restore_depth_reversed.frag`, `glClipControl(GL_LOWER_LEFT, GL_ZERO_TO_ONE)`, DEPTH32F, \
         GEQUAL, cleared to 0, `n·f / (d·(f − n) + n)`). The engine's `--depth d32f-reversed` is the \
         last column's convention. Steps are the theoretical distance of one depth-buffer \
         unit, quantisation only, without the f32 arithmetic of projection and restore (unorm: \
         z²(f − n)/(f·n)·2⁻ᴺ; D32F standard: 2⁻²³ of NDC; reversed D32F: d·2⁻²³ with d ≈ n/z). The \
         sample at 0.99·far can round onto the far plane and read back as sky (= far). \
         {}\n",
        r.depth_probe_note
    )?;
    // Summary: the largest relative error per mode, over distances up to half of far (the last
    // sample, at 0.99·far, can round onto the far plane and read back as sky = far).
    if let Some(first) = r.depth_precision.first().and_then(|c| c.samples.first()) {
        let labels: Vec<String> = first
            .probe
            .iter()
            .map(|p| p.0.replace("DEPTH_COMPONENT", "D"))
            .collect();
        writeln!(s, "Largest |restored − exact| / z for z ≤ far / 2:\n")?;
        writeln!(
            s,
            "| near | far | engine D32 | {} |",
            labels
                .iter()
                .map(|l| format!("probe {l}"))
                .collect::<Vec<_>>()
                .join(" | ")
        )?;
        writeln!(s, "|---:|---:|---:|{}", "---:|".repeat(labels.len()))?;
        for c in &r.depth_precision {
            let near_half: Vec<&DepthSample> = c
                .samples
                .iter()
                .filter(|x| x.distance <= c.far as f64 * 0.5)
                .collect();
            let worst = |f: &dyn Fn(&DepthSample) -> Option<f64>| {
                near_half
                    .iter()
                    .filter_map(|x| f(x).map(|e| (e / x.distance).abs()))
                    .fold(None, |m: Option<f64>, v| Some(m.map_or(v, |m| m.max(v))))
                    .map_or("n/a".to_string(), sci)
            };
            let probes: Vec<String> = (0..labels.len())
                .map(|i| worst(&|x: &DepthSample| x.probe[i].1))
                .collect();
            writeln!(
                s,
                "| {} | {} | {} | {} |",
                c.near,
                c.far,
                worst(&|x: &DepthSample| Some(x.engine_d32)),
                probes.join(" | ")
            )?;
        }
        writeln!(s)?;
    }
    for c in &r.depth_precision {
        writeln!(s, "### near {} m, far {} m\n", c.near, c.far)?;
        let labels: Vec<String> = c.samples.first().map_or(Vec::new(), |x| {
            x.probe.iter().map(|p| p.0.clone()).collect()
        });
        writeln!(
            s,
            "| z (m) | engine D32 | {} | step D24 | step D32F | step D32F rev-Z |",
            labels
                .iter()
                .map(|l| format!("probe {}", l.replace("DEPTH_COMPONENT", "D")))
                .collect::<Vec<_>>()
                .join(" | ")
        )?;
        writeln!(
            s,
            "|---:|---:|{}---:|---:|---:|",
            "---:|".repeat(labels.len())
        )?;
        for x in &c.samples {
            let probe: Vec<String> = x
                .probe
                .iter()
                .map(|p| p.1.map_or("n/a".into(), sci))
                .collect();
            let step = |label: &str| {
                x.step
                    .iter()
                    .find(|p| p.0 == label)
                    .map_or("".into(), |p| sci(p.1))
            };
            writeln!(
                s,
                "| {:.4} | {} | {} | {} | {} | {} |",
                x.distance,
                sci(x.engine_d32),
                probe.join(" | "),
                step(DepthFormat::D24.label()),
                step(DepthFormat::D32F.label()),
                step(DepthFormat::D32FReversed.label())
            )?;
        }
        writeln!(s)?;
    }
    Ok(s)
}
