//! Finding files in `Res/`: a list of folders searched in order (a student's folder first, then the
//! project's own `Res/`), so a student folder may hold only the shaders they changed.

use std::path::{Path, PathBuf};
use std::time::SystemTime;

/// A file that none of the searched folders holds.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[error("'{name}' not found in {searched}")]
pub struct NotFound {
    pub name: String,
    pub searched: String,
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

/// The crate's own `Res/` folder (found from the build location, so the binary works from any directory).
pub fn project_res_dir() -> PathBuf {
    let built = Path::new(env!("CARGO_MANIFEST_DIR")).join("Res");
    if built.is_dir() {
        return built;
    }
    // A moved binary: look beside it and in the working directory.
    if let Some(dir) = std::env::current_exe()
        .ok()
        .and_then(|p| p.parent().map(|d| d.join("Res")))
    {
        if dir.is_dir() {
            return dir;
        }
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
        for d in &self.dirs {
            let p = d.join(name);
            if p.is_file() {
                return Ok(p);
            }
        }
        Err(NotFound {
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
