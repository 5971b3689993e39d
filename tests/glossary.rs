//! Japanese text follows `lessons/ja/glossary.md`, read here so that its list lives in one place: the
//! terms table (each concept, its one term and the variants never used), the writing rules (spacing,
//! units, brackets, ranges, the multiplication sign, full-width letters) and the exceptions table.
//! Checked: the Japanese lesson pages, `docs/**/*.ja.md`, `README.ja.md`, `locales/ja.yml` and the
//! comments of every file `lesson start` writes for a Japanese student. Each problem is reported as
//! file:line with the fix.

use opengl3d::i18n::Lang;
use std::collections::BTreeSet;
use std::path::{Path, PathBuf};

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

fn read(p: &Path) -> String {
    std::fs::read_to_string(p).unwrap_or_else(|e| panic!("{}: {e}", p.display()))
}

/// The rows of the first Markdown table after the heading `## {heading}` (header and rule left out).
fn table(text: &str, heading: &str) -> Vec<Vec<String>> {
    let section = text
        .split(&format!("\n## {heading}\n"))
        .nth(1)
        .unwrap_or_else(|| panic!("glossary: no section ## {heading}"));
    let section = section.split("\n## ").next().unwrap();
    section
        .lines()
        .filter(|l| l.starts_with('|'))
        .skip(2)
        .map(|l| {
            l.trim()
                .trim_matches('|')
                .split('|')
                .map(|c| c.trim().to_string())
                .collect()
        })
        .collect()
}

struct Term {
    term: String,
    variants: Vec<String>,
}

struct Glossary {
    terms: Vec<Term>,
    /// Phrases that may contain a variant (「画面の隅」 is no crease).
    phrases: Vec<String>,
    /// `locales/ja.yml` key prefixes left out, each with the reason the glossary gives.
    skipped_keys: Vec<(String, String)>,
}

fn glossary_from(text: &str) -> Glossary {
    let terms = table(text, "用語")
        .into_iter()
        .map(|cells| {
            assert_eq!(
                cells.len(),
                4,
                "glossary: a row of 用語 has 4 cells: {cells:?}"
            );
            Term {
                term: cells[1].clone(),
                variants: cells[3]
                    .split('、')
                    .map(str::trim)
                    .filter(|v| !v.is_empty())
                    .map(String::from)
                    .collect(),
            }
        })
        .collect();
    let mut phrases = Vec::new();
    let mut skipped_keys = Vec::new();
    for cells in table(text, "例外") {
        assert_eq!(
            cells.len(),
            3,
            "glossary: a row of 例外 has 3 cells: {cells:?}"
        );
        assert!(
            !cells[2].is_empty(),
            "glossary: the exception {cells:?} says no reason"
        );
        match cells[0].as_str() {
            "語句" => phrases.push(cells[1].clone()),
            "キー" => skipped_keys.push((cells[1].clone(), cells[2].clone())),
            _ => {}
        }
    }
    Glossary {
        terms,
        phrases,
        skipped_keys,
    }
}

fn glossary() -> Glossary {
    glossary_from(&read(&root().join("lessons/ja/glossary.md")))
}

/// Japanese text: kana, kanji, CJK punctuation and full-width forms.
fn is_japanese(c: char) -> bool {
    matches!(c, '\u{3000}'..='\u{30ff}' | '\u{4e00}'..='\u{9fff}' | '\u{ff01}'..='\u{ffef}')
}

/// Half-width text that takes no space next to Japanese: letters, digits, the mark left where inline
/// code was, brackets, slashes and quotes.
fn is_half_width(c: char) -> bool {
    c.is_ascii_alphanumeric() || matches!(c, '`' | '(' | ')' | '[' | ']' | '/' | '\'' | '"')
}

/// Units written after a number with one space (longest first, so `ms` is not read as `m`).
const UNITS: &[&str] = &["MiB", "GiB", "KiB", "ms", "cm", "mm", "km", "px", "dB", "m"];

