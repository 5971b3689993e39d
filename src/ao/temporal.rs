//! Temporal accumulation for the screen-space methods: each frame the method's sample directions
//! and steps turn by the next point of the R2 sequence (`frame_jitter`, the one input the method
//! shaders read for it: `aoFrameJitter` in `Res/ao/common.glsl`), and `Res/ao/temporal_accumulate.frag`
//! blends the frame's occlusion with the previous frames' reprojected through the two cameras,
//! dropping the history where depth or normal disagree (disocclusion) and clamping it to the 3×3
//! range of the current occlusion. The running mean stops growing at `accumulate` frames and goes
//! on as an exponential mean of that length. XeGTAO and other engines spread their samples over
//! frames the same way and leave the reprojection to TAA; here the AO keeps its own history.
//!
//! `rtao` accumulates through the same pass: its rays move on along its own sequence each frame,
//! the neighbourhood clamp is off (a surface point's traced occlusion does not change with the
//! view, and a few rays' neighbourhood says little about its range), only an opposite normal drops
//! its history (`RTAO_NORMAL_COSINE`) and the mean undoes its intensity; the method restarts the history when an object moves (`RtaoMethod::restarted`).
//!
//! On only with `accumulate` > 1 and a method other than the lesson's SAO (left as it is): the
//! single-frame outputs stay what they were.

use super::settings::{AoMethod, AoSettings};
use super::targets::AoTargets;
use crate::gl::pass_state::Depth;
use crate::gl::preprocess::glsl_float;
use crate::gl::{FramebufferObject, Gl, MeshBuffer, PassState, ProgramError, ProgramObject};
use crate::gl::{Texture, TextureDesc};
use crate::math::camera::fov_scale;
use crate::math::Camera;
use crate::res::ResDirs;
use crate::shader_interface::{binding, loc};
use anyhow::Result;
use glam::{Mat3, Mat4};
use glow::HasContext;
use std::cell::{Cell, RefCell};
use std::rc::Rc;

pub const SHADER: &str = "ao/temporal_accumulate.frag";
/// The same shader built for the sky texels alone (the first of the pass's two draws).
pub const SKY_PASS_DEFINE: &str = "TEMPORAL_SKY_PASS";

/// Depth the history may differ by and still be the same surface, as a fraction of the depth.
pub const DEPTH_TOLERANCE: f32 = 0.02;
/// Least cosine between the history's normal and the current one (about 25°).
pub const NORMAL_COSINE: f32 = 0.9;
/// `rtao`'s: only a normal facing the other way (the far side of a thin sheet) drops the history.
/// A traced point's occlusion does not depend on the view, the depth test already finds the same
/// surface, and at a quarter of the size the normal rebuilt from neighbouring texels turns at every
/// small feature of a detailed model, dropping history that still holds.
pub const RTAO_NORMAL_COSINE: f32 = 0.0;
/// How far (in occlusion) the history may lie outside the current 3×3 range: the range of a
/// blurred, noisy frame is narrow, and a clamp exactly to it would hold the mean at each frame's
/// noise; this much lets it converge while a moved shadow still goes within a frame or two.
pub const CLAMP_SLACK: f32 = 0.05;

/// Whether `settings` accumulate over frames (a screen-space method or `rtao`).
pub fn applies(settings: &AoSettings) -> bool {
    settings.enabled && settings.accumulate > 1 && settings.method != AoMethod::SaoLesson
}

/// How far the history may lie outside the current 3×3 range: `CLAMP_SLACK`, or no clamp for `rtao`.
pub fn clamp_slack(settings: &AoSettings) -> f32 {
    if settings.method == AoMethod::Rtao {
        1.0
    } else {
        CLAMP_SLACK
    }
}

/// The least cosine between the history's normal and the current one that keeps the history.
pub fn normal_cosine(settings: &AoSettings) -> f32 {
    if settings.method == AoMethod::Rtao {
        RTAO_NORMAL_COSINE
    } else {
        NORMAL_COSINE
    }
}

