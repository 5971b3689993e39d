//! Loading a model file by its kind: glTF 2.0 (`.gltf`, `.glb`; `super::gltf_file`) or Wavefront OBJ
//! (any other name; `super::obj`). What a loader skipped is printed on stderr once per process.

use super::mesh::{MeshBuffer, MeshData, StaticMesh};
use anyhow::{bail, Result};
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