/// `line` with what the rules leave alone taken out: inline code becomes one backtick, link targets
/// go, the inside of 「」 goes, `%{name}` placeholders become `0` (a number is put there) and the
/// glossary's allowed phrases become `＿`.
fn prose(line: &str, phrases: &[String]) -> String {
    let mut s = String::new();
    for (i, part) in line.split('`').enumerate() {
        s.push_str(if i % 2 == 0 { part } else { "`" });
    }
    while let Some(i) = s.find("](") {
        let Some(k) = s[i..].find(')') else { break };
        s.replace_range(i + 1..i + k + 1, "");
    }
    while let Some(i) = s.find("%{") {
        let Some(k) = s[i..].find('}') else { break };
        s.replace_range(i..i + k + 1, "0");
    }
    let mut out = String::new();
    let mut depth = 0usize;
    for c in s.chars() {
        match c {
            '「' => {
                depth += 1;
                out.push(c);
            }
            '」' => {
                depth = depth.saturating_sub(1);
                out.push(c);
            }
            _ if depth > 0 => {}
            _ => out.push(c),
        }
    }
    for p in phrases {
        out = out.replace(p.as_str(), "＿");
    }
    out
}

/// The rules' problems in one line of prose (as `prose` left it), each with its fix.
fn rule_problems(text: &str) -> Vec<String> {
    let mut out = Vec::new();
    let chars: Vec<char> = text.chars().collect();
    for (i, w) in chars.windows(3).enumerate() {
        // An option (`--out`) or a file extension (`.zip`) starts half-width text too.
        let next = chars.get(i + 3).copied().unwrap_or(' ');
        let starts_half_width = is_half_width(w[2])
            || (matches!(w[2], '-' | '.') && (next.is_ascii_alphanumeric() || next == '-'));
        if w[1] == ' '
            && ((is_japanese(w[0]) && starts_half_width)
                || (is_half_width(w[0]) && is_japanese(w[2])))
        {
            out.push(format!(
                "a space between Japanese and half-width text: write \"{}{}\"",
                w[0], w[2]
            ));
        }
    }
    for (i, &c) in chars.iter().enumerate() {
        let before = |k: usize| (i >= k).then(|| chars[i - k]);
        match c {
            '（' | '）' => out.push(format!(
                "a full-width bracket: write \"{}\"",
                if c == '（' { '(' } else { ')' }
            )),
            '〜' => out.push("a wave dash (U+301C): write the course's ～ (U+FF5E)".into()),
            '０'..='９' | 'Ａ'..='Ｚ' | 'ａ'..='ｚ' => {
                let half = char::from_u32(c as u32 - 0xfee0).unwrap();
                out.push(format!("a full-width letter or digit: write \"{half}\""));
            }
            '%' if before(1) == Some(' ') && before(2).is_some_and(|d| d.is_ascii_digit()) => {
                out.push("a space before %: write \"10%\"".into())
            }
            _ => {}
        }
        // A number: `2x2` and a unit written without its space.
        let starts_number = c.is_ascii_digit()
            && !before(1)
                .is_some_and(|b| b.is_ascii_alphanumeric() || matches!(b, '.' | '_' | '-'));
        if starts_number {
            let mut j = i;
            while j < chars.len() && (chars[j].is_ascii_digit() || chars[j] == '.') {
                j += 1;
            }
            let number: String = chars[i..j].iter().collect();
            let rest: String = chars[j..].iter().collect();
            let ends_word = |s: &str| !s.starts_with(|c: char| c.is_ascii_alphanumeric());
            if let Some(r) = rest.strip_prefix('x') {
                if r.starts_with(|c: char| c.is_ascii_digit()) {
                    let tail: String = r.chars().take_while(char::is_ascii_digit).collect();
                    out.push(format!(
                        "\"{number}x{tail}\": write \"{number}×{tail}\" (the multiplication sign)"
                    ));
                }
            }
            if let Some(u) = UNITS
                .iter()
                .find(|u| rest.strip_prefix(**u).is_some_and(ends_word))
            {
                out.push(format!(
                    "\"{number}{u}\": write \"{number} {u}\" (a space before the unit)"
                ));
            }
        }
    }
    out
}

