//! Ray-traced AO: the scene's world-space triangles in a binary BVH (`scene::bvh`, built on the CPU
//! the first time the method runs and again only when an object moves), traversed per pixel by
//! `Res/ao/rtao.frag` with a few cosine-weighted rays of length R. The result is the visibility the
//! CPU reference measures, with Monte-Carlo noise instead of a screen-space model's bias: occluders
//! off screen or behind other surfaces count. The noise is smoothed by the packed edge-aware blur and,
//! with `accumulate` > 1, by the mean over frames of `ao::temporal`: each frame traces the next rays
//! of the sequence, and the history follows the camera (a surface point's occlusion does not depend
//! on the view), starting again only where an object moved or a setting changed; from
//! `UNBLURRED_FROM_RAYS` rays per pixel on, the mean alone.

use crate::ao::method_pass::{AoInputs, AoMethodPass, ShaderMethod};
use crate::ao::method_row::MethodRow;
use crate::ao::settings::{AoMethod, AoSettings};
use crate::gl::{Gl, ProgramError, ProgramObject, StorageBuffer, Texture};
use crate::math::Camera;
use crate::res::ResDirs;
use crate::scene::bvh::{BvhStats, FlatBvh};
use crate::scene::game_object::GameObject;
use crate::shader_interface::{binding, loc, s, storage, u, Sampler, Uniform};
use anyhow::Result;
use glam::Vec3;
use glow::HasContext;
use std::cell::{Cell, RefCell};
use std::collections::hash_map::DefaultHasher;
use std::hash::{Hash, Hasher};
use std::rc::Rc;

pub const ROW: MethodRow = MethodRow {
    build: |gl, res, camera, _| Ok(Box::new(RtaoMethod::build(gl, res, camera)?)),
    uniforms: UNIFORMS,
    samplers: SAMPLERS,
};

const UNIFORMS: &[Uniform] = &[
    u("aoInfo", loc::AO_INFO),
    u("ndcToView", loc::NDC_TO_VIEW),
    u("aoSurfaceNormals", loc::AO_SURFACE_NORMALS),
    u("viewToWorld", loc::RTAO_VIEW_TO_WORLD),
    u("rtaoFrame", loc::RTAO_FRAME),
    u("rtaoNodeCount", loc::RTAO_NODE_COUNT),
];
const SAMPLERS: &[Sampler] = &[
    s("texDepth", binding::INPUT),
    s("texNormal", binding::SURFACE_NORMALS),
];

/// `aoCounts` = (rays per pixel and frame, unused).
pub fn counts(s: &AoSettings) -> [i32; 2] {
    [s.rays as i32, 1]
}

/// Rays per pixel (frames averaged × rays per frame) from which the output is left unblurred: on the
/// bench's three scenes at 960×540 (R = 1 m), 11 rays in one frame were 0.1–0.8 dB closer to the
/// reference blurred, 2 rays × 16 frames 1.2–2.4 dB closer unblurred (the blur's bias then outweighs
/// the noise it removes).
pub const UNBLURRED_FROM_RAYS: u32 = 16;

/// Frames of a texel's history below which the accumulation takes the blurred frame instead of the
/// raw one (the `UNBLURRED_FROM_RAYS` rule, per texel); 0 where nothing is blurred.
pub fn blurred_frames(s: &AoSettings, blurred: bool) -> u32 {
    if blurred {
        UNBLURRED_FROM_RAYS.div_ceil(s.rays.max(1))
    } else {
        0
    }
}

/// The BVH in storage buffers, and the objects it was built from.
struct GpuBvh {
    key: u64,
    nodes: StorageBuffer,
    triangles: StorageBuffer,
    stats: BvhStats,
}

/// Frames since the scene or a setting last changed (the camera may move: the history follows it).
#[derive(Clone, Copy, Default)]
struct Accumulation {
    key: u64,
    frames: u32,
    /// Frames in the last output's mean (at most `accumulate`).
    averaged: u32,
}

/// The shared skeleton, tracing the BVH, with its running mean.
pub struct RtaoMethod {
    gl: Gl,
    pass: ShaderMethod,
    bvh: RefCell<Option<GpuBvh>>,
    builds: Cell<u32>,
    accumulation: Cell<Accumulation>,
    /// The last pass's count of pixels whose rays the driver cut short (`RtaoStatus`).
    status: RefCell<Option<StorageBuffer>>,
}

