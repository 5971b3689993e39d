//! The bench's `report.html`: well-formed (parsed as XML), every picture it names is in
//! `pictures/` and is a PNG, every test camera of every row is pictured, the chart is drawn in the
//! page, and every link of the summary leads to a setting on the page.

use quick_xml::events::Event;
use std::collections::BTreeSet;
use std::path::Path;

fn attr(tag: &quick_xml::events::BytesStart, name: &str) -> Option<String> {
    tag.try_get_attribute(name).unwrap().map(|a| {
        a.normalized_value(quick_xml::XmlVersion::Explicit1_0)
            .unwrap()
            .into_owned()
    })
}

/// Checks `dir/report.html` of a run with `rows` rows, each with its AO view and error map (and
/// its ceiling's, when the run split the error) at each of its test cameras.
pub fn check(dir: &Path, rows: usize) {
    let text = std::fs::read_to_string(dir.join("report.html")).expect("report.html");
    // Every row's test cameras, as report.json lists them, each pictured once.
    let json: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("report.json")).unwrap()).unwrap();
    let mut pictured = 0;
    for row in json["rows"].as_array().unwrap() {
        let test: BTreeSet<&str> = row["cameras"]
            .as_array()
            .unwrap()
            .iter()
            .filter(|c| c["train"] == false)
            .map(|c| c["camera"].as_str().unwrap())
            .collect();
        let shown: BTreeSet<&str> = row["pictures"]
            .as_array()
            .unwrap()
            .iter()
            .map(|p| p["camera"].as_str().unwrap())
            .collect();
        assert!(test.len() >= 2 && shown == test, "{shown:?} vs {test:?}");
        pictured += test.len();
    }
    let mut reader = quick_xml::Reader::from_str(&text);
    let (mut images, mut links, mut ids) = (Vec::new(), BTreeSet::new(), BTreeSet::new());
    let mut open = Vec::new();
    loop {
        let (tag, start) = match reader.read_event() {
            Ok(Event::Eof) => break,
            Ok(Event::Start(e)) => (e.into_owned(), true),
            Ok(Event::Empty(e)) => (e.into_owned(), false),
            Ok(Event::End(e)) => {
                let closed = open.pop().expect("an end tag closes an open one");
                assert_eq!(e.name().as_ref(), closed, "{text}");
                continue;
            }
            Ok(_) => continue,
            Err(e) => panic!("report.html is not well-formed ({e}):\n{text}"),
        };
        if start {
            open.push(tag.name().as_ref().to_vec());
        }
        match tag.name().as_ref() {
            b"img" => images.push(attr(&tag, "src").expect("an img has a src")),
            b"a" => {
                links.insert(attr(&tag, "href").expect("a link has an href"));
            }
            _ => {}
        }
        if let Some(id) = attr(&tag, "id") {
            ids.insert(format!("#{id}"));
        }
    }
    assert!(open.is_empty(), "unclosed elements in report.html");
    // Each row's AO view and error map, and at least one truth.
    assert!(images.len() > 2 * pictured, "{images:?}");
    for src in &images {
        assert!(src.starts_with("pictures/"), "{src}");
        let img = image::open(dir.join(src)).unwrap_or_else(|e| panic!("{src}: {e}"));
        assert!(img.width() > 0 && img.height() > 0);
    }
    let (ceilings, errors): (Vec<&String>, Vec<&String>) = images
        .iter()
        .filter(|s| s.ends_with("-error.png"))
        .partition(|s| s.contains("-ceiling-"));
    assert_eq!(errors.len(), pictured, "{images:?}");
    // With the error split, each picture of a row has its ceiling's error map beside it.
    assert!(
        ceilings.is_empty() || ceilings.len() == pictured,
        "{images:?}"
    );
    assert_eq!(links.len(), rows, "{links:?}");
    for link in &links {
        assert!(ids.contains(link), "{link} leads nowhere: {ids:?}");
    }
    assert!(text.contains("PSNR") && text.contains(" ms"));
    if dir.join("report.svg").is_file() {
        check_chart(dir);
        // The chart is drawn in the page itself: its tooltips are there.
        assert!(text.contains("<svg") && text.contains("(Pareto front)"));
    }
}

