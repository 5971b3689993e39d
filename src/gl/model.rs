//! Loading a model file by its kind: glTF 2.0 (`.gltf`, `.glb`; `super::gltf_file`) or Wavefront OBJ
//! (any other name; `super::obj`). What a loader skipped is printed on stderr once per process.

use super::mesh::{MeshBuffer, MeshData, StaticMesh};
use anyhow::{bail, Context as _, Result};
use rust_i18n::t;
use std::collections::HashSet;
use std::path::Path;

/// Warnings already printed (a file is often loaded twice: for its bounds, then to draw it).
static PRINTED: std::sync::Mutex<Option<HashSet<String>>> = std::sync::Mutex::new(None);

/// Refuses what is not a regular file before it is opened: a FIFO would block the open until a
/// writer comes, a device such as `/dev/null` or `/dev/zero` holds no model.
fn check_regular(path: &Path) -> Result<()> {
    let shown = path.display();
    let meta = std::fs::metadata(path).map_err(|e| crate::io::io_error(path, "read", &e))?;
    if meta.is_dir() {
        bail!("{}", t!("io.is_folder", path = shown));
    }
    if !meta.is_file() {
        bail!("{}", t!("model.not_regular", path = shown));
    }
    Ok(())
}

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
            t!("model.outside_folder", path = shown, what = what, name = name, dir = dir)
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
        return Err(anyhow::anyhow!("{}", t!("model.not_regular", path = shown_file))
            .context(message.into_owned()));
    }
    crate::io::read_capped(&resolved, limit)
        .with_context(|| t!("model.reference", path = shown, what = what).into_owned())
}

/// Whether a relative path stays in its folder as written: no `..` climbs above where it starts.
fn stays_inside(relative: &Path) -> bool {
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

impl MeshData {
    /// Loads a model file (glTF by its extension, else OBJ) as one triangle mesh; warnings are
    /// printed once per process. Errors name the file (and its line or part).
    pub fn load_model(path: &Path) -> Result<MeshData> {
        check_regular(path)?;
        let (mesh, warnings) = if super::gltf_file::is_gltf_path(path) {
            let m = super::gltf_file::read_gltf(path)?;
            (m.mesh, m.warnings)
        } else {
            let m = super::obj::read_obj(path)?;
            (m.mesh, m.warnings)
        };
        let mut printed = PRINTED.lock().unwrap_or_else(|e| e.into_inner());
        let printed = printed.get_or_insert_with(HashSet::new);
        for w in warnings {
            if printed.insert(w.clone()) {
                eprintln!("{}", t!("render.warning", message = w));
            }
        }
        Ok(mesh)
    }
}

impl MeshBuffer {
    /// Loads a model file into the shared buffers under `name` (once: a second call returns it).
    pub fn load_model(&mut self, name: &str, path: &Path) -> Result<StaticMesh> {
        if let Some(m) = self.get(name) {
            return Ok(m);
        }
        let data = MeshData::load_model(path)?;
        self.add(name, data)
    }
}
