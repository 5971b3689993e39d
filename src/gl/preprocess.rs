//! The one shader preprocessor, used by the engine and the grader: decodes the file (UTF-8, UTF-16,
//! Shift-JIS), expands `#include "file"`, injects `#define`s after `#version` with `#line` so that
//! compiler messages keep the file's line numbers, and maps driver logs back to `file:line:col`.
//!
//! Shaders may be a student's untrusted files (the grader runs them): an `#include` must stay in
//! the including shader's folder, and a file over `MAX_SHADER_BYTES` is refused before it is read.

use super::shader_error::ProgramError;
use std::io::Read as _;
use std::path::{Path, PathBuf};

/// The largest shader file accepted. The course's biggest shader is about 10 kB; a file of
/// megabytes is a mistake (or an attempt to make the compiler or the grader run out of memory).
pub const MAX_SHADER_BYTES: u64 = 1 << 20;

/// Decoded shader source with its path (for messages).
#[derive(Clone, Debug)]
pub struct ShaderSource {
    pub path: PathBuf,
    pub text: String,
    /// The encoding the file was decoded from (the GL compiler only takes ASCII; anything but UTF-8 is
    /// worth a warning so the student can re-save the file).
    pub encoding: TextEncoding,
    /// Where an `#include` not found beside the shader is looked for next: the engine's own
    /// headers (`Res/ao/`) for a method file's shader, which lives in the user's folder.
    pub include_fallback: Option<PathBuf>,
}

impl ShaderSource {
    /// Reads and decodes `path`; a file over `MAX_SHADER_BYTES` is refused by its size before it
    /// is read.
    pub fn load(path: &Path) -> Result<ShaderSource, ProgramError> {
        let shown = path.display().to_string();
        let io = |cause| ProgramError::Io {
            path: shown.clone(),
            cause,
        };
        let file = std::fs::File::open(path).map_err(io)?;
        let size = file.metadata().map_err(io)?.len();
        if size > MAX_SHADER_BYTES {
            return Err(io(too_big(size)));
        }
        // The size on disk can lie (a device, a pipe, a file still growing): read at most one byte
        // past the limit, so that nothing larger is ever held in memory.
        let mut bytes = Vec::with_capacity(size as usize);
        file.take(MAX_SHADER_BYTES + 1)
            .read_to_end(&mut bytes)
            .map_err(io)?;
        if bytes.len() as u64 > MAX_SHADER_BYTES {
            return Err(io(too_big(bytes.len() as u64)));
        }
        let (text, encoding) =
            decode_shader_bytes(&bytes).ok_or(ProgramError::Encoding { path: shown })?;
        Ok(ShaderSource {
            path: path.to_path_buf(),
            text,
            encoding,
            include_fallback: None,
        })
    }
}

/// The error for a shader file of `size` bytes (or more), over the limit.
fn too_big(size: u64) -> std::io::Error {
    std::io::Error::new(
        std::io::ErrorKind::InvalidData,
        format!(
            "the file is {size} bytes or more; shader files over {} bytes (1 MiB) are refused",
            MAX_SHADER_BYTES
        ),
    )
}

/// The text encodings a shader file may come in (Windows editors save UTF-16 as "Unicode" and
/// Shift-JIS as "ANSI" on Japanese systems).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum TextEncoding {
    Utf8,
    Utf16Le,
    Utf16Be,
    ShiftJis,
}

impl TextEncoding {
    pub fn name(self) -> &'static str {
        match self {
            TextEncoding::Utf8 => "UTF-8",
            TextEncoding::Utf16Le => "UTF-16LE",
            TextEncoding::Utf16Be => "UTF-16BE",
            TextEncoding::ShiftJis => "Shift-JIS",
        }
    }
}

