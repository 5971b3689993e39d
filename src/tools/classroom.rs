//! `opengl3d lesson start --classroom DIR`: the student repository a teacher publishes as a GitHub
//! Classroom assignment. It holds what `lesson start` writes (the stub shaders and the rest of
//! `Res/`) and `.github/workflows/classroom.yml`, which follows GitHub Classroom's autograding
//! conventions: one `education/autograding-command-grader@v1` step per graded shader, worth that
//! step's points (`grade --points`), then `education/autograding-grader-reporter@v1`. Classroom's
//! runners have no GPU; the grader runs on Mesa's llvmpipe, installed with apt.

use crate::tools::grade::points::Points;
use crate::tools::grade::Step;
use anyhow::Result;
use rust_i18n::t;
use std::path::{Path, PathBuf};

/// Where the workflow takes the grader from unless the teacher sets another source (the
/// `OPENGL3D_GIT` and `OPENGL3D_PATH` variables at the top of the workflow).
pub const GRADER_GIT_PLACEHOLDER: &str = "https://github.com/YOUR-ORGANISATION/opengl3d";

/// The workflow's path in the repository.
pub const WORKFLOW: &str = ".github/workflows/classroom.yml";

/// Minutes each test may take (the command grader's `timeout` is in minutes): grading one shader
/// takes seconds on llvmpipe; the grader's own per-step limit stops an endless loop first.
pub const TEST_TIMEOUT_MINUTES: u32 = 5;

/// One autograding test: the grading of one step.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct ClassroomTest {
    /// The workflow step's id (letters, digits and `_`: it also names an environment variable).
    pub id: String,
    pub name: String,
    /// The command, run in the repository's root with the grader on `PATH` as `opengl3d`.
    pub command: String,
    pub max_score: u32,
}

/// The tests of the workflow, one per graded shader in the lesson's order, messages in `lang`.
pub fn tests(points: &Points, lang: &str) -> Vec<ClassroomTest> {
    Step::ALL
        .iter()
        .map(|s| ClassroomTest {
            id: s.name().replace('-', "_"),
            name: format!("{} ({})", s.name(), s.file()),
            command: format!("opengl3d --lang {lang} --res . grade --step {}", s.name()),
            max_score: points.of(*s),
        })
        .collect()
}

/// `text` as a YAML double-quoted scalar.
fn quoted(text: &str) -> String {
    let mut s = String::from("\"");
    for c in text.chars() {
        match c {
            '"' => s.push_str("\\\""),
            '\\' => s.push_str("\\\\"),
            '\n' => s.push_str("\\n"),
            c => s.push(c),
        }
    }
    s.push('"');
    s
}

