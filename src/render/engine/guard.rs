//! The engine's AO chain when it draws geometry of its own: the guard band (`[ao] guard_band`) and
//! the surface passes (back faces, second layer, normals). Their depth, normals and back faces are
//! drawn at the AO size itself, over the view or over a field of view widened by a margin of whole
//! pixels on each side (same pixel size and centres), so that occluders just off screen count. The
//! method and its blur then draw the view and the blur's reach around it (the margin is read as
//! depth only), and the inner part of the results is copied into the AO targets the composite, the
//! views and the tools read, which never see the margin.
//!
//! Drawn at the AO size, each texel's front depth, back face, hidden layer and normal belong to one
//! point of the scene, the texel's centre: the surface passes cost the AO size's pixels, not the
//! output's (a quarter of them at half resolution).

use super::Engine;
use crate::ao::guard_band::{ao_offset, crop, guard_band_pixels, read_region, widen, GuardFrame};
use crate::ao::AoTargets;
use crate::render::frame::Frame;
use crate::render::view::View;
use anyhow::Result;

impl Engine {
    /// The guard band a frame showing `view` gives the AO chain: none for the lesson's SAO (the
    /// course renders the view only) and for the depth views.
    pub fn guard_frame(&self, view: View) -> Option<GuardFrame> {
        let s = &self.ao_settings;
        if !s.method.info().engine_chain || view.is_depth() {
            return None;
        }
        let px = guard_band_pixels(s.guard_band, &self.camera, self.size(), s.radius);
        if px == 0 {
            return None;
        }
        widen(&self.camera, self.size(), px)
    }

    /// The AO chain with its own geometry at the AO size: the surface-normal pass draws the depth
    /// (and normals) over the view or the widened view `guard`, then the depth chain, the surface
    /// passes, the method and its blur run over it; with a margin the inner part goes to `targets`.
    pub(super) fn run_ao_size_chain(
        &self,
        f: &Frame,
        targets: &AoTargets,
        view: View,
        guard: Option<&GuardFrame>,
    ) -> Result<()> {
        let resolution = self.ao_settings.effective_resolution();
        let widened;
        let (work, camera) = match guard {
            Some(g) => {
                let levels = targets.tex_depth.levels();
                widened = self
                    .guard_targets
                    .get(&self.gl, g.size, levels, resolution)?;
                (widened.as_ref(), &g.camera)
            }
            None => (targets, f.camera),
        };
        let at_ao_size = Frame {
            camera,
            size: work.size(),
            ..*f
        };
        let passes = &self.surface;
        // One pass draws the depth and the normals; the stats name it for what the method reads.
        let name = if self.ao_settings.uses_surface_normals() {
            "surface normals"
        } else {
            "surface depth"
        };
        let normals = self.pass(name, "ao", || {
            passes.normals.draw(&at_ao_size, None, work.size())
        })?;
        let depth = passes.normals.depth_texture()?;
        self.restore_depth_chain(work, &depth)?;
        if self.finish_depth_view(&at_ao_size, &depth, work.size(), view)? {
            return Ok(());
        }
        let mut surface =
            self.run_surface_passes(&at_ao_size, &depth, work.size(), Some(normals))?;
        surface.window_depth = Some(depth);
        let offset = guard.map(|g| ao_offset(g.pixels, resolution));
        // With a margin, AO only where the view's AO and its blur read it.
        let region = offset.map(|o| read_region(work.size(), targets.size(), o));
        let blurred = self.run_method(camera, work, &surface, view, region)?;
        let Some(offset) = offset else {
            return Ok(());
        };
        self.pass("guard band crop", "ao", || {
            crop(&self.gl, work, targets, offset, blurred)
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
