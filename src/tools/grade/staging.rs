//! Staging: copying the graded file, and the files it `#include`s, into the step's private folder,
//! so that only this one file of the student's is used.

use crate::gl::preprocess::{include_target, resolve_include, ShaderSource, MAX_SHADER_BYTES};
use crate::gl::ProgramError;
use anyhow::{bail, Context as _, Result};
use std::io::Read as _;
use std::path::{Path, PathBuf};

/// Copies `file` into a fresh `dir`, with the files it `#include`s (resolved next to it, as the
/// engine does, and refused when they lead out of its folder), keeping their relative paths. A
/// missing include is not an error here: building the shader reports it with file:line.
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
    // Loading checks the size and the encoding, naming the student's file.
    let source = ShaderSource::load(file)?;
    copy(file, &to)?;
    for (i, line) in source.text.lines().enumerate() {
        let Some(name) = include_target(line) else {
            continue;
        };
        let src = match resolve_include(file, i + 1, name) {
            Ok(src) => src,
            Err(ProgramError::Io { .. }) => continue,
            Err(refused) => return Err(refused.into()),
        };
        let dst = dir.join(name);
        if let Some(parent) = dst.parent() {
            std::fs::create_dir_all(parent)
                .with_context(|| format!("cannot create {}", parent.display()))?;
        }
        copy(&src, &dst)?;
    }
    Ok(to)
}

/// Copies a file of at most `MAX_SHADER_BYTES` (a larger one, or one that is not a plain file, is
/// refused before it is copied: building the copy would refuse it anyway).
fn copy(from: &Path, to: &Path) -> Result<()> {
    let file =
        std::fs::File::open(from).with_context(|| format!("cannot read {}", from.display()))?;
    let meta = file
        .metadata()
        .with_context(|| format!("cannot read {}", from.display()))?;
    if !meta.is_file() {
        bail!("{}: not a plain file", from.display());
    }
    let mut bytes = Vec::new();
    file.take(MAX_SHADER_BYTES + 1)
        .read_to_end(&mut bytes)
        .with_context(|| format!("cannot read {}", from.display()))?;
    if bytes.len() as u64 > MAX_SHADER_BYTES {
        bail!(
            "{}: over {MAX_SHADER_BYTES} bytes (1 MiB); shader files that big are refused",
            from.display()
        );
    }
    std::fs::write(to, bytes).with_context(|| format!("cannot write {}", to.display()))
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
            "#version 450\n#include \"lib/h.glsl\"\n#include \"missing.glsl\"\n",
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
    fn an_include_out_of_the_folder_is_refused_without_copying_it() {
        let root = scratch("out");
        let student = root.join("student");
        std::fs::create_dir_all(&student).unwrap();
        std::fs::write(root.join("outside.glsl"), "SECRET TEXT").unwrap();
        let shader = student.join("sao.frag");
        std::fs::write(&shader, "#version 450\n\n#include \"../outside.glsl\"\n").unwrap();
        let work = root.join("work");
        let e = format!("{:#}", stage(&shader, &work).unwrap_err());
        assert!(e.contains("student/sao.frag:3"), "{e}");
        assert!(!e.contains("SECRET"), "{e}");
        let names: Vec<_> = std::fs::read_dir(&work)
            .unwrap()
            .map(|e| e.unwrap().file_name().into_string().unwrap())
            .collect();
        assert_eq!(names, ["sao.frag"], "nothing but the shader is copied");
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
