//! Joint bilateral up-sampling of the engine's AO (half, full or quarter size) to the main size
//! (`Res/ao/bilateral_upsample.glsl`): silhouettes keep their own occlusion instead of the linear
//! filter's blocky halo. The blended composites up-sample as they blend
//! (`Res/ao/composite_bilateral.frag`, one full-size pass and one full-size texture fewer); the AO
//! views and the ambient-only lighting read an up-sampled texture (`Res/ao/upsample_bilateral.frag`).
//! The lesson's `sao-lesson` keeps the course's linear filter.

use crate::gl::{
    FramebufferObject, Gl, MeshBuffer, PassState, ProgramObject, Texture, TextureDesc,
};
use crate::math::{Camera, DepthMode};
use crate::shader_interface::{binding, loc};
use anyhow::Result;
use glow::HasContext;
use std::cell::RefCell;
use std::rc::Rc;

pub const SHADER: &str = "ao/upsample_bilateral.frag";
pub const COMPOSITE_SHADER: &str = "ao/composite_bilateral.frag";
/// The composite built for power 1 (the lesson's blend and the default): no `pow` per pixel, which a
/// software rasteriser would evaluate even where a branch skips it.
pub const POWER_ONE_DEFINE: &str = "AO_POWER_ONE";

pub struct BilateralUpsample {
    pub program: ProgramObject,
    /// Up-samples and blends over the main colour in one pass.
    pub composite_program: ProgramObject,
    /// The same with power 1.
    pub composite_power_one: ProgramObject,
    /// Main-size R8 target with the main depth buffer attached, (re)created when either changes.
    target: RefCell<Option<FramebufferObject>>,
}

/// What one up-sampling reads.
pub struct UpsampleInputs<'a> {
    pub occlusion: &'a Texture,
    /// Linear depth at the AO size.
    pub ao_depth: &'a Texture,
    /// Also attached to the up-sampling target as its depth buffer (tested, never written).
    pub main_depth: &'a Rc<Texture>,
    pub camera: &'a Camera,
    pub mode: DepthMode,
}

impl BilateralUpsample {
    pub fn new(
        program: ProgramObject,
        composite_program: ProgramObject,
        composite_power_one: ProgramObject,
    ) -> BilateralUpsample {
        BilateralUpsample {
            program,
            composite_program,
            composite_power_one,
            target: RefCell::new(None),
        }
    }

    /// Up-samples `inputs.occlusion` to the main depth buffer's size; returns the result.
    ///
    /// Sky pixels hold 0: the target is cleared to it and the quad, at the sky's depth, is tested
    /// against the main depth buffer (attached, not written), so only surface pixels run the shader,
    /// as in `composite`.
    pub fn run(
        &self,
        gl: &Gl,
        meshes: &MeshBuffer,
        inputs: &UpsampleInputs,
    ) -> Result<Rc<Texture>> {
        let size = (inputs.main_depth.width(), inputs.main_depth.height());
        let mut target = self.target.borrow_mut();
        let fits = target.as_ref().is_some_and(|f| {
            (f.width(), f.height()) == size
                && f.depth_texture().map(|d| d.id()) == Some(inputs.main_depth.id())
        });
        if !fits {
            *target = None;
            // Nearest filtering (the default): the composite reads it texel for texel.
            let tex = Rc::new(Texture::new(
                gl,
                TextureDesc::target("FBO(ao upsampled)", size.0, size.1, glow::R8),
            )?);
            *target = Some(FramebufferObject::new(
                gl,
                Some(tex),
                Some(inputs.main_depth.clone()),
                0,
                0,
            )?);
        }
        let fbo = target.as_ref().expect("created above");
        fbo.bind();
        PassState::FULLSCREEN.apply(gl, None);
        // SAFETY: colour buffer 0 of a complete framebuffer; four floats as the call reads.
        unsafe { gl.clear_named_framebuffer_f32_slice(Some(fbo.id()), glow::COLOR, 0, &[0.0; 4]) };
        super::composite::surface_pixels_test(
            inputs.mode.clear_value(),
            super::composite::sky_farther(inputs.mode),
        )
        .apply(gl, None);
        self.program.use_program();
        self.program
            .set_vec3(loc::UPSAMPLE_DEPTH_PLANES, depth_planes(inputs));
        bind_inputs(inputs);
        meshes.draw_plane_xy();
        PassState::FULLSCREEN.apply(gl, None);
        fbo.color_texture()
            .cloned()
            .ok_or_else(|| anyhow::anyhow!("the up-sampling target has no colour texture"))
    }

    /// Blends the up-sampled occlusion over `main`'s colour: colour moves toward `tint` by
    /// 1 − visibility^`power`; the lesson's blend is tint 0, power 1.
    ///
    /// Only pixels with a surface are shaded: the quad lies at the sky's depth and passes where the
    /// stored depth is nearer, so the depth test drops sky pixels before the shader runs (about a
    /// third of this pass on a scene of models under open sky). The shader also reads that depth
    /// buffer while it is attached; depth writes are off, and OpenGL 4.5 (section 9.3.1, rendering
    /// feedback loops) leaves a draw's results undefined only where texels it reads are also
    /// written.
    pub fn composite(
        &self,
        gl: &Gl,
        meshes: &MeshBuffer,
        inputs: &UpsampleInputs,
        main: &FramebufferObject,
        tint: [f32; 3],
        power: f32,
    ) {
        super::composite::surface_pixels_only(
            inputs.mode.clear_value(),
            super::composite::sky_farther(inputs.mode),
        )
        .apply(gl, None);
        let program = if power == 1.0 {
            &self.composite_power_one
        } else {
            &self.composite_program
        };
        program.use_program();
        program.set_vec3(loc::UPSAMPLE_DEPTH_PLANES, depth_planes(inputs));
        program.set_vec3(loc::AO_TINT, tint);
        program.set_f32(loc::AO_TINT_POWER, power);
        main.bind();
        bind_inputs(inputs);
        meshes.draw_plane_xy();
        PassState::FULLSCREEN.apply(gl, None);
    }

    pub fn textures(&self) -> Vec<Rc<Texture>> {
        self.target
            .borrow()
            .iter()
            .filter_map(|f| f.color_texture().cloned())
            .collect()
    }

    pub fn release_targets(&self) {
        *self.target.borrow_mut() = None;
    }
}

/// (near, far, 1 for reversed-Z): what `linear_depth.glsl` needs to linearise the main depth.
fn depth_planes(inputs: &UpsampleInputs) -> [f32; 3] {
    let reversed = if inputs.mode.reversed() { 1.0 } else { 0.0 };
    [inputs.camera.near, inputs.camera.far, reversed]
}

fn bind_inputs(inputs: &UpsampleInputs) {
    inputs.occlusion.bind(binding::INPUT);
    inputs.ao_depth.bind(binding::SECOND_INPUT);
    inputs.main_depth.bind(binding::THIRD_INPUT);
}
