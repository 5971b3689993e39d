//! The first two passes every AO method shares: restore linear depth from the main depth buffer at
//! half size (`sao_restore_depth.frag`, or `ao/restore_depth_reversed.frag` for reversed-Z) or at
//! full size (`ao/restore_depth_full.frag`, `ao/restore_depth_full_reversed.frag`), then the min mip
//! chain (`sao_down_sampling.frag`).

use super::settings::AoResolution;
use super::targets::AoTargets;
use crate::gl::preprocess::glsl_float;
use crate::gl::{
    FramebufferObject, Gl, MeshBuffer, PassState, ProgramError, ProgramObject, Texture,
};
use crate::math::{Camera, DepthMode};
use crate::res::ResDirs;
use crate::shader_interface::loc;

/// CAMERA_NEAR / CAMERA_FAR as the restore, down-sampling and blur shaders read them (compile-time
/// constants, as in the course).
pub fn camera_defines(camera: &Camera) -> Vec<(&'static str, String)> {
    vec![
        ("CAMERA_NEAR", glsl_float(camera.near)),
        ("CAMERA_FAR", glsl_float(camera.far)),
    ]
}

/// The restore and down-sampling programs.
pub struct DepthChain {
    pub restore: ProgramObject,
    /// Built the first time reversed-Z is used.
    pub restore_reversed: Option<ProgramObject>,
    /// Full-resolution restores (standard, reversed-Z), built the first time they are needed.
    pub restore_full: Option<ProgramObject>,
    pub restore_full_reversed: Option<ProgramObject>,
    pub down_sampling: ProgramObject,
    res: ResDirs,
}

impl DepthChain {
    pub fn new(gl: &Gl, res: &ResDirs, camera: &Camera) -> Result<DepthChain, ProgramError> {
        let planes = camera_defines(camera);
        Ok(DepthChain {
            restore: ProgramObject::from_res(
                gl,
                res,
                "simple.vert",
                "sao_restore_depth.frag",
                &planes,
            )?,
            restore_reversed: None,
            restore_full: None,
            restore_full_reversed: None,
            down_sampling: ProgramObject::from_res(
                gl,
                res,
                "simple.vert",
                "sao_down_sampling.frag",
                &planes,
            )?,
            res: res.clone(),
        })
    }

    /// Builds what `mode` and `resolution` need (the reversed-Z and full-size restores) if not
    /// built yet.
    pub fn prepare(
        &mut self,
        gl: &Gl,
        mode: DepthMode,
        resolution: AoResolution,
        camera: &Camera,
    ) -> Result<(), ProgramError> {
        let full = resolution == AoResolution::Full;
        let (slot, file) = match (mode.reversed(), full) {
            (false, false) => return Ok(()),
            (true, false) => (&mut self.restore_reversed, "ao/restore_depth_reversed.frag"),
            (false, true) => (&mut self.restore_full, "ao/restore_depth_full.frag"),
            (true, true) => (
                &mut self.restore_full_reversed,
                "ao/restore_depth_full_reversed.frag",
            ),
        };
        if slot.is_none() {
            *slot = Some(ProgramObject::from_res(
                gl,
                &self.res,
                "simple.vert",
                file,
                &camera_defines(camera),
            )?);
        }
        Ok(())
    }

    pub fn programs_mut(&mut self) -> Vec<&mut ProgramObject> {
        let mut v = vec![&mut self.restore, &mut self.down_sampling];
        v.extend(self.restore_reversed.as_mut());
        v.extend(self.restore_full.as_mut());
        v.extend(self.restore_full_reversed.as_mut());
        v
    }

    pub fn update_camera(&mut self, camera: &Camera) -> Result<(), ProgramError> {
        let planes = camera_defines(camera);
        for p in self.programs_mut() {
            p.set_defines(&planes)?;
        }
        Ok(())
    }

    /// Main depth → linear depth level 0 with the restore that matches `mode`'s convention and the
    /// targets' size (full when they are as large as the main depth buffer); an error when that
    /// restore was not prepared.
    pub fn restore_linear_depth(
        &self,
        gl: &Gl,
        targets: &AoTargets,
        meshes: &MeshBuffer,
        main_depth: &Texture,
        mode: DepthMode,
    ) -> anyhow::Result<()> {
        let main_size = (main_depth.width(), main_depth.height());
        let full = targets.size() == main_size && targets.size() != (1, 1);
        if !full && targets.size() != super::targets::half_size(main_size.0, main_size.1) {
            anyhow::bail!(
                "no linear-depth restore from {}x{} to {}x{} (the engine draws a quarter-size depth itself)",
                main_size.0,
                main_size.1,
                targets.size().0,
                targets.size().1
            );
        }
        let program = match (mode.reversed(), full) {
            (false, false) => Some(&self.restore),
            (true, false) => self.restore_reversed.as_ref(),
            (false, true) => self.restore_full.as_ref(),
            (true, true) => self.restore_full_reversed.as_ref(),
        };
        let program = program.ok_or_else(|| {
            anyhow::anyhow!(
                "the linear-depth restore for {} at {} resolution was not prepared",
                mode.name(),
                if full { "full" } else { "half" }
            )
        })?;
        restore(gl, program, &targets.fbo_depth[0], meshes, main_depth);
        Ok(())
    }
}

/// main depth → `texSAODepth` level 0 (linear metres, half size, nearest of 2×2).
pub fn restore(
    gl: &Gl,
    program: &ProgramObject,
    level0: &FramebufferObject,
    meshes: &MeshBuffer,
    main_depth: &Texture,
) {
    PassState::FULLSCREEN.apply(gl, None);
    program.use_program();
    level0.bind();
    main_depth.bind(0);
    meshes.draw_plane_xy();
}

/// Levels 1.. of `texSAODepth`, each the min of 2×2 texels of the level above.
pub fn down_sample(gl: &Gl, program: &ProgramObject, targets: &AoTargets, meshes: &MeshBuffer) {
    PassState::FULLSCREEN.apply(gl, None);
    program.use_program();
    let tex = &targets.tex_depth;
    tex.bind(0);
    for (i, fbo) in targets.fbo_depth.iter().enumerate().skip(1) {
        // Limit sampling to the levels already written so that the level being written is not
        // also readable (no feedback loop), keeping the lesson's texelFetch(…, mipLevel) valid.
        tex.set_level_range(0, i as u32 - 1);
        fbo.bind();
        program.set_i32(loc::SAO_MIP_LEVEL, i as i32 - 1);
        meshes.draw_plane_xy();
    }
    tex.set_level_range(0, tex.levels() - 1);
}
