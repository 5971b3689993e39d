//! Visibility-bitmask AO (Therrien et al. 2023): per slice, 32 sectors of equal cosine weight, each
//! depth sample occluding the sectors its slab (surface to `thickness` behind, within the radius)
//! covers. Shader: `Res/ao/vbao.frag`; quality presets shared with `gtao` (`settings::SlicePreset`).
//! With the slab hierarchy (`AoSettings::uses_slab_hierarchy`) the taps read `ao::slab_hierarchy`'s
//! levels instead of single texels.

use crate::ao::method_pass::{
    method_defines, units_for_budget, AoInputs, AoMethodPass, ShaderMethod,
};
use crate::ao::method_row::MethodRow;
use crate::ao::settings::{AoMethod, AoSettings};
use crate::ao::slab_hierarchy::SlabLevels;
use crate::gl::{Gl, ProgramError, ProgramObject, Texture};
use crate::math::Camera;
use crate::res::ResDirs;
use crate::shader_interface::{binding, loc, s, u, Sampler, Uniform};
use anyhow::Result;
use std::rc::Rc;

/// Slices when no preset is set: two, as `gtao`, so `--samples N` buys both methods the same depth
/// taps (slices × 2 sides × steps ≈ N).
pub const DEFAULT_SLICES: i32 = 2;

/// `aoCounts` = (slices, steps per side): the preset's when one is set.
pub fn counts(s: &AoSettings) -> [i32; 2] {
    if let Some(q) = s.quality {
        let (slices, steps) = q.vbao_slices_steps();
        return [slices as i32, steps as i32];
    }
    [
        DEFAULT_SLICES,
        units_for_budget(s.samples, 2 * DEFAULT_SLICES as u32),
    ]
}

/// The inputs `vbao.frag` compiles in (VBAO_*): the ones `settings` make the engine draw. Each
/// left out is code a software rasteriser would otherwise run for every tap, taken or not.
pub fn feature_defines(settings: &AoSettings) -> Vec<(&'static str, String)> {
    let flag = |on: bool| u8::from(on).to_string();
    vec![
        ("VBAO_SLABS", flag(settings.uses_slab_hierarchy())),
        ("VBAO_BACK_FACES", flag(settings.uses_back_faces())),
        ("VBAO_SECOND_LAYER", flag(settings.uses_second_layer())),
        (
            "VBAO_SECOND_LAYER_BACK_FACES",
            flag(settings.uses_second_layer_back_faces()),
        ),
    ]
}

pub const ROW: MethodRow = MethodRow {
    build: |gl, res, camera, _| Ok(Box::new(VbaoMethod::build(gl, res, camera)?)),
    uniforms: UNIFORMS,
    samplers: SAMPLERS,
};

const UNIFORMS: &[Uniform] = &[
    u("aoInfo", loc::AO_INFO),
    u("ndcToView", loc::NDC_TO_VIEW),
    u("aoCounts", loc::AO_COUNTS),
    u("maxRadiusPixels", loc::MAX_RADIUS_PIXELS),
    u("aoThickness", loc::AO_THICKNESS),
    u("aoBackFaces", loc::AO_BACK_FACES),
    u("aoSurfaceNormals", loc::AO_SURFACE_NORMALS),
    u("aoLayers", loc::AO_LAYERS),
    u("aoLayerBackFaces", loc::AO_LAYER_BACK_FACES),
    u("aoSlabLevels", loc::AO_SLAB_LEVELS),
    u("aoFrameJitter", loc::AO_FRAME_JITTER),
];
const SAMPLERS: &[Sampler] = &[
    s("texDepth", binding::INPUT),
    s("texBackDepth", binding::SECOND_INPUT),
    s("texNormal", binding::SURFACE_NORMALS),
    s("texSecondDepth", binding::SECOND_LAYER),
    s("texSecondBackDepth", binding::SECOND_LAYER_BACK),
    s("texSlabs", binding::SLAB_HIERARCHY),
];

/// The occlusion pass and, when the settings ask for it, the slab hierarchy it reads.
pub struct VbaoMethod {
    pass: ShaderMethod,
    slabs: SlabLevels,
}

impl VbaoMethod {
    pub fn build(gl: &Gl, res: &ResDirs, camera: &Camera) -> Result<VbaoMethod, ProgramError> {
        Ok(VbaoMethod {
            pass: ShaderMethod::build(AoMethod::Vbao, counts, gl, res, camera)?,
            slabs: SlabLevels::new(gl, res, &method_defines(camera))?,
        })
    }
}

impl VbaoMethod {
    /// The slab hierarchy from the last frame that built one.
    pub fn slab_hierarchy(&self) -> Option<Rc<Texture>> {
        self.slabs.texture()
    }
}

impl AoMethodPass for VbaoMethod {
    fn method(&self) -> AoMethod {
        AoMethod::Vbao
    }
    fn programs_mut(&mut self) -> Vec<&mut ProgramObject> {
        let mut v = self.pass.programs_mut();
        v.push(&mut self.slabs.program);
        v
    }
    fn update_defines(&mut self, camera: &Camera, s: &AoSettings) -> Result<(), ProgramError> {
        self.pass
            .update_defines_with(camera, s, &feature_defines(s))?;
        self.slabs.program.set_defines(&method_defines(camera))
    }
    fn compute(&self, inputs: &AoInputs) -> Result<()> {
        let levels = if inputs.settings.uses_slab_hierarchy() {
            let tex = self.slabs.build(inputs)?;
            tex.bind(binding::SLAB_HIERARCHY);
            tex.levels() as i32
        } else {
            0
        };
        self.pass.program().set_i32(loc::AO_SLAB_LEVELS, levels);
        self.pass.compute(inputs)
    }
    fn blur(&self, inputs: &AoInputs) -> Result<()> {
        self.pass.blur(inputs)
    }
    fn textures(&self) -> Vec<Rc<Texture>> {
        let mut v = self.pass.textures();
        v.extend(self.slabs.texture());
        v
    }
    fn release_targets(&mut self) {
        self.pass.release_targets();
        self.slabs.release();
    }
}
