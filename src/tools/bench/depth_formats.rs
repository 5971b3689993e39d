//! Linear-depth precision of several main depth formats, through the engine's own parts: the
//! engine's projection for the convention (`math::depth::projection`), `glClipControl` as the engine
//! loads it, `shadow.vert` drawing a camera-facing plane at a known distance into a depth texture of
//! the chosen format, and the engine's restore shader (`sao_restore_depth.frag`, or
//! `ao/restore_depth_reversed.frag`) turning it back into metres.
//!
//! * `D24`, `D32`, `D32F`: OpenGL's default clip space ([-1, 1] depth), depth test LEQUAL, cleared to 1.
//! * `D32FReversed`: the engine's reversed-Z (near → 1, far → 0, [0, 1] clip depth), test GEQUAL,
//!   cleared to 0.

use crate::ao::depth_chain::{camera_defines, restore};
use crate::gl::clip_control::ClipControl;
use crate::gl::pass_state::Depth;
use crate::gl::{
    FramebufferObject, Gl, MeshBuffer, PassState, ProgramObject, Texture, TextureDesc,
};
use crate::math::depth::projection;
use crate::math::{Camera, DepthMode};
use crate::res::ResDirs;
use crate::shader_interface::loc;
use anyhow::{bail, Result};
use glam::{Mat4, Vec3};
use glow::HasContext;
use serde::Serialize;
use std::rc::Rc;

/// A depth-buffer format and the convention it is used with.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
pub enum DepthFormat {
    D24,
    D32,
    D32F,
    D32FReversed,
}

impl DepthFormat {
    pub const ALL: [DepthFormat; 4] = [
        DepthFormat::D24,
        DepthFormat::D32,
        DepthFormat::D32F,
        DepthFormat::D32FReversed,
    ];
    pub fn label(self) -> &'static str {
        match self {
            DepthFormat::D24 => "DEPTH_COMPONENT24",
            DepthFormat::D32 => "DEPTH_COMPONENT32",
            DepthFormat::D32F => "DEPTH_COMPONENT32F",
            DepthFormat::D32FReversed => "DEPTH_COMPONENT32F reversed-Z",
        }
    }
    fn internal_format(self) -> u32 {
        match self {
            DepthFormat::D24 => glow::DEPTH_COMPONENT24,
            DepthFormat::D32 => glow::DEPTH_COMPONENT32,
            DepthFormat::D32F | DepthFormat::D32FReversed => glow::DEPTH_COMPONENT32F,
        }
    }
    /// The engine's convention this format is drawn with.
    pub fn convention(self) -> DepthMode {
        match self {
            DepthFormat::D32FReversed => DepthMode::D32fReversed,
            _ => DepthMode::D32,
        }
    }

    /// Theoretical distance step of one depth-buffer unit at view distance `z` (f64 analysis):
    /// unorm N bits: Δz = z²(f − n)/(f·n)·2⁻ᴺ; D32F with [-1, 1] clip space: the float NDC value
    /// near 1 has spacing 2⁻²⁴ (window depth 2⁻²⁵·2 after the 0.5·x + 0.5 map, i.e. like 24 bits,
    /// but the f32 NDC computation already rounds at 2⁻²³ near 1); reversed D32F: d ≈ n/z, spacing
    /// d·2⁻²³ → Δz ≈ z·2⁻²³.
    pub fn theoretical_step(self, z: f64, n: f64, f: f64) -> f64 {
        let dd_dz = f * n / ((f - n) * z * z); // |d window depth / dz|
        match self {
            DepthFormat::D24 => 2f64.powi(-24) / dd_dz,
            DepthFormat::D32 => 2f64.powi(-32) / dd_dz,
            DepthFormat::D32F => 2f64.powi(-23) / dd_dz,
            DepthFormat::D32FReversed => {
                let d = crate::math::depth::delinearize(DepthMode::D32fReversed, z, n, f);
                (d.abs() * 2f64.powi(-23)).max(f64::MIN_POSITIVE) / dd_dz
            }
        }
    }
}

/// The probe: measures restored linear depth of a facing plane for one format and camera.
pub struct DepthProbe {
    gl: Gl,
    res: ResDirs,
    meshes: MeshBuffer,
    /// `shadow.vert` + `shadow.frag`: position only.
    plane: ProgramObject,
    clip_control: Option<ClipControl>,
    /// Why reversed-Z is unavailable, when it is.
    pub clip_control_error: Option<String>,
}