/// Identifies the objects' geometry: mesh names, triangle counts and model matrices.
fn objects_key(objects: &[GameObject], meshes: &crate::gl::MeshBuffer) -> u64 {
    let mut h = DefaultHasher::new();
    for o in objects {
        o.name.hash(&mut h);
        meshes.data(&o.name).map(|d| d.indices.len()).hash(&mut h);
        for v in o.model().to_cols_array() {
            v.to_bits().hash(&mut h);
        }
    }
    h.finish()
}

/// The count after one more frame whose inputs hash to `key`, and the frames already in the mean
/// before it (0: start again). A new key, or `accumulate` 1, starts again.
fn next_accumulation(previous: Accumulation, key: u64, accumulate: u32) -> (Accumulation, u32) {
    let frames = if previous.key == key && accumulate > 1 {
        previous.frames
    } else {
        0
    };
    let next = Accumulation {
        key,
        frames: frames.saturating_add(1),
        averaged: frames.min(accumulate.max(1) - 1) + 1,
    };
    (next, frames)
}

/// Every object's triangles in world space.
pub fn world_triangles(objects: &[GameObject], meshes: &crate::gl::MeshBuffer) -> Vec<[Vec3; 3]> {
    let mut out = Vec::new();
    for o in objects {
        let m = o.model();
        if let Some(d) = meshes.data(&o.name) {
            out.extend(d.triangles().map(|t| t.map(|p| m.transform_point3(p))));
        }
    }
    out
}

impl RtaoMethod {
    pub fn build(gl: &Gl, res: &ResDirs, camera: &Camera) -> Result<RtaoMethod, ProgramError> {
        Ok(RtaoMethod {
            gl: gl.clone(),
            pass: ShaderMethod::build(AoMethod::Rtao, counts, gl, res, camera)?,
            bvh: RefCell::new(None),
            builds: Cell::new(0),
            accumulation: Cell::new(Accumulation::default()),
            status: RefCell::new(None),
        })
    }

    /// Builds and uploads the BVH unless the objects are those it was built from.
    fn ensure_bvh(&self, inputs: &AoInputs) -> Result<u64> {
        let key = objects_key(inputs.objects, inputs.meshes);
        if self.bvh.borrow().as_ref().is_some_and(|b| b.key == key) {
            return Ok(key);
        }
        *self.bvh.borrow_mut() = None;
        let flat = FlatBvh::build(&world_triangles(inputs.objects, inputs.meshes))?;
        self.builds.set(self.builds.get() + 1);
        let stats = BvhStats {
            builds: self.builds.get(),
            ..flat.stats()
        };
        let gl = &self.gl;
        *self.bvh.borrow_mut() = Some(GpuBvh {
            key,
            nodes: StorageBuffer::new(gl, "rtao BVH nodes", &flat.node_words())?,
            triangles: StorageBuffer::new(gl, "rtao BVH triangles", &flat.triangle_words())?,
            stats,
        });
        Ok(key)
    }

    /// Frames already averaged into the history for this frame (0: start again). The camera is not
    /// in the key: `ao::temporal` reprojects the history through it.
    fn frames_before(&self, inputs: &AoInputs, bvh_key: u64) -> u32 {
        let s = inputs.settings;
        let mut h = DefaultHasher::new();
        bvh_key.hash(&mut h);
        for v in [s.radius, s.intensity] {
            v.to_bits().hash(&mut h);
        }
        (s.rays, s.accumulate, s.stratified, inputs.targets.size()).hash(&mut h);
        let key = h.finish();
        let (next, frames) = next_accumulation(self.accumulation.get(), key, s.accumulate);
        self.accumulation.set(next);
        frames
    }
}

impl RtaoMethod {
    /// The BVH it traces, once built, with its build time and size.
    pub fn bvh_stats(&self) -> Option<BvhStats> {
        self.bvh.borrow().as_ref().map(|b| b.stats)
    }

    /// Frames averaged into its last output (`accumulate`) where the history was kept; 1 without
    /// accumulation.
    pub fn accumulated_frames(&self) -> u32 {
        self.accumulation.get().averaged.max(1)
    }

    /// Whether its last frame started the mean again (the first frame, a moved object, a changed
    /// setting, a restart): the engine then drops the reprojected history too.
    pub fn restarted(&self) -> bool {
        self.accumulation.get().frames <= 1
    }

    /// Pixels of its last pass whose rays the driver ended before they were all traced (a driver's
    /// loop limit); those pixels hold the mean of the rays that finished.
    pub fn cut_pixels(&self) -> u32 {
        let status = self.status.borrow();
        let Some(buffer) = status.as_ref() else {
            return 0;
        };
        // SAFETY: a barrier, so the shader's atomic writes are visible to the read below.
        unsafe { self.gl.memory_barrier(glow::BUFFER_UPDATE_BARRIER_BIT) };
        buffer.read_words().first().copied().unwrap_or(0)
    }