/// UTF-16 with a byte-order mark, or without one when every other byte of an ASCII-looking text is
/// zero; then UTF-8 (with or without BOM); then Shift-JIS. `None` when none decodes cleanly.
pub fn decode_shader_bytes(bytes: &[u8]) -> Option<(String, TextEncoding)> {
    if let Some(enc) = utf16_encoding(bytes) {
        let (codec, le) = match enc {
            TextEncoding::Utf16Le => (encoding_rs::UTF_16LE, true),
            _ => (encoding_rs::UTF_16BE, false),
        };
        let body = match (le, bytes) {
            (true, [0xFF, 0xFE, rest @ ..]) | (false, [0xFE, 0xFF, rest @ ..]) => rest,
            _ => bytes,
        };
        let (text, had_errors) = codec.decode_without_bom_handling(body);
        return (!had_errors).then(|| (text.into_owned(), enc));
    }
    let bytes = bytes.strip_prefix(&[0xEF, 0xBB, 0xBF]).unwrap_or(bytes);
    if let Ok(s) = std::str::from_utf8(bytes) {
        if !s.contains('\0') {
            return Some((s.to_string(), TextEncoding::Utf8));
        }
    }
    let (text, _, had_errors) = encoding_rs::SHIFT_JIS.decode(bytes);
    if had_errors || text.contains('\0') {
        return None;
    }
    Some((text.into_owned(), TextEncoding::ShiftJis))
}

/// UTF-16 by its BOM, or by zero bytes: GLSL source is mostly ASCII, so UTF-16 text has a zero in
/// (nearly) every high byte, which no UTF-8 or Shift-JIS text has.
fn utf16_encoding(bytes: &[u8]) -> Option<TextEncoding> {
    match bytes {
        [0xFF, 0xFE, ..] => return Some(TextEncoding::Utf16Le),
        [0xFE, 0xFF, ..] => return Some(TextEncoding::Utf16Be),
        _ => {}
    }
    if bytes.len() < 8 || !bytes.len().is_multiple_of(2) {
        return None;
    }
    let zeros_at = |parity: usize| {
        bytes
            .iter()
            .skip(parity)
            .step_by(2)
            .filter(|b| **b == 0)
            .count()
    };
    let half = bytes.len() / 2;
    // At least 90 % of the high bytes zero: ASCII in UTF-16.
    if zeros_at(1) * 10 >= half * 9 && zeros_at(0) == 0 {
        Some(TextEncoding::Utf16Le)
    } else if zeros_at(0) * 10 >= half * 9 && zeros_at(1) == 0 {
        Some(TextEncoding::Utf16Be)
    } else {
        None
    }
}

/// The file named by an `#include "name"` line, if `line` is one (the one place that parses the
/// directive: the engine's preprocessor and the grader's staging both use it).
pub fn include_target(line: &str) -> Option<&str> {
    let rest = line.trim_start().strip_prefix("#include")?;
    let name = rest.trim().trim_matches('"');
    (!name.is_empty()).then_some(name)
}

/// The file an `#include "name"` on line `line` (1-based) of `shader` names, checked to stay inside
/// the shader's folder: no absolute path, no `..`, and, once symbolic links are followed, still
/// below the folder. Only the paths are looked at: a refused target is never opened, so its text
/// cannot leak into a message. A target that does not exist is an I/O error naming it.
pub fn resolve_include(shader: &Path, line: usize, name: &str) -> Result<PathBuf, ProgramError> {
    let dir = shader.parent().unwrap_or(Path::new("."));
    let dir = if dir.as_os_str().is_empty() {
        Path::new(".")
    } else {
        dir
    };
    let refuse = |why: &str| {
        let at = format!("{}:{line}", shader.display());
        ProgramError::Compile {
            messages: vec![format!(
                "{at}: #include \"{name}\" {why}; an included file must be in the shader's \
                 folder {} or below it",
                dir.display()
            )],
            path: shader.display().to_string(),
        }
    };
    // Both separators: a `..\` written on Windows must not slip through on Linux either.
    let absolute = Path::new(name).is_absolute()
        || name.starts_with(['/', '\\'])
        || name.chars().nth(1) == Some(':');
    if absolute {
        return Err(refuse("is an absolute path"));
    }
    if name.split(['/', '\\']).any(|part| part == "..") {
        return Err(refuse("goes up with '..'"));
    }
    let path = dir.join(name);
    let io = |p: &Path| {
        let shown = format!("{} (included at {}:{line})", p.display(), shader.display());
        move |cause| ProgramError::Io { path: shown, cause }
    };
    let real_dir = dir.canonicalize().map_err(io(dir))?;
    let real = path.canonicalize().map_err(io(&path))?;
    if !real.starts_with(&real_dir) {
        return Err(refuse("leads outside it through a symbolic link"));
    }
    Ok(path)
}

