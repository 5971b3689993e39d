//! A bound on the storage a shader declares, checked on the preprocessed source before the GL
//! driver sees it. Mesa's compiler (llvmpipe) lowers a local array indexed at run time into one
//! value per element and a chain of selects per access, so its memory and time grow with the
//! array (measured here on llvmpipe 22.3: a `float[1024]` indexed in a loop took 15 s and 150 MB to
//! compile, `float[4096]` 105 s and 280 MB, `float[20000]` over 5 minutes and 950 MB and still
//! growing), and `float a[100000000]` asks it for gigabytes: its allocation failure aborts the
//! whole process, which no error path can catch. So the declared arrays are added up
//! here (object-like `#define`s expanded, integer `const`s and constant expressions evaluated) and a
//! shader over the bound is refused by file and line. A macro whose expansion would be enormous is
//! refused too, as it would exhaust the driver's preprocessor the same way.
//!
//! The count is in components (a `float` 1, a `vec4` 4, a `mat4` 16, a struct the sum of its
//! members); arrays whose size cannot be evaluated here are left to the compiler.

use std::collections::HashMap;

/// The most components a shader may declare in all its arrays together: 4096 (16 KiB of floats,
/// e.g. 1024 `vec4`s or 256 `mat4`s), well above a screen-space shader's sample kernel or weight
/// table, and what the driver still compiles in minutes and a few hundred MB.
pub const MAX_DECLARED_COMPONENTS: u64 = 1 << 12;
/// The most tokens object-like macros may expand to, in the whole shader.
const MAX_EXPANDED_TOKENS: usize = 1 << 20;

/// Why a shader is refused: the declaration (or macro use) at `line` of source string `source`
/// (0 the shader, k its k-th `#include`).
#[derive(Debug, PartialEq)]
pub enum Refusal {
    /// `name` at `line` declares `components`, the whole shader `total`.
    Storage {
        source: usize,
        line: usize,
        name: String,
        components: u64,
        total: u64,
    },
    /// Macros expand past `MAX_EXPANDED_TOKENS` at `line`.
    Macros { source: usize, line: usize },
}

#[derive(Clone, Debug, PartialEq)]
struct Token {
    text: String,
    source: usize,
    line: usize,
}

/// Checks the preprocessed `text` (the GL compiler's input, with `#line` directives).
pub fn check(text: &str) -> Result<(), Refusal> {
    let tokens = tokens(&strip_comments(text))?;
    Scan::new(&tokens).run()
}

/// `text` with `//` and `/* */` comments blanked, newlines kept so lines do not move.
pub fn strip_comments(text: &str) -> String {
    let mut out = String::with_capacity(text.len());
    let mut chars = text.chars().peekable();
    while let Some(c) = chars.next() {
        match (c, chars.peek()) {
            ('/', Some('/')) => {
                while chars.peek().is_some_and(|&c| c != '\n') {
                    chars.next();
                }
            }
            ('/', Some('*')) => {
                chars.next();
                let mut last = ' ';
                for c in chars.by_ref() {
                    if c == '\n' {
                        out.push('\n');
                    }
                    if last == '*' && c == '/' {
                        break;
                    }
                    last = c;
                }
                out.push(' ');
            }
            _ => out.push(c),
        }
    }
    out
}

/// Splits a line into identifiers/numbers and single punctuation characters.
fn split(line: &str) -> Vec<String> {
    let mut out = Vec::new();
    let mut word = String::new();
    for c in line.chars() {
        if c.is_ascii_alphanumeric() || c == '_' || (c == '.' && starts_number(&word)) {
            word.push(c);
            continue;
        }
        if !word.is_empty() {
            out.push(std::mem::take(&mut word));
        }
        if !c.is_whitespace() {
            out.push(c.to_string());
        }
    }
    if !word.is_empty() {
        out.push(word);
    }
    out
}

fn starts_number(word: &str) -> bool {
    word.starts_with(|c: char| c.is_ascii_digit())
}

