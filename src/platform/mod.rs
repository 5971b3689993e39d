//! Where frames are drawn: a desktop window (winit + glutin) or a headless EGL context.
//! Rendering code never depends on which one it runs in.

pub mod headless;
pub mod panel;
pub mod panel_fonts;
pub mod shader_errors;
pub mod window;

pub use headless::HeadlessContext;

/// True when a desktop display looks reachable (X11 or Wayland).
pub fn display_available() -> bool {
    std::env::var_os("DISPLAY").is_some_and(|v| !v.is_empty())
        || std::env::var_os("WAYLAND_DISPLAY").is_some_and(|v| !v.is_empty())
}
