//! The run-time-against-error chart (`report.svg`, `report.png`) with plotters. Text needs a TrueType
//! font: one is looked up in the usual system folders (Debian's fonts-dejavu-core is enough) or in
//! `OPENGL3D_FONT`; without one, no chart is written and the caller says so.

use super::report::{Report, Row};
use anyhow::{anyhow, bail, Context as _, Result};
use plotters::prelude::*;
use std::path::{Path, PathBuf};
use std::sync::OnceLock;

const FONT_CANDIDATES: [&str; 6] = [
    "/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf",
    "/usr/share/fonts/TTF/DejaVuSans.ttf",
    "/usr/share/fonts/dejavu/DejaVuSans.ttf",
    "/usr/share/fonts/truetype/liberation/LiberationSans-Regular.ttf",
    "/usr/share/fonts/liberation/LiberationSans-Regular.ttf",
    "/usr/share/fonts/truetype/freefont/FreeSans.ttf",
];

/// Registers a sans-serif font once; `Err` with the places searched when none is found.
fn ensure_font() -> Result<()> {
    static FONT: OnceLock<Option<PathBuf>> = OnceLock::new();
    let found = FONT.get_or_init(|| {
        let mut paths: Vec<PathBuf> = std::env::var_os("OPENGL3D_FONT")
            .map(PathBuf::from)
            .into_iter()
            .collect();
        paths.extend(FONT_CANDIDATES.iter().map(PathBuf::from));
        for p in paths {
            if let Ok(bytes) = std::fs::read(&p) {
                let bytes: &'static [u8] = Box::leak(bytes.into_boxed_slice());
                if plotters::style::register_font("sans-serif", FontStyle::Normal, bytes).is_ok() {
                    return Some(p);
                }
            }
        }
        None
    });
    match found {
        Some(_) => Ok(()),
        None => bail!(
            "no TrueType font found (set OPENGL3D_FONT or install fonts-dejavu-core); searched {}",
            FONT_CANDIDATES.join(", ")
        ),
    }
}

const PALETTE: [RGBColor; 8] = [
    RGBColor(31, 119, 180),
    RGBColor(214, 39, 40),
    RGBColor(44, 160, 44),
    RGBColor(255, 127, 14),
    RGBColor(148, 103, 189),
    RGBColor(140, 86, 75),
    RGBColor(227, 119, 194),
    RGBColor(23, 190, 207),
];

fn draw<DB: DrawingBackend>(
    root: DrawingArea<DB, plotters::coord::Shift>,
    report: &Report,
    title: &str,
) -> Result<()>
where
    DB::ErrorType: 'static,
{
    let err = |e: DrawingAreaErrorKind<DB::ErrorType>| anyhow!("{e:?}");
    root.fill(&WHITE).map_err(err)?;
    let (w, _) = root.dim_in_pixel();
    let (left, right) = root.split_horizontally(w / 2);
    let proc = if report.software { "llvmpipe" } else { "GPU" };
    panel(
        left,
        report,
        &|r| r.total_ms,
        &format!(
            "{title}AO chain wall clock vs error, {}x{} ({proc})",
            report.width, report.height
        ),
        "AO chain, median wall ms per frame (around glFinish)",
    )?;
    panel(
        right,
        report,
        &|r| r.total_cpu_ms,
        &format!(
            "{title}AO chain CPU time vs error, {}x{} ({proc})",
            report.width, report.height
        ),
        "AO chain, median CPU ms per frame (process, all threads)",
    )?;
    root.present().map_err(err)?;
    Ok(())
}

