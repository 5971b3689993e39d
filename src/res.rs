//! Finding files in `Res/`: a list of folders searched in order (a student's folder first, then the
//! project's own `Res/`), so a student folder may hold only the shaders they changed.

use std::path::{Path, PathBuf};
use std::time::SystemTime;

/// A file that none of the searched folders holds, or that a folder holds as something other than a
/// readable file (a folder, a symbolic link that leads nowhere or loops): then the search stops
/// there, since taking the next folder's file would silently ignore the student's.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct NotFound {
    pub name: String,
    pub searched: String,
    /// What stands at the name in the first folder that has something there, in words.
    pub blocked: Option<String>,
}

impl std::fmt::Display for NotFound {
    fn fmt(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
        match &self.blocked {
            Some(what) => write!(f, "{what}"),
            None => write!(f, "'{}' not found in {}", self.name, self.searched),
        }
    }
}

impl std::error::Error for NotFound {}

/// What stands at `path` when it is not a file that can be read, in words (`None` when nothing is
/// there, or a readable file is).
pub fn blocking_entry(path: &Path) -> Option<String> {
    let link = std::fs::symlink_metadata(path).ok()?;
    let shown = path.display();
    match std::fs::metadata(path) {
        Ok(m) if m.is_file() => None,
        Ok(m) if m.is_dir() => Some(rust_i18n::t!("res.blocked_folder", path = shown).into_owned()),
        Ok(_) => Some(rust_i18n::t!("res.blocked_special", path = shown).into_owned()),
        Err(_) if link.file_type().is_symlink() => {
            Some(rust_i18n::t!("res.blocked_link", path = shown).into_owned())
        }
        Err(e) => Some(format!("{shown}: {e}")),
    }
}

/// When the file was last written (`None` when it cannot be read): the window's and the programs'
/// hot reload compare these.
pub fn modified_time(path: &Path) -> Option<SystemTime> {
    std::fs::metadata(path).and_then(|m| m.modified()).ok()
}

#[derive(Clone, Debug)]
pub struct ResDirs {
    dirs: Vec<PathBuf>,
}

/// The project's own `Res/` folder, in this order: a `Res/` folder beside the executable (a release
/// archive unpacked with it); the source tree's when the executable was built inside it (`cargo run`,
/// `cargo test`: edits to its shaders show at once); else the copy carried in the binary, written
/// once to the user's cache folder. An installed binary never reads the tree it was built from, which
/// may have moved on to other shaders or been deleted.
pub fn project_res_dir() -> PathBuf {
    let exe = std::env::current_exe().ok();
    if let Some(dir) = exe.as_ref().and_then(|p| p.parent().map(|d| d.join("Res"))) {
        if dir.is_dir() {
            return dir;
        }
    }
    let source = Path::new(env!("CARGO_MANIFEST_DIR"));
    if exe.as_ref().is_some_and(|e| e.starts_with(source)) && source.join("Res").is_dir() {
        return source.join("Res");
    }
    if let Some(dir) = crate::res_embedded::extracted_res_dir() {
        return dir;
    }
    PathBuf::from("Res")
}

impl Default for ResDirs {
    fn default() -> Self {
        ResDirs {
            dirs: vec![project_res_dir()],
        }
    }
}

impl ResDirs {
    /// `student` (if any) is searched first, then the project's `Res/`.
    pub fn with_override(student: Option<&Path>) -> ResDirs {
        let mut dirs = Vec::new();
        if let Some(d) = student {
            dirs.push(d.to_path_buf());
        }
        dirs.push(project_res_dir());
        ResDirs { dirs }
    }
    /// Only the given folders, no fallback.
    pub fn only(dirs: Vec<PathBuf>) -> ResDirs {
        ResDirs { dirs }
    }
    pub fn dirs(&self) -> &[PathBuf] {
        &self.dirs
    }
    /// The first folder holding `name`.
    pub fn find(&self, name: &str) -> Result<PathBuf, NotFound> {
        self.find_path(Path::new(name))
    }
    /// Resolves a data path: an absolute path as given, a relative one in the `Res/` folders. The
    /// working directory is never searched: a file there must not silently replace a scene's mesh
    /// (scene files resolve their meshes relative to themselves when they are loaded).
    pub fn resolve_data(&self, name: &Path) -> Result<PathBuf, NotFound> {
        if name.is_absolute() {
            return Ok(name.to_path_buf());
        }
        self.find_path(name)
    }

    /// `find` for a relative path that need not be UTF-8.
    pub fn find_path(&self, name: &Path) -> Result<PathBuf, NotFound> {
        let mut blocked = None;
        for d in &self.dirs {
            let p = d.join(name);
            if p.is_file() {
                return Ok(p);
            }
            blocked = blocking_entry(&p);
            if blocked.is_some() {
                break;
            }
        }
        Err(NotFound {
            blocked,
            name: name.display().to_string(),
            searched: self
                .dirs
                .iter()
                .map(|d| d.display().to_string())
                .collect::<Vec<_>>()
                .join(", "),
        })
    }
}