/// `resolve_include`, then, for a file the shader's folder does not have, the source's fallback
/// folder under the same rules.
fn resolve_include_with_fallback(
    src: &ShaderSource,
    line: usize,
    name: &str,
) -> Result<PathBuf, ProgramError> {
    let beside = resolve_include(&src.path, line, name);
    match (&src.include_fallback, beside) {
        (Some(folder), Err(ProgramError::Io { .. })) if folder.join(name).is_file() => {
            // Resolved as if the shader were in that folder: the same confinement applies there.
            let stand_in = folder.join(src.path.file_name().unwrap_or_default());
            resolve_include(&stand_in, line, name)
        }
        (_, beside) => beside,
    }
}

/// A float literal GLSL accepts, exact for f32 (Rust's shortest round-trip form plus a '.0' if needed).
pub fn glsl_float(v: f32) -> String {
    let s = format!("{v:?}");
    if s.contains('.') || s.contains('e') || s.contains("inf") || s.contains("NaN") {
        s
    } else {
        format!("{s}.0")
    }
}

/// Prepares source for the GL compiler: inserts `#define`s after `#version` (with `#line` so that
/// error lines still match the file) and blanks non-ASCII characters (Japanese comments), which GLSL
/// does not allow, without moving any line.
pub fn prepare_source(
    src: &ShaderSource,
    defines: &[(String, String)],
) -> Result<String, ProgramError> {
    prepare_source_with_includes(src, defines).map(|(text, _)| text)
}

/// As `prepare_source`, also expanding `#include "file"` lines (relative to the shader's folder,
/// one level deep) with `#line` directives so that errors map back to the right file: source string
/// 0 is the shader itself, k is the k-th included file (the returned list, in order).
pub fn prepare_source_with_includes(
    src: &ShaderSource,
    defines: &[(String, String)],
) -> Result<(String, Vec<PathBuf>), ProgramError> {
    let mut out = String::with_capacity(src.text.len() + 128);
    let mut includes = Vec::new();
    let mut seen_version = false;
    let ascii_only = |line: &str| -> String {
        line.chars()
            .map(|c| if c.is_ascii() { c } else { ' ' })
            .collect()
    };
    for (i, line) in src.text.lines().enumerate() {
        let ascii = ascii_only(line);
        if let Some(name) = include_target(&ascii) {
            let path = resolve_include_with_fallback(src, i + 1, name)?;
            include_cycle(&src.path, i + 1, name, &path)?;
            let inc = ShaderSource::load(&path)?;
            includes.push(path);
            out.push_str(&format!("#line 1 {}\n", includes.len()));
            for l in inc.text.lines() {
                out.push_str(&ascii_only(l));
                out.push('\n');
            }
            out.push_str(&format!("#line {} 0\n", i + 2));
            continue;
        }
        out.push_str(&ascii);
        out.push('\n');
        if !seen_version && ascii.trim_start().starts_with("#version") {
            seen_version = true;
            for (k, v) in defines {
                out.push_str(&format!("#define {k} {v}\n"));
            }
            // GLSL's #line N says the *next* line is N.
            out.push_str(&format!("#line {}\n", i + 2));
        }
    }
    if !seen_version {
        return Err(ProgramError::NoVersion {
            path: src.path.display().to_string(),
        });
    }
    Ok((out, includes))
}