    /// Starts its running mean again at the next frame (the window, after any change of setting).
    pub fn restart_accumulation(&self) {
        self.accumulation.set(Accumulation::default());
    }
}

impl AoMethodPass for RtaoMethod {
    fn method(&self) -> AoMethod {
        AoMethod::Rtao
    }
    fn programs_mut(&mut self) -> Vec<&mut ProgramObject> {
        self.pass.programs_mut()
    }
    fn update_defines(&mut self, camera: &Camera, s: &AoSettings) -> Result<(), ProgramError> {
        self.pass.update_defines(camera, s)
    }
    fn compute(&self, inputs: &AoInputs) -> Result<()> {
        let bvh_key = self.ensure_bvh(inputs)?;
        let s = inputs.settings;
        // The frames are averaged by `ao::temporal`; here they are only counted, so that each
        // frame traces the next rays of the sequence.
        let since_reset = if s.accumulate > 1 {
            self.frames_before(inputs, bvh_key)
        } else {
            self.accumulation.set(Accumulation::default());
            0
        };
        let p = self.pass.program();
        p.set_mat4(loc::RTAO_VIEW_TO_WORLD, &inputs.camera.view().inverse());
        let rays = s.rays.max(1);
        // The stratified lattice: this pass's share of it (`lattice_slice`), else all of it.
        let (first, sequence) = match (s.stratified, s.lattice_slice) {
            (true, (first, of)) if of > 0 => (first, of),
            (true, _) => (0, rays),
            (false, _) => (since_reset.wrapping_mul(rays), 0),
        };
        let location = glow::NativeUniformLocation(loc::RTAO_FRAME as u32);
        // SAFETY: an ivec4 uniform at a location the interface test checks.
        unsafe {
            inputs.gl.program_uniform_4_i32(
                p.id(),
                Some(&location),
                rays as i32,
                first as i32,
                0,
                sequence as i32,
            )
        };
        let bvh = self.bvh.borrow();
        let bvh = bvh.as_ref().expect("built above");
        p.set_i32(loc::RTAO_NODE_COUNT, bvh.stats.nodes as i32);
        bvh.nodes.bind(storage::BVH_NODES);
        bvh.triangles.bind(storage::BVH_TRIANGLES);
        let status = StorageBuffer::new(inputs.gl, "rtao status", &[0])?;
        status.bind(storage::RTAO_STATUS);
        *self.status.borrow_mut() = Some(status);
        // The skeleton's pass: common uniforms, targets, depth and normals, one draw.
        self.pass.compute(inputs)?;
        Ok(())
    }
    fn blur(&self, inputs: &AoInputs) -> Result<()> {
        let rays_so_far = self.accumulated_frames() * inputs.settings.rays.max(1);
        // Accumulated, each texel's history holds its own count of frames (fewer where it came into
        // view): the blurred frame is made every frame and `ao::temporal` takes it while a texel has
        // fewer than `UNBLURRED_FROM_RAYS` rays (`blurred_frames`).
        if inputs.settings.accumulate > 1 || rays_so_far < UNBLURRED_FROM_RAYS {
            return self.pass.blur(inputs);
        }
        let t = inputs.targets;
        let (w, h) = t.size();
        let (w, h) = (w as i32, h as i32);
        // SAFETY: a copy between two live framebuffers of the same size.
        unsafe {
            inputs.gl.blit_named_framebuffer(
                Some(t.fbo_sao.id()),
                Some(t.fbo_blur.id()),
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
            )
        };
        Ok(())
    }
    fn textures(&self) -> Vec<Rc<Texture>> {
        self.pass.textures()
    }
    fn release_targets(&mut self) {
        self.pass.release_targets();
        self.accumulation.set(Accumulation::default());
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_frame_count_grows_on_the_same_inputs_and_starts_again_on_new_ones() {
        let mut a = Accumulation::default();
        let mut before = Vec::new();
        for key in [7, 7, 7, 8, 8] {
            let (next, frames) = next_accumulation(a, key, 16);
            before.push(frames);
            a = next;
        }
        assert_eq!(before, [0, 1, 2, 0, 1]);
        assert_eq!(a.averaged, 2);
        // The mean stops growing at `accumulate` frames.
        for _ in 0..20 {
            a = next_accumulation(a, 8, 4).0;
        }
        assert_eq!(a.averaged, 4);
        // Without accumulation every frame starts again; a restart (the default) does too.
        assert_eq!(next_accumulation(a, 8, 1).1, 0);
        assert_eq!(next_accumulation(Accumulation::default(), 8, 16).1, 0);
    }
}
