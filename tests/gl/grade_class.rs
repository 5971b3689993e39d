//! `opengl3d grade --class DIR` run as a teacher would run it, on a class built from
//! tests/mutants/: one student with correct shaders, one with a broken SAO step (and a name that
//! needs quoting and escaping), one empty folder, one whose SAO shader never ends.

use quick_xml::events::Event;
use std::path::{Path, PathBuf};
use std::process::{Command, Output};

pub(crate) fn mutant(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/mutants")
        .join(name)
}

pub(crate) fn temp_dir(name: &str) -> PathBuf {
    let d = Path::new(env!("CARGO_TARGET_TMPDIR")).join(format!("{name}-{}", std::process::id()));
    match std::fs::remove_dir_all(&d) {
        Err(e) if e.kind() != std::io::ErrorKind::NotFound => panic!("{}: {e}", d.display()),
        _ => {}
    }
    std::fs::create_dir_all(&d).unwrap();
    d
}

/// A student folder `class/name` holding the shaders of the mutant folders `from`.
fn student(class: &Path, name: &str, from: &[&str]) {
    let dir = class.join(name);
    std::fs::create_dir_all(&dir).unwrap();
    for m in from {
        for f in std::fs::read_dir(mutant(m)).unwrap() {
            let f = f.unwrap();
            std::fs::copy(f.path(), dir.join(f.file_name())).unwrap();
        }
    }
}

pub(crate) const CORRECT: [&str; 5] = [
    "lesson-restore",
    "listing-down-sampling",
    "listing-simple",
    "lesson-sao",
    "listing-blur",
];
const BROKEN_SAO: [&str; 5] = [
    "lesson-restore",
    "listing-down-sampling",
    "listing-simple",
    "sao-flipped-normal",
    "listing-blur",
];
const ODD_NAME: &str = "bob, \"<b>\" & 'co'";

pub(crate) fn grade_class(class: &Path, args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_opengl3d"))
        .arg("grade")
        .arg("--class")
        .arg(class)
        .args(args)
        .output()
        .expect("run opengl3d")
}

/// The records of a CSV text (RFC 4180: quoted fields, doubled quotes, CRLF).
pub(crate) fn parse_csv(text: &str) -> Vec<Vec<String>> {
    let mut rows = Vec::new();
    let (mut row, mut field) = (Vec::new(), String::new());
    let (mut quoted, mut chars) = (false, text.chars().peekable());
    while let Some(c) = chars.next() {
        match (quoted, c) {
            (true, '"') if chars.peek() == Some(&'"') => {
                chars.next();
                field.push('"');
            }
            (true, '"') => quoted = false,
            (true, c) => field.push(c),
            (false, '"') => quoted = true,
            (false, ',') => row.push(std::mem::take(&mut field)),
            (false, '\r') => {}
            (false, '\n') => {
                row.push(std::mem::take(&mut field));
                rows.push(std::mem::take(&mut row));
            }
            (false, c) => field.push(c),
        }
    }
    assert!(!quoted && field.is_empty() && row.is_empty(), "{text}");
    rows
}

/// How many elements of each name the XML holds, and the `name` attributes of the test suites;
/// panics when it is not well-formed XML.
fn parse_junit(text: &str) -> (std::collections::BTreeMap<String, usize>, Vec<String>) {
    let mut reader = quick_xml::Reader::from_str(text);
    let mut counts = std::collections::BTreeMap::new();
    let mut suites = Vec::new();
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
            Err(e) => panic!("junit.xml is not XML ({e}):\n{text}"),
        };
        let name = String::from_utf8(tag.name().as_ref().to_vec()).unwrap();
        if name == "testsuite" {
            let attr = tag
                .try_get_attribute("name")
                .unwrap()
                .expect("a testsuite has a name");
            suites.push(
                attr.normalized_value(quick_xml::XmlVersion::Explicit1_0)
                    .unwrap()
                    .into_owned(),
            );
        }
        if start {
            open.push(tag.name().as_ref().to_vec());
        }
        *counts.entry(name).or_insert(0) += 1;
    }
    assert!(open.is_empty(), "unclosed elements in {text}");
    (counts, suites)
}

