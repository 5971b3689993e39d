//! Writing a class's files: the kind's own module writes them (the shared pieces are in `mod.rs`).

use super::{actions, classroom50, ClassroomKind, ClassroomOptions};
use anyhow::Result;
use std::path::{Path, PathBuf};

/// Writes what `options.kind` needs into `dir`; returns the files written.
pub fn start(dir: &Path, options: &ClassroomOptions) -> Result<Vec<PathBuf>> {
    let mut written = match options.kind {
        ClassroomKind::Classroom50 => classroom50::start(dir, options)?,
        ClassroomKind::Actions => actions::start(dir, options)?,
    };
    written.sort();
    Ok(written)
}
