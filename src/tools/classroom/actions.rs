//! `lesson start --classroom actions DIR`: the template repository for a class graded with plain
//! GitHub Actions. Its workflow `.github/workflows/classroom.yml` installs Mesa, gets the pinned
//! grader (the class's prebuilt Release, or built from the pinned tag and cached under a key that
//! names it), grades once with `grade --format classroom50` (result.json and the pictures), then
//! gives each graded step its points with one `classroom-resources/autograding-command-grader`
//! test that reads that step's verdict from result.json, and reports them with
//! `classroom-resources/autograding-grading-reporter`. The pictures and the feedback page are
//! uploaded as the run's artifact.

use super::{student_readme, write_new, ClassroomOptions, APT_PACKAGES, GRADER_ASSET, REPORT_DIR};
use anyhow::Result;
use std::path::{Path, PathBuf};

/// The workflow's path in the repository.
pub const WORKFLOW: &str = ".github/workflows/classroom.yml";

/// Minutes each reading test may take (the command grader's `timeout` is in minutes).
pub const TEST_TIMEOUT_MINUTES: u32 = 1;

/// Minutes the whole grading job may take: a build from source takes most of it; grading the five
/// shaders takes about a minute on llvmpipe, and the grader's own per-step limit stops an endless
/// loop first.
pub const JOB_TIMEOUT_MINUTES: u32 = 45;

/// One autograding test: the reading of one graded unit's verdict from result.json.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct ActionsTest {
    /// The workflow step's id (letters, digits and `_`: it also names an environment variable).
    pub id: String,
    /// The unit's id in result.json (`restore`, `down-sampling`, …).
    pub unit: String,
    pub name: String,
    pub max_score: u32,
}

/// The tests: one per graded unit in the lesson's order (the units of result.json's tests).
pub fn tests(options: &ClassroomOptions) -> Vec<ActionsTest> {
    crate::tools::grade::classroom50::units(&options.points)
        .into_iter()
        .map(|u| ActionsTest {
            id: u.id.replace(['-', '.'], "_"),
            unit: u.id,
            name: u.name,
            max_score: u.max_score,
        })
        .collect()
}