/// The exponent of the intensity curve the mean undoes: `rtao`'s (intensity / 5), else 1 (the
/// screen-space methods average their output as it is).
pub fn curve(settings: &AoSettings) -> f32 {
    if settings.method == AoMethod::Rtao && settings.intensity > 0.0 {
        settings.intensity / 5.0
    } else {
        1.0
    }
}

/// Frame `index` of the R2 sequence (Roberts 2018, "The unreasonable effectiveness of
/// quasirandom sequences"): (rotation, step offset), each in [0, 1); frame 0 is (0, 0), the
/// single-frame pattern.
pub fn r2(index: u32) -> [f32; 2] {
    // 1/g and 1/g² for the plastic number g, in f64 so that long runs stay evenly spread.
    const A1: f64 = 0.754_877_666_246_692_7;
    const A2: f64 = 0.569_840_290_998_053_2;
    let i = index as f64;
    [(i * A1).fract() as f32, (i * A2).fract() as f32]
}

/// The camera a history was made with.
#[derive(Clone, Copy)]
struct HistoryCamera {
    view: Mat4,
    ndc_to_view: [f32; 2],
    size: (u32, u32),
}

/// Two histories, written in turn, sharing one depth buffer that marks the sky texels.
struct Histories {
    fbo: [FramebufferObject; 2],
}

/// The pass draws twice: the sky texels first, with a trivial build of the shader that leaves a
/// depth of 0 where it wrote, then the full shader on the texels still at the cleared depth. A
/// software rasteriser runs a shader's whole body for every block with one live pixel, so the
/// full shader over the sky (a model under open sky leaves most texels there) costs as much as
/// over surfaces; the depth test drops those blocks before the shader runs.
pub struct TemporalAccumulation {
    program: ProgramObject,
    sky_program: ProgramObject,
    histories: RefCell<Option<Histories>>,
    /// Frames accumulated since the last restart (the R2 index of the next frame).
    frame: Cell<u32>,
    /// Which history the last frame wrote, and its camera; `None` until a frame ran.
    last: Cell<Option<(usize, HistoryCamera)>>,
}

impl TemporalAccumulation {
    pub fn new(
        gl: &Gl,
        res: &ResDirs,
        camera: &Camera,
    ) -> Result<TemporalAccumulation, ProgramError> {
        let program = ProgramObject::from_res(gl, res, "simple.vert", SHADER, &defines(camera))?;
        let sky_program =
            ProgramObject::from_res(gl, res, "simple.vert", SHADER, &sky_defines(camera))?;
        Ok(TemporalAccumulation {
            program,
            sky_program,
            histories: RefCell::new(None),
            frame: Cell::new(0),
            last: Cell::new(None),
        })
    }

    pub fn programs_mut(&mut self) -> [&mut ProgramObject; 2] {
        [&mut self.program, &mut self.sky_program]
    }

    pub fn update_defines(&mut self, camera: &Camera) -> Result<(), ProgramError> {
        self.program.set_defines(&defines(camera))?;
        self.sky_program.set_defines(&sky_defines(camera))
    }

    /// The rotation and step offset the method shaders add this frame ([0, 0] when off).
    pub fn frame_jitter(&self, settings: &AoSettings) -> [f32; 2] {
        if applies(settings) {
            r2(self.frame.get())
        } else {
            [0.0; 2]
        }
    }

    /// Frames drawn since the history started (0 before any frame); the mean holds at most
    /// `accumulate` of them.
    pub fn frames(&self) -> u32 {
        self.frame.get()
    }

    /// Drops the history: the next frame starts the mean again.
    pub fn restart(&self) {
        self.frame.set(0);
        self.last.set(None);
    }

    /// Drops the size-dependent textures (and the history with them).
    pub fn release_targets(&mut self) {
        *self.histories.borrow_mut() = None;
        self.restart();
    }

