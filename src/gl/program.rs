//! `ProgramObject`: a vertex + fragment program built from shader files in `Res/`.
//!
//! Errors name the file and line (`Res/sao.frag:42: ...`), a failed rebuild keeps the last working
//! program, and files saved as Shift-JIS (common on Japanese Windows) are decoded rather than rejected.

use super::Gl;
use crate::res::ResDirs;
use glow::HasContext;
use std::path::{Path, PathBuf};
use std::time::SystemTime;

#[derive(Debug, thiserror::Error)]
pub enum ProgramError {
    #[error("{path}: cannot read shader file: {source}")]
    Io {
        path: String,
        source: std::io::Error,
    },
    #[error("{path}: shader file is neither UTF-8 nor Shift-JIS text; save it as UTF-8")]
    Encoding { path: String },
    #[error("{path}: no '#version' line (the course's shaders start with '#version 450')")]
    NoVersion { path: String },
    #[error("{}", .messages.join("\n"))]
    Compile { path: String, messages: Vec<String> },
    #[error("{vert} + {frag}: link error: {log}")]
    Link {
        vert: String,
        frag: String,
        log: String,
    },
    #[error("shader '{name}' not found in {searched}")]
    NotFound { name: String, searched: String },
    #[error("GL error: {0}")]
    Gl(String),
}

impl ProgramError {
    /// The first `file:line` this error points at, if any (for an editor or the window's overlay).
    pub fn location(&self) -> Option<String> {
        match self {
            ProgramError::Compile { messages, .. } => messages.first().and_then(|m| {
                let mut parts = m.splitn(3, ':');
                Some(format!("{}:{}", parts.next()?, parts.next()?))
            }),
            _ => None,
        }
    }
}

/// Decoded shader source with its path (for messages).
#[derive(Clone, Debug)]
pub struct ShaderSource {
    pub path: PathBuf,
    pub text: String,
    /// True when the file was not UTF-8 and was decoded as Shift-JIS.
    pub was_shift_jis: bool,
}

impl ShaderSource {
    pub fn load(path: &Path) -> Result<ShaderSource, ProgramError> {
        let shown = path.display().to_string();
        let bytes = std::fs::read(path).map_err(|source| ProgramError::Io {
            path: shown.clone(),
            source,
        })?;
        let (text, was_shift_jis) =
            decode_shader_bytes(&bytes).ok_or(ProgramError::Encoding { path: shown })?;
        Ok(ShaderSource {
            path: path.to_path_buf(),
            text,
            was_shift_jis,
        })
    }
}

