//! Constants the course scatters through its C++ and GLSL, defined once.
//!
//! The course hard-codes near/far in `standard.vert`, `sao_restore_depth.frag` and the engine; here they
//! live in one place and the engine hands them to shaders that need them.

/// Vertical field of view of the course's camera, in degrees.
pub const FOV_Y_DEG: f32 = 60.0;
/// Near plane distance in metres (the course's `near`).
pub const NEAR: f32 = 0.35;
/// Far plane distance in metres (the course's `far`).
pub const FAR: f32 = 1000.0;

/// The course's `GetFovScale()`: 1 / tan(fovY / 2), ≈ 1.732 for 60°.
pub fn fov_scale(fov_y_deg: f32) -> f32 {
    1.0 / (fov_y_deg.to_radians() * 0.5).tan()
}

/// Number of levels of the SAO linear-depth texture (`fboSAODepth[4]` in the course: a count, not a max index).
pub const SAO_DEPTH_LEVELS: usize = 4;

/// Uniform locations shared by shaders, mirroring the course's `layout(location=N)` table.
pub mod loc {
    /// standard.vert / shadow.vert: model matrix.
    pub const MODEL: i32 = 0;
    /// standard.vert / shadow.vert / sky: view-projection matrix.
    pub const VIEW_PROJECTION: i32 = 1;
    /// standard.vert: light's shadow view-projection matrix.
    pub const SHADOW_MATRIX: i32 = 2;
    /// standard.frag: object base colour (rgba).
    pub const OBJECT_COLOR: i32 = 100;
    /// standard.frag: light direction (towards the light), world space.
    pub const LIGHT_DIRECTION: i32 = 101;
    /// standard.frag: light colour.
    pub const LIGHT_COLOR: i32 = 102;
    /// standard.frag: ambient colour.
    pub const AMBIENT_COLOR: i32 = 103;
    /// standard.frag: 1 = sample the shadow map, 0 = fully lit.
    pub const SHADOW_ENABLED: i32 = 104;
    /// standard.frag: AO on the ambient term only (1/0), 1/screen size, visibility power.
    pub const AO_AMBIENT_ONLY: i32 = 105;
    pub const INV_SCREEN_SIZE: i32 = 106;
    pub const AO_POWER: i32 = 107;
    /// ao/composite_tint.frag: tint colour and power.
    pub const AO_TINT: i32 = 220;
    pub const AO_TINT_POWER: i32 = 221;
    /// sky.frag: inverse of the view-projection matrix (to get a view ray per pixel).
    pub const INVERSE_VIEW_PROJECTION: i32 = 110;
    /// image_processing.frag: colour matrix; bloom strength.
    pub const COLOR_MATRIX: i32 = 120;
    pub const BLOOM_STRENGTH: i32 = 121;
    /// bloom passes: threshold (bright pass) or source level.
    pub const BLOOM_THRESHOLD: i32 = 130;
    /// sao_down_sampling.frag: source mip level (the course's `mipLevel`, location 200).
    pub const SAO_MIP_LEVEL: i32 = 200;
    /// sao.frag: (radius², radius in texcoords at 1 m, bias, intensity / r⁶) (the course's `saoInfo`).
    pub const SAO_INFO: i32 = 200;
    /// sao.frag: NDC → view-space factors at 1 m (the course's `ndcToView`).
    pub const SAO_NDC_TO_VIEW: i32 = 201;
    /// sao.frag (optional, this port's addition): (sample count, spiral turns).
    pub const SAO_SAMPLING: i32 = 202;
    /// debug_view.frag: which buffer to show, and a value scale.
    pub const DEBUG_VIEW_MODE: i32 = 210;
    pub const DEBUG_VIEW_SCALE: i32 = 211;
}

/// Texture bindings used by the engine's own shaders.
pub mod binding {
    pub const SHADOW_MAP: u32 = 2;
    /// standard.frag: occlusion for AO on the ambient term only.
    pub const AO_AMBIENT: u32 = 3;
}
