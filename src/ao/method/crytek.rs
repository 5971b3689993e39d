//! Crytek's SSAO (Mittring 2007, "Finding Next Gen: CryEngine 2"): points in a sphere around the pixel, occluded when the depth buffer is
//! nearer than the point. Shader: `Res/ao/crytek.frag`.

use crate::ao::method_pass::ShaderMethod;
use crate::ao::method_row::MethodRow;
use crate::ao::settings::{AoMethod, AoSettings};
use crate::shader_interface::{binding, s, AO_SPHERE_UNIFORMS};

/// `aoCounts` = (sample count, unused).
pub fn counts(s: &AoSettings) -> [i32; 2] {
    [s.samples.max(1) as i32, 1]
}

pub const ROW: MethodRow = MethodRow {
    build: |gl, res, camera, _| {
        let pass = ShaderMethod::build(AoMethod::Crytek, counts, gl, res, camera)?;
        Ok(Box::new(pass))
    },
    uniforms: AO_SPHERE_UNIFORMS,
    samplers: &[s("texDepth", binding::INPUT)],
};
