//! Linear-depth precision of several main depth formats, outside the engine: a small self-contained
//! pipeline that draws a camera-facing plane at a known distance into a depth texture of the chosen
//! format and restores linear depth from it in a fragment shader, as `sao_restore_depth.frag` does.
//!
//! * `D24`, `D32`, `D32F`: OpenGL's default clip space ([-1, 1] depth), `glam::Mat4::perspective_rh_gl`
//!   (the engine's projection), depth test LEQUAL, cleared to 1; restored with the lesson's formula
//!   `A / ((2d − 1) − B)` in f32.
//! * `D32FReversed`: `glClipControl(GL_LOWER_LEFT, GL_ZERO_TO_ONE)`, a projection mapping near → 1 and
//!   far → 0, DEPTH_COMPONENT32F, depth test GREATER, cleared to 0; restored with `n·f / (d·(f − n) + n)`.
//!
//! glow 0.17 has no `clip_control`, so `glClipControl` is loaded through `eglGetProcAddress`.

use crate::gl::{FramebufferObject, Gl, Texture, TextureDesc};
use anyhow::{anyhow, bail, Result};
use glam::Mat4;
use glow::HasContext;
use serde::Serialize;
use std::rc::Rc;

#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
pub enum DepthMode {
    D24,
    D32,
    D32F,
    D32FReversed,
}

impl DepthMode {
    pub const ALL: [DepthMode; 4] = [
        DepthMode::D24,
        DepthMode::D32,
        DepthMode::D32F,
        DepthMode::D32FReversed,
    ];
    pub fn label(self) -> &'static str {
        match self {
            DepthMode::D24 => "DEPTH_COMPONENT24",
            DepthMode::D32 => "DEPTH_COMPONENT32",
            DepthMode::D32F => "DEPTH_COMPONENT32F",
            DepthMode::D32FReversed => "DEPTH_COMPONENT32F reversed-Z",
        }
    }
    fn format(self) -> u32 {
        match self {
            DepthMode::D24 => glow::DEPTH_COMPONENT24,
            DepthMode::D32 => glow::DEPTH_COMPONENT32,
            DepthMode::D32F | DepthMode::D32FReversed => glow::DEPTH_COMPONENT32F,
        }
    }
    fn reversed(self) -> bool {
        self == DepthMode::D32FReversed
    }

    /// Theoretical distance step of one depth-buffer unit at view distance `z` (f64 analysis):
    /// unorm N bits: Δz = z²(f − n)/(f·n)·2⁻ᴺ; D32F with [-1, 1] clip space: the float NDC value
    /// near 1 has spacing 2⁻²⁴ (window depth 2⁻²⁵·2 after the 0.5·x + 0.5 map, i.e. like 24 bits,
    /// but the f32 NDC computation already rounds at 2⁻²³ near 1); reversed D32F: d ≈ n/z, spacing
    /// d·2⁻²³ → Δz ≈ z·2⁻²³.
    pub fn theoretical_step(self, z: f64, n: f64, f: f64) -> f64 {
        let dd_dz = f * n / ((f - n) * z * z); // |d window depth / dz|
        match self {
            DepthMode::D24 => 2f64.powi(-24) / dd_dz,
            DepthMode::D32 => 2f64.powi(-32) / dd_dz,
            DepthMode::D32F => 2f64.powi(-23) / dd_dz,
            DepthMode::D32FReversed => {
                let d = n * (f - z) / (z * (f - n));
                (d.abs() * 2f64.powi(-23)).max(f64::MIN_POSITIVE) / dd_dz
            }
        }
    }
}

type ClipControlFn = unsafe extern "system" fn(u32, u32);

/// Loads `glClipControl` from the current EGL context's driver.
fn load_clip_control() -> Result<ClipControlFn> {
    unsafe {
        let lib =
            libloading::Library::new("libEGL.so.1").map_err(|e| anyhow!("libEGL.so.1: {e}"))?;
        let get: libloading::Symbol<
            unsafe extern "C" fn(*const std::ffi::c_char) -> *const std::ffi::c_void,
        > = lib
            .get(b"eglGetProcAddress\0")
            .map_err(|e| anyhow!("eglGetProcAddress: {e}"))?;
        let p = get(c"glClipControl".as_ptr());
        // libEGL stays loaded by the context itself; keep our handle alive too.
        std::mem::forget(lib);
        if p.is_null() {
            bail!("glClipControl is not available");
        }
        Ok(std::mem::transmute::<*const std::ffi::c_void, ClipControlFn>(p))
    }
}