/// The source's tokens with `#line` followed and object-like macros expanded.
fn tokens(text: &str) -> Result<Vec<Token>, Refusal> {
    let mut defines: HashMap<String, Vec<String>> = HashMap::new();
    let mut out = Vec::new();
    let (mut source, mut line) = (0usize, 0usize);
    for raw in text.lines() {
        line += 1;
        let words = split(raw);
        if words.first().map(String::as_str) == Some("#") {
            match words.get(1).map(String::as_str) {
                Some("line") => {
                    // `#line N S`: the next line is line N of source string S.
                    if let Some(n) = words.get(2).and_then(|w| w.parse::<usize>().ok()) {
                        line = n.saturating_sub(1);
                    }
                    if let Some(s) = words.get(3).and_then(|w| w.parse().ok()) {
                        source = s;
                    }
                }
                Some("define") => {
                    if let Some(name) = words.get(2) {
                        // A function-like macro has '(' right after its name; it is not expanded.
                        let after = raw.split_once(name.as_str()).map_or("", |(_, r)| r);
                        if !after.starts_with('(') {
                            defines.insert(name.clone(), words[3..].to_vec());
                        }
                    }
                }
                Some("undef") => {
                    if let Some(name) = words.get(2) {
                        defines.remove(name);
                    }
                }
                _ => {}
            }
            continue;
        }
        for w in words {
            expand(&w, &defines, &mut Vec::new(), &mut |text| {
                out.push(Token { text, source, line });
                out.len() <= MAX_EXPANDED_TOKENS
            })
            .then_some(())
            .ok_or(Refusal::Macros { source, line })?;
        }
    }
    Ok(out)
}

/// Emits `word` with object-like macros expanded (a macro is not expanded inside itself, as the
/// C preprocessor does); false once `emit` says the output is too long.
fn expand(
    word: &str,
    defines: &HashMap<String, Vec<String>>,
    active: &mut Vec<String>,
    emit: &mut dyn FnMut(String) -> bool,
) -> bool {
    match defines.get(word) {
        Some(body) if !active.iter().any(|a| a == word) => {
            active.push(word.to_string());
            let ok = body.iter().all(|w| expand(w, defines, active, emit));
            active.pop();
            ok
        }
        _ => emit(word.to_string()),
    }
}

/// Components of one value of a built-in type, `None` for a word that is not one.
fn builtin_components(word: &str) -> Option<u64> {
    let scalar = |w: &str| match w {
        "float" | "int" | "uint" | "bool" => Some(1),
        "double" => Some(2),
        _ => None,
    };
    if let Some(n) = scalar(word) {
        return Some(n);
    }
    let digit = |c: Option<char>| c.and_then(|c| c.to_digit(10)).map(u64::from);
    for (prefix, per) in [
        ("vec", 1),
        ("ivec", 1),
        ("uvec", 1),
        ("bvec", 1),
        ("dvec", 2),
    ] {
        if let Some(rest) = word.strip_prefix(prefix) {
            return digit(rest.chars().next())
                .filter(|_| rest.len() == 1)
                .map(|n| n * per);
        }
    }
    for (prefix, per) in [("mat", 1), ("dmat", 2)] {
        if let Some(rest) = word.strip_prefix(prefix) {
            let mut c = rest.chars();
            let n = digit(c.next())?;
            return match (c.next(), digit(c.next()), c.next()) {
                (None, _, _) => Some(n * n * per),
                (Some('x'), Some(m), None) => Some(n * m * per),
                _ => None,
            };
        }
    }
    (word.starts_with("sampler") || word.starts_with("image")).then_some(1)
}

/// The declaration scan: struct sizes, integer constants, and the running total.
struct Scan<'a> {
    tokens: &'a [Token],
    structs: HashMap<String, u64>,
    consts: HashMap<String, i64>,
}

impl<'a> Scan<'a> {
    fn new(tokens: &'a [Token]) -> Self {
        Scan {
            tokens,
            structs: HashMap::new(),
            consts: HashMap::new(),
        }
    }

