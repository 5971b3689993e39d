//! Normal-oriented hemisphere SSAO (Filion and McNaughton 2008, StarCraft II): the sphere kernel flipped into the surface's
//! hemisphere, with a range check so distant occluders do not count. Shader: `Res/ao/hemisphere.frag`.

use crate::ao::method_pass::ShaderMethod;
use crate::ao::method_row::MethodRow;
use crate::ao::settings::{AoMethod, AoSettings};
use crate::shader_interface::{AO_METHOD_SAMPLERS, AO_UNCLAMPED_UNIFORMS};

/// `aoCounts` = (sample count, unused).
pub fn counts(s: &AoSettings) -> [i32; 2] {
    [s.samples.max(1) as i32, 1]
}

pub const ROW: MethodRow = MethodRow {
    build: |gl, res, camera, _| {
        let pass = ShaderMethod::build(AoMethod::Hemisphere, counts, gl, res, camera)?;
        Ok(Box::new(pass))
    },
    uniforms: AO_UNCLAMPED_UNIFORMS,
    samplers: AO_METHOD_SAMPLERS,
};
