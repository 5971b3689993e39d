//! `glClipControl` (OpenGL 4.5), which glow 0.17 does not wrap. The platform layer that creates a
//! context registers its `get_proc_address`; the engine then looks the entry point up through it,
//! never by opening driver libraries itself.

use std::ffi::{c_void, CStr};
use std::sync::OnceLock;

type ClipControlFn = unsafe extern "system" fn(u32, u32);

/// The entry point found through the first context's loader. EGL and GLX return dispatch stubs that
/// call into whichever context is current, so one pointer serves every context of the process.
static ENTRY: OnceLock<Option<usize>> = OnceLock::new();

/// Called by the platform right after a context is created, with that context's loader.
pub fn register_loader(get_proc_address: impl Fn(&CStr) -> *const c_void) {
    ENTRY.get_or_init(|| {
        let p = get_proc_address(c"glClipControl");
        (!p.is_null()).then_some(p as usize)
    });
}

#[derive(Clone, Copy)]
pub struct ClipControl(ClipControlFn);

impl ClipControl {
    /// The registered entry point; an error when no context registered one or the driver lacks it.
    pub fn get() -> Result<ClipControl, String> {
        match ENTRY.get() {
            Some(Some(p)) => {
                // SAFETY: the pointer came from the context's loader for "glClipControl", whose
                // signature is void(GLenum origin, GLenum depth).
                Ok(ClipControl(unsafe {
                    std::mem::transmute::<*const c_void, ClipControlFn>(*p as *const c_void)
                }))
            }
            Some(None) => {
                Err("reversed-Z needs glClipControl (OpenGL 4.5); the driver has none".into())
            }
            None => Err(
                "reversed-Z needs glClipControl, but no GL context registered its loader".into(),
            ),
        }
    }

    /// Sets the clip-space depth range: [0, 1] for reversed-Z passes, OpenGL's [-1, 1] otherwise.
    pub fn set(&self, zero_to_one: bool) {
        let depth = if zero_to_one {
            glow::ZERO_TO_ONE
        } else {
            glow::NEGATIVE_ONE_TO_ONE
        };
        // SAFETY: called with a current GL ≥ 4.5 context, valid enums.
        unsafe { (self.0)(glow::LOWER_LEFT, depth) }
    }
}