    fn text(&self, i: usize) -> &str {
        self.tokens.get(i).map_or("", |t| t.text.as_str())
    }

    fn components(&self, word: &str) -> Option<u64> {
        builtin_components(word).or_else(|| self.structs.get(word).copied())
    }

    fn run(mut self) -> Result<(), Refusal> {
        let mut total = 0u64;
        // Open struct bodies: (name, components so far, brace depth at its '{').
        let mut open: Vec<(String, u64, usize)> = Vec::new();
        let mut depth = 0usize;
        let mut i = 0;
        while i < self.tokens.len() {
            let word = self.text(i).to_string();
            match word.as_str() {
                "{" => depth += 1,
                "}" => {
                    depth = depth.saturating_sub(1);
                    if open.last().is_some_and(|(_, _, d)| *d == depth) {
                        let (name, size) = open.pop().map(|(n, s, _)| (n, s)).unwrap_or_default();
                        self.structs.insert(name, size.max(1));
                    }
                }
                "struct" if self.text(i + 2) == "{" => {
                    open.push((self.text(i + 1).to_string(), 0, depth));
                }
                "const" => self.constant(i),
                _ => {}
            }
            let declares = self.components(&word).is_some()
                && i.checked_sub(1).is_none_or(|p| self.text(p) != ".")
                && (self.text(i + 1) == "[" || (self.is_name(i + 1) && self.text(i + 2) != "("));
            if !declares {
                i += 1;
                continue;
            }
            let (declared, next) = self.declarators(i);
            for (token, components) in declared {
                match open.last_mut() {
                    Some((_, size, _)) => *size = size.saturating_add(components),
                    None => total = total.saturating_add(components),
                }
                if components > MAX_DECLARED_COMPONENTS || total > MAX_DECLARED_COMPONENTS {
                    let t = &self.tokens[token];
                    return Err(Refusal::Storage {
                        source: t.source,
                        line: t.line,
                        name: t.text.clone(),
                        components,
                        total: total.max(components),
                    });
                }
            }
            i = next;
        }
        Ok(())
    }

    fn is_name(&self, i: usize) -> bool {
        let w = self.text(i);
        w.starts_with(|c: char| c.is_ascii_alphabetic() || c == '_')
    }

    /// The declarators of the declaration whose type is at `i` ("float a[4], b[N]"): each name's
    /// token and its components; and the token after the declaration.
    fn declarators(&self, i: usize) -> (Vec<(usize, u64)>, usize) {
        let per = self.components(self.text(i)).unwrap_or(1);
        let (type_count, mut j) = self.dims(i + 1);
        let mut out = Vec::new();
        while self.is_name(j) {
            let name = j;
            let (count, after) = self.dims(j + 1);
            let elements = count.saturating_mul(type_count);
            out.push((name, elements.saturating_mul(per)));
            // Skip an initializer up to the ',' or ';' that ends this declarator.
            j = after;
            let mut nest = 0usize;
            while j < self.tokens.len() {
                match self.text(j) {
                    "(" | "[" | "{" => nest += 1,
                    ")" | "]" | "}" if nest == 0 => return (out, j),
                    ")" | "]" | "}" => nest -= 1,
                    "," | ";" if nest == 0 => break,
                    _ => {}
                }
                j += 1;
            }
            if self.text(j) != "," {
                return (out, j + 1);
            }
            j += 1;
        }
        (out, j.max(i + 1))
    }

    /// The product of the array sizes `[e][e]...` starting at `i` (1 for none; an unsized or
    /// unevaluable size counts 1) and the token after them.
    fn dims(&self, mut i: usize) -> (u64, usize) {
        let mut product = 1u64;
        while self.text(i) == "[" {
            let Some(close) = self.matching(i) else {
                return (product, self.tokens.len());
            };
            let words: Vec<&str> = (i + 1..close).map(|k| self.text(k)).collect();
            if let Some(n) = Expr::new(&words, &self.consts).parse() {
                product = product.saturating_mul(n.max(1) as u64);
            }
            i = close + 1;
        }
        (product, i)
    }

