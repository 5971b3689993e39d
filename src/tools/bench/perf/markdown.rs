//! `report.md`: how the bench measured, the results table, the error split and the per-camera
//! figures.

use super::config::PerfConfig;
use super::report::{Report, Row};
use crate::tools::metrics;
use std::collections::BTreeMap;
use std::fmt::{self, Write as _};

/// Role of a pass in the AO chain (the table's columns), from its name.
fn pass_role(name: &str) -> &'static str {
    if name.contains("restore") {
        "restore"
    } else if name.contains("down sampling") {
        "down"
    } else if name.contains("composite") {
        "composite"
    } else if name.contains("blur") {
        "blur"
    } else {
        "ao"
    }
}

const AO_PASS_ROLES: [&str; 5] = ["restore", "down", "ao", "blur", "composite"];
const NON_AO_PASSES: [&str; 7] = [
    "shadow map",
    "opaque",
    "sky",
    "transparent",
    "bloom",
    "image processing",
    "debug view",
];

fn role_ms(row: &Row, role: &str) -> Option<f64> {
    role_sum(&row.passes, role)
}

fn role_sum(passes: &BTreeMap<String, f64>, role: &str) -> Option<f64> {
    let v: Vec<f64> = passes
        .iter()
        .filter(|(k, _)| !NON_AO_PASSES.contains(&k.as_str()) && pass_role(k) == role)
        .map(|(_, v)| *v)
        .collect();
    (!v.is_empty()).then(|| v.iter().sum())
}

/// The scene a row was measured on (its cameras carry the name).
fn scene_of(row: &Row) -> &str {
    row.cameras.first().map_or("", |c| c.scene.as_str())
}

fn f(v: f64, digits: usize) -> String {
    format!("{v:.digits$}")
}

