//! The Markdown of the repository keeps to what exists: every relative link and image points at a file
//! that is there, every `#anchor` at a heading of its target (GitHub's slugs), and the pages that list
//! the AO methods name each one `--method` accepts and count them as the code does.

use clap::CommandFactory;
use std::collections::{BTreeMap, BTreeSet};
use std::path::{Component, Path, PathBuf};

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

/// Every `.md` file below `dir`, skipping build output and version control.
fn markdown_files(dir: &Path) -> Vec<PathBuf> {
    let mut out = Vec::new();
    let mut stack = vec![dir.to_path_buf()];
    while let Some(d) = stack.pop() {
        for e in std::fs::read_dir(&d).unwrap_or_else(|e| panic!("{}: {e}", d.display())) {
            let p = e.unwrap().path();
            let name = p.file_name().unwrap().to_string_lossy().into_owned();
            if p.is_dir() {
                if !matches!(name.as_str(), "target" | ".git" | "node_modules") {
                    stack.push(p);
                }
            } else if name.ends_with(".md") {
                out.push(p);
            }
        }
    }
    out.sort();
    out
}

/// The lines of `text` outside fenced code blocks, numbered from 1.
fn prose_lines(text: &str) -> Vec<(usize, &str)> {
    let mut fence: Option<&str> = None;
    let mut out = Vec::new();
    for (i, line) in text.lines().enumerate() {
        let t = line.trim_start();
        let marker = ["```", "~~~"].into_iter().find(|m| t.starts_with(m));
        match (fence, marker) {
            (None, Some(m)) => fence = Some(m),
            (Some(f), Some(m)) if f == m => fence = None,
            (None, None) => out.push((i + 1, line)),
            _ => {}
        }
    }
    out
}

/// `line` with inline code spans blanked out (same length, so positions still hold).
fn without_code_spans(line: &str) -> String {
    let mut out = String::with_capacity(line.len());
    let mut in_code = false;
    for c in line.chars() {
        if c == '`' {
            in_code = !in_code;
            out.push(' ');
        } else if in_code {
            out.extend(std::iter::repeat_n(' ', c.len_utf8()));
        } else {
            out.push(c);
        }
    }
    out
}

/// The targets of the inline links and images of one line (`[text](target "title")`, `![alt](target)`)
/// and of a reference definition (`[label]: target`).
fn link_targets(line: &str) -> Vec<String> {
    let clean = without_code_spans(line);
    let mut out = Vec::new();
    let t = clean.trim_start();
    if t.starts_with('[') {
        if let Some(end) = t.find("]:") {
            if !t[..end].contains('(') {
                if let Some(target) = t[end + 2..].split_whitespace().next() {
                    out.push(target.trim_matches(['<', '>']).to_string());
                }
                return out;
            }
        }
    }
    let bytes = clean.as_bytes();
    let mut i = 0;
    while let Some(pos) = clean[i..].find("](") {
        let start = i + pos + 2;
        let mut depth = 1;
        let mut j = start;
        while j < bytes.len() {
            match bytes[j] {
                b'(' => depth += 1,
                b')' => {
                    depth -= 1;
                    if depth == 0 {
                        break;
                    }
                }
                _ => {}
            }
            j += 1;
        }
        let inner = clean[start..j.min(bytes.len())].trim();
        let target = if let Some(rest) = inner.strip_prefix('<') {
            rest.split('>').next().unwrap_or("")
        } else {
            inner.split_whitespace().next().unwrap_or("")
        };
        if !target.is_empty() {
            out.push(target.to_string());
        }
        i = j.min(bytes.len());
    }
    out
}

/// `%20` and the like decoded (link targets may be percent-encoded).
fn percent_decode(s: &str) -> String {
    let b = s.as_bytes();
    let hex = |c: u8| (c as char).to_digit(16);
    let mut out = Vec::with_capacity(b.len());
    let mut i = 0;
    while i < b.len() {
        if b[i] == b'%' && i + 2 < b.len() {
            if let (Some(h), Some(l)) = (hex(b[i + 1]), hex(b[i + 2])) {
                out.push((h * 16 + l) as u8);
                i += 3;
                continue;
            }
        }
        out.push(b[i]);
        i += 1;
    }
    String::from_utf8_lossy(&out).into_owned()
}