    fn matching(&self, open: usize) -> Option<usize> {
        let mut nest = 0usize;
        for k in open..self.tokens.len() {
            match self.text(k) {
                "[" => nest += 1,
                "]" if nest == 1 => return Some(k),
                "]" => nest -= 1,
                _ => {}
            }
        }
        None
    }

    /// Records `const int|uint NAME = expr;` starting at the `const` at `i`.
    fn constant(&mut self, i: usize) {
        let mut j = i + 1;
        while matches!(self.text(j), "highp" | "mediump" | "lowp" | "precise") {
            j += 1;
        }
        if !matches!(self.text(j), "int" | "uint") || self.text(j + 2) != "=" {
            return;
        }
        let end = (j + 3..self.tokens.len())
            .find(|&k| self.text(k) == ";")
            .unwrap_or(self.tokens.len());
        let words: Vec<&str> = (j + 3..end).map(|k| self.text(k)).collect();
        if let Some(v) = Expr::new(&words, &self.consts).parse() {
            self.consts.insert(self.text(j + 1).to_string(), v);
        }
    }
}

/// An integer constant expression: literals, known constants, parentheses, unary -, + - * / % << >>.
struct Expr<'a> {
    words: &'a [&'a str],
    at: usize,
    consts: &'a HashMap<String, i64>,
}

impl<'a> Expr<'a> {
    fn new(words: &'a [&'a str], consts: &'a HashMap<String, i64>) -> Self {
        Expr {
            words,
            at: 0,
            consts,
        }
    }

    /// The value, if the whole expression is understood.
    fn parse(mut self) -> Option<i64> {
        let v = self.shift()?;
        (self.at == self.words.len()).then_some(v)
    }

    fn peek(&self) -> &str {
        self.words.get(self.at).copied().unwrap_or("")
    }

    fn shift(&mut self) -> Option<i64> {
        let mut v = self.sum()?;
        while matches!(
            (self.peek(), self.words.get(self.at + 1)),
            ("<" | ">", Some(&"<" | &">"))
        ) {
            let left = self.peek() == "<";
            self.at += 2;
            let by = u32::try_from(self.sum()?).ok().filter(|&b| b < 63)?;
            v = if left { v.checked_shl(by)? } else { v >> by };
        }
        Some(v)
    }

    fn sum(&mut self) -> Option<i64> {
        let mut v = self.product()?;
        while matches!(self.peek(), "+" | "-") {
            let plus = self.peek() == "+";
            self.at += 1;
            let r = self.product()?;
            v = if plus {
                v.checked_add(r)?
            } else {
                v.checked_sub(r)?
            };
        }
        Some(v)
    }

    fn product(&mut self) -> Option<i64> {
        let mut v = self.unary()?;
        while matches!(self.peek(), "*" | "/" | "%") {
            let op = self.peek().to_string();
            self.at += 1;
            let r = self.unary()?;
            v = match op.as_str() {
                "*" => v.saturating_mul(r),
                "/" => v.checked_div(r)?,
                _ => v.checked_rem(r)?,
            };
        }
        Some(v)
    }

    fn unary(&mut self) -> Option<i64> {
        match self.peek() {
            "-" => {
                self.at += 1;
                self.unary().map(|v| v.saturating_neg())
            }
            "+" => {
                self.at += 1;
                self.unary()
            }
            "(" => {
                self.at += 1;
                let v = self.shift()?;
                (self.peek() == ")").then_some(())?;
                self.at += 1;
                Some(v)
            }
            word => {
                let v = literal(word).or_else(|| self.consts.get(word).copied())?;
                self.at += 1;
                Some(v)
            }
        }
    }
}

