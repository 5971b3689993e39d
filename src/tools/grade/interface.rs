//! Before anything is rendered: the student's program against the lesson's interface
//! (`shader_interface::PROGRAMS`). The engine sets uniforms by location and binds textures by unit,
//! so a uniform declared without its `layout(location=N)`, with another type, or a sampler on another
//! unit silently reads 0 or the wrong texture; rendering would then blame whatever that breaks (a
//! `mipLevel` without its location reads as "level 0 is always read"). This names the declaration.

use crate::i18n::Text;
use crate::shader_interface::{ProgramInterface, PROGRAMS};
use crate::tools::grade::say::say;
use glow::HasContext;

/// How much of the file the lesson has written so far.
#[derive(Clone, Copy, PartialEq, Eq, Debug)]
pub enum Written {
    /// The whole shader: every uniform and sampler of the interface must be read.
    Complete,
    /// Its start (`sao.frag` in lessons 6–7): what it declares must be where the engine sets it, and
    /// these uniforms and samplers must be read (none, to check declarations only); those the later
    /// lessons use may still be unread.
    Begun(&'static [&'static str]),
}

impl Written {
    /// Whether the shader must already read the uniform or sampler `name`.
    fn must_read(self, name: &str) -> bool {
        match self {
            Written::Complete => true,
            Written::Begun(reads) => reads.contains(&name),
        }
    }
}

/// One active uniform of a linked program.
struct Active {
    name: String,
    location: i32,
    gl_type: u32,
    /// The texture unit, for samplers.
    unit: Option<i32>,
}

fn is_sampler(gl_type: u32) -> bool {
    matches!(
        gl_type,
        glow::SAMPLER_2D
            | glow::SAMPLER_2D_SHADOW
            | glow::SAMPLER_CUBE
            | glow::SAMPLER_3D
            | glow::INT_SAMPLER_2D
            | glow::UNSIGNED_INT_SAMPLER_2D
            | glow::SAMPLER_2D_ARRAY
    )
}

/// The GLSL name of a uniform type, for messages.
fn glsl_type(gl_type: u32) -> String {
    match gl_type {
        glow::FLOAT => "float",
        glow::FLOAT_VEC2 => "vec2",
        glow::FLOAT_VEC3 => "vec3",
        glow::FLOAT_VEC4 => "vec4",
        glow::INT => "int",
        glow::INT_VEC2 => "ivec2",
        glow::INT_VEC3 => "ivec3",
        glow::INT_VEC4 => "ivec4",
        glow::UNSIGNED_INT => "uint",
        glow::BOOL => "bool",
        glow::FLOAT_MAT3 => "mat3",
        glow::FLOAT_MAT4 => "mat4",
        glow::SAMPLER_2D => "sampler2D",
        glow::SAMPLER_2D_SHADOW => "sampler2DShadow",
        glow::SAMPLER_CUBE => "samplerCube",
        glow::SAMPLER_3D => "sampler3D",
        glow::INT_SAMPLER_2D => "isampler2D",
        glow::UNSIGNED_INT_SAMPLER_2D => "usampler2D",
        glow::SAMPLER_2D_ARRAY => "sampler2DArray",
        other => return format!("0x{other:x}"),
    }
    .to_string()
}

/// The type the engine sets each of the lesson's uniforms with (`ProgramObject::set_*`).
fn lesson_type(name: &str) -> Option<u32> {
    match name {
        "mipLevel" => Some(glow::INT),
        "saoInfo" => Some(glow::FLOAT_VEC4),
        "ndcToView" => Some(glow::FLOAT_VEC2),
        _ => None,
    }
}

