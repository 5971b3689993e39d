//! Which clock times a render pass, and the GL timer query that measures one on a hardware driver.
//!
//! On a GPU the device's own time is what a pass costs: a `GL_TIME_ELAPSED` query around the pass
//! counts the nanoseconds the GPU spent on its commands. Mesa's software drivers (llvmpipe,
//! softpipe) implement the query, but their figure does not follow the rasteriser threads' real
//! time, so there the pass is timed by the wall clock between two `glFinish` calls.

use super::Gl;
use glow::HasContext;
use serde::Serialize;

/// The clock of a pass's `ms`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
pub enum PassClock {
    /// `GL_TIME_ELAPSED` timer query: time on the device.
    #[serde(rename = "gpu timer")]
    GpuTimer,
    /// Wall clock between two `glFinish` calls (software GL).
    #[serde(rename = "wall clock")]
    WallClock,
}

impl PassClock {
    /// The clock for the driver whose `GL_RENDERER` (or the whole "vendor renderer (version)"
    /// string) is `renderer`: the wall clock on Mesa's software drivers, the timer query elsewhere.
    pub fn for_renderer(renderer: &str) -> PassClock {
        let r = renderer.to_ascii_lowercase();
        if r.contains("llvmpipe") || r.contains("softpipe") {
            PassClock::WallClock
        } else {
            PassClock::GpuTimer
        }
    }

    /// The clock of the current context.
    pub fn of_context(gl: &glow::Context) -> PassClock {
        PassClock::for_renderer(&super::describe_renderer(gl))
    }

    /// Short name, as `--stats`, the reports and the panel print it.
    pub fn name(self) -> &'static str {
        match self {
            PassClock::GpuTimer => "gpu timer",
            PassClock::WallClock => "wall clock",
        }
    }

    /// One sentence for reports.
    pub fn description(self) -> &'static str {
        match self {
            PassClock::GpuTimer => {
                "GPU time per pass (GL_TIME_ELAPSED timer query; glFinish between passes)"
            }
            PassClock::WallClock => {
                "wall clock around glFinish per pass (software GL: Mesa's timer queries do not \
                 measure real time there)"
            }
        }
    }

    /// Axis and column label: "GPU ms" or "wall ms".
    pub fn unit(self) -> &'static str {
        match self {
            PassClock::GpuTimer => "GPU ms",
            PassClock::WallClock => "wall ms",
        }
    }
}

/// A `GL_TIME_ELAPSED` query object, deleted on drop. One pass is timed at a time.
pub struct TimerQuery {
    gl: Gl,
    query: glow::Query,
}

impl TimerQuery {
    /// `None` when the driver cannot create a query object (the caller falls back to the wall
    /// clock).
    pub fn new(gl: &Gl) -> Option<TimerQuery> {
        // SAFETY: a plain object creation on the current context.
        let query = unsafe { gl.create_query() }.ok()?;
        Some(TimerQuery {
            gl: gl.clone(),
            query,
        })
    }

    /// Runs `f` inside the query; returns its result and the device's milliseconds for it. Waits
    /// for the result (the passes are bracketed by glFinish anyway).
    pub fn time<T>(&self, f: impl FnOnce() -> T) -> (T, f64) {
        // SAFETY: begin/end pair on one query object; no other TIME_ELAPSED query is active
        // (the caller times one pass at a time).
        unsafe { self.gl.begin_query(glow::TIME_ELAPSED, self.query) };
        let out = f();
        let ns = unsafe {
            self.gl.end_query(glow::TIME_ELAPSED);
            self.gl
                .get_query_parameter_u64(self.query, glow::QUERY_RESULT)
        };
        (out, ns as f64 * 1e-6)
    }
}

impl Drop for TimerQuery {
    fn drop(&mut self) {
        // SAFETY: the query was created on this context and is deleted once.
        unsafe { self.gl.delete_query(self.query) };
    }
}

#[cfg(test)]
mod tests {
    use super::PassClock;

    #[test]
    fn software_drivers_get_the_wall_clock() {
        for r in [
            "Mesa llvmpipe (LLVM 15.0.6, 256 bits) (OpenGL 4.5 (Core Profile) Mesa 22.3.6)",
            "Mesa softpipe",
            "Mesa/X.org LLVMPIPE",
        ] {
            assert_eq!(PassClock::for_renderer(r), PassClock::WallClock, "{r}");
        }
        for r in [
            "NVIDIA Corporation NVIDIA H200/PCIe/SSE2",
            "AMD Radeon RX 7900 (radeonsi)",
        ] {
            assert_eq!(PassClock::for_renderer(r), PassClock::GpuTimer, "{r}");
        }
        assert_eq!(PassClock::WallClock.name(), "wall clock");
        assert_eq!(PassClock::GpuTimer.unit(), "GPU ms");
    }
}
