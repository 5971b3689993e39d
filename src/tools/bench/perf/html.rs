//! `report.html`: the bench's pictures on one page, readable offline (no script, no outside
//! style, the pictures in `pictures/` next to it): a summary table linking to each setting, the
//! cost-against-error chart drawn in the page, then per scene the truth at each radius and each
//! setting's AO view and signed error map at every test camera, with the PSNR and the cost in each
//! caption. Every text is escaped; the page is well-formed XML.

use super::report::{Report, Row};
use crate::tools::error_map::DEFAULT_RANGE;
use std::fmt::Write as _;

/// `text` escaped for HTML text and quoted attribute values.
fn esc(text: &str) -> String {
    let mut out = String::with_capacity(text.len());
    for c in text.chars() {
        match c {
            '&' => out.push_str("&amp;"),
            '<' => out.push_str("&lt;"),
            '>' => out.push_str("&gt;"),
            '"' => out.push_str("&quot;"),
            '\'' => out.push_str("&#39;"),
            _ => out.push(c),
        }
    }
    out
}

const STYLE: &str = "body{font-family:sans-serif;margin:1.5em;color:#222}\
table{border-collapse:collapse}td,th{border:1px solid #bbb;padding:2px 8px;text-align:right}\
td:first-child,td:nth-child(2),td:nth-child(3){text-align:left}\
.pics{display:flex;flex-wrap:wrap;gap:12px;margin-bottom:8px}figure{margin:0}\
.chart svg{max-width:100%;height:auto}\
img{width:320px;image-rendering:pixelated;border:1px solid #888}\
figcaption{font-size:90%;max-width:320px}";

fn scene_of(row: &Row) -> &str {
    row.cameras.first().map_or("", |c| c.scene.as_str())
}

fn figure(out: &mut String, src: &str, alt: &str, caption: &str) {
    let _ = write!(
        out,
        "<figure><img src=\"{}\" alt=\"{}\"/><figcaption>{}</figcaption></figure>",
        esc(src),
        esc(alt),
        esc(caption)
    );
}

/// `svg` (a chart the bench drew) as an element of the page: from its `<svg` tag on, without
/// any XML prolog, scaled to the page's width.
fn inline_svg(svg: &str) -> Option<&str> {
    let start = svg.find("<svg")?;
    let end = svg.rfind("</svg>")? + "</svg>".len();
    (start < end).then(|| &svg[start..end])
}

