//! `--res DIR` is checked before any command runs: a folder that does not exist, is a file, or holds
//! none of the files the command reads from it is an error naming it (otherwise the project's own
//! files would be used without a word, and a student would grade the wrong shaders).

use anyhow::{bail, Result};
use rust_i18n::t;
use std::path::Path;

/// What a command reads from `--res`.
#[derive(Clone, Copy, Debug)]
pub enum ResUse {
    /// Shaders (`*.vert`, `*.frag`, `*.glsl`, also in `ao/`) or scene data (`*.toml`, `*.obj`).
    ShadersOrScenes,
    /// Scene data only (the ray-traced reference draws nothing with GL).
    Scenes,
    /// At least one of these files (a lesson step's shaders).
    AnyOf(&'static [&'static str]),
    /// A folder to write into.
    Folder,
}

/// Fails unless `dir` is a folder holding something `what` reads.
pub fn check_res(dir: &Path, what: ResUse) -> Result<()> {
    let shown = dir.display();
    match std::fs::metadata(dir) {
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => {
            bail!("{}", t!("cli.res_missing", dir = shown))
        }
        Err(e) => {
            let error = crate::i18n::io_cause(&e, &rust_i18n::locale());
            bail!("{}", t!("cli.res_unreadable", dir = shown, error = error))
        }
        Ok(m) if !m.is_dir() => bail!("{}", t!("cli.res_is_file", dir = shown)),
        Ok(_) => {}
    }
    let is_shader = |n: &str| n.ends_with(".vert") || n.ends_with(".frag") || n.ends_with(".glsl");
    let is_scene = |n: &str| {
        [".toml", ".obj", ".gltf", ".glb"]
            .iter()
            .any(|ext| n.ends_with(ext))
    };
    let (found, wanted) = match what {
        ResUse::Folder => return Ok(()),
        ResUse::AnyOf(names) => (
            names.iter().any(|n| dir.join(n).is_file()),
            names.join(", "),
        ),
        ResUse::ShadersOrScenes => (
            has_file(dir, &|n| is_shader(n) || is_scene(n))?,
            t!("cli.wanted_shaders_or_scenes").into_owned(),
        ),
        ResUse::Scenes => (
            has_file(dir, &is_scene)?,
            t!("cli.wanted_scenes").into_owned(),
        ),
    };
    if !found {
        // A wanted name that is a folder or a broken link: say so rather than "holds none".
        let named = |n: &str| is_shader(n) || is_scene(n);
        if let Some(what) = std::fs::read_dir(dir)
            .into_iter()
            .flatten()
            .flatten()
            .filter(|e| named(&e.file_name().to_string_lossy()))
            .find_map(|e| crate::res::blocking_entry(&e.path()))
        {
            bail!("{what}");
        }
        bail!("{}", t!("cli.res_empty", dir = shown, wanted = wanted));
    }
    Ok(())
}

/// Whether `dir` or one of its folders (one level down, like `ao/` and `meshes/`) holds a file whose
/// name passes `wanted`.
fn has_file(dir: &Path, wanted: &dyn Fn(&str) -> bool) -> Result<bool> {
    let cannot_list = |d: &Path, e: std::io::Error| {
        anyhow::anyhow!(
            "{}",
            t!(
                "cli.res_cannot_list",
                dir = d.display(),
                error = crate::i18n::io_cause(&e, &rust_i18n::locale())
            )
        )
    };
    let read = |d: &Path| std::fs::read_dir(d).map_err(|e| cannot_list(d, e));
    for entry in read(dir)? {
        let path = entry.map_err(|e| cannot_list(dir, e))?.path();
        if path.is_dir() {
            for inner in read(&path)? {
                let inner = inner.map_err(|e| cannot_list(&path, e))?.path();
                if inner.is_file() && wanted(&inner.to_string_lossy()) {
                    return Ok(true);
                }
            }
        } else if path.is_file() && wanted(&path.to_string_lossy()) {
            return Ok(true);
        }
    }
    Ok(false)
}
