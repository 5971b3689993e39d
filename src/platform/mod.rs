//! Where frames are drawn: a desktop window (winit + glutin) or a headless EGL context.
//! Rendering code never depends on which one it runs in.

pub mod headless;
#[cfg(feature = "window")]
pub mod panel;
#[cfg(feature = "window")]
pub mod panel_fonts;
#[cfg(feature = "window")]
pub mod shader_errors;
#[cfg(feature = "window")]
pub mod window;

pub use headless::HeadlessContext;

/// True when a desktop display looks reachable (X11 or Wayland; Windows always has one) and this
/// build has the window.
pub fn display_available() -> bool {
    if cfg!(not(feature = "window")) {
        return false;
    }
    if cfg!(windows) {
        return true;
    }
    std::env::var_os("DISPLAY").is_some_and(|v| !v.is_empty())
        || std::env::var_os("WAYLAND_DISPLAY").is_some_and(|v| !v.is_empty())
}
