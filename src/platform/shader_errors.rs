//! The window's list of shader errors (overlay, title, console): each kept until the file it names
//! is saved and builds again; and the stamps that notice a student's shader being saved.

use crate::gl::ProgramError;
use crate::res::{modified_time as mtime, ResDirs};
use std::path::{Path, PathBuf};
use std::time::SystemTime;

/// Shader errors on screen, each kept until the file it names is saved and builds again.
#[derive(Default)]
pub struct ShaderErrors {
    pub entries: Vec<ShaderErrorEntry>,
}

pub struct ShaderErrorEntry {
    /// The file whose change may fix the error (None: only a forced rebuild clears it).
    pub file: Option<PathBuf>,
    pub stamp: Option<SystemTime>,
    pub text: String,
}

/// The file an error points at.
fn error_file(e: &ProgramError) -> Option<PathBuf> {
    match e {
        ProgramError::Io { path, .. }
        | ProgramError::Encoding { path }
        | ProgramError::NoVersion { path }
        | ProgramError::Compile { path, .. }
        | ProgramError::IncludeCycle { path, .. }
        | ProgramError::Storage { path, .. } => Some(PathBuf::from(path)),
        ProgramError::Link { frag, .. } => Some(PathBuf::from(frag)),
        ProgramError::NotFound(_) | ProgramError::Gl(_) => None,
    }
}

impl ShaderErrors {
    pub fn is_empty(&self) -> bool {
        self.entries.is_empty()
    }
    pub fn lines(&self) -> Vec<String> {
        self.entries.iter().map(|e| e.text.clone()).collect()
    }
    pub fn text(&self) -> String {
        self.lines().join("\n")
    }
    pub fn clear(&mut self) {
        self.entries.clear();
    }
    /// Records `errors`, replacing older ones about the same files; true when any text is new.
    pub fn record(&mut self, errors: &[ProgramError]) -> bool {
        let batch: Vec<(Option<PathBuf>, String)> = errors
            .iter()
            .map(|e| (error_file(e), e.to_string()))
            .collect();
        let new = batch
            .iter()
            .any(|(_, t)| !self.entries.iter().any(|x| &x.text == t));
        self.entries
            .retain(|x| x.file.is_none() || !batch.iter().any(|(f, _)| *f == x.file));
        for (file, text) in batch {
            if !self.entries.iter().any(|x| x.text == text) {
                self.entries.push(ShaderErrorEntry {
                    stamp: file.as_deref().and_then(mtime),
                    file,
                    text,
                });
            }
        }
        new
    }
    /// Records any error: a shader error with its file, anything else as text (cleared by a forced
    /// rebuild). True when the text is new.
    pub fn record_any(&mut self, e: &anyhow::Error) -> bool {
        if let Some(p) = e.downcast_ref::<ProgramError>() {
            return self.record(std::slice::from_ref(p));
        }
        let text = format!("{e:#}");
        let new = !self.entries.iter().any(|x| x.text == text);
        if new {
            self.entries.push(ShaderErrorEntry {
                file: None,
                stamp: None,
                text,
            });
        }
        new
    }
    /// Drops errors whose file changed since they were recorded and did not fail again (`still`).
    pub fn drop_fixed(&mut self, still: &[ProgramError]) {
        let failing: Vec<Option<PathBuf>> = still.iter().map(error_file).collect();
        self.entries.retain(|x| match &x.file {
            None => true,
            Some(f) => mtime(f) == x.stamp || failing.contains(&x.file),
        });
    }
}

/// Shader files of the student's folders, to notice when a broken start-up shader is saved again.
pub fn shader_stamps(res: &ResDirs) -> Vec<(PathBuf, Option<SystemTime>)> {
    fn walk(dir: &Path, depth: u32, out: &mut Vec<(PathBuf, Option<SystemTime>)>) {
        let Ok(entries) = std::fs::read_dir(dir) else {
            return;
        };
        for e in entries.flatten() {
            let p = e.path();
            if p.is_dir() {
                if depth > 0 {
                    walk(&p, depth - 1, out);
                }
            } else if p
                .extension()
                .is_some_and(|x| matches!(x.to_str(), Some("vert" | "frag" | "glsl")))
            {
                let t = mtime(&p);
                out.push((p, t));
            }
        }
    }
    let mut out = Vec::new();
    // The last folder is the project's own Res/.
    let dirs = res.dirs();
    for d in &dirs[..dirs.len().saturating_sub(1)] {
        walk(d, 3, &mut out);
    }
    out.sort();
    out
}
