//! Thin owners of OpenGL objects, mirroring the course's classes (Texture, FramebufferObject,
//! ProgramObject, MeshBuffer). Each type deletes its GL object when dropped.

pub mod framebuffer;
pub mod mesh;
pub mod program;
pub mod texture;

pub use framebuffer::FramebufferObject;
pub use mesh::{MeshBuffer, StaticMesh, Vertex};
pub use program::{ProgramError, ProgramObject, ShaderSource};
pub use texture::{Texture, TextureDesc};

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
