//! The guard band of the engine's AO chain (`[ao] guard_band`): the depth, the normals and the back
//! faces are rendered over a field of view widened by a margin of whole pixels on each side, at the
//! view's pixel size and pixel centres, and the method and its blur run over the whole of it, so that
//! occluders just off screen count. The inner part of the results is then copied into the AO targets
//! the composite, the views and the tools read, which never see the margin.

use super::Engine;
use crate::ao::guard_band::{ao_offset, crop, guard_band_pixels, widen, GuardFrame};
use crate::ao::{AoMethod, AoTargets};
use crate::render::frame::Frame;
use crate::render::view::View;
use anyhow::Result;

impl Engine {
    /// The guard band a frame showing `view` gives the AO chain: none for the lesson's SAO (the
    /// course renders the view only) and for the depth views.
    pub fn guard_frame(&self, view: View) -> Option<GuardFrame> {
        let s = &self.ao_settings;
        if s.method == AoMethod::SaoLesson || view.is_depth() {
            return None;
        }
        let px = guard_band_pixels(s.guard_band, &self.camera, self.size(), s.radius);
        if px == 0 {
            return None;
        }
        widen(&self.camera, self.size(), px)
    }

    /// The AO chain over the widened view: the surface-normal pass draws its depth (and normals),
    /// the depth chain, the surface passes, the method and its blur run over it, and the inner part
    /// goes to `targets`.
    pub(super) fn run_guarded_ao(
        &self,
        f: &Frame,
        targets: &AoTargets,
        view: View,
        g: &GuardFrame,
    ) -> Result<()> {
        let wide = Frame {
            camera: &g.camera,
            size: g.size,
            ..*f
        };
        let resolution = self.ao_settings.effective_resolution();
        let levels = targets.tex_depth.levels();
        let work = self
            .guard_targets
            .get(&self.gl, g.size, levels, resolution)?;
        let passes = &self.surface;
        let normals = self.pass("surface normals", "ao", || {
            passes.normals.draw(&wide, None, work.size())
        })?;
        let depth = passes.normals.depth_texture()?;
        self.restore_depth_chain(&work, &depth)?;
        let surface = self.run_surface_passes(&wide, &depth, work.size(), Some(normals))?;
        let blurred = self.run_method(&g.camera, &work, &surface, view)?;
        let offset = ao_offset(g.pixels, resolution);
        self.pass("guard band crop", "ao", || {
            crop(&self.gl, &work, targets, offset, blurred)
        });
        // The view's own depth chain from its cropped level 0, for the views and tools that read
        // the levels.
        self.pass("view depth levels", "ao", || {
            crate::ao::depth_chain::down_sample(
                &self.gl,
                &self.ao.depth_chain.down_sampling,
                targets,
                &self.meshes,
            )
        });
        Ok(())
    }
}
