//! `render --camera-path N`: N frames along the bench's camera path (`bench --camera-path`: an
//! orbit to the left around the scene camera's target while closing in), each written beside
//! `--out` with its number. An accumulating method's history follows the motion from frame to
//! frame, which is what the sequence shows.

use super::output::write_view;
use crate::render::{Engine, View};
use anyhow::Result;
use rust_i18n::t;
use std::path::{Path, PathBuf};

/// The file of frame `i` of `count`: `out`'s stem, `-`, the number with as many digits as the last
/// one's (at least three), `out`'s extension.
pub fn frame_path(out: &Path, i: u32, count: u32) -> PathBuf {
    let digits = (count.saturating_sub(1).max(1).ilog10() + 1).max(3) as usize;
    let stem = out
        .file_stem()
        .map_or_else(|| "frame".to_string(), |s| s.to_string_lossy().into_owned());
    let name = match out.extension() {
        Some(ext) => format!("{stem}-{i:0digits$}.{}", ext.to_string_lossy()),
        None => format!("{stem}-{i:0digits$}"),
    };
    out.with_file_name(name)
}

/// Draws `frames` frames along the path from the engine's camera and writes each; the paths
/// written, first and last.
pub fn run(engine: &mut Engine, view: View, out: &Path, frames: u32) -> Result<(PathBuf, PathBuf)> {
    let start = engine.camera;
    let cameras = crate::tools::bench::camera_path::path(&start, 0, frames);
    let show = std::io::IsTerminal::is_terminal(&std::io::stderr());
    let bar = crate::tools::bench::progress::bar(
        frames as u64,
        "render {bar:40} {pos}/{len} frames [{elapsed_precise} < {eta_precise}]",
        show,
    );
    for (i, camera) in cameras.iter().enumerate() {
        engine.camera = *camera;
        write_view(engine, view, &frame_path(out, i as u32, frames))?;
        bar.inc(1);
    }
    bar.finish_and_clear();
    engine.camera = start;
    let first = frame_path(out, 0, frames);
    let last = frame_path(out, frames - 1, frames);
    crate::outln!(
        "{}",
        t!(
            "render.wrote_path",
            frames = frames,
            first = first.display(),
            last = last.display()
        )
    );
    Ok((first, last))
}

#[cfg(test)]
mod tests {
    use super::frame_path;
    use std::path::Path;

    #[test]
    fn frames_are_numbered_beside_the_output_with_enough_digits() {
        let out = Path::new("out/frame.png");
        assert_eq!(frame_path(out, 0, 60), Path::new("out/frame-000.png"));
        assert_eq!(frame_path(out, 59, 60), Path::new("out/frame-059.png"));
        assert_eq!(frame_path(out, 1234, 2000), Path::new("out/frame-1234.png"));
        assert_eq!(frame_path(out, 999, 1000), Path::new("out/frame-999.png"));
        assert_eq!(
            frame_path(Path::new("ao.pfm"), 7, 8),
            Path::new("ao-007.pfm")
        );
    }
}
