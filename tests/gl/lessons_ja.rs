//! The Japanese lessons (`lessons/ja/`) stay in step with the English ones: the same pages, the same
//! heading structure, the same code blocks (every checkpoint command and listing, verbatim once the
//! comments, which each language writes in its own words, are taken out) and the same images;
//! `README.ja.md` and `README.md` link each other. Figures with words on them have a Japanese twin in
//! an `img/ja/` folder, which the Japanese pages show instead.

use std::collections::BTreeSet;
use std::path::{Component, Path, PathBuf};

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

/// Markdown pages below `dir` (relative paths), skipping `skip` folders.
fn pages(dir: &Path, skip: &str) -> BTreeSet<PathBuf> {
    let mut out = BTreeSet::new();
    let mut stack = vec![dir.to_path_buf()];
    while let Some(d) = stack.pop() {
        for e in std::fs::read_dir(&d).unwrap_or_else(|e| panic!("{}: {e}", d.display())) {
            let p = e.unwrap().path();
            if p.is_dir() {
                if p.file_name().is_some_and(|n| n != skip) {
                    stack.push(p);
                }
            } else if p.extension().is_some_and(|x| x == "md") {
                out.insert(p.strip_prefix(dir).unwrap().to_path_buf());
            }
        }
    }
    out
}

/// What must agree between a page and its translation.
#[derive(Debug, Default)]
struct Outline {
    /// Heading levels, in order.
    headings: Vec<usize>,
    /// Fenced code blocks without their comments (`comment_free`).
    code: Vec<String>,
    /// Image targets resolved against the page's folder, in order.
    images: Vec<PathBuf>,
}

/// `a/b/../c` → `a/c` without touching the file system.
fn normalise(p: &Path) -> PathBuf {
    let mut out = PathBuf::new();
    for c in p.components() {
        match c {
            Component::ParentDir => {
                out.pop();
            }
            Component::CurDir => {}
            c => out.push(c),
        }
    }
    out
}

/// Where the comment of `line` starts in a block of language `lang`: `//` outside a string in
/// GLSL, Rust and C++; `#` at the start or after a space in shell and TOML. Other blocks (formulas,
/// output) have no comments.
fn comment_start(lang: &str, line: &str) -> Option<usize> {
    match lang {
        "glsl" | "rust" | "cpp" | "c++" | "c" => line
            .match_indices("//")
            .map(|(i, _)| i)
            .find(|&i| line[..i].matches('"').count().is_multiple_of(2)),
        "sh" | "bash" | "toml" => line.char_indices().find_map(|(i, c)| {
            let starts = i == 0 || line[..i].ends_with(char::is_whitespace);
            let ends = line[i + 1..].is_empty() || line[i + 1..].starts_with(char::is_whitespace);
            (c == '#' && starts && ends).then_some(i)
        }),
        _ => None,
    }
}

/// A code block without its comments: each line cut at its comment and trimmed at the end, lines
/// left empty dropped (so a comment may take more or fewer lines in a translation). A block without a
/// language (formulas, diagrams) keeps only its symbols (`formula_symbols`): its words are translated.
fn comment_free(lang: &str, body: &str) -> String {
    if lang.is_empty() || lang == "text" {
        return body
            .lines()
            .map(formula_symbols)
            .filter(|l| !l.is_empty())
            .map(|l| l + "\n")
            .collect();
    }
    let mut out = String::new();
    for line in body.lines() {
        let code = match comment_start(lang, line) {
            Some(i) => &line[..i],
            None => line,
        }
        .trim_end();
        if !code.is_empty() {
            out.push_str(code);
            out.push('\n');
        }
    }
    out
}

/// What a translation of a formula line keeps: every symbol, number and one-letter variable, without
/// spaces, words (two letters or more, hyphenated ones too) and Japanese.
fn formula_symbols(line: &str) -> String {
    let mut out = String::new();
    let mut word = String::new();
    let flush = |word: &mut String, out: &mut String| {
        if word.chars().filter(char::is_ascii_alphabetic).count() < 2 {
            out.push_str(word);
        }
        word.clear();
    };
    for c in line.chars() {
        let joins = !word.is_empty() && c == '-';
        if c.is_ascii_alphabetic() || joins {
            word.push(c);
            continue;
        }
        flush(&mut word, &mut out);
        if !c.is_whitespace() && !is_japanese(c) {
            out.push(c);
        }
    }
    flush(&mut word, &mut out);
    out
}

