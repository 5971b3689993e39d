//! The engine's passes over the geometry that AO reads besides the depth chain (back-face depth,
//! surface normals), and their read-back for tests and the screen-space reference.

use super::Engine;
use crate::gl::check_error;
use crate::gl::readback::flip_rows;
use crate::gl::Texture;
use crate::math::octahedral::decode_octahedral;
use crate::render::frame::Frame;
use crate::render::passes::surface::SurfaceInputs;
use crate::render::view::View;
use anyhow::{anyhow, Result};
use std::rc::Rc;

impl Engine {
    /// Linear depth (m) of the back faces at the AO size, from the last frame that needed it
    /// (`vbao` with `thickness = "backface"`); rows bottom-up.
    pub fn back_face_depth(&self) -> Option<Rc<Texture>> {
        self.surface.back_faces.linear_depth()
    }

    /// Linear depth (m) of the second depth layer at the AO size, from the last frame that needed it
    /// (`vbao` with `layers = 2`); rows bottom-up, `far` where nothing lies behind.
    pub fn second_layer_depth(&self) -> Option<Rc<Texture>> {
        self.surface.second_layer.linear_depth()
    }

    /// Linear depth (m) of the nearest back faces behind the second depth layer at the AO size, from
    /// the last frame that needed them (`vbao` with `layers = 2` and `thickness = "backface"`); rows
    /// bottom-up, `far` where none.
    pub fn second_layer_back_depth(&self) -> Option<Rc<Texture>> {
        self.surface.second_layer.back_linear_depth()
    }

    /// Linear depth (m) of the nearest back faces at the full output size and the current camera,
    /// whatever the AO settings: the pass `vbao` reads with `thickness = "backface"` at full AO
    /// resolution (the screen-space reference's per-pixel thickness). Rows top-down; exactly `far`
    /// where no back face lies behind the pixel.
    pub fn render_back_face_depth(&mut self) -> Result<Vec<f32>> {
        let front = self.render_front_depth()?;
        let f = self.frame();
        let back = self
            .surface
            .back_faces
            .draw(&f, &self.shadow.program, &front, self.size())?;
        let mut v = back.read_f32(0, 1);
        flip_rows(&mut v, self.width as usize, self.height as usize);
        check_error(&self.gl, "reading the back-face depth")?;
        Ok(v)
    }

    /// Linear depth (m) of the second depth layer `separation` metres or more behind the visible
    /// surface, at the full output size and the current camera, whatever the AO settings: what
    /// `vbao` with `layers = 2` reads at full AO resolution (the screen-space reference's), and with
    /// `back_faces` the back faces that close it (what `vbao` reads with `thickness = "backface"`
    /// as well). Rows top-down; exactly `far` where nothing lies behind the pixel.
    pub fn render_second_layer_depths(
        &mut self,
        separation: f32,
        back_faces: bool,
    ) -> Result<(Vec<f32>, Option<Vec<f32>>)> {
        let front = self.render_front_depth()?;
        let f = self.frame();
        let (w, h) = (self.width as usize, self.height as usize);
        let passes = &self.surface.second_layer;
        let mut layer = passes
            .draw(&f, &front, separation, self.size())?
            .read_f32(0, 1);
        flip_rows(&mut layer, w, h);
        let back = if back_faces {
            let mut v = passes
                .draw_back_faces(&f, &front, self.size())?
                .read_f32(0, 1);
            flip_rows(&mut v, w, h);
            Some(v)
        } else {
            None
        };
        check_error(&self.gl, "reading the second depth layer")?;
        Ok((layer, back))
    }

    /// The surface normals (view space, unit length) at the AO size from the last frame that ran
    /// the pass (`normals = "geometric"`); rows bottom-up.
    pub fn surface_normals(&self) -> Option<Vec<[f32; 3]>> {
        Some(decode_normals(
            &self.surface.normals.restored()?.read_f32(0, 2),
        ))
    }

    /// The surface normals at the full output size and the current camera, whatever the AO
    /// settings: what a method reading geometric normals at full AO resolution sees (the
    /// screen-space reference's). View space, unit length, rows top-down.
    pub fn render_surface_normals(&mut self) -> Result<Vec<[f32; 3]>> {
        let front = self.render_front_depth()?;
        let f = self.frame();
        let codes = self
            .surface
            .normals
            .draw(&f, Some(&front), self.size())?
            .read_f32(0, 2);
        let mut v = decode_normals(&codes);
        flip_rows(&mut v, self.width as usize, self.height as usize);
        check_error(&self.gl, "reading the surface normals")?;
        Ok(v)
    }

    /// The main depth buffer after the opaque pass of the current camera (the linear-depth view runs
    /// no AO method): the surface passes' restores keep the texel whose front is nearest.
    fn render_front_depth(&mut self) -> Result<Rc<Texture>> {
        self.render_values(View::LinearDepth)?;
        self.fbo_main
            .depth_texture()
            .cloned()
            .ok_or_else(|| anyhow!("the main FBO has no depth texture"))
    }

    /// The passes over the geometry that the AO settings read besides the depth chain.
    /// `normals_drawn`: the normals, when the pass already ran this frame (a guard band's depth).
    pub(super) fn run_surface_passes(
        &self,
        f: &Frame,
        depth: &Texture,
        ao_size: (u32, u32),
        normals_drawn: Option<Rc<Texture>>,
    ) -> Result<SurfaceInputs> {
        let (s, passes) = (&self.ao_settings, &self.surface);
        let mut out = SurfaceInputs::default();
        if s.uses_back_faces() {
            out.back_depth = Some(self.pass("back-face depth", "ao", || {
                let depth_only = &self.shadow.program;
                passes.back_faces.draw(f, depth_only, depth, ao_size)
            })?);
        }
        if s.uses_second_layer() {
            out.second_depth = Some(self.pass("second depth layer", "ao", || {
                let separation = s.layer_separation_metres();
                passes.second_layer.draw(f, depth, separation, ao_size)
            })?);
            if s.uses_second_layer_back_faces() {
                out.second_back_depth = Some(self.pass("second layer back faces", "ao", || {
                    passes.second_layer.draw_back_faces(f, depth, ao_size)
                })?);
            }
        }
        if s.uses_surface_normals() {
            out.normals = match normals_drawn {
                Some(n) => Some(n),
                None => Some(self.pass("surface normals", "ao", || {
                    passes.normals.draw(f, Some(depth), ao_size)
                })?),
            };
        }
        Ok(out)
    }
}

/// Unit normals from the octahedral codes the surface-normal pass writes (two floats per texel).
fn decode_normals(codes: &[f32]) -> Vec<[f32; 3]> {
    codes
        .chunks_exact(2)
        .map(|c| decode_octahedral([c[0], c[1]]))
        .collect()
}