/// The workflow file for `tests`.
pub fn workflow(tests: &[ClassroomTest]) -> String {
    let mut y = format!(
        "# GitHub Classroom autograding for the opengl3d AO lesson (written by `opengl3d lesson start
# --classroom`). Each test grades one shader with the opengl3d grader on Mesa's software OpenGL
# (llvmpipe: Classroom's runners have no GPU) and is worth its points.
# Where the grader comes from: set OPENGL3D_GIT to the opengl3d repository the class uses, or
# OPENGL3D_PATH to a folder of this repository holding its source (then OPENGL3D_GIT is unused).
name: Autograding Tests
on:
  push:
  workflow_dispatch:
  repository_dispatch:
permissions:
  checks: write
  actions: read
  contents: read
env:
  OPENGL3D_GIT: {git}
  OPENGL3D_PATH: \"\"
jobs:
  run-autograding-tests:
    runs-on: ubuntu-latest
    if: github.actor != 'github-classroom[bot]'
    steps:
      - name: Checkout code
        uses: actions/checkout@v4
      - name: Mesa (software OpenGL through EGL)
        run: |
          sudo apt-get update -qq
          sudo apt-get install -y -qq --no-install-recommends libegl1 libegl-mesa0 libgl1 libgl1-mesa-dri libglx-mesa0 libgbm1
      - name: Rust
        uses: dtolnay/rust-toolchain@stable
      # The grader kept between runs: from OPENGL3D_GIT, `cargo install` skips a commit it has built.
      - name: Keep the grader between runs
        uses: actions/cache@v4
        with:
          path: |
            ~/.cargo/bin/opengl3d
            ~/.cargo/.crates.toml
            ~/.cargo/.crates2.json
            ~/.cargo/git
          key: opengl3d-${{{{ runner.os }}}}-${{{{ env.OPENGL3D_GIT }}}}-${{{{ env.OPENGL3D_PATH }}}}
      - name: The grader
        run: |
          if [ -n \"$OPENGL3D_PATH\" ]; then
            cargo install --locked --path \"$OPENGL3D_PATH\"
          else
            cargo install --locked --git \"$OPENGL3D_GIT\" opengl3d
          fi
",
        git = quoted(GRADER_GIT_PLACEHOLDER)
    );
    for test in tests {
        y.push_str(&format!(
            "      - name: {name}
        id: {id}
        uses: education/autograding-command-grader@v1
        with:
          test-name: {name}
          setup-command: \"\"
          command: {command}
          timeout: {TEST_TIMEOUT_MINUTES}
          max-score: {max}
",
            name = quoted(&test.name),
            id = test.id,
            command = quoted(&test.command),
            max = test.max_score
        ));
    }
    y.push_str(
        "      - name: Autograding Reporter
        uses: education/autograding-grader-reporter@v1
        env:
",
    );
    for test in tests {
        y.push_str(&format!(
            "          {}_RESULTS: \"${{{{steps.{}.outputs.result}}}}\"\n",
            test.id.to_uppercase(),
            test.id
        ));
    }
    let runners: Vec<&str> = tests.iter().map(|t| t.id.as_str()).collect();
    y.push_str(&format!(
        "        with:\n          runners: {}\n",
        runners.join(",")
    ));
    y
}

/// Writes the student repository into `dir`: `lesson start`'s files, the workflow and a
/// `.gitignore` for what the grader and the lessons write. Existing files are kept (said on
/// stderr). Returns the files written.
pub fn start(dir: &Path) -> Result<Vec<PathBuf>> {
    let mut written = crate::tools::lesson::start(dir, crate::i18n::current())?;
    let lang = crate::i18n::current().code();
    let files = [
        (
            PathBuf::from(WORKFLOW),
            workflow(&tests(&Points::default(), lang)),
        ),
        (
            PathBuf::from(".gitignore"),
            "out/\ngrade-report/\n".to_string(),
        ),
    ];
    for (rel, text) in files {
        let path = dir.join(&rel);
        if path.exists() {
            eprintln!("{}", t!("lesson.kept_existing", path = path.display()));
            continue;
        }
        if let Some(parent) = path.parent() {
            crate::io::create_dir_all(parent)?;
        }
        std::fs::write(&path, text).map_err(|e| crate::io::io_error(&path, "write", &e))?;
        written.push(path);
    }
    written.sort();
    Ok(written)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_step_is_a_test_worth_its_points() {
        let p = Points::default();
        let t = tests(&p, "ja");
        assert_eq!(t.len(), Step::ALL.len());
        assert_eq!(t.iter().map(|t| t.max_score).sum::<u32>(), 100);
        assert_eq!(t[1].id, "down_sampling");
        assert_eq!(
            t[1].command,
            "opengl3d --lang ja --res . grade --step down-sampling"
        );
        let y = workflow(&t);
        for test in &t {
            assert!(y.contains(&format!("id: {}\n", test.id)), "{y}");
            assert!(y.contains(&format!("steps.{}.outputs.result", test.id)));
        }
        assert!(y.contains("runners: restore,down_sampling,simple,sao,blur\n"));
    }

    #[test]
    fn quoted_scalars_escape_what_yaml_needs() {
        assert_eq!(quoted(r#"a "b" \ c"#), r#""a \"b\" \\ c""#);
    }
}
