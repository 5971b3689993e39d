//! A GLSL mutant generator for measuring the grader's sensitivity (`grade --mutation-score`): small,
//! typical slips applied one at a time to a lesson shader, in a fixed order, each with an id and a
//! one-line description (`line:col operator`).
//!
//! Operators: flip a sign (`+`↔`-`, `+=`↔`-=`, drop a unary `-`), swap the operands of a
//! non-commutative binary operator, ±1 on an integer constant, ×2 and ×0.5 on a float constant,
//! `min`↔`max`, swap `x`↔`y` (and `r`↔`g`) in a swizzle, drop a statement, `<`↔`<=` and `>`↔`>=`.
//! Only the shader's body is mutated: preprocessor lines (`#version`, `#define`, …), lines with a
//! `layout(` qualifier (the engine's interface) and comments are left alone.

/// One mutant of a shader.
#[derive(Clone, Debug, PartialEq)]
pub struct Mutant {
    /// 1-based, in generation order (by position in the file, then operator).
    pub index: usize,
    /// `line:col operator`, e.g. `28:18 min→max`.
    pub description: String,
    /// The whole mutated shader.
    pub source: String,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Kind {
    Ident,
    Int,
    Float,
    Punct,
}

#[derive(Clone, Debug)]
struct Token {
    kind: Kind,
    text: String,
    /// Byte offset in the source.
    start: usize,
    line: usize,
    col: usize,
}

/// Multi-character operators, longest first.
const PUNCTS: [&str; 20] = [
    "<<=", ">>=", "<=", ">=", "==", "!=", "&&", "||", "^^", "++", "--", "+=", "-=", "*=", "/=",
    "%=", "<<", ">>", "&=", "|=",
];

/// Whether line `line` (its text) is one the generator must not touch.
fn frozen_line(text: &str) -> bool {
    let t = text.trim_start();
    t.starts_with('#') || t.contains("layout(") || t.contains("layout (")
}

/// The tokens of `src` outside comments and frozen lines.
fn tokenize(src: &str) -> Vec<Token> {
    let bytes = src.as_bytes();
    let mut line_frozen: Vec<bool> = src.lines().map(frozen_line).collect();
    line_frozen.push(false);
    let mut out = Vec::new();
    let (mut i, mut line, mut line_start) = (0usize, 1usize, 0usize);
    while i < bytes.len() {
        let c = bytes[i];
        if c == b'\n' {
            i += 1;
            line += 1;
            line_start = i;
            continue;
        }
        if c.is_ascii_whitespace() {
            i += 1;
            continue;
        }
        if src[i..].starts_with("//") {
            while i < bytes.len() && bytes[i] != b'\n' {
                i += 1;
            }
            continue;
        }
        if src[i..].starts_with("/*") {
            let end = src[i + 2..]
                .find("*/")
                .map_or(bytes.len(), |e| i + 2 + e + 2);
            for &b in &bytes[i..end] {
                if b == b'\n' {
                    line += 1;
                }
            }
            if let Some(nl) = src[..end].rfind('\n') {
                if nl >= i {
                    line_start = nl + 1;
                }
            }
            i = end;
            continue;
        }
        let start = i;
        let kind = if c.is_ascii_alphabetic() || c == b'_' {
            while i < bytes.len() && (bytes[i].is_ascii_alphanumeric() || bytes[i] == b'_') {
                i += 1;
            }
            Kind::Ident
        } else if c.is_ascii_digit()
            || (c == b'.' && bytes.get(i + 1).is_some_and(u8::is_ascii_digit))
        {
            let mut float = false;
            while i < bytes.len() {
                let b = bytes[i];
                if b.is_ascii_digit() {
                    i += 1;
                } else if b == b'.' {
                    float = true;
                    i += 1;
                } else if (b == b'e' || b == b'E')
                    && (bytes.get(i + 1).is_some_and(u8::is_ascii_digit)
                        || (matches!(bytes.get(i + 1), Some(b'+' | b'-'))
                            && bytes.get(i + 2).is_some_and(u8::is_ascii_digit)))
                {
                    float = true;
                    i += 2;
                } else {
                    break;
                }
            }
            // Suffixes (f, u, lf) belong to the literal.
            while i < bytes.len() && bytes[i].is_ascii_alphabetic() {
                float |= bytes[i] == b'f' || bytes[i] == b'F';
                i += 1;
            }
            if float {
                Kind::Float
            } else {
                Kind::Int
            }
        } else {
            let len = PUNCTS
                .iter()
                .find(|p| src[i..].starts_with(**p))
                .map_or_else(
                    || src[i..].chars().next().map_or(1, char::len_utf8),
                    |p| p.len(),
                );
            i += len;
            Kind::Punct
        };
        if !line_frozen[line - 1] {
            out.push(Token {
                kind,
                text: src[start..i].to_string(),
                start,
                line,
                col: src[line_start..start].chars().count() + 1,
            });
        }
    }
    out
}

/// Binding strength of a binary operator (higher binds tighter), as in GLSL.
fn precedence(op: &str) -> Option<u8> {
    Some(match op {
        "*" | "/" | "%" => 10,
        "+" | "-" => 9,
        "<<" | ">>" => 8,
        "<" | ">" | "<=" | ">=" => 7,
        "==" | "!=" => 6,
        "&" => 5,
        "^" => 4,
        "|" => 3,
        "&&" => 2,
        "^^" => 1,
        "||" => 0,
        _ => return None,
    })
}

/// Whether the token at `i` ends an operand (so that a following `-` or `+` is binary).
fn ends_operand(t: &Token) -> bool {
    matches!(t.kind, Kind::Ident | Kind::Int | Kind::Float) || matches!(t.text.as_str(), ")" | "]")
}

/// The token range `[a, b)` of the primary expression ending at token `end` (inclusive): a literal,
/// a name with calls, indexing and member access, or a parenthesised group.
fn operand_before(toks: &[Token], end: usize) -> Option<usize> {
    let mut i = end;
    loop {
        let t = &toks[i];
        match t.text.as_str() {
            ")" | "]" => {
                let (open, close) = if t.text == ")" {
                    ("(", ")")
                } else {
                    ("[", "]")
                };
                let mut depth = 0i32;
                let mut j = i;
                loop {
                    if toks[j].text == close {
                        depth += 1;
                    } else if toks[j].text == open {
                        depth -= 1;
                        if depth == 0 {
                            break;
                        }
                    }
                    j = j.checked_sub(1)?;
                }
                // A call or an index: the name (or expression) before the bracket belongs to it.
                if j > 0 && (toks[j - 1].kind == Kind::Ident || toks[j - 1].text == "]") {
                    i = j - 1;
                    continue;
                }
                if open == "[" && j > 0 {
                    i = j - 1;
                    continue;
                }
                return Some(j);
            }
            _ if matches!(t.kind, Kind::Ident | Kind::Int | Kind::Float) => {
                // Member access: `a.b`.
                if i >= 2 && toks[i - 1].text == "." {
                    i -= 2;
                    continue;
                }
                return Some(i);
            }
            _ => return None,
        }
    }
}

/// The index one past the primary expression starting at token `start`.
fn operand_after(toks: &[Token], start: usize) -> Option<usize> {
    let mut i = start;
    let t = toks.get(i)?;
    if t.text == "(" {
        i = close_of(toks, i)? + 1;
    } else if matches!(t.kind, Kind::Ident | Kind::Int | Kind::Float) {
        i += 1;
    } else {
        return None;
    }
    loop {
        match toks.get(i).map(|t| t.text.as_str()) {
            Some("(") | Some("[") => i = close_of(toks, i)? + 1,
            Some(".") if toks.get(i + 1).is_some_and(|t| t.kind == Kind::Ident) => i += 2,
            _ => return Some(i),
        }
    }
}

/// The matching closing bracket of the opening one at `open`.
fn close_of(toks: &[Token], open: usize) -> Option<usize> {
    let (o, c) = match toks[open].text.as_str() {
        "(" => ("(", ")"),
        "[" => ("[", "]"),
        "{" => ("{", "}"),
        _ => return None,
    };
    let mut depth = 0i32;
    for (j, t) in toks.iter().enumerate().skip(open) {
        if t.text == o {
            depth += 1;
        } else if t.text == c {
            depth -= 1;
            if depth == 0 {
                return Some(j);
            }
        }
    }
    None
}

/// Text of a float constant scaled by `k`, written so that GLSL still reads a float.
fn scaled_float(text: &str, k: f64) -> Option<String> {
    let digits = text.trim_end_matches(['f', 'F']);
    let v: f64 = digits.parse().ok()?;
    let s = format!("{}", v * k);
    Some(if s.contains(['.', 'e', 'E']) {
        s
    } else {
        format!("{s}.0")
    })
}

/// A swizzle with x↔y (and r↔g) swapped, if that changes it.
fn swapped_swizzle(s: &str) -> Option<String> {
    if s.is_empty() || s.len() > 4 || !s.chars().all(|c| "xyzwrgba".contains(c)) {
        return None;
    }
    let out: String = s
        .chars()
        .map(|c| match c {
            'x' => 'y',
            'y' => 'x',
            'r' => 'g',
            'g' => 'r',
            c => c,
        })
        .collect();
    (out != s).then_some(out)
}

/// Type names that start a declaration (dropping one only gives a compile error).
const TYPES: [&str; 16] = [
    "const", "float", "int", "uint", "bool", "vec2", "vec3", "vec4", "ivec2", "ivec3", "ivec4",
    "mat2", "mat3", "mat4", "uvec2", "double",
];

/// An edit: replace `src[start..end]` by `with`.
struct Edit {
    start: usize,
    end: usize,
    with: String,
    /// Where it is reported (line, col) and what it does.
    line: usize,
    col: usize,
    what: String,
}

fn edit_at(t: &Token, with: impl Into<String>, what: impl Into<String>) -> Edit {
    Edit {
        start: t.start,
        end: t.start + t.text.len(),
        with: with.into(),
        line: t.line,
        col: t.col,
        what: what.into(),
    }
}

/// Every edit of `toks`, in token order, then operator order.
fn edits(src: &str, toks: &[Token]) -> Vec<Edit> {
    let mut out = Vec::new();
    let mut depth = 0i32; // brace depth: statements live inside function bodies
    let mut paren = 0i32;
    let mut stmt_start: Option<usize> = None;
    for (i, t) in toks.iter().enumerate() {
        let prev = i.checked_sub(1).map(|p| &toks[p]);
        let binary = prev.is_some_and(ends_operand);
        match t.text.as_str() {
            "{" => depth += 1,
            "}" => depth -= 1,
            "(" => paren += 1,
            ")" => paren -= 1,
            _ => {}
        }
        if depth >= 1
            && paren == 0
            && stmt_start.is_none()
            && !matches!(t.text.as_str(), "{" | "}" | ";")
        {
            stmt_start = Some(i);
        }
        match (t.kind, t.text.as_str()) {
            (Kind::Punct, "+") if binary => out.push(edit_at(t, "-", "flip sign + → -")),
            (Kind::Punct, "-") if binary => out.push(edit_at(t, "+", "flip sign - → +")),
            (Kind::Punct, "-") => out.push(edit_at(t, "", "drop unary -")),
            (Kind::Punct, "+=") => out.push(edit_at(t, "-=", "flip sign += → -=")),
            (Kind::Punct, "-=") => out.push(edit_at(t, "+=", "flip sign -= → +=")),
            (Kind::Punct, "<") => out.push(edit_at(t, "<=", "< → <=")),
            (Kind::Punct, "<=") => out.push(edit_at(t, "<", "<= → <")),
            (Kind::Punct, ">") => out.push(edit_at(t, ">=", "> → >=")),
            (Kind::Punct, ">=") => out.push(edit_at(t, ">", ">= → >")),
            (Kind::Int, text) => {
                if let Ok(v) = text.parse::<i64>() {
                    out.push(edit_at(t, (v + 1).to_string(), format!("{v} → {}", v + 1)));
                    out.push(edit_at(t, (v - 1).to_string(), format!("{v} → {}", v - 1)));
                }
            }
            (Kind::Float, text) => {
                for (k, name) in [(2.0, "×2"), (0.5, "×0.5")] {
                    if let Some(s) = scaled_float(text, k) {
                        out.push(edit_at(t, s.clone(), format!("{text} {name} → {s}")));
                    }
                }
            }
            (Kind::Ident, "min") if toks.get(i + 1).is_some_and(|n| n.text == "(") => {
                out.push(edit_at(t, "max", "min → max"))
            }
            (Kind::Ident, "max") if toks.get(i + 1).is_some_and(|n| n.text == "(") => {
                out.push(edit_at(t, "min", "max → min"))
            }
            (Kind::Ident, text) if prev.is_some_and(|p| p.text == ".") => {
                if let Some(s) = swapped_swizzle(text) {
                    out.push(edit_at(t, s.clone(), format!(".{text} → .{s}")));
                }
            }
            _ => {}
        }
        // Swap the operands of a non-commutative binary operator.
        if binary
            && matches!(
                t.text.as_str(),
                "-" | "/" | "%" | "<" | ">" | "<=" | ">=" | "<<" | ">>"
            )
        {
            if let Some(e) = swap_operands(src, toks, i) {
                out.push(e);
            }
        }
        if t.text == ";" && paren == 0 {
            if let Some(s) = stmt_start.take() {
                let first = &toks[s];
                if depth >= 1 && !TYPES.contains(&first.text.as_str()) {
                    out.push(Edit {
                        start: first.start,
                        end: t.start + 1,
                        with: String::new(),
                        line: first.line,
                        col: first.col,
                        what: format!(
                            "drop statement `{}`",
                            statement_text(src, first.start, t.start + 1)
                        ),
                    });
                }
            }
        }
        if matches!(t.text.as_str(), "{" | "}") {
            stmt_start = None;
        }
    }
    out
}

/// A statement's text on one line, shortened for a description.
fn statement_text(src: &str, start: usize, end: usize) -> String {
    let one_line = src[start..end]
        .split_whitespace()
        .collect::<Vec<_>>()
        .join(" ");
    if one_line.chars().count() > 40 {
        format!("{}…", one_line.chars().take(39).collect::<String>())
    } else {
        one_line
    }
}

/// `a OP b` → `b OP a` for the operator at token `op`, when `a` and `b` are its whole operands.
fn swap_operands(src: &str, toks: &[Token], op: usize) -> Option<Edit> {
    let prec = precedence(&toks[op].text)?;
    let a = operand_before(toks, op - 1)?;
    let b_end = operand_after(toks, op + 1)?;
    // The left operand is all of `a` only when nothing before it binds at least as tightly.
    if a > 0
        && precedence(&toks[a - 1].text).is_some_and(|p| p >= prec)
        && ends_operand_before(toks, a)
    {
        return None;
    }
    // A unary minus before `a` would bind to it, not to the whole operand.
    if a > 0
        && matches!(toks[a - 1].text.as_str(), "-" | "!" | "~")
        && !ends_operand_before(toks, a)
    {
        return None;
    }
    // The right operand is all of `b` only when nothing after it binds more tightly.
    if toks
        .get(b_end)
        .is_some_and(|t| precedence(&t.text).is_some_and(|p| p > prec))
    {
        return None;
    }
    let (sa, ea) = (toks[a].start, toks[op - 1].start + toks[op - 1].text.len());
    let (sb, eb) = (
        toks[op + 1].start,
        toks[b_end - 1].start + toks[b_end - 1].text.len(),
    );
    let (ta, tb) = (&src[sa..ea], &src[sb..eb]);
    let between = &src[ea..sb];
    let t = &toks[op];
    Some(Edit {
        start: sa,
        end: eb,
        with: format!("{tb}{between}{ta}"),
        line: t.line,
        col: t.col,
        what: format!("swap operands of {}", t.text),
    })
}

/// Whether the token before `a` (at `a - 1`, an operator) is binary, i.e. preceded by an operand.
fn ends_operand_before(toks: &[Token], a: usize) -> bool {
    a >= 2 && ends_operand(&toks[a - 2])
}

/// Every mutant of `src`, in a fixed order.
pub fn mutants(src: &str) -> Vec<Mutant> {
    let toks = tokenize(src);
    let mut seen = std::collections::HashSet::new();
    let mut out = Vec::new();
    for e in edits(src, &toks) {
        let source = format!("{}{}{}", &src[..e.start], e.with, &src[e.end..]);
        // Two operators can write the same text (e.g. dropping a unary minus twice): keep one.
        if source == src || !seen.insert(source.clone()) {
            continue;
        }
        out.push(Mutant {
            index: out.len() + 1,
            description: format!("{}:{} {}", e.line, e.col, e.what),
            source,
        });
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    fn descriptions(src: &str) -> Vec<String> {
        mutants(src).into_iter().map(|m| m.description).collect()
    }

    fn sources(src: &str) -> Vec<String> {
        mutants(src).into_iter().map(|m| m.source).collect()
    }

    #[test]
    fn frozen_lines_and_comments_are_not_mutated() {
        let src = "#version 450\nlayout(location=200) uniform int mipLevel;\n// a - b 1.5\n/* min(2, 3) */\n#define X 3\n";
        assert!(mutants(src).is_empty(), "{:?}", descriptions(src));
    }

    #[test]
    fn each_operator_writes_what_it_says() {
        let src = "void main()\n{\n  float a = min(b.x, 2.0) - c / 4;\n  d = e - f;\n  \
                   if (a < 1) { a += -b.y; }\n}\n";
        let s = sources(src);
        let has = |t: &str| s.iter().any(|m| m.contains(t));
        assert!(has("float a = max(b.x, 2.0) - c / 4;"), "min→max");
        assert!(has("float a = min(b.y, 2.0) - c / 4;"), "swizzle");
        assert!(has("float a = min(b.x, 4.0) - c / 4;"), "×2");
        assert!(has("float a = min(b.x, 1.0) - c / 4;"), "×0.5");
        assert!(has("float a = min(b.x, 2.0) + c / 4;"), "flip sign");
        // `c / 4` is the right operand of `-`, not `c`: no swap there.
        assert!(!has("float a = c - min(b.x, 2.0) / 4;"), "not a swap of -");
        assert!(has("d = f - e;"), "swap -");
        assert!(has("float a = min(b.x, 2.0) - 4 / c;"), "swap /");
        assert!(has("c / 5;") && has("c / 3;"), "±1");
        assert!(has("if (a <= 1)"), "< → <=");
        assert!(has("a -= -b.y;"), "+= → -=");
        assert!(has("a += b.y;"), "drop unary -");
        assert!(has("{  }"), "drop statement");
        // A declaration is never dropped: that only makes a compile error.
        assert!(!has("{\n  \n  d = e"), "{s:?}");
    }

    #[test]
    fn operands_are_swapped_only_when_they_are_whole() {
        // `b` is not the left operand of the second `-` (that is `a - b`), nor `c` the right
        // operand of the first when a `*` binds it to `d`.
        let s = sources("void main() { x = a - b - c * d; }");
        assert!(s.iter().any(|m| m.contains("x = b - a - c * d;")), "{s:?}");
        assert!(!s.iter().any(|m| m.contains("a - c - b")), "{s:?}");
        assert!(!s.iter().any(|m| m.contains("x = a - c - b * d")), "{s:?}");
        let s = sources("void main() { x = f(a, b) / g[2].y; }");
        assert!(
            s.iter().any(|m| m.contains("x = g[2].y / f(a, b);")),
            "{s:?}"
        );
    }

    #[test]
    fn ids_follow_the_file_and_descriptions_name_the_place() {
        let m = mutants("void main()\n{\n  y = min(a, 1);\n}\n");
        assert_eq!(m[0].index, 1);
        assert_eq!(m[0].description, "3:7 min → max");
        assert!(m.windows(2).all(|w| w[0].index + 1 == w[1].index));
        assert_eq!(
            mutants("void main()\n{\n  y = min(a, 1);\n}\n"),
            m,
            "deterministic"
        );
    }

    #[test]
    fn the_lesson_shaders_give_mutants_of_every_kind() {
        let src = std::fs::read_to_string(crate::res::project_res_dir().join("sao.frag"))
            .expect("Res/sao.frag");
        let d = descriptions(&src);
        for what in [
            "min → max",
            "max → min",
            "flip sign",
            "swap operands",
            "×2",
            "×0.5",
            "< → <=",
            "drop statement",
            ".x → .y",
        ] {
            assert!(d.iter().any(|s| s.contains(what)), "no `{what}` in {d:#?}");
        }
        // Nothing from the interface or the engine's defines.
        assert!(
            !d.iter()
                .any(|s| s.starts_with("12:") || s.starts_with("23:")),
            "{d:#?}"
        );
    }
}
