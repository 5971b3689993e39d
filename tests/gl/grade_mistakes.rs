//! The pages' "Typical mistakes" (and 「よくある間違い」) against the mutant corpus: every item of every
//! list, in both languages, is a row of `tests/mutants/mistakes.md`, either with mutants that
//! `grade --level lesson` rejects or marked `left`, and then the page says in that item (or in the
//! list's heading) that `grade` leaves it to the student. A mistake added to a page without a mutant
//! or a word on why fails here, and so does a mutant named there that the grader passes.

use std::path::{Path, PathBuf};
use std::process::Command;

fn root() -> &'static Path {
    Path::new(env!("CARGO_MANIFEST_DIR"))
}

/// One list: its heading line and its items (each item's lines joined).
struct List {
    heading: String,
    items: Vec<String>,
}

/// The mistakes list of the lesson page `NN-*.md` in `dir`: the lines from the heading (`heading`)
/// to the first blank line, each item starting with "- ".
fn list(dir: &Path, page: &str, heading: &str) -> List {
    let file = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .find(|p| {
            p.file_name()
                .and_then(|n| n.to_str())
                .is_some_and(|n| n.starts_with(&format!("{page}-")) && n.ends_with(".md"))
        })
        .unwrap_or_else(|| panic!("no page {page} in {}", dir.display()));
    let text = std::fs::read_to_string(&file).unwrap();
    let mut lines = text.lines().skip_while(|l| !l.starts_with(heading));
    let heading = lines
        .next()
        .unwrap_or_else(|| panic!("{}: no {heading} list", file.display()))
        .to_string();
    let mut items: Vec<String> = Vec::new();
    for l in lines.take_while(|l| !l.trim().is_empty()) {
        match l.strip_prefix("- ") {
            Some(item) => items.push(item.to_string()),
            None => {
                let last = items.last_mut().expect("a list starts with an item");
                last.push(' ');
                last.push_str(l.trim());
            }
        }
    }
    List { heading, items }
}

/// The rows of `tests/mutants/mistakes.md`: (page, item, how to grade, mutants or empty for `left`).
fn rows() -> Vec<(String, usize, String, Vec<String>)> {
    let text = std::fs::read_to_string(root().join("tests/mutants/mistakes.md")).unwrap();
    text.lines()
        .filter(|l| l.starts_with("| ") && !l.starts_with("| page"))
        .map(|l| {
            let cells: Vec<&str> = l.trim_matches('|').split('|').map(str::trim).collect();
            assert_eq!(cells.len(), 4, "{l}");
            let mutants = match cells[3] {
                "left" => Vec::new(),
                m => m.split_whitespace().map(str::to_string).collect(),
            };
            (
                cells[0].to_string(),
                cells[1].parse().unwrap(),
                cells[2].to_string(),
                mutants,
            )
        })
        .collect()
}

fn says_left_en(text: &str) -> bool {
    text.contains("`grade` leaves th")
}

fn says_left_ja(text: &str) -> bool {
    text.contains("`grade`は") && text.contains("確かめません")
}

/// Grades mutant `name` at `--level lesson` as `how` says (`--step STEP`, or `--lesson N`):
/// whether it passed, and the output.
fn passes(name: &str, how: &str) -> (bool, String) {
    let dir: PathBuf = root().join("tests/mutants").join(name);
    assert!(
        dir.is_dir(),
        "mistakes.md names {name}, which is not in tests/mutants"
    );
    let mut cmd = Command::new(env!("CARGO_BIN_EXE_opengl3d"));
    cmd.arg("--res")
        .arg(&dir)
        .args(["grade", "--level", "lesson"]);
    match how.strip_prefix("lesson ") {
        Some(n) => cmd.args(["--lesson", n]),
        None => cmd.args(["--step", how]),
    };
    let o = cmd.output().expect("run opengl3d");
    (
        o.status.success(),
        String::from_utf8_lossy(&o.stdout).into_owned(),
    )
}

#[test]
fn every_listed_mistake_has_a_mutant_the_lesson_level_rejects_or_the_page_says_why_not() {
    let rows = rows();
    let readme = std::fs::read_to_string(root().join("tests/mutants/README.md")).unwrap();
    for page in (1..=12).map(|n| format!("{n:02}")) {
        let en = list(&root().join("lessons"), &page, "**Typical mistakes");
        let ja = list(&root().join("lessons/ja"), &page, "**よくある間違い");
        assert_eq!(
            en.items.len(),
            ja.items.len(),
            "page {page}: the English and Japanese lists differ in length"
        );
        let mine: Vec<&(String, usize, String, Vec<String>)> =
            rows.iter().filter(|r| r.0 == page).collect();
        let numbers: Vec<usize> = mine.iter().map(|r| r.1).collect();
        assert_eq!(
            numbers,
            (1..=en.items.len()).collect::<Vec<_>>(),
            "page {page}: mistakes.md must have one row per listed mistake, in order"
        );
        for (row, (item_en, item_ja)) in mine.iter().zip(en.items.iter().zip(&ja.items)) {
            let (_, n, how, mutants) = row;
            if mutants.is_empty() {
                assert!(
                    says_left_en(item_en) || says_left_en(&en.heading),
                    "page {page} item {n} is left to the student, but the page does not say so: {item_en}"
                );
                assert!(
                    says_left_ja(item_ja) || says_left_ja(&ja.heading),
                    "page {page} item {n} is left to the student, but the Japanese page does not say so: {item_ja}"
                );
                continue;
            }
            for m in mutants {
                assert!(
                    readme.contains(&format!("`{m}`")),
                    "{m} is not described in tests/mutants/README.md"
                );
                let (passed, out) = passes(m, how);
                assert!(
                    !passed,
                    "page {page} item {n} ({item_en}): the lesson level passes {m}:\n{out}"
                );
            }
        }
    }
}
