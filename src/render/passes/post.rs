//! Into the output: image processing (colour matrix, bloom added), or one AO buffer shown as grey
//! for the debug views.

use crate::gl::{
    FramebufferObject, Gl, MeshBuffer, PassState, ProgramObject, Texture, TextureDesc,
};
use crate::render::view::View;
use crate::res::ResDirs;
use crate::shader_interface::{binding, loc};
use anyhow::Result;
use glam::Mat3;
use glow::HasContext;

pub struct PostPass {
    pub image: ProgramObject,
    pub debug: ProgramObject,
    /// Stands in for bloom when it is off.
    black: Texture,
}

impl PostPass {
    pub fn new(gl: &Gl, res: &ResDirs) -> Result<PostPass> {
        let p = |frag: &str| ProgramObject::from_res(gl, res, "simple.vert", frag, &[]);
        let black = Texture::new(gl, TextureDesc::target("black", 1, 1, glow::RGBA8))?;
        black.upload_f32(0, 4, &[0.0, 0.0, 0.0, 1.0])?;
        Ok(PostPass {
            image: p("image_processing.frag")?,
            debug: p("debug_view.frag")?,
            black,
        })
    }

    /// Binds the output: `None` = the default framebuffer (window) at `size`.
    fn bind_output(gl: &Gl, target: Option<&FramebufferObject>, (w, h): (u32, u32)) {
        match target {
            Some(f) => f.bind(),
            None => unsafe {
                gl.bind_framebuffer(glow::FRAMEBUFFER, None);
                gl.viewport(0, 0, w as i32, h as i32);
            },
        }
        PassState::FULLSCREEN.apply(gl, None);
    }

    pub fn draw_image(
        &self,
        gl: &Gl,
        meshes: &MeshBuffer,
        target: Option<&FramebufferObject>,
        size: (u32, u32),
        main_color: &Texture,
        bloom: Option<(&Texture, f32)>,
    ) {
        Self::bind_output(gl, target, size);
        self.image.set_mat3(loc::COLOR_MATRIX, &Mat3::IDENTITY);
        self.image
            .set_f32(loc::BLOOM_STRENGTH, bloom.map_or(0.0, |b| b.1));
        self.image.use_program();
        main_color.bind(binding::INPUT);
        match bloom {
            Some((tex, _)) => tex.bind(binding::SECOND_INPUT),
            None => self.black.bind(binding::SECOND_INPUT),
        }
        meshes.draw_plane_xy();
    }

    /// Shows `tex` as grey: linear depth scaled for the eye (or raw values), or occlusion as visibility.
    #[allow(clippy::too_many_arguments)]
    pub fn draw_debug(
        &self,
        gl: &Gl,
        meshes: &MeshBuffer,
        target: Option<&FramebufferObject>,
        size: (u32, u32),
        view: View,
        tex: &Texture,
        raw_values: bool,
    ) {
        Self::bind_output(gl, target, size);
        // 0.02: 50 m of depth spans black to white, the demo scene's range.
        let (mode, scale) = match view {
            View::LinearDepth | View::SecondLayerDepth => (0, 0.02),
            _ => (1, 1.0),
        };
        self.debug.set_i32(loc::DEBUG_VIEW_MODE, mode);
        self.debug
            .set_f32(loc::DEBUG_VIEW_SCALE, if raw_values { 1.0 } else { scale });
        self.debug.use_program();
        tex.bind(binding::INPUT);
        meshes.draw_plane_xy();
    }
}
