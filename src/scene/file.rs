//! Reading a scene file: its values, where each is written (for errors that point at a line), and
//! its meshes found next to it before anywhere else.

use super::check::Issue;
use super::desc::SceneDesc;
use super::places::KeyPlaces;
use anyhow::{bail, Context as _, Result};
use std::path::{Path, PathBuf};

/// The largest scene file read: scenes are a few kilobytes, so anything bigger (or endless, such as
/// `/dev/zero`) is the wrong file.
pub const MAX_SCENE_BYTES: u64 = 1 << 20;

/// A scene as read from a file, before any flag changes it.
#[derive(Clone, Debug)]
pub struct SceneFile {
    pub path: PathBuf,
    pub desc: SceneDesc,
    text: String,
    places: KeyPlaces,
}

impl SceneFile {
    /// Reads and parses `path` (unchecked: flags may still replace values). Relative mesh paths that
    /// name a file beside the scene file resolve to that file, so a file of the same name in the
    /// working folder or in `Res/` never replaces the scene's own mesh.
    pub fn read(path: &Path) -> Result<SceneFile> {
        let shown = path.display();
        let bytes = crate::io::read_capped(path, MAX_SCENE_BYTES)
            .with_context(|| rust_i18n::t!("scene.cannot_read"))?;
        if bytes.is_empty() {
            bail!("{}", rust_i18n::t!("scene.empty", path = shown));
        }
        let text = String::from_utf8(bytes).map_err(|e| {
            let byte = e.utf8_error().valid_up_to();
            anyhow::anyhow!(
                "{}",
                rust_i18n::t!("scene.not_utf8", path = shown, byte = byte)
            )
        })?;
        let mut desc: SceneDesc = toml::from_str(&text)
            .map_err(|e| anyhow::anyhow!("{}: invalid scene file: {e}", path.display()))?;
        desc.ao.written = super::ao_defaults::WrittenKeys::in_scene_text(&text);
        let folder = path.parent().unwrap_or(Path::new(""));
        for o in &mut desc.objects {
            let mesh = Path::new(&o.mesh);
            if mesh.is_absolute() {
                continue;
            }
            let beside = folder.join(mesh);
            if !beside.is_file() {
                continue;
            }
            let beside = std::path::absolute(&beside)
                .with_context(|| format!("{}: cannot make the path absolute", beside.display()))?;
            // A UTF-8 absolute path is spelled in `mesh` itself; any path is also kept as found.
            if let Some(s) = beside.to_str() {
                o.mesh = s.to_string();
            }
            desc.mesh_files.insert(o.mesh.clone(), beside);
        }
        let places = KeyPlaces::of(&text);
        Ok(SceneFile {
            path: path.to_path_buf(),
            desc,
            text,
            places,
        })
    }

    /// "FILE:LINE:COL" of `key`'s value, if the file writes it.
    pub fn place(&self, key: &str) -> Option<String> {
        let (line, col) = self.places.line_col(key, &self.text)?;
        Some(format!("{}:{line}:{col}", self.path.display()))
    }

    /// An issue as "FILE:LINE:COL: key = value: message"; a key the file does not write is a
    /// default, shown at its table's header when there is one.
    pub fn describe(&self, issue: &Issue) -> String {
        let shown = self.path.display();
        match self.places.nearest_line_col(&issue.key, &self.text) {
            Some((line, col, true)) => format!("{shown}:{line}:{col}: {issue}"),
            Some((line, col, false)) => {
                format!("{shown}:{line}:{col}: {issue} (not written in this table: the default)")
            }
            None => format!("{shown}: {issue} (not written in the file: the default)"),
        }
    }
}

impl SceneDesc {
    /// Reads, clamps (warning on stderr) and checks a scene file; errors name FILE:LINE:COL.
    pub fn load(path: &Path) -> Result<SceneDesc> {
        let mut file = SceneFile::read(path)?;
        for w in file.desc.clamp_values() {
            eprintln!("warning: {}", file.describe(&w));
        }
        let errors = file.desc.errors();
        if !errors.is_empty() {
            let lines: Vec<String> = errors.iter().map(|e| file.describe(e)).collect();
            bail!("{}", lines.join("\n"));
        }
        Ok(file.desc)
    }

    /// Parses and checks scene text (meshes resolve through `Res/`); errors name LINE:COL.
    pub fn parse(text: &str) -> Result<SceneDesc> {
        let mut desc: SceneDesc = toml::from_str(text)?;
        desc.ao.written = super::ao_defaults::WrittenKeys::in_scene_text(text);
        let errors = desc.errors();
        if !errors.is_empty() {
            let places = KeyPlaces::of(text);
            let lines: Vec<String> = errors
                .iter()
                .map(|e| match places.line_col(&e.key, text) {
                    Some((l, c)) => format!("{l}:{c}: {e}"),
                    None => e.to_string(),
                })
                .collect();
            bail!("{}", lines.join("\n"));
        }
        Ok(desc)
    }
}