/// The variants in one line of prose, each as (variant, term); a variant inside a term written out
/// (シェーダ in シェーダー) is no use of it.
fn variants_in(text: &str, terms: &[Term]) -> Vec<(String, String)> {
    let mut found = Vec::new();
    for t in terms {
        for v in &t.variants {
            for (at, _) in text.match_indices(v.as_str()) {
                let inside_a_term = terms.iter().any(|other| {
                    other.term.match_indices(v.as_str()).any(|(k, _)| {
                        at >= k
                            && text
                                .get(at - k..)
                                .is_some_and(|rest| rest.starts_with(other.term.as_str()))
                    })
                });
                if !inside_a_term {
                    found.push((v.clone(), t.term.clone()));
                }
            }
        }
    }
    found
}

/// Where the comment of `line` starts in a listing of language `lang` (as `tests/gl/lessons_ja.rs`
/// reads them): `//` outside a string in GLSL, Rust and C++; `#` at the start or after a space in
/// shell and TOML.
fn comment_start(lang: &str, line: &str) -> Option<usize> {
    match lang {
        "glsl" | "frag" | "vert" | "rust" | "cpp" | "c++" | "c" => line
            .match_indices("//")
            .map(|(i, _)| i)
            .find(|&i| line[..i].matches('"').count().is_multiple_of(2)),
        "sh" | "bash" | "toml" | "yml" => line.char_indices().find_map(|(i, c)| {
            let starts = i == 0 || line[..i].ends_with(char::is_whitespace);
            (c == '#' && starts && !line[..i].contains('"')).then_some(i)
        }),
        _ => None,
    }
}

/// A comment without its marker (`//`, `///`, `#`), which takes its space.
fn comment_text(comment: &str) -> String {
    comment.trim_start_matches(['/', '#', '!']).to_string()
}

/// The text of `file` the rules apply to, line by line (1-based): Markdown outside its code blocks
/// plus the comments inside them, a YAML file's comments and values (but those under a skipped key),
/// a shader's or scene's comments.
fn checked_lines(file: &Path, text: &str, g: &Glossary) -> Vec<(usize, String)> {
    let ext = file.extension().and_then(|e| e.to_str()).unwrap_or("");
    let mut out = Vec::new();
    let mut fence: Option<(String, String)> = None;
    for (n, line) in text.lines().enumerate() {
        let piece = match ext {
            "md" => {
                let t = line.trim_start();
                if let Some((marker, lang)) = &fence {
                    if t.starts_with(marker.as_str()) {
                        fence = None;
                        continue;
                    }
                    comment_start(lang, line).map(|i| comment_text(&line[i..]))
                } else if t.starts_with("```") || t.starts_with("~~~") {
                    fence = Some((t[..3].to_string(), t[3..].trim().to_string()));
                    continue;
                } else {
                    Some(line.to_string())
                }
            }
            "yml" => match comment_start("yml", line) {
                Some(i) => Some(comment_text(&line[i..])),
                None => line.split_once(": ").and_then(|(key, value)| {
                    let skipped = g
                        .skipped_keys
                        .iter()
                        .any(|(k, _)| key.starts_with(k.as_str()));
                    // An escaped quote is a quote.
                    (!skipped).then(|| value.replace("\\\"", "\""))
                }),
            },
            _ => comment_start(ext, line).map(|i| comment_text(&line[i..])),
        };
        if let Some(p) = piece {
            out.push((n + 1, prose(&p, &g.phrases)));
        }
    }
    out
}

fn problems_in(file: &Path, name: &str, g: &Glossary) -> Vec<String> {
    let text = read(file);
    let mut out = Vec::new();
    for (n, line) in checked_lines(file, &text, g) {
        for (variant, term) in variants_in(&line, &g.terms) {
            out.push(format!(
                "{name}:{n}: {variant}: write {term} (the glossary's term)"
            ));
        }
        for p in rule_problems(&line) {
            out.push(format!("{name}:{n}: {p}"));
        }
    }
    out
}

/// Files below `dir` whose name ends with `suffix`.
fn files_under(dir: &Path, suffix: &str) -> Vec<PathBuf> {
    let mut out = Vec::new();
    let mut stack = vec![dir.to_path_buf()];
    while let Some(d) = stack.pop() {
        for e in std::fs::read_dir(&d).unwrap_or_else(|e| panic!("{}: {e}", d.display())) {
            let p = e.unwrap().path();
            if p.is_dir() {
                stack.push(p);
            } else if p.to_string_lossy().ends_with(suffix) {
                out.push(p);
            }
        }
    }
    out.sort();
    out
}