    pub fn textures(&self) -> Vec<Rc<Texture>> {
        self.histories
            .borrow()
            .iter()
            .flat_map(|h| h.fbo.iter().filter_map(|f| f.color_texture().cloned()))
            .collect()
    }

    /// Blends this frame's occlusion in `targets` (blurred or raw, as `blurred` says) with the
    /// history and writes the result back there, for the up-sampling and the composite. Where a
    /// texel's history holds `blurred_frames` frames or more, the raw occlusion is blended instead
    /// of the blurred (`rtao`: the blur's bias outweighs the noise it removes); 0: never.
    #[allow(clippy::too_many_arguments)]
    pub fn run(
        &self,
        gl: &Gl,
        meshes: &MeshBuffer,
        targets: &AoTargets,
        camera: &Camera,
        settings: &AoSettings,
        blurred: bool,
        blurred_frames: u32,
    ) -> Result<()> {
        let size = targets.size();
        self.ensure_histories(gl, size)?;
        let histories = self.histories.borrow();
        let histories = histories.as_ref().expect("created above");
        let fov = fov_scale(camera.fov_y_deg);
        let now = HistoryCamera {
            view: camera.view(),
            ndc_to_view: [size.0 as f32 / size.1 as f32 / fov, 1.0 / fov],
            size,
        };
        let last = self.last.get().filter(|(_, c)| c.size == size);
        let write = last.map_or(0, |(read, _)| 1 - read);
        let previous = last.map_or(now, |(_, c)| c);
        let p = &self.program;
        p.set_mat4(
            loc::TEMPORAL_CURRENT_TO_PREVIOUS,
            &(previous.view * now.view.inverse()),
        );
        p.set_mat3(
            loc::TEMPORAL_VIEW_TO_WORLD,
            &Mat3::from_mat4(now.view.inverse()),
        );
        p.set_vec2(loc::TEMPORAL_NDC_TO_VIEW, now.ndc_to_view);
        p.set_vec2(loc::TEMPORAL_PREVIOUS_NDC_TO_VIEW, previous.ndc_to_view);
        p.set_vec4(
            loc::TEMPORAL_INFO,
            [
                settings.accumulate as f32,
                DEPTH_TOLERANCE,
                normal_cosine(settings),
                clamp_slack(settings),
            ],
        );
        p.set_i32(loc::TEMPORAL_HISTORY_VALID, last.is_some() as i32);
        p.set_f32(loc::TEMPORAL_CURVE, curve(settings));
        p.set_f32(loc::TEMPORAL_BLURRED_FRAMES, blurred_frames as f32);
        let out = &histories.fbo[write];
        out.bind();
        // SAFETY: a viewport of the target's own size.
        unsafe { gl.viewport(0, 0, size.0 as i32, size.1 as i32) };
        let history_tex = histories.fbo[1 - write]
            .color_texture()
            .expect("created with a colour texture");
        targets.result_texture(blurred).bind(0);
        targets.tex_depth.bind(1);
        history_tex.bind(2);
        targets.result_texture(false).bind(binding::TEMPORAL_RAW);
        // Depth 1 everywhere, then 0 where the sky draw wrote; the full draw at 0.5 passes where
        // the depth stayed 1.
        let marks = PassState {
            depth: Depth::Test {
                func: glow::ALWAYS,
                write: true,
            },
            depth_range: (0.0, 0.0),
            ..PassState::FULLSCREEN
        };
        marks.apply(gl, None);
        // SAFETY: the depth buffer of a complete framebuffer; one float as the call reads.
        unsafe { gl.clear_named_framebuffer_f32_slice(Some(out.id()), glow::DEPTH, 0, &[1.0]) };
        self.sky_program.use_program();
        meshes.draw_plane_xy();
        PassState {
            depth: Depth::Test {
                func: glow::LESS,
                write: false,
            },
            depth_range: (0.5, 0.5),
            ..PassState::FULLSCREEN
        }
        .apply(gl, None);
        p.use_program();
        meshes.draw_plane_xy();
        PassState::FULLSCREEN.apply(gl, None);
        // The blend back into the target the rest of the frame reads (RGBA32F → R8: red only).
        let result = if blurred {
            &targets.fbo_blur
        } else {
            &targets.fbo_sao
        };
        let (w, h) = (size.0 as i32, size.1 as i32);
        // SAFETY: both framebuffers are complete and `size` large.
        unsafe {
            gl.blit_named_framebuffer(
                Some(out.id()),
                Some(result.id()),
                0,
                0,
                w,
                h,
                0,
                0,
                w,
                h,
                glow::COLOR_BUFFER_BIT,
                glow::NEAREST,
            );
        }
        self.last.set(Some((write, now)));
        self.frame.set(self.frame.get().saturating_add(1));
        Ok(())
    }

