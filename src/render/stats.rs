//! What a frame cost: per-pass wall and CPU time (`render --stats`, the bench, the panel) and the
//! AO textures the engine holds.

use crate::gl::{PassClock, Texture, TimerQuery};
use std::cell::Cell;

/// Time and draw calls of one pass of the last frame.
#[derive(Clone, Debug, serde::Serialize)]
pub struct PassStat {
    pub name: &'static str,
    /// shadow, opaque, ao, sky, transparent, bloom or post.
    pub group: &'static str,
    /// Milliseconds by `clock`: the GPU's time (timer query) on a hardware driver, the wall clock
    /// between two glFinish calls on software GL (whose timer queries do not measure real time).
    pub ms: f64,
    /// Which clock `ms` is.
    pub clock: PassClock,
    /// Wall-clock milliseconds between two glFinish calls, on every driver.
    pub wall_ms: f64,
    /// CPU milliseconds the whole process (llvmpipe's threads included) spent in the pass: unlike
    /// `ms`, barely changed by other programs competing for the cores (benchmarks on shared machines).
    pub cpu_ms: f64,
    pub draw_calls: u64,
}

/// Times the engine's passes (with `Engine::collect_stats`) by the driver's clock
/// (`PassClock::for_renderer`).
pub struct PassTimer {
    clock: PassClock,
    /// The timer query on hardware drivers; `None` on software GL.
    query: Option<TimerQuery>,
    /// A pass is being timed: a pass inside it gets the wall clock (one TIME_ELAPSED query at a
    /// time).
    busy: Cell<bool>,
}

/// What one pass cost, by `PassTimer::time`.
pub struct Timed {
    pub ms: f64,
    pub clock: PassClock,
    pub wall_ms: f64,
    pub cpu_ms: f64,
}

impl PassTimer {
    pub fn new(gl: &crate::gl::Gl) -> PassTimer {
        let query = match PassClock::of_context(gl) {
            PassClock::GpuTimer => TimerQuery::new(gl),
            PassClock::WallClock => None,
        };
        PassTimer {
            clock: if query.is_some() {
                PassClock::GpuTimer
            } else {
                PassClock::WallClock
            },
            query,
            busy: Cell::new(false),
        }
    }

    /// The clock of the passes' `ms`.
    pub fn clock(&self) -> PassClock {
        self.clock
    }

    /// Runs `f` between two glFinish calls and measures it by the clock (and the wall and CPU
    /// clocks).
    pub fn time<T>(&self, gl: &glow::Context, f: impl FnOnce() -> T) -> (T, Timed) {
        use glow::HasContext;
        // SAFETY: glFinish on the current context.
        unsafe { gl.finish() };
        let t = std::time::Instant::now();
        let cpu = process_cpu_seconds();
        let query = self.query.as_ref().filter(|_| !self.busy.replace(true));
        let (out, device_ms) = match query {
            Some(q) => {
                let (out, ms) = q.time(f);
                self.busy.set(false);
                (out, Some(ms))
            }
            None => (f(), None),
        };
        unsafe { gl.finish() };
        let wall_ms = t.elapsed().as_secs_f64() * 1e3;
        let timed = Timed {
            ms: device_ms.unwrap_or(wall_ms),
            clock: if device_ms.is_some() {
                PassClock::GpuTimer
            } else {
                PassClock::WallClock
            },
            wall_ms,
            cpu_ms: (process_cpu_seconds() - cpu) * 1e3,
        };
        (out, timed)
    }
}

/// CPU time of the whole process (all threads), in seconds.
#[cfg(unix)]
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

/// Elsewhere (Windows) the wall-clock time since the first call stands in for the CPU time: the
/// per-pass figures then read as wall-clock milliseconds.
#[cfg(not(unix))]
pub fn process_cpu_seconds() -> f64 {
    static START: std::sync::OnceLock<std::time::Instant> = std::sync::OnceLock::new();
    START
        .get_or_init(std::time::Instant::now)
        .elapsed()
        .as_secs_f64()
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
