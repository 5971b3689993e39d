//! What a frame cost: per-pass wall and CPU time (`render --stats`, the bench, the panel) and the
//! AO textures the engine holds.

use crate::gl::Texture;

/// Time and draw calls of one pass of the last frame.
#[derive(Clone, Debug, serde::Serialize)]
pub struct PassStat {
    pub name: &'static str,
    /// shadow, opaque, ao, sky, transparent, bloom or post.
    pub group: &'static str,
    /// Wall-clock milliseconds between two glFinish calls (timer queries do not measure real time on llvmpipe).
    pub ms: f64,
    /// CPU milliseconds the whole process (llvmpipe's threads included) spent in the pass: unlike
    /// `ms`, barely changed by other programs competing for the cores (benchmarks on shared machines).
    pub cpu_ms: f64,
    pub draw_calls: u64,
}

/// CPU time of the whole process (all threads), in seconds.
pub fn process_cpu_seconds() -> f64 {
    let mut ts = libc::timespec {
        tv_sec: 0,
        tv_nsec: 0,
    };
    // SAFETY: clock_gettime writes one timespec; CLOCK_PROCESS_CPUTIME_ID exists on Linux.
    let rc = unsafe { libc::clock_gettime(libc::CLOCK_PROCESS_CPUTIME_ID, &mut ts) };
    if rc != 0 {
        return 0.0;
    }
    ts.tv_sec as f64 + ts.tv_nsec as f64 * 1e-9
}

/// One texture the engine owns for AO (`Engine::ao_textures`).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct AoTextureInfo {
    pub name: String,
    pub width: u32,
    pub height: u32,
    pub levels: u32,
    pub internal_format: u32,
    /// Bytes of storage, all levels.
    pub bytes: u64,
}

impl AoTextureInfo {
    pub fn of(t: &Texture) -> AoTextureInfo {
        let d = t.desc();
        let texel = match d.internal_format {
            glow::R8 => 1,
            glow::R16F | glow::RG8 => 2,
            glow::R32F | glow::RG16F | glow::RGBA8 => 4,
            glow::DEPTH_COMPONENT32 | glow::DEPTH_COMPONENT32F => 4,
            glow::RG32F | glow::RGBA16F => 8,
            _ => 16,
        };
        let bytes = (0..t.levels())
            .map(|l| {
                let (w, h) = t.size_at(l);
                w as u64 * h as u64 * texel
            })
            .sum();
        AoTextureInfo {
            name: d.name.clone(),
            width: d.width,
            height: d.height,
            levels: t.levels(),
            internal_format: d.internal_format,
            bytes,
        }
    }
}