#[test]
fn a_class_is_graded_into_csv_html_and_junit() {
    let class = temp_dir("grade-class");
    student(&class, "ada", &CORRECT);
    student(&class, ODD_NAME, &BROKEN_SAO);
    student(&class, "cleo", &[]);
    student(&class, "dan", &["sao-endless-loop"]);
    // A file beside the folders is no student.
    std::fs::write(class.join("notes.txt"), "not a student").unwrap();
    let report = temp_dir("grade-class-report");
    let o = grade_class(
        &class,
        &[
            "--out",
            report.to_str().unwrap(),
            "--jobs",
            "2",
            "--timeout",
            "6",
        ],
    );
    let (stdout, stderr) = (
        String::from_utf8_lossy(&o.stdout),
        String::from_utf8_lossy(&o.stderr),
    );
    assert_eq!(o.status.code(), Some(1), "{stdout}\n{stderr}");
    assert!(stderr.contains("notes.txt"), "{stderr}");

    let csv = std::fs::read_to_string(report.join("results.csv")).unwrap();
    let rows = parse_csv(&csv);
    let expected: Vec<Vec<&str>> = vec![
        vec![
            "student",
            "restore",
            "down-sampling",
            "simple",
            "sao",
            "blur",
            "passed",
            "level",
        ],
        vec!["ada", "PASS", "PASS", "PASS", "PASS", "PASS", "5", "lesson"],
        vec![
            ODD_NAME, "PASS", "PASS", "PASS", "FAIL", "PASS", "4", "lesson",
        ],
        vec![
            "cleo",
            "not submitted",
            "not submitted",
            "not submitted",
            "not submitted",
            "not submitted",
            "0",
            "lesson",
        ],
        vec![
            "dan",
            "not submitted",
            "not submitted",
            "not submitted",
            "FAIL",
            "not submitted",
            "0",
            "lesson",
        ],
    ];
    assert_eq!(rows, expected, "{csv}\n{stdout}");

    let junit = std::fs::read_to_string(report.join("junit.xml")).unwrap();
    let (counts, suites) = parse_junit(&junit);
    assert_eq!(counts.get("testsuites"), Some(&1), "{junit}");
    assert_eq!(counts.get("testsuite"), Some(&4), "{junit}");
    assert_eq!(counts.get("testcase"), Some(&20), "{junit}");
    // bob's SAO, cleo's five, dan's five (four not submitted, SAO timed out).
    assert_eq!(counts.get("failure"), Some(&11), "{junit}");
    assert_eq!(suites, ["ada", ODD_NAME, "cleo", "dan"], "{junit}");
    assert!(junit.contains("timed out after 6 s"), "{junit}");

    let html = std::fs::read_to_string(report.join("report.html")).unwrap();
    for name in ["ada", "cleo", "dan"] {
        assert!(html.contains(&format!("\">{name}</a></th>")), "{html}");
    }
    assert!(
        html.contains("\">bob, &quot;&lt;b&gt;&quot; &amp; &#39;co&#39;</a></th>"),
        "{html}"
    );
    assert!(!html.contains("\"<b>\""), "{html}");
    assert!(
        html.contains("<b>not submitted</b><div class=\"why\">no sao.frag in"),
        "{html}"
    );
    assert!(html.contains("timed out after 6 s"), "{html}");

    // Only bob's failing SAO step has a heat map (dan's was killed before it drew one): a
    // thumbnail linked to a picture in the report folder, at least 256 px wide.
    let images = attribute_values(&html, "img src=\"");
    assert_eq!(images.len(), 1, "{html}");
    assert!(
        images[0].starts_with("pictures/002-bob") && images[0].ends_with("/sao-difference.png"),
        "{html}"
    );
    assert!(
        html.contains(&format!("<a class=\"heat\" href=\"{}\">", images[0])),
        "{html}"
    );
    let picture = image::open(report.join(&images[0])).unwrap();
    assert!(picture.width() >= 256, "{}", picture.width());
    for link in attribute_values(&html, "href=\"") {
        assert!(report.join(&link).is_file(), "{link} is not in the report");
    }
    // Passing steps leave no pictures behind.
    let folders: Vec<String> = std::fs::read_dir(report.join("pictures"))
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    assert_eq!(folders.len(), 1, "{folders:?}");
    // Nothing from outside the report folder: no scripts, no remote address.
    assert!(
        !html.contains("<script") && !html.contains("http"),
        "{html}"
    );
}

/// Every value of the attribute that `start` opens (`src="`), as written (no entities in them).
fn attribute_values(html: &str, start: &str) -> Vec<String> {
    html.split(start)
        .skip(1)
        .map(|rest| rest[..rest.find('"').unwrap()].to_string())
        .collect()
}

#[test]
fn a_class_that_passes_exits_0() {
    let class = temp_dir("grade-class-pass");
    student(&class, "ada", &CORRECT);
    // A name a spreadsheet would run as a formula.
    student(&class, "=1+1", &CORRECT);
    let report = temp_dir("grade-class-pass-report");
    let o = grade_class(&class, &["--out", report.to_str().unwrap()]);
    let stdout = String::from_utf8_lossy(&o.stdout);
    assert_eq!(o.status.code(), Some(0), "{stdout}");
    let csv = std::fs::read_to_string(report.join("results.csv")).unwrap();
    let names: Vec<String> = parse_csv(&csv).into_iter().map(|r| r[0].clone()).collect();
    assert_eq!(names, ["student", "'=1+1", "ada"], "{csv}");
    let (counts, _) = parse_junit(&std::fs::read_to_string(report.join("junit.xml")).unwrap());
    assert_eq!(counts.get("testcase"), Some(&10));
    assert_eq!(counts.get("failure"), None);
}

