//! Ground-truth-based AO (Jimenez et al. 2016): per slice, the two horizons found by marching the
//! depth buffer, then the cosine-weighted visible arc integrated in closed form. Shader:
//! `Res/ao/gtao.frag`; quality presets in `settings::SlicePreset`.

use crate::ao::method_pass::{units_for_budget, ShaderMethod};
use crate::ao::method_row::MethodRow;
use crate::ao::settings::{AoMethod, AoSettings};
use crate::shader_interface::{AO_METHOD_SAMPLERS, AO_METHOD_UNIFORMS};

/// Slices when no preset is set: two (the XeGTAO "medium" count), the sample budget going to steps
/// per side (each slice marches both sides: slices × 2 × steps ≈ samples).
pub const DEFAULT_SLICES: i32 = 2;

/// `aoCounts` = (slices, steps per side): the preset's when one is set.
pub fn counts(s: &AoSettings) -> [i32; 2] {
    if let Some(q) = s.quality {
        let (slices, steps) = q.gtao_slices_steps();
        return [slices as i32, steps as i32];
    }
    [
        DEFAULT_SLICES,
        units_for_budget(s.samples, 2 * DEFAULT_SLICES as u32),
    ]
}

pub const ROW: MethodRow = MethodRow {
    build: |gl, res, camera, _| {
        let pass = ShaderMethod::build(AoMethod::Gtao, counts, gl, res, camera)?;
        Ok(Box::new(pass))
    },
    uniforms: AO_METHOD_UNIFORMS,
    samplers: AO_METHOD_SAMPLERS,
};
