//! The engine's AO chain: the depth chain, the surface passes and the method with its blur, over the
//! view or a widened one (`guard`).

use super::Engine;
use crate::ao::method_pass::AoInputs;
use crate::ao::sky_skip::AoSizeDepth;
use crate::ao::{AoResolution, AoTargets};
use crate::gl::{PassState, Texture};
use crate::math::Camera;
use crate::render::frame::Frame;
use crate::render::passes::surface::SurfaceInputs;
use crate::render::view::View;
use anyhow::{anyhow, Result};

impl Engine {
    /// Frames averaged into the last frame's AO: `rtao`'s running mean, or the screen-space
    /// methods' temporal accumulation (`ao::temporal`); 1 without either.
    pub fn accumulated_frames(&self) -> u32 {
        let method = self.ao_settings.method;
        if method.info().rays {
            return self.ao.accumulated_frames(method);
        }
        if crate::ao::temporal::applies(&self.ao_settings) {
            // The mean stops growing at `accumulate` frames (then an exponential mean of that length).
            return self
                .temporal
                .frames()
                .clamp(1, self.ao_settings.accumulate.max(1));
        }
        1
    }

    /// The AO chain: restore and down-sample the depth, then the method and its blur (only what
    /// `view` shows); drawn at the AO size over a widened view when the settings ask for a guard
    /// band, or over the view when they ask for surface passes or a quarter-size AO (`guard`).
    pub(super) fn run_ao(&self, f: &Frame, targets: &AoTargets, view: View) -> Result<()> {
        if let Some(g) = self.guard_frame(view) {
            return self.run_ao_size_chain(f, targets, view, Some(&g));
        }
        let s = &self.ao_settings;
        let quarter = s.effective_resolution() == AoResolution::Quarter;
        if quarter || !view.is_depth() && s.uses_surface_passes() {
            return self.run_ao_size_chain(f, targets, view, None);
        }
        let depth = self
            .fbo_main
            .depth_texture()
            .ok_or_else(|| anyhow!("the main FBO has no depth texture"))?;
        self.restore_depth_chain(targets, depth)?;
        if self.finish_depth_view(f, depth, targets.size(), view)? {
            return Ok(());
        }
        let surface = self.run_surface_passes(f, depth, targets.size(), None)?;
        self.run_method(f.camera, targets, &surface, view, None)?;
        Ok(())
    }

    /// What a depth view needs once the depth chain ran from `depth` (window depth at `f`'s size):
    /// nothing more for the linear depth, the second layer at `size` for its view. `true` when `view`
    /// is a depth view, whose chain ends there.
    pub(super) fn finish_depth_view(
        &self,
        f: &Frame,
        depth: &Texture,
        size: (u32, u32),
        view: View,
    ) -> Result<bool> {
        match view {
            View::LinearDepth => Ok(true),
            View::SecondLayerDepth => {
                self.pass("second depth layer", "ao", || {
                    let separation = self.ao_settings.layer_separation_metres();
                    let layer = &self.surface.second_layer;
                    layer.draw(f, depth, separation, size)
                })?;
                Ok(true)
            }
            _ => Ok(false),
        }
    }

    /// The lesson's first two passes: linear depth from `depth` and its mip chain.
    pub(super) fn restore_depth_chain(&self, targets: &AoTargets, depth: &Texture) -> Result<()> {
        let chain = &self.ao.depth_chain;
        self.pass("sao restore depth", "ao", || {
            chain.restore_linear_depth(&self.gl, targets, &self.meshes, depth, self.depth_mode)
        })?;
        self.pass("sao down sampling", "ao", || {
            crate::ao::depth_chain::down_sample(
                &self.gl,
                &chain.down_sampling,
                targets,
                &self.meshes,
            )
        });
        Ok(())
    }

    /// The method's pass and its blur (unless the view shows the raw occlusion), drawing only
    /// `region` of `targets` when given (`AoInputs::region`); whether it blurred.
    pub(super) fn run_method(
        &self,
        camera: &Camera,
        targets: &AoTargets,
        surface: &SurfaceInputs,
        view: View,
        region: Option<[i32; 4]>,
    ) -> Result<bool> {
        let method = self.ao_settings.method;
        let inputs = AoInputs {
            gl: &self.gl,
            meshes: &self.meshes,
            targets,
            camera,
            settings: &self.ao_settings,
            back_depth: surface.back_depth.as_deref(),
            normals: surface.normals.as_deref(),
            second_depth: surface.second_depth.as_deref(),
            second_back_depth: surface.second_back_depth.as_deref(),
            objects: &self.objects,
            region,
            ao_size_depth: surface.window_depth.as_ref().map(|texture| AoSizeDepth {
                texture,
                mode: self.depth_mode,
                far: camera.far,
            }),
            frame_jitter: self.temporal.frame_jitter(&self.ao_settings),
        };
        let info = method.info();
        let (pass_name, blur_name) = self
            .ao
            .own_labels(method)
            .unwrap_or((info.pass_label, info.blur_label));
        self.pass(pass_name, "ao", || self.ao.compute(method, &inputs))?;
        let blur = self.ao_settings.blur && view != View::AoRaw;
        if blur {
            self.pass(blur_name, "ao", || self.ao.blur(method, &inputs))?;
        }
        // No scissor beyond the chain.
        PassState::FULLSCREEN.apply(&self.gl, None);
        Ok(blur)
    }
}