fn outline(file: &Path) -> Outline {
    let text = std::fs::read_to_string(file).unwrap_or_else(|e| panic!("{}: {e}", file.display()));
    let dir = file.parent().unwrap();
    let mut o = Outline::default();
    // The open fence: its marker, its language and the body so far.
    let mut fence: Option<(String, String, String)> = None;
    for line in text.lines() {
        let t = line.trim_start();
        if let Some((marker, lang, body)) = &mut fence {
            if t.starts_with(marker.as_str()) {
                o.code.push(comment_free(lang, body));
                fence = None;
            } else {
                body.push_str(line);
                body.push('\n');
            }
            continue;
        }
        if t.starts_with("```") || t.starts_with("~~~") {
            fence = Some((t[..3].to_string(), t[3..].trim().to_string(), String::new()));
            continue;
        }
        let hashes = line.chars().take_while(|c| *c == '#').count();
        if hashes > 0 && line[hashes..].starts_with(' ') {
            o.headings.push(hashes);
        }
        let mut rest = line;
        while let Some(i) = rest.find("![") {
            rest = &rest[i + 2..];
            let Some(j) = rest.find("](") else { break };
            let after = &rest[j + 2..];
            let Some(k) = after.find(')') else { break };
            let target = after[..k].split_whitespace().next().unwrap_or("");
            if !target.contains("://") {
                o.images.push(normalise(&dir.join(target)));
            }
            rest = &after[k..];
        }
    }
    o
}

#[test]
fn japanese_lessons_match_the_english_ones() {
    let en_dir = root().join("lessons");
    let ja_dir = en_dir.join("ja");
    let en = pages(&en_dir, "ja");
    let ja = pages(&ja_dir, "");
    let missing: Vec<_> = en.difference(&ja).collect();
    let extra: Vec<_> = ja.difference(&en).collect();
    assert!(
        missing.is_empty() && extra.is_empty(),
        "lessons/ja/ lacks {missing:?} and has no English original for {extra:?}"
    );
    let mut problems = Vec::new();
    for page in &en {
        let (e, j) = (outline(&en_dir.join(page)), outline(&ja_dir.join(page)));
        let name = page.display();
        if e.headings != j.headings {
            problems.push(format!(
                "{name}: headings {:?} (en) vs {:?} (ja)",
                e.headings, j.headings
            ));
        }
        if e.code != j.code {
            let first = e.code.iter().zip(&j.code).position(|(a, b)| a != b);
            problems.push(format!(
                "{name}: code blocks differ ({} en, {} ja; first difference at block {first:?})",
                e.code.len(),
                j.code.len()
            ));
        }
        let j_as_en: Vec<PathBuf> = j.images.iter().map(|p| english_twin(p)).collect();
        if e.images != j_as_en {
            problems.push(format!(
                "{name}: images {:?} (en) vs {:?} (ja)",
                e.images, j.images
            ));
        }
        for img in &j.images {
            if !img.is_file() {
                problems.push(format!("{name}: image {} does not exist", img.display()));
            }
        }
    }
    assert!(problems.is_empty(), "{}", problems.join("\n"));
}

/// The English figure a Japanese one translates: `…/img/ja/x.png` → `…/img/x.png`; other paths as they are.
fn english_twin(p: &Path) -> PathBuf {
    let in_img_ja = p.parent().is_some_and(|d| {
        d.file_name().is_some_and(|n| n == "ja")
            && d.parent()
                .and_then(Path::file_name)
                .is_some_and(|n| n == "img")
    });
    match (in_img_ja, p.file_name()) {
        (true, Some(name)) => p.parent().unwrap().parent().unwrap().join(name),
        _ => p.to_path_buf(),
    }
}