    fn ensure_histories(&self, gl: &Gl, size: (u32, u32)) -> Result<()> {
        let fits = self
            .histories
            .borrow()
            .as_ref()
            .is_some_and(|h| (h.fbo[0].width(), h.fbo[0].height()) == size);
        if fits {
            return Ok(());
        }
        let marks = Rc::new(Texture::new(
            gl,
            TextureDesc::target(
                "ao history sky marks",
                size.0,
                size.1,
                glow::DEPTH_COMPONENT32F,
            ),
        )?);
        let make = |name: &str| -> Result<FramebufferObject> {
            let tex = Texture::new(gl, TextureDesc::target(name, size.0, size.1, glow::RGBA32F))?;
            FramebufferObject::new(gl, Some(Rc::new(tex)), Some(marks.clone()), 0, 0)
        };
        *self.histories.borrow_mut() = Some(Histories {
            fbo: [make("FBO(ao history 0)")?, make("FBO(ao history 1)")?],
        });
        self.last.set(None);
        Ok(())
    }
}

fn defines(camera: &Camera) -> Vec<(&'static str, String)> {
    vec![("CAMERA_FAR", glsl_float(camera.far))]
}

fn sky_defines(camera: &Camera) -> Vec<(&'static str, String)> {
    let mut d = defines(camera);
    d.push((SKY_PASS_DEFINE, "1".into()));
    d
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn r2_starts_at_the_single_frame_pattern_and_spreads_evenly() {
        assert_eq!(r2(0), [0.0, 0.0]);
        // Any 16 consecutive points leave no quarter of either axis empty.
        for start in [1, 100, 10_000] {
            for axis in 0..2 {
                let mut seen = [false; 4];
                for i in start..start + 16 {
                    let v = r2(i)[axis];
                    assert!((0.0..1.0).contains(&v));
                    seen[(v * 4.0) as usize] = true;
                }
                assert!(seen.iter().all(|&s| s), "axis {axis} from {start}");
            }
        }
    }

    #[test]
    fn every_method_but_the_lesson_with_accumulate_above_one_accumulates() {
        let base = AoSettings {
            method: AoMethod::Vbao,
            accumulate: 8,
            ..Default::default()
        };
        assert!(applies(&base));
        assert!(!applies(&AoSettings {
            accumulate: 1,
            ..base
        }));
        let lesson = AoSettings {
            method: AoMethod::SaoLesson,
            ..base
        };
        assert!(!applies(&lesson));
        let rtao = AoSettings {
            method: AoMethod::Rtao,
            ..base
        };
        assert!(applies(&rtao));
        // rtao's history is not clamped, and its intensity is undone for the mean.
        assert_eq!(clamp_slack(&base), CLAMP_SLACK);
        assert_eq!(clamp_slack(&rtao), 1.0);
        assert_eq!(curve(&base), 1.0);
        assert_eq!(
            curve(&AoSettings {
                intensity: 10.0,
                ..rtao
            }),
            2.0
        );
    }
}
