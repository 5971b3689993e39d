//! The student's loop: `opengl3d lesson N` runs the engine at step N of the AO lesson, and
//! `opengl3d lesson start DIR` writes a working copy of `Res/` with the lesson's shaders as stubs.

use crate::i18n::Lang;
use crate::render::View;
use crate::res::project_res_dir;
use anyhow::{bail, Result};
use rust_i18n::t;
use std::path::{Path, PathBuf};

/// Number of steps (lessons/01-… to 12-…).
pub const STEPS: u32 = 12;

/// The five shaders the lesson has students write, in the order they are written: `simple.frag`
/// (course section 1.6, the texture display the composite uses too) comes with step 5.
pub const LESSON_SHADERS: [&str; 5] = [
    "sao_restore_depth.frag",
    "sao_down_sampling.frag",
    "simple.frag",
    "sao.frag",
    "sao_blur.frag",
];

/// The step from which `sao.frag`, begun in step 6, computes the occlusion (steps 6 and 7 write its
/// start and show debug views).
pub const SAO_COMPLETE_STEP: u32 = 8;
/// The step that adds the 2×2 smoothing to `sao.frag` (after the occlusion of `SAO_COMPLETE_STEP`).
pub const SAO_SMOOTHING_STEP: u32 = 9;
/// The first step that has the student write a shader (the restore pass); step 1 is maths only.
pub const FIRST_SHADER_STEP: u32 = 2;

/// What step `n` shows: steps 1–5 the linear depth (restore + down-sampling only), 6–10 the raw SAO
/// buffer, 11 the blurred buffer, 12 the composite.
pub fn view_for_step(n: u32) -> Result<View> {
    Ok(match n {
        1..=5 => View::LinearDepth,
        6..=10 => View::AoRaw,
        11 => View::Ao,
        12 => View::Composite,
        _ => bail!("{}", t!("lesson.no_such_step", n = n, steps = STEPS)),
    })
}

/// The shader files step `n` needs the student to have written (begun, for those in
/// `begun_at_step`).
pub fn shaders_for_step(n: u32) -> &'static [&'static str] {
    match n {
        1..=3 => &LESSON_SHADERS[..1],
        4 => &LESSON_SHADERS[..2],
        5 => &LESSON_SHADERS[..3],
        6..=10 => &LESSON_SHADERS[..4],
        _ => &LESSON_SHADERS[..],
    }
}

/// A shader a lesson step has only begun, and the uniforms and samplers its start already reads.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Begun {
    pub file: &'static str,
    pub reads: &'static [&'static str],
}

/// The file of `shaders_for_step(n)` that step `n` has only begun, if any: it can be checked for
/// building, keeping its interface, reading what its start reads and the step's debug output, not
/// for the occlusion. Step 6
/// rebuilds positions and normals (`texDepth`, `ndcToView`); step 7 adds the disc's radius
/// (`saoInfo`).
pub fn begun_at_step(n: u32) -> Option<Begun> {
    let reads: &'static [&'static str] = match n {
        6 => &["texDepth", "ndcToView"],
        7 => &["texDepth", "ndcToView", "saoInfo"],
        _ => return None,
    };
    Some(Begun {
        file: "sao.frag",
        reads,
    })
}

/// Writes the starting folder: every shader and scene of `Res/`, with the lesson's five shaders
/// replaced by stubs that compile, commented in `lang` and pointing to that language's lesson pages
/// (`Res/lesson-stubs/`, `Res/lesson-stubs/ja/`). In Japanese every other file comes from its
/// Japanese twin in `Res/lesson-stubs/ja/` where there is one (the same code, comments translated),
/// so the student reads no English. Existing files are never overwritten. Returns the files written.
pub fn start(dir: &Path, lang: Lang) -> Result<Vec<PathBuf>> {
    let res = project_res_dir();
    let stubs = match lang {
        Lang::En => res.join("lesson-stubs"),
        Lang::Ja => res.join("lesson-stubs").join("ja"),
    };
    crate::io::create_dir_all(&dir.join("scenes"))?;
    let mut written = Vec::new();
    let mut copy = |from: PathBuf, to: PathBuf| -> Result<()> {
        // A symbolic link is never written through (it may lead out of the folder, or nowhere).
        if let Ok(target) = std::fs::read_link(&to) {
            let (path, target) = (to.display(), target.display());
            eprintln!("{}", t!("lesson.kept_link", path = path, target = target));
            return Ok(());
        }
        if to.exists() {
            eprintln!("{}", t!("lesson.kept_existing", path = to.display()));
            return Ok(());
        }
        std::fs::copy(&from, &to)
            .map_err(|e| crate::io::io_error(&to, &format!("copy {} to it", from.display()), &e))?;
        written.push(to);
        Ok(())
    };
    for p in list_dir(&res)? {
        let Some(name) = p.file_name().map(|n| n.to_string_lossy().into_owned()) else {
            continue;
        };
        let is_shader = name.ends_with(".frag") || name.ends_with(".vert");
        if !is_shader || !p.is_file() {
            continue;
        }
        if LESSON_SHADERS.contains(&name.as_str()) {
            copy(stubs.join(&name), dir.join(&name))?;
        } else {
            copy(translated(&stubs, lang, &name, p), dir.join(&name))?;
        }
    }
    for p in list_dir(&res.join("scenes"))? {
        if let Some(name) = p.file_name().map(|n| n.to_string_lossy().into_owned()) {
            let from = translated(&stubs, lang, &format!("scenes/{name}"), p);
            copy(from, dir.join("scenes").join(name))?;
        }
    }
    written.sort();
    Ok(written)
}

/// The file to copy for `original` (at `rel` in `Res/`): its twin in the Japanese stubs' folder
/// when `lang` is Japanese and one exists, else the original.
fn translated(stubs: &Path, lang: Lang, rel: &str, original: PathBuf) -> PathBuf {
    let twin = stubs.join(rel);
    match lang {
        Lang::Ja if twin.is_file() => twin,
        _ => original,
    }
}

/// The paths in folder `dir` (errors name the folder).
fn list_dir(dir: &Path) -> Result<Vec<PathBuf>> {
    let read_error = |e: std::io::Error| crate::io::io_error(dir, "list the folder", &e);
    let mut out = Vec::new();
    for entry in std::fs::read_dir(dir).map_err(read_error)? {
        out.push(entry.map_err(read_error)?.path());
    }
    Ok(out)
}