#[test]
fn a_missing_or_empty_class_is_an_error_naming_it() {
    let missing = Path::new(env!("CARGO_TARGET_TMPDIR")).join("no-such-class");
    let o = grade_class(&missing, &[]);
    let stderr = String::from_utf8_lossy(&o.stderr);
    assert_ne!(o.status.code(), Some(0));
    assert!(stderr.contains("no-such-class"), "{stderr}");

    let empty = temp_dir("grade-class-empty");
    std::fs::write(empty.join("notes.txt"), "not a student").unwrap();
    let o = grade_class(&empty, &[]);
    let stderr = String::from_utf8_lossy(&o.stderr);
    assert_ne!(o.status.code(), Some(0));
    assert!(
        stderr.contains(&*empty.to_string_lossy()) && stderr.contains("no student folder or .zip"),
        "{stderr}"
    );
}

#[test]
fn an_interrupted_grader_leaves_no_private_folder_behind() {
    let class = temp_dir("grade-class-interrupted");
    student(&class, "dan", &["sao-endless-loop"]);
    student(&class, "ada", &CORRECT);
    // The grader's private folders go under TMPDIR: a folder of this test's own, watched until the
    // steps are at work in one, then the grader is told to stop.
    let tmp = temp_dir("grade-class-interrupted-tmp");
    let report = temp_dir("grade-class-interrupted-report");
    let mut child = Command::new(env!("CARGO_BIN_EXE_opengl3d"))
        .args(["grade", "--class"])
        .arg(&class)
        .args(["--timeout", "60", "--out", report.to_str().unwrap()])
        .env("TMPDIR", &tmp)
        .stdout(std::process::Stdio::null())
        .stderr(std::process::Stdio::null())
        .spawn()
        .expect("run opengl3d");
    let ours = |tmp: &Path| -> Vec<PathBuf> {
        std::fs::read_dir(tmp)
            .unwrap()
            .map(|e| e.unwrap().path())
            .filter(|p| {
                p.file_name()
                    .unwrap()
                    .to_string_lossy()
                    .starts_with("opengl3d-")
            })
            .collect()
    };
    // Mid-grading: a private folder holding the steps' copies, the steps running.
    let busy = |tmp: &Path| {
        ours(tmp)
            .iter()
            .any(|d| std::fs::read_dir(d).is_ok_and(|mut e| e.next().is_some()))
    };
    let start = std::time::Instant::now();
    while !busy(&tmp) {
        assert!(
            start.elapsed().as_secs() < 120,
            "no private folder appeared in {}",
            tmp.display()
        );
        assert!(
            child.try_wait().unwrap().is_none(),
            "the grader ended early"
        );
        std::thread::sleep(std::time::Duration::from_millis(20));
    }
    // SAFETY: a signal to the child this test started and has not reaped.
    assert_eq!(unsafe { libc::kill(child.id() as i32, libc::SIGTERM) }, 0);
    let status = child.wait().unwrap();
    assert_eq!(status.code(), Some(130), "{status:?}");
    assert_eq!(ours(&tmp), Vec::<PathBuf>::new(), "left behind");
}

#[test]
fn a_japanese_class_report_is_japanese_and_each_student_has_a_page() {
    let class = temp_dir("class-ja");
    student(&class, "ada", &["lesson-restore"]);
    student(&class, "bob", &["restore-max"]);
    let out = temp_dir("class-ja-report");
    let o = Command::new(env!("CARGO_BIN_EXE_opengl3d"))
        .args(["--lang", "ja", "grade", "--class"])
        .arg(&class)
        .args(["--step", "restore", "--points", "--jobs", "1", "--out"])
        .arg(&out)
        .output()
        .expect("run opengl3d");
    assert_eq!(o.status.code(), Some(1), "{}", crate::common::stderr(&o));
    let csv = std::fs::read_to_string(out.join("results.csv")).unwrap();
    let rows: Vec<&str> = csv.lines().collect();
    assert_eq!(
        rows[0], "学生,restore,restoreの点数,合格数,点数,満点,採点の基準",
        "{csv}"
    );
    assert!(rows.contains(&"ada,合格,20,1,20,20,lesson"), "{csv}");
    assert!(rows.contains(&"bob,不合格,0,0,0,20,lesson"), "{csv}");
    let junit = std::fs::read_to_string(out.join("junit.xml")).unwrap();
    assert!(junit.contains("type=\"不合格\""), "{junit}");
    assert!(!junit.contains("failed"), "no English verdict: {junit}");
    let html = std::fs::read_to_string(out.join("report.html")).unwrap();
    for (name, page) in [
        ("ada", "students/001-ada.html"),
        ("bob", "students/002-bob.html"),
    ] {
        assert!(
            html.contains(&format!("href=\"{page}\">{name}</a>")),
            "{html}"
        );
        let text = std::fs::read_to_string(out.join(page)).unwrap();
        assert!(text.contains(&format!("{name}さんの採点結果")), "{text}");
        // Every picture the page shows is there, one folder up.
        for src in text.split("src=\"").skip(1) {
            let rel = &src[..src.find('"').unwrap()];
            assert!(out.join("students").join(rel).is_file(), "{page}: {rel}");
        }
    }
    let bob = std::fs::read_to_string(out.join("students/002-bob.html")).unwrap();
    assert!(
        bob.contains("restore-difference.png") && bob.contains("不合格"),
        "{bob}"
    );
    assert!(bob.contains("20点中0点"), "{bob}");
}
