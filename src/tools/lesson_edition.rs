//! `opengl3d lesson edition DIR`: the lesson for a class to work from. The pages (both languages,
//! with their pictures) without the folded answer listings, and in `start/` the starting folder
//! `lesson start` writes (the five lesson shaders as stubs, in the language the command runs in).
//! The grader keeps its own reference shaders inside the binary, so nothing it needs is withheld.

use crate::i18n::Lang;
use anyhow::{bail, Result};
use rust_i18n::t;
use std::path::{Path, PathBuf};

/// What was written.
pub struct Written {
    pub pages: usize,
    /// Folded answers left out, over all pages.
    pub withheld: usize,
}

/// The summaries that mark a folded answer listing on the pages.
const ANSWER_SUMMARIES: [&str; 2] = ["Show the listing", "解答のプログラムリスト"];

/// `page` without its folded answers (a `<details>` block whose summary is one of
/// `ANSWER_SUMMARIES`), each replaced by `note`; other folded blocks stay. Returns the page and
/// how many answers were left out.
pub fn withhold_answers(page: &str, note: &str) -> (String, usize) {
    let mut out = String::with_capacity(page.len());
    let mut withheld = 0;
    let mut lines = page.split_inclusive('\n').peekable();
    while let Some(line) = lines.next() {
        let opens = line.trim_start().starts_with("<details");
        let is_answer = opens
            && lines
                .peek()
                .is_some_and(|next| ANSWER_SUMMARIES.iter().any(|s| next.contains(s)));
        if !is_answer {
            out.push_str(line);
            continue;
        }
        // Skip to the matching </details> (blocks do not nest on the pages; a nested one is
        // counted so that its end does not close the answer early).
        let mut depth = 1;
        for inner in lines.by_ref() {
            let t = inner.trim_start();
            if t.starts_with("<details") {
                depth += 1;
            } else if t.starts_with("</details>") {
                depth -= 1;
                if depth == 0 {
                    break;
                }
            }
        }
        withheld += 1;
        out.push_str(note);
        out.push('\n');
    }
    (out, withheld)
}

/// The lesson pages of the source tree this binary was built from, when they are still there.
fn default_pages() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("lessons")
}

/// Copies `from` into `to` (files and folders; symbolic links are not followed).
fn copy_tree(from: &Path, to: &Path) -> Result<()> {
    crate::io::create_dir_all(to)?;
    let read_error = |e: std::io::Error| crate::io::io_error(from, "list the folder", &e);
    for entry in std::fs::read_dir(from).map_err(read_error)? {
        let entry = entry.map_err(read_error)?;
        let kind = entry.file_type().map_err(read_error)?;
        let (src, dst) = (entry.path(), to.join(entry.file_name()));
        if kind.is_dir() {
            copy_tree(&src, &dst)?;
        } else if kind.is_file() {
            std::fs::copy(&src, &dst).map_err(|e| {
                crate::io::io_error(&dst, &format!("copy {} to it", src.display()), &e)
            })?;
        }
    }
    Ok(())
}

/// The Markdown pages of `dir` (not its subfolders), sorted.
fn pages_in(dir: &Path) -> Result<Vec<PathBuf>> {
    let read_error = |e: std::io::Error| crate::io::io_error(dir, "list the folder", &e);
    let mut pages = Vec::new();
    for entry in std::fs::read_dir(dir).map_err(read_error)? {
        let p = entry.map_err(read_error)?.path();
        if p.extension().is_some_and(|e| e == "md") && p.is_file() {
            pages.push(p);
        }
    }
    pages.sort();
    Ok(pages)
}

/// Writes the class edition into `dir`: `dir/lessons/` (English), `dir/lessons/ja/` (Japanese),
/// `dir/lessons/img/` and `dir/start/` (the stubs, commented in `lang`).
pub fn write(dir: &Path, pages: Option<&Path>, lang: Lang) -> Result<Written> {
    let source = pages.map_or_else(default_pages, Path::to_path_buf);
    if !source.join("README.md").is_file() || !source.join("ja").is_dir() {
        bail!("{}", t!("edition.no_pages", dir = source.display()));
    }
    let mut written = Written {
        pages: 0,
        withheld: 0,
    };
    for (from, to, locale) in [
        (source.clone(), dir.join("lessons"), "en"),
        (source.join("ja"), dir.join("lessons").join("ja"), "ja"),
    ] {
        crate::io::create_dir_all(&to)?;
        let note = t!("edition.withheld", locale = locale);
        for page in pages_in(&from)? {
            let text = std::fs::read_to_string(&page)
                .map_err(|e| crate::io::io_error(&page, "read", &e))?;
            let (text, withheld) = withhold_answers(&text, &note);
            let out = to.join(page.file_name().unwrap_or_default());
            std::fs::write(&out, text).map_err(|e| crate::io::io_error(&out, "write", &e))?;
            written.pages += 1;
            written.withheld += withheld;
        }
    }
    if source.join("img").is_dir() {
        copy_tree(&source.join("img"), &dir.join("lessons").join("img"))?;
    }
    crate::tools::lesson::start(&dir.join("start"), lang)?;
    Ok(written)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn answers_go_and_other_folded_blocks_stay() {
        let page = "# Step\ntext\n<details>\n<summary>Show the listing (try writing it first)</summary>\n\n```glsl\nsecret();\n```\n</details>\n\nmore\n<details>\n<summary>Why</summary>\nkept\n</details>\n";
        let (out, n) = withhold_answers(page, "NOTE");
        assert_eq!(n, 1);
        assert!(!out.contains("secret"), "{out}");
        assert!(out.contains("NOTE\n") && out.contains("kept") && out.contains("more"));
        assert!(out.starts_with("# Step\ntext\nNOTE\n"), "{out}");
    }
}
