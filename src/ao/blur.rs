//! The blurs of the occlusion buffer: the lesson's 9×9 bilateral blur (`sao_blur.frag`), the engine's
//! two-pass separable bilateral blur (`ao/blur_separable.frag`) and its packed variant that reads
//! (occlusion, depth) from one texture per tap (`ao/blur_packed.frag`, used by every engine method:
//! `packed.rs`).

use super::sky_skip::{draw_texels, SkyValues, Texels};
use super::targets::AoTargets;
use crate::gl::{
    FramebufferObject, Gl, MeshBuffer, PassState, ProgramObject, Texture, TextureDesc,
};
use crate::shader_interface::{binding, loc};
use anyhow::Result;
use glow::HasContext;
use std::cell::RefCell;
use std::rc::Rc;

/// `sao_blur.frag`: `texSAO` → `texSAOBlur` in one pass, weights from linear depth.
pub fn lesson_blur(gl: &Gl, program: &ProgramObject, targets: &AoTargets, meshes: &MeshBuffer) {
    PassState::FULLSCREEN.apply(gl, None);
    program.use_program();
    targets.fbo_blur.bind();
    targets.sao_texture().bind(binding::INPUT);
    targets.tex_depth.bind(binding::SECOND_INPUT);
    meshes.draw_plane_xy();
}

/// Texels each pass of the engine's separable blurs reads on either side of its own
/// (`blur_separable.frag`, `blur_packed.frag`): what AO beyond the texels it must produce a blur
/// needs.
pub const BLUR_REACH: u32 = 4;

/// `BLUR_WEIGHTS` for `blur_packed.frag` when the method's row names a Gaussian of its own
/// (`MethodInfo::blur_sigma`, in AO texels): the BLUR_REACH + 1 weights from the centre out, six
/// decimals; `None` keeps the shader's own table.
pub fn weights_define(sigma: Option<f32>) -> Option<(&'static str, String)> {
    let sigma = f64::from(sigma?);
    let w: Vec<f64> = (0..=BLUR_REACH)
        .map(|r| (-f64::from(r * r) / (2.0 * sigma * sigma)).exp())
        .collect();
    let total = w[0] + 2.0 * w[1..].iter().sum::<f64>();
    let table = w.iter().map(|x| format!("{:.6}", x / total));
    Some(("BLUR_WEIGHTS", table.collect::<Vec<_>>().join(", ")))
}

fn set_axis(gl: &Gl, program: &ProgramObject, axis: [i32; 2]) {
    let location = glow::NativeUniformLocation(loc::BLUR_AXIS as u32);
    // SAFETY: an ivec2 uniform at a location the interface test checks.
    unsafe { gl.program_uniform_2_i32(program.id(), Some(&location), axis[0], axis[1]) };
}

/// The separable blur's program and its AO-size intermediate target (R8). The engine's methods
/// blur with the packed blur; this one is the two-texture form tests compare it with.
pub struct SeparableBlur {
    pub program: ProgramObject,
    /// Created on the first blur and dropped by `release_targets` (an engine with AO off owns no AO
    /// texture).
    tmp: RefCell<Option<FramebufferObject>>,
}

impl SeparableBlur {
    pub fn new(program: ProgramObject) -> SeparableBlur {
        SeparableBlur {
            program,
            tmp: RefCell::new(None),
        }
    }

    pub fn release_targets(&mut self) {
        *self.tmp.get_mut() = None;
    }

    pub fn textures(&self) -> Vec<Rc<Texture>> {
        self.tmp
            .borrow()
            .iter()
            .filter_map(|f| f.color_texture().cloned())
            .collect()
    }

