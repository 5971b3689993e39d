//! Horizon-based AO (Bavoil, Sainz and Dimitrov 2008): marches screen-space directions, keeps the highest horizon per
//! direction. Shader: `Res/ao/hbao.frag`.

use crate::ao::method_pass::{units_for_budget, ShaderMethod};
use crate::ao::method_row::MethodRow;
use crate::ao::settings::{AoMethod, AoSettings};
use crate::shader_interface::{AO_METHOD_SAMPLERS, AO_METHOD_UNIFORMS};

/// Four directions (the fewest that cover both screen axes both ways); the rest of the sample
/// budget goes to steps per direction, so directions × steps ≈ samples.
pub const DIRECTIONS: i32 = 4;

/// `aoCounts` = (directions, steps per direction).
pub fn counts(s: &AoSettings) -> [i32; 2] {
    [DIRECTIONS, units_for_budget(s.samples, DIRECTIONS as u32)]
}

pub const ROW: MethodRow = MethodRow {
    build: |gl, res, camera, _| {
        let pass = ShaderMethod::build(AoMethod::Hbao, counts, gl, res, camera)?;
        Ok(Box::new(pass))
    },
    uniforms: AO_METHOD_UNIFORMS,
    samplers: AO_METHOD_SAMPLERS,
};
