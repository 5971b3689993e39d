//! `lesson start --classroom classroom50 DIR`: what a teacher needs for a Classroom 50 assignment.
//!
//! * `DIR/template/`: the template repository (the stub shaders with the rest of `Res/`, the
//!   student's README in the class's language, a `.gitignore`). Classroom 50 adds its own grading
//!   workflow to each student's copy when the student accepts, so the template has none.
//! * `DIR/autograder/autograder.py`: the per-assignment autograder (Classroom 50 runs it in the
//!   student's checkout): it gets the pinned grader and runs `grade --format classroom50`, which
//!   writes `result.json` (one test per graded step) and the pictures.
//! * `DIR/runtime.json`: the assignment's `runtime` block (the runner and Mesa's apt packages).
//! * `DIR/assignment.json`: the assignment's fields to set (`runtime`, `release_assets`: the heat
//!   maps and the feedback page, `submission_mode: tag`, so that only submissions are graded).
//! * `DIR/TEACHER.md`: the steps, in the class's language.

use super::{
    grader_tag, student_readme, write_new, ClassroomOptions, APT_PACKAGES, GRADER_ASSET,
    GRADER_VERSION, REPORT_DIR,
};
use crate::tools::grade::Step;
use anyhow::Result;
use serde_json::json;
use std::path::{Path, PathBuf};

/// The autograder as written in the repository; its `{{NAME}}` fields are filled in by [`autograder`].
const AUTOGRADER_TEMPLATE: &str = include_str!("autograder.py");

/// The files Classroom 50 attaches to each submission's Release: the feedback page and each step's
/// heat map with the expected and the submitted pictures (a file the grading did not write, as for
/// a passing step, is skipped by the runner with a warning and changes no score).
pub fn release_assets() -> Vec<String> {
    let mut assets = vec![format!("{REPORT_DIR}/feedback.html")];
    for s in Step::ALL {
        for kind in ["difference", "expected", "actual"] {
            assets.push(format!("{REPORT_DIR}/{}-{kind}.png", s.name()));
        }
    }
    assets
}

/// `text` as a Python string literal's contents (the values are checked ASCII names and URLs, but
/// a quote or backslash must still not end the literal).
fn python_text(text: &str) -> String {
    text.replace('\\', "\\\\").replace('"', "\\\"")
}

/// The autograder with the options' values.
pub fn autograder(options: &ClassroomOptions) -> String {
    let fields = [
        ("{{VERSION}}", GRADER_VERSION.to_string()),
        ("{{TAG}}", grader_tag()),
        ("{{RELEASE_URL}}", options.release_url()),
        ("{{ASSET}}", GRADER_ASSET.to_string()),
        ("{{GIT_URL}}", options.git_url()),
        ("{{LANG}}", options.lang.code().to_string()),
        ("{{POINTS}}", options.points_spec()),
    ];
    let mut text = AUTOGRADER_TEMPLATE.to_string();
    for (field, value) in fields {
        text = text.replace(field, &python_text(&value));
    }
    text
}

/// The `runtime` block: GitHub's Ubuntu runner with Mesa's EGL and software OpenGL.
pub fn runtime() -> serde_json::Value {
    json!({ "runs-on": "ubuntu-latest", "apt": APT_PACKAGES })
}

/// The assignment's fields this lesson needs.
pub fn assignment_fields() -> serde_json::Value {
    json!({
        "runtime": runtime(),
        "release_assets": release_assets(),
        "submission_mode": "tag",
    })
}

/// The teacher's steps, in the class's language.
fn teacher_notes(options: &ClassroomOptions) -> String {
    rust_i18n::t!(
        "classroom.teacher_c50",
        locale = options.lang.code(),
        version = GRADER_VERSION,
        tag = grader_tag(),
        repo = options.grader_repo,
        release = options.release_url(),
        asset = GRADER_ASSET,
        points = options.points_spec()
    )
    .into_owned()
}

/// Writes the template repository, the autograder bundle and the assignment's settings into `dir`.
pub fn start(dir: &Path, options: &ClassroomOptions) -> Result<Vec<PathBuf>> {
    let template = dir.join("template");
    let mut written = crate::tools::lesson::start(&template, options.lang)?;
    let pretty = |v: serde_json::Value| serde_json::to_string_pretty(&v).map(|s| s + "\n");
    written.extend(write_new(
        dir,
        vec![
            (PathBuf::from("template/README.md"), student_readme(options)),
            (
                PathBuf::from("template/.gitignore"),
                format!("out/\n{REPORT_DIR}/\nresult.json\n"),
            ),
            (
                PathBuf::from("autograder/autograder.py"),
                autograder(options),
            ),
            (PathBuf::from("runtime.json"), pretty(runtime())?),
            (
                PathBuf::from("assignment.json"),
                pretty(assignment_fields())?,
            ),
            (PathBuf::from("TEACHER.md"), teacher_notes(options)),
        ],
    )?);
    Ok(written)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn release_assets_keep_classroom50s_limits() {
        let assets = release_assets();
        assert!(assets.len() <= 50);
        assert!(assets.iter().map(|a| a.len() + 1).sum::<usize>() <= 8 * 1024);
        let mut names: Vec<&str> = assets
            .iter()
            .map(|a| a.rsplit('/').next().unwrap())
            .collect();
        for n in &names {
            assert!(
                n.chars()
                    .all(|c| c.is_ascii_alphanumeric() || matches!(c, '.' | '_' | '-'))
                    && !n.starts_with('.')
                    && !n.ends_with('.')
                    && !n.contains("..")
                    && *n != "result.json"
                    && *n != "release-body.md",
                "{n}"
            );
        }
        names.sort();
        names.dedup();
        assert_eq!(names.len(), assets.len(), "basenames are unique");
    }

    #[test]
    fn the_autograder_has_every_field_filled() {
        let options = ClassroomOptions {
            kind: super::super::ClassroomKind::Classroom50,
            points: Default::default(),
            grader_repo: "school/opengl3d".into(),
            lang: crate::i18n::Lang::Ja,
        };
        let text = autograder(&options);
        assert!(!text.contains("{{"), "a field is left: {text}");
        assert!(text.contains("GRADER_TAG = \"v"));
        assert!(text.contains("https://github.com/school/opengl3d/releases/download/v"));
        assert!(text.contains("LANG = \"ja\""));
        assert!(text.contains("restore=20,down-sampling=10,simple=10,sao.normal=10,"));
    }
}