/// The text a heading shows: links and images reduced to their text, code marks, emphasis and HTML
/// tags dropped.
fn heading_text(raw: &str) -> String {
    let mut s = raw.trim().trim_end_matches('#').trim().to_string();
    // [text](url) and ![alt](url) → text / alt.
    while let Some(close) = s.find("](") {
        let open = s[..close].rfind('[');
        let end = s[close..].find(')').map(|e| close + e);
        match (open, end) {
            (Some(o), Some(e)) => {
                let text = s[o + 1..close].to_string();
                let o = if o > 0 && s.as_bytes()[o - 1] == b'!' {
                    o - 1
                } else {
                    o
                };
                s.replace_range(o..=e, &text);
            }
            _ => break,
        }
    }
    // HTML tags.
    while let (Some(a), Some(b)) = (s.find('<'), s.find('>')) {
        if b <= a {
            break;
        }
        s.replace_range(a..=b, "");
    }
    s.replace(['`', '*'], "")
}

/// GitHub's anchor for a heading: lower case, spaces to `-`, every other character that is not a
/// letter, a digit, `-` or `_` dropped (Japanese letters stay).
fn slug(heading: &str) -> String {
    heading_text(heading)
        .to_lowercase()
        .chars()
        .filter_map(|c| match c {
            ' ' => Some('-'),
            '-' | '_' => Some(c),
            c if c.is_alphanumeric() => Some(c),
            _ => None,
        })
        .collect()
}