/// Figures with English words drawn on them (labels, axis titles; not command options): the Japanese
/// pages show their `img/ja/` twins, drawn by `figures.py --lang ja`.
const FIGURES_WITH_WORDS: &[&str] = &[
    "lessons/img/depth-curve.png",
    "lessons/img/spiral.png",
    "lessons/img/mip-chain.png",
    "lessons/img/mistakes-sao.png",
    "lessons/img/blur-edges.png",
    "lessons/methods/img/crytek-rescale.png",
    "lessons/methods/img/hbao-tangent-fix.png",
    "lessons/methods/img/vbao-thickness.png",
    "lessons/methods/img/sao-blurs.png",
    // The bench's error maps: their colour scale is labelled.
    "lessons/methods/img/bench-sao-lesson-error.png",
    "lessons/methods/img/bench-sao-error.png",
    "lessons/methods/img/bench-crytek-error.png",
    "lessons/methods/img/bench-hemisphere-error.png",
    "lessons/methods/img/bench-hbao-error.png",
    "lessons/methods/img/bench-angle-based-error.png",
    "lessons/methods/img/bench-gtao-error.png",
    "lessons/methods/img/bench-vbao-error.png",
    "lessons/methods/img/bench-rtao-error.png",
];

/// Every `.png` a page points at, as an image or a link, resolved against the page's folder.
fn png_targets(file: &Path) -> Vec<PathBuf> {
    let text = std::fs::read_to_string(file).unwrap_or_else(|e| panic!("{}: {e}", file.display()));
    let dir = file.parent().unwrap();
    let mut out = Vec::new();
    for (i, _) in text.match_indices("](") {
        let after = &text[i + 2..];
        let Some(k) = after.find(')') else { continue };
        let target = after[..k].split_whitespace().next().unwrap_or("");
        if target.ends_with(".png") && !target.contains("://") {
            out.push(normalise(&dir.join(target)));
        }
    }
    out
}

/// The Markdown pages of the course in both languages and the READMEs.
fn course_pages() -> Vec<PathBuf> {
    let lessons = root().join("lessons");
    let mut out: Vec<PathBuf> = pages(&lessons, "")
        .into_iter()
        .map(|p| lessons.join(p))
        .collect();
    out.push(root().join("README.md"));
    out.push(root().join("README.ja.md"));
    out
}

#[test]
fn every_picture_a_page_shows_exists() {
    let pages = course_pages();
    assert!(pages.len() > 40, "{pages:?}");
    let mut problems = Vec::new();
    for page in &pages {
        for png in png_targets(page) {
            if !png.is_file() {
                problems.push(format!(
                    "{}: {} does not exist",
                    page.display(),
                    png.display()
                ));
            }
        }
    }
    assert!(problems.is_empty(), "{}", problems.join("\n"));
}

#[test]
fn japanese_pages_show_the_japanese_figures() {
    let labelled: BTreeSet<PathBuf> = FIGURES_WITH_WORDS.iter().map(|f| root().join(f)).collect();
    let mut problems = Vec::new();
    for en in &labelled {
        let ja = en
            .parent()
            .unwrap()
            .join("ja")
            .join(en.file_name().unwrap());
        if !en.is_file() || !ja.is_file() {
            problems.push(format!(
                "{} needs itself and {}",
                en.display(),
                ja.display()
            ));
        }
    }
    // Each Japanese twin is of a listed figure, so the list names every figure with words.
    for dir in ["lessons/img/ja", "lessons/methods/img/ja"] {
        for e in std::fs::read_dir(root().join(dir)).unwrap() {
            let p = e.unwrap().path();
            if !labelled.contains(&english_twin(&p)) {
                problems.push(format!(
                    "{} is not the twin of a listed figure",
                    p.display()
                ));
            }
        }
    }
    let japanese = course_pages()
        .into_iter()
        .filter(|p| p.starts_with(root().join("lessons/ja")) || p.ends_with("README.ja.md"));
    for page in japanese {
        for png in png_targets(&page) {
            if labelled.contains(&png) {
                problems.push(format!(
                    "{}: shows {} with English words; its Japanese twin is in img/ja/",
                    page.display(),
                    png.display()
                ));
            }
        }
    }
    assert!(problems.is_empty(), "{}", problems.join("\n"));
}

