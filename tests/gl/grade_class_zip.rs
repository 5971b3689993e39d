//! `grade --class` with `.zip` submissions, the archives written here with the zip crate: a good
//! archive (flat, or one folder inside) is graded as its folder is; an archive with an entry that
//! climbs out of its folder (zip-slip), a symbolic link, a zip bomb, or bytes that are no archive
//! fail that student with the reason, and the class goes on.

use super::grade_class::{grade_class, mutant, parse_csv, temp_dir, CORRECT};
use std::io::Write as _;
use std::path::Path;
use zip::write::SimpleFileOptions;

fn deflated() -> SimpleFileOptions {
    SimpleFileOptions::default().compression_method(zip::CompressionMethod::Deflated)
}

/// Writes `path` as a zip of the correct shaders, each under `prefix` (`""` or `"folder/"`), then
/// whatever `more` adds.
fn correct_zip(path: &Path, prefix: &str, more: impl FnOnce(&mut zip::ZipWriter<std::fs::File>)) {
    let mut zip = zip::ZipWriter::new(std::fs::File::create(path).unwrap());
    for m in CORRECT {
        for f in std::fs::read_dir(mutant(m)).unwrap() {
            let f = f.unwrap();
            let name = format!("{prefix}{}", f.file_name().to_string_lossy());
            zip.start_file(name, deflated()).unwrap();
            zip.write_all(&std::fs::read(f.path()).unwrap()).unwrap();
        }
    }
    more(&mut zip);
    zip.finish().unwrap();
}

#[test]
fn zips_are_graded_as_folders_and_unsafe_ones_refused_with_the_reason() {
    let class = temp_dir("grade-class-zip");
    correct_zip(&class.join("ada.zip"), "", |_| {});
    // Zipped as a folder (the Finder's litter beside it is skipped).
    correct_zip(&class.join("bea.zip"), "bea-lesson/", |z| {
        z.start_file("__MACOSX/bea-lesson/._sao.frag", deflated())
            .unwrap();
        z.write_all(b"resource fork").unwrap();
    });
    // Zip-slip: the shaders, and one entry that would land beside the class folder.
    correct_zip(&class.join("eve.zip"), "", |z| {
        z.start_file("../escaped.frag", deflated()).unwrap();
        z.write_all(b"#version 450\n").unwrap();
    });
    correct_zip(&class.join("kim.zip"), "", |z| {
        z.add_symlink("notes.txt", "/etc/passwd", SimpleFileOptions::default())
            .unwrap();
    });
    // A zip bomb: 64 MiB of zeros deflate to about 64 KiB.
    correct_zip(&class.join("zed.zip"), "", |z| {
        z.start_file("padding.bin", deflated()).unwrap();
        let zeros = vec![0u8; 1 << 20];
        for _ in 0..64 {
            z.write_all(&zeros).unwrap();
        }
    });
    std::fs::write(class.join("pat.zip"), "PK not really").unwrap();
    // No sao.frag: "not submitted", naming the archive and its folder, not the private copy.
    let mut zip = zip::ZipWriter::new(std::fs::File::create(class.join("cid.zip")).unwrap());
    for m in [
        "lesson-restore",
        "listing-down-sampling",
        "listing-simple",
        "listing-blur",
    ] {
        for f in std::fs::read_dir(mutant(m)).unwrap() {
            let f = f.unwrap();
            let name = format!("work/{}", f.file_name().to_string_lossy());
            zip.start_file(name, deflated()).unwrap();
            zip.write_all(&std::fs::read(f.path()).unwrap()).unwrap();
        }
    }
    zip.finish().unwrap();
    assert!(std::fs::metadata(class.join("zed.zip")).unwrap().len() < 1 << 20);

    let report = temp_dir("grade-class-zip-report");
    let o = grade_class(&class, &["--out", report.to_str().unwrap(), "--jobs", "2"]);
    let (stdout, stderr) = (
        String::from_utf8_lossy(&o.stdout),
        String::from_utf8_lossy(&o.stderr),
    );
    assert_eq!(o.status.code(), Some(1), "{stdout}\n{stderr}");
    for beside in [class.parent().unwrap(), &std::env::temp_dir()] {
        assert!(
            !beside.join("escaped.frag").exists(),
            "the zip-slip entry was written into {}",
            beside.display()
        );
    }

    let csv = std::fs::read_to_string(report.join("results.csv")).unwrap();
    let rows: Vec<String> = parse_csv(&csv).into_iter().map(|r| r.join(" ")).collect();
    let fails = "FAIL FAIL FAIL FAIL FAIL 0 lesson";
    assert_eq!(
        rows,
        [
            "student restore down-sampling simple sao blur passed level".to_string(),
            "ada PASS PASS PASS PASS PASS 5 lesson".into(),
            "bea PASS PASS PASS PASS PASS 5 lesson".into(),
            "cid PASS PASS PASS not submitted PASS 4 lesson".into(),
            format!("eve {fails}"),
            format!("kim {fails}"),
            format!("pat {fails}"),
            format!("zed {fails}"),
        ],
        "{csv}\n{stdout}\n{stderr}"
    );
    let junit = std::fs::read_to_string(report.join("junit.xml")).unwrap();
    for reason in [
        "entry &quot;../escaped.frag&quot; points outside its folder",
        "entry &quot;notes.txt&quot; is a symbolic link",
        "zed.zip unpacks to more than 16 MiB",
        "pat.zip is not a readable .zip file",
        "not submitted: no sao.frag in cid.zip/work",
    ] {
        assert!(junit.contains(reason), "{reason}\n{junit}");
    }
    // No private folder is left behind.
    let leftovers: Vec<_> = std::fs::read_dir(std::env::temp_dir())
        .unwrap()
        .filter_map(|e| e.ok())
        .map(|e| e.file_name().to_string_lossy().into_owned())
        .filter(|n| n.starts_with("opengl3d-class-"))
        .collect();
    assert!(leftovers.is_empty(), "{leftovers:?}");
}
