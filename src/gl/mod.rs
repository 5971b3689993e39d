//! Thin owners of OpenGL objects, mirroring the course's classes (Texture, FramebufferObject,
//! ProgramObject, MeshBuffer), each deleting its GL object when dropped; the shader preprocessor;
//! the render state every pass states (`PassState`).

pub mod clip_control;
pub mod framebuffer;
pub mod gltf_file;
pub mod mesh;
pub mod model;
pub mod model_refs;
pub mod obj;
pub mod pass_state;
pub mod preprocess;
pub mod program;
pub mod readback;
pub mod shader_error;
pub mod shader_storage;
pub mod storage_buffer;
pub mod texture;
pub mod timer;

pub use framebuffer::FramebufferObject;
pub use mesh::{MeshBuffer, StaticMesh, Vertex};
pub use pass_state::PassState;
pub use preprocess::ShaderSource;
pub use program::ProgramObject;
pub use shader_error::ProgramError;
pub use storage_buffer::StorageBuffer;
pub use texture::{Texture, TextureDesc};
pub use timer::{PassClock, TimerQuery};

use std::rc::Rc;

/// Shared handle to the GL function table. One per context; objects keep a clone so they can delete themselves.
pub type Gl = Rc<glow::Context>;

/// Reads and clears the GL error flag, returning a readable name for the first error seen.
pub fn take_error(gl: &glow::Context) -> Option<&'static str> {
    use glow::HasContext;
    let mut first = None;
    loop {
        let e = unsafe { gl.get_error() };
        if e == glow::NO_ERROR {
            break;
        }
        first.get_or_insert(match e {
            glow::INVALID_ENUM => "GL_INVALID_ENUM",
            glow::INVALID_VALUE => "GL_INVALID_VALUE",
            glow::INVALID_OPERATION => "GL_INVALID_OPERATION",
            glow::INVALID_FRAMEBUFFER_OPERATION => "GL_INVALID_FRAMEBUFFER_OPERATION",
            glow::OUT_OF_MEMORY => "GL_OUT_OF_MEMORY",
            _ => "GL error",
        });
    }
    first
}

/// An error naming `what` when GL recorded one since the last check.
pub fn check_error(gl: &glow::Context, what: &str) -> anyhow::Result<()> {
    match take_error(gl) {
        Some(e) => anyhow::bail!("{e} while {what}"),
        None => Ok(()),
    }
}

/// "vendor / renderer / version" of the current context.
pub fn describe_renderer(gl: &glow::Context) -> String {
    use glow::HasContext;
    unsafe {
        format!(
            "{} {} (OpenGL {})",
            gl.get_parameter_string(glow::VENDOR),
            gl.get_parameter_string(glow::RENDERER),
            gl.get_parameter_string(glow::VERSION)
        )
    }
}
