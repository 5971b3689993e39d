//! What can go wrong building a program, each error naming its file (and line when the compiler gives one).

#[derive(Debug, thiserror::Error)]
pub enum ProgramError {
    /// The cause is part of the message (not a chained source, which would print it twice).
    #[error("{path}: cannot read shader file: {cause}")]
    Io { path: String, cause: std::io::Error },
    #[error("{path}: shader file is neither UTF-8, UTF-16 nor Shift-JIS text; save it as UTF-8")]
    Encoding { path: String },
    #[error("{path}: no '#version' line (the course's shaders start with '#version 450')")]
    NoVersion { path: String },
    #[error("{}", .messages.join("\n"))]
    Compile { path: String, messages: Vec<String> },
    /// `#include "{name}"` on line `line` of `path` leads back to `target`, a file already being
    /// expanded (the shader itself, or the included file).
    #[error(
        "{path}:{line}: #include \"{name}\" includes {target} again: an #include cycle (a file \
         cannot include itself, directly or through the file it includes)"
    )]
    IncludeCycle {
        path: String,
        line: usize,
        name: String,
        target: String,
    },
    /// Refused before compiling: the arrays declared at `line` of `path` (or its macros) would
    /// exhaust the driver's memory (`super::shader_storage`).
    #[error("{path}:{line}: {message}")]
    Storage {
        path: String,
        line: usize,
        message: String,
    },
    #[error("{vert} + {frag}: link error: {log}")]
    Link {
        vert: String,
        frag: String,
        log: String,
    },
    #[error(transparent)]
    NotFound(#[from] crate::res::NotFound),
    #[error("GL error: {0}")]
    Gl(String),
}

impl ProgramError {
    /// The first `file:line` this error points at, if any (for an editor or the window's overlay).
    pub fn location(&self) -> Option<String> {
        match self {
            ProgramError::Compile { messages, .. } => messages.first().and_then(|m| {
                let mut parts = m.splitn(3, ':');
                Some(format!("{}:{}", parts.next()?, parts.next()?))
            }),
            ProgramError::Storage { path, line, .. } => Some(format!("{path}:{line}")),
            _ => None,
        }
    }
}