/// A GLSL integer literal (decimal, octal, hex; `u` suffix).
fn literal(word: &str) -> Option<i64> {
    let w = word.trim_end_matches(['u', 'U']);
    if let Some(hex) = w.strip_prefix("0x").or_else(|| w.strip_prefix("0X")) {
        i64::from_str_radix(hex, 16).ok()
    } else if w.len() > 1 && w.starts_with('0') {
        i64::from_str_radix(&w[1..], 8).ok()
    } else {
        w.parse().ok()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn refused(src: &str) -> Option<(usize, String, u64)> {
        match check(src) {
            Err(Refusal::Storage {
                line,
                name,
                components,
                ..
            }) => Some((line, name, components)),
            _ => None,
        }
    }

    #[test]
    fn course_sized_arrays_pass() {
        let src = "#version 450\nuniform vec3 kernel[64];\nconst int N = 16;\nvoid main() {\n  \
                   float w[N * 2]; vec4 taps[5]; mat4 m[4];\n  w[100000000] = 1.0;\n}\n";
        assert_eq!(check(src), Ok(()));
    }

    #[test]
    fn a_huge_local_array_is_refused_by_line_and_name() {
        let src = "#version 450\nvoid main() {\n  float a[100000000];\n}\n";
        assert_eq!(refused(src), Some((3, "a".into(), 100_000_000)));
    }

    #[test]
    fn sizes_through_defines_consts_dimensions_and_types_count() {
        let define = "#version 450\n#define N 100\nvoid main() { float a[N][N]; }\n";
        assert_eq!(refused(define), Some((3, "a".into(), 10_000)));
        let constant = "#version 450\nconst uint K = 1u << 6;\nvec4 big[K * K];\n";
        assert_eq!(refused(constant), Some((3, "big".into(), 16_384)));
        // Each fits alone; together they do not.
        let list = "#version 450\nfloat small[4], b[3000], c[2000];\n";
        assert_eq!(refused(list), Some((2, "c".into(), 2000)));
        let array_type = "#version 450\nmat4[500] m;\n";
        assert_eq!(refused(array_type), Some((2, "m".into(), 8000)));
        let structs = "#version 450\nstruct S { float x[100]; vec4 y; };\nS s[100];\n";
        assert_eq!(refused(structs), Some((3, "s".into(), 10_400)));
        // `#line` directives name the source string and line the compiler would.
        let included = "#version 450\n#line 1 2\n\nfloat a[300000];\n";
        let Err(Refusal::Storage { source, line, .. }) = check(included) else {
            panic!("not refused");
        };
        assert_eq!((source, line), (2, 2));
    }

    #[test]
    fn comments_and_function_like_macros_do_not_count() {
        let src = "#version 450\n// float a[100000000];\n/* float b[100000000]; */\n\
                   #define F(x) x\nvoid main() { }\n";
        assert_eq!(check(src), Ok(()));
    }

    #[test]
    fn an_exploding_macro_is_refused() {
        let mut src = String::from("#version 450\n#define A0 x\n");
        for k in 1..40 {
            src.push_str(&format!("#define A{k} A{} A{}\n", k - 1, k - 1));
        }
        src.push_str("float f = A39;\n");
        assert!(matches!(check(&src), Err(Refusal::Macros { line: 42, .. })));
    }

    #[test]
    fn every_shader_of_the_project_passes() {
        fn walk(dir: &std::path::Path, found: &mut Vec<std::path::PathBuf>) {
            for entry in std::fs::read_dir(dir).unwrap().flatten() {
                let path = entry.path();
                if path.is_dir() {
                    walk(&path, found);
                } else if path
                    .extension()
                    .is_some_and(|e| e == "frag" || e == "vert" || e == "glsl")
                {
                    found.push(path);
                }
            }
        }
        let mut found = Vec::new();
        walk(
            &std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("Res"),
            &mut found,
        );
        assert!(found.len() > 20, "{found:?}");
        for path in found {
            let text = std::fs::read_to_string(&path).unwrap();
            assert_eq!(check(&text), Ok(()), "{}", path.display());
        }
    }
}
