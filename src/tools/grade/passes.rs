//! Running the lesson's passes of one side of the rig (the project's or the student's) on given
//! inputs, and reading their output back.

use crate::ao::{AoSettings, SaoLesson};
use crate::gl::MeshBuffer;
use anyhow::Result;

/// Which mip levels of `texSAODepth` the SAO pass gets to see.
#[derive(Clone, Copy, PartialEq, Eq)]
pub enum Mips {
    /// The down-sampling pass's output, as in the engine.
    Filled,
    /// Every level above 0 pushed to the far plane after down-sampling: samples read from levels
    /// 1–3 then see nothing, so the output changes only where a shader reads the mips.
    Emptied,
    /// Only the last level pushed to the far plane: the output changes only where a shader reads it.
    LastEmptied,
}

/// Linear depth `depth` (metres, `far` for sky) → down-sampling → SAO; returns the raw occlusion.
pub fn run_sao(
    lesson: &SaoLesson,
    meshes: &MeshBuffer,
    camera: &crate::math::Camera,
    depth: &[f32],
    params: &AoSettings,
    mips: Mips,
) -> Result<Vec<f32>> {
    lesson.targets.tex_depth.upload_f32(0, 1, depth)?;
    lesson.down_sample(meshes);
    let levels = lesson.targets.tex_depth.levels();
    let emptied = match mips {
        Mips::Filled => levels..levels,
        Mips::Emptied => 1..levels,
        Mips::LastEmptied => levels - 1..levels,
    };
    for level in emptied {
        let (w, h) = lesson.targets.tex_depth.size_at(level);
        let far = vec![camera.far; (w * h) as usize];
        lesson.targets.tex_depth.upload_f32(level, 1, &far)?;
    }
    lesson.compute_sao(meshes, camera, params);
    Ok(lesson.sao_texture().read_f32(0, 1))
}

/// Linear depth and occlusion → blur; returns the blurred occlusion.
pub fn run_blur(
    lesson: &SaoLesson,
    meshes: &MeshBuffer,
    depth: &[f32],
    occlusion: &[f32],
) -> Result<Vec<f32>> {
    lesson.targets.tex_depth.upload_f32(0, 1, depth)?;
    lesson.sao_texture().upload_f32(0, 1, occlusion)?;
    lesson.blur(meshes);
    Ok(lesson.result_texture(true).read_f32(0, 1))
}

/// The project's and the student's SAO on the same linear depth, mip chain filled as the lesson
/// builds it: (the project's, the student's) raw outputs.
pub fn run_sao_pair(
    reference: &SaoLesson,
    student: &SaoLesson,
    meshes: &MeshBuffer,
    camera: &crate::math::Camera,
    depth: &[f32],
    params: &AoSettings,
) -> Result<(Vec<f32>, Vec<f32>)> {
    let run = |lesson| run_sao(lesson, meshes, camera, depth, params, Mips::Filled);
    Ok((run(reference)?, run(student)?))
}
