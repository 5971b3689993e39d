//! Finding files in `Res/`: a list of folders searched in order (a student's folder first, then the
//! project's own `Res/`), so a student folder may hold only the shaders they changed.

use crate::gl::ProgramError;
use std::path::{Path, PathBuf};

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
    pub fn find(&self, name: &str) -> Result<PathBuf, ProgramError> {
        for d in &self.dirs {
            let p = d.join(name);
            if p.is_file() {
                return Ok(p);
            }
        }
        Err(ProgramError::NotFound {
            name: name.to_string(),
            searched: self
                .dirs
                .iter()
                .map(|d| d.display().to_string())
                .collect::<Vec<_>>()
                .join(", "),
        })
    }
    /// Resolves a data path: absolute or existing relative to the working directory as given, else in `Res/`.
    pub fn resolve_data(&self, name: &str) -> PathBuf {
        let p = Path::new(name);
        if p.is_absolute() || p.exists() {
            return p.to_path_buf();
        }
        self.find(name).unwrap_or_else(|_| p.to_path_buf())
    }
}