/// Checks `dir/report.svg` against `dir/report.json`: it parses as XML, has one panel per
/// (scene, radius) of the rows, names the clock on the cost axis, and a tooltip per row.
pub fn check_chart(dir: &Path) {
    let json: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("report.json")).unwrap()).unwrap();
    let svg = std::fs::read_to_string(dir.join("report.svg")).expect("report.svg");
    let mut reader = quick_xml::Reader::from_str(&svg);
    let (mut texts, mut titles, mut depth) = (Vec::new(), Vec::new(), 0i32);
    let mut current: Option<&'static str> = None;
    loop {
        match reader.read_event() {
            Ok(Event::Eof) => break,
            Ok(Event::Start(e)) => {
                depth += 1;
                current = match e.name().as_ref() {
                    b"text" => Some("text"),
                    b"title" => Some("title"),
                    _ => current,
                };
            }
            Ok(Event::End(_)) => {
                depth -= 1;
                current = None;
            }
            Ok(Event::Text(t)) => {
                let t = String::from_utf8_lossy(t.as_ref()).trim().to_string();
                match current {
                    Some("text") => texts.push(t),
                    Some("title") => titles.push(t),
                    _ => {}
                }
            }
            Ok(_) => {}
            Err(e) => panic!("report.svg is not well-formed ({e})"),
        }
    }
    assert_eq!(depth, 0, "unclosed elements in report.svg");
    let rows = json["rows"].as_array().unwrap();
    let (w, h) = (&json["width"], &json["height"]);
    let mut panels: BTreeSet<String> = BTreeSet::new();
    for row in rows {
        let scene = row["cameras"][0]["scene"].as_str().unwrap();
        let radius = row["radius"].as_f64().unwrap() as f32;
        panels.insert(format!("{scene}, R {radius} m ({w}x{h})"));
    }
    for p in &panels {
        let n = texts.iter().filter(|t| *t == p).count();
        assert_eq!(n, 1, "panel {p:?} appears {n} times: {texts:?}");
    }
    let captions = texts.iter().filter(|t| t.contains(", R ")).count();
    assert_eq!(
        captions,
        panels.len(),
        "one panel per scene and radius: {texts:?}"
    );
    let clock = json["clock"].as_str().unwrap();
    assert!(
        texts
            .iter()
            .any(|t| t.contains("AO chain") && t.contains(clock)),
        "the cost axis names the clock {clock}: {texts:?}"
    );
    assert_eq!(titles.len(), rows.len(), "one tooltip per row: {titles:?}");
    for row in rows {
        let name = format!(
            "{} {}:",
            row["method"].as_str().unwrap(),
            row["setting"].as_str().unwrap()
        );
        assert!(
            titles.iter().any(|t| t.starts_with(&name)),
            "{name} {titles:?}"
        );
    }
    // Every panel has a front, named in its points' tooltips.
    assert!(
        titles
            .iter()
            .filter(|t| t.contains("(Pareto front)"))
            .count()
            >= panels.len()
    );
}

/// A plain `opengl3d bench` with only a few flags: the options not given take the quick run's
/// values and the reports list them; the references go to the cache folder the environment
/// names, and the chart has a panel for each radius.
#[test]
fn quick_run_lists_what_it_scaled_and_caches_where_told() {
    let dir = crate::common::temp_dir("bench-quick-cli");
    let cache = dir.join("cache");
    let out = dir.join("out");
    let o = crate::common::bin()
        .env(opengl3d::tools::reference::CACHE_ENV, &cache)
        .args([
            "bench",
            "--width",
            "48",
            "--height",
            "28",
            "--methods",
            "sao,gtao",
        ])
        .args([
            "--samples",
            "4,8",
            "--radii",
            "0.5,1",
            "--ref-rays",
            "8",
            "--frames",
            "1",
        ])
        .arg("--out")
        .arg(&out)
        .output()
        .expect("run opengl3d");
    let stderr = String::from_utf8_lossy(&o.stderr);
    assert!(o.status.success(), "{stderr}");
    // The plan and the quick run's notes come before the work.
    assert!(
        stderr.contains("8 settings") && stderr.contains("opengl3d bench --full"),
        "{stderr}"
    );
    let cached = std::fs::read_dir(&cache).expect("the cache folder").count();
    // 4 cameras × 2 radii, at 1/4 of the output (the quick run's scale).
    assert_eq!(cached, 8, "{stderr}");
    let md = std::fs::read_to_string(out.join("report.md")).unwrap();
    let html = std::fs::read_to_string(out.join("report.html")).unwrap();
    for needle in [
        "references 12×7",
        "error split skipped",
        "opengl3d bench --full",
        "1 warm-up",
    ] {
        assert!(md.contains(needle), "report.md lacks {needle}:\n{md}");
        assert!(html.contains(needle), "report.html lacks {needle}");
    }
    // Flags given are not listed as scaled: the settings were chosen.
    assert!(!md.contains("5 per method"), "{md}");
    assert!(!md.contains("## Error split"), "{md}");
    check(&out, 8);
}
