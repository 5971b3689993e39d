//! The camera path's files: `camera-path.json` (every frame), `camera-path.md` (the means) and
//! `camera-path-SCENE.svg` / `.png` (PSNR over the frames, one line per configuration, the mean of
//! the test cameras).

use super::camera_path_score::{PathReport, PathRun};
use anyhow::{anyhow, Context as _, Result};
use plotters::prelude::*;
use std::fmt::Write as _;
use std::path::Path;

pub fn write(report: &PathReport, out: &Path) -> Result<()> {
    let json = serde_json::to_string_pretty(report)?;
    crate::io::write_file(&out.join("camera-path.json"), json.as_bytes())?;
    crate::io::write_file(&out.join("camera-path.md"), markdown(report).as_bytes())?;
    super::perf::chart::ensure_font()?;
    let mut scenes: Vec<&str> = report.runs.iter().map(|r| r.scene.as_str()).collect();
    scenes.dedup();
    for scene in scenes {
        let runs: Vec<&PathRun> = report.runs.iter().filter(|r| r.scene == scene).collect();
        chart(report, scene, &runs, out)?;
    }
    Ok(())
}

/// The table of means, one row per scene, camera and configuration.
pub fn markdown(r: &PathReport) -> String {
    let mut s = String::new();
    let _ = writeln!(
        s,
        "# Camera path: {}x{}, truth at 1/{} ({} rays, footprint means), {} still + {} moving \
         frames ({}° orbit and {:.1} % dolly per frame), history {} frames\n",
        r.width,
        r.height,
        r.ref_scale,
        r.ref_rays,
        r.still_frames,
        r.moving_frames,
        r.orbit_deg_per_frame,
        100.0 * r.dolly_per_frame,
        r.accumulate
    );
    let _ = writeln!(s, "Renderer: {}; {:.0} s.\n", r.renderer, r.run_s);
    s.push_str(
        "| scene | camera | configuration | still PSNR dB | moving PSNR dB | flicker still | \
         flicker moving | fresh-pixel RMSE (n) | AO CPU ms | × lesson |\n",
    );
    s.push_str("|---|---|---|---:|---:|---:|---:|---:|---:|---:|\n");
    for run in &r.runs {
        let m = &run.summary;
        let _ = writeln!(
            s,
            "| {} | {} | {} | {:.2} | {:.2} | {:.4} | {:.4} | {:.4} ({}) | {:.0} | {:.2}× |",
            run.scene,
            run.camera,
            run.setting.label,
            m.still_psnr,
            m.moving_psnr,
            m.still_flicker,
            m.moving_flicker,
            m.fresh_rmse,
            m.fresh_pixels,
            m.ao_cpu_ms,
            m.cost_ratio
        );
    }
    s.push_str("\nConfigurations:\n\n");
    let mut seen = Vec::new();
    for run in &r.runs {
        if !seen.contains(&&run.setting.label) {
            seen.push(&run.setting.label);
            let _ = writeln!(s, "- {}: {}", run.setting.label, run.setting.settings);
        }
    }
    s
}

/// Per configuration, the PSNR of each frame averaged over the scene's test cameras.
fn series(runs: &[&PathRun]) -> Vec<(String, Vec<f64>)> {
    let mut out: Vec<(String, Vec<f64>, usize)> = Vec::new();
    for run in runs {
        let psnr: Vec<f64> = run.frames.iter().map(|f| f.psnr).collect();
        match out.iter_mut().find(|(l, _, _)| *l == run.setting.label) {
            Some((_, sum, n)) => {
                for (s, p) in sum.iter_mut().zip(&psnr) {
                    *s += p;
                }
                *n += 1;
            }
            None => out.push((run.setting.label.clone(), psnr, 1)),
        }
    }
    out.into_iter()
        .map(|(l, sum, n)| (l, sum.iter().map(|s| s / n as f64).collect()))
        .collect()
}

fn chart(report: &PathReport, scene: &str, runs: &[&PathRun], out: &Path) -> Result<()> {
    let lines = series(runs);
    let svg = out.join(format!("camera-path-{scene}.svg"));
    let size = (900, 520);
    let mut text = String::new();
    draw(
        SVGBackend::with_string(&mut text, size).into_drawing_area(),
        report,
        scene,
        &lines,
    )
    .with_context(|| format!("cannot draw {}", svg.display()))?;
    crate::io::write_file(&svg, text.as_bytes())?;
    let mut buf = vec![0u8; (size.0 * size.1 * 3) as usize];
    {
        let root = BitMapBackend::with_buffer(&mut buf, size).into_drawing_area();
        draw(root, report, scene, &lines)?;
    }
    let png = out.join(format!("camera-path-{scene}.png"));
    image::RgbImage::from_raw(size.0, size.1, buf)
        .ok_or_else(|| anyhow!("chart buffer size"))?
        .save(&png)
        .with_context(|| format!("cannot write {}", png.display()))
}

fn draw<DB: DrawingBackend>(
    root: DrawingArea<DB, plotters::coord::Shift>,
    report: &PathReport,
    scene: &str,
    lines: &[(String, Vec<f64>)],
) -> Result<()>
where
    DB::ErrorType: 'static,
{
    root.fill(&WHITE).map_err(|e| anyhow!("{e}"))?;
    let frames = lines.iter().map(|(_, v)| v.len()).max().unwrap_or(1);
    let finite = lines
        .iter()
        .flat_map(|(_, v)| v.iter().copied())
        .filter(|p| p.is_finite());
    let (lo, hi) = finite.fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), p| {
        (a.min(p), b.max(p))
    });
    let (lo, hi) = if lo.is_finite() {
        (lo.floor() - 0.5, hi.ceil() + 0.5)
    } else {
        (0.0, 1.0)
    };
    let caption = format!(
        "{scene}: PSNR against each frame's truth (test cameras' mean); still until frame {}, then moving",
        report.still_frames
    );
    let mut chart = ChartBuilder::on(&root)
        .caption(caption, ("sans-serif", 16))
        .margin(12)
        .x_label_area_size(36)
        .y_label_area_size(48)
        .build_cartesian_2d(0f64..frames as f64, lo..hi)
        .map_err(|e| anyhow!("{e}"))?;
    chart
        .configure_mesh()
        .x_desc("frame")
        .y_desc("PSNR dB")
        .draw()
        .map_err(|e| anyhow!("{e}"))?;
    let still = report.still_frames as f64;
    chart
        .draw_series(LineSeries::new(
            [(still, lo), (still, hi)],
            BLACK.mix(0.3).stroke_width(1),
        ))
        .map_err(|e| anyhow!("{e}"))?;
    for (k, (label, v)) in lines.iter().enumerate() {
        let colour = Palette99::pick(k).to_rgba();
        let points = v
            .iter()
            .enumerate()
            .filter(|(_, p)| p.is_finite())
            .map(|(i, p)| (i as f64, *p));
        chart
            .draw_series(LineSeries::new(points, colour.stroke_width(2)))
            .map_err(|e| anyhow!("{e}"))?
            .label(label.clone())
            .legend(move |(x, y)| PathElement::new([(x, y), (x + 18, y)], colour.stroke_width(2)));
    }
    chart
        .configure_series_labels()
        .background_style(WHITE.mix(0.85))
        .border_style(BLACK.mix(0.4))
        .position(SeriesLabelPosition::LowerRight)
        .draw()
        .map_err(|e| anyhow!("{e}"))?;
    root.present().map_err(|e| anyhow!("{e}"))?;
    Ok(())
}
