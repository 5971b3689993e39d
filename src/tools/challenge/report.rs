//! The challenge's results: `results.json`, `report.md` and `report.html` (the ranking, then per
//! entry and scene its AO and error map beside the truth at the first test camera).

use super::protocol::ChallengeConfig;
use super::standings::Standing;
use crate::tools::bench::perf::references::SceneData;
use anyhow::Result;
use rust_i18n::t;
use std::fmt::Write as _;
use std::path::Path;

/// The truth's picture at each scene's first test camera (`truth-SCENE.png`).
pub fn write_truth_pictures(out: &Path, sd: &SceneData) -> Result<()> {
    let Some(ci) = (0..sd.cameras.len()).find(|&ci| !sd.cameras[ci].train) else {
        return Ok(());
    };
    let radius = sd.desc.ao.radius;
    let truth = &sd.refs[&(ci, radius.to_bits())];
    let path = out.join(format!("truth-{}.png", sd.name));
    crate::io::gray_to_png(&path, truth.width, truth.height, &truth.ao, 1.0)
}

use crate::tools::grade::feedback::html as html_escape;

fn figure(f: Option<f64>, digits: usize) -> String {
    f.map_or("–".to_string(), |v| format!("{v:.digits$}"))
}

/// One line per entry: place, name, file, PSNR, cost, reason.
fn rows(standings: &[Standing]) -> Vec<[String; 6]> {
    standings
        .iter()
        .map(|s| {
            [
                s.rank.map_or("–".to_string(), |r| r.to_string()),
                s.name.clone(),
                s.file.display().to_string(),
                figure(s.psnr, 2),
                figure(s.cost_ratio, 2),
                s.reason.clone().unwrap_or_default(),
            ]
        })
        .collect()
}

fn headings() -> [String; 6] {
    ["rank", "name", "file", "psnr", "cost", "reason"].map(|k| {
        let key = format!("challenge.column_{k}");
        t!(&key).into_owned()
    })
}

pub fn write(cfg: &ChallengeConfig, standings: &[Standing]) -> Result<()> {
    let json = serde_json::json!({
        "protocol": cfg.protocol,
        "budget": cfg.budget,
        "entries": standings,
    });
    crate::io::write_file(
        &cfg.out.join("results.json"),
        serde_json::to_string_pretty(&json)?.as_bytes(),
    )?;

    let intro = t!(
        "challenge.intro",
        budget = format!("{:.2}", cfg.budget),
        width = cfg.protocol.width,
        height = cfg.protocol.height,
        rays = cfg.protocol.ref_rays
    );
    let mut md = format!("# {}\n\n{intro}\n\n", t!("challenge.title"));
    let head = headings();
    let _ = writeln!(md, "| {} |", head.join(" | "));
    let _ = writeln!(md, "|{}", "---|".repeat(head.len()));
    for r in rows(standings) {
        let cells: Vec<String> = r.iter().map(|c| c.replace('|', "\\|")).collect();
        let _ = writeln!(md, "| {} |", cells.join(" | "));
    }
    crate::io::write_file(&cfg.out.join("report.md"), md.as_bytes())?;

    let mut html = format!(
        "<!doctype html>\n<html lang=\"{}\"><head><meta charset=\"utf-8\"><title>{}</title>\
         <style>body{{font-family:sans-serif}}table{{border-collapse:collapse}}td,th{{border:1px solid #ccc;padding:2px 6px}}\
         img{{image-rendering:pixelated;width:320px;vertical-align:top}}</style></head><body>\n<h1>{}</h1>\n<p>{}</p>\n<table>\n<tr>",
        crate::i18n::current().code(),
        html_escape(&t!("challenge.title")),
        html_escape(&t!("challenge.title")),
        html_escape(&intro)
    );
    for h in &head {
        let _ = write!(html, "<th>{}</th>", html_escape(h));
    }
    html.push_str("</tr>\n");
    for r in rows(standings) {
        html.push_str("<tr>");
        for c in &r {
            let _ = write!(html, "<td>{}</td>", html_escape(c));
        }
        html.push_str("</tr>\n");
    }
    html.push_str("</table>\n");
    for s in standings {
        let Some(score) = &s.score else { continue };
        let _ = writeln!(html, "<h2>{}</h2>", html_escape(&s.name));
        for sc in &score.scenes {
            let entry = &s.pictures;
            let caption = t!(
                "challenge.pictures",
                scene = sc.scene,
                psnr = format!("{:.2}", sc.psnr),
                cost = format!("{:.2}", sc.cost_ratio)
            );
            let _ = writeln!(
                html,
                "<p>{}</p><p><img src=\"truth-{scene}.png\" alt=\"{truth}\"> <img src=\"{entry}/{ao}\" alt=\"{ao_alt}\"> \
                 <img src=\"{entry}/{err}\" alt=\"{err_alt}\"></p>",
                html_escape(&caption),
                scene = html_escape(&sc.scene),
                truth = html_escape(&t!("challenge.alt_truth")),
                ao = html_escape(&sc.ao_picture),
                ao_alt = html_escape(&t!("challenge.alt_ao")),
                err = html_escape(&sc.error_picture),
                err_alt = html_escape(&t!("challenge.alt_error")),
            );
        }
    }
    html.push_str("</body></html>\n");
    crate::io::write_file(&cfg.out.join("report.html"), html.as_bytes())
}