fn panel<DB: DrawingBackend>(
    root: DrawingArea<DB, plotters::coord::Shift>,
    report: &Report,
    x_of: &dyn Fn(&Row) -> f64,
    caption: &str,
    x_desc: &str,
) -> Result<()>
where
    DB::ErrorType: 'static,
{
    let err = |e: DrawingAreaErrorKind<DB::ErrorType>| anyhow!("{e:?}");
    let xs: Vec<f64> = report.rows.iter().map(x_of).collect();
    let ys: Vec<f64> = report
        .rows
        .iter()
        .flat_map(|r| [r.rmse, r.fitted.rmse])
        .collect();
    let xmax = xs.iter().copied().fold(1e-3, f64::max) * 1.1;
    let xmin = xs.iter().copied().fold(f64::INFINITY, f64::min).min(xmax) * 0.9;
    let ymax = ys.iter().copied().fold(1e-3, f64::max) * 1.1;
    let mut chart = ChartBuilder::on(&root)
        .caption(caption, ("sans-serif", 20))
        .margin(16)
        .x_label_area_size(44)
        .y_label_area_size(64)
        .build_cartesian_2d(xmin.max(0.0)..xmax, 0.0..ymax)
        .map_err(err)?;
    chart
        .configure_mesh()
        .x_desc(x_desc)
        .y_desc("RMSE vs ray-traced visibility (test cameras)")
        .label_style(("sans-serif", 14))
        .draw()
        .map_err(err)?;
    let mut methods: Vec<&str> = Vec::new();
    for r in &report.rows {
        if !methods.contains(&r.method.as_str()) {
            methods.push(&r.method);
        }
    }
    for (i, m) in methods.iter().enumerate() {
        let color = PALETTE[i % PALETTE.len()];
        let rows: Vec<&Row> = report.rows.iter().filter(|r| r.method == *m).collect();
        chart
            .draw_series(
                rows.iter()
                    .map(|r| Circle::new((x_of(r), r.rmse), 5, color.filled())),
            )
            .map_err(err)?
            .label(format!("{m} raw"))
            .legend(move |(x, y)| Circle::new((x + 8, y), 5, color.filled()));
        chart
            .draw_series(
                rows.iter()
                    .map(|r| Circle::new((x_of(r), r.fitted.rmse), 5, color.stroke_width(2))),
            )
            .map_err(err)?
            .label(format!("{m} fitted a·v^b"))
            .legend(move |(x, y)| Circle::new((x + 8, y), 5, color.stroke_width(2)));
        // Label each raw point with its setting.
        chart
            .draw_series(rows.iter().map(|r| {
                EmptyElement::at((x_of(r), r.rmse))
                    + Text::new(
                        r.setting.clone(),
                        (7, -13),
                        ("sans-serif", 11).into_font().color(&color.mix(0.85)),
                    )
            }))
            .map_err(err)?;
    }
    chart
        .configure_series_labels()
        .background_style(WHITE.mix(0.85))
        .border_style(BLACK)
        .label_font(("sans-serif", 13))
        .position(SeriesLabelPosition::LowerRight)
        .draw()
        .map_err(err)?;
    Ok(())
}

/// Writes `report.svg` and `report.png` into `out` (every row), and with several scenes
/// `report-SCENE.svg` / `.png` for each (its rows only: errors are not comparable across scenes);
/// returns the files written.
pub fn write_charts(report: &Report, out: &Path) -> Result<Vec<PathBuf>> {
    ensure_font()?;
    if report.rows.is_empty() {
        bail!("no rows to chart");
    }
    let mut written = write_chart_pair(report, out, "report", "")?;
    if report.scenes.len() > 1 {
        for scene in &report.scenes {
            let mut one = report.clone();
            one.rows
                .retain(|r| r.cameras.first().is_some_and(|c| &c.scene == scene));
            if one.rows.is_empty() {
                continue;
            }
            let title = format!("{scene}: ");
            let stem = format!("report-{scene}");
            written.extend(write_chart_pair(&one, out, &stem, &title)?);
        }
    }
    Ok(written)
}

fn write_chart_pair(report: &Report, out: &Path, stem: &str, title: &str) -> Result<Vec<PathBuf>> {
    let (w, h) = (2000u32, 760u32);
    let svg = out.join(format!("{stem}.svg"));
    draw(
        SVGBackend::new(&svg, (w, h)).into_drawing_area(),
        report,
        title,
    )
    .with_context(|| format!("cannot write {}", svg.display()))?;
    let png = out.join(format!("{stem}.png"));
    let mut buf = vec![0u8; (w * h * 3) as usize];
    {
        let root = BitMapBackend::with_buffer(&mut buf, (w, h)).into_drawing_area();
        draw(root, report, title)?;
    }
    image::RgbImage::from_raw(w, h, buf)
        .ok_or_else(|| anyhow!("chart buffer size"))?
        .save(&png)
        .with_context(|| format!("cannot write {}", png.display()))?;
    Ok(vec![svg, png])
}
