//! The project's `Res/` folder carried inside the binary, so that an installed grader (`cargo install`,
//! a release archive) works after its source tree is gone. Its files are written once into a folder
//! of the user's cache named by the crate's version and a hash of their contents, and read from there
//! like any `Res/` folder: the shader preprocessor, the hot reload and the error messages all work on
//! real paths.

use include_dir::{include_dir, Dir};
use std::path::{Path, PathBuf};
use std::sync::OnceLock;

static EMBEDDED: Dir<'static> = include_dir!("$CARGO_MANIFEST_DIR/Res");

/// Written last into an extracted folder: a folder without it was interrupted and is written again.
const COMPLETE_MARKER: &str = ".opengl3d-complete";

/// Every embedded file, as (path relative to `Res/`, contents), in a stable order.
pub fn files() -> Vec<(&'static Path, &'static [u8])> {
    fn walk(dir: &'static Dir<'static>, out: &mut Vec<(&'static Path, &'static [u8])>) {
        for f in dir.files() {
            out.push((f.path(), f.contents()));
        }
        for d in dir.dirs() {
            walk(d, out);
        }
    }
    let mut out = Vec::new();
    walk(&EMBEDDED, &mut out);
    out.sort_by(|a, b| a.0.cmp(b.0));
    out
}

/// FNV-1a over the paths and contents: names the extracted folder, so that two builds with different
/// files never share one (stable across Rust versions, unlike `DefaultHasher`).
pub fn content_hash() -> u64 {
    let mut h: u64 = 0xcbf2_9ce4_8422_2325;
    let mut eat = |bytes: &[u8]| {
        for b in bytes {
            h ^= u64::from(*b);
            h = h.wrapping_mul(0x0100_0000_01b3);
        }
    };
    for (path, contents) in files() {
        eat(path.to_string_lossy().as_bytes());
        eat(&[0]);
        eat(&(contents.len() as u64).to_le_bytes());
        eat(contents);
    }
    h
}

/// The folders the embedded files may be written under, best first: the user's cache folder (the
/// XDG convention; `%LOCALAPPDATA%` on Windows), then the system's temporary folder.
fn cache_roots() -> Vec<PathBuf> {
    let var = |name: &str| {
        std::env::var_os(name)
            .filter(|v| !v.is_empty())
            .map(PathBuf::from)
            .filter(|p| p.is_absolute())
    };
    let mut roots = Vec::new();
    if let Some(dir) = var("XDG_CACHE_HOME") {
        roots.push(dir);
    } else if let Some(dir) = var("LOCALAPPDATA") {
        roots.push(dir);
    } else if let Some(home) = var("HOME") {
        roots.push(home.join(".cache"));
    }
    roots.push(std::env::temp_dir());
    roots
}

/// Whether `dir` holds every embedded file with its size (a folder someone pruned is rewritten).
fn is_whole(dir: &Path) -> bool {
    dir.join(COMPLETE_MARKER).is_file()
        && files().iter().all(|(rel, contents)| {
            std::fs::metadata(dir.join(rel))
                .is_ok_and(|m| m.is_file() && m.len() == contents.len() as u64)
        })
}

/// Writes the embedded files into `dir` through a private temporary folder renamed into place, so
/// that two processes starting at once never read a half-written folder.
fn extract_into(dir: &Path) -> std::io::Result<()> {
    let parent = dir.parent().unwrap_or(Path::new("."));
    std::fs::create_dir_all(parent)?;
    let name = dir
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_default();
    let temp = parent.join(format!(".{name}.{}.partial", std::process::id()));
    let _ = std::fs::remove_dir_all(&temp);
    for (rel, contents) in files() {
        let path = temp.join(rel);
        if let Some(p) = path.parent() {
            std::fs::create_dir_all(p)?;
        }
        std::fs::write(&path, contents)?;
    }
    std::fs::write(temp.join(COMPLETE_MARKER), env!("CARGO_PKG_VERSION"))?;
    if dir.exists() {
        // A pruned or interrupted copy: moved aside first (a rename cannot replace a folder).
        let stale = parent.join(format!(".{name}.{}.stale", std::process::id()));
        let _ = std::fs::rename(dir, &stale);
        let _ = std::fs::remove_dir_all(&stale);
    }
    match std::fs::rename(&temp, dir) {
        Ok(()) => Ok(()),
        // Another process won the race: its copy is as good as ours.
        Err(_) if is_whole(dir) => {
            let _ = std::fs::remove_dir_all(&temp);
            Ok(())
        }
        Err(e) => {
            let _ = std::fs::remove_dir_all(&temp);
            Err(e)
        }
    }
}

/// The folder holding the embedded `Res/` files, written on first use (`None` when no cache or
/// temporary folder can be written: said once on stderr).
pub fn extracted_res_dir() -> Option<PathBuf> {
    static DIR: OnceLock<Option<PathBuf>> = OnceLock::new();
    DIR.get_or_init(|| {
        let name = format!("res-{}-{:016x}", env!("CARGO_PKG_VERSION"), content_hash());
        let mut failures = Vec::new();
        for root in cache_roots() {
            let dir = root.join("opengl3d").join(&name);
            if is_whole(&dir) {
                return Some(dir);
            }
            match extract_into(&dir) {
                Ok(()) => return Some(dir),
                Err(e) => failures.push(format!("{}: {e}", dir.display())),
            }
        }
        eprintln!(
            "{}",
            rust_i18n::t!("res.embedded_unwritable", failures = failures.join("; "))
        );
        None
    })
    .clone()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_embedded_files_are_the_source_trees() {
        let res = Path::new(env!("CARGO_MANIFEST_DIR")).join("Res");
        let embedded = files();
        assert!(embedded.len() > 40, "{} files", embedded.len());
        for (rel, contents) in &embedded {
            let on_disk = std::fs::read(res.join(rel)).unwrap();
            assert!(
                on_disk == *contents,
                "{} differs from the source tree",
                rel.display()
            );
        }
        assert!(embedded.iter().any(|(p, _)| p == &Path::new("sao.frag")));
        assert!(embedded
            .iter()
            .any(|(p, _)| p == &Path::new("ao/vbao.frag")));
    }

    #[test]
    fn an_extracted_folder_is_whole_and_a_pruned_one_is_rewritten() {
        let root = std::env::temp_dir().join(format!("opengl3d-res-test-{}", std::process::id()));
        let dir = root.join("res");
        extract_into(&dir).unwrap();
        assert!(is_whole(&dir));
        std::fs::remove_file(dir.join("sao.frag")).unwrap();
        assert!(!is_whole(&dir), "a missing file is noticed");
        extract_into(&dir).unwrap();
        assert!(is_whole(&dir));
        let _ = std::fs::remove_dir_all(&root);
    }
}
