//! Finding the student's file for a step. A step whose file is missing, misnamed, a folder, not a
//! plain file, a link leading out of the folder, or unreadable is "not submitted": it fails, and is
//! never graded on the project's file instead (which would print PASS for an empty folder).

use super::args::Step;
use crate::i18n::Text;
use rust_i18n::t;
use std::path::{Path, PathBuf};

/// The file `step` grades in the student's folder `dir`, or why it counts as not submitted
/// (naming the expected file and the folder looked in).
pub fn find(dir: &Path, step: Step) -> Result<PathBuf, Text> {
    let name = step.file();
    let path = dir.join(name);
    let (shown_dir, shown_path) = (dir.display(), path.display());
    let cannot_read = |e: &std::io::Error| {
        Text::new(|l| {
            t!(
                "grade.cannot_read",
                locale = l,
                path = shown_path,
                error = crate::i18n::io_cause(e, l)
            )
            .into()
        })
    };
    let meta = match std::fs::metadata(&path) {
        Ok(m) => m,
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => {
            return Err(Text::new(|l| {
                let hint = near_names_hint(dir, name, l);
                t!(
                    "grade.no_file",
                    locale = l,
                    name = name,
                    dir = shown_dir,
                    hint = hint
                )
                .into()
            }))
        }
        Err(e) => return Err(cannot_read(&e)),
    };
    if meta.is_dir() {
        return Err(Text::new(|l| {
            t!(
                "grade.is_folder",
                locale = l,
                path = shown_path,
                name = name
            )
            .into()
        }));
    }
    if !meta.is_file() {
        return Err(Text::new(|l| {
            t!("grade.not_plain_file", locale = l, path = shown_path).into()
        }));
    }
    // A link to a file elsewhere would let the grader read (and echo in compiler messages) any file.
    let inside = match (dir.canonicalize(), path.canonicalize()) {
        (Ok(d), Ok(p)) => p.starts_with(d),
        (Err(e), _) => {
            return Err(Text::new(|l| {
                t!(
                    "grade.cannot_read_folder",
                    locale = l,
                    dir = shown_dir,
                    error = crate::i18n::io_cause(&e, l)
                )
                .into()
            }))
        }
        (_, Err(e)) => return Err(cannot_read(&e)),
    };
    if !inside {
        return Err(Text::new(|l| {
            t!(
                "grade.link_outside",
                locale = l,
                path = shown_path,
                dir = shown_dir
            )
            .into()
        }));
    }
    if let Err(e) = std::fs::File::open(&path) {
        return Err(cannot_read(&e));
    }
    Ok(path)
}

/// " (found X: rename it to NAME)" when the folder holds files that look like a misspelt `name`
/// (another case, an extra extension, another extension); "" otherwise. In the language `locale`.
fn near_names_hint(dir: &Path, name: &str, locale: &str) -> String {
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
    let found = near.join(", ");
    t!(
        "grade.near_names",
        locale = locale,
        found = found,
        name = name
    )
    .into()
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
        let e = find(&d, Step::Sao).unwrap_err().en;
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
        let e = find(&d.join("student"), Step::Sao).unwrap_err().en;
        assert!(e.contains("is a folder"), "{e}");
        std::fs::write(d.join("outside.frag"), "#version 450").unwrap();
        std::os::unix::fs::symlink(d.join("outside.frag"), d.join("student/sao_blur.frag"))
            .unwrap();
        let e = find(&d.join("student"), Step::Blur).unwrap_err().en;
        assert!(e.contains("link to a file outside"), "{e}");
        std::fs::write(d.join("student/sao_restore_depth.frag"), "#version 450").unwrap();
        assert!(find(&d.join("student"), Step::Restore).is_ok());
        std::fs::remove_dir_all(&d).unwrap();
    }
}