pub fn markdown(r: &Report, cfg: &PerfConfig) -> Result<String, fmt::Error> {
    let mut s = String::new();
    writeln!(s, "# AO benchmark: run time against error\n")?;
    writeln!(
        s,
        "`opengl3d bench` at {}×{} on **{}** ({} CPU threads visible).\n",
        r.width, r.height, r.renderer, r.cpus
    )?;
    scaled_section(&mut s, r)?;
    writeln!(s, "## How it was measured\n")?;
    writeln!(
        s,
        "- **Timing**: {}. The whole frame (composite view: shadow, opaque, AO chain, sky, bloom, \
         image processing) is rendered {} times to warm up, then {} times timed, at the scene's own \
         camera. Each pass's column is its median {} (and, in brackets, its median CPU ms); **AO ms** is the median of the per-frame sum of \
         the AO passes (restore + down-sampling + the method + blur + composite); the range is the \
         fastest and slowest frame. **AO CPU ms** is the median CPU time the process (llvmpipe's \
         rasteriser threads included) spent in the same passes (`clock_gettime(CLOCK_PROCESS_CPUTIME_ID)`): \
         it barely moves when other programs load the machine, so it is the fairer cost to compare \
         settings by; on an idle machine wall ≈ CPU / threads for well-parallelised passes. Frame ms is \
         the median whole frame. Timing brackets every pass with \
         glFinish, so passes do not overlap: the sum is slower than an untimed frame.",
        r.timing,
        r.warmup_frames,
        r.timed_frames,
        r.clock.unit()
    )?;
    writeln!(
        s,
        "- **Ground truth**: CPU ray tracing of the same triangles ({}), {} rays per pixel, ray length = the \
         setting's radius, at {}×{}{}. Cached under `{}` ({} rendered in {:.0} s this run, {} read from \
         the cache).",
        r.reference.variant,
        r.reference.rays,
        r.reference.width,
        r.reference.height,
        if r.reference.width != r.width {
            format!(
                " (the engine's {}×{} output is box-averaged {}× before comparing; each truth pixel \
                 is the mean over the same footprint, {n}×{n} sub-pixel centres sharing its rays)",
                r.width,
                r.height,
                cfg.ref_scale,
                n = cfg.ref_scale
            )
        } else {
            " (the engine's output size)".to_string()
        },
        cfg.cache.display(),
        r.reference.rendered,
        r.reference.render_s,
        r.reference.cached
    )?;
    writeln!(
        s,
        "- **Error**: the blurred AO view (`render_values(View::Ao)`, ambient visibility, 1 = open) \
         against the reference on non-sky pixels: RMSE, MAE, PSNR (peak 1, capped at {} dB), SSIM \
         (Gaussian σ = 1.5, 11×11), FLIP (LDR ꟻLIP, 67 px/°, images shown as grey sRGB). \
         **Raw** is the method as configured (scene intensity and bias). **Fitted** maps visibility \
         through min(1, a·v^b), with a and b least-squares fitted on the training cameras and reported \
         on the test cameras only.",
        metrics::PSNR_CAP_DB
    )?;
    if !r.ceilings {
        writeln!(
            s,
            "- **Error split**: skipped (no screen-space references); `--ceilings` or `--full` \
             computes them."
        )?;
    } else {
        writeln!(
        s,
        "- **Error split**: a **screen-space reference** is computed from the engine's own depth \
         buffer at the engine's size ({}×{}), its visibility averaged over the blocks the comparison \
         box-averages (each truth pixel's footprint): the same visibility (radius and sampling; at least {} rays per block, test cameras only), but with the \
         scene replaced by the depth buffer (normals as the scene's engine methods read them: each triangle's own with `[ao] normals = \"geometric\"`, and then each pixel's footprint holds the plane through its centre with that normal, solid to its exact back face; else (the default) rebuilt from the depth buffer, and then inverse depth is interpolated over triangles between pixel centres, a triangle solid only where its pixels' slabs overlap; as wide as the scene's `[ao] guard_band`) and every ray \
         marched exactly through every pixel or cell it crosses, without mips; rays leaving the screen \
         count as open. It is what a perfect screen-space method could compute. **Depth-buffer \
         error** = screen-space reference against the ray-traced one (hidden surfaces, thickness, \
         off-screen occluders: the same for every method with the same thickness model at a camera and radius); **sampling \
         error** = the method (raw) against the screen-space reference (what its samples, mips, \
         blur and intensity lose). Both on the ray-traced reference's non-sky pixels, means over \
         the test cameras, without FLIP. At the ray-traced reference's rays per block (the default) \
         each of its pixels traces the rays that reference traces for the same sub-pixel, so the \
         two share their Monte Carlo noise, which the depth-buffer error then does not hold; at \
         other counts both errors hold both references' noise. The second layer's patches are \
         flat (it has no normals of its own). \
         Each method is split against the ceiling with its own model of what lies behind a depth \
         sample: `vbao` against slabs of its thickness (the solid at a pixel is [z, z + T] in linear \
         depth) or, with `thickness = \"backface\"`, against slabs reaching each pixel's back \
         face (T where it has none, as `vbao` does; with the triangles, never thinner than T), and with \
         `layers = 2` the second layer's slabs reaching its own back faces, never thinner than T/4, as \
         `vbao`'s; every other method against the heightfield (∞). The split table's \
         ceiling column says which each row used. Cached under the same folder ({} rendered in {:.0} s this run, {} read from the cache).",
        r.width,
        r.height,
        r.reference.screen_rays,
        r.reference.screen_rendered,
        r.reference.screen_render_s,
        r.reference.screen_cached
    )?;
    }
    writeln!(s, "- **Cameras** (train / test):")?;
    for (scene, c) in &r.cameras {
        writeln!(
            s,
            "  - {scene}/{}: eye {:?}, target {:?}, fov {}° — {}",
            c.name,
            c.eye,
            c.target,
            c.fov_y,
            if c.train { "train" } else { "test" }
        )?;
    }
    let load = |l: &Option<[f64; 3]>| {
        l.map_or("unknown".to_string(), |l| {
            format!("{:.2} {:.2} {:.2}", l[0], l[1], l[2])
        })
    };
    writeln!(
        s,
        "- Error figures are the mean over the test cameras. Load average (1/5/15 min) when timing \
         started: {}, when it ended: {}, on {} CPU threads: other processes on the machine slow frames \
         down, so compare settings through the fastest frame (range) as well as the median, and treat \
         differences under ~10–20% as noise.\n",
        load(&r.load_before),
        load(&r.load_after),
        r.cpus
    )?;
    writeln!(s, "## Results\n")?;
    writeln!(
        s,
        "| scene | method | setting | restore | down | AO pass | blur | composite | **AO ms** (range) | AO CPU ms | frame ms | RMSE | MAE | PSNR dB | SSIM | FLIP | fit a, b | fitted RMSE | fitted PSNR | fitted SSIM | fitted FLIP |"
    )?;
    writeln!(s, "|---|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---|---:|---:|---:|---:|")?;
    for row in &r.rows {
        let roles: Vec<String> = AO_PASS_ROLES
            .iter()
            .map(
                |role| match (role_ms(row, role), role_sum(&row.passes_cpu, role)) {
                    (Some(w), Some(c)) => format!("{} ({})", f(w, 1), f(c, 0)),
                    _ => "–".into(),
                },
            )
            .collect();
        writeln!(
            s,
            "| {} | {} | {} | {} | **{}** ({}–{}) | {} | {} | {} | {} | {} | {} | {} | {}, {} | {} | {} | {} | {} |",
            scene_of(row),
            row.method,
            row.setting,
            roles.join(" | "),
            f(row.total_ms, 1),
            f(row.total_ms_min, 1),
            f(row.total_ms_max, 1),
            f(row.total_cpu_ms, 1),
            f(row.frame_ms, 0),
            f(row.rmse, 4),
            f(row.mae, 4),
            f(row.psnr, 2),
            f(row.ssim, 4),
            f(row.flip, 4),
            f(row.fit.a, 3),
            f(row.fit.b, 3),
            f(row.fitted.rmse, 4),
            f(row.fitted.psnr, 2),
            f(row.fitted.ssim, 4),
            f(row.fitted.flip, 4),
        )?;
    }
    // Best settings.
    let best = |key: &dyn Fn(&Row) -> f64| {
        r.rows
            .iter()
            .max_by(|a, b| key(a).total_cmp(&key(b)))
            .map(|row| format!("{} {} ({})", row.method, row.setting, scene_of(row)))
            .unwrap_or_default()
    };
    writeln!(s)?;
    writeln!(
        s,
        "Best raw PSNR: {}. Best fitted PSNR: {}.\n",
        best(&|r| r.psnr),
        best(&|r| r.fitted.psnr)
    )?;
    if r.ceilings {
        split_section(&mut s, r)?;
    }
    writeln!(s, "## Per camera (PSNR dB, raw / fitted)\n")?;
    for scene in &r.scenes {
        let rows: Vec<&Row> = r.rows.iter().filter(|row| scene_of(row) == scene).collect();
        let Some(first) = rows.first() else {
            continue;
        };
        let header: Vec<String> = first
            .cameras
            .iter()
            .map(|c| format!("{}{}", c.camera, if c.train { " (train)" } else { "" }))
            .collect();
        writeln!(s, "| {scene} | setting | {} |", header.join(" | "))?;
        writeln!(s, "|---|---|{}", "---:|".repeat(header.len()))?;
        for row in rows {
            let cells: Vec<String> = row
                .cameras
                .iter()
                .map(|c| {
                    if c.train {
                        f(c.raw.psnr, 2)
                    } else {
                        format!("{} / {}", f(c.raw.psnr, 2), f(c.fitted.psnr, 2))
                    }
                })
                .collect();
            writeln!(
                s,
                "| {} | {} | {} |",
                row.method,
                row.setting,
                cells.join(" | ")
            )?;
        }
        writeln!(s)?;
    }
    writeln!(
        s,
        "Charts: `report.svg` (and `report.png` when a TrueType font was found): one panel per scene \
         and radius, raw PSNR against the AO chain's median {} (each radius has its own truth, so \
         radii are never mixed), one colour per method on every chart, the Pareto front (no other \
         setting is both cheaper and closer to the truth) drawn as a line with its settings \
         labelled; the other points are named in the SVG's tooltips.\n\nRun time of the whole bench: {:.0} s.",
        r.clock.unit(),
        r.run_s
    )?;
    Ok(s)
}

