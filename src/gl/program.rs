//! `ProgramObject`: a vertex + fragment program built from shader files in `Res/`.
//!
//! Errors name the file and line (`Res/sao.frag:42: ...`), a failed rebuild keeps the last working
//! program; sources go through the preprocessor (`preprocess.rs`).

use super::preprocess::{
    format_compile_log_sources, prepare_source_with_includes, ShaderSource, TextEncoding,
};
use super::shader_error::ProgramError;
use super::Gl;
use crate::res::{modified_time as mtime, ResDirs};
use glow::HasContext;
use std::path::{Path, PathBuf};
use std::time::SystemTime;

pub struct ProgramObject {
    gl: Gl,
    id: glow::Program,
    vert_path: PathBuf,
    frag_path: PathBuf,
    defines: Vec<(String, String)>,
    /// Where `#include`s the fragment shader's folder lacks are found (a method file's shader).
    include_fallback: Option<PathBuf>,
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
        ProgramObject::from_paths(gl, vert_path, frag_path, defines, None)
    }

    /// Builds a program from files given by path; `#include`s the fragment shader's folder lacks
    /// are looked for in `include_fallback` (the engine's headers, for a shader outside `Res/`).
    pub fn from_paths(
        gl: &Gl,
        vert_path: PathBuf,
        frag_path: PathBuf,
        defines: &[(&str, String)],
        include_fallback: Option<PathBuf>,
    ) -> Result<ProgramObject, ProgramError> {
        let defines: Vec<(String, String)> = defines
            .iter()
            .map(|(k, v)| (k.to_string(), v.clone()))
            .collect();
        let sources = Sources {
            vert: &vert_path,
            frag: &frag_path,
            include_fallback: include_fallback.as_deref(),
        };
        let id = build(gl, &sources, &defines)?;
        let stamp = mtime(&vert_path).zip(mtime(&frag_path));
        let active = active_locations(gl, id);
        Ok(ProgramObject {
            gl: gl.clone(),
            id,
            vert_path,
            frag_path,
            defines,
            include_fallback,
            stamp,
            active,
        })
    }

    /// Rebuilds from the files; on failure the previous program stays in use and the error is returned.
    pub fn reload(&mut self) -> Result<(), ProgramError> {
        self.stamp = mtime(&self.vert_path).zip(mtime(&self.frag_path));
        let sources = Sources {
            vert: &self.vert_path,
            frag: &self.frag_path,
            include_fallback: self.include_fallback.as_deref(),
        };
        let id = build(&self.gl, &sources, &self.defines)?;
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

/// A program's two files, and where the fragment shader's missing includes are found.
struct Sources<'a> {
    vert: &'a Path,
    frag: &'a Path,
    include_fallback: Option<&'a Path>,
}

fn compile(
    gl: &glow::Context,
    kind: u32,
    path: &Path,
    defines: &[(String, String)],
    include_fallback: Option<&Path>,
) -> Result<glow::Shader, ProgramError> {
    let mut src = ShaderSource::load(path)?;
    src.include_fallback = include_fallback.map(Path::to_path_buf);
    if src.encoding != TextEncoding::Utf8 {
        log::warn!(
            "{}: decoded as {}; consider saving it as UTF-8",
            path.display(),
            src.encoding.name()
        );
    }
    let (text, includes) = prepare_source_with_includes(&src, defines)?;
    check_storage(&text, path, &includes)?;
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

/// Refuses a shader whose declared arrays or macro expansions would exhaust the driver's memory
/// (`super::shader_storage`), naming the file among the shader and its includes, and the line.
fn check_storage(text: &str, path: &Path, includes: &[PathBuf]) -> Result<(), ProgramError> {
    use super::shader_storage::{check, Refusal, MAX_DECLARED_COMPONENTS as LIMIT};
    let file = |source: usize| {
        let file = source
            .checked_sub(1)
            .and_then(|k| includes.get(k))
            .map_or(path, PathBuf::as_path);
        file.display().to_string()
    };
    let (path, line, message) = match check(text) {
        Ok(()) => return Ok(()),
        Err(Refusal::Storage {
            source,
            line,
            name,
            components,
            total,
        }) => {
            let message = rust_i18n::t!(
                "shader.too_much_storage",
                name = name,
                components = components,
                total = total,
                limit = LIMIT
            );
            (file(source), line, message)
        }
        Err(Refusal::Macros { source, line }) => {
            (file(source), line, rust_i18n::t!("shader.macro_too_large"))
        }
    };
    let message = message.into_owned();
    Err(ProgramError::Storage {
        path,
        line,
        message,
    })
}

fn build(
    gl: &glow::Context,
    sources: &Sources,
    defines: &[(String, String)],
) -> Result<glow::Program, ProgramError> {
    let (vert, frag) = (sources.vert, sources.frag);
    let vs = compile(gl, glow::VERTEX_SHADER, vert, defines, None)?;
    let fs = match compile(
        gl,
        glow::FRAGMENT_SHADER,
        frag,
        defines,
        sources.include_fallback,
    ) {
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
