//! The bench's `report.html`: well-formed (parsed as XML), every picture it names is in
//! `pictures/` and is a PNG, and every link of the summary leads to a setting on the page.

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

/// Checks `dir/report.html` of a run with `rows` rows, each with its AO view and error map.
pub fn check(dir: &Path, rows: usize) {
    let text = std::fs::read_to_string(dir.join("report.html")).expect("report.html");
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
    assert!(images.len() > 2 * rows, "{images:?}");
    for src in &images {
        assert!(src.starts_with("pictures/"), "{src}");
        let img = image::open(dir.join(src)).unwrap_or_else(|e| panic!("{src}: {e}"));
        assert!(img.width() > 0 && img.height() > 0);
    }
    let errors = images.iter().filter(|s| s.ends_with("-error.png")).count();
    assert_eq!(errors, rows, "{images:?}");
    assert_eq!(links.len(), rows, "{links:?}");
    for link in &links {
        assert!(ids.contains(link), "{link} leads nowhere: {ids:?}");
    }
    assert!(text.contains("PSNR") && text.contains(" ms"));
}