/// Whether `#include "name"` on line `line` of `shader`, resolved to `included`, closes a cycle:
/// `included` is the shader itself, or one of its own `#include` lines leads back to the shader or to
/// itself. Expanded, such a file would bring a second `#version` (or an `#include` the compiler does
/// not know) into the middle of the source, and the compiler's message would blame that instead.
fn include_cycle(
    shader: &Path,
    line: usize,
    name: &str,
    included: &Path,
) -> Result<(), ProgramError> {
    let same = |a: &Path, b: &Path| match (a.canonicalize(), b.canonicalize()) {
        (Ok(a), Ok(b)) => a == b,
        _ => false,
    };
    let cycle = |target: &Path| ProgramError::IncludeCycle {
        path: shader.display().to_string(),
        line,
        name: name.to_string(),
        target: target.display().to_string(),
    };
    if same(shader, included) {
        return Err(cycle(shader));
    }
    // The chain of includes below it (a -> b -> a as well as a -> a), bounded in depth and files.
    let (Ok(top), Ok(first)) = (shader.canonicalize(), included.canonicalize()) else {
        return Ok(());
    };
    let mut chain = vec![top, first];
    let mut budget = 256;
    match leads_back(included, &mut chain, &mut budget) {
        Some(target) => Err(cycle(&target)),
        None => Ok(()),
    }
}

/// The first file that `file`'s `#include` lines, followed down, lead back to while it is still on
/// `chain` (the files being expanded, outermost first). `budget` bounds the files looked at.
fn leads_back(file: &Path, chain: &mut Vec<PathBuf>, budget: &mut usize) -> Option<PathBuf> {
    let inner = ShaderSource::load(file).ok()?;
    for (k, l) in inner.text.lines().enumerate() {
        let Some(name) = include_target(l) else {
            continue;
        };
        let Ok(target) = resolve_include(file, k + 1, name) else {
            continue;
        };
        let Ok(real) = target.canonicalize() else {
            continue;
        };
        if chain.contains(&real) {
            return Some(target);
        }
        if *budget == 0 || chain.len() >= 32 {
            return None;
        }
        *budget -= 1;
        chain.push(real);
        let found = leads_back(&target, chain, budget);
        chain.pop();
        if found.is_some() {
            return found;
        }
    }
    None
}

/// Turns a driver log ("0:12(5): error: ...") into "path:12:5: error: ..." lines.
pub fn format_compile_log(path: &str, log: &str) -> Vec<String> {
    format_compile_log_sources(path, &[], log)
}

/// As `format_compile_log`, naming included files by their source-string number (1, 2, …).
pub fn format_compile_log_sources(path: &str, includes: &[PathBuf], log: &str) -> Vec<String> {
    let mut out = Vec::new();
    for line in log.lines().map(str::trim).filter(|l| !l.is_empty()) {
        // Mesa: "0:12(5): error: msg"; NVIDIA: "0(12) : error C0000: msg".
        let parsed = parse_mesa(line).or_else(|| parse_nvidia(line));
        let source: usize = line
            .split([':', '('])
            .next()
            .and_then(|s| s.trim().parse().ok())
            .unwrap_or(0);
        let inc_name;
        let path = match source.checked_sub(1).and_then(|k| includes.get(k)) {
            Some(p) => {
                inc_name = p.display().to_string();
                inc_name.as_str()
            }
            None => path,
        };
        match parsed {
            Some((l, c, msg)) => out.push(match c {
                Some(c) => format!("{path}:{l}:{c}: {msg}"),
                None => format!("{path}:{l}: {msg}"),
            }),
            None => out.push(format!("{path}: {line}")),
        }
    }
    if out.is_empty() {
        out.push(format!("{path}: compile failed (driver gave no log)"));
    }
    out
}