const VS_PLANE: &str = r#"#version 450
layout(location=0) uniform mat4 proj;
layout(location=1) uniform float dist;
void main() {
  vec2 c = vec2((gl_VertexID & 1) != 0 ? 1.0 : -1.0, (gl_VertexID & 2) != 0 ? 1.0 : -1.0);
  gl_Position = proj * vec4(c * (2.0 * dist), -dist, 1.0);
}
"#;
const FS_PLANE: &str = r#"#version 450
out vec4 color;
void main() { color = vec4(1.0); }
"#;
const VS_FULL: &str = r#"#version 450
void main() {
  vec2 c = vec2((gl_VertexID & 1) != 0 ? 1.0 : -1.0, (gl_VertexID & 2) != 0 ? 1.0 : -1.0);
  gl_Position = vec4(c, 0.0, 1.0);
}
"#;
/// The lesson's restore formula (sao_restore_depth.frag) for the standard modes.
const FS_RESTORE: &str = r#"#version 450
out float outColor;
layout(binding=0) uniform sampler2D texDepth;
void main() {
  float depth = texelFetch(texDepth, ivec2(gl_FragCoord.xy), 0).x;
  const float near = CAMERA_NEAR;
  const float far = CAMERA_FAR;
#ifdef REVERSED_Z
  if (depth <= 0.0) { outColor = far; return; }
  outColor = min(near * far / (depth * (far - near) + near), far);
#else
  const float A = -2 * far * near / (far - near);
  const float B = (far + near) / (far - near);
  if (depth >= 1.0) { outColor = far; return; }
  depth = 2 * depth - 1;
  outColor = min(A / (depth - B), far);
#endif
}
"#;

unsafe fn compile(gl: &Gl, vs: &str, fs: &str) -> Result<glow::Program> {
    let p = gl.create_program().map_err(|e| anyhow!(e))?;
    let mut shaders = Vec::new();
    for (kind, src) in [(glow::VERTEX_SHADER, vs), (glow::FRAGMENT_SHADER, fs)] {
        let s = gl.create_shader(kind).map_err(|e| anyhow!(e))?;
        gl.shader_source(s, src);
        gl.compile_shader(s);
        if !gl.get_shader_compile_status(s) {
            bail!("depth probe shader: {}", gl.get_shader_info_log(s));
        }
        gl.attach_shader(p, s);
        shaders.push(s);
    }
    gl.link_program(p);
    if !gl.get_program_link_status(p) {
        bail!("depth probe program: {}", gl.get_program_info_log(p));
    }
    for s in shaders {
        gl.detach_shader(p, s);
        gl.delete_shader(s);
    }
    Ok(p)
}

fn glsl_float(v: f32) -> String {
    crate::gl::preprocess::glsl_float(v)
}

/// The reversed-Z projection for a [0, 1] clip range: depth = n·(f − z) / (z·(f − n)) (near → 1, far → 0).
pub fn reversed_projection(fov_y_deg: f32, aspect: f32, near: f32, far: f32) -> Mat4 {
    let mut m = Mat4::perspective_rh_gl(fov_y_deg.to_radians(), aspect, near, far);
    // Row 2 (z): clip.z = m22·z_view + m32 with z_view = −z: we need A·z + B with A = −n/(f−n), B = n·f/(f−n).
    let (n, f) = (near as f64, far as f64);
    let c = m.z_axis;
    m.z_axis = glam::Vec4::new(c.x, c.y, (n / (f - n)) as f32, c.w);
    let w = m.w_axis;
    m.w_axis = glam::Vec4::new(w.x, w.y, (n * f / (f - n)) as f32, w.w);
    m
}

/// The probe: measures restored linear depth of a facing plane for one mode and camera.
pub struct DepthProbe {
    gl: Gl,
    vao: glow::VertexArray,
    plane: glow::Program,
    clip_control: Option<ClipControlFn>,
    /// Why reversed-Z is unavailable, when it is.
    pub clip_control_error: Option<String>,
}

impl DepthProbe {
    pub fn new(gl: &Gl) -> Result<DepthProbe> {
        let (clip_control, clip_control_error) = match load_clip_control() {
            Ok(f) => (Some(f), None),
            Err(e) => (None, Some(format!("{e:#}"))),
        };
        unsafe {
            let vao = gl.create_vertex_array().map_err(|e| anyhow!(e))?;
            let plane = compile(gl, VS_PLANE, FS_PLANE)?;
            Ok(DepthProbe {
                gl: gl.clone(),
                vao,
                plane,
                clip_control,
                clip_control_error,
            })
        }
    }