    /// `texSAO` → intermediate (horizontal) → `texSAOBlur` (vertical), within `region` when given
    /// (`AoInputs::region`).
    pub fn run(
        &self,
        gl: &Gl,
        targets: &AoTargets,
        meshes: &MeshBuffer,
        region: Option<[i32; 4]>,
    ) -> Result<()> {
        let size = targets.size();
        let mut tmp = self.tmp.borrow_mut();
        if tmp.as_ref().map(|f| (f.width(), f.height())) != Some(size) {
            *tmp = None;
            *tmp = Some(ao_size_target(gl, "FBO(ao blur tmp)", size, glow::R8)?);
        }
        let fbo_tmp = tmp.as_ref().expect("created above");
        PassState::FULLSCREEN.with_scissor(region).apply(gl, None);
        self.program.use_program();
        targets.tex_depth.bind(binding::SECOND_INPUT);
        set_axis(gl, &self.program, [1, 0]);
        fbo_tmp.bind();
        targets.sao_texture().bind(binding::INPUT);
        meshes.draw_plane_xy();
        set_axis(gl, &self.program, [0, 1]);
        targets.fbo_blur.bind();
        fbo_tmp
            .color_texture()
            .expect("created with a colour texture")
            .bind(binding::INPUT);
        meshes.draw_plane_xy();
        Ok(())
    }
}

/// The packed blur: `packed` (RG32F: occlusion, depth) → `tmp` (RG32F) → the targets' blur target,
/// shading `texels` (`AoInputs::texels`).
pub fn packed_blur(
    gl: &Gl,
    program: &ProgramObject,
    packed: &Texture,
    tmp: &FramebufferObject,
    targets: &AoTargets,
    meshes: &MeshBuffer,
    texels: Texels,
) {
    // A sky texel passes its (0, far) pair on, then 0 into the R8 target.
    let far = texels.sky_far();
    program.use_program();
    set_axis(gl, program, [1, 0]);
    packed.bind(binding::INPUT);
    let pair = [[0.0, far, 0.0, 0.0]];
    let horizontal = SkyValues {
        fbo: tmp,
        per_draw_buffer: &pair,
    };
    draw_texels(gl, texels, horizontal, || meshes.draw_plane_xy());
    set_axis(gl, program, [0, 1]);
    tmp.color_texture()
        .expect("created with a colour texture")
        .bind(binding::INPUT);
    let vertical = SkyValues {
        fbo: &targets.fbo_blur,
        per_draw_buffer: &[[0.0; 4]],
    };
    draw_texels(gl, texels, vertical, || meshes.draw_plane_xy());
}

/// A one-level colour target of the AO size (`size`: half, full or quarter of the main image).
pub fn ao_size_target(
    gl: &Gl,
    name: &str,
    (w, h): (u32, u32),
    format: u32,
) -> Result<FramebufferObject> {
    let tex = Rc::new(Texture::new(gl, TextureDesc::target(name, w, h, format))?);
    FramebufferObject::new(gl, Some(tex), None, 0, 0)
}

#[cfg(test)]
mod tests {
    use super::weights_define;
    use crate::ao::AoMethod;

    #[test]
    fn a_methods_gaussian_is_written_out_from_its_sigma() {
        assert_eq!(weights_define(None), None);
        let (name, table) = weights_define(Some(1.0)).unwrap();
        assert_eq!(name, "BLUR_WEIGHTS");
        // 1 / (1 + 2 (e^-1/2 + e^-2 + e^-9/2 + e^-8)), then each weight's share.
        assert_eq!(table, "0.398943, 0.241971, 0.053991, 0.004432, 0.000134");
        // rtao's narrows as its rays per frame add up; vbao's is fixed; the others keep the table.
        let rtao = AoMethod::Rtao.info().blur_sigma.unwrap();
        assert_eq!((rtao(1), rtao(4), rtao(16)), (3.0, 1.5, 0.75));
        assert_eq!(AoMethod::Vbao.info().blur_sigma.map(|f| f(4)), Some(1.0));
        assert!(AoMethod::Sao.info().blur_sigma.is_none());
    }

    #[test]
    fn the_blurs_read_their_reach_from_the_injected_define_only() {
        for shader in ["blur_separable.frag", "blur_packed.frag"] {
            let path = format!("{}/Res/ao/{shader}", env!("CARGO_MANIFEST_DIR"));
            let text = std::fs::read_to_string(&path).unwrap();
            let loop_header = "for (int r = -BLUR_REACH; r <= BLUR_REACH; ++r)";
            assert!(
                text.contains(loop_header),
                "{shader} has no `{loop_header}`"
            );
            assert!(text.contains("axis * r"), "{shader}: taps one texel apart");
            assert!(
                !text.contains("#define BLUR_REACH") && !text.contains("#define CAMERA_FAR"),
                "{shader} defines a value the engine injects"
            );
        }
    }
}