/// What a quick run scaled down or skipped against the full protocol (nothing for a full run).
fn scaled_section(s: &mut String, r: &Report) -> fmt::Result {
    if r.scaled.is_empty() {
        return Ok(());
    }
    writeln!(
        s,
        "## A quick run\n\nScaled down or skipped against the full protocol (`{}`):\n",
        super::protocol::FULL_COMMAND
    )?;
    for line in &r.scaled {
        writeln!(s, "- {line}")?;
    }
    writeln!(s)
}

/// Mean of a per-camera figure over a row's test cameras.
fn mean_test(row: &Row, pick: impl Fn(&super::report::CameraError) -> f64) -> f64 {
    let test: Vec<f64> = row.cameras.iter().filter(|c| !c.train).map(pick).collect();
    test.iter().sum::<f64>() / test.len().max(1) as f64
}

/// The depth buffer's PSNR with the screen-space reference's own Monte Carlo noise taken out (its
/// squared error against the ray tracer is the depth buffer's plus σ², the two independent), mean
/// over the test cameras: what "ceiling above method" compares, since a method's blurred output
/// carries little noise and the reference at 64 rays a block carries σ ≈ 0.03.
fn depth_buffer_psnr_without_noise(row: &Row) -> f64 {
    mean_test(row, |c| {
        let mse = c.depth_buffer_error.rmse.powi(2) - c.ceiling_own_noise_rms.powi(2);
        -10.0 * mse.max(1e-10).log10()
    })
}