fn parse_mesa(line: &str) -> Option<(u32, Option<u32>, String)> {
    let (head, msg) = line.split_once("): ")?;
    let (_, rest) = head.split_once(':')?;
    let (l, c) = rest.split_once('(')?;
    Some((
        l.trim().parse().ok()?,
        c.trim().parse().ok(),
        msg.trim().to_string(),
    ))
}

fn parse_nvidia(line: &str) -> Option<(u32, Option<u32>, String)> {
    let (head, msg) = line.split_once(") :")?;
    let (_, l) = head.split_once('(')?;
    Some((l.trim().parse().ok()?, None, msg.trim().to_string()))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A fresh folder under the system's temporary folder.
    fn scratch(name: &str) -> PathBuf {
        let d =
            std::env::temp_dir().join(format!("opengl3d-preprocess-{name}-{}", std::process::id()));
        match std::fs::remove_dir_all(&d) {
            Err(e) if e.kind() != std::io::ErrorKind::NotFound => panic!("{}: {e}", d.display()),
            _ => {}
        }
        std::fs::create_dir_all(d.join("shaders/lib")).unwrap();
        std::fs::write(d.join("secret.glsl"), "SECRET TEXT").unwrap();
        std::fs::write(d.join("shaders/lib/ok.glsl"), "float ok;").unwrap();
        d
    }

    /// Builds `shaders/s.frag` holding `include` on its line 3; the error text, or "" when it built.
    fn build_with(root: &Path, include: &str) -> String {
        let shader = root.join("shaders/s.frag");
        std::fs::write(
            &shader,
            format!("#version 450\n\n{include}\nvoid main() {{}}\n"),
        )
        .unwrap();
        let src = ShaderSource::load(&shader).unwrap();
        match prepare_source_with_includes(&src, &[]) {
            Ok(_) => String::new(),
            Err(e) => e.to_string(),
        }
    }

    #[test]
    fn an_include_the_folder_lacks_comes_from_the_fallback_under_the_same_rules() {
        let root = scratch("fallback");
        let engine = root.join("engine");
        std::fs::create_dir_all(&engine).unwrap();
        std::fs::write(engine.join("common.glsl"), "float fromEngine;").unwrap();
        std::fs::write(root.join("shaders/lib/own.glsl"), "float own;").unwrap();
        std::fs::write(engine.join("own.glsl"), "float engineOwn;").unwrap();
        let shader = root.join("shaders/s.frag");
        let expand = |include: &str, fallback: Option<&Path>| {
            std::fs::write(
                &shader,
                format!("#version 450\n{include}\nvoid main() {{}}\n"),
            )
            .unwrap();
            let mut src = ShaderSource::load(&shader).unwrap();
            src.include_fallback = fallback.map(Path::to_path_buf);
            prepare_source_with_includes(&src, &[]).map(|(text, _)| text)
        };
        let text = expand("#include \"common.glsl\"", Some(&engine)).unwrap();
        assert!(text.contains("fromEngine"), "{text}");
        // Without the fallback the same include is a missing file.
        assert!(expand("#include \"common.glsl\"", None).is_err());
        // The shader's own folder wins.
        let text = expand("#include \"lib/own.glsl\"", Some(&engine)).unwrap();
        assert!(
            text.contains("float own;") && !text.contains("engineOwn"),
            "{text}"
        );
        // Climbing out stays refused, in the fallback too.
        for include in [
            "#include \"../secret.glsl\"",
            "#include \"../engine/common.glsl\"",
        ] {
            let e = expand(include, Some(&engine)).unwrap_err().to_string();
            assert!(e.contains("'..'"), "{include}: {e}");
        }
        std::fs::remove_dir_all(&root).unwrap();
    }

    #[test]
    fn includes_out_of_the_shaders_folder_are_refused_unread() {
        let root = scratch("escape");
        let secret = root.join("secret.glsl");
        std::os::unix::fs::symlink(&secret, root.join("shaders/link.glsl")).unwrap();
        for include in [
            format!("#include \"{}\"", secret.display()),
            "#include \"/etc/passwd\"".to_string(),
            "#include \"../secret.glsl\"".to_string(),
            "#include \"lib/../../secret.glsl\"".to_string(),
            "#include \"..\\secret.glsl\"".to_string(),
            "#include \"link.glsl\"".to_string(),
        ] {
            let e = build_with(&root, &include);
            assert!(e.contains("shaders/s.frag:3: #include"), "{include}: {e}");
            assert!(e.contains("in the shader's folder"), "{include}: {e}");
            assert!(
                !e.contains("SECRET") && !e.contains("root:"),
                "{include}: {e}"
            );
        }
        assert_eq!(build_with(&root, "#include \"lib/ok.glsl\""), "");
        let e = build_with(&root, "#include \"lib/none.glsl\"");
        assert!(e.contains("lib/none.glsl (included at "), "{e}");
        assert!(e.contains("shaders/s.frag:3)"), "{e}");
        std::fs::remove_dir_all(&root).unwrap();
    }

    #[test]
    fn an_include_that_leads_back_is_a_cycle() {
        let root = scratch("cycle");
        // The shader itself.
        let e = build_with(&root, "#include \"s.frag\"");
        assert!(
            e.contains("shaders/s.frag:3: #include \"s.frag\" includes"),
            "{e}"
        );
        assert!(e.contains("an #include cycle"), "{e}");
        // Through the file it includes, back to the shader or to that file.
        std::fs::write(root.join("shaders/self.glsl"), "#include \"self.glsl\"\n").unwrap();
        let e = build_with(&root, "#include \"self.glsl\"");
        assert!(e.contains("self.glsl again: an #include cycle"), "{e}");
        std::fs::write(root.join("shaders/a.glsl"), "#include \"s.frag\"\n").unwrap();
        let e = build_with(&root, "#include \"a.glsl\"");
        assert!(
            e.contains("shaders/s.frag:3: #include \"a.glsl\" includes"),
            "{e}"
        );
        assert!(e.contains("s.frag again: an #include cycle"), "{e}");
        // Two files that include each other, below the shader: a -> b -> a.
        std::fs::write(root.join("shaders/p.glsl"), "#include \"q.glsl\"\n").unwrap();
        std::fs::write(
            root.join("shaders/q.glsl"),
            "float q;\n#include \"p.glsl\"\n",
        )
        .unwrap();
        let e = build_with(&root, "#include \"p.glsl\"");
        assert!(
            e.contains("#include \"p.glsl\" includes")
                && e.contains("p.glsl again: an #include cycle"),
            "{e}"
        );
        // An ordinary include still builds.
        assert_eq!(build_with(&root, "#include \"lib/ok.glsl\""), "");
        std::fs::remove_dir_all(&root).unwrap();
    }

    #[test]
    fn a_shader_over_one_mib_is_refused_by_name_and_size() {
        let root = scratch("big");
        let big = root.join("big.frag");
        let mut text = b"#version 450\n".to_vec();
        text.resize(MAX_SHADER_BYTES as usize + 1, b' ');
        std::fs::write(&big, &text).unwrap();
        let e = ShaderSource::load(&big).unwrap_err().to_string();
        assert!(e.contains("big.frag"), "{e}");
        assert!(e.contains("1048577 bytes"), "{e}");
        text.truncate(MAX_SHADER_BYTES as usize);
        std::fs::write(&big, &text).unwrap();
        assert!(ShaderSource::load(&big).is_ok(), "exactly 1 MiB is allowed");
        std::fs::remove_dir_all(&root).unwrap();
    }
}
