//! The cost-against-error chart (`report.svg`, `report.png`) with plotters: one panel per scene and
//! radius, the Pareto front as a line, a fixed colour per method (`front.rs`). Text needs a TrueType
//! font: one is looked up in the usual system folders (Debian's fonts-dejavu-core is enough) or in
//! `OPENGL3D_FONT`; without one, no chart is written and the caller says so.

mod front;

use super::report::Report;
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
pub(crate) fn ensure_font() -> Result<()> {
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

/// Pixels of one panel, and of the legend strip under the panels.
const PANEL: (u32, u32) = (680, 460);
const LEGEND_HEIGHT: u32 = 56;
const MAX_COLUMNS: usize = 3;

/// A point's SVG tooltip: where it was drawn (backend pixels) and what it is.
struct Tip {
    at: (i32, i32),
    text: String,
}

fn draw<DB: DrawingBackend>(
    root: DrawingArea<DB, plotters::coord::Shift>,
    report: &Report,
    tips: &mut Vec<Tip>,
) -> Result<()>
where
    DB::ErrorType: 'static,
{
    let err = |e: DrawingAreaErrorKind<DB::ErrorType>| anyhow!("{e:?}");
    root.fill(&WHITE).map_err(err)?;
    let (_, h) = root.dim_in_pixel();
    let (grid, legend_area) = root.split_vertically(h - LEGEND_HEIGHT);
    let panels = front::panels(&report.scenes, &report.rows);
    let columns = panels.len().clamp(1, MAX_COLUMNS);
    let rows = panels.len().div_ceil(columns).max(1);
    let areas = grid.split_evenly((rows, columns));
    for (panel, area) in panels.iter().zip(areas) {
        draw_panel(area, report, panel, tips)?;
    }
    legend(legend_area, report)?;
    root.present().map_err(err)?;
    Ok(())
}

/// One scene and radius: PSNR against the AO chain's cost, the Pareto front as a line with its
/// settings labelled, every other point named only in its tooltip.
fn draw_panel<DB: DrawingBackend>(
    root: DrawingArea<DB, plotters::coord::Shift>,
    report: &Report,
    panel: &front::Panel,
    tips: &mut Vec<Tip>,
) -> Result<()>
where
    DB::ErrorType: 'static,
{
    let err = |e: DrawingAreaErrorKind<DB::ErrorType>| anyhow!("{e:?}");
    let points: Vec<(f64, f64)> = panel.rows.iter().map(|r| (r.total_ms, r.psnr)).collect();
    let finite = |v: f64| v.is_finite();
    let xmax = points
        .iter()
        .map(|p| p.0)
        .filter(|v| finite(*v))
        .fold(1e-3, f64::max)
        * 1.15;
    let ys: Vec<f64> = points.iter().map(|p| p.1).filter(|v| finite(*v)).collect();
    let ymin = ys.iter().copied().fold(f64::INFINITY, f64::min);
    let ymax = ys.iter().copied().fold(f64::NEG_INFINITY, f64::max);
    let (ymin, ymax) = if ymin.is_finite() && ymax.is_finite() {
        (ymin - 1.0, ymax + 1.5)
    } else {
        (0.0, 1.0)
    };
    let caption = format!(
        "{}, R {} m ({}x{})",
        panel.scene, panel.radius, report.width, report.height
    );
    let mut chart = ChartBuilder::on(&root)
        .caption(caption, ("sans-serif", 18))
        .margin(12)
        .x_label_area_size(44)
        .y_label_area_size(56)
        .build_cartesian_2d(0.0..xmax, ymin..ymax)
        .map_err(err)?;
    chart
        .configure_mesh()
        .x_desc(format!(
            "AO chain, median {} per frame ({})",
            report.clock.unit(),
            report.clock.name()
        ))
        .y_desc("PSNR dB vs ray-traced truth (test cameras)")
        .label_style(("sans-serif", 13))
        .draw()
        .map_err(err)?;
    let front = front::pareto_front(&points);
    chart
        .draw_series(LineSeries::new(
            front.iter().map(|&i| points[i]),
            BLACK.mix(0.6).stroke_width(2),
        ))
        .map_err(err)?;
    let mut placed: Vec<Rect> = Vec::new();
    for (i, row) in panel.rows.iter().enumerate() {
        if !(finite(points[i].0) && finite(points[i].1)) {
            continue;
        }
        let colour = front::method_colour(&row.method);
        let on_front = front.contains(&i);
        let size = if on_front { 6 } else { 4 };
        chart
            .draw_series(std::iter::once(Circle::new(
                points[i],
                size,
                colour.filled(),
            )))
            .map_err(err)?;
        let label = format!("{} {}", row.method, row.setting);
        let offset = on_front
            .then(|| free_spot(chart.backend_coord(&points[i]), &label, &mut placed))
            .flatten();
        if let Some(offset) = offset {
            chart
                .draw_series(std::iter::once(
                    EmptyElement::at(points[i])
                        + Text::new(
                            label,
                            offset,
                            ("sans-serif", 12).into_font().color(&colour.mix(0.95)),
                        ),
                ))
                .map_err(err)?;
        }
        tips.push(Tip {
            at: chart.backend_coord(&points[i]),
            text: format!(
                "{} {}: {:.2} {}, PSNR {:.2} dB{}",
                row.method,
                row.setting,
                row.total_ms,
                report.clock.unit(),
                row.psnr,
                if on_front { " (Pareto front)" } else { "" }
            ),
        });
    }
    Ok(())
}

/// A label's box in backend pixels: left, top, right, bottom.
type Rect = (i32, i32, i32, i32);

/// Where a label of `text` beside the point at `at` (backend pixels) overlaps no label placed
/// before: the offset from the point, first free of a few spots right, left, above and below;
/// `None` when all are taken (the point keeps its tooltip). Text is 12 px high, ~7 px a character.
fn free_spot(at: (i32, i32), text: &str, placed: &mut Vec<Rect>) -> Option<(i32, i32)> {
    let (w, h) = (7 * text.chars().count() as i32, 14);
    let candidates = [
        (8, -16),
        (8, 4),
        (-w - 8, -16),
        (-w - 8, 4),
        (8, -32),
        (8, 20),
        (-w / 2, -34),
        (-w / 2, 22),
    ];
    let overlaps = |a: &Rect, b: &Rect| a.0 < b.2 && b.0 < a.2 && a.1 < b.3 && b.1 < a.3;
    for (dx, dy) in candidates {
        let rect = (at.0 + dx, at.1 + dy, at.0 + dx + w, at.1 + dy + h);
        if !placed.iter().any(|p| overlaps(p, &rect)) {
            placed.push(rect);
            return Some((dx, dy));
        }
    }
    None
}

/// Each method's colour (the same on every chart) and the front's line.
fn legend<DB: DrawingBackend>(
    root: DrawingArea<DB, plotters::coord::Shift>,
    report: &Report,
) -> Result<()>
where
    DB::ErrorType: 'static,
{
    let err = |e: DrawingAreaErrorKind<DB::ErrorType>| anyhow!("{e:?}");
    let mut methods: Vec<&str> = Vec::new();
    for r in &report.rows {
        if !methods.contains(&r.method.as_str()) {
            methods.push(&r.method);
        }
    }
    let font = ("sans-serif", 15).into_font();
    let y = (LEGEND_HEIGHT / 2) as i32;
    let mut x = 20;
    root.draw(&PathElement::new(
        vec![(x, y), (x + 30, y)],
        BLACK.mix(0.6).stroke_width(2),
    ))
    .map_err(err)?;
    let front_label = "Pareto front (nothing cheaper scores higher)";
    root.draw(&Text::new(front_label, (x + 38, y - 8), font.clone()))
        .map_err(err)?;
    x += 48 + 8 * front_label.len() as i32;
    for m in methods {
        let colour = front::method_colour(m);
        root.draw(&Circle::new((x, y), 6, colour.filled()))
            .map_err(err)?;
        root.draw(&Text::new(m.to_string(), (x + 12, y - 8), font.clone()))
            .map_err(err)?;
        x += 30 + 9 * m.len() as i32;
    }
    Ok(())
}

/// Writes `report.svg` and `report.png` into `out` (a panel per scene and radius), and with
/// several scenes `report-SCENE.svg` / `.png` for each; returns the files written.
pub fn write_charts(report: &Report, out: &Path) -> Result<Vec<PathBuf>> {
    ensure_font()?;
    if report.rows.is_empty() {
        bail!("no rows to chart");
    }
    let mut written = write_chart_pair(report, out, "report")?;
    if report.scenes.len() > 1 {
        for scene in &report.scenes {
            let mut one = report.clone();
            one.rows.retain(|r| front::scene_of(r) == scene);
            one.scenes = vec![scene.clone()];
            if one.rows.is_empty() {
                continue;
            }
            let stem = format!("report-{scene}");
            written.extend(write_chart_pair(&one, out, &stem)?);
        }
    }
    Ok(written)
}

/// The picture's size for `report`'s panels.
fn size_of(report: &Report) -> (u32, u32) {
    let n = front::panels(&report.scenes, &report.rows).len().max(1);
    let columns = n.min(MAX_COLUMNS) as u32;
    let rows = n.div_ceil(MAX_COLUMNS) as u32;
    (PANEL.0 * columns.max(2), PANEL.1 * rows + LEGEND_HEIGHT)
}

/// `text` escaped for SVG text.
fn xml_escape(text: &str) -> String {
    text.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('"', "&quot;")
}

fn write_chart_pair(report: &Report, out: &Path, stem: &str) -> Result<Vec<PathBuf>> {
    let (w, h) = size_of(report);
    let svg = out.join(format!("{stem}.svg"));
    let mut text = String::new();
    let mut tips = Vec::new();
    draw(
        SVGBackend::with_string(&mut text, (w, h)).into_drawing_area(),
        report,
        &mut tips,
    )
    .with_context(|| format!("cannot draw {}", svg.display()))?;
    // Tooltips: an invisible disc over each point, titled with its method, setting and figures.
    let mut overlay = String::new();
    for t in &tips {
        overlay.push_str(&format!(
            "<circle cx=\"{}\" cy=\"{}\" r=\"7\" fill=\"white\" fill-opacity=\"0\"><title>{}</title></circle>\n",
            t.at.0,
            t.at.1,
            xml_escape(&t.text)
        ));
    }
    let end = text
        .rfind("</svg>")
        .ok_or_else(|| anyhow!("the SVG backend wrote no closing tag"))?;
    text.insert_str(end, &overlay);
    crate::io::write_file(&svg, text.as_bytes())?;
    let png = out.join(format!("{stem}.png"));
    let mut buf = vec![0u8; (w * h * 3) as usize];
    {
        let root = BitMapBackend::with_buffer(&mut buf, (w, h)).into_drawing_area();
        draw(root, report, &mut Vec::new())?;
    }
    image::RgbImage::from_raw(w, h, buf)
        .ok_or_else(|| anyhow!("chart buffer size"))?
        .save(&png)
        .with_context(|| format!("cannot write {}", png.display()))?;
    Ok(vec![svg, png])
}

#[cfg(test)]
mod tests {
    use super::{free_spot, Rect};

    #[test]
    fn labels_of_points_at_one_place_never_overlap() {
        let mut placed: Vec<Rect> = Vec::new();
        let mut n = 0;
        while free_spot((200, 200), "hemisphere n8 r1", &mut placed).is_some() {
            n += 1;
            assert!(n < 100);
        }
        assert!(n >= 6, "{n} labels placed");
        for (i, a) in placed.iter().enumerate() {
            for b in &placed[..i] {
                let overlap = a.0 < b.2 && b.0 < a.2 && a.1 < b.3 && b.1 < a.3;
                assert!(!overlap, "{a:?} overlaps {b:?}");
            }
        }
        // A point elsewhere still gets its label.
        assert!(free_spot((600, 200), "gtao n8 r1", &mut placed).is_some());
    }
}