/// Allowed gap (dB) between a method's PSNR and the PSNR of its two parts added in squares.
const ADDS_UP_DB: f64 = 1.0;

/// The error split table and whether each row's split adds up.
fn split_section(s: &mut String, r: &Report) -> fmt::Result {
    writeln!(s, "## Error split: depth buffer against sampling\n")?;
    writeln!(
        s,
        "| scene | method | setting | ceiling thickness | vs ray-traced RMSE | PSNR dB | depth-buffer RMSE | depth-buffer PSNR dB | without its noise | sampling RMSE | sampling PSNR dB | sampling SSIM | ceiling noise σ | parts PSNR dB | gap dB (max) | adds up | ceiling above method |"
    )?;
    writeln!(
        s,
        "|---|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---|---|"
    )?;
    for row in &r.rows {
        let thickness = &row.ceiling_label;
        writeln!(
            s,
            "| {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} ({}) | {} | {} |",
            scene_of(row),
            row.method,
            row.setting,
            thickness,
            f(row.rmse, 4),
            f(row.psnr, 2),
            f(row.depth_buffer_error.rmse, 4),
            f(row.depth_buffer_error.psnr, 2),
            f(depth_buffer_psnr_without_noise(row), 2),
            f(row.sampling_error.rmse, 4),
            f(row.sampling_error.psnr, 2),
            f(row.sampling_error.ssim, 4),
            f(mean_test(row, |c| c.ceiling_noise_rms), 4),
            f(row.parts_psnr, 2),
            f(row.split_gap_db, 2),
            f(row.split_gap_max_db, 2),
            if row.split_gap_max_db <= ADDS_UP_DB {
                "yes"
            } else {
                "no"
            },
            if depth_buffer_psnr_without_noise(row) > row.psnr {
                "yes"
            } else {
                "no"
            },
        )?;
    }
    let adds_up = r
        .rows
        .iter()
        .filter(|row| row.split_gap_max_db <= ADDS_UP_DB)
        .count();
    let ceiling = r
        .rows
        .iter()
        .filter(|row| depth_buffer_psnr_without_noise(row) > row.psnr)
        .count();
    writeln!(
        s,
        "\nThe depth-buffer columns depend only on the camera, the radius and the ceiling's thickness. \
         **Does the split add up?** For each test camera, **parts PSNR** = 10·log10(1 / (RMSE_db² + \
         RMSE_s² − 2σ_own²)), the PSNR the method would have if its error against the ray-traced \
         reference were the depth buffer's error and its sampling error added in squares \
         (uncorrelated). **Ceiling noise** σ (RMS) is the screen-space reference's standard error. \
         Where it traces the ray-traced reference's own rays (`--screen-rays` equal to `--ref-rays`, \
         the default) its noise is the truth's: in the sampling part and the total alike, not in the \
         depth-buffer part, and σ_own = 0. Where it draws rays of its own, σ_own = σ: its noise is in \
         both parts but not in the total, so it is taken out twice; **gap** = \
         method PSNR − parts PSNR (mean over the test cameras; in brackets the largest |gap| of one \
         camera). A positive gap means the two parts partly cancel (the method under-darkens where the \
         depth buffer over-darkens), a negative one that they add up more than in squares. **Adds up**: \
         every test camera's |gap| ≤ {ADDS_UP_DB} dB ({adds_up} of {} rows). **Ceiling above method**: the \
         screen-space reference, its own noise taken out (**without its noise**: 10·log10(1 / \
         (RMSE_db² − σ_own²)) per test camera), scores a higher PSNR against the ray-traced one than the \
         method does ({ceiling} of {} rows).\n",
        r.rows.len(),
        r.rows.len()
    )?;
    Ok(())
}
