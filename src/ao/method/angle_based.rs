//! UE4-style angle-based SSAO (Mittring 2012, the Elemental demo): samples in mirrored pairs, occlusion from the angle the
//! pair makes over the pixel. Shader: `Res/ao/angle_based.frag`.

use crate::ao::method_pass::{units_for_budget, ShaderMethod};
use crate::ao::method_row::MethodRow;
use crate::ao::settings::{AoMethod, AoSettings};
use crate::shader_interface::{AO_METHOD_SAMPLERS, AO_METHOD_UNIFORMS};

/// `aoCounts` = (pairs, unused): each pair is two taps, so pairs = samples / 2.
pub fn counts(s: &AoSettings) -> [i32; 2] {
    [units_for_budget(s.samples, 2), 1]
}

pub const ROW: MethodRow = MethodRow {
    build: |gl, res, camera, _| {
        let pass = ShaderMethod::build(AoMethod::AngleBased, counts, gl, res, camera)?;
        Ok(Box::new(pass))
    },
    uniforms: AO_METHOD_UNIFORMS,
    samplers: AO_METHOD_SAMPLERS,
};