/// 4×4 depth texels: the restore reads 2×2 of them per output texel, all at the same distance.
const PROBE_SIZE: u32 = 4;

impl DepthProbe {
    pub fn new(gl: &Gl, res: &ResDirs) -> Result<DepthProbe> {
        let (clip_control, clip_control_error) = match ClipControl::get() {
            Ok(c) => (Some(c), None),
            Err(e) => (None, Some(e)),
        };
        Ok(DepthProbe {
            gl: gl.clone(),
            res: res.clone(),
            meshes: MeshBuffer::new(gl)?,
            plane: ProgramObject::from_res(gl, res, "shadow.vert", "shadow.frag", &[])?,
            clip_control,
            clip_control_error,
        })
    }

    pub fn supports(&self, format: DepthFormat) -> bool {
        !format.convention().reversed() || self.clip_control.is_some()
    }

    /// Restored linear depth (metres) of a plane facing the camera at each distance, with the given
    /// planes and a 60° field of view; one 4×4 render per distance.
    pub fn measure(
        &self,
        format: DepthFormat,
        near: f32,
        far: f32,
        distances: &[f64],
    ) -> Result<Vec<f32>> {
        let gl = &self.gl;
        let mode = format.convention();
        if mode.reversed() && self.clip_control.is_none() {
            bail!(
                "reversed-Z needs glClipControl: {}",
                self.clip_control_error.clone().unwrap_or_default()
            );
        }
        let depth = Rc::new(Texture::new(
            gl,
            TextureDesc::target(
                "probe depth",
                PROBE_SIZE,
                PROBE_SIZE,
                format.internal_format(),
            )
            .compare(false),
        )?);
        let fbo_depth = FramebufferObject::new(gl, None, Some(depth.clone()), 0, 0)?;
        let half = PROBE_SIZE / 2;
        let out = Rc::new(Texture::new(
            gl,
            TextureDesc::target("probe linear depth", half, half, glow::R32F),
        )?);
        let fbo_out = FramebufferObject::new(gl, Some(out.clone()), None, 0, 0)?;
        let camera = Camera {
            eye: Vec3::ZERO,
            target: Vec3::NEG_Z,
            fov_y_deg: 60.0,
            near,
            far,
            ..Camera::default()
        };
        let restore_shader = if mode.reversed() {
            "ao/restore_depth_reversed.frag"
        } else {
            "sao_restore_depth.frag"
        };
        let restore_program = ProgramObject::from_res(
            gl,
            &self.res,
            "simple.vert",
            restore_shader,
            &camera_defines(&camera),
        )?;
        let view_projection = projection(mode, 60.0, 1.0, near, far) * camera.view();
        let draw_state = PassState {
            depth: Depth::Test {
                func: mode.nearer_or_equal(),
                write: true,
            },
            clip_zero_to_one: mode.reversed(),
            ..PassState::FULLSCREEN
        };
        let mut result = Vec::with_capacity(distances.len());
        for &d in distances {
            fbo_depth.bind();
            draw_state.apply(gl, self.clip_control.as_ref());
            // SAFETY: clearing the bound FBO's depth with writes enabled by the state above.
            unsafe {
                gl.clear_depth_f32(mode.clear_value());
                gl.clear(glow::DEPTH_BUFFER_BIT);
            }
            // The unit quad in XY, scaled to cover the view at distance d and moved there.
            let model = Mat4::from_translation(Vec3::new(0.0, 0.0, -d as f32))
                * Mat4::from_scale(Vec3::new(2.0 * d as f32, 2.0 * d as f32, 1.0));
            self.plane.set_mat4(loc::MODEL, &model);
            self.plane.set_mat4(loc::VIEW_PROJECTION, &view_projection);
            self.plane.use_program();
            self.meshes.draw_plane_xy();
            PassState::FULLSCREEN.apply(gl, self.clip_control.as_ref());
            restore(gl, &restore_program, &fbo_out, &self.meshes, &depth);
            let v = out.read_f32(0, 1);
            // Every texel sees the same distance.
            result.push(v[(half * half / 2 + half / 2) as usize]);
        }
        if let Some(e) = crate::gl::take_error(gl) {
            bail!("{e} in the depth probe ({})", format.label());
        }
        Ok(result)
    }
}
