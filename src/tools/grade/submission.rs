//! Finding the student's file for a step. A step whose file is missing, misnamed, a folder, not a
//! plain file, a link leading out of the folder, or unreadable is "not submitted": it fails, and is
//! never graded on the project's file instead (which would print PASS for an empty folder).

use super::args::Step;
use std::path::{Path, PathBuf};

/// The file `step` grades in the student's folder `dir`, or why it counts as not submitted
/// (naming the expected file and the folder looked in).
pub fn find(dir: &Path, step: Step) -> Result<PathBuf, String> {
    let name = step.file();
    let path = dir.join(name);
    let meta = match std::fs::metadata(&path) {
        Ok(m) => m,
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => {
            return Err(format!(
                "no {name} in {}{}",
                dir.display(),
                near_names_hint(dir, name)
            ))
        }
        Err(e) => return Err(format!("cannot read {}: {e}", path.display())),
    };
    if meta.is_dir() {
        return Err(format!(
            "{} is a folder; the shader must be a file named {name}",
            path.display()
        ));
    }
    if !meta.is_file() {
        return Err(format!("{} is not a plain file", path.display()));
    }
    // A link to a file elsewhere would let the grader read (and echo in compiler messages) any file.
    let inside = match (dir.canonicalize(), path.canonicalize()) {
        (Ok(d), Ok(p)) => p.starts_with(d),
        (Err(e), _) => return Err(format!("cannot read folder {}: {e}", dir.display())),
        (_, Err(e)) => return Err(format!("cannot read {}: {e}", path.display())),
    };
    if !inside {
        return Err(format!(
            "{} is a link to a file outside {}",
            path.display(),
            dir.display()
        ));
    }
    if let Err(e) = std::fs::File::open(&path) {
        return Err(format!("cannot read {}: {e}", path.display()));
    }
    Ok(path)
}

/// " (found X: rename it to NAME)" when the folder holds files that look like a misspelt `name`
/// (another case, an extra extension, another extension); "" otherwise.
fn near_names_hint(dir: &Path, name: &str) -> String {
    let Ok(entries) = std::fs::read_dir(dir) else {
        return String::new();
    };
    let lower = name.to_lowercase();
    let stem = lower.split('.').next().unwrap_or(&lower).to_string();
    let mut near: Vec<String> = entries
        .filter_map(|e| e.ok()?.file_name().into_string().ok())
        .filter(|f| {
            let f = f.to_lowercase();
            f != lower && (f.starts_with(&lower) || f.split('.').next() == Some(stem.as_str()))
        })
        .collect();
    if near.is_empty() {
        return String::new();
    }
    near.sort();
    format!(" (found {}: rename it to {name})", near.join(", "))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn scratch(name: &str) -> PathBuf {
        let d =
            std::env::temp_dir().join(format!("opengl3d-submission-{name}-{}", std::process::id()));
        match std::fs::remove_dir_all(&d) {
            Err(e) if e.kind() != std::io::ErrorKind::NotFound => panic!("{}: {e}", d.display()),
            _ => {}
        }
        std::fs::create_dir_all(&d).unwrap();
        d
    }

    #[test]
    fn a_missing_file_names_the_file_the_folder_and_near_names() {
        let d = scratch("missing");
        std::fs::write(d.join("SAO.frag.txt"), "x").unwrap();
        std::fs::write(d.join("sao_blur.frag"), "x").unwrap();
        let e = find(&d, Step::Sao).unwrap_err();
        assert!(e.starts_with("no sao.frag in "), "{e}");
        assert!(e.contains(&d.display().to_string()), "{e}");
        assert!(
            e.contains("found SAO.frag.txt: rename it to sao.frag"),
            "{e}"
        );
        assert!(!e.contains("sao_blur"), "{e}");
        std::fs::remove_dir_all(&d).unwrap();
    }

    #[test]
    #[cfg(unix)]
    fn a_folder_or_a_link_out_is_not_a_submission() {
        let d = scratch("folder");
        std::fs::create_dir_all(d.join("student/sao.frag")).unwrap();
        let e = find(&d.join("student"), Step::Sao).unwrap_err();
        assert!(e.contains("is a folder"), "{e}");
        std::fs::write(d.join("outside.frag"), "#version 450").unwrap();
        std::os::unix::fs::symlink(d.join("outside.frag"), d.join("student/sao_blur.frag"))
            .unwrap();
        let e = find(&d.join("student"), Step::Blur).unwrap_err();
        assert!(e.contains("link to a file outside"), "{e}");
        std::fs::write(d.join("student/sao_restore_depth.frag"), "#version 450").unwrap();
        assert!(find(&d.join("student"), Step::Restore).is_ok());
        std::fs::remove_dir_all(&d).unwrap();
    }
}