/// Every active uniform of `program` (uniform-block members, which have no location, left out).
fn active_uniforms(gl: &glow::Context, program: glow::Program) -> Vec<Active> {
    let mut out = Vec::new();
    // SAFETY: queries on a linked program of the current context.
    unsafe {
        for i in 0..gl.get_active_uniforms(program) {
            let Some(u) = gl.get_active_uniform(program, i) else {
                continue;
            };
            let Some(location) = gl.get_uniform_location(program, &u.name) else {
                continue;
            };
            let unit = is_sampler(u.utype).then(|| {
                let mut unit = [0i32];
                gl.get_uniform_i32(program, &location, &mut unit);
                unit[0]
            });
            out.push(Active {
                name: u.name.trim_end_matches("[0]").to_string(),
                location: location.0 as i32,
                gl_type: u.utype,
                unit,
            });
        }
    }
    out
}

/// The lesson's interface of the shader `file`, if it has one.
fn interface_of(file: &str) -> Option<&'static ProgramInterface> {
    PROGRAMS.iter().find(|p| p.frag == file)
}

/// The first way `program` (built from the student's `file`) departs from the lesson's interface, as
/// the step's failing message; `None` when it keeps it.
pub fn check(
    gl: &glow::Context,
    program: glow::Program,
    file: &str,
    written: Written,
) -> Option<Text> {
    let interface = interface_of(file)?;
    let active = active_uniforms(gl, program);
    for u in interface.uniforms {
        let want = lesson_type(u.name);
        let decl = format!(
            "layout(location={}) uniform {} {}",
            u.location,
            want.map(glsl_type).unwrap_or_else(|| "…".into()),
            u.name
        );
        let at = active
            .iter()
            .find(|a| a.unit.is_none() && a.location == u.location);
        match at {
            Some(a) => {
                if let Some(t) = want.filter(|t| *t != a.gl_type) {
                    return Some(say!(
                        "grade.verdict.interface_wrong_type",
                        name = a.name,
                        location = u.location,
                        got = glsl_type(a.gl_type),
                        want = glsl_type(t),
                        decl = decl
                    ));
                }
            }
            None => {
                if let Some(a) = active.iter().find(|a| a.name == u.name) {
                    return Some(say!(
                        "grade.verdict.interface_misplaced_uniform",
                        name = u.name,
                        got = a.location,
                        location = u.location,
                        decl = decl
                    ));
                }
                if written.must_read(u.name) {
                    return Some(if u.name == "mipLevel" {
                        say!("grade.verdict.interface_unused_mip_level", decl = decl)
                    } else {
                        say!(
                            "grade.verdict.interface_unused_uniform",
                            name = u.name,
                            location = u.location,
                            decl = decl
                        )
                    });
                }
            }
        }
    }
    let samplers: Vec<&Active> = active.iter().filter(|a| a.unit.is_some()).collect();
    for s in interface.samplers {
        let decl = format!("layout(binding={}) uniform sampler2D {}", s.binding, s.name);
        let on_unit = samplers.iter().find(|a| a.unit == Some(s.binding as i32));
        match on_unit {
            Some(a) if a.gl_type != glow::SAMPLER_2D => {
                return Some(say!(
                    "grade.verdict.interface_sampler_type",
                    name = a.name,
                    got = glsl_type(a.gl_type),
                    unit = s.binding,
                    decl = decl
                ))
            }
            Some(_) => {}
            None => {
                // The same name on another unit, or the only sampler of a one-texture shader.
                let moved = samplers.iter().find(|a| a.name == s.name).or(
                    match (interface.samplers.len(), samplers.as_slice()) {
                        (1, [only]) => Some(only),
                        _ => None,
                    },
                );
                if let Some(a) = moved {
                    return Some(say!(
                        "grade.verdict.interface_misplaced_sampler",
                        name = a.name,
                        got = a.unit.unwrap_or(0),
                        unit = s.binding,
                        decl = decl
                    ));
                }
                if written.must_read(s.name) {
                    return Some(say!(
                        "grade.verdict.interface_unused_sampler",
                        name = s.name,
                        unit = s.binding,
                        decl = decl
                    ));
                }
            }
        }
    }
    None
}