/// `text` as a YAML double-quoted scalar.
pub fn quoted(text: &str) -> String {
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

/// The shell command of a test: prints the unit's message, then succeeds only when it passed.
fn reading_command(unit: &str) -> String {
    let select = format!(".tests[] | select(.id == \"{unit}\")");
    format!("jq -r '{select} | .message' result.json && jq -e '{select} | .passed' result.json > /dev/null")
}

/// The workflow file.
pub fn workflow(options: &ClassroomOptions) -> String {
    let tests = tests(options);
    let mut y = format!(
        "# Autograding of the opengl3d AO lesson on plain GitHub Actions (written by `opengl3d lesson
# start --classroom actions`). The grader is pinned to opengl3d {version} (tag {tag}): set
# OPENGL3D_RELEASE to \"\" to build it from OPENGL3D_GIT at that tag instead of downloading the
# class's prebuilt grader. Moving a class to a newer grader: docs/grade/classroom.md.
name: Autograding Tests
on:
  push:
  workflow_dispatch:
permissions:
  checks: write
  actions: read
  contents: read
env:
  OPENGL3D_VERSION: {version_q}
  OPENGL3D_TAG: {tag_q}
  OPENGL3D_GIT: {git}
  OPENGL3D_RELEASE: {release}
jobs:
  run-autograding-tests:
    runs-on: ubuntu-latest
    timeout-minutes: {JOB_TIMEOUT_MINUTES}
    steps:
      - name: Checkout code
        uses: actions/checkout@v4
      - name: Mesa (software OpenGL through EGL)
        run: |
          sudo apt-get update -qq
          sudo apt-get install -y -qq --no-install-recommends {apt}
      - name: Prebuilt grader
        if: env.OPENGL3D_RELEASE != ''
        run: |
          mkdir -p \"$HOME/.local/bin\"
          cd \"$RUNNER_TEMP\"
          curl -fsSL -o grader.tar.gz \"$OPENGL3D_RELEASE/{asset}\"
          curl -fsSL -o grader.sha256 \"$OPENGL3D_RELEASE/{asset}.sha256\"
          echo \"$(cut -d' ' -f1 grader.sha256)  grader.tar.gz\" | sha256sum -c -
          tar -xzf grader.tar.gz -C \"$HOME/.local/bin\" opengl3d
          echo \"$HOME/.local/bin\" >> \"$GITHUB_PATH\"
      - name: Rust (only to build the grader)
        if: env.OPENGL3D_RELEASE == ''
        uses: dtolnay/rust-toolchain@stable
      # The key names the pinned tag: a new pin builds once, then every run reuses it.
      - name: Keep the built grader between runs
        if: env.OPENGL3D_RELEASE == ''
        uses: actions/cache@v4
        with:
          path: ~/.cargo/bin/opengl3d
          key: opengl3d-grader-${{{{ runner.os }}}}-${{{{ env.OPENGL3D_TAG }}}}-${{{{ env.OPENGL3D_GIT }}}}
      - name: Grader built from the pinned tag
        if: env.OPENGL3D_RELEASE == ''
        run: |
          if ! opengl3d --version 2>/dev/null | grep -qx \"opengl3d $OPENGL3D_VERSION\"; then
            cargo install --locked --force --profile grader --no-default-features --features grade --git \"$OPENGL3D_GIT\" --tag \"$OPENGL3D_TAG\" opengl3d
          fi
      - name: Grade (result.json and {report}/)
        run: opengl3d --lang {lang} --res . grade --format classroom50 --points {points} --out {report}
      - name: Pictures and feedback page
        if: always()
        uses: actions/upload-artifact@v4
        with:
          name: grade-report
          path: {report}/
          if-no-files-found: ignore
",
        version = super::GRADER_VERSION,
        tag = super::grader_tag(),
        version_q = quoted(super::GRADER_VERSION),
        tag_q = quoted(&super::grader_tag()),
        git = quoted(&options.git_url()),
        release = quoted(&options.release_url()),
        apt = APT_PACKAGES.join(" "),
        asset = GRADER_ASSET,
        report = REPORT_DIR,
        lang = options.lang.code(),
        points = quoted(&options.points_spec()),
    );
    for test in &tests {
        y.push_str(&format!(
            "      - name: {name}
        id: {id}
        uses: classroom-resources/autograding-command-grader@v1
        with:
          test-name: {name}
          setup-command: \"\"
          command: {command}
          timeout: {TEST_TIMEOUT_MINUTES}
          max-score: {max}
",
            name = quoted(&test.name),
            id = test.id,
            command = quoted(&reading_command(&test.unit)),
            max = test.max_score
        ));
    }
    y.push_str(
        "      - name: Autograding Reporter
        uses: classroom-resources/autograding-grading-reporter@v1
        env:
",
    );
    for test in &tests {
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

/// Writes the template repository into `dir`: `lesson start`'s files, the workflow, the student's
/// README and a `.gitignore` for what the grader and the lessons write.
pub fn start(dir: &Path, options: &ClassroomOptions) -> Result<Vec<PathBuf>> {
    let mut written = crate::tools::lesson::start(dir, options.lang)?;
    written.extend(write_new(
        dir,
        vec![
            (PathBuf::from(WORKFLOW), workflow(options)),
            (PathBuf::from("README.md"), student_readme(options)),
            (
                PathBuf::from(".gitignore"),
                format!("out/\n{REPORT_DIR}/\nresult.json\n"),
            ),
        ],
    )?);
    Ok(written)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn quoted_scalars_escape_what_yaml_needs() {
        assert_eq!(quoted(r#"a "b" \ c"#), r#""a \"b\" \\ c""#);
    }

    #[test]
    fn a_reading_command_selects_its_unit_only() {
        let c = reading_command("down-sampling");
        assert!(c.contains("select(.id == \"down-sampling\")"), "{c}");
        assert!(c.contains("jq -e"), "{c}");
    }
}