/// UTF-8 (with or without BOM) first, then Shift-JIS; `None` when neither decodes cleanly.
pub fn decode_shader_bytes(bytes: &[u8]) -> Option<(String, bool)> {
    let bytes = bytes.strip_prefix(&[0xEF, 0xBB, 0xBF]).unwrap_or(bytes);
    if let Ok(s) = std::str::from_utf8(bytes) {
        return Some((s.to_string(), false));
    }
    let (text, _, had_errors) = encoding_rs::SHIFT_JIS.decode(bytes);
    if had_errors || text.contains('\0') {
        return None;
    }
    Some((text.into_owned(), true))
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
        if let Some(rest) = ascii.trim_start().strip_prefix("#include") {
            let name = rest.trim().trim_matches('"');
            let path = src.path.parent().unwrap_or(Path::new(".")).join(name);
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
            .split(|c| c == ':' || c == '(')
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

pub struct ProgramObject {
    gl: Gl,
    id: glow::Program,
    vert_path: PathBuf,
    frag_path: PathBuf,
    defines: Vec<(String, String)>,
    stamp: Option<(SystemTime, SystemTime)>,
    /// Locations of the active uniforms: setting an absent location is a GL error, and a student's
    /// shader may lack this port's optional uniforms (or the compiler may have removed unused ones).
    active: std::collections::HashSet<i32>,
}

fn active_locations(gl: &glow::Context, p: glow::Program) -> std::collections::HashSet<i32> {
    let mut out = std::collections::HashSet::new();
    unsafe {
        for i in 0..gl.get_active_uniforms(p) {
            if let Some(u) = gl.get_active_uniform(p, i) {
                if let Some(l) = gl.get_uniform_location(p, &u.name) {
                    out.insert(l.0 as i32);
                }
            }
        }
    }
    out
}

fn mtime(p: &Path) -> Option<SystemTime> {
    std::fs::metadata(p).and_then(|m| m.modified()).ok()
}

impl ProgramObject {
    /// Builds a program from `vert` and `frag`, looked up in `res` (first folder that has the file wins).
    pub fn from_res(
        gl: &Gl,
        res: &ResDirs,
        vert: &str,
        frag: &str,
        defines: &[(&str, String)],
    ) -> Result<ProgramObject, ProgramError> {
        let vert_path = res.find(vert)?;
        let frag_path = res.find(frag)?;
        let defines: Vec<(String, String)> = defines
            .iter()
            .map(|(k, v)| (k.to_string(), v.clone()))
            .collect();
        let id = build(gl, &vert_path, &frag_path, &defines)?;
        let stamp = mtime(&vert_path).zip(mtime(&frag_path));
        let active = active_locations(gl, id);
        Ok(ProgramObject {
            gl: gl.clone(),
            id,
            vert_path,
            frag_path,
            defines,
            stamp,
            active,
        })
    }

    /// Rebuilds from the files; on failure the previous program stays in use and the error is returned.
    pub fn reload(&mut self) -> Result<(), ProgramError> {
        self.stamp = mtime(&self.vert_path).zip(mtime(&self.frag_path));
        let id = build(&self.gl, &self.vert_path, &self.frag_path, &self.defines)?;
        unsafe { self.gl.delete_program(self.id) };
        self.id = id;
        self.active = active_locations(&self.gl, id);
        Ok(())
    }

    /// Changes the injected defines and rebuilds (keeps the old program on failure).
    pub fn set_defines(&mut self, defines: &[(&str, String)]) -> Result<(), ProgramError> {
        let new: Vec<(String, String)> = defines
            .iter()
            .map(|(k, v)| (k.to_string(), v.clone()))
            .collect();
        if new == self.defines {
            return Ok(());
        }
        let old = std::mem::replace(&mut self.defines, new);
        self.reload().inspect_err(|_| {
            self.defines = old;
        })
    }

    /// True when either source file changed on disk since the last build attempt.
    pub fn sources_changed(&self) -> bool {
        mtime(&self.vert_path).zip(mtime(&self.frag_path)) != self.stamp
    }

    pub fn id(&self) -> glow::Program {
        self.id
    }
    pub fn frag_path(&self) -> &Path {
        &self.frag_path
    }
    pub fn vert_path(&self) -> &Path {
        &self.vert_path
    }
    pub fn use_program(&self) {
        unsafe { self.gl.use_program(Some(self.id)) }
    }

    /// True when the program has an active uniform called `name` (optional uniforms of this port).
    pub fn has_uniform(&self, name: &str) -> bool {
        unsafe { self.gl.get_uniform_location(self.id, name).is_some() }
    }

    fn loc(location: i32) -> glow::UniformLocation {
        glow::NativeUniformLocation(location as u32)
    }
    /// True when the program has an active uniform at `location`.
    pub fn has_location(&self, location: i32) -> bool {
        self.active.contains(&location)
    }
    pub fn set_i32(&self, location: i32, v: i32) {
        if !self.has_location(location) {
            return;
        }
        unsafe {
            self.gl
                .program_uniform_1_i32(self.id, Some(&Self::loc(location)), v)
        }
    }
    pub fn set_f32(&self, location: i32, v: f32) {
        if !self.has_location(location) {
            return;
        }
        unsafe {
            self.gl
                .program_uniform_1_f32(self.id, Some(&Self::loc(location)), v)
        }
    }
    pub fn set_vec2(&self, location: i32, v: [f32; 2]) {
        if !self.has_location(location) {
            return;
        }
        unsafe {
            self.gl
                .program_uniform_2_f32(self.id, Some(&Self::loc(location)), v[0], v[1])
        }
    }
    pub fn set_vec3(&self, location: i32, v: [f32; 3]) {
        if !self.has_location(location) {
            return;
        }
        unsafe {
            self.gl
                .program_uniform_3_f32(self.id, Some(&Self::loc(location)), v[0], v[1], v[2])
        }
    }
    pub fn set_vec4(&self, location: i32, v: [f32; 4]) {
        if !self.has_location(location) {
            return;
        }
        unsafe {
            self.gl.program_uniform_4_f32(
                self.id,
                Some(&Self::loc(location)),
                v[0],
                v[1],
                v[2],
                v[3],
            )
        }
    }
    pub fn set_mat4(&self, location: i32, m: &glam::Mat4) {
        if !self.has_location(location) {
            return;
        }
        unsafe {
            self.gl.program_uniform_matrix_4_f32_slice(
                self.id,
                Some(&Self::loc(location)),
                false,
                &m.to_cols_array(),
            )
        }
    }
    pub fn set_mat3(&self, location: i32, m: &glam::Mat3) {
        if !self.has_location(location) {
            return;
        }
        unsafe {
            self.gl.program_uniform_matrix_3_f32_slice(
                self.id,
                Some(&Self::loc(location)),
                false,
                &m.to_cols_array(),
            )
        }
    }
}

fn compile(
    gl: &glow::Context,
    kind: u32,
    path: &Path,
    defines: &[(String, String)],
) -> Result<glow::Shader, ProgramError> {
    let src = ShaderSource::load(path)?;
    if src.was_shift_jis {
        log::warn!(
            "{}: decoded as Shift-JIS; consider saving it as UTF-8",
            path.display()
        );
    }
    let (text, includes) = prepare_source_with_includes(&src, defines)?;
    unsafe {
        let sh = gl.create_shader(kind).map_err(ProgramError::Gl)?;
        gl.shader_source(sh, &text);
        gl.compile_shader(sh);
        if !gl.get_shader_compile_status(sh) {
            let log = gl.get_shader_info_log(sh);
            gl.delete_shader(sh);
            let shown = path.display().to_string();
            return Err(ProgramError::Compile {
                messages: format_compile_log_sources(&shown, &includes, &log),
                path: shown,
            });
        }
        Ok(sh)
    }
}

fn build(
    gl: &glow::Context,
    vert: &Path,
    frag: &Path,
    defines: &[(String, String)],
) -> Result<glow::Program, ProgramError> {
    let vs = compile(gl, glow::VERTEX_SHADER, vert, defines)?;
    let fs = match compile(gl, glow::FRAGMENT_SHADER, frag, defines) {
        Ok(fs) => fs,
        Err(e) => {
            unsafe { gl.delete_shader(vs) };
            return Err(e);
        }
    };
    unsafe {
        let p = gl.create_program().map_err(ProgramError::Gl)?;
        gl.attach_shader(p, vs);
        gl.attach_shader(p, fs);
        gl.link_program(p);
        gl.detach_shader(p, vs);
        gl.detach_shader(p, fs);
        gl.delete_shader(vs);
        gl.delete_shader(fs);
        if !gl.get_program_link_status(p) {
            let log = gl.get_program_info_log(p);
            gl.delete_program(p);
            return Err(ProgramError::Link {
                vert: vert.display().to_string(),
                frag: frag.display().to_string(),
                log: log.trim().to_string(),
            });
        }
        Ok(p)
    }
}

impl Drop for ProgramObject {
    fn drop(&mut self) {
        unsafe { self.gl.delete_program(self.id) }
    }
}