    pub fn supports(&self, mode: DepthMode) -> bool {
        !mode.reversed() || self.clip_control.is_some()
    }

    /// Restored linear depth (metres) of a plane facing the camera at each distance, with the given
    /// planes and a 60° field of view; one 4×4 render per distance.
    pub fn measure(
        &self,
        mode: DepthMode,
        near: f32,
        far: f32,
        distances: &[f64],
    ) -> Result<Vec<f32>> {
        let gl = &self.gl;
        if mode.reversed() && self.clip_control.is_none() {
            bail!(
                "reversed-Z needs glClipControl: {}",
                self.clip_control_error.clone().unwrap_or_default()
            );
        }
        let size = 4;
        let depth = Rc::new(Texture::new(
            gl,
            TextureDesc::target("probe depth", size, size, mode.format()),
        )?);
        let fbo_depth = FramebufferObject::new(gl, None, Some(depth.clone()), 0, 0)?;
        let out = Rc::new(Texture::new(
            gl,
            TextureDesc::target("probe linear depth", size, size, glow::R32F),
        )?);
        let fbo_out = FramebufferObject::new(gl, Some(out.clone()), None, 0, 0)?;
        let mut fs = String::from(FS_RESTORE);
        let mut defines = format!(
            "#define CAMERA_NEAR {}\n#define CAMERA_FAR {}\n",
            glsl_float(near),
            glsl_float(far)
        );
        if mode.reversed() {
            defines.push_str("#define REVERSED_Z 1\n");
        }
        fs = fs.replacen("#version 450\n", &format!("#version 450\n{defines}"), 1);
        let restore = unsafe { compile(gl, VS_FULL, &fs)? };
        let proj = if mode.reversed() {
            reversed_projection(60.0, 1.0, near, far)
        } else {
            Mat4::perspective_rh_gl(60f32.to_radians(), 1.0, near, far)
        };
        let mut result = Vec::with_capacity(distances.len());
        unsafe {
            gl.bind_vertex_array(Some(self.vao));
            gl.disable(glow::BLEND);
            gl.disable(glow::CULL_FACE);
            gl.disable(glow::SCISSOR_TEST);
            if let (true, Some(cc)) = (mode.reversed(), self.clip_control) {
                cc(glow::LOWER_LEFT, glow::ZERO_TO_ONE);
            }
            for &d in distances {
                fbo_depth.bind();
                gl.enable(glow::DEPTH_TEST);
                gl.depth_mask(true);
                if mode.reversed() {
                    gl.clear_depth_f32(0.0);
                    gl.depth_func(glow::GREATER);
                } else {
                    gl.clear_depth_f32(1.0);
                    gl.depth_func(glow::LEQUAL);
                }
                gl.clear(glow::DEPTH_BUFFER_BIT);
                gl.use_program(Some(self.plane));
                gl.uniform_matrix_4_f32_slice(
                    Some(&glow::NativeUniformLocation(0)),
                    false,
                    &proj.to_cols_array(),
                );
                gl.uniform_1_f32(Some(&glow::NativeUniformLocation(1)), d as f32);
                gl.draw_arrays(glow::TRIANGLE_STRIP, 0, 4);

                fbo_out.bind();
                gl.disable(glow::DEPTH_TEST);
                gl.depth_mask(false);
                gl.use_program(Some(restore));
                depth.bind(0);
                gl.draw_arrays(glow::TRIANGLE_STRIP, 0, 4);
                let v = out.read_f32(0, 1);
                // Centre texel: every texel sees the same distance.
                result.push(v[(size * size / 2 + size / 2) as usize]);
            }
            if mode.reversed() {
                if let Some(cc) = self.clip_control {
                    cc(glow::LOWER_LEFT, glow::NEGATIVE_ONE_TO_ONE);
                }
                gl.clear_depth_f32(1.0);
            }
            gl.depth_func(glow::LEQUAL);
            gl.depth_mask(true);
            gl.use_program(None);
            gl.bind_vertex_array(None);
            gl.delete_program(restore);
        }
        if let Some(e) = crate::gl::take_error(gl) {
            bail!("{e} in the depth probe ({})", mode.label());
        }
        Ok(result)
    }
}

impl Drop for DepthProbe {
    fn drop(&mut self) {
        unsafe {
            self.gl.delete_vertex_array(self.vao);
            self.gl.delete_program(self.plane);
        }
    }
}
