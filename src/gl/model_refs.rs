//! The files a model file refers to (a glTF buffer, an OBJ material library), read only where they
//! stay inside the model's folder.

use anyhow::{Context as _, Result};
use rust_i18n::t;
use std::path::Path;

/// Reads `name`, a file a model file `model` refers to (a glTF buffer, an OBJ material library),
/// only where it stays inside the model's folder: `name` must be relative, and resolved (`..` and
/// links followed) it must still lie in that folder and be a regular file; at most `limit` bytes
/// are read. `what` says which reference it is ("buffer 0 (…)") in the error, which names the model.
pub fn read_beside(model: &Path, what: &str, name: &str, limit: u64) -> Result<Vec<u8>> {
    let shown = model.display().to_string();
    let folder = match model.parent() {
        Some(p) if !p.as_os_str().is_empty() => p,
        _ => Path::new("."),
    };
    let outside = || {
        let dir = folder.display();
        anyhow::anyhow!(
            "{}",
            t!(
                "model.outside_folder",
                path = shown,
                what = what,
                name = name,
                dir = dir
            )
        )
    };
    let relative = Path::new(name);
    if relative.has_root() || !stays_inside(relative) {
        return Err(outside());
    }
    let file = folder.join(relative);
    let (Ok(base), Ok(resolved)) = (folder.canonicalize(), file.canonicalize()) else {
        // Missing: the usual error, naming the file the model asked for.
        let e = std::fs::metadata(&file).err();
        let e = e.unwrap_or_else(|| std::io::Error::from(std::io::ErrorKind::NotFound));
        let message = t!("model.reference", path = shown, what = what);
        return Err(crate::io::io_error(&file, "read", &e).context(message.into_owned()));
    };
    if !resolved.starts_with(&base) {
        return Err(outside());
    }
    let meta = std::fs::metadata(&resolved).map_err(|e| crate::io::io_error(&file, "read", &e))?;
    if !meta.is_file() {
        let message = t!("model.reference", path = shown, what = what);
        let shown_file = file.display();
        return Err(
            anyhow::anyhow!("{}", t!("model.not_regular", path = shown_file))
                .context(message.into_owned()),
        );
    }
    crate::io::read_capped(&resolved, limit)
        .with_context(|| t!("model.reference", path = shown, what = what).into_owned())
}

/// Whether a relative path stays in its folder as written: no `..` climbs above where it starts.
pub fn stays_inside(relative: &Path) -> bool {
    use std::path::Component;
    let mut depth = 0usize;
    for c in relative.components() {
        match c {
            Component::Normal(_) => depth += 1,
            Component::CurDir => {}
            Component::ParentDir if depth > 0 => depth -= 1,
            _ => return false,
        }
    }
    true
}
