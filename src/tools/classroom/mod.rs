//! `opengl3d lesson start --classroom KIND DIR`: what a teacher publishes to run the lesson as an
//! assignment, graded on GitHub Actions by this grader on Mesa's software OpenGL (no GPU needed).
//!
//! * `classroom50` ([`classroom50`]): a template repository and the Classroom 50 autograder bundle
//!   (`autograder.py`, its `runtime` block and the assignment's `release_assets`), graded on the
//!   student's `submit/*` tags.
//! * `actions` ([`actions`]): a template repository with its own workflow for teachers who grade
//!   with plain GitHub Actions (the `classroom-resources` autograding actions).
//!
//! Everything written names one grader version, this crate's, and its tag `vVERSION`: grades never
//! change under a class unless the teacher moves the pin (docs/grade/classroom.md says how).

pub mod actions;
pub mod classroom50;
mod write;

pub use write::start;

use crate::tools::grade::points::Points;
use anyhow::{bail, Result};
use rust_i18n::t;
use std::path::{Path, PathBuf};

/// The grader version every template names.
pub const GRADER_VERSION: &str = env!("CARGO_PKG_VERSION");

/// The repository the templates take the grader from until the teacher names theirs
/// (`--grader-repo OWNER/REPO`).
pub const GRADER_REPO_PLACEHOLDER: &str = "YOUR-ORGANISATION/opengl3d";

/// The release asset holding the prebuilt grader (built by `.github/workflows/grader-release.yml`).
pub const GRADER_ASSET: &str = "opengl3d-grader-x86_64-linux.tar.gz";

/// Debian/Ubuntu packages the grader needs on a runner: Mesa's EGL and software OpenGL.
pub const APT_PACKAGES: [&str; 6] = [
    "libegl1",
    "libegl-mesa0",
    "libgl1",
    "libgl1-mesa-dri",
    "libglx-mesa0",
    "libgbm1",
];

/// The folder the grader writes its pictures and feedback page to in a student's checkout.
pub const REPORT_DIR: &str = "grade-report";

/// The git tag of the pinned grader version.
pub fn grader_tag() -> String {
    format!("v{GRADER_VERSION}")
}

/// Where a class is graded.
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
pub enum ClassroomKind {
    Classroom50,
    Actions,
}

/// What the teacher chose.
#[derive(Clone, Debug)]
pub struct ClassroomOptions {
    pub kind: ClassroomKind,
    pub points: Points,
    /// `OWNER/REPO` of the class's copy of opengl3d on GitHub.
    pub grader_repo: String,
    /// The class's language: messages, test names, the student's README. Test names follow the
    /// language the command runs in, which is this one.
    pub lang: crate::i18n::Lang,
}

impl ClassroomOptions {
    /// The grader's git URL.
    pub fn git_url(&self) -> String {
        format!("https://github.com/{}", self.grader_repo)
    }
    /// The Release of the pinned tag, where the prebuilt grader is downloaded from.
    pub fn release_url(&self) -> String {
        format!("{}/releases/download/{}", self.git_url(), grader_tag())
    }
    /// The `--points` value the templates pass to the grader.
    pub fn points_spec(&self) -> String {
        self.points.spec()
    }
}

/// Checks `OWNER/REPO` (GitHub's letters, digits, `-`, `_` and `.`): the value lands in shell,
/// YAML and Python text.
pub fn check_grader_repo(repo: &str) -> Result<()> {
    let ok_part = |p: &str| {
        !p.is_empty()
            && p != "."
            && p != ".."
            && p.chars()
                .all(|c| c.is_ascii_alphanumeric() || matches!(c, '-' | '_' | '.'))
    };
    match repo.split_once('/') {
        Some((owner, name)) if ok_part(owner) && ok_part(name) => Ok(()),
        _ => bail!("{}", t!("classroom.bad_grader_repo", repo = repo)),
    }
}

/// Writes `files` (paths relative to `dir`) unless a file is already there (said on stderr);
/// returns those written.
pub(crate) fn write_new(dir: &Path, files: Vec<(PathBuf, String)>) -> Result<Vec<PathBuf>> {
    let mut written = Vec::new();
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
    Ok(written)
}

/// The student's README of the template repository, in the class's language: what to do, how to
/// check a step, and how to submit.
pub(crate) fn student_readme(options: &ClassroomOptions) -> String {
    let l = options.lang.code();
    let submit = match options.kind {
        ClassroomKind::Classroom50 => t!("classroom.readme_submit_c50", locale = l),
        ClassroomKind::Actions => t!("classroom.readme_submit_actions", locale = l),
    };
    t!(
        "classroom.readme",
        locale = l,
        version = GRADER_VERSION,
        tag = grader_tag(),
        git = options.git_url(),
        submit = submit,
        report = REPORT_DIR
    )
    .into_owned()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn grader_repos_are_owner_slash_name_only() {
        for ok in ["a/b", "my-org/opengl3d", "x_y/z.rs"] {
            assert!(check_grader_repo(ok).is_ok(), "{ok}");
        }
        for bad in [
            "a", "a/b/c", "/b", "a/", "a b/c", "a/$(x)", "a/\"b", "../x", "a/..",
        ] {
            assert!(check_grader_repo(bad).is_err(), "{bad}");
        }
    }
}