/// The page (links and pictures relative to the report's folder); `chart`: the text of
/// `report.svg` when the run drew it, shown in the page.
pub fn html(report: &Report, chart: Option<&str>) -> String {
    let mut out = String::new();
    out.push_str("<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\"/>");
    let _ = writeln!(
        out,
        "<title>AO bench pictures</title><style>{STYLE}</style></head><body>"
    );
    out.push_str("<h1>AO bench: where each method is wrong</h1>\n");
    let r = &report.reference;
    let _ = writeln!(
        out,
        "<p>{}</p>",
        esc(&format!(
            "Renderer {}; methods at {}x{}, box-averaged to the truth's {}x{} (ray-traced, {} rays per pixel, \
             over the pixel's whole footprint). \
             The pictures show every test camera. Error maps: engine minus truth, blue too dark, \
             orange too light, full colour at ±{DEFAULT_RANGE}, white 0, sky grey. AO ms: median \
             of the AO chain at {}x{} by the {} ({}); PSNR: the mean over the test cameras, and in \
             the captions at the camera shown.",
            report.renderer, report.width, report.height, r.width, r.height, r.rays, report.width,
            report.height, report.clock.name(), report.timing
        ))
    );
    if !report.scaled.is_empty() {
        let _ = writeln!(
            out,
            "<h2>A quick run</h2>\n<p>Scaled down or skipped against the full protocol (<code>{}</code>):</p>\n<ul>",
            esc(super::protocol::FULL_COMMAND)
        );
        for line in &report.scaled {
            let _ = writeln!(out, "<li>{}</li>", esc(line));
        }
        out.push_str("</ul>\n");
    }
    out.push_str("<h2>Summary</h2>\n<table><tr><th>scene</th><th>method</th><th>setting</th>");
    let _ = writeln!(
        out,
        "<th>R (m)</th><th>AO {}</th><th>PSNR (dB)</th><th>pictures</th></tr>",
        report.clock.unit()
    );
    for (i, row) in report.rows.iter().enumerate() {
        let cameras: Vec<&str> = row.pictures.iter().map(|p| p.camera.as_str()).collect();
        let link = if cameras.is_empty() {
            "-".into()
        } else {
            format!("<a href=\"#row-{i}\">{}</a>", esc(&cameras.join(", ")))
        };
        let _ = writeln!(
            out,
            "<tr><td>{}</td><td>{}</td><td>{}</td><td>{}</td><td>{:.2}</td><td>{:.2}</td><td>{link}</td></tr>",
            esc(scene_of(row)),
            esc(&row.method),
            esc(&row.setting),
            row.radius,
            row.total_ms,
            row.psnr
        );
    }
    out.push_str("</table>\n");
    if let Some(svg) = chart.and_then(inline_svg) {
        out.push_str("<h2 id=\"chart\">AO cost against PSNR</h2>\n<div class=\"chart\">");
        out.push_str(svg);
        out.push_str("</div>\n");
    }
    for (si, scene) in report.scenes.iter().enumerate() {
        let _ = writeln!(out, "<h2 id=\"scene-{si}\">{}</h2>", esc(scene));
        let rows: Vec<(usize, &Row)> = report
            .rows
            .iter()
            .enumerate()
            .filter(|(_, r)| scene_of(r) == scene)
            .collect();
        // The truths, one per camera and radius.
        out.push_str("<div class=\"pics\">");
        let mut shown: Vec<&str> = Vec::new();
        for (_, row) in &rows {
            for p in &row.pictures {
                if shown.contains(&p.truth.as_str()) {
                    continue;
                }
                shown.push(&p.truth);
                let caption = format!("truth: camera {}, R {} m", p.camera, row.radius);
                figure(&mut out, &p.truth, &caption, &caption);
            }
        }
        out.push_str("</div>\n");
        for (i, row) in rows {
            if row.pictures.is_empty() {
                continue;
            }
            let title = format!("{} {}", row.method, row.setting);
            let _ = writeln!(out, "<h3 id=\"row-{i}\">{}</h3>", esc(&title));
            let cost = format!("AO {:.2} {}", row.total_ms, report.clock.unit());
            for p in &row.pictures {
                out.push_str("<div class=\"pics\">");
                figure(
                    &mut out,
                    &p.ao,
                    &format!("{title}: AO at {}", p.camera),
                    &format!("{title}: AO view at camera {} ({cost})", p.camera),
                );
                figure(
                    &mut out,
                    &p.error,
                    &format!("{title}: error at {}", p.camera),
                    &format!(
                        "{title}: error at camera {}, PSNR {:.2} dB, {cost}",
                        p.camera, p.psnr
                    ),
                );
                if let (Some(map), Some(psnr)) = (&p.ceiling_error, p.ceiling_psnr) {
                    // What the depth buffer alone allows, on the same scale: the row's error minus
                    // this is what its sampling loses.
                    figure(
                        &mut out,
                        map,
                        &format!("{title}: its ceiling's error at {}", p.camera),
                        &format!(
                            "ceiling ({}) at camera {}: error, PSNR {psnr:.2} dB",
                            row.ceiling_label, p.camera
                        ),
                    );
                }
                out.push_str("</div>\n");
            }
        }
    }
    out.push_str("</body></html>\n");
    out
}

#[cfg(test)]
mod tests {
    use super::{esc, inline_svg};

    #[test]
    fn markup_characters_are_escaped() {
        assert_eq!(
            esc("<a href=\"x\">&'</a>"),
            "&lt;a href=&quot;x&quot;&gt;&amp;&#39;&lt;/a&gt;"
        );
    }

    #[test]
    fn a_chart_is_inlined_from_its_svg_tag() {
        let svg = "<?xml version=\"1.0\"?>\n<svg width=\"2\"><rect/></svg>\n";
        assert_eq!(inline_svg(svg), Some("<svg width=\"2\"><rect/></svg>"));
        assert_eq!(inline_svg("not a chart"), None);
    }
}