#[test]
fn a_japanese_figure_stands_for_its_english_twin() {
    assert_eq!(
        english_twin(Path::new("lessons/img/ja/spiral.png")),
        Path::new("lessons/img/spiral.png")
    );
    assert_eq!(
        english_twin(Path::new("lessons/ja/img/spiral.png")),
        Path::new("lessons/ja/img/spiral.png")
    );
    let dir = std::env::temp_dir().join(format!("opengl3d-ja-png-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let page = dir.join("p.md");
    std::fs::write(
        &page,
        "![a](img/a.png) and [b](../b.png \"t\"), [c](c.md)\n",
    )
    .unwrap();
    let found = png_targets(&page);
    std::fs::remove_dir_all(&dir).unwrap();
    assert_eq!(
        found,
        [dir.join("img/a.png"), dir.parent().unwrap().join("b.png")]
    );
}

/// The comments in the fenced code blocks of a page: (line number, the comment without its marker).
fn listing_comments(text: &str) -> Vec<(usize, String)> {
    let mut out = Vec::new();
    let mut fence: Option<(String, String)> = None;
    for (n, line) in text.lines().enumerate() {
        let t = line.trim_start();
        if let Some((marker, lang)) = &fence {
            if t.starts_with(marker.as_str()) {
                fence = None;
            } else if let Some(i) = comment_start(lang, line) {
                let body = line[i..].trim_start_matches(['/', '#']).trim();
                out.push((n + 1, body.to_string()));
            }
            continue;
        }
        if t.starts_with("```") || t.starts_with("~~~") {
            fence = Some((t[..3].to_string(), t[3..].trim().to_string()));
        }
    }
    out
}

/// A comment written in English: no Japanese in it and at least two words of letters only (so
/// `// x = y`, `// dot(D, V)` or a lone identifier pass as code).
fn is_english_prose(comment: &str) -> bool {
    let words = comment
        .split_whitespace()
        .map(|w| w.trim_end_matches([',', '.', ':', ';', '!', '?']))
        .filter(|w| w.len() >= 2 && w.chars().all(|c| c.is_ascii_alphabetic()))
        .count();
    !comment.chars().any(is_japanese) && words >= 2
}

#[test]
fn japanese_listings_comment_in_japanese() {
    let mut problems = Vec::new();
    for page in pages(&root().join("lessons/ja"), "") {
        let file = root().join("lessons/ja").join(&page);
        let text = std::fs::read_to_string(&file).unwrap();
        for (line, comment) in listing_comments(&text) {
            if is_english_prose(&comment) {
                problems.push(format!(
                    "lessons/ja/{}:{line}: an English comment: {comment}",
                    page.display()
                ));
            }
        }
    }
    assert!(problems.is_empty(), "{}", problems.join("\n"));
}

/// Lines of the formula blocks (no language) of a page with two English words or more in a row.
fn english_in_formulas(text: &str) -> Vec<(usize, String)> {
    let mut out = Vec::new();
    let mut fence: Option<String> = None;
    for (n, line) in text.lines().enumerate() {
        let t = line.trim_start();
        if t.starts_with("```") || t.starts_with("~~~") {
            fence = match fence {
                Some(_) => None,
                None => Some(t[3..].trim().to_string()),
            };
            continue;
        }
        if !fence
            .as_deref()
            .is_some_and(|l| l.is_empty() || l == "text")
        {
            continue;
        }
        let words: Vec<bool> = line
            .split(' ')
            .filter(|w| !w.is_empty())
            .map(|w| {
                let w = w.trim_matches(|c: char| "(),:;".contains(c));
                w.len() >= 2 && w.chars().all(|c| c.is_ascii_alphabetic() || c == '-')
            })
            .collect();
        if words.windows(2).any(|p| p[0] && p[1]) {
            out.push((n + 1, line.to_string()));
        }
    }
    out
}

#[test]
fn japanese_formulas_are_written_in_japanese() {
    assert_eq!(
        english_in_formulas(
            "```\nd = A / (D' − B)\nD' = 2D − 1 (back to NDC z)\n```\nback to prose\n"
        ),
        [(3, "D' = 2D − 1 (back to NDC z)".to_string())]
    );
    let mut problems = Vec::new();
    for page in pages(&root().join("lessons/ja"), "") {
        let text = std::fs::read_to_string(root().join("lessons/ja").join(&page)).unwrap();
        for (line, said) in english_in_formulas(&text) {
            problems.push(format!(
                "lessons/ja/{}:{line}: English: {said}",
                page.display()
            ));
        }
    }
    assert!(problems.is_empty(), "{}", problems.join("\n"));
}

#[test]
fn the_comment_check_tells_english_from_code_and_japanese() {
    let page = "```glsl\nfloat r = 1.0; // disc radius in pixels\nx = y; // x = y\n```\n\
                ```sh\ncargo test  # 全部\necho '#1' # run it all\n```\n// outside a listing\n";
    let comments = listing_comments(page);
    let said: Vec<_> = comments.iter().map(|(l, c)| (*l, c.as_str())).collect();
    assert_eq!(
        said,
        [
            (2, "disc radius in pixels"),
            (3, "x = y"),
            (6, "全部"),
            (7, "run it all")
        ]
    );
    let english: Vec<_> = comments
        .iter()
        .filter(|(_, c)| is_english_prose(c))
        .map(|(l, _)| *l)
        .collect();
    assert_eq!(english, [2, 7]);
    assert!(!is_english_prose("dot(D, V) / len"));
    assert!(!is_english_prose("32バイト。count 0は内部ノード"));
}

#[test]
fn readmes_link_each_other() {
    let en = std::fs::read_to_string(root().join("README.md")).unwrap();
    let ja = std::fs::read_to_string(root().join("README.ja.md")).expect("README.ja.md");
    assert!(
        en.contains("](README.ja.md)"),
        "README.md must link README.ja.md"
    );
    assert!(
        ja.contains("](README.md)"),
        "README.ja.md must link README.md"
    );
    let (e, j) = (
        outline(&root().join("README.md")),
        outline(&root().join("README.ja.md")),
    );
    assert_eq!(
        e.code, j.code,
        "README code blocks (the commands) must be the same"
    );
    assert_eq!(e.images, j.images, "README images must be the same");
}

#[test]
fn comments_may_differ_but_code_may_not() {
    let en = "float a = 1.0; // one\n// two lines\n// of comment\nb = \"x//y\";\n";
    let ja = "float a = 1.0; // 一\n// 日本語のコメント\nb = \"x//y\";\n";
    assert_eq!(comment_free("glsl", en), comment_free("glsl", ja));
    assert_eq!(comment_free("glsl", en), "float a = 1.0;\nb = \"x//y\";\n");
    let changed = "float a = 2.0; // one\nb = \"x//y\";\n";
    assert_ne!(comment_free("glsl", en), comment_free("glsl", changed));
    assert_eq!(
        comment_free("sh", "cargo test   # everything\necho '#1'\n"),
        "cargo test\necho '#1'\n"
    );
    // Formulas keep every symbol and variable; their words may be translated.
    assert_eq!(comment_free("", "x = y // 2\n"), "x=y//2\n");
    assert_eq!(
        comment_free("", "D' = 2D − 1   (back to NDC z)\n"),
        comment_free("", "D' = 2D − 1   (NDCのzに戻す)\n")
    );
    assert_ne!(
        comment_free("", "D' = 2D − 1   (back to NDC z)\n"),
        comment_free("", "D' = 2D + 1   (NDCのzに戻す)\n")
    );
    assert_eq!(
        comment_free("", "AO: restore → down-sample → SAO\n"),
        comment_free("", "AO: 復元 → 縮小 → SAO\n")
    );
}

#[test]
fn the_outline_check_notices_a_dropped_code_block_and_a_moved_image() {
    let dir = std::env::temp_dir().join(format!("opengl3d-ja-outline-{}", std::process::id()));
    std::fs::create_dir_all(dir.join("sub")).unwrap();
    let a = dir.join("a.md");
    let b = dir.join("sub/a.md");
    std::fs::write(&a, "# T\n\n```sh\ncargo test\n```\n\n![x](img.png)\n").unwrap();
    std::fs::write(&b, "# T\n\n![x](../img.png)\n").unwrap();
    let (oa, ob) = (outline(&a), outline(&b));
    assert_eq!(oa.images, ob.images, "the same image seen from two folders");
    assert_ne!(oa.code, ob.code, "a dropped code block is seen");
    std::fs::write(&b, "# T\n\n```sh\ncargo test\n```\n\n![x](img.png)\n").unwrap();
    assert_ne!(
        oa.images,
        outline(&b).images,
        "an image link not rewritten for the deeper folder is seen"
    );
    std::fs::remove_dir_all(&dir).unwrap();
}

/// Japanese text: kana, kanji, CJK punctuation and full-width forms.
fn is_japanese(c: char) -> bool {
    matches!(c, '\u{3001}'..='\u{30ff}' | '\u{4e00}'..='\u{9fff}' | '\u{ff01}'..='\u{ffef}')
}

// The glossary (terms, spacing, brackets) is checked by `tests/glossary.rs`, which reads it.