/// The anchors a Markdown file offers: its headings' slugs (repeats get `-1`, `-2`, …) and the
/// `id`/`name` of HTML anchors.
fn anchors(text: &str) -> BTreeSet<String> {
    let mut seen: BTreeMap<String, usize> = BTreeMap::new();
    let mut out = BTreeSet::new();
    for (_, line) in prose_lines(text) {
        let t = line.trim_start();
        let hashes = t.chars().take_while(|c| *c == '#').count();
        if (1..=6).contains(&hashes) && t[hashes..].starts_with(' ') {
            let base = slug(&t[hashes..]);
            let n = seen.entry(base.clone()).or_insert(0);
            out.insert(if *n == 0 {
                base.clone()
            } else {
                format!("{base}-{n}")
            });
            *n += 1;
        }
        for key in ["id=\"", "name=\""] {
            let mut rest = line;
            while let Some(p) = rest.find(key) {
                rest = &rest[p + key.len()..];
                if let Some(e) = rest.find('"') {
                    out.insert(rest[..e].to_string());
                }
            }
        }
    }
    out
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

/// Every broken relative link of the Markdown below `repo`, as `file:line: target (why)`.
fn broken_links(repo: &Path) -> Vec<String> {
    let mut cache: BTreeMap<PathBuf, BTreeSet<String>> = BTreeMap::new();
    let mut anchors_of = |p: &Path| -> BTreeSet<String> {
        cache
            .entry(p.to_path_buf())
            .or_insert_with(|| anchors(&std::fs::read_to_string(p).unwrap_or_default()))
            .clone()
    };
    let mut bad = Vec::new();
    for file in markdown_files(repo) {
        let text = std::fs::read_to_string(&file).unwrap();
        let shown = file.strip_prefix(repo).unwrap().display().to_string();
        for (n, line) in prose_lines(&text) {
            for target in link_targets(line) {
                let lower = target.to_ascii_lowercase();
                if ["http://", "https://", "mailto:", "ftp://"]
                    .iter()
                    .any(|s| lower.starts_with(s))
                {
                    continue;
                }
                let (path, anchor) = match target.split_once('#') {
                    Some((p, a)) => (p, Some(a)),
                    None => (target.as_str(), None),
                };
                let path = percent_decode(path.split('?').next().unwrap_or(""));
                let resolved = if path.is_empty() {
                    file.clone()
                } else if let Some(abs) = path.strip_prefix('/') {
                    repo.join(abs)
                } else {
                    normalise(&file.parent().unwrap().join(&path))
                };
                if !resolved.exists() {
                    bad.push(format!("{shown}:{n}: {target} (no such file)"));
                    continue;
                }
                let Some(anchor) = anchor.filter(|a| !a.is_empty()) else {
                    continue;
                };
                if resolved.extension().is_some_and(|x| x == "md") {
                    let anchor = percent_decode(anchor);
                    if !anchors_of(&resolved).contains(&anchor) {
                        bad.push(format!("{shown}:{n}: {target} (no heading #{anchor})"));
                    }
                }
            }
        }
    }
    bad
}

#[test]
fn every_relative_link_and_anchor_resolves() {
    let bad = broken_links(&root());
    assert!(bad.is_empty(), "broken links:\n{}", bad.join("\n"));
}

/// A scratch folder under the system's temporary directory, empty.
fn scratch(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("opengl3d-docs-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(d.join("sub")).unwrap();
    d
}

#[test]
fn the_checker_names_the_file_the_line_and_the_target() {
    let d = scratch("links");
    std::fs::write(
        d.join("sub/page.md"),
        "# Page\n\n## A heading, with `code`\n\n## A heading, with `code`\n",
    )
    .unwrap();
    std::fs::write(d.join("pic.png"), b"").unwrap();
    std::fs::write(
        d.join("README.md"),
        "# Top\n\
         [ok](sub/page.md) and [ok too](sub/page.md#a-heading-with-code-1) ![p](pic.png)\n\
         [gone](sub/missing.md)\n\
         ```\n[in code](nowhere.md)\n```\n\
         `[in a span](nowhere.md)` [web](https://example.com/x) [self](#top)\n\
         [bad anchor](sub/page.md#no-such-heading) [bad self](#nothing)\n\
         [ref]: sub/also-missing.md\n",
    )
    .unwrap();
    let bad = broken_links(&d);
    assert_eq!(
        bad,
        [
            "README.md:3: sub/missing.md (no such file)",
            "README.md:8: sub/page.md#no-such-heading (no heading #no-such-heading)",
            "README.md:8: #nothing (no heading #nothing)",
            "README.md:9: sub/also-missing.md (no such file)",
        ],
        "{bad:#?}"
    );
    std::fs::remove_dir_all(&d).unwrap();
}

#[test]
fn slugs_follow_github() {
    assert_eq!(slug(" Why depth is not linear"), "why-depth-is-not-linear");
    assert_eq!(slug(" The `isSky` test, step 2"), "the-issky-test-step-2");
    assert_eq!(slug(" 1. Mip levels: 0–3 (four)"), "1-mip-levels-03-four");
    assert_eq!(slug(" 比較"), "比較");
    assert_eq!(slug(" 空と、`far`へのクランプ"), "空とfarへのクランプ");
    assert_eq!(slug(" [Link](x.md) and *stress*"), "link-and-stress");
    assert_eq!(slug(" snake_case-name"), "snake_case-name");
    let a = anchors("# A\n## A\n```\n# A\n```\n### A\n");
    assert_eq!(
        a,
        ["a", "a-1", "a-2"].map(String::from).into_iter().collect()
    );
}

/// The names `render --method` accepts, from the command line's own definition.
fn method_names() -> Vec<String> {
    let cmd = opengl3d::cli::Cli::command();
    let render = cmd.find_subcommand("render").expect("a render subcommand");
    let method = render
        .get_arguments()
        .find(|a| a.get_id() == "method")
        .expect("render --method");
    method
        .get_possible_values()
        .iter()
        .map(|v| v.get_name().to_string())
        .collect()
}

/// The number a word or numeral stands for (`nine`, `9`), if it is one.
fn number(word: &str) -> Option<usize> {
    const WORDS: [&str; 13] = [
        "zero", "one", "two", "three", "four", "five", "six", "seven", "eight", "nine", "ten",
        "eleven", "twelve",
    ];
    let w = word.to_lowercase();
    WORDS
        .iter()
        .position(|x| *x == w)
        .or_else(|| w.parse().ok())
}

/// The counts of methods a page states, each with its line and whether it counts the methods other
/// than the lesson's (`others`): English "nine AO methods", "eight others", "the other eight",
/// "nine middles", "eight methods in `Res/ao/`"; Japanese "9つのAO手法", "8つの手法も", "9種類の中間処理".
fn stated_counts(text: &str) -> Vec<(usize, usize, bool, String)> {
    let mut out = Vec::new();
    // Words of all prose lines in one run (a phrase may break across lines), each with its line.
    let mut words: Vec<(usize, &str)> = Vec::new();
    for (n, line) in prose_lines(text) {
        words.extend(
            line.split(|c: char| !(c.is_alphanumeric() || c == '/' || c == '`' || c == '-'))
                .filter(|w| !w.is_empty())
                .map(|w| (n, w)),
        );
    }
    let word = |i: usize| words.get(i).map_or("", |w| w.1);
    for (i, &(n, w)) in words.iter().enumerate() {
        let (prev, next, after) = (
            if i > 0 { word(i - 1) } else { "" },
            word(i + 1),
            word(i + 2),
        );
        let Some(k) = number(w) else { continue };
        // "these two methods" points back at a named subset, not at the set.
        if ["these", "those", "both"].contains(&prev.to_lowercase().as_str()) {
            continue;
        }
        let others = next == "others"
            || prev.eq_ignore_ascii_case("other")
            || (next == "methods" && after == "in");
        let counts = next == "methods"
            || next == "middles"
            || (next == "AO" && after == "methods")
            || next == "others"
            || (prev.eq_ignore_ascii_case("other") && next != "passes");
        if counts {
            out.push((n, k, others, format!("{prev} {w} {next}")));
        }
    }
    for (n, line) in prose_lines(text) {
        // Japanese: a numeral followed by つの(AO)手法 or 種類の中間処理.
        let chars: Vec<char> = line.chars().collect();
        let mut i = 0;
        while i < chars.len() {
            if chars[i].is_ascii_digit() {
                let start = i;
                while i < chars.len() && chars[i].is_ascii_digit() {
                    i += 1;
                }
                let k: usize = chars[start..i].iter().collect::<String>().parse().unwrap();
                let rest: String = chars[i..].iter().take(8).collect();
                let before: String = chars[start.saturating_sub(12)..start].iter().collect();
                let subset = before.ends_with("この") || before.ends_with("その");
                if !subset && rest.starts_with("つの手法")
                    || rest.starts_with("つのAO手法")
                    || rest.starts_with("種類の中間処理")
                {
                    let others = rest.starts_with("つの手法も") || before.contains("Res/ao/");
                    out.push((n, k, others, format!("{before}{k}{rest}")));
                }
            } else {
                i += 1;
            }
        }
    }
    out
}

/// The pages that present the whole set of methods.
const METHOD_INDEXES: [&str; 6] = [
    "README.md",
    "README.ja.md",
    "lessons/methods/README.md",
    "lessons/ja/methods/README.md",
    "docs/commands.md",
    "docs/commands.ja.md",
];

#[test]
fn the_method_pages_name_and_count_what_the_code_runs() {
    let names = method_names();
    assert!(
        names.len() >= 2 && names.contains(&"sao-lesson".to_string()),
        "{names:?}"
    );
    let total = names.len();
    let mut bad = Vec::new();
    for page in METHOD_INDEXES {
        let text = std::fs::read_to_string(root().join(page)).unwrap();
        for name in &names {
            if !text.contains(&format!("`{name}`")) {
                bad.push(format!("{page}: does not name `{name}`"));
            }
        }
    }
    for name in &names {
        for dir in ["lessons/methods", "lessons/ja/methods"] {
            if !root().join(dir).join(format!("{name}.md")).is_file() {
                bad.push(format!("{dir}/{name}.md: missing (a page per method)"));
            }
        }
    }
    let mut pages: Vec<String> = METHOD_INDEXES.iter().map(|s| s.to_string()).collect();
    pages.extend(
        [
            "docs/architecture.md",
            "docs/architecture.ja.md",
            "lessons/README.md",
        ]
        .map(String::from),
    );
    pages.push("lessons/ja/README.md".into());
    for page in &pages {
        let text = std::fs::read_to_string(root().join(page)).unwrap();
        for (line, k, others, phrase) in stated_counts(&text) {
            let want = if others { total - 1 } else { total };
            if k != want {
                bad.push(format!(
                    "{page}:{line}: \"{phrase}\" says {k}, the code has {want} ({total} methods: {})",
                    names.join(", ")
                ));
            }
        }
    }
    assert!(bad.is_empty(), "{}", bad.join("\n"));
}

#[test]
fn the_count_check_reads_the_phrases_it_is_for() {
    let counts = stated_counts(
        "Nine AO methods. The engine runs eight others; the other eight and nine middles.\n\
         The eight methods in `Res/ao/`. Four passes, the other passes, these two methods.\n\
         9つのAO手法。8つの手法も。9種類の中間処理。`Res/ao/`にある8つの手法。この2つの手法。\n\
         ```\nseven methods\n```\n",
    );
    let got: Vec<(usize, usize, bool)> = counts.iter().map(|c| (c.0, c.1, c.2)).collect();
    assert_eq!(
        got,
        [
            (1, 9, false),
            (1, 8, true),
            (1, 8, true),
            (1, 9, false),
            (2, 8, true),
            (3, 9, false),
            (3, 8, true),
            (3, 9, false),
            (3, 8, true),
        ],
        "{counts:#?}"
    );
}

/// Lesson 2 says the restore pass's clamp matters only for a full-size side of 1 pixel: the half size
/// is rounded down, so the 2×2 block of the last half-size texel, `2x + 1`, stays inside any side but 1.
#[test]
fn only_a_one_pixel_side_reads_past_the_edge_without_the_clamp() {
    for full in 1..=4097u32 {
        let (half, _) = opengl3d::ao::targets::half_size(full, 8);
        let last_read = 2 * (half - 1) + 1;
        assert_eq!(last_read > full - 1, full == 1, "side {full}: half {half}");
    }
}