/// The Japanese pages and messages: the lessons (but the glossary, whose table names the variants),
/// the Japanese docs, the README and the messages.
fn japanese_pages() -> Vec<PathBuf> {
    let mut files: Vec<PathBuf> = files_under(&root().join("lessons/ja"), ".md")
        .into_iter()
        .filter(|p| !p.ends_with("lessons/ja/glossary.md"))
        .collect();
    files.extend(files_under(&root().join("docs"), ".ja.md"));
    files.push(root().join("README.ja.md"));
    files.push(root().join("locales/ja.yml"));
    files
}

/// What `lesson start` writes for a Japanese student, each as (written file, the project file it
/// was copied from).
fn japanese_copies(tag: &str) -> Vec<(PathBuf, PathBuf)> {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR"))
        .join(format!("glossary-start-{tag}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    let written = opengl3d::tools::lesson::start(&dir, Lang::Ja).expect("lesson start");
    assert!(written.len() > 10, "{written:?}");
    let res = root().join("Res");
    written
        .into_iter()
        .map(|w| {
            let rel = w.strip_prefix(&dir).unwrap().to_path_buf();
            let ja = res.join("lesson-stubs/ja").join(&rel);
            let source = if ja.is_file() { ja } else { res.join(&rel) };
            assert_eq!(
                std::fs::read(&w).unwrap(),
                std::fs::read(&source).unwrap(),
                "{} is not a copy of {}",
                w.display(),
                source.display()
            );
            (w, source)
        })
        .collect()
}

fn relative(p: &Path) -> String {
    p.strip_prefix(root()).unwrap_or(p).display().to_string()
}

#[test]
fn japanese_text_follows_the_glossary() {
    let g = glossary();
    assert!(g.terms.len() > 30, "glossary: too few terms");
    let mut problems = Vec::new();
    for f in japanese_pages() {
        problems.extend(problems_in(&f, &relative(&f), &g));
    }
    let copied: BTreeSet<PathBuf> = japanese_copies("rules")
        .into_iter()
        .map(|(_, s)| s)
        .collect();
    for source in &copied {
        problems.extend(problems_in(source, &relative(source), &g));
    }
    assert!(
        problems.is_empty(),
        "{} problems (lessons/ja/glossary.md says why):\n{}",
        problems.len(),
        problems.join("\n")
    );
    // The pending skips are said out loud, so that they are not forgotten.
    for (key, why) in &g.skipped_keys {
        eprintln!("locales/ja.yml: {key}* not checked: {why}");
    }
}

/// A comment written in English: no Japanese in it and at least two words of letters only (so
/// `// x = y` or a lone identifier pass as code).
fn is_english_prose(comment: &str) -> bool {
    let words = comment
        .split_whitespace()
        .map(|w| w.trim_matches(|c: char| ",.:;!?()".contains(c)))
        .filter(|w| w.len() >= 2 && w.chars().all(|c| c.is_ascii_alphabetic()))
        .count();
    !comment.chars().any(is_japanese) && words >= 2
}

#[test]
fn the_files_lesson_start_writes_in_japanese_comment_in_japanese() {
    let mut problems = Vec::new();
    for (written, source) in japanese_copies("comments") {
        let ext = source
            .extension()
            .and_then(|e| e.to_str())
            .unwrap_or("")
            .to_string();
        let text = read(&written);
        for (n, line) in text.lines().enumerate() {
            if let Some(i) = comment_start(&ext, line) {
                let comment = line[i..].trim_start_matches(['/', '#']).trim();
                if is_english_prose(comment) {
                    problems.push(format!(
                        "{}:{}: an English comment (a Japanese student gets this file): {comment}",
                        relative(&source),
                        n + 1
                    ));
                }
            }
        }
    }
    assert!(problems.is_empty(), "{}", problems.join("\n"));
}

/// A file without its comments: each line cut at its comment and trimmed, empty lines dropped.
fn comment_free(ext: &str, text: &str) -> String {
    let mut out = String::new();
    for line in text.lines() {
        let code = match comment_start(ext, line) {
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

#[test]
fn japanese_copies_of_project_files_differ_only_in_their_comments() {
    let res = root().join("Res");
    let ja = res.join("lesson-stubs/ja");
    let lesson_shaders = opengl3d::tools::lesson::LESSON_SHADERS;
    let mut checked = 0;
    for twin in files_under(&ja, "") {
        let rel = twin.strip_prefix(&ja).unwrap();
        if lesson_shaders.iter().any(|s| rel == Path::new(s)) {
            continue; // the stubs, which are no copies
        }
        let original = res.join(rel);
        let ext = rel.extension().and_then(|e| e.to_str()).unwrap_or("");
        assert!(
            original.is_file(),
            "{} has no original {}",
            relative(&twin),
            relative(&original)
        );
        assert_eq!(
            comment_free(ext, &read(&twin)),
            comment_free(ext, &read(&original)),
            "{} must be {} with its comments translated",
            relative(&twin),
            relative(&original)
        );
        checked += 1;
    }
    assert!(checked > 0, "no Japanese copies under Res/lesson-stubs/ja");
}

#[test]
fn the_checks_catch_each_rule_and_spare_code_quotes_and_phrases() {
    let g = glossary_from(
        "# x\n\n## 用語\n\n| a | b | c | d |\n|---|---|---|---|\n\
         | shader | シェーダー | shader | シェーダ |\n| crease | 折れ目 | crease | 隅 |\n\n\
         ## 例外\n\n| a | b | c |\n|---|---|---|\n| 語句 | 画面の隅 | 角のこと |\n\
         | キー | grade.verdict. | 保留 |\n",
    );
    assert_eq!(g.phrases, ["画面の隅"]);
    assert_eq!(g.skipped_keys[0].0, "grade.verdict.");
    let found = |line: &str| -> Vec<String> {
        let p = prose(line, &g.phrases);
        let mut out: Vec<String> = variants_in(&p, &g.terms)
            .into_iter()
            .map(|(v, _)| v)
            .collect();
        out.extend(rule_problems(&p));
        out
    };
    assert!(found("シェーダーを書き、画面の隅を見ます").is_empty());
    assert_eq!(found("シェーダを書く"), ["シェーダ"]);
    assert_eq!(found("壁と床の隅"), ["隅"]);
    assert!(found("講座の「シェーダ」と`2x2`と[a](09-2x2.md)").is_empty());
    assert_eq!(found("レッスン 7 で").len(), 2);
    assert_eq!(found("`sao.frag` を").len(), 1);
    assert_eq!(found("指定します --out と .zip").len(), 3);
    assert!(found("- 箇条書き\n").is_empty());
    assert_eq!(found("全 %{count} ステップ").len(), 2);
    assert_eq!(found("半径（m）").len(), 2);
    assert_eq!(found("1〜12").len(), 1);
    assert_eq!(found("2x2の平滑化").len(), 1);
    assert_eq!(found("4msかかり、10 %遅い").len(), 2);
    assert!(found("4 msかかり、10%遅い。d32fとR8").is_empty());
    assert_eq!(found("ＡＯ").len(), 2);
    // A YAML file: values and comments, but not the skipped keys.
    let dir =
        Path::new(env!("CARGO_TARGET_TMPDIR")).join(format!("glossary-yml-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let yml = dir.join("ja.yml");
    std::fs::write(
        &yml,
        "# 日本語 (メモ)\na.b: \"AO の半径\"\ngrade.verdict.x: \"AO の半径\"\n",
    )
    .unwrap();
    let problems = problems_in(&yml, "ja.yml", &g);
    assert_eq!(problems.len(), 2, "{problems:?}");
    assert!(problems[0].starts_with("ja.yml:1:") && problems[1].starts_with("ja.yml:2:"));
    // Markdown: a listing's comments are checked, its code is not.
    let md = dir.join("p.md");
    std::fs::write(&md, "```glsl\nfloat x2x2 = 1.0; // シェーダ\n```\n").unwrap();
    let problems = problems_in(&md, "p.md", &g);
    std::fs::remove_dir_all(&dir).unwrap();
    assert_eq!(
        problems,
        ["p.md:2: シェーダ: write シェーダー (the glossary's term)"]
    );
    assert!(is_english_prose("Nearest texel of level 0"));
    assert!(!is_english_prose("レベル0の最も近いテクセル(nearest)"));
}
