//! Staging: copying the graded file, and the files it `#include`s, into the step's private folder,
//! so that only this one file of the student's is used.

use crate::gl::preprocess::include_target;
use anyhow::{Context as _, Result};
use std::path::{Component, Path, PathBuf};

/// Copies `file` into a fresh `dir`, with the files it `#include`s (resolved next to it, as the
/// engine does), keeping their relative paths. A missing include is not an error here: building the
/// shader reports it with file:line.
pub fn stage(file: &Path, dir: &Path) -> Result<PathBuf> {
    match std::fs::remove_dir_all(dir) {
        Ok(()) => {}
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => {}
        Err(e) => return Err(e).with_context(|| format!("cannot empty {}", dir.display())),
    }
    std::fs::create_dir_all(dir).with_context(|| format!("cannot create {}", dir.display()))?;
    let name = file
        .file_name()
        .with_context(|| format!("{} names no file", file.display()))?;
    let to = dir.join(name);
    copy(file, &to)?;
    let bytes = std::fs::read(file).with_context(|| format!("cannot read {}", file.display()))?;
    let from_dir = file.parent().unwrap_or(Path::new("."));
    for name in String::from_utf8_lossy(&bytes)
        .lines()
        .filter_map(include_target)
    {
        let rel = Path::new(name);
        // Only paths below the shader's folder: the copy must stay inside `dir`.
        if rel.is_absolute() || rel.components().any(|c| !matches!(c, Component::Normal(_))) {
            continue;
        }
        let (src, dst) = (from_dir.join(rel), dir.join(rel));
        if src.is_file() {
            if let Some(parent) = dst.parent() {
                std::fs::create_dir_all(parent)
                    .with_context(|| format!("cannot create {}", parent.display()))?;
            }
            copy(&src, &dst)?;
        }
    }
    Ok(to)
}

fn copy(from: &Path, to: &Path) -> Result<()> {
    std::fs::copy(from, to)
        .map(|_| ())
        .with_context(|| format!("cannot copy {} to {}", from.display(), to.display()))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn include_lines_name_their_file() {
        assert_eq!(include_target("#include \"a.glsl\""), Some("a.glsl"));
        assert_eq!(
            include_target("  #include  \"sub/b.glsl\"  "),
            Some("sub/b.glsl")
        );
        assert_eq!(include_target("#include \"\""), None);
        assert_eq!(include_target("// #include \"c.glsl\""), None);
        assert_eq!(include_target("#version 450"), None);
    }

    /// A fresh folder under the system's temporary folder.
    fn scratch(name: &str) -> PathBuf {
        let d =
            std::env::temp_dir().join(format!("opengl3d-staging-{name}-{}", std::process::id()));
        match std::fs::remove_dir_all(&d) {
            Err(e) if e.kind() != std::io::ErrorKind::NotFound => panic!("{}: {e}", d.display()),
            _ => {}
        }
        std::fs::create_dir_all(&d).unwrap();
        d
    }

    #[test]
    fn staging_copies_the_file_and_its_includes_below_its_folder_only() {
        let root = scratch("copies");
        let student = root.join("student");
        std::fs::create_dir_all(student.join("lib")).unwrap();
        std::fs::write(root.join("outside.glsl"), "// outside").unwrap();
        std::fs::write(student.join("lib/h.glsl"), "// helper").unwrap();
        let shader = student.join("sao.frag");
        std::fs::write(
            &shader,
            "#version 450\n#include \"lib/h.glsl\"\n#include \"../outside.glsl\"\n#include \"missing.glsl\"\n",
        )
        .unwrap();
        let work = root.join("a/work");
        std::fs::create_dir_all(&work).unwrap();
        std::fs::write(work.join("stale.frag"), "left from before").unwrap();
        let staged = stage(&shader, &work).unwrap();
        assert_eq!(staged, work.join("sao.frag"));
        assert_eq!(
            std::fs::read_to_string(work.join("lib/h.glsl")).unwrap(),
            "// helper"
        );
        assert!(
            !work.join("stale.frag").exists(),
            "the folder is emptied first"
        );
        assert!(
            !root.join("a/outside.glsl").exists(),
            "nothing is copied above the folder"
        );
        assert!(!work.join("missing.glsl").exists());
        let mut names: Vec<_> = std::fs::read_dir(&work)
            .unwrap()
            .map(|e| e.unwrap().file_name().into_string().unwrap())
            .collect();
        names.sort();
        assert_eq!(names, ["lib", "sao.frag"]);
        std::fs::remove_dir_all(&root).unwrap();
    }

    #[test]
    fn a_file_that_cannot_be_read_is_named() {
        let root = scratch("missing");
        let missing = root.join("nope/sao.frag");
        let e = stage(&missing, &root.join("work")).unwrap_err();
        assert!(format!("{e:#}").contains("nope/sao.frag"), "{e:#}");
        std::fs::remove_dir_all(&root).unwrap();
    }
}
